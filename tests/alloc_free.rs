//! Issue 11: the hot path allocates nothing in steady state. A counting global allocator
//! counts the allocations of the current thread (other test threads do not disturb it);
//! after a warm-up that lets every reused buffer grow, intersect calls must make none, and a
//! whole via-point search only those of its answer. Every answer is also compared with the
//! allocating `intervals`, so a fast wrong answer cannot pass.

use viaroad::bench::discs::{problem, DiscProblem, GOAL, SEED_RADIUS, START};
use viaroad::interval::IntervalList;
use viaroad::local::viapoint::{ViaPoint, ViaPointOptions};
use viaroad::local::{LocalMethod, Outcome};
use viaroad::oracle::discs::Discs;
use viaroad::oracle::sampled::Sampled;
use viaroad::oracle::{Bounded, CallCounts, CollisionOracle, CountedOracle, Workspace};
use viaroad::space::{Change, Motion, Space};

#[path = "common/counting_alloc.rs"]
mod counting_alloc;
use counting_alloc::allocations;

#[global_allocator]
static GLOBAL: counting_alloc::Counting = counting_alloc::Counting;

/// Segments, lines through the bounds and lines leaving them (so that `Bounded` clips), all
/// built before counting.
fn motions(dim: usize, n: usize) -> Vec<Motion> {
    let mut out = Vec::new();
    for i in 0..n {
        let f = i as f64 / n as f64;
        let origin: Vec<f64> = (0..dim).map(|k| (f * (k + 3) as f64).fract()).collect();
        let delta: Vec<f64> = (0..dim)
            .map(|k| ((k as f64 + 1.0) * 7.1 * f).sin() - 0.2)
            .collect();
        out.push(Motion::segment(
            origin.clone(),
            Change::Linear(delta.iter().map(|d| 0.6 * d).collect()),
        ));
        out.push(Motion::line(origin, Change::Linear(delta)));
    }
    out
}

/// Asks every motion twice (the second pass counted) and compares each answer with the
/// allocating `intersect`. Returns the allocations of the counted pass and the number of
/// answers with at least one collision (so that the motions are known to hit something).
fn count_calls(oracle: &dyn CollisionOracle, motions: &[Motion]) -> (u64, usize) {
    let (mut out, mut ws) = (IntervalList::new(), Workspace::new());
    let mut counts = CallCounts::default();
    for m in motions {
        oracle
            .intersect_into(m, &mut out, &mut ws, &mut counts)
            .unwrap();
    }
    let mut blocked = 0;
    let mut total = 0;
    for m in motions {
        let before = allocations();
        oracle
            .intersect_into(m, &mut out, &mut ws, &mut counts)
            .unwrap();
        total += allocations() - before;
        let expected = oracle.intersect(m, &mut counts).unwrap();
        assert_eq!(
            out, expected,
            "intersect_into differs from intersect on {m:?}"
        );
        blocked += !out.is_empty() as usize;
    }
    (total, blocked)
}

fn unit_box(dim: usize) -> Space {
    Space::euclidean(vec![0.0; dim], vec![1.0; dim]).unwrap()
}

#[test]
fn planar_disc_calls_allocate_nothing() {
    let oracle = problem(3, 0, SEED_RADIUS).oracle();
    let (allocs, blocked) = count_calls(&oracle, &motions(2, 300));
    assert!(blocked > 100, "only {blocked} of 600 motions hit a disc");
    assert_eq!(allocs, 0, "allocations in 600 disc calls");
}

#[test]
fn ball_calls_in_r3_allocate_nothing() {
    let centres: Vec<Vec<f64>> = (0..40)
        .map(|i| {
            let f = i as f64 * 0.618_033_988_7;
            vec![f.fract(), (2.0 * f).fract(), (3.0 * f).fract()]
        })
        .collect();
    let oracle = Bounded::new(unit_box(3), Discs::new(3, &centres, &[0.08; 40]));
    let (allocs, blocked) = count_calls(&oracle, &motions(3, 300));
    assert!(blocked > 100, "only {blocked} of 600 motions hit a ball");
    assert_eq!(allocs, 0, "allocations in 600 ball calls");
}

#[test]
fn sampled_calls_allocate_nothing() {
    let p = problem(3, 1, SEED_RADIUS);
    let centres: Vec<Vec<f64>> = p.centres.iter().map(|c| c.to_vec()).collect();
    let discs = Discs::new(2, &centres, &vec![p.radius; centres.len()]);
    let oracle = Bounded::new(unit_box(2), Sampled::new(unit_box(2), discs, 0.01));
    let (allocs, blocked) = count_calls(&oracle, &motions(2, 100));
    assert!(blocked > 30, "only {blocked} of 200 motions hit a disc");
    assert_eq!(allocs, 0, "allocations in 200 sampled calls");
}

#[test]
fn a_via_point_search_allocates_only_its_answer() {
    let space = DiscProblem::space();
    let method = ViaPoint::new(ViaPointOptions {
        discoveries: false,
        ..ViaPointOptions::seed_experiment()
    });
    let oracles: Vec<_> = (0..32)
        .map(|i| problem(2, i, SEED_RADIUS).oracle())
        .collect();
    // warm-up: the thread's search buffers grow to the largest of these searches
    let first: Vec<_> = oracles
        .iter()
        .map(|o| method.connect(&space, o, &START, &GOAL).unwrap())
        .collect();
    let mut calls = 0;
    for (o, expected) in oracles.iter().zip(&first) {
        let before = allocations();
        let c = method.connect(&space, o, &START, &GOAL).unwrap();
        let allocs = allocations() - before;
        // the same answer as the first time (reused buffers carry nothing over)
        assert_eq!(c.path, expected.path);
        assert_eq!(c.counts, expected.counts);
        calls += c.counts.intersect_calls();
        // the answer: the path (one vector per corner, the list and its growth), the
        // discoveries' two ends; nothing per node or per intersect call (these searches make
        // up to ~400 calls, and one allocation per call or node would show at once)
        let answer = 2 * c.path.len() as u64 + 6;
        assert!(
            allocs <= answer,
            "{allocs} allocations for a search of {} calls with a path of {} corners ({:?})",
            c.counts.intersect_calls(),
            c.path.len(),
            c.outcome
        );
        if c.outcome == Outcome::Connected {
            assert!(c.path.len() >= 2);
        }
    }
    assert!(calls > 32 * 50, "the searches made only {calls} calls");
}

#[test]
fn with_discoveries_a_search_allocates_only_what_it_reports() {
    // the roadmap's default records what it learns: merging the configurations (cheap keys,
    // kept tables) must not allocate per node either
    let space = DiscProblem::space();
    let method = ViaPoint::default();
    let oracles: Vec<_> = (0..32)
        .map(|i| problem(4, i, SEED_RADIUS).oracle())
        .collect();
    let first: Vec<_> = oracles
        .iter()
        .map(|o| method.connect(&space, o, &START, &GOAL).unwrap())
        .collect();
    let mut configs = 0;
    for (o, expected) in oracles.iter().zip(&first) {
        let before = allocations();
        let c = method.connect(&space, o, &START, &GOAL).unwrap();
        let allocs = allocations() - before;
        assert_eq!(c.discoveries, expected.discoveries);
        let d = &c.discoveries;
        configs += d.configs.len();
        // one vector per path corner and per configuration reported, the lists and their growth
        let reported = 2 * (c.path.len() + d.configs.len()) as u64 + 12;
        assert!(
            allocs <= reported,
            "{allocs} allocations for a search of {} calls reporting {} corners, {} configurations",
            c.counts.intersect_calls(),
            c.path.len(),
            d.configs.len()
        );
    }
    assert!(configs > 32 * 3, "only {configs} configurations discovered");
}
