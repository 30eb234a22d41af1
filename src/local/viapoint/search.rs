//! The tree of subproblems the via-point planner searches (CHS §1.3, Fig 1.3 and 1.6).
//!
//! A node is a subproblem `connect(a, z, j)`: walk the direct path from `a` towards `z`,
//! changing DOF group `j` first and the others in cyclic order; every free piece is kept; at the
//! first blocked piece the node asks for via points `q` on borderlines and has two children per
//! via point, `connect(cur, q, k)` and `connect(q, z, i)` (CHS Fig 1.6: "change coordinate k
//! before i", then "i before k"). With one DOF group this is exactly Fig 1.3.
//!
//! The same tree serves every strategy of CHS §1.3: depth-first recursion with a limit (plain
//! recursion is the tree thrown away after each limit; *deepening with re-use* keeps it, so
//! that solved and failed subproblems and all oracle answers are remembered — Table A.2), and a
//! breadth-first expansion level by level.
//!
//! Configurations live in one flat arena and nodes refer to them by index: a search makes
//! millions of subproblems in the worst cases of the seed's experiments, and per-node
//! allocations used to cost more than the oracle.

use super::borderline::{
    base_parameter, borderlines_into, candidates_into, free_sections_into, round_is_empty,
    via_point, Candidate, Crossing, Lines,
};
use super::options::{BasePoint, Directions, ViaLimit, ViaPointOptions};
use crate::deadline::Deadline;
use crate::fast_hash::{FastMap, FastSet};
use crate::interval::{Interval, IntervalList};
use crate::local::{Borderline, Discoveries};
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError, Workspace};
use crate::space::extend_small;
use crate::space::{Config, Group, Motion, Space};
use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::hash_map::Entry;

pub(super) type NodeId = usize;
type Pt = u32;

/// The direct path of a node, walked as far as it is free.
struct Walk {
    /// Arena indices of the corners reached after the node's start (the last is the current
    /// configuration): `first_corner..end` plus the goal itself if the walk reached it.
    first_corner: Pt,
    end: Pt,
    reached_goal: bool,
    /// Length of the free part.
    length: f64,
    /// The first blocked piece: the configuration it aims at (its group taken from the goal),
    /// the index of the group, and the borderline's base point on it.
    blocked: Option<Blocked>,
}

struct Blocked {
    target: Pt,
    group: usize,
    base: Pt,
    /// Kept only when tracing (boxed: a node is moved whenever the node list grows, and
    /// three words fewer keep that move a few register copies instead of a `memcpy` call).
    collisions: Option<Box<IntervalList>>,
}

impl Walk {
    fn cur(&self, node_a: Pt) -> Pt {
        if self.end > self.first_corner {
            self.end - 1
        } else {
            node_a
        }
    }
}

struct Via {
    q: Pt,
    /// The group the via point dodges in: its left child changes this group first.
    group: usize,
    left: Option<NodeId>,
    right: Option<NodeId>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Status {
    /// Not solved yet; known to fail for every recursion limit `≤ failed_up_to` (−1: none).
    Open { failed_up_to: i64 },
    /// Solved with a path of this recursion depth through via point `via` (`None`: the direct
    /// path is free).
    Solved { depth: u32, via: Option<usize> },
    /// Fails whatever the limit: every alternative is blocked without reaching the limit.
    Dead,
}

struct Node {
    a: Pt,
    z: Pt,
    first_group: usize,
    walk: Option<Walk>,
    vias: Vec<Via>,
    rounds: u32,
    rounds_exhausted: bool,
    status: Status,
}

/// Everything a search allocates, kept between searches (one set per thread, see
/// [`super::ViaPoint`]) so that in steady state a search allocates nothing but its answer
/// (allocating per search cost more than the oracle's work): the arena, the nodes (and their via lists, recycled), the motions asked about,
/// the oracle's answers and workspace, and the candidate lists.
#[derive(Default)]
pub(super) struct Buffers {
    pts: Vec<f64>,
    nodes: Vec<Node>,
    spare_vias: Vec<Vec<Via>>,
    segments: Vec<(Pt, Pt)>,
    vias_found: Vec<Pt>,
    /// Configuration scratch: `buf` for via and base points, the others for walks.
    buf: Config,
    cur: Config,
    goal: Config,
    next: Config,
    base: Config,
    /// One motion slot per DOF group (a slot keeps its kind of change, so no buffer is
    /// dropped when SE(3) walks alternate between translations and rotations).
    group_motions: Vec<Motion>,
    blocked_motion: Motion,
    lines: Lines,
    hits: IntervalList,
    complement: IntervalList,
    sections: Vec<Interval>,
    cands: Vec<Candidate>,
    pool: Vec<(usize, usize, f64, f64)>,
    ws: Workspace,
    merge: Merge,
}

impl Buffers {
    /// Arena sizes above which the buffers are not kept for the next search: a rare deep
    /// search should not hold its memory for the rest of the thread's life.
    const MAX_KEPT_NODES: usize = 1 << 16;
    const MAX_KEPT_NUMBERS: usize = 1 << 20;

    /// Empties the buffers for reuse, dropping oversized ones.
    fn recycle(&mut self) {
        let Buffers {
            pts,
            nodes,
            spare_vias,
            segments,
            vias_found,
            ..
        } = self;
        for n in nodes.drain(..) {
            let mut v = n.vias;
            v.clear();
            spare_vias.push(v);
        }
        if nodes.capacity() > Self::MAX_KEPT_NODES {
            *nodes = Vec::new();
            spare_vias.truncate(Self::MAX_KEPT_NODES);
            spare_vias.shrink_to_fit();
        }
        if pts.capacity() > Self::MAX_KEPT_NUMBERS {
            *pts = Vec::new();
        }
        pts.clear();
        segments.clear();
        vias_found.clear();
        if segments.capacity() > Self::MAX_KEPT_NODES {
            *segments = Vec::new();
        }
        if vias_found.capacity() > Self::MAX_KEPT_NODES {
            *vias_found = Vec::new();
        }
    }
}

/// One connection attempt's search state.
pub(super) struct Search<'a> {
    space: &'a Space,
    oracle: &'a dyn CollisionOracle,
    options: &'a ViaPointOptions,
    groups: &'a [Group],
    dim: usize,
    /// Oracle work so far.
    pub counts: CallCounts,
    recording: bool,
    /// Borderlines asked about (when tracing).
    pub borderlines: Vec<Borderline>,
    /// Some branch was cut off by the recursion limit (in the current pass).
    pub limit_hit: bool,
    /// The call budget ran out, or the deadline passed.
    pub budget_hit: bool,
    /// The deadline passed (checked before every oracle call).
    pub interrupted: bool,
    deadline: &'a Deadline,
    /// Plain recursion: drop the subtrees of failed via points, as the seed's recursion does,
    /// so memory stays proportional to the depth rather than to the number of calls.
    forget_failures: bool,
    /// The arena (`b.pts`: flat configurations, `dim` numbers each; 0 is the start, 1 the
    /// goal), the nodes, what was recorded, and scratch.
    b: Buffers,
}

/// A node's random stream, seeded only when a random choice is actually made: the default
/// settings never draw, and seeding ChaCha per node cost more than the oracle.
/// The numbers drawn are the same as from `ChaCha8Rng::seed_from_u64(seed)`.
/// Where the settings make no random choice at all, not even the seed is hashed (`seed` is
/// `None`); [`draws_base`] and [`draws_directions`] decide that.
struct NodeRng {
    seed: Option<u64>,
    rng: Option<ChaCha8Rng>,
}

impl NodeRng {
    fn get(&mut self) -> &mut ChaCha8Rng {
        debug_assert!(
            self.seed.is_some(),
            "a node drew from a stream it said it would not"
        );
        let seed = self.seed.unwrap_or(0);
        self.rng
            .get_or_insert_with(|| ChaCha8Rng::seed_from_u64(seed))
    }
}

/// Whether [`base_parameter`] draws a random number for this strategy.
pub(super) fn draws_base(strategy: BasePoint) -> bool {
    matches!(
        strategy,
        BasePoint::RandomInFirst | BasePoint::CentreOfRandom | BasePoint::RandomInMotion
    )
}

/// Whether erecting borderlines draws random numbers with these directions.
fn draws_directions(directions: Directions) -> bool {
    matches!(directions, Directions::Random { .. })
}

impl RngCore for NodeRng {
    fn next_u32(&mut self) -> u32 {
        self.get().next_u32()
    }
    fn next_u64(&mut self) -> u64 {
        self.get().next_u64()
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.get().fill_bytes(dst)
    }
}

impl<'a> Search<'a> {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        space: &'a Space,
        oracle: &'a dyn CollisionOracle,
        options: &'a ViaPointOptions,
        groups: &'a [Group],
        a: &[f64],
        z: &[f64],
        forget_failures: bool,
        deadline: &'a Deadline,
        mut b: Buffers,
    ) -> Self {
        b.recycle();
        b.pts.reserve(64 * a.len());
        b.pts.extend_from_slice(a);
        b.pts.extend_from_slice(z);
        b.buf.clear();
        b.buf.resize(a.len(), 0.0);
        b.group_motions.resize_with(groups.len(), Motion::default);
        Search {
            space,
            oracle,
            options,
            groups,
            dim: a.len(),
            counts: CallCounts::default(),
            recording: options.discoveries,
            borderlines: Vec::new(),
            limit_hit: false,
            budget_hit: false,
            interrupted: false,
            deadline,
            forget_failures,
            b,
        }
    }

    /// The buffers, for the next search on this thread.
    pub fn into_buffers(self) -> Buffers {
        self.b
    }

    fn pt(&self, i: Pt) -> &[f64] {
        let d = self.dim;
        &self.b.pts[i as usize * d..(i as usize + 1) * d]
    }

    fn push_pt(&mut self, q: &[f64]) -> Pt {
        extend_small(&mut self.b.pts, q);
        (self.b.pts.len() / self.dim - 1) as Pt
    }

    fn pt_count(&self) -> usize {
        self.b.pts.len() / self.dim
    }

    /// Drops the nodes from `from` on, keeping their via lists for reuse.
    fn truncate_nodes(&mut self, from: usize) {
        let Buffers {
            nodes, spare_vias, ..
        } = &mut self.b;
        for n in nodes.drain(from..) {
            let mut v = n.vias;
            v.clear();
            spare_vias.push(v);
        }
    }

    /// Forgets the tree (plain recursion re-computes everything for the next limit) but keeps
    /// the counts and what was learnt. Returns the new root.
    pub fn new_root(&mut self) -> NodeId {
        self.truncate_nodes(0);
        self.new_node(0, 1, 0)
    }

    fn new_node(&mut self, a: Pt, z: Pt, first_group: usize) -> NodeId {
        let vias = self.b.spare_vias.pop().unwrap_or_default();
        self.b.nodes.push(Node {
            a,
            z,
            first_group,
            walk: None,
            vias,
            rounds: 0,
            rounds_exhausted: false,
            status: Status::Open { failed_up_to: -1 },
        });
        self.b.nodes.len() - 1
    }

    /// Whether the call budget is spent or the deadline has passed (remembered, so that the
    /// clock is read at most once per oracle call and a stopped search stays stopped).
    fn out_of_budget(&mut self) -> bool {
        self.out_of_time()
            || self
                .options
                .max_calls
                .is_some_and(|m| self.counts.intersect_calls() >= m)
    }

    /// Whether the deadline has passed (remembered: a stopped search stays stopped).
    fn out_of_time(&mut self) -> bool {
        if !self.interrupted && self.deadline.expired() {
            self.interrupted = true;
            self.budget_hit = true;
        }
        self.interrupted
    }

    /// Whether a node still to be walked must not be, because the deadline has passed: the
    /// walk asks the oracle (the call budget keeps its old meaning: it is checked between
    /// via points, so a walk may finish past it).
    fn walk_refused(&mut self, id: NodeId) -> bool {
        self.b.nodes[id].walk.is_none() && self.out_of_time()
    }

    /// Walks the node's direct path (one intersectSegment per group it changes); at the first
    /// blocked piece, fixes the borderline's base point.
    fn ensure_walk(&mut self, id: NodeId) -> Result<(), OracleError> {
        if self.b.nodes[id].walk.is_some() {
            return Ok(());
        }
        let (space, groups) = (self.space, self.groups);
        let (a, z, first) = (
            self.b.nodes[id].a,
            self.b.nodes[id].z,
            self.b.nodes[id].first_group,
        );
        // the walk's configurations live in buffers of the search, taken out for the walk
        let mut goal = std::mem::take(&mut self.b.goal);
        let mut cur = std::mem::take(&mut self.b.cur);
        let mut next = std::mem::take(&mut self.b.next);
        let mut collisions = std::mem::take(&mut self.b.hits);
        goal.clear();
        extend_small(&mut goal, self.pt(z));
        cur.clear();
        extend_small(&mut cur, self.pt(a));
        let mut cur_idx = a;
        let first_corner = self.pt_count() as Pt;
        let mut length = 0.0;
        let mut reached_goal = false;
        let mut blocked = None;
        for k in 0..groups.len() {
            let gi = (first + k) % groups.len();
            let g = &groups[gi];
            if space.same_in_group(&cur, &goal, g) {
                continue;
            }
            let motion = &mut self.b.group_motions[gi];
            space.group_motion_into(&cur, &goal, g, motion);
            self.oracle.intersect_into(
                motion,
                &mut collisions,
                &mut self.b.ws,
                &mut self.counts,
            )?;
            space.with_group_of_into(&cur, &goal, g, &mut next);
            if !collisions.is_empty() {
                let mut rng = self.node_rng(id, 0, draws_base(self.options.base_point));
                let t = base_parameter(self.options.base_point, &collisions, &mut rng);
                let mut base = std::mem::take(&mut self.b.buf);
                self.b.group_motions[gi].write_at(t, &mut base);
                space.normalize(&mut base);
                let base_idx = self.push_pt(&base);
                self.b.buf = base;
                let target = self.push_pt(&next);
                blocked = Some(Blocked {
                    target,
                    group: gi,
                    base: base_idx,
                    collisions: self.options.trace.then(|| Box::new(collisions.clone())),
                });
                break;
            }
            length += space.motion_length(&self.b.group_motions[gi], 0.0, 1.0);
            reached_goal = groups.iter().all(|h| space.same_in_group(&next, &goal, h));
            let idx = if reached_goal { z } else { self.push_pt(&next) };
            if self.recording {
                self.b.segments.push((cur_idx, idx));
            }
            std::mem::swap(&mut cur, &mut next);
            cur_idx = idx;
        }
        self.b.goal = goal;
        self.b.cur = cur;
        self.b.next = next;
        self.b.hits = collisions;
        // corners are the points pushed before any base/target of a blocked piece
        let end = match &blocked {
            Some(b) => b.base,
            None => self.pt_count() as Pt,
        };
        if blocked.is_none() {
            self.b.nodes[id].status = Status::Solved {
                depth: 0,
                via: None,
            };
        }
        self.b.nodes[id].walk = Some(Walk {
            first_corner,
            end,
            reached_goal,
            length,
            blocked,
        });
        Ok(())
    }

    /// A random stream of its own for each node and round, so that random choices do not depend
    /// on the order in which the search meets the node (seeded lazily, see [`NodeRng`]).
    fn node_rng(&self, id: NodeId, round: u32, draws: bool) -> NodeRng {
        if !draws {
            return NodeRng {
                seed: None,
                rng: None,
            };
        }
        let n = &self.b.nodes[id];
        let mut h = 0xcbf2_9ce4_8422_2325u64 ^ self.options.seed;
        let words = self.pt(n.a).iter().chain(self.pt(n.z)).map(|x| x.to_bits());
        for v in words.chain([n.first_group as u64, round as u64]) {
            h = (h ^ v).wrapping_mul(0x0000_0100_0000_01b3);
            h ^= h >> 29;
        }
        NodeRng {
            seed: Some(h),
            rng: None,
        }
    }

    /// Computes the via points of the next round of borderlines. `false` when there are no more
    /// rounds.
    fn extend_vias(&mut self, id: NodeId) -> Result<bool, OracleError> {
        if self.b.nodes[id].rounds_exhausted {
            return Ok(false);
        }
        let round = self.b.nodes[id].rounds;
        let node = &self.b.nodes[id];
        let Some(walk) = &node.walk else {
            return Ok(false);
        };
        let Some(blocked) = &walk.blocked else {
            return Ok(false);
        };
        let (cur_pt, base_pt, target, group) = (
            walk.cur(node.a),
            blocked.base,
            blocked.target,
            blocked.group,
        );
        let (space, groups, options) = (self.space, self.groups, self.options);
        if round_is_empty(groups, options, group, round) {
            // what erecting this round's (no) borderlines would conclude, without building the
            // blocked motion first
            self.b.nodes[id].rounds_exhausted = true;
            return Ok(false);
        }
        let mut base = std::mem::take(&mut self.b.base);
        base.clear();
        extend_small(&mut base, self.pt(base_pt));
        let mut blocked_motion = std::mem::take(&mut self.b.blocked_motion);
        space.group_motion_into(
            self.pt(cur_pt),
            self.pt(target),
            &groups[group],
            &mut blocked_motion,
        );
        let mut rng = self.node_rng(id, round + 1, draws_directions(options.directions));
        let crossing = Crossing {
            motion: &blocked_motion,
            group,
            base: &base,
        };
        let mut lines = std::mem::take(&mut self.b.lines);
        borderlines_into(
            space, groups, options, &crossing, round, &mut rng, &mut lines,
        );
        if lines.len() == 0 {
            self.b.nodes[id].rounds_exhausted = true;
            self.b.base = base;
            self.b.blocked_motion = blocked_motion;
            self.b.lines = lines;
            return Ok(false);
        }
        // (borderline index, candidate); ties keep the order of the borderlines and sections
        let mut pool = std::mem::take(&mut self.b.pool);
        let mut scratch = std::mem::take(&mut self.b.buf);
        let mut collisions = std::mem::take(&mut self.b.hits);
        let mut complement = std::mem::take(&mut self.b.complement);
        let mut sections = std::mem::take(&mut self.b.sections);
        let mut cands = std::mem::take(&mut self.b.cands);
        pool.clear();
        for (k, (motion, _)) in lines.as_slice().iter().enumerate() {
            if self.out_of_budget() {
                self.budget_hit = true;
                break;
            }
            self.oracle.intersect_into(
                motion,
                &mut collisions,
                &mut self.b.ws,
                &mut self.counts,
            )?;
            free_sections_into(motion, &collisions, &mut complement, &mut sections);
            cands.clear();
            candidates_into(
                space,
                motion,
                &sections,
                &base,
                options.beta,
                &mut scratch,
                &mut cands,
            );
            if options.trace {
                self.record_borderline(id, &blocked_motion, &base, motion, &sections, &cands);
            }
            let n = pool.len();
            pool.extend(
                cands
                    .iter()
                    .enumerate()
                    .map(|(j, c)| (k, n + j, c.t, c.value)),
            );
        }
        pool.sort_unstable_by(|a, b| a.3.total_cmp(&b.3).then(a.1.cmp(&b.1)));
        if let ViaLimit::Best(k) = options.via {
            pool.truncate(k);
        }
        self.push_vias(id, &pool, &lines, &mut scratch);
        self.b.nodes[id].rounds += 1;
        self.b.pool = pool;
        self.b.buf = scratch;
        self.b.hits = collisions;
        self.b.complement = complement;
        self.b.sections = sections;
        self.b.cands = cands;
        self.b.base = base;
        self.b.blocked_motion = blocked_motion;
        self.b.lines = lines;
        Ok(true)
    }

    /// Keeps a borderline of node `id`'s blocked motion for the trace: what it crossed, its
    /// free sections and the via points they gave.
    fn record_borderline(
        &mut self,
        id: NodeId,
        blocked_motion: &Motion,
        base: &Config,
        motion: &Motion,
        sections: &[Interval],
        cands: &[Candidate],
    ) {
        let space = self.space;
        let blocked = self.b.nodes[id]
            .walk
            .as_ref()
            .and_then(|w| w.blocked.as_ref());
        self.borderlines.push(Borderline {
            blocked: blocked_motion.clone(),
            collisions: blocked
                .and_then(|b| b.collisions.as_deref().cloned())
                .unwrap_or_default(),
            base: base.clone(),
            motion: motion.clone(),
            free: IntervalList::from_unsorted(sections.to_vec()),
            via_points: cands
                .iter()
                .map(|c| via_point(space, motion, c.t))
                .collect(),
        });
    }

    /// Adds the via points of the candidates kept (`pool`: borderline index, order, parameter,
    /// value) to node `id`, each written into `scratch` rather than a new vector.
    #[inline]
    fn push_vias(
        &mut self,
        id: NodeId,
        pool: &[(usize, usize, f64, f64)],
        lines: &Lines,
        scratch: &mut Config,
    ) {
        for &(k, _, t, _) in pool {
            let (motion, dodge_group) = &lines.as_slice()[k];
            // the via point (`via_point`)
            motion.write_at(t, scratch);
            self.space.normalize(scratch);
            let q = self.push_pt(scratch);
            if self.recording {
                self.b.vias_found.push(q);
            }
            self.b.nodes[id].vias.push(Via {
                q,
                group: *dodge_group,
                left: None,
                right: None,
            });
        }
    }

    /// The left (`cur → q`) or right (`q → z`) child of via point `i`.
    fn child(&mut self, id: NodeId, i: usize, left: bool) -> NodeId {
        let node = &self.b.nodes[id];
        let via = &node.vias[i];
        if let Some(c) = if left { via.left } else { via.right } {
            return c;
        }
        let walk = node.walk.as_ref().expect("children only of walked nodes");
        let blocked_group = walk.blocked.as_ref().map_or(0, |b| b.group);
        let (a, z, first) = if left {
            (walk.cur(node.a), via.q, via.group)
        } else {
            (via.q, node.z, blocked_group)
        };
        let c = self.new_node(a, z, first);
        let v = &mut self.b.nodes[id].vias[i];
        if left {
            v.left = Some(c);
        } else {
            v.right = Some(c);
        }
        c
    }

    fn depth_of(&self, id: NodeId) -> u32 {
        match self.b.nodes[id].status {
            Status::Solved { depth, .. } => depth,
            _ => 0,
        }
    }

    fn is_dead(&self, id: Option<NodeId>) -> bool {
        id.is_some_and(|c| self.b.nodes[c].status == Status::Dead)
    }

    /// Depth-first search with recursion limit `rec` (CHS Fig 1.3 with backtracking). Solved
    /// and failed subproblems are remembered in the tree.
    pub fn depth_first(&mut self, id: NodeId, rec: u32) -> Result<bool, OracleError> {
        if self.walk_refused(id) {
            return Ok(false);
        }
        self.ensure_walk(id)?;
        match self.b.nodes[id].status {
            Status::Solved { depth, .. } if depth <= rec => return Ok(true),
            Status::Dead => return Ok(false),
            Status::Open { failed_up_to } if rec as i64 <= failed_up_to => {
                self.limit_hit = true;
                return Ok(false);
            }
            _ => {}
        }
        if rec == 0 {
            self.limit_hit = true;
            self.b.nodes[id].status = Status::Open { failed_up_to: 0 };
            return Ok(false);
        }
        let mut i = 0;
        loop {
            if self.out_of_budget() {
                self.budget_hit = true;
                return Ok(false);
            }
            if i == self.b.nodes[id].vias.len() {
                if self.extend_vias(id)? {
                    continue;
                }
                break;
            }
            let (node_mark, pt_mark) = (self.b.nodes.len(), self.b.pts.len());
            let left = self.child(id, i, true);
            if self.depth_first(left, rec - 1)? {
                let right = self.child(id, i, false);
                if self.depth_first(right, rec - 1)? {
                    let depth = 1 + self.depth_of(left).max(self.depth_of(right));
                    self.b.nodes[id].status = Status::Solved {
                        depth,
                        via: Some(i),
                    };
                    return Ok(true);
                }
            }
            if self.forget_failures && !self.budget_hit {
                // the subtrees of via i, and the configurations only they use, were created
                // after the marks; nothing else refers to them
                self.truncate_nodes(node_mark);
                if !self.recording {
                    self.b.pts.truncate(pt_mark);
                }
                let v = &mut self.b.nodes[id].vias[i];
                v.left = None;
                v.right = None;
            }
            i += 1;
        }
        if self.budget_hit {
            return Ok(false);
        }
        // (with forgotten subtrees nothing is known dead, which only costs the early stop)
        let node = &self.b.nodes[id];
        let dead = node.rounds_exhausted
            && node
                .vias
                .iter()
                .all(|v| self.is_dead(v.left) || self.is_dead(v.right));
        self.b.nodes[id].status = if dead {
            Status::Dead
        } else {
            Status::Open {
                failed_up_to: rec as i64,
            }
        };
        Ok(false)
    }

    /// Breadth-first: makes sure every subproblem within `remaining` levels below `id` is
    /// walked, and every blocked one above the last level has all its via points and children.
    pub fn expand(&mut self, id: NodeId, remaining: u32) -> Result<(), OracleError> {
        if self.walk_refused(id) {
            return Ok(());
        }
        self.ensure_walk(id)?;
        if remaining == 0
            || matches!(
                self.b.nodes[id].status,
                Status::Solved { .. } | Status::Dead
            )
        {
            return Ok(());
        }
        while !self.out_of_budget() && self.extend_vias(id)? {}
        if self.out_of_budget() {
            self.budget_hit = true;
            return Ok(());
        }
        for i in 0..self.b.nodes[id].vias.len() {
            if self.out_of_budget() {
                self.budget_hit = true;
                return Ok(());
            }
            let left = self.child(id, i, true);
            self.expand(left, remaining - 1)?;
            let right = self.child(id, i, false);
            self.expand(right, remaining - 1)?;
        }
        Ok(())
    }

    /// Breadth-first: the length of the shortest path of depth `≤ bound` below `id`, choosing
    /// the via points that give it; `None` if there is none in the tree expanded so far.
    pub fn shortest(&mut self, id: NodeId, bound: u32) -> Option<(u32, f64)> {
        let walk = self.b.nodes[id].walk.as_ref()?;
        let prefix = walk.length;
        if walk.blocked.is_none() {
            return Some((0, prefix));
        }
        if bound == 0 {
            return None;
        }
        let mut best: Option<(usize, u32, f64)> = None;
        for i in 0..self.b.nodes[id].vias.len() {
            let (Some(l), Some(r)) = (
                self.b.nodes[id].vias[i].left,
                self.b.nodes[id].vias[i].right,
            ) else {
                continue;
            };
            let Some((dl, ll)) = self.shortest(l, bound - 1) else {
                continue;
            };
            let Some((dr, lr)) = self.shortest(r, bound - 1) else {
                continue;
            };
            let len = prefix + ll + lr;
            if best.is_none_or(|(_, _, b)| len < b) {
                best = Some((i, 1 + dl.max(dr), len));
            }
        }
        let (i, depth, len) = best?;
        self.b.nodes[id].status = Status::Solved {
            depth,
            via: Some(i),
        };
        Some((depth, len))
    }

    /// Breadth-first: whether `id` fails at any depth (all alternatives dead), marking it.
    pub fn mark_dead(&mut self, id: NodeId) -> bool {
        let node = &self.b.nodes[id];
        let Some(walk) = &node.walk else { return false };
        if walk.blocked.is_none() {
            return false;
        }
        if node.status == Status::Dead {
            return true;
        }
        if !node.rounds_exhausted {
            return false;
        }
        let pairs: Vec<(Option<NodeId>, Option<NodeId>)> =
            node.vias.iter().map(|v| (v.left, v.right)).collect();
        let mut dead = true;
        for (l, r) in pairs {
            let (Some(l), Some(r)) = (l, r) else {
                dead = false;
                continue;
            };
            let dl = self.mark_dead(l);
            let dr = self.mark_dead(r);
            dead &= dl || dr;
        }
        if dead {
            self.b.nodes[id].status = Status::Dead;
        }
        dead
    }

    /// Whether the node is known to fail at every depth.
    pub fn dead(&self, id: NodeId) -> bool {
        self.b.nodes[id].status == Status::Dead
    }

    /// Recursion depth of the solution found at `id`.
    pub fn solution_depth(&self, id: NodeId) -> u32 {
        self.depth_of(id)
    }

    /// Appends the corners of the solution below `id` (not its start) to `out`.
    pub fn append_path(&self, id: NodeId, out: &mut Vec<Config>) {
        let node = &self.b.nodes[id];
        let Some(walk) = &node.walk else { return };
        for c in walk.first_corner..walk.end {
            out.push(self.pt(c).to_vec());
        }
        if walk.reached_goal {
            out.push(self.pt(node.z).to_vec());
        }
        if let Status::Solved { via: Some(i), .. } = node.status {
            let v = &node.vias[i];
            if let (Some(l), Some(r)) = (v.left, v.right) {
                self.append_path(l, out);
                self.append_path(r, out);
            }
        }
    }

    /// What was learnt, with identical configurations merged (index 0 the start, 1 the goal):
    /// the certified free segments connected to the start or to the goal — the partial
    /// successes "a → q found while q → z failed" and their mirror images — and the via points
    /// among their ends. Fragments of failed branches that hang off neither end are left out:
    /// they would only add components of their own to a roadmap.
    pub fn discoveries(&mut self) -> Discoveries {
        let (a, z) = (self.pt(0), self.pt(1));
        let mut found = Discoveries::new(a, z);
        if !self.recording {
            return found;
        }
        let mut m = std::mem::take(&mut self.b.merge);
        m.clear();
        let (pts, dim) = (&self.b.pts[..], self.dim);
        // merge identical configurations first: the same corner may be reached by several
        // walks (ids in order of first appearance; the start is 0, the goal 1 unless it has
        // the start's very bits)
        m.configs.extend([0, 1]);
        canonical(&mut m.index, &mut m.configs, pts, dim, 0, Some(0));
        canonical(&mut m.index, &mut m.configs, pts, dim, 1, Some(1));
        for &(i, j) in &self.b.segments {
            let i = canonical(&mut m.index, &mut m.configs, pts, dim, i, None);
            let j = canonical(&mut m.index, &mut m.configs, pts, dim, j, None);
            m.segments.push((i, j));
        }
        for &v in &self.b.vias_found {
            let v = canonical(&mut m.index, &mut m.configs, pts, dim, v, None);
            m.vias.push(v);
        }
        // components of the segment graph (union–find)
        let n = m.configs.len();
        m.parent.extend(0..n as u32);
        fn find(p: &mut [u32], mut x: u32) -> u32 {
            while p[x as usize] != x {
                p[x as usize] = p[p[x as usize] as usize];
                x = p[x as usize];
            }
            x
        }
        for &(i, j) in &m.segments {
            let (ri, rj) = (find(&mut m.parent, i), find(&mut m.parent, j));
            m.parent[ri as usize] = rj;
        }
        let (ra, rz) = (find(&mut m.parent, 0), find(&mut m.parent, 1));
        // canonical id → index in `found` (NONE: not kept)
        const NONE: u32 = u32::MAX;
        m.new_index.resize(n, NONE);
        m.new_index[0] = 0;
        m.new_index[1] = 1;
        for &(i, j) in &m.segments {
            let r = find(&mut m.parent, i);
            let keep = r == ra || r == rz;
            if i == j || !keep || !m.seen.insert(((i.min(j) as u64) << 32) | i.max(j) as u64) {
                continue;
            }
            let mut map = |c: u32| {
                if m.new_index[c as usize] == NONE {
                    let p = m.configs[c as usize] as usize;
                    m.new_index[c as usize] = found.add(pts[p * dim..(p + 1) * dim].to_vec());
                }
                m.new_index[c as usize]
            };
            let (i, j) = (map(i), map(j));
            found.free_segments.push((i, j));
        }
        m.vias_seen.resize(found.configs.len(), false);
        for &v in &m.vias {
            let n = m.new_index[v as usize];
            if n != NONE && n > 1 && !m.vias_seen[n as usize] {
                m.vias_seen[n as usize] = true;
                found.via_points.push(n);
            }
        }
        self.b.merge = m;
        found
    }
}

/// Buffers of [`Search::discoveries`], kept between searches like the others.
#[derive(Default)]
pub(super) struct Merge {
    /// Hash of a configuration's bits → its canonical id (collisions probe onwards).
    index: FastMap<u64, u32>,
    /// Canonical id → arena index of its first appearance.
    configs: Vec<Pt>,
    segments: Vec<(u32, u32)>,
    vias: Vec<u32>,
    parent: Vec<u32>,
    new_index: Vec<u32>,
    seen: FastSet<u64>,
    vias_seen: Vec<bool>,
}

impl Merge {
    fn clear(&mut self) {
        self.index.clear();
        self.configs.clear();
        self.segments.clear();
        self.vias.clear();
        self.parent.clear();
        self.new_index.clear();
        self.seen.clear();
        self.vias_seen.clear();
    }
}

/// The canonical id of arena point `p`: the id of an earlier point with the same bits, or a
/// new one (`fixed`, or the next free id, recorded in `configs`).
fn canonical(
    index: &mut FastMap<u64, u32>,
    configs: &mut Vec<Pt>,
    pts: &[f64],
    dim: usize,
    p: Pt,
    fixed: Option<u32>,
) -> u32 {
    let at = |i: Pt| &pts[i as usize * dim..(i as usize + 1) * dim];
    let q = at(p);
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for x in q {
        h = (h ^ x.to_bits()).wrapping_mul(0x0000_0100_0000_01b3);
        h ^= h >> 29;
    }
    loop {
        match index.entry(h) {
            Entry::Occupied(o) => {
                let id = *o.get();
                let other = at(configs[id as usize]);
                if other.iter().zip(q).all(|(x, y)| x.to_bits() == y.to_bits()) {
                    return id;
                }
                // a different configuration with the same hash: probe on
                h = h.wrapping_add(0x9e37_79b9_7f4a_7c15);
            }
            Entry::Vacant(v) => {
                let id = fixed.unwrap_or_else(|| {
                    configs.push(p);
                    (configs.len() - 1) as u32
                });
                v.insert(id);
                return id;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::viapoint::borderline::base_parameter;

    /// A random source that fails the test when drawn from.
    struct Untouchable;
    impl RngCore for Untouchable {
        fn next_u32(&mut self) -> u32 {
            panic!("drew a random number")
        }
        fn next_u64(&mut self) -> u64 {
            panic!("drew a random number")
        }
        fn fill_bytes(&mut self, _: &mut [u8]) {
            panic!("drew a random number")
        }
    }

    #[test]
    fn strategies_said_not_to_draw_do_not_draw() {
        // the lazily seeded node streams skip hashing for these: if one of them drew,
        // the search would use a stream of the wrong seed
        let hits = IntervalList::from_unsorted(vec![
            Interval { lo: 0.1, hi: 0.2 },
            Interval { lo: 0.4, hi: 0.6 },
            Interval { lo: 0.8, hi: 0.9 },
        ]);
        let mut drawing = 0;
        for b in BasePoint::ALL {
            if draws_base(b) {
                drawing += 1;
                // and those said to draw really do
                let r = std::panic::catch_unwind(|| base_parameter(b, &hits, &mut Untouchable));
                assert!(r.is_err(), "{b:?} said to draw but did not");
            } else {
                base_parameter(b, &hits, &mut Untouchable);
            }
        }
        assert_eq!(drawing, 3);
    }
}
