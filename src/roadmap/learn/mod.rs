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

//! | file | idea |
//! |---|---|
//! | `outcome` | what learning reports: errors, progress, stop reason, the learnt roadmap |
//! | `streams` | the per-candidate random streams that make rounds reproducible |
//! | `work` | the roadmap while it grows |
//! | `feedback` | applying an attempt, discoveries fed back (CHS §1.6) |
//! | `attempts` | connection attempts towards neighbours |
//! | `construction` | construction rounds (`growRoadmap`) |
//! | `expansion` | expansion rounds: random-bounce walks (`expandRoadmap`) |
//! | `grow` | the loop: stages, rounds, snapshots |
//! | `merge` | roadmaps learnt apart joined: union, then connections across parts |

mod attempts;
mod construction;
mod expansion;
mod feedback;
mod grow;
mod keep;
mod merge;
mod outcome;
mod seeds;
mod streams;
mod work;

pub use merge::{MergeError, MergeProgress, MergeReport, MergeStop, Merged};
pub use outcome::{LearnError, LearnReport, Learnt, PairLearnt, Phase, Progress, StopReason};
pub use streams::stream;

use super::graph::Roadmap;
use super::params::{Budget, LearnParams};
use super::shard::Shard;
use crate::deadline::Deadline;
use crate::local::LocalMethod;
use crate::oracle::CollisionOracle;
use crate::scene::Scene;
use crate::space::Space;
use seeds::Seeds;
use std::ops::ControlFlow;
use std::time::Duration;

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
        let (learnt, _) =
            self.grow_within(params, Seeds::default(), budget, seed, deadline, progress)?;
        Ok(learnt)
    }

    /// Grows a roadmap until `start` and `goal` are in one component (OMPL's PRM `solve`):
    /// from `base` (a learnt roadmap, not changed: its nodes and edges are copied with their
    /// indices) or from nothing, with `start` and `goal` as its first new nodes, tried against
    /// each other and their nearest nodes, then construction and expansion rounds as in
    /// [`learn`](Self::learn) until they meet ([`StopReason::Connected`]) or the budget or
    /// `deadline` ends it. Expansion favours nodes whose attempts fail (OS94), so an end that
    /// cannot be attached soon becomes the start of random-bounce walks; a share of the walks
    /// are directed instead, pushing the two ends' components out towards uniform samples
    /// ([`LearnParams::directed_share`]).
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
        let seeds = Seeds {
            base,
            pair: Some((start, goal)),
        };
        let (learnt, pair) = self.grow_within(params, seeds, budget, seed, deadline, progress)?;
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
        self.learn_in_stages_from(None, params, stages, time, seed, progress, on_stage)
    }

    /// [`learn_in_stages`](Self::learn_in_stages) starting from `base` (copied with its
    /// indices, as in [`learn_from`](Self::learn_from)) when one is given: `bench local
    /// --seed-from cones` grows the seed roadmap of Brooks's freeways in stages.
    /// The stages count the copied nodes; a stage not above the base's node count is reached
    /// at once, without a round.
    #[allow(clippy::too_many_arguments)]
    pub fn learn_in_stages_from(
        &self,
        base: Option<&Roadmap>,
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
            Seeds { base, pair: None },
            &stages,
            time,
            seed,
            &Deadline::none(),
            progress,
            on_stage,
        )?;
        Ok(learnt)
    }
}

impl Learner<'_> {
    /// [`learn_within`](Self::learn_within) starting from `base` instead of nothing: its nodes
    /// and edges are copied with their indices and learning continues until the budget (which
    /// counts the copied nodes too). For roadmaps seeded by a global method (the
    /// spine points of Brooks's freeways, `build --seed-from cones`).
    pub fn learn_from(
        &self,
        base: &Roadmap,
        params: &LearnParams,
        budget: &Budget,
        seed: u64,
        deadline: &Deadline,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<Learnt, LearnError> {
        let seeds = Seeds {
            base: Some(base),
            pair: None,
        };
        let (learnt, _) = self.grow_within(params, seeds, budget, seed, deadline, progress)?;
        Ok(learnt)
    }

    /// Learns shard `shard` of a roadmap whose shards share `seed` and `budget`
    /// ([`super::shard`]): [`learn_within`](Self::learn_within) with the shard's seed
    /// ([`Shard::seed`]) and its part of the node budget ([`Shard::nodes`]); a time budget is
    /// the shard's own. The roadmap records the shard's seed.
    pub fn learn_shard(
        &self,
        params: &LearnParams,
        budget: &Budget,
        (seed, shard): (u64, Shard),
        deadline: &Deadline,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<Learnt, LearnError> {
        let budget = Budget {
            nodes: budget.nodes.map(|n| shard.nodes(n)),
            time: budget.time,
        };
        self.learn_within(params, &budget, shard.seed(seed), deadline, progress)
    }

    /// The one-stage grow behind [`learn_within`](Self::learn_within),
    /// [`connect_pair`](Self::connect_pair) and [`learn_from`](Self::learn_from): the budget
    /// checked, one stage to its node budget, no stage handler.
    fn grow_within(
        &self,
        params: &LearnParams,
        seeds: Seeds<'_>,
        budget: &Budget,
        seed: u64,
        deadline: &Deadline,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<(Learnt, Option<(u32, u32)>), LearnError> {
        check_budget(params, budget, deadline)?;
        self.grow(
            params,
            seeds,
            &[budget.nodes],
            budget.time,
            seed,
            deadline,
            progress,
            &mut |_| ControlFlow::Continue(()),
        )
    }
}
