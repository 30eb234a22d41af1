//! Collision intervals of a polygonal robot turning about its reference point (the planar
//! analogue of CHS §2.3.2).
//!
//! Measure the turn by the angle `φ` turned since the start. A robot point `x` then sits at
//! `R(φ)·x` relative to the centre of rotation, and every test of the static predicate (see
//! [`translation`](super::translation) for the three conditions on a pair of closed edges)
//! becomes `α cos φ + β sin φ + γ ≥ 0` with
//!
//! - `(R(φ)u) × v = cos φ · (u × v) − sin φ · (u · v)` and
//! - `(R(φ)u) · v = cos φ · (u · v) + sin φ · (u × v)`
//!
//! for a rotating `u` and a fixed `v`. Each such atom holds on one arc of the circle, at most
//! two intervals of the window, found in the half-angle parameter `τ` ([`HalfAngle`], the kernel's one solver);
//! the pair's predicate is evaluated on those interval lists (`∧` = intersection, `∨` =
//! union) and only the final ends are turned back into angles. Unlike under translation, the
//! two ends of an edge move differently, so "0 between `s(a)` and `s(b)`" is kept as the
//! disjunction `(s(a) ≥ 0 ∧ s(b) ≤ 0) ∨ (s(a) ≤ 0 ∧ s(b) ≥ 0)`.
//!
//! Containment (CHS §2.3.2: "the circle a point describes"): the reference vertex of every
//! robot part runs on a circle about the centre and is tested against the obstacles'
//! triangles; the reference vertex of every obstacle, seen from the robot, runs on a circle
//! the other way and is tested against the robot's triangles — both as three atoms per
//! triangle. Enveloping: annuli about the centre (the seed's cylindrical boxes with the angle
//! neglected) — one for the whole robot to query the obstacle tree, then one per robot edge
//! and reference vertex against the candidates' distances from the centre.

use super::envelope::Annulus;
use crate::geometry::kernel::spans::Spans;
use crate::geometry::kernel::trig::HalfAngle;

/// The value of one pair's predicate: at most five pieces in a window of one turn.
type SmallSet = Spans<6>;
use super::prepared::{dot, perp_dot, placement, Polygons, P};
use crate::interval::Interval;
use std::ops::ControlFlow;

/// Coefficients `(α, β, γ)` of an atom.
type Atom = (f64, f64, f64);

/// `{x ≥ −tol}` and `{x ≤ tol}` for the atom `x`.
#[inline]
fn both_signs(x: Atom, tol: f64, h: &HalfAngle) -> (SmallSet, SmallSet) {
    (h.solve(x.0, x.1, x.2 + tol), h.solve(-x.0, -x.1, tol - x.2))
}

/// `(x ≥ 0 ∧ y ≤ 0) ∨ (x ≤ 0 ∧ y ≥ 0)`: zero lies between `x` and `y`.
#[inline]
fn straddles(x: Atom, y: Atom, tol: f64, h: &HalfAngle) -> SmallSet {
    let (x_pos, x_neg) = both_signs(x, tol, h);
    let (y_pos, y_neg) = both_signs(y, tol, h);
    x_pos.intersect(&y_neg).union(&x_neg.intersect(&y_pos))
}

/// The angles (as `τ` of `h`) at which the closed robot edge `[R(φ)a, R(φ)b]` (of length
/// `le`) meets the closed obstacle edge `[c, d]` (of length `lf`), all relative to the centre
/// of rotation; tests relaxed by `tol`.
#[allow(clippy::too_many_arguments)]
pub(super) fn edge_edge(
    a: P,
    b: P,
    le: f64,
    c: P,
    d: P,
    lf: f64,
    tol: f64,
    h: &HalfAngle,
) -> SmallSet {
    let e = [b[0] - a[0], b[1] - a[1]];
    let f = [d[0] - c[0], d[1] - c[1]];
    let tf = tol * lf;
    // (1) s(x) = f × (R(φ)x − c)
    let s = |x: P| (-perp_dot(x, f), dot(x, f), perp_dot(c, f));
    let mut set = straddles(s(a), s(b), tf, h);
    if set.is_empty() {
        return set;
    }
    // (2) r(y) = (R(φ)e) × (y − R(φ)a) = (R(φ)e) × y − e × a
    let te = tol * le;
    let r = |y: P| (perp_dot(e, y), -dot(e, y), -perp_dot(e, a));
    set = set.intersect(&straddles(r(c), r(d), te, h));
    if set.is_empty() {
        return set;
    }
    // (3) p(x) = (R(φ)x − c)·f reaches [0, |f|²]
    let p = |x: P| (dot(x, f), perp_dot(x, f), -dot(c, f));
    let (pa, pb) = (p(a), p(b));
    let after_c = h
        .solve(pa.0, pa.1, pa.2 + tf)
        .union(&h.solve(pb.0, pb.1, pb.2 + tf));
    set = set.intersect(&after_c);
    if set.is_empty() {
        return set;
    }
    let ff = lf * lf;
    let before_d =
        h.solve(-pa.0, -pa.1, ff - pa.2 + tf)
            .union(&h.solve(-pb.0, -pb.1, ff - pb.2 + tf));
    set.intersect(&before_d)
}

/// The angles (as `τ` of `h`) at which the rotating point `R(φ)v` lies in the fixed closed
/// counter-clockwise triangle `tri` (edge lengths `lens`; all relative to the centre).
pub(super) fn point_in_triangle(
    v: P,
    tri: &[P; 3],
    lens: &[f64; 3],
    tol: f64,
    h: &HalfAngle,
) -> SmallSet {
    let mut set = h.all();
    for i in 0..3 {
        let (u, w) = (tri[i], tri[(i + 1) % 3]);
        let g = [w[0] - u[0], w[1] - u[1]];
        // g × (R(φ)v − u)
        let gamma = -perp_dot(g, u) + tol * lens[i];
        set = set.intersect(&h.solve(-perp_dot(v, g), dot(v, g), gamma));
        if set.is_empty() {
            break;
        }
    }
    set
}

/// The angles (as `τ` of `h`) at which the fixed point `w` lies in the rotating closed
/// counter-clockwise triangle `R(φ)·tri` (edge lengths `lens`; all relative to the centre).
pub(super) fn triangle_contains(
    tri: &[P; 3],
    lens: &[f64; 3],
    w: P,
    tol: f64,
    h: &HalfAngle,
) -> SmallSet {
    let mut set = h.all();
    for i in 0..3 {
        let (u, v) = (tri[i], tri[(i + 1) % 3]);
        let g = [v[0] - u[0], v[1] - u[1]];
        // (R(φ)g) × (w − R(φ)u) = (R(φ)g) × w − g × u
        let gamma = -perp_dot(g, u) + tol * lens[i];
        set = set.intersect(&h.solve(perp_dot(g, w), -dot(g, w), gamma));
        if set.is_empty() {
            break;
        }
    }
    set
}

/// Hands the intervals of `set` (in `τ` of `h`) to `sink` as angles.
fn emit(
    set: SmallSet,
    h: &HalfAngle,
    sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
) -> ControlFlow<()> {
    set.as_slice().iter().try_for_each(|&iv| sink(h.angles(iv)))
}

/// Distance from the origin to the closed segment `[a, b]`.
pub(super) fn segment_distance(a: P, b: P) -> f64 {
    let e = [b[0] - a[0], b[1] - a[1]];
    let ee = dot(e, e);
    let s = if ee > 0.0 {
        (-dot(a, e) / ee).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (a[0] + s * e[0], a[1] + s * e[1]);
    (x * x + y * y).sqrt()
}

/// Distance range `[min, max]` from the origin to the closed triangle.
pub(super) fn triangle_radii(tri: &[P; 3]) -> (f64, f64) {
    let hi = tri
        .iter()
        .map(|p| (p[0] * p[0] + p[1] * p[1]).sqrt())
        .fold(0.0, f64::max);
    let inside = (0..3).all(|i| {
        let (u, v) = (tri[i], tri[(i + 1) % 3]);
        perp_dot([v[0] - u[0], v[1] - u[1]], [-u[0], -u[1]]) >= 0.0
    });
    let lo = if inside {
        0.0
    } else {
        (0..3)
            .map(|i| segment_distance(tri[i], tri[(i + 1) % 3]))
            .fold(f64::INFINITY, f64::min)
    };
    (lo, hi)
}

/// Reusable buffers of a rotation sweep (the candidates the tree returns, the robot's
/// reference points), kept in the oracle's per-thread scratch space.
#[derive(Default)]
pub(super) struct Buffers {
    cands: Vec<(usize, [P; 2], (f64, f64))>,
    refs: Vec<(P, f64)>,
    tris: Vec<(usize, [P; 3], (f64, f64))>,
    points: Vec<(P, f64)>,
}

/// Runs over every primitive pair a turn of the robot about `centre` can collide in, for the
/// turned angles `φ ∈ window` (length at most `2π`) from orientation `theta`, and hands every
/// pair's collision set (in `φ`) to `sink`, stopping when it breaks. Counts pairs in `pairs`.
///
/// Enveloping: one query of the obstacle tree per kind of primitive with the annulus the robot
/// sweeps, then, per robot primitive, its own annulus against the candidates' distances.
pub(super) fn sweep(
    oracle: &Polygons,
    centre: P,
    theta: f64,
    window: Interval,
    pairs: &mut u64,
    bufs: &mut Buffers,
    sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let tol = oracle.tolerance_at(centre);
    let turning = Turning {
        oracle,
        centre,
        env: oracle.enveloping,
        tol,
        slack: 4.0 * tol,
        // robot points relative to the centre at φ = 0; obstacle points relative to the centre
        turn: placement([0.0, 0.0], theta),
        h: HalfAngle::new(window),
    };
    turning.edges(&mut bufs.cands, pairs, sink)?;
    turning.robot_refs(&mut bufs.refs, &mut bufs.tris, pairs, sink)?;
    turning.obstacle_refs(&mut bufs.points, pairs, sink)
}

/// What the three kinds of primitive pairs of one turn share.
struct Turning<'a, F> {
    oracle: &'a Polygons,
    centre: P,
    env: bool,
    tol: f64,
    slack: f64,
    /// A robot point at φ = 0 relative to the centre.
    turn: F,
    h: HalfAngle,
}

impl<F: Fn(P) -> P> Turning<'_, F> {
    /// An obstacle point relative to the centre.
    #[inline]
    fn rel(&self, p: P) -> P {
        [p[0] - self.centre[0], p[1] - self.centre[1]]
    }

    /// Whether the distances `[lo, hi]` from the centre meet the range `r`, within the slack.
    #[inline]
    fn overlap(&self, lo: f64, hi: f64, r: (f64, f64)) -> bool {
        lo - self.slack <= r.1 && r.0 <= hi + self.slack
    }

    /// An annulus about the centre, widened by the slack, for the obstacle trees.
    fn ring(&self, r_lo: f64, r_hi: f64) -> Annulus {
        Annulus {
            centre: self.centre,
            r_lo: r_lo - self.slack,
            r_hi: r_hi + self.slack,
        }
    }

    /// Edge against edge; a robot edge sweeps the annulus of its distances from the centre.
    fn edges(
        &self,
        cands: &mut Vec<(usize, [P; 2], (f64, f64))>,
        pairs: &mut u64,
        sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (body, world, env, tol, h) = (
            &self.oracle.body,
            &self.oracle.world,
            self.env,
            self.tol,
            &self.h,
        );
        cands.clear();
        let keep_edge = |j: usize| {
            let [c, d] = world.edges[j];
            let (c, d) = (self.rel(c), self.rel(d));
            (j, [c, d], (segment_distance(c, d), norm(c).max(norm(d))))
        };
        if env {
            let ring = self.ring(body.edge_inner_radius, body.radius);
            let _ = world.edge_tree.query::<()>(
                |bx| ring.overlaps(bx),
                |j| {
                    cands.push(keep_edge(j));
                    ControlFlow::Continue(())
                },
            );
        } else {
            cands.extend((0..world.edges.len()).map(keep_edge));
        }
        for ((edge, &le), &(lo, hi)) in body.edges.iter().zip(&body.edge_len).zip(&body.edge_radii)
        {
            let (a, b) = ((self.turn)(edge[0]), (self.turn)(edge[1]));
            for &(j, [c, d], radii) in cands.iter() {
                if env && !self.overlap(lo, hi, radii) {
                    continue;
                }
                *pairs += 1;
                emit(
                    edge_edge(a, b, le, c, d, world.edge_len[j], tol, h),
                    h,
                    sink,
                )?;
            }
        }
        ControlFlow::Continue(())
    }

    /// The reference vertex of every robot part on its circle, against obstacle triangles.
    fn robot_refs(
        &self,
        refs: &mut Vec<(P, f64)>,
        tris: &mut Vec<(usize, [P; 3], (f64, f64))>,
        pairs: &mut u64,
        sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (body, world, env, tol, h) = (
            &self.oracle.body,
            &self.oracle.world,
            self.env,
            self.tol,
            &self.h,
        );
        refs.clear();
        refs.extend(body.refs.iter().map(|&r| {
            let v = (self.turn)(r);
            (v, norm(v))
        }));
        tris.clear();
        let keep_tri = |j: usize| {
            let t = world.tris[j];
            let tri = [self.rel(t[0]), self.rel(t[1]), self.rel(t[2])];
            (j, tri, triangle_radii(&tri))
        };
        if env {
            let (lo, hi) = refs
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(_, r)| {
                    (lo.min(r), hi.max(r))
                });
            let ring = self.ring(lo, hi);
            let _ = world.tri_tree.query::<()>(
                |bx| ring.overlaps(bx),
                |j| {
                    tris.push(keep_tri(j));
                    ControlFlow::Continue(())
                },
            );
        } else {
            tris.extend((0..world.tris.len()).map(keep_tri));
        }
        for &(v, rho) in refs.iter() {
            for &(j, tri, radii) in tris.iter() {
                if env && !self.overlap(rho, rho, radii) {
                    continue;
                }
                *pairs += 1;
                emit(
                    point_in_triangle(v, &tri, &world.tri_len[j], tol, h),
                    h,
                    sink,
                )?;
            }
        }
        ControlFlow::Continue(())
    }

    /// The reference vertex of every obstacle, against the robot's triangles.
    fn obstacle_refs(
        &self,
        points: &mut Vec<(P, f64)>,
        pairs: &mut u64,
        sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (body, world, env, tol, h) = (
            &self.oracle.body,
            &self.oracle.world,
            self.env,
            self.tol,
            &self.h,
        );
        if body.tris.is_empty() {
            return ControlFlow::Continue(());
        }
        points.clear();
        let keep_point = |j: usize| {
            let w = self.rel(world.refs[j]);
            (w, norm(w))
        };
        if env {
            let ring = self.ring(body.tri_inner_radius, body.radius);
            let _ = world.ref_tree.query::<()>(
                |bx| ring.overlaps(bx),
                |j| {
                    points.push(keep_point(j));
                    ControlFlow::Continue(())
                },
            );
        } else {
            points.extend((0..world.refs.len()).map(keep_point));
        }
        if points.is_empty() {
            return ControlFlow::Continue(());
        }
        for ((tri, lens), &(lo, hi)) in body.tris.iter().zip(&body.tri_len).zip(&body.tri_radii) {
            let placed = [
                (self.turn)(tri[0]),
                (self.turn)(tri[1]),
                (self.turn)(tri[2]),
            ];
            for &(w, rho) in points.iter() {
                if env && !self.overlap(lo, hi, (rho, rho)) {
                    continue;
                }
                *pairs += 1;
                emit(triangle_contains(&placed, lens, w, tol, h), h, sink)?;
            }
        }
        ControlFlow::Continue(())
    }
}

/// Distance of `p` from the origin.
#[inline]
fn norm(p: P) -> f64 {
    (p[0] * p[0] + p[1] * p[1]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    const TURN: Interval = Interval { lo: -PI, hi: PI };

    /// A set in `τ` of a full turn as angles.
    fn angles(set: SmallSet) -> Vec<Interval> {
        let h = HalfAngle::new(TURN);
        set.as_slice().iter().map(|&iv| h.angles(iv)).collect()
    }

    fn turn() -> HalfAngle {
        HalfAngle::new(TURN)
    }

    #[test]
    fn a_bar_sweeps_over_a_crossing_edge() {
        // the bar [1, 2] × {0} turning about the origin meets the vertical edge x = 1.5,
        // y ∈ [0, 10] for φ ∈ [0, acos(1.5/2)]
        let set = angles(edge_edge(
            [1.0, 0.0],
            [2.0, 0.0],
            1.0,
            [1.5, 0.0],
            [1.5, 10.0],
            10.0,
            0.0,
            &turn(),
        ));
        assert_eq!(set.len(), 1, "{set:?}");
        let iv = set[0];
        assert!(iv.lo.abs() < 1e-12);
        assert!((iv.hi - (0.75f64).acos()).abs() < 1e-12);
    }

    #[test]
    fn collinear_at_an_instant_but_disjoint() {
        // the bar [1, 2] × {0} turning; the edge [3, 4] × {0} is collinear at φ = 0 and π but
        // never met; at φ = π the bar lies on [−2, −1] × {0}, disjoint from [−4, −3] too
        let set = angles(edge_edge(
            [1.0, 0.0],
            [2.0, 0.0],
            1.0,
            [3.0, 0.0],
            [4.0, 0.0],
            1.0,
            0.0,
            &turn(),
        ));
        assert!(set.is_empty(), "{set:?}");
        // but the edge [−3, −1.5] × {0} is met at φ = π exactly
        let set = angles(edge_edge(
            [1.0, 0.0],
            [2.0, 0.0],
            1.0,
            [-3.0, 0.0],
            [-1.5, 0.0],
            1.5,
            0.0,
            &turn(),
        ));
        assert!(set.iter().any(|iv| iv.contains(PI)), "{set:?}");
        // (and at φ = −π, the same placement); nowhere else
        assert!(set.iter().all(|iv| iv.lo > PI - 1e-6 || iv.hi < -PI + 1e-6));
    }

    #[test]
    fn a_point_on_a_circle_through_a_triangle() {
        // the point (1, 0) on the unit circle, the triangle covering the positive y axis
        let tri = [[-0.5, 0.5], [0.5, 0.5], [0.0, 2.0]];
        let set = angles(point_in_triangle([1.0, 0.0], &tri, &[1.0; 3], 0.0, &turn()));
        assert_eq!(set.len(), 1);
        let iv = set[0];
        // the circle crosses y = 0.5 at x = ±√0.75; the slanted edges are crossed inside
        assert!(iv.lo > 0.5 && iv.hi < PI - 0.5);
        assert!(iv.contains(FRAC_PI_2));
        // the same seen from the robot: a fixed point in a rotating triangle, turning the
        // triangle by −φ instead
        let set2 = angles(triangle_contains(&tri, &[1.0; 3], [1.0, 0.0], 0.0, &turn()));
        let iv2 = set2[0];
        assert!((iv2.lo + iv.hi).abs() < 1e-12 && (iv2.hi + iv.lo).abs() < 1e-12);
    }

    #[test]
    fn radii_of_triangles() {
        let (lo, hi) = triangle_radii(&[[-1.0, -1.0], [1.0, -1.0], [0.0, 1.0]]);
        assert_eq!(lo, 0.0);
        assert!((hi - 2f64.sqrt()).abs() < 1e-15);
        let (lo, _) = triangle_radii(&[[2.0, -1.0], [3.0, -1.0], [2.0, 1.0]]);
        assert!((lo - 2.0).abs() < 1e-15);
    }
}
