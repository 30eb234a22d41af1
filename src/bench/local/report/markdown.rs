//! The Markdown summary of a benchmark report (printed on stdout and saved as `summary.md`).

use super::super::run::RunStop;
use super::{Report, SceneReport, Stats};
use std::fmt::Write as _;

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
        if let Some(calls) = p.query_calls {
            let _ = writeln!(
                o,
                "A query may spend at most {calls} intersect calls (`--query-calls`; shortening a path found aside): queries that spend them count as unsolved.\n"
            );
        }
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
        self.ranking_table(o, s);
        self.end_table(o, s);
        self.feedback_table(o, s);
        self.seeding_table(o, s);
    }

    /// What the cone seeds are worth: methods that differ only in seeding, side
    /// by side.
    fn seeding_table(&self, o: &mut String, s: &SceneReport) {
        let pct = 100.0 * self.plan.target;
        let pairs = s.seeding_pairs();
        if pairs.is_empty() {
            return;
        }
        let _ = writeln!(
            o,
            "\nWhat the seeds are worth: the same method learnt from nothing and from the seed roadmap, medians; learning time and calls of a seeded run include building and checking its seeds:\n"
        );
        let _ = writeln!(
            o,
            "| method | seeding | seed nodes | seed comps | seed s | reached | time→{pct:.0} % s | nodes→{pct:.0} % | calls→{pct:.0} % | comps at end | solved % | path short |"
        );
        let _ = writeln!(o, "|{}", "---|".repeat(12));
        // each plain method once, followed by its seeded variants
        let mut shown = None;
        for (a, b) in pairs {
            let rows = if shown == Some(a) {
                vec![b]
            } else {
                vec![a, b]
            };
            shown = Some(a);
            for m in rows.into_iter().map(|k| &s.methods[k]) {
                let _ = writeln!(
                    o,
                    "| {} | {} | {} | {} | {} | {}/{} | {} | {} | {} | {} | {} | {} |",
                    m.method,
                    m.seeding,
                    num(m.seed_nodes.median),
                    num(m.seed_components.median),
                    num(m.seed_seconds.median),
                    m.reached_solvable,
                    m.runs,
                    range(&m.time_to_solvable),
                    range(&m.nodes_to_solvable),
                    num(m.calls_to_solvable.median),
                    num(m.components.median),
                    num(m.solved_share.median.map(|x| 100.0 * x)),
                    num(m.path_length.median),
                );
            }
        }
    }

    /// The methods ranked by learning time to the target share of the solvable queries.
    fn ranking_table(&self, o: &mut String, s: &SceneReport) {
        let pct = 100.0 * self.plan.target;
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
    }

    /// Each method at the end of its runs.
    fn end_table(&self, o: &mut String, s: &SceneReport) {
        let i = &s.info;
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
        if self.plan.query_calls.is_some() {
            let _ = writeln!(o);
            for m in s.methods.iter().filter(|m| m.out_of_calls > 0) {
                let _ = writeln!(
                    o,
                    "{}: {} scored queries of the last evaluations spent their call budget.",
                    m.method, m.out_of_calls
                );
            }
        }
    }

    /// What feedback is worth: methods that differ only in feedback, side by side.
    fn feedback_table(&self, o: &mut String, s: &SceneReport) {
        let pct = 100.0 * self.plan.target;
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_ranges_read_well() {
        assert_eq!(range(&Stats::of([1.0, 4.0])), "2.50 [1–4]");
        assert_eq!(num(Some(123456.0)), "123.5k");
        assert_eq!(num(None), "—");
        assert_eq!(num(Some(0.5)), "0.500");
        assert_eq!(num(Some(0.00123)), "0.00123");
        assert_eq!(num(Some(1e-9)), "0.000000");
    }
}
