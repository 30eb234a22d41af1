//! What a scene is: its robot, its obstacles and its queries (the methods are in the parent
//! module, the readers in one module per format).

use super::arm_robot::ArmRobot;
use crate::geometry::{Polygon, TriMesh};
use crate::space::{Config, Space};
use std::path::PathBuf;

/// The moving body.
#[derive(Clone, Debug, PartialEq)]
pub enum Robot {
    /// A point (R^n scenes).
    Point,
    /// The union of polygons in the body frame (SE(2) scenes); the reference point is the origin.
    Polygons(Vec<Polygon>),
    /// A triangle mesh in the body frame (SE(3) scenes); the reference point is the origin.
    Mesh(TriMesh),
    /// A robot arm's planning group among a MoveIt environment (joint-space scenes);
    /// the environment lives here, not in [`Scene::obstacles`].
    Arm(Box<ArmRobot>),
    /// Several bodies that move concurrently (SE(2)^k scenes, [`crate::space::bodies`]), in
    /// the order of their poses in a configuration.
    Bodies(Vec<Body>),
    /// Several rigid bodies that move concurrently in space (SE(3)^k scenes,
    /// [`crate::space::bodies3`]), in the order of their poses in a configuration.
    MeshBodies(Vec<MeshBody>),
}

/// One of several moving bodies in space.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshBody {
    /// Its name in the scene file (unique within the scene).
    pub name: String,
    /// A triangle mesh in its body frame; its reference point is the origin.
    pub mesh: TriMesh,
}

/// One of several moving bodies.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Its name in the scene file (unique within the scene).
    pub name: String,
    /// The union of polygons in its body frame; its reference point is the origin.
    pub parts: Vec<Polygon>,
}

/// A fixed obstacle.
#[derive(Clone, Debug, PartialEq)]
pub enum Obstacle {
    /// A closed ball (a disc in the plane).
    Disc {
        /// Centre.
        centre: Vec<f64>,
        /// Radius (≥ 0).
        radius: f64,
    },
    /// A polygon (SE(2) scenes; boxes become rectangles).
    Polygon(Polygon),
    /// A triangle mesh (SE(3) scenes; boxes become closed cuboids).
    Mesh(TriMesh),
}

/// A start and a goal.
#[derive(Clone, Debug, PartialEq)]
pub struct Query {
    /// Start configuration.
    pub start: Config,
    /// Goal configuration.
    pub goal: Config,
}

/// A motion planning scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Name (from the file).
    pub name: String,
    /// Configuration space with bounds.
    pub space: Space,
    /// The moving body.
    pub robot: Robot,
    /// The fixed obstacles.
    pub obstacles: Vec<Obstacle>,
    /// The scene's own queries.
    pub queries: Vec<Query>,
    /// The file it was read from, if any.
    pub source: Option<PathBuf>,
    /// Things worth telling the user (open meshes whose containment cannot be decided …).
    pub warnings: Vec<String>,
}
