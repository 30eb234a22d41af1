//! What `viaroad info` prints about a roadmap.

use super::graph::Roadmap;
use super::params::LearnParams;
use super::persist::FORMAT_VERSION;
use crate::oracle::CallCounts;
use serde::Serialize;
use std::fmt;

/// A summary of a roadmap: its size, its components and how it was learnt.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoadmapInfo {
    /// Format version of the file layout this build writes.
    pub format_version: u32,
    /// Space kind (`r2`, `se2`, …).
    pub space: String,
    /// Nodes.
    pub nodes: usize,
    /// Edges.
    pub edges: usize,
    /// Interior corners kept on edges (learnt without feedback).
    pub edge_corners: usize,
    /// Connected components.
    pub components: usize,
    /// Nodes in the largest component.
    pub largest_component: usize,
    /// Oracle work spent on learning.
    pub counts: CallCounts,
    /// Learning parameters.
    pub params: LearnParams,
    /// Local method spec.
    pub local_spec: String,
    /// Seed.
    pub seed: u64,
    /// Node budget learning ran with.
    pub node_budget: Option<u64>,
    /// Rounds learning ran.
    pub rounds: u64,
    /// Fingerprint of the scene.
    pub fingerprint: u64,
}

impl Roadmap {
    /// The summary `viaroad info` shows.
    pub fn info(&self) -> RoadmapInfo {
        let h = self.header();
        RoadmapInfo {
            format_version: FORMAT_VERSION,
            space: h.space.kind().to_string(),
            nodes: self.node_count(),
            edges: self.edge_count(),
            edge_corners: self
                .edges()
                .iter()
                .map(|e| e.corners.len() / self.dim())
                .sum(),
            components: self.component_count(),
            largest_component: self.largest_component(),
            counts: h.counts,
            params: h.params.clone(),
            local_spec: h.local_spec.to_string(),
            seed: h.seed,
            node_budget: h.node_budget,
            rounds: h.rounds,
            fingerprint: h.fingerprint,
        }
    }
}

impl fmt::Display for RoadmapInfo {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.params;
        writeln!(f, "format version   {}", self.format_version)?;
        writeln!(f, "space            {}", self.space)?;
        writeln!(f, "scene            {:016x}", self.fingerprint)?;
        writeln!(f, "nodes            {}", self.nodes)?;
        writeln!(
            f,
            "edges            {} ({} interior corners)",
            self.edges, self.edge_corners
        )?;
        writeln!(
            f,
            "components       {} (largest {} nodes)",
            self.components, self.largest_component
        )?;
        writeln!(
            f,
            "oracle calls     {} intersect ({} segment, {} line), {} state checks, {} pairs",
            self.counts.intersect_calls(),
            self.counts.segment_calls,
            self.counts.line_calls,
            self.counts.state_checks,
            self.counts.pairs_tested
        )?;
        writeln!(f, "local method     {}", self.local_spec)?;
        writeln!(f, "seed             {}", self.seed)?;
        match self.node_budget {
            Some(n) => writeln!(f, "budget           {n} nodes, {} rounds", self.rounds)?,
            None => writeln!(f, "budget           time, {} rounds", self.rounds)?,
        }
        writeln!(f, "sampler          {}", p.sampler)?;
        let radius = p.radius.map_or("none".to_string(), |r| r.to_string());
        writeln!(
            f,
            "parameters       neighbours={} radius={} expansion_share={:.3} bounce_steps={} \
             bounce_nodes={} round_size={} sample_attempts={} cycle_edges={} feedback={} \
             stall_rounds={} deep_neighbours={}",
            p.neighbours,
            radius,
            p.expansion_share,
            p.bounce_steps,
            p.bounce_nodes,
            p.round_size,
            p.sample_attempts,
            p.cycle_edges,
            p.feedback,
            p.stall_rounds,
            p.deep_neighbours
                .map_or("all".to_string(), |d| d.to_string())
        )
    }
}
