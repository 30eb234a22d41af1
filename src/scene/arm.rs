//! Arm scenes: a URDF robot's planning group among a MoveIt PlanningScene, as a
//! TOML scene of `[space] kind = "arm"`.
//!
//! ```toml
//! name = "panda-table-pick-1"          # optional
//! [space]
//! kind = "arm"                         # nothing else: the bounds are the joint limits
//! [robot]
//! urdf = "panda/panda.urdf"            # relative to this file; meshes relative to the URDF
//! srdf = "panda/panda.srdf"            # optional: groups, disable_collisions
//! group = ["panda_joint1", "panda_joint2"]   # joints in this order; or an SRDF group's name
//!                                      # (group = "panda_arm"); default: the first
//!                                      # moveit_request's group_name, else the SRDF's first
//! fixed = { panda_finger_joint1 = 0.04 }     # optional: joints outside the group
//! exact_meshes = false                 # optional: true plans against every mesh as it is,
//!                                      # not a big mesh's envelope (robot::shapes::envelope)
//! [environment]                        # optional (without it only self-collision counts)
//! moveit_scene = "mbm/table_pick/scene0001.yaml"
//! [[query]]
//! moveit_request = "mbm/table_pick/request0001.yaml"
//! [[query]]
//! start = [0, -0.785, 0, -2.356, 0, 1.571, 0.785]    # group order, one value per joint
//! goal  = [0.5, -0.5, 0, -2.0, 0, 1.571, 0.785]
//! ```
//!
//! Joints outside the group take, in this order, the scene's `robot_state`, the start state
//! of every `moveit_request` (MoveIt's rule: the request's start state wins), then `fixed`;
//! a MoveIt state may name joints the URDF lacks (skipped,
//! [`crate::scene::moveit::JointState::set_known`]), and a request's ends are moved onto joint
//! limits as MoveIt moves them ([`crate::scene::moveit::MotionPlanRequest::ends`]; the scene
//! warns where it did). Collision objects may be given in the world or in a link the group does
//! not move ([`crate::robot::Arm::frame_pose`]).
//! The environment's curved primitives become circumscribed polytopes
//! ([`crate::robot::Primitive::polytope`]), so a path certified against them is certified
//! against the true shapes.
//!
//! The oracle ([`ArmCollision`]) answers a motion of one joint exactly with
//! [`ArmOracle::joint_move`] (the distal part turns about the joint's fixed axis, CHS §2.3.2;
//! the proximal links are static obstacles), a configuration with [`ArmOracle::collides`];
//! motions of several joints at once are not straight in any sense the oracle knows, so it
//! refuses them ([`OracleError::Unsupported`]): the via-point planner moves one joint per
//! segment (CHS §1.5).
//!
//! [`ArmOracle::joint_move`]: crate::robot::ArmOracle::joint_move
//! [`ArmOracle::collides`]: crate::robot::ArmOracle::collides
//! [`OracleError::Unsupported`]: crate::oracle::OracleError::Unsupported

pub use super::arm_robot::{ArmCollision, ArmRobot};

use super::checks::{check_queries_on_load, default_name};
use super::error::SceneError;
use super::moveit::{load_motion_plan_request, load_planning_scene};
use super::types::{Query, Robot, Scene};
use crate::robot::arm::GroupChoice;
use crate::robot::urdf::JointKind;
use crate::robot::{Arm, ArmOptions, RobotError};
use crate::space::Space;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: Option<String>,
    #[serde(rename = "space")]
    _space: SpaceSpec,
    robot: RobotSpec,
    environment: Option<EnvironmentSpec>,
    #[serde(default, rename = "query")]
    queries: Vec<QuerySpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpaceSpec {
    #[serde(rename = "kind")]
    _kind: String,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum GroupSpec {
    Name(String),
    Joints(Vec<String>),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotSpec {
    urdf: String,
    srdf: Option<String>,
    group: Option<GroupSpec>,
    #[serde(default)]
    fixed: BTreeMap<String, f64>,
    #[serde(default)]
    exact_meshes: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EnvironmentSpec {
    moveit_scene: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QuerySpec {
    moveit_request: Option<String>,
    start: Option<Vec<f64>>,
    goal: Option<Vec<f64>>,
}

/// Whether a parsed TOML document is an arm scene (`[space] kind = "arm"`).
pub(crate) fn is_arm_scene(text: &str) -> bool {
    let Ok(v) = text.parse::<toml::Table>() else {
        return false;
    };
    v.get("space")
        .and_then(|s| s.get("kind"))
        .and_then(|k| k.as_str())
        == Some("arm")
}

/// Reads an arm scene from TOML text; `path` names the file and anchors relative paths.
pub(crate) fn from_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
    let file: File = toml::from_str(text).map_err(|e| SceneError::Parse {
        path: path.to_path_buf(),
        message: e.to_string().trim_end().replace('\n', " "),
    })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let invalid = |message: String| SceneError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    let robot_err = |e: RobotError| match e {
        RobotError::Input(e) => e.into(),
        other => invalid(other.to_string()),
    };
    let urdf = dir.join(&file.robot.urdf);
    let srdf = file.robot.srdf.as_ref().map(|s| dir.join(s));
    // without a group of its own, the scene plans for its first MoveIt request's group (as
    // MoveIt would), else for the SRDF's first group
    let request_group = || -> Result<Option<String>, SceneError> {
        let Some(r) = file.queries.iter().find_map(|q| q.moveit_request.as_ref()) else {
            return Ok(None);
        };
        let group = load_motion_plan_request(&dir.join(r))?.group;
        Ok((!group.is_empty()).then_some(group))
    };
    let group = match &file.robot.group {
        None => match request_group()? {
            Some(g) => GroupChoice::Srdf(g),
            None => GroupChoice::FirstSrdfGroup,
        },
        Some(GroupSpec::Name(n)) => GroupChoice::Srdf(n.clone()),
        Some(GroupSpec::Joints(j)) => GroupChoice::Joints(j.clone()),
    };
    // the environment is read (and its limits checked) before the robot's meshes are
    let moveit_scene = file
        .environment
        .as_ref()
        .and_then(|e| e.moveit_scene.as_ref())
        .map(|s| dir.join(s));
    let planning_scene = moveit_scene
        .as_deref()
        .map(load_planning_scene)
        .transpose()?;
    let mut arm = Arm::load(
        &urdf,
        srdf.as_deref(),
        &ArmOptions {
            group,
            exact_meshes: file.robot.exact_meshes,
        },
    )
    .map_err(robot_err)?;
    let mut warnings = std::mem::take(&mut arm.warnings);
    let objects = match planning_scene {
        Some(ps) => {
            ps.apply_to(&mut arm).map_err(robot_err)?;
            ps.objects
        }
        None => Vec::new(),
    };
    let mut queries = Vec::new();
    let mut first_values: Option<Vec<f64>> = None;
    for (i, q) in file.queries.iter().enumerate() {
        let what = format!("query {}", i + 1);
        match (&q.moveit_request, &q.start, &q.goal) {
            (Some(r), None, None) => {
                let req = load_motion_plan_request(&dir.join(r))?;
                let (start, goal) = req
                    .start_goal(&mut arm)
                    .map_err(|e| invalid(format!("{what} ({r}): {e}")))?;
                for note in req.moved_onto_limits(&arm) {
                    warnings.push(format!("{what} ({r}): {note}"));
                }
                match &first_values {
                    None => first_values = Some(arm.values.clone()),
                    Some(v) if *v != arm.values => warnings.push(format!(
                        "{what} ({r}): its start state sets the joints outside the group \
                         differently from the first request's; the last one given applies"
                    )),
                    Some(_) => {}
                }
                queries.push(Query { start, goal });
            }
            (None, Some(start), Some(goal)) => queries.push(Query {
                start: start.clone(),
                goal: goal.clone(),
            }),
            _ => {
                return Err(invalid(format!(
                    "{what}: give either moveit_request or both start and goal"
                )))
            }
        }
    }
    if !file.robot.fixed.is_empty() {
        let (names, values): (Vec<String>, Vec<f64>) = file.robot.fixed.into_iter().unzip();
        for n in &names {
            if arm
                .model
                .joint(n)
                .is_some_and(|k| arm.group.joints.contains(&k))
            {
                return Err(invalid(format!(
                    "[robot] fixed names {n}, a joint of the planning group"
                )));
            }
        }
        arm.set_joint_values(&names, &values).map_err(robot_err)?;
    }
    let name = file.name.unwrap_or_else(|| default_name(path));
    let robot = ArmRobot::new(arm, objects, urdf, srdf, moveit_scene).map_err(robot_err)?;
    let mut scene = arm_scene(name, robot, queries, path)?;
    scene.warnings.extend(warnings);
    check_queries_on_load(&mut scene)?;
    Ok(scene)
}

/// A scene of `robot` with these queries (unchecked: [`Scene::checked_queries`] checks them);
/// `source` names it in errors. What `bench mbm` builds for each MotionBenchMaker problem.
pub fn arm_scene(
    name: String,
    robot: ArmRobot,
    queries: Vec<Query>,
    source: &Path,
) -> Result<Scene, SceneError> {
    let space = joint_space(&robot.arm).map_err(|e| SceneError::Invalid {
        path: source.to_path_buf(),
        message: format!("the planning group: {e}"),
    })?;
    Ok(Scene {
        name,
        space,
        robot: Robot::Arm(Box::new(robot)),
        obstacles: Vec::new(),
        queries,
        source: Some(source.to_path_buf()),
        warnings: Vec::new(),
    })
}

/// The joint space of the arm's planning group: its limits as bounds, continuous joints
/// wrapping.
pub fn joint_space(arm: &Arm) -> Result<Space, crate::space::SpaceError> {
    let continuous: Vec<bool> = arm
        .group
        .joints
        .iter()
        .map(|&k| matches!(arm.model.urdf.joints[k].kind, JointKind::Continuous))
        .collect();
    Space::joints(
        arm.group.lower.clone(),
        arm.group.upper.clone(),
        &continuous,
    )
}
