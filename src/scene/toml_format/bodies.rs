//! Scenes of several moving bodies: `[[body]]` tables in place of the one `[robot]`.
//!
//! ```toml
//! [space]
//! kind = "se2"
//! lower = [0.0, 0.0]                  # every body's reference point stays in this box
//! upper = [6.0, 2.0]
//!
//! [[body]]                            # in configuration order; at least one
//! name = "left"                       # unique
//! polygon = { vertices = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]] }
//! # any shape a se2 [robot] takes (box, polygon, polygons, convex, mesh), and its center
//!
//! [[body]]
//! name = "right"
//! box = { half_extents = [0.5, 0.5] }
//!
//! [[query]]
//! start = [1.0, 0.5, 0.0, 3.0, 0.5, 0.0]   # the bodies' poses x y θ, concatenated
//! goal  = [3.0, 0.5, 0.0, 1.0, 0.5, 0.0]
//! ```
//!
//! The rotation scale defaults to the largest body's radius about its reference point.

use super::spec::File;
use super::{Kind, Reader};
use crate::geometry::Polygon;
use crate::scene::error::SceneError;
use crate::scene::types::{Body, Robot, Scene};
use crate::space::bodies::MAX_BODIES;
use crate::space::Space;

impl Reader<'_> {
    /// A scene of the bodies of `file` (which has at least one `[[body]]`).
    pub(super) fn bodies_scene(&mut self, file: File, kind: Kind) -> Result<Scene, SceneError> {
        if kind == Kind::Se3 {
            return self.bodies3_scene(file);
        }
        if kind != Kind::Se2 {
            return Err(self.invalid(format!(
                "[[body]] tables move several bodies in a se2 space; a {} scene {}",
                file.space.kind,
                if kind == Kind::Se3 {
                    "moves one [robot]"
                } else {
                    "moves a point"
                }
            )));
        }
        if file.robot.is_some() {
            return Err(self.invalid(
                "a scene has either one [robot] or several [[body]] tables, not both".into(),
            ));
        }
        if file.bodies.len() > MAX_BODIES {
            return Err(self.invalid(format!(
                "{} [[body]] tables; at most {MAX_BODIES} bodies are accepted",
                file.bodies.len()
            )));
        }
        let mut bodies: Vec<Body> = Vec::with_capacity(file.bodies.len());
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
            let parts = self.robot_2d(&format!("body \"{name}\""), &spec.shape())?;
            bodies.push(Body { name, parts });
        }
        let obstacles = self.rigid_obstacles(&file, kind)?;
        let space = self.bodies_space(&file, &bodies)?;
        Ok(self.assemble(file, space, Robot::Bodies(bodies), obstacles))
    }

    fn bodies_space(&self, file: &File, bodies: &[Body]) -> Result<Space, SceneError> {
        let radius = bodies
            .iter()
            .flat_map(|b| &b.parts)
            .map(Polygon::radius)
            .fold(0.0, f64::max);
        let max = crate::limits::MAX_COORDINATE;
        if !(radius.is_finite() && radius <= max) {
            return Err(self.invalid(format!(
                "a body is too large: its radius about its reference point is {radius:?}, more \
                 than {max:e}, where distances overflow"
            )));
        }
        let scale = self.rotation_scale(file.space.rotation_scale, radius, "every body's")?;
        let (lo, hi) = (&file.space.lower, &file.space.upper);
        Space::se2_bodies(bodies.len(), [lo[0], lo[1]], [hi[0], hi[1]], scale)
            .map_err(|e| self.invalid(format!("[space] {e}")))
    }
}
