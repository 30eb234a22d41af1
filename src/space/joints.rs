//! The joint space of a robot arm's planning group.
//!
//! A configuration is the group's joint values in group order, one number per joint. Joint
//! limits are the bounds (outside them counts as obstacle, as for R^n). Every joint is a DOF
//! group of its own: moving one revolute joint turns the whole distal part rigidly about an
//! axis fixed in the world, which the exact oracle answers like the seed's rotation about a
//! fixed axis (CHS §2.3.2), and the via-point planner's separate degrees of freedom (CHS §1.5,
//! Fig 1.6: one group per joint, dodging into the others) become "one link moves at a time"
//! (seed l. 438/497).
//!
//! Continuous joints have no limits: their coordinate wraps into `[-π, π)` and moves the
//! shorter way round, like SE(2)'s angle. The distance is the plain Euclidean one over the
//! joint values (with the wrapped difference for continuous joints): the same metric OMPL's
//! real-vector joint spaces and the arm checker's sampling use, so that resolutions compare.

use super::rotation::wrap_angle;
use super::types::{Space, SpaceError, SpaceKind};
use std::f64::consts::PI;

/// The most joints a joint space has: continuous joints are kept as a 64-bit set.
pub const MAX_JOINTS: usize = 64;

/// Whether bit `i` of `set` is set.
#[inline]
pub fn bit(set: u64, i: usize) -> bool {
    i < 64 && set >> i & 1 == 1
}

/// Wraps the continuous joints' values into `[-π, π)`.
pub fn wrap_continuous(continuous: u64, q: &mut [f64]) {
    if continuous == 0 {
        return;
    }
    for (i, v) in q.iter_mut().enumerate() {
        if bit(continuous, i) {
            *v = wrap_angle(*v);
        }
    }
}

/// The change of joint `i` from `a` to `b`: the shorter way round for a continuous joint.
#[inline]
fn diff(continuous: u64, i: usize, a: f64, b: f64) -> f64 {
    if bit(continuous, i) {
        wrap_angle(b - a)
    } else {
        b - a
    }
}

/// Euclidean distance of two joint vectors, continuous joints the shorter way round.
pub fn distance(continuous: u64, a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .enumerate()
        .map(|(i, (x, y))| {
            let d = diff(continuous, i, *x, *y);
            d * d
        })
        .sum::<f64>()
        .sqrt()
}

/// All joints at once, linearly (continuous joints the shorter way round, wrapped).
pub fn interpolate(continuous: u64, a: &[f64], b: &[f64], t: f64) -> Vec<f64> {
    let mut q: Vec<f64> = a
        .iter()
        .zip(b)
        .enumerate()
        .map(|(i, (x, y))| x + t * diff(continuous, i, *x, *y))
        .collect();
    wrap_continuous(continuous, &mut q);
    q
}

/// A point whose Euclidean distances bound [`distance`] from below: the joint values, a
/// continuous joint as `(cos θ, sin θ)` (a chord is never longer than its arc).
pub fn embedding(continuous: u64, q: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(q.len() + continuous.count_ones() as usize);
    for (i, &v) in q.iter().enumerate() {
        if bit(continuous, i) {
            out.push(v.cos());
            out.push(v.sin());
        } else {
            out.push(v);
        }
    }
    out
}

impl Space {
    /// The joint space of a planning group: `lower`/`upper` are the joint limits in group
    /// order; `continuous[i]` marks a joint without limits (its bounds are ignored and
    /// recorded as `[-π, π]`). At least two joints: a single joint leaves the via-point
    /// planner no other group to dodge into.
    pub fn joints(
        lower: Vec<f64>,
        upper: Vec<f64>,
        continuous: &[bool],
    ) -> Result<Space, SpaceError> {
        let n = lower.len();
        if !(2..=MAX_JOINTS).contains(&n) {
            return Err(SpaceError::Bounds(format!(
                "a joint space needs 2 to {MAX_JOINTS} joints, got {n}"
            )));
        }
        if continuous.len() != n || upper.len() != n {
            return Err(SpaceError::Bounds(format!(
                "{n} lower limits, {} upper limits and {} continuity flags",
                upper.len(),
                continuous.len()
            )));
        }
        let mut set = 0u64;
        let (mut lower, mut upper) = (lower, upper);
        for (i, &c) in continuous.iter().enumerate() {
            if c {
                set |= 1 << i;
                lower[i] = -PI;
                upper[i] = PI;
            }
        }
        Space::build(
            SpaceKind::Joints {
                dof: n,
                continuous: set,
            },
            lower,
            upper,
            1.0,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::GroupKind;

    fn space() -> Space {
        Space::joints(
            vec![-1.0, -2.0, 0.0],
            vec![1.0, 2.0, 0.0],
            &[false, false, true],
        )
        .unwrap()
    }

    #[test]
    fn one_group_per_joint_continuous_ones_wrap() {
        let s = space();
        for split in [false, true] {
            let g = s.groups(split);
            assert_eq!(g.len(), 3);
            assert_eq!(g[0].kind, GroupKind::Linear);
            assert_eq!(g[2].kind, GroupKind::Angle);
            assert_eq!(g[2].coords, 2..3);
        }
        // the continuous joint: no bounds, the shorter way round
        assert!(s.in_bounds(&[0.0, 0.0, 7.0]));
        assert!(!s.in_bounds(&[1.5, 0.0, 0.0]));
        let (a, b) = ([0.0, 0.0, 3.0], [0.0, 0.0, -3.0]);
        assert!((s.distance(&a, &b) - (2.0 * PI - 6.0)).abs() < 1e-12);
        let g = &s.groups(false)[2];
        let m = s.group_motion(&a, &b, g);
        let mut end = m.at(1.0);
        s.normalize(&mut end);
        assert!((end[2] - wrap_angle(-3.0)).abs() < 1e-12);
        assert!((s.motion_length(&m, 0.0, 1.0) - s.distance(&a, &b)).abs() < 1e-12);
        // a turn of the continuous joint is never clipped by the bounds
        let turn = s.turn_through(&a, g, [0.0, 0.0, 1.0]);
        assert_eq!(s.inside_range(&turn), Some(turn.range));
    }

    #[test]
    fn embedding_bounds_the_distance_from_below() {
        let s = space();
        crate::space::assert_embedding_below_distance(&s, 5);
    }

    #[test]
    fn bad_joint_spaces_are_refused() {
        assert!(Space::joints(vec![0.0], vec![1.0], &[false]).is_err());
        assert!(Space::joints(vec![0.0, 0.0], vec![1.0, 0.0], &[false, false]).is_err());
        assert!(Space::joints(vec![0.0, 0.0], vec![1.0, 1.0], &[false]).is_err());
        assert!(Space::joints(vec![0.0, 0.0], vec![1.0, 0.0], &[false, true]).is_ok());
    }
}
