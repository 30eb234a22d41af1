//! A polyhedral robot among polyhedral obstacles in SE(3): *all* collision intervals of a
//! straight motion, exactly (CHS Chapter 2).
//!
//! Collision means that a robot triangle and an obstacle triangle meet (touching counts), or —
//! only when both meshes are closed — that one body lies inside the other (containment, CHS
//! §2.1). That is what OMPL.app asks of FCL on its open, double-sided triangle soups, plus
//! solids for closed meshes. Every obstacle mesh is a separate body.
//!
//! The seed separates the degrees of freedom (CHS Chapter 2: "either one object may rotate
//! about a fixed axis … or all may translate"), and so does this oracle:
//! - a **translation** (bounded segment or unbounded line) makes every atom of the edge–face
//!   predicate linear in the motion parameter (`translation.rs`, CHS §2.2);
//! - a **rotation about a fixed axis** through the robot's reference point (bounded angle or
//!   full turn) makes every atom `α cos φ + β sin φ + γ` (`rotation.rs`, `trig.rs`, CHS §2.3.2);
//! - the predicate is evaluated on interval lists (∧ = intersection, ∨ = union) and the
//!   results of all pairs are merged by one sort, `O(n log n)`;
//! - containment is decided along the path one surface point describes (`containment.rs`);
//! - enveloping (`envelope.rs`, `bvh.rs`) rules out far-away pairs first: a ball about the
//!   robot's reference point against a ball around each obstacle for the whole motion, then the
//!   robot's tree against the obstacles' tree, descended together with bounds swept over the
//!   motion (boxes along a translation, cylindrical height/radius/sector bounds and swept balls
//!   for a turn) that narrow the motion's window on the way down, then per-face boxes in a
//!   frame aligned with the motion, then — per pair of faces — whether each face reaches the
//!   other's plane at all. Robots of at most 128 faces query the obstacle tree with
//!   their swept box instead (static test and translations), which is cheaper for a few leaves.
//!   Every bound is conservative, with margins for rounding, so culling never loses a contact
//!   (tests/oracle_polyhedra.rs compares with brute force and with parry on alpha-1.5 and
//!   Apartment).
//!
//! `CallCounts::pairs_tested` counts the edge–face pairs evaluated after culling, the
//! point–face tests of containment, and for a static test six edge–face pairs per pair of
//! triangles examined.
//!
//! Numerics: closed intervals, and every atom of the predicate is relaxed by
//! [`Polyhedra::tolerance`] (10⁻¹¹ of the scene's size) in favour of collision, so that a contact
//! at an edge shared by two faces is not lost to rounding in both; edges within 10⁻¹⁰ rad of a
//! face's plane count as parallel (Lemma 2.1).
//!
//! Anything else — a linear change of quaternion coordinates, translation and rotation at
//! once — is [`OracleError::Unsupported`].
//!
//! All computations happen in one frame per call: the robot's body frame at `t = 0` (the
//! reference point at the origin). Obstacle faces are brought into it only when the tree
//! returns them.
//!
//! # Entry points for a robot arm
//!
//! The arm oracle needs, per joint, "the rotation intervals of a rigid body (a set of link
//! meshes) about an arbitrary fixed axis against static meshes" and "translation along an
//! axis". Both are this oracle with the body expressed in a frame whose origin lies on the
//! joint axis: build [`Polyhedra::new`] with the distal links' meshes in that frame (their
//! union is one robot mesh; the arm's own proximal links go with the static obstacles), place
//! the frame with the configuration `[origin; quaternion]`, and ask
//! [`CollisionOracle::intervals`] about a [`Motion`] with `Change::Rotation { axis, angle }`
//! (a revolute joint: every atom is `α cos φ + β sin φ + γ`, the kernel's
//! `geometry/kernel/trig.rs`) or `Change::Linear` with a zero quaternion part (a prismatic
//! joint). The per-call work is allocation-free (`tests/alloc_free_rigid.rs`), so a per-joint
//! oracle can be asked millions of times; what a per-configuration body would add is the
//! construction of its face tree ([`Polyhedra::new`]), which is linear-logarithmic in its faces.
//! [`Polyhedra::turn_about`] avoids it: a link built once in its own frame turns about an axis
//! through any pivot, its faces and tree shifted (linear, no welding or tree building) so that
//! the pivot becomes the reference point, the obstacles shared.

mod body;
mod caches;
mod containment;
mod envelope;
mod model;
mod pose;
mod predicate;
mod rotation;
mod translation;
mod turning;

pub use model::Polyhedra;
pub(crate) use pose::Aabb;

use caches::Caches;
use model::SMALL_ROBOT;
use pose::{Pose, V3};

use super::{CallCounts, CollisionOracle, OracleError, Workspace};
use crate::geometry::kernel::hits::Hits;
use crate::geometry::TriMesh;
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Motion};
pub(crate) use body::Body;
use body::Face;
pub(crate) use envelope::AngleRange;
use predicate::Tolerance;
use std::cell::RefCell;
use std::f64::consts::TAU;
use std::sync::Arc;

/// Most full turns a rotational motion may sweep (the collision set repeats every turn; this
/// bounds the size of the answer).
pub const MAX_TURNS: f64 = 1000.0;

/// Everything a call needs besides the oracle: the pieces, one turn's pieces, the caches.
/// One per thread, reused, so that a call allocates nothing but its answer.
#[derive(Default)]
struct Scratch {
    hits: Hits,
    turn: Hits,
    caches: Caches,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Runs `f` with this thread's scratch space (a fresh one should a call ever nest).
fn with_scratch<R>(f: impl FnOnce(&mut Scratch) -> R) -> R {
    SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut s) => f(&mut s),
        Err(_) => f(&mut Scratch::default()),
    })
}

/// What a motion does, in the world frame.
enum Kind {
    /// Nothing moves.
    Still,
    /// The reference point moves by `t · dir`.
    Translation(V3),
    /// The robot turns by `t · angle` (`angle > 0`) about the unit `axis` through its reference
    /// point.
    Rotation { axis: V3, angle: f64 },
}

impl Polyhedra {
    /// `robot` in its body frame (reference point at the origin), obstacles in the world frame.
    pub fn new(robot: TriMesh, obstacles: Vec<TriMesh>) -> Polyhedra {
        let r = Body::new(std::slice::from_ref(&robot));
        let o = Body::new(&obstacles);
        Polyhedra::of_bodies(Arc::new(robot), r, Arc::new(obstacles), Arc::new(o))
    }

    /// [`Polyhedra::new`] from bodies already prepared (`robot` from `robot_mesh`, `obstacles`
    /// from `obstacle_meshes`, by [`Body::new`]): an arm's oracles share one body per link and
    /// one of the environment instead of welding and indexing them again for every pair.
    pub(crate) fn of_bodies(
        robot_mesh: Arc<TriMesh>,
        r: Body,
        obstacle_meshes: Arc<Vec<TriMesh>>,
        o: Arc<Body>,
    ) -> Polyhedra {
        let scale = r.radius + o.aabb.diagonal() + o.aabb.lo.abs().max().max(o.aabb.hi.abs().max());
        let scale = if scale.is_finite() && scale > 0.0 {
            scale
        } else {
            1.0
        };
        Polyhedra {
            robot_mesh,
            obstacle_meshes,
            robot: r,
            obstacles: o,
            tol: Tolerance::for_scale(scale),
            enveloping: true,
        }
    }

    /// Switches enveloping (bounding volumes, trees, per-face boxes, skipping pairs whose window
    /// already collides) on or off. Off, every edge–face pair is evaluated: the brute-force
    /// reference for benchmarks and tests. On by default.
    pub fn with_enveloping(mut self, on: bool) -> Polyhedra {
        self.enveloping = on;
        self
    }

    /// Whether enveloping is on.
    pub fn enveloping(&self) -> bool {
        self.enveloping
    }

    /// The robot mesh, in its body frame.
    pub fn robot(&self) -> &TriMesh {
        &self.robot_mesh
    }

    /// The obstacle meshes, in the world frame.
    pub fn obstacles(&self) -> &[TriMesh] {
        &self.obstacle_meshes
    }

    /// Distance below which a point counts as lying on a plane (contacts are reported with
    /// this much slack, in favour of collision).
    pub fn tolerance(&self) -> f64 {
        self.tol.dist
    }

    /// Number of distinct robot and obstacle triangles the predicate works on (each
    /// geometric triangle once, however often and in whichever winding the meshes list it).
    pub fn face_counts(&self) -> (usize, usize) {
        (self.robot.faces.len(), self.obstacles.faces.len())
    }

    /// Whether containment is decided for the robot and for each obstacle (closed meshes with
    /// an inside).
    pub fn solids(&self) -> (bool, Vec<bool>) {
        (
            self.robot.parts.first().is_some_and(|p| p.solid),
            self.obstacles.parts.iter().map(|p| p.solid).collect(),
        )
    }

    /// The collision intervals, in `t ∈ [0, 1]`, of the robot placed at the SE(3)
    /// configuration `pose` (`[x, y, z, qx, qy, qz, qw]`) turning by `t · angle` about the
    /// world `axis` through the world point `pivot`, which need not be the robot's reference
    /// point (CHS §2.3.2's rotation about a fixed axis, for a body that is not built about the
    /// axis: a link of a robot arm turned by a joint above it). The robot's faces and
    /// tree are reused, moved so that the pivot becomes the reference point, instead of being
    /// built again; the obstacles are shared. With the pivot at the reference point this is
    /// [`CollisionOracle::intervals`] of `Change::Rotation { axis, angle }`.
    pub fn turn_about(
        &self,
        pose: &[f64],
        pivot: [f64; 3],
        axis: [f64; 3],
        angle: f64,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        Polyhedra::gather(Gather::All, |g| {
            g.turn_about(self, pose, pivot, axis, angle, Interval::UNIT, counts)?;
            Ok(g.to_list())
        })
    }

    /// Runs `f` with an empty [`Gathered`] of this thread's scratch space: the collision pieces,
    /// in `t ∈ [0, 1]`, of one motion asked of several oracles (the links of an arm turned by
    /// one joint), each call skipping what the earlier ones already found.
    ///
    /// A turn is solved, pair by pair, only in the part of the pair's window not yet known to
    /// collide (`Hits::uncovered`): the union cannot change, and the pairs deep inside a
    /// collision piece get narrow windows, most of them decided by bounds alone.
    /// [`Polyhedra::gather_unclipped`] solves every pair in its whole window (the reference).
    pub(crate) fn gather<R>(mode: Gather, f: impl FnOnce(&mut Gathered<'_>) -> R) -> R {
        Self::gather_with(mode, true, f)
    }

    /// [`Polyhedra::gather`] with every pair of a turn solved in its whole window (pairs whose
    /// window is already known to collide still skipped): the reference of the narrowed sweep.
    pub(crate) fn gather_unclipped<R>(mode: Gather, f: impl FnOnce(&mut Gathered<'_>) -> R) -> R {
        Self::gather_with(mode, false, f)
    }

    fn gather_with<R>(mode: Gather, clip: bool, f: impl FnOnce(&mut Gathered<'_>) -> R) -> R {
        with_scratch(|s| {
            s.hits.reset(mode == Gather::Any);
            // a yes/no gather stops at its first piece: nothing to narrow by
            s.hits.set_clip(clip && mode != Gather::Any);
            f(&mut Gathered { s, mode })
        })
    }

    fn classify(motion: &Motion) -> Result<(Pose, Kind), OracleError> {
        let pose = Pose::from_config(&motion.origin)?;
        if motion.range.lo.is_nan() || motion.range.hi.is_nan() || motion.range.lo > motion.range.hi
        {
            return Err(OracleError::Unsupported(
                "polyhedra: empty or NaN parameter range".into(),
            ));
        }
        let kind = match &motion.change {
            Change::Linear(delta) => {
                if delta.len() != 7 {
                    return Err(OracleError::Unsupported(format!(
                        "polyhedra: a change of {} coordinates in SE(3)",
                        delta.len()
                    )));
                }
                if !delta.iter().all(|c| c.is_finite()) {
                    return Err(OracleError::Unsupported(
                        "polyhedra: change with a coordinate that is not finite".into(),
                    ));
                }
                if delta[3..7].iter().any(|&c| c != 0.0) {
                    return Err(OracleError::Unsupported(
                        "polyhedra: a linear change of quaternion coordinates is not a rotation \
                         about a fixed axis (translate, or turn with Change::Rotation)"
                            .into(),
                    ));
                }
                let dir = V3::new(delta[0], delta[1], delta[2]);
                if dir == V3::zeros() {
                    Kind::Still
                } else {
                    Kind::Translation(dir)
                }
            }
            Change::Rotation { axis, angle } => {
                let a = V3::new(axis[0], axis[1], axis[2]);
                if !angle.is_finite() || !a.iter().all(|c| c.is_finite()) {
                    return Err(OracleError::Unsupported(
                        "polyhedra: rotation with an axis or angle that is not finite".into(),
                    ));
                }
                let n = a.norm();
                if *angle == 0.0 {
                    Kind::Still
                } else if n < 1e-12 {
                    return Err(OracleError::Unsupported(
                        "polyhedra: rotation about a zero axis".into(),
                    ));
                } else if *angle > 0.0 {
                    Kind::Rotation {
                        axis: a / n,
                        angle: *angle,
                    }
                } else {
                    Kind::Rotation {
                        axis: -a / n,
                        angle: -angle,
                    }
                }
            }
            Change::BodyRotation { .. } => {
                return Err(OracleError::Unsupported(
                    "polyhedra: a turn of one of several bodies asked of one body".into(),
                ))
            }
        };
        Ok((pose, kind))
    }

    /// The sweep behind both `intervals` and `motion_is_free`: collision pieces in `t` into
    /// `scratch.hits` (reset by the caller).
    fn sweep(
        &self,
        motion: &Motion,
        scratch: &mut Scratch,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let Scratch {
            hits: sink,
            turn: local,
            caches,
        } = scratch;
        let (pose, kind) = Self::classify(motion)?;
        let range = motion.range;
        if self.obstacles.faces.is_empty() || self.robot.faces.is_empty() {
            return Ok(());
        }
        match kind {
            Kind::Still => {
                if self.collides_at(&pose, caches, counts) {
                    let _ = sink.add(range);
                }
            }
            Kind::Translation(dir) => {
                translation::sweep(self, &pose, &dir, range, sink, caches, counts);
                if sink.was_interrupted() {
                    return Err(OracleError::Interrupted);
                }
            }
            Kind::Rotation { axis, angle } => {
                if !range.is_bounded() {
                    return Err(OracleError::Unsupported(
                        "polyhedra: a rotation over an unbounded parameter range".into(),
                    ));
                }
                let (p0, p1) = (range.lo * angle, range.hi * angle);
                if p1 - p0 > MAX_TURNS * TAU {
                    return Err(OracleError::Unsupported(format!(
                        "polyhedra: a rotation of more than {MAX_TURNS} turns"
                    )));
                }
                // the collision set repeats every turn: work on one turn, then copy it
                let one = Interval {
                    lo: p0,
                    hi: p1.min(p0 + TAU),
                };
                local.reset(sink.is_first_only());
                if sink.is_prefix() {
                    local.reset_prefix();
                }
                local.set_clip(sink.clips());
                if p1 - p0 <= TAU {
                    // what other oracles found for this motion (a gathered sweep): windows it
                    // covers are skipped (the answer repeats every turn, so only within one)
                    for iv in sink.as_slice() {
                        let _ = local.add(Interval {
                            lo: (iv.lo * angle).max(p0),
                            hi: (iv.hi * angle).min(p1),
                        });
                    }
                }
                rotation::sweep(self, &pose, &axis, one, local, caches, counts);
                if local.was_interrupted() {
                    return Err(OracleError::Interrupted);
                }
                let turns = ((p1 - p0) / TAU).ceil().max(1.0) as usize;
                for k in 0..turns {
                    let shift = k as f64 * TAU;
                    for iv in local.as_slice() {
                        let piece = Interval {
                            lo: (iv.lo + shift).max(p0),
                            hi: (iv.hi + shift).min(p1),
                        };
                        if piece.lo <= piece.hi
                            && sink
                                .add(Interval {
                                    lo: piece.lo / angle,
                                    hi: piece.hi / angle,
                                })
                                .is_break()
                        {
                            return Ok(());
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The static test at a pose: surface contact by the predicate in both directions, then
    /// containment.
    fn collides_at(&self, pose: &Pose, caches: &mut Caches, counts: &mut CallCounts) -> bool {
        let (robot, obst) = (&self.robot, &self.obstacles);
        let m = self.tol.dist;
        let test = |rf: &Face, of: &Face, counts: &mut CallCounts| -> bool {
            counts.pairs_tested += 6;
            predicate::faces_meet(rf, of, &self.tol)
        };
        let mut hit = false;
        if self.enveloping {
            // both trees at once (CHS §2.2, enveloping): a robot node's box placed at the pose
            // against an obstacle node's box, and the same in the robot's frame; the leaves'
            // faces by their own boxes in the robot's frame
            let world = pose.world_box(&robot.aabb).grown(m);
            if !world.overlaps(&obst.aabb) {
                return containment::at_pose(self, pose, counts);
            }
            if robot.faces.len() <= SMALL_ROBOT {
                // a robot of a few leaves: one query of the obstacle tree with its box, then
                // one query of its own tree per obstacle face is cheaper than the double descent
                obst.bvh.visit_overlapping(&world, |o| {
                    let of = Face::new(obst.corners(o).map(|w| pose.body_point(&w)));
                    let obox = Aabb::of_points(of.v.iter()).grown(m);
                    robot.bvh.visit_overlapping(&obox, |r| {
                        let rf = robot.face(r);
                        hit = Aabb::of_points(rf.v.iter()).overlaps(&obox) && test(rf, &of, counts);
                        !hit
                    })
                });
                return hit || containment::at_pose(self, pose, counts);
            }
            let placed = &mut caches.placed;
            placed.reset(robot.bvh.node_count());
            let posed = &mut caches.posed_faces;
            posed.reset(obst.faces.len());
            robot.bvh.visit_pairs(
                &obst.bvh,
                (),
                |a, _, rb, ob, ()| {
                    let world = placed.get_or_insert_with(a as usize, || pose.world_box(rb));
                    (world.overlaps(&ob.grown(m)) && rb.overlaps(&pose.body_box(ob).grown(m)))
                        .then_some(())
                },
                |ri, oi, ()| {
                    for &o in oi {
                        let (of, obox) = &*posed.get_or_insert_with(o as usize, || {
                            let of = Face::new(obst.corners(o).map(|w| pose.body_point(&w)));
                            let obox = Aabb::of_points(of.v.iter()).grown(m);
                            (of, obox)
                        });
                        for &r in ri {
                            let rf = robot.face(r);
                            if Aabb::of_points(rf.v.iter()).overlaps(obox) && test(rf, of, counts) {
                                hit = true;
                                return false;
                            }
                        }
                    }
                    true
                },
            );
        } else {
            'all: for o in 0..obst.faces.len() as u32 {
                let of = Face::new(obst.corners(o).map(|w| pose.body_point(&w)));
                for r in 0..robot.faces.len() as u32 {
                    if test(robot.face(r), &of, counts) {
                        hit = true;
                        break 'all;
                    }
                }
            }
        }
        hit || containment::at_pose(self, pose, counts)
    }
}

/// What a [`Gathered`] sweep wants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Gather {
    /// Every collision piece.
    All,
    /// Whether there is any: stops at the first piece.
    Any,
    /// The first collision only: once a piece is known, everything after its start counts as
    /// known too, so later calls only look before it.
    First,
}

/// The collision pieces of one motion (parameter `t ∈ [0, 1]`) gathered over several oracles
/// that share the thread's scratch space ([`Polyhedra::gather`]). What is already known to
/// collide is handed to each further call, which skips pairs whose window it covers (the
/// `Hits::covers` shortcut across oracles); an `Any` gather stops at the first piece, a `First`
/// gather narrows the window to what lies before the earliest piece.
pub(crate) struct Gathered<'s> {
    s: &'s mut Scratch,
    mode: Gather,
}

impl Gathered<'_> {
    /// Adds the pieces of `oracle`'s robot at `pose` turning by `t · angle` about the world
    /// `axis` through `pivot` ([`Polyhedra::turn_about`]), `t ∈ range` (the caller knows the
    /// rest of `[0, 1]` free).
    #[allow(clippy::too_many_arguments)]
    pub fn turn_about(
        &mut self,
        oracle: &Polyhedra,
        pose: &[f64],
        pivot: [f64; 3],
        axis: [f64; 3],
        angle: f64,
        range: Interval,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        if self.done() {
            return Ok(());
        }
        let at = Pose::from_config(pose)?;
        if !pivot.iter().all(|c| c.is_finite()) {
            return Err(OracleError::Unsupported(
                "polyhedra: a pivot with a coordinate that is not finite".into(),
            ));
        }
        let mut origin = pose.to_vec();
        origin[..3].copy_from_slice(&pivot);
        let mut motion = Motion::segment(origin, Change::Rotation { axis, angle });
        motion.range = range;
        // body point v sits at rot · v + pos = rot · (v + s) + pivot with s = rotᵀ (pos − pivot)
        let s = at.rot.tr_mul(&(at.pos - V3::from(pivot)));
        if s == V3::zeros() {
            oracle.sweep(&motion, self.s, counts)?;
        } else {
            let view = Polyhedra {
                robot_mesh: Arc::clone(&oracle.robot_mesh),
                obstacle_meshes: Arc::clone(&oracle.obstacle_meshes),
                robot: oracle.robot.shifted(&s),
                obstacles: Arc::clone(&oracle.obstacles),
                tol: oracle.tol,
                enveloping: oracle.enveloping,
            };
            view.sweep(&motion, self.s, counts)?;
        }
        self.narrow();
        Ok(())
    }

    /// Adds the pieces of `oracle`'s robot at `pose` translating by `t · dir`, `t ∈ range`.
    pub fn slide(
        &mut self,
        oracle: &Polyhedra,
        pose: &[f64],
        dir: [f64; 3],
        range: Interval,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        if self.done() {
            return Ok(());
        }
        let mut motion = Motion::segment(
            pose.to_vec(),
            Change::Linear(vec![dir[0], dir[1], dir[2], 0.0, 0.0, 0.0, 0.0]),
        );
        motion.range = range;
        oracle.sweep(&motion, self.s, counts)?;
        self.narrow();
        Ok(())
    }

    /// Adds a known collision piece (a static pair that collides throughout, say).
    pub fn add(&mut self, iv: Interval) {
        let _ = self.s.hits.add(iv);
        self.narrow();
    }

    /// In a `First` gather: everything from the earliest piece on counts as known.
    fn narrow(&mut self) {
        if self.mode == Gather::First {
            if let Some(first) = self.s.hits.as_slice().first() {
                let lo = first.lo;
                let _ = self.s.hits.add(Interval { lo, hi: 1.0 });
            }
        }
    }

    /// Whether further calls can change nothing: an `Any` gather has its piece, or all of
    /// `[0, 1]` is known to collide.
    pub fn done(&self) -> bool {
        self.s.hits.done() || self.s.hits.covers(Interval::UNIT)
    }

    /// The start of the earliest piece.
    pub fn first(&self) -> Option<f64> {
        self.s.hits.as_slice().first().map(|iv| iv.lo.max(0.0))
    }

    /// The pieces within `[0, 1]` (in a `First` gather: `[first, 1]`).
    pub fn to_list(&self) -> IntervalList {
        self.s.hits.to_list(Interval::UNIT)
    }
}

impl CollisionOracle for Polyhedra {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        with_scratch(|s| {
            s.hits.reset(false);
            self.sweep(motion, s, counts)?;
            Ok(s.hits.to_list(motion.range))
        })
    }

    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        _ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        with_scratch(|s| {
            s.hits.reset(false);
            self.sweep(motion, s, counts)?;
            s.hits.write_into(out, motion.range);
            Ok(())
        })
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        match Pose::from_config(q) {
            Ok(pose) => {
                !self.obstacles.faces.is_empty()
                    && !self.robot.faces.is_empty()
                    && with_scratch(|s| self.collides_at(&pose, &mut s.caches, counts))
            }
            // not a configuration of this space: nothing sensible to place, report collision
            Err(_) => true,
        }
    }

    fn first_collision(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        with_scratch(|s| {
            s.hits.reset_prefix();
            self.sweep(motion, s, counts)?;
            Ok(s.hits
                .as_slice()
                .iter()
                .find_map(|iv| iv.meet(&motion.range))
                .map(|iv| iv.lo))
        })
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        with_scratch(|s| {
            s.hits.reset(true);
            self.sweep(motion, s, counts)?;
            Ok(s.hits
                .as_slice()
                .iter()
                .all(|iv| iv.meet(&motion.range).is_none()))
        })
    }
}
