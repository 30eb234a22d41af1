//! The numbers of a benchmark report, apart from how they are printed: statistics over runs,
//! the solvable set of a scene, per-method summaries, rankings and feedback pairs.

use super::super::queries::{QueryRole, QuerySet};
use super::super::run::{hex_to_bits, target_count as needed, RunRecord, RunStop, StageRecord};
use super::super::spec::Plan;
use serde::Serialize;

/// Median, range and mean of one measure over runs (runs without a value are left out).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Stats {
    /// Runs with a value.
    pub n: usize,
    /// Median (the mean of the two middle values for an even count).
    pub median: Option<f64>,
    /// Smallest value.
    pub min: Option<f64>,
    /// Largest value.
    pub max: Option<f64>,
    /// Mean.
    pub mean: Option<f64>,
}

impl Stats {
    /// Statistics of `values`.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Stats {
        let mut v: Vec<f64> = values.into_iter().filter(|x| !x.is_nan()).collect();
        if v.is_empty() {
            return Stats::default();
        }
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            (v[n / 2 - 1] + v[n / 2]) / 2.0
        };
        Stats {
            n,
            median: Some(median),
            min: Some(v[0]),
            max: Some(v[n - 1]),
            mean: Some(v.iter().sum::<f64>() / n as f64),
        }
    }
}

/// What the report needs to know about a scene besides its runs.
#[derive(Clone, Debug, Serialize)]
pub struct SceneInfo {
    /// Scene name.
    pub name: String,
    /// Scene as given on the command line.
    pub source: String,
    /// Where its queries come from.
    pub query_source: String,
    /// Queries in the set.
    pub queries: usize,
    /// Indices of the scored queries.
    pub scored: Vec<usize>,
    /// Indices of the separate group.
    pub separate: Vec<usize>,
    /// Name of the separate group.
    pub separate_group: Option<String>,
    /// Invalid queries with the reason.
    pub invalid: Vec<(usize, String)>,
}

impl SceneInfo {
    /// The information of a scene with query set `set`.
    pub fn new(name: &str, source: &str, set: &QuerySet) -> SceneInfo {
        SceneInfo {
            name: name.to_string(),
            source: source.to_string(),
            query_source: set.source.clone(),
            queries: set.len(),
            scored: set.scored(),
            separate: set.separate(),
            separate_group: set.separate_group.clone(),
            invalid: set
                .roles
                .iter()
                .enumerate()
                .filter_map(|(i, r)| match r {
                    QueryRole::Invalid(why) => Some((i, why.clone())),
                    _ => None,
                })
                .collect(),
        }
    }
}

/// One method on one scene, over its runs.
#[derive(Clone, Debug, Serialize)]
pub struct MethodSummary {
    /// Method label.
    pub method: String,
    /// Canonical local-method spec.
    pub local_spec: String,
    /// Feedback on.
    pub feedback: bool,
    /// Canonical sampler spec.
    pub sampler: String,
    /// What the roadmap started from (`plain`, `cones`).
    pub seeding: String,
    /// Seed nodes of seeded runs (no values for plain runs).
    pub seed_nodes: Stats,
    /// Components of the seed roadmaps.
    pub seed_components: Stats,
    /// Seconds of building the freeways and checking the seeds (part of the learning times).
    pub seed_seconds: Stats,
    /// Runs.
    pub runs: usize,
    /// Runs that reached the target share of the scored queries.
    pub reached: usize,
    /// Runs that reached the target share of the solvable queries.
    pub reached_solvable: usize,
    /// Learning time to the target share of the scored queries, seconds.
    pub time_to_target: Stats,
    /// Nodes at that stage.
    pub nodes_at_target: Stats,
    /// Learning time to the target share of the solvable queries, seconds.
    pub time_to_solvable: Stats,
    /// Nodes at that stage.
    pub nodes_to_solvable: Stats,
    /// Intersect calls (segment + line) of learning at that stage.
    pub calls_to_solvable: Stats,
    /// State checks of learning at that stage.
    pub state_checks_to_solvable: Stats,
    /// How the runs ended (one entry per run, in run order).
    pub stops: Vec<RunStop>,
    /// Learning time at the end, seconds.
    pub learn_seconds: Stats,
    /// Nodes at the end.
    pub nodes: Stats,
    /// Edges at the end.
    pub edges: Stats,
    /// Components at the end.
    pub components: Stats,
    /// Segment calls of learning.
    pub segment_calls: Stats,
    /// Line calls of learning.
    pub line_calls: Stats,
    /// State checks of learning.
    pub state_checks: Stats,
    /// Primitive pairs tested by learning.
    pub pairs_tested: Stats,
    /// Share of the scored queries solved at the end.
    pub solved_share: Stats,
    /// Separate-group queries solved at the end.
    pub separate_solved: Stats,
    /// Returned paths found colliding, summed over runs.
    pub invalid_paths: usize,
    /// Returned paths, summed over runs (scored and separate).
    pub returned_paths: usize,
    /// Scored queries of the last evaluations that spent their call budget
    /// ([`Plan::query_calls`]), summed over runs.
    pub out_of_calls: usize,
    /// Median query latency, ms.
    pub query_p50_ms: Stats,
    /// 95th percentile latency, ms.
    pub query_p95_ms: Stats,
    /// Mean path length before shortening.
    pub path_length_raw: Stats,
    /// Mean path length after shortening.
    pub path_length: Stats,
    /// Peak resident set, MiB.
    pub peak_rss_mib: Stats,
    /// Roadmap file size, bytes.
    pub roadmap_bytes: Stats,
}

/// One scene: its queries, its method summaries in the order given, and every run.
#[derive(Clone, Debug, Serialize)]
pub struct SceneReport {
    /// The scene and its query set.
    pub info: SceneInfo,
    /// Scored queries solved (with a free path) at some stage of some run: the solvable set.
    pub solvable: Vec<usize>,
    /// Scored queries the target asks of the solvable set: `⌈target · |solvable|⌉`.
    pub solvable_needed: usize,
    /// Per method.
    pub methods: Vec<MethodSummary>,
    /// Every run.
    pub runs: Vec<RunRecord>,
}

/// A whole benchmark.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// When it started (UTC).
    pub date: String,
    /// Host name.
    pub host: String,
    /// CPU model and cores.
    pub cpu: String,
    /// The command line.
    pub command: String,
    /// viaroad's version.
    pub version: String,
    /// What was run.
    pub plan: Plan,
    /// Wall time of the whole benchmark, seconds.
    pub wall_seconds: f64,
    /// Per scene.
    pub scenes: Vec<SceneReport>,
    /// Runs that failed, with the error.
    pub failures: Vec<String>,
}

/// The first stage of `run` that solves `need` of the queries in `among`.
pub fn first_stage_solving<'r>(
    run: &'r RunRecord,
    among: &[usize],
    need: usize,
) -> Option<&'r StageRecord> {
    run.stages.iter().find(|s| {
        let bits = hex_to_bits(&s.solved_queries, run.queries);
        among.iter().filter(|&&i| bits[i]).count() >= need
    })
}

/// Scored queries of `info` solved (with a free path) at some stage of some run.
fn solvable_set(info: &SceneInfo, runs: &[RunRecord]) -> Vec<usize> {
    let mut solved_any = vec![false; info.queries];
    for r in runs {
        for s in &r.stages {
            for (i, b) in hex_to_bits(&s.solved_queries, info.queries)
                .into_iter()
                .enumerate()
            {
                solved_any[i] |= b;
            }
        }
    }
    info.scored
        .iter()
        .copied()
        .filter(|&i| solved_any[i])
        .collect()
}

impl MethodSummary {
    /// The summary of method `method`'s runs `rs` (`None` without runs), its times and nodes
    /// to `need` of the `solvable` queries.
    fn of(method: &str, rs: &[&RunRecord], solvable: &[usize], need: usize) -> Option<Self> {
        let first = rs.first()?;
        let to_solvable: Vec<Option<&StageRecord>> = rs
            .iter()
            .map(|r| first_stage_solving(r, solvable, need))
            .collect();
        let st = |f: &dyn Fn(&RunRecord) -> f64| Stats::of(rs.iter().map(|r| f(r)));
        let at =
            |f: &dyn Fn(&StageRecord) -> f64| Stats::of(to_solvable.iter().flatten().map(|s| f(s)));
        Some(MethodSummary {
            method: method.to_string(),
            local_spec: first.local_spec.clone(),
            feedback: first.feedback,
            sampler: first.sampler.clone(),
            seeding: first.seeding.clone(),
            seed_nodes: Stats::of(
                rs.iter()
                    .filter_map(|r| r.seeded.as_ref().map(|s| s.nodes as f64)),
            ),
            seed_components: Stats::of(
                rs.iter()
                    .filter_map(|r| r.seeded.as_ref().map(|s| s.components as f64)),
            ),
            seed_seconds: Stats::of(
                rs.iter()
                    .filter_map(|r| r.seeded.as_ref().map(|s| s.seconds)),
            ),
            runs: rs.len(),
            reached: rs.iter().filter(|r| r.stop == RunStop::Target).count(),
            reached_solvable: to_solvable.iter().flatten().count(),
            time_to_target: Stats::of(rs.iter().filter_map(|r| r.time_to_target)),
            nodes_at_target: Stats::of(
                rs.iter()
                    .filter_map(|r| r.nodes_at_target.map(|n| n as f64)),
            ),
            time_to_solvable: at(&|s| s.learn_seconds),
            nodes_to_solvable: at(&|s| s.nodes as f64),
            calls_to_solvable: at(&|s| s.counts.intersect_calls() as f64),
            state_checks_to_solvable: at(&|s| s.counts.state_checks as f64),
            stops: rs.iter().map(|r| r.stop).collect(),
            learn_seconds: st(&|r| r.learn_seconds),
            nodes: st(&|r| r.nodes as f64),
            edges: st(&|r| r.edges as f64),
            components: st(&|r| r.components as f64),
            segment_calls: st(&|r| r.counts.segment_calls as f64),
            line_calls: st(&|r| r.counts.line_calls as f64),
            state_checks: st(&|r| r.counts.state_checks as f64),
            pairs_tested: st(&|r| r.counts.pairs_tested as f64),
            solved_share: st(&|r| r.solved as f64 / r.scored.max(1) as f64),
            separate_solved: st(&|r| r.separate_solved as f64),
            invalid_paths: rs.iter().map(|r| r.invalid_paths).sum(),
            returned_paths: rs.iter().map(|r| r.claimed + r.separate_claimed).sum(),
            out_of_calls: rs.iter().map(|r| r.out_of_calls).sum(),
            query_p50_ms: st(&|r| r.query_p50_ms),
            query_p95_ms: st(&|r| r.query_p95_ms),
            path_length_raw: Stats::of(rs.iter().filter_map(|r| r.path_length_raw)),
            path_length: Stats::of(rs.iter().filter_map(|r| r.path_length)),
            peak_rss_mib: Stats::of(rs.iter().filter_map(|r| r.peak_rss_mib)),
            roadmap_bytes: st(&|r| r.roadmap_bytes as f64),
        })
    }
}

impl SceneReport {
    /// Summarises the runs of one scene; `methods` gives the order (labels).
    pub fn build(info: SceneInfo, methods: &[String], runs: Vec<RunRecord>, target: f64) -> Self {
        let solvable = solvable_set(&info, &runs);
        let solvable_needed = needed(target, solvable.len());
        let summaries = methods
            .iter()
            .filter_map(|m| {
                let rs: Vec<&RunRecord> = runs.iter().filter(|r| &r.method == m).collect();
                MethodSummary::of(m, &rs, &solvable, solvable_needed)
            })
            .collect();
        SceneReport {
            info,
            solvable,
            solvable_needed,
            methods: summaries,
            runs,
        }
    }

    /// Method indices ordered by time to the target share of the solvable queries: methods
    /// whose runs reached it more often first, then by median time.
    pub fn ranking_by_time(&self) -> Vec<usize> {
        self.rank(|m| m.time_to_solvable.median)
    }

    /// Method indices ordered by nodes needed, like [`ranking_by_time`](Self::ranking_by_time).
    pub fn ranking_by_nodes(&self) -> Vec<usize> {
        self.rank(|m| m.nodes_to_solvable.median)
    }

    fn rank(&self, key: impl Fn(&MethodSummary) -> Option<f64>) -> Vec<usize> {
        let mut idx: Vec<usize> = (0..self.methods.len()).collect();
        idx.sort_by(|&a, &b| {
            let (ma, mb) = (&self.methods[a], &self.methods[b]);
            let share = |m: &MethodSummary| m.reached_solvable as f64 / m.runs.max(1) as f64;
            share(mb)
                .total_cmp(&share(ma))
                .then_with(|| {
                    key(ma)
                        .unwrap_or(f64::INFINITY)
                        .total_cmp(&key(mb).unwrap_or(f64::INFINITY))
                })
                .then(a.cmp(&b))
        });
        idx
    }

    /// Pairs of methods that differ only in feedback: (index with feedback, index without).
    pub fn feedback_pairs(&self) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (i, on) in self.methods.iter().enumerate() {
            if !on.feedback {
                continue;
            }
            if let Some(j) = self.methods.iter().position(|off| {
                !off.feedback
                    && off.local_spec == on.local_spec
                    && off.sampler == on.sampler
                    && off.seeding == on.seeding
            }) {
                out.push((i, j));
            }
        }
        out
    }

    /// Pairs of methods that differ only in seeding: (index of the plain one, index of one
    /// seeded otherwise), in the order of the seeded methods (so the pairs of one plain method
    /// follow each other when seedings vary fastest, as [`super::super::Method::parse_all_crossed`]
    /// orders them).
    pub fn seeding_pairs(&self) -> Vec<(usize, usize)> {
        let plain = crate::global::Seeding::Plain.to_string();
        let mut out = Vec::new();
        for (j, seeded) in self.methods.iter().enumerate() {
            if seeded.seeding == plain {
                continue;
            }
            if let Some(i) = self.methods.iter().position(|m| {
                m.seeding == plain
                    && m.local_spec == seeded.local_spec
                    && m.sampler == seeded.sampler
                    && m.feedback == seeded.feedback
            }) {
                out.push((i, j));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_take_medians_and_ranges() {
        let s = Stats::of([3.0, 1.0, 2.0, f64::NAN]);
        assert_eq!(
            (s.n, s.median, s.min, s.max),
            (3, Some(2.0), Some(1.0), Some(3.0))
        );
        assert_eq!(Stats::of([1.0, 4.0]).median, Some(2.5));
        assert_eq!(Stats::of(std::iter::empty()).median, None);
    }

    #[test]
    fn targets_round_up() {
        assert_eq!(needed(0.99, 100), 99);
        assert_eq!(needed(0.99, 50), 50);
        assert_eq!(needed(0.99, 25), 25);
        assert_eq!(needed(0.99, 0), 0);
        assert_eq!(needed(1.0, 7), 7);
    }
}
