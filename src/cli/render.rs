//! `viaroad render`: a picture of a scene and one query solved by the local method, with the
//! borderlines and via points it tried.

use super::local_args::LocalArgs;
use super::solve::solve_query;
use anyhow::Context;
use clap::Args;
use std::path::PathBuf;
use viaroad::local::LocalSpec;
use viaroad::render::Picture;
use viaroad::scene::Scene;

/// Arguments of `render`.
#[derive(Args)]
pub struct RenderArgs {
    /// Scene file.
    pub scene: PathBuf,
    /// Output SVG file.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Which of the scene's queries to solve and draw (1-based); 0 draws the scene only.
    #[arg(long, default_value_t = 1)]
    pub query: usize,
    #[command(flatten)]
    pub local: LocalArgs,
    /// Draw Brooks's freeways (generalized cones and their spines) and solve the query along
    /// them instead of with the local method (issue 14).
    #[arg(long)]
    pub freeways: bool,
}

/// Runs `render`.
pub fn run(a: RenderArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let mut spec = a.local.spec_or(LocalSpec::default())?;
    if let LocalSpec::ViaPoint(o) = &mut spec {
        o.trace = true;
    }
    // refused before the solving, not after it
    viaroad::safe_file::resolve_target(&a.output)?;
    let mut status = None;
    let mut picture = Picture::new(&scene);
    picture.obstacles(&scene);
    if a.freeways {
        let fw = viaroad::global::cones::Freeways::build(&scene).context("generalized cones")?;
        picture.freeways(&fw);
        if let Some(q) = a.query.checked_sub(1).and_then(|i| scene.queries.get(i)) {
            let oracle = scene.oracle();
            let start = scene.check_config(oracle.as_ref(), "start", &q.start)?;
            let goal = scene.check_config(oracle.as_ref(), "goal", &q.goal)?;
            match fw.solve(&scene, oracle.as_ref(), &start, &goal)? {
                viaroad::global::cones::ConeOutcome::Solved(p) => {
                    picture.path(&scene, &p.path, false);
                    status = Some(format!(
                        "query {}: solved along the freeways, length {:.4}",
                        a.query, p.length
                    ));
                }
                viaroad::global::cones::ConeOutcome::NotFound(why) => {
                    status = Some(format!(
                        "query {}: not solved along the freeways: {why}",
                        a.query
                    ));
                }
            }
        }
    } else if a.query > 0 {
        let q = scene.queries.get(a.query - 1).with_context(|| {
            format!(
                "{} has {} queries, not {}",
                a.scene.display(),
                scene.queries.len(),
                a.query
            )
        })?;
        let oracle = scene.oracle();
        let start = scene.check_config(oracle.as_ref(), "start", &q.start)?;
        let goal = scene.check_config(oracle.as_ref(), "goal", &q.goal)?;
        let s = solve_query(
            &scene,
            oracle.as_ref(),
            &spec,
            &start,
            &goal,
            &viaroad::deadline::Deadline::none(),
        )?;
        picture
            .borderlines(&s.connection.borderlines)
            .path(&scene, &s.connection.path, false)
            .path(&scene, &s.shortened, true);
        status = Some(format!(
            "query {}: {:?}, depth {}, {} intersect calls, {} borderlines",
            a.query,
            s.connection.outcome,
            s.connection.depth,
            s.connection.counts.intersect_calls(),
            s.connection.borderlines.len()
        ));
    }
    super::output::save(&a.output, picture.to_svg().as_bytes())?;
    // status lines after the save: none precedes an `error:` line (issue 16)
    if let Some(line) = status {
        eprintln!("{line}");
    }
    eprintln!("wrote {}", a.output.display());
    Ok(())
}
