//! The exact arm oracle for a **single-joint move** (issue 10; CHS §1.5 and §2.3.2): moving
//! one revolute joint turns the whole distal part of the chain rigidly about the joint's axis,
//! which stays fixed in the world; a prismatic joint translates it. So the collision intervals
//! of the move are the rotation (translation) intervals of the distal links, as rigid bodies,
//! against the environment **and** the proximal links, which stand still during the move
//! (self-collision becomes a static obstacle). The polyhedra oracle answers exactly that.
//!
//! Per call, for joint `k` moving by `delta` from configuration `q`:
//! - the body frame is the joint's child frame at `q` (its origin lies on the axis);
//! - each distal link with geometry becomes one [`Polyhedra`] robot, its obstacles the
//!   environment's polytopes and the proximal links it is not exempt from (SRDF
//!   `disable_collisions`, the scene's allowed-collision matrix), placed at `q`;
//! - link pairs that keep their relative pose during the move (distal–distal,
//!   proximal–proximal, proximal–environment) collide for the whole move or not at all: they
//!   are tested once, statically;
//! - the answer is the union, in `t ∈ [0, 1]`.
//!
//! Curved primitives are their circumscribed polytopes ([`super::shapes`]), so the answer
//! contains every true collision. This first version builds the polyhedra per call (about a
//! millisecond for the Panda among a dozen boxes); enveloping per link and cached trees are
//! what issue 10 part 4 asks next.

use super::arm::Arm;
use super::RobotError;
use crate::geometry::TriMesh;
use crate::interval::{Interval, IntervalList};
use crate::oracle::polyhedra::Polyhedra;
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::robot::urdf::JointKind;
use crate::scene::moveit::{CollisionObject, ObjectShape};
use crate::space::{Change, Motion};
use nalgebra::Isometry3;

/// Exact collision intervals of single-joint moves of one arm in one scene.
#[derive(Clone, Debug)]
pub struct ArmOracle {
    arm: Arm,
    /// Environment polytopes in the world frame.
    environment: Vec<TriMesh>,
    /// Per link: its collision polytopes in the link frame (empty for links without geometry).
    link_meshes: Vec<Option<TriMesh>>,
}

/// A mesh moved rigidly.
fn placed(mesh: &TriMesh, pose: &Isometry3<f64>) -> TriMesh {
    TriMesh {
        vertices: mesh.vertices.iter().map(|v| pose * v).collect(),
        triangles: mesh.triangles.clone(),
    }
}

/// Several meshes as one (one rigid body).
fn merged(meshes: impl IntoIterator<Item = TriMesh>) -> Option<TriMesh> {
    let mut out: Option<TriMesh> = None;
    for m in meshes {
        match &mut out {
            None => out = Some(m),
            Some(o) => {
                let base = o.vertices.len() as u32;
                o.vertices.extend(m.vertices);
                o.triangles
                    .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
            }
        }
    }
    out
}

/// The SE(3) configuration `[x, y, z, qx, qy, qz, qw]` of a pose (OMPL's order).
fn se3(pose: &Isometry3<f64>) -> Vec<f64> {
    let t = pose.translation.vector;
    let q = pose.rotation.coords;
    vec![t.x, t.y, t.z, q[0], q[1], q[2], q[3]]
}

impl ArmOracle {
    /// The oracle of `arm` (with its group, other joint values, base and exempt pairs as set)
    /// among the scene's collision objects (curved primitives circumscribed).
    pub fn new(arm: &Arm, objects: &[CollisionObject]) -> Result<ArmOracle, RobotError> {
        let mut environment = Vec::new();
        for o in objects {
            for (pose, shape) in &o.parts {
                let local = match shape {
                    ObjectShape::Primitive(p) => p.polytope().map_err(|e| RobotError::Config {
                        what: format!("collision object {}", o.id),
                        message: e.to_string(),
                    })?,
                    ObjectShape::Mesh(m) => m.clone(),
                };
                environment.push(placed(&local, pose));
            }
        }
        let link_meshes = (0..arm.model.urdf.links.len())
            .map(|l| {
                merged(
                    arm.shapes
                        .iter()
                        .filter(|s| s.link == l)
                        .map(|s| placed(&s.polytope, &s.origin)),
                )
            })
            .collect();
        Ok(ArmOracle {
            arm: arm.clone(),
            environment,
            link_meshes,
        })
    }

    /// The arm.
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// Whether two placed meshes meet (exact static test of the polyhedra oracle).
    fn meet(a: TriMesh, b: TriMesh, counts: &mut CallCounts) -> bool {
        let identity = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        Polyhedra::new(a, vec![b]).collides(&identity, counts)
    }

    /// Whether a placed link mesh meets the environment.
    fn in_environment(&self, mesh: TriMesh, counts: &mut CallCounts) -> bool {
        let identity = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        !self.environment.is_empty()
            && Polyhedra::new(mesh, self.environment.clone()).collides(&identity, counts)
    }

    fn exempt(&self, a: usize, b: usize) -> bool {
        let pair = (a.min(b), a.max(b));
        !self.arm.self_pairs.contains(&pair)
    }

    /// Whether group configuration `q` collides (self or environment; bounds not checked).
    pub fn collides(&self, q: &[f64], counts: &mut CallCounts) -> Result<bool, RobotError> {
        self.arm.check_config(q, "configuration")?;
        let poses = self.arm.link_poses(q);
        let world: Vec<Option<TriMesh>> = self
            .link_meshes
            .iter()
            .zip(&poses)
            .map(|(m, p)| m.as_ref().map(|m| placed(m, p)))
            .collect();
        for &(a, b) in &self.arm.self_pairs {
            if let (Some(ma), Some(mb)) = (&world[a], &world[b]) {
                if Self::meet(ma.clone(), mb.clone(), counts) {
                    return Ok(true);
                }
            }
        }
        // link by link: a merged body with one open mesh would lose containment for all
        for m in world.into_iter().flatten() {
            if self.in_environment(m, counts) {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// The collision intervals, in `t ∈ [0, 1]`, of moving group joint `joint` (an index into
    /// the group) by `delta` from `q`: `q(t) = q + t · delta · e_joint`.
    pub fn joint_move(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, RobotError> {
        self.arm.check_config(q, "configuration")?;
        let unsupported = |m: String| RobotError::Config {
            what: "joint move".into(),
            message: m,
        };
        let model = &self.arm.model;
        let k = *self
            .arm
            .group
            .joints
            .get(joint)
            .ok_or_else(|| unsupported(format!("no group joint {joint}")))?;
        if !delta.is_finite() {
            return Err(unsupported(format!("the move {delta} is not finite")));
        }
        if (0..model.urdf.joints.len()).any(|m| model.mimic_master[m] == Some(k)) {
            return Err(unsupported(format!(
                "joint {} drives a mimic joint: its distal part does not move rigidly",
                model.urdf.joints[k].name
            )));
        }
        counts.segment_calls += 1;
        let poses = self.arm.link_poses(q);
        // the distal links: the subtree below joint k
        let child = model.joint_links[k].1;
        let mut distal = vec![false; model.urdf.links.len()];
        distal[child] = true;
        for &j in &model.order {
            let (p, c) = model.joint_links[j];
            if distal[p] {
                distal[c] = true;
            }
        }
        let world: Vec<Option<TriMesh>> = self
            .link_meshes
            .iter()
            .zip(&poses)
            .map(|(m, p)| m.as_ref().map(|m| placed(m, p)))
            .collect();
        let whole = || IntervalList::single(Interval::UNIT);
        // pairs whose relative pose the move keeps: all of [0, 1] or nothing
        for &(a, b) in &self.arm.self_pairs {
            if distal[a] != distal[b] {
                continue;
            }
            if let (Some(ma), Some(mb)) = (&world[a], &world[b]) {
                if Self::meet(ma.clone(), mb.clone(), counts) {
                    return Ok(whole());
                }
            }
        }
        for l in (0..world.len()).filter(|&l| !distal[l]) {
            if let Some(m) = &world[l] {
                if self.in_environment(m.clone(), counts) {
                    return Ok(whole());
                }
            }
        }
        // the moving part, link by link, in the joint's child frame at q
        let frame = poses[child];
        let axis_world = frame.rotation * model.urdf.joints[k].axis.into_inner();
        let change = match model.urdf.joints[k].kind {
            JointKind::Revolute { .. } | JointKind::Continuous => Change::Rotation {
                axis: [axis_world.x, axis_world.y, axis_world.z],
                angle: delta,
            },
            JointKind::Prismatic { .. } => {
                let d = axis_world * delta;
                Change::Linear(vec![d.x, d.y, d.z, 0.0, 0.0, 0.0, 0.0])
            }
            JointKind::Fixed => return Err(unsupported("a fixed joint does not move".into())),
        };
        let motion = Motion::segment(se3(&frame), change);
        let to_frame = frame.inverse();
        let mut answer = IntervalList::new();
        for l in (0..world.len()).filter(|&l| distal[l]) {
            let Some(mesh) = &self.link_meshes[l] else {
                continue;
            };
            let body = placed(mesh, &(to_frame * poses[l]));
            let mut obstacles = self.environment.clone();
            obstacles.extend(
                (0..world.len())
                    .filter(|&m| !distal[m] && !self.exempt(l, m))
                    .filter_map(|m| world[m].clone()),
            );
            if obstacles.is_empty() {
                continue;
            }
            let hits = Polyhedra::new(body, obstacles)
                .intervals(&motion, counts)
                .map_err(|OracleError::Unsupported(m)| unsupported(m))?;
            answer = answer.union(&hits);
        }
        Ok(answer)
    }
}
