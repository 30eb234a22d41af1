//! What learning reports: its errors, progress, why it stopped, and the learnt roadmap.

use super::super::graph::Roadmap;
use crate::oracle::{CallCounts, OracleError};
use std::time::Duration;

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
    /// The time budget ran out (or the caller's [`Deadline`](crate::deadline::Deadline) passed).
    TimeBudget,
    /// The caller cancelled ([`Deadline::with_cancel`](crate::deadline::Deadline::with_cancel): Ctrl-C).
    Cancelled,
    /// The two configurations of [`Learner::connect_pair`](super::Learner::connect_pair) are in one component.
    Connected,
    /// [`LearnParams::stall_rounds`](crate::roadmap::LearnParams::stall_rounds) rounds in a row added no node.
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

/// A roadmap grown to join two configurations ([`Learner::connect_pair`](super::Learner::connect_pair)).
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
