//! What a local-method benchmark runs: scenes × methods × runs, the node schedule of a run, and
//! one run as a self-contained job (serialised for a child process).

use super::queries::QueryChoice;
use super::BenchError;
use crate::global::Seeding;
use crate::limits::{MAX_GENERATED_DISCS, MAX_NODES, MAX_QUERIES, MAX_RUNS, MAX_SECONDS};
use crate::local::LocalSpec;
use crate::roadmap::Sampler;
use crate::scene::{Obstacle, Robot, Scene};
use crate::space::Space;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

/// A scene named on the command line: a scene file (TOML or OMPL.app `.cfg`), or a random disc
/// scene generated from a seed, written `gen:discs:n=200,r=0.035,seed=2026` (`n` discs of
/// radius `r`, centres uniform in the unit square; the recipe of the roadmap benchmark's
/// denser scene, so the same numbers give the same scene).
#[derive(Clone, Debug, PartialEq)]
pub enum SceneSource {
    /// A scene file.
    File(PathBuf),
    /// Generated discs in the unit square.
    Discs {
        /// Number of discs.
        count: usize,
        /// Their common radius.
        radius: f64,
        /// Seed of the centres.
        seed: u64,
    },
}

impl SceneSource {
    /// Loads or generates the scene.
    pub fn load(&self) -> Result<Scene, BenchError> {
        match self {
            SceneSource::File(p) => Ok(Scene::load(p)?),
            SceneSource::Discs {
                count,
                radius,
                seed,
            } => Ok(generated_discs(*count, *radius, *seed)),
        }
    }
}

/// `count` discs of `radius`, centres uniform in the unit square, from ChaCha8 seeded with
/// `seed`.
fn generated_discs(count: usize, radius: f64, seed: u64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let obstacles = (0..count)
        .map(|_| Obstacle::Disc {
            centre: vec![rng.random::<f64>(), rng.random::<f64>()],
            radius,
        })
        .collect();
    Scene {
        name: format!("discs-n{count}-r{radius}-s{seed}"),
        space: Space::euclidean(vec![0.0, 0.0], vec![1.0, 1.0]).expect("the unit square"),
        robot: Robot::Point,
        obstacles,
        queries: Vec::new(),
        source: None,
        warnings: Vec::new(),
    }
}

impl FromStr for SceneSource {
    type Err = BenchError;
    fn from_str(s: &str) -> Result<Self, BenchError> {
        let Some(rest) = s.strip_prefix("gen:") else {
            return Ok(SceneSource::File(PathBuf::from(s)));
        };
        let bad = |why: String| BenchError::Invalid(format!("scene `{s}`: {why}"));
        let (kind, params) = rest.split_once(':').unwrap_or((rest, ""));
        if kind != "discs" {
            return Err(bad(format!("unknown generator `{kind}`; expected discs")));
        }
        let (mut count, mut radius, mut seed) = (200usize, 0.035f64, 1u64);
        for kv in params.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            let (k, v) = kv
                .split_once('=')
                .ok_or_else(|| bad(format!("`{kv}` is not key=value")))?;
            match k.trim() {
                "n" => {
                    count = v
                        .trim()
                        .parse()
                        .map_err(|_| bad(format!("n={v} is not a count")))?;
                    if count > MAX_GENERATED_DISCS {
                        return Err(bad(format!(
                            "n={v} is more than the {MAX_GENERATED_DISCS} discs a generated \
                             scene may have"
                        )));
                    }
                }
                "r" => {
                    radius = v
                        .trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|r| r.is_finite() && *r >= 0.0 && *r < 0.5)
                        .ok_or_else(|| bad(format!("r={v} must lie in [0, 0.5)")))?
                }
                "seed" => {
                    seed = v
                        .trim()
                        .parse()
                        .map_err(|_| bad(format!("seed={v} is not a whole number")))?
                }
                other => return Err(bad(format!("unknown key `{other}`; expected n, r, seed"))),
            }
        }
        Ok(SceneSource::Discs {
            count,
            radius,
            seed,
        })
    }
}

impl fmt::Display for SceneSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneSource::File(p) => write!(f, "{}", p.display()),
            SceneSource::Discs {
                count,
                radius,
                seed,
            } => write!(f, "gen:discs:n={count},r={radius},seed={seed}"),
        }
    }
}

impl Serialize for SceneSource {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for SceneSource {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// A [`LocalSpec`] in reports and child jobs as its spec string: the typed form leaves out
/// knobs that roadmap files do not record (`sidestep`).
mod spec_text {
    use crate::local::LocalSpec;
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(spec: &LocalSpec, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&spec.to_string())
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Either {
        Text(String),
        Typed(LocalSpec),
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<LocalSpec, D::Error> {
        match Either::deserialize(d)? {
            Either::Text(s) => s.parse().map_err(serde::de::Error::custom),
            Either::Typed(spec) => Ok(spec),
        }
    }
}

/// One benchmarked method: a local method, whether what it discovers is fed back into the
/// roadmap ([`crate::roadmap::LearnParams::feedback`], CHS §1.6), where construction draws
/// its nodes ([`crate::roadmap::LearnParams::sampler`]) and what the roadmap starts from
/// ([`Seeding`]: nothing, or the freeways of Brooks's cones): samplers and seedings
/// are compared like local methods, inside the same learner on the same queries.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Method {
    /// The local method (written as its spec string, which names every knob; read from a
    /// string or from the typed form of older reports).
    #[serde(with = "spec_text")]
    pub local: LocalSpec,
    /// Feedback of via points and free segments.
    pub feedback: bool,
    /// The sampler of construction.
    #[serde(default)]
    pub sampler: Sampler,
    /// What the roadmap starts from.
    #[serde(default)]
    pub seeding: Seeding,
}

impl Method {
    /// A short name: the method and the parameters that differ from its defaults, with
    /// `+nofeedback` when feedback is off, ` @SAMPLER` when the sampler is not the
    /// learner's default and ` from SEEDING` when the roadmap does not start from nothing
    /// (`viapoint`, `viapoint:beta=0.5`, `sampled:res=0.01`, `viapoint+nofeedback`,
    /// `viapoint @bridge:sigma=0.1`, `viapoint from cones`).
    pub fn label(&self) -> String {
        let mut label = self.local_label();
        if self.sampler != Sampler::default() {
            label = format!("{label} @{}", self.sampler);
        }
        if self.seeding != Seeding::Plain {
            label = format!("{label} from {}", self.seeding);
        }
        label
    }

    fn local_label(&self) -> String {
        let spec = self.local.to_string();
        let base = match &self.local {
            LocalSpec::ViaPoint(_) => {
                let default = LocalSpec::default().to_string();
                let pairs = |s: &str| -> Vec<String> {
                    s.split_once(':')
                        .map(|(_, r)| r.split(',').map(str::to_string).collect())
                        .unwrap_or_default()
                };
                let defaults = pairs(&default);
                let differing: Vec<String> = pairs(&spec)
                    .into_iter()
                    .filter(|kv| !defaults.contains(kv))
                    .collect();
                if differing.is_empty() {
                    "viapoint".to_string()
                } else {
                    format!("viapoint:{}", differing.join(","))
                }
            }
            _ => spec,
        };
        if self.feedback {
            base
        } else {
            format!("{base}+nofeedback")
        }
    }

    /// Parses method arguments: spec strings as [`LocalSpec::parse_grid`] reads them (grids
    /// expand to one method per value), each optionally followed by `+nofeedback`,
    /// `+feedback` or `+both`; without a suffix `feedback` decides (`None`: both variants).
    /// Duplicates are dropped, the order is kept.
    pub fn parse_all(items: &[String], feedback: Option<bool>) -> Result<Vec<Method>, BenchError> {
        Self::parse_all_with(items, feedback, &[Sampler::default()])
    }

    /// [`parse_all`](Self::parse_all) crossed with `samplers`: every method with every
    /// sampler, samplers varying fastest.
    pub fn parse_all_with(
        items: &[String],
        feedback: Option<bool>,
        samplers: &[Sampler],
    ) -> Result<Vec<Method>, BenchError> {
        Self::parse_all_crossed(items, feedback, samplers, &[Seeding::Plain])
    }

    /// [`parse_all_with`](Self::parse_all_with) crossed with `seedings` too: every method with
    /// every sampler and every seeding, seedings varying fastest (so `viapoint` and
    /// `viapoint from cones` stand side by side).
    pub fn parse_all_crossed(
        items: &[String],
        feedback: Option<bool>,
        samplers: &[Sampler],
        seedings: &[Seeding],
    ) -> Result<Vec<Method>, BenchError> {
        if samplers.is_empty() {
            return Err(BenchError::Invalid("no samplers given".into()));
        }
        if seedings.is_empty() {
            return Err(BenchError::Invalid("no seedings given".into()));
        }
        let mut out: Vec<Method> = Vec::new();
        for item in items {
            let (spec, variants): (&str, Vec<bool>) =
                if let Some(s) = item.strip_suffix("+nofeedback") {
                    (s, vec![false])
                } else if let Some(s) = item.strip_suffix("+feedback") {
                    (s, vec![true])
                } else if let Some(s) = item.strip_suffix("+both") {
                    (s, vec![true, false])
                } else {
                    (item, feedback.map_or(vec![true, false], |f| vec![f]))
                };
            for local in LocalSpec::parse_grid(spec)? {
                for &f in &variants {
                    for sampler in samplers {
                        for &seeding in seedings {
                            let m = Method {
                                local: local.clone(),
                                feedback: f,
                                sampler: sampler.clone(),
                                seeding,
                            };
                            if !out.contains(&m) {
                                out.push(m);
                            }
                        }
                    }
                }
            }
        }
        if out.is_empty() {
            return Err(BenchError::Invalid("no methods given".into()));
        }
        Ok(out)
    }
}

/// The node counts at which a run stops learning to answer its queries: `first`, then
/// `first · growth^k` rounded, strictly increasing, up to and including `cap`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Schedule {
    /// First stage.
    pub first: usize,
    /// Factor between stages (> 1).
    pub growth: f64,
    /// Last stage: the node cap of a run.
    pub cap: usize,
}

impl Default for Schedule {
    /// 25 nodes, growing by √2 (so two stages per doubling), up to 10 000.
    fn default() -> Self {
        Schedule {
            first: 25,
            growth: std::f64::consts::SQRT_2,
            cap: 10_000,
        }
    }
}

/// Most stages a schedule may have (each is a measurement of every query).
pub const MAX_STAGES: usize = 10_000;

impl Schedule {
    /// Checks the numbers.
    pub fn validate(&self) -> Result<(), BenchError> {
        if self.first == 0 || self.cap == 0 {
            return Err(BenchError::Invalid(
                "the first stage and the node cap must be at least 1".into(),
            ));
        }
        if !(self.growth.is_finite() && self.growth > 1.0) {
            return Err(BenchError::Invalid(format!(
                "the growth factor must be a number above 1, got {}",
                self.growth
            )));
        }
        if self.cap > MAX_NODES {
            return Err(BenchError::Invalid(format!(
                "the node cap {} is more than the {MAX_NODES} nodes a roadmap may have",
                self.cap
            )));
        }
        // stages are counted before they are listed: a growth of 1 + 1e-15 would list
        // billions of them
        let count =
            ((self.cap as f64).ln() - (self.first.min(self.cap) as f64).ln()) / self.growth.ln();
        if count > MAX_STAGES as f64 {
            return Err(BenchError::Invalid(format!(
                "the growth factor {} makes about {count:.0} stages from {} to {} nodes; \
                 at most {MAX_STAGES} are allowed",
                self.growth, self.first, self.cap
            )));
        }
        Ok(())
    }

    /// The stages.
    pub fn stages(&self) -> Vec<usize> {
        let mut out = Vec::new();
        let mut x = self.first.min(self.cap) as f64;
        loop {
            let n = (x.round() as usize).min(self.cap);
            if out.last().is_none_or(|&l| n > l) {
                out.push(n);
            }
            if n >= self.cap {
                break;
            }
            x *= self.growth;
        }
        out
    }
}

/// A whole benchmark.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// Scenes, in order.
    pub scenes: Vec<SceneSource>,
    /// Methods, in order.
    pub methods: Vec<Method>,
    /// Runs per scene and method.
    pub runs: u32,
    /// Benchmark seed: run `r` learns with seed `seed + r`; the query sets use `seed`.
    pub seed: u64,
    /// Node stages of each run.
    pub schedule: Schedule,
    /// Learning-time limit per run, seconds (not reproducible).
    pub time_limit: Option<f64>,
    /// Which queries.
    pub queries: QueryChoice,
    /// Share of the scored queries at which a run stops (0.99).
    pub target: f64,
    /// Let a query try the local method straight from start to goal before the roadmap
    /// ([`crate::roadmap::QueryOptions::try_direct`]); off measures the roadmap alone.
    pub direct: bool,
    /// Nearest nodes a query tries to attach start and goal to
    /// ([`crate::roadmap::QueryOptions::attach_candidates`]).
    pub attach: usize,
    /// Nearest nodes a side a via-point roadmap retries with the deep planner when its own
    /// method fails ([`crate::roadmap::QueryOptions::escalation_candidates`]). 0 (the
    /// benchmark's default) keeps every query to the run's own local method, so methods are
    /// compared on what their roadmaps answer; `viaroad query` escalates with 3.
    #[serde(default)]
    pub escalation: usize,
    /// The intersect calls one query may spend in the evaluations after each stage
    /// ([`crate::roadmap::QueryOptions::max_calls`]; `None`: no limit). Deep via-point
    /// settings attach start and goal with searches of thousands of calls each; a budget keeps
    /// a stage's evaluation on an SE(3) scene to seconds, reproducibly (queries that spend it
    /// count as unsolved).
    #[serde(default)]
    pub query_calls: Option<u64>,
}

impl Plan {
    /// Checks the numbers.
    pub fn validate(&self) -> Result<(), BenchError> {
        if self.scenes.is_empty() {
            return Err(BenchError::Invalid("no scenes given".into()));
        }
        if self.methods.is_empty() {
            return Err(BenchError::Invalid("no methods given".into()));
        }
        if self.runs == 0 {
            return Err(BenchError::Invalid("--runs must be at least 1".into()));
        }
        if self.runs > MAX_RUNS {
            return Err(BenchError::Invalid(format!(
                "--runs {} is more than the {MAX_RUNS} runs allowed",
                self.runs
            )));
        }
        self.schedule.validate()?;
        if let Some(t) = self.time_limit {
            if crate::limits::duration_from_secs(t).is_none() {
                return Err(BenchError::Invalid(format!(
                    "the time limit must be a positive number of seconds of at most \
                     {MAX_SECONDS:e}, got {t:?}"
                )));
            }
        }
        if let QueryChoice::Auto { count } | QueryChoice::Random { count } = self.queries {
            if count > MAX_QUERIES {
                return Err(BenchError::Invalid(format!(
                    "--queries {count} is more than the {MAX_QUERIES} random queries allowed"
                )));
            }
        }
        for m in &self.methods {
            crate::local::check_local_spec(&m.local).map_err(BenchError::Invalid)?;
        }
        if self.query_calls == Some(0) {
            return Err(BenchError::Invalid(
                "a query's call budget must be at least 1 call".into(),
            ));
        }
        if self.attach == 0 {
            return Err(BenchError::Invalid(
                "queries must try at least one node to attach to".into(),
            ));
        }
        if !(self.target > 0.0 && self.target <= 1.0) {
            return Err(BenchError::Invalid(format!(
                "the target share must lie in (0, 1], got {}",
                self.target
            )));
        }
        Ok(())
    }

    /// Whether every method's seeding can start a roadmap of `scene` (cone seeds need a planar
    /// scene): [`BenchError::Seeding`] names the first that cannot. Checked before any run, so
    /// that an SE(3) scene with `--seed-from cones` fails at once, not after hours.
    pub fn check_scene(&self, scene: &Scene) -> Result<(), BenchError> {
        for m in &self.methods {
            m.seeding
                .check(scene)
                .map_err(|source| BenchError::Seeding {
                    seeding: m.seeding,
                    scene: scene.name.clone(),
                    source,
                })?;
        }
        Ok(())
    }

    /// Every run, scene by scene; within a scene run 0 of every method, then run 1 of every
    /// method, …, so that drift of the machine over time affects the methods alike.
    pub fn jobs(&self) -> Vec<RunJob> {
        let mut out = Vec::new();
        for scene in &self.scenes {
            for run in 0..self.runs {
                for method in &self.methods {
                    out.push(RunJob {
                        scene: scene.clone(),
                        method: method.clone(),
                        run,
                        seed: self.seed.wrapping_add(u64::from(run)),
                        stages: self.schedule.stages(),
                        time_limit: self.time_limit,
                        queries: self.queries.clone(),
                        query_seed: self.seed,
                        target: self.target,
                        direct: self.direct,
                        attach: self.attach,
                        escalation: self.escalation,
                        query_calls: self.query_calls,
                        keep_paths: false,
                    });
                }
            }
        }
        out
    }
}

/// One run, self-contained: everything a child process needs to repeat it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunJob {
    /// The scene.
    pub scene: SceneSource,
    /// The method.
    pub method: Method,
    /// Index of the run (0-based).
    pub run: u32,
    /// Learning seed.
    pub seed: u64,
    /// Node stages.
    pub stages: Vec<usize>,
    /// Learning-time limit, seconds.
    pub time_limit: Option<f64>,
    /// Which queries.
    pub queries: QueryChoice,
    /// Seed of a random query set.
    pub query_seed: u64,
    /// Share of the scored queries at which the run stops.
    pub target: f64,
    /// Queries try the local method from start to goal first.
    #[serde(default = "yes")]
    pub direct: bool,
    /// Nearest nodes tried for attaching start and goal.
    #[serde(default = "default_attach")]
    pub attach: usize,
    /// Nearest nodes a side retried with the deep via-point planner (0: none).
    #[serde(default)]
    pub escalation: usize,
    /// The intersect calls one query may spend ([`Plan::query_calls`]).
    #[serde(default)]
    pub query_calls: Option<u64>,
    /// Keep the paths of the last evaluation in the record (for tests and debugging).
    #[serde(default)]
    pub keep_paths: bool,
}

fn yes() -> bool {
    true
}

fn default_attach() -> usize {
    crate::roadmap::QueryOptions::default().attach_candidates
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schedule_grows_to_the_cap() {
        let s = Schedule {
            first: 25,
            growth: 2.0,
            cap: 300,
        };
        assert_eq!(s.stages(), vec![25, 50, 100, 200, 300]);
        let s = Schedule::default().stages();
        assert_eq!(&s[..5], &[25, 35, 50, 71, 100]);
        assert_eq!(*s.last().unwrap(), 10_000);
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        let tiny = Schedule {
            first: 1,
            growth: 1.01,
            cap: 5,
        };
        assert_eq!(tiny.stages(), vec![1, 2, 3, 4, 5]);
        let capped = Schedule {
            first: 50,
            growth: 2.0,
            cap: 20,
        };
        assert_eq!(capped.stages(), vec![20]);
    }

    #[test]
    fn methods_expand_grids_and_feedback() {
        let items = vec![
            "straight".to_string(),
            "viapoint+both".to_string(),
            "viapoint:beta=0,0.5".to_string(),
            "viapoint".to_string(),
        ];
        let m = Method::parse_all(&items, Some(true)).unwrap();
        let labels: Vec<String> = m.iter().map(Method::label).collect();
        assert_eq!(
            labels,
            [
                "straight",
                "viapoint",
                "viapoint+nofeedback",
                "viapoint:beta=0",
                "viapoint:beta=0.5"
            ]
        );
        let both = Method::parse_all(&["sampled:res=0.02".to_string()], None).unwrap();
        assert_eq!(both.len(), 2);
        assert_eq!(both[1].label(), "sampled:res=0.02+nofeedback");
        assert!(Method::parse_all(&["curved".to_string()], None).is_err());
    }

    #[test]
    fn methods_cross_with_samplers() {
        let samplers: Vec<Sampler> = ["uniform", "bridge:sigma=0.05", "uniform"]
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        let m = Method::parse_all_with(
            &["straight".to_string(), "viapoint".to_string()],
            Some(true),
            &samplers,
        )
        .unwrap();
        let labels: Vec<String> = m.iter().map(Method::label).collect();
        assert_eq!(
            labels,
            [
                "straight",
                "straight @bridge:sigma=0.05",
                "viapoint",
                "viapoint @bridge:sigma=0.05"
            ]
        );
        let json = serde_json::to_string(&m[3]).unwrap();
        assert_eq!(serde_json::from_str::<Method>(&json).unwrap(), m[3]);
        assert!(Method::parse_all_with(&["viapoint".to_string()], None, &[]).is_err());
    }

    #[test]
    fn methods_cross_with_seedings() {
        let m = Method::parse_all_crossed(
            &["straight".to_string(), "viapoint".to_string()],
            Some(true),
            &[
                "uniform".parse().unwrap(),
                "bridge:sigma=0.05".parse().unwrap(),
            ],
            &[
                Seeding::Plain,
                Seeding::Cones { nodes: None },
                Seeding::Plain,
            ],
        )
        .unwrap();
        let labels: Vec<String> = m.iter().map(Method::label).collect();
        assert_eq!(
            labels,
            [
                "straight",
                "straight from cones",
                "straight @bridge:sigma=0.05",
                "straight @bridge:sigma=0.05 from cones",
                "viapoint",
                "viapoint from cones",
                "viapoint @bridge:sigma=0.05",
                "viapoint @bridge:sigma=0.05 from cones"
            ]
        );
        let json = serde_json::to_string(&m[5]).unwrap();
        assert_eq!(serde_json::from_str::<Method>(&json).unwrap(), m[5]);
        // a method recorded before seedings existed reads as plain
        let mut old = serde_json::to_value(&m[1]).unwrap();
        old.as_object_mut().unwrap().remove("seeding");
        assert_eq!(
            serde_json::from_value::<Method>(old).unwrap().seeding,
            Seeding::Plain
        );
        assert!(Method::parse_all_crossed(
            &["viapoint".to_string()],
            None,
            &[Sampler::default()],
            &[]
        )
        .is_err());
    }

    #[test]
    fn scene_sources_round_trip() {
        let s: SceneSource = "gen:discs:n=30,r=0.05,seed=7".parse().unwrap();
        assert_eq!(
            s,
            SceneSource::Discs {
                count: 30,
                radius: 0.05,
                seed: 7
            }
        );
        assert_eq!(s.to_string().parse::<SceneSource>().unwrap(), s);
        let scene = s.load().unwrap();
        assert_eq!(scene.obstacles.len(), 30);
        assert_eq!(scene, s.load().unwrap());
        for bad in [
            "gen:boxes",
            "gen:discs:r=0.7",
            "gen:discs:n=x",
            "gen:discs:q=1",
        ] {
            assert!(bad.parse::<SceneSource>().is_err(), "{bad}");
        }
        let json = serde_json::to_string(&s).unwrap();
        assert_eq!(serde_json::from_str::<SceneSource>(&json).unwrap(), s);
    }
}
