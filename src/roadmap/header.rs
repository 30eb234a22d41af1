//! The header of a roadmap: how it was learnt and for which scene. The graph carries it and the
//! file ([`super::persist`]) signs it.

use super::params::LearnParams;
use crate::local::LocalSpec;
use crate::oracle::CallCounts;
use crate::space::Space;
use serde::{Deserialize, Serialize};

/// How a roadmap was learnt and for which scene: the signed part of the file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// The configuration space, with bounds.
    pub space: Space,
    /// Fingerprint of the scene learnt ([`crate::scene::Scene::fingerprint`]).
    pub fingerprint: u64,
    /// The learning parameters.
    pub params: LearnParams,
    /// The local method the roadmap was learnt with; queries rebuild it (and its budgeted and
    /// deeper variants) from this, so that the groups of edges and attaching paths agree.
    pub local_spec: LocalSpec,
    /// Seed of the random streams.
    pub seed: u64,
    /// The node budget learning ran with, if any (a time budget is not recorded: it is not
    /// reproducible).
    pub node_budget: Option<u64>,
    /// Rounds learning ran.
    pub rounds: u64,
    /// Oracle work spent on learning.
    pub counts: CallCounts,
}
