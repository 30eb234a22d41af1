//! `viaroad bench validity`: many random queries on every scene kind, every answered path
//! re-checked by the checkers of [`crate::checker`], which share no code with the library's
//! exact oracles: only an independent check turns "our tests pass" into "0 invalid in 100 000".
//!
//! Both the raw path and the shortened one are checked.

pub use crate::checker::{planar, rigid, segment_point_distance, Checker};
use crate::local::LocalSpec;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::roadmap::RoadmapError;
use crate::roadmap::{Budget, LearnError, LearnParams, Learner, QueryOptions, QueryPlanner};
use crate::scene::{Obstacle, Robot, Scene};
use crate::short;
use crate::space::{Config, Space};
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
