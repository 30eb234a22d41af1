//! Learning: validity against the independent checker, feedback on and off, determinism across
//! thread counts, budgets and parameter errors.

use crate::roadmap_support;

use roadmap_support::*;
use viaroad::local::LocalSpec;
use viaroad::roadmap::{Budget, LearnError, LearnParams, Learner, StopReason};

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

#[test]
fn roadmaps_are_valid_with_and_without_feedback() {
    let scene = disc_scene(11, 40, 0.06);
    let d = discs(&scene);
    for spec in [LocalSpec::Straight, LocalSpec::default()] {
        for (feedback, bounce_nodes) in [(true, false), (false, false), (true, true)] {
            let params = LearnParams {
                feedback,
                bounce_nodes,
                ..LearnParams::default()
            };
            let learnt = learn(&scene, &spec, &params, 400, 3);
            let r = &learnt.roadmap;
            assert!(r.node_count() >= 400, "{} nodes", r.node_count());
            assert!(r.edge_count() > 0);
            roadmap_valid(r, &d).unwrap_or_else(|e| panic!("{spec} feedback={feedback}: {e}"));
            assert_eq!(r.component_labels(), bfs_labels(r).as_slice());
            let corners: usize = r.edges().iter().map(|e| e.corners.len()).sum();
            eprintln!(
                "{spec} feedback={feedback} bounce_nodes={bounce_nodes}: {} nodes {} edges {} components (largest {}), {} rounds, {:?}",
                r.node_count(),
                r.edge_count(),
                r.component_count(),
                r.largest_component(),
                learnt.report.rounds,
                learnt.report.elapsed
            );
            if feedback && bounce_nodes {
                // every feedback edge and every walk step is one straight segment
                assert_eq!(corners, 0, "{spec}");
            } else if !feedback {
                // walks, and connections through via points, keep their corners on the edge
                assert!(corners > 0, "{spec}");
            }
            assert_eq!(learnt.report.stop, StopReason::NodeBudget);
            assert_eq!(r.header().local_spec, spec);
            if spec == LocalSpec::Straight {
                // a construction round adds at most one node per candidate here
                assert!(learnt.report.expansion_rounds > 0);
            }
        }
    }
}

/// The same seed gives the same file bytes with one and with two threads, with feedback on and
/// off; another seed gives another roadmap.
#[test]
fn same_seed_same_bytes_with_one_and_two_threads() {
    let scene = disc_scene(5, 50, 0.05);
    for feedback in [true, false] {
        let params = LearnParams {
            feedback,
            round_size: 24,
            ..LearnParams::default()
        };
        let bytes = |threads: usize, seed: u64| {
            pool(threads).install(|| {
                learn(&scene, &LocalSpec::default(), &params, 500, seed)
                    .roadmap
                    .to_bytes()
                    .unwrap()
            })
        };
        let one = bytes(1, 42);
        let two = bytes(2, 42);
        assert!(
            one == two,
            "feedback={feedback}: files differ between 1 and 2 threads"
        );
        assert_ne!(
            one,
            bytes(2, 43),
            "another seed should give another roadmap"
        );
    }
}

/// The node budget stops learning as soon as it is reached: at least the budget, and not more
/// than one candidate's or walk's worth beyond it.
#[test]
fn node_budget_is_met_and_barely_exceeded() {
    let scene = disc_scene(2, 30, 0.05);
    for feedback in [true, false] {
        for budget in [1, 37, 150] {
            let params = LearnParams {
                feedback,
                ..LearnParams::default()
            };
            let learnt = learn(&scene, &LocalSpec::Straight, &params, budget, 9);
            let n = learnt.roadmap.node_count();
            // a walk adds at most `bounce_steps` nodes, a candidate with the straight method
            // at most itself plus its path's corners (none in R^2)
            assert!(
                n >= budget && n < budget + params.bounce_steps,
                "feedback={feedback} budget={budget}: {n} nodes"
            );
            assert_eq!(learnt.roadmap.header().node_budget, Some(budget as u64));
        }
    }
    let empty = learn(&scene, &LocalSpec::Straight, &LearnParams::default(), 0, 1);
    assert_eq!(empty.roadmap.node_count(), 0);
    assert_eq!(empty.report.rounds, 0);
}

/// A scene without free space stalls instead of looping forever.
#[test]
fn a_scene_without_free_space_stalls() {
    let mut scene = disc_scene(1, 0, 0.1);
    scene.obstacles.push(viaroad::scene::Obstacle::Disc {
        centre: vec![0.5, 0.5],
        radius: 1.0,
    });
    let params = LearnParams {
        stall_rounds: 3,
        round_size: 4,
        sample_attempts: 5,
        ..LearnParams::default()
    };
    let learnt = learn(&scene, &LocalSpec::Straight, &params, 10, 1);
    assert_eq!(learnt.report.stop, StopReason::Stalled);
    assert_eq!(learnt.roadmap.node_count(), 0);
    assert_eq!(learnt.report.rounds, 3);
    // every sample was checked and counted
    assert_eq!(learnt.roadmap.header().counts.state_checks, 3 * 4 * 5);
}

/// Oracle calls are counted: the header's totals are the learner's, identical across runs.
#[test]
fn oracle_calls_are_recorded() {
    let scene = disc_scene(8, 30, 0.05);
    let a = learn(
        &scene,
        &LocalSpec::Straight,
        &LearnParams::default(),
        300,
        4,
    );
    let c = a.roadmap.header().counts;
    assert!(c.state_checks >= 300 / 2, "{c:?}");
    assert!(c.segment_calls as usize >= a.report.attempts as usize);
    assert!(c.line_calls > 0, "bounce walks ask intersectLine: {c:?}");
    let b = learn(
        &scene,
        &LocalSpec::Straight,
        &LearnParams::default(),
        300,
        4,
    );
    assert_eq!(b.roadmap.header().counts, c);
}

#[test]
fn bad_parameters_and_missing_budget_are_typed_errors() {
    let scene = disc_scene(1, 5, 0.05);
    let oracle = scene.oracle();
    let local = LocalSpec::Straight.build();
    let learner = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref());
    let run = |p: &LearnParams, b: &Budget| learner.learn(p, b, 0, &mut |_| {});
    assert!(matches!(
        run(&LearnParams::default(), &Budget::default()),
        Err(LearnError::NoBudget)
    ));
    for bad in [
        LearnParams {
            neighbours: 0,
            ..LearnParams::default()
        },
        LearnParams {
            radius: Some(-1.0),
            ..LearnParams::default()
        },
        LearnParams {
            expansion_share: 1.0,
            ..LearnParams::default()
        },
        LearnParams {
            round_size: 0,
            ..LearnParams::default()
        },
    ] {
        assert!(matches!(
            run(&bad, &Budget::nodes(10)),
            Err(LearnError::Params(_))
        ));
    }
}

/// A connection radius keeps every edge a construction attempt makes within the radius; the
/// time budget ends learning (not reproducible, so only checked to stop).
#[test]
fn radius_and_time_budget() {
    let scene = disc_scene(3, 20, 0.05);
    let params = LearnParams {
        radius: Some(0.1),
        feedback: false,
        expansion_share: 0.0,
        ..LearnParams::default()
    };
    let learnt = learn(&scene, &LocalSpec::Straight, &params, 300, 2);
    for e in learnt.roadmap.edges() {
        assert!(e.length <= 0.1 + 1e-12, "edge of length {}", e.length);
    }
    let oracle = scene.oracle();
    let local = LocalSpec::Straight.build();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref())
        .learn(
            &LearnParams::default(),
            &Budget::time(std::time::Duration::from_millis(30)),
            1,
            &mut |_| {},
        )
        .unwrap();
    assert_eq!(learnt.report.stop, StopReason::TimeBudget);
    assert_eq!(learnt.roadmap.header().node_budget, None);
}

/// Progress is reported after every round, with growing node counts.
#[test]
fn progress_is_reported_every_round() {
    let scene = disc_scene(4, 20, 0.05);
    let oracle = scene.oracle();
    let local = LocalSpec::Straight.build();
    let mut seen = Vec::new();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(400), 1, &mut |p| {
            seen.push((p.rounds, p.nodes))
        })
        .unwrap();
    assert_eq!(seen.len() as u64, learnt.report.rounds);
    assert!(seen
        .windows(2)
        .all(|w| w[1].0 == w[0].0 + 1 && w[1].1 >= w[0].1));
    assert_eq!(seen.last().unwrap().1, learnt.roadmap.node_count());
}

/// Extreme but valid parameters neither panic nor allocate by their value.
#[test]
fn extreme_parameters_are_harmless() {
    let scene = disc_scene(6, 20, 0.05);
    let params = LearnParams {
        neighbours: usize::MAX,
        radius: Some(f64::INFINITY),
        bounce_steps: 1 << 40,
        stall_rounds: usize::MAX,
        ..LearnParams::default()
    };
    // bounce walks this long would never end: keep them out with a construction-only split
    let params = LearnParams {
        expansion_share: 0.0,
        ..params
    };
    let learnt = learn(&scene, &LocalSpec::Straight, &params, 60, 1);
    assert!(learnt.roadmap.node_count() >= 60);
    let oracle = scene.oracle();
    let planner = viaroad::roadmap::QueryPlanner::new(&learnt.roadmap, oracle.as_ref())
        .unwrap()
        .with_options(viaroad::roadmap::QueryOptions {
            attach_candidates: usize::MAX,
            attach_direct_candidates: usize::MAX,
            try_direct: false,
            direct_calls: 0,
            shorten: true,
            exact_shortening_limit: usize::MAX,
            landmarks: 8,
            escalation_candidates: usize::MAX,
            time: None,
            grow: false,
            trees: None,
            max_calls: Some(u64::MAX),
            return_trees: false,
            race: None,
            straight_shortcuts: true,
        });
    let (s, g) = random_queries(&scene, 1, 4).remove(0);
    assert!(planner.query(&s, &g).is_ok());
    let too_big = LearnParams {
        round_size: LearnParams::MAX_ROUND_SIZE + 1,
        ..LearnParams::default()
    };
    let local = LocalSpec::Straight.build();
    assert!(matches!(
        Learner::for_scene(&scene, oracle.as_ref(), local.as_ref()).learn(
            &too_big,
            &Budget::nodes(1),
            0,
            &mut |_| {}
        ),
        Err(LearnError::Params(_))
    ));
}

/// Cheap attempts beyond the nearest `d` neighbours: the roadmap stays valid under the
/// independent check, and the deep searches are fewer, so fewer intersect calls are spent per
/// attempt than with the full method towards every neighbour.
#[test]
fn deep_neighbours_keep_roadmaps_valid_and_cheaper() {
    let scene = disc_scene(13, 60, 0.05);
    let d = discs(&scene);
    let spec = LocalSpec::roadmap_default();
    let per_attempt = |deep: Option<usize>| {
        let params = LearnParams {
            deep_neighbours: deep,
            ..LearnParams::default()
        };
        let learnt = learn(&scene, &spec, &params, 400, 5);
        roadmap_valid(&learnt.roadmap, &d).unwrap_or_else(|e| panic!("deep={deep:?}: {e}"));
        assert_eq!(
            learnt.roadmap.component_labels(),
            bfs_labels(&learnt.roadmap).as_slice()
        );
        let calls = learnt.roadmap.header().counts.intersect_calls();
        calls as f64 / learnt.report.attempts as f64
    };
    let (all, cheap) = (per_attempt(None), per_attempt(Some(1)));
    assert!(
        cheap < all,
        "{cheap} calls per attempt with d = 1, {all} with all"
    );
    let zero = LearnParams {
        deep_neighbours: Some(0),
        ..LearnParams::default()
    };
    assert!(zero.validate().is_err());
}
