//! `viaroad solve`: a scene's queries answered by the local method alone.

use super::local_args::LocalArgs;
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use viaroad::local::{path_length, shorten, LocalSpec};
use viaroad::oracle::CollisionOracle;
use viaroad::scene::Scene;

/// Arguments of `solve`.
#[derive(Args)]
pub struct SolveArgs {
    /// Scene file (.toml or OMPL.app .cfg).
    pub scene: PathBuf,
    #[command(flatten)]
    pub local: LocalArgs,
    /// One JSON object per query on stdout.
    #[arg(long)]
    pub json: bool,
    /// Write each solved query's shortened path as an OMPL state file (one state per line);
    /// several queries get `-1`, `-2`, … before the extension.
    #[arg(long, value_name = "FILE")]
    pub path_out: Option<PathBuf>,
}

/// One solved query, as printed.
pub struct Solved {
    pub connection: viaroad::local::Connection,
    pub shortened: Vec<viaroad::space::Config>,
}

/// Solves one query with the local method and shortens the path.
pub fn solve_query(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    spec: &LocalSpec,
    start: &[f64],
    goal: &[f64],
) -> anyhow::Result<Solved> {
    let method = spec.build();
    let mut connection = method
        .connect(&scene.space, oracle, start, goal)
        .context("local method")?;
    let shortened = if connection.is_connected() {
        let groups = method.groups(&scene.space);
        shorten(
            &scene.space,
            oracle,
            &groups,
            &connection.path,
            &mut connection.counts,
        )
        .context("shortening")?
    } else {
        Vec::new()
    };
    Ok(Solved {
        connection,
        shortened,
    })
}

/// Runs `solve`.
pub fn run(a: SolveArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let spec = a.local.spec_or(LocalSpec::default())?;
    let oracle = scene.oracle();
    if scene.queries.is_empty() {
        anyhow::bail!("{} has no [[query]]", a.scene.display());
    }
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    let groups = spec.build().groups(&scene.space);
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
        let s = solve_query(&scene, oracle.as_ref(), &spec, &start, &goal)?;
        if let Some(out) = &mut path_out {
            out.write(i, &s.shortened)?;
        }
        let c = &s.connection;
        if a.json {
            println!(
                "{}",
                json!({
                    "solved": c.is_connected(),
                    "path": c.path,
                    "shortened": s.shortened,
                    "calls": c.counts.intersect_calls(),
                    "depth": c.depth,
                })
            );
        } else if c.is_connected() {
            println!(
                "query {}: solved, depth {}, {} intersect calls, {} corners, length {:.4} (shortened {} corners, {:.4})",
                i + 1,
                c.depth,
                c.counts.intersect_calls(),
                c.path.len(),
                path_length(&scene.space, &groups, &c.path),
                s.shortened.len(),
                path_length(&scene.space, &groups, &s.shortened),
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
