//! A point turned about an axis (CHS formula 2.1) and the box a turning body sweeps: the
//! geometry shared by the rotational case ([`super::rotation`]) and containment
//! ([`super::containment`]).

use super::envelope::AngleRange;
use super::pose::{Aabb, Pose};
use crate::geometry::kernel::trig::Trig;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// `s·x_φ` for fixed `s` and `x` turning about the unit `axis` (formula 2.1).
pub(crate) fn lin(s: &V3, x: &V3, axis: &V3) -> Trig {
    let sr = s.dot(axis);
    let rx = axis.dot(x);
    Trig {
        alpha: s.dot(x) - sr * rx,
        beta: s.dot(&axis.cross(x)),
        gamma: sr * rx,
    }
}

/// `x` turned by `phi` about the unit `axis` through the origin (formula 2.1).
pub(crate) fn turn(x: &V3, axis: &V3, phi: f64) -> V3 {
    let (s, c) = phi.sin_cos();
    axis * ((1.0 - c) * axis.dot(x)) + x * c + axis.cross(x) * s
}

/// Corner `k` (0–7) of a box: bit 0 picks x's end, bit 1 y's, bit 2 z's. A turned box stays in
/// the hull of its turned corners, so sweeps bound a turn through them.
pub(crate) fn box_corner(b: &Aabb, k: usize) -> V3 {
    let end = |bit: usize, lo: f64, hi: f64| if k & bit == 0 { lo } else { hi };
    V3::new(
        end(1, b.lo.x, b.hi.x),
        end(2, b.lo.y, b.hi.y),
        end(4, b.lo.z, b.hi.z),
    )
}

/// The world box around everything a body-frame box at `pose` sweeps while turning about the
/// world `axis` through `pose`'s position: the arcs of its eight corners (a turned convex set
/// stays in the hull of its turned corners), cut down to the sphere of `radius` about the
/// reference point (CHS §2.3.2: spheres "can easily be handled even during rotations").
pub(crate) fn swept_box(
    pose: &Pose,
    body_box: &Aabb,
    radius: f64,
    axis: &V3,
    turning: &AngleRange,
) -> Aabb {
    if body_box.is_empty() {
        return *body_box;
    }
    let mut b = Aabb::EMPTY;
    for k in 0..8 {
        let c = box_corner(body_box, k);
        b = b.merge(&turning.arc_box(&(pose.rot * c), axis));
    }
    let sphere = Aabb {
        lo: V3::repeat(-radius),
        hi: V3::repeat(radius),
    };
    b.meet(&sphere).shifted(&pose.pos)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(a: [f64; 3]) -> V3 {
        V3::new(a[0], a[1], a[2])
    }

    #[test]
    fn lin_matches_turning() {
        let axis = v([0.2, -0.4, 0.9]).normalize();
        let (s, x) = (v([1.0, 2.0, -0.5]), v([-0.3, 0.7, 1.1]));
        let f = lin(&s, &x, &axis);
        for k in 0..20 {
            let phi = -3.0 + 0.3 * k as f64;
            assert!((f.eval(phi) - s.dot(&turn(&x, &axis, phi))).abs() < 1e-12);
        }
    }
}
