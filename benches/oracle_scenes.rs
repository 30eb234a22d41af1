//! Benchmarks of the exact SE(3) oracle on OMPL.app's own problems (`scenes/ompl/3D/*.cfg`:
//! Apartment, alpha-1.5, Home, Twistycool), loaded as `viaroad` loads them.
//!
//! Per scene, from collision-free starts drawn with a fixed seed: translations of 2–15 % of the
//! space's extent and turns of 0.1–1 rad about random axes through the reference point (the
//! two motion kinds of CHS Chapter 2, the only ones the via-point planner asks for):
//! - `intervals/translation|rotation`: every collision interval of the motion;
//! - `is_free/translation|rotation`: the yes/no check that stops at the first collision;
//! - `collides`: a state check at the starts and at random poses;
//! - `parry_state_check`: parry's `intersection_test` between the two meshes at the same
//!   poses — a local yardstick for an FCL state check (the issue's target is "a motion within
//!   10× the cost of one state check").
//!
//! Before criterion runs, five passes per scene outside criterion print the mean wall time of
//! each kind of call (the least of the five) (`oracle_scenes <scene>: …`), so that two builds can be compared back to
//! back with `cargo bench --bench oracle_scenes -- --list` (no criterion sampling at all).
//! Scenes are parsed outside the timed loops.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use parry3d_f64::query;
use parry3d_f64::shape::SharedShape;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};
use viaroad::geometry::TriMesh;
use viaroad::oracle::polyhedra::Polyhedra;
use viaroad::oracle::{CallCounts, CollisionOracle};
use viaroad::scene::{Obstacle, Robot, Scene};
use viaroad::space::rotation::{axis_angle, quat_to_slice};
use viaroad::space::{Change, Motion};

/// Motions of each kind per scene.
const MOTIONS: usize = 12;

fn unit_vector(rng: &mut ChaCha8Rng) -> [f64; 3] {
    let z: f64 = rng.random_range(-1.0..1.0);
    let a: f64 = rng.random_range(0.0..TAU);
    let r = (1.0 - z * z).sqrt();
    [r * a.cos(), r * a.sin(), z]
}

fn iso(c: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(c[0], c[1], c[2]),
        UnitQuaternion::from_quaternion(Quaternion::new(c[6], c[3], c[4], c[5])),
    )
}

struct Case {
    name: String,
    oracle: Polyhedra,
    robot: SharedShape,
    env: SharedShape,
    translations: Vec<Motion>,
    rotations: Vec<Motion>,
    poses: Vec<Vec<f64>>,
}

fn load(name: &str) -> Option<Case> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/ompl/3D")
        .join(format!("{name}.cfg"));
    let scene = match Scene::load(&path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("oracle_scenes: {name} skipped ({e})");
            return None;
        }
    };
    let Robot::Mesh(robot) = &scene.robot else {
        return None;
    };
    let obstacles: Vec<TriMesh> = scene
        .obstacles
        .iter()
        .filter_map(|o| match o {
            Obstacle::Mesh(m) => Some(m.clone()),
            _ => None,
        })
        .collect();
    let env = TriMesh::new(
        obstacles
            .iter()
            .flat_map(|m| m.vertices.iter().copied())
            .collect(),
        {
            let mut base = 0u32;
            let mut t = Vec::new();
            for m in &obstacles {
                t.extend(m.triangles.iter().map(|x| x.map(|k| k + base)));
                base += m.vertices.len() as u32;
            }
            t
        },
    )
    .ok()?;
    let oracle = Polyhedra::new(robot.clone(), obstacles);
    let (lower, upper) = (scene.space.lower(), scene.space.upper());
    let extent = scene.space.extent();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let random_pose = |rng: &mut ChaCha8Rng| {
        let mut c = vec![0.0; 7];
        for i in 0..3 {
            c[i] = rng.random_range(lower[i]..upper[i]);
        }
        let q = axis_angle(unit_vector(rng), rng.random_range(-PI..PI));
        quat_to_slice(&q, &mut c[3..7]);
        c
    };
    let mut starts = Vec::new();
    let mut poses = Vec::new();
    for _ in 0..20_000 {
        if starts.len() >= 2 * MOTIONS {
            break;
        }
        let q = random_pose(&mut rng);
        if poses.len() < 2 * MOTIONS {
            poses.push(q.clone());
        }
        if !oracle.collides(&q, &mut CallCounts::default()) {
            starts.push(q);
        }
    }
    let (mut translations, mut rotations) = (Vec::new(), Vec::new());
    for (i, s) in starts.iter().enumerate() {
        if i % 2 == 0 {
            let len = extent * rng.random_range(0.02..0.15);
            let d = unit_vector(&mut rng).map(|c| c * len);
            translations.push(Motion::segment(
                s.clone(),
                Change::Linear(vec![d[0], d[1], d[2], 0.0, 0.0, 0.0, 0.0]),
            ));
        } else {
            rotations.push(Motion::segment(
                s.clone(),
                Change::Rotation {
                    axis: unit_vector(&mut rng),
                    angle: rng.random_range(0.1..1.0),
                },
            ));
        }
    }
    poses.extend(starts);
    Some(Case {
        name: name.to_string(),
        oracle,
        robot: SharedShape::trimesh(robot.vertices.clone(), robot.triangles.clone()).ok()?,
        env: SharedShape::trimesh(env.vertices, env.triangles).ok()?,
        translations,
        rotations,
        poses,
    })
}

impl Case {
    fn parry_collides(&self, q: &[f64]) -> bool {
        query::intersection_test(
            &iso(q),
            self.robot.as_ref(),
            &Isometry3::identity(),
            self.env.as_ref(),
        )
        .unwrap()
    }

    /// Every kind of call, timed by hand: mean microseconds per call (least of five passes).
    fn summary(&self) {
        // the least of five passes: the machine is shared, and others only ever add time
        let per_call = |n: usize, f: &mut dyn FnMut()| {
            (0..5)
                .map(|_| {
                    let t = Instant::now();
                    f();
                    t.elapsed().as_secs_f64() * 1e6 / n.max(1) as f64
                })
                .fold(f64::INFINITY, f64::min)
        };
        let mut counts = [CallCounts::default(), CallCounts::default()];
        let mut hit = [0usize; 2];
        let it = per_call(self.translations.len(), &mut || {
            for m in &self.translations {
                hit[0] +=
                    usize::from(!self.oracle.intervals(m, &mut counts[0]).unwrap().is_empty());
            }
        });
        let ir = per_call(self.rotations.len(), &mut || {
            for m in &self.rotations {
                hit[1] +=
                    usize::from(!self.oracle.intervals(m, &mut counts[1]).unwrap().is_empty());
            }
        });
        let pairs = [0, 1].map(|k| {
            counts[k].pairs_tested
                / (5 * [&self.translations, &self.rotations][k].len().max(1)) as u64
        });
        let mut counts = CallCounts::default();
        let ft = per_call(self.translations.len(), &mut || {
            for m in &self.translations {
                black_box(self.oracle.motion_is_free(m, &mut counts).unwrap());
            }
        });
        let fr = per_call(self.rotations.len(), &mut || {
            for m in &self.rotations {
                black_box(self.oracle.motion_is_free(m, &mut counts).unwrap());
            }
        });
        let st = per_call(self.poses.len(), &mut || {
            for q in &self.poses {
                black_box(self.oracle.collides(q, &mut counts));
            }
        });
        let ps = per_call(self.poses.len(), &mut || {
            for q in &self.poses {
                black_box(self.parry_collides(q));
            }
        });
        // the median motion, each timed alone (least of five): a few motions deep in collision
        // (thousands of pieces) dominate the means
        let median = |ms: &[Motion]| -> f64 {
            let mut t: Vec<f64> = ms
                .iter()
                .map(|m| {
                    (0..5)
                        .map(|_| {
                            let t = Instant::now();
                            black_box(
                                self.oracle
                                    .intervals(m, &mut CallCounts::default())
                                    .unwrap(),
                            );
                            t.elapsed().as_secs_f64() * 1e6
                        })
                        .fold(f64::INFINITY, f64::min)
                })
                .collect();
            t.sort_by(f64::total_cmp);
            t.get(t.len() / 2).copied().unwrap_or(f64::NAN)
        };
        let (mt, mr) = (median(&self.translations), median(&self.rotations));
        let (nr, no) = self.oracle.face_counts();
        eprintln!(
            "oracle_scenes {}: {nr} x {no} faces; mean µs per call: intervals translation {it:.0} \
             ({}/{} collide, {} pairs tested), rotation {ir:.0} ({}/{}, {} pairs); is_free translation {ft:.0}, rotation \
             {fr:.0}; collides {st:.1}; parry state check {ps:.1}; median µs of intervals: \
             translation {mt:.0}, rotation {mr:.0}",
            self.name,
            hit[0] / 5,
            self.translations.len(),
            pairs[0],
            hit[1] / 5,
            self.rotations.len(),
            pairs[1]
        );
    }
}

fn scenes(c: &mut Criterion) {
    let mut group = c.benchmark_group("oracle_scenes");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_secs(2));
    for name in ["Apartment", "alpha-1.5", "Home", "Twistycool"] {
        let Some(case) = load(name) else { continue };
        case.summary();
        for (kind, ms) in [
            ("translation", &case.translations),
            ("rotation", &case.rotations),
        ] {
            group.bench_function(BenchmarkId::new(format!("intervals/{kind}"), name), |b| {
                b.iter(|| {
                    for m in ms.iter() {
                        black_box(
                            case.oracle
                                .intervals(m, &mut CallCounts::default())
                                .unwrap(),
                        );
                    }
                })
            });
            group.bench_function(BenchmarkId::new(format!("is_free/{kind}"), name), |b| {
                b.iter(|| {
                    for m in ms.iter() {
                        black_box(
                            case.oracle
                                .motion_is_free(m, &mut CallCounts::default())
                                .unwrap(),
                        );
                    }
                })
            });
        }
        group.bench_function(BenchmarkId::new("collides", name), |b| {
            b.iter(|| {
                for q in &case.poses {
                    black_box(case.oracle.collides(q, &mut CallCounts::default()));
                }
            })
        });
        group.bench_function(BenchmarkId::new("parry_state_check", name), |b| {
            b.iter(|| {
                for q in &case.poses {
                    black_box(case.parry_collides(q));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, scenes);
criterion_main!(benches);
