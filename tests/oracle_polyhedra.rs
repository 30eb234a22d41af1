//! The exact SE(3) oracle (CHS Chapter 2) against an independent reference: parry's static
//! `intersection_test` at densely sampled configurations, on OMPL.app's Easy meshes (open,
//! double-sided soups: surface contact only, like FCL), random convex solids, axis-aligned
//! boxes on a grid (many coincident planes and edges), thin plates and a ring of boxes; plus
//! hand-computed cases to 1e-9.

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::SharedShape;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::Path;
use viaroad::geometry::TriMesh;
use viaroad::interval::{Interval, IntervalList};
use viaroad::oracle::polyhedra::Polyhedra;
use viaroad::oracle::{CallCounts, CollisionOracle, OracleError};
use viaroad::space::rotation::{axis_angle, quat_to_slice};
use viaroad::space::{Change, Motion};

// ---------------------------------------------------------------------------------------------
// geometry

fn cuboid_at(centre: [f64; 3], half: [f64; 3]) -> TriMesh {
    TriMesh::cuboid(half)
        .unwrap()
        .translated(Vector3::from(centre))
}

/// Every triangle a second time with the other winding: an open, double-sided soup like
/// OMPL.app's meshes, which has no inside.
fn double_sided(m: &TriMesh) -> TriMesh {
    let mut tris = m.triangles.clone();
    tris.extend(m.triangles.iter().map(|t| [t[0], t[2], t[1]]));
    TriMesh::new(m.vertices.clone(), tris).unwrap()
}

/// The box without its +y side: open, so no containment.
fn open_box(centre: [f64; 3], half: [f64; 3]) -> TriMesh {
    let mut m = cuboid_at(centre, half);
    m.triangles.drain(6..8);
    assert!(!m.is_closed());
    m
}

/// The convex hull of `points`, outward-oriented; `None` if it is (nearly) flat, which parry
/// returns as a double-sided polygon (four random points can lie almost in one plane).
fn try_hull(points: &[Point3<f64>]) -> Option<TriMesh> {
    let (v, mut t) = parry3d_f64::transformation::convex_hull(points);
    // six times the signed volume
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
    let m = TriMesh::new(v, t).ok()?;
    (m.is_closed() && vol.abs() > 1e-9).then_some(m)
}

fn hull(points: &[Point3<f64>]) -> TriMesh {
    let m = try_hull(points).expect("a solid hull");
    assert!(m.is_closed());
    m
}

/// The hull of `n` random points around `centre` (within `size` per axis), drawn again until
/// it is a solid.
fn random_solid(rng: &mut ChaCha8Rng, n: usize, centre: [f64; 3], size: f64) -> TriMesh {
    loop {
        if let Some(m) = try_hull(&random_points(rng, n, centre, size)) {
            return m;
        }
    }
}

fn random_points(rng: &mut ChaCha8Rng, n: usize, centre: [f64; 3], size: f64) -> Vec<Point3<f64>> {
    (0..n)
        .map(|_| {
            Point3::new(
                centre[0] + size * rng.random_range(-1.0..1.0),
                centre[1] + size * rng.random_range(-1.0..1.0),
                centre[2] + size * rng.random_range(-1.0..1.0),
            )
        })
        .collect()
}

/// A coordinate as `f64`, whether tobj stores `f32` or (with its `use_f64` feature) `f64`.
fn widen<T: Into<f64>>(x: T) -> f64 {
    x.into()
}

fn load_obj(name: &str) -> TriMesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/polyhedra")
        .join(name);
    let (models, _) = tobj::load_obj(
        &path,
        &tobj::LoadOptions {
            triangulate: true,
            single_index: false,
            ..Default::default()
        },
    )
    .unwrap();
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
    TriMesh::new(vertices, triangles).unwrap()
}

/// OMPL.app's Easy problem: robot in its body frame, the environment.
fn easy() -> (TriMesh, TriMesh) {
    let centre = Vector3::new(270.4043, 160.6562, -297.8234);
    let robot = load_obj("Easy_robot.obj").translated(-centre);
    (robot, load_obj("Easy_env.obj"))
}

fn soup_shape(m: &TriMesh) -> SharedShape {
    SharedShape::trimesh(m.vertices.clone(), m.triangles.clone()).unwrap()
}

fn convex_shape(m: &TriMesh) -> SharedShape {
    SharedShape::convex_hull(&m.vertices).unwrap()
}

// ---------------------------------------------------------------------------------------------
// configurations and motions

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

fn translation(delta: [f64; 3]) -> Change {
    Change::Linear(vec![delta[0], delta[1], delta[2], 0.0, 0.0, 0.0, 0.0])
}

fn random_rotation(rng: &mut ChaCha8Rng) -> UnitQuaternion<f64> {
    let axis = random_axis(rng);
    axis_angle(axis, rng.random_range(-PI..PI))
}

fn random_axis(rng: &mut ChaCha8Rng) -> [f64; 3] {
    let z: f64 = rng.random_range(-1.0..1.0);
    let a: f64 = rng.random_range(0.0..TAU);
    let r = (1.0 - z * z).sqrt();
    [r * a.cos(), r * a.sin(), z]
}

/// A random motion of one of the four kinds the oracle answers, and the range to sample.
fn random_motion(rng: &mut ChaCha8Rng, start: Vec<f64>, reach: f64) -> (Motion, Interval) {
    match rng.random_range(0..4) {
        0 => {
            let d = random_axis(rng).map(|c| c * reach * rng.random_range(0.2..1.0));
            let m = Motion::segment(start.clone(), translation(d));
            (m, Interval::UNIT)
        }
        1 => {
            let d = random_axis(rng).map(|c| c * reach * 0.3);
            let m = Motion::line(start.clone(), translation(d));
            (m, Interval { lo: -2.0, hi: 2.0 })
        }
        2 => {
            let change = Change::Rotation {
                axis: random_axis(rng),
                angle: rng.random_range(-PI..PI),
            };
            (Motion::segment(start, change), Interval::UNIT)
        }
        _ => {
            let change = Change::Rotation {
                axis: random_axis(rng),
                angle: TAU,
            };
            (Motion::turn(start, change), Interval { lo: -0.5, hi: 0.5 })
        }
    }
}

// ---------------------------------------------------------------------------------------------
// the independent reference and the comparison

struct Reference {
    robot: SharedShape,
    /// The robot grown by the touching distance, where parry can grow it (convex shapes):
    /// parry's `distance` is unreliable for exactly touching boxes, an intersection test with
    /// the grown robot is not.
    grown: Option<SharedShape>,
    obstacles: Vec<SharedShape>,
}

impl Reference {
    fn intersects(&self, q: &[f64]) -> bool {
        let pose = iso(q);
        self.obstacles.iter().any(|o| {
            query::intersection_test(
                &pose,
                self.robot.as_ref(),
                &Isometry3::identity(),
                o.as_ref(),
            )
            .unwrap()
        })
    }

    /// Whether the robot at `q` is within `touch` of an obstacle.
    fn touches(&self, q: &[f64], touch: f64) -> bool {
        let pose = iso(q);
        match &self.grown {
            Some(g) => self.obstacles.iter().any(|o| {
                query::intersection_test(&pose, g.as_ref(), &Isometry3::identity(), o.as_ref())
                    .unwrap()
            }),
            None => self.distance(q) <= touch,
        }
    }

    fn distance(&self, q: &[f64]) -> f64 {
        let pose = iso(q);
        self.obstacles
            .iter()
            .map(|o| {
                query::distance(
                    &pose,
                    self.robot.as_ref(),
                    &Isometry3::identity(),
                    o.as_ref(),
                )
                .unwrap()
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Compares the oracle's answer for `motion` with the reference over `span`:
/// - at `samples + 1` evenly spaced parameters both agree, except within `ENDPOINT_SLACK` of an
///   interval end, and except where the oracle reports a touching contact that parry's GJK
///   reports as free (distance ≤ `touch`);
/// - every interval end inside `span` is a real change of state: just inside, the reference
///   collides (or touches), and just outside — within one sampling step — it is free.
fn compare(
    oracle: &Polyhedra,
    reference: &Reference,
    motion: &Motion,
    span: Interval,
    samples: usize,
    touch: f64,
) -> Result<IntervalList, String> {
    const ENDPOINT_SLACK: f64 = 1e-7;
    let ours = oracle
        .intervals(motion, &mut CallCounts::default())
        .map_err(|e| format!("{e}"))?;
    for iv in ours.iter() {
        if !(iv.lo.is_finite() && iv.hi.is_finite())
            && span.is_bounded()
            && motion.range.is_bounded()
        {
            return Err(format!("infinite end in {ours:?}"));
        }
        if iv.lo.is_nan() || iv.hi.is_nan() {
            return Err(format!("NaN in {ours:?}"));
        }
    }
    let step = span.length() / samples as f64;
    let near_end = |t: f64| {
        ours.iter()
            .any(|iv| (t - iv.lo).abs() <= ENDPOINT_SLACK || (t - iv.hi).abs() <= ENDPOINT_SLACK)
    };
    for i in 0..=samples {
        let t = span.lo + step * i as f64;
        let q = motion.at(t);
        let (mine, theirs) = (ours.contains(t), reference.intersects(&q));
        if mine == theirs || near_end(t) {
            continue;
        }
        if mine && reference.touches(&q, touch) {
            continue;
        }
        return Err(format!(
            "t = {t}: oracle says {mine}, parry says {theirs}; intervals {ours:?}, motion {motion:?}"
        ));
    }
    // every end inside the span is a change of state within one step
    let probes = [1e-9, 1e-7, 1e-5, 1e-3, step];
    for iv in ours.iter() {
        for (end, inward) in [(iv.lo, 1.0), (iv.hi, -1.0)] {
            let inner = span.lo.max(motion.range.lo) + 1e-9 < end
                && end < span.hi.min(motion.range.hi) - 1e-9;
            if !inner {
                continue;
            }
            let len = iv.length();
            let inside_ok = if len <= 2e-9 {
                reference.touches(&motion.at(end), touch)
            } else {
                probes.iter().filter(|&&s| s < len).any(|&s| {
                    let q = motion.at(end + inward * s);
                    reference.intersects(&q) || reference.touches(&q, touch)
                })
            };
            if !inside_ok {
                return Err(format!(
                    "interval {iv:?}: the reference is free just inside its end {end}; motion {motion:?}"
                ));
            }
            let outside_ok = probes.iter().any(|&s| {
                let t = end - inward * s;
                if ours.contains(t) {
                    return false;
                }
                !reference.intersects(&motion.at(t))
            });
            let gap = ours
                .iter()
                .filter(|o| *o != iv)
                .map(|o| (o.lo - end).abs().min((o.hi - end).abs()))
                .fold(f64::INFINITY, f64::min);
            if !outside_ok && gap > step {
                return Err(format!(
                    "interval {iv:?}: the reference still collides within a step outside {end}; motion {motion:?}"
                ));
            }
        }
    }
    Ok(ours)
}

fn intervals(oracle: &Polyhedra, m: &Motion) -> IntervalList {
    oracle.intervals(m, &mut CallCounts::default()).unwrap()
}

fn assert_close(got: &IntervalList, want: &[(f64, f64)], eps: f64) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (iv, w) in got.iter().zip(want) {
        assert!(
            (iv.lo - w.0).abs() <= eps && (iv.hi - w.1).abs() <= eps,
            "{got:?} vs {want:?}"
        );
    }
}

fn identity() -> UnitQuaternion<f64> {
    UnitQuaternion::identity()
}

// ---------------------------------------------------------------------------------------------
// hand-computed cases

#[test]
fn unit_cube_slides_through_a_box() {
    let oracle = Polyhedra::new(
        cuboid_at([0.0; 3], [0.5; 3]),
        vec![cuboid_at([0.0; 3], [1.0; 3])],
    );
    // centre from x = −5 to x = 5: contact while |x| ≤ 1.5
    for y in [0.0, 0.7, 1.5] {
        let start = config([-5.0, y, 0.2], &identity());
        let m = Motion::segment(start.clone(), translation([10.0, 0.0, 0.0]));
        assert_close(&intervals(&oracle, &m), &[(0.35, 0.65)], 1e-9);
    }
    // just beyond touching
    let start = config([-5.0, 1.5 + 1e-6, 0.0], &identity());
    let m = Motion::segment(start.clone(), translation([10.0, 0.0, 0.0]));
    assert!(intervals(&oracle, &m).is_empty());
    // a diagonal line: contact while max(|x|, |y|) ≤ 1.5 with x = y = −5 + 10t
    let start = config([-5.0, -5.0, 0.3], &identity());
    let m = Motion::line(start.clone(), translation([10.0, 10.0, 0.0]));
    assert_close(&intervals(&oracle, &m), &[(0.35, 0.65)], 1e-9);
}

#[test]
fn containment_of_closed_bodies_but_not_of_soups() {
    // a small cube crossing a big box: surface contact at the walls, containment in between
    let small = cuboid_at([0.0; 3], [0.25; 3]);
    let start = config([-5.0, 0.1, -0.2], &identity());
    let m = Motion::segment(start.clone(), translation([10.0, 0.0, 0.0]));
    let solid = Polyhedra::new(small.clone(), vec![cuboid_at([0.0; 3], [2.0; 3])]);
    assert_close(&intervals(&solid, &m), &[(0.275, 0.725)], 1e-9);
    // the same box as a double-sided soup, or with a side missing: only the walls
    let walls = [(0.275, 0.325), (0.675, 0.725)];
    let soup = Polyhedra::new(
        small.clone(),
        vec![double_sided(&cuboid_at([0.0; 3], [2.0; 3]))],
    );
    assert_close(&intervals(&soup, &m), &walls, 1e-9);
    let open = Polyhedra::new(small, vec![open_box([0.0; 3], [2.0; 3])]);
    assert_close(&intervals(&open, &m), &walls, 1e-9);
    // the other way round: a big robot swallowing a small obstacle
    let big = Polyhedra::new(
        cuboid_at([0.0; 3], [2.0; 3]),
        vec![cuboid_at([0.0, 0.3, 0.1], [0.25; 3])],
    );
    assert_close(&intervals(&big, &m), &[(0.275, 0.725)], 1e-9);
    let q = config([0.0, 0.0, 0.0], &identity());
    assert!(big.collides(&q, &mut CallCounts::default()));
    assert!(solid.collides(
        &config([0.5, 0.0, 0.0], &identity()),
        &mut CallCounts::default()
    ));
    assert!(!soup.collides(
        &config([0.5, 0.0, 0.0], &identity()),
        &mut CallCounts::default()
    ));
}

/// A bar of half-length 2 (half-width 0.1) turning about its centre towards a wall whose face
/// is the plane x = 1: it reaches the wall when 0.1 |cos φ| + 2 |sin φ| = 1.
#[test]
fn bar_turns_into_a_wall() {
    let a = 0.1f64.hypot(2.0);
    let hit = 2.0f64.atan2(0.1) - (1.0 / a).acos();
    let bar = cuboid_at([0.0; 3], [0.1, 2.0, 0.1]);
    let wall = cuboid_at([1.5, 0.0, 0.0], [0.5, 5.0, 5.0]);
    let oracle = Polyhedra::new(bar.clone(), vec![wall.clone()]);
    let start = config([0.0; 3], &identity());
    let quarter = Motion::segment(
        start.clone(),
        Change::Rotation {
            axis: [0.0, 0.0, 1.0],
            angle: FRAC_PI_2,
        },
    );
    assert_close(
        &intervals(&oracle, &quarter),
        &[(hit / FRAC_PI_2, 1.0)],
        1e-9,
    );
    // the other sense of turning reaches the wall just the same (|sin| is even)
    let back = Motion::segment(
        start.clone(),
        Change::Rotation {
            axis: [0.0, 0.0, -1.0],
            angle: FRAC_PI_2,
        },
    );
    assert_close(&intervals(&oracle, &back), &[(hit / FRAC_PI_2, 1.0)], 1e-9);
    // a full turn, t ∈ [−½, ½] for φ ∈ [−π, π]
    let turn = Motion::turn(
        start,
        Change::Rotation {
            axis: [0.0, 0.0, 1.0],
            angle: TAU,
        },
    );
    let want = [
        ((-PI + hit) / TAU, -hit / TAU),
        (hit / TAU, (PI - hit) / TAU),
    ];
    assert_close(&intervals(&oracle, &turn), &want, 1e-9);

    // the same scene moved and turned as a whole: the bar lies along x in its body frame and
    // is turned into place; everything is shifted and the axis follows
    let frame = axis_angle(Vector3::new(0.3, -0.5, 0.8).normalize().into(), 1.1);
    let shift = Vector3::new(10.0, -3.0, 7.0);
    let place = |m: &TriMesh| TriMesh {
        vertices: m.vertices.iter().map(|v| frame * v + shift).collect(),
        triangles: m.triangles.clone(),
    };
    let body_bar = TriMesh {
        vertices: bar
            .vertices
            .iter()
            .map(|v| Point3::new(v.y, -v.x, v.z))
            .collect(),
        triangles: bar.triangles.clone(),
    };
    let oracle = Polyhedra::new(body_bar, vec![place(&wall)]);
    // body x ↦ world y: first turn by +90° about z, then by `frame`
    let orientation = frame * axis_angle([0.0, 0.0, 1.0], FRAC_PI_2);
    let start = config([shift.x, shift.y, shift.z], &orientation);
    let axis = frame * Vector3::z();
    let quarter = Motion::segment(
        start,
        Change::Rotation {
            axis: [axis.x, axis.y, axis.z],
            angle: FRAC_PI_2,
        },
    );
    assert_close(
        &intervals(&oracle, &quarter),
        &[(hit / FRAC_PI_2, 1.0)],
        1e-9,
    );
}

#[test]
fn unsupported_motions_are_errors() {
    let oracle = Polyhedra::new(
        cuboid_at([0.0; 3], [0.5; 3]),
        vec![cuboid_at([3.0, 0.0, 0.0], [1.0; 3])],
    );
    let start = config([0.0; 3], &identity());
    let mut c = CallCounts::default();
    let quat = Motion::segment(
        start.clone(),
        Change::Linear(vec![0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0]),
    );
    assert!(matches!(
        oracle.intervals(&quat, &mut c),
        Err(OracleError::Unsupported(_))
    ));
    let both = Motion::segment(
        start.clone(),
        Change::Linear(vec![1.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.0]),
    );
    assert!(matches!(
        oracle.intervals(&both, &mut c),
        Err(OracleError::Unsupported(_))
    ));
    let short = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![1.0, 0.0, 0.0]));
    assert!(matches!(
        oracle.intervals(&short, &mut c),
        Err(OracleError::Unsupported(_))
    ));
    let nan = Motion::segment(
        start.clone(),
        Change::Rotation {
            axis: [f64::NAN, 0.0, 1.0],
            angle: 1.0,
        },
    );
    assert!(matches!(
        oracle.intervals(&nan, &mut c),
        Err(OracleError::Unsupported(_))
    ));
    let endless = Motion::line(
        start.clone(),
        Change::Rotation {
            axis: [0.0, 0.0, 1.0],
            angle: 1.0,
        },
    );
    assert!(matches!(
        oracle.motion_is_free(&endless, &mut c),
        Err(OracleError::Unsupported(_))
    ));
    // standing still is a static test over the whole range
    let still = Motion::line(start, Change::Linear(vec![0.0; 7]));
    assert!(intervals(&oracle, &still).is_empty());
    let inside = Motion::segment(
        config([3.0, 0.0, 0.0], &identity()),
        Change::Linear(vec![0.0; 7]),
    );
    assert_close(&intervals(&oracle, &inside), &[(0.0, 1.0)], 0.0);
    assert!(oracle.collides(&[0.0, 0.0], &mut c));
}

// ---------------------------------------------------------------------------------------------
// cross-checks against parry

#[test]
fn easy_meshes_agree_with_parry() {
    let (robot, env) = easy();
    let oracle = Polyhedra::new(robot.clone(), vec![env.clone()]);
    assert_eq!(oracle.solids(), (false, vec![false]));
    let reference = Reference {
        robot: soup_shape(&robot),
        grown: None,
        obstacles: vec![soup_shape(&env)],
    };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (lo, hi) = ([14.46, -24.25, -504.86], [457.96, 321.25, -72.86]);
    let mut colliding = 0;
    for k in 0..1000 {
        let p = [0, 1, 2].map(|i| rng.random_range(lo[i]..hi[i]));
        let q = if k % 3 == 0 {
            identity()
        } else {
            random_rotation(&mut rng)
        };
        let (m, span) = random_motion(&mut rng, config(p, &q), 150.0);
        let got = compare(&oracle, &reference, &m, span, 300, 1e-6).unwrap();
        colliding += usize::from(!got.is_empty());
    }
    // the sample must exercise both answers
    assert!(colliding > 200, "only {colliding} motions collide");
    // OMPL.app's own query: start → goal is blocked by the wall
    let start = config([270.0, 160.0, -200.0], &identity());
    let m = Motion::segment(start.clone(), translation([0.0, 0.0, -200.0]));
    let got = compare(&oracle, &reference, &m, Interval::UNIT, 2000, 1e-6).unwrap();
    assert!(!got.is_empty());
    assert!(!got.contains(0.0) && !got.contains(1.0));
}

#[test]
fn thin_plates_and_single_triangles_agree_with_parry() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for _ in 0..150 {
        let tri = |rng: &mut ChaCha8Rng, c: [f64; 3]| {
            let p = random_points(rng, 3, c, 1.0);
            TriMesh::new(p, vec![[0, 1, 2]]).unwrap()
        };
        let robot = tri(&mut rng, [0.0; 3]);
        let plate = {
            let p = random_points(&mut rng, 3, [0.0; 3], 1.5);
            let d = p[1] - p[0] + (p[2] - p[0]);
            let mut v = p.clone();
            v.push(p[0] + d);
            double_sided(&TriMesh::new(v, vec![[0, 1, 2], [1, 3, 2]]).unwrap())
        };
        let single = tri(&mut rng, [0.5, 0.0, 0.0]);
        for obstacle in [single, plate] {
            let oracle = Polyhedra::new(robot.clone(), vec![obstacle.clone()]);
            let reference = Reference {
                robot: soup_shape(&robot),
                grown: None,
                obstacles: vec![soup_shape(&obstacle)],
            };
            let start = config(
                [0, 1, 2].map(|_| rng.random_range(-2.0..2.0)),
                &random_rotation(&mut rng),
            );
            let (m, span) = random_motion(&mut rng, start, 4.0);
            let got = compare(&oracle, &reference, &m, span, 400, 1e-7).unwrap();
            // under translation one pair of triangles meets on one interval (the Minkowski
            // difference of two triangles is convex)
            if matches!(m.change, Change::Linear(_)) && obstacle.triangles.len() == 1 {
                assert!(got.len() <= 1, "{got:?}");
            }
        }
    }
}

/// `n` random points on an ellipsoid with semi-axes `axes` about `centre`: their hull has them
/// all as vertices, about `2n` small faces (fine enough for the trees to cull).
fn ellipsoid_points(
    rng: &mut ChaCha8Rng,
    n: usize,
    centre: [f64; 3],
    axes: [f64; 3],
) -> Vec<Point3<f64>> {
    (0..n)
        .map(|_| {
            let d = random_axis(rng);
            Point3::new(
                centre[0] + axes[0] * d[0],
                centre[1] + axes[1] * d[1],
                centre[2] + axes[2] * d[2],
            )
        })
        .collect()
}

/// A robot and one to three obstacles, all convex: coarse hulls of a few random points, or
/// (when `fine`) finely tessellated ellipsoids.
fn convex_scene(rng: &mut ChaCha8Rng) -> (TriMesh, Vec<TriMesh>) {
    if rng.random_range(0..3) == 0 {
        let axes = |rng: &mut ChaCha8Rng| [0, 1, 2].map(|_| rng.random_range(0.2..1.5));
        let a = axes(rng);
        let robot = hull(&ellipsoid_points(rng, 60, [0.0; 3], a));
        let obstacles = (0..rng.random_range(1..3))
            .map(|_| {
                let c = [0, 1, 2].map(|_| rng.random_range(-2.5..2.5));
                let a = axes(rng);
                hull(&ellipsoid_points(rng, 60, c, a))
            })
            .collect();
        return (robot, obstacles);
    }
    let n = rng.random_range(4..12);
    let robot = random_solid(rng, n, [0.0; 3], 1.0);
    let k = rng.random_range(1..4);
    let obstacles = (0..k)
        .map(|_| {
            let c = [0, 1, 2].map(|_| rng.random_range(-2.5..2.5));
            let n = rng.random_range(4..14);
            let s = rng.random_range(0.3..1.8);
            random_solid(rng, n, c, s)
        })
        .collect();
    (robot, obstacles)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    /// Random convex solids (closed: containment counts, parry's convex shapes are solid too).
    #[test]
    fn random_convex_solids_agree_with_parry(seed in any::<u64>()) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (robot, obstacles) = convex_scene(&mut rng);
        let oracle = Polyhedra::new(robot.clone(), obstacles.clone());
        let reference = Reference {
            robot: convex_shape(&robot),
            grown: SharedShape::round_convex_hull(&robot.vertices, 1e-7),
            obstacles: obstacles.iter().map(convex_shape).collect(),
        };
        let start = config([0, 1, 2].map(|_| rng.random_range(-3.0..3.0)), &random_rotation(&mut rng));
        let (m, span) = random_motion(&mut rng, start, 6.0);
        let got = compare(&oracle, &reference, &m, span, 400, 1e-7);
        prop_assert!(got.is_ok(), "{}", got.unwrap_err());
        // one convex body against one convex body under translation: one interval at most
        if matches!(m.change, Change::Linear(_)) && obstacles.len() == 1 {
            prop_assert!(got.unwrap().len() <= 1);
        }
    }

    /// Axis-aligned boxes on a grid, moving along axes or turning about z by grid angles:
    /// faces slide in each other's planes, edges pass through edges — the degenerate cases.
    #[test]
    fn boxes_on_a_grid_agree_with_parry(seed in any::<u64>()) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let grid = |rng: &mut ChaCha8Rng, n: i32| rng.random_range(-n..=n) as f64 * 0.25;
        let half = |rng: &mut ChaCha8Rng| [0, 1, 2].map(|_| rng.random_range(1..=6) as f64 * 0.25);
        let rh = half(&mut rng);
        let robot = cuboid_at([0.0; 3], rh);
        let mut obstacles = Vec::new();
        let mut shapes = Vec::new();
        for _ in 0..rng.random_range(1..4) {
            let c = [0, 1, 2].map(|_| grid(&mut rng, 8));
            let h = half(&mut rng);
            obstacles.push(cuboid_at(c, h));
            shapes.push(SharedShape::compound(vec![(
                Isometry3::translation(c[0], c[1], c[2]),
                SharedShape::cuboid(h[0], h[1], h[2]),
            )]));
        }
        let oracle = Polyhedra::new(robot, obstacles);
        let reference = Reference {
            robot: SharedShape::cuboid(rh[0], rh[1], rh[2]),
            grown: Some(SharedShape::round_cuboid(rh[0], rh[1], rh[2], 1e-7)),
            obstacles: shapes,
        };
        let yaw = rng.random_range(0..8) as f64 * FRAC_PI_2 / 2.0;
        let start = config([0, 1, 2].map(|_| grid(&mut rng, 8)), &axis_angle([0.0, 0.0, 1.0], yaw));
        let (m, span) = match rng.random_range(0..3) {
            0 => {
                let mut d = [0.0; 3];
                d[rng.random_range(0..3)] = grid(&mut rng, 16);
                (Motion::segment(start.clone(), translation(d)), Interval::UNIT)
            }
            1 => (
                Motion::segment(start, Change::Rotation { axis: [0.0, 0.0, 1.0], angle: rng.random_range(1..8) as f64 * FRAC_PI_2 / 2.0 }),
                Interval::UNIT,
            ),
            _ => (
                Motion::turn(start, Change::Rotation { axis: [0.0, 0.0, 1.0], angle: TAU }),
                Interval { lo: -0.5, hi: 0.5 },
            ),
        };
        let got = compare(&oracle, &reference, &m, span, 400, 1e-7);
        prop_assert!(got.is_ok(), "{}", got.unwrap_err());
    }
}

/// A ring of eight boxes in one closed mesh (eight separate solids), and a robot that fits
/// inside one of them: containment must be decided per connected piece.
#[test]
fn ring_of_boxes_agrees_with_parry() {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let mut parts = Vec::new();
    for k in 0..8 {
        let a = k as f64 * TAU / 8.0;
        let c = [4.0 * a.cos(), 4.0 * a.sin(), 0.0];
        let b = cuboid_at(c, [0.9, 0.9, 0.9]);
        let base = vertices.len() as u32;
        vertices.extend(b.vertices.iter().cloned());
        triangles.extend(b.triangles.iter().map(|t| t.map(|i| i + base)));
        parts.push((
            Isometry3::translation(c[0], c[1], c[2]),
            SharedShape::cuboid(0.9, 0.9, 0.9),
        ));
    }
    let ring = TriMesh::new(vertices, triangles).unwrap();
    let robot = cuboid_at([0.0; 3], [0.2, 0.3, 0.25]);
    let oracle = Polyhedra::new(robot.clone(), vec![ring]);
    let reference = Reference {
        robot: SharedShape::cuboid(0.2, 0.3, 0.25),
        grown: Some(SharedShape::round_cuboid(0.2, 0.3, 0.25, 1e-7)),
        obstacles: vec![SharedShape::compound(parts)],
    };
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..60 {
        let r = rng.random_range(2.5..5.5);
        let a: f64 = rng.random_range(0.0..TAU);
        let start = config(
            [r * a.cos(), r * a.sin(), rng.random_range(-0.5..0.5)],
            &random_rotation(&mut rng),
        );
        let (m, span) = random_motion(&mut rng, start, 6.0);
        compare(&oracle, &reference, &m, span, 400, 1e-7).unwrap();
    }
    // turning about the ring's axis with the robot inside one box: inside during part of the turn
    let start = config([4.0, 0.0, 0.0], &identity());
    let m = Motion::turn(
        start,
        Change::Rotation {
            axis: [0.0, 0.0, 1.0],
            angle: TAU,
        },
    );
    let got = intervals(&oracle, &m);
    assert!(got.contains(0.0));
}

// ---------------------------------------------------------------------------------------------
// internal consistency

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, ..ProptestConfig::default() })]

    /// Enveloping only culls: with and without it the answers are the same, and it tests fewer
    /// pairs; lines and turns agree with segments; yes/no checks agree with the intervals and
    /// the static test agrees with them at sample points.
    #[test]
    fn culling_lines_turns_and_static_tests_are_consistent(seed in any::<u64>()) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (robot, obstacles) = if seed % 2 == 0 {
            convex_scene(&mut rng)
        } else {
            let (r, e) = easy();
            (r, vec![e])
        };
        let scale = if seed % 2 == 0 { 3.0 } else { 150.0 };
        let fast = Polyhedra::new(robot.clone(), obstacles.clone());
        let brute = Polyhedra::new(robot, obstacles).with_enveloping(false);
        let centre = if seed % 2 == 0 { [0.0; 3] } else { [236.0, 148.0, -288.0] };
        let p = [0, 1, 2].map(|i| centre[i] + scale * rng.random_range(-1.0..1.0));
        let start = config(p, &random_rotation(&mut rng));
        let (m, span) = random_motion(&mut rng, start, 2.0 * scale);
        let (mut cf, mut cb) = (CallCounts::default(), CallCounts::default());
        let a = fast.intervals(&m, &mut cf).unwrap();
        let b = brute.intervals(&m, &mut cb).unwrap();
        prop_assert_eq!(a.len(), b.len(), "{:?} vs {:?}", a, b);
        for (x, y) in a.iter().zip(b.iter()) {
            prop_assert!((x.lo - y.lo).abs() <= 1e-9 && (x.hi - y.hi).abs() <= 1e-9, "{:?} vs {:?}", a, b);
        }
        prop_assert!(cf.pairs_tested <= cb.pairs_tested);
        prop_assert_eq!(fast.motion_is_free(&m, &mut cf).unwrap(), a.is_empty());

        // a line, clipped to [0, 1], is the segment; a turn is two half-turn segments
        match &m.change {
            Change::Linear(_) => {
                let seg = intervals(&fast, &Motion::segment(m.origin.clone(), m.change.clone()));
                let line = intervals(&fast, &Motion::line(m.origin.clone(), m.change.clone())).clip(Interval::UNIT);
                prop_assert_eq!(seg.len(), line.len(), "{:?} vs {:?}", seg, line);
                for (x, y) in seg.iter().zip(line.iter()) {
                    prop_assert!((x.lo - y.lo).abs() <= 1e-9 && (x.hi - y.hi).abs() <= 1e-9);
                }
            }
            Change::Rotation { axis, .. } => {
                let turn = intervals(&fast, &Motion::turn(m.origin.clone(), Change::Rotation { axis: *axis, angle: TAU }));
                let fwd = intervals(&fast, &Motion::segment(m.origin.clone(), Change::Rotation { axis: *axis, angle: PI }));
                let bwd = intervals(&fast, &Motion::segment(m.origin.clone(), Change::Rotation { axis: *axis, angle: -PI }));
                for k in 0..=200 {
                    let t = -0.5 + k as f64 / 200.0;
                    let other = if t >= 0.0 { fwd.contains(2.0 * t) } else { bwd.contains(-2.0 * t) };
                    let near = turn.iter().any(|iv| (iv.lo - t).abs() < 1e-7 || (iv.hi - t).abs() < 1e-7);
                    prop_assert!(near || turn.contains(t) == other, "t = {}: {:?} / {:?} {:?}", t, turn, fwd, bwd);
                }
            }
            Change::BodyRotation { .. } => unreachable!("one body's motions only"),
        }

        // the static test at sample points
        for k in 0..=100 {
            let t = span.lo + span.length() * k as f64 / 100.0;
            let near = a.iter().any(|iv| (iv.lo - t).abs() < 1e-7 || (iv.hi - t).abs() < 1e-7);
            let hit = fast.collides(&m.at(t), &mut CallCounts::default());
            prop_assert!(near || hit == a.contains(t), "t = {}: collides {} but {:?}", t, hit, a);
        }
    }
}

#[test]
fn counts_pairs_and_culls_far_obstacles() {
    let (robot, env) = easy();
    let fast = Polyhedra::new(robot.clone(), vec![env.clone()]);
    let brute = Polyhedra::new(robot, vec![env]).with_enveloping(false);
    let start = config([270.0, 160.0, -200.0], &identity());
    let m = Motion::segment(start.clone(), translation([0.0, 0.0, 10.0]));
    let (mut a, mut b) = (CallCounts::default(), CallCounts::default());
    assert!(fast.intervals(&m, &mut a).unwrap().is_empty());
    assert!(brute.intervals(&m, &mut b).unwrap().is_empty());
    let (nr, no) = fast.face_counts();
    // without culling every robot edge meets every obstacle face and vice versa
    assert!(
        b.pairs_tested as usize >= 2 * nr * no,
        "{} vs {nr}·{no}",
        b.pairs_tested
    );
    assert!(
        a.pairs_tested * 20 < b.pairs_tested,
        "{} vs {}",
        a.pairs_tested,
        b.pairs_tested
    );
    // the call itself is not counted by the oracle
    assert_eq!(a.segment_calls + a.line_calls + a.state_checks, 0);
}

// ---------------------------------------------------------------------------------------------
// big meshes: OMPL.app's alpha-1.5 and Apartment, as `viaroad` loads them

/// An OMPL.app problem from `scenes/ompl/3D`: the robot (body frame) and the obstacles.
fn ompl_problem(name: &str) -> (TriMesh, Vec<TriMesh>) {
    use viaroad::scene::{Obstacle, Robot, Scene};
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/ompl/3D")
        .join(format!("{name}.cfg"));
    let scene = Scene::load(&path).unwrap();
    let Robot::Mesh(robot) = scene.robot else {
        panic!("{name}: not a mesh robot")
    };
    let obstacles = scene
        .obstacles
        .into_iter()
        .map(|o| match o {
            Obstacle::Mesh(m) => m,
            other => panic!("{name}: obstacle {other:?}"),
        })
        .collect();
    (robot, obstacles)
}

/// A start near the obstacles: a random obstacle vertex, moved by up to `spread` per axis.
fn start_near(rng: &mut ChaCha8Rng, obstacles: &[TriMesh], spread: f64) -> Vec<f64> {
    let m = &obstacles[rng.random_range(0..obstacles.len())];
    let v = m.vertices[rng.random_range(0..m.vertices.len())];
    let p = [0, 1, 2].map(|i| v[i] + spread * rng.random_range(-1.0..1.0));
    config(p, &random_rotation(rng))
}

/// The radius of `robot` about its reference point.
fn radius(robot: &TriMesh) -> f64 {
    robot
        .vertices
        .iter()
        .map(|v| v.coords.norm())
        .fold(0.0, f64::max)
}

/// The culling by both trees (robot nodes against obstacle nodes, swept along the motion) must
/// not lose a pair: on thousands of triangles, every kind of motion, started next to the
/// obstacles, agrees with parry at fine resolution, and so do the static test and the yes/no
/// check.
#[test]
fn big_meshes_agree_with_parry() {
    for (name, motions, samples, seed) in [("alpha-1.5", 40, 600, 21), ("Apartment", 10, 200, 22)] {
        let (robot, obstacles) = ompl_problem(name);
        let oracle = Polyhedra::new(robot.clone(), obstacles.clone());
        let reference = Reference {
            robot: soup_shape(&robot),
            grown: None,
            obstacles: obstacles.iter().map(soup_shape).collect(),
        };
        let r = radius(&robot);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (mut colliding, mut free) = (0, 0);
        for _ in 0..motions {
            let start = start_near(&mut rng, &obstacles, r);
            let (m, span) = random_motion(&mut rng, start, r);
            let got = compare(&oracle, &reference, &m, span, samples, 1e-6)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let on_segment = got.iter().any(|iv| iv.meet(&m.range).is_some());
            assert_eq!(
                oracle
                    .motion_is_free(&m, &mut CallCounts::default())
                    .unwrap(),
                !on_segment,
                "{name}: yes/no check against {got:?}, motion {m:?}"
            );
            colliding += usize::from(!got.is_empty());
            free += usize::from(got.is_empty());
            for k in [0, samples / 3, samples / 2] {
                let t = span.lo + span.length() * k as f64 / samples as f64;
                let q = m.at(t);
                let near = got
                    .iter()
                    .any(|iv| (iv.lo - t).abs() < 1e-7 || (iv.hi - t).abs() < 1e-7);
                let hit = oracle.collides(&q, &mut CallCounts::default());
                assert!(
                    near || hit == reference.intersects(&q),
                    "{name}: static test at t = {t} says {hit}; intervals {got:?}, motion {m:?}"
                );
            }
        }
        // both answers must be exercised, or the test proves nothing
        assert!(
            colliding >= motions / 5 && free >= motions / 10,
            "{name}: {colliding} colliding, {free} free"
        );
    }
}

/// A piece of `mesh`: its triangles with a corner within `r` of `centre`.
fn crop(mesh: &TriMesh, centre: &Vector3<f64>, r: f64) -> Option<TriMesh> {
    let tris: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| {
            t.iter()
                .any(|&k| (mesh.vertices[k as usize].coords - centre).norm() <= r)
        })
        .copied()
        .collect();
    TriMesh::new(mesh.vertices.clone(), tris).ok()
}

/// On pieces of alpha-1.5 (a few hundred triangles each, so that brute force stays cheap), the
/// culled answer equals the brute-force one — every edge–face pair evaluated — to 1e-9, with
/// far fewer pairs; the yes/no check and the static test agree with brute force too.
#[test]
fn big_mesh_culling_equals_brute_force() {
    let (robot, obstacles) = ompl_problem("alpha-1.5");
    let r = radius(&robot);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut colliding, mut fewer) = (0, 0);
    let cases = 12;
    for case in 0..cases {
        let start = start_near(&mut rng, &obstacles, 0.3 * r);
        let p = Vector3::new(start[0], start[1], start[2]);
        let piece_robot = crop(&robot, &Vector3::zeros(), 0.15 * r);
        let piece_env: Vec<TriMesh> = obstacles
            .iter()
            .filter_map(|o| crop(o, &p, 0.25 * r))
            .collect();
        let (Some(piece_robot), false) = (piece_robot, piece_env.is_empty()) else {
            continue;
        };
        let fast = Polyhedra::new(piece_robot.clone(), piece_env.clone());
        let brute = Polyhedra::new(piece_robot, piece_env).with_enveloping(false);
        let (m, span) = random_motion(&mut rng, start, 0.5 * r);
        let (mut cf, mut cb) = (CallCounts::default(), CallCounts::default());
        let a = fast.intervals(&m, &mut cf).unwrap();
        let b = brute.intervals(&m, &mut cb).unwrap();
        assert_eq!(
            a.len(),
            b.len(),
            "case {case}: {a:?} vs {b:?}, motion {m:?}"
        );
        for (x, y) in a.iter().zip(b.iter()) {
            assert!(
                (x.lo - y.lo).abs() <= 1e-9 && (x.hi - y.hi).abs() <= 1e-9,
                "case {case}: {a:?} vs {b:?}, motion {m:?}"
            );
        }
        assert_eq!(
            fast.motion_is_free(&m, &mut CallCounts::default()).unwrap(),
            brute
                .motion_is_free(&m, &mut CallCounts::default())
                .unwrap(),
            "case {case}: {a:?}"
        );
        for k in 0..=20 {
            let q = m.at(span.lo + span.length() * k as f64 / 20.0);
            assert_eq!(
                fast.collides(&q, &mut CallCounts::default()),
                brute.collides(&q, &mut CallCounts::default()),
                "case {case}: static test at {q:?}"
            );
        }
        colliding += usize::from(!a.is_empty());
        fewer += usize::from(cf.pairs_tested * 10 < cb.pairs_tested);
    }
    assert!(
        colliding >= cases / 4,
        "only {colliding} of {cases} collide"
    );
    assert!(
        fewer >= cases / 2,
        "culling saved little: {fewer} of {cases}"
    );
}
