//! RRT-Connect with exact single-group extends (`roadmap::tree`): every path joins start and
//! goal by free single-group motions — re-checked by the independent checkers (segment–disc
//! distances, exact polygon sweeps in the plane, parry by conservative advancement in SE(3)) —
//! the same seed and node budget give the same answer, the node budget holds, and the
//! shortcut path is checked the same way.

use crate::common;

use common::cli::{fails_with, stderr, stdout, viaroad};
use common::tree::grow;
use std::path::PathBuf;
use viaroad::bench::validity::Checker;
use viaroad::deadline::Deadline;
use viaroad::oracle::CallCounts;
use viaroad::roadmap::tree::{shortcut, Prefix, Stairs, TreeOutcome, TreeParams, TreeStop};
use viaroad::scene::Scene;
use viaroad::space::Config;

fn scene(rel: &str) -> Scene {
    Scene::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
}

/// A uniform sample of `s`'s space that `oracle` finds free (rejection sampling).
fn free_sample(
    s: &Scene,
    oracle: &dyn viaroad::oracle::CollisionOracle,
    rng: &mut rand_chacha::ChaCha8Rng,
    counts: &mut CallCounts,
) -> Config {
    loop {
        let q = s.space.sample_uniform(rng);
        if viaroad::oracle::CountedOracle::is_free(oracle, &q, counts) {
            return q;
        }
    }
}

/// Checks `path` independently: from the query's start to its goal, every step in one DOF
/// group, every corner and motion free under the scene's checker.
fn check(scene: &Scene, path: &[Config]) {
    let q = &scene.checked_queries().unwrap()[0];
    let groups = scene.space.groups(false);
    assert_eq!(
        path.first(),
        Some(&q.start),
        "{}: path leaves the start",
        scene.name
    );
    assert_eq!(
        path.last(),
        Some(&q.goal),
        "{}: path misses the goal",
        scene.name
    );
    for w in path.windows(2) {
        let differing = groups
            .iter()
            .filter(|g| !scene.space.same_in_group(&w[0], &w[1], g))
            .count();
        assert!(
            differing <= 1,
            "{}: a step moved {differing} groups",
            scene.name
        );
    }
    Checker::for_scene(scene)
        .unwrap()
        .check_path(path)
        .unwrap_or_else(|e| panic!("{}: a tree path collides: {e}", scene.name));
}

fn params(max_nodes: usize) -> TreeParams {
    TreeParams {
        max_nodes: Some(max_nodes),
        ..TreeParams::default()
    }
}

#[test]
fn paths_are_free_single_group_and_shortcuts_too() {
    for (rel, nodes, seeds) in [
        ("scenes/discs-cluttered.toml", 4000, 1..=4),
        ("scenes/se2-corridor.toml", 4000, 1..=3),
        ("scenes/ompl/3D/Easy.cfg", 20000, 1..=2),
    ] {
        let s = scene(rel);
        let oracle = s.oracle();
        let groups = s.space.groups(false);
        let mut solved = 0;
        for (seed, stairs) in seeds
            .clone()
            .flat_map(|seed| [(seed, Stairs::Whole), (seed, Stairs::Prefix)])
        {
            let p = TreeParams {
                stairs,
                ..params(nodes)
            };
            let out = grow(&s, &p, seed);
            let Some(path) = &out.path else { continue };
            assert_eq!(out.stop, TreeStop::Connected);
            solved += 1;
            check(&s, path);
            let mut counts = CallCounts::default();
            let short = shortcut(
                &s.space,
                oracle.as_ref(),
                &groups,
                path,
                16,
                &mut counts,
                &Deadline::none(),
            )
            .unwrap();
            assert!(
                short.len() <= path.len() * 2,
                "{rel}: shortcut grew the path"
            );
            check(&s, &short);
        }
        assert!(solved > 0, "{rel}: no seed of {seeds:?} solved");
    }
}

#[test]
fn yes_no_first_finds_paths_as_free() {
    let s = scene("scenes/se2-corridor.toml");
    let p = TreeParams {
        prefix: Prefix::YesNoFirst,
        stairs: Stairs::Prefix,
        ..params(4000)
    };
    let out = grow(&s, &p, 1);
    check(&s, out.path.as_ref().expect("corridor not solved"));
}

#[test]
fn same_seed_same_answer_and_the_node_budget_holds() {
    let s = scene("scenes/discs-cluttered.toml");
    let a = grow(&s, &params(3000), 5);
    let b = grow(&s, &params(3000), 5);
    assert_eq!(a.path, b.path);
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(a.counts.intersect_calls(), b.counts.intersect_calls());
    // a budget too small to connect stops within one extend of it (a staircase of at most
    // range / stair stairs, one node per group)
    let p = TreeParams {
        range: 0.2,
        stair: 0.05,
        ..params(30)
    };
    let out = grow(&s, &p, 5);
    if out.path.is_none() {
        assert_eq!(out.stop, TreeStop::NodeBudget);
    }
    assert!(out.nodes[0] + out.nodes[1] <= 30 + 4 * 2, "{:?}", out.nodes);
}

#[test]
fn free_space_connects_in_one_straight_staircase() {
    let mut s = scene("scenes/discs-cluttered.toml");
    s.obstacles.clear();
    let p = TreeParams {
        range: 2.0,
        ..params(1000)
    };
    let out = grow(&s, &p, 1);
    let path = out.path.expect("free space not solved");
    check(&s, &path);
    // the first extend aims at the goal itself and, within range, reaches it
    assert_eq!(out.nodes[1], 1, "the goal tree grew: {:?}", out.nodes);
}

#[test]
fn cli_tree_with_a_node_budget_is_reproducible_and_its_paths_are_checked() {
    let s = scene("scenes/discs-cluttered.toml");
    let (centres, radii): (Vec<Vec<f64>>, Vec<f64>) = s
        .obstacles
        .iter()
        .map(|o| match o {
            viaroad::scene::Obstacle::Disc { centre, radius } => (centre.clone(), *radius),
            _ => panic!("a disc scene"),
        })
        .unzip();
    let run = |extra: &[&str]| {
        let mut args = vec![
            "solve",
            "scenes/discs-cluttered.toml",
            "--tree",
            "--nodes",
            "3000",
            "--seed",
            "4",
            "--json",
        ];
        args.extend_from_slice(extra);
        let o = viaroad(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        stdout(&o)
            .lines()
            .map(|l| {
                let mut v: serde_json::Value = serde_json::from_str(l).unwrap();
                // the timings are the only fields that may differ between two runs
                let m = v.as_object_mut().unwrap();
                m.remove("seconds");
                m.remove("grow_seconds");
                v
            })
            .collect::<Vec<_>>()
    };
    for extra in [
        &[][..],
        &["--tree-coarse", "--tree-stair", "0.05"][..],
        &["--tree-restart", "40"][..],
    ] {
        let a = run(extra);
        assert_eq!(a, run(extra), "{extra:?}: two runs differ");
        assert!(!a.is_empty());
        let solved = a.iter().filter(|v| v["solved"] == true).count();
        assert!(
            solved * 2 >= a.len(),
            "{extra:?}: only {solved} of {} solved",
            a.len()
        );
        for v in a.iter().filter(|v| v["solved"] == true) {
            assert_eq!(v["stop"], "Connected");
            assert!(v["attempts"].as_u64().is_some_and(|n| n >= 1), "{v}");
            for key in ["path", "shortened"] {
                let p: Vec<Vec<f64>> = serde_json::from_value(v[key].clone()).unwrap();
                common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9)
                    .unwrap();
            }
        }
    }
    fails_with(
        &[
            "solve",
            "scenes/discs-cluttered.toml",
            "--tree",
            "--tree-stair",
            "0",
        ],
        "stair",
    );
    fails_with(
        &[
            "solve",
            "scenes/discs-cluttered.toml",
            "--tree",
            "--tree-restart",
            "0",
        ],
        "restarts",
    );
    // centring and the coarse first try walk partial stairs: whole ones are refused
    for flag in [&["--tree-centre", "2"][..], &["--tree-coarse"][..]] {
        let mut args = vec![
            "solve",
            "scenes/discs-cluttered.toml",
            "--tree",
            "--tree-stairs",
            "whole",
        ];
        args.extend_from_slice(flag);
        fails_with(&args, "not whole ones");
    }
    // one single-query planner at a time (a usage error: clap's exit status 2)
    let o = viaroad(&[
        "solve",
        "scenes/discs-cluttered.toml",
        "--tree",
        "--roadmap",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--roadmap"), "{}", stderr(&o));
}

#[test]
fn first_collision_is_the_start_of_the_first_interval() {
    use rand::SeedableRng;
    use viaroad::oracle::CollisionOracle;
    for rel in [
        "scenes/ompl/3D/Twistycool.cfg",
        "scenes/ompl/3D/alpha-1.5.cfg",
        "scenes/ompl/3D/bugtrap.cfg",
        "scenes/se2-corridor.toml",
    ] {
        let s = scene(rel);
        let oracle = s.oracle();
        let groups = s.space.groups(false);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let mut counts = CallCounts::default();
        let (mut blocked, mut partial, mut free) = (0, 0, 0);
        let q0 = &s.checked_queries().unwrap()[0].start;
        for i in 0..300 {
            // from the query's start (alpha's is entangled) or a random free configuration,
            // a stair of random length towards a uniform sample
            let from = if i % 2 == 0 {
                q0.clone()
            } else {
                free_sample(&s, oracle.as_ref(), &mut rng, &mut counts)
            };
            let to = s.space.sample_uniform(&mut rng);
            let t: f64 = rand::Rng::random_range(&mut rng, 0.001..1.0);
            let aim = s.space.interpolate(&from, &to, t);
            let g = &groups[i % groups.len()];
            let motion = s
                .space
                .group_motion(&from, &s.space.with_group_of(&from, &aim, g), g);
            let all = oracle.intervals(&motion, &mut counts).unwrap();
            let first = oracle.first_collision(&motion, &mut counts).unwrap();
            assert_eq!(
                first,
                all.first().map(|iv| iv.lo),
                "{rel}: motion {i}: first collision differs from the intervals {all:?}"
            );
            match first {
                None => free += 1,
                Some(x) if x <= 0.0 => blocked += 1,
                Some(_) => partial += 1,
            }
        }
        // the comparison covered all three cases
        assert!(
            free > 0 && partial > 0,
            "{rel}: free {free}, partial {partial}, blocked {blocked}"
        );
    }
}

#[test]
fn first_hit_prefixes_grow_the_same_trees_as_intervals() {
    let s = scene("scenes/ompl/3D/alpha-1.5.cfg");
    let grow_with = |prefix| {
        let p = TreeParams {
            prefix,
            stairs: Stairs::Prefix,
            ..params(1500)
        };
        let o = grow(&s, &p, 3);
        (o.path, o.nodes, o.counts.intersect_calls())
    };
    assert_eq!(grow_with(Prefix::Intervals), grow_with(Prefix::FirstHit));
}

/// Two discs with a gap between them, for the centring tests.
fn gap_scene(discs: &[([f64; 2], f64)]) -> Scene {
    let mut s = scene("scenes/discs-cluttered.toml");
    s.obstacles = discs
        .iter()
        .map(|(c, r)| viaroad::scene::Obstacle::Disc {
            centre: c.to_vec(),
            radius: *r,
        })
        .collect();
    s
}

#[test]
fn centring_moves_to_the_middle_of_a_bounded_chord_only() {
    use viaroad::roadmap::centre::{centre_round, Across};
    let s = gap_scene(&[([0.3, 0.5], 0.15), ([0.7, 0.5], 0.15)]);
    let oracle = s.oracle();
    let groups = s.space.groups(false);
    let mut counts = CallCounts::default();
    // blocked going up: centred across, along x, between the two discs
    let across = Across::Translation {
        group: 0,
        dir: vec![0.0, 1.0],
    };
    let q = [0.45, 0.45];
    let out = centre_round(
        &s.space,
        oracle.as_ref(),
        &groups,
        &q,
        &across,
        0.3,
        0.05,
        &mut counts,
        &Deadline::none(),
    )
    .unwrap();
    assert_eq!(out.len(), 1, "{out:?}");
    assert!((out[0][0] - 0.5).abs() < 1e-9, "{out:?}");
    assert_eq!(out[0][1], 0.45);
    // a chord bounded on both sides: one first-collision call each way
    assert_eq!(counts.intersect_calls(), 2);
    Checker::for_scene(&s)
        .unwrap()
        .check_path(&[q.to_vec(), out[0].clone()])
        .unwrap();
    // one disc only: the chord is open on one side within the reach, nothing moves; the open
    // side is the one asked first, so the other is not asked at all
    let s = gap_scene(&[([0.3, 0.5], 0.15)]);
    let oracle = s.oracle();
    let mut counts = CallCounts::default();
    let out = centre_round(
        &s.space,
        oracle.as_ref(),
        &groups,
        &q,
        &across,
        0.3,
        0.05,
        &mut counts,
        &Deadline::none(),
    )
    .unwrap();
    assert!(out.is_empty(), "{out:?}");
    assert_eq!(counts.intersect_calls(), 1);
}

/// The chord a centring round moves across, from all intervals of the line or turn through
/// `q` within `clip`: the free section containing 0, if bounded on both sides inside `clip`.
fn chord_from_intervals(
    oracle: &dyn viaroad::oracle::CollisionOracle,
    motion: &viaroad::space::Motion,
    clip: viaroad::interval::Interval,
) -> Option<viaroad::interval::Interval> {
    use viaroad::oracle::CountedOracle;
    let mut m = motion.clone();
    m.range = clip;
    let hits = oracle.intersect(&m, &mut CallCounts::default()).unwrap();
    let chord = hits
        .complement_within(clip)
        .iter()
        .find(|c| c.contains(0.0))
        .copied()?;
    (chord.lo > clip.lo && chord.hi < clip.hi).then_some(chord)
}

#[test]
fn centring_chords_from_first_collisions_are_the_chords_of_all_intervals() {
    // bugtrap's long rod turning by up to ±0.45 turns and sliding across its shell, and
    // alpha-1.5's entangled start: every centring move must land where the chord of all
    // intervals puts it (two first-collision calls each way replace one interval call)
    use rand::SeedableRng;
    use viaroad::interval::Interval;
    use viaroad::roadmap::centre::{centre_round, Across};
    use viaroad::space::GroupKind;
    let mut moved = 0;
    for rel in ["scenes/ompl/3D/bugtrap.cfg", "scenes/ompl/3D/alpha-1.5.cfg"] {
        let s = scene(rel);
        let oracle = s.oracle();
        let groups = s.space.groups(false);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let mut counts = CallCounts::default();
        let q0 = s.checked_queries().unwrap()[0].start.clone();
        let reach = 0.05 * s.space.extent();
        for i in 0..40 {
            let q = if i % 2 == 0 {
                q0.clone()
            } else {
                free_sample(&s, oracle.as_ref(), &mut rng, &mut counts)
            };
            let dir = [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.6, 0.0, 0.8]][i % 3];
            let across = Across::Translation {
                group: 0,
                dir: dir.to_vec(),
            };
            let out = centre_round(
                &s.space,
                oracle.as_ref(),
                &groups,
                &q,
                &across,
                reach,
                0.45,
                &mut counts,
                &Deadline::none(),
            )
            .unwrap();
            // replay the round with chords of all intervals
            let mut current = q.clone();
            let mut expected = Vec::new();
            for g in &groups {
                let motions: Vec<(viaroad::space::Motion, f64)> = match g.kind {
                    GroupKind::Linear => viaroad::roadmap::centre::perpendiculars(&dir)
                        .iter()
                        .map(|d| (s.space.line_through(&current, g, d), reach))
                        .collect(),
                    _ => std::iter::once(dir)
                        .chain(
                            viaroad::roadmap::centre::perpendiculars(&dir)
                                .iter()
                                .map(|v| [v[0], v[1], v[2]]),
                        )
                        .map(|a| (s.space.turn_through(&current, g, a), 0.45))
                        .collect(),
                };
                for (mut m, r) in motions {
                    m.origin.clone_from(&current);
                    let clip = Interval { lo: -r, hi: r };
                    let Some(c) = chord_from_intervals(oracle.as_ref(), &m, clip) else {
                        continue;
                    };
                    let t = 0.5 * (c.lo + c.hi);
                    let mut next = m.at(t);
                    if g.kind != GroupKind::Linear {
                        s.space.normalize(&mut next);
                    }
                    if t != 0.0 && next != current {
                        expected.push(next.clone());
                        current = next;
                    }
                }
            }
            assert_eq!(
                out.len(),
                expected.len(),
                "{rel} #{i}: {out:?} vs {expected:?}"
            );
            for (a, b) in out.iter().zip(&expected) {
                assert!(
                    s.space.distance(a, b) <= 1e-9 * s.space.extent(),
                    "{rel} #{i}: {a:?} vs {b:?}"
                );
            }
            moved += out.len();
        }
    }
    assert!(moved > 0, "no centring move was compared");
}

#[test]
fn centring_trees_find_checked_paths_deterministically_within_the_budget() {
    let centring = |nodes| TreeParams {
        centre: 2,
        stairs: Stairs::Prefix,
        ..params(nodes)
    };
    for (rel, nodes, seeds) in [
        ("scenes/discs-cluttered.toml", 4000, 1..=3),
        ("scenes/se2-corridor.toml", 4000, 1..=3),
        ("scenes/ompl/3D/Easy.cfg", 20000, 1..=2),
    ] {
        let s = scene(rel);
        let mut solved = 0;
        for seed in seeds.clone() {
            let out = grow(&s, &centring(nodes), seed);
            let Some(path) = &out.path else { continue };
            solved += 1;
            check(&s, path);
        }
        assert!(
            solved > 0,
            "{rel}: no seed of {seeds:?} solved with centring"
        );
    }
    let s = scene("scenes/se2-corridor.toml");
    let a = grow(&s, &centring(3000), 4);
    let b = grow(&s, &centring(3000), 4);
    assert_eq!(a.path, b.path);
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(a.counts.intersect_calls(), b.counts.intersect_calls());
    // the budget holds to within one extend: its stairs, and per blocked stair at most
    // `centre` rounds of one node per direction (2 translations + 1 turn in SE(2))
    let p = TreeParams {
        stair: 0.05,
        ..centring(40)
    };
    let out = grow(&s, &p, 4);
    if out.path.is_none() {
        assert_eq!(out.stop, TreeStop::NodeBudget);
    }
    assert!(
        out.nodes[0] + out.nodes[1] <= 40 + 4 * 2 + 2 * 3,
        "{:?}",
        out.nodes
    );
}

#[test]
fn restarts_begin_with_the_plain_run_and_keep_to_the_node_budget() {
    let s = scene("scenes/se2-corridor.toml");
    let plain = grow(&s, &params(4000), 2);
    let needed = plain.nodes[0] + plain.nodes[1];
    assert!(plain.path.is_some() && needed > 100, "{:?}", plain.nodes);
    let restarting = |first, nodes| TreeParams {
        restart: Some(first),
        ..params(nodes)
    };
    let key = |o: &TreeOutcome| (o.path.clone(), o.nodes, o.counts.intersect_calls());
    // a first attempt large enough is the plain run itself
    let roomy = grow(&s, &restarting(4000, 4000), 2);
    assert_eq!(key(&roomy), key(&plain));
    assert_eq!((roomy.attempts, plain.attempts), (1, 1));
    // a first attempt too small: fresh trees from new streams, twice the nodes each time; the
    // answer is checked and the same twice
    let small = restarting(needed / 8, 64 * needed);
    let (a, b) = (grow(&s, &small, 2), grow(&s, &small, 2));
    assert!(
        a.attempts > 1,
        "solved in the first attempt of {}",
        needed / 8
    );
    check(
        &s,
        a.path.as_ref().expect("corridor not solved with restarts"),
    );
    assert_eq!((key(&a), a.attempts), (key(&b), b.attempts));
    // the last attempt kept to its doubled budget (plus at most one extend's staircase)
    let last = (needed / 8) << (a.attempts - 1);
    assert!(
        a.nodes[0] + a.nodes[1] <= last + 60,
        "{:?} > {last}",
        a.nodes
    );
    // all attempts together keep to `max_nodes`: 10 + 20 + 40 + what is left of 90
    let tight = grow(&s, &restarting(10, 90), 2);
    assert_eq!(
        (tight.path.is_none(), tight.stop),
        (true, TreeStop::NodeBudget)
    );
    assert!(
        (3..=4).contains(&tight.attempts),
        "{} attempts",
        tight.attempts
    );
    assert!(TreeParams {
        restart: Some(0),
        ..TreeParams::default()
    }
    .validate()
    .is_err());
}

/// Streams race (`TreeParams::streams`), but without a time limit each runs to its node budget
/// and the first in stream order that connected answers: the same path, nodes and calls in a
/// pool of one thread and of three; stream 0 is the run without streams; and a later stream
/// answers where stream 0 alone does not.
#[test]
fn streams_answer_the_same_on_any_thread_count() {
    let s = scene("scenes/discs-cluttered.toml");
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    let (one, three) = (pool(1), pool(3));
    let racing = TreeParams {
        streams: 3,
        ..params(BUDGET)
    };
    const BUDGET: usize = 550;
    let (mut alone_solved, mut rescued) = (0, 0);
    for seed in 1..=40 {
        let a = one.install(|| grow(&s, &racing, seed));
        let b = three.install(|| grow(&s, &racing, seed));
        assert_eq!(
            a.path, b.path,
            "seed {seed}: the thread count changed the path"
        );
        assert_eq!(a.nodes, b.nodes, "seed {seed}");
        assert_eq!(a.counts, b.counts, "seed {seed}");
        let alone = grow(&s, &params(BUDGET), seed);
        match (&alone.path, &a.path) {
            (Some(p), Some(q)) => {
                assert_eq!(p, q, "seed {seed}: stream 0 connected, so it answers");
                alone_solved += 1;
            }
            (Some(_), None) => panic!("seed {seed}: streams lost stream 0's answer"),
            (None, Some(q)) => {
                check(&s, q);
                rescued += 1;
            }
            (None, None) => {}
        }
    }
    assert!(
        alone_solved > 0 && rescued > 0,
        "{alone_solved} answered by stream 0, {rescued} by a later stream: both cases needed"
    );
}

/// Whole stairs (`Stairs::Whole`, the default): paths re-checked by the independent
/// checkers, the same seed gives the same answer, and in free space the first extend reaches
/// the goal in one staircase.
#[test]
fn whole_stairs_find_checked_paths_deterministically() {
    let whole = |nodes| TreeParams {
        stairs: Stairs::Whole,
        ..params(nodes)
    };
    for (rel, nodes) in [
        ("scenes/discs-cluttered.toml", 6000),
        ("scenes/se2-corridor.toml", 6000),
    ] {
        let s = scene(rel);
        let mut solved = 0;
        for seed in 1..=3 {
            let a = grow(&s, &whole(nodes), seed);
            let b = grow(&s, &whole(nodes), seed);
            assert_eq!(a.path, b.path, "{rel} seed {seed}");
            assert_eq!(a.counts, b.counts, "{rel} seed {seed}");
            if let Some(path) = &a.path {
                check(&s, path);
                solved += 1;
            }
        }
        assert!(solved > 0, "{rel}: no seed solved with whole stairs");
    }
    let mut s = scene("scenes/discs-cluttered.toml");
    s.obstacles.clear();
    let p = TreeParams {
        range: 2.0,
        ..whole(1000)
    };
    let out = grow(&s, &p, 1);
    check(&s, &out.path.expect("free space not solved"));
    assert_eq!(out.nodes[1], 1, "the goal tree grew: {:?}", out.nodes);
}

/// Parameters the trees cannot run with are refused before anything grows, each with what is
/// wrong (before, `rrt_connect` did not check them: a NaN range reached the extends, no streams
/// grew one).
#[test]
fn invalid_parameters_are_refused_with_their_own_error() {
    use viaroad::roadmap::tree::{rrt_connect, Domain, TreeError};
    let s = scene("scenes/discs-cluttered.toml");
    let oracle = s.oracle();
    let groups = s.space.groups(false);
    let q = &s.checked_queries().unwrap()[0];
    for (bad, says) in [
        (
            TreeParams {
                range: f64::NAN,
                ..params(500)
            },
            "range",
        ),
        (
            TreeParams {
                stair: 0.0,
                ..params(500)
            },
            "stair",
        ),
        (
            TreeParams {
                streams: 0,
                ..params(500)
            },
            "streams",
        ),
        (
            TreeParams {
                restart: Some(0),
                ..params(500)
            },
            "restarts",
        ),
        (
            TreeParams {
                domain: Domain::with_radius(f64::NAN),
                ..params(500)
            },
            "domain radii",
        ),
        (
            TreeParams {
                domain: Some(Domain {
                    least: 5.0,
                    ..Domain::ARM
                }),
                ..params(500)
            },
            "domain radii",
        ),
        (
            TreeParams {
                domain: Some(Domain {
                    alpha: 1.0,
                    ..Domain::ARM
                }),
                ..params(500)
            },
            "domain alpha",
        ),
    ] {
        let e = rrt_connect(
            &s.space,
            oracle.as_ref(),
            &groups,
            &q.start,
            &q.goal,
            &bad,
            1,
            &Deadline::none(),
        )
        .unwrap_err();
        assert!(
            matches!(&e, TreeError::Params(m) if m.contains(says)),
            "{says}: {e}"
        );
        assert!(e.to_string().starts_with("invalid tree parameters"), "{e}");
    }
    // and the valid ones still grow
    assert!(grow(&s, &params(500), 1).nodes.iter().sum::<usize>() > 2);
}

/// Consecutive pieces of one straight motion (as `straight_corners_of_motions` cuts an arm's
/// extends) are walked along the path, not asked again: a shortcut across them costs no call
/// and leaves the corners as they are; named as motions of their own, the same corners are
/// asked.
#[test]
fn a_shortcut_along_one_motion_is_walked_without_a_call() {
    use rand::SeedableRng;
    use viaroad::local::KnownPieces;
    use viaroad::roadmap::tree::shortcut_known;
    let s = scene("scenes/discs-cluttered.toml");
    let oracle = s.oracle();
    let groups = s.space.groups(false);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    // four corners 0.01 apart along x, the whole run free
    let path: Vec<Config> = loop {
        let q = free_sample(&s, oracle.as_ref(), &mut rng, &mut CallCounts::default());
        let path: Vec<Config> = (0..4).map(|k| vec![q[0] + 0.01 * k as f64, q[1]]).collect();
        if s.space.in_bounds(&path[3]) {
            let all = s.space.group_motion(&path[0], &path[3], &groups[0]);
            if viaroad::oracle::CountedOracle::check_motion(
                oracle.as_ref(),
                &all,
                &mut CallCounts::default(),
            )
            .unwrap()
            {
                break path;
            }
        }
    };
    for (motions, asked) in [(vec![0, 0, 0], false), (vec![0, 1, 2], true)] {
        let mut known = KnownPieces::new();
        known.certify_path(&s.space, &groups, &path);
        let (mut m, mut counts) = (motions.clone(), CallCounts::default());
        let short = shortcut_known(
            &s.space,
            oracle.as_ref(),
            &groups,
            &path,
            &mut m,
            16,
            &mut known,
            &mut counts,
            &Deadline::none(),
        )
        .unwrap();
        assert_eq!(counts.intersect_calls() > 0, asked, "motions {motions:?}");
        assert_eq!(m.len(), short.len() - 1);
        if !asked {
            assert_eq!((short.as_slice(), m), (path.as_slice(), motions));
        }
        assert_eq!((short.first(), short.last()), (path.first(), path.last()));
        Checker::for_scene(&s)
            .unwrap()
            .check_path(&short)
            .unwrap_or_else(|e| panic!("the shortcut path collides: {e}"));
    }
}
