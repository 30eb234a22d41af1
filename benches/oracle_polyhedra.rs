//! Benchmarks of the exact SE(3) oracle (CHS Chapter 2).
//!
//! - `complexity/*`: one interval call against mesh complexity (tessellated ellipsoids of about
//!   2n faces each), with enveloping and without (brute force over every edge–face pair);
//! - `ompl/*`: on OMPL.app's meshes (Easy from `tests/data`, and cubicles, Apartment, alpha from
//!   `/work/shared/ompl-scenes/3D` when present), for the same motions: one exact interval call,
//!   one exact yes/no check, and the sampled check it replaces — parry's `intersection_test`
//!   between the two triangle meshes at OMPL's default resolution (1 % of the space's extent
//!   along a translation, 0.01·π of rotation), stopping at the first collision like OMPL's
//!   `DiscreteMotionValidator`.
//!
//! Motions come from a seeded RNG and start at collision-free configurations; half translate
//! (2–15 % of the extent), half turn about a random axis (0.1–1 rad). Inputs are built outside
//! the timed loops; one iteration answers every motion of the batch.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::SharedShape;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Duration;
use viaroad::geometry::TriMesh;
use viaroad::oracle::polyhedra::Polyhedra;
use viaroad::oracle::{CallCounts, CollisionOracle};
use viaroad::space::rotation::{axis_angle, quat_to_slice};
use viaroad::space::{Change, Motion};

fn unit_vector(rng: &mut ChaCha8Rng) -> [f64; 3] {
    let z: f64 = rng.random_range(-1.0..1.0);
    let a: f64 = rng.random_range(0.0..TAU);
    let r = (1.0 - z * z).sqrt();
    [r * a.cos(), r * a.sin(), z]
}

fn config(p: [f64; 3], q: &UnitQuaternion<f64>) -> Vec<f64> {
    let mut c = vec![p[0], p[1], p[2], 0.0, 0.0, 0.0, 1.0];
    quat_to_slice(q, &mut c[3..7]);
    c
}

fn iso(c: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(c[0], c[1], c[2]),
        UnitQuaternion::from_quaternion(Quaternion::new(c[6], c[3], c[4], c[5])),
    )
}

/// The closed hull of `n` random points on an ellipsoid (about 2n faces).
fn ellipsoid(rng: &mut ChaCha8Rng, n: usize, centre: [f64; 3], axes: [f64; 3]) -> TriMesh {
    let pts: Vec<Point3<f64>> = (0..n)
        .map(|_| {
            let d = unit_vector(rng);
            Point3::new(
                centre[0] + axes[0] * d[0],
                centre[1] + axes[1] * d[1],
                centre[2] + axes[2] * d[2],
            )
        })
        .collect();
    let (v, mut t) = parry3d_f64::transformation::convex_hull(&pts);
    let vol: f64 = t
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|k| v[k as usize].coords);
            a.dot(&b.cross(&c))
        })
        .sum();
    if vol < 0.0 {
        t.iter_mut().for_each(|f| f.swap(1, 2));
    }
    TriMesh::new(v, t).unwrap()
}

/// Random motions from `starts`: translations of length `reach·[0.2, 1]` and turns of
/// 0.1–1 rad, alternating.
fn motions(rng: &mut ChaCha8Rng, starts: &[Vec<f64>], reach: f64) -> Vec<Motion> {
    starts
        .iter()
        .enumerate()
        .map(|(i, s)| {
            if i % 2 == 0 {
                let len = reach * rng.random_range(0.2..1.0);
                let d = unit_vector(rng).map(|c| c * len);
                Motion::segment(
                    s.clone(),
                    Change::Linear(vec![d[0], d[1], d[2], 0.0, 0.0, 0.0, 0.0]),
                )
            } else {
                Motion::segment(
                    s.clone(),
                    Change::Rotation {
                        axis: unit_vector(rng),
                        angle: rng.random_range(0.1..1.0),
                    },
                )
            }
        })
        .collect()
}

fn complexity(c: &mut Criterion) {
    let mut group = c.benchmark_group("complexity");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    // the same shapes and motions for every n; only the tessellation changes
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let starts: Vec<Vec<f64>> = (0..16)
        .map(|k| {
            let a = (k as f64 + 0.5) * TAU / 16.0;
            let p = [1.6 * a.cos(), 1.6 * a.sin(), rng.random_range(-0.5..0.5)];
            config(
                p,
                &axis_angle(unit_vector(&mut rng), rng.random_range(-PI..PI)),
            )
        })
        .collect();
    let ms = motions(&mut rng, &starts, 3.0);
    for n in [16usize, 64, 256, 1024] {
        let mut rng = ChaCha8Rng::seed_from_u64(n as u64);
        let robot = ellipsoid(&mut rng, n, [0.0; 3], [1.0, 0.6, 0.4]);
        let obstacles: Vec<TriMesh> = (0..4)
            .map(|k| {
                let a = k as f64 * TAU / 4.0;
                ellipsoid(
                    &mut rng,
                    n,
                    [3.0 * a.cos(), 3.0 * a.sin(), 0.0],
                    [0.8, 1.0, 1.2],
                )
            })
            .collect();
        let faces =
            robot.triangles.len() + obstacles.iter().map(|o| o.triangles.len()).sum::<usize>();
        let brute_too = n <= 64;
        let fast = Polyhedra::new(robot.clone(), obstacles.clone());
        let brute = Polyhedra::new(robot, obstacles).with_enveloping(false);
        let mut counts = (CallCounts::default(), CallCounts::default());
        let mut colliding = 0;
        for m in &ms {
            colliding += usize::from(!fast.intervals(m, &mut counts.0).unwrap().is_empty());
            if brute_too {
                brute.intervals(m, &mut counts.1).unwrap();
            }
        }
        eprintln!(
            "complexity n={n}: {faces} faces in the scene, {} motions ({colliding} colliding), \
             pairs tested per call {} with enveloping, {} without",
            ms.len(),
            counts.0.pairs_tested / ms.len() as u64,
            if brute_too {
                format!("{}", counts.1.pairs_tested / ms.len() as u64)
            } else {
                "(not run)".into()
            }
        );
        group.bench_function(BenchmarkId::new("enveloping", faces), |b| {
            b.iter(|| {
                for m in &ms {
                    black_box(fast.intervals(m, &mut CallCounts::default()).unwrap());
                }
            })
        });
        if brute_too {
            group.bench_function(BenchmarkId::new("brute_force", faces), |b| {
                b.iter(|| {
                    for m in &ms {
                        black_box(brute.intervals(m, &mut CallCounts::default()).unwrap());
                    }
                })
            });
        }
    }
    group.finish();
}

/// An OMPL.app problem: meshes, robot centre (OMPL.app's body origin), state-space bounds.
struct Problem {
    name: &'static str,
    robot: PathBuf,
    env: PathBuf,
    centre: [f64; 3],
    lower: [f64; 3],
    upper: [f64; 3],
}

fn problems() -> Vec<Problem> {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/polyhedra");
    let shared = Path::new("/work/shared/ompl-scenes/3D");
    let mut out = vec![Problem {
        name: "Easy",
        robot: data.join("Easy_robot.obj"),
        env: data.join("Easy_env.obj"),
        centre: [270.4043, 160.6562, -297.8234],
        lower: [14.4604492188, -24.25, -504.855102539],
        upper: [457.960449219, 321.25, -72.8550872803],
    }];
    // (name, robot, env, centre, lower, upper) from ompl-scenes/README.md
    let more = [
        (
            "cubicles",
            "cubicles_robot.obj",
            "cubicles_env.obj",
            [-4.9580, -40.6201, 70.5650],
            [-508.88, -230.13, -123.75],
            [319.62, 531.87, 101.0],
        ),
        (
            "Apartment",
            "Apartment_robot.obj",
            "Apartment_env.obj",
            [-31.1927, -99.8490, 36.4595],
            [-73.76, -179.59, -0.03],
            [295.77, 168.26, 90.39],
        ),
        (
            "alpha-1.5",
            "alpha_robot.obj",
            "alpha_env-1.5.obj",
            [-21.9097, -11.1070, -14.1355],
            [-281.64, -119.64, -176.86],
            [189.05, 189.18, 174.86],
        ),
    ];
    for (name, r, e, centre, lower, upper) in more {
        let (robot, env) = (shared.join(r), shared.join(e));
        if robot.exists() && env.exists() {
            out.push(Problem {
                name,
                robot,
                env,
                centre,
                lower,
                upper,
            });
        } else {
            eprintln!("ompl: {name} skipped ({} not found)", shared.display());
        }
    }
    out
}

/// A coordinate as `f64`, whether tobj stores `f32` or (with its `use_f64` feature) `f64`.
fn widen<T: Into<f64>>(x: T) -> f64 {
    x.into()
}

fn load_obj(path: &Path) -> Option<TriMesh> {
    let (models, _) = tobj::load_obj(
        path,
        &tobj::LoadOptions {
            triangulate: true,
            ..Default::default()
        },
    )
    .ok()?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for m in models {
        let base = vertices.len() as u32;
        for p in m.mesh.positions.chunks(3) {
            vertices.push(Point3::new(widen(p[0]), widen(p[1]), widen(p[2])));
        }
        for t in m.mesh.indices.chunks(3) {
            triangles.push([base + t[0], base + t[1], base + t[2]]);
        }
    }
    TriMesh::new(vertices, triangles).ok()
}

/// OMPL-style sampled check with parry: states spaced at most one step apart, the end state
/// first, then the interior ones; stops at the first collision. Returns whether free.
struct SampledParry {
    robot: SharedShape,
    env: SharedShape,
    translation_step: f64,
    rotation_step: f64,
}

impl SampledParry {
    fn collides(&self, q: &[f64]) -> bool {
        query::intersection_test(
            &iso(q),
            self.robot.as_ref(),
            &Isometry3::identity(),
            self.env.as_ref(),
        )
        .unwrap()
    }

    fn steps(&self, m: &Motion) -> usize {
        let n = match &m.change {
            Change::Linear(d) => {
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / self.translation_step
            }
            Change::Rotation { angle, .. } | Change::BodyRotation { angle, .. } => {
                angle.abs() / self.rotation_step
            }
        };
        (n.ceil() as usize).max(1)
    }

    fn motion_is_free(&self, m: &Motion) -> bool {
        let n = self.steps(m);
        let mut q = m.origin.clone();
        m.write_at(1.0, &mut q);
        if self.collides(&q) {
            return false;
        }
        (1..n).all(|i| {
            m.write_at(i as f64 / n as f64, &mut q);
            !self.collides(&q)
        })
    }
}

fn ompl(c: &mut Criterion) {
    let mut group = c.benchmark_group("ompl");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(3));
    for p in problems() {
        let (Some(robot), Some(env)) = (load_obj(&p.robot), load_obj(&p.env)) else {
            eprintln!("ompl: {} skipped (unreadable mesh)", p.name);
            continue;
        };
        let robot = robot.translated(-Vector3::from(p.centre));
        let extent = (Vector3::from(p.upper) - Vector3::from(p.lower)).norm();
        let exact = Polyhedra::new(robot.clone(), vec![env.clone()]);
        let sampled = SampledParry {
            robot: SharedShape::trimesh(robot.vertices.clone(), robot.triangles.clone()).unwrap(),
            env: SharedShape::trimesh(env.vertices.clone(), env.triangles.clone()).unwrap(),
            translation_step: 0.01 * extent,
            rotation_step: 0.01 * PI,
        };
        // collision-free starts, uniformly in the bounds
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        let mut starts = Vec::new();
        let mut tries = 0;
        while starts.len() < 40 && tries < 20_000 {
            tries += 1;
            let pos = [0, 1, 2].map(|i| rng.random_range(p.lower[i]..p.upper[i]));
            let q = config(
                pos,
                &axis_angle(unit_vector(&mut rng), rng.random_range(-PI..PI)),
            );
            if !sampled.collides(&q) {
                starts.push(q);
            }
        }
        let ms = motions(&mut rng, &starts, 0.15 * extent);
        let (mut free, mut states) = (0, 0);
        let mut counts = CallCounts::default();
        for m in &ms {
            let ivs = exact.intervals(m, &mut counts).unwrap();
            free += usize::from(ivs.is_empty());
            states += sampled.steps(m);
            assert_eq!(
                exact.motion_is_free(m, &mut CallCounts::default()).unwrap(),
                ivs.is_empty()
            );
        }
        let (nr, no) = exact.face_counts();
        eprintln!(
            "ompl {}: {nr} robot / {no} obstacle faces (distinct), extent {extent:.1}, {} motions \
             ({free} free), {:.1} states per motion at OMPL's resolution, {} pairs tested per \
             interval call",
            p.name,
            ms.len(),
            states as f64 / ms.len() as f64,
            counts.pairs_tested / ms.len() as u64
        );
        group.bench_function(BenchmarkId::new("exact_intervals", p.name), |b| {
            b.iter(|| {
                for m in &ms {
                    black_box(exact.intervals(m, &mut CallCounts::default()).unwrap());
                }
            })
        });
        group.bench_function(BenchmarkId::new("exact_is_free", p.name), |b| {
            b.iter(|| {
                for m in &ms {
                    black_box(exact.motion_is_free(m, &mut CallCounts::default()).unwrap());
                }
            })
        });
        group.bench_function(BenchmarkId::new("sampled_parry", p.name), |b| {
            b.iter(|| {
                for m in &ms {
                    black_box(sampled.motion_is_free(m));
                }
            })
        });
        // the free motions alone: there the sampled check has to look at every state
        let free_ms: Vec<Motion> = ms
            .iter()
            .filter(|m| exact.motion_is_free(m, &mut CallCounts::default()).unwrap())
            .cloned()
            .collect();
        if !free_ms.is_empty() {
            group.bench_function(BenchmarkId::new("exact_intervals_free", p.name), |b| {
                b.iter(|| {
                    for m in &free_ms {
                        black_box(exact.intervals(m, &mut CallCounts::default()).unwrap());
                    }
                })
            });
            group.bench_function(BenchmarkId::new("sampled_parry_free", p.name), |b| {
                b.iter(|| {
                    for m in &free_ms {
                        black_box(sampled.motion_is_free(m));
                    }
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, complexity, ompl);
criterion_main!(benches);
