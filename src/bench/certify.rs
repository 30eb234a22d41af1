//! `viaroad bench certify`: another planner's paths for a MotionBenchMaker family certified and,
//! where blocked, repaired ([`crate::certify`]). The paths come as JSON lines (one object per
//! problem with `family`, `index`, `path`, as the VAMP peer writes them; `solved: false` lines
//! are skipped) or as a folder of OMPL path files named `<family>_<NNNN>.path`. Each path's
//! problem is the family folder `<family>_<robot>` (or `<family>`) of the problems folder.

use super::mbm::{problem_scene, Problem, Stats};
use crate::certify::{repair, Certifier, MotionModel, RepairOptions, Status, Verdict};
use crate::deadline::Deadline;
use crate::robot::Arm;
use crate::space::Config;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Why a run cannot start.
#[derive(Debug, thiserror::Error)]
pub enum BenchCertifyError {
    /// The paths cannot be read.
    #[error("{path}: {message}")]
    Input {
        /// The file or folder.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

/// One path to certify.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The family as the planner names it (`table_pick`).
    pub family: String,
    /// The problem's number (1-based).
    pub index: usize,
    /// The waypoints, in the group's joint order.
    pub path: Vec<Config>,
    /// The planner's own time, milliseconds, where given (`total_ms`).
    pub planner_ms: Option<f64>,
    /// The robot as the planner names it (`robot`, e.g. `ur5`), where given: the family
    /// folders are named after it (`box_ur5`), not after the URDF's robot (`ur5_robotiq85`).
    pub robot: Option<String>,
}

/// Reads the entries of `input`: a JSON lines file or a folder of path files.
pub fn read_entries(input: &Path) -> Result<Vec<Entry>, BenchCertifyError> {
    let bad = |message: String| BenchCertifyError::Input {
        path: input.to_path_buf(),
        message,
    };
    if input.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(input)
            .map_err(|e| bad(e.to_string()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "path"))
            .collect();
        files.sort();
        let mut out = Vec::new();
        for f in files {
            let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or_default();
            let Some((family, index)) = stem
                .rsplit_once('_')
                .and_then(|(fam, i)| Some((fam.to_string(), i.parse::<usize>().ok()?)))
            else {
                continue;
            };
            let text = std::fs::read_to_string(&f).map_err(|e| bad(e.to_string()))?;
            let path: Result<Vec<Config>, _> = text
                .lines()
                .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
                .map(|l| l.split_whitespace().map(str::parse::<f64>).collect())
                .collect();
            let path = path.map_err(|e| bad(format!("{}: {e}", f.display())))?;
            out.push(Entry {
                family,
                index,
                path,
                planner_ms: None,
                robot: None,
            });
        }
        return Ok(out);
    }
    let text = std::fs::read_to_string(input).map_err(|e| bad(e.to_string()))?;
    let mut out = Vec::new();
    for (k, line) in text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
    {
        let v: serde_json::Value =
            serde_json::from_str(line).map_err(|e| bad(format!("line {}: {e}", k + 1)))?;
        if v.get("solved").and_then(|s| s.as_bool()) == Some(false)
            || v.get("path").is_none_or(|p| p.is_null())
        {
            continue;
        }
        let entry: Option<Entry> = (|| {
            Some(Entry {
                family: v.get("family")?.as_str()?.to_string(),
                index: v.get("index")?.as_u64()? as usize,
                path: serde_json::from_value(v.get("path")?.clone()).ok()?,
                planner_ms: v.get("total_ms").and_then(|t| t.as_f64()),
                robot: v.get("robot").and_then(|r| r.as_str()).map(str::to_string),
            })
        })();
        out.push(entry.ok_or_else(|| bad(format!("line {}: no family, index or path", k + 1)))?);
    }
    Ok(out)
}

/// How to run.
#[derive(Clone, Debug)]
pub struct BenchCertifyOptions {
    /// Repair the paths not proved free.
    pub repair: Option<RepairOptions>,
    /// Time to certify one path.
    pub time: Option<Duration>,
}

/// One path's outcome.
#[derive(Clone, Debug, Default, Serialize)]
pub struct CertifyResult {
    /// Family (the planner's name).
    pub family: String,
    /// Problem number.
    pub index: usize,
    /// `free`, `collides`, `undecided`, or empty on error.
    pub status: String,
    /// Segments: free, colliding, undecided.
    pub segments: [usize; 3],
    /// Defects (bounds, ends).
    pub defects: usize,
    /// Seconds certifying (the scene's set-up excluded).
    pub certify_s: f64,
    /// Seconds setting up the scene, oracle and checker.
    pub setup_s: f64,
    /// The planner's own time, milliseconds.
    pub planner_ms: Option<f64>,
    /// Witnesses of the colliding segments: segment, parameter, configuration, pairs.
    pub witnesses: Vec<(usize, f64, Config, Vec<[String; 2]>)>,
    /// Whether the repaired path is certified free (`None`: not repaired).
    pub repaired: Option<bool>,
    /// Seconds repairing.
    pub repair_s: f64,
    /// Length before and after the repair.
    pub length: [f64; 2],
    /// The repaired path.
    pub fixed: Vec<Config>,
    /// Why a repair is not certified: its detours' errors, or the fixed path's status.
    pub repair_errors: Vec<String>,
    /// Why it could not run.
    pub error: String,
}

/// The problem of an entry in `problems` (the family folders): `<family>_<robot>` with the
/// entry's robot name or the URDF's (`robot`), else `<family>`.
fn problem_of(problems: &Path, robot: &str, e: &Entry) -> Problem {
    let dir = e
        .robot
        .iter()
        .map(String::as_str)
        .chain([robot])
        .map(|r| problems.join(format!("{}_{r}", e.family)))
        .find(|d| d.is_dir())
        .unwrap_or_else(|| problems.join(&e.family));
    Problem {
        family: e.family.clone(),
        id: format!("{:04}", e.index),
        scene: dir.join(format!("scene{:04}.yaml", e.index)),
        request: dir.join(format!("request{:04}.yaml", e.index)),
    }
}

/// Certifies (and repairs) one entry.
pub fn run_entry(
    arm: &Arm,
    robot: &str,
    problems: &Path,
    e: &Entry,
    o: &BenchCertifyOptions,
) -> CertifyResult {
    let mut r = CertifyResult {
        family: e.family.clone(),
        index: e.index,
        planner_ms: e.planner_ms,
        ..CertifyResult::default()
    };
    let began = Instant::now();
    let scene = match problem_scene(arm, &problem_of(problems, robot, e)) {
        Ok(s) => s,
        Err(err) => {
            r.error = err.to_string();
            return r;
        }
    };
    let certifier = match Certifier::new(&scene, MotionModel::Interpolate) {
        Ok(c) => c,
        Err(err) => {
            r.error = err.to_string();
            return r;
        }
    };
    r.setup_s = began.elapsed().as_secs_f64();
    let cert = match certifier.certify(&e.path, &Deadline::none().within(o.time)) {
        Ok(c) => c,
        Err(err) => {
            r.error = err.to_string();
            return r;
        }
    };
    r.certify_s = cert.seconds;
    r.segments = cert.counts();
    r.defects = cert.defects.len();
    r.status = serde_json::to_value(cert.status())
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default();
    for (i, v) in cert.segments.iter().enumerate() {
        if let Verdict::Collides(c) = v {
            r.witnesses
                .push((i, c.witness_t, c.witness.clone(), c.pairs.clone()));
        }
    }
    if let (Some(ro), true) = (&o.repair, cert.status() != Status::Free) {
        match repair(&certifier, &e.path, &cert, ro, &Deadline::none()) {
            Ok(fixed) => {
                r.repaired = Some(fixed.report.certified);
                r.repair_s = fixed.report.seconds;
                r.length = [fixed.report.length_before, fixed.report.length_after];
                r.repair_errors = fixed
                    .report
                    .detours
                    .iter()
                    .filter_map(|d| d.error.clone())
                    .collect();
                if !fixed.report.certified && r.repair_errors.is_empty() {
                    let [_, c, u] = fixed.certificate.counts();
                    r.repair_errors.push(format!(
                        "the fixed path: {c} segments collide, {u} undecided, {} defects",
                        fixed.certificate.defects.len()
                    ));
                }
                r.fixed = fixed.path;
            }
            Err(err) => {
                r.repaired = Some(false);
                r.error = err.to_string();
            }
        }
    }
    r
}

/// The summary table: per family, paths, proved free, colliding, undecided, repairs, and
/// times.
pub fn summary_markdown(results: &[CertifyResult]) -> String {
    let mut families: Vec<&str> = results.iter().map(|r| r.family.as_str()).collect();
    families.sort();
    families.dedup();
    let mut out = String::from(
        "| family | paths | free | collides | undecided | errors | repaired | certify ms p50 (free) | certify ms p50 (all) | repair ms p50 | length change p50 |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let row = |name: &str, rs: Vec<&CertifyResult>| {
        let n = |s: &str| rs.iter().filter(|r| r.status == s).count();
        let ms = |v: Vec<f64>| Stats::of(&v).p50 * 1e3;
        let free_ms = ms(rs
            .iter()
            .filter(|r| r.status == "free")
            .map(|r| r.certify_s)
            .collect());
        let all_ms = ms(rs
            .iter()
            .filter(|r| r.error.is_empty())
            .map(|r| r.certify_s)
            .collect());
        let tried: Vec<&&CertifyResult> = rs.iter().filter(|r| r.repaired.is_some()).collect();
        let ok = tried.iter().filter(|r| r.repaired == Some(true)).count();
        let rep_ms = ms(tried.iter().map(|r| r.repair_s).collect());
        let change: Vec<f64> = tried
            .iter()
            .filter(|r| r.repaired == Some(true) && r.length[0] > 0.0)
            .map(|r| r.length[1] / r.length[0] - 1.0)
            .collect();
        format!(
            "| {name} | {} | {} | {} | {} | {} | {ok}/{} | {free_ms:.3} | {all_ms:.3} | {rep_ms:.1} | {:+.1} % |\n",
            rs.len(),
            n("free"),
            n("collides"),
            n("undecided"),
            rs.iter().filter(|r| !r.error.is_empty() && r.status.is_empty()).count(),
            tried.len(),
            Stats::of(&change).p50 * 100.0,
        )
    };
    for f in &families {
        out.push_str(&row(f, results.iter().filter(|r| r.family == *f).collect()));
    }
    out.push_str(&row("**ALL**", results.iter().collect()));
    out
}
