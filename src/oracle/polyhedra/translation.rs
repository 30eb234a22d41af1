//! The translational case (CHS §2.2): the robot moves by `λ·r`.
//!
//! With the edge moving and the face fixed, every atom of `S(l_{p,q}, f)` is linear in λ:
//! `n·x^λ − c = λ·(n·r) + (n·x − c)` and, since `q^λ − p^λ = q − p`,
//! `det[q−p, e, p^λ − v] = λ·((q−p)×e)·r + ((q−p)×e)·(p − v)`. Each gives one half-line (or
//! everything, or nothing), so a conjunction gives one interval. The case split `n·(q−p)` is
//! constant under translation and picks the outward or the inward case once per pair.
//!
//! For obstacle edges against robot faces the roles swap: relative to the robot the obstacle
//! moves by `−λ·r`. The pieces of all pairs are merged by one sort ([`IntervalList::from_unsorted`]),
//! `O(n log n)` for `n` pairs — the seed's balanced ∨-tree in another guise.
//!
//! [`IntervalList::from_unsorted`]: crate::interval::IntervalList::from_unsorted

use super::body::Face;
use super::caches::Caches;
use super::containment;
use super::envelope::{sphere_sweep, FrameBox, MotionFrame};
use super::model::{descend_pairs, note_earliest, Polyhedra, SMALL_ROBOT};
use super::pose::{Aabb, Pose};
use super::predicate::Tolerance;
use crate::geometry::kernel::hits::Hits;
use crate::geometry::kernel::memo::Memo;
use crate::interval::Interval;
use crate::oracle::CallCounts;
use nalgebra::Vector3;
use std::cell::Cell;
use std::ops::ControlFlow;

type V3 = Vector3<f64>;

/// `{λ ∈ window : S(l_{p+λr, q+λr}, f)}` for an edge moving by `λ·dir` against a fixed face:
/// one interval or none. Parallel pairs give none (Lemma 2.1).
pub(crate) fn edge_face(
    p: &V3,
    q: &V3,
    f: &Face,
    dir: &V3,
    window: Interval,
    tol: &Tolerance,
) -> Option<Interval> {
    let d = q - p;
    let nn = f.n_norm;
    let g = f.n.dot(&d);
    // outward (g > 0) or inward (g < 0): every atom is multiplied by the sign of g
    let s = g.signum();
    let (mut lo, mut hi) = (window.lo, window.hi);
    // s·(a·λ + b) ≥ −slack
    let mut atom = |a: f64, b: f64, slack: f64| -> bool {
        let (a, b) = (s * a, s * b);
        if a > 0.0 {
            lo = lo.max((-slack - b) / a);
        } else if a < 0.0 {
            hi = hi.min((-slack - b) / a);
        } else if b < -slack {
            return false;
        }
        lo <= hi
    };
    let nr = f.n.dot(dir);
    let th = tol.dist * nn;
    // the edge's tail is behind the plane, its head in front (outward; mirrored inward); these
    // two atoms first, which rule out most pairs without the edge's length (a square root):
    // a parallel pair gives none either way
    if !atom(-nr, f.offset - f.n.dot(p), th) || !atom(nr, f.n.dot(q) - f.offset, th) {
        return None;
    }
    let dl = d.norm();
    if g.abs() <= tol.parallel * nn * dl {
        return None;
    }
    let e = f.edges();
    for ((ei, vi), el) in e.iter().zip(&f.v).zip(&f.e_len) {
        let w = d.cross(ei);
        if !atom(w.dot(dir), w.dot(&(p - vi)), tol.dist * dl * el) {
            return None;
        }
    }
    Some(Interval { lo, hi })
}

/// The λ of `window` at which the triangle `corners`, moved by `λ·dir`, reaches the plane of the
/// fixed face `f`: an edge of it meets `f` only there (the first atoms of the predicate: one end
/// on each side of the plane, within its slack). All corners move alike, so their signed
/// distances share one slope and the condition `min ≤ slack`, `max ≥ −slack` is one interval.
/// The slack is twice the predicate's, which keeps rounding on the safe side.
fn straddle(
    corners: &[V3; 3],
    f: &Face,
    dir: &V3,
    tol: &Tolerance,
    window: Interval,
) -> Option<Interval> {
    let th = 2.0 * tol.dist * f.n_norm;
    let a = corners.map(|x| f.n.dot(&x) - f.offset);
    let (lo, hi) = (a[0].min(a[1]).min(a[2]), a[0].max(a[1]).max(a[2]));
    let k = f.n.dot(dir);
    // lo + λk ≤ th and hi + λk ≥ −th
    let (x, y) = ((th - lo) / k, (-th - hi) / k);
    let iv = if k > 0.0 {
        Interval { lo: y, hi: x }
    } else if k < 0.0 {
        Interval { lo: x, hi: y }
    } else if lo <= th && hi >= -th {
        window
    } else {
        return None;
    };
    iv.meet(&window)
}

/// Position of vertex `v` among the corners `ids` of a face.
fn corner(ids: &[u32; 3], v: u32) -> usize {
    ids.iter().position(|&i| i == v).unwrap_or(0)
}

/// All collision pieces of the robot at `pose` moving by `t·dir_w` (world), `t ∈ range`.
pub(crate) fn sweep(
    ph: &Polyhedra,
    pose: &Pose,
    dir_w: &V3,
    range: Interval,
    sink: &mut Hits,
    caches: &mut Caches,
    counts: &mut CallCounts,
) {
    let Some(window) = reachable_window(ph, pose, dir_w, range) else {
        return;
    };
    let dir = pose.body_dir(dir_w);
    let Caches {
        frame_boxes,
        placed,
        pieces,
        ..
    } = caches;
    frame_boxes.reset(ph.robot.faces.len());
    let mut pairs = FacePairs {
        ph,
        dir,
        speed: dir.norm(),
        margin: 4.0 * ph.tol.dist,
        frame: MotionFrame::new(&dir),
        robot_boxes: frame_boxes,
    };
    if ph.enveloping && ph.robot.faces.len() <= SMALL_ROBOT {
        descend_obstacles(&mut pairs, pose, dir_w, window, sink, counts);
    } else if ph.enveloping {
        descend_both(&mut pairs, placed, pose, dir_w, window, sink, counts);
    } else {
        'all: for o in 0..ph.obstacles.faces.len() as u32 {
            let of = Face::new(ph.obstacles.corners(o).map(|x| pose.body_point(&x)));
            let obox = pairs.frame.box_of(&of.v);
            for r in 0..ph.robot.faces.len() as u32 {
                if !pairs.pair(r, o, &of, &obox, window, sink, counts) {
                    break 'all;
                }
            }
        }
    }
    if !sink.done() {
        containment::translation(ph, pose, dir_w, window, sink, pieces, counts);
    }
}

/// The part of `range` in which the robot can touch an obstacle at all: nothing can happen while
/// the robot's box, moving, misses the obstacles' box, which also makes an unbounded line
/// bounded; then (enveloping) the robot's ball about its reference point against each
/// obstacle's ball. `None` when the motion is free throughout.
fn reachable_window(ph: &Polyhedra, pose: &Pose, dir_w: &V3, range: Interval) -> Option<Interval> {
    let (robot, obst) = (&ph.robot, &ph.obstacles);
    let margin = 4.0 * ph.tol.dist;
    let window = pose
        .world_box(&robot.aabb)
        .sweep_range(dir_w, &obst.aabb.grown(margin))
        .and_then(|w| w.meet(&range))?;
    if !ph.enveloping {
        return Some(window);
    }
    let hull = obst
        .parts
        .iter()
        .filter_map(|p| {
            sphere_sweep(
                &pose.pos,
                dir_w,
                robot.radius + margin,
                &p.sphere.0,
                p.sphere.1,
            )
        })
        .reduce(|a, b| Interval {
            lo: a.lo.min(b.lo),
            hi: a.hi.max(b.hi),
        });
    hull.and_then(|h| h.meet(&window))
}

/// What every pair of faces of one translation shares: the motion in the robot's frame and the
/// per-face boxes of its frame, computed once per call and reused by all the pairs.
struct FacePairs<'a> {
    ph: &'a Polyhedra,
    /// The motion's direction in the robot's frame.
    dir: V3,
    speed: f64,
    margin: f64,
    frame: MotionFrame,
    robot_boxes: &'a mut Memo<FrameBox>,
}

impl FacePairs<'_> {
    /// Robot face `r` against obstacle face `o` (`of`: in the robot's frame, `obox`: its box in
    /// the motion frame) for λ in `w`; returns whether to go on.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn pair(
        &mut self,
        r: u32,
        o: u32,
        of: &Face,
        obox: &FrameBox,
        w: Interval,
        sink: &mut Hits,
        counts: &mut CallCounts,
    ) -> bool {
        if sink.interrupted() {
            return false;
        }
        let (ph, robot, obst, tol) = (self.ph, &self.ph.robot, &self.ph.obstacles, self.ph.tol);
        let dir = self.dir;
        let rc = robot.corners(r);
        let pair_window = if ph.enveloping {
            let frame = &self.frame;
            let rbox = self
                .robot_boxes
                .get_or_insert_with(r as usize, || frame.box_of(&rc));
            match rbox
                .sweep_window(obox, self.speed, self.margin)
                .and_then(|x| x.meet(&w))
            {
                Some(x) => x,
                None => return true,
            }
        } else {
            w
        };
        if ph.enveloping && sink.covers(pair_window) {
            return true;
        }
        // robot edges moving by +λ·dir against the obstacle face, only while the robot face
        // reaches the obstacle face's plane
        let rf = robot.face(r);
        let robot_window = if ph.enveloping {
            straddle(&rc, of, &dir, &tol, pair_window)
        } else {
            Some(pair_window)
        };
        if let Some(w) = robot_window {
            for &e in robot.owned_edges(r) {
                let (p, q) = robot.edge(e);
                counts.pairs_tested += 1;
                if let Some(iv) = edge_face(&p, &q, of, &dir, w, &tol) {
                    if sink.add(iv).is_break() {
                        return false;
                    }
                }
            }
        }
        // obstacle edges moving by −λ·dir against the robot face, likewise
        let obstacle_window = if ph.enveloping {
            straddle(&of.v, rf, &-dir, &tol, pair_window)
        } else {
            Some(pair_window)
        };
        let Some(w) = obstacle_window else {
            return true;
        };
        let ids = obst.faces[o as usize];
        for &e in obst.owned_edges(o) {
            let [a, b] = obst.edges[e as usize];
            let (p, q) = (of.v[corner(&ids, a)], of.v[corner(&ids, b)]);
            counts.pairs_tested += 1;
            if let Some(iv) = edge_face(&p, &q, rf, &-dir, w, &tol) {
                if sink.add(iv).is_break() {
                    return false;
                }
            }
        }
        true
    }
}

/// A robot of a few leaves: the obstacle tree descended with the robot's box moving along the
/// motion, each node and face entered only for the λ at which the moving box meets it (exact for
/// two boxes, so conservative for their contents; far tighter than the box around the whole
/// sweep once the motion is long and not axis-parallel), then the robot's tree likewise with
/// each obstacle face's box, for that face's λ only.
fn descend_obstacles(
    pairs: &mut FacePairs,
    pose: &Pose,
    dir_w: &V3,
    window: Interval,
    sink: &mut Hits,
    counts: &mut CallCounts,
) {
    let ph = pairs.ph;
    let (robot, obst, margin) = (&ph.robot, &ph.obstacles, pairs.margin);
    let robot_world = pose.world_box(&robot.aabb);
    // (a node or face whose window is known to collide already is skipped: the union cannot
    // change)
    let _ = obst.bvh.query_windows(
        sink,
        |sink, b| {
            let w = robot_world
                .sweep_range(dir_w, &b.grown(margin))?
                .meet(&window)?;
            (!sink.covers(w)).then_some(w)
        },
        |sink, o, wo| {
            let of = Face::new(obst.corners(o).map(|x| pose.body_point(&x)));
            let obox = pairs.frame.box_of(&of.v);
            let b = Aabb::of_points(of.v.iter()).grown(margin);
            let dir = pairs.dir;
            let go_on = robot.bvh.visit(
                |rb| rb.sweep_range(&dir, &b).and_then(|x| x.meet(&wo)).is_some(),
                |r| pairs.pair(r, o, &of, &obox, wo, sink, counts),
            );
            if go_on {
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            }
        },
    );
}

/// Both trees at once: a robot node's box, placed at the pose (world frame) and moved by
/// λ·dir_w, against an obstacle node's box grown by the margin gives the λ for which the two may
/// meet (exact for two boxes, so conservative for their contents); the window only narrows on
/// the way down, and a pair of leaves passes it on to the per-face boxes of the motion frame.
fn descend_both(
    pairs: &mut FacePairs,
    placed: &mut Memo<Aabb>,
    pose: &Pose,
    dir_w: &V3,
    window: Interval,
    sink: &mut Hits,
    counts: &mut CallCounts,
) {
    let ph = pairs.ph;
    let (robot, obst, margin) = (&ph.robot, &ph.obstacles, pairs.margin);
    let dir_body = pairs.dir;
    placed.reset(robot.bvh.node_count());
    // a first-collision question: node pairs whose window starts after the earliest piece found
    // so far are pruned (`cutoff`), and the earlier window is descended first
    let prefix = sink.is_prefix();
    let cutoff = Cell::new(f64::INFINITY);
    let test = |a: u32, _: u32, rb: &Aabb, ob: &Aabb, w: Interval| {
        let placed = placed.get_or_insert_with(a as usize, || pose.world_box(rb));
        let w = placed.sweep_range(dir_w, &ob.grown(margin))?.meet(&w)?;
        // the same test in the robot's frame (the obstacle box turned into it), which is tight
        // where the first one is loose
        rb.sweep_range(&dir_body, &pose.body_box(ob).grown(margin))?
            .meet(&w)
    };
    let leaves = |ri: &[u32], oi: &[u32], w: Interval| {
        if sink.covers(w) {
            return true;
        }
        for &o in oi {
            let of = Face::new(obst.corners(o).map(|x| pose.body_point(&x)));
            let obox = pairs.frame.box_of(&of.v);
            for &r in ri {
                if !pairs.pair(r, o, &of, &obox, w, sink, counts) {
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
        window,
        prefix,
        &cutoff,
        |w| w.lo,
        test,
        leaves,
    );
}

#[cfg(test)]
mod tests {
    use super::super::predicate::edge_meets_face;
    use super::*;
    use proptest::prelude::*;

    fn v(a: [f64; 3]) -> V3 {
        V3::new(a[0], a[1], a[2])
    }

    #[test]
    fn edge_sliding_across_a_face() {
        let f = Face::new([v([0.0, 0.0, 0.0]), v([1.0, 0.0, 0.0]), v([0.0, 1.0, 0.0])]);
        let tol = Tolerance::for_scale(1.0);
        // a vertical edge at (x, 0.25) sliding along x from −1
        let iv = edge_face(
            &v([-1.0, 0.25, -1.0]),
            &v([-1.0, 0.25, 1.0]),
            &f,
            &v([1.0, 0.0, 0.0]),
            Interval::ALL,
            &tol,
        )
        .unwrap();
        assert!(
            (iv.lo - 1.0).abs() < 1e-9 && (iv.hi - 1.75).abs() < 1e-9,
            "{iv:?}"
        );
    }

    proptest! {
        /// The interval agrees with the static predicate at sampled λ.
        #[test]
        fn interval_matches_static_predicate(
            c in prop::array::uniform9(-1.0f64..1.0),
            e in prop::array::uniform6(-1.5f64..1.5),
            r in prop::array::uniform3(-1.0f64..1.0),
        ) {
            let f = Face::new([v([c[0], c[1], c[2]]), v([c[3], c[4], c[5]]), v([c[6], c[7], c[8]])]);
            prop_assume!(f.n_norm > 1e-3);
            let (p, q, dir) = (v([e[0], e[1], e[2]]), v([e[3], e[4], e[5]]), v(r));
            let tol = Tolerance::for_scale(1.0);
            let iv = edge_face(&p, &q, &f, &dir, Interval { lo: -3.0, hi: 3.0 }, &tol);
            for k in 0..=600 {
                let l = -3.0 + k as f64 * 0.01;
                let stat = edge_meets_face(&(p + l * dir), &(q + l * dir), &f, &tol);
                let inside = iv.is_some_and(|iv| iv.lo - 1e-9 <= l && l <= iv.hi + 1e-9);
                let strictly = iv.is_some_and(|iv| iv.lo + 1e-7 < l && l < iv.hi - 1e-7);
                if stat { prop_assert!(inside, "λ = {} collides statically, interval {:?}", l, iv); }
                if strictly { prop_assert!(stat, "λ = {} inside {:?} but static says free", l, iv); }
            }
        }
    }
}
