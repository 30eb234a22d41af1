//! The rotational case (CHS §2.3.2): the robot turns by φ about a fixed axis through its
//! reference point.
//!
//! With `x_φ` the point `x` turned by φ about the unit axis `r` (formula 2.1:
//! `x_φ = (1 − cos φ)(rᵀx) r + cos φ x + sin φ r × x`), every atom of the edge–face predicate
//! becomes `α cos φ + β sin φ + γ R 0` ([`super::trig`]):
//! - `n·x_φ − c` has `α = n·x − (n·r)(r·x)`, `β = n·(r × x)`, `γ = (n·r)(r·x) − c`;
//! - `det[d_φ, e, p_φ − v]` splits into `det[d_φ, e, p_φ] − det[d_φ, e, v]`; the first is
//!   `e·(p × d)_φ` because the cross product turns with its factors, the second `(e × v)·d_φ`
//!   — both of the first kind (the seed gets the same by turning the parallelepiped back by −φ);
//! - the case split `n·d_φ` is itself such an atom, so outward and inward are both evaluated,
//!   each restricted to where its sign holds.
//!
//! The edge moves and the face stays: robot edges turn by `+φ` against obstacle faces;
//! obstacle edges turn by `−φ` (about `−r` by `+φ`) against robot faces, in the robot's frame
//! ("swap the role of object and obstacle while negating the axis of rotation").
//!
//! Each atom gives at most one arc, so at most two intervals in a window of one turn; the
//! conjunctions are evaluated on small interval lists ([`Spans`]).

use super::body::{Body, Face};
use super::caches::{Caches, NodeBounds, ObstNodeBounds};
use super::containment;
use super::envelope::{sector_window, AngleRange, CylBounds, CylBox, CylFrame};
use super::model::{descend_pairs, note_earliest, Polyhedra};
use super::pose::{Aabb, Pose, Spans};
use super::predicate::Tolerance;
use super::turning::{lin, swept_box};
use crate::geometry::kernel::hits::Hits;
use crate::geometry::kernel::memo::Memo;
use crate::geometry::kernel::trig::{arc_in_window, Arc, Trig};
use crate::interval::Interval;
use crate::oracle::CallCounts;
use nalgebra::Vector3;
use std::cell::Cell;
use std::f64::consts::PI;
use std::ops::ControlFlow;

type V3 = Vector3<f64>;

/// A piece of a pair's answer shorter than this (radians) …
const DEGENERATE_SPAN: f64 = 1e-7;
/// … at whose middle the edge is this close to parallel to the face (as a sine) is a
/// degenerate instant of Lemma 2.1, not a collision of this pair.
const DEGENERATE_PARALLEL: f64 = 1e-7;

/// A face whose corners stay more than this many times the predicate's slack on one side of
/// another face's plane over a window has no edge that meets that face (its first atoms fail).
const OFF_NEAR: f64 = 2.0;
/// … more than this many times: the two faces do not meet at all (no edge of the other face,
/// which lies in that plane, reaches it either; the margin covers the determinants' slack).
const OFF_FAR: f64 = 16.0;

/// A pair of faces is solved only where its window is not yet known to collide, reaching this
/// far (radians) into the known pieces on either side ([`Hits::uncovered`]): more than
/// [`DEGENERATE_SPAN`], so that a piece continuing a known one is never dropped as a sliver.
const CLIP_OVERLAP: f64 = 1e-6;

/// A window of angles summarised for cheap bounds: with `m` the window's middle and `h` its half
/// width, `a cos φ + b sin φ + c = P cos(φ − m) + Q sin(φ − m) + c` with `P = a cos m + b sin m`,
/// `Q = b cos m − a sin m`; over `|φ − m| ≤ h` it peaks at `c + √(P² + Q²)` if its crest lies in
/// the window (`P ≥ √(P² + Q²) cos h`), else at an end (`c + P cos h + |Q| sin h`), and likewise
/// for the trough. Exact extremes for a few products, which rule most atoms in or out without
/// solving for their zeros.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Around {
    hull: Interval,
    cos: f64,
    sin: f64,
    cos_half: f64,
    sin_half: f64,
}

impl Around {
    /// The summary of `[lo, hi]` (at most one turn).
    pub fn new(hull: Interval) -> Around {
        let half = (0.5 * (hull.hi - hull.lo)).min(PI);
        let (sin, cos) = (0.5 * (hull.lo + hull.hi)).sin_cos();
        let (sin_half, cos_half) = half.sin_cos();
        Around {
            hull,
            cos,
            sin,
            cos_half,
            sin_half,
        }
    }

    /// Bounds of `f` over the window (conservative: a relative 1e-12 of its coefficients, and
    /// 1e-9 of its amplitude for the rounding of the middle and half width, on either side).
    pub fn bounds(&self, f: &Trig) -> (f64, f64) {
        let p = f.alpha * self.cos + f.beta * self.sin;
        let q = f.beta * self.cos - f.alpha * self.sin;
        let amp = (p * p + q * q).sqrt();
        let crest = amp * self.cos_half;
        let ends = self.cos_half * p;
        let side = self.sin_half * q.abs();
        let hi = if p >= crest { amp } else { ends + side };
        let lo = if -p >= crest { -amp } else { ends - side };
        let spread = 1e-12 * (f.alpha.abs() + f.beta.abs() + f.gamma.abs()) + 1e-9 * amp;
        (f.gamma + lo - spread, f.gamma + hi + spread)
    }

    /// `{φ ∈ hull : f(φ) + slack ≥ 0}`, solved only when the bounds cannot tell.
    fn at_least(&self, f: Trig, slack: f64) -> Spans {
        let (lo, hi) = self.bounds(&f);
        if lo + slack >= 0.0 {
            Spans::single(self.hull)
        } else if hi + slack < 0.0 {
            Spans::EMPTY
        } else {
            f.plus(slack).nonneg_in(self.hull)
        }
    }

    /// `{φ ∈ hull : f(φ) ≤ slack}`.
    fn at_most(&self, f: Trig, slack: f64) -> Spans {
        self.at_least(f.neg(), slack)
    }
}

/// `{φ ∈ window : S(l_{p_φ, q_φ}, f)}` for an edge turning by φ about the unit `axis` (through
/// the origin) against a fixed face. `window` lies within one turn.
#[cfg(test)]
pub(crate) fn edge_face(
    p: &V3,
    q: &V3,
    f: &Face,
    axis: &V3,
    window: &Spans,
    tol: &Tolerance,
) -> Spans {
    let (Some(first), Some(last)) = (window.as_slice().first(), window.as_slice().last()) else {
        return Spans::EMPTY;
    };
    let around = Around::new(Interval {
        lo: first.lo,
        hi: last.hi,
    });
    edge_face_around(p, q, f, axis, window, &around, tol)
}

/// [`edge_face`] with the window's hull summarised by the caller (shared by the six edge–face
/// pairs of a pair of faces).
#[allow(clippy::too_many_arguments)]
pub(crate) fn edge_face_around(
    p: &V3,
    q: &V3,
    f: &Face,
    axis: &V3,
    window: &Spans,
    around: &Around,
    tol: &Tolerance,
) -> Spans {
    if window.is_empty() {
        return Spans::EMPTY;
    }
    let d = q - p;
    let nn = f.n_norm;
    let dl = d.norm();
    let g = lin(&f.n, &d, axis);
    let kg = tol.parallel * nn * dl;
    if g.alpha.abs() <= kg && g.beta.abs() <= kg && g.gamma.abs() <= kg {
        // parallel throughout the turn: Lemma 2.1
        return Spans::EMPTY;
    }
    let th = tol.dist * nn;
    let hp = lin(&f.n, p, axis).plus(-f.offset);
    let hq = lin(&f.n, q, axis).plus(-f.offset);
    // outward: g ≥ 0, hq ≥ 0, hp ≤ 0, D_i ≥ 0; inward: g ≤ 0, hp ≥ 0, hq ≤ 0, D_i ≤ 0
    let mut out = window.intersect(&around.at_least(hq, th));
    if !out.is_empty() {
        out = out.intersect(&around.at_most(hp, th));
    }
    let mut inw = window.intersect(&around.at_least(hp, th));
    if !inw.is_empty() {
        inw = inw.intersect(&around.at_most(hq, th));
    }
    if out.is_empty() && inw.is_empty() {
        return Spans::EMPTY;
    }
    if !out.is_empty() {
        out = out.intersect(&around.at_least(g, kg));
    }
    if !inw.is_empty() {
        inw = inw.intersect(&around.at_most(g, kg));
    }
    let m = p.cross(&d);
    let e = f.edges();
    for ((ei, vi), el) in e.iter().zip(&f.v).zip(&f.e_len) {
        if out.is_empty() && inw.is_empty() {
            return Spans::EMPTY;
        }
        let di = lin(ei, &m, axis).minus(lin(&ei.cross(vi), &d, axis));
        let slack = tol.dist * dl * el;
        if !out.is_empty() {
            out = out.intersect(&around.at_least(di, slack));
        }
        if !inw.is_empty() {
            inw = inw.intersect(&around.at_most(di, slack));
        }
    }
    let both = out.union(&inw);
    // drop isolated instants at which the edge lies in the face's plane (Lemma 2.1): there
    // every determinant vanishes and the closed predicate holds whether or not they overlap
    let mut kept = Spans::EMPTY;
    for iv in both.as_slice() {
        let degenerate = iv.hi - iv.lo <= DEGENERATE_SPAN
            && g.eval(0.5 * (iv.lo + iv.hi)).abs() <= DEGENERATE_PARALLEL * nn * dl;
        if !degenerate {
            kept.push(*iv);
        }
    }
    kept
}

/// All collision pieces (in φ) of the robot at `pose` turning about the unit world `axis_w`
/// through its reference point, `φ ∈ phis` (at most one turn).
pub(crate) fn sweep(
    ph: &Polyhedra,
    pose: &Pose,
    axis_w: &V3,
    phis: Interval,
    sink: &mut Hits,
    caches: &mut Caches,
    counts: &mut CallCounts,
) {
    let (robot, obst) = (&ph.robot, &ph.obstacles);
    let margin = 4.0 * ph.tol.dist;
    let axis = pose.body_dir(axis_w).normalize();
    let turning = AngleRange::new(phis.lo, phis.hi);
    if !turn_may_reach(ph, pose, axis_w, &turning, margin) {
        return;
    }
    let cyl = CylFrame::new(&axis);
    let Caches {
        cyl_boxes,
        nodes,
        swept,
        vertex_arcs,
        robot_edges,
        obst_edges,
        obst_nodes,
        obst_world,
        obst_faces,
        pieces,
        ..
    } = caches;
    cyl_boxes.reset(robot.faces.len());
    robot_edges.reset(robot.edges.len());
    obst_edges.reset(obst.edges.len());
    let mut pairs = FacePairs {
        ph,
        axis,
        margin,
        cyl,
        whole: Spans::single(phis),
        robot_boxes: cyl_boxes,
        robot_edges,
        obst_edges,
    };
    if ph.enveloping {
        let memos = DescentMemos {
            robot_nodes: nodes,
            robot_swept: swept,
            vertex_arcs,
            obst_nodes,
            obst_world,
            obst_faces,
        };
        descend_both(
            &mut pairs, memos, pose, axis_w, &turning, phis, sink, counts,
        );
    } else {
        'all: for o in 0..obst.faces.len() as u32 {
            let of = Face::new(obst.corners(o).map(|x| pose.body_point(&x)));
            let obox = cyl.box_of(&of.v, margin);
            for r in 0..robot.faces.len() as u32 {
                if !pairs.pair(r, o, &of, &obox, phis, sink, counts) {
                    break 'all;
                }
            }
        }
    }
    if !sink.done() {
        containment::rotation(ph, pose, axis_w, phis, sink, pieces, counts);
    }
}

/// Whether the turning robot can touch an obstacle at all: the first level of the descent,
/// cheap enough to rule out most far-away turns at once. The robot's ball about the reference
/// point does not move while it turns (enveloping only); then the world box the robot sweeps
/// must meet the obstacles' box.
fn turn_may_reach(
    ph: &Polyhedra,
    pose: &Pose,
    axis_w: &V3,
    turning: &AngleRange,
    margin: f64,
) -> bool {
    let (robot, obst) = (&ph.robot, &ph.obstacles);
    let reach = robot.radius + margin;
    if ph.enveloping
        && !obst
            .parts
            .iter()
            .any(|p| (pose.pos - p.sphere.0).norm() <= reach + p.sphere.1)
    {
        return false;
    }
    let swept_world = swept_box(pose, &robot.aabb, robot.radius, axis_w, turning).grown(margin);
    swept_world.overlaps(&obst.aabb)
}

/// What every pair of faces of one turn shares: the axis in the robot's frame, its cylindrical
/// frame, and the per-face and per-edge cylindrical boxes, computed once per call and reused by
/// all the pairs.
struct FacePairs<'a> {
    ph: &'a Polyhedra,
    /// The axis in the robot's frame.
    axis: V3,
    margin: f64,
    cyl: CylFrame,
    /// The whole turn, the window of every pair when not enveloping.
    whole: Spans,
    robot_boxes: &'a mut Memo<CylBox>,
    robot_edges: &'a mut Memo<CylBox>,
    obst_edges: &'a mut Memo<CylBox>,
}

/// The memos of the descent of both trees, apart from those of the pairs of faces (which the
/// descent lends to [`FacePairs`] while it holds these).
struct DescentMemos<'a> {
    robot_nodes: &'a mut Memo<NodeBounds>,
    robot_swept: &'a mut Memo<Aabb>,
    vertex_arcs: &'a mut Memo<Aabb>,
    obst_nodes: &'a mut Memo<ObstNodeBounds>,
    obst_world: &'a mut Memo<Aabb>,
    obst_faces: &'a mut Memo<(Face, CylBox)>,
}

/// A pair's window, narrowed again whenever the sink has learnt of new collisions since: the
/// pair is solved only where it can still change the union.
struct PairWindow {
    spans: Spans,
    /// The sink's generation the window was last narrowed at.
    known: u64,
    enveloping: bool,
}

impl PairWindow {
    /// Narrows the window to what is not yet known to collide; whether anything is left.
    #[inline]
    fn narrow(&mut self, sink: &Hits) -> bool {
        if self.enveloping && sink.generation() != self.known {
            self.known = sink.generation();
            self.spans = sink.uncovered(&self.spans, CLIP_OVERLAP);
        }
        !self.spans.is_empty()
    }
}

impl FacePairs<'_> {
    /// Robot face `r` against obstacle face `o` (`of`: in the robot's frame, `obox`: its
    /// cylindrical box) for φ in `w`; returns whether to go on.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn pair(
        &mut self,
        r: u32,
        o: u32,
        of: &Face,
        obox: &CylBox,
        w: Interval,
        sink: &mut Hits,
        counts: &mut CallCounts,
    ) -> bool {
        if sink.interrupted() {
            return false;
        }
        let (ph, robot, tol, axis) = (self.ph, &self.ph.robot, &self.ph.tol, self.axis);
        let rc = robot.corners(r);
        let Some((pair_window, rbox)) = self.face_window(r, &rc, obox, w) else {
            return true;
        };
        // only where the pair can change the union: not inside what is known to collide
        let known = sink.generation();
        let pair_window = if ph.enveloping {
            sink.uncovered(&pair_window, CLIP_OVERLAP)
        } else {
            pair_window
        };
        let (Some(first), Some(last)) = (
            pair_window.as_slice().first(),
            pair_window.as_slice().last(),
        ) else {
            return true;
        };
        let hull = Interval {
            lo: first.lo,
            hi: last.hi,
        };
        if ph.enveloping && sink.covers(hull) {
            return true;
        }
        let around = Around::new(hull);
        // the robot face off the obstacle face's plane: no robot edge reaches that face, and
        // (well off, beyond the in-plane slack of the determinants too) no obstacle edge, which
        // lies in that plane, reaches the robot face
        let rf = robot.face(r);
        let robot_off = if ph.enveloping {
            off_plane(&rc, of, &axis, &around, tol)
        } else {
            0.0
        };
        if ph.enveloping && robot_off > OFF_FAR {
            return true;
        }
        if ph.enveloping
            && (outside_prism(&rc, of, &axis, &around, tol)
                || outside_prism(&of.v, rf, &-axis, &around, tol))
        {
            return true;
        }
        let mut window = PairWindow {
            spans: pair_window,
            known,
            enveloping: ph.enveloping,
        };
        if robot_off <= OFF_NEAR {
            if let ControlFlow::Break(go_on) =
                self.robot_edges_on(r, of, obox, w, &around, &mut window, sink, counts)
            {
                return go_on;
            }
        }
        if ph.enveloping && off_plane(&of.v, rf, &-axis, &around, tol) > OFF_NEAR {
            return true;
        }
        self.obstacle_edges_on(
            o,
            of,
            rf,
            rbox.as_ref(),
            w,
            &around,
            &mut window,
            sink,
            counts,
        )
    }

    /// The window of robot face `r` (corners `rc`) against an obstacle face's box `obox` within
    /// `w`, with the robot face's cylindrical box when enveloping; `None` when the boxes never
    /// meet, whatever the angle.
    #[inline]
    fn face_window(
        &mut self,
        r: u32,
        rc: &[V3; 3],
        obox: &CylBox,
        w: Interval,
    ) -> Option<(Spans, Option<CylBox>)> {
        if !self.ph.enveloping {
            return Some((self.whole, None));
        }
        let (cyl, margin) = (&self.cyl, self.margin);
        let b = *self
            .robot_boxes
            .get_or_insert_with(r as usize, || cyl.box_of(rc, margin));
        if !b.fixed_overlap(obox) {
            return None;
        }
        let spans = match b.turn_window(obox) {
            Some((start, length)) => arc_in_window(Arc { start, length }, w),
            None => Spans::single(w),
        };
        Some((spans, Some(b)))
    }

    /// The edges of robot face `r`, turning by `+φ`, against the obstacle face `of`. Breaks
    /// with whether to go on when the pair is done: its window emptied (`true`) or the sink
    /// asked to stop (`false`).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn robot_edges_on(
        &mut self,
        r: u32,
        of: &Face,
        obox: &CylBox,
        w: Interval,
        around: &Around,
        window: &mut PairWindow,
        sink: &mut Hits,
        counts: &mut CallCounts,
    ) -> ControlFlow<bool> {
        let (ph, robot, tol) = (self.ph, &self.ph.robot, &self.ph.tol);
        let (cyl, margin) = (&self.cyl, self.margin);
        for &e in robot.owned_edges(r) {
            if !window.narrow(sink) {
                return ControlFlow::Break(true);
            }
            let (p, q) = robot.edge(e);
            // the edge's own cylindrical box against the obstacle face's: a narrower window
            // than the face's, or none
            if ph.enveloping {
                let eb = self
                    .robot_edges
                    .get_or_insert_with(e as usize, || cyl.box_of(&[p, q, q], margin));
                if !edge_reaches(eb, obox, &window.spans, w) {
                    continue;
                }
            }
            counts.pairs_tested += 1;
            for iv in
                edge_face_around(&p, &q, of, &self.axis, &window.spans, around, tol).as_slice()
            {
                if sink.add(*iv).is_break() {
                    return ControlFlow::Break(false);
                }
            }
        }
        ControlFlow::Continue(())
    }

    /// The edges of obstacle face `o` (`of` in the robot's frame), turning by `−φ`, against
    /// robot face `rf` (cylindrical box `rbox` when enveloping); returns whether to go on.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn obstacle_edges_on(
        &mut self,
        o: u32,
        of: &Face,
        rf: &Face,
        rbox: Option<&CylBox>,
        w: Interval,
        around: &Around,
        window: &mut PairWindow,
        sink: &mut Hits,
        counts: &mut CallCounts,
    ) -> bool {
        let (obst, tol) = (&self.ph.obstacles, &self.ph.tol);
        let (cyl, margin) = (&self.cyl, self.margin);
        let ids = obst.faces[o as usize];
        for &e in obst.owned_edges(o) {
            if !window.narrow(sink) {
                return true;
            }
            let [a, b] = obst.edges[e as usize];
            let pos = |v: u32| ids.iter().position(|&i| i == v).unwrap_or(0);
            let (p, q) = (of.v[pos(a)], of.v[pos(b)]);
            // the obstacle edge's cylindrical box: the robot face turned by +φ must reach it
            if let Some(rb) = rbox {
                let eb = self
                    .obst_edges
                    .get_or_insert_with(e as usize, || cyl.box_of(&[p, q, q], margin));
                if !edge_reaches(rb, eb, &window.spans, w) {
                    continue;
                }
            }
            counts.pairs_tested += 1;
            for iv in
                edge_face_around(&p, &q, rf, &-self.axis, &window.spans, around, tol).as_slice()
            {
                if sink.add(*iv).is_break() {
                    return false;
                }
            }
        }
        true
    }
}

/// How far a face's `corners` stay on one side of `face`'s plane over the window summarised by
/// `around`, in units of the predicate's slack (0: they may reach it). An edge meets a face only
/// where its ends are not both strictly on one side of the face's plane (the predicate's first
/// atoms, with their slack doubled): if all three corners of a face stay on one side for the
/// whole window, its edges are skipped.
#[inline]
fn off_plane(corners: &[V3; 3], face: &Face, axis: &V3, around: &Around, tol: &Tolerance) -> f64 {
    let th = tol.dist * face.n_norm;
    let b = corners.map(|x| around.bounds(&lin(&face.n, &x, axis).plus(-face.offset)));
    let above = b.iter().map(|(lo, _)| *lo).fold(f64::INFINITY, f64::min);
    let below = b.iter().map(|(_, hi)| -*hi).fold(f64::INFINITY, f64::min);
    (above.max(below) / th).max(0.0)
}

/// Whether a face's `corners` all stay outside the prism over `face` (beyond the plane through
/// one of its edges, perpendicular to it) over the window summarised by `around`: then the two
/// faces cannot meet either.
#[inline]
fn outside_prism(
    corners: &[V3; 3],
    face: &Face,
    axis: &V3,
    around: &Around,
    tol: &Tolerance,
) -> bool {
    let e = face.edges();
    (0..3).any(|i| {
        let m = face.n.cross(&e[i]);
        let th = OFF_FAR * tol.dist * face.n_norm * face.e_len[i];
        let c = m.dot(&face.v[i]);
        corners
            .iter()
            .all(|x| around.bounds(&lin(&m, x, axis).plus(-c)).1 < -th)
    })
}

/// Both trees at once, in cylindrical coordinates about the axis (CHS §2.3.2): height and
/// radius of a node do not change while the robot turns, so nodes whose ranges miss are pruned
/// for the whole turn; away from the axis both nodes have an angular sector, and the robot's,
/// turned by φ, meets the obstacle's only for φ in a window that narrows on the way down. Robot
/// nodes are bounded in the robot's frame, obstacle nodes in the world (the same cylinder, its
/// frame turned by the pose). Besides, each robot node's ball (about its box's centre) swept
/// along its arc gives a world box for the whole turn (computed once per node and call), and
/// each robot face its swept world box (the arcs of its corners).
///
/// Per call, every obstacle node's bounds and every obstacle face brought into the robot's
/// frame (with its cylindrical box) are computed once (`obst_nodes`, `obst_faces`): the same
/// values every time, so the same answer, bit for bit. Each pair of nodes hands the robot
/// node's cylindrical bounds down with its window, so that at the leaves an obstacle face whose
/// height or radius range misses the robot leaf's is skipped for all of the leaf's faces at once
/// (each face's own range lies inside the leaf's, so `CylBox::fixed_overlap` would rule out
/// every one of those pairs anyway).
#[allow(clippy::too_many_arguments)]
fn descend_both(
    pairs: &mut FacePairs,
    memos: DescentMemos,
    pose: &Pose,
    axis_w: &V3,
    turning: &AngleRange,
    phis: Interval,
    sink: &mut Hits,
    counts: &mut CallCounts,
) {
    let ph = pairs.ph;
    let (robot, obst, margin, cyl) = (&ph.robot, &ph.obstacles, pairs.margin, pairs.cyl);
    let DescentMemos {
        robot_nodes,
        robot_swept,
        vertex_arcs,
        obst_nodes,
        obst_world,
        obst_faces,
    } = memos;
    let world_cyl = cyl.rotated(&pose.rot);
    robot_nodes.reset(robot.bvh.node_count());
    robot_swept.reset(robot.faces.len());
    vertex_arcs.reset(robot.vertices.len());
    obst_nodes.reset(obst.bvh.node_count());
    obst_world.reset(obst.faces.len());
    obst_faces.reset(obst.faces.len());
    let unbounded = CylBounds::everything();
    // a first-collision question: node pairs whose window starts after the earliest piece found
    // so far are pruned (`cutoff`), and the earlier window is descended first
    let prefix = sink.is_prefix();
    let cutoff = Cell::new(f64::INFINITY);
    let test = |a: u32, b: u32, rb: &Aabb, ob: &Aabb, (w, _): (Interval, CylBounds)| {
        let (rn, rsector, swept) = *robot_nodes.get_or_insert_with(a as usize, || {
            let half = 0.5 * (rb.hi - rb.lo);
            let n = cyl.node_bounds(&rb.centre(), &half, margin);
            let c = pose.rot * rb.centre();
            let ball = half.norm() * (1.0 + 1e-12) + margin;
            let swept = turning.arc_box(&c, axis_w).grown(ball).shifted(&pose.pos);
            (n, n.sector(), swept)
        });
        if !swept.overlaps(ob) {
            return None;
        }
        let (on, osector) = *obst_nodes.get_or_insert_with(b as usize, || {
            let on =
                world_cyl.node_bounds(&(ob.centre() - pose.pos), &(0.5 * (ob.hi - ob.lo)), margin);
            (on, on.sector())
        });
        if !rn.fixed_overlap(&on) {
            return None;
        }
        let w = match (rsector, osector) {
            (Some(m), Some(f)) => sector_window(m, f, w)?,
            _ => w,
        };
        Some((w, rn))
    };
    let leaves = |ri: &[u32], oi: &[u32], (w, rn): (Interval, CylBounds)| {
        if sink.covers(w) {
            return true;
        }
        for &o in oi {
            let (of, obox) = obst_faces.get_or_insert_with(o as usize, || {
                let of = Face::new(obst.corners(o).map(|x| pose.body_point(&x)));
                let obox = cyl.box_of(&of.v, margin);
                (of, obox)
            });
            if !rn.fixed_overlap_box(obox) {
                continue;
            }
            let owbox = *obst_world
                .get_or_insert_with(o as usize, || Aabb::of_points(obst.corners(o).iter()));
            let mut face_swept_box = |r: u32| {
                *robot_swept.get_or_insert_with(r as usize, || {
                    face_swept(pose, robot, r, axis_w, turning, margin, vertex_arcs)
                })
            };
            if !ri.iter().any(|&r| face_swept_box(r).overlaps(&owbox)) {
                continue;
            }
            for &r in ri {
                if !face_swept_box(r).overlaps(&owbox) {
                    continue;
                }
                if !pairs.pair(r, o, of, obox, w, sink, counts) {
                    return false;
                }
            }
        }
        if prefix {
            note_earliest(sink, &cutoff);
        }
        true
    };
    descend_pairs(
        &robot.bvh,
        &obst.bvh,
        (phis, unbounded),
        prefix,
        &cutoff,
        |(w, _): &(Interval, CylBounds)| w.lo,
        test,
        leaves,
    );
}

/// Whether a box `m` turning by `+φ` can meet the fixed box `f` (one of them an edge's, the
/// other a face's) within the faces' window `pair` (part of the node window `w`): the same tests
/// as for the faces, on the edge's smaller box. (The pair is then solved in the faces' window:
/// a narrower one would change nothing but the rounding of the answer.)
fn edge_reaches(m: &CylBox, f: &CylBox, pair: &Spans, w: Interval) -> bool {
    if !m.fixed_overlap(f) {
        return false;
    }
    let Some((start, length)) = m.turn_window(f) else {
        return true;
    };
    !pair
        .intersect(&arc_in_window(Arc { start, length }, w))
        .is_empty()
}

/// The world box around everything robot face `r` at `pose` sweeps while turning about the
/// world `axis` through `pose`'s position: the arcs of its corners (the face is the hull of its
/// corners, and a turned hull is the hull of the turned corners), grown by `margin` and by a
/// relative 1e-12 against rounding. A corner's arc box is computed once per call
/// (`vertex_arcs`): a vertex is shared by about six faces.
fn face_swept(
    pose: &Pose,
    robot: &Body,
    r: u32,
    axis: &V3,
    turning: &AngleRange,
    margin: f64,
    vertex_arcs: &mut Memo<Aabb>,
) -> Aabb {
    let b = robot.faces[r as usize].iter().fold(Aabb::EMPTY, |b, &i| {
        b.merge(vertex_arcs.get_or_insert_with(i as usize, || {
            turning.arc_box(&(pose.rot * robot.vertices[i as usize]), axis)
        }))
    });
    let size = b.lo.abs().max().max(b.hi.abs().max());
    b.grown(margin + 1e-12 * size).shifted(&pose.pos)
}

#[cfg(test)]
mod tests {
    use super::super::predicate::edge_meets_face;
    use super::super::turning::turn;
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    fn v(a: [f64; 3]) -> V3 {
        V3::new(a[0], a[1], a[2])
    }

    proptest! {
        /// The window's bounds hold every sampled value and are tight: the sampled extremes
        /// come within the sampling error (amplitude × step) of them.
        #[test]
        fn window_bounds_are_exact(
            f in prop::array::uniform3(-3.0f64..3.0),
            lo in -7.0f64..7.0,
            len in 0.0f64..6.3,
        ) {
            let f = Trig { alpha: f[0], beta: f[1], gamma: f[2] };
            let around = Around::new(Interval { lo, hi: lo + len });
            let (b_lo, b_hi) = around.bounds(&f);
            let (mut s_lo, mut s_hi) = (f64::INFINITY, f64::NEG_INFINITY);
            const N: usize = 4000;
            for k in 0..=N {
                let v = f.eval(lo + len * k as f64 / N as f64);
                prop_assert!(b_lo <= v && v <= b_hi, "{} outside [{}, {}]", v, b_lo, b_hi);
                s_lo = s_lo.min(v);
                s_hi = s_hi.max(v);
            }
            let slack = f.amplitude() * len / N as f64 + 1e-8;
            prop_assert!(s_lo - b_lo <= slack && b_hi - s_hi <= slack, "[{}, {}] vs sampled [{}, {}]", b_lo, b_hi, s_lo, s_hi);
        }

        /// The arcs agree with the static predicate at sampled φ.
        #[test]
        fn arcs_match_static_predicate(
            c in prop::array::uniform9(-1.0f64..1.0),
            e in prop::array::uniform6(-1.5f64..1.5),
            a in prop::array::uniform3(-1.0f64..1.0),
        ) {
            let f = Face::new([v([c[0], c[1], c[2]]), v([c[3], c[4], c[5]]), v([c[6], c[7], c[8]])]);
            prop_assume!(f.n_norm > 1e-3);
            let axis = v(a);
            prop_assume!(axis.norm() > 1e-2);
            let axis = axis.normalize();
            let (p, q) = (v([e[0], e[1], e[2]]), v([e[3], e[4], e[5]]));
            let tol = Tolerance::for_scale(1.0);
            let w = Spans::single(Interval { lo: -PI, hi: PI });
            let set = edge_face(&p, &q, &f, &axis, &w, &tol);
            for k in 0..=1000 {
                let phi = -PI + k as f64 * (2.0 * PI / 1000.0);
                let (pp, qq) = (turn(&p, &axis, phi), turn(&q, &axis, phi));
                let stat = edge_meets_face(&pp, &qq, &f, &tol);
                let near = set.as_slice().iter().any(|iv| iv.lo - 1e-6 <= phi && phi <= iv.hi + 1e-6);
                let strictly = set.as_slice().iter().any(|iv| iv.lo + 1e-6 < phi && phi < iv.hi - 1e-6);
                if stat { prop_assert!(near, "φ = {} collides statically, set {:?}", phi, set); }
                if strictly { prop_assert!(stat, "φ = {} inside {:?} but static says free", phi, set); }
            }
        }
    }
}
