//! Collision intervals of a translating polygonal robot (the planar analogue of CHS §2.2).
//!
//! When the robot moves by `t·m`, every orientation test of the static predicate is linear in
//! `t`, so each atomic test keeps a half-line of `t`, and a conjunction of them keeps one
//! interval ([`Span`]). For one (moving edge, fixed edge) pair the set of colliding `t` is a
//! single interval anyway: the edges meet iff `t·m` lies in the parallelogram
//! `[c, d] ⊖ [a, b]` (a Minkowski difference, convex).
//!
//! The closed segments `[a, b]` and `[c, d]` meet iff
//! 1. `a` and `b` are not strictly on the same side of the line `cd`,
//! 2. `c` and `d` are not strictly on the same side of the line `ab`, and
//! 3. the projections of `a` and `b` onto `d − c` are not both before `c` or both after `d`.
//!
//! (1) and (2) alone are the textbook test, which is wrong for collinear segments that do not
//! overlap; (3) repairs exactly that case and is implied by (1) ∧ (2) otherwise. Because both
//! ends of a translating edge move with the same velocity, "0 between `s(a)` and `s(b)`" is the
//! pair of linear inequalities `min(s(a), s(b)) ≤ 0 ≤ max(s(a), s(b))` — six in all.
//!
//! Containment (CHS §2.2, "containment along the motion direction") uses one reference vertex
//! per polygon and the triangles of the other polygon: a moving point is in a fixed triangle
//! for one interval of `t` (three linear inequalities), and likewise a fixed point in a moving
//! triangle.
//!
//! A zero motion (`m = 0`) gives the static test: every pair then keeps all of the range or
//! nothing, so the same code answers [`CollisionOracle::collides`](super::CollisionOracle).

use super::envelope::SweptBox;
use super::prepared::{dot, perp_dot, placement, Polygons, P};
use crate::interval::Interval;
use std::ops::ControlFlow;

/// The `t` of a range that satisfy a conjunction of linear inequalities `k·t + b ≥ 0`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Span {
    lo: f64,
    hi: f64,
}

impl Span {
    /// All of `range`.
    pub fn within(range: Interval) -> Span {
        Span {
            lo: range.lo,
            hi: range.hi,
        }
    }

    /// Keeps the `t` with `k·t + b ≥ 0`.
    #[inline]
    pub fn require(&mut self, k: f64, b: f64) {
        if k > 0.0 {
            self.lo = self.lo.max(-b / k);
        } else if k < 0.0 {
            self.hi = self.hi.min(-b / k);
        } else if b < 0.0 {
            self.lo = f64::INFINITY;
            self.hi = f64::NEG_INFINITY;
        }
    }

    /// Whether no `t` is left.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.lo.is_nan() || self.hi.is_nan() || self.lo > self.hi
    }

    /// What is left, if anything.
    pub fn get(&self) -> Option<Interval> {
        Interval::new(self.lo, self.hi)
    }
}

/// The `t ∈ span` at which the closed edge `[a + t·m, b + t·m]` (of length `le`) meets the
/// closed edge `[c, d]` (of length `lf`), with every orientation test relaxed by `tol` (a
/// length) in favour of collision.
#[allow(clippy::too_many_arguments)]
pub(super) fn edge_edge(
    a: P,
    b: P,
    le: f64,
    m: P,
    c: P,
    d: P,
    lf: f64,
    tol: f64,
    mut span: Span,
) -> Option<Interval> {
    let e = [b[0] - a[0], b[1] - a[1]];
    let f = [d[0] - c[0], d[1] - c[1]];
    let tf = tol * lf;
    // (1) sides of a(t), b(t) w.r.t. the line cd: s(t) = f × (x − c) + t · f × m
    let sa = perp_dot(f, [a[0] - c[0], a[1] - c[1]]);
    let sb = perp_dot(f, [b[0] - c[0], b[1] - c[1]]);
    let k = perp_dot(f, m);
    span.require(-k, tf - sa.min(sb));
    span.require(k, sa.max(sb) + tf);
    if span.is_empty() {
        return None;
    }
    // (2) sides of c, d w.r.t. the moving line ab: r(t) = e × (y − a) − t · e × m
    let te = tol * le;
    let rc = perp_dot(e, [c[0] - a[0], c[1] - a[1]]);
    let rd = perp_dot(e, [d[0] - a[0], d[1] - a[1]]);
    let k = -perp_dot(e, m);
    span.require(-k, te - rc.min(rd));
    span.require(k, rc.max(rd) + te);
    if span.is_empty() {
        return None;
    }
    // (3) projections onto f: p(t) = (x − c)·f + t · m·f must reach [0, |f|²]
    let pa = dot([a[0] - c[0], a[1] - c[1]], f);
    let pb = dot([b[0] - c[0], b[1] - c[1]], f);
    let k = dot(m, f);
    span.require(k, pa.max(pb) + tf);
    span.require(-k, lf * lf - pa.min(pb) + tf);
    span.get()
}

/// The `t ∈ span` at which the point `p + t·m` lies in the closed counter-clockwise triangle
/// `tri` (edge lengths `lens`), every edge test relaxed by `tol` (a length).
pub(super) fn point_in_triangle(
    p: P,
    m: P,
    tri: &[P; 3],
    lens: &[f64; 3],
    tol: f64,
    mut span: Span,
) -> Option<Interval> {
    for i in 0..3 {
        let (u, v) = (tri[i], tri[(i + 1) % 3]);
        let g = [v[0] - u[0], v[1] - u[1]];
        let b = perp_dot(g, [p[0] - u[0], p[1] - u[1]]) + tol * lens[i];
        span.require(perp_dot(g, m), b);
        if span.is_empty() {
            return None;
        }
    }
    span.get()
}

/// Ranges of projections onto the two axes of the motion's frame.
#[derive(Clone, Copy, Debug)]
struct Ranges {
    u: (f64, f64),
    n: (f64, f64),
}

impl Ranges {
    fn meets(&self, o: &Ranges) -> bool {
        self.u.0 <= o.u.1 && o.u.0 <= self.u.1 && self.n.0 <= o.n.1 && o.n.0 <= self.n.1
    }
}

/// The frame of a translation: `u` along the motion, `n` across it, and how far along `u`
/// the motion carries the robot at the ends of the range.
struct Frame {
    u: P,
    n: P,
    s_lo: f64,
    s_hi: f64,
    slack: f64,
}

impl Frame {
    /// Projection ranges of `points` where they are.
    fn bounds(&self, points: &[P]) -> Ranges {
        let mut r = Ranges {
            u: (f64::INFINITY, f64::NEG_INFINITY),
            n: (f64::INFINITY, f64::NEG_INFINITY),
        };
        for &p in points {
            let (pu, pn) = (dot(p, self.u), dot(p, self.n));
            r.u = (r.u.0.min(pu), r.u.1.max(pu));
            r.n = (r.n.0.min(pn), r.n.1.max(pn));
        }
        r
    }

    /// Projection ranges of everything `points` sweep over the motion, grown by the slack.
    fn swept(&self, points: &[P]) -> Ranges {
        let r = self.bounds(points);
        Ranges {
            u: (
                r.u.0 + self.s_lo - self.slack,
                r.u.1 + self.s_hi + self.slack,
            ),
            n: (r.n.0 - self.slack, r.n.1 + self.slack),
        }
    }

    /// The same as a box for the obstacle tree.
    fn boxed(&self, r: &Ranges) -> SweptBox {
        SweptBox::new(self.u, self.n, r.u, r.n)
    }
}

/// Reusable buffers of a translation sweep (the robot placed, the candidates the tree returns),
/// kept in the oracle's per-thread scratch space.
#[derive(Default)]
pub(super) struct Buffers {
    vertices: Vec<P>,
    cands: Vec<(usize, Ranges)>,
    refs: Vec<P>,
    points: Vec<(P, Ranges)>,
}

/// Runs over every primitive pair a translation of the robot by `t·m`, `t ∈ range`, from the
/// placement `(centre, theta)` can collide in, and hands every pair's collision interval to
/// `sink` (stopping when it breaks). Counts the pairs evaluated in `pairs`.
///
/// Enveloping: one query of the obstacle tree with the box the whole robot sweeps, then, per
/// robot primitive, the box it sweeps itself against the candidates' projections.
#[allow(clippy::too_many_arguments)]
pub(super) fn sweep(
    oracle: &Polygons,
    centre: P,
    theta: f64,
    m: P,
    range: Interval,
    pairs: &mut u64,
    bufs: &mut Buffers,
    sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let Buffers {
        vertices,
        cands,
        refs,
        points,
    } = bufs;
    let tol = oracle.tolerance_at(centre);
    let place = placement(centre, theta);
    let frame = Frame::of_motion(m, range, tol);
    vertices.clear();
    vertices.extend(oracle.body.vertices.iter().map(|&v| place(v)));
    let robot = frame.boxed(&frame.swept(vertices));
    let sliding = Sliding {
        oracle,
        env: oracle.enveloping,
        tol,
        m,
        place,
        frame,
        full: Span::within(range),
        robot,
    };
    sliding.edges(cands, pairs, sink)?;
    sliding.robot_refs(refs, cands, pairs, sink)?;
    sliding.obstacle_refs(points, pairs, sink)
}

impl Frame {
    /// The frame of the motion `m` over `range`; a static test uses the world axes.
    fn of_motion(m: P, range: Interval, tol: f64) -> Frame {
        let speed = (m[0] * m[0] + m[1] * m[1]).sqrt();
        if speed > 0.0 {
            let u = [m[0] / speed, m[1] / speed];
            Frame {
                u,
                n: [-u[1], u[0]],
                s_lo: range.lo * speed,
                s_hi: range.hi * speed,
                slack: 4.0 * tol,
            }
        } else {
            Frame {
                u: [1.0, 0.0],
                n: [0.0, 1.0],
                s_lo: 0.0,
                s_hi: 0.0,
                slack: 4.0 * tol,
            }
        }
    }
}

/// Ranges that meet every other: what a candidate gets when nothing is culled.
const UNCULLED: Ranges = Ranges {
    u: (0.0, 0.0),
    n: (0.0, 0.0),
};

/// What the three kinds of primitive pairs of one translation share.
struct Sliding<'a, F> {
    oracle: &'a Polygons,
    env: bool,
    tol: f64,
    m: P,
    /// A robot point placed at the start of the motion.
    place: F,
    frame: Frame,
    full: Span,
    /// The box the whole robot sweeps.
    robot: SweptBox,
}

impl<F: Fn(P) -> P> Sliding<'_, F> {
    /// Edge against edge.
    fn edges(
        &self,
        cands: &mut Vec<(usize, Ranges)>,
        pairs: &mut u64,
        sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (body, world, env, frame) =
            (&self.oracle.body, &self.oracle.world, self.env, &self.frame);
        cands.clear();
        if env {
            let _ = world.edge_tree.query::<()>(
                |bx| self.robot.overlaps(bx),
                |j| {
                    cands.push((j, frame.bounds(&world.edges[j])));
                    ControlFlow::Continue(())
                },
            );
        } else {
            cands.extend((0..world.edges.len()).map(|j| (j, UNCULLED)));
        }
        for (edge, &le) in body.edges.iter().zip(&body.edge_len) {
            let (a, b) = ((self.place)(edge[0]), (self.place)(edge[1]));
            let swept = frame.swept(&[a, b]);
            for &(j, r) in cands.iter() {
                if env && !swept.meets(&r) {
                    continue;
                }
                *pairs += 1;
                let [c, d] = world.edges[j];
                let len = world.edge_len[j];
                if let Some(iv) = edge_edge(a, b, le, self.m, c, d, len, self.tol, self.full) {
                    sink(iv)?;
                }
            }
        }
        ControlFlow::Continue(())
    }

    /// A reference vertex of every robot part in the obstacles' triangles.
    fn robot_refs(
        &self,
        refs: &mut Vec<P>,
        cands: &mut Vec<(usize, Ranges)>,
        pairs: &mut u64,
        sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (body, world, env, frame) =
            (&self.oracle.body, &self.oracle.world, self.env, &self.frame);
        refs.clear();
        refs.extend(body.refs.iter().map(|&r| (self.place)(r)));
        cands.clear();
        if env {
            let paths = frame.boxed(&frame.swept(refs));
            let _ = world.tri_tree.query::<()>(
                |bx| paths.overlaps(bx),
                |j| {
                    cands.push((j, frame.bounds(&world.tris[j])));
                    ControlFlow::Continue(())
                },
            );
        } else {
            cands.extend((0..world.tris.len()).map(|j| (j, UNCULLED)));
        }
        for &p in refs.iter() {
            let path = frame.swept(&[p]);
            for &(j, r) in cands.iter() {
                if env && !path.meets(&r) {
                    continue;
                }
                *pairs += 1;
                let (tri, lens) = (&world.tris[j], &world.tri_len[j]);
                if let Some(iv) = point_in_triangle(p, self.m, tri, lens, self.tol, self.full) {
                    sink(iv)?;
                }
            }
        }
        ControlFlow::Continue(())
    }

    /// A reference vertex of every obstacle in the robot's triangles (moving the other way).
    fn obstacle_refs(
        &self,
        points: &mut Vec<(P, Ranges)>,
        pairs: &mut u64,
        sink: &mut impl FnMut(Interval) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (body, world, env, frame) =
            (&self.oracle.body, &self.oracle.world, self.env, &self.frame);
        if body.tris.is_empty() {
            return ControlFlow::Continue(());
        }
        points.clear();
        if env {
            let _ = world.ref_tree.query::<()>(
                |bx| self.robot.overlaps(bx),
                |j| {
                    let w = world.refs[j];
                    points.push((w, frame.bounds(&[w])));
                    ControlFlow::Continue(())
                },
            );
        } else {
            points.extend(world.refs.iter().map(|&w| (w, UNCULLED)));
        }
        if points.is_empty() {
            return ControlFlow::Continue(());
        }
        let back = [-self.m[0], -self.m[1]];
        for (tri, lens) in body.tris.iter().zip(&body.tri_len) {
            let placed = [
                (self.place)(tri[0]),
                (self.place)(tri[1]),
                (self.place)(tri[2]),
            ];
            let swept = frame.swept(&placed);
            for &(w, r) in points.iter() {
                if env && !swept.meets(&r) {
                    continue;
                }
                *pairs += 1;
                if let Some(iv) = point_in_triangle(w, back, &placed, lens, self.tol, self.full) {
                    sink(iv)?;
                }
            }
        }
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: Interval = Interval::ALL;
    /// Edge lengths of the test triangle (they only scale the tolerance, 0 here).
    const LENS: [f64; 3] = [2.0, 2.83, 2.0];

    #[test]
    fn crossing_edges_give_the_exact_interval() {
        // a vertical unit edge at x = 0 moving right through a vertical edge at x = 2
        let iv = edge_edge(
            [0.0, 0.0],
            [0.0, 1.0],
            1.0,
            [1.0, 0.0],
            [2.0, 0.5],
            [2.0, 3.0],
            2.5,
            0.0,
            Span::within(ALL),
        )
        .unwrap();
        assert_eq!(iv, Interval { lo: 2.0, hi: 2.0 });
        // a horizontal edge moving right through a vertical one: [1, 3]
        let iv = edge_edge(
            [0.0, 0.0],
            [1.0, 0.0],
            1.0,
            [1.0, 0.0],
            [2.0, -1.0],
            [2.0, 1.0],
            2.0,
            0.0,
            Span::within(ALL),
        )
        .unwrap();
        assert_eq!(iv, Interval { lo: 1.0, hi: 2.0 });
    }

    #[test]
    fn collinear_edges_meet_only_while_overlapping() {
        // [0, 1] × {0} sliding along the x axis against [3, 4] × {0}: overlap for t ∈ [2, 4]
        let iv = edge_edge(
            [0.0, 0.0],
            [1.0, 0.0],
            1.0,
            [1.0, 0.0],
            [3.0, 0.0],
            [4.0, 0.0],
            1.0,
            0.0,
            Span::within(ALL),
        )
        .unwrap();
        assert_eq!(iv, Interval { lo: 2.0, hi: 4.0 });
        // static, collinear, disjoint: the textbook test would say "intersect"
        assert!(edge_edge(
            [0.0, 0.0],
            [1.0, 0.0],
            1.0,
            [0.0, 0.0],
            [3.0, 0.0],
            [4.0, 0.0],
            1.0,
            0.0,
            Span::within(ALL)
        )
        .is_none());
        // parallel edges one unit apart moving across: collinear at one instant
        let iv = edge_edge(
            [0.0, 0.0],
            [1.0, 0.0],
            1.0,
            [0.0, 1.0],
            [0.5, 1.0],
            [3.0, 1.0],
            2.5,
            0.0,
            Span::within(ALL),
        )
        .unwrap();
        assert_eq!(iv, Interval { lo: 1.0, hi: 1.0 });
    }

    #[test]
    fn point_through_triangle() {
        let tri = [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]];
        let iv = point_in_triangle([-1.0, 0.5], [1.0, 0.0], &tri, &LENS, 0.0, Span::within(ALL))
            .unwrap();
        assert_eq!(iv, Interval { lo: 1.0, hi: 2.5 });
        assert!(
            point_in_triangle([-1.0, 3.0], [1.0, 0.0], &tri, &LENS, 0.0, Span::within(ALL))
                .is_none()
        );
    }
}
