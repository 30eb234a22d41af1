//! The robot's placement at the start of a motion, and the box types every test works with.

use crate::geometry::kernel::{aabb, bvh, spans};
use crate::oracle::OracleError;
use crate::space::rotation::quat_from_slice;
use nalgebra::{Matrix3, Vector3};

/// A box in space (the kernel's).
pub(crate) type Aabb = aabb::Aabb<3>;
/// The face trees (the kernel's).
pub(crate) type Bvh = bvh::Bvh<3>;
/// The value of one edge–face predicate under rotation: more than the k + 1 = 7 pieces a
/// conjunction of six arcs can have.
pub(crate) type Spans = spans::Spans<8>;

pub(super) type V3 = Vector3<f64>;

/// The placement of the robot at the start of a motion: `x_world = rot · x_body + pos`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pose {
    pub(super) pos: V3,
    pub(super) rot: Matrix3<f64>,
}

impl Pose {
    pub(super) fn from_config(q: &[f64]) -> Result<Pose, OracleError> {
        if q.len() != 7 {
            return Err(OracleError::Unsupported(format!(
                "polyhedra: an SE(3) configuration has 7 coordinates, got {}",
                q.len()
            )));
        }
        if !q.iter().all(|c| c.is_finite()) {
            return Err(OracleError::Unsupported(
                "polyhedra: configuration with a coordinate that is not finite".into(),
            ));
        }
        let n2: f64 = q[3..7].iter().map(|c| c * c).sum();
        if n2 < 1e-24 {
            return Err(OracleError::Unsupported(
                "polyhedra: quaternion of zero length".into(),
            ));
        }
        let rot = *quat_from_slice(&q[3..7]).to_rotation_matrix().matrix();
        Ok(Pose {
            pos: V3::new(q[0], q[1], q[2]),
            rot,
        })
    }

    /// World point → body frame at this pose.
    pub(super) fn body_point(&self, w: &V3) -> V3 {
        self.rot.tr_mul(&(w - self.pos))
    }

    /// Body point → world.
    pub(super) fn world_point(&self, v: &V3) -> V3 {
        self.rot * v + self.pos
    }

    /// World direction → body frame.
    pub(super) fn body_dir(&self, d: &V3) -> V3 {
        self.rot.tr_mul(d)
    }

    /// The world box around a body-frame box placed at this pose.
    pub(super) fn world_box(&self, b: &Aabb) -> Aabb {
        if b.is_empty() {
            return *b;
        }
        let c = self.world_point(&b.centre());
        let h = self.rot.abs() * (0.5 * (b.hi - b.lo));
        Aabb {
            lo: c - h,
            hi: c + h,
        }
    }

    /// The body-frame box around a world box.
    pub(super) fn body_box(&self, b: &Aabb) -> Aabb {
        if b.is_empty() {
            return *b;
        }
        let c = self.body_point(&b.centre());
        let h = self.rot.transpose().abs() * (0.5 * (b.hi - b.lo));
        Aabb {
            lo: c - h,
            hi: c + h,
        }
    }
}
