//! Straight motions in configuration space: what the collision oracle is asked about.
//!
//! A motion is a configuration at `t = 0` plus a rule for how it changes with `t`, and the
//! parameter range that is asked about: `[0, 1]` for a bounded motion (CHS *intersectSegment*),
//! the whole line for an unbounded one (*intersectLine*), `[-½, ½]` for a full turn (the
//! rotational borderline of CHS §2.3.1).

use super::rotation;
use super::types::{extend_small, Config};
use crate::interval::Interval;
use serde::{Deserialize, Serialize};

/// How a configuration changes along a motion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Change {
    /// Every coordinate moves linearly: `q(t)[i] = q(0)[i] + t · delta[i]`. `delta` has one entry
    /// per coordinate of the space. This covers R^n motions, translations of rigid bodies
    /// (zero entries on orientation coordinates) and SE(2) turns (non-zero only on θ).
    Linear(Vec<f64>),
    /// An SE(3) rigid body turns about the world-frame unit `axis` through its reference point
    /// by `t · angle` radians: `orientation(t) = R(axis, t · angle) · orientation(0)`; the
    /// position (coordinates 0..3) stays fixed. Acts on the quaternion at coordinates 3..7 in
    /// OMPL's order `(qx, qy, qz, qw)`.
    Rotation {
        /// Unit axis of rotation in the world frame.
        axis: [f64; 3],
        /// Angle in radians turned between `t = 0` and `t = 1`.
        angle: f64,
    },
    /// One of several SE(3) bodies turns about the world-frame unit `axis` through its
    /// reference point by `t · angle` radians; every other coordinate stays fixed. Acts on body
    /// `body`'s quaternion, coordinates `7·body + 3..7·body + 7` (see
    /// [`crate::space::bodies3`]); [`Change::Rotation`] is body 0 of one.
    BodyRotation {
        /// The turning body, in configuration order.
        body: usize,
        /// Unit axis of rotation in the world frame.
        axis: [f64; 3],
        /// Angle in radians turned between `t = 0` and `t = 1`.
        angle: f64,
    },
}

/// What kind of question a motion asks; decides how the call is counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Sweep {
    /// A bounded motion, `t ∈ [0, 1]` (intersectSegment).
    Segment,
    /// An unbounded straight line, `t ∈ ℝ` (intersectLine).
    Line,
    /// A full turn, `t ∈ [-½, ½]` with both ends the same configuration (a rotational
    /// borderline).
    Turn,
}

/// A straight motion through configuration space and the parameter range asked about.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Motion {
    /// Configuration at `t = 0`.
    pub origin: Config,
    /// How the configuration changes with `t`.
    pub change: Change,
    /// The parameter range asked about. Collision intervals are clipped to it.
    pub range: Interval,
    /// What kind of question this is.
    pub sweep: Sweep,
}

/// A segment of no coordinates: a slot to be overwritten by the `*_into` builders of
/// [`Space`](super::Space) (the via-point search keeps such slots).
impl Default for Motion {
    fn default() -> Self {
        Motion::segment(Vec::new(), Change::Linear(Vec::new()))
    }
}

impl Motion {
    /// The bounded motion `t ∈ [0, 1]`.
    pub fn segment(origin: Config, change: Change) -> Motion {
        Motion {
            origin,
            change,
            range: Interval::UNIT,
            sweep: Sweep::Segment,
        }
    }

    /// The unbounded motion `t ∈ ℝ` through `origin`.
    pub fn line(origin: Config, change: Change) -> Motion {
        Motion {
            origin,
            change,
            range: Interval::ALL,
            sweep: Sweep::Line,
        }
    }

    /// A full turn: `change` must turn by `2π` over unit `t`; asks about `t ∈ [-½, ½]`.
    pub fn turn(origin: Config, change: Change) -> Motion {
        Motion {
            origin,
            change,
            range: Interval { lo: -0.5, hi: 0.5 },
            sweep: Sweep::Turn,
        }
    }

    /// The same motion asked about a narrower range (used to clip lines to the space's bounds).
    pub fn with_range(&self, range: Interval) -> Motion {
        Motion {
            range,
            ..self.clone()
        }
    }

    /// Overwrites `self` with `other`, keeping `self`'s buffers where the kinds of change
    /// agree (the allocation-free hot path).
    pub fn copy_from(&mut self, other: &Motion) {
        self.origin.clear();
        extend_small(&mut self.origin, &other.origin);
        match (&mut self.change, &other.change) {
            (Change::Linear(mine), Change::Linear(theirs)) => {
                mine.clear();
                mine.extend_from_slice(theirs);
            }
            (mine, theirs) => mine.clone_from(theirs),
        }
        self.range = other.range;
        self.sweep = other.sweep;
    }

    /// Resets `self` to a linear motion from `origin` with a zero `delta` (one entry per
    /// coordinate), reusing the buffers, and hands out the delta to be filled in.
    pub(crate) fn reset_linear(
        &mut self,
        origin: &[f64],
        range: Interval,
        sweep: Sweep,
    ) -> &mut [f64] {
        self.origin.clear();
        extend_small(&mut self.origin, origin);
        self.range = range;
        self.sweep = sweep;
        if !matches!(self.change, Change::Linear(_)) {
            self.change = Change::Linear(Vec::with_capacity(origin.len()));
        }
        match &mut self.change {
            Change::Linear(delta) => {
                delta.clear();
                delta.resize(origin.len(), 0.0);
                delta
            }
            Change::Rotation { .. } | Change::BodyRotation { .. } => {
                unreachable!("set to linear just above")
            }
        }
    }

    /// Resets `self` to a rotation from `origin`, reusing the origin's buffer.
    pub(crate) fn reset_rotation(
        &mut self,
        origin: &[f64],
        axis: [f64; 3],
        angle: f64,
        range: Interval,
        sweep: Sweep,
    ) {
        self.origin.clear();
        extend_small(&mut self.origin, origin);
        self.range = range;
        self.sweep = sweep;
        self.change = Change::Rotation { axis, angle };
    }

    /// Resets `self` to a motion of `change` from `origin`, reusing the origin's buffer.
    pub(crate) fn reset_change(
        &mut self,
        origin: &[f64],
        change: Change,
        range: Interval,
        sweep: Sweep,
    ) {
        self.origin.clear();
        extend_small(&mut self.origin, origin);
        self.range = range;
        self.sweep = sweep;
        self.change = change;
    }

    /// The configuration at parameter `t` (not normalised: SE(2) angles are not wrapped).
    pub fn at(&self, t: f64) -> Config {
        let mut q = self.origin.clone();
        self.write_at(t, &mut q);
        q
    }

    /// Allocation-free twin of [`at`](Self::at): overwrites `out` (which must have the
    /// origin's length) with the configuration at `t`.
    pub fn write_at(&self, t: f64, out: &mut [f64]) {
        match &self.change {
            Change::Linear(delta) => {
                for ((o, &q0), &d) in out.iter_mut().zip(&self.origin).zip(delta) {
                    *o = q0 + t * d;
                }
            }
            Change::Rotation { axis, angle } => {
                out.copy_from_slice(&self.origin);
                let q0 = rotation::quat_from_slice(&self.origin[3..7]);
                let q = rotation::axis_angle(*axis, t * angle) * q0;
                rotation::quat_to_slice(&q, &mut out[3..7]);
            }
            Change::BodyRotation { body, axis, angle } => {
                out.copy_from_slice(&self.origin);
                let c = 7 * body + 3..7 * body + 7;
                let q0 = rotation::quat_from_slice(&self.origin[c.clone()]);
                let q = rotation::axis_angle(*axis, t * angle) * q0;
                rotation::quat_to_slice(&q, &mut out[c]);
            }
        }
    }

    /// The translational velocity of the robot's reference point (position coordinates
    /// `0..position_dim`) per unit `t`; zero for rotations.
    pub fn translation_rate(&self, position_dim: usize) -> &[f64] {
        match &self.change {
            Change::Linear(delta) => &delta[..position_dim],
            Change::Rotation { .. } | Change::BodyRotation { .. } => &[],
        }
    }
}
