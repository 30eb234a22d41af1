//! `viaroad solve`: a scene's queries answered by the portfolio suited to the scene
//! ([`super::solver`]), or by one planner asked for: the local method alone, a grown roadmap
//! or two trees.

use super::solve_args::{check_both, solve_query, verdict_text, SingleQuery, SolveArgs};
use anyhow::Context;
use serde_json::json;
use std::time::Instant;
use viaroad::deadline::Deadline;
use viaroad::local::{path_length, LocalSpec};
use viaroad::roadmap::{Budget, LearnParams, Learner, QueryOptions, QueryPlanner};
use viaroad::scene::Scene;

/// Runs `solve`: the mode asked for, else the portfolio suited to the scene.
pub fn run(a: SolveArgs) -> anyhow::Result<()> {
    if a.roadmap {
        return run_roadmap(a);
    }
    if a.tree {
        return run_tree(a);
    }
    if let Some(g) = &a.global {
        return super::global::run_global(&a, g);
    }
    match a.oracle.as_deref() {
        None | Some("exact") => {}
        Some("minkowski") => {
            let spec = a.local.spec_or(LocalSpec::default())?;
            return super::global::run_minkowski(&a, &spec);
        }
        Some(o) => anyhow::bail!("--oracle {o}: expected `exact` (the default) or `minkowski`"),
    }
    let scene = Scene::load(&a.scene)?;
    if a.local_alone() {
        if a.sampler.is_some() {
            anyhow::bail!("--sampler: the local method alone draws no samples");
        }
        return run_local(&a, &scene);
    }
    super::solver::run_solver(&a, &scene)
}

/// `solve --local-only`: each query connected by the local method alone, its path shortened.
fn run_local(a: &SolveArgs, scene: &Scene) -> anyhow::Result<()> {
    let spec = a.local.spec_or(LocalSpec::default_for(&scene.space))?;
    let time = super::limits::optional_seconds("--time", a.time)?;
    let oracle = scene.oracle();
    if scene.queries.is_empty() {
        anyhow::bail!("{} has no [[query]]", a.scene.display());
    }
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    let groups = spec.build().groups(&scene.space);
    let checker = super::query::independent_checker(scene, a.check)?;
    let mut path_out = match &a.path_out {
        Some(base) => Some(super::path_out::PathOut::new(base, scene.queries.len())?),
        None => None,
    };
    for (i, q) in scene.queries.iter().enumerate() {
        let start = scene.check_config(
            oracle.as_ref(),
            &format!("start of query {}", i + 1),
            &q.start,
        )?;
        let goal = scene.check_config(
            oracle.as_ref(),
            &format!("goal of query {}", i + 1),
            &q.goal,
        )?;
        let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
        let s = solve_query(scene, oracle.as_ref(), &spec, &start, &goal, &deadline)?;
        if let Some(out) = &mut path_out {
            out.write(i, &s.shortened)?;
        }
        let c = &s.connection;
        let verdict = match &checker {
            Some(ch) if c.is_connected() => Some(check_both(ch, &c.path, &s.shortened)),
            _ => None,
        };
        if a.json {
            println!(
                "{}",
                json!({
                    "solved": c.is_connected(),
                    "path": c.path,
                    "shortened": s.shortened,
                    "calls": c.counts.intersect_calls(),
                    "depth": c.depth,
                    "certified": verdict.as_ref().map(|v| v.is_ok()),
                    "check_error": verdict.as_ref().and_then(|v| v.as_ref().err()),
                })
            );
        } else if c.is_connected() {
            println!(
                "query {}: solved, depth {}, {} intersect calls, {} corners, length {:.4} (shortened {} corners, {:.4}){}",
                i + 1,
                c.depth,
                c.counts.intersect_calls(),
                c.path.len(),
                path_length(&scene.space, &groups, &c.path),
                s.shortened.len(),
                path_length(&scene.space, &groups, &s.shortened),
                verdict_text(verdict.as_ref()),
            );
        } else {
            println!(
                "query {}: not solved ({:?} at depth {}), {} intersect calls",
                i + 1,
                c.outcome,
                c.depth,
                c.counts.intersect_calls()
            );
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}

/// `solve --roadmap`: each query answered by a roadmap grown from its start and goal.
fn run_roadmap(a: SolveArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let spec = a
        .local
        .spec_or(LocalSpec::roadmap_default_for(&scene.space))?;
    let SingleQuery {
        time,
        queries,
        mut path_out,
    } = SingleQuery::prepare(&a, &scene, "a roadmap that large does not fit in memory")?;
    let oracle = scene.oracle();
    let checker = super::query::independent_checker(&scene, a.check)?;
    let method = spec.build();
    let learner = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .with_attempt_cap(time.map(Learner::attempt_cap_for));
    let groups = method.groups(&scene.space);
    let mut params = LearnParams::default();
    if let Some(share) = a.directed_share {
        params.directed_share = share;
    }
    if let Some(sampler) = &a.sampler {
        params.sampler = sampler.clone();
    }
    params.validate().map_err(anyhow::Error::msg)?;
    for (i, q) in queries.iter().enumerate() {
        let began = Instant::now();
        let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
        let grown = learner
            .connect_pair(
                &params,
                None,
                (&q.start, &q.goal),
                &Budget {
                    nodes: a.nodes,
                    time: None,
                },
                a.seed,
                &deadline,
                &mut |_| {},
            )
            .context("learning")?;
        let roadmap = &grown.learnt.roadmap;
        let mut answer = None;
        if grown.connected {
            // start and goal are nodes of one component: the query attaches them to themselves
            let planner = QueryPlanner::new(roadmap, oracle.as_ref())?.with_options(QueryOptions {
                landmarks: 0,
                grow: false,
                ..QueryOptions::default()
            });
            answer = Some(planner.query(&q.start, &q.goal)?).filter(|r| r.is_solved());
        }
        let secs = began.elapsed().as_secs_f64();
        let verdict = match (&checker, &answer) {
            (Some(c), Some(r)) => Some(check_both(c, &r.raw_path, &r.path)),
            _ => None,
        };
        let calls = roadmap.header().counts.intersect_calls()
            + answer.as_ref().map_or(0, |r| r.counts.intersect_calls());
        if let (Some(out), Some(r)) = (&mut path_out, &answer) {
            out.write(i, &r.path)?;
        }
        if a.json {
            println!(
                "{}",
                json!({
                    "query": i + 1,
                    "solved": answer.is_some(),
                    "path": answer.as_ref().map(|r| &r.raw_path),
                    "shortened": answer.as_ref().map(|r| &r.path),
                    "length": answer.as_ref().map(|r| r.length),
                    "calls": calls,
                    "nodes": roadmap.node_count(),
                    "edges": roadmap.edge_count(),
                    "seconds": secs,
                    "stop": format!("{:?}", grown.learnt.report.stop),
                    "certified": verdict.as_ref().map(|v| v.is_ok()),
                    "check_error": verdict.as_ref().and_then(|v| v.as_ref().err()),
                })
            );
        } else if let Some(r) = &answer {
            println!(
                "query {}: solved by a roadmap of {} nodes in {secs:.3} s, {calls} intersect calls, {} corners, length {:.4} (raw {:.4}){}",
                i + 1,
                roadmap.node_count(),
                r.path.len(),
                path_length(&scene.space, &groups, &r.path),
                r.raw_length,
                verdict_text(verdict.as_ref()),
            );
        } else {
            println!(
                "query {}: not solved in {secs:.3} s ({:?}; roadmap of {} nodes, {} components), {calls} intersect calls",
                i + 1,
                grown.learnt.report.stop,
                roadmap.node_count(),
                roadmap.component_count(),
            );
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}

/// The trees' parameters `a` asks for in `space`.
fn tree_params(a: &SolveArgs, space: &viaroad::space::Space) -> viaroad::roadmap::tree::TreeParams {
    use viaroad::roadmap::tree::{Domain, Stairs, TreeParams};
    // centring and coarse extends need partial stairs
    let stairs = a
        .tree_stairs
        .unwrap_or(if a.tree_centre > 0 || a.tree_coarse {
            Stairs::Prefix
        } else {
            Stairs::Whole
        });
    TreeParams {
        range: a.tree_range,
        stair: a.tree_stair,
        prefix: a.tree_prefix,
        balance: a.tree_balance.unwrap_or(stairs == Stairs::Whole),
        centre: a.tree_centre,
        centre_turn: a.tree_centre_turn,
        coarse: a.tree_coarse,
        max_nodes: a.nodes,
        restart: a.tree_restart,
        streams: a.tree_streams,
        stairs,
        straight: !a.no_straight,
        staircase: true,
        domain: match a.tree_domain {
            Some(radius) => Domain::with_radius(radius),
            None => TreeParams::for_space(space).domain,
        },
    }
}

/// `solve --tree`: each query answered by RRT-Connect with exact single-group extends.
fn run_tree(a: SolveArgs) -> anyhow::Result<()> {
    use viaroad::roadmap::tree::{rrt_connect, shortcut};
    let scene = Scene::load(&a.scene)?;
    let params = tree_params(&a, &scene.space);
    params.validate().map_err(anyhow::Error::msg)?;
    // checked before the path files are prepared (which removes those of earlier runs)
    let SingleQuery {
        time,
        queries,
        mut path_out,
    } = SingleQuery::prepare(&a, &scene, "trees that large do not fit in memory")?;
    let oracle = scene.oracle();
    let groups = scene.space.groups(false);
    let checker = super::query::independent_checker(&scene, a.check)?;
    for (i, q) in queries.iter().enumerate() {
        let began = Instant::now();
        let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
        let found = rrt_connect(
            &scene.space,
            oracle.as_ref(),
            &groups,
            &q.start,
            &q.goal,
            &params,
            a.seed,
            &deadline,
        )
        .context("growing trees")?;
        let grow_secs = began.elapsed().as_secs_f64();
        let mut counts = found.counts;
        // shortcutting gets what is left of the budget (none left: the raw path, also free)
        let short_deadline = deadline.clone();
        let shortened = match &found.path {
            Some(p) => Some(
                shortcut(
                    &scene.space,
                    oracle.as_ref(),
                    &groups,
                    p,
                    32,
                    &mut counts,
                    &short_deadline,
                )
                .context("shortcutting")?,
            ),
            None => None,
        };
        let secs = began.elapsed().as_secs_f64();
        if let (Some(out), Some(p)) = (&mut path_out, &shortened) {
            out.write(i, p)?;
        }
        let verdict = match (&checker, &found.path, &shortened) {
            (Some(c), Some(raw), Some(p)) => Some(check_both(c, raw, p)),
            _ => None,
        };
        let length = shortened
            .as_ref()
            .map(|p| path_length(&scene.space, &groups, p));
        if a.json {
            println!(
                "{}",
                json!({
                    "query": i + 1,
                    "solved": found.path.is_some(),
                    "path": found.path,
                    "shortened": shortened,
                    "length": length,
                    "calls": counts.intersect_calls(),
                    "nodes": found.nodes[0] + found.nodes[1],
                    "start_tree": found.nodes[0],
                    "goal_tree": found.nodes[1],
                    "extends": found.extends,
                    "attempts": found.attempts,
                    "seconds": secs,
                    "grow_seconds": grow_secs,
                    "stop": format!("{:?}", found.stop),
                    "certified": verdict.as_ref().map(|v| v.is_ok()),
                    "check_error": verdict.as_ref().and_then(|v| v.as_ref().err()),
                })
            );
        } else if let (Some(raw), Some(p)) = (&found.path, &shortened) {
            let attempt = match found.attempts {
                1 => String::new(),
                n => format!(" (attempt {n})"),
            };
            println!(
                "query {}: solved by trees of {} + {} nodes{attempt} in {secs:.3} s ({grow_secs:.3} s growing), {} intersect calls, {} corners (raw {}), length {:.4}{}",
                i + 1,
                found.nodes[0],
                found.nodes[1],
                counts.intersect_calls(),
                p.len(),
                raw.len(),
                length.unwrap_or(0.0),
                verdict_text(verdict.as_ref()),
            );
        } else {
            println!(
                "query {}: not solved in {secs:.3} s ({:?}; {} attempt(s), the last with trees of {} + {} nodes; {} extends), {} intersect calls",
                i + 1,
                found.stop,
                found.attempts,
                found.nodes[0],
                found.nodes[1],
                found.extends,
                counts.intersect_calls(),
            );
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}
