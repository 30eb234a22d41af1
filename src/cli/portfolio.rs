//! `viaroad solve --portfolio` (the default for arm scenes): each query planned by the stages
//! `bench mbm` runs ([`viaroad::portfolio`]): the direct path, two trees for a fifth of the
//! time, the via-point planner, the trees afresh.

use super::solve_args::{SingleQuery, SolveArgs};
use serde_json::json;
use std::time::Instant;
use viaroad::deadline::Deadline;
use viaroad::local::{path_length, LocalSpec};
use viaroad::portfolio::{Planning, Portfolio};
use viaroad::scene::Scene;

/// Runs `solve --portfolio` on the loaded `scene`.
pub fn run_portfolio(a: &SolveArgs, scene: &Scene) -> anyhow::Result<()> {
    let mut portfolio = Portfolio {
        seed: a.seed,
        ..Portfolio::default()
    };
    if let Some(tree) = &mut portfolio.tree {
        tree.max_nodes = a.nodes;
        tree.validate().map_err(anyhow::Error::msg)?;
    }
    let SingleQuery {
        time,
        queries,
        mut path_out,
    } = SingleQuery::prepare(a, scene, "trees that large do not fit in memory")?;
    let oracle = scene.oracle();
    let groups = LocalSpec::default().build().groups(&scene.space);
    let planning = Planning {
        scene,
        oracle: oracle.as_ref(),
        groups: &groups,
        straight: !a.no_straight,
    };
    for (i, q) in queries.iter().enumerate() {
        let began = Instant::now();
        let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
        let answer = portfolio.plan(&planning, (&q.start, &q.goal), &deadline);
        let secs = began.elapsed().as_secs_f64();
        let (raw, short) = match &answer.path {
            Some((raw, short)) => (Some(raw), Some(short)),
            None => (None, None),
        };
        // a stage that failed before another answered is worth a warning; with no answer it
        // is the answer
        match (&answer.error, short) {
            (Some(e), None) => anyhow::bail!("query {}: {e}", i + 1),
            (Some(e), Some(_)) => eprintln!("warning: query {}: {e}", i + 1),
            _ => {}
        }
        if let (Some(out), Some(p)) = (&mut path_out, short) {
            out.write(i, p)?;
        }
        let length = |p: &Vec<_>| path_length(&scene.space, &groups, p);
        let stage = answer.stage.map(|s| s.name());
        let calls = answer.counts.intersect_calls();
        if a.json {
            println!(
                "{}",
                json!({
                    "query": i + 1,
                    "solved": short.is_some(),
                    "stage": stage,
                    "path": raw,
                    "shortened": short,
                    "raw_length": raw.map(length),
                    "length": short.map(length),
                    "calls": calls,
                    "nodes": answer.nodes,
                    "seconds": secs,
                    "direct_seconds": answer.direct_s,
                    "grow_seconds": answer.grow_s,
                    "shorten_seconds": answer.shorten_s,
                })
            );
        } else if let (Some(raw), Some(p), Some(stage)) = (raw, short, stage) {
            println!(
                "query {}: solved ({stage}) in {secs:.3} s ({:.3} s shortening), trees of {} nodes, {calls} intersect calls, {} corners (raw {}), length {:.4} (raw {:.4})",
                i + 1,
                answer.shorten_s,
                answer.nodes,
                p.len(),
                raw.len(),
                length(p),
                length(raw),
            );
        } else {
            println!(
                "query {}: not solved in {secs:.3} s (trees of {} nodes), {calls} intersect calls",
                i + 1,
                answer.nodes,
            );
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}
