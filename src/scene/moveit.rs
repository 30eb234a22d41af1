//! MoveIt's own formats: a PlanningScene YAML (the environment: collision
//! objects, the robot's state, the allowed-collision matrix) and a MotionPlanRequest YAML (the
//! query: group, start state, goal joint constraints), as MotionBenchMaker writes them.
//!
//! Read from a PlanningScene: `world.collision_objects[]` with `id`, an optional object
//! `pose`, `primitives[]` (`type` as a name or `shape_msgs/SolidPrimitive`'s number;
//! `dimensions`: box `[x, y, z]` full sides, sphere `[r]`, cylinder and cone `[height,
//! radius]`) with `primitive_poses[]`, and `meshes[]` (`vertices`, `triangles[].vertex_indices`)
//! with `mesh_poses[]`; `robot_state.joint_state` (`name`, `position`) and the virtual joint's
//! transform in `robot_state.multi_dof_joint_state`; `allowed_collision_matrix`. Poses are
//! `position` + `orientation` (quaternion `[x, y, z, w]`, or `{x, y, z, w}` maps), composed as
//! `pose · primitive_pose`, in the frame `header.frame_id` names: the world (empty, `world`, a
//! virtual joint's parent frame) or a link of the robot that the planning group does not move,
//! placed by [`CollisionObject::placed`] once the robot's state is known ([`Arm::frame_pose`]);
//! attached objects, planes and octomaps are not read.
//!
//! A file is read if it has at most [`MAX_MOVEIT_YAML_BYTES`], nests at most
//! [`MAX_YAML_DEPTH`] lists and maps, and a scene at most [`MAX_SCENE_OBJECTS`] objects and
//! [`MAX_SCENE_SHAPES`] primitives and meshes ([`crate::limits`]).
//!
//! Curved primitives become polytopes that contain them ([`crate::robot::shapes`]) when the
//! exact oracle needs them; here they stay exact [`Primitive`]s.

use super::error::{read_input_text_within, SceneError};
use crate::geometry::TriMesh;
use crate::limits::{MAX_MOVEIT_YAML_BYTES, MAX_SCENE_OBJECTS, MAX_SCENE_SHAPES, MAX_YAML_DEPTH};
pub use crate::robot::objects::{placed_objects, CollisionObject, ObjectShape};
use crate::robot::{Arm, Primitive, RobotError};
use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion};
use serde::Deserialize;
use std::path::Path;

/// A MoveIt PlanningScene: the obstacles and the robot's state.
#[derive(Clone, Debug)]
pub struct PlanningScene {
    /// The scene's `name` (often empty).
    pub name: String,
    /// The world's collision objects.
    pub objects: Vec<CollisionObject>,
    /// `robot_state.joint_state`: joint names and positions.
    pub joint_state: JointState,
    /// The virtual joint's transform (`robot_state.multi_dof_joint_state`), if given.
    pub base: Option<Isometry3<f64>>,
    /// Pairs the allowed-collision matrix allows (names of links or objects). Link–link pairs
    /// are applied by [`PlanningScene::apply_to`]; link–object pairs are read but not yet
    /// applied by the checker or the oracle (the MotionBenchMaker scenes have none).
    pub allowed: Vec<(String, String)>,
}

/// Joint names with one position each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointState {
    /// Joint names.
    pub names: Vec<String>,
    /// Positions, one per name.
    pub positions: Vec<f64>,
}

impl JointState {
    /// Sets the joints outside `arm`'s group to these values, skipping names the robot model
    /// does not have: a MoveIt state describes the whole robot it was recorded on, and a
    /// trimmed URDF (VAMP's Fetch has no wheels) lacks joints that could not move any link of
    /// it. A group joint missing from a start state or goal is still an error
    /// ([`Arm::group_config`]).
    pub fn set_known(&self, arm: &mut Arm) -> Result<(), RobotError> {
        if self.names.len() != self.positions.len() {
            return arm.set_joint_values(&self.names, &self.positions);
        }
        let (names, values): (Vec<String>, Vec<f64>) = self
            .names
            .iter()
            .zip(&self.positions)
            .filter(|(n, _)| arm.model.joint(n).is_some())
            .map(|(n, &v)| (n.clone(), v))
            .unzip();
        arm.set_joint_values(&names, &values)
    }
}

/// A MoveIt MotionPlanRequest: a joint-space query.
#[derive(Clone, Debug)]
pub struct MotionPlanRequest {
    /// `group_name`.
    pub group: String,
    /// `start_state.joint_state`.
    pub start: JointState,
    /// The virtual joint's transform in the start state, if given.
    pub base: Option<Isometry3<f64>>,
    /// The first goal's `joint_constraints` (names and positions).
    pub goal: JointState,
    /// `allowed_planning_time` in seconds, if given.
    pub allowed_planning_time: Option<f64>,
}

// ---- the YAML as written (serde) ----

/// How a list longer than its limit ends its message, so that [`parse_yaml`] can tell it from
/// a YAML of the wrong shape.
const TOO_MANY: &str = "the most viaroad reads";

/// A list of at most `MAX` items, refused at the first item past the limit (before it or any
/// later one is built).
fn at_most<'de, const MAX: usize, T, D>(de: D) -> Result<Vec<T>, D::Error>
where
    T: Deserialize<'de>,
    D: serde::Deserializer<'de>,
{
    struct Bounded<const MAX: usize, T>(std::marker::PhantomData<T>);
    impl<'de, const MAX: usize, T: Deserialize<'de>> serde::de::Visitor<'de> for Bounded<MAX, T> {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a list of at most {MAX} items")
        }
        fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let mut items = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(MAX));
            while let Some(item) = seq.next_element()? {
                if items.len() == MAX {
                    return Err(serde::de::Error::custom(format!(
                        "more than {MAX} items, {TOO_MANY},"
                    )));
                }
                items.push(item);
            }
            Ok(items)
        }
    }
    de.deserialize_seq(Bounded::<MAX, T>(std::marker::PhantomData))
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawVec3 {
    List([f64; 3]),
    Map { x: f64, y: f64, z: f64 },
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawQuat {
    List([f64; 4]),
    Map { x: f64, y: f64, z: f64, w: f64 },
}

#[derive(Deserialize)]
struct RawPose {
    position: RawVec3,
    orientation: RawQuat,
}

#[derive(Deserialize)]
struct RawTransform {
    translation: RawVec3,
    rotation: RawQuat,
}

#[derive(Deserialize, Default)]
struct RawJointState {
    #[serde(default)]
    name: Vec<String>,
    #[serde(default)]
    position: Vec<f64>,
}

#[derive(Deserialize, Default)]
struct RawMultiDof {
    #[serde(default)]
    transforms: Vec<RawTransform>,
}

#[derive(Deserialize, Default)]
struct RawRobotState {
    #[serde(default)]
    joint_state: RawJointState,
    #[serde(default)]
    multi_dof_joint_state: RawMultiDof,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawPrimitiveType {
    Name(String),
    Number(u8),
}

#[derive(Deserialize)]
struct RawPrimitive {
    #[serde(rename = "type")]
    ty: RawPrimitiveType,
    dimensions: Vec<f64>,
}

#[derive(Deserialize)]
struct RawTriangle {
    vertex_indices: [u32; 3],
}

#[derive(Deserialize)]
struct RawMesh {
    triangles: Vec<RawTriangle>,
    vertices: Vec<RawVec3>,
}

#[derive(Deserialize, Default)]
struct RawHeader {
    #[serde(default)]
    frame_id: String,
}

#[derive(Deserialize)]
struct RawObject {
    id: String,
    #[serde(default)]
    header: RawHeader,
    #[serde(default)]
    pose: Option<RawPose>,
    #[serde(default, deserialize_with = "at_most::<MAX_SCENE_SHAPES, _, _>")]
    primitives: Vec<RawPrimitive>,
    #[serde(default, deserialize_with = "at_most::<MAX_SCENE_SHAPES, _, _>")]
    primitive_poses: Vec<RawPose>,
    #[serde(default, deserialize_with = "at_most::<MAX_SCENE_SHAPES, _, _>")]
    meshes: Vec<RawMesh>,
    #[serde(default, deserialize_with = "at_most::<MAX_SCENE_SHAPES, _, _>")]
    mesh_poses: Vec<RawPose>,
}

#[derive(Deserialize, Default)]
struct RawWorld {
    #[serde(default, deserialize_with = "at_most::<MAX_SCENE_OBJECTS, _, _>")]
    collision_objects: Vec<RawObject>,
}

#[derive(Deserialize, Default)]
struct RawAcm {
    #[serde(default)]
    entry_names: Vec<String>,
    #[serde(default)]
    entry_values: Vec<Vec<bool>>,
}

#[derive(Deserialize)]
struct RawScene {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    robot_state: RawRobotState,
    #[serde(default)]
    world: RawWorld,
    #[serde(default)]
    allowed_collision_matrix: RawAcm,
}

#[derive(Deserialize)]
struct RawJointConstraint {
    joint_name: String,
    position: f64,
}

#[derive(Deserialize)]
struct RawConstraints {
    #[serde(default)]
    joint_constraints: Vec<RawJointConstraint>,
}

#[derive(Deserialize)]
struct RawRequest {
    group_name: String,
    #[serde(default)]
    start_state: RawRobotState,
    #[serde(default)]
    goal_constraints: Vec<RawConstraints>,
    #[serde(default)]
    allowed_planning_time: Option<f64>,
}

// ---- conversion ----

fn finite(v: f64, what: &str) -> Result<f64, String> {
    if v.is_finite() && v.abs() <= crate::limits::MAX_COORDINATE {
        Ok(v)
    } else {
        Err(format!("{what}: {v} is not a finite number in range"))
    }
}

fn vec3(v: &RawVec3, what: &str) -> Result<[f64; 3], String> {
    let [x, y, z] = match *v {
        RawVec3::List(a) => a,
        RawVec3::Map { x, y, z } => [x, y, z],
    };
    Ok([finite(x, what)?, finite(y, what)?, finite(z, what)?])
}

/// A unit quaternion from `[x, y, z, w]`, normalised; a zero or non-finite one is an error.
fn quat(q: &RawQuat, what: &str) -> Result<UnitQuaternion<f64>, String> {
    let [x, y, z, w] = match *q {
        RawQuat::List(a) => a,
        RawQuat::Map { x, y, z, w } => [x, y, z, w],
    };
    let q = Quaternion::new(
        finite(w, what)?,
        finite(x, what)?,
        finite(y, what)?,
        finite(z, what)?,
    );
    if q.norm() < 1e-6 {
        return Err(format!("{what}: the quaternion {q:?} has no direction"));
    }
    Ok(UnitQuaternion::from_quaternion(q))
}

fn pose(p: &RawPose, what: &str) -> Result<Isometry3<f64>, String> {
    let [x, y, z] = vec3(&p.position, what)?;
    Ok(Isometry3::from_parts(
        Translation3::new(x, y, z),
        quat(&p.orientation, what)?,
    ))
}

fn transform(t: &RawTransform, what: &str) -> Result<Isometry3<f64>, String> {
    let [x, y, z] = vec3(&t.translation, what)?;
    Ok(Isometry3::from_parts(
        Translation3::new(x, y, z),
        quat(&t.rotation, what)?,
    ))
}

fn joint_state(raw: &RawJointState, what: &str) -> Result<JointState, String> {
    if raw.name.len() != raw.position.len() {
        return Err(format!(
            "{what}: {} joint names but {} positions",
            raw.name.len(),
            raw.position.len()
        ));
    }
    let positions = raw
        .position
        .iter()
        .map(|&v| finite(v, what))
        .collect::<Result<_, _>>()?;
    Ok(JointState {
        names: raw.name.clone(),
        positions,
    })
}

fn primitive(p: &RawPrimitive, what: &str) -> Result<Primitive, String> {
    let d = &p.dimensions;
    for &v in d {
        if finite(v, what)? <= 0.0 {
            return Err(format!("{what}: dimension {v} is not positive"));
        }
    }
    let kind = match &p.ty {
        RawPrimitiveType::Name(n) => n.to_ascii_lowercase(),
        RawPrimitiveType::Number(1) => "box".into(),
        RawPrimitiveType::Number(2) => "sphere".into(),
        RawPrimitiveType::Number(3) => "cylinder".into(),
        RawPrimitiveType::Number(4) => "cone".into(),
        RawPrimitiveType::Number(n) => format!("number {n}"),
    };
    let want = |n: usize| {
        if d.len() == n {
            Ok(())
        } else {
            Err(format!(
                "{what}: a {kind} needs {n} dimensions, not {}",
                d.len()
            ))
        }
    };
    Ok(match kind.as_str() {
        "box" => {
            want(3)?;
            Primitive::Box {
                size: [d[0], d[1], d[2]],
            }
        }
        "sphere" => {
            want(1)?;
            Primitive::Sphere { radius: d[0] }
        }
        "cylinder" => {
            want(2)?;
            Primitive::Cylinder {
                length: d[0],
                radius: d[1],
            }
        }
        "cone" => {
            want(2)?;
            Primitive::Cone {
                length: d[0],
                radius: d[1],
            }
        }
        other => return Err(format!("{what}: unknown primitive type {other}")),
    })
}

fn object(o: &RawObject) -> Result<CollisionObject, String> {
    let what = format!("collision object {}", o.id);
    let frame = o.header.frame_id.trim_start_matches('/');
    let base = match &o.pose {
        Some(p) => pose(p, &what)?,
        None => Isometry3::identity(),
    };
    if o.primitives.len() != o.primitive_poses.len() || o.meshes.len() != o.mesh_poses.len() {
        return Err(format!("{what}: every primitive and mesh needs one pose"));
    }
    let mut parts = Vec::new();
    for (p, at) in o.primitives.iter().zip(&o.primitive_poses) {
        parts.push((
            base * pose(at, &what)?,
            ObjectShape::Primitive(primitive(p, &what)?),
        ));
    }
    for (m, at) in o.meshes.iter().zip(&o.mesh_poses) {
        let vertices = m
            .vertices
            .iter()
            .map(|v| vec3(v, &what).map(Point3::from))
            .collect::<Result<Vec<_>, _>>()?;
        let triangles = m.triangles.iter().map(|t| t.vertex_indices).collect();
        let mesh = TriMesh::new(vertices, triangles).map_err(|e| format!("{what}: {e}"))?;
        parts.push((base * pose(at, &what)?, ObjectShape::Mesh(mesh)));
    }
    Ok(CollisionObject {
        id: o.id.clone(),
        frame: if frame == "world" {
            String::new()
        } else {
            frame.to_string()
        },
        parts,
    })
}

/// Deserializes a MoveIt message, after checking that it nests at most
/// [`MAX_YAML_DEPTH`] collections deep ([`super::yaml_depth`]).
fn parse_yaml<T: serde::de::DeserializeOwned>(text: &str, path: &Path) -> Result<T, SceneError> {
    if let Some(line) = super::yaml_depth::first_too_deep(text, MAX_YAML_DEPTH) {
        return Err(SceneError::Invalid {
            path: path.to_path_buf(),
            message: format!(
                "line {line}: YAML nested deeper than {MAX_YAML_DEPTH} lists and maps \
                 (a MoveIt message nests about eight)"
            ),
        });
    }
    yaml_serde::from_str(text).map_err(|e| {
        let e = e.to_string();
        if e.contains(TOO_MANY) {
            SceneError::Invalid {
                path: path.to_path_buf(),
                message: e,
            }
        } else {
            SceneError::Parse {
                path: path.to_path_buf(),
                message: format!("not a MoveIt YAML message of the expected shape: {e}"),
            }
        }
    })
}

/// Parses a PlanningScene YAML; `path` names the file in errors. At most
/// [`MAX_SCENE_OBJECTS`] collision objects and [`MAX_SCENE_SHAPES`] primitives and meshes in
/// all are read; a longer list is refused at its first item past the limit.
pub fn parse_planning_scene(text: &str, path: &Path) -> Result<PlanningScene, SceneError> {
    let raw: RawScene = parse_yaml(text, path)?;
    let invalid = |message: String| SceneError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    let shapes: usize = raw
        .world
        .collision_objects
        .iter()
        .map(|o| o.primitives.len() + o.meshes.len())
        .sum();
    if shapes > MAX_SCENE_SHAPES {
        return Err(invalid(format!(
            "{shapes} primitives and meshes: more than the {MAX_SCENE_SHAPES} viaroad reads \
             from a scene"
        )));
    }
    let objects = raw
        .world
        .collision_objects
        .iter()
        .map(object)
        .collect::<Result<Vec<_>, _>>()
        .map_err(invalid)?;
    let joint_state = joint_state(&raw.robot_state.joint_state, "robot_state").map_err(invalid)?;
    let base = raw
        .robot_state
        .multi_dof_joint_state
        .transforms
        .first()
        .map(|t| transform(t, "robot_state virtual joint"))
        .transpose()
        .map_err(invalid)?;
    let acm = &raw.allowed_collision_matrix;
    let n = acm.entry_names.len();
    if acm.entry_values.len() != n || acm.entry_values.iter().any(|r| r.len() != n) {
        return Err(invalid(format!(
            "the allowed collision matrix is not {n} × {n} for its {n} names"
        )));
    }
    let mut allowed = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if acm.entry_values[i][j] || acm.entry_values[j][i] {
                allowed.push((acm.entry_names[i].clone(), acm.entry_names[j].clone()));
            }
        }
    }
    Ok(PlanningScene {
        name: raw.name.unwrap_or_default(),
        objects,
        joint_state,
        base,
        allowed,
    })
}

/// Reads a PlanningScene YAML file of at most [`MAX_MOVEIT_YAML_BYTES`] (checked before it is
/// read).
pub fn load_planning_scene(path: &Path) -> Result<PlanningScene, SceneError> {
    parse_planning_scene(&read_input_text_within(path, MAX_MOVEIT_YAML_BYTES)?, path)
}

/// Parses a MotionPlanRequest YAML; `path` names the file in errors. The goal is the first
/// goal constraint's joint constraints (MotionBenchMaker writes one).
pub fn parse_motion_plan_request(text: &str, path: &Path) -> Result<MotionPlanRequest, SceneError> {
    let raw: RawRequest = parse_yaml(text, path)?;
    let invalid = |message: String| SceneError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    let start = joint_state(&raw.start_state.joint_state, "start_state").map_err(invalid)?;
    let base = raw
        .start_state
        .multi_dof_joint_state
        .transforms
        .first()
        .map(|t| transform(t, "start_state virtual joint"))
        .transpose()
        .map_err(invalid)?;
    let goal = raw
        .goal_constraints
        .first()
        .filter(|g| !g.joint_constraints.is_empty())
        .ok_or_else(|| invalid("no goal joint_constraints".into()))?;
    let mut names = Vec::new();
    let mut positions = Vec::new();
    for c in &goal.joint_constraints {
        names.push(c.joint_name.clone());
        positions.push(finite(c.position, "goal joint constraint").map_err(invalid)?);
    }
    let time = raw
        .allowed_planning_time
        .map(|t| {
            if t.is_finite() && t >= 0.0 {
                Ok(t)
            } else {
                Err(invalid(format!(
                    "allowed_planning_time {t} is not a duration"
                )))
            }
        })
        .transpose()?;
    Ok(MotionPlanRequest {
        group: raw.group_name,
        start,
        base,
        goal: JointState { names, positions },
        allowed_planning_time: time,
    })
}

/// Reads a MotionPlanRequest YAML file of at most [`MAX_MOVEIT_YAML_BYTES`] (checked before it
/// is read).
pub fn load_motion_plan_request(path: &Path) -> Result<MotionPlanRequest, SceneError> {
    parse_motion_plan_request(&read_input_text_within(path, MAX_MOVEIT_YAML_BYTES)?, path)
}

impl PlanningScene {
    /// Puts the arm into this scene: joints outside its group take the `robot_state` values,
    /// the root takes the virtual joint's transform, and link pairs the allowed-collision
    /// matrix allows are exempt from self-collision checking (as MoveIt does).
    pub fn apply_to(&self, arm: &mut Arm) -> Result<(), RobotError> {
        self.joint_state.set_known(arm)?;
        if let Some(b) = self.base {
            arm.base = b;
        }
        for (a, b) in &self.allowed {
            arm.allow_pair(a, b);
        }
        Ok(())
    }
}

impl MotionPlanRequest {
    /// Start and goal in the arm's group order, after setting the joints outside the group
    /// (and the root pose) from the start state, which takes precedence over the scene's
    /// `robot_state` (MoveIt's rule).
    pub fn start_goal(&self, arm: &mut Arm) -> Result<(Vec<f64>, Vec<f64>), RobotError> {
        self.start.set_known(arm)?;
        if let Some(b) = self.base {
            arm.base = b;
        }
        self.ends(arm)
    }

    /// Start and goal in the arm's group order, moved onto the joint limits as MoveIt moves
    /// them: a goal joint constraint beyond a limit is taken at the limit
    /// (`JointConstraint::configure`, "assuming maximum bounds instead"; MotionBenchMaker's
    /// Fetch goals at ±π against VAMP's limits of ±3.14159), a start state beyond a limit by
    /// at most [`START_BOUNDS_ERROR`] is moved onto it (the `FixStartStateBounds` adapter's
    /// default); a start further out stays as it is, for the scene to refuse.
    pub fn ends(&self, arm: &Arm) -> Result<(Vec<f64>, Vec<f64>), RobotError> {
        let mut start =
            arm.group_config(&self.start.names, &self.start.positions, "start state")?;
        let mut goal = arm.group_config(&self.goal.names, &self.goal.positions, "goal")?;
        let g = &arm.group;
        for i in (0..g.dof()).filter(|&i| arm.is_bounded(i)) {
            let (lo, hi) = (g.lower[i], g.upper[i]);
            goal[i] = goal[i].clamp(lo, hi);
            if start[i] < lo && lo - start[i] <= START_BOUNDS_ERROR {
                start[i] = lo;
            } else if start[i] > hi && start[i] - hi <= START_BOUNDS_ERROR {
                start[i] = hi;
            }
        }
        Ok((start, goal))
    }

    /// Where [`Self::ends`] moved a value onto a limit, one line per joint (for a warning:
    /// MoveIt warns too).
    pub fn moved_onto_limits(&self, arm: &Arm) -> Vec<String> {
        let (Ok(start), Ok(goal), Ok((s, g))) = (
            arm.group_config(&self.start.names, &self.start.positions, "start state"),
            arm.group_config(&self.goal.names, &self.goal.positions, "goal"),
            self.ends(arm),
        ) else {
            return Vec::new();
        };
        let names = arm.group_joint_names();
        let mut notes = Vec::new();
        for (what, asked, taken) in [("start", &start, &s), ("goal", &goal, &g)] {
            for i in (0..asked.len()).filter(|&i| asked[i] != taken[i]) {
                notes.push(format!(
                    "the {what}'s {} = {} lies beyond its limit: taken at {}",
                    names[i], asked[i], taken[i]
                ));
            }
        }
        notes
    }
}

/// How far (rad or m) beyond a joint limit a request's start state is moved onto it: MoveIt's
/// `start_state_max_bounds_error` default.
pub const START_BOUNDS_ERROR: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_primitives_poses_meshes_and_the_acm() {
        let s = parse_planning_scene(
            r#"
robot_state:
  joint_state: {name: [a, b], position: [0.5, -1]}
  multi_dof_joint_state:
    transforms: [{translation: [1, 0, 0], rotation: [0, 0, 0, 1]}]
allowed_collision_matrix:
  entry_names: [l1, l2, l3]
  entry_values: [[false, true, false], [true, false, false], [false, false, false]]
world:
  collision_objects:
    - id: Can
      primitives: [{type: cylinder, dimensions: [0.2, 0.05]}, {type: 2, dimensions: [0.1]}]
      primitive_poses:
        - {position: [0, 0, 1], orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]}
        - {position: {x: 1, y: 2, z: 3}, orientation: {x: 0, y: 0, z: 0, w: 2}}
    - id: Tri
      pose: {position: [0, 0, 5], orientation: [0, 0, 0, 1]}
      meshes: [{vertices: [[0, 0, 0], {x: 1, y: 0, z: 0}, [0, 1, 0]], triangles: [{vertex_indices: [0, 1, 2]}]}]
      mesh_poses: [{position: [0, 0, 1], orientation: [0, 0, 0, 1]}]
"#,
            Path::new("s.yaml"),
        )
        .unwrap();
        assert_eq!(s.joint_state.names, ["a", "b"]);
        assert_eq!(s.joint_state.positions, [0.5, -1.0]);
        assert_eq!(s.base.unwrap().translation.vector.x, 1.0);
        assert_eq!(s.allowed, [("l1".to_string(), "l2".to_string())]);
        assert_eq!(s.objects.len(), 2);
        let (p, shape) = &s.objects[0].parts[0];
        assert!(matches!(
            shape,
            ObjectShape::Primitive(Primitive::Cylinder { radius, length }) if *radius == 0.05 && *length == 0.2
        ));
        // a quarter turn about z
        let x = p.rotation * nalgebra::Vector3::x();
        assert!((x - nalgebra::Vector3::y()).norm() < 1e-12);
        // a non-unit quaternion is normalised
        assert!((s.objects[0].parts[1].0.rotation.angle()).abs() < 1e-12);
        // object pose · mesh pose
        assert_eq!(s.objects[1].parts[0].0.translation.vector.z, 6.0);
    }

    #[test]
    fn reads_a_request() {
        let r = parse_motion_plan_request(
            r#"
group_name: arm
allowed_planning_time: 5
start_state:
  joint_state: {name: [a, b], position: [0, 1]}
goal_constraints:
  - joint_constraints: [{joint_name: b, position: 2}, {position: 3, joint_name: a}]
"#,
            Path::new("r.yaml"),
        )
        .unwrap();
        assert_eq!(r.group, "arm");
        assert_eq!(r.goal.names, ["b", "a"]);
        assert_eq!(r.goal.positions, [2.0, 3.0]);
        assert_eq!(r.allowed_planning_time, Some(5.0));
    }

    #[test]
    fn bad_input_is_an_error() {
        let p = Path::new("x.yaml");
        for bad in [
            "world: [",
            "world: {collision_objects: [{id: a, primitives: [{type: box, dimensions: [1, 1]}], primitive_poses: [{position: [0,0,0], orientation: [0,0,0,1]}]}]}",
            "world: {collision_objects: [{id: a, primitives: [{type: box, dimensions: [1, 1, 1]}], primitive_poses: []}]}",
            "world: {collision_objects: [{id: a, primitives: [{type: box, dimensions: [1, -1, 1]}], primitive_poses: [{position: [0,0,0], orientation: [0,0,0,1]}]}]}",
            "world: {collision_objects: [{id: a, primitives: [{type: torus, dimensions: [1]}], primitive_poses: [{position: [0,0,0], orientation: [0,0,0,1]}]}]}",
            "world: {collision_objects: [{id: a, primitives: [{type: sphere, dimensions: [1]}], primitive_poses: [{position: [0,0,0], orientation: [0,0,0,0]}]}]}",
            "robot_state: {joint_state: {name: [a], position: []}}",
            "allowed_collision_matrix: {entry_names: [a, b], entry_values: [[false]]}",
            "world: {collision_objects: [{id: a, meshes: [{vertices: [[0,0,0]], triangles: [{vertex_indices: [0, 1, 2]}]}], mesh_poses: [{position: [0,0,0], orientation: [0,0,0,1]}]}]}",
        ] {
            assert!(parse_planning_scene(bad, p).is_err(), "accepted {bad}");
        }
        for bad in [
            "start_state: {}",
            "group_name: g\ngoal_constraints: []",
            "group_name: g\ngoal_constraints: [{joint_constraints: [{joint_name: a, position: .nan}]}]",
        ] {
            assert!(parse_motion_plan_request(bad, p).is_err(), "accepted {bad}");
        }
    }
}
