//! One axis-aligned box for both rigid-body oracles, in the plane (`Aabb<2>`) and in space
//! (`Aabb<3>`): the cheapest enveloping volume of CHS §2.2 ("Enveloping Techniques"), and the
//! node volume of the [`super::bvh::Bvh`].

use crate::interval::Interval;
use nalgebra::{ArrayStorage, SVector};

/// An axis-aligned box `[lo, hi]` in `D` dimensions; empty when `lo > hi` in some coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Aabb<const D: usize> {
    /// Lower corner.
    pub lo: SVector<f64, D>,
    /// Upper corner.
    pub hi: SVector<f64, D>,
}

impl<const D: usize> Aabb<D> {
    /// The empty box (neutral element of [`merge`](Self::merge)).
    pub const EMPTY: Aabb<D> = Aabb {
        lo: SVector::from_array_storage(ArrayStorage([[f64::INFINITY; D]; 1])),
        hi: SVector::from_array_storage(ArrayStorage([[f64::NEG_INFINITY; D]; 1])),
    };

    /// The box around `points`.
    pub fn of_points<'a>(points: impl IntoIterator<Item = &'a SVector<f64, D>>) -> Aabb<D> {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.add_point(p);
        }
        b
    }

    /// Grows the box to contain `p`.
    #[inline]
    pub fn add_point(&mut self, p: &SVector<f64, D>) {
        self.lo = self.lo.inf(p);
        self.hi = self.hi.sup(p);
    }

    /// The box around both.
    #[inline]
    pub fn merge(&self, o: &Aabb<D>) -> Aabb<D> {
        Aabb {
            lo: self.lo.inf(&o.lo),
            hi: self.hi.sup(&o.hi),
        }
    }

    /// The common part (possibly empty).
    pub fn meet(&self, o: &Aabb<D>) -> Aabb<D> {
        Aabb {
            lo: self.lo.sup(&o.lo),
            hi: self.hi.inf(&o.hi),
        }
    }

    /// No point inside.
    pub fn is_empty(&self) -> bool {
        // written with `all` so that NaN ends count as empty
        !(0..D).all(|k| self.lo[k] <= self.hi[k])
    }

    /// Centre.
    #[inline]
    pub fn centre(&self) -> SVector<f64, D> {
        0.5 * (self.lo + self.hi)
    }

    /// Half of the side lengths.
    #[inline]
    pub fn half_extents(&self) -> SVector<f64, D> {
        0.5 * (self.hi - self.lo)
    }

    /// Length of the diagonal (0 for an empty box).
    pub fn diagonal(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            (self.hi - self.lo).norm()
        }
    }

    /// Grown by `m` on every side.
    #[inline]
    pub fn grown(&self, m: f64) -> Aabb<D> {
        Aabb {
            lo: self.lo.add_scalar(-m),
            hi: self.hi.add_scalar(m),
        }
    }

    /// Whether the closed boxes share a point.
    #[inline]
    pub fn overlaps(&self, o: &Aabb<D>) -> bool {
        (0..D).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    /// The box moved by `d`.
    #[inline]
    pub fn shifted(&self, d: &SVector<f64, D>) -> Aabb<D> {
        Aabb {
            lo: self.lo + d,
            hi: self.hi + d,
        }
    }

    /// Square of the smallest distance from `p` to the box (0 inside).
    pub fn distance_squared_to(&self, p: &SVector<f64, D>) -> f64 {
        (0..D)
            .map(|k| (self.lo[k] - p[k]).max(p[k] - self.hi[k]).max(0.0).powi(2))
            .sum()
    }

    /// Square of the largest distance from `p` to a point of the box (its farthest corner).
    pub fn farthest_squared_from(&self, p: &SVector<f64, D>) -> f64 {
        (0..D)
            .map(|k| {
                (p[k] - self.lo[k])
                    .abs()
                    .max((self.hi[k] - p[k]).abs())
                    .powi(2)
            })
            .sum()
    }

    /// The parameters `s` for which `origin + s·dir` lies in the box (slab test), if any.
    pub fn line_range(&self, origin: &SVector<f64, D>, dir: &SVector<f64, D>) -> Option<Interval> {
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..D {
            if dir[k] == 0.0 {
                if origin[k] < self.lo[k] || origin[k] > self.hi[k] {
                    return None;
                }
            } else {
                let a = (self.lo[k] - origin[k]) / dir[k];
                let b = (self.hi[k] - origin[k]) / dir[k];
                lo = lo.max(a.min(b));
                hi = hi.min(a.max(b));
            }
        }
        Interval::new(lo, hi)
    }

    /// The parameters `λ` for which this box moved by `λ·dir` overlaps `other` (CHS §2.2: a
    /// box translated along a line meets another box for one interval of the parameter).
    pub fn sweep_range(&self, dir: &SVector<f64, D>, other: &Aabb<D>) -> Option<Interval> {
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..D {
            // other.lo - self.hi <= λ dir <= other.hi - self.lo
            let (a, b) = (other.lo[k] - self.hi[k], other.hi[k] - self.lo[k]);
            if dir[k] == 0.0 {
                if a > 0.0 || b < 0.0 {
                    return None;
                }
            } else {
                let (x, y) = (a / dir[k], b / dir[k]);
                lo = lo.max(x.min(y));
                hi = hi.min(x.max(y));
            }
        }
        Interval::new(lo, hi)
    }
}

impl Aabb<2> {
    /// The box around points of the plane given as coordinate pairs (the polygon oracle's
    /// representation).
    pub fn of_plane_points(points: &[[f64; 2]]) -> Aabb<2> {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.add_point(&(*p).into());
        }
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Vector2, Vector3};

    #[test]
    fn empty_is_the_identity_of_merge() {
        let b = Aabb::of_points([&Vector3::new(1.0, 2.0, 3.0), &Vector3::new(-1.0, 0.0, 5.0)]);
        assert_eq!(Aabb::EMPTY.merge(&b), b);
        assert!(Aabb::<3>::EMPTY.is_empty() && !b.is_empty());
        assert!(!Aabb::EMPTY.overlaps(&b));
        assert_eq!(b.centre(), Vector3::new(0.0, 1.0, 4.0));
    }

    #[test]
    fn distances_to_a_box() {
        let b = Aabb::of_plane_points(&[[0.0, 0.0], [2.0, 1.0]]);
        assert_eq!(b.distance_squared_to(&Vector2::new(1.0, 0.5)), 0.0);
        assert_eq!(b.distance_squared_to(&Vector2::new(5.0, 5.0)), 25.0);
        assert_eq!(b.farthest_squared_from(&Vector2::new(0.0, 0.0)), 5.0);
    }

    #[test]
    fn sweep_range_matches_sampling() {
        let a = Aabb::of_points([&Vector3::new(0.0, 0.0, 0.0), &Vector3::new(1.0, 1.0, 1.0)]);
        let b = Aabb::of_points([&Vector3::new(3.0, 0.5, -1.0), &Vector3::new(4.0, 2.0, 2.0)]);
        let dir = Vector3::new(1.0, 0.1, 0.0);
        let iv = a.sweep_range(&dir, &b).unwrap();
        for k in -100..=600 {
            let l = k as f64 * 0.01;
            let hit = a.shifted(&(dir * l)).overlaps(&b);
            if hit {
                assert!(iv.lo - 1e-12 <= l && l <= iv.hi + 1e-12, "{l} {iv:?}");
            } else {
                assert!(!(iv.lo + 1e-12 < l && l < iv.hi - 1e-12), "{l} {iv:?}");
            }
        }
    }
}
