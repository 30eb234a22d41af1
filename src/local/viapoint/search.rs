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

use super::borderline::{base_parameter, borderlines, candidates, free_sections, Crossing};
use super::options::{ViaLimit, ViaPointOptions};
use crate::interval::IntervalList;
use crate::local::{Borderline, Discoveries};
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::space::{Config, Group, Motion, Space};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::{HashMap, HashSet};

pub(super) type NodeId = usize;

/// The first blocked piece of a node's direct path.
struct Blocked {
    motion: Motion,
    group: usize,
    collisions: IntervalList,
}

/// The direct path of a node, walked as far as it is free.
struct Walk {
    /// Corners reached after the node's start (the last is `cur`).
    corners: Vec<Config>,
    cur: Config,
    cur_idx: u32,
    /// Length of the free part.
    length: f64,
    blocked: Option<Blocked>,
}

struct Via {
    q: Config,
    q_idx: u32,
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
    a: Config,
    z: Config,
    a_idx: u32,
    z_idx: u32,
    first_group: usize,
    walk: Option<Walk>,
    base: Option<Config>,
    vias: Vec<Via>,
    rounds: u32,
    rounds_exhausted: bool,
    status: Status,
}

/// One connection attempt's search state.
pub(super) struct Search<'a> {
    space: &'a Space,
    oracle: &'a dyn CollisionOracle,
    options: &'a ViaPointOptions,
    groups: &'a [Group],
    nodes: Vec<Node>,
    /// Oracle work so far.
    pub counts: CallCounts,
    /// What was learnt (configurations deduplicated by their exact coordinates).
    pub found: Discoveries,
    config_index: HashMap<Vec<u64>, u32>,
    segment_seen: HashSet<(u32, u32)>,
    via_seen: HashSet<u32>,
    /// Borderlines asked about (when tracing).
    pub borderlines: Vec<Borderline>,
    /// Keep what was learnt (off for benchmarks: it grows with the number of calls).
    recording: bool,
    /// Plain recursion: drop the subtrees of failed via points, as the seed's recursion does,
    /// so memory stays proportional to the depth rather than to the number of calls.
    forget_failures: bool,
    /// Some branch was cut off by the recursion limit (in the current pass).
    pub limit_hit: bool,
    /// The call budget ran out.
    pub budget_hit: bool,
}

impl<'a> Search<'a> {
    pub fn new(
        space: &'a Space,
        oracle: &'a dyn CollisionOracle,
        options: &'a ViaPointOptions,
        groups: &'a [Group],
        a: &[f64],
        z: &[f64],
        forget_failures: bool,
    ) -> Self {
        let mut s = Search {
            space,
            oracle,
            options,
            groups,
            nodes: Vec::new(),
            counts: CallCounts::default(),
            found: Discoveries::new(a, z),
            config_index: HashMap::new(),
            segment_seen: HashSet::new(),
            via_seen: HashSet::new(),
            borderlines: Vec::new(),
            limit_hit: false,
            budget_hit: false,
            recording: options.discoveries,
            forget_failures,
        };
        s.config_index.insert(key(a), 0);
        s.config_index.entry(key(z)).or_insert(1);
        s
    }

    /// Forgets the tree (plain recursion re-computes everything for the next limit) but keeps
    /// the counts and discoveries. Returns the new root.
    pub fn new_root(&mut self) -> NodeId {
        self.nodes.clear();
        let (a, z) = (self.found.configs[0].clone(), self.found.configs[1].clone());
        self.new_node(a, z, 0, 1, 0)
    }

    fn new_node(
        &mut self,
        a: Config,
        z: Config,
        a_idx: u32,
        z_idx: u32,
        first_group: usize,
    ) -> NodeId {
        self.nodes.push(Node {
            a,
            z,
            a_idx,
            z_idx,
            first_group,
            walk: None,
            base: None,
            vias: Vec::new(),
            rounds: 0,
            rounds_exhausted: false,
            status: Status::Open { failed_up_to: -1 },
        });
        self.nodes.len() - 1
    }

    fn record(&mut self, q: &[f64]) -> u32 {
        if !self.recording {
            return u32::MAX;
        }
        if let Some(&i) = self.config_index.get(&key(q)) {
            return i;
        }
        let i = self.found.add(q.to_vec());
        self.config_index.insert(key(q), i);
        i
    }

    fn record_segment(&mut self, i: u32, j: u32) {
        if self.recording && i != j && self.segment_seen.insert((i.min(j), i.max(j))) {
            self.found.free_segments.push((i, j));
        }
    }

    fn out_of_budget(&self) -> bool {
        self.options
            .max_calls
            .is_some_and(|m| self.counts.intersect_calls() >= m)
    }

    /// Walks the node's direct path (one intersectSegment per group it changes).
    fn ensure_walk(&mut self, id: NodeId) -> Result<(), OracleError> {
        if self.nodes[id].walk.is_some() {
            return Ok(());
        }
        let (space, groups) = (self.space, self.groups);
        let z = self.nodes[id].z.clone();
        let z_idx = self.nodes[id].z_idx;
        let first = self.nodes[id].first_group;
        let mut cur = self.nodes[id].a.clone();
        let mut cur_idx = self.nodes[id].a_idx;
        let mut corners = Vec::new();
        let mut length = 0.0;
        let mut blocked = None;
        for k in 0..groups.len() {
            let gi = (first + k) % groups.len();
            let g = &groups[gi];
            if space.same_in_group(&cur, &z, g) {
                continue;
            }
            let motion = space.group_motion(&cur, &z, g);
            let collisions = self.oracle.intersect(&motion, &mut self.counts)?;
            if !collisions.is_empty() {
                blocked = Some(Blocked {
                    motion,
                    group: gi,
                    collisions,
                });
                break;
            }
            let next = space.with_group_of(&cur, &z, g);
            let at_goal = groups.iter().all(|h| space.same_in_group(&next, &z, h));
            let idx = if at_goal { z_idx } else { self.record(&next) };
            self.record_segment(cur_idx, idx);
            length += space.motion_length(&motion, 0.0, 1.0);
            corners.push(next.clone());
            cur = next;
            cur_idx = idx;
        }
        if blocked.is_none() {
            self.nodes[id].status = Status::Solved {
                depth: 0,
                via: None,
            };
        }
        self.nodes[id].walk = Some(Walk {
            corners,
            cur,
            cur_idx,
            length,
            blocked,
        });
        Ok(())
    }

    /// A random stream of its own for each node and round, so that random choices do not depend
    /// on the order in which the search meets the node.
    fn node_rng(&self, id: NodeId, round: u32) -> ChaCha8Rng {
        let n = &self.nodes[id];
        let mut h = 0xcbf2_9ce4_8422_2325u64 ^ self.options.seed;
        for v in
            n.a.iter()
                .chain(&n.z)
                .map(|x| x.to_bits())
                .chain([n.first_group as u64, round as u64])
        {
            h = (h ^ v).wrapping_mul(0x0000_0100_0000_01b3);
            h ^= h >> 29;
        }
        ChaCha8Rng::seed_from_u64(h)
    }

    /// Computes the via points of the next round of borderlines. `false` when there are no more
    /// rounds.
    fn extend_vias(&mut self, id: NodeId) -> Result<bool, OracleError> {
        if self.nodes[id].rounds_exhausted {
            return Ok(false);
        }
        let round = self.nodes[id].rounds;
        let mut rng = self.node_rng(id, round);
        let Some(blocked) = self.nodes[id]
            .walk
            .as_ref()
            .and_then(|w| w.blocked.as_ref())
        else {
            return Ok(false);
        };
        let (blocked_motion, blocked_group) = (blocked.motion.clone(), blocked.group);
        let base = match &self.nodes[id].base {
            Some(b) => b.clone(),
            None => {
                let t = base_parameter(self.options.base_point, &blocked.collisions, &mut rng);
                let mut b = blocked_motion.at(t);
                self.space.normalize(&mut b);
                self.nodes[id].base = Some(b.clone());
                b
            }
        };
        let crossing = Crossing {
            motion: &blocked_motion,
            group: blocked_group,
            base: &base,
        };
        let lines = borderlines(
            self.space,
            self.groups,
            self.options,
            &crossing,
            round,
            &mut rng,
        );
        if lines.is_empty() {
            self.nodes[id].rounds_exhausted = true;
            return Ok(false);
        }
        let mut pool = Vec::new();
        for (motion, group) in lines {
            if self.out_of_budget() {
                self.budget_hit = true;
                break;
            }
            let collisions = self.oracle.intersect(&motion, &mut self.counts)?;
            let sections = free_sections(&motion, &collisions);
            let cands = candidates(self.space, &motion, &sections, &base, self.options.beta);
            if self.options.trace {
                let blocked = self.nodes[id]
                    .walk
                    .as_ref()
                    .and_then(|w| w.blocked.as_ref());
                self.borderlines.push(Borderline {
                    blocked: blocked_motion.clone(),
                    collisions: blocked.map(|b| b.collisions.clone()).unwrap_or_default(),
                    base: base.clone(),
                    motion: motion.clone(),
                    free: IntervalList::from_unsorted(sections),
                    via_points: cands.iter().map(|c| c.q.clone()).collect(),
                });
            }
            pool.extend(cands.into_iter().map(|c| (c, group)));
        }
        // best first; ties keep the order of the borderlines and sections
        pool.sort_by(|a, b| a.0.value.total_cmp(&b.0.value));
        if let ViaLimit::Best(k) = self.options.via {
            pool.truncate(k);
        }
        for (c, group) in pool {
            let q_idx = self.record(&c.q);
            if self.recording && self.via_seen.insert(q_idx) {
                self.found.via_points.push(q_idx);
            }
            self.nodes[id].vias.push(Via {
                q: c.q,
                q_idx,
                group,
                left: None,
                right: None,
            });
        }
        self.nodes[id].rounds += 1;
        Ok(true)
    }

    /// The left (`cur → q`) or right (`q → z`) child of via point `i`.
    fn child(&mut self, id: NodeId, i: usize, left: bool) -> NodeId {
        let existing = if left {
            self.nodes[id].vias[i].left
        } else {
            self.nodes[id].vias[i].right
        };
        if let Some(c) = existing {
            return c;
        }
        let node = &self.nodes[id];
        let walk = node.walk.as_ref().expect("children only of walked nodes");
        let blocked_group = walk.blocked.as_ref().map_or(0, |b| b.group);
        let via = &node.vias[i];
        let (a, z, a_idx, z_idx, first) = if left {
            (
                walk.cur.clone(),
                via.q.clone(),
                walk.cur_idx,
                via.q_idx,
                via.group,
            )
        } else {
            (
                via.q.clone(),
                node.z.clone(),
                via.q_idx,
                node.z_idx,
                blocked_group,
            )
        };
        let c = self.new_node(a, z, a_idx, z_idx, first);
        if left {
            self.nodes[id].vias[i].left = Some(c);
        } else {
            self.nodes[id].vias[i].right = Some(c);
        }
        c
    }

    fn depth_of(&self, id: NodeId) -> u32 {
        match self.nodes[id].status {
            Status::Solved { depth, .. } => depth,
            _ => 0,
        }
    }

    fn is_dead(&self, id: Option<NodeId>) -> bool {
        id.is_some_and(|c| self.nodes[c].status == Status::Dead)
    }

    /// Depth-first search with recursion limit `rec` (CHS Fig 1.3 with backtracking). Solved
    /// and failed subproblems are remembered in the tree.
    pub fn depth_first(&mut self, id: NodeId, rec: u32) -> Result<bool, OracleError> {
        self.ensure_walk(id)?;
        match self.nodes[id].status {
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
            self.nodes[id].status = Status::Open { failed_up_to: 0 };
            return Ok(false);
        }
        let mut i = 0;
        loop {
            if self.out_of_budget() {
                self.budget_hit = true;
                return Ok(false);
            }
            if i == self.nodes[id].vias.len() {
                if self.extend_vias(id)? {
                    continue;
                }
                break;
            }
            let mark = self.nodes.len();
            let left = self.child(id, i, true);
            if self.depth_first(left, rec - 1)? {
                let right = self.child(id, i, false);
                if self.depth_first(right, rec - 1)? {
                    let depth = 1 + self.depth_of(left).max(self.depth_of(right));
                    self.nodes[id].status = Status::Solved {
                        depth,
                        via: Some(i),
                    };
                    return Ok(true);
                }
            }
            if self.forget_failures && !self.budget_hit {
                // the subtrees of via i were created after `mark`; nothing else refers to them
                self.nodes.truncate(mark);
                let v = &mut self.nodes[id].vias[i];
                v.left = None;
                v.right = None;
            }
            i += 1;
        }
        if self.budget_hit {
            return Ok(false);
        }
        let node = &self.nodes[id];
        // (with forgotten subtrees nothing is known dead, which only costs the early stop)
        let dead = node.rounds_exhausted
            && node
                .vias
                .iter()
                .all(|v| self.is_dead(v.left) || self.is_dead(v.right));
        self.nodes[id].status = if dead {
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
        self.ensure_walk(id)?;
        if remaining == 0 || matches!(self.nodes[id].status, Status::Solved { .. } | Status::Dead) {
            return Ok(());
        }
        while !self.out_of_budget() && self.extend_vias(id)? {}
        for i in 0..self.nodes[id].vias.len() {
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
        let walk = self.nodes[id].walk.as_ref()?;
        let prefix = walk.length;
        if walk.blocked.is_none() {
            return Some((0, prefix));
        }
        if bound == 0 {
            return None;
        }
        let mut best: Option<(usize, u32, f64)> = None;
        for i in 0..self.nodes[id].vias.len() {
            let (Some(l), Some(r)) = (self.nodes[id].vias[i].left, self.nodes[id].vias[i].right)
            else {
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
        self.nodes[id].status = Status::Solved {
            depth,
            via: Some(i),
        };
        Some((depth, len))
    }

    /// Breadth-first: whether `id` fails at any depth (all alternatives dead), marking it.
    pub fn mark_dead(&mut self, id: NodeId) -> bool {
        let node = &self.nodes[id];
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
            self.nodes[id].status = Status::Dead;
        }
        dead
    }

    /// Whether the node is known to fail at every depth.
    pub fn dead(&self, id: NodeId) -> bool {
        self.nodes[id].status == Status::Dead
    }

    /// Recursion depth of the solution found at `id`.
    pub fn solution_depth(&self, id: NodeId) -> u32 {
        self.depth_of(id)
    }

    /// Appends the corners of the solution below `id` (not its start) to `out`.
    pub fn append_path(&self, id: NodeId, out: &mut Vec<Config>) {
        let node = &self.nodes[id];
        let Some(walk) = &node.walk else { return };
        out.extend(walk.corners.iter().cloned());
        if let Status::Solved { via: Some(i), .. } = node.status {
            let v = &node.vias[i];
            if let (Some(l), Some(r)) = (v.left, v.right) {
                self.append_path(l, out);
                self.append_path(r, out);
            }
        }
    }
}

fn key(q: &[f64]) -> Vec<u64> {
    q.iter().map(|x| x.to_bits()).collect()
}
