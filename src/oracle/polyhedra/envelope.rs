//! Enveloping (CHS §2.2 "Enveloping Techniques", §2.3.2): cheap bounds that rule out most
//! edge–face pairs before the predicate is evaluated.
//!
//! The hierarchy, coarse to fine:
//! 1. the robot's bounding sphere / box swept over the whole motion against the obstacles'
//!    bounding box — a motion far from everything costs nothing;
//! 2. the robot's tree against the obstacles' tree (the kernel's `Bvh::visit_pairs`), each
//!    pair of nodes with a window of the motion parameter in which they may meet: along a
//!    translation, the λ for which a robot node's box (placed in the world, and the obstacle
//!    node's box turned into the robot's frame) moved by λ overlaps the other box; for a turn,
//!    the cylindrical bounds of both nodes ([`CylBounds`]: height and radius ranges fixed, an
//!    angular sector that turns with φ, [`sector_window`]) and the box around a robot node's
//!    ball swept along its arc. A pair whose window is empty is pruned with all its
//!    descendants;
//! 3. per-face boxes in a frame aligned with the motion: for a translation, a Cartesian frame
//!    whose z-axis is the direction of motion (x and y stay fixed, z grows with λ:
//!    [`MotionFrame`]); for a rotation, cylindrical coordinates about the axis — height and
//!    radius stay fixed, the angle grows with φ ([`CylBox`]). Two faces can only meet where
//!    both fixed coordinates overlap, and only for the parameters where the moving coordinate
//!    overlaps, which also gives a window for the exact computation.
//!
//! The seed computes the boxes once per polyhedron and direction; we compute the robot's
//! lazily per call (a call has one direction) and the obstacle's only for faces the trees
//! return. Angles come from a polynomial arctangent ([`fast_atan2`]) whose error bound
//! ([`ATAN_ERR`]) widens every angular bound, so bounds stay conservative.

use super::pose::Aabb;
use crate::interval::Interval;
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

type V3 = Vector3<f64>;

/// The λ for which the ball of radius `r` about `c + λ·dir` meets the ball of radius `radius`
/// about `centre`: one quadratic inequality (CHS §2.2, "a simple quadratic inequality can tell
/// whether the moving sphere intersects the other at some time during the motion").
pub(crate) fn sphere_sweep(c: &V3, dir: &V3, r: f64, centre: &V3, radius: f64) -> Option<Interval> {
    let w = c - centre;
    let s = r + radius;
    let a = dir.norm_squared();
    let b = dir.dot(&w);
    let e = w.norm_squared() - s * s;
    if a == 0.0 {
        return (e <= 0.0).then_some(Interval::ALL);
    }
    let disc = b * b - a * e;
    if disc < 0.0 {
        return None;
    }
    // a λ² + 2 b λ + e ≤ 0, roots without cancellation
    let q = -(b + disc.sqrt().copysign(b));
    let (l1, l2) = if q == 0.0 { (0.0, 0.0) } else { (q / a, e / q) };
    Some(Interval {
        lo: l1.min(l2),
        hi: l1.max(l2),
    })
}

/// The extremes of `a cos φ + b sin φ + c` over the angles of `r` (which may exceed 2π).
///
/// The maximum `c + √(a² + b²)` is reached at the angle θ of `(a, b)`, the minimum at θ + π;
/// θ lies in the range iff `cos(θ − mid) ≥ cos(half)` (mid and half-width of the range), i.e.
/// `a cos mid + b sin mid ≥ √(a² + b²) · cos(half)` — no arctangent, no reduction modulo 2π.
/// The test is loosened by a relative 1e-12 and the half-width by [`ATAN_ERR`], so an extreme
/// on the edge of the range counts as inside (a box a little larger, never smaller).
fn trig_range(a: f64, b: f64, c: f64, r: &AngleRange) -> (f64, f64) {
    let amp = norm2(a, b);
    if r.full {
        return (c - amp, c + amp);
    }
    let f0 = a * r.cs0.0 + b * r.cs0.1 + c;
    let f1 = a * r.cs1.0 + b * r.cs1.1 + c;
    let (mut lo, mut hi) = (f0.min(f1), f0.max(f1));
    if amp > 0.0 {
        let d = a * r.cs_mid.0 + b * r.cs_mid.1;
        let reach = amp * (r.cos_half - 1e-12);
        if d >= reach {
            hi = c + amp;
        }
        if -d >= reach {
            lo = c - amp;
        }
    }
    (lo, hi)
}

/// Precomputed cosines and sines of the ends and the middle of an angle range, shared by many
/// arcs ([`AngleRange::arc_box`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct AngleRange {
    cs0: (f64, f64),
    cs1: (f64, f64),
    /// Cosine and sine of the middle angle.
    cs_mid: (f64, f64),
    /// Cosine of the half-width widened by [`ATAN_ERR`] (−1 once that reaches π).
    cos_half: f64,
    /// Whether the range covers a whole turn.
    full: bool,
}

impl AngleRange {
    /// `[p0, p1]`.
    pub fn new(p0: f64, p1: f64) -> AngleRange {
        let half = 0.5 * (p1 - p0) + ATAN_ERR;
        let mid = 0.5 * (p0 + p1);
        AngleRange {
            cs0: (p0.cos(), p0.sin()),
            cs1: (p1.cos(), p1.sin()),
            cs_mid: (mid.cos(), mid.sin()),
            cos_half: if half >= PI { -1.0 } else { half.cos() },
            full: p1 - p0 >= TAU,
        }
    }

    /// The box around the arc that `x` describes when turned about the unit `axis` (through the
    /// origin) by every angle of the range. By formula (2.1) every coordinate of `x_φ` is
    /// `a cos φ + b sin φ + c`.
    pub fn arc_box(&self, x: &V3, axis: &V3) -> Aabb {
        let rx = axis.dot(x);
        let c = axis * rx;
        let a = x - c;
        let b = axis.cross(x);
        let mut out = Aabb::EMPTY;
        for k in 0..3 {
            let (lo, hi) = trig_range(a[k], b[k], c[k], self);
            out.lo[k] = lo;
            out.hi[k] = hi;
        }
        out
    }
}

/// An orthonormal frame whose third axis is the direction of a translation (CHS §2.2: "boxes
/// in a special orthogonal coordinate system with r as z-axis; x- and y-coordinates remain
/// fixed under translation").
#[derive(Clone, Copy, Debug)]
pub(crate) struct MotionFrame {
    u: V3,
    w: V3,
    z: V3,
}

/// A box in a [`MotionFrame`]: `[min, max]` of the u, w and z coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrameBox {
    /// Lower ends (u, w, z).
    pub lo: [f64; 3],
    /// Upper ends (u, w, z).
    pub hi: [f64; 3],
}

impl MotionFrame {
    /// The frame for direction `dir` (not zero).
    pub fn new(dir: &V3) -> MotionFrame {
        let z = dir.normalize();
        let helper = if z.x.abs() < 0.6 {
            V3::x()
        } else if z.y.abs() < 0.6 {
            V3::y()
        } else {
            V3::z()
        };
        let u = z.cross(&helper).normalize();
        let w = z.cross(&u);
        MotionFrame { u, w, z }
    }

    /// The box of the points in this frame.
    pub fn box_of(&self, pts: &[V3; 3]) -> FrameBox {
        let mut b = FrameBox {
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
        };
        for p in pts {
            let c = [self.u.dot(p), self.w.dot(p), self.z.dot(p)];
            for (k, ck) in c.into_iter().enumerate() {
                b.lo[k] = b.lo[k].min(ck);
                b.hi[k] = b.hi[k].max(ck);
            }
        }
        b
    }
}

impl FrameBox {
    /// For a face with this box moving by `λ·speed` along z against a fixed face with box `o`:
    /// the λ for which the boxes overlap (`None` if the fixed coordinates never do), each side
    /// grown by `margin`.
    pub fn sweep_window(&self, o: &FrameBox, speed: f64, margin: f64) -> Option<Interval> {
        for k in 0..2 {
            if self.lo[k] > o.hi[k] + margin || o.lo[k] > self.hi[k] + margin {
                return None;
            }
        }
        Interval::new(
            (o.lo[2] - self.hi[2] - margin) / speed,
            (o.hi[2] - self.lo[2] + margin) / speed,
        )
    }
}

/// A box in cylindrical coordinates about a rotation axis through the origin (CHS §2.3.2:
/// "bounding boxes are computed in a cylindrical coordinate system whose axes represent angle,
/// height, and distance with respect to the fixed rotational axis").
#[derive(Clone, Copy, Debug)]
pub(crate) struct CylBox {
    /// Height along the axis.
    pub h: (f64, f64),
    /// Distance from the axis.
    pub rho: (f64, f64),
    /// Angle about the axis, `lo <= hi < lo + π`; `None` when the face surrounds or touches the
    /// axis (every angle).
    pub angle: Option<(f64, f64)>,
}

/// An orthonormal frame `(e1, e2, axis)` for cylindrical coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CylFrame {
    e1: V3,
    e2: V3,
    axis: V3,
}

impl CylFrame {
    /// The frame about the unit `axis`.
    pub fn new(axis: &V3) -> CylFrame {
        let f = MotionFrame::new(axis);
        CylFrame {
            e1: f.u,
            e2: f.w,
            axis: *axis,
        }
    }

    /// The cylindrical box of a triangle; `margin` is added to every radial and height end.
    pub fn box_of(&self, pts: &[V3; 3], margin: f64) -> CylBox {
        let mut h = (f64::INFINITY, f64::NEG_INFINITY);
        let mut xy = [(0.0, 0.0); 3];
        let mut rho_hi: f64 = 0.0;
        for (i, p) in pts.iter().enumerate() {
            let z = self.axis.dot(p);
            h = (h.0.min(z), h.1.max(z));
            xy[i] = (self.e1.dot(p), self.e2.dot(p));
            rho_hi = rho_hi.max(norm2(xy[i].0, xy[i].1));
        }
        let rho_lo = origin_distance_2d(&xy);
        let angle = if rho_lo > 4.0 * margin {
            let a0 = fast_atan2(xy[0].1, xy[0].0);
            let (mut lo, mut hi) = (0.0f64, 0.0f64);
            for p in &xy[1..] {
                let d = wrap_pi(fast_atan2(p.1, p.0) - a0);
                lo = lo.min(d);
                hi = hi.max(d);
            }
            // the face stays at least rho_lo from the axis: a margin there is an angle; each
            // end is a difference of two approximate angles plus a third
            let slack = margin / rho_lo + 1e-12 + 3.0 * ATAN_ERR;
            Some((a0 + lo - slack, a0 + hi + slack))
        } else {
            None
        };
        CylBox {
            h: (h.0 - margin, h.1 + margin),
            rho: ((rho_lo - margin).max(0.0), rho_hi + margin),
            angle,
        }
    }
}

impl CylBox {
    /// Whether the fixed coordinates (height and radius) of two faces overlap.
    pub fn fixed_overlap(&self, o: &CylBox) -> bool {
        self.h.0 <= o.h.1 && o.h.0 <= self.h.1 && self.rho.0 <= o.rho.1 && o.rho.0 <= self.rho.1
    }

    /// For this face turned by `+φ` against the fixed face `o`: the angles φ (an arc
    /// `(start, length)`, length < 2π) for which their angular ranges overlap; `None` if every
    /// angle may.
    pub fn turn_window(&self, o: &CylBox) -> Option<(f64, f64)> {
        let (m, f) = (self.angle?, o.angle?);
        // m.lo + φ <= f.hi and f.lo <= m.hi + φ
        let start = f.0 - m.1;
        let len = (f.1 - f.0) + (m.1 - m.0);
        (len < TAU).then_some((start, len))
    }
}

/// Bounds of a tree node in cylindrical coordinates about a rotation axis (CHS §2.3.2): height
/// range, radius range and, away from the axis, an angular sector. Height and radius do not
/// change while the node turns about the axis, the sector turns with it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CylBounds {
    /// Height along the axis.
    pub h: (f64, f64),
    /// Distance from the axis.
    pub rho: (f64, f64),
    /// Radial offset of the node's centre from the axis, in the frame's `(e1, e2)` plane.
    centre: (f64, f64),
    /// Radius of the disc (about `centre`) that holds the node's projection onto that plane.
    spread: f64,
}

impl CylBounds {
    /// The angular sector `(middle, half width)` (half width < π/2), or `None` when the node
    /// comes close to the axis.
    pub fn sector(&self) -> Option<(f64, f64)> {
        let rc = norm2(self.centre.0, self.centre.1);
        // the disc of radius `spread` about a point at distance rc > spread subtends
        // ±asin(spread / rc) ≤ ±tan(asin(spread / rc)) = ±spread / √(rc² − spread²); the
        // factor keeps clear of the steep end, the relative and absolute terms of rounding
        if rc <= 1.01 * self.spread || rc <= 0.0 {
            return None;
        }
        let tan = self.spread / ((rc - self.spread) * (rc + self.spread)).sqrt();
        let half = tan * (1.0 + 1e-9) + 1e-12 + ATAN_ERR;
        Some((fast_atan2(self.centre.1, self.centre.0), half))
    }

    /// Whether the fixed coordinates (height, radius) of two nodes overlap.
    pub fn fixed_overlap(&self, o: &CylBounds) -> bool {
        self.h.0 <= o.h.1 && o.h.0 <= self.h.1 && self.rho.0 <= o.rho.1 && o.rho.0 <= self.rho.1
    }

    /// Whether the fixed coordinates of this node and of a face's box overlap.
    pub fn fixed_overlap_box(&self, o: &CylBox) -> bool {
        self.h.0 <= o.h.1 && o.h.0 <= self.h.1 && self.rho.0 <= o.rho.1 && o.rho.0 <= self.rho.1
    }

    /// Bounds that meet everything (the start of a descent, before any node is bounded).
    pub fn everything() -> CylBounds {
        CylBounds {
            h: (f64::NEG_INFINITY, f64::INFINITY),
            rho: (0.0, f64::INFINITY),
            centre: (0.0, 0.0),
            spread: f64::INFINITY,
        }
    }
}

impl CylFrame {
    /// The same frame seen from another frame: `rot` maps this frame's coordinates to the
    /// other's.
    pub fn rotated(&self, rot: &nalgebra::Matrix3<f64>) -> CylFrame {
        CylFrame {
            e1: rot * self.e1,
            e2: rot * self.e2,
            axis: rot * self.axis,
        }
    }

    /// Cylindrical bounds of the box with centre `c` (relative to a point of the axis) and
    /// half extents `half`, grown by `margin`, both in the coordinates of this frame's vectors.
    /// Conservative: the height range is the box's projection (exact), the radius range and
    /// the sector come from the smallest disc about the centre's projection that holds the
    /// projections of the box's corners.
    pub fn node_bounds(&self, c: &V3, half: &V3, margin: f64) -> CylBounds {
        let z = self.axis.dot(c);
        let hz = self.axis.abs().dot(half);
        // the corners relative to the centre are ±(s ∘ half); their distance from the axis
        // direction, at most over the four sign patterns
        let mut spread2: f64 = 0.0;
        for s in [
            [1.0, 1.0, 1.0],
            [1.0, 1.0, -1.0],
            [1.0, -1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ] {
            let v = V3::new(s[0] * half.x, s[1] * half.y, s[2] * half.z);
            let along = self.axis.dot(&v);
            spread2 = spread2.max(v.norm_squared() - along * along);
        }
        // rounding: a relative 1e-12 of the sizes involved, far below the margin's 4e-11 of
        // the scene for scene-sized numbers, added on top of it
        let round = 1e-12 * (c.norm() + half.norm());
        let spread = spread2.max(0.0).sqrt() + margin + round;
        let centre = (self.e1.dot(c), self.e2.dot(c));
        let rc = norm2(centre.0, centre.1);
        CylBounds {
            h: (z - hz - margin - round, z + hz + margin + round),
            rho: ((rc - spread).max(0.0), rc + spread),
            centre,
            spread,
        }
    }
}

/// For a node with sector `m` turned by `+φ` against a fixed node with sector `f`: the hull of
/// the angles of `window` (at most one turn) at which the sectors overlap; `None` if none.
pub(crate) fn sector_window(m: (f64, f64), f: (f64, f64), window: Interval) -> Option<Interval> {
    let half = m.1 + f.1;
    if half >= PI {
        return Some(window);
    }
    let start = wrap_pi(f.0 - m.0 - half);
    let spans: super::pose::Spans = crate::geometry::kernel::trig::arc_in_window(
        crate::geometry::kernel::trig::Arc {
            start,
            length: 2.0 * half,
        },
        window,
    );
    let s = spans.as_slice();
    Some(Interval {
        lo: s.first()?.lo,
        hi: s.last()?.hi,
    })
}

/// Distance from the origin to the triangle `xy` in the plane (0 if inside).
fn origin_distance_2d(xy: &[(f64, f64); 3]) -> f64 {
    let cross = |a: (f64, f64), b: (f64, f64)| a.0 * b.1 - a.1 * b.0;
    let s: [f64; 3] = std::array::from_fn(|i| cross(xy[i], xy[(i + 1) % 3]));
    if (s[0] >= 0.0 && s[1] >= 0.0 && s[2] >= 0.0) || (s[0] <= 0.0 && s[1] <= 0.0 && s[2] <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|i| {
            let (a, b) = (xy[i], xy[(i + 1) % 3]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let l2 = dx * dx + dy * dy;
            let t = if l2 > 0.0 {
                (-(a.0 * dx + a.1 * dy) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            norm2(a.0 + t * dx, a.1 + t * dy)
        })
        .fold(f64::INFINITY, f64::min)
}

/// `√(a² + b²)` without `hypot`'s care for overflow (scene coordinates are far from it), which
/// costs several times as much; within two ulps.
fn norm2(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// Bound on the error of [`fast_atan2`] in radians (its polynomial is within 1.7e-6 of the
/// arctangent; a unit test checks 2.5e-6 on dense samples).
pub(crate) const ATAN_ERR: f64 = 1e-5;

/// The angle of `(x, y)` within [`ATAN_ERR`], in `[−π, π]`: an odd polynomial of degree 11 for
/// the arctangent on `[0, 1]`, folded to the other octants. The bounds that use it widen their
/// angles by the error, so they stay conservative; it is 3–4× cheaper than `atan2`, which is
/// called for every tree node and face box of a turn.
pub(crate) fn fast_atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let (num, den) = if ay <= ax { (ay, ax) } else { (ax, ay) };
    if den == 0.0 {
        return 0.0;
    }
    let t = num / den;
    let t2 = t * t;
    let mut p = -0.011_721_20;
    for c in [
        0.052_653_32,
        -0.116_432_87,
        0.193_543_46,
        -0.332_623_47,
        0.999_977_26,
    ] {
        p = p * t2 + c;
    }
    let mut a = p * t;
    if ay > ax {
        a = FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = PI - a;
    }
    if y < 0.0 {
        -a
    } else {
        a
    }
}

/// Wraps into `(-π, π]`.
pub(crate) fn wrap_pi(a: f64) -> f64 {
    let w = a - TAU * ((a + PI) / TAU).floor();
    // w in [-π, π); move -π to π
    if w <= -PI {
        w + TAU
    } else {
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::rotation::axis_angle;

    #[test]
    fn arc_box_contains_sampled_arc_and_is_tight() {
        let axis = V3::new(0.3, -0.5, 0.8).normalize();
        let x = V3::new(1.0, 2.0, -0.5);
        for &(p0, p1) in &[(0.0, 0.3), (-1.0, 2.5), (-PI, PI), (2.0, 7.0)] {
            let r = AngleRange::new(p0, p1);
            let b = r.arc_box(&x, &axis);
            let mut s = Aabb::EMPTY;
            for i in 0..=2000 {
                let phi = p0 + (p1 - p0) * i as f64 / 2000.0;
                let q = axis_angle([axis.x, axis.y, axis.z], phi);
                let y = q * x;
                s.add_point(&y);
            }
            for k in 0..3 {
                assert!(b.lo[k] <= s.lo[k] + 1e-12 && s.hi[k] <= b.hi[k] + 1e-12);
                assert!(s.lo[k] - b.lo[k] < 1e-5 && b.hi[k] - s.hi[k] < 1e-5);
            }
        }
    }

    #[test]
    fn cylindrical_box_of_a_face_off_the_axis() {
        let f = CylFrame::new(&V3::z());
        let pts = [
            V3::new(2.0, -1.0, 0.0),
            V3::new(3.0, 1.0, 1.0),
            V3::new(2.0, 1.0, 2.0),
        ];
        let b = f.box_of(&pts, 0.0);
        assert_eq!(b.h, (0.0, 2.0));
        assert!((b.rho.0 - 2.0).abs() < 1e-12);
        assert!((b.rho.1 - 10f64.sqrt()).abs() < 1e-12);
        let (lo, hi) = b.angle.unwrap();
        // the exact width, widened by at most the allowance for the fast arctangent
        let excess = hi - lo - 2.0 * 0.5f64.atan();
        assert!((0.0..=8.0 * ATAN_ERR).contains(&excess), "{excess}");
        // a face around the axis has every angle
        let around = [
            V3::new(1.0, -1.0, 0.0),
            V3::new(1.0, 1.0, 0.0),
            V3::new(-1.0, 0.0, 0.0),
        ];
        assert!(f.box_of(&around, 0.0).angle.is_none());
    }

    #[test]
    fn moving_sphere_meets_a_sphere() {
        // centre from (−5, 0.6, 0) along x; radii 1 and 0.5: meet while x² + 0.36 ≤ 2.25
        let iv = sphere_sweep(
            &V3::new(-5.0, 0.6, 0.0),
            &V3::new(1.0, 0.0, 0.0),
            1.0,
            &V3::zeros(),
            0.5,
        )
        .unwrap();
        let x = (2.25f64 - 0.36).sqrt();
        assert!((iv.lo - (5.0 - x)).abs() < 1e-12 && (iv.hi - (5.0 + x)).abs() < 1e-12);
        assert!(sphere_sweep(&V3::new(0.0, 2.0, 0.0), &V3::x(), 1.0, &V3::zeros(), 0.5).is_none());
        assert_eq!(
            sphere_sweep(&V3::zeros(), &V3::zeros(), 1.0, &V3::x(), 0.5),
            Some(Interval::ALL)
        );
    }

    #[test]
    fn fast_atan2_is_within_its_error_bound() {
        let mut worst: f64 = 0.0;
        for i in 0..200_000 {
            let a = -PI + TAU * i as f64 / 200_000.0;
            for r in [1e-3, 1.0, 250.0] {
                let (y, x) = (r * a.sin(), r * a.cos());
                let d = wrap_pi(fast_atan2(y, x) - y.atan2(x)).abs();
                worst = worst.max(d);
            }
        }
        assert!(worst <= 2.5e-6, "{worst}");
        assert!(worst < ATAN_ERR / 4.0);
        assert_eq!(fast_atan2(0.0, 0.0), 0.0);
        assert!((fast_atan2(1.0, 0.0) - FRAC_PI_2).abs() < 1e-5);
    }

    #[test]
    fn wrap_is_half_open_at_minus_pi() {
        assert!((wrap_pi(PI) - PI).abs() < 1e-15);
        assert!((wrap_pi(-PI) - PI).abs() < 1e-15);
        assert!((wrap_pi(3.0 * PI + 0.1) - (-PI + 0.1)).abs() < 1e-12);
    }
}
