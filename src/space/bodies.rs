//! SE(2)^k: several rigid bodies moving in the plane at once (CHS Chapter 2, "concurrently
//! moving objects").
//!
//! A configuration is the bodies' poses concatenated in their order,
//! `[x₀, y₀, θ₀, x₁, y₁, θ₁, …]`. The seed's motion model fixes the DOF groups: "at a given
//! time either one object may rotate about a fixed axis with constant angular velocity or all
//! may translate simultaneously, each with its own fixed speed and direction". So there is one
//! translation group — every body's `(x, y)`, a [`Group`] that repeats the run `0..2` with
//! stride 3 — and one angle group per body. With split axes the translation splits into "all
//! bodies move along x" and "all bodies move along y", each body by its own amount.
//!
//! Every reference point is bounded by the same box of the plane; the angles wrap into
//! `[-π, π)` and are the space's [`wrapping`](Space::wrapping) coordinates. The distance is the
//! sum over the bodies of their SE(2) distances, `‖Δp‖ + s·|Δθ|`: the total length the bodies'
//! reference points travel plus their turning, so a motion's length is the same sum.

use super::rotation::wrap_angle;
use super::types::{Group, GroupKind, Space, SpaceError, SpaceKind};
use std::f64::consts::PI;

/// The most bodies a space of several bodies holds: their angles are kept as a 64-bit set,
/// and beyond this many the quadratic number of body pairs dominates every call.
pub const MAX_BODIES: usize = 16;

/// The bit set of the angle coordinates `3i + 2` of `k` bodies.
pub fn angle_bits(k: usize) -> u64 {
    (0..k.min(MAX_BODIES)).fold(0, |set, i| set | 1 << (3 * i + 2))
}

impl Space {
    /// `bodies` rigid bodies in the plane, every reference point inside the box
    /// `[lower, upper]`; `rotation_scale` is the length one radian of turning counts as (the
    /// largest body's radius, for a scene).
    pub fn se2_bodies(
        bodies: usize,
        lower: [f64; 2],
        upper: [f64; 2],
        rotation_scale: f64,
    ) -> Result<Space, SpaceError> {
        if !(1..=MAX_BODIES).contains(&bodies) {
            return Err(SpaceError::Bounds(format!(
                "a space of several bodies holds 1 to {MAX_BODIES} bodies, got {bodies}"
            )));
        }
        let mut lo = Vec::with_capacity(3 * bodies);
        let mut hi = Vec::with_capacity(3 * bodies);
        for _ in 0..bodies {
            lo.extend_from_slice(&[lower[0], lower[1], -PI]);
            hi.extend_from_slice(&[upper[0], upper[1], PI]);
        }
        Space::build(SpaceKind::Se2Bodies(bodies), lo, hi, rotation_scale)
    }

    /// Number of bodies: `k` for SE(2)^k, 1 for a space of one rigid body or a point.
    pub fn body_count(&self) -> usize {
        match self.kind {
            SpaceKind::Se2Bodies(k) | SpaceKind::Se3Bodies(k) => k,
            _ => 1,
        }
    }

    /// The coordinates of body `body` in a configuration: the poses are concatenated in body
    /// order, each of `dim / body_count` numbers.
    pub fn body_coords(&self, body: usize) -> std::ops::Range<usize> {
        let per = self.dim() / self.body_count().max(1);
        per * body..per * (body + 1)
    }

    /// Whether body `body`'s pose in `q` lies inside the bounds (its wrapping angles always do).
    pub fn body_in_bounds(&self, q: &[f64], body: usize) -> bool {
        let wraps = self.wrapping();
        self.body_coords(body).all(|i| {
            let (v, l, u) = (q.get(i), self.lower.get(i), self.upper.get(i));
            match (v, l, u) {
                (Some(v), Some(l), Some(u)) => (l <= v && v <= u) || super::joints::bit(wraps, i),
                _ => false,
            }
        })
    }
}

/// The groups of `k` bodies: the translation of all (or, with `split_axes`, one group per
/// axis), then one angle per body.
pub(super) fn groups_into(k: usize, split_axes: bool, groups: &mut Vec<Group>) {
    let translation = |coords| Group {
        kind: GroupKind::Linear,
        coords,
        stride: 3,
        repeats: k,
    };
    if split_axes {
        groups.push(translation(0..1));
        groups.push(translation(1..2));
    } else {
        groups.push(translation(0..2));
    }
    groups.extend((0..k).map(|i| Group::run(GroupKind::Angle, 3 * i + 2..3 * i + 3)));
}

/// The sum of the bodies' SE(2) distances.
pub(super) fn distance(scale: f64, a: &[f64], b: &[f64]) -> f64 {
    a.chunks_exact(3)
        .zip(b.chunks_exact(3))
        .map(|(p, q)| (q[0] - p[0]).hypot(q[1] - p[1]) + scale * wrap_angle(q[2] - p[2]).abs())
        .sum()
}

/// The length of a linear change of all coordinates over unit parameter, in the units of
/// [`distance`].
pub(super) fn change_length(scale: f64, delta: &[f64]) -> f64 {
    delta
        .chunks_exact(3)
        .map(|d| d[0].hypot(d[1]) + scale * d[2].abs())
        .sum()
}

/// The length of the group motion from `a` towards `z` in `group`.
pub(super) fn group_length(scale: f64, a: &[f64], z: &[f64], group: &Group) -> f64 {
    let mut delta = vec![0.0; a.len()];
    for i in group.indices() {
        delta[i] = match group.kind {
            GroupKind::Angle => wrap_angle(z[i] - a[i]),
            _ => z[i] - a[i],
        };
    }
    change_length(scale, &delta)
}

/// `[x, y, s·cos θ, s·sin θ]` of every body: Euclidean distances of these bound [`distance`]
/// from below (per body a chord is never longer than its arc, and the Euclidean norm of the
/// concatenation is at most the sum of the bodies' norms).
pub(super) fn embedding(scale: f64, q: &[f64]) -> Vec<f64> {
    q.chunks_exact(3)
        .flat_map(|p| [p[0], p[1], scale * p[2].cos(), scale * p[2].sin()])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_move_all_bodies_or_turn_one() {
        let s = Space::se2_bodies(3, [0.0, 0.0], [4.0, 1.0], 0.5).unwrap();
        let g = s.groups(false);
        assert_eq!(g.len(), 4);
        assert_eq!(g[0].indices().collect::<Vec<_>>(), [0, 1, 3, 4, 6, 7]);
        assert_eq!(g[2].indices().collect::<Vec<_>>(), [5]);
        let split = s.groups(true);
        assert_eq!(split[1].indices().collect::<Vec<_>>(), [1, 4, 7]);
        let a = [0.5, 0.5, 0.0, 1.5, 0.5, 1.0, 2.5, 0.5, -1.0];
        let z = [1.0, 0.2, 3.0, 1.0, 0.5, 0.0, 2.0, 0.9, 1.0];
        let m = s.group_motion(&a, &z, &g[0]);
        let end = m.at(1.0);
        assert_eq!(end, s.with_group_of(&a, &z, &g[0]));
        assert_eq!(end[2], 0.0);
        let len = s.motion_length(&m, 0.0, 1.0);
        assert!((len - s.distance(&a, &end)).abs() < 1e-12);
        assert!((len - s.group_length(&a, &z, &g[0])).abs() < 1e-12);
        // a turn of body 1 changes its angle only
        let turn = s.group_motion(&a, &z, &g[2]);
        let end = turn.at(1.0);
        assert_eq!(&end[..5], &a[..5]);
        assert_eq!(&end[6..], &a[6..]);
    }

    #[test]
    fn bounds_apply_to_positions_and_angles_wrap() {
        let s = Space::se2_bodies(2, [0.0, 0.0], [1.0, 1.0], 1.0).unwrap();
        assert!(s.in_bounds(&[0.5, 0.5, 9.0, 0.5, 0.5, -9.0]));
        assert!(!s.in_bounds(&[0.5, 0.5, 0.0, 1.5, 0.5, 0.0]));
        let mut q = vec![0.5, 0.5, 4.0, 0.5, 0.5, 0.0];
        s.normalize(&mut q);
        assert!((q[2] - (4.0 - 2.0 * PI)).abs() < 1e-12);
        assert!(Space::se2_bodies(0, [0.0; 2], [1.0; 2], 1.0).is_err());
        assert!(Space::se2_bodies(MAX_BODIES + 1, [0.0; 2], [1.0; 2], 1.0).is_err());
    }

    #[test]
    fn embedding_bounds_the_distance_from_below() {
        let s = Space::se2_bodies(3, [-1.0, -1.0], [1.0, 1.0], 0.7).unwrap();
        crate::space::assert_embedding_below_distance(&s, 9);
    }
}
