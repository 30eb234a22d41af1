//! Benchmarks of the robot-arm foundations (issue 10) on the shipped Panda in MotionBenchMaker
//! scenes (scenes/arms/):
//!
//! - `checker/state`: the independent checker (parry, every non-exempt pair) at one
//!   configuration;
//! - `oracle/state`: the exact arm oracle's static test at one configuration;
//! - `oracle/joint_move`: the exact collision intervals of one single-joint move (the distal
//!   links turning about the joint axis);
//! - `oracle/joint_move_rebuilt`: the same intervals the first way (one polyhedra oracle
//!   rebuilt per call and moving link), the reference for the pivoted per-link oracles;
//! - `sampled/joint_move`: the same move checked by the parry checker at OMPL's default
//!   resolution (1 % of the group's extent, 0.134 rad), stopping at the first collision, as
//!   OMPL's `DiscreteMotionValidator` would.
//!
//! Configurations and moves come from a seeded RNG and start collision-free; one iteration
//! handles the whole batch (16 items). Inputs are built outside the timed loops.

use criterion::{criterion_group, criterion_main, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use viaroad::oracle::CallCounts;
use viaroad::robot::{Arm, ArmChecker, ArmOptions, ArmOracle};
use viaroad::scene::moveit::load_planning_scene;

const BATCH: usize = 16;

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let dir = root.join("panda");
    let mut arm = Arm::load(
        &dir.join("panda.urdf"),
        Some(&dir.join("panda.srdf")),
        &ArmOptions::default(),
    )
    .unwrap();
    let scene = load_planning_scene(&root.join("mbm/table_pick/scene0001.yaml")).unwrap();
    scene.apply_to(&mut arm).unwrap();
    let checker = ArmChecker::new(&arm, &scene.objects).unwrap();
    let oracle = ArmOracle::new(&arm, &scene.objects).unwrap();
    let g = arm.group.clone();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut moves = Vec::new();
    while moves.len() < BATCH {
        let q: Vec<f64> = (0..g.dof())
            .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
            .collect();
        if checker.is_valid(&q) {
            let j = rng.random_range(0..g.dof());
            let delta = rng.random_range(g.lower[j]..=g.upper[j]) - q[j];
            moves.push((q, j, delta));
        }
    }
    let step = 0.01 * g.max_extent();
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
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
