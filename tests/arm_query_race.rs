//! A roadmap query that races trees out of the roadmap (`QueryOptions::race`, the default of
//! `viaroad query` and `serve` for arms): its answer is certified by the independent
//! [`viaroad::robot::ArmChecker`], without a time limit it is the same on every run (both sides
//! run to their own budgets, the roadmap's answer preferred), and an end in collision is refused
//! before any tree grows; an error of the trees is reported when the roadmap gives no answer.

use std::path::Path;
use std::time::Duration;
use viaroad::bench::mbm::{check_step, checker};
use viaroad::interval::IntervalList;
use viaroad::local::LocalSpec;
use viaroad::oracle::{CallCounts, CollisionOracle, OracleError};
use viaroad::roadmap::tree::{Stairs, TreeParams};
use viaroad::roadmap::{
    Budget, LearnParams, Learner, QueryError, QueryOptions, QueryOutcome, QueryPlanner, Roadmap,
};
use viaroad::scene::Scene;
use viaroad::space::Motion;

/// MotionBenchMaker's box 1 and a 40-node roadmap of it, which does not reach into the box
/// (tests/arm_workcell.rs): its query is left to the trees.
fn box_and_roadmap() -> (Scene, Roadmap) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda-box-1.toml");
    let scene = Scene::load(&path).unwrap();
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let roadmap = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(40), 1, &mut |_| {})
        .unwrap()
        .roadmap;
    (scene, roadmap)
}

#[test]
fn a_racing_query_is_certified_reproducible_and_refuses_an_end_in_collision() {
    let (scene, roadmap) = box_and_roadmap();
    let oracle = scene.oracle();
    let trees = TreeParams {
        max_nodes: Some(3000),
        ..TreeParams::for_space(&scene.space)
    };
    let options = QueryOptions {
        trees: Some(trees),
        race: Some(Duration::ZERO),
        max_calls: Some(2000),
        landmarks: 0,
        ..QueryOptions::default()
    };
    assert_eq!(
        QueryOptions::default().with_arm_trees(&scene.space).race,
        Some(QueryOptions::DEFAULT_HEAD_START)
    );
    // a fresh oracle for the queries: the learner's keeps its answers, so that a query asking
    // it tests fewer pairs than one asking a fresh one
    let asked = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, asked.as_ref())
        .unwrap()
        .with_options(options);
    let q = &scene.checked_queries().unwrap()[0];
    let a = planner.query(&q.start, &q.goal).unwrap();
    // the 40-node roadmap does not reach into the box (tests/arm_workcell.rs): the trees answer
    assert_eq!(a.outcome, QueryOutcome::Trees, "{:?}", a.outcome);
    assert!(a.grown_nodes > 0 && a.path.len() >= 2);
    assert!(a.length <= a.raw_length + 1e-9);
    let check = checker(&scene).unwrap();
    for p in [&a.raw_path, &a.path] {
        assert_eq!((p.first(), p.last()), (Some(&q.start), Some(&q.goal)));
        let report = check.check_path(p, check_step(&check)).unwrap();
        assert!(report.valid, "{report:?}");
    }
    // the roadmap's calls are counted with the trees'
    assert!(a.counts.intersect_calls() > 0);
    // asked again of another fresh oracle (the first one now keeps this query's answers)
    let fresh = scene.oracle();
    let again = QueryPlanner::new(&roadmap, fresh.as_ref())
        .unwrap()
        .with_options(planner.options().clone());
    let b = again.query(&q.start, &q.goal).unwrap();
    // everything but the primitive pairs tested, which the thread's warm caches of the exact
    // sweep lower (the calls are the same)
    let same = |r: &viaroad::roadmap::QueryResult| {
        (
            r.outcome,
            r.raw_path.clone(),
            r.path.clone(),
            r.counts.intersect_calls(),
            r.counts.state_checks,
            r.grown_nodes,
        )
    };
    assert_eq!(same(&b), same(&a), "no time limit: the same answer again");
    // an end in collision: a typed error, whichever end
    let inside = (0..200)
        .map(|k| {
            let mut c = q.goal.clone();
            c[1] += 0.01 * k as f64;
            c
        })
        .find(|c| scene.space.check(c).is_ok() && oracle.collides(c, &mut CallCounts::default()))
        .expect("bending joint 2 down runs the arm into the box");
    for (s, g) in [(&inside, &q.goal), (&q.start, &inside)] {
        match planner.query(s, g) {
            Err(QueryError::InCollision { .. }) => {}
            other => panic!("expected InCollision, got {other:?}"),
        }
    }
}

/// The scene's oracle refusing first-hit questions, which only the trees ask (first-hit
/// prefixes of partial stairs): the trees fail, the roadmap's search does not.
struct NoFirstHit(Box<dyn CollisionOracle>);

impl CollisionOracle for NoFirstHit {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        self.0.intervals(motion, counts)
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        self.0.collides(q, counts)
    }

    fn surely_collides(&self, q: &[f64]) -> Option<bool> {
        self.0.surely_collides(q)
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        self.0.motion_is_free(motion, counts)
    }

    fn first_collision(
        &self,
        _motion: &Motion,
        _counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        Err(OracleError::Unsupported("first hits refused".into()))
    }
}

#[test]
fn the_trees_error_is_reported_when_the_roadmap_gives_no_answer() {
    let (scene, roadmap) = box_and_roadmap();
    let refusing = NoFirstHit(scene.oracle());
    let planner = QueryPlanner::new(&roadmap, &refusing)
        .unwrap()
        .with_options(QueryOptions {
            // staircases, whose stairs ask for first hits, where a straight extend is not proved
            trees: Some(TreeParams {
                stairs: Stairs::Prefix,
                staircase: true,
                ..TreeParams::for_space(&scene.space)
            }),
            race: Some(Duration::ZERO),
            max_calls: Some(300),
            landmarks: 0,
            ..QueryOptions::default()
        });
    let q = &scene.checked_queries().unwrap()[0];
    match planner.query(&q.start, &q.goal) {
        Err(QueryError::Oracle(OracleError::Unsupported(m))) => {
            assert!(m.contains("first hits refused"), "{m}")
        }
        other => panic!("expected the trees' error, got {other:?}"),
    }
}

/// A race is a schedule, not a thread: with no pool thread free to grow the trees (a pool of
/// one thread, a batch of more racing queries than threads), the query runs the roadmap's
/// search and the trees in turn and answers as it does alone, never timing out while the trees
/// wait for a thread.
#[test]
fn racing_arm_queries_are_answered_on_one_thread_and_in_a_batch_larger_than_the_pool() {
    let (scene, roadmap) = box_and_roadmap();
    let oracle = scene.oracle();
    let options = QueryOptions {
        time: Some(Duration::from_secs(30)),
        ..QueryOptions::default().with_arm_trees(&scene.space)
    };
    assert!(options.race.is_some() && options.trees.is_some());
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(options);
    let q = &scene.checked_queries().unwrap()[0];
    let check = checker(&scene).unwrap();
    let certified = |a: &viaroad::roadmap::QueryResult, (s, g): (&Vec<f64>, &Vec<f64>)| {
        assert!(a.is_solved(), "{:?}", a.outcome);
        assert_eq!((a.path.first(), a.path.last()), (Some(s), Some(g)));
        let report = check.check_path(&a.path, check_step(&check)).unwrap();
        assert!(report.valid, "{report:?}");
    };
    let pool = |n| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
    };
    // both ways, so that the batch is not one query asked eight times
    let batch: Vec<_> = (0..8)
        .map(|i| match i % 2 {
            0 => (q.start.clone(), q.goal.clone()),
            _ => (q.goal.clone(), q.start.clone()),
        })
        .collect();
    let one = pool(1);
    let alone = one.install(|| planner.query(&q.start, &q.goal)).unwrap();
    certified(&alone, (&q.start, &q.goal));
    let answers = one.install(|| planner.query_batch(&batch[..2]));
    for (answer, (s, g)) in answers.into_iter().zip(&batch) {
        certified(&answer.result.unwrap(), (s, g));
    }
    let answers = pool(2).install(|| planner.query_batch(&batch));
    for (answer, (s, g)) in answers.into_iter().zip(&batch) {
        certified(&answer.result.unwrap(), (s, g));
    }
}
