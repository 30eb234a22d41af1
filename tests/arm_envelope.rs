//! A link mesh of thousands of triangles is planned against its envelope
//! (`robot::shapes::envelope`): a polytope of a few hundred faces containing it. Containment is
//! what makes it safe: every configuration the independent checker (the mesh itself) finds
//! colliding lies inside the envelope oracle's intervals, and so inside the exact mesh oracle's
//! intervals' envelope; the envelope only ever adds collision.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;
use viaroad::oracle::CallCounts;
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::shapes::{envelope, Primitive, ENVELOPE_ABOVE, ENVELOPE_GAP};
use viaroad::robot::{Arm, ArmChecker, ArmOptions, ArmOracle};
use viaroad::scene::moveit::{CollisionObject, ObjectShape};

/// A closed puck (a cylinder of `sides` sides and `rings` bands along its axis, capped by fans
/// about the axis) of radius 0.06 and height 0.04, as OBJ text: thousands of triangles for
/// what a few hundred faces contain.
fn puck_obj(sides: usize, rings: usize) -> String {
    let (r, h) = (0.06, 0.04);
    let mut obj = String::new();
    for k in 0..=rings {
        let z = -h / 2.0 + h * k as f64 / rings as f64;
        for i in 0..sides {
            let a = std::f64::consts::TAU * i as f64 / sides as f64;
            writeln!(obj, "v {} {} {}", r * a.cos(), r * a.sin(), z).unwrap();
        }
    }
    let centre = |z: f64, obj: &mut String| writeln!(obj, "v 0 0 {z}").unwrap();
    centre(-h / 2.0, &mut obj);
    centre(h / 2.0, &mut obj);
    let v = |k: usize, i: usize| k * sides + i % sides + 1; // OBJ counts from 1
    for k in 0..rings {
        for i in 0..sides {
            let (a, b, c, d) = (v(k, i), v(k, i + 1), v(k + 1, i + 1), v(k + 1, i));
            writeln!(obj, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    let (bottom, top) = ((rings + 1) * sides + 1, (rings + 1) * sides + 2);
    for i in 0..sides {
        writeln!(obj, "f {bottom} {} {}", v(0, i + 1), v(0, i)).unwrap();
        writeln!(obj, "f {top} {} {}", v(rings, i), v(rings, i + 1)).unwrap();
    }
    obj
}

/// Writes the turntable arm's URDF and its puck into `dir`.
fn write_puck_arm(dir: &std::path::Path) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("puck.obj"), puck_obj(240, 8)).unwrap();
    std::fs::write(
        dir.join("puck.urdf"),
        r#"<robot name="puck">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="beam"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="beam"><collision><origin xyz="0.23 0 0"/><geometry><box size="0.36 0.03 0.03"/></geometry></collision></link>
  <joint name="spin" type="revolute"><parent link="beam"/><child link="puck"/><origin xyz="0.5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="puck"><collision><geometry><mesh filename="puck.obj"/></geometry></collision></link>
</robot>"#,
    )
    .unwrap();
}

/// A turntable arm (a revolute joint about z) carrying the puck at the end of a beam (and
/// spinning it about its axis), loaded with and without envelopes.
fn puck_arm(exact_meshes: bool) -> Arm {
    let dir = std::env::temp_dir().join(format!(
        "viaroad-puck-arm-{}-{exact_meshes}",
        std::process::id()
    ));
    write_puck_arm(&dir);
    let arm = Arm::load(
        &dir.join("puck.urdf"),
        None,
        &ArmOptions {
            group: GroupChoice::Joints(vec!["turn".into()]),
            exact_meshes,
        },
    )
    .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    arm
}

#[test]
fn a_big_mesh_is_planned_against_a_small_polytope_that_contains_it() {
    let arm = puck_arm(false);
    let puck = arm
        .shapes
        .iter()
        .find(|s| s.envelope_gap.is_some())
        .unwrap();
    let viaroad::robot::arm::ShapeSource::Mesh { mesh, .. } = &puck.source else {
        panic!("the puck is a mesh")
    };
    assert!(mesh.triangles.len() > ENVELOPE_ABOVE);
    assert!(
        puck.polytope.triangles.len() < 1_000,
        "{}",
        puck.polytope.triangles.len()
    );
    // every vertex of the mesh inside every face plane of the polytope
    for i in 0..puck.polytope.triangles.len() {
        let [a, b, c] = puck.polytope.triangle(i);
        let n = (b - a).cross(&(c - a));
        for p in &mesh.vertices {
            assert!(n.dot(&(p - a)) <= 1e-12, "vertex {p} outside face {i}");
        }
    }
    // a puck of radius 0.06: the polytope stands off it by millimetres
    let gap = puck.envelope_gap.unwrap();
    assert!(gap > 0.0 && gap < 0.01, "{gap}");
    // the small links and an exact-meshes load are left as they are
    assert!(
        arm.shapes
            .iter()
            .filter(|s| s.envelope_gap.is_some())
            .count()
            == 1
    );
    assert!(puck_arm(true)
        .shapes
        .iter()
        .all(|s| s.envelope_gap.is_none()));
}

#[test]
fn the_envelope_only_adds_collision() {
    let enveloped = puck_arm(false);
    let exact = puck_arm(true);
    let post = |id: &str, at: [f64; 3], size: [f64; 3]| {
        let at = nalgebra::Isometry3::translation(at[0], at[1], at[2]);
        CollisionObject::in_world(
            id,
            vec![(at, ObjectShape::Primitive(Primitive::Box { size }))],
        )
    };
    // posts about the puck's circle (0.44–0.56 from the joint; the beam reaches 0.41), some
    // grazing its rim
    let objects: Vec<CollisionObject> = (0..6)
        .map(|i| {
            let a = 1.0 * i as f64 - 2.5;
            let r = 0.6 + 0.02 * (i as f64 - 2.5);
            post(
                &format!("post{i}"),
                [r * a.cos(), r * a.sin(), 0.1],
                [0.05, 0.05, 0.3],
            )
        })
        .collect();
    let checker = ArmChecker::new(&exact, &objects).unwrap();
    let around = ArmOracle::new(&enveloped, &objects).unwrap();
    let inside = ArmOracle::new(&exact, &objects).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut partial, mut hits) = (0, 0);
    let (mut blocked_around, mut blocked_inside) = (0.0, 0.0);
    for _ in 0..60 {
        let q = [rng.random_range(-3.0..=3.0)];
        let delta = rng.random_range(-3.0..=3.0) - q[0];
        let c = &mut CallCounts::default();
        let a = around.joint_move(&q, 0, delta, c).unwrap();
        let e = inside.joint_move(&q, 0, delta, c).unwrap();
        if !e.is_empty() && e.as_slice() != [viaroad::interval::Interval::UNIT] {
            partial += 1;
        }
        let covered = |t: f64, ivs: &viaroad::interval::IntervalList| {
            ivs.iter().any(|iv| iv.lo - 1e-9 <= t && t <= iv.hi + 1e-9)
        };
        for k in 0..=400 {
            let t = k as f64 / 400.0;
            let qt = [q[0] + t * delta];
            if !checker.is_valid(&qt) {
                hits += 1;
                assert!(
                    covered(t, &e),
                    "the exact oracle misses t = {t} from {q:?} by {delta}"
                );
                assert!(
                    covered(t, &a),
                    "the envelope misses t = {t} from {q:?} by {delta}"
                );
            }
            if covered(t, &e) && !covered(t, &a) {
                panic!("the envelope frees t = {t} the mesh blocks, from {q:?} by {delta}");
            }
        }
        // every interval of the mesh inside one of the envelope's
        for iv in e.iter() {
            assert!(
                a.iter()
                    .any(|w| w.lo - 1e-9 <= iv.lo && iv.hi <= w.hi + 1e-9),
                "{iv:?} outside {a:?}, from {q:?} by {delta}"
            );
        }
        let measure = |ivs: &viaroad::interval::IntervalList| -> f64 {
            ivs.iter().map(|iv| iv.hi - iv.lo).sum::<f64>() * delta.abs()
        };
        blocked_around += measure(&a);
        blocked_inside += measure(&e);
    }
    // the test means something: collisions found, and the envelope is not the mesh (it
    // blocks a little more of the turns, in radians)
    assert!(hits > 100, "{hits}");
    assert!(
        blocked_around > blocked_inside,
        "{blocked_around} vs {blocked_inside}"
    );
    assert!(partial > 10, "{partial}");
}

#[test]
fn small_or_hollow_meshes_keep_their_triangles() {
    let tri = |v: Vec<[f64; 3]>, t: Vec<[u32; 3]>| {
        viaroad::geometry::TriMesh::new(v.into_iter().map(nalgebra::Point3::from).collect(), t)
            .unwrap()
    };
    // a small mesh: below the threshold
    let small = tri(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    );
    assert!(envelope(&small).is_none());
    // a sheet of many triangles, and a U of two such sheets a unit apart: any polytope around
    // the U stands off it by far more than a quarter of its radius
    let n = 50u32;
    let mut v = Vec::new();
    let mut t = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            v.push([i as f64 / n as f64, j as f64 / n as f64, 0.0]);
        }
    }
    for i in 0..n {
        for j in 0..n {
            let k = i * (n + 1) + j;
            t.push([k, k + 1, k + n + 2]);
            t.push([k, k + n + 2, k + n + 1]);
        }
    }
    assert!(t.len() > ENVELOPE_ABOVE);
    let m = v.len() as u32;
    let mut walls = v.clone();
    walls.extend(v.iter().map(|p| [p[0], p[1], 1.0]));
    let mut faces = t.clone();
    faces.extend(t.iter().map(|f| [f[0] + m, f[2] + m, f[1] + m]));
    let u = tri(walls, faces);
    assert!(envelope(&u).is_none());
    let (lo, hi) = u.aabb();
    assert!(0.5 > ENVELOPE_GAP * (hi - lo).norm() / 2.0);
}

#[test]
fn an_arm_scene_chooses_with_exact_meshes() {
    let dir = std::env::temp_dir().join(format!("viaroad-puck-scene-{}", std::process::id()));
    write_puck_arm(&dir);
    let gaps = |exact: Option<bool>| {
        let line = exact.map_or(String::new(), |e| format!("exact_meshes = {e}\n"));
        let toml = format!(
            "[space]\nkind = \"arm\"\n[robot]\nurdf = \"puck.urdf\"\ngroup = [\"turn\", \"spin\"]\n{line}\
             [[query]]\nstart = [0.0, 0.0]\ngoal = [1.0, 0.0]\n"
        );
        let path = dir.join("puck.toml");
        std::fs::write(&path, toml).unwrap();
        let scene = viaroad::scene::Scene::load(&path).unwrap();
        let viaroad::scene::Robot::Arm(a) = &scene.robot else {
            panic!("an arm scene")
        };
        a.arm
            .shapes
            .iter()
            .filter(|s| s.envelope_gap.is_some())
            .count()
    };
    assert_eq!(gaps(None), 1);
    assert_eq!(gaps(Some(false)), 1);
    assert_eq!(gaps(Some(true)), 0);
    std::fs::remove_dir_all(&dir).ok();
}
