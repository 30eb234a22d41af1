//! `viaroad export`: a scene, its robot and a planned path as a glTF 2.0 binary;
//! the planning shared with `viaroad view`.

use super::local_args::LocalArgs;
use super::query::Shortening;
use anyhow::Context;
use clap::Args;
use std::path::{Path, PathBuf};
use viaroad::deadline::Deadline;
use viaroad::export::{Legend, Plan};
use viaroad::local::{first_collision_on_path, path_length, shorten, LocalSpec};
use viaroad::roadmap::{QueryOptions, QueryPlanner, Roadmap};
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{Arm, ArmChecker, ArmOptions};
use viaroad::scene::moveit::{load_motion_plan_request, load_planning_scene};
use viaroad::scene::{ompl_cfg, Scene};
use viaroad::space::Config;
use viaroad::space::{Group, Space};

/// What to draw and how to find the path: shared by `export` and `view`.
#[derive(Args)]
pub struct PlanArgs {
    /// Scene file (.toml or OMPL.app .cfg).
    pub scene: PathBuf,
    /// Answer the query with this saved roadmap (else it is planned as `solve` plans it: the
    /// portfolio suited to the scene).
    #[arg(long)]
    pub roadmap: Option<PathBuf>,
    /// Draw this path (an OMPL state file, one state per line) instead of planning one. It is
    /// checked first, as exactly as the scene's oracle answers: a path that collides is drawn
    /// as it is (not shortened) and said so in the legend and in a warning.
    #[arg(long, conflicts_with = "roadmap")]
    pub path: Option<PathBuf>,
    /// Which of the scene's queries to plan (1-based).
    #[arg(long, default_value_t = 1, conflicts_with = "path")]
    pub query: usize,
    /// Path shortening (as in `query`): the shortened path is drawn beside the raw one and the
    /// robot follows it; `off` draws the raw path alone.
    #[arg(long, value_enum, default_value_t = Shortening::Fast, help_heading = "Tuning")]
    pub shorten: Shortening,
    /// Also draw the roadmap's nodes and edges (at the robot's reference point): the saved one,
    /// or else the query is planned by a roadmap grown from start and goal (as `solve
    /// --roadmap`) rather than by `solve`'s default.
    #[arg(long)]
    pub show_roadmap: bool,
    /// Most nodes of the trees and roadmaps grown to plan the query (no `--roadmap`, no
    /// `--path`): a budget that gives the same path on any machine.
    #[arg(long, default_value_t = 5000, help_heading = "Tuning")]
    pub nodes: usize,
    /// Seconds the planning may take (no `--roadmap`, no `--path`). Default: the `.cfg` file's
    /// `[benchmark] time_limit`, else 60 s.
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Seed of the trees and roadmaps grown to plan the query.
    #[arg(long, default_value_t = 1, help_heading = "Tuning")]
    pub seed: u64,
    #[command(flatten)]
    pub local: LocalArgs,
    /// A MoveIt MotionPlanRequest: SCENE is then a MoveIt PlanningScene (YAML) and the robot
    /// the arm of `--urdf` (and `--srdf`). The arm follows `--path` (joint vectors of the
    /// request's group, one per line, as OMPL writes them) or, without it, the straight joint
    /// motion from the request's start to its goal; either is checked by the independent arm
    /// checker and drawn even where it collides (the legend says so).
    #[arg(long, requires = "urdf", conflicts_with = "roadmap")]
    pub request: Option<PathBuf>,
    /// The arm's URDF (with `--request`).
    #[arg(long, requires = "request")]
    pub urdf: Option<PathBuf>,
    /// The arm's SRDF (with `--request`): planning groups, self-collision exemptions.
    #[arg(long, requires = "request")]
    pub srdf: Option<PathBuf>,
}

/// What `export` writes and `view` embeds.
pub struct Exported {
    /// The glTF binary.
    pub glb: Vec<u8>,
    /// One line on what it shows.
    pub summary: String,
    /// What the viewer page's legend says.
    pub legend: Legend,
}

/// Where a path collides, as the legend and the warning say it: `segment` 0-based (shown
/// 1-based: the motion from configuration k to k + 1), `t` the share of it travelled; where
/// not `proved`, the segment is only not proved free from `t` on.
fn collision_text(corners: usize, segment: usize, t: f64, proved: bool) -> String {
    if corners == 1 {
        "collides at its only configuration".to_string()
    } else if proved {
        format!("collides in segment {} at t = {t:.3}", segment + 1)
    } else {
        format!(
            "is not proved free in segment {} from t = {t:.3} (too close to an obstacle to certify)",
            segment + 1
        )
    }
}

/// Reads a `--path` file, refusing one with no configuration (nothing to draw or follow).
fn read_path(file: &Path, space: &Space) -> anyhow::Result<Vec<viaroad::space::Config>> {
    let path = ompl_cfg::read_states(file, space)?;
    if path.is_empty() {
        anyhow::bail!("the path file {} holds no configuration", file.display());
    }
    Ok(path)
}

/// Plans (or reads) the path and builds the `.glb`: a rigid-body scene, or an arm in a MoveIt
/// scene with `--request`.
pub fn export(a: &PlanArgs) -> anyhow::Result<Exported> {
    match (&a.request, &a.urdf) {
        (Some(request), Some(urdf)) => export_arm(a, request, urdf),
        _ => {
            let p = plan(a)?;
            let (glb, summary) = glb(&p)?;
            Ok(Exported {
                glb,
                summary,
                legend: p.legend,
            })
        }
    }
}

/// The arm of `--urdf` in the MoveIt scene, following `--path` or the request's start → goal.
fn export_arm(a: &PlanArgs, request: &Path, urdf: &Path) -> anyhow::Result<Exported> {
    let scene = load_planning_scene(&a.scene)?;
    let req = load_motion_plan_request(request)?;
    let mut arm = Arm::load(
        urdf,
        a.srdf.as_deref(),
        &ArmOptions {
            group: GroupChoice::Srdf(req.group.clone()),
            ..ArmOptions::default()
        },
    )?;
    for w in &arm.warnings {
        eprintln!("warning: {w}");
    }
    scene.apply_to(&mut arm)?;
    let (start, goal) = req.start_goal(&mut arm)?;
    let (path, source, raw_name) = match &a.path {
        Some(file) => {
            let space = Space::euclidean(arm.group.lower.clone(), arm.group.upper.clone())?;
            let path = read_path(file, &space)?;
            (path, format!("path file {}", file.display()), "given path")
        }
        None => (
            vec![start, goal],
            "start → goal".to_string(),
            "straight motion start → goal",
        ),
    };
    let checker = ArmChecker::new(&arm, &scene.objects)?;
    // the checker's own sampling step in joint space (radians): about 0.6° per joint
    let report = checker.check_path(&path, 0.01)?;
    let collision = report.first_invalid.as_ref().map(|(seg, t, c)| {
        let what: Vec<String> = c.iter().map(|c| format!("{}–{}", c.a, c.b)).collect();
        let text = collision_text(path.len(), *seg, *t, true);
        if what.is_empty() {
            format!("{text} (out of bounds)")
        } else {
            format!("{text} ({})", what.join(", "))
        }
    });
    // MotionBenchMaker scenes have no name: their family folder and file say which they are
    let name = if scene.name.is_empty() {
        let part = |p: Option<&std::ffi::OsStr>| p.map(|s| s.to_string_lossy().into_owned());
        let stem = part(a.scene.file_stem()).unwrap_or_else(|| "arm".into());
        match part(a.scene.parent().and_then(Path::file_name)) {
            Some(dir) => format!("{dir}/{stem}"),
            None => stem,
        }
    } else {
        scene.name.clone()
    };
    // from +0.0: a sum of no terms would be -0.0
    let length: f64 = path
        .windows(2)
        .map(|w| {
            w[0].iter()
                .zip(&w[1])
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, |total, l| total + l);
    let verdict = match &collision {
        None => "free",
        Some(_) => "collides",
    };
    let mut legend = Legend {
        scene: name.clone(),
        space: format!("arm, {} joints ({})", arm.group.dof(), arm.group.name),
        source: format!("{source}; arm checker: {verdict}"),
        ..Legend::default()
    };
    let plan = Plan {
        raw: path.clone(),
        shortened: Vec::new(),
    };
    legend.set_paths(&plan, raw_name, length, length, collision.as_deref());
    // the shortened length is the raw one here: no second row, no raw length to show
    legend.raw_length = None;
    let g = viaroad::export::arm::arm_gltf(&arm, &scene.objects, &plan, 0, &legend)?;
    if let Some(c) = &collision {
        eprintln!("warning: the {raw_name} {c}; drawn as it is");
    }
    Ok(Exported {
        summary: format!(
            "{name}: {} corners, joint-space length {length:.4}; {}",
            path.len(),
            legend.source
        ),
        glb: g.to_glb(),
        legend,
    })
}

/// A scene with the plan to draw, the roadmap that found it and the legend.
pub struct Planned {
    pub scene: Scene,
    pub groups: Vec<Group>,
    pub plan: Plan,
    pub roadmap: Option<Roadmap>,
    pub legend: Legend,
}

/// Loads the scene and finds the path to draw (see [`PlanArgs`]).
pub fn plan(a: &PlanArgs) -> anyhow::Result<Planned> {
    let scene = Scene::load(&a.scene)?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    let spec = a.local.spec_or(LocalSpec::roadmap_default())?;
    let method = spec.build();
    let groups = method.groups(&scene.space);
    let oracle = scene.oracle();
    let mut legend = Legend {
        scene: scene.name.clone(),
        space: scene.space.kind().to_string(),
        ..Legend::default()
    };
    legend.set_bodies(&scene);
    let mut roadmap = None;
    let mut collision = None;
    let plan = if let Some(file) = &a.path {
        let raw = read_path(file, &scene.space)?;
        let mut counts = viaroad::oracle::CallCounts::default();
        // a given path is vouched for by no planner: checked before anything trusts it
        // (shortening assumes a free path)
        let hit =
            first_collision_on_path(&scene.space, oracle.as_ref(), &groups, &raw, &mut counts)
                .context("checking the path")?;
        collision = hit.map(|h| collision_text(raw.len(), h.segment, h.t, h.proved));
        let shortened = if a.shorten == Shortening::Off || hit.is_some() {
            Vec::new()
        } else {
            shorten(&scene.space, oracle.as_ref(), &groups, &raw, &mut counts)
                .context("shortening")?
        };
        if let Some(c) = &collision {
            eprintln!(
                "warning: the given path {} {c}; drawn as it is, not shortened",
                file.display()
            );
        }
        legend.source = format!("path file {}", file.display());
        legend.calls = Some(counts.intersect_calls());
        Plan { raw, shortened }
    } else {
        let queries = scene.checked_queries()?;
        let q = queries.get(a.query.wrapping_sub(1)).with_context(|| {
            format!(
                "{} has {} queries, not {}",
                a.scene.display(),
                queries.len(),
                a.query
            )
        })?;
        if let Some(file) = &a.roadmap {
            let (raw, shortened, map, calls) =
                through_roadmap(a, file, &scene, oracle.as_ref(), q)?;
            legend.source = format!("roadmap {}", file.display());
            legend.calls = Some(calls);
            roadmap = Some(map);
            Plan { raw, shortened }
        } else {
            let s = plan_as_solve(a, &scene, oracle.as_ref(), q)?;
            legend.source = format!(
                "planned as `solve` plans ({}), {} nodes grown",
                s.method.map_or("", |m| m.name()),
                s.nodes
            );
            legend.calls = Some(s.counts.intersect_calls());
            roadmap = s.roadmap;
            let shortened = match a.shorten {
                Shortening::Off => Vec::new(),
                _ => s.shortened,
            };
            Plan {
                raw: s.raw,
                shortened,
            }
        }
    };
    let raw_name = if a.path.is_some() {
        "given path"
    } else if plan.shortened.is_empty() {
        "path"
    } else {
        "raw path"
    };
    legend.set_paths(
        &plan,
        raw_name,
        path_length(&scene.space, &groups, &plan.raw),
        path_length(&scene.space, &groups, plan.animated()),
        collision.as_deref(),
    );
    Ok(Planned {
        scene,
        groups,
        plan,
        roadmap: roadmap.filter(|_| a.show_roadmap),
        legend,
    })
}

/// The query planned by the planner `solve` uses by default, within `--time` and `--nodes`.
fn plan_as_solve(
    a: &PlanArgs,
    scene: &Scene,
    oracle: &dyn viaroad::oracle::CollisionOracle,
    q: &viaroad::scene::Query,
) -> anyhow::Result<viaroad::solve::Solution> {
    super::limits::count_in_range(
        "--nodes",
        a.nodes,
        viaroad::limits::MAX_NODES,
        "trees and roadmaps that large do not fit in memory",
    )?;
    let seconds = match a.time {
        Some(t) => t,
        None => super::solve_args::default_seconds(&a.scene)?,
    };
    let time = super::limits::parse_seconds("--time", seconds)?;
    let solver = viaroad::solve::Solver {
        seed: a.seed,
        nodes: Some(a.nodes),
        ..viaroad::solve::Solver::default()
    };
    let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(Some(time));
    // a roadmap to draw is a roadmap to plan with
    let s = match a.show_roadmap {
        true => solver.plan_by_roadmap(scene, oracle, (&q.start, &q.goal), &deadline)?,
        false => solver.plan(scene, oracle, (&q.start, &q.goal), &deadline)?,
    };
    if let Some(w) = &s.warning {
        eprintln!("warning: {w}");
    }
    if !s.is_solved() {
        anyhow::bail!(
            "query {} of {} not solved in {seconds} s with {} nodes; try a longer --time, more --nodes or another --seed",
            a.query,
            a.scene.display(),
            a.nodes
        );
    }
    Ok(s)
}

/// The query answered through the saved roadmap `file`: the raw and shortened paths, the
/// roadmap and the oracle calls.
fn through_roadmap(
    a: &PlanArgs,
    file: &Path,
    scene: &Scene,
    oracle: &dyn viaroad::oracle::CollisionOracle,
    q: &viaroad::scene::Query,
) -> anyhow::Result<(Vec<Config>, Vec<Config>, Roadmap, u64)> {
    let map = Roadmap::load(file, scene.fingerprint())?;
    let options = QueryOptions {
        landmarks: 0,
        shorten: a.shorten != Shortening::Off,
        exact_shortening_limit: if a.shorten == Shortening::Exact {
            usize::MAX
        } else {
            QueryOptions::default().exact_shortening_limit
        },
        grow: true,
        ..QueryOptions::default()
    };
    let planner = QueryPlanner::new(&map, oracle)?.with_options(options);
    let r = planner.query(&q.start, &q.goal)?;
    if !r.is_solved() {
        anyhow::bail!(
            "query {} of {} not solved ({:?}) through {}",
            a.query,
            a.scene.display(),
            r.outcome,
            file.display()
        );
    }
    let shortened = match a.shorten {
        Shortening::Off => Vec::new(),
        _ => r.path,
    };
    let calls = r.counts.intersect_calls();
    drop(planner);
    Ok((r.raw_path, shortened, map, calls))
}

/// Arguments of `export`.
#[derive(Args)]
pub struct ExportArgs {
    #[command(flatten)]
    pub plan: PlanArgs,
    /// Output glTF binary (.glb).
    #[arg(short, long)]
    pub output: PathBuf,
}

/// The `.glb` of a planned scene, and a one-line summary of what it shows.
pub fn glb(p: &Planned) -> anyhow::Result<(Vec<u8>, String)> {
    let g =
        viaroad::export::scene_gltf(&p.scene, &p.groups, &p.plan, p.roadmap.as_ref(), &p.legend)?;
    let l = &p.legend;
    let summary = format!(
        "{}: {} corners (raw {}), length {:.4} (raw {:.4}), {} intersect calls; {}",
        l.scene,
        p.plan.animated().len(),
        p.plan.raw.len(),
        l.length.unwrap_or(f64::NAN),
        l.raw_length.unwrap_or(f64::NAN),
        l.calls.unwrap_or(0),
        l.source
    );
    Ok((g.to_glb(), summary))
}

/// Runs `export`.
pub fn run(a: ExportArgs) -> anyhow::Result<()> {
    // refused before the planning, not after it
    super::output::check_writable(&a.output)?;
    let e = export(&a.plan)?;
    super::output::save(&a.output, &e.glb)?;
    eprintln!("{}", e.summary);
    eprintln!("wrote {} ({} bytes)", a.output.display(), e.glb.len());
    Ok(())
}
