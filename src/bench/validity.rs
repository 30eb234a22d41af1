//! `viaroad bench validity`: many random queries on every scene kind, every answered path
//! re-checked by checkers that share no code with the library's exact oracles (issue 15,
//! part 3). A planner whose oracle misses a collision produces paths that look fine to
//! itself; only an independent check turns "our tests pass" into "0 invalid in 100 000".
//!
//! * Discs (R^n, closed balls around a point robot): the distance from each segment of the
//!   path to each centre, in closed form, must not be below the radius.
//! * SE(2) polygons and SE(3) meshes: parry shapes (ear-clipped triangles in the plane, parry
//!   trimeshes in space) and *conservative advancement* along every straight motion: with
//!   clearance `d` at `t₀`, nothing can touch before every robot point has moved `d`, and no
//!   point moves faster than `|Δp| + r·|Δθ|` (r = the robot's radius about its reference
//!   point). Pieces are halved until certified; a piece below 1e-10 of the motion that cannot
//!   be certified is a collision (touching counts as collision, the library's convention).
//!   This is stronger than sampling at any resolution: it certifies the whole motion.
//!   SE(3) containment (a robot wholly inside a closed obstacle or holding one) is checked at
//!   the first configuration; surfaces that never touch cannot change it along the path.
//!
//! Both the raw path and the shortened one are checked.

use crate::geometry::Polygon;
use crate::local::LocalSpec;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::roadmap::RoadmapError;
use crate::roadmap::{Budget, LearnError, LearnParams, Learner, QueryOptions, QueryPlanner};
use crate::scene::{Obstacle, Robot, Scene};
use crate::short;
use crate::space::{Config, Space, SpaceKind};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;
use std::time::{Duration, Instant};

/// Why a validity run could not run (an invalid path is a result, not an error).
#[derive(Debug, thiserror::Error)]
pub enum ValidityError {
    /// Learning the roadmap failed.
    #[error("learning the roadmap of {scene}: {source}")]
    Learn {
        /// The scene.
        scene: String,
        /// Why.
        source: LearnError,
    },
    /// The roadmap's planner could not be made.
    #[error("the roadmap of {scene}: {source}")]
    Roadmap {
        /// The scene.
        scene: String,
        /// Why.
        source: RoadmapError,
    },
    /// The independent checker cannot handle this scene (mixed obstacle kinds, a mesh parry
    /// refuses).
    #[error("{scene}: no independent checker: {reason}")]
    Unsupported {
        /// The scene.
        scene: String,
        /// Why.
        reason: String,
    },
    /// A scene could not be loaded.
    #[error("{spec}: {source}")]
    Scene {
        /// The scene as named.
        spec: String,
        /// Why.
        source: crate::scene::SceneError,
    },
    /// A generated scene's description is malformed.
    #[error("{spec}: {reason}")]
    BadSpec {
        /// The description.
        spec: String,
        /// What is wrong.
        reason: String,
    },
    /// No free configuration was found to start a query from.
    #[error("{scene}: no free configuration in {attempts} samples")]
    NoFreeSpace {
        /// The scene.
        scene: String,
        /// Samples drawn.
        attempts: usize,
    },
}

/// A scene named on the command line: a scene file, or `gen:discs:dim=D,n=N,r=R,seed=S`
/// ([`disc_scene`]; `dim` 2 unless given).
pub fn load_scene(spec: &str) -> Result<Scene, ValidityError> {
    let bad = |reason: String| ValidityError::BadSpec {
        spec: spec.to_string(),
        reason,
    };
    let Some(rest) = spec.strip_prefix("gen:discs:") else {
        return Scene::load(std::path::Path::new(spec)).map_err(|source| ValidityError::Scene {
            spec: spec.to_string(),
            source,
        });
    };
    let (mut dim, mut count, mut radius, mut seed) = (2usize, None, None, 1u64);
    for kv in rest.split(',') {
        let (k, v) = kv
            .split_once('=')
            .ok_or_else(|| bad(format!("`{kv}` is not key=value")))?;
        let num = |what: &str| bad(format!("{what}: `{v}` is not a number"));
        match k {
            "dim" => dim = v.parse().map_err(|_| num("dim"))?,
            "n" => count = Some(v.parse::<usize>().map_err(|_| num("n"))?),
            "r" => radius = Some(v.parse::<f64>().map_err(|_| num("r"))?),
            "seed" => seed = v.parse().map_err(|_| num("seed"))?,
            _ => return Err(bad(format!("unknown key `{k}`; expected dim, n, r, seed"))),
        }
    }
    let count = count.ok_or_else(|| bad("n= is missing".into()))?;
    let radius = radius.ok_or_else(|| bad("r= is missing".into()))?;
    if !(1..=MAX_DIM).contains(&dim) {
        return Err(bad(format!("dim must lie in 1..={MAX_DIM}")));
    }
    if count > crate::limits::MAX_GENERATED_DISCS {
        return Err(bad(format!(
            "n must be at most {}",
            crate::limits::MAX_GENERATED_DISCS
        )));
    }
    if !(radius.is_finite() && radius > 0.0 && radius < 1.0) {
        return Err(bad("r must lie in (0, 1)".into()));
    }
    Ok(disc_scene(dim, count, radius, seed))
}

/// Largest dimension of a generated disc scene (the sweep uses 2, 3 and 6).
const MAX_DIM: usize = 16;

/// How one scene is exercised.
#[derive(Clone, Debug)]
pub struct ValidityConfig {
    /// Node budget of the roadmap (deterministic).
    pub nodes: usize,
    /// Random queries answered.
    pub queries: usize,
    /// Seed of the roadmap and of the queries.
    pub seed: u64,
    /// Time limit of one query (no growing: the roadmap answers or the query fails).
    pub query_time: Duration,
    /// Solved queries whose paths are kept in [`ValidityReport::sample`] (spread evenly over
    /// the solved ones), for a second, external check such as the OMPL peer's `check`.
    pub sample: usize,
}

/// A solved query's paths, kept for an external check.
#[derive(Clone, Debug)]
pub struct SampledPath {
    /// Index of the query in the scene's random queries.
    pub query: usize,
    /// The path before shortening.
    pub raw: Vec<Config>,
    /// The shortened path.
    pub shortened: Vec<Config>,
}

/// What one scene gave.
#[derive(Clone, Debug, Serialize)]
pub struct ValidityReport {
    /// Scene name.
    pub scene: String,
    /// Space kind (`r2`, `r6`, `se2`, `se3`).
    pub kind: String,
    /// Roadmap nodes.
    pub nodes: usize,
    /// Queries asked.
    pub queries: usize,
    /// Queries answered with a path.
    pub solved: usize,
    /// Paths (raw or shortened) the independent checker refused: must be 0.
    pub invalid: usize,
    /// Queries that ended in an error (not a failure to find a path).
    pub errors: usize,
    /// The first few refusals and errors, described.
    pub failures: Vec<String>,
    /// Seconds spent learning.
    pub learn_secs: f64,
    /// Seconds spent answering.
    pub query_secs: f64,
    /// Seconds spent checking.
    pub check_secs: f64,
    /// Paths kept for an external check ([`ValidityConfig::sample`]).
    #[serde(skip)]
    pub sample: Vec<SampledPath>,
}

/// A random disc scene in `[0, 1]^dim`: `count` closed balls of `radius` at uniform centres
/// (the R^n scenes of the sweep; CHS A.1.3's discs are the case `dim = 2`).
pub fn disc_scene(dim: usize, count: usize, radius: f64, seed: u64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let obstacles = (0..count)
        .map(|_| Obstacle::Disc {
            centre: (0..dim).map(|_| rng.random::<f64>()).collect(),
            radius,
        })
        .collect();
    Scene {
        name: format!("discs-d{dim}-n{count}-r{radius}-s{seed}"),
        space: Space::euclidean(vec![0.0; dim], vec![1.0; dim]).expect("the unit cube"),
        robot: Robot::Point,
        obstacles,
        queries: Vec::new(),
        source: None,
        warnings: Vec::new(),
    }
}

/// Learns a roadmap of `scene`, answers `cfg.queries` random queries between free
/// configurations (drawn with `cfg.seed`) and re-checks every path independently.
pub fn run_scene(scene: &Scene, cfg: &ValidityConfig) -> Result<ValidityReport, ValidityError> {
    let checker = Checker::for_scene(scene).map_err(|reason| ValidityError::Unsupported {
        scene: scene.name.clone(),
        reason,
    })?;
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let began = Instant::now();
    let learnt = Learner::for_scene(scene, oracle.as_ref(), method.as_ref())
        .learn(
            &LearnParams::default(),
            &Budget::nodes(cfg.nodes),
            cfg.seed,
            &mut |_| {},
        )
        .map_err(|source| ValidityError::Learn {
            scene: scene.name.clone(),
            source,
        })?;
    let learn_secs = began.elapsed().as_secs_f64();
    let queries = random_queries(scene, oracle.as_ref(), cfg)?;
    let planner = QueryPlanner::new(&learnt.roadmap, oracle.as_ref())
        .map_err(|source| ValidityError::Roadmap {
            scene: scene.name.clone(),
            source,
        })?
        .with_options(QueryOptions {
            time: Some(cfg.query_time),
            grow: false,
            ..QueryOptions::default()
        });
    let began = Instant::now();
    let answers = planner.query_batch(&queries);
    let query_secs = began.elapsed().as_secs_f64();
    let began = Instant::now();
    let verdicts: Vec<Verdict> = answers
        .par_iter()
        .map(|a| match &a.result {
            Err(e) => Verdict::Error(e.to_string()),
            Ok(r) if !r.is_solved() => Verdict::Unsolved,
            Ok(r) => {
                for (what, path) in [("raw", &r.raw_path), ("shortened", &r.path)] {
                    let ends = path.first() == Some(&r.start) && path.last() == Some(&r.goal);
                    if !ends {
                        return Verdict::Invalid(format!(
                            "{what} path does not join {} to {}",
                            short::config(&r.start),
                            short::config(&r.goal)
                        ));
                    }
                    if let Err(e) = checker.check_path(path) {
                        return Verdict::Invalid(format!("{what} path ({:?}): {e}", r.outcome));
                    }
                }
                Verdict::Valid
            }
        })
        .collect();
    let check_secs = began.elapsed().as_secs_f64();
    let mut report = ValidityReport {
        scene: scene.name.clone(),
        kind: scene.space.kind().to_string(),
        nodes: learnt.roadmap.node_count(),
        queries: queries.len(),
        solved: 0,
        invalid: 0,
        errors: 0,
        failures: Vec::new(),
        learn_secs,
        query_secs,
        check_secs,
        sample: Vec::new(),
    };
    let solved: Vec<usize> = answers
        .iter()
        .enumerate()
        .filter(|(_, a)| a.result.as_ref().is_ok_and(|r| r.is_solved()))
        .map(|(i, _)| i)
        .collect();
    let keep = cfg.sample.min(solved.len());
    for k in 0..keep {
        let i = solved[k * solved.len() / keep];
        if let Ok(r) = &answers[i].result {
            report.sample.push(SampledPath {
                query: i,
                raw: r.raw_path.clone(),
                shortened: r.path.clone(),
            });
        }
    }
    for (i, v) in verdicts.into_iter().enumerate() {
        match v {
            Verdict::Valid => report.solved += 1,
            Verdict::Unsolved => {}
            Verdict::Invalid(e) => {
                report.solved += 1;
                report.invalid += 1;
                if report.failures.len() < 10 {
                    report.failures.push(format!("query {i}: {e}"));
                }
            }
            Verdict::Error(e) => {
                report.errors += 1;
                if report.failures.len() < 10 {
                    report.failures.push(format!("query {i}: error: {e}"));
                }
            }
        }
    }
    Ok(report)
}

enum Verdict {
    Valid,
    Unsolved,
    Invalid(String),
    Error(String),
}

/// Random pairs of free configurations (free by the scene's oracle: the checker re-checks the
/// ends as part of every path).
fn random_queries(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    cfg: &ValidityConfig,
) -> Result<Vec<(Config, Config)>, ValidityError> {
    const ATTEMPTS: usize = 10_000;
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed ^ 0x0005_eed0_f9e7_a11d);
    let mut counts = CallCounts::default();
    let mut free = || {
        for _ in 0..ATTEMPTS {
            let q = scene.space.sample_uniform(&mut rng);
            if oracle.is_free(&q, &mut counts) {
                return Ok(q);
            }
        }
        Err(ValidityError::NoFreeSpace {
            scene: scene.name.clone(),
            attempts: ATTEMPTS,
        })
    };
    (0..cfg.queries).map(|_| Ok((free()?, free()?))).collect()
}

/// An independent path checker for one scene.
pub enum Checker {
    /// A point among closed balls in a box.
    Discs {
        /// Ball centres.
        centres: Vec<Vec<f64>>,
        /// Ball radii.
        radii: Vec<f64>,
        /// Box corners.
        lower: Vec<f64>,
        /// Box corners.
        upper: Vec<f64>,
    },
    /// Polygons in the plane.
    Planar(planar::PlanarChecker),
    /// Meshes in space.
    Rigid(rigid::RigidChecker),
    /// Several polygonal bodies in the plane.
    Bodies(bodies::BodiesChecker),
    /// A jointed arm among MoveIt collision objects: parry on the exact primitives, sampled along
    /// every joint move at `step` (1/10 of OMPL's default resolution, 0.1 % of the joint space's
    /// extent), sharing no code with the exact single-joint oracle.
    Arm {
        /// The checker.
        checker: Box<crate::robot::ArmChecker>,
        /// Sampling step in joint space.
        step: f64,
    },
}

/// Slack for rounding in the bounds and disc checks.
const TOL: f64 = 1e-9;

impl Checker {
    /// The checker of `scene`'s kind, or why there is none.
    pub fn for_scene(scene: &Scene) -> Result<Checker, String> {
        match (&scene.robot, scene.space.kind()) {
            (Robot::Point, SpaceKind::Euclidean(_)) => {
                let mut centres = Vec::new();
                let mut radii = Vec::new();
                for o in &scene.obstacles {
                    match o {
                        Obstacle::Disc { centre, radius } => {
                            centres.push(centre.clone());
                            radii.push(*radius);
                        }
                        _ => return Err("a point robot among non-disc obstacles".into()),
                    }
                }
                Ok(Checker::Discs {
                    centres,
                    radii,
                    lower: scene.space.lower().to_vec(),
                    upper: scene.space.upper().to_vec(),
                })
            }
            (Robot::Polygons(_), SpaceKind::Se2) => {
                planar::PlanarChecker::se2(scene).map(Checker::Planar)
            }
            (Robot::Mesh(_), SpaceKind::Se3) => rigid::RigidChecker::se3(scene).map(Checker::Rigid),
            (Robot::Bodies(_), SpaceKind::Se2Bodies(_)) => {
                bodies::BodiesChecker::new(scene).map(Checker::Bodies)
            }
            (Robot::Arm(a), SpaceKind::Joints { .. }) => {
                let checker =
                    crate::robot::ArmChecker::new(&a.arm, &a.objects).map_err(|e| e.to_string())?;
                let step = 0.001 * checker.arm().group.max_extent();
                Ok(Checker::Arm {
                    checker: Box::new(checker),
                    step,
                })
            }
            (r, k) => Err(format!("robot {r:?} in {k}")),
        }
    }

    /// Checks a path: every corner in the bounds, every straight motion free (touching counts
    /// as collision). Returns the first violation.
    pub fn check_path(&self, path: &[Config]) -> Result<(), String> {
        match self {
            Checker::Discs {
                centres,
                radii,
                lower,
                upper,
            } => check_disc_path(path, centres, radii, lower, upper),
            Checker::Planar(c) => c.certify_path(path),
            Checker::Rigid(c) => c.certify_path(path),
            Checker::Bodies(c) => c.certify_path(path),
            Checker::Arm { checker, step } => {
                let report = checker.check_path(path, *step).map_err(|e| e.to_string())?;
                match report.first_invalid {
                    None => Ok(()),
                    Some((segment, t, hits)) => Err(format!(
                        "segment {segment} at t = {t:.4}: {}",
                        if hits.is_empty() {
                            "outside the joint limits".to_string()
                        } else {
                            format!("{hits:?}")
                        }
                    )),
                }
            }
        }
    }
}

/// Distance from point `c` to the segment `a`–`b` (any dimension).
pub fn segment_point_distance(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
    let ac: Vec<f64> = a.iter().zip(c).map(|(x, y)| y - x).collect();
    let len2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if len2 > 0.0 {
        (ab.iter().zip(&ac).map(|(u, v)| u * v).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a.iter()
        .zip(&ab)
        .zip(c)
        .map(|((x, d), y)| (x + t * d - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn check_disc_path(
    path: &[Config],
    centres: &[Vec<f64>],
    radii: &[f64],
    lower: &[f64],
    upper: &[f64],
) -> Result<(), String> {
    for (k, q) in path.iter().enumerate() {
        if q.len() != lower.len() {
            return Err(format!(
                "corner {k} {} has the wrong dimension",
                short::config(q)
            ));
        }
        for i in 0..q.len() {
            if !(q[i] >= lower[i] - TOL && q[i] <= upper[i] + TOL) {
                return Err(format!(
                    "corner {k} {} outside the bounds",
                    short::config(q)
                ));
            }
        }
    }
    if path.len() == 1 {
        for (c, r) in centres.iter().zip(radii) {
            if segment_point_distance(&path[0], &path[0], c) <= *r {
                return Err(format!(
                    "{} lies in disc {} of radius {}",
                    short::config(&path[0]),
                    short::config(c),
                    short::num(*r)
                ));
            }
        }
    }
    for (k, w) in path.windows(2).enumerate() {
        for (c, r) in centres.iter().zip(radii) {
            let d = segment_point_distance(&w[0], &w[1], c);
            // closed balls: a segment at exactly the radius touches, and touching collides
            if d < r - TOL {
                return Err(format!(
                    "segment {k} {}→{} passes {} from disc {} of radius {}",
                    short::config(&w[0]),
                    short::config(&w[1]),
                    short::num(d),
                    short::config(c),
                    short::num(*r)
                ));
            }
        }
    }
    Ok(())
}

/// Conservative advancement over `t ∈ [0, 1]` (module docs): fails where the clearance is zero
/// or a piece shorter than 1e-10 still cannot be certified.
fn certify_by_advancement(
    rate: f64,
    clearance_at: impl Fn(f64) -> Result<f64, String>,
) -> Result<(), String> {
    let mut stack = vec![(0.0f64, 1.0f64)];
    while let Some((t0, t1)) = stack.pop() {
        let d = clearance_at(t0)?;
        if d > rate * (t1 - t0) {
            continue;
        }
        if d <= 0.0 || t1 - t0 < 1e-10 {
            return Err(format!("touches an obstacle near t = {t0} (clearance {d})"));
        }
        let m = 0.5 * (t0 + t1);
        stack.push((m, t1));
        stack.push((t0, m));
    }
    // the end itself (the loop certifies [t0, t1) pieces up to their end by continuity, but a
    // clearance of exactly 0 at t = 1 is a touch)
    let d = clearance_at(1.0)?;
    if d <= 0.0 {
        return Err(format!("touches an obstacle at t = 1 (clearance {d})"));
    }
    Ok(())
}

fn in_box(q: &[f64], lower: &[f64], upper: &[f64]) -> Result<(), String> {
    for i in 0..lower.len() {
        if !(q[i] >= lower[i] - TOL && q[i] <= upper[i] + TOL) {
            return Err(format!("{} lies outside the bounds", short::config(q)));
        }
    }
    Ok(())
}

pub mod bodies;

/// The SE(2) checker: parry2d compounds of ear-clipped triangles.
pub mod planar {
    use super::*;
    use parry2d_f64::math::{Isometry, Point};
    use parry2d_f64::shape::{Compound, SharedShape, Triangle};

    /// Ear clipping of a simple counter-clockwise polygon (independent of the library's
    /// polygon code).
    fn triangles(p: &Polygon) -> Vec<[Point<f64>; 3]> {
        let mut v: Vec<Point<f64>> = p.vertices.iter().map(|q| Point::new(q.x, q.y)).collect();
        let cross = |a: Point<f64>, b: Point<f64>, c: Point<f64>| (b - a).perp(&(c - a));
        let mut out = Vec::new();
        while v.len() > 3 {
            let n = v.len();
            let ear = (0..n).find(|&i| {
                let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
                cross(a, b, c) > 0.0
                    && v.iter().all(|&q| {
                        q == a
                            || q == b
                            || q == c
                            || !(cross(a, b, q) >= 0.0
                                && cross(b, c, q) >= 0.0
                                && cross(c, a, q) >= 0.0)
                    })
            });
            let i = ear.unwrap_or(0); // degenerate input: cut anyway (more triangles, not fewer)
            out.push([v[(i + n - 1) % n], v[i], v[(i + 1) % n]]);
            v.remove(i);
        }
        if v.len() == 3 {
            out.push([v[0], v[1], v[2]]);
        }
        out
    }

    pub(super) fn compound(polys: &[Polygon]) -> Result<Compound, String> {
        let parts: Vec<(Isometry<f64>, SharedShape)> = polys
            .iter()
            .flat_map(triangles)
            .map(|[a, b, c]| {
                (
                    Isometry::identity(),
                    SharedShape::new(Triangle::new(a, b, c)),
                )
            })
            .collect();
        if parts.is_empty() {
            return Err("no triangles".into());
        }
        Ok(Compound::new(parts))
    }

    /// Polygonal robot among polygons.
    pub struct PlanarChecker {
        robot: Compound,
        radius: f64,
        obstacles: Option<Compound>,
        lower: [f64; 2],
        upper: [f64; 2],
    }

    impl PlanarChecker {
        /// The checker of an SE(2) scene.
        pub fn se2(scene: &Scene) -> Result<PlanarChecker, String> {
            let Robot::Polygons(parts) = &scene.robot else {
                return Err("not a polygon robot".into());
            };
            let mut obstacles = Vec::new();
            for o in &scene.obstacles {
                match o {
                    Obstacle::Polygon(p) => obstacles.push(p.clone()),
                    _ => return Err("a non-polygon obstacle in SE(2)".into()),
                }
            }
            Ok(PlanarChecker {
                radius: parts
                    .iter()
                    .flat_map(|p| &p.vertices)
                    .map(|v| v.coords.norm())
                    .fold(0.0, f64::max),
                robot: compound(parts)?,
                obstacles: if obstacles.is_empty() {
                    None
                } else {
                    Some(compound(&obstacles)?)
                },
                lower: [scene.space.lower()[0], scene.space.lower()[1]],
                upper: [scene.space.upper()[0], scene.space.upper()[1]],
            })
        }

        /// Distance between the robot at `q` and the obstacles (0 when they overlap).
        pub fn clearance(&self, q: &[f64]) -> Result<f64, String> {
            let Some(obstacles) = &self.obstacles else {
                return Ok(f64::INFINITY);
            };
            let pose = Isometry::new(parry2d_f64::na::Vector2::new(q[0], q[1]), q[2]);
            parry2d_f64::query::distance(&pose, &self.robot, &Isometry::identity(), obstacles)
                .map_err(|e| format!("parry: {e}"))
        }

        /// Certifies the straight motion from `a` to `b` (position or angle, the angle the
        /// shorter way round, as the planner turns).
        pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let mut dt = (b[2] - a[2]).rem_euclid(std::f64::consts::TAU);
            if dt > std::f64::consts::PI {
                dt -= std::f64::consts::TAU;
            }
            let dp = (dx * dx + dy * dy).sqrt();
            if dp > 0.0 && dt.abs() > 1e-12 {
                return Err(format!("{a:?} → {b:?} translates and turns at once"));
            }
            let rate = dp + self.radius * dt.abs();
            let at = |t: f64| [a[0] + t * dx, a[1] + t * dy, a[2] + t * dt];
            certify_by_advancement(rate, |t| self.clearance(&at(t)))
                .map_err(|e| format!("{e} of {a:?} → {b:?}"))
        }

        /// Certifies a path: position bounds and every motion.
        pub fn certify_path(&self, path: &[Config]) -> Result<(), String> {
            for q in path {
                if q.len() != 3 {
                    return Err(format!("{q:?} is not an SE(2) configuration"));
                }
                in_box(q, &self.lower, &self.upper)?;
            }
            if let [q] = path {
                return self.certify_motion(q, q);
            }
            for w in path.windows(2) {
                self.certify_motion(&w[0], &w[1])?;
            }
            Ok(())
        }
    }
}

/// The SE(3) checker: parry3d trimeshes.
pub mod rigid {
    use super::*;
    use parry3d_f64::math::{Isometry, Translation, Vector};
    use parry3d_f64::na::{Quaternion, Unit, UnitQuaternion};
    use parry3d_f64::query::PointQuery;
    use parry3d_f64::shape::{TriMesh, TriMeshFlags};

    fn parry_mesh(m: &crate::geometry::TriMesh) -> Result<TriMesh, String> {
        TriMesh::with_flags(
            m.vertices.clone(),
            m.triangles.clone(),
            TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES,
        )
        .or_else(|_| TriMesh::new(m.vertices.clone(), m.triangles.clone()))
        .map_err(|e| format!("parry refuses a mesh: {e}"))
    }

    fn pose(q: &[f64]) -> Isometry<f64> {
        let r = UnitQuaternion::from_quaternion(Quaternion::new(q[6], q[3], q[4], q[5]));
        Isometry::from_parts(Translation::new(q[0], q[1], q[2]), r)
    }

    /// Mesh robot among meshes.
    pub struct RigidChecker {
        robot: TriMesh,
        robot_closed: bool,
        robot_radius: f64,
        obstacles: Vec<(TriMesh, bool)>,
        lower: Vec<f64>,
        upper: Vec<f64>,
    }

    impl RigidChecker {
        /// The checker of an SE(3) scene.
        pub fn se3(scene: &Scene) -> Result<RigidChecker, String> {
            let Robot::Mesh(robot) = &scene.robot else {
                return Err("not a mesh robot".into());
            };
            let mut obstacles = Vec::new();
            for o in &scene.obstacles {
                match o {
                    Obstacle::Mesh(m) => obstacles.push((parry_mesh(m)?, m.is_closed())),
                    _ => return Err("a non-mesh obstacle in SE(3)".into()),
                }
            }
            Ok(RigidChecker {
                robot_radius: robot
                    .vertices
                    .iter()
                    .map(|v| v.coords.norm())
                    .fold(0.0, f64::max),
                robot_closed: robot.is_closed(),
                robot: parry_mesh(robot)?,
                obstacles,
                lower: scene.space.lower()[..3].to_vec(),
                upper: scene.space.upper()[..3].to_vec(),
            })
        }

        /// Distance between the robot's surface at `q` and the nearest obstacle surface.
        pub fn clearance(&self, q: &[f64]) -> Result<f64, String> {
            let p = pose(q);
            let mut best = f64::INFINITY;
            for (o, _) in &self.obstacles {
                let d = parry3d_f64::query::distance(&p, &self.robot, &Isometry::identity(), o)
                    .map_err(|e| format!("parry: {e}"))?;
                best = best.min(d);
            }
            Ok(best)
        }

        fn contained(&self, q: &[f64]) -> bool {
            let p = pose(q);
            self.obstacles.iter().any(|(o, closed)| {
                (*closed
                    && self
                        .robot
                        .vertices()
                        .iter()
                        .any(|v| o.contains_point(&Isometry::identity(), &(p * v))))
                    || (self.robot_closed
                        && o.vertices()
                            .iter()
                            .any(|v| self.robot.contains_point(&p, v)))
            })
        }

        /// Certifies the straight motion from `a` to `b` (a translation, or a turn about one
        /// axis; both at once is refused: the planner never moves so).
        pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
            let ra = UnitQuaternion::from_quaternion(Quaternion::new(a[6], a[3], a[4], a[5]));
            let mut rb = UnitQuaternion::from_quaternion(Quaternion::new(b[6], b[3], b[4], b[5]));
            if ra.coords.dot(&rb.coords) < 0.0 {
                rb = UnitQuaternion::new_unchecked(-rb.into_inner());
            }
            let dp = Vector::new(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
            let rel = rb * ra.inverse();
            let angle = rel.angle();
            if dp.norm() > 0.0 && angle > 1e-12 {
                return Err(format!("{a:?} → {b:?} translates and turns at once"));
            }
            let axis = rel.axis().unwrap_or(Unit::new_normalize(Vector::x()));
            let at = |t: f64| -> Vec<f64> {
                let r = UnitQuaternion::from_axis_angle(&axis, t * angle) * ra;
                vec![
                    a[0] + t * dp.x,
                    a[1] + t * dp.y,
                    a[2] + t * dp.z,
                    r.i,
                    r.j,
                    r.k,
                    r.w,
                ]
            };
            let rate = dp.norm() + self.robot_radius * angle;
            certify_by_advancement(rate, |t| self.clearance(&at(t)))
                .map_err(|e| format!("{e} of {a:?} → {b:?}"))
        }

        /// Certifies a whole path: bounds, containment at the start, every motion.
        pub fn certify_path(&self, path: &[Config]) -> Result<(), String> {
            for q in path {
                if q.len() != 7 {
                    return Err(format!("{q:?} is not an SE(3) configuration"));
                }
                in_box(q, &self.lower, &self.upper)?;
            }
            if let Some(q) = path.first() {
                if self.contained(q) {
                    return Err(format!(
                        "the robot at {} lies inside an obstacle (or holds one)",
                        short::config(q)
                    ));
                }
            }
            if let [q] = path {
                return self.certify_motion(q, q);
            }
            for w in path.windows(2) {
                self.certify_motion(&w[0], &w[1])?;
            }
            Ok(())
        }
    }
}

/// The report as a Markdown table row set, for the terminal and the README.
pub fn table(reports: &[ValidityReport]) -> String {
    let mut s = String::from(
        "| scene | kind | nodes | queries | solved | invalid | errors | learn s | query s | check s |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in reports {
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.1} |\n",
            r.scene,
            r.kind,
            r.nodes,
            r.queries,
            r.solved,
            r.invalid,
            r.errors,
            r.learn_secs,
            r.query_secs,
            r.check_secs
        );
    }
    s
}
