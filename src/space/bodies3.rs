//! SE(3)^k: several rigid bodies moving in space at once (CHS Chapter 2, "concurrently moving
//! objects"), the spatial twin of [`super::bodies`].
//!
//! A configuration is the bodies' SE(3) poses concatenated in their order,
//! `[x₀, y₀, z₀, qx₀, qy₀, qz₀, qw₀, x₁, …]`, each pose in OMPL's layout as for one rigid body.
//! The seed's motion model fixes the DOF groups: "at a given time either one object may rotate
//! about a fixed axis with constant angular velocity or all may translate simultaneously, each
//! with its own fixed speed and direction". So there is one translation group — every body's
//! `(x, y, z)`, a [`Group`] that repeats the run `0..3` with stride 7 — and one quaternion
//! group per body, whose straight motion is a turn about one fixed axis through the body's
//! reference point ([`Change::BodyRotation`]), as the one SE(3) body's orientation group. With
//! split axes the translation splits into "all bodies move along x", "… along y", "… along z".
//!
//! Every reference point is bounded by the same box; the quaternion coordinates carry the
//! bounds `[-1, 1]` and are the space's [`wrapping`](Space::wrapping) coordinates (unbounded:
//! a bit set of 64 coordinates, hence at most [`MAX_SOLID_BODIES`] bodies). The distance is
//! the sum over the bodies of their SE(3) distances, `‖Δp‖ + s·angle`: the total length the
//! reference points travel plus their turning, so a motion's length is the same sum.

use super::motion::Change;
use super::rotation;
use super::types::{Group, GroupKind, Space, SpaceError, SpaceKind};
use rand::Rng;
use std::f64::consts::TAU;

/// The most bodies a space of several SE(3) bodies holds: its 7 coordinates per body must fit
/// the 64-bit set of [`Space::wrapping`].
pub const MAX_SOLID_BODIES: usize = 9;

/// Coordinates per body.
pub const POSE: usize = 7;

/// The bit set of the quaternion coordinates `7i + 3 .. 7i + 7` of `k` bodies.
pub fn quaternion_bits(k: usize) -> u64 {
    (0..k.min(MAX_SOLID_BODIES)).fold(0, |set, i| set | (0b1111 << (POSE * i + 3)))
}

impl Space {
    /// `bodies` rigid bodies in space, every reference point inside the box `[lower, upper]`;
    /// `rotation_scale` is the length one radian of turning counts as (the largest body's
    /// radius, for a scene).
    pub fn se3_bodies(
        bodies: usize,
        lower: [f64; 3],
        upper: [f64; 3],
        rotation_scale: f64,
    ) -> Result<Space, SpaceError> {
        if !(1..=MAX_SOLID_BODIES).contains(&bodies) {
            return Err(SpaceError::Bounds(format!(
                "a space of several SE(3) bodies holds 1 to {MAX_SOLID_BODIES} bodies, got \
                 {bodies}"
            )));
        }
        let mut lo = Vec::with_capacity(POSE * bodies);
        let mut hi = Vec::with_capacity(POSE * bodies);
        for _ in 0..bodies {
            lo.extend_from_slice(&lower);
            lo.extend_from_slice(&[-1.0; 4]);
            hi.extend_from_slice(&upper);
            hi.extend_from_slice(&[1.0; 4]);
        }
        Space::build(SpaceKind::Se3Bodies(bodies), lo, hi, rotation_scale)
    }
}

/// The groups of `k` bodies: the translation of all (or, with `split_axes`, one group per
/// axis), then one orientation per body.
pub(super) fn groups_into(k: usize, split_axes: bool, groups: &mut Vec<Group>) {
    let translation = |coords| Group {
        kind: GroupKind::Linear,
        coords,
        stride: POSE,
        repeats: k,
    };
    if split_axes {
        groups.extend((0..3).map(|a| translation(a..a + 1)));
    } else {
        groups.push(translation(0..3));
    }
    groups.extend((0..k).map(|i| Group::run(GroupKind::Quaternion, POSE * i + 3..POSE * i + 7)));
}

/// The turn of the body whose quaternion `group` holds about `axis` by `angle`.
pub(super) fn turn(group: &Group, axis: [f64; 3], angle: f64) -> Change {
    Change::BodyRotation {
        body: group.coords.start / POSE,
        axis,
        angle,
    }
}

/// The axis and angle that take the orientation of `group`'s body in `a` to that in `z`.
pub(super) fn relative_turn(a: &[f64], z: &[f64], group: &Group) -> ([f64; 3], f64) {
    let c = group.coords.clone();
    let qa = rotation::quat_from_slice(&a[c.clone()]);
    let qz = rotation::quat_from_slice(&z[c]);
    rotation::relative_axis_angle(&qa, &qz)
}

/// The sum of the bodies' SE(3) distances.
pub(super) fn distance(scale: f64, a: &[f64], b: &[f64]) -> f64 {
    a.chunks_exact(POSE)
        .zip(b.chunks_exact(POSE))
        .map(|(p, q)| {
            let d = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2);
            d.sqrt() + scale * rotation::rotation_angle(&p[3..7], &q[3..7])
        })
        .sum()
}

/// The length of a translation of all bodies by `delta` over unit parameter (its quaternion
/// entries are zero for the space's motions and count for nothing).
pub(super) fn change_length(delta: &[f64]) -> f64 {
    delta
        .chunks_exact(POSE)
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .sum()
}

/// The length of the group motion from `a` towards `z` in `group`.
pub(super) fn group_length(scale: f64, a: &[f64], z: &[f64], group: &Group) -> f64 {
    match group.kind {
        GroupKind::Quaternion => scale * relative_turn(a, z, group).1.abs(),
        _ => {
            let mut delta = vec![0.0; a.len()];
            for i in group.indices() {
                delta[i] = z[i] - a[i];
            }
            change_length(&delta)
        }
    }
}

/// Per body `[x, y, z]` and the rotation matrix's nine entries times `s/√2`: the Frobenius
/// distance of two rotation matrices is `2√2·sin(θ/2) ≤ √2·θ`, so per body the Euclidean
/// distance of these bounds `‖Δp‖ + s·θ` from below, and the norm of the concatenation is at
/// most the sum of the bodies' norms. (Quaternions would need both signs of each body's, 2^k
/// points per configuration.)
pub(super) fn embedding(scale: f64, q: &[f64]) -> Vec<f64> {
    let w = scale / std::f64::consts::SQRT_2;
    let mut out = Vec::with_capacity(12 * q.len() / POSE);
    for p in q.chunks_exact(POSE) {
        out.extend_from_slice(&p[..3]);
        let m = rotation::quat_from_slice(&p[3..7]).to_rotation_matrix();
        out.extend(m.matrix().iter().map(|v| w * v));
    }
    out
}

/// Embedding coordinates per body.
pub const EMBEDDING: usize = 12;

/// Every body's position linearly, its orientation by slerp (what one SE(3) body does).
pub(super) fn interpolate(a: &[f64], b: &[f64], t: f64) -> Vec<f64> {
    let mut q = vec![0.0; a.len()];
    for ((out, p), r) in q
        .chunks_exact_mut(POSE)
        .zip(a.chunks_exact(POSE))
        .zip(b.chunks_exact(POSE))
    {
        for i in 0..3 {
            out[i] = p[i] + t * (r[i] - p[i]);
        }
        let qa = rotation::quat_from_slice(&p[3..7]);
        let mut qb = rotation::quat_from_slice(&r[3..7]);
        if qa.coords.dot(&qb.coords) < 0.0 {
            qb = nalgebra::UnitQuaternion::new_unchecked(-qb.into_inner());
        }
        let s = qa.try_slerp(&qb, t, 1e-12).unwrap_or(qa);
        rotation::quat_to_slice(&s, &mut out[3..7]);
    }
    q
}

/// Every body's quaternion scaled to unit length.
pub(super) fn normalize(q: &mut [f64]) {
    for p in q.chunks_exact_mut(POSE) {
        let n = p[3..7].iter().map(|v| v * v).sum::<f64>().sqrt();
        if n > 0.0 {
            p[3..7].iter_mut().for_each(|v| *v /= n);
        }
    }
}

/// The first body whose quaternion has (almost) zero length, and that length.
pub(super) fn degenerate_quaternion(q: &[f64]) -> Option<f64> {
    q.chunks_exact(POSE)
        .map(|p| p[3..7].iter().map(|v| v * v).sum::<f64>().sqrt())
        .find(|n| *n < 1e-9)
}

/// Overwrites every body's quaternion by a uniformly random rotation (Shoemake's method).
pub(super) fn sample_orientations<R: Rng + ?Sized>(q: &mut [f64], rng: &mut R) {
    for p in q.chunks_exact_mut(POSE) {
        let (u1, u2, u3): (f64, f64, f64) = (rng.random(), rng.random(), rng.random());
        let (s1, s2) = ((1.0 - u1).sqrt(), u1.sqrt());
        p[3..7].copy_from_slice(&[
            s1 * (TAU * u2).sin(),
            s1 * (TAU * u2).cos(),
            s2 * (TAU * u3).sin(),
            s2 * (TAU * u3).cos(),
        ]);
    }
}

/// Near `mean`'s orientations: every body turned by a random rotation vector with isotropic
/// normal components (RMS angle `angle_sigma`, drawn by `normal`), or a uniform orientation
/// where `angle_sigma` exceeds a quarter turn (what the sampler does for one SE(3) body).
/// Positions are left as they are in `q`.
pub fn perturb_orientations<R: Rng + ?Sized>(
    q: &mut [f64],
    mean: &[f64],
    angle_sigma: f64,
    rng: &mut R,
    normal: impl Fn(&mut R) -> f64,
) {
    if angle_sigma > std::f64::consts::FRAC_PI_2 {
        sample_orientations(q, rng);
        return;
    }
    let s = angle_sigma / 3f64.sqrt();
    for (p, m) in q.chunks_exact_mut(POSE).zip(mean.chunks_exact(POSE)) {
        let v = nalgebra::Vector3::new(s * normal(rng), s * normal(rng), s * normal(rng));
        let r = nalgebra::UnitQuaternion::from_scaled_axis(v) * rotation::quat_from_slice(&m[3..7]);
        rotation::quat_to_slice(&r, &mut p[3..7]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn groups_move_all_bodies_or_turn_one() {
        let s = Space::se3_bodies(2, [-2.0; 3], [2.0; 3], 0.5).unwrap();
        let g = s.groups(false);
        assert_eq!(g.len(), 3);
        assert_eq!(g[0].indices().collect::<Vec<_>>(), [0, 1, 2, 7, 8, 9]);
        assert_eq!(g[2].indices().collect::<Vec<_>>(), [10, 11, 12, 13]);
        assert_eq!(s.groups(true).len(), 5);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        for _ in 0..50 {
            let a = s.sample_uniform(&mut rng);
            let z = s.sample_uniform(&mut rng);
            for gr in &g {
                let m = s.group_motion(&a, &z, gr);
                let end = m.at(1.0);
                let want = s.with_group_of(&a, &z, gr);
                assert!(s.distance(&end, &want) < 1e-9, "{gr:?}");
                let len = s.motion_length(&m, 0.0, 1.0);
                assert!((len - s.distance(&a, &end)).abs() < 1e-9);
                assert!((len - s.group_length(&a, &z, gr)).abs() < 1e-9);
            }
            // turning body 1 leaves body 0 alone
            let end = s.group_motion(&a, &z, &g[2]).at(0.7);
            assert_eq!(&end[..10], &a[..10]);
        }
    }

    #[test]
    fn checks_bounds_and_quaternions() {
        let s = Space::se3_bodies(2, [0.0; 3], [1.0; 3], 1.0).unwrap();
        let q = [
            0.5, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0, 0.5, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0,
        ];
        assert!(s.in_bounds(&q));
        let mut out = q;
        out[8] = 1.5;
        assert!(!s.in_bounds(&out));
        let mut zero = q;
        zero[10..14].copy_from_slice(&[0.0; 4]);
        assert!(matches!(s.check(&zero), Err(SpaceError::Quaternion(_))));
        assert!(matches!(
            s.check(&q[..13]),
            Err(SpaceError::Dimension { .. })
        ));
        let mut long = q;
        long[3..7].copy_from_slice(&[0.0, 0.0, 0.0, 2.0]);
        s.normalize(&mut long);
        assert_eq!(long[6], 1.0);
        assert!(Space::se3_bodies(0, [0.0; 3], [1.0; 3], 1.0).is_err());
        assert!(Space::se3_bodies(MAX_SOLID_BODIES + 1, [0.0; 3], [1.0; 3], 1.0).is_err());
    }

    #[test]
    fn embedding_bounds_the_distance_from_below() {
        let s = Space::se3_bodies(3, [-1.0; 3], [1.0; 3], 0.7).unwrap();
        for (a, b) in crate::space::assert_embedding_below_distance(&s, 9) {
            let mid = s.interpolate(&a, &b, 0.5);
            assert!(s.distance(&a, &mid) <= s.distance(&a, &b) + 1e-9);
        }
    }
}
