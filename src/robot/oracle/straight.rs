//! Straight motions of several joints at once, certified by conservative advancement: the
//! shortcuts a staircase of single-joint moves cannot take (in the cage's workcell
//! the kept answers' staircases cost 6–23 ms of shortening and lose 5 % of their length).
//!
//! No exact intervals here, only a proof: along `q(t) = q0 + t (q1 − q0)` a point of link `l`
//! moves at most `Σ_k |Δ_k| R_kl` per unit of `t` (Schwarzer, Saha and Latombe's bound for
//! articulated robots), `R_kl` bounding the point's distance from the axis of joint `k` (a
//! prismatic joint slides it by `|Δ_k|`). `R_kl` needs no configuration: rotations keep lengths,
//! so the link's origin lies at most the joint offsets below `k` (and the prismatic travels)
//! away from `k`'s origin, on its axis, and its vertices at most their largest norm from its
//! origin. At each plane the bound is tightened to the moment's geometry: the distance of the
//! link's ball from each joint's axis then, growing at most as fast as the joints after it move
//! the link (so the step solves a quadratic, [`clearance::Speed`]). Two bodies a separating
//! plane shows `g` apart stay apart while their points, moving relative to each other, cover
//! less than `g` ([`clearance::apart_along`]); for two links only the joints between them and
//! their deepest common link move one relative to the other.
//!
//! Those bounds add every joint's worst case. Toward one plane a link moves far slower: at a
//! moment its points approach along the normal `n` at most `|n · v| + r |n × ω|` (`v`, `ω`:
//! the velocity of its ball's centre and its angular velocity, from the joints' axes then;
//! `r`: the ball's radius), and that rate changes no faster than the points' acceleration,
//! bounded over the whole motion by `Σ_k |Δ_k| R_kl (|Δ_k| + 2 Σ_{j<k} |Δ_j|)`
//! ([`ArmOracle::moving`], [`clearance::Along`]). Each plane steps by the better of the two.
//! In the Panda's cage workcell the proofs near the bars took half the planes, and the query
//! p50 fell from 1.3–2.3 ms to 0.4–0.5 ms.
//!
//! Every link–obstacle and non-exempt link–link pair whose balls, grown by the motion's bound,
//! meet, and whose outer sphere covers ([`crate::robot::cover`]), grown alike, come near, is
//! proved apart plane after plane, or the motion is not certified. Two links are grown by how
//! far they may move relative to each other, by the joints between them only: the wrist's
//! links, always close, mostly turn little one against the other. The pairs
//! whose covers come closest go first: a motion that is not free mostly fails there, before
//! the others are proved apart for nothing. Where a link's cover reaches into an obstacle,
//! the sure test at the moment it reaches deepest, and deeper still the two hulls there, end
//! most colliding motions before any plane is sought (a pair within the margin at a moment
//! of its window is never proved apart, so the verdict is the planes'). Near
//! contact the planes' steps shrink and the proof gives up: a motion it does not prove is
//! treated as blocked (planners ask only the yes/no question), never as a collision found.

use super::{l_cloud, ArmOracle, Ball, CLEARANCE_PER_TOLERANCE};
use crate::interval::Interval;
use crate::oracle::CallCounts;
use crate::robot::clearance::{self, Speed};
use crate::robot::urdf::JointKind;
use crate::robot::RobotError;
use nalgebra::{Isometry3, Point3};

/// Separating planes sought per pair and window, from both ends together, before a motion is
/// given up as not proved. A pair that passes close to an obstacle needs many: in the Panda's
/// cage workcell 24 proved too little (query p50 18.6 ms, the goals no longer attached), 48
/// 1.7–1.9 ms, 96–384 1.2–1.3 ms with shorter paths.
const MAX_PLANES: usize = 128;

/// How far a link's points may move in half a piece of time at most, where the pieces are
/// few enough ([`MAX_PIECES`]).
const PIECE_GROWTH: f64 = 0.1;

/// How deep (m) a link's cover must reach into an obstacle's outer shape at a moment of a
/// motion for the proof to test the link's hull against the obstacle's there before any plane
/// ([`ArmOracle::environment_tasks`]): most motions it finds colliding past a shelf's boards
/// end there, at a fifth of the work (a bookshelf_tall query's 421 straight motions, the 17
/// not proved after the sure test: 37 → 26 µs each, the 24 proved 1 µs dearer).
const DEEP_COVER: f64 = 0.05;

/// Pieces of time a motion is cut into at most.
const MAX_PIECES: usize = 32;

/// Points along a motion the sure test looks at first: its end, then in halving order (½, ¼,
/// ¾, ⅛, …, ⅞). A motion that passes pays every one of them before its proof: a finer round
/// of sixteen caught about one rejected motion in eighty and cost 7 % of the planning (Panda,
/// eight problems of each family, instructions counted).
const SURE_SAMPLES: usize = 8;

/// A proof stops once the deadline watched on this thread has passed
/// ([`crate::deadline::watching`]), as it starts and before each pair's window of at most
/// [`MAX_PLANES`] planes:
/// a query's time is a promise, and an interrupted proof is an error, never a "not proved"
/// that would be kept as the motion's answer.
fn interrupted() -> Result<(), RobotError> {
    if crate::deadline::watched_expired() {
        Err(RobotError::Interrupted)
    } else {
        Ok(())
    }
}

/// One straight motion of the arm: how far and how fast each joint moves, for bounds on how
/// fast the links' points move.
struct Straight<'a> {
    oracle: &'a ArmOracle,
    /// Every joint's value at the start (the group's from `q0`, the others as set).
    start: Vec<f64>,
    /// [`Self::place`]'s buffer of every joint's value.
    values: std::cell::RefCell<Vec<f64>>,
    /// Each joint's change over the motion ([`ArmOracle::joint_deltas`]).
    delta: Vec<f64>,
    /// Each joint's rate: the size of its change.
    rate: Vec<f64>,
}

/// The motion in pieces of time, short enough that each link's ball, grown by how far its
/// points may move in half a piece, keeps close to it: a pair is asked only over the pieces in
/// which its balls (an obstacle's box) meet.
struct Pieces {
    n: usize,
    /// Each piece's grown balls, link by link (`None`: no geometry), piece after piece.
    balls: Vec<Option<Ball>>,
    /// Each piece's link poses (at its middle), where the covers are placed, piece after
    /// piece.
    poses: Vec<Isometry3<f64>>,
    /// Per link, how far its points may move in half a piece.
    grow: Vec<f64>,
    /// Each link's cover placed at each piece's pose, on first use ([`Self::place_cover`]).
    covers: CoverCache,
}

/// World centres of links' cover balls at pieces' poses, placed when a pair first asks for
/// them: a link near a shelf is asked against each board and each link near it, piece by
/// piece, and its balls are placed once for all of them.
struct CoverCache {
    /// Per piece and link (`p * links + l`), where its centres start in `centres`
    /// (`u32::MAX`: not placed yet).
    at: std::cell::RefCell<Vec<u32>>,
    centres: std::cell::RefCell<Vec<Point3<f64>>>,
}

impl Pieces {
    /// The links (one entry per link in every piece's run of the buffers).
    fn links(&self) -> usize {
        self.grow.len()
    }

    /// Link `l`'s grown ball in piece `p`.
    fn ball(&self, p: usize, l: usize) -> Option<&Ball> {
        self.balls[p * self.links() + l].as_ref()
    }

    /// Link `l`'s pose at the middle of piece `p`.
    fn pose(&self, p: usize, l: usize) -> &Isometry3<f64> {
        &self.poses[p * self.links() + l]
    }

    /// Where link `l`'s cover balls' world centres in piece `p` lie in
    /// [`Self::centres`], placed at the piece's pose the first time.
    fn place_cover(&self, o: &ArmOracle, p: usize, l: usize) -> std::ops::Range<usize> {
        let slot = p * self.links() + l;
        let balls = o.covers[l].len();
        let known = self.covers.at.borrow()[slot];
        let start = if known == u32::MAX {
            let mut centres = self.covers.centres.borrow_mut();
            let start = centres.len();
            let pose = self.pose(p, l);
            centres.extend(o.covers[l].iter().map(|b| pose * b.centre));
            self.covers.at.borrow_mut()[slot] = start as u32;
            start
        } else {
            known as usize
        };
        start..start + balls
    }

    /// The cover balls' centres placed so far ([`Self::place_cover`]).
    fn centres(&self) -> std::cell::Ref<'_, Vec<Point3<f64>>> {
        self.covers.centres.borrow()
    }

    /// Per link, a ball holding its balls of every piece (`None`: no geometry): a pair whose
    /// balls miss each other meets in no piece.
    fn held(&self) -> Vec<Option<Ball>> {
        (0..self.links())
            .map(|l| {
                let first = self.ball(0, l)?;
                let last = self.ball(self.n - 1, l)?;
                let centre = (first.centre + last.centre) / 2.0;
                let radius = (0..self.n)
                    .filter_map(|p| self.ball(p, l))
                    .map(|b| (b.centre - centre).norm() + b.radius)
                    .fold(0.0, f64::max);
                Some(Ball {
                    centre,
                    radius: radius * (1.0 + 1e-9) + 1e-12,
                })
            })
            .collect()
    }

    /// The runs of consecutive pieces in which `look(piece)` finds the pair near, as ranges of
    /// `t` with the closest its covers come in each run (less how far the links may move in
    /// half a piece) and the piece where they do; pieces a look finds apart ahead of it are not
    /// looked at.
    fn runs(&self, look: &dyn Fn(usize) -> Look) -> Vec<Run> {
        let n = self.n;
        let mut out: Vec<Run> = Vec::new();
        let mut p = 0;
        while p < n {
            let closest = match look(p) {
                Look::Near(closest) => closest,
                Look::Apart(ahead) => {
                    p = p.saturating_add(ahead).saturating_add(1);
                    continue;
                }
            };
            let (lo, hi) = (p as f64 / n as f64, (p + 1) as f64 / n as f64);
            match out.last_mut() {
                Some(run) if run.window.hi == lo => {
                    run.window.hi = hi;
                    // the least, as `f64::min` takes it (a NaN gives way to a number)
                    if closest < run.closest || run.closest.is_nan() {
                        (run.closest, run.deepest) = (closest, p);
                    }
                }
                _ => out.push(Run {
                    window: Interval { lo, hi },
                    closest,
                    deepest: p,
                }),
            }
            p += 1;
        }
        out
    }
}

/// A run of pieces in which a pair may come near ([`Pieces::runs`]).
struct Run {
    window: Interval,
    /// How close the pair's covers come in the run, less how far the links may move in half a
    /// piece.
    closest: f64,
    /// The piece where they come closest.
    deepest: usize,
}

/// What a pair's look at one piece found.
enum Look {
    /// The pair may come near there: how close its covers come, less how far its links may
    /// move in half a piece.
    Near(f64),
    /// Apart there, and in this many pieces after it.
    Apart(usize),
}

impl Look {
    /// The look at a piece where the pair's covers are `d` apart, its links' points moving at
    /// most `grow` relative to each other in half a piece: near within `margin`; else apart in
    /// the pieces after it too while the points, `d` apart at this piece's middle and coming
    /// at most `2 grow` nearer from piece to piece, stay more than `margin` apart.
    fn at(d: f64, grow: f64, margin: f64) -> Look {
        let closest = d - grow;
        // (a NaN is near: nothing is skipped on it)
        if closest.is_nan() || closest <= margin {
            return Look::Near(closest);
        }
        let ahead = (closest - margin) / (2.0 * grow) * (1.0 - 1e-9);
        Look::Apart(if ahead < usize::MAX as f64 {
            ahead as usize
        } else {
            usize::MAX
        })
    }
}

/// One pair's stretch of a motion to prove apart: two links or a link and an obstacle.
struct Task {
    pair: TaskPair,
    window: Interval,
    /// How close the pair's covers come in the window, less how far the links may move in
    /// half a piece: the proofs run closest first.
    closest: f64,
}

#[derive(Clone, Copy)]
enum TaskPair {
    /// Two links (a self pair).
    Links(usize, usize),
    /// A link and an environment polytope.
    Obstacle(usize, usize),
}

impl Straight<'_> {
    /// A bound on how fast link `l`'s points move, by the joints between it and the root that
    /// are not also `except`'s (the common ones carry both links alike).
    fn speed(&self, l: usize, except: Option<usize>) -> f64 {
        let o = self.oracle;
        o.reach[l]
            .iter()
            .filter(|(k, _)| except.is_none_or(|e| !o.reach[e].iter().any(|(m, _)| m == k)))
            .map(|&(k, f)| self.rate[k] * f)
            .sum()
    }

    /// The link poses at `t` (every joint's value from the motion's start and change, in a
    /// buffer the motion keeps: no allocation per moment).
    fn place(&self, t: f64, poses: &mut [Isometry3<f64>]) {
        self.place_first(t, poses, usize::MAX);
    }

    /// [`Self::place`] for the links the first `joints` joints of the kinematic order place
    /// ([`crate::robot::kinematics::Model::order_prefix`]): the links of a pair and those
    /// above them, whose joints' axes the bounds on their speed read.
    fn place_first(&self, t: f64, poses: &mut [Isometry3<f64>], joints: usize) {
        let arm = &self.oracle.arm;
        let mut values = self.values.borrow_mut();
        for ((v, a), d) in values.iter_mut().zip(&self.start).zip(&self.delta) {
            *v = a + t * d;
        }
        arm.model
            .link_poses_prefix(&arm.base, &values, poses, joints);
    }

    /// Whether the sure test finds a collision at a few points along the motion: its end (an
    /// extend towards a sample in an obstacle ends in it), then halving the step each round.
    fn surely_collides_somewhere(&self, poses: &mut [Isometry3<f64>]) -> bool {
        let o = self.oracle;
        let mut balls = Vec::with_capacity(poses.len());
        let mut k = 1;
        while k <= SURE_SAMPLES {
            for i in (1..k.max(2)).step_by(2) {
                self.place(i as f64 / k as f64, poses);
                balls.clear();
                balls.extend(
                    o.link_meshes
                        .iter()
                        .zip(poses.iter())
                        .map(|(m, p)| m.as_ref().map(|(_, b)| b.placed(p))),
                );
                if o.surely_collides_with(poses, &balls, false) {
                    return true;
                }
            }
            k *= 2;
        }
        false
    }

    /// The motion cut into pieces, each link's ball placed at the middle of each piece and
    /// grown by how far its points may move in half a piece.
    fn pieces(&self, poses: &mut [Isometry3<f64>]) -> Pieces {
        let o = self.oracle;
        let fastest_link = (0..o.link_meshes.len())
            .map(|l| self.speed(l, None))
            .fold(0.0, f64::max);
        let n = ((fastest_link / PIECE_GROWTH).ceil() as usize).clamp(1, MAX_PIECES);
        let links = o.link_meshes.len();
        let mut balls: Vec<Option<Ball>> = Vec::with_capacity(n * links);
        let mut at = Vec::with_capacity(n * links);
        let grow: Vec<f64> = (0..links)
            .map(|l| self.speed(l, None) / (2 * n) as f64)
            .collect();
        for p in 0..n {
            self.place((p as f64 + 0.5) / n as f64, poses);
            at.extend_from_slice(&poses[..links]);
            balls.extend(o.link_meshes.iter().enumerate().map(|(l, m)| {
                m.as_ref().map(|(_, b)| {
                    let mut b = b.placed(&poses[l]);
                    b.radius += grow[l];
                    b
                })
            }));
        }
        Pieces {
            n,
            balls,
            poses: at,
            grow,
            covers: CoverCache {
                at: std::cell::RefCell::new(vec![u32::MAX; n * links]),
                centres: std::cell::RefCell::new(Vec::new()),
            },
        }
    }

    /// How fast link `l`'s points may move at the poses of a moment, by the joints between it
    /// and the root that are not also `except`'s (the common ones carry both links alike): each
    /// joint's rate times the distance of the link's ball from its axis then, which grows at
    /// most as fast as the joints after it move the link (their bounds).
    fn tight(&self, l: usize, except: Option<usize>, poses: &[Isometry3<f64>]) -> Speed {
        let o = self.oracle;
        let model = &o.arm.model;
        let mut speed = Speed {
            rate: 0.0,
            growth: 0.0,
            along: None,
        };
        let Some((_, own)) = &o.link_meshes[l] else {
            return speed;
        };
        let shared = |k: usize| except.is_some_and(|e| o.reach[e].iter().any(|(m, _)| *m == k));
        let centre = poses[l] * nalgebra::Point3::from(own.centre);
        // the joints after the one at hand, by their bounds
        let mut drift = 0.0;
        for &(k, f) in o.reach[l].iter().rev() {
            if shared(k) {
                // the chains share a prefix: every joint before this one is shared too
                break;
            }
            if self.rate[k] != 0.0 {
                let joint = &model.urdf.joints[k];
                if matches!(joint.kind, JointKind::Prismatic { .. }) {
                    speed.rate += self.rate[k] * f;
                } else {
                    // the axis at this moment, through the joint's child frame
                    let frame = &poses[model.joint_links[k].1];
                    let axis = frame.rotation * joint.axis.into_inner();
                    let off = centre - nalgebra::Point3::from(frame.translation.vector);
                    let from_axis = (off.cross(&axis).norm() + own.radius) * (1.0 + 1e-9);
                    speed.rate += self.rate[k] * from_axis.min(f);
                    speed.growth += self.rate[k] * drift;
                }
            }
            drift += self.rate[k] * f;
        }
        speed
    }
}

impl ArmOracle {
    /// Whether the straight motion from `q0` to `q1` (group configurations; any number of
    /// joints moving at once, each linearly in `t`) is proved free of collision by conservative
    /// advancement (see the module's text). `false` means *not proved*: a collision, or two
    /// bodies too close for the proof to finish. One joint moving is a straight motion too,
    /// but [`Self::joint_move_free`] answers it exactly. [`RobotError::Interrupted`] once a
    /// deadline watched on this thread has passed ([`crate::deadline::watching`]).
    pub fn straight_free(
        &self,
        q0: &[f64],
        q1: &[f64],
        counts: &mut CallCounts,
    ) -> Result<bool, RobotError> {
        self.arm.check_config(q0, "configuration")?;
        self.arm.check_config(q1, "configuration")?;
        counts.segment_calls += 1;
        let delta = self.joint_deltas(q0, q1);
        let start = self.arm.full_values(q0);
        let motion = Straight {
            oracle: self,
            values: std::cell::RefCell::new(start.clone()),
            start,
            rate: delta.iter().map(|d| d.abs()).collect(),
            delta,
        };
        let mut poses = vec![Isometry3::identity(); self.arm.model.urdf.links.len()];
        // a motion through an obstacle is found by the sure test at a few points along it
        // (~1 µs each) before advancement creeps up to the contact plane by plane
        if self.sure_test && motion.surely_collides_somewhere(&mut poses) {
            return Ok(false);
        }
        let pieces = motion.pieces(&mut poses);
        self.prove(&motion, &pieces, &mut poses, counts)
    }

    /// Whether every pair that may meet is proved apart over the pieces of time in which it
    /// may, the pairs that come closest first: a motion that is not free fails at the pair
    /// that comes closest, mostly, and asked first it ends the proof before the others are
    /// proved apart for nothing.
    fn prove(
        &self,
        motion: &Straight,
        pieces: &Pieces,
        poses: &mut [Isometry3<f64>],
        counts: &mut CallCounts,
    ) -> Result<bool, RobotError> {
        interrupted()?;
        let held = pieces.held();
        let Some(mut tasks) = self.environment_tasks(pieces, &held) else {
            return Ok(false);
        };
        tasks.extend(self.self_pair_tasks(motion, pieces, &held));
        tasks.sort_by(|x, y| x.closest.total_cmp(&y.closest));
        for task in tasks {
            interrupted()?;
            let apart = match task.pair {
                TaskPair::Links(a, b) => {
                    self.pair_apart_in(a, b, motion, task.window, poses, counts)
                }
                TaskPair::Obstacle(l, i) => {
                    self.env_apart_in(l, i, motion, task.window, poses, counts)
                }
            };
            if !apart {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// The self pairs' stretches to prove: where their grown balls meet and their covers'
    /// balls, grown by how far the links may move relative to each other in half a piece,
    /// come near.
    fn self_pair_tasks(
        &self,
        motion: &Straight,
        pieces: &Pieces,
        held: &[Option<Ball>],
    ) -> Vec<Task> {
        let mut tasks = Vec::new();
        for &(a, b) in &self.arm.self_pairs {
            if !matches!((&held[a], &held[b]), (Some(x), Some(y)) if x.meets(y)) {
                continue;
            }
            let margin = self
                .pair_oracles
                .get(&(a, b))
                .map_or(0.0, |o| o.tolerance() * CLEARANCE_PER_TOLERANCE);
            // only the joints between the links move one relative to the other
            let relative = motion.speed(a, Some(b)) + motion.speed(b, Some(a));
            let grow = relative / (2 * pieces.n) as f64;
            let near = |p: usize| match (pieces.ball(p, a), pieces.ball(p, b)) {
                (Some(ba), Some(bb)) if ba.meets(bb) => {
                    let (ra, rb) = (
                        pieces.place_cover(self, p, a),
                        pieces.place_cover(self, p, b),
                    );
                    let c = pieces.centres();
                    let (ca, cb) = (&c[ra], &c[rb]);
                    let d = self.placed_cover_to_link(a, |i, _| ca[i], b, |j, _| cb[j]);
                    Look::at(d, grow, margin)
                }
                _ => Look::Apart(0),
            };
            tasks.extend(pieces.runs(&near).into_iter().map(|r| Task {
                pair: TaskPair::Links(a, b),
                window: r.window,
                closest: r.closest,
            }));
        }
        tasks
    }

    /// Whether links `a` and `b` (a self pair) are proved apart by separating planes over the
    /// window `w` of the motion (`false`: not proved).
    fn pair_apart_in(
        &self,
        a: usize,
        b: usize,
        motion: &Straight,
        w: Interval,
        poses: &mut [Isometry3<f64>],
        counts: &mut CallCounts,
    ) -> bool {
        let (Some(ca), Some(cb), Some(o)) = (
            l_cloud(&self.link_clouds, a),
            l_cloud(&self.link_clouds, b),
            self.pair_oracles.get(&(a, b)),
        ) else {
            return false;
        };
        counts.pairs_tested += 1;
        let relative = motion.speed(a, Some(b)) + motion.speed(b, Some(a));
        let margin = o.tolerance() * CLEARANCE_PER_TOLERANCE;
        let prefix = &self.arm.model.order_prefix;
        let joints = prefix[a].max(prefix[b]);
        let mut at = |t: f64| {
            motion.place_first(t, poses, joints);
            let (sa, sb) = (
                motion.tight(a, Some(b), poses),
                motion.tight(b, Some(a), poses),
            );
            let along = self
                .moving(a, Some(b), &motion.delta, poses)
                .zip(self.moving(b, Some(a), &motion.delta, poses))
                .map(|((ma, xa), (mb, xb))| clearance::Along {
                    bodies: [ma, mb],
                    accel: xa + xb,
                });
            let speed = Speed {
                rate: sa.rate + sb.rate,
                growth: sa.growth + sb.growth,
                along,
            };
            (poses[a], poses[b], speed)
        };
        clearance::apart_along(ca, cb, &mut at, w, relative, margin, MAX_PLANES)
    }

    /// The link–obstacle stretches to prove: where the link's grown ball meets the obstacle's
    /// ball and box, and its cover's balls, grown alike, come near the obstacle's outer shape.
    /// `None` where the sure test finds a link in an obstacle at a moment of the motion.
    fn environment_tasks(&self, pieces: &Pieces, held: &[Option<Ball>]) -> Option<Vec<Task>> {
        let mut tasks = Vec::new();
        let links = (0..held.len()).filter(|&l| held[l].is_some());
        let reachable = |l: usize| self.reachable[l].iter().map(move |&i| (l, i as usize));
        for (l, i) in links.flat_map(reachable) {
            let ob = &self.environment[i].1;
            let reaches =
                |b: &Ball| b.meets(ob) && (!self.culling || self.env_boxes[i].meets_ball(b));
            if !held[l].as_ref().is_some_and(reaches) {
                continue;
            }
            let margin = self.env_oracles[l]
                .as_ref()
                .map_or(0.0, |o| o.tolerance() * CLEARANCE_PER_TOLERANCE);
            let near = |p: usize| match pieces.ball(p, l) {
                Some(b) if b.meets(ob) && (!self.culling || self.env_boxes[i].meets_ball(b)) => {
                    let r = pieces.place_cover(self, p, l);
                    let c = &pieces.centres()[r];
                    let d = self.placed_cover_to_obstacle(l, |k, _| c[k], i);
                    Look::at(d, pieces.grow[l], margin)
                }
                _ => Look::Apart(0),
            };
            for r in pieces.runs(&near) {
                // a cover in the part: the sure test at its deepest moment, and deeper the
                // hulls, find most collisions the proof would creep up to plane by plane (a
                // pair within the margin at a moment of its window is never proved apart)
                if r.closest < 0.0
                    && self.sure_test
                    && self.surely_meets_obstacle(l, pieces.pose(r.deepest, l), i)
                {
                    return None;
                }
                if r.closest < -DEEP_COVER
                    && self.hulls_meet(l, pieces.pose(r.deepest, l), i, margin)
                {
                    return None;
                }
                tasks.push(Task {
                    pair: TaskPair::Obstacle(l, i),
                    window: r.window,
                    closest: r.closest,
                });
            }
        }
        Some(tasks)
    }

    /// Whether link `l` is proved apart from environment polytope `i` by separating planes
    /// over the window `w` of the motion (`false`: not proved).
    fn env_apart_in(
        &self,
        l: usize,
        i: usize,
        motion: &Straight,
        w: Interval,
        poses: &mut [Isometry3<f64>],
        counts: &mut CallCounts,
    ) -> bool {
        let (Some(cl), Some(o), Some(ce)) = (
            l_cloud(&self.link_clouds, l),
            &self.env_oracles[l],
            self.env_clouds[i].as_ref(),
        ) else {
            return false;
        };
        let margin = o.tolerance() * CLEARANCE_PER_TOLERANCE;
        counts.pairs_tested += 1;
        let fastest = motion.speed(l, None);
        let joints = self.arm.model.order_prefix[l];
        let mut at = |t: f64| {
            motion.place_first(t, poses, joints);
            let mut speed = motion.tight(l, None, poses);
            speed.along = self
                .moving(l, None, &motion.delta, poses)
                .map(|(m, accel)| clearance::Along {
                    bodies: [m, clearance::Moving::default()],
                    accel,
                });
            (poses[l], Isometry3::identity(), speed)
        };
        clearance::apart_along(cl, ce, &mut at, w, fastest, margin, MAX_PLANES)
    }

    /// Whether link `l` at `pose` and environment part `i` are not shown more than `margin`
    /// apart by their hulls: no separating plane can pass there, so no motion through that
    /// moment is proved.
    fn hulls_meet(&self, l: usize, pose: &Isometry3<f64>, i: usize, margin: f64) -> bool {
        match (l_cloud(&self.link_clouds, l), self.env_clouds[i].as_ref()) {
            (Some(cl), Some(ce)) => !clearance::apart(cl, pose, ce, &Isometry3::identity(), margin),
            _ => false,
        }
    }

    /// Per link, a bound on how far any point of the link (of any of its collision shapes:
    /// the polytopes the bound is taken over contain them) moves per unit of the parameter of
    /// the straight motion from `q0` to `q1`, relative to the world: `Σ_k |Δ_k| R_kl`
    /// (`R_kl`: the distance of its points from joint `k`'s axis, bounded over all
    /// configurations). 0 for a link without geometry. Conservative advancement on other
    /// distances (the certifier's, on the true shapes) steps by it.
    pub fn point_speeds(&self, q0: &[f64], q1: &[f64]) -> Vec<f64> {
        let delta = self.joint_deltas(q0, q1);
        self.reach
            .iter()
            .map(|r| r.iter().map(|&(k, f)| delta[k].abs() * f).sum::<f64>() * (1.0 + 1e-9))
            .collect()
    }

    /// How far each joint of the robot turns or slides along the straight motion from `q0` to
    /// `q1` (signed): the group's own, a mimic joint's from its master's, 0 for the others.
    fn joint_deltas(&self, q0: &[f64], q1: &[f64]) -> Vec<f64> {
        let model = &self.arm.model;
        let mut delta = vec![0.0; model.urdf.joints.len()];
        for (g, &k) in self.arm.group.joints.iter().enumerate() {
            delta[k] = q1[g] - q0[g];
        }
        for (k, master) in model.mimic_master.iter().enumerate() {
            if let (Some(m), Some(mimic)) = (master, &model.urdf.joints[k].mimic) {
                delta[k] = mimic.multiplier * delta[*m];
            }
        }
        delta
    }

    /// How link `l` moves at the link poses `poses` of a straight motion whose joints change by
    /// `delta` ([`Self::joint_deltas`]), by the joints between it and the root that are not also
    /// `except`'s (the links' deepest common link carries both alike: the velocities are
    /// relative to it, in world axes), and a bound on its points' acceleration (relative to
    /// that link) over the whole motion: `|∂²p/∂q_j∂q_k|` is at most `p`'s distance from the
    /// later joint's axis, at most `R_kl` ([`Reach`](super::reach::Reach)), so `Σ_k |Δ_k| R_kl (|Δ_k| + 2 Σ_{j<k}
    /// |Δ_j|)` bounds it. `None` for a link without geometry or one a prismatic joint moves.
    fn moving(
        &self,
        l: usize,
        except: Option<usize>,
        delta: &[f64],
        poses: &[Isometry3<f64>],
    ) -> Option<(clearance::Moving, f64)> {
        let model = &self.arm.model;
        let (_, own) = self.link_meshes[l].as_ref()?;
        let centre = poses[l] * nalgebra::Point3::from(own.centre);
        let mut m = clearance::Moving {
            // a relative margin for the rounding of the sums
            radius: own.radius * (1.0 + 1e-9) + 1e-12,
            ..clearance::Moving::default()
        };
        let (mut before, mut accel) = (0.0, 0.0);
        for &(k, f) in &self.reach[l] {
            if delta[k] == 0.0 || except.is_some_and(|o| self.reach[o].iter().any(|(j, _)| *j == k))
            {
                continue;
            }
            if matches!(model.urdf.joints[k].kind, JointKind::Prismatic { .. }) {
                return None;
            }
            let frame = &poses[model.joint_links[k].1];
            let axis = frame.rotation * model.urdf.joints[k].axis.into_inner();
            let off = centre - nalgebra::Point3::from(frame.translation.vector);
            m.spin += axis * delta[k];
            m.velocity += axis.cross(&off) * delta[k];
            let rate = delta[k].abs();
            before += rate;
            accel += rate * f * (2.0 * before - rate);
        }
        Some((m, accel * (1.0 + 1e-9)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::arm::tests::panda;
    use nalgebra::{Point3, Vector3};
    use rand::{Rng, SeedableRng};

    /// The bound along a plane's normal ([`ArmOracle::moving`], [`clearance::Along`]) holds for
    /// every vertex of a link, between random moments of random straight motions, along random
    /// normals and along the vertex's own displacement (where it is tightest), for a link alone
    /// (relative to the world) and for a link relative to the deepest link it shares with
    /// another (a self pair's frame); and it is not vacuous: it is often far below the sum of
    /// the joints' worst cases.
    #[test]
    fn the_bound_along_a_normal_holds_for_every_vertex() {
        let arm = panda();
        let oracle = ArmOracle::new(&arm, &[]).unwrap();
        let model = &arm.model;
        let g = &arm.group;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let unit = |rng: &mut rand_chacha::ChaCha8Rng| {
            Vector3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize()
        };
        let poses_at = |q0: &[f64], q1: &[f64], t: f64| {
            let q: Vec<f64> = q0.iter().zip(q1).map(|(a, b)| a + t * (b - a)).collect();
            arm.link_poses(&q)
        };
        let (mut checked, mut tighter) = (0, 0);
        for trial in 0..400 {
            let q0: Vec<f64> = (0..g.dof())
                .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
                .collect();
            let q1: Vec<f64> = (0..g.dof())
                .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
                .collect();
            let delta = oracle.joint_deltas(&q0, &q1);
            // a link alone, or a self pair's first link relative to the pair's common link
            let (l, except, common) = if trial % 2 == 0 {
                let l = rng.random_range(0..oracle.link_meshes.len());
                (l, None, None)
            } else {
                let (a, b) = arm.self_pairs[rng.random_range(0..arm.self_pairs.len())];
                let (ca, cb) = (model.chain_to(a), model.chain_to(b));
                let shared = ca.iter().zip(&cb).take_while(|(x, y)| x == y).count();
                let common = shared.checked_sub(1).map(|i| model.joint_links[ca[i]].1);
                (a, Some(b), common)
            };
            let Some((mesh, _)) = &oracle.link_meshes[l] else {
                continue;
            };
            let t0 = rng.random_range(0.0..=1.0);
            let sigma = rng.random_range(-0.4..=0.4);
            let (p0, p1) = (poses_at(&q0, &q1, t0), poses_at(&q0, &q1, t0 + sigma));
            let (m, accel) = oracle.moving(l, except, &delta, &p0).unwrap();
            // where a vertex is, in the frame that stands still (the world, or the common link)
            let frame =
                |poses: &[Isometry3<f64>]| common.map_or(Isometry3::identity(), |c| poses[c]);
            let place =
                |poses: &[Isometry3<f64>], v: &Point3<f64>| frame(poses).inverse() * (poses[l] * v);
            // the velocities are the motion's own (central differences), the acceleration bound
            // holds for every vertex (second differences)
            let h = 1e-5;
            let (pm, pp) = (poses_at(&q0, &q1, t0 - h), poses_at(&q0, &q1, t0 + h));
            let (_, ball) = oracle.link_meshes[l].as_ref().unwrap();
            let c = Point3::from(ball.centre);
            let velocity = frame(&p0).rotation * ((place(&pp, &c) - place(&pm, &c)) / (2.0 * h));
            let scale = m.velocity.norm() + m.spin.norm() + 1e-3;
            assert!(
                (velocity - m.velocity).norm() < 1e-5 * scale,
                "{velocity} {}",
                m.velocity
            );
            let turn = (frame(&pm).inverse() * pm[l])
                .rotation
                .rotation_to(&(frame(&pp).inverse() * pp[l]).rotation);
            let spin = frame(&p0).rotation * (turn.scaled_axis() / (2.0 * h));
            assert!((spin - m.spin).norm() < 1e-5 * scale, "{spin} {}", m.spin);
            for v in &mesh.vertices {
                let second = (place(&pp, v) - 2.0 * place(&p0, v).coords + place(&pm, v).coords)
                    .coords
                    / (h * h);
                assert!(
                    second.norm() <= accel * (1.0 + 1e-3) + 1e-3,
                    "{} > {accel}",
                    second.norm()
                );
            }
            let v = mesh.vertices[rng.random_range(0..mesh.vertices.len())];
            let own = place(&p1, &v) - place(&p0, &v);
            for n_here in [
                unit(&mut rng),
                own.try_normalize(1e-12).unwrap_or(Vector3::x()),
            ] {
                // the normal is fixed in the still frame; `Moving` speaks in world axes
                let n_world = frame(&p0).rotation * n_here;
                let rate =
                    n_world.dot(&m.velocity).abs() + m.radius * n_world.cross(&m.spin).norm();
                let bound = rate * sigma.abs() + accel * sigma * sigma / 2.0 + 1e-12;
                for v in &mesh.vertices {
                    let moved = n_here.dot(&(place(&p1, v) - place(&p0, v)));
                    assert!(
                        moved <= bound,
                        "link {l} (except {except:?}) moved {moved} along {n_here:?}, bound {bound}"
                    );
                }
                checked += 1;
                let worst: f64 = oracle.reach[l]
                    .iter()
                    .filter(|(k, _)| {
                        except.is_none_or(|o| !oracle.reach[o].iter().any(|(j, _)| j == k))
                    })
                    .map(|&(k, f)| delta[k].abs() * f)
                    .sum();
                tighter += usize::from(rate < 0.5 * worst);
            }
        }
        assert!(checked > 500, "only {checked} checks");
        assert!(
            tighter > checked / 4,
            "tighter in only {tighter} of {checked}"
        );
    }
}
