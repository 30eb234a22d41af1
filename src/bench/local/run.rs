//! One run of a local-method benchmark: learn in stages, answer the query set after each
//! stage, stop at the target share, and re-check every returned path with the exact oracle.

use super::machine;
use super::queries::QuerySet;
use super::spec::RunJob;
use super::BenchError;
use crate::local::path_pieces;
use crate::local::LocalMethod;
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::roadmap::{
    LearnParams, Learner, Learnt, QueryOptions, QueryOutcome, QueryPlanner, Roadmap, StopReason,
};
use crate::scene::Scene;
use crate::space::{Config, Group, Space};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;
use std::time::{Duration, Instant};

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStop {
    /// A stage solved the target share of the scored queries.
    Target,
    /// The last stage (the node cap) was reached first.
    NodeCap,
    /// The learning-time limit ran out.
    TimeLimit,
    /// Learning stopped adding nodes.
    Stalled,
}

impl RunStop {
    /// Short description.
    pub fn description(&self) -> &'static str {
        match self {
            RunStop::Target => "target reached",
            RunStop::NodeCap => "node cap",
            RunStop::TimeLimit => "time limit",
            RunStop::Stalled => "stalled",
        }
    }
}

/// The roadmap after one stage and how it answered the scored queries.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StageRecord {
    /// Nodes.
    pub nodes: usize,
    /// Edges.
    pub edges: usize,
    /// Connected components.
    pub components: usize,
    /// Nodes in the largest component.
    pub largest_component: usize,
    /// Learning rounds so far.
    pub rounds: u64,
    /// Learning time so far, seconds (query answering excluded).
    pub learn_seconds: f64,
    /// Oracle work of learning so far.
    pub counts: CallCounts,
    /// Local-method attempts of learning so far.
    pub attempts: u64,
    /// Of which connected.
    pub connected: u64,
    /// Scored queries solved with a path the exact oracle finds free.
    pub solved: usize,
    /// Scored queries the roadmap returned a path for (free or not).
    pub claimed: usize,
    /// Returned paths the exact oracle finds colliding.
    pub invalid_paths: usize,
    /// Which queries of the set were solved (free path), as a hex bit mask: bit `i % 4` of
    /// digit `i / 4` is query `i`.
    pub solved_queries: String,
    /// Wall time of answering and re-checking the queries, seconds.
    pub eval_seconds: f64,
}

/// The seed roadmap a seeded run started from ([`crate::global::Seeding`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SeedRecord {
    /// Freeways (generalized cones) the seeds came from.
    pub freeways: usize,
    /// Seed nodes: the roadmap's nodes before learning.
    pub nodes: usize,
    /// Seed edges.
    pub edges: usize,
    /// Components of the seed roadmap.
    pub components: usize,
    /// Wall time of building the freeways and checking the seeds, seconds (part of every
    /// stage's learning time).
    pub seconds: f64,
    /// Oracle work of checking the seeds (part of every stage's counts).
    pub counts: CallCounts,
}

/// Everything measured in one run. The summary fields describe the last stage.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Scene name.
    pub scene: String,
    /// Scene as given (file or generator).
    pub scene_source: String,
    /// Method label ([`super::Method::label`]).
    pub method: String,
    /// Canonical local-method spec.
    pub local_spec: String,
    /// Feedback of discoveries.
    pub feedback: bool,
    /// Canonical sampler spec of construction.
    #[serde(default)]
    pub sampler: String,
    /// What the roadmap started from ([`crate::global::Seeding`]: `plain` or `cones`).
    #[serde(default = "plain")]
    pub seeding: String,
    /// The seed roadmap of a seeded run (`None`: plain).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seeded: Option<SeedRecord>,
    /// Run index.
    pub run: u32,
    /// Learning seed.
    pub seed: u64,
    /// Rayon threads of the process that ran it.
    pub threads: usize,
    /// Queries in the set.
    pub queries: usize,
    /// Of which scored.
    pub scored: usize,
    /// Of which in the separate group.
    pub separate: usize,
    /// Of which invalid (not asked).
    pub invalid_queries: usize,
    /// Target share.
    pub target: f64,
    /// Queries tried the local method from start to goal first.
    pub direct: bool,
    /// The intersect calls a query could spend ([`RunJob::query_calls`]; `None`: no limit).
    #[serde(default)]
    pub query_calls: Option<u64>,
    /// Scored queries the target asks for: `⌈target · scored⌉`.
    pub needed: usize,
    /// Every stage evaluated, in order.
    pub stages: Vec<StageRecord>,
    /// Why the run ended.
    pub stop: RunStop,
    /// Learning time at the first stage that reached the target, seconds.
    pub time_to_target: Option<f64>,
    /// Nodes at that stage.
    pub nodes_at_target: Option<usize>,
    /// Nodes at the end.
    pub nodes: usize,
    /// Edges at the end.
    pub edges: usize,
    /// Components at the end.
    pub components: usize,
    /// Learning time at the end, seconds.
    pub learn_seconds: f64,
    /// Oracle work of learning.
    pub counts: CallCounts,
    /// Local-method attempts of learning.
    pub attempts: u64,
    /// Of which connected.
    pub connected: u64,
    /// Scored queries solved at the end (free paths).
    pub solved: usize,
    /// Scored queries answered at the end (free or not).
    pub claimed: usize,
    /// Returned paths at the end that the exact oracle finds colliding (the shortened paths
    /// users get).
    pub invalid_paths: usize,
    /// Returned paths whose unshortened form collides.
    pub invalid_raw_paths: usize,
    /// Scored queries at the end that spent the call budget before an answer
    /// ([`RunJob::query_calls`]).
    #[serde(default)]
    pub out_of_calls: usize,
    /// Separate-group queries solved at the end.
    pub separate_solved: usize,
    /// Separate-group queries answered at the end (free or not).
    pub separate_claimed: usize,
    /// Median query latency over the scored queries at the end, milliseconds.
    pub query_p50_ms: f64,
    /// 95th percentile of the latency, milliseconds.
    pub query_p95_ms: f64,
    /// Mean latency, milliseconds.
    pub query_mean_ms: f64,
    /// Oracle work of answering the scored queries at the end.
    pub query_counts: CallCounts,
    /// Mean length of the solved queries' paths before shortening.
    pub path_length_raw: Option<f64>,
    /// Mean length after shortening.
    pub path_length: Option<f64>,
    /// Size of the roadmap file (bincode), bytes.
    pub roadmap_bytes: usize,
    /// Peak resident set during the run, MiB (see [`machine::peak_rss_mib`]).
    pub peak_rss_mib: Option<f64>,
    /// Wall time of the whole run with every evaluation, seconds.
    pub wall_seconds: f64,
    /// With [`RunJob::keep_paths`]: the path returned for each query at the end (`None`: not
    /// answered or not asked).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paths: Option<Vec<Option<Vec<Config>>>>,
}

fn plain() -> String {
    crate::global::Seeding::Plain.to_string()
}

/// Whether every piece of `path` (corners joined by direct paths in `groups`, CHS §1.5) is
/// free under `oracle`: the exact re-check of returned paths.
pub fn path_is_free(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
) -> Result<bool, OracleError> {
    let mut counts = CallCounts::default();
    if path.len() == 1 {
        return Ok(!oracle.collides(&path[0], &mut counts));
    }
    for w in path.windows(2) {
        for (motion, _) in path_pieces(space, groups, &w[0], &w[1]) {
            if !oracle.motion_is_free(&motion, &mut counts)? {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// `bits` as hex digits, four queries a digit, lowest index in the lowest bit.
pub fn bits_to_hex(bits: &[bool]) -> String {
    bits.chunks(4)
        .map(|c| {
            let v = c
                .iter()
                .enumerate()
                .fold(0u32, |v, (k, &b)| v | (u32::from(b) << k));
            char::from_digit(v, 16).expect("a nibble")
        })
        .collect()
}

/// The inverse of [`bits_to_hex`] for `n` bits (missing digits are zeros, bad digits too).
pub fn hex_to_bits(hex: &str, n: usize) -> Vec<bool> {
    let digits: Vec<u32> = hex.chars().map(|c| c.to_digit(16).unwrap_or(0)).collect();
    (0..n)
        .map(|i| digits.get(i / 4).is_some_and(|d| d >> (i % 4) & 1 == 1))
        .collect()
}

/// Queries a target share asks of `n`: `⌈target · n⌉`, forgiving rounding (0.99 · 100 = 99).
pub fn target_count(target: f64, n: usize) -> usize {
    ((target * n as f64) - 1e-9).ceil().max(0.0) as usize
}

/// Nearest-rank percentile `p` of sorted `values` (0 for none).
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// How the roadmap answered a list of queries.
struct Evaluation {
    /// Per query of the set: solved with a free path.
    solved: Vec<bool>,
    valid: usize,
    claimed: usize,
    invalid: usize,
    invalid_raw: usize,
    /// Queries that spent their call budget before an answer.
    out_of_calls: usize,
    latencies: Vec<f64>,
    raw_lengths: Vec<f64>,
    lengths: Vec<f64>,
    counts: CallCounts,
    seconds: f64,
    paths: Vec<(usize, Vec<Config>)>,
}

/// Answers queries `which` of `set` with `planner` and re-checks every returned path with the
/// exact `oracle`.
fn evaluate(
    planner: &QueryPlanner<'_>,
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    set: &QuerySet,
    which: &[usize],
    keep_paths: bool,
) -> Result<Evaluation, BenchError> {
    let began = Instant::now();
    let pairs: Vec<(Config, Config)> = which.iter().map(|&i| set.pairs[i].clone()).collect();
    let answers = planner.query_batch(&pairs);
    let checked: Vec<Result<_, BenchError>> = answers
        .into_par_iter()
        .map(|a| {
            let r = a.result?;
            let (ok, raw_ok) = if r.is_solved() {
                (
                    path_is_free(space, oracle, groups, &r.path)?,
                    path_is_free(space, oracle, groups, &r.raw_path)?,
                )
            } else {
                (false, false)
            };
            Ok((r, ok, raw_ok, a.elapsed.as_secs_f64()))
        })
        .collect();
    let mut e = Evaluation {
        solved: vec![false; set.len()],
        valid: 0,
        claimed: 0,
        invalid: 0,
        invalid_raw: 0,
        out_of_calls: 0,
        latencies: Vec::with_capacity(which.len()),
        raw_lengths: Vec::new(),
        lengths: Vec::new(),
        counts: CallCounts::default(),
        seconds: 0.0,
        paths: Vec::new(),
    };
    for (&i, c) in which.iter().zip(checked) {
        let (r, ok, raw_ok, secs) = c?;
        e.latencies.push(secs);
        e.counts += r.counts;
        e.out_of_calls += usize::from(r.outcome == QueryOutcome::OutOfCalls);
        if r.is_solved() {
            e.claimed += 1;
            e.invalid += usize::from(!ok);
            e.invalid_raw += usize::from(!raw_ok);
            if keep_paths {
                e.paths.push((i, r.path.clone()));
            }
        }
        if ok {
            e.solved[i] = true;
            e.valid += 1;
            e.raw_lengths.push(r.raw_length);
            e.lengths.push(r.length);
        }
    }
    e.latencies.sort_by(f64::total_cmp);
    e.seconds = began.elapsed().as_secs_f64();
    Ok(e)
}

/// The record of a stage; a seeded run's seed time and calls count as learning.
fn stage_record(l: &Learnt, e: &Evaluation, seeded: Option<&SeedRecord>) -> StageRecord {
    let r = &l.roadmap;
    let (seed_seconds, seed_counts) =
        seeded.map_or((0.0, CallCounts::default()), |s| (s.seconds, s.counts));
    StageRecord {
        nodes: r.node_count(),
        edges: r.edge_count(),
        components: r.component_count(),
        largest_component: r.largest_component(),
        rounds: l.report.rounds,
        learn_seconds: seed_seconds + l.report.elapsed.as_secs_f64(),
        counts: r.header().counts + seed_counts,
        attempts: l.report.attempts,
        connected: l.report.connected,
        solved: e.valid,
        claimed: e.claimed,
        invalid_paths: e.invalid,
        solved_queries: bits_to_hex(&e.solved),
        eval_seconds: e.seconds,
    }
}

fn mean(v: &[f64]) -> Option<f64> {
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// Runs `job`: loads (or generates) its scene, builds its query set, and calls [`run_on`].
pub fn run_job(job: &RunJob) -> Result<RunRecord, BenchError> {
    let scene = job.scene.load()?;
    let set = QuerySet::build(&scene, &job.queries, job.query_seed)?;
    run_on(&scene, &set, job)
}

/// Runs `job` on a loaded `scene` with its query `set` (the one [`QuerySet::build`] gives for
/// the job), on the current rayon pool.
pub fn run_on(scene: &Scene, set: &QuerySet, job: &RunJob) -> Result<RunRecord, BenchError> {
    let wall = Instant::now();
    machine::reset_peak_rss();
    let oracle = scene.oracle();
    let local = job.method.local.build();
    let bench = Bench {
        scene,
        set,
        job,
        oracle: oracle.as_ref(),
        groups: local.groups(&scene.space),
        options: query_options(job),
    };
    let scored = set.scored();
    let needed = target_count(job.target, scored.len());
    let (learnt, stages, eval, seeded) = bench.learn_in_stages(local.as_ref(), &scored, needed)?;
    let (Some(eval), Some(end)) = (eval, stages.last().cloned()) else {
        return Err(BenchError::Invalid(
            "learning ended before its first stage".into(),
        ));
    };
    let reached = eval.valid >= needed;
    let stop = run_stop(reached, learnt.report.stop);
    // the separate group, once, against the final roadmap
    let separate = set.separate();
    let apart = bench.evaluate(&learnt.roadmap, &separate)?;
    let paths = job
        .keep_paths
        .then(|| all_paths(set.len(), &eval.paths, &apart.paths));
    Ok(bench.record(RunEnd {
        seeded,
        end,
        stages,
        eval,
        apart,
        stop,
        needed,
        reached,
        roadmap_bytes: learnt.roadmap.to_bytes()?.len(),
        paths,
        wall_seconds: wall.elapsed().as_secs_f64(),
    }))
}

/// How a run ended, for its record.
struct RunEnd {
    /// The seed roadmap of a seeded run.
    seeded: Option<SeedRecord>,
    /// The last stage.
    end: StageRecord,
    /// Every stage evaluated.
    stages: Vec<StageRecord>,
    /// The last evaluation of the scored queries.
    eval: Evaluation,
    /// The evaluation of the separate group.
    apart: Evaluation,
    stop: RunStop,
    /// Scored queries the target asks for.
    needed: usize,
    /// Whether the last stage solved them.
    reached: bool,
    roadmap_bytes: usize,
    paths: Option<Vec<Option<Vec<Config>>>>,
    wall_seconds: f64,
}

/// The query options of `job`'s evaluations.
fn query_options(job: &RunJob) -> QueryOptions {
    QueryOptions {
        try_direct: job.direct,
        attach_candidates: job.attach.max(1),
        escalation_candidates: job.escalation,
        max_calls: job.query_calls,
        ..QueryOptions::default()
    }
}

/// `job`'s learning-time limit, checked.
fn time_limit(job: &RunJob) -> Result<Option<Duration>, BenchError> {
    let Some(t) = job.time_limit else {
        return Ok(None);
    };
    crate::limits::duration_from_secs(t)
        .map(Some)
        .ok_or_else(|| {
            BenchError::Invalid(format!(
                "the time limit must be a positive number of seconds of at most {:e}, got {t:?}",
                crate::limits::MAX_SECONDS
            ))
        })
}

/// The stages of a run seeded with `seed_nodes` nodes: the seed roadmap alone first, then
/// the job's stages above it (a stage at or below it would evaluate the same roadmap again).
fn seeded_stages(stages: &[usize], seed_nodes: usize) -> Vec<usize> {
    if seed_nodes == 0 {
        return stages.to_vec();
    }
    std::iter::once(seed_nodes)
        .chain(stages.iter().copied().filter(|&n| n > seed_nodes))
        .collect()
}

/// Why a run ended, from whether it `reached` its target and why learning stopped.
fn run_stop(reached: bool, stop: StopReason) -> RunStop {
    if reached {
        return RunStop::Target;
    }
    match stop {
        StopReason::NodeBudget => RunStop::NodeCap,
        StopReason::TimeBudget | StopReason::Cancelled => RunStop::TimeLimit,
        StopReason::Stalled => RunStop::Stalled,
        // learn_in_stages grows no pair
        StopReason::Connected => RunStop::Target,
    }
}

/// The paths kept by two evaluations, per query of a set of `n` (`None`: none returned).
fn all_paths(
    n: usize,
    scored: &[(usize, Vec<Config>)],
    separate: &[(usize, Vec<Config>)],
) -> Vec<Option<Vec<Config>>> {
    let mut all: Vec<Option<Vec<Config>>> = vec![None; n];
    for (i, p) in scored.iter().chain(separate) {
        all[*i] = Some(p.clone());
    }
    all
}

/// One run's fixed parts: the scene, its queries, the job, the exact oracle and the query
/// options of every evaluation.
struct Bench<'a> {
    scene: &'a Scene,
    set: &'a QuerySet,
    job: &'a RunJob,
    oracle: &'a dyn CollisionOracle,
    groups: Vec<Group>,
    options: QueryOptions,
}

impl Bench<'_> {
    /// Answers queries `which` with `roadmap` and re-checks the paths ([`evaluate`]).
    fn evaluate(&self, roadmap: &Roadmap, which: &[usize]) -> Result<Evaluation, BenchError> {
        let planner = QueryPlanner::new(roadmap, self.oracle)?.with_options(self.options.clone());
        evaluate(
            &planner,
            &self.scene.space,
            self.oracle,
            &self.groups,
            self.set,
            which,
            self.job.keep_paths,
        )
    }

    /// The seed roadmap of the job's seeding (`None`: plain), of at most half the node cap
    /// (as `build --seed-from` keeps half the node budget for the learner), and its record.
    fn seed(
        &self,
        local: &dyn LocalMethod,
        params: &LearnParams,
    ) -> Result<Option<(Roadmap, SeedRecord)>, BenchError> {
        let seeding = self.job.method.seeding;
        let cap = self.job.stages.last().copied().unwrap_or(0);
        let seeded = seeding
            .seed_roadmap(
                self.scene,
                self.oracle,
                params,
                &local.spec(),
                self.job.seed,
                (cap / 2).max(1),
            )
            .map_err(|source| BenchError::Seeding {
                seeding,
                scene: self.scene.name.clone(),
                source,
            })?;
        Ok(seeded.map(|s| {
            let r = &s.roadmap;
            let record = SeedRecord {
                freeways: s.freeways,
                nodes: r.node_count(),
                edges: r.edge_count(),
                components: r.component_count(),
                seconds: s.elapsed.as_secs_f64(),
                counts: r.header().counts,
            };
            (s.roadmap, record)
        }))
    }

    /// Learns in the job's stages with `local`, evaluating the `scored` queries after each,
    /// until a stage solves `needed` of them; a seeded job starts from its seed roadmap
    /// ([`seeded_stages`]). Returns the last roadmap, every stage's record, the last
    /// evaluation and the seed's record.
    #[allow(clippy::type_complexity)]
    fn learn_in_stages(
        &self,
        local: &dyn LocalMethod,
        scored: &[usize],
        needed: usize,
    ) -> Result<
        (
            Learnt,
            Vec<StageRecord>,
            Option<Evaluation>,
            Option<SeedRecord>,
        ),
        BenchError,
    > {
        let params = LearnParams {
            feedback: self.job.method.feedback,
            sampler: self.job.method.sampler.clone(),
            ..LearnParams::default()
        };
        let seed = self.seed(local, &params)?;
        let (base, seeded) = match seed {
            Some((roadmap, record)) => (Some(roadmap), Some(record)),
            None => (None, None),
        };
        let job_stages = match &seeded {
            Some(s) => seeded_stages(&self.job.stages, s.nodes),
            None => self.job.stages.clone(),
        };
        // the seeds' time is learning time: what is left of a time limit is the learner's
        let time = time_limit(self.job)?.map(|t| {
            t.saturating_sub(Duration::from_secs_f64(
                seeded.as_ref().map_or(0.0, |s| s.seconds),
            ))
        });
        let learner = Learner::for_scene(self.scene, self.oracle, local);
        let mut stages: Vec<StageRecord> = Vec::new();
        let mut last: Option<Evaluation> = None;
        let mut failure: Option<BenchError> = None;
        let learnt = learner.learn_in_stages_from(
            base.as_ref(),
            &params,
            &job_stages,
            time,
            self.job.seed,
            &mut |_| {},
            &mut |l| match self.evaluate(&l.roadmap, scored) {
                Ok(e) => {
                    stages.push(stage_record(l, &e, seeded.as_ref()));
                    let done = e.valid >= needed;
                    last = Some(e);
                    if done {
                        ControlFlow::Break(())
                    } else {
                        ControlFlow::Continue(())
                    }
                }
                Err(e) => {
                    failure = Some(e);
                    ControlFlow::Break(())
                }
            },
        )?;
        match failure {
            Some(e) => Err(e),
            None => Ok((learnt, stages, last, seeded)),
        }
    }

    /// The run's record; its summary fields describe the last stage.
    fn record(&self, run: RunEnd) -> RunRecord {
        let (job, set) = (self.job, self.set);
        let RunEnd {
            seeded,
            end,
            stages,
            eval,
            apart,
            stop,
            needed,
            reached,
            roadmap_bytes,
            paths,
            wall_seconds,
        } = run;
        RunRecord {
            scene: self.scene.name.clone(),
            scene_source: job.scene.to_string(),
            method: job.method.label(),
            local_spec: job.method.local.to_string(),
            feedback: job.method.feedback,
            sampler: job.method.sampler.to_string(),
            seeding: job.method.seeding.to_string(),
            seeded,
            run: job.run,
            seed: job.seed,
            threads: rayon::current_num_threads(),
            queries: set.len(),
            scored: set.scored().len(),
            separate: set.separate().len(),
            invalid_queries: set.invalid().len(),
            target: job.target,
            direct: job.direct,
            query_calls: job.query_calls,
            needed,
            time_to_target: reached.then_some(end.learn_seconds),
            nodes_at_target: reached.then_some(end.nodes),
            stop,
            nodes: end.nodes,
            edges: end.edges,
            components: end.components,
            learn_seconds: end.learn_seconds,
            counts: end.counts,
            attempts: end.attempts,
            connected: end.connected,
            solved: eval.valid,
            claimed: eval.claimed,
            invalid_paths: eval.invalid + apart.invalid,
            invalid_raw_paths: eval.invalid_raw + apart.invalid_raw,
            out_of_calls: eval.out_of_calls,
            separate_solved: apart.valid,
            separate_claimed: apart.claimed,
            query_p50_ms: 1e3 * percentile(&eval.latencies, 0.5),
            query_p95_ms: 1e3 * percentile(&eval.latencies, 0.95),
            query_mean_ms: 1e3 * mean(&eval.latencies).unwrap_or(0.0),
            query_counts: eval.counts,
            path_length_raw: mean(&eval.raw_lengths),
            path_length: mean(&eval.lengths),
            roadmap_bytes,
            peak_rss_mib: machine::peak_rss_mib(),
            wall_seconds,
            paths,
            stages,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_masks_round_trip() {
        let bits: Vec<bool> = (0..23).map(|i| i % 3 == 0 || i == 22).collect();
        let hex = bits_to_hex(&bits);
        assert_eq!(hex.len(), 6);
        assert_eq!(hex_to_bits(&hex, 23), bits);
        assert_eq!(bits_to_hex(&[true, false, false, true]), "9");
        assert_eq!(hex_to_bits("", 3), vec![false; 3]);
    }

    #[test]
    fn seeded_runs_start_with_the_seed_roadmap() {
        let stages = [25, 50, 100, 200];
        assert_eq!(seeded_stages(&stages, 0), stages);
        assert_eq!(seeded_stages(&stages, 60), [60, 100, 200]);
        assert_eq!(seeded_stages(&stages, 50), [50, 100, 200]);
        assert_eq!(seeded_stages(&stages, 300), [300]);
    }

    #[test]
    fn percentiles_are_nearest_rank() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(percentile(&v, 0.5), 51.0);
        assert_eq!(percentile(&v, 0.95), 95.0);
        assert_eq!(percentile(&[], 0.5), 0.0);
    }
}
