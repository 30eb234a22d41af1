//! The polygon oracle (SE(2)): time of one interval call against the number of obstacle
//! edges, with and without enveloping; and one exact call against a sampled check of the same
//! motion at OMPL's resolution (1 % of the extent for translation, 0.01·π for rotation) with
//! parry2d's static tests — on random triangle soups and, when `/work/shared/ompl-scenes/2D`
//! is present, on OMPL.app's BugTrap, Maze and RandomPolygons with the car robot.
//!
//! Inputs come from a seeded RNG and are built outside the timed loops. Every benchmark times
//! a batch of motions and reports throughput in motions per second.
//!
//! `cargo bench --bench oracle_polygons`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Point3, Vector2};
use parry2d_f64::math::Isometry;
use parry2d_f64::query;
use parry2d_f64::shape::{Compound, SharedShape, Triangle};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use viaroad::geometry::{Polygon, TriMesh};
use viaroad::interval::IntervalList;
use viaroad::oracle::polygons::{footprint_polygons, Polygons};
use viaroad::oracle::sampled::{Sampled, OMPL_DEFAULT_RESOLUTION};
use viaroad::oracle::{CallCounts, CollisionOracle, OracleError};
use viaroad::space::{Change, Motion, Space};

/// parry2d's static test on the triangles of robot and obstacles: the inner check of the
/// sampled baseline.
struct ParryStatic {
    robot: Compound,
    obstacles: Compound,
}

fn compound(polys: &[Polygon]) -> Compound {
    // the polygons used here are triangles (footprints) or convex (the car)
    let parts = polys
        .iter()
        .flat_map(|p| {
            let v = &p.vertices;
            (1..v.len() - 1).map(move |i| {
                (
                    Isometry::identity(),
                    SharedShape::new(Triangle::new(v[0], v[i], v[i + 1])),
                )
            })
        })
        .collect();
    Compound::new(parts)
}

impl ParryStatic {
    fn new(robot: &[Polygon], obstacles: &[Polygon]) -> ParryStatic {
        ParryStatic {
            robot: compound(robot),
            obstacles: compound(obstacles),
        }
    }
}

impl CollisionOracle for ParryStatic {
    fn intervals(&self, _: &Motion, _: &mut CallCounts) -> Result<IntervalList, OracleError> {
        Err(OracleError::Unsupported("static checks only".into()))
    }
    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        counts.pairs_tested += 1;
        let iso = Isometry::new(Vector2::new(q[0], q[1]), q[2]);
        query::intersection_test(&iso, &self.robot, &Isometry::identity(), &self.obstacles)
            .unwrap_or(true)
    }
}

/// A 5 × 2.5 car like OMPL.app's `car1_planar_robot`, as its two cap triangles.
fn car() -> Vec<Polygon> {
    let (a, b, c, d) = (
        Point2::new(-2.5, -1.25),
        Point2::new(2.5, -1.25),
        Point2::new(2.5, 1.25),
        Point2::new(-2.5, 1.25),
    );
    vec![
        Polygon::new(vec![a, b, c]).unwrap(),
        Polygon::new(vec![a, c, d]).unwrap(),
    ]
}

/// `n` random small triangles in [−50, 50]² (a footprint-like soup).
fn soup(n: usize, rng: &mut ChaCha8Rng) -> Vec<Polygon> {
    (0..n)
        .map(|_| {
            let (x, y) = (rng.random_range(-50.0..50.0), rng.random_range(-50.0..50.0));
            let s = rng.random_range(0.5..3.0);
            let pts = (0..3)
                .map(|k| {
                    let a = k as f64 * 2.0 * PI / 3.0 + rng.random_range(-0.4..0.4);
                    Point2::new(x + s * a.cos(), y + s * a.sin())
                })
                .collect();
            Polygon::new(pts).unwrap()
        })
        .collect()
}

fn random_config(rng: &mut ChaCha8Rng, lo: [f64; 2], hi: [f64; 2]) -> Vec<f64> {
    vec![
        rng.random_range(lo[0]..hi[0]),
        rng.random_range(lo[1]..hi[1]),
        rng.random_range(-PI..PI),
    ]
}

/// Translations of length up to `len` and rotations of up to ±π, from random placements.
fn motions(
    rng: &mut ChaCha8Rng,
    lo: [f64; 2],
    hi: [f64; 2],
    len: f64,
) -> (Vec<Motion>, Vec<Motion>) {
    let n = 32;
    let translations = (0..n)
        .map(|_| {
            let a = rng.random_range(0.0..2.0 * PI);
            let l = rng.random_range(0.2 * len..len);
            Motion::segment(
                random_config(rng, lo, hi),
                Change::Linear(vec![l * a.cos(), l * a.sin(), 0.0]),
            )
        })
        .collect();
    let rotations = (0..n)
        .map(|_| {
            Motion::segment(
                random_config(rng, lo, hi),
                Change::Linear(vec![0.0, 0.0, rng.random_range(-PI..PI)]),
            )
        })
        .collect();
    (translations, rotations)
}

fn run_intervals(oracle: &impl CollisionOracle, motions: &[Motion]) -> usize {
    let mut counts = CallCounts::default();
    motions
        .iter()
        .map(|m| {
            oracle
                .intervals(black_box(m), &mut counts)
                .map_or(0, |l| l.len())
        })
        .sum()
}

fn run_free(oracle: &impl CollisionOracle, motions: &[Motion]) -> usize {
    let mut counts = CallCounts::default();
    motions
        .iter()
        .filter(|m| {
            oracle
                .motion_is_free(black_box(m), &mut counts)
                .unwrap_or(false)
        })
        .count()
}

/// Mean primitive pairs evaluated per interval call.
fn pairs_per_call(oracle: &Polygons, motions: &[Motion]) -> f64 {
    let mut counts = CallCounts::default();
    for m in motions {
        let _ = oracle.intervals(m, &mut counts);
    }
    counts.pairs_tested as f64 / motions.len() as f64
}

/// One interval call against the number of obstacle edges, with and without enveloping.
fn interval_vs_edges(c: &mut Criterion) {
    let mut group = c.benchmark_group("polygons/interval_vs_edges");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for n in [16usize, 64, 256, 1024, 4096] {
        let mut rng = ChaCha8Rng::seed_from_u64(n as u64);
        let obstacles = soup(n, &mut rng);
        let oracle = Polygons::new(car(), obstacles);
        let edges = oracle.obstacle_edge_count();
        let (trans, rots) = motions(&mut rng, [-50.0, -50.0], [50.0, 50.0], 20.0);
        group.throughput(Throughput::Elements(trans.len() as u64));
        for (on, label) in [(true, "enveloping"), (false, "all_pairs")] {
            let o = oracle.clone().with_enveloping(on);
            eprintln!(
                "{edges} obstacle edges, {label}: {:.1} pairs per translation, {:.1} per rotation",
                pairs_per_call(&o, &trans),
                pairs_per_call(&o, &rots)
            );
            group.bench_with_input(
                BenchmarkId::new(format!("translation/{label}"), edges),
                &trans,
                |b, ms| b.iter(|| run_intervals(&o, ms)),
            );
            group.bench_with_input(
                BenchmarkId::new(format!("rotation/{label}"), edges),
                &rots,
                |b, ms| b.iter(|| run_intervals(&o, ms)),
            );
        }
    }
    group.finish();
}

/// Reads an OBJ mesh (positions and faces only).
fn read_obj(path: &Path) -> Option<TriMesh> {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &opts).ok()?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for m in models {
        let base = vertices.len() as u32;
        vertices.extend(
            m.mesh
                .positions
                .chunks(3)
                .map(|p| Point3::new(p[0], p[1], p[2])),
        );
        triangles.extend(
            m.mesh
                .indices
                .chunks(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
    }
    TriMesh::new(vertices, triangles).ok()
}

/// A scene for the exact-versus-sampled comparison.
struct Case {
    name: String,
    robot: Vec<Polygon>,
    obstacles: Vec<Polygon>,
    lower: [f64; 2],
    upper: [f64; 2],
}

fn ompl_cases() -> Vec<Case> {
    let dir = Path::new("/work/shared/ompl-scenes/2D");
    let Some(car_mesh) = read_obj(&dir.join("car1_planar_robot.obj")) else {
        eprintln!(
            "oracle_polygons bench: {} not found, OMPL.app scenes skipped",
            dir.display()
        );
        return Vec::new();
    };
    // OMPL.app centres the robot on the mean of its vertices
    let n = car_mesh.vertices.len() as f64;
    let (mx, my) = car_mesh
        .vertices
        .iter()
        .fold((0.0, 0.0), |(x, y), v| (x + v.x / n, y + v.y / n));
    let robot: Vec<Polygon> = footprint_polygons(&car_mesh)
        .into_iter()
        .map(|p| p.translated(Vector2::new(-mx, -my)))
        .collect();
    [
        "BugTrap_planar_env",
        "Maze_planar_env",
        "RandomPolygons_planar_env",
    ]
    .iter()
    .filter_map(|name| {
        let mesh = read_obj(&dir.join(format!("{name}.obj")))?;
        let (lo, hi) = mesh.aabb();
        Some(Case {
            name: name.to_string(),
            robot: robot.clone(),
            obstacles: footprint_polygons(&mesh),
            lower: [lo.x, lo.y],
            upper: [hi.x, hi.y],
        })
    })
    .collect()
}

/// One exact call against a sampled check of the same motion (OMPL's resolution, parry2d).
fn exact_vs_sampled(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut cases = vec![Case {
        name: "soup_1024".into(),
        robot: car(),
        obstacles: soup(1024, &mut rng),
        lower: [-55.0, -55.0],
        upper: [55.0, 55.0],
    }];
    cases.extend(ompl_cases());
    let mut group = c.benchmark_group("polygons/exact_vs_sampled");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for case in &cases {
        let exact = Polygons::new(case.robot.clone(), case.obstacles.clone());
        let space = Space::se2(case.lower, case.upper, exact.robot_radius()).unwrap();
        let sampled = Sampled::new(
            space.clone(),
            ParryStatic::new(&case.robot, &case.obstacles),
            OMPL_DEFAULT_RESOLUTION,
        );
        let len = 0.2 * space.extent();
        let (trans, rots) = motions(&mut rng, case.lower, case.upper, len);
        eprintln!(
            "{}: {} obstacle edges, {} of 32 translations and {} of 32 rotations free",
            case.name,
            exact.obstacle_edge_count(),
            run_free(&exact, &trans),
            run_free(&exact, &rots)
        );
        for (kind, ms) in [("translation", &trans), ("rotation", &rots)] {
            group.throughput(Throughput::Elements(ms.len() as u64));
            let id = |what: &str| BenchmarkId::new(format!("{kind}/{what}"), &case.name);
            group.bench_with_input(id("exact_intervals"), ms, |b, ms| {
                b.iter(|| run_intervals(&exact, ms))
            });
            group.bench_with_input(id("sampled_intervals"), ms, |b, ms| {
                b.iter(|| run_intervals(&sampled, ms))
            });
            group.bench_with_input(id("exact_is_free"), ms, |b, ms| {
                b.iter(|| run_free(&exact, ms))
            });
            group.bench_with_input(id("sampled_is_free"), ms, |b, ms| {
                b.iter(|| run_free(&sampled, ms))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, interval_vs_edges, exact_vs_sampled);
criterion_main!(benches);
