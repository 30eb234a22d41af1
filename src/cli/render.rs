//! `viaroad render`: a picture of a scene and one query solved by the local method, with the
//! borderlines and via points it tried.

use super::local_args::LocalArgs;
use super::solve_args::solve_query;
use anyhow::Context;
use clap::Args;
use std::path::PathBuf;
use viaroad::local::LocalSpec;
use viaroad::render::Picture;
use viaroad::scene::arm::ArmRobot;
use viaroad::scene::moveit::ObjectShape;
use viaroad::scene::{Robot, Scene};

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
    /// them instead of with the local method.
    #[arg(long)]
    pub freeways: bool,
    /// Draw this path (an OMPL state file, as `--path-out` writes) instead of solving a query:
    /// for paths found by `solve --roadmap`, `query` or another planner.
    #[arg(long, value_name = "FILE", conflicts_with = "freeways")]
    pub path: Option<PathBuf>,
}

/// Runs `render`.
pub fn run(a: RenderArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let mut spec = a.local.spec_or(LocalSpec::default_for(&scene.space))?;
    if let LocalSpec::ViaPoint(o) = &mut spec {
        o.trace = true;
    }
    // refused before the solving, not after it
    viaroad::safe_file::resolve_target(&a.output)?;
    if let Robot::Arm(arm) = &scene.robot {
        return run_arm(&a, &scene, arm, &spec);
    }
    let mut status = None;
    let mut picture = Picture::new(&scene);
    picture.obstacles(&scene);
    if let Some(file) = &a.path {
        let path = viaroad::scene::ompl_cfg::read_states(file, &scene.space)?;
        picture.path(&scene, &path, true);
        status = Some(format!("{}: {} states", file.display(), path.len()));
    } else if a.freeways {
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
    // status lines after the save: none precedes an `error:` line
    if let Some(line) = status {
        eprintln!("{line}");
    }
    eprintln!("wrote {}", a.output.display());
    Ok(())
}

/// An arm scene from the side (world x–z plane): the environment's polytopes shaded, the arm
/// as the polyline through its link origins at every corner of the shortened path (start
/// blue, goal red, the corners between grey). A sketch for orientation; the glTF export draws
/// the real shapes.
fn run_arm(a: &RenderArgs, scene: &Scene, arm: &ArmRobot, spec: &LocalSpec) -> anyhow::Result<()> {
    let mut path: Vec<Vec<f64>> = Vec::new();
    let mut status = None;
    if a.query > 0 {
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
            scene,
            oracle.as_ref(),
            spec,
            &start,
            &goal,
            &viaroad::deadline::Deadline::none(),
        )?;
        status = Some(format!(
            "query {}: {:?}, depth {}, {} intersect calls; drawn from the side (x–z)",
            a.query,
            s.connection.outcome,
            s.connection.depth,
            s.connection.counts.intersect_calls(),
        ));
        path = if s.shortened.is_empty() {
            vec![start, goal]
        } else {
            s.shortened
        };
    }
    let mut polys: Vec<(Vec<[f64; 2]>, &str, f64)> = Vec::new();
    for o in &arm.objects {
        for (pose, shape) in &o.parts {
            let mesh = match shape {
                ObjectShape::Primitive(p) => match p.polytope() {
                    Ok(m) => m,
                    Err(_) => continue,
                },
                ObjectShape::Mesh(m) => m.clone(),
            };
            for i in 0..mesh.triangles.len() {
                let t = mesh.triangle(i).map(|v| {
                    let w = pose * v;
                    [w.x, w.z]
                });
                polys.push((t.to_vec(), "#888888", 0.08));
            }
        }
    }
    let n = path.len();
    for (k, q) in path.iter().enumerate() {
        let pts: Vec<[f64; 2]> = arm
            .arm
            .link_poses(q)
            .iter()
            .map(|p| [p.translation.vector.x, p.translation.vector.z])
            .collect();
        let colour = if k == 0 {
            "#1f5fbf"
        } else if k + 1 == n {
            "#c0392b"
        } else {
            "#555555"
        };
        polys.push((pts, colour, -1.0));
    }
    let all = polys.iter().flat_map(|(p, _, _)| p.iter());
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in all {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    if !lo[0].is_finite() {
        (lo, hi) = ([-1.0, -1.0], [1.0, 1.0]);
    }
    let size = 600.0;
    let scale = size / (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let xy = |p: &[f64; 2]| {
        format!(
            "{:.2},{:.2}",
            20.0 + (p[0] - lo[0]) * scale,
            20.0 + (hi[1] - p[1]) * scale
        )
    };
    let mut svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{w:.0}" viewBox="0 0 {w:.0} {w:.0}"><rect width="100%" height="100%" fill="white"/>"#,
        w = size + 40.0
    );
    svg.push('\n');
    for (pts, colour, opacity) in &polys {
        let p: Vec<String> = pts.iter().map(xy).collect();
        if *opacity >= 0.0 {
            svg += &format!(
                r#"<polygon points="{}" fill="{colour}" fill-opacity="{opacity}" stroke="none"/>"#,
                p.join(" ")
            );
        } else {
            svg += &format!(
                r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="2" stroke-opacity="0.7"/>"#,
                p.join(" ")
            );
        }
        svg.push('\n');
    }
    svg += "</svg>\n";
    super::output::save(&a.output, svg.as_bytes())?;
    if let Some(line) = status {
        eprintln!("{line}");
    }
    eprintln!("wrote {}", a.output.display());
    Ok(())
}
