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
//! for a rotating `u` and a fixed `v`. Each such atom holds on one arc ([`trig::solve`]), at
//! most two intervals of the window, and the pair's predicate is evaluated on those interval
//! lists: `∧` = intersection, `∨` = union. Unlike under translation, the two ends of an edge
//! now move differently, so "0 between `s(a)` and `s(b)`" is kept as the disjunction
//! `(s(a) ≥ 0 ∧ s(b) ≤ 0) ∨ (s(a) ≤ 0 ∧ s(b) ≥ 0)`.
//!
//! Containment (CHS §2.3.2: "the circle a point describes"): the reference vertex of every
//! robot part runs on a circle about the centre and is tested against the obstacles'
//! triangles; the reference vertex of every obstacle, seen from the robot, runs on a circle
//! the other way and is tested against the robot's triangles — both as three atoms per
//! triangle. Enveloping: annuli about the centre (the seed's cylindrical boxes with the angle
//! neglected), for every robot edge and every reference vertex.

use super::envelope::Annulus;
use super::small_set::SmallSet;
use super::trig;
use super::{dot, perp_dot, Polygons, P};
use crate::interval::Interval;
use std::ops::ControlFlow;

/// `{φ ∈ window : α cos φ + β sin φ + γ ≥ 0}`.
#[inline]
fn atom(alpha: f64, beta: f64, gamma: f64, window: Interval) -> SmallSet {
    let mut s = SmallSet::new();
    trig::solve(alpha, beta, gamma).pieces_in(window, |iv| s.push(iv));
    s
}

/// Coefficients `(α, β, γ)` of an atom.
type Atom = (f64, f64, f64);

/// `{φ : x ≥ −tol}` and `{φ : x ≤ tol}` for the atom `x`.
fn both_signs(x: Atom, tol: f64, window: Interval) -> (SmallSet, SmallSet) {
    (
        atom(x.0, x.1, x.2 + tol, window),
        atom(-x.0, -x.1, tol - x.2, window),
    )
}

/// `(x ≥ 0 ∧ y ≤ 0) ∨ (x ≤ 0 ∧ y ≥ 0)`: zero lies between `x` and `y`.
fn straddles(x: Atom, y: Atom, tol: f64, window: Interval) -> SmallSet {
    let (x_pos, x_neg) = both_signs(x, tol, window);
    let (y_pos, y_neg) = both_signs(y, tol, window);
    SmallSet::union(
        &SmallSet::intersection(&x_pos, &y_neg),
        &SmallSet::intersection(&x_neg, &y_pos),
    )
}

/// The angles `φ ∈ window` at which the closed robot edge `[R(φ)a, R(φ)b]` meets the closed
/// obstacle edge `[c, d]`, all relative to the centre of rotation; tests relaxed by `tol`.
pub(super) fn edge_edge(a: P, b: P, c: P, d: P, tol: f64, window: Interval) -> SmallSet {
    let e = [b[0] - a[0], b[1] - a[1]];
    let f = [d[0] - c[0], d[1] - c[1]];
    let lf = f[0].hypot(f[1]);
    let tf = tol * lf;
    // (1) s(x) = f × (R(φ)x − c)
    let s = |x: P| (-perp_dot(x, f), dot(x, f), perp_dot(c, f));
    let mut set = straddles(s(a), s(b), tf, window);
    if set.is_empty() {
        return set;
    }
    // (2) r(y) = (R(φ)e) × (y − R(φ)a) = (R(φ)e) × y − e × a
    let te = tol * e[0].hypot(e[1]);
    let r = |y: P| (perp_dot(e, y), -dot(e, y), -perp_dot(e, a));
    set = SmallSet::intersection(&set, &straddles(r(c), r(d), te, window));
    if set.is_empty() {
        return set;
    }
    // (3) p(x) = (R(φ)x − c)·f reaches [0, |f|²]
    let p = |x: P| (dot(x, f), perp_dot(x, f), -dot(c, f));
    let (pa, pb) = (p(a), p(b));
    let after_c = SmallSet::union(
        &atom(pa.0, pa.1, pa.2 + tf, window),
        &atom(pb.0, pb.1, pb.2 + tf, window),
    );
    set = SmallSet::intersection(&set, &after_c);
    if set.is_empty() {
        return set;
    }
    let ff = lf * lf;
    let before_d = SmallSet::union(
        &atom(-pa.0, -pa.1, ff - pa.2 + tf, window),
        &atom(-pb.0, -pb.1, ff - pb.2 + tf, window),
    );
    SmallSet::intersection(&set, &before_d)
}

/// The angles at which the rotating point `R(φ)v` lies in the fixed closed counter-clockwise
/// triangle `tri` (all relative to the centre).
pub(super) fn point_in_triangle(v: P, tri: &[P; 3], tol: f64, window: Interval) -> SmallSet {
    let mut set = SmallSet::new();
    set.push(window);
    for i in 0..3 {
        let (u, w) = (tri[i], tri[(i + 1) % 3]);
        let g = [w[0] - u[0], w[1] - u[1]];
        // g × (R(φ)v − u)
        let gamma = -perp_dot(g, u) + tol * g[0].hypot(g[1]);
        set = SmallSet::intersection(&set, &atom(-perp_dot(v, g), dot(v, g), gamma, window));
        if set.is_empty() {
            break;
        }
    }
    set
}

/// The angles at which the fixed point `w` lies in the rotating closed counter-clockwise
/// triangle `R(φ)·tri` (all relative to the centre).
pub(super) fn triangle_contains(tri: &[P; 3], w: P, tol: f64, window: Interval) -> SmallSet {
    let mut set = SmallSet::new();
    set.push(window);
    for i in 0..3 {
        let (u, v) = (tri[i], tri[(i + 1) % 3]);
        let g = [v[0] - u[0], v[1] - u[1]];
        // (R(φ)g) × (w − R(φ)u) = (R(φ)g) × w − g × u
        let gamma = -perp_dot(g, u) + tol * g[0].hypot(g[1]);
        set = SmallSet::intersection(&set, &atom(perp_dot(g, w), -dot(g, w), gamma, window));
        if set.is_empty() {
            break;
        }
    }
    set
}

/// Hands the intervals of `set` to `sink`.
fn emit(set: SmallSet, sink: &mut impl FnMut(Interval) -> ControlFlow<()>) -> ControlFlow<()> {
    set.as_slice().iter().try_for_each(|&iv| sink(iv))
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
    (a[0] + s * e[0]).hypot(a[1] + s * e[1])
}

/// Distance range `[min, max]` from the origin to the closed triangle.
pub(super) fn triangle_radii(tri: &[P; 3]) -> (f64, f64) {
    let hi = tri.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
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

/// Runs over every primitive pair a turn of the robot about `centre` can collide in, for the
/// turned angles `φ ∈ window` (length at most `2π`) from orientation `theta`, and hands every
/// pair's collision set (in `φ`) to `sink`, stopping when it breaks. Counts pairs in `pairs`.
pub(super) fn sweep(
    oracle: &Polygons,
    centre: P,
    theta: f64,
    window: Interval,
    pairs: &mut u64,
    sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let body = &oracle.body;
    let world = &oracle.world;
    let tol = oracle.tolerance_at(centre);
    let slack = 4.0 * tol;
    // robot points relative to the centre at φ = 0; obstacle points relative to the centre
    let turn = super::placement([0.0, 0.0], theta);
    let rel = |p: P| [p[0] - centre[0], p[1] - centre[1]];

    // edge against edge; a robot edge sweeps the annulus of its distances from the centre
    for (edge, &(r_lo, r_hi)) in body.edges.iter().zip(&body.edge_radii) {
        let (a, b) = (turn(edge[0]), turn(edge[1]));
        let ring = Annulus {
            centre,
            r_lo: r_lo - slack,
            r_hi: r_hi + slack,
        };
        let mut test = |j: usize| {
            let [c, d] = world.edges[j];
            let (c, d) = (rel(c), rel(d));
            if oracle.enveloping {
                let far = c[0].hypot(c[1]).max(d[0].hypot(d[1]));
                if !ring.meets_radii(segment_distance(c, d), far) {
                    return ControlFlow::Continue(());
                }
            }
            *pairs += 1;
            emit(edge_edge(a, b, c, d, tol, window), sink)
        };
        if oracle.enveloping {
            world.edge_tree.query(|bx| ring.overlaps(bx), &mut test)?;
        } else {
            (0..world.edges.len()).try_for_each(&mut test)?;
        }
    }

    // the reference vertex of every robot part on its circle, against obstacle triangles
    for &r in &body.refs {
        let v = turn(r);
        let rho = v[0].hypot(v[1]);
        let ring = Annulus {
            centre,
            r_lo: rho - slack,
            r_hi: rho + slack,
        };
        let mut test = |j: usize| {
            let t = world.tris[j];
            let tri = [rel(t[0]), rel(t[1]), rel(t[2])];
            if oracle.enveloping {
                let (lo, hi) = triangle_radii(&tri);
                if !ring.meets_radii(lo, hi) {
                    return ControlFlow::Continue(());
                }
            }
            *pairs += 1;
            emit(point_in_triangle(v, &tri, tol, window), sink)
        };
        if oracle.enveloping {
            world.tri_tree.query(|bx| ring.overlaps(bx), &mut test)?;
        } else {
            (0..world.tris.len()).try_for_each(&mut test)?;
        }
    }

    // the reference vertex of every obstacle, against the robot's triangles
    let mut robot_test = |w: P, pairs: &mut u64| {
        let w = rel(w);
        let rho = w[0].hypot(w[1]);
        for (tri, &(lo, hi)) in body.tris.iter().zip(&body.tri_radii) {
            if oracle.enveloping && !(lo - slack <= rho && rho <= hi + slack) {
                continue;
            }
            *pairs += 1;
            let placed = [turn(tri[0]), turn(tri[1]), turn(tri[2])];
            emit(triangle_contains(&placed, w, tol, window), sink)?;
        }
        ControlFlow::Continue(())
    };
    if body.tris.is_empty() {
        return ControlFlow::Continue(());
    }
    if oracle.enveloping {
        let ring = Annulus {
            centre,
            r_lo: body.tri_inner_radius - slack,
            r_hi: body.radius + slack,
        };
        world
            .ref_tree
            .query(|bx| ring.overlaps(bx), |j| robot_test(world.refs[j], pairs))
    } else {
        world.refs.iter().try_for_each(|&w| robot_test(w, pairs))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    const TURN: Interval = Interval { lo: -PI, hi: PI };

    #[test]
    fn a_bar_sweeps_over_a_crossing_edge() {
        // the bar [1, 2] × {0} turning about the origin meets the vertical edge x = 1.5,
        // y ∈ [0, 10] for φ ∈ [0, acos(1.5/2)]
        let set = edge_edge([1.0, 0.0], [2.0, 0.0], [1.5, 0.0], [1.5, 10.0], 0.0, TURN);
        assert_eq!(set.as_slice().len(), 1, "{set:?}");
        let iv = set.as_slice()[0];
        assert!(iv.lo.abs() < 1e-12);
        assert!((iv.hi - (0.75f64).acos()).abs() < 1e-12);
    }

    #[test]
    fn collinear_at_an_instant_but_disjoint() {
        // the bar [1, 2] × {0} turning; the edge [3, 4] × {0} is collinear at φ = 0 and π but
        // never met; at φ = π the bar lies on [−2, −1] × {0}, disjoint from [−4, −3] too
        let set = edge_edge([1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.0], 0.0, TURN);
        assert!(set.is_empty(), "{set:?}");
        // but the edge [−3, −1.5] × {0} is met at φ = π exactly
        let set = edge_edge([1.0, 0.0], [2.0, 0.0], [-3.0, 0.0], [-1.5, 0.0], 0.0, TURN);
        assert!(set.as_slice().iter().any(|iv| iv.contains(PI)), "{set:?}");
        // (and at φ = −π, the same placement); nowhere else
        assert!(set
            .as_slice()
            .iter()
            .all(|iv| iv.lo > PI - 1e-6 || iv.hi < -PI + 1e-6));
    }

    #[test]
    fn a_point_on_a_circle_through_a_triangle() {
        // the point (1, 0) on the unit circle, the triangle covering the positive y axis
        let tri = [[-0.5, 0.5], [0.5, 0.5], [0.0, 2.0]];
        let set = point_in_triangle([1.0, 0.0], &tri, 0.0, TURN);
        assert_eq!(set.as_slice().len(), 1);
        let iv = set.as_slice()[0];
        // the circle crosses y = 0.5 at x = ±√0.75; the slanted edges are crossed inside
        assert!(iv.lo > 0.5 && iv.hi < PI - 0.5);
        assert!(iv.contains(FRAC_PI_2));
        // the same seen from the robot: a fixed point in a rotating triangle, turning the
        // triangle by −φ instead
        let set2 = triangle_contains(&tri, [1.0, 0.0], 0.0, TURN);
        let iv2 = set2.as_slice()[0];
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
