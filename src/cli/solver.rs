//! `viaroad solve` without a mode flag: each query planned by [`viaroad::solve::Solver`], the
//! portfolio suited to the scene (an arm's stages; elsewhere a cheap direct try, then trees and
//! a grown roadmap raced), so that nobody has to know in advance which planner a problem needs.

use super::solve_args::{SingleQuery, SolveArgs};
use serde_json::json;
use std::time::Instant;
use viaroad::deadline::Deadline;
use viaroad::local::path_length;
use viaroad::scene::Scene;
use viaroad::solve::Solver;

/// Runs the default `solve` on the loaded `scene`.
pub fn run_solver(a: &SolveArgs, scene: &Scene) -> anyhow::Result<()> {
    if let Some(s) = &a.sampler {
        s.validate()
            .map_err(|e| anyhow::anyhow!("--sampler {s}: {e}"))?;
    }
    let solver = Solver {
        seed: a.seed,
        nodes: a.nodes,
        straight: !a.no_straight,
        sampler: a.sampler.clone(),
        ..Solver::default()
    };
    let SingleQuery {
        time,
        queries,
        mut path_out,
    } = SingleQuery::prepare(a, scene, "trees that large do not fit in memory")?;
    let oracle = scene.oracle();
    let checker = super::query::independent_checker(scene, a.check)?;
    // lengths by the natural groups: a split planner's corners differ along one axis each,
    // and the trees' staircases move all of a body's position at once
    let groups = scene.space.groups(false);
    let length = |p: &Vec<_>| path_length(&scene.space, &groups, p);
    for (i, q) in queries.iter().enumerate() {
        let began = Instant::now();
        let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
        let s = solver
            .plan(scene, oracle.as_ref(), (&q.start, &q.goal), &deadline)
            .map_err(|e| anyhow::anyhow!("query {}: {e}", i + 1))?;
        let secs = began.elapsed().as_secs_f64();
        if let Some(w) = &s.warning {
            eprintln!("warning: query {}: {w}", i + 1);
        }
        if let (Some(out), true) = (&mut path_out, s.is_solved()) {
            out.write(i, &s.shortened)?;
        }
        let method = s.method.map(|m| m.name());
        let calls = s.counts.intersect_calls();
        let verdict = match &checker {
            Some(c) if s.is_solved() => {
                Some(super::solve_args::check_both(c, &s.raw, &s.shortened))
            }
            _ => None,
        };
        if a.json {
            let solved = s.is_solved();
            println!(
                "{}",
                json!({
                    "query": i + 1,
                    "solved": solved,
                    "method": method,
                    "path": solved.then_some(&s.raw),
                    "shortened": solved.then_some(&s.shortened),
                    "raw_length": solved.then(|| length(&s.raw)),
                    "length": solved.then(|| length(&s.shortened)),
                    "calls": calls,
                    "nodes": s.nodes,
                    "seconds": secs,
                    "certified": verdict.as_ref().map(|v| v.is_ok()),
                    "check_error": verdict.as_ref().and_then(|v| v.as_ref().err()),
                })
            );
        } else if let Some(method) = method {
            println!(
                "query {}: solved ({method}) in {secs:.3} s, {} nodes, {calls} intersect calls, {} corners (raw {}), length {:.4} (raw {:.4}){}",
                i + 1,
                s.nodes,
                s.shortened.len(),
                s.raw.len(),
                length(&s.shortened),
                length(&s.raw),
                super::solve_args::verdict_text(verdict.as_ref()),
            );
        } else {
            println!(
                "query {}: not solved in {secs:.3} s ({} nodes), {calls} intersect calls; a longer --time may solve it",
                i + 1,
                s.nodes,
            );
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}
