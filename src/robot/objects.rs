//! The world's collision objects an arm is checked against: parts (MoveIt's primitives or
//! meshes) placed in a frame, the world or a link of the robot. Read from a MoveIt
//! PlanningScene by [`crate::scene::moveit`], or built in code.

use super::{Arm, Primitive, RobotError};
use crate::geometry::TriMesh;
use nalgebra::Isometry3;

/// One collision object: parts placed in a frame (the world once [`CollisionObject::placed`]).
#[derive(Clone, Debug)]
pub struct CollisionObject {
    /// The object's id (names it in collision reports).
    pub id: String,
    /// The frame the parts' poses are in: `header.frame_id` as written (without a leading
    /// `/`), empty for the world.
    pub frame: String,
    /// Pose (in `frame`) and shape of each part.
    pub parts: Vec<(Isometry3<f64>, ObjectShape)>,
}

impl CollisionObject {
    /// An object of these parts placed in the world (an object built in code rather than read).
    pub fn in_world(id: impl Into<String>, parts: Vec<(Isometry3<f64>, ObjectShape)>) -> Self {
        CollisionObject {
            id: id.into(),
            frame: String::new(),
            parts,
        }
    }

    /// The object in the world frame: its parts moved by the pose of its frame on `arm` (the
    /// arm's base and joint values as set; see [`Arm::frame_pose`] for the frames allowed).
    pub fn placed(&self, arm: &Arm) -> Result<CollisionObject, RobotError> {
        let at = arm
            .frame_pose(&self.frame)
            .map_err(|e| RobotError::Config {
                what: format!("collision object {}", self.id),
                message: e.to_string(),
            })?;
        Ok(CollisionObject {
            id: self.id.clone(),
            frame: String::new(),
            parts: self
                .parts
                .iter()
                .map(|(pose, shape)| (at * pose, shape.clone()))
                .collect(),
        })
    }
}

/// Every object of `objects` in the world frame ([`CollisionObject::placed`]).
pub fn placed_objects(
    objects: &[CollisionObject],
    arm: &Arm,
) -> Result<Vec<CollisionObject>, RobotError> {
    objects.iter().map(|o| o.placed(arm)).collect()
}

/// The shape of a part of a collision object.
#[derive(Clone, Debug)]
pub enum ObjectShape {
    /// A box, sphere, cylinder or cone (exact).
    Primitive(Primitive),
    /// A triangle mesh in the part's frame.
    Mesh(TriMesh),
}
