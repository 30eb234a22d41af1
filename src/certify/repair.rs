//! Repairing a path: every segment proved free is kept; each run of segments that collide or
//! are undecided is replaced by a detour between the last configuration proved free before
//! it and the first one after it (inside the run's first and last segments where their ends
//! are proved free). A detour is planned by the via-point local method first (a search bounded
//! in oracle calls: CHS's answer to a blocked straight motion), then by the portfolio (trees,
//! the via-point planner again) within the time left, and shortened. The fixed path is then
//! certified like any other.

use super::{Certificate, Certifier, CertifyError, Verdict};
use crate::deadline::Deadline;
use crate::local::{path_pieces, shorten_known, KnownPieces, LocalSpec};
use crate::oracle::{CallCounts, CountedOracle};
use crate::portfolio::{Planning, Portfolio};
use crate::space::Config;
use serde::Serialize;
use std::time::{Duration, Instant};

/// How to repair.
#[derive(Clone, Debug)]
pub struct RepairOptions {
    /// Time for all detours together (`None`: no limit).
    pub time: Option<Duration>,
    /// Oracle calls the via-point local method may spend per detour before the portfolio.
    pub local_calls: u64,
    /// Seed of the portfolio's trees.
    pub seed: u64,
}

impl Default for RepairOptions {
    fn default() -> Self {
        RepairOptions {
            time: Some(Duration::from_secs(10)),
            local_calls: 300,
            seed: 1,
        }
    }
}

/// One run of blocked segments and its detour.
#[derive(Clone, Debug, Serialize)]
pub struct DetourReport {
    /// The run's first and last segment (0-based, of the path given).
    pub segments: [usize; 2],
    /// What planned the detour: `local` (the via-point method), `direct` or `tree` (the
    /// portfolio's stages), or `failed`.
    pub stage: String,
    /// Length of the detour (the space's distance along its waypoints).
    pub length: f64,
    /// Length of the part of the path it replaces.
    pub replaced: f64,
    /// Seconds spent.
    pub seconds: f64,
    /// Why it failed, if it did.
    pub error: Option<String>,
}

/// What a repair did.
#[derive(Clone, Debug, Serialize)]
pub struct RepairReport {
    /// Segments that were not proved free.
    pub segments_repaired: usize,
    /// One entry per run of such segments.
    pub detours: Vec<DetourReport>,
    /// Sum of the detours' lengths.
    pub detour_length: f64,
    /// The path's length before and after.
    pub length_before: f64,
    /// The path's length after.
    pub length_after: f64,
    /// Seconds, planning and certifying the result.
    pub seconds: f64,
    /// Whether every run got a detour and the fixed path is certified free.
    pub certified: bool,
}

/// The fixed path, its report and its certificate.
#[derive(Clone, Debug, Serialize)]
pub struct Repaired {
    /// The fixed path (the path given, clamped into the bounds, where a run had no detour).
    pub path: Vec<Config>,
    /// What was done.
    pub report: RepairReport,
    /// The fixed path's certificate.
    pub certificate: Certificate,
}

/// Length of a path by the space's distance between consecutive waypoints.
pub fn length(c: &Certifier, path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| c.scene().space.distance(&w[0], &w[1]))
        .fold(0.0, |s, d| s + d)
}

/// The point of segment `a → b` at `t` under the certifier's motion model, for the ends of a
/// detour inside a segment (only used with the interpolation: a direct path's pieces keep
/// their waypoints).
fn point(c: &Certifier, a: &[f64], b: &[f64], t: f64) -> Config {
    match &c.scene().robot {
        crate::scene::Robot::Arm(_) => a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect(),
        _ => c.scene().space.interpolate(a, b, t),
    }
}

/// Repairs `path` given its certificate `cert` (from the same certifier), within
/// `options.time` (and `deadline`).
pub fn repair(
    c: &Certifier,
    path: &[Config],
    cert: &Certificate,
    options: &RepairOptions,
    deadline: &Deadline,
) -> Result<Repaired, CertifyError> {
    let began = Instant::now();
    let deadline = deadline.within(options.time);
    let (waypoints, _) = c.prepare(path)?;
    let bad: Vec<bool> = cert.segments.iter().map(|v| v.name() != "free").collect();
    let mut runs: Vec<[usize; 2]> = Vec::new();
    for (i, &b) in bad.iter().enumerate() {
        match runs.last_mut() {
            Some(r) if b && r[1] + 1 == i => r[1] = i,
            _ if b => runs.push([i, i]),
            _ => {}
        }
    }
    let mut out: Vec<Config> = Vec::with_capacity(waypoints.len());
    let mut detours = Vec::new();
    let mut next = 0; // the next waypoint of the given path to copy
    for (k, run) in runs.iter().enumerate() {
        let [s, e] = *run;
        if waypoints.len() == 1 {
            detours.push(failed(*run, 0.0, "a single waypoint in collision".into()));
            break;
        }
        out.extend(waypoints[next..=s].iter().cloned());
        next = e + 1;
        let inner = |v: &Verdict, before: bool| match v {
            Verdict::Collides(col) if before && col.free_before > 0.0 => {
                Some(0.5 * col.free_before)
            }
            Verdict::Collides(col) if !before && col.free_after < 1.0 => {
                Some(col.free_after + 0.5 * (1.0 - col.free_after))
            }
            _ => None,
        };
        let from_t =
            inner(&cert.segments[s], true).filter(|_| c.model() == super::MotionModel::Interpolate);
        let to_t = inner(&cert.segments[e], false)
            .filter(|_| c.model() == super::MotionModel::Interpolate);
        let from = from_t.map_or(waypoints[s].clone(), |t| {
            point(c, &waypoints[s], &waypoints[s + 1], t)
        });
        let to = to_t.map_or(waypoints[e + 1].clone(), |t| {
            point(c, &waypoints[e], &waypoints[e + 1], t)
        });
        let replaced = length(
            c,
            &std::iter::once(from.clone())
                .chain(waypoints[s + 1..=e].iter().cloned())
                .chain(std::iter::once(to.clone()))
                .collect::<Vec<_>>(),
        );
        // the time left shared among the runs left
        let share = deadline
            .remaining()
            .map(|r| r.div_f64((runs.len() - k) as f64));
        let d = deadline.within(share);
        let started = Instant::now();
        match detour(c, &from, &to, options, &d) {
            Ok((stage, corners)) => {
                if from_t.is_some() {
                    out.push(from.clone());
                }
                out.extend(corners.iter().skip(1).cloned());
                if to_t.is_none() {
                    out.pop();
                }
                let mut full = vec![from.clone()];
                full.extend(corners.iter().skip(1).cloned());
                detours.push(DetourReport {
                    segments: *run,
                    stage,
                    length: length(c, &full),
                    replaced,
                    seconds: started.elapsed().as_secs_f64(),
                    error: None,
                });
            }
            Err(why) => {
                // keep the blocked segments as they were
                out.extend(waypoints[s + 1..=e].iter().cloned());
                detours.push(failed(*run, started.elapsed().as_secs_f64(), why));
            }
        }
    }
    out.extend(waypoints[next.min(waypoints.len())..].iter().cloned());
    // the fixed path is certified within the repair's budget again (at least 10 s), so that a
    // run left blocked cannot hold the repair up
    let again = options.time.map(|t| t.max(Duration::from_secs(10)));
    let certificate = c.certify(&out, &Deadline::none().within(again))?;
    let all_planned = detours.iter().all(|d| d.error.is_none());
    Ok(Repaired {
        report: RepairReport {
            segments_repaired: bad.iter().filter(|b| **b).count(),
            detour_length: detours.iter().map(|d| d.length).sum(),
            length_before: length(c, &waypoints),
            length_after: length(c, &out),
            seconds: began.elapsed().as_secs_f64(),
            certified: all_planned && certificate.status() == super::Status::Free,
            detours,
        },
        path: out,
        certificate,
    })
}

fn failed(segments: [usize; 2], seconds: f64, why: String) -> DetourReport {
    DetourReport {
        segments,
        stage: "failed".into(),
        length: 0.0,
        replaced: 0.0,
        seconds,
        error: Some(why),
    }
}

/// A detour from `from` to `to` (both free for the true shapes; where the oracle's enclosing
/// shapes refuse one, the detour runs from or to a free neighbour of it, [`anchor`]).
fn detour(
    c: &Certifier,
    from: &Config,
    to: &Config,
    options: &RepairOptions,
    deadline: &Deadline,
) -> Result<(String, Vec<Config>), String> {
    let mut counts = CallCounts::default();
    // an end only the oracle's enclosing shapes refuse is reached from a free neighbour by a
    // segment proved on the true shapes; the detour is planned between the neighbours
    let mut ends = Vec::with_capacity(2);
    for (what, q, other) in [("start", from, to), ("end", to, from)] {
        match anchor(c, q, other, options.seed, deadline, &mut counts) {
            Some(a) => ends.push(a),
            None if c.witness(q).is_some() => {
                return Err(format!("the detour's {what} collides (the true shapes)"))
            }
            None => {
                return Err(format!(
                    "the detour's {what} is free, but the oracle's enclosing shapes collide \
                     there and no free neighbour joins it"
                ))
            }
        }
    }
    let (inner_from, inner_to) = (&ends[0], &ends[1]);
    let (stage, mut corners) = plan_detour(c, inner_from, inner_to, options, deadline)?;
    if inner_from != from {
        corners.insert(0, from.clone());
    }
    if inner_to != to {
        corners.push(to.clone());
    }
    Ok((stage, corners))
}

/// Offsets from a refused end, as shares of the way towards a target or of a random
/// direction's unit step (radians or scene units): far first, for a neighbour the oracle
/// leaves room around (a near one sits in a pocket the detour cannot leave).
const ANCHOR_SHARES: [f64; 7] = [0.35, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005];

/// Random directions tried per share after the way towards the other end.
const ANCHOR_DIRECTIONS: usize = 16;

/// `q` itself where the oracle finds it free; else, where the true shapes leave `q` free, a
/// configuration near it that the oracle finds free and from which the certifier proves the
/// segment to `q` free: towards `other` first, then in seeded random directions, the farthest
/// first. `None` where there is none.
fn anchor(
    c: &Certifier,
    q: &Config,
    other: &Config,
    seed: u64,
    deadline: &Deadline,
    counts: &mut CallCounts,
) -> Option<Config> {
    use rand::{Rng, SeedableRng};
    let oracle = c.oracle();
    if oracle.is_free(q, counts) {
        return Some(q.clone());
    }
    if c.witness(q).is_some() {
        return None;
    }
    let space = &c.scene().space;
    let (lower, upper) = (space.lower(), space.upper());
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let directions: Vec<Vec<f64>> = (0..ANCHOR_DIRECTIONS)
        .map(|_| {
            let v: Vec<f64> = q.iter().map(|_| rng.random_range(-1.0..1.0)).collect();
            let n = v.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-12);
            v.into_iter().map(|x| x / n).collect()
        })
        .collect();
    for share in ANCHOR_SHARES {
        let mut candidates = vec![point(c, q, other, share)];
        for d in &directions {
            let mut p: Config = q.iter().zip(d).map(|(x, y)| x + share * y).collect();
            if matches!(c.scene().robot, crate::scene::Robot::Arm(_)) {
                for (i, x) in p.iter_mut().enumerate() {
                    *x = x.clamp(lower[i], upper[i]);
                }
            } else {
                space.normalize(&mut p);
            }
            candidates.push(p);
        }
        for p in candidates {
            if deadline.expired() {
                return None;
            }
            if space.check(&p).is_ok()
                && oracle.is_free(&p, counts)
                && c.segment(&p, q, deadline, counts) == Verdict::Free
            {
                return Some(p);
            }
        }
    }
    None
}

/// The detour between two ends the oracle finds free: the via-point method, then the
/// portfolio; shortened; joined as the certifier's model moves.
fn plan_detour(
    c: &Certifier,
    from: &Config,
    to: &Config,
    options: &RepairOptions,
    deadline: &Deadline,
) -> Result<(String, Vec<Config>), String> {
    let scene = c.scene();
    let oracle = c.oracle();
    let mut counts = CallCounts::default();
    let spec = LocalSpec::default_for(&scene.space)
        .budgeted(options.local_calls)
        .unwrap_or_default();
    let method = spec.build();
    let groups = method.groups(&scene.space);
    let planning = Planning {
        scene,
        oracle,
        groups: &groups,
        straight: true,
    };
    let local = method.connect_within(&scene.space, oracle, from, to, deadline);
    let (stage, raw) = match local {
        Ok(conn) if conn.is_connected() => ("local".to_string(), conn.path),
        _ => {
            let portfolio = Portfolio {
                seed: options.seed,
                ..Portfolio::default()
            };
            let answer = portfolio.plan(&planning, (from, to), deadline);
            match (answer.path, answer.stage) {
                (Some((_, short)), Some(stage)) => (stage.name().to_string(), short),
                _ => {
                    return Err(answer.error.map_or_else(
                        || "no detour found within the time".to_string(),
                        |e| e.to_string(),
                    ))
                }
            }
        }
    };
    let mut path = raw;
    if path.first() != Some(from) {
        path.insert(0, from.clone());
    }
    let shortcut = planning.shortcut_groups();
    let mut known = KnownPieces::new();
    known.certify_path(&scene.space, &shortcut, &path);
    if let Ok(short) = shorten_known(
        &scene.space,
        oracle,
        &shortcut,
        &path,
        &mut known,
        &mut counts,
        deadline,
    ) {
        path = short;
    }
    // the planners' paths join corners by single-group motions or (arms) straight motions of
    // several joints: made waypoints of the model, one piece per pair
    let mut out = vec![path[0].clone()];
    for w in path.windows(2) {
        let pieces = path_pieces(&scene.space, &groups, &w[0], &w[1]);
        if pieces.len() <= 1 {
            out.push(w[1].clone());
        } else {
            out.extend(pieces.into_iter().map(|(_, end)| end));
        }
    }
    Ok((stage, out))
}
