//! Learning a roadmap: Overmars and Švestka's construction and expansion steps (OS94), with
//! the local method's discoveries fed back into the graph (CHS §1.6).
//!
//! **Construction** (OMPL's `growRoadmap`): sample free configurations uniformly; each new node
//! tries the local method towards its nearest nodes, skipping nodes in a component it has
//! already joined. **Expansion** (`expandRoadmap`): nodes are weighted by their failure ratio
//! `f / (n + 1)` (failed over all connection attempts), a node is drawn by weight and a
//! [random-bounce walk](super::bounce) leaves it; the walk's end becomes a node (joined to the
//! node it left by an edge that keeps the walk's corners, or with every corner a node, see
//! [`LearnParams::bounce_nodes`]) and tries to connect to its nearest nodes in other
//! components.
//!
//! **Feedback** (CHS §1.6: "the via points and direct connections it discovers correspond to
//! nodes and edges"): with [`LearnParams::feedback`] every certified free segment a connection
//! attempt found becomes an edge and its ends (via points, corners) nodes — also when the
//! attempt failed as a whole (a→q found while q→z failed). Identical configurations are one
//! node. Via points the search generated but never joined to anything by a free segment are
//! not kept: they would be isolated nodes that use up the node budget and connect nothing.
//! Feedback edges are kept even where they close a cycle: they came at no extra cost.
//!
//! **Parallel and reproducible.** Learning runs in rounds of [`LearnParams::round_size`]
//! candidates (or walks), fewer when the node budget lacks fewer nodes than that. Candidate `i` of round `r` draws from its own ChaCha stream derived
//! from `(seed, r, i)`; the freedom checks, neighbour searches and local-method calls of a
//! round run in parallel on the rayon pool against the roadmap as it was when the round began;
//! the results are then applied one after another in candidate order. Nothing depends on
//! which thread ran what, so the same seed gives the same roadmap — byte for byte once saved —
//! with any number of threads. A node budget is deterministic; a time budget is not.
//!
//! Departure from OS94/OMPL, forced by the rounds: a candidate does not see the connections
//! made by the candidates before it in the same round, so it may try two nodes that those
//! connections have just joined (its result is then kept only if feedback is on or cycle
//! edges are wanted). Construction and expansion are split by rounds, not by time.
//!
//! **Budgets** ([`Learner::learn_within`]): a time budget and the caller's
//! [`Deadline`] are checked before every oracle call of the local method, between sampling
//! attempts and between the steps of a walk, so learning stops within about one call of them;
//! the round is then applied as far as it got (interrupted attempts keep their certified free
//! segments and do not count as failures).
//!
//! **Joining a pair** ([`Learner::connect_pair`], OMPL's PRM `solve`): start and goal become
//! the first candidates, learning stops when they share a component, and expansion walks leave
//! only their two components, half from each.

use super::bounce::random_bounce;
use super::graph::{Edge, Roadmap};
use super::nn::NearestNeighbours;
use super::params::{Budget, LearnParams};
use super::persist::Header;
use crate::deadline::Deadline;
use crate::local::{
    direct_connection, direct_length, path_length, Connection, LocalMethod, Outcome,
};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::scene::Scene;
use crate::space::{Config, Group, Space};
use petgraph::unionfind::UnionFind;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::ops::ControlFlow;
use std::time::{Duration, Instant};

/// Why learning could not run.
#[derive(Debug, thiserror::Error)]
pub enum LearnError {
    /// Neither a node nor a time budget was given.
    #[error("learning needs a budget: a number of nodes, a time, or both")]
    NoBudget,
    /// A parameter out of range.
    #[error("invalid learning parameter: {0}")]
    Params(String),
    /// The oracle cannot answer a motion the learner or the local method asked about.
    #[error("collision oracle: {0}")]
    Oracle(#[from] OracleError),
    /// The local method reported configurations that cannot be stored (not finite numbers):
    /// a defect of the local method, reported rather than saved.
    #[error("the local method produced an unusable roadmap: {0}")]
    Malformed(String),
}

/// Which step a round ran.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Sampling new nodes and connecting them.
    Construction,
    /// Random-bounce walks from difficult nodes.
    Expansion,
}

/// Where learning stands after a round (for progress bars; the library prints nothing).
#[derive(Clone, Debug, PartialEq)]
pub struct Progress {
    /// Rounds finished.
    pub rounds: u64,
    /// The step the last round ran.
    pub phase: Phase,
    /// Nodes so far.
    pub nodes: usize,
    /// Edges so far.
    pub edges: usize,
    /// Connected components so far.
    pub components: usize,
    /// The node budget, if any.
    pub node_budget: Option<usize>,
    /// Wall-clock time since learning began.
    pub elapsed: Duration,
    /// Oracle work so far.
    pub counts: CallCounts,
}

/// Why learning stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The roadmap reached the node budget.
    NodeBudget,
    /// The time budget ran out (or the caller's [`Deadline`] passed).
    TimeBudget,
    /// The caller cancelled ([`Deadline::with_cancel`]: Ctrl-C).
    Cancelled,
    /// The two configurations of [`Learner::connect_pair`] are in one component.
    Connected,
    /// [`LearnParams::stall_rounds`] rounds in a row added no node.
    Stalled,
}

/// What learning did, beyond the roadmap (not stored in the file: it holds wall-clock time).
#[derive(Clone, Debug, PartialEq)]
pub struct LearnReport {
    /// Rounds run.
    pub rounds: u64,
    /// Of which construction rounds.
    pub construction_rounds: u64,
    /// Of which expansion rounds.
    pub expansion_rounds: u64,
    /// Local-method connection attempts.
    pub attempts: u64,
    /// Of which connected.
    pub connected: u64,
    /// Why it stopped.
    pub stop: StopReason,
    /// Wall-clock time.
    pub elapsed: Duration,
}

/// A learnt roadmap and the report of its learning.
#[derive(Clone, Debug)]
pub struct Learnt {
    /// The roadmap.
    pub roadmap: Roadmap,
    /// How learning went.
    pub report: LearnReport,
}

/// Valid parameters and at least one thing that ends learning: nodes, time or a deadline.
fn check_budget(
    params: &LearnParams,
    budget: &Budget,
    deadline: &Deadline,
) -> Result<(), LearnError> {
    params.validate().map_err(LearnError::Params)?;
    if budget.nodes.is_none() && budget.time.is_none() && !deadline.is_limited() {
        return Err(LearnError::NoBudget);
    }
    Ok(())
}

/// A roadmap grown to join two configurations ([`Learner::connect_pair`]).
#[derive(Clone, Debug)]
pub struct PairLearnt {
    /// The roadmap (the base roadmap's nodes and edges first, with their indices) and its
    /// report; [`LearnReport::stop`] is [`StopReason::Connected`] when the ends met.
    pub learnt: Learnt,
    /// The start's node.
    pub start: u32,
    /// The goal's node (the start's when they are the same configuration).
    pub goal: u32,
    /// Whether start and goal ended in one component.
    pub connected: bool,
}

/// What a roadmap grows from: a learnt roadmap and/or a pair of configurations to join.
#[derive(Clone, Copy, Default)]
struct Seeds<'r> {
    base: Option<&'r Roadmap>,
    pair: Option<(&'r [f64], &'r [f64])>,
}

/// Learns roadmaps of one scene with one local method.
pub struct Learner<'a> {
    space: &'a Space,
    oracle: &'a dyn CollisionOracle,
    local: &'a dyn LocalMethod,
    fingerprint: u64,
    attempt_cap: Option<Duration>,
}

/// Under a time budget, one connection attempt may use at most this share of it
/// ([`Learner::attempt_cap_for`]).
pub const ATTEMPT_SHARE: u32 = 200;

/// The least time an attempt is capped to.
pub const MIN_ATTEMPT: Duration = Duration::from_millis(50);

/// The weight every node of a focused component has beyond its failure ratio, so that walks
/// also leave components whose nodes have not failed yet.
const FOCUS_FLOOR: f64 = 0.05;

/// Separates the random streams of the two steps.
const SAMPLE_STREAM: u64 = 1;
const WALK_STREAM: u64 = 2;

/// The random stream of candidate `index` in round `round`: a ChaCha8 generator keyed by
/// `(seed, round, index, purpose)`, so that every candidate's draws are fixed whatever thread
/// runs it.
pub fn stream(seed: u64, round: u64, index: u64, purpose: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    key[8..16].copy_from_slice(&round.to_le_bytes());
    key[16..24].copy_from_slice(&index.to_le_bytes());
    key[24..].copy_from_slice(&purpose.to_le_bytes());
    ChaCha8Rng::from_seed(key)
}

/// A neighbour of a construction candidate: an existing node, or an earlier candidate of the
/// same round.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Target {
    Node(u32),
    Candidate(usize),
}

/// A connection attempt made in the parallel part of a round, applied later.
struct Attempt {
    target: Target,
    connection: Connection,
}

/// A walk made in the parallel part of an expansion round.
struct Walk {
    from: u32,
    corners: Vec<Config>,
    attempts: Vec<Attempt>,
}

/// The roadmap while it grows.
struct Work<'s> {
    space: &'s Space,
    groups: Vec<Group>,
    dim: usize,
    feedback: bool,
    cycle_edges: bool,
    coords: Vec<f64>,
    edges: Vec<Edge>,
    edge_set: HashSet<(u32, u32)>,
    by_bits: HashMap<Vec<u64>, u32>,
    uf: UnionFind<u32>,
    components: usize,
    /// Connection attempts and failures per node (OS94's failure ratio).
    tries: Vec<u32>,
    failures: Vec<u32>,
    nn: NearestNeighbours,
    counts: CallCounts,
    attempts: u64,
    connected: u64,
    /// The learning deadline passed during the round being applied.
    stopped: bool,
}

impl<'s> Work<'s> {
    fn node_count(&self) -> usize {
        self.coords.len() / self.dim
    }

    fn node(&self, i: u32) -> &[f64] {
        let s = i as usize * self.dim;
        &self.coords[s..s + self.dim]
    }

    fn nearest(&self, q: &[f64], k: usize, radius: Option<f64>) -> Vec<(u32, f64)> {
        self.nn.nearest(q, k, radius, |i| self.node(i))
    }

    /// The node at `q`, added if no node has exactly these coordinates (bit for bit: an SE(3)
    /// orientation and its antipode make two nodes, joined by whatever joins them).
    fn add_node(&mut self, q: &[f64]) -> u32 {
        let bits: Vec<u64> = q.iter().map(|v| v.to_bits()).collect();
        if let Some(&i) = self.by_bits.get(&bits) {
            return i;
        }
        let i = self.node_count() as u32;
        self.by_bits.insert(bits, i);
        self.coords.extend_from_slice(q);
        self.uf.new_set();
        self.components += 1;
        self.tries.push(0);
        self.failures.push(0);
        self.nn.insert(i, q);
        i
    }

    /// Copies a learnt roadmap's nodes (same indices) and edges, to grow it further. Failure
    /// counts start at zero: the file does not keep them.
    fn copy_roadmap(&mut self, base: &Roadmap) {
        for q in base.nodes() {
            self.add_node(q);
        }
        for e in base.edges() {
            if e.a != e.b && self.edge_set.insert((e.a.min(e.b), e.a.max(e.b))) {
                self.edges.push(e.clone());
                if self.uf.union(e.a, e.b) {
                    self.components -= 1;
                }
            }
        }
    }

    /// Adds the edge `a → corners → b` unless it is a loop or the pair is joined already.
    fn add_edge(&mut self, a: u32, b: u32, corners: &[Config]) {
        if a == b || !self.edge_set.insert((a.min(b), a.max(b))) {
            return;
        }
        debug_assert!(
            !corners.is_empty()
                || self
                    .groups
                    .iter()
                    .filter(|g| !self.space.same_in_group(self.node(a), self.node(b), g))
                    .count()
                    <= 1,
            "a single-segment edge must change one DOF group (LocalMethod contract)"
        );
        let length = if corners.is_empty() {
            direct_length(self.space, &self.groups, self.node(a), self.node(b))
        } else {
            let mut path = Vec::with_capacity(corners.len() + 2);
            path.push(self.node(a).to_vec());
            path.extend(corners.iter().cloned());
            path.push(self.node(b).to_vec());
            path_length(self.space, &self.groups, &path)
        };
        self.edges.push(Edge {
            a,
            b,
            length,
            corners: corners.iter().flatten().copied().collect(),
        });
        if self.uf.union(a, b) {
            self.components -= 1;
        }
    }

    /// Records an attempt from node `a` to node `z` and keeps what it found.
    fn apply(&mut self, a: u32, z: u32, c: &Connection) {
        self.counts += c.counts;
        self.attempts += 1;
        let ok = c.is_connected();
        self.connected += u64::from(ok);
        // an attempt the learning deadline stopped says nothing about how hard its ends are
        // (one its own time cap stopped failed like one that ran out of calls)
        if !(c.outcome == Outcome::Interrupted && self.stopped) {
            for n in [a, z] {
                self.tries[n as usize] += 1;
                self.failures[n as usize] += u32::from(!ok);
            }
        }
        if self.feedback {
            // a discovered configuration becomes a node when a certified free segment joins it
            // to something: via points the search made but never connected stay out
            let configs = &c.discoveries.configs;
            let mut ids: Vec<Option<u32>> = vec![None; configs.len()];
            if let Some(first) = ids.first_mut() {
                *first = Some(a);
            }
            if let Some(second) = ids.get_mut(1) {
                *second = Some(z);
            }
            for &(i, j) in &c.discoveries.free_segments {
                let (i, j) = (i as usize, j as usize);
                if i >= configs.len() || j >= configs.len() {
                    continue;
                }
                let x = *ids[i].get_or_insert_with(|| self.add_node(&configs[i]));
                let y = *ids[j].get_or_insert_with(|| self.add_node(&configs[j]));
                self.add_edge(x, y, &[]);
            }
            if ok && c.path.len() >= 2 {
                // the path itself, in case the method did not list all its segments
                let mut prev = a;
                for (k, q) in c.path.iter().enumerate().skip(1) {
                    let id = if k + 1 == c.path.len() {
                        z
                    } else {
                        self.add_node(q)
                    };
                    self.add_edge(prev, id, &[]);
                    prev = id;
                }
            }
        } else if ok && (self.cycle_edges || !self.uf.equiv(a, z)) {
            let interior = if c.path.len() >= 2 {
                &c.path[1..c.path.len() - 1]
            } else {
                &[]
            };
            self.add_edge(a, z, interior);
        }
    }
}

impl<'a> Learner<'a> {
    /// A learner for `space` (the scene's, with bounds), its oracle, the local method, and the
    /// scene's fingerprint to record.
    pub fn new(
        space: &'a Space,
        oracle: &'a dyn CollisionOracle,
        local: &'a dyn LocalMethod,
        fingerprint: u64,
    ) -> Self {
        Learner {
            space,
            oracle,
            local,
            fingerprint,
            attempt_cap: None,
        }
    }

    /// The same learner with every connection attempt limited to `cap` of wall-clock time
    /// (stopped like a call budget, and counted as a failure). A call budget counts the seed's
    /// cost measure, but what one call costs differs 1000-fold between a disc and a rotation
    /// among 37 000 triangles: under a time budget, a cap in time adapts to that cost (a
    /// roadmap of OMPL.app's Apartment spent one 30-s budget on 28 attempts). Not
    /// reproducible, like any time budget; `None` (the default) leaves attempts to their
    /// call budget.
    pub fn with_attempt_cap(mut self, cap: Option<Duration>) -> Self {
        self.attempt_cap = cap;
        self
    }

    /// The attempt cap for a time budget `time`: 1/[`ATTEMPT_SHARE`] of it, at least
    /// [`MIN_ATTEMPT`] (what `viaroad build --time`, `solve --roadmap` and growing queries use).
    pub fn attempt_cap_for(time: Duration) -> Duration {
        (time / ATTEMPT_SHARE).max(MIN_ATTEMPT)
    }

    /// A learner for `scene` with `oracle` (normally `scene.oracle()`) and `local`.
    pub fn for_scene(
        scene: &'a Scene,
        oracle: &'a dyn CollisionOracle,
        local: &'a dyn LocalMethod,
    ) -> Self {
        Self::new(&scene.space, oracle, local, scene.fingerprint())
    }

    /// Learns a roadmap within `budget`, reproducibly from `seed` (see the module docs).
    /// Runs on the current rayon pool; `progress` is called after every round.
    pub fn learn(
        &self,
        params: &LearnParams,
        budget: &Budget,
        seed: u64,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<Learnt, LearnError> {
        self.learn_within(params, budget, seed, &Deadline::none(), progress)
    }

    /// [`learn`](Self::learn), also stopped by `deadline` (a time limit or a cancel flag, for
    /// Ctrl-C). The deadline and the time budget are checked before every oracle call of the
    /// local method and between samples, not only between rounds, so learning returns within
    /// about one oracle call of either, with the roadmap learnt so far (interrupted attempts
    /// keep the free segments they certified).
    pub fn learn_within(
        &self,
        params: &LearnParams,
        budget: &Budget,
        seed: u64,
        deadline: &Deadline,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<Learnt, LearnError> {
        check_budget(params, budget, deadline)?;
        let (learnt, _) = self.grow(
            params,
            Seeds::default(),
            &[budget.nodes],
            budget.time,
            seed,
            deadline,
            progress,
            &mut |_| ControlFlow::Continue(()),
        )?;
        Ok(learnt)
    }

    /// Grows a roadmap until `start` and `goal` are in one component (OMPL's PRM `solve`):
    /// from `base` (a learnt roadmap, not changed: its nodes and edges are copied with their
    /// indices) or from nothing, with `start` and `goal` as its first new nodes, tried against
    /// each other and their nearest nodes, then construction and expansion rounds as in
    /// [`learn`](Self::learn) until they meet ([`StopReason::Connected`]) or the budget or
    /// `deadline` ends it. Expansion favours nodes whose attempts fail (OS94), so an end that
    /// cannot be attached soon becomes the start of random-bounce walks.
    ///
    /// `start` and `goal` must be free, in bounds and normalised (see
    /// [`crate::space::Space::normalize`]); the caller checks them.
    #[allow(clippy::too_many_arguments)]
    pub fn connect_pair(
        &self,
        params: &LearnParams,
        base: Option<&Roadmap>,
        (start, goal): (&[f64], &[f64]),
        budget: &Budget,
        seed: u64,
        deadline: &Deadline,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<PairLearnt, LearnError> {
        check_budget(params, budget, deadline)?;
        let seeds = Seeds {
            base,
            pair: Some((start, goal)),
        };
        let (learnt, pair) = self.grow(
            params,
            seeds,
            &[budget.nodes],
            budget.time,
            seed,
            deadline,
            progress,
            &mut |_| ControlFlow::Continue(()),
        )?;
        let (start, goal) = pair
            .ok_or_else(|| LearnError::Malformed("start or goal was not kept as a node".into()))?;
        Ok(PairLearnt {
            connected: learnt.report.stop == StopReason::Connected,
            learnt,
            start,
            goal,
        })
    }

    /// Learns in stages of growing node counts, for benchmarks that ask how many nodes (and how
    /// much time) a roadmap needs: learning runs until the roadmap has `stages[0]` nodes, hands
    /// a snapshot to `on_stage`, continues with the same graph, round numbering and random
    /// streams to `stages[1]`, and so on, until `on_stage` breaks, the last stage is reached,
    /// `time` runs out or learning stalls. `on_stage` sees every stage, the last one included;
    /// the last snapshot is returned.
    ///
    /// Stage `k`'s roadmap is a subgraph of stage `k + 1`'s (nodes and edges are only ever
    /// added, with the same indices). Rounds near a stage's target are clipped to the nodes
    /// still missing, as with a node budget, so a stage's roadmap is reproducible from `seed`
    /// and the stage list but is not the roadmap [`learn`](Self::learn) would give for the same
    /// node count. The time `on_stage` takes and the time to assemble the snapshots is not
    /// learning time: [`LearnReport::elapsed`], [`Progress::elapsed`] and the `time` budget
    /// count learning only.
    pub fn learn_in_stages(
        &self,
        params: &LearnParams,
        stages: &[usize],
        time: Option<Duration>,
        seed: u64,
        progress: &mut dyn FnMut(&Progress),
        on_stage: &mut dyn FnMut(&Learnt) -> ControlFlow<()>,
    ) -> Result<Learnt, LearnError> {
        if stages.is_empty() {
            return Err(LearnError::NoBudget);
        }
        if stages.windows(2).any(|w| w[0] >= w[1]) {
            return Err(LearnError::Params(format!(
                "stages must be strictly increasing node counts, got {stages:?}"
            )));
        }
        let stages: Vec<Option<usize>> = stages.iter().map(|&n| Some(n)).collect();
        let (learnt, _) = self.grow(
            params,
            Seeds::default(),
            &stages,
            time,
            seed,
            &Deadline::none(),
            progress,
            on_stage,
        )?;
        Ok(learnt)
    }

    /// The learning loop behind [`learn`](Self::learn) and
    /// [`learn_in_stages`](Self::learn_in_stages): one stage per node target (`None`: no node
    /// target, only `time`).
    #[allow(clippy::too_many_arguments)]
    fn grow(
        &self,
        params: &LearnParams,
        seeds: Seeds<'_>,
        stages: &[Option<usize>],
        time: Option<Duration>,
        seed: u64,
        deadline: &Deadline,
        progress: &mut dyn FnMut(&Progress),
        on_stage: &mut dyn FnMut(&Learnt) -> ControlFlow<()>,
    ) -> Result<(Learnt, Option<(u32, u32)>), LearnError> {
        params.validate().map_err(LearnError::Params)?;
        let Some(&first) = stages.first() else {
            return Err(LearnError::NoBudget);
        };
        let began = Instant::now();
        // time spent outside learning (snapshots, the caller's stage handler)
        let mut paused = Duration::ZERO;
        let learning = |paused: Duration| began.elapsed().saturating_sub(paused);
        let groups = self.local.groups(self.space);
        let mut work = Work {
            space: self.space,
            groups,
            dim: self.space.dim(),
            feedback: params.feedback,
            cycle_edges: params.cycle_edges,
            coords: Vec::new(),
            edges: Vec::new(),
            edge_set: HashSet::new(),
            by_bits: HashMap::new(),
            uf: UnionFind::new(0),
            components: 0,
            tries: Vec::new(),
            failures: Vec::new(),
            nn: NearestNeighbours::new(self.space),
            counts: CallCounts::default(),
            attempts: 0,
            connected: 0,
            stopped: false,
        };
        if let Some(base) = seeds.base {
            work.copy_roadmap(base);
        }
        // the pair's two ends are the first candidates: tried against each other and their
        // nearest nodes before any sampling
        let pair = match seeds.pair {
            Some((s, g)) => {
                let first = deadline.within(time);
                let ends = vec![s.to_vec(), g.to_vec()];
                let ids =
                    self.connect_candidates(&mut work, params, &Budget::default(), &first, ends)?;
                Some((ids[0], ids[1]))
            }
            None => None,
        };
        let joined = |work: &Work<'_>| pair.is_some_and(|(s, g)| work.uf.equiv(s, g));
        let (mut rounds, mut construction_rounds, mut expansion_rounds) = (0u64, 0u64, 0u64);
        let mut stalled = 0usize;
        // nodes the last round added per candidate: with feedback one connection attempt can
        // bring dozens of via points and corners, so a full round near the end of a budget
        // would compute many attempts only to throw them away
        let mut nodes_per_candidate = 1.0f64;
        let (mut stage, mut target) = (0, first);
        loop {
            let budget = Budget {
                nodes: target,
                time,
            };
            let stop = loop {
                if joined(&work) {
                    break StopReason::Connected;
                }
                if budget.nodes.is_some_and(|n| work.node_count() >= n) {
                    break StopReason::NodeBudget;
                }
                if deadline.cancelled() {
                    break StopReason::Cancelled;
                }
                // the time left, as a deadline the round checks before every oracle call
                let round_deadline =
                    deadline.within(time.map(|t| t.saturating_sub(learning(paused))));
                if round_deadline.expired() {
                    break StopReason::TimeBudget;
                }
                if stalled >= params.stall_rounds {
                    break StopReason::Stalled;
                }
                let before = work.node_count();
                // slow start (8, 16, 32, … candidates) and never more candidates than the nodes
                // still missing are expected to need, judged by the last round's yield; both
                // depend only on earlier results, so the schedule is the same with any thread
                // count
                let slow_start = 8usize.saturating_mul(1 << rounds.min(16));
                let size = budget.nodes.map_or(params.round_size, |n| {
                    let missing = n.saturating_sub(before) as f64;
                    ((missing / nodes_per_candidate).ceil() as usize).clamp(1, params.round_size)
                });
                let size = size.min(slow_start).max(1);
                let phase = if params.is_expansion_round(rounds) && before > 0 {
                    self.expansion_round(
                        &mut work,
                        params,
                        &budget,
                        &round_deadline,
                        pair,
                        (seed, rounds, size),
                    )?;
                    expansion_rounds += 1;
                    Phase::Expansion
                } else {
                    self.construction_round(
                        &mut work,
                        params,
                        &budget,
                        &round_deadline,
                        (seed, rounds, size),
                    )?;
                    construction_rounds += 1;
                    Phase::Construction
                };
                rounds += 1;
                nodes_per_candidate = ((work.node_count() - before) as f64 / size as f64).max(1.0);
                stalled = if work.node_count() > before {
                    0
                } else {
                    stalled + 1
                };
                progress(&Progress {
                    rounds,
                    phase,
                    nodes: work.node_count(),
                    edges: work.edges.len(),
                    components: work.components,
                    node_budget: budget.nodes,
                    elapsed: learning(paused),
                    counts: work.counts,
                });
            };
            let elapsed = learning(paused);
            let pause = Instant::now();
            let last = stage + 1 == stages.len() || stop != StopReason::NodeBudget;
            let header = Header {
                space: self.space.clone(),
                fingerprint: self.fingerprint,
                params: params.clone(),
                local_spec: self.local.spec(),
                seed,
                node_budget: budget.nodes.map(|n| n as u64),
                rounds,
                counts: work.counts,
            };
            let report = LearnReport {
                rounds,
                construction_rounds,
                expansion_rounds,
                attempts: work.attempts,
                connected: work.connected,
                stop,
                elapsed,
            };
            // the last stage hands over the graph; earlier ones copy it and go on growing
            let (coords, edges) = if last {
                (
                    std::mem::take(&mut work.coords),
                    std::mem::take(&mut work.edges),
                )
            } else {
                (work.coords.clone(), work.edges.clone())
            };
            let roadmap =
                Roadmap::assemble(header, coords, edges).map_err(LearnError::Malformed)?;
            let learnt = Learnt { roadmap, report };
            let flow = on_stage(&learnt);
            paused += pause.elapsed();
            if last || flow.is_break() {
                return Ok((learnt, pair));
            }
            stage += 1;
            target = stages[stage];
        }
    }

    /// Tries the local method from `q` towards `targets` (nearest first), skipping targets in a
    /// component `q` has joined in this attempt sequence unless cycle edges are wanted.
    /// `component` names a target's component as the round began.
    fn attempts(
        &self,
        q: &[f64],
        targets: &[(Target, &[f64])],
        mut joined: Vec<Target>,
        component: impl Fn(Target) -> Target,
        (cycle_edges, deep): (bool, Option<usize>),
        deadline: &Deadline,
    ) -> Result<Vec<Attempt>, OracleError> {
        let mut out = Vec::with_capacity(targets.len());
        let groups = deep.map(|_| self.local.groups(self.space));
        for &(target, tq) in targets {
            let comp = component(target);
            if !cycle_edges && joined.contains(&comp) {
                continue;
            }
            if deadline.expired() {
                break;
            }
            // cheap attempts beyond the nearest `deep` ones (LearnParams::deep_neighbours)
            let mut connection = match (&groups, deep) {
                (Some(groups), Some(d)) if out.len() >= d => {
                    direct_connection(self.space, self.oracle, groups, q, tq)?
                }
                _ => self.local.connect_within(
                    self.space,
                    self.oracle,
                    q,
                    tq,
                    &deadline.within(self.attempt_cap),
                )?,
            };
            connection.borderlines.clear();
            if connection.is_connected() {
                joined.push(comp);
            }
            out.push(Attempt { target, connection });
        }
        Ok(out)
    }

    fn construction_round(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        budget: &Budget,
        deadline: &Deadline,
        (seed, round, size): (u64, u64, usize),
    ) -> Result<(), LearnError> {
        let samples: Vec<(Result<Option<Config>, OracleError>, CallCounts)> = (0..size as u64)
            .into_par_iter()
            .map(|i| {
                let mut rng = stream(seed, round, i, SAMPLE_STREAM);
                let mut counts = CallCounts::default();
                // one attempt at a time, so that the deadline is checked between attempts (an
                // attempt of the obstacle-based samplers asks the oracle about motions)
                let mut q = Ok(None);
                for _ in 0..params.sample_attempts {
                    if deadline.expired() {
                        break;
                    }
                    q = params
                        .sampler
                        .sample(self.space, self.oracle, 1, &mut rng, &mut counts);
                    if !matches!(q, Ok(None)) {
                        break;
                    }
                }
                (q, counts)
            })
            .collect();
        let mut candidates = Vec::with_capacity(samples.len());
        for (q, counts) in samples {
            work.counts += counts;
            candidates.extend(q?);
        }
        self.connect_candidates(work, params, budget, deadline, candidates)?;
        Ok(())
    }

    /// Adds `candidates` (free configurations) as nodes, each tried against its nearest nodes
    /// and the candidates before it (in parallel, applied in order). Returns their node
    /// indices, as far as the node budget let them in.
    fn connect_candidates(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        budget: &Budget,
        deadline: &Deadline,
        candidates: Vec<Config>,
    ) -> Result<Vec<u32>, LearnError> {
        let shared: &Work<'_> = work;
        let plans: Vec<Result<Vec<Attempt>, OracleError>> = (0..candidates.len())
            .into_par_iter()
            .map(|i| {
                let q = &candidates[i];
                let mut near: Vec<(f64, Target)> = shared
                    .nearest(q, params.neighbours, params.radius)
                    .into_iter()
                    .map(|(n, d)| (d, Target::Node(n)))
                    .collect();
                for (j, c) in candidates[..i].iter().enumerate() {
                    let d = self.space.distance(q, c);
                    if params.radius.is_none_or(|r| d <= r) {
                        near.push((d, Target::Candidate(j)));
                    }
                }
                near.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                near.truncate(params.neighbours);
                let targets: Vec<(Target, &[f64])> = near
                    .iter()
                    .map(|&(_, t)| {
                        let tq = match t {
                            Target::Node(n) => shared.node(n),
                            Target::Candidate(j) => &candidates[j][..],
                        };
                        (t, tq)
                    })
                    .collect();
                let component = |t: Target| match t {
                    Target::Node(n) => Target::Node(shared.uf.find(n)),
                    c => c,
                };
                self.attempts(
                    q,
                    &targets,
                    Vec::new(),
                    component,
                    (params.cycle_edges, params.deep_neighbours),
                    deadline,
                )
            })
            .collect();
        work.stopped = deadline.expired();
        let mut ids: Vec<u32> = Vec::with_capacity(candidates.len());
        let mut stopped = false;
        for (i, plan) in plans.into_iter().enumerate() {
            if budget.nodes.is_some_and(|n| work.node_count() >= n) {
                stopped = true;
            }
            if stopped {
                // spent but not applied: still counted
                if let Ok(plan) = plan {
                    plan.iter().for_each(|a| work.counts += a.connection.counts);
                }
                continue;
            }
            let plan = plan?;
            let id = work.add_node(&candidates[i]);
            ids.push(id);
            for a in &plan {
                let target = match a.target {
                    Target::Node(n) => n,
                    Target::Candidate(j) => ids[j],
                };
                work.apply(id, target, &a.connection);
            }
        }
        Ok(ids)
    }

    fn expansion_round(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        budget: &Budget,
        deadline: &Deadline,
        focus: Option<(u32, u32)>,
        (seed, round, size): (u64, u64, usize),
    ) -> Result<(), LearnError> {
        // OS94's weights f / (n + 1), as cumulative sums for drawing by weight
        let ratio = |i: usize| f64::from(work.failures[i]) / (f64::from(work.tries[i]) + 1.0);
        let mut cumulative = Vec::with_capacity(work.node_count());
        let mut total = 0.0;
        match focus.map(|(s, g)| (work.uf.find(s), work.uf.find(g))) {
            // joining a pair: walks leave only the two components that must meet, half from
            // each, weighted by failure ratio within each (a small component boxed in by a
            // narrow passage gets as many walks as the rest of the roadmap)
            Some((cs, cg)) if cs != cg => {
                let side = |i: usize| {
                    let c = work.uf.find(i as u32);
                    (c == cs, c == cg)
                };
                let (mut sum_s, mut sum_g) = (0.0, 0.0);
                for i in 0..work.node_count() {
                    let w = ratio(i) + FOCUS_FLOOR;
                    match side(i) {
                        (true, _) => sum_s += w,
                        (_, true) => sum_g += w,
                        _ => {}
                    }
                }
                for i in 0..work.node_count() {
                    let w = ratio(i) + FOCUS_FLOOR;
                    total += match side(i) {
                        (true, _) => w / sum_s,
                        (_, true) => w / sum_g,
                        _ => 0.0,
                    };
                    cumulative.push(total);
                }
            }
            _ => {
                for i in 0..work.node_count() {
                    total += ratio(i);
                    cumulative.push(total);
                }
            }
        }
        let shared: &Work<'_> = work;
        let n_nodes = shared.node_count() as u32;
        let walks: Vec<(Result<Walk, OracleError>, CallCounts)> = (0..size as u64)
            .into_par_iter()
            .map(|i| {
                let mut rng = stream(seed, round, i, WALK_STREAM);
                let mut counts = CallCounts::default();
                let from = if total > 0.0 {
                    let u = rng.random::<f64>() * total;
                    (cumulative.partition_point(|&c| c <= u) as u32).min(n_nodes - 1)
                } else {
                    rng.random_range(0..n_nodes)
                };
                let walk = (|| {
                    if deadline.expired() {
                        return Ok(Walk {
                            from,
                            corners: Vec::new(),
                            attempts: Vec::new(),
                        });
                    }
                    let corners = random_bounce(
                        self.space,
                        self.oracle,
                        &shared.groups,
                        shared.node(from),
                        params.bounce_steps,
                        &mut rng,
                        &mut counts,
                        deadline,
                    )?;
                    let attempts = match corners.last() {
                        None => Vec::new(),
                        Some(end) => {
                            let near = shared.nearest(end, params.neighbours, params.radius);
                            let targets: Vec<(Target, &[f64])> = near
                                .iter()
                                .map(|&(n, _)| (Target::Node(n), shared.node(n)))
                                .collect();
                            let component = |t: Target| match t {
                                Target::Node(n) => Target::Node(shared.uf.find(n)),
                                c => c,
                            };
                            let joined = vec![Target::Node(shared.uf.find(from))];
                            self.attempts(
                                end,
                                &targets,
                                joined,
                                component,
                                (params.cycle_edges, params.deep_neighbours),
                                deadline,
                            )?
                        }
                    };
                    Ok(Walk {
                        from,
                        corners,
                        attempts,
                    })
                })();
                (walk, counts)
            })
            .collect();
        work.stopped = deadline.expired();
        let mut stopped = false;
        for (walk, counts) in walks {
            work.counts += counts;
            if budget.nodes.is_some_and(|n| work.node_count() >= n) {
                stopped = true;
            }
            if stopped {
                if let Ok(walk) = walk {
                    walk.attempts
                        .iter()
                        .for_each(|a| work.counts += a.connection.counts);
                }
                continue;
            }
            let walk = walk?;
            work.tries[walk.from as usize] += 1;
            let Some(last) = walk.corners.last() else {
                continue;
            };
            let end = if params.bounce_nodes {
                let mut prev = walk.from;
                for q in &walk.corners {
                    let id = work.add_node(q);
                    work.add_edge(prev, id, &[]);
                    prev = id;
                }
                prev
            } else {
                let end = work.add_node(last);
                work.add_edge(walk.from, end, &walk.corners[..walk.corners.len() - 1]);
                end
            };
            for a in &walk.attempts {
                // walks only target nodes that existed when the round began
                if let Target::Node(target) = a.target {
                    work.apply(end, target, &a.connection);
                }
            }
        }
        Ok(())
    }
}
