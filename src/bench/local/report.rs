//! Summaries of a local-method benchmark: per scene × method over the runs, rankings by time
//! and by nodes to 99 % of the queries, what feedback is worth; Markdown, CSV and JSON.

use super::queries::{QueryRole, QuerySet};
use super::run::{hex_to_bits, target_count as needed, RunRecord, RunStop, StageRecord};
use super::spec::Plan;
use serde::Serialize;
use std::fmt::Write as _;

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

impl SceneReport {
    /// Summarises the runs of one scene; `methods` gives the order (labels).
    pub fn build(info: SceneInfo, methods: &[String], runs: Vec<RunRecord>, target: f64) -> Self {
        let mut solved_any = vec![false; info.queries];
        for r in &runs {
            for s in &r.stages {
                for (i, b) in hex_to_bits(&s.solved_queries, info.queries)
                    .into_iter()
                    .enumerate()
                {
                    solved_any[i] |= b;
                }
            }
        }
        let solvable: Vec<usize> = info
            .scored
            .iter()
            .copied()
            .filter(|&i| solved_any[i])
            .collect();
        let solvable_needed = needed(target, solvable.len());
        let summaries = methods
            .iter()
            .filter_map(|m| {
                let rs: Vec<&RunRecord> = runs.iter().filter(|r| &r.method == m).collect();
                let first = rs.first()?;
                let to_solvable: Vec<Option<&StageRecord>> = rs
                    .iter()
                    .map(|r| first_stage_solving(r, &solvable, solvable_needed))
                    .collect();
                let st = |f: &dyn Fn(&RunRecord) -> f64| Stats::of(rs.iter().map(|r| f(r)));
                let at = |f: &dyn Fn(&StageRecord) -> f64| {
                    Stats::of(to_solvable.iter().flatten().map(|s| f(s)))
                };
                Some(MethodSummary {
                    method: m.clone(),
                    local_spec: first.local_spec.clone(),
                    feedback: first.feedback,
                    sampler: first.sampler.clone(),
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
                    query_p50_ms: st(&|r| r.query_p50_ms),
                    query_p95_ms: st(&|r| r.query_p95_ms),
                    path_length_raw: Stats::of(rs.iter().filter_map(|r| r.path_length_raw)),
                    path_length: Stats::of(rs.iter().filter_map(|r| r.path_length)),
                    peak_rss_mib: Stats::of(rs.iter().filter_map(|r| r.peak_rss_mib)),
                    roadmap_bytes: st(&|r| r.roadmap_bytes as f64),
                })
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
                !off.feedback && off.local_spec == on.local_spec && off.sampler == on.sampler
            }) {
                out.push((i, j));
            }
        }
        out
    }
}

/// A number for a table: `—` for none, otherwise a sensible number of digits.
fn num(v: Option<f64>) -> String {
    match v {
        None => "—".into(),
        Some(0.0) => "0".into(),
        Some(x) if x.abs() >= 1e6 => format!("{:.2}M", x / 1e6),
        Some(x) if x.abs() >= 1e4 => format!("{:.1}k", x / 1e3),
        Some(x) if x.abs() >= 100.0 || x.fract() == 0.0 => format!("{x:.0}"),
        Some(x) if x.abs() >= 1.0 => format!("{x:.2}"),
        // three significant digits, so millisecond learning times still compare
        Some(x) => {
            let decimals = (2 - x.abs().log10().floor() as i32).clamp(3, 6) as usize;
            format!("{x:.decimals$}")
        }
    }
}

/// `median [min–max]` of a statistic (just the median for a single run).
fn range(s: &Stats) -> String {
    match (s.median, s.min, s.max) {
        (Some(m), Some(lo), Some(hi)) if s.n > 1 && lo != hi => {
            format!("{} [{}–{}]", num(Some(m)), num(Some(lo)), num(Some(hi)))
        }
        (m, _, _) => num(m),
    }
}

fn ratio(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.2}×", a / b),
        _ => "—".into(),
    }
}

impl Report {
    /// The Markdown summary printed on stdout.
    pub fn markdown(&self) -> String {
        let mut o = String::new();
        let p = &self.plan;
        let _ = writeln!(o, "## viaroad bench local — {} UTC\n", self.date);
        let _ = writeln!(
            o,
            "viaroad {} on {} ({}), {:.1} s wall. `{}`\n",
            self.version, self.host, self.cpu, self.wall_seconds, self.command
        );
        let stages = p.schedule.stages();
        let _ = writeln!(
            o,
            "{} run(s) per scene and method, seed {} (run r learns with seed {} + r); node stages {} … {} ({} stages, ×{:.3}); learning time limit {}; a run stops at {:.0} % of its scored queries; queries {}.\n",
            p.runs,
            p.seed,
            p.seed,
            stages.first().copied().unwrap_or(0),
            stages.last().copied().unwrap_or(0),
            stages.len(),
            p.schedule.growth,
            p.time_limit.map_or("none".to_string(), |t| format!("{t} s")),
            100.0 * p.target,
            if p.direct {
                format!(
                    "first try the local method from start to goal, then attach to the roadmap (up to {} nearest nodes a side)",
                    p.attach
                )
            } else {
                format!(
                    "use the roadmap only, no direct try (attach to up to {} nearest nodes a side)",
                    p.attach
                )
            }
        );
        let _ = writeln!(
            o,
            "{}\n",
            match p.escalation {
                0 => "Queries use each run's own local method only (no escalation to the deep via-point planner).".to_string(),
                n => format!("Via-point roadmaps retry failed queries with the deep via-point planner (up to {n} nearest nodes a side), as `viaroad query` does; other methods do not."),
            }
        );
        for s in &self.scenes {
            self.scene_markdown(&mut o, s);
        }
        if !self.failures.is_empty() {
            let _ = writeln!(o, "\n### Failed runs\n");
            for f in &self.failures {
                let _ = writeln!(o, "- {f}");
            }
        }
        o
    }

    fn scene_markdown(&self, o: &mut String, s: &SceneReport) {
        let i = &s.info;
        let pct = 100.0 * self.plan.target;
        let _ = writeln!(o, "\n### {} (`{}`)\n", i.name, i.source);
        let _ = write!(
            o,
            "Queries: {} — {} in all, {} scored",
            i.query_source,
            i.queries,
            i.scored.len()
        );
        if !i.separate.is_empty() {
            let _ = write!(
                o,
                ", {} apart ({})",
                i.separate.len(),
                i.separate_group.as_deref().unwrap_or("separate group")
            );
        }
        if !i.invalid.is_empty() {
            let _ = write!(o, ", {} invalid under our oracle", i.invalid.len());
        }
        let _ = writeln!(
            o,
            ". Solved by some run (the solvable set): {} of {}; {pct:.0} % of them = {}.\n",
            s.solvable.len(),
            i.scored.len(),
            s.solvable_needed
        );
        let by_nodes = s.ranking_by_nodes();
        let _ = writeln!(
            o,
            "Ranked by learning time to {pct:.0} % of the solvable queries (median [min–max] over the runs that got there):\n"
        );
        let _ = writeln!(
            o,
            "| rank | method | reached | time→{pct:.0} % s | nodes→{pct:.0} % | rank by nodes | intersect calls→{pct:.0} % | state checks→{pct:.0} % |"
        );
        let _ = writeln!(o, "|---|---|---|---|---|---|---|---|");
        for (rank, &k) in s.ranking_by_time().iter().enumerate() {
            let m = &s.methods[k];
            let node_rank = by_nodes.iter().position(|&x| x == k).unwrap_or(0) + 1;
            let _ = writeln!(
                o,
                "| {} | {} | {}/{} | {} | {} | {} | {} | {} |",
                rank + 1,
                m.method,
                m.reached_solvable,
                m.runs,
                range(&m.time_to_solvable),
                range(&m.nodes_to_solvable),
                node_rank,
                num(m.calls_to_solvable.median),
                num(m.state_checks_to_solvable.median)
            );
        }
        let _ = writeln!(o, "\nAt the end of each run (medians over runs):\n");
        let _ = writeln!(
            o,
            "| method | ended | nodes | edges | comps | learn s | segment calls | line calls | state checks | pairs tested | solved % | apart solved | invalid paths | query p50 ms | p95 ms | path raw | path short | RSS MiB |"
        );
        let _ = writeln!(o, "|{}", "---|".repeat(18));
        for m in &s.methods {
            let mut ends: Vec<String> = Vec::new();
            for stop in [
                RunStop::Target,
                RunStop::NodeCap,
                RunStop::TimeLimit,
                RunStop::Stalled,
            ] {
                let n = m.stops.iter().filter(|&&x| x == stop).count();
                if n == m.stops.len() {
                    ends.push(stop.description().to_string());
                } else if n > 0 {
                    ends.push(format!("{n}× {}", stop.description()));
                }
            }
            let _ = writeln!(
                o,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {}/{} | {} | {} | {} | {} | {} |",
                m.method,
                ends.join(", "),
                num(m.nodes.median),
                num(m.edges.median),
                num(m.components.median),
                num(m.learn_seconds.median),
                num(m.segment_calls.median),
                num(m.line_calls.median),
                num(m.state_checks.median),
                num(m.pairs_tested.median),
                num(m.solved_share.median.map(|x| 100.0 * x)),
                if i.separate.is_empty() {
                    "—".to_string()
                } else {
                    format!("{}/{}", num(m.separate_solved.median), i.separate.len())
                },
                m.invalid_paths,
                m.returned_paths,
                num(m.query_p50_ms.median),
                num(m.query_p95_ms.median),
                num(m.path_length_raw.median),
                num(m.path_length.median),
                num(m.peak_rss_mib.median)
            );
        }
        let pairs = s.feedback_pairs();
        if !pairs.is_empty() {
            let _ = writeln!(
                o,
                "\nWhat feedback of via points and free segments is worth (CHS §1.6), medians to {pct:.0} % of the solvable queries:\n"
            );
            let _ = writeln!(
                o,
                "| method | time on | time off | off/on | nodes on | nodes off | off/on | calls on | calls off | off/on |"
            );
            let _ = writeln!(o, "|---|---|---|---|---|---|---|---|---|---|");
            for (a, b) in pairs {
                let (on, off) = (&s.methods[a], &s.methods[b]);
                let _ = writeln!(
                    o,
                    "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                    on.method,
                    num(on.time_to_solvable.median),
                    num(off.time_to_solvable.median),
                    ratio(off.time_to_solvable.median, on.time_to_solvable.median),
                    num(on.nodes_to_solvable.median),
                    num(off.nodes_to_solvable.median),
                    ratio(off.nodes_to_solvable.median, on.nodes_to_solvable.median),
                    num(on.calls_to_solvable.median),
                    num(off.calls_to_solvable.median),
                    ratio(off.calls_to_solvable.median, on.calls_to_solvable.median),
                );
            }
        }
    }

    /// One CSV row per run.
    pub fn csv(&self) -> String {
        let mut o = String::from(
            "scene,method,local_spec,feedback,sampler,run,seed,threads,stop,queries,scored,separate,invalid_queries,needed,time_to_target_s,nodes_at_target,time_to_solvable_s,nodes_to_solvable,nodes,edges,components,learn_s,segment_calls,line_calls,state_checks,pairs_tested,attempts,connected,solved,claimed,invalid_paths,invalid_raw_paths,separate_solved,query_p50_ms,query_p95_ms,query_mean_ms,path_length_raw,path_length,roadmap_bytes,peak_rss_mib,wall_s,stages\n",
        );
        let opt = |v: Option<f64>| v.map(|x| x.to_string()).unwrap_or_default();
        for s in &self.scenes {
            for r in &s.runs {
                let at = first_stage_solving(r, &s.solvable, s.solvable_needed);
                let _ = writeln!(
                    o,
                    "\"{}\",\"{}\",\"{}\",{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                    r.scene,
                    r.method,
                    r.local_spec,
                    r.feedback,
                    r.sampler,
                    r.run,
                    r.seed,
                    r.threads,
                    r.stop.description(),
                    r.queries,
                    r.scored,
                    r.separate,
                    r.invalid_queries,
                    r.needed,
                    opt(r.time_to_target),
                    opt(r.nodes_at_target.map(|n| n as f64)),
                    opt(at.map(|s| s.learn_seconds)),
                    opt(at.map(|s| s.nodes as f64)),
                    r.nodes,
                    r.edges,
                    r.components,
                    r.learn_seconds,
                    r.counts.segment_calls,
                    r.counts.line_calls,
                    r.counts.state_checks,
                    r.counts.pairs_tested,
                    r.attempts,
                    r.connected,
                    r.solved,
                    r.claimed,
                    r.invalid_paths,
                    r.invalid_raw_paths,
                    r.separate_solved,
                    r.query_p50_ms,
                    r.query_p95_ms,
                    r.query_mean_ms,
                    opt(r.path_length_raw),
                    opt(r.path_length),
                    r.roadmap_bytes,
                    opt(r.peak_rss_mib),
                    r.wall_seconds,
                    r.stages.len()
                );
            }
        }
        o
    }

    /// The whole report as JSON (every run with its stages).
    pub fn json(&self) -> Result<String, serde_json::Error> {
        serde_json::to_string_pretty(self)
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
        assert_eq!(range(&Stats::of([1.0, 4.0])), "2.50 [1–4]");
        assert_eq!(num(Some(123456.0)), "123.5k");
        assert_eq!(num(None), "—");
        assert_eq!(num(Some(0.5)), "0.500");
        assert_eq!(num(Some(0.00123)), "0.00123");
        assert_eq!(num(Some(1e-9)), "0.000000");
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
