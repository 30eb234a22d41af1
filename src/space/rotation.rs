//! Unit quaternions for SE(3) orientations (CHS §2.3.1).
//!
//! Configurations store quaternions in OMPL's order `(qx, qy, qz, qw)`; `q` and `-q` are the
//! same rotation. A straight rotational motion is a rotation about one fixed axis, i.e. an arc of
//! a great circle on S³; perpendicular dodging uses great circles whose axes are perpendicular
//! (CHS Lemma 2.2).

use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};

/// Reads `(qx, qy, qz, qw)` into a unit quaternion (renormalised).
pub fn quat_from_slice(q: &[f64]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q[3], q[0], q[1], q[2]))
}

/// Writes `(qx, qy, qz, qw)`.
pub fn quat_to_slice(q: &UnitQuaternion<f64>, out: &mut [f64]) {
    out[0] = q.i;
    out[1] = q.j;
    out[2] = q.k;
    out[3] = q.w;
}

/// Rotation by `angle` radians about the unit `axis`.
pub fn axis_angle(axis: [f64; 3], angle: f64) -> UnitQuaternion<f64> {
    let axis = Unit::new_unchecked(Vector3::from(axis));
    UnitQuaternion::from_axis_angle(&axis, angle)
}

/// The rotation taking orientation `a` to orientation `z` along the shorter great-circle arc,
/// as a world-frame axis and an angle in `[0, π]`: `z = R(axis, angle) · a` (up to sign).
/// For equal orientations the axis is `x` and the angle `0`.
pub fn relative_axis_angle(a: &UnitQuaternion<f64>, z: &UnitQuaternion<f64>) -> ([f64; 3], f64) {
    let mut r = z * a.inverse();
    if r.w < 0.0 {
        r = UnitQuaternion::new_unchecked(-r.into_inner());
    }
    match r.axis_angle() {
        Some((axis, angle)) => ([axis.x, axis.y, axis.z], angle),
        None => ([1.0, 0.0, 0.0], 0.0),
    }
}

/// Angle of the rotation between two orientations, in `[0, π]` (twice the quaternion arc
/// `acos |a·z|`, which is what OMPL's SO(3) metric reports). Computed as
/// `4·atan2(min(|a-z|, |a+z|), max(…))`, which stays accurate for nearby orientations where
/// `acos` loses half the digits.
pub fn rotation_angle(a: &[f64], z: &[f64]) -> f64 {
    let na = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]).sqrt();
    let nz = (z[0] * z[0] + z[1] * z[1] + z[2] * z[2] + z[3] * z[3]).sqrt();
    let (mut minus, mut plus) = (0.0, 0.0);
    for k in 0..4 {
        let (x, y) = (a[k] / na, z[k] / nz);
        minus += (x - y) * (x - y);
        plus += (x + y) * (x + y);
    }
    let (minus, plus) = (minus.sqrt(), plus.sqrt());
    4.0 * minus.min(plus).atan2(minus.max(plus))
}

/// OMPL's `SO3StateSpace::StateType::setAxisAngle`: `(sin(θ/2)·a/|a|, cos(θ/2))`, identity if
/// `|a| ≈ 0`. Returned in OMPL's order `(qx, qy, qz, qw)`.
pub fn ompl_axis_angle(axis: [f64; 3], theta: f64) -> [f64; 4] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    if n < f64::EPSILON {
        return [0.0, 0.0, 0.0, 1.0];
    }
    let s = (0.5 * theta).sin() / n;
    [s * axis[0], s * axis[1], s * axis[2], (0.5 * theta).cos()]
}

/// Wraps an angle into `[-π, π)`, OMPL's SO(2) range.
pub fn wrap_angle(theta: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let mut t = (theta + std::f64::consts::PI).rem_euclid(two_pi) - std::f64::consts::PI;
    if t >= std::f64::consts::PI {
        t -= two_pi;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apartment_axis_angle_matches_ompl() {
        // the scenes README: axis (0,0,-1), θ = 3.12413936107 → (0, 0, −0.99996192, 0.00872654)
        let q = ompl_axis_angle([0.0, 0.0, -1.0], 3.12413936107);
        assert!((q[2] + 0.99996192).abs() < 1e-8 && (q[3] - 0.00872654).abs() < 1e-8);
    }

    #[test]
    fn relative_rotation_reaches_the_goal() {
        let a = axis_angle([0.0, 0.0, 1.0], 0.3);
        let z = axis_angle([1.0, 0.0, 0.0], 2.5) * a;
        let (axis, angle) = relative_axis_angle(&a, &z);
        let reached = axis_angle(axis, angle) * a;
        assert!(reached.angle_to(&z) < 1e-12);
        assert!((angle - 2.5).abs() < 1e-12);
    }

    #[test]
    fn rotation_angle_is_accurate_and_sign_blind() {
        let a = axis_angle([0.0, 1.0, 0.0], 0.0);
        let z = axis_angle([0.0, 1.0, 0.0], 1e-9);
        let (mut qa, mut qz) = ([0.0; 4], [0.0; 4]);
        quat_to_slice(&a, &mut qa);
        quat_to_slice(&z, &mut qz);
        assert!((rotation_angle(&qa, &qz) - 1e-9).abs() < 1e-18);
        let neg = qz.map(|v| -v);
        assert!((rotation_angle(&qa, &neg) - 1e-9).abs() < 1e-18);
        let z = axis_angle([0.0, 1.0, 0.0], 3.0);
        quat_to_slice(&z, &mut qz);
        assert!((rotation_angle(&qa, &qz) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn wrap_is_half_open() {
        assert!((wrap_angle(std::f64::consts::PI) + std::f64::consts::PI).abs() < 1e-15);
        assert!((wrap_angle(-std::f64::consts::PI) + std::f64::consts::PI).abs() < 1e-15);
        assert!((wrap_angle(7.0) - (7.0 - std::f64::consts::TAU)).abs() < 1e-12);
    }
}
