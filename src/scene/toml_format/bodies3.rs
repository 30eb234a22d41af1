//! Scenes of several bodies moving in space: `[[body]]` tables in a `se3` scene.
//!
//! ```toml
//! [space]
//! kind = "se3"
//! lower = [-3.0, -3.0, -1.0]          # every body's reference point stays in this box
//! upper = [3.0, 3.0, 4.0]
//!
//! [[body]]                            # in configuration order; at least one
//! name = "red"                        # unique
//! box = { half_extents = [0.5, 0.5, 0.5] }
//! # any shape a se3 [robot] takes (box, convex, mesh), and its center
//!
//! [[body]]
//! name = "blue"
//! mesh = "meshes/cube.obj"
//! center = "mean"
//!
//! [[query]]                           # the bodies' poses x y z qx qy qz qw, concatenated
//! start = [2.0, 2.0, 2.5, 0, 0, 0, 1, -2.0, 2.0, 2.5, 0, 0, 0, 1]
//! goal  = [1.0, 0.0, 0.55, 0, 0, 0, 1, -1.0, 0.0, 0.55, 0, 0, 0, 1]
//! ```
//!
//! The rotation scale defaults to the largest body's radius about its reference point.

use super::spec::File;
use super::{Kind, Reader};
use crate::scene::error::SceneError;
use crate::scene::types::{MeshBody, Robot, Scene};
use crate::space::bodies3::MAX_SOLID_BODIES;
use crate::space::Space;

impl Reader<'_> {
    /// A scene of the bodies of `file` (a `se3` scene with at least one `[[body]]`).
    pub(super) fn bodies3_scene(&mut self, file: File) -> Result<Scene, SceneError> {
        if file.robot.is_some() {
            return Err(self.invalid(
                "a scene has either one [robot] or several [[body]] tables, not both".into(),
            ));
        }
        if file.bodies.len() > MAX_SOLID_BODIES {
            return Err(self.invalid(format!(
                "{} [[body]] tables; at most {MAX_SOLID_BODIES} bodies are accepted in a se3 \
                 scene",
                file.bodies.len()
            )));
        }
        let mut bodies: Vec<MeshBody> = Vec::with_capacity(file.bodies.len());
        for (i, spec) in file.bodies.iter().enumerate() {
            let name = match &spec.name {
                Some(n) if !n.trim().is_empty() => n.clone(),
                _ => return Err(self.invalid(format!("[[body]] {}: give it a name", i + 1))),
            };
            if bodies.iter().any(|b| b.name == name) {
                return Err(self.invalid(format!(
                    "[[body]] {}: the name \"{name}\" is taken by an earlier body",
                    i + 1
                )));
            }
            let mesh = self.robot_3d(&format!("body \"{name}\""), &spec.shape())?;
            bodies.push(MeshBody { name, mesh });
        }
        let obstacles = self.rigid_obstacles(&file, Kind::Se3)?;
        let space = self.bodies3_space(&file, &bodies)?;
        Ok(self.assemble(file, space, Robot::MeshBodies(bodies), obstacles))
    }

    fn bodies3_space(&self, file: &File, bodies: &[MeshBody]) -> Result<Space, SceneError> {
        let radius = bodies.iter().map(|b| b.mesh.radius()).fold(0.0, f64::max);
        let max = crate::limits::MAX_COORDINATE;
        if !(radius.is_finite() && radius <= max) {
            return Err(self.invalid(format!(
                "a body is too large: its radius about its reference point is {radius:?}, more \
                 than {max:e}, where distances overflow"
            )));
        }
        let scale = self.rotation_scale(file.space.rotation_scale, radius, "every body's")?;
        let (lo, hi) = (&file.space.lower, &file.space.upper);
        Space::se3_bodies(
            bodies.len(),
            [lo[0], lo[1], lo[2]],
            [hi[0], hi[1], hi[2]],
            scale,
        )
        .map_err(|e| self.invalid(format!("[space] {e}")))
    }
}
