//! Local methods: connect two configurations by a collision-free path, or fail quickly.
//!
//! In Overmars–Švestka's learning approach the local method must be deterministic and
//! symmetric and may fail "now and then" (CHS §1.6). [`StraightLine`] asks one question per DOF
//! group; [`ViaPoint`] is the recursive via-point planner of CHS §1.3–1.5, which also reports
//! what it learnt on the way — via points and certified free segments — so the roadmap can keep
//! them ([`Discoveries`]).
//!
//! A *direct path* between two configurations changes one DOF group at a time in cyclic order
//! (CHS §1.5, Fig 1.6): in R^n that is one straight segment, for a rigid body a translation and
//! a rotation about one fixed axis. Every path a local method returns is a list of corners
//! joined by such single-group straight motions.

pub mod shorten;
pub mod spec;
pub mod straight;
pub mod viapoint;

pub use shorten::{drop_corners, drop_corners_known, shorten, shorten_known};
pub use spec::{check_local_spec, LocalSpec};
pub use straight::StraightLine;
pub use viapoint::{ViaPoint, ViaPointOptions};

use crate::deadline::Deadline;
use crate::fast_hash::FastMap;
use crate::interval::IntervalList;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::space::{Config, Group, Motion, Space};
use serde::{Deserialize, Serialize};

/// How a connection attempt ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Outcome {
    /// A collision-free path was found.
    Connected,
    /// The search ran out of alternatives without ever reaching its depth limit: with these
    /// settings no deeper search would help.
    Blocked,
    /// The depth limit (or the call budget) cut the search off.
    DepthExhausted,
    /// The deadline ([`crate::deadline::Deadline`]) stopped the search before it ended.
    Interrupted,
}

/// What a local method learnt about free space while searching (CHS §1.6: "the via points and
/// direct connections it discovers correspond to nodes and edges"): certified free segments
/// reachable from the start or from the goal — the whole path when connected, the partial
/// successes when not.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Discoveries {
    /// Free configurations met: index 0 is the start, 1 the goal, then via points and corners
    /// of direct paths in the order they were found.
    pub configs: Vec<Config>,
    /// Pairs of indices into `configs` joined by a certified free single-group straight motion.
    pub free_segments: Vec<(u32, u32)>,
    /// Indices into `configs` of the via points (the rest beyond 0 and 1 are corners).
    pub via_points: Vec<u32>,
}

impl Discoveries {
    /// Starts a record for a connection from `a` to `z`.
    pub fn new(a: &[f64], z: &[f64]) -> Self {
        Discoveries {
            configs: vec![a.to_vec(), z.to_vec()],
            free_segments: Vec::new(),
            via_points: Vec::new(),
        }
    }

    /// Adds a configuration and returns its index.
    pub fn add(&mut self, q: Config) -> u32 {
        self.configs.push(q);
        (self.configs.len() - 1) as u32
    }
}

/// One borderline the via-point planner asked about, kept for pictures and debugging.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Borderline {
    /// The blocked straight motion the borderline divides.
    pub blocked: Motion,
    /// Its collision intervals.
    pub collisions: IntervalList,
    /// The borderline's base point on the blocked motion.
    pub base: Config,
    /// The unbounded motion asked about (a line or a full turn through `base`).
    pub motion: Motion,
    /// Free sections of the borderline.
    pub free: IntervalList,
    /// The via points taken from it, in order of valuation.
    pub via_points: Vec<Config>,
}

/// The result of one connection attempt.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Connection {
    /// How the attempt ended.
    pub outcome: Outcome,
    /// The path from start to goal (corners joined by single-group straight motions) when
    /// connected; empty otherwise.
    pub path: Vec<Config>,
    /// Recursion depth of the path found (0 = the direct path was free); for a failure, the
    /// deepest limit tried.
    pub depth: u32,
    /// Oracle work spent on this attempt.
    pub counts: CallCounts,
    /// Via points and certified free segments met, also on failure.
    pub discoveries: Discoveries,
    /// Borderlines asked about, if the method was asked to keep them.
    pub borderlines: Vec<Borderline>,
}

impl Connection {
    /// The outcome of checking a direct path: `corners` (after `a`, ending at `z`) when it was
    /// free, with its pieces recorded as certified free segments; blocked otherwise.
    pub fn from_corners(
        a: &[f64],
        z: &[f64],
        corners: Option<Vec<Config>>,
        counts: CallCounts,
    ) -> Self {
        let mut discoveries = Discoveries::new(a, z);
        let (outcome, path) = match corners {
            Some(corners) => {
                let mut prev = 0u32;
                for (k, c) in corners.iter().enumerate() {
                    let idx = if k + 1 == corners.len() {
                        1
                    } else {
                        discoveries.add(c.clone())
                    };
                    discoveries.free_segments.push((prev, idx));
                    prev = idx;
                }
                let mut path = vec![a.to_vec()];
                path.extend(corners);
                (Outcome::Connected, path)
            }
            None => (Outcome::Blocked, Vec::new()),
        };
        Connection {
            outcome,
            path,
            depth: 0,
            counts,
            discoveries,
            borderlines: Vec::new(),
        }
    }

    /// An attempt that did not start because the deadline had passed.
    pub fn interrupted(a: &[f64], z: &[f64]) -> Self {
        Connection {
            outcome: Outcome::Interrupted,
            path: Vec::new(),
            depth: 0,
            counts: CallCounts::default(),
            discoveries: Discoveries::new(a, z),
            borderlines: Vec::new(),
        }
    }

    /// Whether a path was found.
    pub fn is_connected(&self) -> bool {
        self.outcome == Outcome::Connected
    }
}

/// A local method (OS94; CHS §1.6).
///
/// # Contract
/// - `a` and `z` are valid, collision-free configurations of `space` (the method does not
///   re-check them) and `oracle` answers for that space.
/// - Deterministic: the same inputs give the same [`Connection`], whatever thread runs it.
/// - Every oracle question is counted in [`Connection::counts`].
/// - Must be thread safe.
pub trait LocalMethod: Send + Sync {
    /// The method and its parameters ([`LocalSpec`]; its `Display` is the spec string):
    /// recorded in a roadmap's header, from which queries rebuild the method, and by
    /// benchmarks.
    fn spec(&self) -> LocalSpec;

    /// Tries to connect `a` to `z`.
    fn connect(
        &self,
        space: &Space,
        oracle: &dyn CollisionOracle,
        a: &[f64],
        z: &[f64],
    ) -> Result<Connection, OracleError> {
        self.connect_within(space, oracle, a, z, &Deadline::none())
    }

    /// Tries to connect `a` to `z`, stopping with [`Outcome::Interrupted`] once `deadline`
    /// has passed (checked before every oracle call, so an attempt overruns it by at most one
    /// call). What was certified before the stop is still reported in
    /// [`Connection::discoveries`].
    fn connect_within(
        &self,
        space: &Space,
        oracle: &dyn CollisionOracle,
        a: &[f64],
        z: &[f64],
        deadline: &Deadline,
    ) -> Result<Connection, OracleError>;

    /// The DOF groups this method's paths change one at a time (see [`Space::groups`]).
    fn groups(&self, space: &Space) -> Vec<Group> {
        space.groups(false)
    }
}

/// The pieces of the direct path from `a` to `z` that changes the groups in cyclic order
/// starting at group `first`: the motions and the corner each one ends at. Groups in which `a`
/// and `z` already agree are skipped.
pub fn direct_pieces(
    space: &Space,
    groups: &[Group],
    first: usize,
    a: &[f64],
    z: &[f64],
) -> Vec<(Motion, Config)> {
    let mut pieces = Vec::new();
    let mut cur = a.to_vec();
    for k in 0..groups.len() {
        let g = &groups[(first + k) % groups.len()];
        if space.same_in_group(&cur, z, g) {
            continue;
        }
        let motion = space.group_motion(&cur, z, g);
        let next = space.with_group_of(&cur, z, g);
        pieces.push((motion, next.clone()));
        cur = next;
    }
    pieces
}

/// The motions joining two consecutive corners `a`, `z` of a path, each with the corner it
/// ends at: the direct path's pieces ([`direct_pieces`]), except in a joint space, where
/// corners differing in several joints are joined by one straight motion of them all (a
/// shortcut certified at once, [`crate::robot::ArmOracle::straight_free`]): every path a
/// planner returns there moves one joint per pair of corners or goes straight.
pub fn path_pieces(space: &Space, groups: &[Group], a: &[f64], z: &[f64]) -> Vec<(Motion, Config)> {
    if goes_straight(space, groups, a, z) {
        let whole = space.straight_group().expect("a joint space");
        return vec![(space.group_motion(a, z, &whole), z.to_vec())];
    }
    direct_pieces(space, groups, 0, a, z)
}

/// The straight motion of several joints from `a` to `z` as a connection (corners `[z]`), where
/// the space has a straight group ([`Space::straight_group`]), `a` and `z` differ in more than
/// one of `groups`, and the oracle proves it free (one counted yes/no call, into `counts`).
/// `None` otherwise: not asked, or not proved — the caller tries the direct path.
pub fn straight_connection(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    a: &[f64],
    z: &[f64],
    counts: &mut CallCounts,
) -> Result<Option<Connection>, OracleError> {
    let Some(whole) = space
        .straight_group()
        .filter(|_| goes_straight(space, groups, a, z))
    else {
        return Ok(None);
    };
    let free = oracle.check_motion(&space.group_motion(a, z, &whole), counts)?;
    Ok(free.then(|| Connection::from_corners(a, z, Some(vec![z.to_vec()]), CallCounts::default())))
}

/// `path` with corners added along its straight motions of several joints ([`path_pieces`]),
/// none of them longer than `piece` (in the space's distance): points of a motion proved free,
/// for shortening to start and end shortcuts at. Other segments are kept as they are.
pub fn straight_corners(space: &Space, path: &[Config], piece: f64) -> Vec<Config> {
    straight_corners_of_motions(space, path, piece).0
}

/// [`straight_corners`], and for each of the result's segments the index of the segment of
/// `path` it lies on: consecutive segments of one motion of `path` are pieces of one straight
/// motion, and a shortcut across them only walks it again.
pub fn straight_corners_of_motions(
    space: &Space,
    path: &[Config],
    piece: f64,
) -> (Vec<Config>, Vec<u32>) {
    let motions = || (0..path.len().saturating_sub(1) as u32).collect();
    let Some(whole) = space.straight_group() else {
        return (path.to_vec(), motions());
    };
    let mut out = Vec::with_capacity(path.len());
    let mut of = Vec::with_capacity(path.len());
    out.extend(path.first().cloned());
    for (m, w) in path.windows(2).enumerate() {
        let moving = w[0].iter().zip(&w[1]).filter(|(a, b)| a != b).count();
        if moving > 1 && piece > 0.0 {
            let pieces = (space.group_length(&w[0], &w[1], &whole) / piece).ceil();
            let pieces = pieces.clamp(1.0, 1e4) as usize;
            out.extend(
                (1..pieces).map(|i| space.interpolate(&w[0], &w[1], i as f64 / pieces as f64)),
            );
            of.extend(std::iter::repeat_n(m as u32, pieces - 1));
        }
        out.push(w[1].clone());
        of.push(m as u32);
    }
    (out, of)
}

/// Whether consecutive corners `a`, `z` of a path are joined by one straight motion of
/// several joints ([`path_pieces`]).
pub(crate) fn goes_straight(space: &Space, groups: &[Group], a: &[f64], z: &[f64]) -> bool {
    space.straight_group().is_some()
        && groups
            .iter()
            .filter(|g| !space.same_in_group(a, z, g))
            .nth(1)
            .is_some()
}

/// Length of the direct path from `a` to `z` (sum over the groups it changes; Manhattan-like
/// when the groups are single axes).
///
/// The same sum as measuring [`direct_pieces`], without building a motion and a corner per
/// piece ([`Space::group_length`]): shortening measures every pair of corners (`m²` of them),
/// and those allocations were 7 % of a workcell query (table_pick) and still 0.17 ms
/// of a 1.1 ms shortening in the box with one motion and corner per pair.
pub fn direct_length(space: &Space, groups: &[Group], a: &[f64], z: &[f64]) -> f64 {
    // a group's piece starts where `a` is in that group (earlier pieces move other groups)
    groups
        .iter()
        .filter(|g| !space.same_in_group(a, z, g))
        .fold(0.0, |total, g| total + space.group_length(a, z, g))
}

/// Checks the direct path from `a` to `z` (yes/no, one counted call per piece, stopping at the
/// first blocked piece). Returns the corners after `a` if the whole path is free.
pub fn check_direct(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    a: &[f64],
    z: &[f64],
    counts: &mut CallCounts,
) -> Result<Option<Vec<Config>>, OracleError> {
    check_direct_known(space, oracle, groups, a, z, None, counts)
}

/// The answers for single-group pieces of direct paths already known during one shortening,
/// keyed by the piece's two ends (bit patterns; a piece is a function of its ends).
///
/// Not in the seed: a rigid body's path alternates translations and turns, so many pairs of
/// corners share a piece (from corner `i`, the direct paths to the corner before a turn and
/// to the one after it begin with the same translation; the direct path from a corner to the
/// one after next is often the two pieces of the path itself), and the greedy pass and the
/// visibility graph ask about the same pairs. Each piece is then asked once, and the pieces of
/// the path being shortened, free by the caller's contract, never.
///
/// The corners of the pieces are kept too (by their bits): a direct path is found blocked by a
/// corner in collision before any of its sweeps is asked ([`check_direct_known`]), and the
/// pairs of one shortening share corners as they share pieces.
#[derive(Debug, Default)]
pub struct KnownPieces {
    known: FastMap<Vec<u64>, bool>,
    /// `false` for a corner known to collide; `true` for one known free (a corner of the path)
    /// or that the oracle's sure test could not show in collision.
    corners: FastMap<Vec<u64>, bool>,
}

impl KnownPieces {
    /// Nothing known.
    pub fn new() -> KnownPieces {
        KnownPieces::default()
    }

    /// Records every piece of the direct paths between consecutive corners of `path` as free
    /// (the contract of [`shorten()`] and [`drop_corners`]: a path's consecutive corners are
    /// joined by free direct paths).
    pub fn certify_path(&mut self, space: &Space, groups: &[Group], path: &[Config]) {
        for w in path.windows(2) {
            let mut cur = w[0].clone();
            self.corners.insert(Self::corner_key(&cur), true);
            for (_, next) in path_pieces(space, groups, &w[0], &w[1]) {
                self.known.insert(Self::key(&cur, &next), true);
                self.corners.insert(Self::corner_key(&next), true);
                cur = next;
            }
        }
    }

    fn key(a: &[f64], z: &[f64]) -> Vec<u64> {
        a.iter().chain(z).map(|x| x.to_bits()).collect()
    }

    fn corner_key(q: &[f64]) -> Vec<u64> {
        q.iter().map(|x| x.to_bits()).collect()
    }

    /// What is known of corner `q` (see [`Self::corners`]), looked up through `buf`.
    fn corner_known(&self, q: &[f64], buf: &mut Vec<u64>) -> Option<bool> {
        buf.clear();
        buf.extend(q.iter().map(|x| x.to_bits()));
        self.corners.get(buf.as_slice()).copied()
    }

    /// The known answer for the piece from `a` to `z`, looked up through `buf`.
    fn piece_known(&self, a: &[f64], z: &[f64], buf: &mut Vec<u64>) -> Option<bool> {
        buf.clear();
        buf.extend(a.iter().chain(z).map(|x| x.to_bits()));
        self.known.get(buf.as_slice()).copied()
    }

    /// Whether corner `q` blocks a path through it, kept: the known answer, else the oracle's
    /// sure test ([`CollisionOracle::surely_collides`]), else, for an oracle without one, its
    /// full static test (a counted state check).
    ///
    /// Where a sure test exists the full test is not asked: the sweeps of a free path cover its
    /// corners anyway, and a collision the sure test misses is found by the sweep that ends
    /// there. In the Panda's box workcell the sure test found two of three colliding corners at
    /// ~1 µs against 10–25 µs for the full test, and leaving the rest to the sweeps lowered the
    /// query p50 from 1.26–1.41 to 1.06–1.09 ms (three runs each, the same paths).
    fn corner_blocks(
        &mut self,
        oracle: &dyn CollisionOracle,
        q: &[f64],
        buf: &mut Vec<u64>,
        counts: &mut CallCounts,
    ) -> bool {
        if let Some(known) = self.corner_known(q, buf) {
            return !known;
        }
        let free = match oracle.surely_collides(q) {
            Some(hit) => !hit,
            None => oracle.is_free(q, counts),
        };
        self.corners.insert(Self::corner_key(q), free);
        !free
    }

    /// Whether what is known already blocks the direct path from `a` to `z` (an inner corner
    /// in collision or a piece blocked), without asking the oracle: a shortening's lazy search
    /// sets aside every such pair on its candidate path at once, where it would otherwise
    /// search again after each (in the box's workcell two of three pairs a shortening looked at
    /// were blocked by a corner already found in collision).
    pub fn blocks(&self, space: &Space, groups: &[Group], a: &[f64], z: &[f64]) -> bool {
        let mut buf = Vec::with_capacity(2 * a.len());
        let mut cur = a.to_vec();
        let mut next = a.to_vec();
        for g in groups {
            if space.same_in_group(&cur, z, g) {
                continue;
            }
            g.copy_coords(&mut next, z);
            if self.piece_known(&cur, &next, &mut buf) == Some(false)
                || (next.as_slice() != z && self.corner_known(&next, &mut buf) == Some(false))
            {
                return true;
            }
            g.copy_coords(&mut cur, z);
        }
        false
    }

    /// Number of pieces known.
    pub fn len(&self) -> usize {
        self.known.len()
    }

    /// Whether nothing is known.
    pub fn is_empty(&self) -> bool {
        self.known.is_empty()
    }
}

/// [`check_direct`] that first looks each piece up in `known` (and records what it asks
/// there): the same answer, and the same corners, with no call for a piece already known.
///
/// With `known`, the corners between the pieces are tested first ([`KnownPieces`]; the sure
/// test where the oracle has one, else a static check; kept): a corner in collision blocks the
/// path, and the sweeps are not asked. Of the pairs a shortening checks most are blocked (a
/// path around an obstacle, tried across it), and a corner inside the obstacle is found by a
/// static test where the sweep before it might be free and the one after it costs most (the
/// box's workcell: query p50 8.2 → 4.6 ms with the full static test, the same paths).
/// Without `known`, the sure test alone ([`surely_blocked`]).
pub fn check_direct_known(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    a: &[f64],
    z: &[f64],
    mut known: Option<&mut KnownPieces>,
    counts: &mut CallCounts,
) -> Result<Option<Vec<Config>>, OracleError> {
    let pieces = direct_pieces(space, groups, 0, a, z);
    let mut buf = Vec::with_capacity(2 * a.len());
    // the last corner is `z`, a corner of the path being shortened or a node: free
    let inner = &pieces[..pieces.len().saturating_sub(1)];
    let blocked = match known.as_mut() {
        Some(k) => inner
            .iter()
            .any(|(_, end)| k.corner_blocks(oracle, end, &mut buf, counts)),
        None => surely_blocked(oracle, &pieces),
    };
    if blocked {
        return Ok(None);
    }
    let mut corners = Vec::with_capacity(pieces.len().max(1));
    let mut cur: &[f64] = a;
    for (motion, end) in &pieces {
        let cached = known
            .as_ref()
            .and_then(|k| k.piece_known(cur, end, &mut buf));
        let free = match cached {
            Some(f) => f,
            None => {
                let f = oracle.check_motion(motion, counts)?;
                if let Some(k) = known.as_mut() {
                    k.known.insert(KnownPieces::key(cur, end), f);
                }
                f
            }
        };
        if !free {
            return Ok(None);
        }
        corners.push(end.clone());
        cur = end;
    }
    if corners.is_empty() {
        corners.push(z.to_vec());
    }
    Ok(Some(corners))
}

/// Whether an inner corner of a direct path's `pieces` (each piece's end but the last's)
/// surely collides ([`CollisionOracle::surely_collides`]): the path is then blocked, whatever
/// its sweeps would say, and none need be asked. Most direct paths a query tries are blocked
/// (attaching to the nearest nodes, shortening across an obstacle), and a sweep costs tens of
/// microseconds where the sure test costs one.
pub fn surely_blocked(oracle: &dyn CollisionOracle, pieces: &[(Motion, Config)]) -> bool {
    pieces[..pieces.len().saturating_sub(1)]
        .iter()
        .any(|(_, end)| oracle.surely_collides(end) == Some(true))
}

/// The direct path from `a` to `z` as a connection attempt (CHS's depth 0): one exact call
/// per DOF group it changes, the corners and free segments recorded for feedback.
pub fn direct_connection(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    a: &[f64],
    z: &[f64],
) -> Result<Connection, OracleError> {
    let mut counts = CallCounts::default();
    let corners = check_direct(space, oracle, groups, a, z, &mut counts)?;
    Ok(Connection::from_corners(a, z, corners, counts))
}

/// Total length of a path of corners joined by direct paths (a straight motion of several
/// joints by its Euclidean length, [`path_pieces`]). Starts from `+0.0`: `Iterator::sum` of
/// no terms is `-0.0`, which a one-corner path would print as `-0.0000`.
pub fn path_length(space: &Space, groups: &[Group], path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| segment_length(space, groups, &w[0], &w[1]))
        .fold(0.0, |total, l| total + l)
}

/// Where a path first collides ([`first_collision_on_path`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathCollision {
    /// The segment, 0-based: the motion from corner `segment` to corner `segment + 1`.
    pub segment: usize,
    /// The share of the segment's length travelled when the robot first touches (0 where the
    /// segment's first corner collides); where not `proved`, the end of the longest part of
    /// the segment proved free.
    pub t: f64,
    /// Whether a collision was found. `false` where the oracle answers a motion only yes or
    /// no and could not prove the rest of the segment free, yet its first configuration
    /// there is free (an arm's straight motion of several joints passing too close to an
    /// obstacle for conservative advancement to finish).
    pub proved: bool,
}

/// Bisections that locate where a motion answered only yes or no stops being proved free:
/// 2⁻²⁰ of the motion, far below what a message shows.
const YES_NO_BISECTIONS: usize = 20;

/// Configurations tried past the part of such a motion proved free, looking for one in
/// collision: steps of 1/1024 of the motion.
const YES_NO_STEPS: usize = 1024;

/// Where `motion` first collides as a share of its range, and whether a collision was found:
/// exact where the oracle answers intervals. Where it answers only yes or no
/// ([`OracleError::Unsupported`], an arm's straight motion of several joints), the longest
/// prefix proved free is found by bisection, and the first configuration in collision past it
/// (in steps of [`YES_NO_STEPS`]) is the answer; with none, the end of that prefix, not
/// proved. `None` if the whole motion is free.
fn first_hit_share(
    oracle: &dyn CollisionOracle,
    motion: &Motion,
    counts: &mut CallCounts,
) -> Result<Option<(f64, bool)>, OracleError> {
    let r = motion.range;
    let share = |t: f64| {
        if r.hi > r.lo {
            ((t - r.lo) / (r.hi - r.lo)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    match oracle.first_hit(motion, counts) {
        Ok(hit) => return Ok(hit.map(|t| (share(t), true))),
        Err(OracleError::Unsupported(_)) => {}
        Err(e) => return Err(e),
    }
    if oracle.check_motion(motion, counts)? {
        return Ok(None);
    }
    if !oracle.is_free(&motion.at(r.lo), counts) {
        return Ok(Some((0.0, true)));
    }
    // [r.lo, lo] proved free, [r.lo, hi] not
    let (mut lo, mut hi) = (r.lo, r.hi);
    for _ in 0..YES_NO_BISECTIONS {
        let mid = 0.5 * (lo + hi);
        let prefix = motion.with_range(crate::interval::Interval { lo: r.lo, hi: mid });
        if oracle.check_motion(&prefix, counts)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let step = (r.hi - r.lo) / YES_NO_STEPS as f64;
    let mut t = hi;
    while t <= r.hi {
        if !oracle.is_free(&motion.at(t), counts) {
            return Ok(Some((share(t), true)));
        }
        t += step;
    }
    Ok(Some((share(lo), false)))
}

/// The first collision along `path`, its corners joined as the planners join them
/// ([`path_pieces`]): as exact as the oracle (the earliest parameter of the first blocked
/// piece, outside the bounds counting as obstacle where the oracle is [`Bounded`]; for a
/// motion the oracle answers only yes or no, see [`PathCollision::proved`]). A path of one
/// corner collides where that corner does (segment 0, `t` 0). `None` if the whole path is
/// free. Checks a path given from outside (a file), which no planner vouches for.
///
/// [`Bounded`]: crate::oracle::Bounded
pub fn first_collision_on_path(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    counts: &mut CallCounts,
) -> Result<Option<PathCollision>, OracleError> {
    let at_corner = |segment| PathCollision {
        segment,
        t: 0.0,
        proved: true,
    };
    if let [q] = path {
        return Ok((!oracle.is_free(q, counts)).then_some(at_corner(0)));
    }
    for (segment, w) in path.windows(2).enumerate() {
        let pieces = path_pieces(space, groups, &w[0], &w[1]);
        if pieces.is_empty() {
            // a repeated corner: no motion, only the corner itself to check
            if !oracle.is_free(&w[0], counts) {
                return Ok(Some(at_corner(segment)));
            }
            continue;
        }
        let total = segment_length(space, groups, &w[0], &w[1]);
        let mut travelled = 0.0;
        let mut from = w[0].clone();
        for (motion, to) in &pieces {
            let length = segment_length(space, groups, &from, to);
            if let Some((share, proved)) = first_hit_share(oracle, motion, counts)? {
                let t = if total > 0.0 {
                    ((travelled + share * length) / total).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                return Ok(Some(PathCollision { segment, t, proved }));
            }
            travelled += length;
            from.clone_from(to);
        }
    }
    Ok(None)
}

/// Length of the motion joining two consecutive corners of a path ([`path_pieces`]): the
/// direct path's, or a straight shortcut's Euclidean length.
pub fn segment_length(space: &Space, groups: &[Group], a: &[f64], z: &[f64]) -> f64 {
    match space.straight_group() {
        Some(whole) if goes_straight(space, groups, a, z) => space.group_length(a, z, &whole),
        _ => direct_length(space, groups, a, z),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `direct_length` skips building the pieces; it must measure them exactly as they are.
    #[test]
    fn direct_length_is_the_sum_of_its_pieces_bit_for_bit() {
        let spaces = [
            Space::euclidean(vec![-1.0; 4], vec![2.0; 4]).unwrap(),
            Space::se2([-3.0, -1.0], [2.0, 5.0], 0.7).unwrap(),
            Space::se3([-3.0, -1.0, 0.0], [2.0, 5.0, 4.0], 1.3).unwrap(),
            Space::joints(
                vec![-2.9, -1.7, -2.9, -3.0],
                vec![2.9, 1.7, 2.9, -0.1],
                &[false, true, false, false],
            )
            .unwrap(),
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for space in &spaces {
            for split in [false, true] {
                let groups = space.groups(split);
                for _ in 0..300 {
                    let a = space.sample_uniform(&mut rng);
                    let mut z = space.sample_uniform(&mut rng);
                    // some pairs share groups, so that pieces are skipped
                    if rng.random_bool(0.3) {
                        z[0] = a[0];
                    }
                    let pieces: f64 = direct_pieces(space, &groups, 0, &a, &z)
                        .iter()
                        .map(|(m, _)| space.motion_length(m, 0.0, 1.0))
                        .sum();
                    let fast = direct_length(space, &groups, &a, &z);
                    assert_eq!(fast.to_bits(), pieces.to_bits(), "{space:?} {a:?} → {z:?}");
                }
            }
        }
    }

    /// Corners along a path's straight motions of several joints: at most `piece` apart, on
    /// the motion's line in order, the path's own corners kept; single-joint stairs and spaces
    /// without straight motions untouched.
    #[test]
    fn straight_corners_split_straight_motions_only() {
        let space = Space::joints(vec![-3.0; 4], vec![3.0; 4], &[false; 4]).unwrap();
        let whole = space.straight_group().unwrap();
        let path = vec![
            vec![0.0, 0.0, 0.0, 0.0],
            vec![1.0, 0.0, 0.0, 0.0],
            vec![2.0, 1.0, -1.0, 0.5],
            vec![2.0, 1.0, -1.0, 0.5],
            vec![2.0, 1.0, -1.0, 0.6],
        ];
        let piece = 0.3;
        let dense = straight_corners(&space, &path, piece);
        // the stair 0 → 1 and the short stair at the end are kept; the straight motion of
        // length √3.25 ≈ 1.80 is cut into 7 pieces; the repeated corner stays
        assert_eq!(dense.len(), path.len() + 6);
        assert_eq!(&dense[..2], &path[..2]);
        assert_eq!(&dense[dense.len() - 3..], &path[2..]);
        let (a, z) = (&path[1], &path[2]);
        let mut last = 0.0;
        for c in &dense[2..8] {
            let t = (c[0] - a[0]) / (z[0] - a[0]);
            assert!(t > last && t < 1.0);
            for i in 0..4 {
                assert!((c[i] - (a[i] + t * (z[i] - a[i]))).abs() < 1e-12);
            }
            last = t;
        }
        for w in dense[1..9].windows(2) {
            assert!(space.group_length(&w[0], &w[1], &whole) <= piece + 1e-12);
        }
        let plane = Space::se2([-3.0, -1.0], [2.0, 5.0], 0.7).unwrap();
        let moves = vec![vec![0.0, 0.0, 0.0], vec![1.0, 2.0, 0.5]];
        assert_eq!(straight_corners(&plane, &moves, 0.1), moves);
    }
}
