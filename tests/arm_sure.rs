//! The arm oracle's sure collision test (`robot::inner`): balls inside each link against the
//! obstacles' true shapes. It may only ever say "collides" where the exact test does, so it
//! changes no verdict, only the work; checked here against the exact oracle with the test off
//! and against the independent checker (parry, the true shapes), which shares no code with it.

use parry3d_f64::math::{Isometry, Point};
use parry3d_f64::query::{intersection_test, PointQuery};
use parry3d_f64::shape::{Ball, Cuboid, Cylinder, TriMesh, TriMeshFlags};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use viaroad::oracle::CallCounts;
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::inner::Solid;
use viaroad::robot::{Arm, ArmChecker, ArmOracle, Primitive};
use viaroad::scene::moveit::load_planning_scene;

use crate::common;
use common::arms::arms_dir;

fn panda() -> Arm {
    common::arms::panda(GroupChoice::FirstSrdfGroup)
}

/// Every inner ball lies inside its link's mesh, by parry's solid point test and distance:
/// the centre inside, the surface no nearer than the radius; every closed mesh has some.
#[test]
fn inner_balls_lie_inside_their_link_meshes() {
    let arm = panda();
    let mut balls = 0;
    for shape in &arm.shapes {
        let m = &shape.polytope;
        let mesh = TriMesh::with_flags(
            m.vertices
                .iter()
                .map(|v| Point::new(v.x, v.y, v.z))
                .collect(),
            m.triangles.clone(),
            TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES,
        )
        .unwrap();
        // an open mesh bounds no solid: no ball can be shown inside it (the Panda's link 6)
        assert_eq!(
            shape.inner.is_empty(),
            !m.is_closed(),
            "link {}: {} balls, closed {}",
            arm.model.urdf.links[shape.link].name,
            shape.inner.len(),
            m.is_closed()
        );
        for b in &shape.inner {
            let c = Point::new(b.centre.x, b.centre.y, b.centre.z);
            assert!(
                mesh.contains_local_point(&c),
                "{b:?} has its centre outside"
            );
            let d = mesh.distance_to_local_point(&c, false);
            assert!(
                d >= b.radius,
                "{b:?} reaches {} beyond the surface",
                b.radius - d
            );
            balls += 1;
        }
    }
    assert!(balls >= 2 * arm.shapes.len(), "only {balls} balls");
    let open = arm.shapes.iter().filter(|s| s.inner.is_empty()).count();
    assert_eq!(open, 1, "the Panda has one open link mesh (link 6)");
}

/// `Solid::meets` against parry's intersection test of the ball with the true shape, at random
/// points around a box, a cylinder and a sphere placed off the origin.
#[test]
fn a_solid_is_met_exactly_where_parry_finds_the_ball_touching_the_true_shape() {
    let pose = nalgebra::Isometry3::new(
        nalgebra::Vector3::new(0.3, -0.2, 0.5),
        nalgebra::Vector3::new(0.4, -0.7, 0.2),
    );
    let shapes: [(Primitive, Box<dyn parry3d_f64::shape::Shape>); 3] = [
        (
            Primitive::Box {
                size: [0.4, 0.2, 0.6],
            },
            Box::new(Cuboid::new(nalgebra::Vector3::new(0.2, 0.1, 0.3))),
        ),
        (
            // parry's cylinder stands along y, the primitive along z
            Primitive::Cylinder {
                radius: 0.15,
                length: 0.5,
            },
            Box::new(Cylinder::new(0.25, 0.15)),
        ),
        (Primitive::Sphere { radius: 0.2 }, Box::new(Ball::new(0.2))),
    ];
    let to_parry_axis =
        nalgebra::Isometry3::rotation(nalgebra::Vector3::x() * std::f64::consts::FRAC_PI_2);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut met, mut missed) = (0, 0);
    for (k, (primitive, parry)) in shapes.iter().enumerate() {
        let solid = Solid::of(primitive, &pose).unwrap();
        let at: Isometry<f64> = if k == 1 { pose * to_parry_axis } else { pose };
        for _ in 0..4000 {
            let c = pose
                * nalgebra::Point3::new(
                    rng.random_range(-0.6..0.6),
                    rng.random_range(-0.6..0.6),
                    rng.random_range(-0.6..0.6),
                );
            let r = rng.random_range(0.01..0.2);
            let ball = Isometry::translation(c.x, c.y, c.z);
            let touching = intersection_test(&ball, &Ball::new(r), &at, parry.as_ref()).unwrap();
            let says = solid.meets(&c, r);
            // the two may differ only within rounding of the boundary
            if says != touching {
                let d = parry.distance_to_point(&at, &c, true);
                assert!(
                    (d - r).abs() < 1e-9,
                    "{primitive:?}: {says} at distance {d}, radius {r}"
                );
            }
            if says {
                met += 1;
            } else {
                missed += 1;
            }
        }
    }
    assert!(met > 1000 && missed > 1000, "{met} met, {missed} missed");
}

/// At random configurations in three shipped scenes the sure test never reports a collision
/// that the exact test (sure test off) or the independent checker does not find, the exact
/// verdicts are the same with it on or off, and it does find most collisions.
#[test]
fn the_sure_test_changes_no_verdict_and_finds_most_collisions() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut colliding, mut sure) = (0, 0);
    for scene in ["box", "bookshelf_thin", "cage"] {
        let mut arm = panda();
        let s =
            load_planning_scene(&arms_dir().join(format!("mbm/{scene}/scene0001.yaml"))).unwrap();
        s.apply_to(&mut arm).unwrap();
        let checker = ArmChecker::new(&arm, &s.objects).unwrap();
        let oracle = ArmOracle::new(&arm, &s.objects).unwrap();
        let exact = ArmOracle::new(&arm, &s.objects)
            .unwrap()
            .with_sure_test(false);
        let g = &arm.group;
        for _ in 0..1500 {
            let q: Vec<f64> = (0..g.dof())
                .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
                .collect();
            let hit = exact.collides(&q, &mut CallCounts::default()).unwrap();
            assert_eq!(
                oracle.collides(&q, &mut CallCounts::default()).unwrap(),
                hit,
                "{scene}: the verdict changed at {q:?}"
            );
            let surely = oracle.surely_collides(&q);
            assert!(!exact.surely_collides(&q), "switched off, it still answers");
            if surely {
                assert!(
                    hit,
                    "{scene}: sure of a collision the exact test does not find at {q:?}"
                );
                assert!(
                    !checker.is_valid(&q),
                    "{scene}: sure of a collision the checker does not find at {q:?}"
                );
            }
            colliding += usize::from(hit);
            sure += usize::from(surely);
        }
    }
    // measured: 69 % of the colliding configurations in the box (the states bench)
    assert!(
        sure * 2 > colliding,
        "the sure test found {sure} of {colliding} collisions"
    );
}

/// Single-joint moves from random free configurations in two shipped scenes: the yes/no
/// answer (`joint_move_free`, which asks the sure test at a few moments of the move before the
/// exact sweep) is the same with the sure test on and off, agrees with the exact intervals
/// (`joint_move`), and a move it refuses collides for the independent checker somewhere
/// along it (sampled finely, the same moments the sure test looks at included).
#[test]
fn the_sure_test_along_a_joint_move_changes_no_verdict() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let (mut blocked, mut asked) = (0, 0);
    for scene in ["box", "cage"] {
        let mut arm = panda();
        let s =
            load_planning_scene(&arms_dir().join(format!("mbm/{scene}/scene0001.yaml"))).unwrap();
        s.apply_to(&mut arm).unwrap();
        let checker = ArmChecker::new(&arm, &s.objects).unwrap();
        let oracle = ArmOracle::new(&arm, &s.objects).unwrap();
        let exact = ArmOracle::new(&arm, &s.objects)
            .unwrap()
            .with_sure_test(false);
        let g = &arm.group;
        while asked < 300 {
            let q: Vec<f64> = (0..g.dof())
                .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
                .collect();
            if exact.collides(&q, &mut CallCounts::default()).unwrap() {
                continue;
            }
            let joint = rng.random_range(0..g.dof());
            let to = rng.random_range(g.lower[joint]..=g.upper[joint]);
            let delta = (to - q[joint]) * rng.random_range(0.05..=1.0);
            let c = &mut CallCounts::default();
            let free = oracle.joint_move_free(&q, joint, delta, c).unwrap();
            assert_eq!(
                free,
                exact.joint_move_free(&q, joint, delta, c).unwrap(),
                "{scene}: the verdict changed for joint {joint} by {delta} from {q:?}"
            );
            assert_eq!(
                free,
                oracle.joint_move(&q, joint, delta, c).unwrap().is_empty()
            );
            if !free {
                let hits = (0..=256).any(|i| {
                    let mut p = q.clone();
                    p[joint] += delta * i as f64 / 256.0;
                    !checker.is_valid(&p)
                });
                // the exact oracle's polytopes contain the true shapes: a refusal the checker
                // does not see along the move is a grazing contact, never a sure one
                if !hits {
                    let mut p = q.clone();
                    p[joint] += delta;
                    assert!(
                        !oracle.surely_collides(&p),
                        "{scene}: sure but free at {p:?}"
                    );
                }
                blocked += 1;
            }
            asked += 1;
        }
        asked = 0;
    }
    assert!(
        blocked > 50,
        "only {blocked} blocked moves: the test asks too little"
    );
}
