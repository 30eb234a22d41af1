//! Merging roadmaps of one scene learnt apart ([shards](crate::roadmap::shard), roadmaps of
//! other machines, a deployed roadmap and parts learnt later): the union of their nodes and
//! certified edges, then the learner's own connection step across parts.
//!
//! **Union.** Parts are copied one after another into one growing roadmap. The first (the
//! *base*) keeps its node indices; a node of a later part gets the index of an identical node
//! already there (bit for bit, as in learning) or the next free one, and its edges follow it.
//! Edges are kept as they are: each was certified when its part was learnt, for the same scene
//! (fingerprint), space and local method, which the merge checks first.
//!
//! **Connection across parts.** Every node of every part is a candidate, in index order, and
//! tries the local method towards its nearest nodes that came from another part and lie in
//! another component, nearest first, skipping components it has joined (OS94's construction
//! step, with the parts' own [`LearnParams`]: neighbours, radius, deep neighbours, feedback).
//! What an attempt discovers is fed back as in learning (CHS §1.6). Candidates run in rounds
//! of growing size (8, 16, … up to the round size) — a round takes the next candidates that
//! have a target at all — planned in parallel against the roadmap as the round began and
//! applied in candidate order, so the result does not depend on the thread count. Once two parts' big components are joined, their other nodes find no target
//! in another component and cost one nearest-neighbour search each: a merge's oracle work is
//! spent where the parts' components meet, not on re-learning the parts.
//!
//! **Order.** Parts other than the base are merged in the order of their content digest
//! ([`Roadmap::digest`]); without a base, the part with the least digest is the base. The
//! same parts give the same merged roadmap, byte for byte, whatever order they are given in;
//! a merge of merges is a roadmap like any other, so reduction trees work.
//!
//! **Budgets.** The deadline (a time budget, Ctrl-C) is checked before every oracle call; a
//! merge it stops keeps the union and every connection made so far.

use super::super::graph::Roadmap;
use super::super::header::Header;
use super::super::params::LearnParams;
use super::attempts::{Attempt, Target};
use super::work::Work;
use super::Learner;
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, OracleError};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Why roadmaps cannot be merged. Parts are numbered from 0 in the order given.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// Nothing to merge.
    #[error("nothing to merge: give at least one roadmap")]
    NoParts,
    /// A part was learnt for another scene.
    #[error(
        "part {part} was learnt for another scene: its fingerprint is {found:016x}, \
         the scene's is {expected:016x}"
    )]
    ForeignScene {
        /// The part.
        part: usize,
        /// The scene's fingerprint.
        expected: u64,
        /// The part's.
        found: u64,
    },
    /// A part's configuration space (kind or bounds) is not the scene's.
    #[error("part {part} has another configuration space than the scene")]
    OtherSpace {
        /// The part.
        part: usize,
    },
    /// A part was learnt with another local method: its edges would not be the paths queries
    /// rebuild them as.
    #[error(
        "part {part} was learnt with local method `{found}`, the merge uses `{expected}`: \
         parts must share their local method"
    )]
    OtherLocalMethod {
        /// The part.
        part: usize,
        /// The merge's local method.
        expected: String,
        /// The part's.
        found: String,
    },
    /// The oracle cannot answer a motion the local method asked about.
    #[error("collision oracle: {0}")]
    Oracle(#[from] OracleError),
    /// The merged roadmap does not fit together (a defect, reported rather than saved).
    #[error("the merged roadmap is malformed: {0}")]
    Malformed(String),
}

/// Why a merge's connection step ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MergeStop {
    /// Every candidate was tried.
    Complete,
    /// The deadline's time ran out.
    TimeBudget,
    /// The caller cancelled.
    Cancelled,
}

/// Where a merge stands after a round (for progress bars).
#[derive(Clone, Debug, PartialEq)]
pub struct MergeProgress {
    /// Candidates tried so far.
    pub tried: usize,
    /// Candidates in all.
    pub candidates: usize,
    /// Nodes so far.
    pub nodes: usize,
    /// Components so far.
    pub components: usize,
    /// Time since the merge began.
    pub elapsed: Duration,
}

/// What a merge did, beyond the roadmap.
#[derive(Clone, Debug, PartialEq)]
pub struct MergeReport {
    /// Parts merged (the base included).
    pub parts: usize,
    /// Nodes of the parts together, before identical nodes were made one.
    pub part_nodes: usize,
    /// Components of the union before the connection step.
    pub union_components: usize,
    /// Rounds of the connection step.
    pub rounds: u64,
    /// Local-method connection attempts across parts.
    pub attempts: u64,
    /// Of which connected.
    pub connected: u64,
    /// Oracle work of the merge alone (the merged header adds the parts' work).
    pub counts: CallCounts,
    /// Why the connection step ended.
    pub stop: MergeStop,
    /// Wall-clock time of the merge.
    pub elapsed: Duration,
}

/// A merged roadmap and what the merge did.
#[derive(Clone, Debug)]
pub struct Merged {
    /// The merged roadmap.
    pub roadmap: Roadmap,
    /// What the merge did.
    pub report: MergeReport,
    /// For each part, in the order given, the merged index of each of its nodes.
    pub node_ids: Vec<Vec<u32>>,
}

/// A node not from any part (fed back during the merge): never a candidate.
const NO_PART: u32 = u32::MAX;

impl Learner<'_> {
    /// Merges `parts` (roadmaps of this learner's scene, space and local method) into one, as
    /// the module docs say: `base`, if given, keeps its node indices and comes first; the other
    /// parts follow in digest order. Stopped by `deadline` with what was joined so far;
    /// `progress` is called after every round.
    pub fn merge(
        &self,
        base: Option<&Roadmap>,
        parts: &[&Roadmap],
        deadline: &Deadline,
        progress: &mut dyn FnMut(&MergeProgress),
    ) -> Result<Merged, MergeError> {
        let began = Instant::now();
        let given: Vec<&Roadmap> = base.into_iter().chain(parts.iter().copied()).collect();
        if given.is_empty() {
            return Err(MergeError::NoParts);
        }
        for (i, part) in given.iter().enumerate() {
            self.check_part(i, part.header())?;
        }
        let order = merge_order(&given, base.is_some())?;
        let params = given[order[0]].header().params.clone();
        let mut work = Work::new(self.space, self.local.groups(self.space), &params);
        let mut node_ids = vec![Vec::new(); given.len()];
        let mut part_of: Vec<u32> = Vec::new();
        for (rank, &i) in order.iter().enumerate() {
            node_ids[i] = work.add_roadmap(given[i]);
            part_of.resize(work.node_count(), rank as u32);
        }
        let union_components = work.components;
        let mut report = MergeReport {
            parts: given.len(),
            part_nodes: given.iter().map(|p| p.node_count()).sum(),
            union_components,
            rounds: 0,
            attempts: 0,
            connected: 0,
            counts: CallCounts::default(),
            stop: MergeStop::Complete,
            elapsed: Duration::ZERO,
        };
        (report.stop, report.rounds) = self.join_parts(
            &mut work,
            &params,
            &mut part_of,
            (deadline, began),
            progress,
        )?;
        report.attempts = work.attempts;
        report.connected = work.connected;
        report.counts = work.counts;
        let header = merged_header(&given, &order, self, &params, &work, report.rounds);
        let roadmap = Roadmap::assemble(
            header,
            std::mem::take(&mut work.coords),
            std::mem::take(&mut work.edges),
        )
        .map_err(MergeError::Malformed)?;
        report.elapsed = began.elapsed();
        Ok(Merged {
            roadmap,
            report,
            node_ids,
        })
    }

    /// Refuses a part of another scene, space or local method.
    fn check_part(&self, part: usize, h: &Header) -> Result<(), MergeError> {
        if h.fingerprint != self.fingerprint {
            return Err(MergeError::ForeignScene {
                part,
                expected: self.fingerprint,
                found: h.fingerprint,
            });
        }
        if h.space != *self.space {
            return Err(MergeError::OtherSpace { part });
        }
        let expected = self.local.spec();
        if h.local_spec != expected {
            return Err(MergeError::OtherLocalMethod {
                part,
                expected: expected.to_string(),
                found: h.local_spec.to_string(),
            });
        }
        Ok(())
    }

    /// The connection step: candidates in rounds until all were tried or the deadline ends it.
    /// Returns why it ended and the rounds it ran.
    fn join_parts(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        part_of: &mut Vec<u32>,
        (deadline, began): (&Deadline, Instant),
        progress: &mut dyn FnMut(&MergeProgress),
    ) -> Result<(MergeStop, u64), MergeError> {
        let candidates = part_of.len();
        let mut next = 0usize;
        let mut rounds = 0u64;
        while next < candidates {
            if deadline.cancelled() {
                return Ok((MergeStop::Cancelled, rounds));
            }
            if deadline.expired() {
                return Ok((MergeStop::TimeBudget, rounds));
            }
            let size = (8usize << rounds.min(16)).min(params.round_size.max(1));
            let shared: &Work<'_> = work;
            let (batch, scanned) = self.next_batch(shared, part_of, params, next, size);
            let plans: Vec<Result<Vec<Attempt>, OracleError>> = batch
                .par_iter()
                .map(|(i, targets)| self.plan_across(shared, (params, deadline), *i, targets))
                .collect();
            work.stopped = deadline.expired();
            for ((i, _), plan) in batch.iter().zip(plans) {
                for a in plan? {
                    if let Target::Node(n) = a.target {
                        work.apply(*i, n, &a.connection);
                    }
                }
            }
            next = scanned;
            // nodes fed back belong to no part: they are not candidates
            part_of.resize(work.node_count(), NO_PART);
            rounds += 1;
            progress(&MergeProgress {
                tried: next,
                candidates,
                nodes: work.node_count(),
                components: work.components,
                elapsed: began.elapsed(),
            });
        }
        let stop = if deadline.cancelled() {
            MergeStop::Cancelled
        } else if work.stopped {
            MergeStop::TimeBudget
        } else {
            MergeStop::Complete
        };
        Ok((stop, rounds))
    }

    /// The round's candidates from `from` on: the next `size` that have a target
    /// ([`Self::targets_across`]), and the index after the last candidate looked at. Most
    /// candidates have none once the parts' big components are joined; skipping them here keeps
    /// a round's attempts as many as its size, so they run in parallel. Candidates are looked
    /// at in parallel chunks, all against the roadmap as the round began, so the batch does not
    /// depend on the thread count.
    fn next_batch(
        &self,
        shared: &Work<'_>,
        part_of: &[u32],
        params: &LearnParams,
        from: usize,
        size: usize,
    ) -> (Vec<(u32, Vec<u32>)>, usize) {
        const CHUNK: usize = 1024;
        let mut batch = Vec::with_capacity(size);
        let mut at = from;
        while at < part_of.len() && batch.len() < size {
            let end = (at + CHUNK).min(part_of.len());
            let found: Vec<(u32, Vec<u32>)> = (at..end)
                .into_par_iter()
                .map(|i| {
                    (
                        i as u32,
                        self.targets_across(shared, part_of, params, i as u32),
                    )
                })
                .filter(|(_, t)| !t.is_empty())
                .collect();
            for (i, t) in found {
                if batch.len() == size {
                    return (batch, i as usize);
                }
                batch.push((i, t));
            }
            at = end;
        }
        (batch, at)
    }

    /// Candidate `i`'s targets: its nearest nodes of other parts in other components, nearest
    /// first, at most [`LearnParams::neighbours`] of them among the nearest three times as many.
    fn targets_across(
        &self,
        shared: &Work<'_>,
        part_of: &[u32],
        params: &LearnParams,
        i: u32,
    ) -> Vec<u32> {
        let part = part_of[i as usize];
        if part == NO_PART {
            return Vec::new();
        }
        let own = shared.uf.find(i);
        let wide = params.neighbours.saturating_mul(3).max(params.neighbours);
        shared
            .nearest(shared.node(i), wide, params.radius)
            .into_iter()
            .filter(|&(n, _)| {
                let p = part_of.get(n as usize).copied().unwrap_or(NO_PART);
                p != part && p != NO_PART && shared.uf.find(n) != own
            })
            .take(params.neighbours)
            .map(|(n, _)| n)
            .collect()
    }

    /// Candidate `i`'s attempts towards `targets`, nearest first, skipping components it has
    /// joined (OS94's construction step).
    fn plan_across(
        &self,
        shared: &Work<'_>,
        (params, deadline): (&LearnParams, &Deadline),
        i: u32,
        targets: &[u32],
    ) -> Result<Vec<Attempt>, OracleError> {
        let targets: Vec<(Target, &[f64])> = targets
            .iter()
            .map(|&n| (Target::Node(n), shared.node(n)))
            .collect();
        let component = |t: Target| match t {
            Target::Node(n) => Target::Node(shared.uf.find(n)),
            c => c,
        };
        self.attempts(
            shared.node(i),
            &targets,
            vec![Target::Node(shared.uf.find(i))],
            component,
            (params.cycle_edges, params.deep_neighbours),
            deadline,
        )
    }
}

/// Indices into `given` in merge order: the base (if `has_base`, index 0) first, the others by
/// digest, ties (identical parts) by position.
fn merge_order(given: &[&Roadmap], has_base: bool) -> Result<Vec<usize>, MergeError> {
    let mut keyed = Vec::with_capacity(given.len());
    for (i, part) in given.iter().enumerate() {
        let digest = part
            .digest()
            .map_err(|e| MergeError::Malformed(e.to_string()))?;
        keyed.push((digest, i));
    }
    let skip = usize::from(has_base);
    keyed[skip..].sort_unstable();
    Ok(keyed.into_iter().map(|(_, i)| i).collect())
}

/// The merged roadmap's header: the scene, space and local method all parts share, the base's
/// parameters and seed, the rounds and oracle work of all parts and the merge, and a node
/// budget when every part had one (their sum).
fn merged_header(
    given: &[&Roadmap],
    order: &[usize],
    learner: &Learner<'_>,
    params: &LearnParams,
    work: &Work<'_>,
    merge_rounds: u64,
) -> Header {
    let mut counts = work.counts;
    let mut rounds = merge_rounds;
    let mut node_budget = Some(0u64);
    for p in given {
        let h = p.header();
        counts += h.counts;
        rounds += h.rounds;
        node_budget = node_budget
            .zip(h.node_budget)
            .map(|(a, b)| a.saturating_add(b));
    }
    Header {
        space: learner.space.clone(),
        fingerprint: learner.fingerprint,
        params: params.clone(),
        local_spec: learner.local.spec(),
        seed: given[order[0]].header().seed,
        node_budget,
        rounds,
        counts,
    }
}
