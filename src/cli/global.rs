//! `viaroad solve --global cones` and `viaroad solve --oracle minkowski`: a scene's queries
//! answered by the methods of the project's other seeds, printed like `solve`'s.

use super::solve_args::SolveArgs;
use anyhow::Context;
use serde_json::json;
use std::time::Instant;
use viaroad::deadline::Deadline;
use viaroad::global::cones::{ConeOutcome, Freeways};
use viaroad::local::{path_length, LocalSpec};
use viaroad::oracle::minkowski::Minkowski;
use viaroad::oracle::Bounded;
use viaroad::scene::{Robot, Scene};
use viaroad::space::Space;

/// `solve --global METHOD`.
pub fn run_global(a: &SolveArgs, method: &str) -> anyhow::Result<()> {
    if method != "cones" {
        anyhow::bail!("--global {method}: the global methods are `cones` (Brooks's freeways)");
    }
    let scene = Scene::load(&a.scene)?;
    let queries = scene.checked_queries()?;
    if queries.is_empty() {
        anyhow::bail!("{} has no [[query]]", a.scene.display());
    }
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    let began = Instant::now();
    let fw = Freeways::build(&scene).context("generalized cones")?;
    let build_secs = began.elapsed().as_secs_f64();
    if !a.json {
        println!(
            "freeways: {} cones from {} candidate edge pairs, {} spine intersections, built in {build_secs:.3} s",
            fw.cones().len(),
            fw.candidates(),
            fw.crossings().len()
        );
    }
    let oracle = scene.oracle();
    let mut path_out = match &a.path_out {
        Some(base) => Some(super::path_out::PathOut::new(base, queries.len())?),
        None => None,
    };
    for (i, q) in queries.iter().enumerate() {
        let t = Instant::now();
        let out = fw.solve(&scene, oracle.as_ref(), &q.start, &q.goal)?;
        let secs = t.elapsed().as_secs_f64();
        if let (Some(o), Some(p)) = (&mut path_out, out.path()) {
            o.write(i, &p.path)?;
        }
        if a.json {
            println!(
                "{}",
                json!({
                    "query": i + 1,
                    "solved": out.path().is_some(),
                    "path": out.path().map(|p| &p.path),
                    "length": out.path().map(|p| p.length),
                    "cones": fw.cones().len(),
                    "seconds": secs,
                    "build_seconds": build_secs,
                    "reason": match &out { ConeOutcome::NotFound(r) => Some(r), _ => None },
                })
            );
        } else {
            match &out {
                ConeOutcome::Solved(p) => println!(
                    "query {}: solved along {} freeways in {secs:.3} s, {} corners, length {:.4}",
                    i + 1,
                    p.cones.len(),
                    p.path.len(),
                    p.length
                ),
                ConeOutcome::NotFound(why) => {
                    println!("query {}: not solved in {secs:.3} s: {why}", i + 1)
                }
            }
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}

/// `solve --oracle minkowski`: the robot keeps each query's start orientation and translates,
/// the local method runs in the plane of positions with the C-obstacle oracle.
pub fn run_minkowski(a: &SolveArgs, spec: &LocalSpec) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let Robot::Polygons(robot) = &scene.robot else {
        anyhow::bail!("--oracle minkowski needs an se2 scene with a polygonal robot");
    };
    let queries = scene.checked_queries()?;
    if queries.is_empty() {
        anyhow::bail!("{} has no [[query]]", a.scene.display());
    }
    let obstacles = scene.polygon_obstacles();
    let (lo, hi) = (scene.space.lower(), scene.space.upper());
    let plane = Space::euclidean(lo[..2].to_vec(), hi[..2].to_vec())?;
    let translating = Scene {
        space: plane.clone(),
        queries: Vec::new(),
        ..scene.clone()
    };
    let time = super::limits::optional_seconds("--time", a.time)?;
    let groups = spec.build().groups(&plane);
    let mut path_out = match &a.path_out {
        Some(base) => Some(super::path_out::PathOut::new(base, queries.len())?),
        None => None,
    };
    for (i, q) in queries.iter().enumerate() {
        let theta = q.start[2];
        let turn = (q.goal[2] - theta).sin().abs() + (1.0 - (q.goal[2] - theta).cos());
        if turn > 1e-12 {
            println!(
                "query {}: not solvable with --oracle minkowski: the robot turns from {theta} to {} (C-obstacles are for a translating robot)",
                i + 1,
                q.goal[2]
            );
            continue;
        }
        let t = Instant::now();
        let oracle = Bounded::new(plane.clone(), Minkowski::new(robot, &obstacles, theta));
        let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
        let s = super::solve_args::solve_query(
            &translating,
            &oracle,
            spec,
            &q.start[..2],
            &q.goal[..2],
            &deadline,
        )?;
        let secs = t.elapsed().as_secs_f64();
        let lift = |p: &[Vec<f64>]| -> Vec<Vec<f64>> {
            p.iter().map(|c| vec![c[0], c[1], theta]).collect()
        };
        let shortened = lift(&s.shortened);
        if let Some(out) = &mut path_out {
            out.write(i, &shortened)?;
        }
        let c = &s.connection;
        if a.json {
            println!(
                "{}",
                json!({
                    "query": i + 1,
                    "solved": c.is_connected(),
                    "path": lift(&c.path),
                    "shortened": shortened,
                    "calls": c.counts.intersect_calls(),
                    "seconds": secs,
                })
            );
        } else if c.is_connected() {
            println!(
                "query {}: solved translating at θ = {theta:.4} in {secs:.3} s, {} intersect calls, length {:.4} (shortened {} corners, {:.4})",
                i + 1,
                c.counts.intersect_calls(),
                path_length(&plane, &groups, &c.path),
                s.shortened.len(),
                path_length(&plane, &groups, &s.shortened),
            );
        } else {
            println!(
                "query {}: not solved translating ({:?}), {} intersect calls",
                i + 1,
                c.outcome,
                c.counts.intersect_calls()
            );
        }
    }
    if let Some(out) = path_out {
        out.finish();
    }
    Ok(())
}

/// `build --seed-from cones`: the roadmap starts from the spine points of Brooks's freeways
/// (checked by the oracle), then learning grows it to the budget as usual.
pub fn learn_seeded(
    scene: &Scene,
    seeding: viaroad::global::Seeding,
    local: &super::local_args::LocalArgs,
    learn: &super::learn_args::LearnArgs,
    default_nodes: usize,
) -> anyhow::Result<viaroad::roadmap::Learnt> {
    let spec = local.spec_or(LocalSpec::roadmap_default())?;
    let (params, budget) = learn.resolve(default_nodes)?;
    let method = spec.build();
    let oracle = scene.oracle();
    let seeded = seeding
        .seed_roadmap(
            scene,
            oracle.as_ref(),
            &params,
            &spec,
            learn.seed,
            // half a node budget at most: the learner grows the rest
            budget
                .nodes
                .map_or(viaroad::global::cones::seeds::MAX_SEED_NODES, |n| n / 2),
        )
        .with_context(|| format!("seeding from {seeding}"))?
        .ok_or_else(|| anyhow::anyhow!("seeding `{seeding}` gives no seed roadmap"))?;
    let base = &seeded.roadmap;
    eprintln!(
        "seeded from {} freeways: {} nodes, {} edges, {} components in {:.3} s",
        seeded.freeways,
        base.node_count(),
        base.edge_count(),
        base.component_count(),
        seeded.elapsed.as_secs_f64()
    );
    let learner = viaroad::roadmap::Learner::for_scene(scene, oracle.as_ref(), method.as_ref())
        .with_attempt_cap(budget.time.map(viaroad::roadmap::Learner::attempt_cap_for));
    let deadline = super::interrupt::on_ctrl_c(Deadline::none());
    let learnt = learner
        .learn_from(base, &params, &budget, learn.seed, &deadline, &mut |_| {})
        .context("learning")?;
    Ok(learnt)
}
