//! The Minkowski C-obstacle oracle against the edge-pair polygon oracle: time of a
//! batch of translations at a fixed orientation on the shipped SE(2) scene and OMPL.app's 2D
//! problems (the scenes' own robots), plus the one-off cost of building the C-obstacles.
//!
//! Inputs come from a seeded RNG and are built outside the timed loops; the two oracles'
//! answers are checked to agree before anything is timed.
//!
//! `cargo bench --bench minkowski`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use viaroad::geometry::Polygon;
use viaroad::interval::IntervalList;
use viaroad::oracle::minkowski::Minkowski;
use viaroad::oracle::polygons::Polygons;
use viaroad::oracle::{CallCounts, CollisionOracle};
use viaroad::scene::{Obstacle, Robot, Scene};
use viaroad::space::{Change, Motion};

const SCENES: [&str; 4] = [
    "scenes/se2-corridor.toml",
    "scenes/ompl/2D/BugTrap_planar.cfg",
    "scenes/ompl/2D/Maze_planar.cfg",
    "scenes/ompl/2D/RandomPolygons_planar.cfg",
];

/// Robot and obstacle polygons of an SE(2) scene.
fn parts(scene: &Scene) -> Option<(Vec<Polygon>, Vec<Polygon>)> {
    let Robot::Polygons(robot) = &scene.robot else {
        return None;
    };
    let obstacles = scene
        .obstacles
        .iter()
        .filter_map(|o| match o {
            Obstacle::Polygon(p) => Some(p.clone()),
            _ => None,
        })
        .collect();
    Some((robot.clone(), obstacles))
}

/// Random translations inside the bounds, each a tenth of the extent long, at `theta`.
fn motions(scene: &Scene, theta: f64, count: usize) -> Vec<Motion> {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    let (lo, hi) = (scene.space.lower(), scene.space.upper());
    let step = 0.1 * scene.space.extent();
    (0..count)
        .map(|_| {
            let x = rng.random_range(lo[0]..hi[0]);
            let y = rng.random_range(lo[1]..hi[1]);
            let a = rng.random_range(0.0..std::f64::consts::TAU);
            Motion::segment(
                vec![x, y, theta],
                Change::Linear(vec![step * a.cos(), step * a.sin(), 0.0]),
            )
        })
        .collect()
}

fn batch(oracle: &dyn CollisionOracle, motions: &[Motion]) -> usize {
    let mut counts = CallCounts::default();
    motions
        .iter()
        .map(|m| oracle.intervals(m, &mut counts).map_or(0, |l| l.len()))
        .sum()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("translation");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20);
    for path in SCENES {
        let Ok(scene) = Scene::load(Path::new(path)) else {
            continue;
        };
        let Some((robot, obstacles)) = parts(&scene) else {
            continue;
        };
        let name = Path::new(path).file_stem().unwrap().to_string_lossy();
        let theta = 0.3;
        let moves = motions(&scene, theta, 500);
        let edge_pair = Polygons::new(robot.clone(), obstacles.clone());
        let mink = Minkowski::new(&robot, &obstacles, theta);
        let mut counts = CallCounts::default();
        for m in &moves {
            let a: IntervalList = edge_pair.intervals(m, &mut counts).unwrap();
            let b = mink.intervals(m, &mut counts).unwrap();
            assert_eq!(a.len(), b.len(), "{name}: {a:?} vs {b:?}");
        }
        group.throughput(Throughput::Elements(moves.len() as u64));
        group.bench_with_input(BenchmarkId::new("edge-pair", &name), &moves, |b, m| {
            b.iter(|| black_box(batch(&edge_pair, m)))
        });
        group.bench_with_input(BenchmarkId::new("minkowski", &name), &moves, |b, m| {
            b.iter(|| black_box(batch(&mink, m)))
        });
    }
    group.finish();
    let mut build = c.benchmark_group("build");
    build
        .sample_size(10)
        .measurement_time(Duration::from_secs(2));
    for path in SCENES {
        let Some((robot, obstacles)) = Scene::load(Path::new(path)).ok().as_ref().and_then(parts)
        else {
            continue;
        };
        let name = Path::new(path).file_stem().unwrap().to_string_lossy();
        build.bench_function(BenchmarkId::new("minkowski", &name), |b| {
            b.iter(|| black_box(Minkowski::new(&robot, &obstacles, 0.3).c_obstacles().len()))
        });
    }
    build.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
