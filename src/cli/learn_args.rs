//! Command-line knobs of learning, shared by `build` and `demo`.

use anyhow::Context;
use clap::Args;
use viaroad::limits::MAX_NODES;
use viaroad::roadmap::{Budget, LearnParams, Sampler};

/// How much to learn and how.
#[derive(Args, Clone, Debug)]
pub struct LearnArgs {
    /// Stop at this many nodes (reproducible; at most 10⁷).
    #[arg(long)]
    pub nodes: Option<usize>,
    /// Stop after this many seconds (not reproducible: depends on the machine; at most 10⁹).
    #[arg(long)]
    pub time: Option<f64>,
    /// Seed of learning.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Do not feed the local method's via points and free segments back into the roadmap.
    #[arg(long, help_heading = "Tuning")]
    pub no_feedback: bool,
    /// Nearest neighbours each new node tries (OMPL's PRM: 10).
    #[arg(long, help_heading = "Tuning")]
    pub neighbours: Option<usize>,
    /// Cheap attempts first: the full local method only towards the nearest N neighbours in
    /// other components, the direct path towards the rest (default: the full method for all).
    #[arg(long, value_name = "N", help_heading = "Tuning")]
    pub deep_neighbours: Option<usize>,
    /// Where construction draws new nodes: `uniform`, `obstacle`, `gaussian:sigma=0.1`,
    /// `bridge:sigma=0.1`, `gap:sigma=0.1` (the bridge test with exact intervals), `bodies`
    /// (several bodies placed one at a time), or a mix
    /// such as `mix:uniform=1,bridge=1,gaussian=1` (sigma and margin are shares of the space's
    /// extent). Default: the learner's.
    #[arg(long, value_name = "SPEC", help_heading = "Tuning")]
    pub sampler: Option<Sampler>,
    /// Share of the expansion walks that are directed, RRT-Connect style, when a query grows
    /// the roadmap to join its ends (0: random bounces only). Default: the learner's.
    #[arg(long, value_name = "SHARE", help_heading = "Tuning")]
    pub directed_share: Option<f64>,
}

impl LearnArgs {
    /// The parameters and budget these flags name (`default_nodes` when neither bound is given).
    pub fn resolve(&self, default_nodes: usize) -> anyhow::Result<(LearnParams, Budget)> {
        let mut params = LearnParams {
            feedback: !self.no_feedback,
            ..LearnParams::default()
        };
        params.deep_neighbours = self.deep_neighbours;
        if let Some(k) = self.neighbours {
            params.neighbours = k;
        }
        if let Some(share) = self.directed_share {
            params.directed_share = share;
        }
        if let Some(s) = &self.sampler {
            params.sampler = s.clone();
        }
        params
            .validate()
            .map_err(anyhow::Error::msg)
            .context("learning parameters")?;
        let time = super::limits::optional_seconds("--time", self.time)?;
        if let Some(n) = self.nodes {
            // a count no memory holds is refused, not run until it fails
            super::limits::count_in_range(
                "--nodes",
                n,
                MAX_NODES,
                "a roadmap that large does not fit in memory; to learn until a deadline, \
                 give --time alone",
            )?;
        }
        let nodes = match (self.nodes, time) {
            (None, None) => Some(default_nodes),
            (n, _) => n,
        };
        Ok((params, Budget { nodes, time }))
    }
}
