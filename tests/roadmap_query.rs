//! Queries: every path re-checked by the independent checker, typed errors for bad ends,
//! A* against an independent Dijkstra, batches equal to single queries in any order.

use crate::roadmap_support;

use roadmap_support::*;
use std::collections::BinaryHeap;
use viaroad::local::LocalSpec;
use viaroad::oracle::CollisionOracle;
use viaroad::roadmap::{
    Endpoint, LearnParams, QueryError, QueryOptions, QueryOutcome, QueryPlanner, Roadmap,
};
use viaroad::scene::Scene;

fn scene_and_roadmap(feedback: bool, nodes: usize) -> (Scene, Roadmap) {
    let scene = disc_scene(21, 45, 0.06);
    let params = LearnParams {
        feedback,
        ..LearnParams::default()
    };
    let roadmap = learn(&scene, &LocalSpec::default(), &params, nodes, 5).roadmap;
    (scene, roadmap)
}

/// Shortest path lengths from `s` over the roadmap's edges: a Dijkstra of the test's own.
fn dijkstra(roadmap: &Roadmap, s: u32) -> Vec<f64> {
    #[derive(PartialEq)]
    struct Item(f64, usize);
    impl Eq for Item {}
    impl PartialOrd for Item {
        fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
            Some(self.cmp(o))
        }
    }
    impl Ord for Item {
        fn cmp(&self, o: &Self) -> std::cmp::Ordering {
            o.0.total_cmp(&self.0)
        }
    }
    let n = roadmap.node_count();
    let mut adj = vec![Vec::new(); n];
    for e in roadmap.edges() {
        adj[e.a as usize].push((e.b as usize, e.length));
        adj[e.b as usize].push((e.a as usize, e.length));
    }
    let mut dist = vec![f64::INFINITY; n];
    dist[s as usize] = 0.0;
    let mut heap = BinaryHeap::from([Item(0.0, s as usize)]);
    while let Some(Item(d, u)) = heap.pop() {
        if d > dist[u] {
            continue;
        }
        for &(v, w) in &adj[u] {
            if d + w < dist[v] {
                dist[v] = d + w;
                heap.push(Item(d + w, v));
            }
        }
    }
    dist
}

/// Every answer, direct or through the roadmap, is a chain of free segments from start to
/// goal; shortening never lengthens it. With the direct connection turned off every answer
/// goes through the roadmap.
#[test]
fn every_answer_is_free_and_shortening_never_lengthens() {
    for feedback in [true, false] {
        let (scene, roadmap) = scene_and_roadmap(feedback, 3000);
        let d = discs(&scene);
        let oracle = scene.oracle();
        let queries = random_queries(&scene, 150, 77);
        let mut solved_by_variant = Vec::new();
        for (try_direct, direct_calls) in [(true, 0), (true, 32), (false, 0)] {
            let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
                .unwrap()
                .with_options(QueryOptions {
                    try_direct,
                    direct_calls,
                    ..QueryOptions::default()
                });
            let mut solved_set = Vec::new();
            let mut solved = 0;
            let mut through_roadmap = 0;
            for (s, g) in &queries {
                let r = planner.query(s, g).unwrap();
                if !r.is_solved() {
                    assert!(r.path.is_empty() && r.raw_path.is_empty());
                    continue;
                }
                solved += 1;
                solved_set.push((s.clone(), g.clone()));
                through_roadmap += usize::from(r.outcome == QueryOutcome::Roadmap);
                for path in [&r.raw_path, &r.path] {
                    assert!(
                        path_free(path, &d),
                        "feedback={feedback}: {path:?} collides"
                    );
                    assert_eq!(path.first(), Some(s));
                    assert_eq!(path.last(), Some(g));
                }
                assert!((polyline_length(&r.path) - r.length).abs() < 1e-9);
                assert!((polyline_length(&r.raw_path) - r.raw_length).abs() < 1e-9);
                assert!(r.length <= r.raw_length + 1e-12);
            }
            eprintln!(
                "feedback={feedback} direct={try_direct} calls={direct_calls}: {solved}/150 \
                 solved, {through_roadmap} through the roadmap"
            );
            if !try_direct {
                assert_eq!(through_roadmap, solved);
            } else if direct_calls > 0 {
                // the via-point planner joins many random pairs of this scene directly
                assert!(through_roadmap < solved, "no query answered directly");
            }
            assert!(
                solved >= 140,
                "feedback={feedback} direct={try_direct}: only {solved} of 150 solved"
            );
            solved_by_variant.push(solved_set);
        }
        // the quick try only reorders the attempts: both direct variants solve the same queries
        assert_eq!(solved_by_variant[0], solved_by_variant[1]);
    }
}

/// The roadmap part of a raw path is a shortest path between the attached nodes (A* with an
/// admissible heuristic equals Dijkstra).
/// With the space's distance alone and with landmarks, A* finds shortest roadmap paths.
#[test]
fn astar_finds_shortest_roadmap_paths() {
    let (scene, roadmap) = scene_and_roadmap(true, 600);
    let oracle = scene.oracle();
    for landmarks in [0, 8] {
        let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
            .unwrap()
            .with_options(QueryOptions {
                try_direct: false,
                shorten: false,
                landmarks,
                ..QueryOptions::default()
            });
        let mut checked = 0;
        for (s, g) in random_queries(&scene, 60, 3) {
            let r = planner.query(&s, &g).unwrap();
            if r.outcome != QueryOutcome::Roadmap {
                continue;
            }
            let (a, b) = (r.start_node.unwrap(), r.goal_node.unwrap());
            assert_eq!(roadmap.component(a), roadmap.component(b));
            assert_eq!(r.shorten_s, 0.0, "nothing shortened, no time shortening");
            assert_eq!(r.path, r.raw_path);
            let through = dijkstra(&roadmap, a)[b as usize];
            // raw = attach(start → a) + roadmap(a → b) + attach(b → goal)
            let ia = r
                .raw_path
                .iter()
                .position(|q| q == roadmap.node(a))
                .unwrap();
            let ib = r
                .raw_path
                .iter()
                .rposition(|q| q == roadmap.node(b))
                .unwrap();
            let middle = polyline_length(&r.raw_path[ia..=ib]);
            assert!(
                (middle - through).abs() < 1e-9 * (1.0 + through),
                "landmarks {landmarks}: A* {middle} vs Dijkstra {through}"
            );
            checked += 1;
        }
        assert!(checked > 20, "only {checked} roadmap answers");
    }
}

/// Landmark bounds never exceed the roadmap distance (A* stays exact) and are not idle: they
/// beat the straight-line distance for many pairs of this cluttered scene.
#[test]
fn landmark_bounds_are_lower_bounds() {
    let (_, roadmap) = scene_and_roadmap(false, 300);
    let landmarks = viaroad::roadmap::Landmarks::new(&roadmap, 8);
    assert_eq!(landmarks.len(), 8);
    let space = roadmap.space();
    let n = roadmap.node_count() as u32;
    let mut tighter = 0;
    for v in (0..n).step_by(7) {
        let d = dijkstra(&roadmap, v);
        for g in 0..n {
            let bound = landmarks.lower_bound(v, g);
            assert!(
                bound <= d[g as usize] + 1e-9 * (1.0 + bound),
                "{v} → {g}: bound {bound} > distance {}",
                d[g as usize]
            );
            if d[g as usize].is_finite()
                && bound > space.distance(roadmap.node(v), roadmap.node(g)) + 1e-9
            {
                tighter += 1;
            }
        }
    }
    assert!(
        tighter > 100,
        "only {tighter} bounds beat the space's distance"
    );
}

#[test]
fn bad_ends_are_typed_errors() {
    let (scene, roadmap) = scene_and_roadmap(true, 100);
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let free = random_queries(&scene, 1, 1)[0].0.clone();
    let inside = match &scene.obstacles[0] {
        viaroad::scene::Obstacle::Disc { centre, .. } => centre.clone(),
        _ => unreachable!(),
    };
    assert!(matches!(
        planner.query(&[0.5], &free),
        Err(QueryError::InvalidConfig {
            endpoint: Endpoint::Start,
            ..
        })
    ));
    assert!(matches!(
        planner.query(&free, &[f64::NAN, 0.5]),
        Err(QueryError::InvalidConfig {
            endpoint: Endpoint::Goal,
            ..
        })
    ));
    assert!(matches!(
        planner.query(&[1.5, 0.5], &free),
        Err(QueryError::OutOfBounds {
            endpoint: Endpoint::Start,
            ..
        })
    ));
    assert!(matches!(
        planner.query(&free, &inside),
        Err(QueryError::InCollision {
            endpoint: Endpoint::Goal,
            ..
        })
    ));
}

/// A start enclosed by a ring of discs: with roadmap nodes inside the ring it is attached to
/// a component the goal never reaches ([`QueryOutcome::Disconnected`]); with none inside it
/// cannot be attached at all, and the outcome says which end failed.
#[test]
fn an_enclosed_start_is_disconnected_or_not_attached() {
    let mut ring = disc_scene(1, 0, 0.1);
    for k in 0..24 {
        let a = k as f64 * std::f64::consts::TAU / 24.0;
        ring.obstacles.push(viaroad::scene::Obstacle::Disc {
            centre: vec![0.5 + 0.2 * a.cos(), 0.5 + 0.2 * a.sin()],
            radius: 0.04,
        });
    }
    let oracle = ring.oracle();
    let params = LearnParams::default();
    let inside = |q: &[f64]| ((q[0] - 0.5).powi(2) + (q[1] - 0.5).powi(2)).sqrt() < 0.2;

    let roadmap = learn(&ring, &LocalSpec::default(), &params, 300, 1).roadmap;
    assert!(roadmap.nodes().any(inside));
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let r = planner.query(&[0.5, 0.5], &[0.02, 0.02]).unwrap();
    assert_eq!(r.outcome, QueryOutcome::Disconnected);
    assert!(!r.is_solved() && r.path.is_empty() && r.attach_attempts >= 2);

    // learnt with the ring's inside filled: no node inside, the start sees none
    let mut filled = ring.clone();
    filled.obstacles.push(viaroad::scene::Obstacle::Disc {
        centre: vec![0.5, 0.5],
        radius: 0.2,
    });
    let roadmap = learn(&filled, &LocalSpec::default(), &params, 300, 1).roadmap;
    assert!(!roadmap.nodes().any(inside));
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let r = planner.query(&[0.5, 0.5], &[0.02, 0.02]).unwrap();
    assert_eq!(
        r.outcome,
        QueryOutcome::NotAttached {
            start_attached: false,
            goal_attached: true
        }
    );
    assert!(r.path.is_empty());
}

/// Without obstacles in the way the direct connection answers.
#[test]
fn a_free_straight_line_is_answered_directly() {
    let scene = disc_scene(1, 0, 0.1);
    let roadmap = learn(&scene, &LocalSpec::Straight, &LearnParams::default(), 50, 1).roadmap;
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let r = planner.query(&[0.1, 0.1], &[0.9, 0.8]).unwrap();
    assert_eq!(r.outcome, QueryOutcome::Direct);
    assert_eq!(r.path, vec![vec![0.1, 0.1], vec![0.9, 0.8]]);
    assert_eq!(r.attach_attempts, 0);
}

/// A batch gives the answers of single queries, in input order, whatever order it is asked in:
/// queries do not change the roadmap.
#[test]
fn batches_answer_like_single_queries_in_any_order() {
    let (scene, roadmap) = scene_and_roadmap(true, 500);
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let mut queries = random_queries(&scene, 60, 12);
    queries.push((vec![2.0, 0.0], queries[0].1.clone()));
    let single: Vec<_> = queries.iter().map(|(s, g)| planner.query(s, g)).collect();
    let batch = planner.query_batch(&queries);
    assert_eq!(batch.len(), queries.len());
    for (a, b) in single.iter().zip(&batch) {
        assert_eq!(a, &b.result);
    }
    let mut reversed = queries.clone();
    reversed.reverse();
    let back = planner.query_batch(&reversed);
    for (a, b) in single.iter().rev().zip(&back) {
        assert_eq!(a, &b.result);
    }
    assert!(matches!(
        batch.last().unwrap().result,
        Err(QueryError::OutOfBounds { .. })
    ));
}

/// Answers serialise to JSON for the command line's `--json`.
#[test]
fn answers_serialise_to_json() {
    let scene = disc_scene(1, 0, 0.1);
    let roadmap = learn(&scene, &LocalSpec::Straight, &LearnParams::default(), 20, 1).roadmap;
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let r = planner.query(&[0.1, 0.1], &[0.9, 0.8]).unwrap();
    let v: serde_json::Value = serde_json::to_value(&r).unwrap();
    assert_eq!(v["outcome"], "direct");
    assert_eq!(v["path"], serde_json::json!([[0.1, 0.1], [0.9, 0.8]]));
    assert_eq!(v["counts"]["segment_calls"], r.counts.segment_calls);
    let info = serde_json::to_value(roadmap.info()).unwrap();
    assert_eq!(info["nodes"], roadmap.node_count());
    assert!(roadmap
        .info()
        .to_string()
        .contains("local method     straight"));
}

/// A per-query call budget ([`QueryOptions::max_calls`]): a budget no query reaches changes no
/// answer; a small one ends queries with [`QueryOutcome::OutOfCalls`] once it is spent, keeps
/// every unsolved query within the budget and one via-point walk past it, and every answer it
/// still gives is free under the independent checker.
#[test]
fn a_call_budget_bounds_each_query() {
    let (scene, roadmap) = scene_and_roadmap(false, 200);
    let d = discs(&scene);
    let oracle = scene.oracle();
    let queries = random_queries(&scene, 100, 31);
    let answers = |max_calls: Option<u64>| {
        let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
            .unwrap()
            .with_options(QueryOptions {
                try_direct: false,
                escalation_candidates: 3,
                max_calls,
                ..QueryOptions::default()
            });
        queries
            .iter()
            .map(|(s, g)| planner.query(s, g).unwrap())
            .collect::<Vec<_>>()
    };
    let unlimited = answers(None);
    assert_eq!(answers(Some(u64::MAX / 2)), unlimited);
    let budget = 6;
    let tight = answers(Some(budget));
    let (mut out_of_calls, mut worst) = (0, 0);
    for (i, r) in tight.iter().enumerate() {
        if r.is_solved() {
            assert!(path_free(&r.path, &d), "query {i}: a colliding path");
            continue;
        }
        let calls = r.counts.intersect_calls();
        worst = worst.max(calls);
        if r.outcome == QueryOutcome::OutOfCalls {
            out_of_calls += 1;
            assert!(calls >= budget, "query {i}: out of calls after {calls}");
        }
    }
    // the via-point search checks its budget between via points: one walk (a few segments
    // on a disc scene) may end past it
    assert!(worst <= budget + 8, "an unsolved query spent {worst} calls");
    assert!(
        out_of_calls > 0,
        "a budget of {budget} calls stopped no query"
    );
    let total = |rs: &[viaroad::roadmap::QueryResult]| -> u64 {
        rs.iter().map(|r| r.counts.intersect_calls()).sum()
    };
    assert!(total(&tight) < total(&unlimited));
}

/// Attaching tries the direct path to each of the nearest nodes before the via-point search
/// (`QueryOptions::attach_direct_candidates`): where a candidate of the start is in straight
/// sight, the answer leaves the start on a straight line to a roadmap node. With that first
/// pass off, the search to the nearest node may dodge through via points instead — the scene
/// has such queries, or this test would show nothing.
#[test]
fn attaching_tries_straight_lines_to_the_candidates_first() {
    let (scene, roadmap) = scene_and_roadmap(true, 200);
    let d = discs(&scene);
    let oracle = scene.oracle();
    let queries = random_queries(&scene, 150, 78);
    let bits = |q: &[f64]| q.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
    let nodes: std::collections::HashSet<Vec<u64>> = (0..roadmap.node_count() as u32)
        .map(|i| bits(roadmap.node(i)))
        .collect();
    let k = QueryOptions::default().attach_candidates;
    let mut via_first = [0usize; 2];
    let mut in_sight = 0;
    for (v, direct) in [0, QueryOptions::default().attach_direct_candidates]
        .into_iter()
        .enumerate()
    {
        let planner = attaching_planner(&roadmap, oracle.as_ref(), direct);
        for (s, g) in &queries {
            let r = planner.query(s, g).unwrap();
            if !r.is_solved() {
                continue;
            }
            assert!(path_free(&r.raw_path, &d) && path_free(&r.path, &d));
            let sight = roadmap
                .nearest(s, k, None)
                .iter()
                .any(|&(n, _)| path_free(&[s.clone(), roadmap.node(n).to_vec()], &d));
            if !sight {
                continue;
            }
            in_sight += usize::from(v == 1);
            if !nodes.contains(&bits(&r.raw_path[1])) {
                via_first[v] += 1;
            }
        }
    }
    eprintln!("{in_sight} starts in sight of a candidate; via points first: {via_first:?}");
    assert!(in_sight > 100, "only {in_sight} starts see a candidate");
    assert_eq!(
        via_first[1], 0,
        "a start in sight of a node attached through via points"
    );
    assert!(
        via_first[0] > 0,
        "no query attaches through via points without the first pass"
    );
}

/// A planner that attaches start and goal (no quick try from one to the other), trying the
/// direct path to the nearest `direct` candidates first.
fn attaching_planner<'a>(
    roadmap: &'a Roadmap,
    oracle: &'a dyn CollisionOracle,
    direct: usize,
) -> QueryPlanner<'a> {
    QueryPlanner::new(roadmap, oracle)
        .unwrap()
        .with_options(QueryOptions {
            try_direct: false,
            attach_direct_candidates: direct,
            ..QueryOptions::default()
        })
}

/// A `straight` roadmap's method is the direct check itself: the first pass of direct paths is
/// not run for it, so each candidate is asked once (the same attempts and calls as without it).
#[test]
fn straight_roadmaps_attach_without_a_first_pass() {
    let scene = disc_scene(22, 150, 0.05);
    let roadmap = learn(
        &scene,
        &LocalSpec::Straight,
        &LearnParams::default(),
        300,
        5,
    )
    .roadmap;
    let oracle = scene.oracle();
    let queries = random_queries(&scene, 40, 79);
    let answers = |direct: usize| -> Vec<(u32, u64)> {
        let planner = attaching_planner(&roadmap, oracle.as_ref(), direct);
        queries
            .iter()
            .map(|(s, g)| {
                let r = planner.query(s, g).unwrap();
                (r.attach_attempts, r.counts.intersect_calls())
            })
            .collect()
    };
    let with = answers(QueryOptions::default().attach_direct_candidates);
    assert!(
        with.iter().any(|&(a, _)| a > 2),
        "every end attached at once"
    );
    assert_eq!(with, answers(0));
}

/// Counts the questions asked of an oracle: all collision intervals, or yes/no.
struct Asked<'a> {
    inner: &'a dyn CollisionOracle,
    intervals: std::sync::atomic::AtomicUsize,
    yes_no: std::sync::atomic::AtomicUsize,
}

impl Asked<'_> {
    /// (intervals, yes/no) asked since the last call; the counts start again from zero.
    fn take(&self) -> (usize, usize) {
        use std::sync::atomic::Ordering::Relaxed;
        (
            self.intervals.swap(0, Relaxed),
            self.yes_no.swap(0, Relaxed),
        )
    }
}

impl CollisionOracle for Asked<'_> {
    fn intervals(
        &self,
        motion: &viaroad::space::Motion,
        counts: &mut viaroad::oracle::CallCounts,
    ) -> Result<viaroad::interval::IntervalList, viaroad::oracle::OracleError> {
        self.intervals
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.inner.intervals(motion, counts)
    }

    fn collides(&self, q: &[f64], counts: &mut viaroad::oracle::CallCounts) -> bool {
        self.inner.collides(q, counts)
    }

    fn motion_is_free(
        &self,
        motion: &viaroad::space::Motion,
        counts: &mut viaroad::oracle::CallCounts,
    ) -> Result<bool, viaroad::oracle::OracleError> {
        self.yes_no
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.inner.motion_is_free(motion, counts)
    }
}

/// The quick try from start to goal is the direct path asked yes/no, piece by piece: where the
/// via-point planner at depth 0 connects, the query answers `Direct` with the same path and
/// asks no collision intervals at all (at depth 0 they are never used, and a blocked piece's
/// intervals cost a whole sweep where yes/no stops at the first collision); where it does not,
/// the query goes on to the roadmap. Axis-parallel groups, so a direct path has two pieces.
#[test]
fn the_quick_try_asks_yes_or_no_for_the_direct_path() {
    let scene = disc_scene(23, 45, 0.06);
    let spec: LocalSpec = "viapoint:max=3,calls=1000,split=true".parse().unwrap();
    let roadmap = learn(&scene, &spec, &LearnParams::default(), 200, 5).roadmap;
    let d = discs(&scene);
    let plain = scene.oracle();
    let asked = Asked {
        inner: plain.as_ref(),
        intervals: 0.into(),
        yes_no: 0.into(),
    };
    let planner = QueryPlanner::new(&roadmap, &asked)
        .unwrap()
        .with_options(QueryOptions {
            shorten: false,
            ..QueryOptions::default()
        });
    let depth0 = spec.budgeted(0).unwrap().build();
    let (mut direct, mut blocked) = (0, 0);
    for (s, g) in random_queries(&scene, 150, 80) {
        let reference = depth0
            .connect(&scene.space, plain.as_ref(), &s, &g)
            .unwrap();
        asked.take();
        let r = planner.query(&s, &g).unwrap();
        let (intervals, yes_no) = asked.take();
        if reference.is_connected() {
            direct += 1;
            assert_eq!(r.outcome, QueryOutcome::Direct);
            assert_eq!(r.raw_path, reference.path);
            assert!(path_free(&r.raw_path, &d));
            assert_eq!((intervals, yes_no), (0, reference.path.len() - 1));
            assert_eq!(
                r.counts.intersect_calls(),
                reference.counts.intersect_calls()
            );
        } else {
            blocked += 1;
            assert!(yes_no >= 1, "the blocked direct path was not asked");
            if r.is_solved() {
                assert!(path_free(&r.raw_path, &d));
            }
        }
    }
    eprintln!("{direct} direct, {blocked} blocked");
    assert!(
        direct >= 10 && blocked >= 10,
        "{direct} direct, {blocked} blocked"
    );
}

/// An answer still longer than `TREE_SHORTENING_FACTOR × exact_shortening_limit` corners after
/// its first greedy pass is shortened by greedy passes alone (the visibility graph over hundreds
/// of corners took 0.9 s in the cage workcell), a shorter one by the visibility graph: both
/// rebuilt here from the answer's raw path with the public passes, every path checked free by
/// the independent segment test.
#[test]
fn long_answers_get_greedy_passes_only() {
    use viaroad::local::{drop_corners, shorten};
    use viaroad::oracle::CallCounts;
    use viaroad::roadmap::query::TREE_SHORTENING_FACTOR;
    let (scene, roadmap) = scene_and_roadmap(true, 400);
    let d = discs(&scene);
    let oracle = scene.oracle();
    let limit = 2;
    let long = TREE_SHORTENING_FACTOR * limit;
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            exact_shortening_limit: limit,
            ..QueryOptions::default()
        });
    let groups = roadmap.header().local_spec.build().groups(roadmap.space());
    let (mut greedy_only, mut graph) = (0, 0);
    for (s, g) in random_queries(&scene, 60, 11) {
        let a = planner.query(&s, &g).unwrap();
        if !a.is_solved() || a.outcome != QueryOutcome::Roadmap {
            continue;
        }
        assert!(path_free(&a.path, &d), "{s:?} → {g:?}");
        let c = &mut CallCounts::default();
        let once = if a.raw_path.len() > limit {
            drop_corners(&scene.space, oracle.as_ref(), &groups, &a.raw_path, c).unwrap()
        } else {
            a.raw_path.clone()
        };
        let want = if once.len() > long {
            greedy_only += 1;
            let mut fewer = once;
            loop {
                let next = drop_corners(&scene.space, oracle.as_ref(), &groups, &fewer, c).unwrap();
                let better = next.len() < fewer.len();
                fewer = next;
                if !better {
                    break fewer;
                }
            }
        } else {
            graph += 1;
            shorten(&scene.space, oracle.as_ref(), &groups, &once, c).unwrap()
        };
        assert_eq!(a.path, want, "{s:?} → {g:?}");
    }
    assert!(
        greedy_only > 0 && graph > 0,
        "{greedy_only} long, {graph} short"
    );
}
