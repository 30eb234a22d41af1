//! Construction rounds (OS94, OMPL's `growRoadmap`): sample free configurations, connect each
//! to its nearest nodes and to the candidates before it.

use super::super::params::{Budget, LearnParams};
use super::attempts::{Attempt, Target};
use super::streams::{stream, SAMPLE_STREAM};
use super::work::Work;
use super::{LearnError, Learner};
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, OracleError};
use crate::space::Config;
use rayon::prelude::*;

impl Learner<'_> {
    /// One construction round of `size` candidates: samples free configurations in parallel
    /// (each candidate from its own stream) and connects them.
    pub(super) fn construction_round(
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
    pub(super) fn connect_candidates(
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
            .map(|i| self.plan_candidate(shared, params, deadline, &candidates, i))
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

    /// The attempts of candidate `i`: towards its nearest nodes and the candidates before it,
    /// nearest first.
    fn plan_candidate(
        &self,
        shared: &Work<'_>,
        params: &LearnParams,
        deadline: &Deadline,
        candidates: &[Config],
        i: usize,
    ) -> Result<Vec<Attempt>, OracleError> {
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
    }
}
