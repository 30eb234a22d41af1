//! MoveIt's rules for what a PlanningScene and a MotionPlanRequest mean, where MotionBenchMaker's
//! Fetch and UR5 problems rely on them (found by running them): objects given in a
//! link's frame, joint states naming joints the URDF lacks, goals beyond a joint limit, and the
//! request's own planning group.

use nalgebra::Isometry3;
use std::path::{Path, PathBuf};
use viaroad::bench::mbm::{problem_scene, Problem};
use viaroad::oracle::CallCounts;
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::ArmChecker;
use viaroad::scene::arm::ArmRobot;
use viaroad::scene::moveit::{
    parse_motion_plan_request, parse_planning_scene, CollisionObject, START_BOUNDS_ERROR,
};
use viaroad::scene::Robot;

use crate::common;
use common::arms::panda;

/// The Panda's ready pose.
const HOME: [f64; 7] = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];

/// A scene with the robot's base one metre along x and one box of side 0.3 at `at`, given in
/// `frame`.
fn scene_with_box(frame: &str, at: [f64; 3]) -> String {
    format!(
        "robot_state:\n  multi_dof_joint_state:\n    transforms: [{{translation: [1, 0, 0], rotation: [0, 0, 0, 1]}}]\n\
         world:\n  collision_objects:\n    - id: crate\n      header: {{frame_id: {frame}}}\n      \
         primitives: [{{type: box, dimensions: [0.3, 0.3, 0.3]}}]\n      \
         primitive_poses: [{{position: [{}, {}, {}], orientation: [0, 0, 0, 1]}}]\n",
        at[0], at[1], at[2]
    )
}

fn robot_in(scene_yaml: &str) -> Result<ArmRobot, viaroad::robot::RobotError> {
    let scene = parse_planning_scene(scene_yaml, Path::new("s.yaml")).unwrap();
    let mut arm = panda(GroupChoice::Srdf("panda_arm".into()));
    scene.apply_to(&mut arm)?;
    ArmRobot::new(arm, scene.objects, PathBuf::new(), None, None)
}

#[test]
fn an_object_in_the_root_link_frame_moves_with_the_base() {
    // 0.5 m above the root link: through the arm standing at (1, 0, 0)
    let in_root = robot_in(&scene_with_box("panda_link0", [0.0, 0.0, 0.5])).unwrap();
    let in_world = robot_in(&scene_with_box("world", [1.0, 0.0, 0.5])).unwrap();
    let beside = robot_in(&scene_with_box("world", [0.0, 0.0, 0.5])).unwrap();
    // placed once, in the world: the same scene as the box given there
    assert_eq!(in_root.digest(), in_world.digest());
    assert_ne!(in_root.digest(), beside.digest());
    let placed = &in_root.objects[0].parts[0].0;
    assert_eq!(
        placed.translation.vector,
        nalgebra::Vector3::new(1.0, 0.0, 0.5)
    );
    // the exact oracle and the independent checker both meet it there, and not beside
    for (robot, hit) in [(&in_root, true), (&beside, false)] {
        let mut counts = CallCounts::default();
        assert_eq!(
            robot.arm_oracle().collides(&HOME, &mut counts).unwrap(),
            hit
        );
        let checker = ArmChecker::new(&robot.arm, &robot.objects).unwrap();
        let crate_hits = checker
            .collisions(&HOME)
            .iter()
            .filter(|c| c.b == "crate")
            .count();
        assert_eq!(crate_hits > 0, hit);
    }
    // the checker places an object in a frame as the oracle does, given it unplaced
    let scene = parse_planning_scene(
        &scene_with_box("panda_link0", [0.0, 0.0, 0.5]),
        Path::new("s.yaml"),
    )
    .unwrap();
    let checker = ArmChecker::new(&in_root.arm, &scene.objects).unwrap();
    assert!(checker.collisions(&HOME).iter().any(|c| c.b == "crate"));
}

#[test]
fn frames_the_robot_cannot_hold_still_are_refused() {
    let arm = panda(GroupChoice::Srdf("panda_arm".into()));
    assert_eq!(arm.frame_pose("world").unwrap(), Isometry3::identity());
    assert_eq!(arm.frame_pose("/world").unwrap(), Isometry3::identity());
    assert_eq!(arm.frame_pose("").unwrap(), Isometry3::identity());
    for (frame, says) in [
        (
            "panda_hand",
            "moves with the planning group's joint panda_joint7",
        ),
        (
            "panda_link3",
            "moves with the planning group's joint panda_joint3",
        ),
        (
            "base_footprint",
            "neither the world nor a link of the robot",
        ),
    ] {
        let e = robot_in(&scene_with_box(frame, [0.0; 3])).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("crate") && text.contains(says),
            "{frame}: {text}"
        );
        let scene =
            parse_planning_scene(&scene_with_box(frame, [0.0; 3]), Path::new("s.yaml")).unwrap();
        let o: &CollisionObject = &scene.objects[0];
        assert!(o.placed(&arm).is_err(), "{frame}");
        assert!(ArmChecker::new(&arm, &scene.objects).is_err(), "{frame}");
    }
}

/// A request of `start` and `goal` for the Panda's seven joints (`panda_joint1` …), the start
/// state naming a joint the Panda does not have too.
fn request(group: &str, start: [f64; 7], goal: [f64; 7]) -> String {
    let names: Vec<String> = (1..=7).map(|i| format!("panda_joint{i}")).collect();
    let goal: Vec<String> = names
        .iter()
        .zip(goal)
        .map(|(n, v)| format!("{{joint_name: {n}, position: {v}}}"))
        .collect();
    format!(
        "group_name: {group}\nstart_state:\n  joint_state: {{name: [l_wheel_joint, {}], position: [3, {}]}}\n\
         goal_constraints:\n  - joint_constraints: [{}]\n",
        names.join(", "),
        start.map(|v| v.to_string()).join(", "),
        goal.join(", ")
    )
}

#[test]
fn ends_follow_moveits_joint_limits_and_unknown_joints_are_skipped() {
    let mut arm = panda(GroupChoice::Srdf("panda_arm".into()));
    let (lo, hi) = (arm.group.lower.clone(), arm.group.upper.clone());
    let mut start = HOME;
    let mut goal = HOME;
    // joint 1's start just beyond its upper limit (moved onto it), joint 2's further than
    // MoveIt moves a start (left for the scene to refuse); goals beyond either limit, by any
    // amount, are taken at the limit
    start[0] = hi[0] + 0.5 * START_BOUNDS_ERROR;
    start[1] = lo[1] - 2.0 * START_BOUNDS_ERROR;
    goal[2] = hi[2] + 1e-6;
    goal[3] = lo[3] - 1.0;
    let req =
        parse_motion_plan_request(&request("panda_arm", start, goal), Path::new("r.yaml")).unwrap();
    let (s, g) = req.start_goal(&mut arm).unwrap();
    assert_eq!(s[0], hi[0]);
    assert_eq!(s[1], start[1]);
    assert!(!arm.group.in_bounds(&s));
    assert_eq!(&s[2..], &start[2..]);
    assert_eq!(g[2], hi[2]);
    assert_eq!(g[3], lo[3]);
    assert!(arm.group.in_bounds(&g));
    assert_eq!(g[..2], goal[..2]);
    // a joint state naming an unknown joint is still refused where nothing else explains it
    assert!(arm
        .set_joint_values(&["l_wheel_joint".to_string()], &[3.0])
        .is_err());
}

#[test]
fn a_problem_plans_for_its_requests_group() {
    let dir = std::env::temp_dir().join(format!("viaroad-arm-moveit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("scene0001.yaml");
    let req = dir.join("request0001.yaml");
    std::fs::write(&scene, scene_with_box("world", [0.0, 0.0, 0.5])).unwrap();
    let mut goal = HOME;
    goal[6] = 0.0;
    std::fs::write(&req, request("panda_arm", HOME, goal)).unwrap();
    // a robot loaded for the first six joints plans for the request's seven
    let six: Vec<String> = (1..=6).map(|i| format!("panda_joint{i}")).collect();
    let robot = panda(GroupChoice::Joints(six));
    let p = Problem {
        family: "f".into(),
        id: "0001".into(),
        scene,
        request: req.clone(),
    };
    let s = problem_scene(&robot, &p).unwrap();
    let Robot::Arm(a) = &s.robot else {
        panic!("an arm scene")
    };
    assert_eq!(a.arm.group.name, "panda_arm");
    assert_eq!(a.arm.group.dof(), 7);
    assert_eq!(s.queries[0].goal, goal.to_vec());
    // a group the SRDF does not have is an error, not the loaded group
    std::fs::write(&req, request("panda_legs", HOME, goal)).unwrap();
    let e = problem_scene(&robot, &p).unwrap_err().to_string();
    assert!(e.contains("panda_legs"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_arm_scene_warns_where_a_request_was_moved_onto_a_limit() {
    let dir = std::env::temp_dir().join(format!("viaroad-arm-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let hi = panda(GroupChoice::Srdf("panda_arm".into())).group.upper[6];
    let robot = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda");
    let mut goal = HOME;
    goal[6] = hi + 0.01;
    std::fs::write(dir.join("request.yaml"), request("panda_arm", HOME, goal)).unwrap();
    let toml = format!(
        "[space]\nkind = \"arm\"\n[robot]\nurdf = \"{}\"\nsrdf = \"{}\"\n\
         [[query]]\nmoveit_request = \"request.yaml\"\n",
        robot.join("panda.urdf").display(),
        robot.join("panda.srdf").display()
    );
    std::fs::write(dir.join("scene.toml"), toml).unwrap();
    let scene = viaroad::scene::Scene::load(&dir.join("scene.toml")).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(scene.queries[0].goal[6], hi);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("goal's panda_joint7") && w.contains("beyond its limit")),
        "{:?}",
        scene.warnings
    );
    // the group came from the request (the TOML names none)
    let Robot::Arm(a) = &scene.robot else {
        panic!("an arm scene")
    };
    assert_eq!(a.arm.group.name, "panda_arm");
}
