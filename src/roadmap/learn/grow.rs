//! The learning loop: stages of node targets, rounds within a stage, a snapshot per stage.

use super::super::graph::Roadmap;
use super::super::params::{Budget, LearnParams};
use super::super::persist::Header;
use super::outcome::{LearnError, LearnReport, Learnt, Phase, Progress, StopReason};
use super::seeds::Seeds;
use super::work::Work;
use super::Learner;
use crate::deadline::Deadline;
use std::ops::ControlFlow;
use std::time::{Duration, Instant};

/// Learning time: wall-clock time since learning began, less the time spent outside learning
/// (snapshots, the caller's stage handler).
struct Clock {
    began: Instant,
    paused: Duration,
}

impl Clock {
    fn learning(&self) -> Duration {
        self.began.elapsed().saturating_sub(self.paused)
    }
}

/// The round schedule so far; it depends only on earlier results, so it is the same with any
/// thread count.
#[derive(Default)]
struct Rounds {
    rounds: u64,
    construction: u64,
    expansion: u64,
    /// Rounds in a row that added no node.
    stalled: usize,
    /// Nodes the last round added per candidate: with feedback one connection attempt can
    /// bring dozens of via points and corners, so a full round near the end of a budget
    /// would compute many attempts only to throw them away.
    nodes_per_candidate: f64,
}

impl Rounds {
    /// The next round's candidates: a slow start (8, 16, 32, …) and never more than the nodes
    /// still missing are expected to need, judged by the last round's yield.
    fn size(&self, params: &LearnParams, budget: &Budget, nodes: usize) -> usize {
        let slow_start = 8usize.saturating_mul(1 << self.rounds.min(16));
        let size = budget.nodes.map_or(params.round_size, |n| {
            let missing = n.saturating_sub(nodes) as f64;
            ((missing / self.nodes_per_candidate).ceil() as usize).clamp(1, params.round_size)
        });
        size.min(slow_start).max(1)
    }

    /// Counts a finished round of `size` candidates that took the roadmap from `before` to
    /// `after` nodes.
    fn record(&mut self, phase: Phase, size: usize, before: usize, after: usize) {
        match phase {
            Phase::Expansion => self.expansion += 1,
            Phase::Construction => self.construction += 1,
        }
        self.rounds += 1;
        self.nodes_per_candidate = ((after - before) as f64 / size as f64).max(1.0);
        self.stalled = if after > before { 0 } else { self.stalled + 1 };
    }
}

impl Learner<'_> {
    /// The learning loop behind [`learn`](Self::learn) and
    /// [`learn_in_stages`](Self::learn_in_stages): one stage per node target (`None`: no node
    /// target, only `time`).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn grow(
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
        if stages.is_empty() {
            return Err(LearnError::NoBudget);
        }
        let mut clock = Clock {
            began: Instant::now(),
            paused: Duration::ZERO,
        };
        let mut work = Work::new(self.space, self.local.groups(self.space), params);
        if let Some(base) = seeds.base {
            work.copy_roadmap(base);
        }
        let (copied, tried) = (work.node_count(), work.attempts);
        let pair = match seeds.pair {
            Some(ends) => Some(self.seed_pair(&mut work, params, ends, &deadline.within(time))?),
            None => None,
        };
        // the ends' attempts size the first round: where one attempt's feedback brings dozens
        // of nodes, a first round of eight candidates, each trying its nearest neighbours,
        // would under a small node budget compute candidates only to drop them at the budget
        let per_attempt =
            (work.node_count() - copied) as f64 / (work.attempts - tried).max(1) as f64;
        let mut rounds = Rounds {
            nodes_per_candidate: match pair {
                Some(_) => (per_attempt * params.neighbours as f64).max(1.0),
                None => 1.0,
            },
            ..Rounds::default()
        };
        let mut stage = 0;
        loop {
            let budget = Budget {
                nodes: stages[stage],
                time,
            };
            let stop = self.run_stage(
                &mut work,
                params,
                (&budget, deadline, &clock),
                pair,
                seed,
                &mut rounds,
                progress,
            )?;
            let elapsed = clock.learning();
            let pause = Instant::now();
            let last = stage + 1 == stages.len() || stop != StopReason::NodeBudget;
            let learnt = self.snapshot(
                &mut work,
                params,
                (seed, &budget),
                &rounds,
                stop,
                elapsed,
                last,
            )?;
            let flow = on_stage(&learnt);
            clock.paused += pause.elapsed();
            if last || flow.is_break() {
                return Ok((learnt, pair));
            }
            stage += 1;
        }
    }

    /// The pair's two ends as the first candidates: tried against each other and their nearest
    /// nodes before any sampling. Returns their nodes.
    fn seed_pair(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        (s, g): (&[f64], &[f64]),
        deadline: &Deadline,
    ) -> Result<(u32, u32), LearnError> {
        let ends = vec![s.to_vec(), g.to_vec()];
        let ids = self.connect_candidates(work, params, &Budget::default(), deadline, ends)?;
        Ok((ids[0], ids[1]))
    }

    /// Runs rounds until the stage's node target, the time, the deadline, stalling or the
    /// pair's meeting ends them; says which.
    #[allow(clippy::too_many_arguments)]
    fn run_stage(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        (budget, deadline, clock): (&Budget, &Deadline, &Clock),
        pair: Option<(u32, u32)>,
        seed: u64,
        rounds: &mut Rounds,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<StopReason, LearnError> {
        loop {
            if pair.is_some_and(|(s, g)| work.uf.equiv(s, g)) {
                return Ok(StopReason::Connected);
            }
            if budget.nodes.is_some_and(|n| work.node_count() >= n) {
                return Ok(StopReason::NodeBudget);
            }
            if deadline.cancelled() {
                return Ok(StopReason::Cancelled);
            }
            // the time left, as a deadline the round checks before every oracle call
            let round_deadline =
                deadline.within(budget.time.map(|t| t.saturating_sub(clock.learning())));
            if round_deadline.expired() {
                return Ok(StopReason::TimeBudget);
            }
            if rounds.stalled >= params.stall_rounds {
                return Ok(StopReason::Stalled);
            }
            let before = work.node_count();
            let size = rounds.size(params, budget, before);
            let round = (seed, rounds.rounds, size);
            let phase = if params.is_expansion_round(rounds.rounds) && before > 0 {
                self.expansion_round(work, params, budget, &round_deadline, pair, round)?;
                Phase::Expansion
            } else {
                self.construction_round(work, params, budget, &round_deadline, round)?;
                Phase::Construction
            };
            rounds.record(phase, size, before, work.node_count());
            progress(&Progress {
                rounds: rounds.rounds,
                phase,
                nodes: work.node_count(),
                edges: work.edges.len(),
                components: work.components,
                node_budget: budget.nodes,
                elapsed: clock.learning(),
                counts: work.counts,
            });
        }
    }

    /// The roadmap and report at the end of a stage. The last stage hands over the graph;
    /// earlier ones copy it and go on growing.
    #[allow(clippy::too_many_arguments)]
    fn snapshot(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        (seed, budget): (u64, &Budget),
        rounds: &Rounds,
        stop: StopReason,
        elapsed: Duration,
        last: bool,
    ) -> Result<Learnt, LearnError> {
        let header = Header {
            space: self.space.clone(),
            fingerprint: self.fingerprint,
            params: params.clone(),
            local_spec: self.local.spec(),
            seed,
            node_budget: budget.nodes.map(|n| n as u64),
            rounds: rounds.rounds,
            counts: work.counts,
        };
        let report = LearnReport {
            rounds: rounds.rounds,
            construction_rounds: rounds.construction,
            expansion_rounds: rounds.expansion,
            attempts: work.attempts,
            connected: work.connected,
            stop,
            elapsed,
        };
        let (coords, edges) = if last {
            (
                std::mem::take(&mut work.coords),
                std::mem::take(&mut work.edges),
            )
        } else {
            (work.coords.clone(), work.edges.clone())
        };
        let roadmap = Roadmap::assemble(header, coords, edges).map_err(LearnError::Malformed)?;
        Ok(Learnt { roadmap, report })
    }
}
