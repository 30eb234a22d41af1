//! Scenes: bounds, robot, obstacles and queries, from a TOML file or an OMPL.app `.cfg`.
//!
//! A scene turns into the oracle for its space ([`Scene::oracle`]): a point among discs in
//! R^n, a polygonal robot among polygons in SE(2), a polyhedral robot among polyhedra in SE(3),
//! always with "outside the bounds is obstacle".
//!
//! | module | reads |
//! |---|---|
//! | [`toml_format`] | viaroad's TOML scenes (the format is documented there) |
//! | [`arm`] | arm scenes: a URDF robot's planning group in a MoveIt scene (`kind = "arm"`) |
//! | [`ompl_cfg`] | OMPL.app problems (`.cfg`), OMPL path files and query-pair files |
//! | [`mesh_io`] | meshes: Wavefront OBJ, STL |
//! | [`moveit`] | MoveIt PlanningScene and MotionPlanRequest YAML (robot arms) |
//! | [`collada`] | Collada meshes as OMPL.app sees them through assimp (frame, robot centre) |
//! | [`shapes`] | convex hulls, 2D footprints of prism meshes, simple-polygon check |

pub mod arm;
mod arm_robot;
mod checks;
pub mod collada;
mod error;
mod fnv;
pub mod mesh_io;
pub mod moveit;
pub mod ompl_cfg;
pub mod toml_format;
mod types;
mod yaml_depth;

pub use crate::geometry::hull as shapes;
pub use error::SceneError;
pub use types::{Body, MeshBody, Obstacle, Query, Robot, Scene};

use crate::geometry::{Polygon, TriMesh};
use crate::oracle::bodies::PlanarBodies;
use crate::oracle::bodies3::SolidBodies;
use crate::oracle::discs::Discs;
use crate::oracle::polygons::Polygons;
use crate::oracle::polyhedra::Polyhedra;
use crate::oracle::{Bounded, CallCounts, CollisionOracle, CountedOracle};
use crate::space::{Config, SpaceKind};
use fnv::Fnv;
use std::path::Path;

impl Scene {
    /// Reads a scene: `.toml` in viaroad's format, `.cfg` as an OMPL.app problem.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        match path.extension().and_then(|e| e.to_str()) {
            Some("cfg") => ompl_cfg::load(path),
            _ => toml_format::load(path),
        }
    }

    /// The scene's own queries, checked (shape, bounds, collision) and normalised: what the
    /// commands that answer them use. Loading accepts a scene whose queries lie outside the
    /// bounds or in collision (with a warning: a roadmap does not need them); this is where
    /// that becomes an error.
    pub fn checked_queries(&self) -> Result<Vec<Query>, SceneError> {
        checks::checked_queries(self)
    }

    /// The polygonal obstacles of a planar scene (none in other scenes).
    pub fn polygon_obstacles(&self) -> Vec<Polygon> {
        self.obstacles
            .iter()
            .filter_map(|o| match o {
                Obstacle::Polygon(p) => Some(p.clone()),
                _ => None,
            })
            .collect()
    }

    /// The mesh obstacles of a scene in space (none in other scenes).
    pub fn mesh_obstacles(&self) -> Vec<TriMesh> {
        self.obstacles
            .iter()
            .filter_map(|o| match o {
                Obstacle::Mesh(m) => Some(m.clone()),
                _ => None,
            })
            .collect()
    }

    /// The collision oracle of this scene, with "outside the bounds is obstacle".
    pub fn oracle(&self) -> Box<dyn CollisionOracle> {
        match (&self.robot, self.space.kind()) {
            (Robot::Point, SpaceKind::Euclidean(n)) => {
                let (centres, radii): (Vec<Vec<f64>>, Vec<f64>) = self
                    .obstacles
                    .iter()
                    .filter_map(|o| match o {
                        Obstacle::Disc { centre, radius } => Some((centre.clone(), *radius)),
                        _ => None,
                    })
                    .unzip();
                Box::new(Bounded::new(
                    self.space.clone(),
                    Discs::new(n, &centres, &radii),
                ))
            }
            (Robot::Polygons(parts), _) => {
                let obstacles = self.polygon_obstacles();
                Box::new(Bounded::new(
                    self.space.clone(),
                    Polygons::new(parts.clone(), obstacles),
                ))
            }
            (Robot::Mesh(mesh), _) => {
                let obstacles = self
                    .obstacles
                    .iter()
                    .filter_map(|o| match o {
                        Obstacle::Mesh(m) => Some(m.clone()),
                        _ => None,
                    })
                    .collect();
                Box::new(Bounded::new(
                    self.space.clone(),
                    Polyhedra::new(mesh.clone(), obstacles),
                ))
            }
            (Robot::Bodies(bodies), _) => {
                let obstacles = self.polygon_obstacles();
                let parts = bodies.iter().map(|b| b.parts.clone()).collect();
                Box::new(Bounded::new(
                    self.space.clone(),
                    PlanarBodies::new(parts, obstacles),
                ))
            }
            (Robot::MeshBodies(bodies), _) => {
                let meshes = bodies.iter().map(|b| b.mesh.clone()).collect();
                Box::new(Bounded::new(
                    self.space.clone(),
                    SolidBodies::new(meshes, self.mesh_obstacles()),
                ))
            }
            (Robot::Arm(a), _) => Box::new(Bounded::new(
                self.space.clone(),
                arm::ArmCollision::new(a.arm_oracle().clone()),
            )),
            (Robot::Point, _) => unreachable!("the loaders only pair a point robot with R^n"),
        }
    }

    /// Checks a configuration given by a user: shape, finiteness, bounds and freedom from
    /// collision. Returns it normalised (angle wrapped, quaternion unit length).
    pub fn check_config(
        &self,
        oracle: &dyn CollisionOracle,
        what: &str,
        q: &[f64],
    ) -> Result<Config, SceneError> {
        self.space.check(q).map_err(|source| SceneError::Config {
            what: what.to_string(),
            source,
        })?;
        let mut q = q.to_vec();
        self.space.normalize(&mut q);
        if !self.space.in_bounds(&q) {
            return Err(SceneError::OutOfBounds {
                what: what.to_string(),
                config: q,
            });
        }
        if !oracle.is_free(&q, &mut CallCounts::default()) {
            return Err(SceneError::InCollision {
                what: what.to_string(),
                config: q,
            });
        }
        Ok(q)
    }

    /// A 64-bit fingerprint of what decides collisions: space kind, bounds, rotation scale,
    /// robot and obstacle geometry (not the name, not the queries). A roadmap records it and is
    /// refused for any other scene.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Fnv::new();
        h.str(&self.space.kind().to_string());
        h.floats(self.space.lower());
        h.floats(self.space.upper());
        h.floats(&[self.space.rotation_scale()]);
        match &self.robot {
            Robot::Point => h.str("point"),
            Robot::Polygons(parts) => {
                h.str("polygons");
                parts.iter().for_each(|p| h.polygon(p));
            }
            Robot::Mesh(m) => {
                h.str("mesh");
                h.mesh(m);
            }
            Robot::Arm(a) => h.bytes(&a.digest().to_le_bytes()),
            Robot::Bodies(bodies) => {
                h.str("bodies");
                for b in bodies {
                    h.bytes(&(b.parts.len() as u64).to_le_bytes());
                    b.parts.iter().for_each(|p| h.polygon(p));
                }
            }
            Robot::MeshBodies(bodies) => {
                h.str("mesh bodies");
                bodies.iter().for_each(|b| h.mesh(&b.mesh));
            }
        }
        for o in &self.obstacles {
            match o {
                Obstacle::Disc { centre, radius } => {
                    h.str("disc");
                    h.floats(centre);
                    h.floats(&[*radius]);
                }
                Obstacle::Polygon(p) => {
                    h.str("polygon");
                    h.polygon(p);
                }
                Obstacle::Mesh(m) => {
                    h.str("mesh");
                    h.mesh(m);
                }
            }
        }
        h.finish()
    }
}
