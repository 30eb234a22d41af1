//! The machine-readable outputs of a benchmark report: one CSV row per run, and JSON of
//! everything.

use super::super::run::SeedRecord;
use super::{first_stage_solving, Report};
use std::fmt::Write as _;

impl Report {
    /// One CSV row per run.
    pub fn csv(&self) -> String {
        let mut o = String::from(
            "scene,method,local_spec,feedback,sampler,run,seed,threads,stop,queries,scored,separate,invalid_queries,needed,time_to_target_s,nodes_at_target,time_to_solvable_s,nodes_to_solvable,nodes,edges,components,learn_s,segment_calls,line_calls,state_checks,pairs_tested,attempts,connected,solved,claimed,invalid_paths,invalid_raw_paths,separate_solved,query_p50_ms,query_p95_ms,query_mean_ms,path_length_raw,path_length,roadmap_bytes,peak_rss_mib,wall_s,stages,query_calls,out_of_calls,seeding,freeways,seed_nodes,seed_edges,seed_components,seed_s,seed_intersect_calls\n",
        );
        let opt = |v: Option<f64>| v.map(|x| x.to_string()).unwrap_or_default();
        for s in &self.scenes {
            for r in &s.runs {
                let at = first_stage_solving(r, &s.solvable, s.solvable_needed);
                let seed = |f: &dyn Fn(&SeedRecord) -> String| -> String {
                    r.seeded.as_ref().map(f).unwrap_or_default()
                };
                let _ = writeln!(
                    o,
                    "\"{}\",\"{}\",\"{}\",{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\",{},{},{},{},{},{}",
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
                    r.stages.len(),
                    r.query_calls.map(|c| c.to_string()).unwrap_or_default(),
                    r.out_of_calls,
                    r.seeding,
                    seed(&|s| s.freeways.to_string()),
                    seed(&|s| s.nodes.to_string()),
                    seed(&|s| s.edges.to_string()),
                    seed(&|s| s.components.to_string()),
                    seed(&|s| s.seconds.to_string()),
                    seed(&|s| s.counts.intersect_calls().to_string()),
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
