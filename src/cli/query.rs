//! `viaroad query`: answer queries against a saved roadmap.

use super::config_arg::parse_config;
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;
use viaroad::roadmap::{BatchAnswer, QueryOptions, QueryPlanner, Roadmap};
use viaroad::scene::{ompl_cfg, Scene};
use viaroad::space::Config;

/// Arguments of `query`.
#[derive(Args)]
pub struct QueryArgs {
    /// The roadmap file.
    pub roadmap: PathBuf,
    /// The scene it was learnt for (checked against the roadmap's fingerprint).
    #[arg(long)]
    pub scene: PathBuf,
    /// Start configuration (numbers separated by commas or spaces).
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "to",
        conflicts_with = "queries"
    )]
    pub from: Option<String>,
    /// Goal configuration.
    #[arg(long, allow_hyphen_values = true, requires = "from")]
    pub to: Option<String>,
    /// A file with one query per line: start then goal coordinates, whitespace separated.
    #[arg(long)]
    pub queries: Option<PathBuf>,
    /// One JSON object per query on stdout.
    #[arg(long)]
    pub json: bool,
    /// Write each solved query's path as an OMPL state file (one state per line); several
    /// queries get `-1`, `-2`, … before the extension.
    #[arg(long, value_name = "FILE")]
    pub path_out: Option<PathBuf>,
    /// Path shortening (CHS A.1): `fast` drops corners greedily on paths of more than 32
    /// corners before the visibility graph, `exact` builds the visibility graph over every
    /// corner (shortest, up to m²/2 checks), `off` returns the roadmap path as found.
    #[arg(long, value_enum, default_value_t = Shortening::Fast)]
    pub shorten: Shortening,
    /// Call budget of the quick via-point try from start to goal before the roadmap
    /// (0: only the direct path is checked).
    #[arg(long, value_name = "N")]
    pub direct_calls: Option<u64>,
    /// Landmarks guiding A* (0: the space's distance alone as the heuristic). Default: 8 for a
    /// batch of queries, 0 for a single one (they cost one graph search each, once).
    #[arg(long, value_name = "N")]
    pub landmarks: Option<usize>,
}

/// How `query` shortens paths.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Shortening {
    /// Greedy corner dropping first on long paths, then the visibility graph.
    Fast,
    /// The visibility graph over every corner.
    Exact,
    /// No shortening.
    Off,
}

/// Percentile `p` (0–1) of sorted values.
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Prints answers, one line (or JSON object) each, then a summary.
pub fn print_answers(answers: &[BatchAnswer], json_lines: bool) {
    let mut ms: Vec<f64> = Vec::with_capacity(answers.len());
    let mut solved = 0;
    for (i, a) in answers.iter().enumerate() {
        let t = a.elapsed.as_secs_f64() * 1e3;
        ms.push(t);
        match &a.result {
            Ok(r) => {
                solved += r.is_solved() as usize;
                if json_lines {
                    println!(
                        "{}",
                        json!({
                            "solved": r.is_solved(),
                            "path": r.raw_path,
                            "shortened": r.path,
                            "calls": r.counts.intersect_calls(),
                            "depth": r.depth,
                            "query_ms": t,
                            "outcome": r.outcome,
                            "length": r.length,
                            "raw_length": r.raw_length,
                        })
                    );
                } else if r.is_solved() {
                    println!(
                        "query {}: solved ({:?}), length {:.4} (raw {:.4}), {} corners, {} intersect calls, {:.3} ms",
                        i + 1,
                        r.outcome,
                        r.length,
                        r.raw_length,
                        r.path.len(),
                        r.counts.intersect_calls(),
                        t
                    );
                } else {
                    println!("query {}: not solved ({:?}), {:.3} ms", i + 1, r.outcome, t);
                }
            }
            Err(e) => {
                if json_lines {
                    println!(
                        "{}",
                        json!({ "solved": false, "error": e.to_string(), "query_ms": t })
                    );
                } else {
                    println!("query {}: error: {e}", i + 1);
                }
            }
        }
    }
    ms.sort_by(f64::total_cmp);
    if !json_lines {
        println!(
            "{solved}/{} solved; latency p50 {:.3} ms, p95 {:.3} ms",
            answers.len(),
            percentile(&ms, 0.5),
            percentile(&ms, 0.95)
        );
    }
}

/// Runs `query`.
pub fn run(a: QueryArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let t = Instant::now();
    let roadmap = Roadmap::load(&a.roadmap, scene.fingerprint())?;
    let load_ms = t.elapsed().as_secs_f64() * 1e3;
    let queries: Vec<(Config, Config)> = match (&a.from, &a.to, &a.queries) {
        (Some(f), Some(t), None) => vec![(parse_config("--from", f)?, parse_config("--to", t)?)],
        (None, None, Some(file)) => ompl_cfg::read_query_pairs(file, &scene.space)?
            .into_iter()
            .map(|q| (q.start, q.goal))
            .collect(),
        _ => anyhow::bail!("give either --from and --to, or --queries FILE"),
    };
    if let (true, Some(file)) = (queries.is_empty(), &a.queries) {
        anyhow::bail!("{}: no queries in the file", file.display());
    }
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).context("roadmap")?;
    let mut defaults = planner.options().clone();
    if let Some(n) = a.direct_calls {
        defaults.direct_calls = n;
    }
    match a.landmarks {
        Some(n) => defaults.landmarks = n,
        // landmarks cost a Dijkstra each, repaid over a batch, not by one query
        None if queries.len() == 1 => defaults.landmarks = 0,
        None => {}
    }
    let options = match a.shorten {
        Shortening::Fast => defaults,
        Shortening::Exact => QueryOptions {
            exact_shortening_limit: usize::MAX,
            ..defaults
        },
        Shortening::Off => QueryOptions {
            shorten: false,
            ..defaults
        },
    };
    let planner = planner.with_options(options);
    let mut path_out = match &a.path_out {
        Some(base) => Some(super::path_out::PathOut::new(base, queries.len())?),
        None => None,
    };
    let answers = planner.query_batch(&queries);
    if queries.len() == 1 {
        if let Err(e) = &answers[0].result {
            anyhow::bail!("{e}");
        }
    }
    // after the errors: a status line must not precede an `error:` line (issue 16)
    if !a.json {
        eprintln!(
            "loaded {} ({} nodes, {} edges) in {load_ms:.2} ms",
            a.roadmap.display(),
            roadmap.node_count(),
            roadmap.edge_count()
        );
    }
    print_answers(&answers, a.json);
    if let Some(out) = &mut path_out {
        for (i, answer) in answers.iter().enumerate() {
            if let Ok(r) = &answer.result {
                out.write(i, &r.path)?;
            }
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}
