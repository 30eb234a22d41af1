//! `viaroad certify`: proves each segment of a path from any planner free, or finds where it
//! collides, and repairs it on request.

use anyhow::Context;
use clap::Args;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Duration;
use viaroad::bench::mbm::{load_robot, problem_scene, Problem};
use viaroad::certify::{
    repair, Certificate, Certifier, Defect, MotionModel, RepairOptions, Repaired, Status, Verdict,
};
use viaroad::deadline::Deadline;
use viaroad::scene::{ompl_cfg, Scene};
use viaroad::short;

/// Arguments of `certify`.
#[derive(Args)]
pub struct CertifyArgs {
    /// Scene: a .toml (any kind, arms included) or OMPL.app .cfg; or a MoveIt PlanningScene
    /// .yaml with `--robot` and `--request`.
    pub scene: PathBuf,
    /// The path: an OMPL state file, one configuration per line in the scene's layout
    /// (`x y z qx qy qz qw`, `x y θ`, n coordinates, or an arm group's joints in order).
    pub path: PathBuf,
    /// One JSON object on stdout (verdicts, defects, the repair's report).
    #[arg(long)]
    pub json: bool,
    /// How the robot moves between waypoints: `interpolate` (default; OMPL's, MoveIt's and
    /// VAMP's: a straight line in joint space with all joints at once, a straight line in R^n,
    /// SE(2)'s line with the angle the shorter way, SE(3)'s linear translation with a slerp)
    /// or `direct` (viaroad's own paths: one DOF group after another).
    #[arg(long, value_name = "MODEL", default_value = "interpolate")]
    pub motion: MotionModel,
    /// Seconds for certifying (segments not reached are undecided); with `--repair`, again
    /// for all detours together (default 10).
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Replace each run of segments not proved free by a certified detour (the via-point
    /// method, then the portfolio) and certify the fixed path.
    #[arg(long)]
    pub repair: bool,
    /// Where `--repair` writes the fixed path (an OMPL state file).
    #[arg(short = 'o', long, value_name = "FIXED", requires = "repair")]
    pub out: Option<PathBuf>,
    /// A folder with the robot's .urdf (and .srdf), for a MoveIt PlanningScene SCENE.
    #[arg(long, value_name = "DIR", requires = "request")]
    pub robot: Option<PathBuf>,
    /// The MotionPlanRequest .yaml of a MoveIt SCENE: its group, start and goal.
    #[arg(long, value_name = "REQ", requires = "robot")]
    pub request: Option<PathBuf>,
}

/// Exit status when a segment collides (or a waypoint is defective).
pub const EXIT_COLLIDES: i32 = 3;
/// Exit status when nothing collides but a segment is undecided.
pub const EXIT_UNDECIDED: i32 = 4;

/// The scene of the arguments.
fn load(a: &CertifyArgs) -> anyhow::Result<Scene> {
    match (&a.robot, &a.request) {
        (Some(robot), Some(request)) => {
            let arm = load_robot(robot)?;
            let problem = Problem {
                family: String::new(),
                id: String::new(),
                scene: a.scene.clone(),
                request: request.clone(),
            };
            Ok(problem_scene(&arm, &problem)?)
        }
        _ => Ok(Scene::load(&a.scene)?),
    }
}

fn seconds(t: Option<f64>) -> anyhow::Result<Option<Duration>> {
    t.map(|s| {
        Duration::try_from_secs_f64(s)
            .map_err(|_| anyhow::anyhow!("--time {s} is not a number of seconds"))
    })
    .transpose()
}

/// Runs `certify`; ends the process with the verdict's exit status.
pub fn run(a: CertifyArgs) -> anyhow::Result<()> {
    let scene = load(&a)?;
    let path = ompl_cfg::read_states(&a.path, &scene.space)?;
    let time = seconds(a.time)?;
    let certifier = Certifier::new(&scene, a.motion)?;
    let deadline = super::interrupt::on_ctrl_c(Deadline::none()).within(time);
    let cert = certifier.certify(&path, &deadline)?;
    let repaired = if a.repair {
        let options = RepairOptions {
            time: time.or(RepairOptions::default().time),
            ..RepairOptions::default()
        };
        let deadline = super::interrupt::on_ctrl_c(Deadline::none());
        let r = repair(&certifier, &path, &cert, &options, &deadline)?;
        if let Some(out) = &a.out {
            ompl_cfg::write_states(out, &r.path)
                .with_context(|| format!("writing {}", out.display()))?;
        }
        Some(r)
    } else {
        None
    };
    let mut stdout = std::io::stdout().lock();
    if a.json {
        let value = serde_json::json!({
            "scene": scene.name,
            "path": a.path.display().to_string(),
            "status": cert.status(),
            "certificate": cert,
            "repair": repaired,
        });
        writeln!(stdout, "{value}")?;
    } else {
        print_text(
            &mut stdout,
            &a.path,
            &cert,
            repaired.as_ref(),
            a.out.as_deref(),
        )?;
    }
    stdout.flush()?;
    drop(stdout);
    let status = repaired
        .as_ref()
        .map_or(cert.status(), |r| r.certificate.status());
    match status {
        Status::Free => Ok(()),
        Status::Collides => std::process::exit(EXIT_COLLIDES),
        Status::Undecided => std::process::exit(EXIT_UNDECIDED),
    }
}

/// One line per segment not proved free, per defect, and a summary.
fn print_text(
    w: &mut impl Write,
    file: &Path,
    cert: &Certificate,
    repaired: Option<&Repaired>,
    out: Option<&Path>,
) -> anyhow::Result<()> {
    for (i, v) in cert.segments.iter().enumerate() {
        match v {
            Verdict::Free => {}
            Verdict::Collides(c) => {
                let at = c
                    .intervals
                    .iter()
                    .map(|[a, b]| format!("[{}, {}]", short::num(*a), short::num(*b)))
                    .collect::<Vec<_>>()
                    .join(" ∪ ");
                let how = if c.exact {
                    "exact".to_string()
                } else if c.resolution > 0.0 {
                    format!("located to {}", short::num(c.resolution))
                } else {
                    "at a waypoint".to_string()
                };
                let pairs = c
                    .pairs
                    .iter()
                    .map(|[a, b]| format!("{a} ~ {b}"))
                    .collect::<Vec<_>>()
                    .join(", ");
                writeln!(
                    w,
                    "segment {}: collides at t ∈ {at} ({how}): {pairs}; witness t = {} {}",
                    i + 1,
                    short::num(c.witness_t),
                    short::config(&c.witness)
                )?;
            }
            Verdict::Undecided { reason } => writeln!(w, "segment {}: undecided: {reason}", i + 1)?,
        }
    }
    for d in &cert.defects {
        writeln!(w, "{}", defect_line(d))?;
    }
    let [free, collides, undecided] = cert.counts();
    writeln!(
        w,
        "{}: {} ({free} free, {collides} colliding, {undecided} undecided of {} segments; {} ms, {} calls, motion {})",
        file.display(),
        match cert.status() {
            Status::Free => "proved free",
            Status::Collides => "collides",
            Status::Undecided => "undecided",
        },
        cert.segments.len(),
        short::num(cert.seconds * 1e3),
        cert.calls,
        serde_json::to_value(cert.model)?.as_str().unwrap_or("?"),
    )?;
    if let Some(r) = repaired {
        let rep = &r.report;
        for d in &rep.detours {
            writeln!(
                w,
                "repair: segments {}–{}: {} (length {} for {}, {} ms){}",
                d.segments[0] + 1,
                d.segments[1] + 1,
                d.stage,
                short::num(d.length),
                short::num(d.replaced),
                short::num(d.seconds * 1e3),
                d.error.as_ref().map_or(String::new(), |e| format!(": {e}"))
            )?;
        }
        writeln!(
            w,
            "repaired: {} ({} segments replaced, length {} → {}, {} ms){}",
            if rep.certified {
                "certified free"
            } else {
                "not certified"
            },
            rep.segments_repaired,
            short::num(rep.length_before),
            short::num(rep.length_after),
            short::num(rep.seconds * 1e3),
            out.map_or(String::new(), |o| format!("; written to {}", o.display()))
        )?;
    }
    Ok(())
}

fn defect_line(d: &Defect) -> String {
    match d {
        Defect::OutOfBounds {
            waypoint,
            coordinate,
            value,
            lower,
            upper,
        } => format!(
            "waypoint {}: coordinate {} = {} outside [{}, {}]",
            waypoint + 1,
            coordinate + 1,
            short::num(*value),
            short::num(*lower),
            short::num(*upper)
        ),
        Defect::StartDiffers { distance } => {
            format!(
                "the first waypoint lies {} from the query's start",
                short::num(*distance)
            )
        }
        Defect::GoalDiffers { distance } => {
            format!(
                "the last waypoint lies {} from the query's goal",
                short::num(*distance)
            )
        }
    }
}
