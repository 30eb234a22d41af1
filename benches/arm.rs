//! Benchmarks of the robot-arm foundations on the shipped Panda in MotionBenchMaker
//! scenes (scenes/arms/):
//!
//! - `checker/state`: the independent checker (parry, every non-exempt pair) at one
//!   configuration;
//! - `oracle/state`: the exact arm oracle's static test at one configuration;
//! - `oracle/joint_move`: the exact collision intervals of one single-joint move (the distal
//!   links turning about the joint axis);
//! - `oracle/joint_move_unshared`: the same intervals with every link oracle answering the
//!   whole move on its own (`ArmOracle::with_culling(false)`), the reference for the shared
//!   sweep (windows one link already found colliding skipped by the others);
//! - `oracle/joint_move_free`, `oracle/joint_move_first_hit`: the yes/no and first-hit
//!   questions, which stop early;
//! - `oracle/joint_move_rebuilt`: the same intervals the first way (one polyhedra oracle
//!   rebuilt per call and moving link), the reference for the pivoted per-link oracles;
//! - `sampled/joint_move`: the same move checked by the parry checker at OMPL's default
//!   resolution (1 % of the group's extent, 0.134 rad), stopping at the first collision, as
//!   OMPL's `DiscreteMotionValidator` would.
//!
//! Configurations and moves come from a seeded RNG and start collision-free; one iteration
//! handles the whole batch (16 items). Inputs are built outside the timed loops.
//!
//! Two more modes, chosen by the environment variable `ARM_MOVES`, for figures per move:
//! - `ARM_MOVES=table`: 64 moves (the batch's 16 first), each timed alone, the variants
//!   interleaved (A/B in one run on a noisy machine); prints mean, median and p95 per variant,
//!   for light moves (free), heavy ones (they collide somewhere along the move) and in all;
//! - `ARM_MOVES=states`: the exact static test at 40 000 uniform configurations of box 1 (a
//!   quarter of them collide), each asked once (the oracle remembers a link's answer per
//!   pose), the mean time of those that collide and of those that do not; shortening's
//!   corner tests are mostly of the first kind;
//! - `ARM_MOVES=straight`: the straight motions of several joints one bookshelf_tall workcell
//!   query asked after its roadmap could not join the goal (`data/bookshelf_tall_straight.txt`:
//!   the goal's direct tries, the trees out of the roadmap, the shortcuts; a goal in a pocket
//!   under a board), each proved `ARM_ROUNDS` times (default 20): µs per motion for those
//!   proved free and the others, for `perf record` (the same motions are the criterion
//!   bench's `oracle/straight_bookshelf`);
//! - `ARM_MOVES=shared|unshared|free|first|rebuilt`: the 64 moves once with that variant and
//!   nothing else, for `valgrind --tool=callgrind` (instruction counts repeat whatever the
//!   load): `ARM_MOVES=shared valgrind --tool=callgrind target/release/deps/arm-*`.

use criterion::{criterion_group, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use viaroad::oracle::CallCounts;
use viaroad::robot::{Arm, ArmChecker, ArmOptions, ArmOracle};
use viaroad::scene::moveit::{load_planning_scene, PlanningScene};

const BATCH: usize = 16;

/// The moves of the per-move table (the criterion batch comes first).
const MOVES: usize = 64;

type Move = (Vec<f64>, usize, f64);

/// A straight motion of several joints: its two ends.
type Straight = (Vec<f64>, Vec<f64>);

/// The shipped Panda in the first scene of MotionBenchMaker family `family`, and the scene.
fn panda_in(family: &str) -> (Arm, PlanningScene) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let dir = root.join("panda");
    let mut arm = Arm::load(
        &dir.join("panda.urdf"),
        Some(&dir.join("panda.srdf")),
        &ArmOptions::default(),
    )
    .unwrap();
    let scene = load_planning_scene(&root.join(format!("mbm/{family}/scene0001.yaml"))).unwrap();
    scene.apply_to(&mut arm).unwrap();
    (arm, scene)
}

/// The Panda in table_pick 1: checker, oracle, and `n` collision-free starts with a move each.
fn setup(n: usize) -> (ArmChecker, ArmOracle, f64, Vec<Move>) {
    let (arm, scene) = panda_in("table_pick");
    let checker = ArmChecker::new(&arm, &scene.objects).unwrap();
    let oracle = ArmOracle::new(&arm, &scene.objects).unwrap();
    let g = arm.group.clone();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut moves = Vec::new();
    while moves.len() < n {
        let q: Vec<f64> = (0..g.dof())
            .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
            .collect();
        if checker.is_valid(&q) {
            let j = rng.random_range(0..g.dof());
            let delta = rng.random_range(g.lower[j]..=g.upper[j]) - q[j];
            moves.push((q, j, delta));
        }
    }
    (checker, oracle, 0.01 * g.max_extent(), moves)
}

/// One variant of the oracle on one move.
fn run(variant: &str, oracle: &ArmOracle, unshared: &ArmOracle, m: &Move, counts: &mut CallCounts) {
    let (q, j, d) = (&m.0, m.1, m.2);
    match variant {
        "shared" => drop(black_box(oracle.joint_move(q, j, d, counts).unwrap())),
        "unshared" => drop(black_box(unshared.joint_move(q, j, d, counts).unwrap())),
        "free" => drop(black_box(oracle.joint_move_free(q, j, d, counts).unwrap())),
        "first" => drop(black_box(
            oracle.joint_move_first_hit(q, j, d, counts).unwrap(),
        )),
        "rebuilt" => drop(black_box(
            oracle.joint_move_rebuilt(q, j, d, counts).unwrap(),
        )),
        other => panic!("ARM_MOVES={other}: shared, unshared, free, first, rebuilt or table"),
    }
}

/// Mean, median and p95 (microseconds) of some per-move times.
fn stats(t: &mut [f64]) -> String {
    if t.is_empty() {
        return "-".into();
    }
    t.sort_by(f64::total_cmp);
    let mean = t.iter().sum::<f64>() / t.len() as f64;
    let at = |p: f64| t[((p * (t.len() - 1) as f64).round() as usize).min(t.len() - 1)];
    format!("{:>9.1} {:>9.1} {:>9.1}", mean, at(0.5), at(0.95))
}

/// `ARM_MOVES=table`: per-move times of every variant, interleaved.
fn table() {
    let (_, oracle, _, moves) = setup(MOVES);
    let unshared = oracle.clone().with_culling(false);
    let variants = ["unshared", "shared", "free", "first"];
    const REPS: usize = 5;
    let mut times = vec![vec![0.0; moves.len()]; variants.len()];
    let mut pairs = vec![vec![0u64; moves.len()]; variants.len()];
    for (i, m) in moves.iter().enumerate() {
        let mut best = vec![Vec::new(); variants.len()];
        for _ in 0..REPS {
            for (v, name) in variants.iter().enumerate() {
                let mut counts = CallCounts::default();
                let t = std::time::Instant::now();
                run(name, &oracle, &unshared, m, &mut counts);
                best[v].push(t.elapsed().as_secs_f64() * 1e6);
                pairs[v][i] = counts.pairs_tested;
            }
        }
        for (v, b) in best.iter_mut().enumerate() {
            b.sort_by(f64::total_cmp);
            times[v][i] = b[REPS / 2];
        }
    }
    // the same classes whatever the build: by the answer, not by the work
    let heavy: Vec<bool> = moves
        .iter()
        .map(|(q, j, d)| {
            !oracle
                .joint_move(q, *j, *d, &mut CallCounts::default())
                .unwrap()
                .is_empty()
        })
        .collect();
    println!(
        "{} moves ({} heavy: they collide somewhere; light: free), median of {REPS} runs each, µs",
        moves.len(),
        heavy.iter().filter(|&&h| h).count()
    );
    println!(
        "{:<9} {:<6} {:>9} {:>9} {:>9} {:>12}",
        "variant", "moves", "mean", "median", "p95", "pairs/move"
    );
    for (v, name) in variants.iter().enumerate() {
        for (class, keep) in [("light", Some(false)), ("heavy", Some(true)), ("all", None)] {
            let pick = |i: &usize| keep.is_none_or(|h| heavy[*i] == h);
            let mut t: Vec<f64> = (0..moves.len()).filter(pick).map(|i| times[v][i]).collect();
            let n = t.len().max(1) as u64;
            let p: u64 = (0..moves.len()).filter(pick).map(|i| pairs[v][i]).sum();
            println!("{name:<9} {class:<6} {} {:>12}", stats(&mut t), p / n);
        }
    }
}

/// `ARM_MOVES=states`: the static test at uniform configurations of box 1, per verdict, with
/// the sure test ([`viaroad::robot::inner`]) and without it (the verdicts compared).
fn states() {
    let (arm, scene) = panda_in("box");
    let started = std::time::Instant::now();
    let oracle = ArmOracle::new(&arm, &scene.objects).unwrap();
    println!(
        "oracle built in {:.1} ms",
        started.elapsed().as_secs_f64() * 1e3
    );
    // built again: a clone would share the first one's memo of static link tests
    let exact = ArmOracle::new(&arm, &scene.objects)
        .unwrap()
        .with_sure_test(false);
    let g = arm.group.clone();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    // [sure test on, off] × [free, collides]: seconds, configurations
    let mut t = [[(0.0, 0usize); 2]; 2];
    let mut counts = [CallCounts::default(), CallCounts::default()];
    // the sure test alone, per verdict: seconds, collisions it found
    let mut sure_t = [(0.0, 0usize); 2];
    for _ in 0..40_000 {
        let q: Vec<f64> = (0..g.dof())
            .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
            .collect();
        let mut hits = [false; 2];
        let order = if rng.random_bool(0.5) { [0, 1] } else { [1, 0] };
        for k in order {
            let o = [&oracle, &exact][k];
            let start = std::time::Instant::now();
            hits[k] = o.collides(&q, &mut counts[k]).unwrap();
            let e = start.elapsed().as_secs_f64();
            t[k][usize::from(hits[k])].0 += e;
            t[k][usize::from(hits[k])].1 += 1;
        }
        assert_eq!(
            hits[0], hits[1],
            "the sure test changed the verdict at {q:?}"
        );
        let start = std::time::Instant::now();
        let sure = oracle.surely_collides(&q);
        sure_t[usize::from(hits[0])].0 += start.elapsed().as_secs_f64();
        sure_t[usize::from(hits[0])].1 += usize::from(sure);
        assert!(
            !sure || hits[0],
            "the sure test found a collision the exact test did not at {q:?}"
        );
    }
    for (v, name) in ["free", "collide"].iter().enumerate() {
        let (secs, found) = sure_t[v];
        let n = t[1][v].1.max(1);
        println!(
            "sure test alone at {name:<8} configurations: {:.2} µs each, found {found} of {n}",
            secs * 1e6 / n as f64
        );
    }
    for (k, mode) in ["sure test", "exact only"].iter().enumerate() {
        for (name, (s, n)) in ["free", "collide"].iter().zip(t[k]) {
            println!(
                "{mode:<10} {name:<8} {n:>6} configurations, {:.1} µs each",
                s * 1e6 / n.max(1) as f64
            );
        }
        println!("{mode:<10} exact pairs {}", counts[k].pairs_tested);
    }
}

/// The recorded straight motions of a bookshelf_tall query (`ARM_MOVES=straight`), and the
/// Panda's oracle in that family's first scene.
fn straight_motions() -> (ArmOracle, Vec<Straight>) {
    let (arm, scene) = panda_in("bookshelf_tall");
    let oracle = ArmOracle::new(&arm, &scene.objects).unwrap();
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/data/bookshelf_tall_straight.txt");
    let parse = |s: &str| -> Vec<f64> { s.split(',').map(|v| v.trim().parse().unwrap()).collect() };
    let motions = std::fs::read_to_string(file)
        .unwrap()
        .lines()
        .filter_map(|l| l.split_once(';'))
        .map(|(a, b)| (parse(a), parse(b)))
        .collect();
    (oracle, motions)
}

/// `ARM_MOVES=straight`: µs per recorded straight motion, by verdict.
fn straight() {
    let (oracle, motions) = straight_motions();
    let rounds: usize = std::env::var("ARM_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(20);
    // [not proved, proved free]: seconds, motions
    let mut t = [(0.0, 0usize); 2];
    // not proved quickly (the sure test) and after the planes began: seconds, motions
    let mut slow = [(0.0, 0usize); 2];
    let mut counts = CallCounts::default();
    for _ in 0..rounds {
        for (q0, q1) in &motions {
            let start = std::time::Instant::now();
            let free = oracle.straight_free(q0, q1, &mut counts).unwrap();
            let e = start.elapsed().as_secs_f64();
            t[usize::from(free)].0 += e;
            t[usize::from(free)].1 += 1;
            if !free {
                let k = usize::from(e > 8e-6);
                slow[k].0 += e;
                slow[k].1 += 1;
            }
        }
    }
    for (name, (secs, n)) in ["not proved", "proved free"].iter().zip(t) {
        println!(
            "{name:<12} {:>5} motions, {:.2} µs each",
            n / rounds,
            secs * 1e6 / n.max(1) as f64
        );
    }
    for (name, (secs, n)) in ["  in < 8 µs", "  in > 8 µs"].iter().zip(slow) {
        println!(
            "{name:<12} {:>5} motions, {:.2} µs each",
            n / rounds,
            secs * 1e6 / n.max(1) as f64
        );
    }
    let all = (t[0].0 + t[1].0) * 1e6 / rounds as f64;
    println!(
        "all          {:>5} motions, {all:.0} µs per round",
        motions.len()
    );
}

/// `ARM_MOVES=<variant>`: the moves once, for callgrind.
fn once(variant: &str) {
    let (_, oracle, _, moves) = setup(MOVES);
    let unshared = oracle.clone().with_culling(false);
    let mut counts = CallCounts::default();
    for m in &moves {
        run(variant, &oracle, &unshared, m, &mut counts);
    }
    println!(
        "{variant}: {} moves, {} exact pairs",
        moves.len(),
        counts.pairs_tested
    );
}

fn bench(c: &mut Criterion) {
    let (checker, oracle, step, moves) = setup(BATCH);
    let unshared = oracle.clone().with_culling(false);
    let mut group = c.benchmark_group("arm");
    group.measurement_time(Duration::from_secs(5));
    group.sample_size(10);
    group.bench_function("checker/state", |b| {
        b.iter(|| {
            for (q, _, _) in &moves {
                black_box(checker.collisions(q));
            }
        })
    });
    group.bench_function("oracle/state", |b| {
        b.iter(|| {
            for (q, _, _) in &moves {
                black_box(oracle.collides(q, &mut CallCounts::default()).unwrap());
            }
        })
    });
    group.bench_function("oracle/joint_move", |b| {
        b.iter(|| {
            for (q, j, d) in &moves {
                black_box(
                    oracle
                        .joint_move(q, *j, *d, &mut CallCounts::default())
                        .unwrap(),
                );
            }
        })
    });
    group.bench_function("oracle/joint_move_unshared", |b| {
        b.iter(|| {
            for (q, j, d) in &moves {
                black_box(
                    unshared
                        .joint_move(q, *j, *d, &mut CallCounts::default())
                        .unwrap(),
                );
            }
        })
    });
    group.bench_function("oracle/joint_move_free", |b| {
        b.iter(|| {
            for (q, j, d) in &moves {
                black_box(
                    oracle
                        .joint_move_free(q, *j, *d, &mut CallCounts::default())
                        .unwrap(),
                );
            }
        })
    });
    group.bench_function("oracle/joint_move_first_hit", |b| {
        b.iter(|| {
            for (q, j, d) in &moves {
                black_box(
                    oracle
                        .joint_move_first_hit(q, *j, *d, &mut CallCounts::default())
                        .unwrap(),
                );
            }
        })
    });
    group.bench_function("oracle/joint_move_rebuilt", |b| {
        b.iter(|| {
            for (q, j, d) in &moves {
                black_box(
                    oracle
                        .joint_move_rebuilt(q, *j, *d, &mut CallCounts::default())
                        .unwrap(),
                );
            }
        })
    });
    group.bench_function("sampled/joint_move", |b| {
        b.iter(|| {
            for (q, j, d) in &moves {
                let n = ((d.abs() / step).ceil() as usize).max(1);
                for k in 1..=n {
                    let mut qt = q.clone();
                    qt[*j] += d * k as f64 / n as f64;
                    if !checker.collisions(&qt).is_empty() {
                        break;
                    }
                }
            }
        })
    });
    let (shelf, motions) = straight_motions();
    group.bench_function("oracle/straight_bookshelf", |b| {
        b.iter(|| {
            let mut counts = CallCounts::default();
            for (q0, q1) in &motions {
                black_box(shelf.straight_free(q0, q1, &mut counts).unwrap());
            }
        })
    });
    group.finish();
}

criterion_group!(benches, bench);

fn main() {
    match std::env::var("ARM_MOVES").as_deref() {
        Ok("table") => table(),
        Ok("states") => states(),
        Ok("straight") => straight(),
        Ok(v) => once(v),
        Err(_) => {
            benches();
            Criterion::default().configure_from_args().final_summary();
        }
    }
}
