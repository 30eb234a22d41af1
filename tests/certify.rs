//! `certify`: hand-made paths that graze an obstacle by 1e-6 are flagged, paths that pass it by
//! 1e-6 are proved free (exact single-group segments and conservative advancement alike),
//! witnesses collide under the independent checkers, repaired paths pass them, and the
//! command's exit codes say free (0), collides (3), undecided (4).

use crate::common;

use common::cli::{temp_dir, viaroad, write};
use common::rigid2d::PlanarChecker;
use nalgebra::Point2;
use viaroad::certify::{certify, repair, Certifier, MotionModel, RepairOptions, Status, Verdict};
use viaroad::deadline::Deadline;
use viaroad::geometry::Polygon;
use viaroad::robot::ArmChecker;
use viaroad::scene::{Obstacle, Robot, Scene};
use viaroad::space::Space;

/// A point in the unit square with one disc of radius 0.1 at (0.5, 0.5).
fn disc_scene() -> Scene {
    Scene {
        name: "one disc".into(),
        space: Space::euclidean(vec![0.0; 2], vec![1.0; 2]).unwrap(),
        robot: Robot::Point,
        obstacles: vec![Obstacle::Disc {
            centre: vec![0.5, 0.5],
            radius: 0.1,
        }],
        queries: Vec::new(),
        source: None,
        warnings: Vec::new(),
    }
}

fn verdicts(scene: &Scene, path: &[Vec<f64>]) -> Vec<Verdict> {
    certify(scene, path, MotionModel::Interpolate, &Deadline::none())
        .unwrap()
        .segments
}

#[test]
fn a_point_grazing_a_disc_by_1e_6_collides_and_one_passing_by_1e_6_is_free() {
    let scene = disc_scene();
    let y = 0.6;
    let graze = [vec![0.2, y - 1e-6], vec![0.8, y - 1e-6]];
    let v = verdicts(&scene, &graze);
    let Verdict::Collides(c) = &v[0] else {
        panic!("{v:?}")
    };
    assert!(c.exact);
    // the witness lies in the disc, by the plain distance
    let d = ((c.witness[0] - 0.5).powi(2) + (c.witness[1] - 0.5).powi(2)).sqrt();
    assert!(d <= 0.1, "witness {d} from the centre");
    assert!(c.intervals[0][0] > 0.49 && c.intervals[0][1] < 0.51);
    let pass = [vec![0.2, y + 1e-6], vec![0.8, y + 1e-6]];
    assert_eq!(verdicts(&scene, &pass), vec![Verdict::Free]);
}

/// A square of half-size `h` centred on the origin of its frame, among one wall above whose
/// lower side is at `wall`.
fn square_under_wall(h: f64, wall: f64) -> Scene {
    Scene {
        name: "square under a wall".into(),
        space: Space::se2([-2.0, -2.0], [2.0, 2.0], 1.0).unwrap(),
        robot: Robot::Polygons(vec![Polygon::rectangle([0.0, 0.0], [h, h]).unwrap()]),
        obstacles: vec![Obstacle::Polygon(
            Polygon::new(vec![
                Point2::new(-2.0, wall),
                Point2::new(2.0, wall),
                Point2::new(2.0, wall + 0.5),
                Point2::new(-2.0, wall + 0.5),
            ])
            .unwrap(),
        )],
        queries: Vec::new(),
        source: None,
        warnings: Vec::new(),
    }
}

/// Translating and turning at once (OMPL's SE(2) interpolation): the square turns by a
/// quarter while it slides under the wall; half-way, turned by 45°, its corner reaches
/// `h·√2`. Conservative advancement proves a pass 1e-6 below the wall and flags one 1e-6 into
/// it.
#[test]
fn a_square_turning_and_sliding_under_a_wall_by_1e_6_is_free_and_into_it_collides() {
    let h = 0.1;
    let top = h * std::f64::consts::SQRT_2;
    let path = [
        vec![-1.0, 0.0, 0.0],
        vec![1.0, 0.0, std::f64::consts::FRAC_PI_2],
    ];
    let free = square_under_wall(h, top + 1e-6);
    assert_eq!(verdicts(&free, &path), vec![Verdict::Free]);
    // the independent checker accepts the same motion split into a slide and a turn each way
    // only; it agrees at the waypoints and at the tightest moment
    let checker = PlanarChecker::se2(&free);
    checker
        .certify_path(&[vec![0.0, 0.0, std::f64::consts::FRAC_PI_4]])
        .unwrap();
    let grazed = square_under_wall(h, top - 1e-6);
    let v = verdicts(&grazed, &path);
    let Verdict::Collides(c) = &v[0] else {
        panic!("{v:?}")
    };
    assert!(!c.exact && c.intervals.iter().any(|[a, b]| *a <= 0.5 && *b >= 0.5));
    assert!(PlanarChecker::se2(&grazed)
        .certify_path(std::slice::from_ref(&c.witness))
        .is_err());
}

#[test]
fn a_blocked_disc_path_is_repaired_and_the_repair_passes_the_plain_distance_check() {
    let scene = disc_scene();
    let path = vec![
        vec![0.1, 0.5],
        vec![0.3, 0.5],
        vec![0.7, 0.5],
        vec![0.9, 0.5],
    ];
    let c = Certifier::new(&scene, MotionModel::Interpolate).unwrap();
    let cert = c.certify(&path, &Deadline::none()).unwrap();
    assert_eq!(cert.status(), Status::Collides);
    let fixed = repair(
        &c,
        &path,
        &cert,
        &RepairOptions::default(),
        &Deadline::none(),
    )
    .unwrap();
    assert!(fixed.report.certified, "{:?}", fixed.report);
    assert_eq!(fixed.path.first(), path.first());
    assert_eq!(fixed.path.last(), path.last());
    common::check_disc_path(
        &fixed.path,
        &[vec![0.5, 0.5]],
        &[0.1],
        &[0.0, 0.0],
        &[1.0, 1.0],
        0.0,
    )
    .unwrap();
}

/// The Panda's box problem: the straight start → goal motion, its witness (if it collides)
/// confirmed by the independent arm checker, its repair accepted by it.
#[test]
fn an_arm_straight_motion_is_located_and_repaired_under_the_independent_checker() {
    let scene = Scene::load(&common::arms::arms_dir().join("panda-box-1.toml")).unwrap();
    let q = scene.checked_queries().unwrap()[0].clone();
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm")
    };
    let checker = ArmChecker::new(&a.arm, &a.objects).unwrap();
    let mid: Vec<f64> = q
        .start
        .iter()
        .zip(&q.goal)
        .map(|(s, g)| 0.5 * (s + g) + 0.6)
        .collect();
    let path = vec![q.start.clone(), mid, q.goal.clone()];
    let c = Certifier::new(&scene, MotionModel::Interpolate).unwrap();
    let cert = c.certify(&path, &Deadline::none()).unwrap();
    for v in &cert.segments {
        if let Verdict::Collides(col) = v {
            assert!(!checker.collisions(&col.witness).is_empty());
        }
    }
    if cert.status() == Status::Free {
        let step = 0.001 * checker.arm().group.max_extent();
        assert!(checker.check_path(&path, step).unwrap().valid);
        return;
    }
    let fixed = repair(
        &c,
        &path,
        &cert,
        &RepairOptions::default(),
        &Deadline::none(),
    )
    .unwrap();
    assert!(fixed.report.certified, "{:?}", fixed.report);
    common::arms::certify(&scene, &fixed.path);
}

#[test]
fn the_command_exits_0_when_free_3_when_colliding_4_when_undecided() {
    let dir = temp_dir("certify", "exit");
    let scene = write(
        &dir,
        "s.toml",
        "name = \"d\"\n[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n\
         [[obstacle]]\ndisc = { center = [0.5, 0.5], radius = 0.1 }\n",
    );
    let free = write(&dir, "free.path", "0.1 0.9\n0.9 0.9\n");
    let hit = write(&dir, "hit.path", "0.1 0.5\n0.9 0.5\n");
    let code = |args: &[&str]| viaroad(args).status.code();
    assert_eq!(code(&["certify", &scene, &free]), Some(0));
    assert_eq!(code(&["certify", &scene, &hit]), Some(3));
    assert_eq!(code(&["certify", &scene, &free, "--time", "0"]), Some(4));
    let fixed = dir.join("fixed.path");
    let o = viaroad(&[
        "certify",
        &scene,
        &hit,
        "--repair",
        "-o",
        &fixed.to_string_lossy(),
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", common::cli::stderr(&o));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["status"], "collides");
    assert_eq!(report["repair"]["report"]["certified"], true);
    assert_eq!(
        code(&["certify", &scene, &fixed.to_string_lossy()]),
        Some(0)
    );
}

/// A two-joint toy arm turning in the plane z = 0.2 (a beam of 0.6 m, a tip of 0.3 m 5 cm past
/// its joint, clear of the beam for turns below 1.1 rad) beside a ball of radius 0.2 whose
/// lowest point along −y lies `gap` above the beam's side at `[0, 0]`. The oracle's polytope for the ball stands about 8 mm off it there (one of its
/// vertices points at the beam), so the oracle refuses `[0, 0]` for any gap below that: the
/// Fetch's head (a sphere of 0.2 m) and its MotionBenchMaker goals 0.2–3 mm below it.
fn toy_arm_under_a_ball(gap: f64) -> (Scene, common::cli::TempDir) {
    let dir = temp_dir("certify", &format!("ball-{gap:e}"));
    write(
        &dir,
        "toy.urdf",
        r#"<robot name="toy">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="beam"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="beam"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.6 0.05 0.05"/></geometry></collision></link>
  <joint name="j2" type="revolute"><parent link="beam"/><child link="tip"/>
    <origin xyz="0.6 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="tip"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.3 0.05 0.05"/></geometry></collision></link>
</robot>"#,
    );
    write(
        &dir,
        "scene.yaml",
        &format!(
            "world:\n  collision_objects:\n    - id: ball\n      header: {{frame_id: world}}\n      \
             primitives: [{{type: sphere, dimensions: [0.2]}}]\n      \
             primitive_poses: [{{position: [0.3, {}, 0.2], orientation: [0, 0, 0, 1]}}]\n",
            0.025 + 0.2 + gap
        ),
    );
    let toml = write(
        &dir,
        "toy.toml",
        "name = \"toy under a ball\"\n[space]\nkind = \"arm\"\n[robot]\nurdf = \"toy.urdf\"\n\
         group = [\"j1\", \"j2\"]\n[environment]\nmoveit_scene = \"scene.yaml\"\n\
         [[query]]\nstart = [-1.0, 0.5]\ngoal = [0.0, 0.0]\n",
    );
    (Scene::load(std::path::Path::new(&toml)).unwrap(), dir)
}

/// Where only the oracle's enclosing polytope meets a curved shape, the segment is proved on
/// the true shapes: 1e-6 below the ball is free (one joint and two joints moving), 1e-6 into
/// it collides with a witness the checker confirms.
#[test]
fn an_arm_ending_1e_6_below_a_ball_is_free_though_the_oracle_s_polytope_meets_it() {
    use viaroad::oracle::{CallCounts, CountedOracle};
    for gap in [1e-6, -1e-6] {
        let (scene, _dir) = toy_arm_under_a_ball(gap);
        let goal = vec![0.0, 0.0];
        let oracle_free = scene.oracle().is_free(&goal, &mut CallCounts::default());
        assert!(!oracle_free, "the polytope should meet the beam at {gap}");
        let Robot::Arm(a) = &scene.robot else {
            panic!("not an arm")
        };
        let checker = ArmChecker::new(&a.arm, &a.objects).unwrap();
        for start in [vec![-1.0, 0.0], vec![-1.0, 0.3]] {
            let v = verdicts(&scene, &[start.clone(), goal.clone()]);
            if gap > 0.0 {
                assert_eq!(v, vec![Verdict::Free], "{start:?}");
            } else {
                let Verdict::Collides(c) = &v[0] else {
                    panic!("{start:?}: {v:?}")
                };
                assert!(!checker.collisions(&c.witness).is_empty());
            }
        }
    }
}

/// A path through the ball to a goal 1 mm below it, which the oracle refuses: the repair ends
/// its detour at a free neighbour of the goal and joins the goal by a segment proved on the
/// true shapes; the fixed path passes the independent checker.
#[test]
fn a_repair_reaches_a_goal_that_only_the_oracle_s_polytope_refuses() {
    let (scene, _dir) = toy_arm_under_a_ball(1e-3);
    let path = vec![vec![-1.0, 0.5], vec![0.6, 0.0], vec![0.0, 0.0]];
    let c = Certifier::new(&scene, MotionModel::Interpolate).unwrap();
    let cert = c.certify(&path, &Deadline::none()).unwrap();
    assert_eq!(cert.status(), Status::Collides);
    let fixed = repair(
        &c,
        &path,
        &cert,
        &RepairOptions::default(),
        &Deadline::none(),
    )
    .unwrap();
    assert!(fixed.report.certified, "{:?}", fixed.report);
    assert_eq!(fixed.certificate.status(), Status::Free);
    assert_eq!(fixed.path.first(), path.first());
    assert_eq!(fixed.path.last(), path.last());
    // the scene's own query check asks the oracle, which refuses the goal: the independent
    // checker alone, at 1/10 of OMPL's default resolution
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm")
    };
    let checker = ArmChecker::new(&a.arm, &a.objects).unwrap();
    let step = 0.001 * checker.arm().group.max_extent();
    let report = checker.check_path(&fixed.path, step).unwrap();
    assert!(report.valid, "{report:?}");
}
