//! Degenerate geometry, each case with its expected answer under the
//! library's documented convention — **touching counts as collision** (closed obstacles and a
//! closed robot; `CollisionOracle::intervals`) — and checked against parry on solid shapes
//! (cuboids, convex polygons and polyhedra: distance 0 means touching or overlapping):
//! flush faces, an edge or a vertex exactly on a face, coplanar and duplicate faces,
//! zero-area triangles, zero-length motions, antipodal quaternions, turns of exactly π and 2π,
//! configurations exactly on the bounds, a robot larger than the space, an empty environment.

use parry2d_f64::shape::ConvexPolygon;
use parry3d_f64::math::{Isometry, Point, Vector};
use parry3d_f64::na::{Quaternion, UnitQuaternion};
use parry3d_f64::shape::{ConvexPolyhedron, Cuboid, SharedShape};
use std::f64::consts::{PI, TAU};
use std::path::Path;
use viaroad::bench::validity::Checker;
use viaroad::local::LocalSpec;
use viaroad::oracle::{CallCounts, CollisionOracle, CountedOracle};
use viaroad::roadmap::{Budget, LearnParams, Learner, QueryPlanner};
use viaroad::scene::toml_format::from_str;
use viaroad::scene::{Obstacle, Scene, SceneError};
use viaroad::space::{Change, Config, Motion};

fn scene(text: &str) -> Scene {
    from_str(text, Path::new("degenerate.toml")).unwrap()
}

fn se3(robot: &str, obstacles: &[&str]) -> Scene {
    let mut t = format!(
        "name = \"d\"\n[space]\nkind = \"se3\"\nlower = [-5.0, -5.0, -5.0]\nupper = [5.0, 5.0, 5.0]\n[robot]\n{robot}\n"
    );
    for o in obstacles {
        t += &format!("[[obstacle]]\n{o}\n");
    }
    scene(&t)
}

fn se2(lower: [f64; 2], upper: [f64; 2], robot: &str, obstacles: &[&str]) -> Scene {
    let mut t = format!(
        "name = \"d\"\n[space]\nkind = \"se2\"\nlower = {lower:?}\nupper = {upper:?}\n[robot]\n{robot}\n"
    );
    for o in obstacles {
        t += &format!("[[obstacle]]\n{o}\n");
    }
    scene(&t)
}

fn at(x: f64, y: f64, z: f64) -> Config {
    vec![x, y, z, 0.0, 0.0, 0.0, 1.0]
}

fn collides(s: &Scene, q: &[f64]) -> bool {
    s.oracle().collides(q, &mut CallCounts::default())
}

fn intervals(s: &Scene, a: &[f64], b: &[f64]) -> viaroad::interval::IntervalList {
    let m = s.space.direct_motion(a, b).expect("one group changes");
    s.oracle()
        .intervals(&m, &mut CallCounts::default())
        .unwrap()
}

/// parry's reference in SE(3): solid shapes placed by `q`.
struct Solid3 {
    robot: SharedShape,
    obstacles: Vec<(Isometry<f64>, SharedShape)>,
}

impl Solid3 {
    fn touches(&self, q: &[f64]) -> bool {
        let r = UnitQuaternion::from_quaternion(Quaternion::new(q[6], q[3], q[4], q[5]));
        let p = Isometry::from_parts(Vector::new(q[0], q[1], q[2]).into(), r);
        self.obstacles.iter().any(|(o, s)| {
            parry3d_f64::query::distance(&p, self.robot.as_ref(), o, s.as_ref()).unwrap() <= 1e-12
        })
    }
}

fn cuboid(h: [f64; 3]) -> SharedShape {
    SharedShape::new(Cuboid::new(Vector::new(h[0], h[1], h[2])))
}

fn placed(c: [f64; 3], s: SharedShape) -> (Isometry<f64>, SharedShape) {
    (Isometry::translation(c[0], c[1], c[2]), s)
}

const UNIT_CUBE: &str = "box = { half_extents = [0.5, 0.5, 0.5] }";

/// Oracle and parry agree at `q`, and both say `expected`.
fn expect3(s: &Scene, reference: &Solid3, q: &[f64], expected: bool) {
    assert_eq!(collides(s, q), expected, "oracle at {q:?}");
    assert_eq!(reference.touches(q), expected, "parry at {q:?}");
}

// ---------------------------------------------------------------------------------------------
// touching contacts

#[test]
fn flush_faces_touch() {
    // robot [-0.5, 0.5]³, obstacle x ∈ [0.5, 1.5]: the faces at x = 0.5 coincide
    let s = se3(
        UNIT_CUBE,
        &["box = { center = [1.0, 0.0, 0.0], half_extents = [0.5, 0.5, 0.5] }"],
    );
    let r = Solid3 {
        robot: cuboid([0.5; 3]),
        obstacles: vec![placed([1.0, 0.0, 0.0], cuboid([0.5; 3]))],
    };
    expect3(&s, &r, &at(0.0, 0.0, 0.0), true);
    expect3(&s, &r, &at(-1e-6, 0.0, 0.0), false);
    // flush and offset sideways so that only a face strip, an edge, a corner meet
    expect3(&s, &r, &at(0.0, 0.9, 0.0), true);
    expect3(&s, &r, &at(0.0, 1.0, 0.0), true);
    expect3(&s, &r, &at(0.0, 1.0, 1.0), true);
    expect3(&s, &r, &at(0.0, 1.0 + 1e-6, 1.0), false);
    // sliding along the flush face collides all the way
    let iv = intervals(&s, &at(0.0, -0.25, 0.0), &at(0.0, 0.25, 0.0));
    assert_eq!(iv.len(), 1, "{iv:?}");
    assert!(iv.first().unwrap().lo <= 1e-12 && iv.first().unwrap().hi >= 1.0 - 1e-12);
    // approaching until flush: the last instant only
    let iv = intervals(&s, &at(-1.0, 0.0, 0.0), &at(0.0, 0.0, 0.0));
    assert!(iv.contains(1.0), "{iv:?}");
    assert!(!iv.contains(0.999), "{iv:?}");
    // and leaving from flush: the first instant only
    let iv = intervals(&s, &at(0.0, 0.0, 0.0), &at(-1.0, 0.0, 0.0));
    assert!(iv.contains(0.0) && !iv.contains(0.001), "{iv:?}");
}

#[test]
fn edge_and_vertex_exactly_on_a_face() {
    // a prism whose vertical edge x = 0.5, y = 0 lies on the obstacle's face x = 0.5
    let prism = "convex = { points = [[-0.5, -0.5, -0.5], [-0.5, 0.5, -0.5], [0.5, 0.0, -0.5], [-0.5, -0.5, 0.5], [-0.5, 0.5, 0.5], [0.5, 0.0, 0.5]] }";
    let obstacle = "box = { center = [1.0, 0.0, 0.0], half_extents = [0.5, 0.5, 0.5] }";
    let s = se3(prism, &[obstacle]);
    let pts: Vec<Point<f64>> = [
        [-0.5, -0.5, -0.5],
        [-0.5, 0.5, -0.5],
        [0.5, 0.0, -0.5],
        [-0.5, -0.5, 0.5],
        [-0.5, 0.5, 0.5],
        [0.5, 0.0, 0.5],
    ]
    .iter()
    .map(|p| Point::new(p[0], p[1], p[2]))
    .collect();
    let r = Solid3 {
        robot: SharedShape::new(ConvexPolyhedron::from_convex_hull(&pts).unwrap()),
        obstacles: vec![placed([1.0, 0.0, 0.0], cuboid([0.5; 3]))],
    };
    expect3(&s, &r, &at(0.0, 0.0, 0.0), true);
    expect3(&s, &r, &at(-1e-6, 0.0, 0.0), false);
    // the edge's end exactly on the obstacle's top edge: still touching
    expect3(&s, &r, &at(0.0, 0.0, 1.0), true);
    expect3(&s, &r, &at(0.0, 0.0, 1.0 + 1e-6), false);
    // a vertex on a face: a tetrahedron with its apex at x = 0.5
    let tet = "convex = { points = [[-0.5, -0.5, -0.5], [-0.5, 0.5, -0.5], [-0.5, 0.0, 0.5], [0.5, 0.0, 0.0]] }";
    let s = se3(tet, &[obstacle]);
    assert!(collides(&s, &at(0.0, 0.0, 0.0)));
    assert!(!collides(&s, &at(-1e-6, 0.0, 0.0)));
}

// ---------------------------------------------------------------------------------------------
// coplanar, duplicate and zero-area faces

/// Oracle and parry agree along a motion, sampled at 401 instants.
fn agree_along(s: &Scene, reference: &Solid3, a: &[f64], b: &[f64]) -> usize {
    let m = s.space.direct_motion(a, b).unwrap();
    let iv = s
        .oracle()
        .intervals(&m, &mut CallCounts::default())
        .unwrap();
    let mut colliding = 0;
    for k in 0..=400 {
        let t = k as f64 / 400.0;
        let q = m.at(t);
        let p = reference.touches(&q);
        assert_eq!(collides(s, &q), p, "state at t = {t}");
        // the intervals agree away from their ends (a sample can land on an end)
        let near_end = iv
            .iter()
            .any(|i| (i.lo - t).abs() < 1e-9 || (i.hi - t).abs() < 1e-9);
        if !near_end {
            assert_eq!(iv.contains(t), p, "intervals {iv:?} at t = {t}");
        }
        colliding += p as usize;
    }
    colliding
}

#[test]
fn coplanar_and_duplicate_faces() {
    // two boxes sharing the face x = 1.5, the second listed twice (every face duplicated)
    let a = "box = { center = [1.0, 0.0, 0.0], half_extents = [0.5, 0.5, 0.5] }";
    let b = "box = { center = [2.0, 0.0, 0.0], half_extents = [0.5, 0.5, 0.5] }";
    let s = se3(UNIT_CUBE, &[a, b, b]);
    let r = Solid3 {
        robot: cuboid([0.5; 3]),
        obstacles: vec![
            placed([1.0, 0.0, 0.0], cuboid([0.5; 3])),
            placed([2.0, 0.0, 0.0], cuboid([0.5; 3])),
        ],
    };
    // passing over the shared face, flush on top (z = 1), then 1e-6 above it
    assert_eq!(
        agree_along(&s, &r, &at(-1.0, 0.0, 1.0), &at(4.0, 0.0, 1.0)),
        (0..=400)
            .filter(|k| {
                let x = -1.0 + 5.0 * *k as f64 / 400.0;
                (0.0..=3.0).contains(&x)
            })
            .count()
    );
    assert_eq!(
        agree_along(
            &s,
            &r,
            &at(-1.0, 0.0, 1.0 + 1e-6),
            &at(4.0, 0.0, 1.0 + 1e-6)
        ),
        0
    );
    // through the shared face along its plane
    assert!(agree_along(&s, &r, &at(1.5, 2.0, 0.0), &at(1.5, -2.0, 0.0)) > 0);
    // coplanar top faces of two separate boxes with a gap between
    let c = "box = { center = [3.0, 0.0, 0.0], half_extents = [0.4, 0.5, 0.5] }";
    let s2 = se3(UNIT_CUBE, &[a, c]);
    let r2 = Solid3 {
        robot: cuboid([0.5; 3]),
        obstacles: vec![
            placed([1.0, 0.0, 0.0], cuboid([0.5; 3])),
            placed([3.0, 0.0, 0.0], cuboid([0.4, 0.5, 0.5])),
        ],
    };
    agree_along(&s2, &r2, &at(-1.0, 0.0, 1.0), &at(4.0, 0.0, 1.0));
    agree_along(&s2, &r2, &at(2.0, -3.0, 0.0), &at(2.0, 3.0, 0.0));
}

#[test]
fn zero_area_triangles_change_nothing() {
    let clean = se3(
        UNIT_CUBE,
        &["box = { center = [1.5, 0.0, 0.0], half_extents = [0.5, 0.5, 0.5] }"],
    );
    let Obstacle::Mesh(m) = &clean.obstacles[0] else {
        panic!("a mesh")
    };
    // add degenerate triangles: a repeated vertex, three collinear vertices (on an edge of the
    // box), a triangle of three copies of one vertex
    let mut v = m.vertices.clone();
    let n = v.len() as u32;
    v.push(Point::new(1.0, -0.5, -0.5));
    v.push(Point::new(1.5, -0.5, -0.5));
    v.push(Point::new(2.0, -0.5, -0.5));
    let mut t = m.triangles.clone();
    t.push([0, 0, 1]);
    t.push([n, n + 1, n + 2]);
    t.push([2, 2, 2]);
    let dirty_mesh = viaroad::geometry::TriMesh::new(v, t).unwrap();
    assert_eq!(
        dirty_mesh.triangles.len(),
        m.triangles.len(),
        "zero-area triangles are dropped"
    );
    let mut dirty = clean.clone();
    dirty.obstacles = vec![Obstacle::Mesh(dirty_mesh)];
    let r = Solid3 {
        robot: cuboid([0.5; 3]),
        obstacles: vec![placed([1.5, 0.0, 0.0], cuboid([0.5; 3]))],
    };
    for (a, b) in [
        (at(-2.0, 0.0, 0.0), at(3.0, 0.0, 0.0)),
        (at(0.0, -2.0, -1.0), at(0.0, 2.0, -1.0)),
        (at(1.5, -2.0, -1.0), at(1.5, 2.0, -1.0)),
    ] {
        agree_along(&clean, &r, &a, &b);
        agree_along(&dirty, &r, &a, &b);
    }
    // an obstacle that is nothing but a zero-area triangle is refused with an error, not a panic
    let flat = viaroad::geometry::TriMesh::new(
        vec![
            Point::new(0.0, 0.0, 0.0),
            Point::new(1.0, 0.0, 0.0),
            Point::new(2.0, 0.0, 0.0),
        ],
        vec![[0, 1, 2]],
    );
    if let Ok(f) = flat {
        assert!(f.triangles.is_empty());
    }
}

// ---------------------------------------------------------------------------------------------
// zero-length motions, antipodal quaternions, turns of π and 2π

#[test]
fn zero_length_motions() {
    let s = se3(
        UNIT_CUBE,
        &["box = { center = [1.0, 0.0, 0.0], half_extents = [0.5, 0.5, 0.5] }"],
    );
    let o = s.oracle();
    for (q, colliding) in [
        (at(-1.0, 0.0, 0.0), false),
        (at(0.0, 0.0, 0.0), true),
        (at(0.5, 0.0, 0.0), true),
    ] {
        for change in [
            Change::Linear(vec![0.0; 7]),
            Change::Rotation {
                axis: [0.0, 0.0, 1.0],
                angle: 0.0,
            },
        ] {
            let m = Motion::segment(q.clone(), change);
            let iv = o.intervals(&m, &mut CallCounts::default()).unwrap();
            if colliding {
                assert!(
                    iv.contains(0.0) && iv.contains(0.5) && iv.contains(1.0),
                    "{q:?}: {iv:?}"
                );
            } else {
                assert!(iv.is_empty(), "{q:?}: {iv:?}");
            }
        }
        assert_eq!(s.space.distance(&q, &q), 0.0);
    }
    // discs: a zero-length segment inside, on the rim, outside a disc
    let d = scene(
        "name = \"d\"\n[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n[[obstacle]]\ndisc = { center = [0.5, 0.5], radius = 0.25 }\n",
    );
    let od = d.oracle();
    for (q, colliding) in [([0.5, 0.5], true), ([0.75, 0.5], true), ([0.8, 0.5], false)] {
        let m = Motion::segment(q.to_vec(), Change::Linear(vec![0.0, 0.0]));
        let iv = od.intervals(&m, &mut CallCounts::default()).unwrap();
        assert_eq!(!iv.is_empty(), colliding, "{q:?}: {iv:?}");
        assert_eq!(
            od.collides(&q, &mut CallCounts::default()),
            colliding,
            "{q:?}"
        );
    }
}

#[test]
fn antipodal_quaternions_are_one_orientation() {
    // an elongated robot beside a box: the orientation matters
    let s = se3(
        "box = { half_extents = [1.0, 0.1, 0.1] }",
        &["box = { center = [0.0, 1.4, 0.0], half_extents = [0.5, 0.5, 0.5] }"],
    );
    let r = Solid3 {
        robot: cuboid([1.0, 0.1, 0.1]),
        obstacles: vec![placed([0.0, 1.4, 0.0], cuboid([0.5; 3]))],
    };
    let h = std::f64::consts::FRAC_1_SQRT_2;
    // turned 90° about z (pointing into the box) and 30° about an oblique axis
    let n = (1.0f64 + 4.0 + 9.0).sqrt();
    let (sn, cs) = (PI / 12.0).sin_cos();
    for q in [
        vec![0.0, 0.0, 0.0, 0.0, 0.0, h, h],
        vec![0.0, -0.5, 0.0, sn / n, 2.0 * sn / n, 3.0 * sn / n, cs],
        vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
    ] {
        let mut neg = q.clone();
        neg[3..].iter_mut().for_each(|v| *v = -*v);
        assert_eq!(collides(&s, &q), collides(&s, &neg), "{q:?}");
        assert_eq!(collides(&s, &q), r.touches(&q), "{q:?}");
        assert_eq!(r.touches(&q), r.touches(&neg));
        assert!(s.space.distance(&q, &neg) < 1e-12, "{q:?}");
        // the motion from q to −q does not turn
        let iv_turn = intervals(&s, &q, &neg);
        assert_eq!(iv_turn.is_empty(), !collides(&s, &q), "{q:?}: {iv_turn:?}");
    }
    // pointing into the box collides, lying along x does not
    assert!(collides(&s, &[0.0, 0.0, 0.0, 0.0, 0.0, h, h]));
    assert!(!collides(&s, &at(0.0, 0.0, 0.0)));
    // a query from q to −q is answered with a path the independent checker accepts
    let q = vec![0.0, -2.0, 0.0, 0.0, 0.0, h, h];
    let neg = vec![0.0, -2.0, 0.0, 0.0, 0.0, -h, -h];
    answer_and_check(&s, &q, &neg);
}

#[test]
fn turns_of_pi_and_two_pi() {
    // SE(3): a rod of half-length 1 turning by exactly π about z sweeps the disc of radius
    // ~1.005; a box at y ≥ 1 is hit in the middle of the turn, not at its ends
    let s = se3(
        "box = { half_extents = [1.0, 0.1, 0.1] }",
        &["box = { center = [0.0, 1.5, 0.0], half_extents = [0.5, 0.5, 0.5] }"],
    );
    let r = Solid3 {
        robot: cuboid([1.0, 0.1, 0.1]),
        obstacles: vec![placed([0.0, 1.5, 0.0], cuboid([0.5; 3]))],
    };
    let a = at(0.0, 0.0, 0.0);
    let b = vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]; // π about z
    assert!(!collides(&s, &a) && !collides(&s, &b));
    assert!((s.space.distance(&a, &b) - PI * s.space.rotation_scale()).abs() < 1e-9);
    let iv = intervals(&s, &a, &b);
    assert!(iv.contains(0.5), "{iv:?}");
    assert!(!iv.contains(0.0) && !iv.contains(1.0), "{iv:?}");
    assert!(agree_along(&s, &r, &a, &b) > 0);
    // a turn by 2π ends where it began: −identity is the identity
    let full = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0];
    assert!(s.space.distance(&a, &full) < 1e-12);
    assert!(intervals(&s, &a, &full).is_empty());
    // the rotation by exactly π as an explicit motion, both ways round, agrees with parry
    for angle in [PI, -PI, TAU] {
        let m = Motion::segment(
            a.clone(),
            Change::Rotation {
                axis: [0.0, 0.0, 1.0],
                angle,
            },
        );
        let iv = s
            .oracle()
            .intervals(&m, &mut CallCounts::default())
            .unwrap();
        for k in 0..=200 {
            let t = k as f64 / 200.0;
            let near_end = iv
                .iter()
                .any(|i| (i.lo - t).abs() < 1e-9 || (i.hi - t).abs() < 1e-9);
            if !near_end {
                assert_eq!(
                    iv.contains(t),
                    r.touches(&m.at(t)),
                    "angle {angle}, t = {t}: {iv:?}"
                );
            }
        }
    }

    // SE(2): θ = π and θ = −π are one configuration, θ = 2π is θ = 0
    let p = se2(
        [0.0, 0.0],
        [10.0, 10.0],
        "box = { half_extents = [1.0, 0.1] }",
        &["box = { center = [5.0, 6.5], half_extents = [0.5, 0.5] }"],
    );
    for (x, y) in [
        ([5.0, 5.0, PI], [5.0, 5.0, -PI]),
        ([5.0, 5.0, 0.0], [5.0, 5.0, TAU]),
    ] {
        assert!(p.space.distance(&x, &y) < 1e-12, "{x:?} {y:?}");
        assert_eq!(collides(&p, &x), collides(&p, &y));
        let mut yn = y.to_vec();
        p.space.normalize(&mut yn);
        assert!((yn[2] - x[2]).abs() < 1e-12 || ((yn[2] - x[2]).abs() - TAU).abs() < 1e-12);
    }
    // the turn by π sweeps into the box at y ∈ [6, 7] (rod half-length ~1.005 from y = 5)
    let iv = intervals(&p, &[5.0, 5.0, 0.0], &[5.0, 5.0, PI]);
    assert!(
        iv.contains(0.5) && !iv.contains(0.0) && !iv.contains(1.0),
        "{iv:?}"
    );
    let pc = Checker::for_scene(&p).unwrap();
    assert!(pc
        .check_path(&[vec![5.0, 5.0, 0.0], vec![5.0, 5.0, PI]])
        .is_err());
    assert!(pc
        .check_path(&[vec![5.0, 3.0, 0.0], vec![5.0, 3.0, PI]])
        .is_ok());
    // parry on the convex pieces, at the middle of the turn
    let rod = ConvexPolygon::from_convex_hull(&[
        parry2d_f64::math::Point::new(-1.0, -0.1),
        parry2d_f64::math::Point::new(1.0, -0.1),
        parry2d_f64::math::Point::new(1.0, 0.1),
        parry2d_f64::math::Point::new(-1.0, 0.1),
    ])
    .unwrap();
    let block = parry2d_f64::shape::Cuboid::new(parry2d_f64::na::Vector2::new(0.5, 0.5));
    let d = parry2d_f64::query::distance(
        &parry2d_f64::math::Isometry::new(parry2d_f64::na::Vector2::new(5.0, 5.0), PI / 2.0),
        &rod,
        &parry2d_f64::math::Isometry::translation(5.0, 6.5),
        &block,
    )
    .unwrap();
    assert_eq!(d <= 1e-12, collides(&p, &[5.0, 5.0, PI / 2.0]));
}

// ---------------------------------------------------------------------------------------------
// bounds, a robot larger than the space, an empty environment

#[test]
fn configurations_exactly_on_the_bounds() {
    let s = se3(UNIT_CUBE, &[]);
    let o = s.oracle();
    for q in [at(-5.0, -5.0, -5.0), at(5.0, 5.0, 5.0), at(-5.0, 0.0, 5.0)] {
        assert!(s.space.in_bounds(&q), "{q:?}");
        assert!(!o.collides(&q, &mut CallCounts::default()), "{q:?}");
        assert_eq!(s.check_config(o.as_ref(), "start", &q).unwrap(), q);
    }
    let outside = at(5.0 + 1e-9, 0.0, 0.0);
    assert!(matches!(
        s.check_config(o.as_ref(), "start", &outside),
        Err(SceneError::OutOfBounds { .. })
    ));
    assert!(o.collides(&outside, &mut CallCounts::default()));
    // a motion ending exactly on the bound is free; one going past it collides from there on
    assert!(intervals(&s, &at(0.0, 0.0, 0.0), &at(5.0, 0.0, 0.0)).is_empty());
    let iv = intervals(&s, &at(0.0, 0.0, 0.0), &at(10.0, 0.0, 0.0));
    // closed intervals: the one leaving the box starts at the instant on the bound itself
    // (x = 5 is free as a configuration, but an interval list cannot be open at its start;
    // the answer errs on the safe side by that single instant)
    assert_eq!(iv.len(), 1, "{iv:?}");
    assert_eq!(iv.first().unwrap().lo, 0.5, "{iv:?}");
    assert!(!iv.contains(0.5 - 1e-9) && iv.contains(0.5 + 1e-9) && iv.contains(1.0));
    // the same in R^2 with discs: a corner of the square, exactly on a disc's rim
    let d = scene(
        "name = \"d\"\n[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n[[obstacle]]\ndisc = { center = [1.0, 1.0], radius = 0.25 }\n",
    );
    let od = d.oracle();
    assert!(!od.collides(&[0.0, 0.0], &mut CallCounts::default()));
    assert!(od.collides(&[1.0, 1.0], &mut CallCounts::default()));
    assert!(
        od.collides(&[0.75, 1.0], &mut CallCounts::default()),
        "touching the rim"
    );
    assert!(!od.collides(&[0.75 - 1e-9, 1.0], &mut CallCounts::default()));
    assert!(
        od.collides(&[1.0 + 1e-12, 0.0], &mut CallCounts::default()),
        "outside"
    );
    assert!(d.check_config(od.as_ref(), "goal", &[1.0, 0.0]).is_ok());
}

fn answer_and_check(s: &Scene, a: &[f64], b: &[f64]) {
    let oracle = s.oracle();
    let method = LocalSpec::roadmap_default().build();
    let learnt = Learner::for_scene(s, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(40), 1, &mut |_| {})
        .unwrap();
    let planner = QueryPlanner::new(&learnt.roadmap, oracle.as_ref()).unwrap();
    let r = planner.query(a, b).unwrap();
    assert!(r.is_solved(), "{:?}", r.outcome);
    Checker::for_scene(s).unwrap().check_path(&r.path).unwrap();
}

#[test]
fn robot_larger_than_the_space() {
    // a 10 × 10 robot whose reference point moves in [0, 1]²: free without obstacles …
    let free = se2(
        [0.0, 0.0],
        [1.0, 1.0],
        "box = { half_extents = [5.0, 5.0] }",
        &[],
    );
    answer_and_check(&free, &[0.0, 0.0, 0.0], &[1.0, 1.0, 1.0]);
    // … and with a wall just outside the bounds every configuration collides: learning stops
    // without nodes, the queries are refused, nothing panics or hangs
    let walled = se2(
        [0.0, 0.0],
        [1.0, 1.0],
        "box = { half_extents = [5.0, 5.0] }",
        &["box = { center = [0.5, -0.6], half_extents = [1.0, 0.5] }"],
    );
    let o = walled.oracle();
    for q in [[0.0, 0.0, 0.0], [1.0, 1.0, PI], [0.5, 0.5, 1.0]] {
        assert!(o.collides(&q, &mut CallCounts::default()));
        assert!(matches!(
            walled.check_config(o.as_ref(), "start", &q),
            Err(SceneError::InCollision { .. })
        ));
    }
    let method = LocalSpec::roadmap_default().build();
    let params = LearnParams {
        stall_rounds: 3,
        sample_attempts: 5,
        ..LearnParams::default()
    };
    let learnt = Learner::for_scene(&walled, o.as_ref(), method.as_ref())
        .learn(&params, &Budget::nodes(20), 1, &mut |_| {})
        .unwrap();
    assert_eq!(learnt.roadmap.node_count(), 0);
    assert!(!o.is_free(&[0.5, 0.5, 0.0], &mut CallCounts::default()));
}

#[test]
fn empty_environments() {
    let se3_empty = se3(UNIT_CUBE, &[]);
    assert!(se3_empty.obstacles.is_empty());
    let h = std::f64::consts::FRAC_1_SQRT_2;
    answer_and_check(
        &se3_empty,
        &at(-4.0, -4.0, -4.0),
        &[4.0, 4.0, 4.0, h, 0.0, 0.0, h],
    );
    let se2_empty = se2(
        [0.0, 0.0],
        [1.0, 1.0],
        "box = { half_extents = [0.1, 0.1] }",
        &[],
    );
    answer_and_check(&se2_empty, &[0.0, 0.0, 0.0], &[1.0, 1.0, PI]);
    let discs_empty = scene(
        "name = \"d\"\n[space]\nkind = \"r3\"\nlower = [0.0, 0.0, 0.0]\nupper = [1.0, 1.0, 1.0]\n",
    );
    answer_and_check(&discs_empty, &[0.0, 0.0, 0.0], &[1.0, 1.0, 1.0]);
    for s in [&se3_empty, &se2_empty, &discs_empty] {
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(3);
        let m = Motion::segment(
            s.space.sample_uniform(&mut rng),
            Change::Linear(vec![0.0; s.space.dim()]),
        );
        assert!(s
            .oracle()
            .intervals(&m, &mut CallCounts::default())
            .unwrap()
            .is_empty());
    }
}
