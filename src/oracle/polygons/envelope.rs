//! Enveloping (CHS §2.2, §2.3.2): simple regions that contain everything a moving part sweeps,
//! so that obstacle parts outside them are never tested.
//!
//! - A translation sweeps a part through a box in the frame of the motion — one axis along the
//!   direction of motion, one across it — the seed's "boxes in a frame whose z-axis is the motion
//!   direction"; for an unbounded line the box is an infinite strip.
//! - A rotation about the reference point sweeps a part through an annulus about that point —
//!   the seed's cylindrical boxes with the angle neglected.
//!
//! Both are tested against axis-aligned boxes (nodes of the obstacle tree, or one obstacle
//! primitive's box), exactly for convex regions: separating axes for the box, distances for
//! the annulus.

use super::prepared::Aabb;
use nalgebra::Vector2;

/// A closed box in the frame of a translation: `u` along the motion, `n` across it (unit
/// vectors); the `u` range may be unbounded.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SweptBox {
    u: [f64; 2],
    n: [f64; 2],
    u_range: (f64, f64),
    n_range: (f64, f64),
    /// The world box around it (possibly unbounded), for the two world axes.
    world: Aabb,
}

/// `[lo, hi] · k` as an ordered range; `[0, 0]` for `k = 0` even for infinite ends.
fn scaled(lo: f64, hi: f64, k: f64) -> (f64, f64) {
    if k == 0.0 {
        (0.0, 0.0)
    } else if k > 0.0 {
        (lo * k, hi * k)
    } else {
        (hi * k, lo * k)
    }
}

impl SweptBox {
    /// The box `{x : u·x ∈ u_range, n·x ∈ n_range}`.
    pub fn new(u: [f64; 2], n: [f64; 2], u_range: (f64, f64), n_range: (f64, f64)) -> SweptBox {
        let mut world = Aabb::EMPTY;
        for axis in 0..2 {
            let a = scaled(u_range.0, u_range.1, u[axis]);
            let b = scaled(n_range.0, n_range.1, n[axis]);
            world.lo[axis] = a.0 + b.0;
            world.hi[axis] = a.1 + b.1;
        }
        SweptBox {
            u,
            n,
            u_range,
            n_range,
            world,
        }
    }

    /// Whether the closed box `b` meets this one (separating-axis test on all four axes).
    pub fn overlaps(&self, b: &Aabb) -> bool {
        if !self.world.overlaps(b) {
            return false;
        }
        let c = b.centre();
        let h = b.half_extents();
        let project = |v: [f64; 2]| {
            let centre = c[0] * v[0] + c[1] * v[1];
            let radius = h[0] * v[0].abs() + h[1] * v[1].abs();
            (centre - radius, centre + radius)
        };
        let (ulo, uhi) = project(self.u);
        let (nlo, nhi) = project(self.n);
        uhi >= self.u_range.0
            && ulo <= self.u_range.1
            && nhi >= self.n_range.0
            && nlo <= self.n_range.1
    }
}

/// The closed annulus of radii `[r_lo, r_hi]` about `centre`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Annulus {
    /// Centre (the reference point of the rotation).
    pub centre: [f64; 2],
    /// Inner radius (may be 0 or negative: a disc).
    pub r_lo: f64,
    /// Outer radius.
    pub r_hi: f64,
}

impl Annulus {
    /// Whether the closed box `b` meets the annulus.
    pub fn overlaps(&self, b: &Aabb) -> bool {
        if self.r_hi < 0.0 {
            return false;
        }
        let near = b.distance_squared_to(&Vector2::from(self.centre));
        near <= self.r_hi * self.r_hi
            && (self.r_lo <= 0.0
                || b.farthest_squared_from(&Vector2::from(self.centre)) >= self.r_lo * self.r_lo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn swept_box_against_boxes() {
        // the strip |y| ≤ 1 along a diagonal direction, u ∈ [0, 10]
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let b = SweptBox::new([s, s], [-s, s], (0.0, 10.0), (-1.0, 1.0));
        let unit = |x: f64, y: f64| Aabb::of_plane_points(&[[x, y], [x + 0.1, y + 0.1]]);
        assert!(b.overlaps(&unit(3.0, 3.0)));
        assert!(!b.overlaps(&unit(3.0, 5.0))); // beside the strip: its world box would say yes
        assert!(!b.overlaps(&unit(-2.0, -2.0))); // behind the start
        assert!(!b.overlaps(&unit(8.0, 8.0))); // beyond the end (u ≈ 11.4)
                                               // unbounded along u
        let line = SweptBox::new(
            [1.0, 0.0],
            [0.0, 1.0],
            (f64::NEG_INFINITY, f64::INFINITY),
            (0.0, 1.0),
        );
        assert!(line.overlaps(&unit(-1e9, 0.5)));
        assert!(!line.overlaps(&unit(-1e9, 1.5)));
    }

    #[test]
    fn annulus_against_boxes() {
        let a = Annulus {
            centre: [0.0, 0.0],
            r_lo: 2.0,
            r_hi: 3.0,
        };
        let b = |x: f64, y: f64, w: f64| Aabb::of_plane_points(&[[x, y], [x + w, y + w]]);
        assert!(a.overlaps(&b(2.5, 0.0, 0.1)));
        assert!(!a.overlaps(&b(0.5, 0.5, 0.5))); // inside the hole
        assert!(!a.overlaps(&b(3.0, 3.0, 1.0))); // outside
        assert!(a.overlaps(&b(-5.0, -5.0, 10.0))); // covers everything
    }
}
