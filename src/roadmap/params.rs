//! The learning parameters (recorded in every roadmap file) and the budget that ends learning.

use super::sampler::Sampler;
use serde::{Deserialize, Serialize};
use std::time::Duration;

/// Parameters of Overmars–Švestka learning, named as in OMPL's `PRM` where it has them. Every
/// field is recorded in the roadmap file, so that a roadmap says how it was learnt.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LearnParams {
    /// How many nearest nodes a new node tries to connect to (OMPL's
    /// `DEFAULT_NEAREST_NEIGHBORS` = 10). Nodes already in a component the new node has joined
    /// are skipped (OS94), unless [`cycle_edges`](Self::cycle_edges) is set.
    pub neighbours: usize,
    /// Only neighbours within this distance ([`crate::space::Space::distance`]) are tried;
    /// `None` (the default) limits by [`neighbours`](Self::neighbours) alone.
    pub radius: Option<f64>,
    /// Share of rounds spent on the expansion step. OMPL's PRM grows for two thirds of its time
    /// and expands for one third; here the split is counted in rounds, not seconds, so that it
    /// does not depend on the machine (rounds are interleaved: two construction rounds, one
    /// expansion round, …).
    pub expansion_share: f64,
    /// Steps of one random-bounce walk (OMPL's `MAX_RANDOM_BOUNCE_STEPS` = 5).
    pub bounce_steps: usize,
    /// Make every corner of a random-bounce walk a node, joined by one edge per step (as OMPL
    /// does). Off (OS94): only the walk's end becomes a node, joined to the node the walk left
    /// by one edge that keeps the corners — the walk then costs one node of the budget.
    pub bounce_nodes: bool,
    /// Candidates (construction) or walks (expansion) per round; a round near the end of a node
    /// budget has only as many as nodes are missing. The rounds' composition fixes the result:
    /// the same seed and round size give the same roadmap with any thread count.
    pub round_size: usize,
    /// Tries per candidate to draw a collision-free configuration before giving up on it
    /// (OMPL's `nr_attempts` of a valid state sampler).
    pub sample_attempts: usize,
    /// How construction draws its candidates: uniformly, or near obstacles to find narrow
    /// passages ([`Sampler`], spec strings such as `bridge:sigma=0.05`).
    pub sampler: Sampler,
    /// Also try neighbours that are already in the new node's component, adding edges that close
    /// cycles (shorter paths, more local-method calls). Off in OS94 and OMPL's PRM.
    pub cycle_edges: bool,
    /// Feed what the local method discovers back into the roadmap (CHS §1.6): via points and
    /// corners become nodes and certified free segments become edges, also of failed attempts.
    /// Off: a successful connection becomes one edge that keeps its path's corners, a failed one
    /// leaves nothing.
    pub feedback: bool,
    /// Learning stops after this many consecutive rounds that added no node (a scene with no
    /// free space, or a node budget larger than the scene allows).
    pub stall_rounds: usize,
    /// Cheap attempts first: a new node runs the full local method only towards its nearest
    /// `d` neighbours in components it has not joined; the farther ones get only the direct
    /// path (one exact call per DOF group). `None` (OS94, OMPL): the full method towards every
    /// neighbour. A deep via-point search costs up to its call budget, and its chance to pay
    /// off falls with the distance (CHS §1.6: a roadmap calls its local method thousands of
    /// times and covers the rest itself).
    pub deep_neighbours: Option<usize>,
    /// Joining a pair (a query that grows the roadmap, `solve --roadmap`): the share of
    /// expansion walks that are directed — RRT-Connect's extend (LaValle–Kuffner 2000) from the
    /// node of one end's component nearest to a uniform sample towards it, each single-group
    /// step as far as it is free, the end then tried against the other end's component too.
    /// The rest are OS94's random-bounce walks. Random bounces explore around difficult nodes;
    /// directed walks push a component's frontier out (Voronoi bias), meant for a start boxed
    /// in by a narrow passage. 0 (the default): bounces only — on alpha-1.5 (`solve --roadmap
    /// --time 30`, 3 seeds) a share of 0.5 solved no more than 0 did (0 of 3 each),
    /// so it stays an option to measure. Learning without a pair ignores it.
    pub directed_share: f64,
}

impl Default for LearnParams {
    fn default() -> Self {
        LearnParams {
            neighbours: 10,
            radius: None,
            expansion_share: 1.0 / 3.0,
            bounce_steps: 5,
            bounce_nodes: false,
            round_size: 64,
            sample_attempts: 100,
            sampler: Sampler::default(),
            cycle_edges: false,
            feedback: true,
            stall_rounds: 100,
            deep_neighbours: None,
            directed_share: 0.0,
        }
    }
}

impl LearnParams {
    /// Largest [`round_size`](Self::round_size): a round holds all its candidates' results in
    /// memory at once.
    pub const MAX_ROUND_SIZE: usize = 1 << 16;

    /// Checks that the numbers make sense; returns what is wrong.
    pub fn validate(&self) -> Result<(), String> {
        if self.neighbours == 0 {
            return Err("neighbours must be at least 1".into());
        }
        if let Some(r) = self.radius {
            if r.is_nan() || r <= 0.0 {
                return Err(format!(
                    "radius must be positive, got {}",
                    crate::short::num(r)
                ));
            }
        }
        if !(0.0..1.0).contains(&self.expansion_share) {
            return Err(format!(
                "expansion_share must lie in [0, 1), got {}",
                self.expansion_share
            ));
        }
        if !(1..=Self::MAX_ROUND_SIZE).contains(&self.round_size) {
            return Err(format!(
                "round_size must lie in 1..={}, got {}",
                Self::MAX_ROUND_SIZE,
                self.round_size
            ));
        }
        if self.sample_attempts == 0 {
            return Err("sample_attempts must be at least 1".into());
        }
        self.sampler
            .validate()
            .map_err(|e| format!("sampler `{}`: {e}", self.sampler))?;
        if self.stall_rounds == 0 {
            return Err("stall_rounds must be at least 1".into());
        }
        if !(0.0..=1.0).contains(&self.directed_share) {
            return Err(format!(
                "directed_share must lie in [0, 1], got {}",
                self.directed_share
            ));
        }
        if self.deep_neighbours == Some(0) {
            return Err("deep_neighbours must be at least 1 (or none: every neighbour)".into());
        }
        Ok(())
    }

    /// Whether round `round` (counted from 0) is an expansion round: the rounds are spread so
    /// that after `r` rounds `⌊r · expansion_share⌋` of them expanded.
    pub fn is_expansion_round(&self, round: u64) -> bool {
        let s = self.expansion_share;
        ((round + 1) as f64 * s).floor() > (round as f64 * s).floor()
    }
}

/// What ends learning. At least one bound must be set.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Budget {
    /// Stop once the roadmap has this many nodes (checked after every candidate or walk, so the
    /// roadmap ends with at least this many, a few more when the last one brought several).
    /// Deterministic.
    pub nodes: Option<usize>,
    /// Stop once this much wall-clock time has passed: checked before every oracle call of the
    /// local method and between samples, so learning ends within about one call of it, with the
    /// roadmap learnt so far. **Not deterministic**: how much fits depends on the machine and
    /// its load.
    pub time: Option<Duration>,
}

impl Budget {
    /// A node budget only (reproducible).
    pub fn nodes(n: usize) -> Self {
        Budget {
            nodes: Some(n),
            time: None,
        }
    }

    /// A time budget only (not reproducible).
    pub fn time(t: Duration) -> Self {
        Budget {
            nodes: None,
            time: Some(t),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_split_two_to_one_by_default() {
        let p = LearnParams::default();
        let kinds: String = (0..9)
            .map(|r| if p.is_expansion_round(r) { 'E' } else { 'C' })
            .collect();
        assert_eq!(kinds, "CCECCECCE");
        let never = LearnParams {
            expansion_share: 0.0,
            ..p.clone()
        };
        assert!((0..1000).all(|r| !never.is_expansion_round(r)));
        let half = LearnParams {
            expansion_share: 0.5,
            ..p
        };
        assert_eq!(
            (0..1000).filter(|&r| half.is_expansion_round(r)).count(),
            500
        );
    }
}
