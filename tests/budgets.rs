//! Budgets that hold: the deadline stops the via-point search, the learner and queries within
//! one oracle call. The tests trip a cancel flag from inside the oracle after a fixed number of
//! calls, so they assert call counts, never wall-clock times.

use crate::roadmap_support;

use roadmap_support::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use viaroad::deadline::Deadline;
use viaroad::interval::IntervalList;
use viaroad::local::{LocalMethod, LocalSpec, Outcome, ViaPoint, ViaPointOptions};
use viaroad::oracle::{CallCounts, CollisionOracle, OracleError};
use viaroad::roadmap::{
    Budget, LearnParams, Learner, QueryOptions, QueryOutcome, QueryPlanner, StopReason,
};
use viaroad::space::Motion;

/// Passes every question to the scene's oracle, counts the motions asked about, and raises
/// `flag` once `trip_at` of them have been answered.
struct Tripwire {
    inner: Box<dyn CollisionOracle>,
    motions: AtomicU64,
    trip_at: u64,
    flag: Arc<AtomicBool>,
    /// The call that trips the wire gives up as a long call does at a watched deadline
    /// ([`viaroad::deadline::watching`]) instead of answering.
    gives_up: bool,
}

impl Tripwire {
    fn new(inner: Box<dyn CollisionOracle>, trip_at: u64) -> Self {
        Tripwire {
            inner,
            motions: AtomicU64::new(0),
            trip_at,
            flag: Arc::new(AtomicBool::new(false)),
            gives_up: false,
        }
    }

    fn giving_up(mut self) -> Self {
        self.gives_up = true;
        self
    }

    fn count(&self) {
        if self.motions.fetch_add(1, Ordering::SeqCst) + 1 >= self.trip_at {
            self.flag.store(true, Ordering::SeqCst);
        }
    }

    fn deadline(&self) -> Deadline {
        Deadline::none().with_cancel(self.flag.clone())
    }

    fn motions(&self) -> u64 {
        self.motions.load(Ordering::SeqCst)
    }
}

impl CollisionOracle for Tripwire {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        self.count();
        if self.gives_up && self.flag.load(Ordering::SeqCst) {
            return Err(OracleError::Interrupted);
        }
        self.inner.intervals(motion, counts)
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        self.inner.collides(q, counts)
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        self.count();
        self.inner.motion_is_free(motion, counts)
    }
}

/// A query of a cluttered disc scene that the deep via-point search needs many calls for.
fn hard_pair(scene: &viaroad::scene::Scene, method: &ViaPoint) -> (Vec<f64>, Vec<f64>, u64) {
    let oracle = scene.oracle();
    random_queries(scene, 200, 3)
        .into_iter()
        .map(|(s, g)| {
            let c = method
                .connect(&scene.space, oracle.as_ref(), &s, &g)
                .unwrap();
            let calls = c.counts.intersect_calls();
            (s, g, calls)
        })
        .max_by_key(|p| p.2)
        .unwrap()
}

/// A cluttered disc scene, the via-point planner without a call budget, and the query it
/// needs the most calls for (more than 40).
fn long_search() -> (viaroad::scene::Scene, ViaPoint, Vec<f64>, Vec<f64>) {
    let scene = disc_scene(4, 120, 0.05);
    let method = ViaPoint::new(ViaPointOptions {
        max_calls: None,
        ..ViaPointOptions::default()
    });
    let (s, g, unlimited) = hard_pair(&scene, &method);
    assert!(
        unlimited > 40,
        "the test needs a long search, got {unlimited} calls"
    );
    (scene, method, s, g)
}

/// What a stopped search certified before the stop is free.
fn assert_discoveries_free(scene: &viaroad::scene::Scene, c: &viaroad::local::Connection) {
    let d = discs(scene);
    for &(i, j) in &c.discoveries.free_segments {
        let (p, q) = (
            &c.discoveries.configs[i as usize],
            &c.discoveries.configs[j as usize],
        );
        assert!(segment_free(p, q, &d), "{p:?} → {q:?}");
    }
}

#[test]
fn the_viapoint_search_stops_within_one_call_of_its_deadline() {
    let (scene, method, s, g) = long_search();
    let wire = Tripwire::new(scene.oracle(), 20);
    let c = method
        .connect_within(&scene.space, &wire, &s, &g, &wire.deadline())
        .unwrap();
    assert_eq!(c.outcome, Outcome::Interrupted);
    assert!(c.path.is_empty());
    assert_eq!(wire.motions(), 20, "asked {} motions", wire.motions());
    assert_eq!(c.counts.intersect_calls(), 20);
    assert_discoveries_free(&scene, &c);
    // a deadline already past asks nothing
    let wire = Tripwire::new(scene.oracle(), 1);
    let c = method
        .connect_within(
            &scene.space,
            &wire,
            &s,
            &g,
            &Deadline::after(Duration::ZERO),
        )
        .unwrap();
    assert_eq!((c.outcome, wire.motions()), (Outcome::Interrupted, 0));
}

/// A call that gives up at the watched deadline ends the search as its deadline does: no
/// path, an interrupted outcome, not an error, and what it certified before is still free.
#[test]
fn a_call_giving_up_at_the_deadline_ends_the_search_as_the_deadline_does() {
    let (scene, method, s, g) = long_search();
    let wire = Tripwire::new(scene.oracle(), 20).giving_up();
    let c = method
        .connect_within(&scene.space, &wire, &s, &g, &Deadline::none())
        .unwrap();
    assert_eq!(c.outcome, Outcome::Interrupted);
    assert!(c.path.is_empty());
    assert_eq!(wire.motions(), 20, "asked {} motions", wire.motions());
    assert_discoveries_free(&scene, &c);
}

/// An exact sweep of a whole joint range among the cage's faces gives up when the deadline
/// watched on its thread has passed, and keeps nothing of it: asked again unwatched, the arm
/// scene's oracle (which keeps its answers) answers as a fresh one does.
#[test]
fn a_long_joint_move_gives_up_at_a_watched_deadline_and_keeps_nothing() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda-cage-1.toml");
    let scene = viaroad::scene::Scene::load(&path).unwrap();
    let groups = LocalSpec::roadmap_default().build().groups(&scene.space);
    let goal = scene.queries[0].goal.clone();
    // joint 1 from its lower limit to its upper one, the arm reaching into the cage: the whole
    // arm swept through the cage's walls
    let (mut a, mut z) = (goal.clone(), goal);
    (a[0], z[0]) = (scene.space.lower()[0], scene.space.upper()[0]);
    let motion = scene.space.group_motion(&a, &z, &groups[0]);
    let oracle = scene.oracle();
    let past = Deadline::after(Duration::ZERO);
    let mut counts = CallCounts::default();
    let given_up = viaroad::deadline::watching(&past, || oracle.intervals(&motion, &mut counts));
    assert!(
        matches!(given_up, Err(OracleError::Interrupted)),
        "{given_up:?}"
    );
    let again = oracle.intervals(&motion, &mut counts).unwrap();
    let fresh = scene.oracle().intervals(&motion, &mut counts).unwrap();
    assert_eq!(again, fresh);
    assert!(!fresh.is_empty(), "the sweep meets the cage");
    // an unlimited deadline is never watched: the call answers
    let whole =
        viaroad::deadline::watching(&Deadline::none(), || oracle.intervals(&motion, &mut counts));
    assert_eq!(whole.unwrap(), fresh);
}

#[test]
fn learning_stops_within_a_call_per_thread_of_a_cancel_and_keeps_a_valid_roadmap() {
    let scene = disc_scene(6, 90, 0.05);
    let local = LocalSpec::roadmap_default().build();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let wire = Tripwire::new(scene.oracle(), 300);
        let learner = Learner::new(&scene.space, &wire, local.as_ref(), scene.fingerprint());
        let learnt = pool
            .install(|| {
                learner.learn_within(
                    &LearnParams::default(),
                    &Budget::nodes(1_000_000),
                    1,
                    &wire.deadline(),
                    &mut |_| {},
                )
            })
            .unwrap();
        assert_eq!(learnt.report.stop, StopReason::Cancelled);
        // each thread finishes the call it is in, nothing more
        assert!(
            wire.motions() < 300 + threads as u64,
            "{threads} threads asked {} motions",
            wire.motions()
        );
        let roadmap = &learnt.roadmap;
        assert!(roadmap.node_count() > 0 && roadmap.node_count() < 1_000_000);
        roadmap_valid(roadmap, &discs(&scene)).unwrap();
    }
    // a deadline already past learns nothing and asks nothing
    let wire = Tripwire::new(scene.oracle(), 1);
    let learner = Learner::new(&scene.space, &wire, local.as_ref(), scene.fingerprint());
    let learnt = learner
        .learn_within(
            &LearnParams::default(),
            &Budget::nodes(100),
            1,
            &Deadline::after(Duration::ZERO),
            &mut |_| {},
        )
        .unwrap();
    assert_eq!(learnt.report.stop, StopReason::TimeBudget);
    assert_eq!((learnt.roadmap.node_count(), wire.motions()), (0, 0));
}

/// A sparse roadmap cannot join some solvable queries; with a time limit the query grows a
/// copy of it around the ends and answers through that ([`QueryOutcome::Grown`]), with a path
/// the independent checker accepts. The saved roadmap is not changed.
#[test]
fn a_query_the_roadmap_cannot_join_grows_it_within_its_time() {
    let scene = disc_scene(8, 70, 0.06);
    let roadmap = learn(&scene, &LocalSpec::Straight, &LearnParams::default(), 12, 2).roadmap;
    let oracle = scene.oracle();
    let grid = GridComponents::new(&scene, 200);
    let d = discs(&scene);
    let plain = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let (s, g) = random_queries(&scene, 400, 9)
        .into_iter()
        .find(|(s, g)| grid.solvable(s, g) == Some(true) && !plain.query(s, g).unwrap().is_solved())
        .expect("a solvable query the sparse roadmap cannot answer");
    let growing = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            time: Some(Duration::from_secs(60)),
            ..QueryOptions::default()
        });
    let r = growing.query(&s, &g).unwrap();
    assert_eq!(r.outcome, QueryOutcome::Grown, "{r:?}");
    assert!(r.grown_nodes > 0);
    assert!(path_free(&r.path, &d) && path_free(&r.raw_path, &d));
    assert_eq!((&r.path[0], r.path.last().unwrap()), (&s, &g));
    // without growing, the same time limit changes nothing
    let no_grow = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            time: Some(Duration::from_secs(60)),
            grow: false,
            ..QueryOptions::default()
        });
    assert!(!no_grow.query(&s, &g).unwrap().is_solved());
}

/// A ring of 24 discs about the centre of the unit square, which nothing can enter or leave,
/// and a 100-node roadmap of it: the centre is free but cannot be joined to the outside.
fn ring_and_roadmap() -> (viaroad::scene::Scene, viaroad::roadmap::Roadmap) {
    let mut ring = disc_scene(1, 0, 0.1);
    for k in 0..24 {
        let a = k as f64 * std::f64::consts::TAU / 24.0;
        ring.obstacles.push(viaroad::scene::Obstacle::Disc {
            centre: vec![0.5 + 0.2 * a.cos(), 0.5 + 0.2 * a.sin()],
            radius: 0.04,
        });
    }
    let roadmap = learn(
        &ring,
        &LocalSpec::default(),
        &LearnParams::default(),
        100,
        1,
    )
    .roadmap;
    (ring, roadmap)
}

/// An enclosed start can never be joined: a growing query ends when its time does, unsolved.
#[test]
fn an_unanswerable_query_times_out() {
    let (ring, roadmap) = ring_and_roadmap();
    let oracle = ring.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            time: Some(Duration::from_millis(300)),
            ..QueryOptions::default()
        });
    let r = planner.query(&[0.5, 0.5], &[0.02, 0.02]).unwrap();
    assert_eq!(r.outcome, QueryOutcome::TimedOut);
    assert!(r.path.is_empty() && !r.is_solved());
}

/// Answers like the scene's oracle, a millisecond late: a scene whose calls are dear.
struct Slow(Box<dyn CollisionOracle>);

impl CollisionOracle for Slow {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        std::thread::sleep(Duration::from_millis(1));
        self.0.intervals(motion, counts)
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        self.0.collides(q, counts)
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        std::thread::sleep(Duration::from_millis(1));
        self.0.motion_is_free(motion, counts)
    }
}

/// Attaching an enclosed start tries its 30 nearest nodes with the via-point planner; where
/// calls are dear that alone outlasts the query's time. A query that may grow gives attaching
/// at most half of its time ([`viaroad::roadmap::ATTACH_SHARE`]), so the rest goes to growing
/// the roadmap, and the answer says it grew.
#[test]
fn dear_attaching_leaves_the_growing_its_share_of_the_time() {
    let (ring, roadmap) = ring_and_roadmap();
    let (start, goal) = ([0.5, 0.5], [0.02, 0.02]);
    // the attaching alone, uncapped: its calls take longer than the query below may
    let fast = ring.oracle();
    let plain = QueryPlanner::new(&roadmap, fast.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            grow: false,
            escalation_candidates: 0,
            ..QueryOptions::default()
        });
    let attaching = plain.query(&start, &goal).unwrap();
    let budget = 600;
    assert!(
        attaching.counts.intersect_calls() > budget,
        "attaching costs {} calls, not enough to outlast the query",
        attaching.counts.intersect_calls()
    );
    let slow = Slow(ring.oracle());
    let planner = QueryPlanner::new(&roadmap, &slow)
        .unwrap()
        .with_options(QueryOptions {
            time: Some(Duration::from_millis(budget)),
            ..QueryOptions::default()
        });
    let r = planner.query(&start, &goal).unwrap();
    assert_eq!(r.outcome, QueryOutcome::TimedOut, "{r:?}");
    assert!(r.grown_nodes > 0, "the query never grew: {r:?}");
}

/// Growing from nothing (single-query PRM): start and goal become connected nodes.
#[test]
fn connect_pair_grows_a_roadmap_from_start_and_goal() {
    let scene = disc_scene(12, 80, 0.05);
    let oracle = scene.oracle();
    let local = LocalSpec::roadmap_default().build();
    let grid = GridComponents::new(&scene, 200);
    let (s, g) = random_queries(&scene, 100, 4)
        .into_iter()
        .find(|(s, g)| grid.solvable(s, g) == Some(true) && !segment_free(s, g, &discs(&scene)))
        .unwrap();
    let learner = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref());
    let grown = learner
        .connect_pair(
            &LearnParams::default(),
            None,
            (&s, &g),
            &Budget::nodes(100_000),
            3,
            &Deadline::none(),
            &mut |_| {},
        )
        .unwrap();
    assert!(grown.connected);
    assert_eq!(grown.learnt.report.stop, StopReason::Connected);
    let roadmap = &grown.learnt.roadmap;
    assert_eq!(roadmap.node(grown.start), &s[..]);
    assert_eq!(roadmap.node(grown.goal), &g[..]);
    assert_eq!(
        roadmap.component(grown.start),
        roadmap.component(grown.goal)
    );
    roadmap_valid(roadmap, &discs(&scene)).unwrap();
}

/// The disc scene and 300-node roadmap of the shortening tests: its queries' raw paths have
/// many corners and many pairs to check.
fn shortening_scene() -> (viaroad::scene::Scene, viaroad::roadmap::Roadmap) {
    let scene = disc_scene(4, 120, 0.05);
    let roadmap = learn(
        &scene,
        &LocalSpec::default(),
        &LearnParams::default(),
        300,
        1,
    )
    .roadmap;
    (scene, roadmap)
}

/// Shortening honours the query's time (it did not: a workcell query of the cage ran its
/// shortening to the end, 19 s on a 5 s budget): the greedy pass and the visibility graph stop
/// within one check of the deadline, and what they return is still a valid path from start to
/// goal, never longer than their input (the greedy pass keeps the rest of its input; the
/// visibility graph returns the shortest path over the pairs it had found free, so a late stop
/// keeps what its checks found).
#[test]
fn shortening_stops_within_one_check_of_its_deadline() {
    use viaroad::local::{drop_corners_known, path_length, shorten_known, KnownPieces};
    let (scene, roadmap) = shortening_scene();
    let d = discs(&scene);
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            shorten: false,
            ..QueryOptions::default()
        });
    // the longest raw path of some queries: many corners, many pairs to check
    let raw = random_queries(&scene, 60, 9)
        .into_iter()
        .filter_map(|(s, g)| planner.query(&s, &g).ok().filter(|r| r.is_solved()))
        .map(|r| r.path)
        .max_by_key(|p| p.len())
        .unwrap();
    assert!(
        raw.len() >= 12,
        "the test needs a long path, got {}",
        raw.len()
    );
    assert!(path_free(&raw, &d));
    let groups = scene.space.groups(false);
    let known = || {
        let mut k = KnownPieces::new();
        k.certify_path(&scene.space, &groups, &raw);
        k
    };
    let ends = |p: &[Vec<f64>]| (p[0].clone(), p[p.len() - 1].clone());
    let want_ends = ends(&raw);
    // the two shortenings, each as `shorten_known` and `drop_corners_known` are called
    type Shortening = fn(
        &viaroad::space::Space,
        &dyn CollisionOracle,
        &[viaroad::space::Group],
        &[Vec<f64>],
        &mut KnownPieces,
        &mut CallCounts,
        &Deadline,
    ) -> Result<Vec<Vec<f64>>, OracleError>;
    let greedy: Shortening = drop_corners_known;
    let graph: Shortening = shorten_known;
    let raw_length = path_length(&scene.space, &groups, &raw);
    let s = &scene.space;
    let mut shorter_when_stopped = false;
    for (name, shorten) in [("the greedy pass", greedy), ("the visibility graph", graph)] {
        // unlimited, to know that the stop cut the work short
        let c = &mut CallCounts::default();
        let unlimited = shorten(
            s,
            oracle.as_ref(),
            &groups,
            &raw,
            &mut known(),
            c,
            &Deadline::none(),
        );
        let full = c.intersect_calls();
        assert!(full > 4 && unlimited.is_ok(), "{name}: {c:?}");
        for trip in [1, 3, full / 2, full - 1] {
            let wire = Tripwire::new(scene.oracle(), trip);
            let c = &mut CallCounts::default();
            let p = shorten(s, &wire, &groups, &raw, &mut known(), c, &wire.deadline()).unwrap();
            assert_eq!(wire.motions(), trip, "{name} went on after its deadline");
            assert!(path_free(&p, &d) && ends(&p) == want_ends, "{name}: {p:?}");
            let length = path_length(s, &groups, &p);
            assert!(
                length <= raw_length + 1e-12,
                "{name}: {length} > {raw_length}"
            );
            if name == "the visibility graph" {
                shorter_when_stopped |= length < raw_length - 1e-9;
            }
        }
    }
    assert!(
        shorter_when_stopped,
        "the visibility graph stopped late kept none of what it found"
    );
}

/// A portfolio's head start ends the search, not the shortening
/// ([`QueryPlanner::query_finding_within`]): a search deadline that fires with the first check
/// after the path is found leaves the answer as shortened as without any deadline, while the
/// same deadline for the whole query cuts the shortening (a valid path, but a longer one). In
/// the workcell's race, cage answers found in the head start came back raw after 50 ms.
#[test]
fn a_search_deadline_does_not_cut_the_shortening() {
    let (scene, roadmap) = shortening_scene();
    let d = discs(&scene);
    let oracle = scene.oracle();
    let plain = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let raw_only = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            shorten: false,
            ..QueryOptions::default()
        });
    // a query through the roadmap whose shortening takes several checks
    let (s, g, full, finding_calls) = random_queries(&scene, 60, 9)
        .into_iter()
        .find_map(|(s, g)| {
            let full = plain.query(&s, &g).ok().filter(|r| r.is_solved())?;
            let found = raw_only.query(&s, &g).ok()?;
            let finding_calls = found.counts.intersect_calls();
            (full.outcome == QueryOutcome::Roadmap
                && full.counts.intersect_calls() >= finding_calls + 3
                && full.length < found.length - 1e-9)
                .then_some((s, g, full, finding_calls))
        })
        .expect("a query whose shortening takes several checks");
    let wire = Tripwire::new(scene.oracle(), finding_calls + 1);
    let planner = QueryPlanner::new(&roadmap, &wire).unwrap();
    let split = planner
        .query_finding_within(&s, &g, &wire.deadline(), &Deadline::none())
        .unwrap();
    assert!(wire.deadline().expired(), "the search deadline fired");
    assert_eq!(split.path, full.path, "shortened as without a deadline");
    let wire = Tripwire::new(scene.oracle(), finding_calls + 1);
    let planner = QueryPlanner::new(&roadmap, &wire).unwrap();
    let cut = planner.query_within(&s, &g, &wire.deadline()).unwrap();
    assert!(cut.is_solved() && path_free(&cut.path, &d));
    assert!(
        cut.length > full.length + 1e-9,
        "one deadline for the whole query cuts the shortening: {} against {}",
        cut.length,
        full.length
    );
}
