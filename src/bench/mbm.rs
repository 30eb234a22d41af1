//! MotionBenchMaker problems: every problem of a family directory planned and
//! re-checked, summarised like VAMP's `evaluate_mbm` ("Solved / Valid / Total", mean, std and
//! percentiles), and the workcell mode (one roadmap of a family's first scene answering the
//! family's requests).
//!
//! A family directory holds `sceneNNNN.yaml` (a MoveIt PlanningScene) and `requestNNNN.yaml`
//! (a MotionPlanRequest) pairs, as in MBM's `problems.tar.bz2`; a directory of family
//! directories runs them all, in name order. Each request plans for its own `group_name`
//! (the Fetch's `arm_with_torso`: eight joints, the torso's prismatic lift first).
//!
//! Each problem is planned first by the via-point planner alone (a bounded search,
//! [`MbmOptions::direct_calls`] oracle calls), then, if it did not connect, by two trees from
//! start and goal ([`Planner::Tree`], as `viaroad solve --tree`) or a roadmap grown from both
//! until they meet ([`Planner::Roadmap`], as `solve --roadmap`, OMPL PRM's `solve`), until the
//! time is up; with [`MbmOptions::race`] the via-point planner and the trees run at once; with
//! [`MbmOptions::trees_first`] (`bench mbm`'s default) the direct path, then the trees for a
//! share of the time, then the via-point search, then the trees again (the stages are
//! [`crate::portfolio`]'s, which `viaroad solve` runs on an arm scene too). The
//! returned path is shortened and then re-checked by the independent
//! [`ArmChecker`] at 1/10 of OMPL's default resolution. "Valid" is the checker's verdict on the
//! start and goal (exact shapes); the exact oracle uses circumscribed shapes, so it may refuse
//! an end the checker accepts ("valid, refused by the oracle").

use crate::deadline::{race, Deadline};
use crate::local::{path_length, LocalMethod, LocalSpec};
use crate::oracle::CollisionOracle;
pub use crate::portfolio::{tree_stage, Planning, TreeStage};
use crate::portfolio::{trees_found, Portfolio, Stage};
use crate::roadmap::query::keep::answer_keeping;
use crate::roadmap::tree::{Rooted, TreeParams};
use crate::roadmap::{
    Budget, LearnParams, Learner, QueryOptions, QueryOutcome, QueryPlanner, QueryResult, Roadmap,
};
use crate::robot::{Arm, ArmChecker, ArmOptions};
use crate::scene::arm::{arm_scene, ArmRobot};
use crate::scene::moveit::{load_motion_plan_request, load_planning_scene};
use crate::scene::{Query, Scene, SceneError};
use crate::space::Config;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What can stop a benchmark before it starts.
#[derive(Debug, thiserror::Error)]
pub enum MbmError {
    /// A directory cannot be listed, or holds no problems or no robot.
    #[error("{path}: {message}")]
    Layout {
        /// The directory.
        path: PathBuf,
        /// What is missing.
        message: String,
    },
    /// The robot cannot be loaded.
    #[error(transparent)]
    Robot(#[from] crate::robot::RobotError),
}

/// One problem: a scene and its request.
#[derive(Clone, Debug)]
pub struct Problem {
    /// The family (the directory's name).
    pub family: String,
    /// The problem's number as written (`0001`).
    pub id: String,
    /// The PlanningScene file.
    pub scene: PathBuf,
    /// The MotionPlanRequest file.
    pub request: PathBuf,
}

/// How to run the problems.
#[derive(Clone, Debug)]
pub struct MbmOptions {
    /// Planning time per problem (the grown roadmap stops there).
    pub time: Duration,
    /// Oracle calls the via-point planner alone may spend before the roadmap grows.
    pub direct_calls: u64,
    /// Seed of the grown roadmaps.
    pub seed: u64,
    /// At most this many problems per family (in name order).
    pub limit: Option<usize>,
    /// What plans after the via-point planner alone: a grown roadmap or two trees.
    pub planner: Planner,
    /// The trees' parameters ([`Planner::Tree`]).
    pub tree: TreeParams,
    /// With [`Planner::Tree`]: run the via-point planner and the trees at once on the rayon
    /// pool, the first to connect answering, rather than one after the other. They solve
    /// different problems (a deep via-point search dodges through a narrow gap the trees miss;
    /// the trees climb staircases the search does not), and the via-point search, whose calls
    /// sweep whole joint ranges, then no longer delays the trees by its failures. The value
    /// is the via-point planner's head start alone ([`race`]; zero: none).
    pub race: Option<Duration>,
    /// With [`Planner::Tree`], not racing, and a via-point budget: the direct path alone, then
    /// the trees alone for this share of [`Self::time`], then the via-point planner, then the
    /// trees afresh (another random stream) for what is left. The trees answer most problems
    /// in a few tens of milliseconds and the via-point search's calls sweep whole joint ranges
    /// (≈ 1–3 ms each), so it waits for the problems the trees do not solve soon (a goal deep
    /// in a narrow shelf); `None`: the via-point planner first, the trees after it.
    pub trees_first: Option<f64>,
    /// Shorten with straight motions of several joints at once where they are proved free
    /// ([`Planning::straight`]).
    pub straight: bool,
    /// Plan each problem this many times more after the measured run, unmeasured, each time
    /// with a fresh oracle: a profiler then sees planning rather than loading scenes.
    pub repeat: usize,
}

impl MbmOptions {
    /// The stages before a grown roadmap ([`Planner::Roadmap`]: the via-point planner alone).
    pub fn portfolio(&self) -> Portfolio {
        let trees = self.planner == Planner::Tree;
        Portfolio {
            direct_calls: self.direct_calls,
            tree: trees.then(|| self.tree.clone()),
            trees_first: self.trees_first,
            race: self.race,
            seed: self.seed,
        }
    }
}

/// The stage after the via-point planner alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Planner {
    /// A roadmap grown from start and goal until they meet (as `solve --roadmap`).
    Roadmap,
    /// Two trees from start and goal (as `solve --tree`, [`crate::roadmap::tree`]): cheap
    /// short single-joint stairs, which build the fine staircases that a roadmap's long
    /// connections do not (cage: the way in is free only as a staircase of ≥ 32 steps per
    /// joint).
    Tree,
}

impl std::str::FromStr for Planner {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "roadmap" => Ok(Planner::Roadmap),
            "tree" => Ok(Planner::Tree),
            _ => Err(format!("unknown planner {s:?} (roadmap | tree)")),
        }
    }
}

pub use crate::roadmap::tree::SHORTCUT_WINDOW;

/// The outcome of one problem.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ProblemResult {
    /// Family.
    pub family: String,
    /// Problem number.
    pub id: String,
    /// Start and goal valid for the independent checker (exact shapes): VAMP's "valid".
    pub valid: bool,
    /// Start and goal accepted by the exact oracle (circumscribed shapes).
    pub oracle_valid: bool,
    /// A path was found.
    pub solved: bool,
    /// How: `direct` (via-point planner alone), `roadmap` (grown roadmap) or `tree` (two
    /// trees); empty if unsolved.
    pub stage: String,
    /// Planning time in seconds (setup of the robot and oracle excluded, see `setup_s`).
    pub time_s: f64,
    /// Loading the problem and building the oracle, seconds.
    pub setup_s: f64,
    /// Of `time_s`: the via-point planner alone (its shortening not included), seconds.
    pub direct_s: f64,
    /// Of `time_s`: growing the trees or the roadmap, seconds.
    pub grow_s: f64,
    /// Of `time_s`: shortening the path found, seconds.
    pub shorten_s: f64,
    /// Nodes of the grown roadmap, or of both trees (0 when the via-point planner alone
    /// solved it in turn; racing, the trees' nodes when it won).
    pub nodes: usize,
    /// Intersect calls (segment + line) of the whole attempt.
    pub calls: u64,
    /// Static configuration checks.
    pub state_checks: u64,
    /// Raw path length (joint-space L2, radians).
    pub raw_length: f64,
    /// Shortened path length.
    pub length: f64,
    /// Corners of the shortened path.
    pub corners: usize,
    /// The independent checker's verdict on the shortened path at 1/10 of OMPL's resolution.
    pub certified: Option<bool>,
    /// Samples the checker took.
    pub check_samples: usize,
    /// Why the problem could not be run, if it could not.
    pub error: String,
    /// The path as found (empty if unsolved), for `bench mbm --paths-out`; not in the JSON.
    #[serde(skip)]
    pub raw_path: Vec<Config>,
    /// The path as returned, shortened (empty if unsolved).
    #[serde(skip)]
    pub path: Vec<Config>,
}

/// Lists the problems of `dir`: its own `sceneNNNN.yaml`/`requestNNNN.yaml` pairs, or those of
/// each subdirectory (a family each), in name order.
pub fn find_problems(dir: &Path, limit: Option<usize>) -> Result<Vec<Problem>, MbmError> {
    let layout = |message: String| MbmError::Layout {
        path: dir.to_path_buf(),
        message,
    };
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| layout(e.to_string()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    let own = family_problems(dir, &entries, limit);
    if !own.is_empty() {
        return Ok(own);
    }
    let mut out = Vec::new();
    for sub in entries.iter().filter(|p| p.is_dir()) {
        let mut inner: Vec<PathBuf> = std::fs::read_dir(sub)
            .map_err(|e| layout(e.to_string()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        inner.sort();
        out.extend(family_problems(sub, &inner, limit));
    }
    if out.is_empty() {
        return Err(layout(
            "no sceneNNNN.yaml + requestNNNN.yaml pairs here or one level below".into(),
        ));
    }
    Ok(out)
}

fn family_problems(dir: &Path, entries: &[PathBuf], limit: Option<usize>) -> Vec<Problem> {
    let family = dir
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut out = Vec::new();
    for p in entries {
        let Some(name) = p.file_name().and_then(|n| n.to_str()) else {
            continue;
        };
        let Some(id) = name
            .strip_prefix("scene")
            .and_then(|r| r.strip_suffix(".yaml"))
        else {
            continue;
        };
        let request = dir.join(format!("request{id}.yaml"));
        if request.is_file() {
            out.push(Problem {
                family: family.clone(),
                id: id.to_string(),
                scene: p.clone(),
                request,
            });
        }
    }
    out.truncate(limit.unwrap_or(usize::MAX));
    out
}

/// The robot of a folder: its one `.urdf` and (optional) one `.srdf`, loaded with the SRDF's
/// first group (each problem then plans for its request's group).
pub fn load_robot(dir: &Path) -> Result<Arm, MbmError> {
    load_robot_with(dir, &ArmOptions::default())
}

/// [`load_robot`] with these options (a big mesh enveloped or not).
pub fn load_robot_with(dir: &Path, options: &ArmOptions) -> Result<Arm, MbmError> {
    let find = |ext: &str| -> Result<Option<PathBuf>, MbmError> {
        let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| MbmError::Layout {
                path: dir.to_path_buf(),
                message: e.to_string(),
            })?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == ext))
            .collect();
        found.sort();
        Ok(found.into_iter().next())
    };
    let urdf = find("urdf")?.ok_or_else(|| MbmError::Layout {
        path: dir.to_path_buf(),
        message: "no .urdf file".into(),
    })?;
    let srdf = find("srdf")?;
    Ok(Arm::load(&urdf, srdf.as_deref(), options)?)
}

/// The scene of one problem: `robot` (cloned) in the problem's environment with the request's
/// start and goal as its one query.
pub fn problem_scene(robot: &Arm, p: &Problem) -> Result<Scene, SceneError> {
    let invalid = |e: crate::robot::RobotError| SceneError::Invalid {
        path: p.request.clone(),
        message: e.to_string(),
    };
    let req = load_motion_plan_request(&p.request)?;
    // the request's group, as MoveIt plans for it (the Fetch's `arm_with_torso`, not the
    // SRDF's first group `arm`)
    let mut arm = if req.group.is_empty() || req.group == robot.group.name {
        robot.clone()
    } else {
        robot.with_srdf_group(&req.group).map_err(invalid)?
    };
    let ps = load_planning_scene(&p.scene)?;
    ps.apply_to(&mut arm).map_err(invalid)?;
    let (start, goal) = req.start_goal(&mut arm).map_err(invalid)?;
    let robot = ArmRobot::new(arm, ps.objects, PathBuf::new(), None, Some(p.scene.clone()))
        .map_err(invalid)?;
    arm_scene(
        format!("{}-{}", p.family, p.id),
        robot,
        vec![Query { start, goal }],
        &p.scene,
    )
}

/// The independent checker of an arm scene.
pub fn checker(scene: &Scene) -> Option<ArmChecker> {
    match &scene.robot {
        crate::scene::Robot::Arm(a) => ArmChecker::new(&a.arm, &a.objects).ok(),
        _ => None,
    }
}

/// The checker's step: 1/10 of OMPL's default resolution (1 % of the space's extent).
pub fn check_step(checker: &ArmChecker) -> f64 {
    0.001 * checker.arm().group.max_extent()
}

/// Plans one problem (see the module docs) and re-checks the path.
pub fn run_problem(robot: &Arm, p: &Problem, o: &MbmOptions) -> ProblemResult {
    let mut r = ProblemResult {
        family: p.family.clone(),
        id: p.id.clone(),
        ..ProblemResult::default()
    };
    let began = Instant::now();
    let scene = match problem_scene(robot, p) {
        Ok(s) => s,
        Err(e) => {
            r.error = e.to_string();
            return r;
        }
    };
    let Some(check) = checker(&scene) else {
        r.error = "the independent checker cannot be built".into();
        return r;
    };
    let q = scene.queries[0].clone();
    r.valid = check.is_valid(&q.start) && check.is_valid(&q.goal);
    let oracle = scene.oracle();
    let ends = scene
        .check_config(oracle.as_ref(), "start", &q.start)
        .and_then(|s| Ok((s, scene.check_config(oracle.as_ref(), "goal", &q.goal)?)));
    r.setup_s = began.elapsed().as_secs_f64();
    let (start, goal) = match ends {
        Ok(e) => e,
        Err(e) => {
            r.error = e.to_string();
            return r;
        }
    };
    r.oracle_valid = true;
    let began = Instant::now();
    let deadline = Deadline::none().within(Some(o.time));
    let method = LocalSpec::default().build();
    let groups = method.groups(&scene.space);
    let planning = Planning {
        scene: &scene,
        oracle: oracle.as_ref(),
        groups: &groups,
        straight: o.straight,
    };
    let answer = o.portfolio().plan(&planning, (&start, &goal), &deadline);
    let mut counts = answer.counts;
    let mut path = answer.path;
    r.direct_s = answer.direct_s;
    r.grow_s = answer.grow_s;
    r.shorten_s = answer.shorten_s;
    r.nodes = answer.nodes;
    r.stage = answer.stage.map_or("", Stage::name).into();
    if let Some(e) = answer.error {
        r.error = e.to_string();
    }
    if path.is_none() && !deadline.expired() && o.planner == Planner::Roadmap {
        let growing = Instant::now();
        let spec = LocalSpec::roadmap_default();
        let method = spec.build();
        let learner = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref());
        match learner.connect_pair(
            &LearnParams::default(),
            None,
            (&start, &goal),
            &Budget {
                nodes: None,
                time: None,
            },
            o.seed,
            &deadline,
            &mut |_| {},
        ) {
            Ok(grown) => {
                r.grow_s = growing.elapsed().as_secs_f64();
                let roadmap = &grown.learnt.roadmap;
                r.nodes = roadmap.node_count();
                counts += roadmap.header().counts;
                if grown.connected {
                    if let Ok(planner) = QueryPlanner::new(roadmap, oracle.as_ref()) {
                        let planner = planner.with_options(QueryOptions {
                            landmarks: 0,
                            grow: false,
                            ..QueryOptions::default()
                        });
                        if let Ok(a) = planner.query(&start, &goal) {
                            counts += a.counts;
                            if a.is_solved() {
                                path = Some((a.raw_path, a.path));
                                r.stage = "roadmap".into();
                            }
                        }
                    }
                }
            }
            Err(e) => r.error = format!("roadmap: {e}"),
        }
    }
    r.time_s = began.elapsed().as_secs_f64();
    plan_again(o, &planning, (&start, &goal));
    r.calls = counts.intersect_calls();
    r.state_checks = counts.state_checks;
    if let Some((raw, short)) = path {
        r.solved = true;
        r.raw_length = path_length(&scene.space, &groups, &raw);
        r.length = path_length(&scene.space, &groups, &short);
        r.corners = short.len();
        if let Ok(rep) = check.check_path(&short, check_step(&check)) {
            r.certified = Some(rep.valid);
            r.check_samples = rep.samples;
        }
        r.raw_path = raw;
        r.path = short;
    }
    r
}

/// Plans the problem [`MbmOptions::repeat`] times more, unmeasured, each time with a fresh
/// oracle: one that kept the measured run's answers would answer at once.
fn plan_again(o: &MbmOptions, planning: &Planning, (start, goal): (&Config, &Config)) {
    for _ in 0..o.repeat {
        let oracle = planning.scene.oracle();
        let again = Planning {
            oracle: oracle.as_ref(),
            ..*planning
        };
        let deadline = Deadline::none().within(Some(o.time));
        o.portfolio().plan(&again, (start, goal), &deadline);
    }
}

/// Mean, standard deviation and percentiles of a sample (VAMP's `evaluate_mbm` columns).
#[derive(Clone, Debug, Default, Serialize)]
pub struct Stats {
    /// Number of values.
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// Standard deviation (population).
    pub std: f64,
    /// Smallest.
    pub min: f64,
    /// 25th percentile.
    pub p25: f64,
    /// Median.
    pub p50: f64,
    /// 75th percentile.
    pub p75: f64,
    /// 95th percentile.
    pub p95: f64,
    /// Largest.
    pub max: f64,
}

impl Stats {
    /// The statistics of `v` (linear interpolation between order statistics, as numpy's
    /// default percentile); all zero when empty.
    pub fn of(v: &[f64]) -> Stats {
        if v.is_empty() {
            return Stats::default();
        }
        let mut s = v.to_vec();
        s.sort_by(f64::total_cmp);
        let n = s.len();
        let mean = s.iter().sum::<f64>() / n as f64;
        let std = (s.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        let pct = |p: f64| {
            let x = p * (n - 1) as f64;
            let (i, f) = (x.floor() as usize, x - x.floor());
            s[i] + f * (s[(i + 1).min(n - 1)] - s[i])
        };
        Stats {
            n,
            mean,
            std,
            min: s[0],
            p25: pct(0.25),
            p50: pct(0.5),
            p75: pct(0.75),
            p95: pct(0.95),
            max: s[n - 1],
        }
    }
}

/// The summary in Markdown: per family and overall, "Solved / Valid / Total", certified
/// paths, and the statistics of time, calls, roadmap nodes and path lengths over solved
/// problems.
pub fn summary_markdown(results: &[ProblemResult]) -> String {
    let mut families: Vec<&str> = results.iter().map(|r| r.family.as_str()).collect();
    families.dedup();
    let mut out = String::new();
    out.push_str(
        "| family | solved / valid / total | oracle-refused ends | certified | time mean ms | std | p50 | p95 | max | calls mean | nodes mean | raw length mean | length mean |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut row = |name: &str, rs: Vec<&ProblemResult>| {
        let solved: Vec<&&ProblemResult> = rs.iter().filter(|r| r.solved).collect();
        let valid = rs.iter().filter(|r| r.valid).count();
        let refused = rs.iter().filter(|r| r.valid && !r.oracle_valid).count();
        let certified = solved.iter().filter(|r| r.certified == Some(true)).count();
        let t = Stats::of(&solved.iter().map(|r| r.time_s * 1e3).collect::<Vec<_>>());
        let mean = |f: &dyn Fn(&ProblemResult) -> f64| {
            Stats::of(&solved.iter().map(|r| f(r)).collect::<Vec<_>>()).mean
        };
        out.push_str(&format!(
            "| {name} | {} / {valid} / {} | {refused} | {certified} / {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.0} | {:.1} | {:.2} | {:.2} |\n",
            solved.len(),
            rs.len(),
            solved.len(),
            t.mean,
            t.std,
            t.p50,
            t.p95,
            t.max,
            mean(&|r| r.calls as f64),
            mean(&|r| r.nodes as f64),
            mean(&|r| r.raw_length),
            mean(&|r| r.length),
        ));
    };
    for f in &families {
        row(f, results.iter().filter(|r| r.family == *f).collect());
    }
    if families.len() > 1 {
        row("**all**", results.iter().collect());
    }
    out
}

/// The per-problem CSV (one header line, one line per problem).
pub fn csv(results: &[ProblemResult]) -> String {
    let mut out = String::from(
        "family,id,valid,oracle_valid,solved,stage,time_s,setup_s,direct_s,grow_s,shorten_s,nodes,calls,state_checks,raw_length,length,corners,certified,check_samples,error\n",
    );
    for r in results {
        out.push_str(&format!(
            "{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{},{},{},{:.6},{:.6},{},{},{},\"{}\"\n",
            r.family,
            r.id,
            r.valid,
            r.oracle_valid,
            r.solved,
            r.stage,
            r.time_s,
            r.setup_s,
            r.direct_s,
            r.grow_s,
            r.shorten_s,
            r.nodes,
            r.calls,
            r.state_checks,
            r.raw_length,
            r.length,
            r.corners,
            r.certified.map_or(String::new(), |c| c.to_string()),
            r.check_samples,
            r.error.replace('"', "'"),
        ));
    }
    out
}

/// The workcell result of one family: one roadmap of the first scene, the family's requests
/// asked of it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct WorkcellResult {
    /// Family.
    pub family: String,
    /// Nodes of the roadmap.
    pub nodes: usize,
    /// Learning time, seconds.
    pub learn_s: f64,
    /// Oracle calls of learning.
    pub learn_calls: u64,
    /// Loading the saved roadmap, milliseconds (median of 5 loads).
    pub load_ms: f64,
    /// Requests of the family.
    pub requests: usize,
    /// Requests whose start and goal are valid in the first scene (exact oracle).
    pub valid: usize,
    /// Valid requests answered.
    pub solved: usize,
    /// Of those, answered by the trees after the roadmap did not answer in its share of the
    /// query time.
    pub by_trees: usize,
    /// Answered paths the independent checker certifies.
    pub certified: usize,
    /// Query latency over the valid requests, milliseconds.
    pub query_ms: Stats,
    /// Each valid request's latency in request order, milliseconds (with `keep_answers`, the
    /// later ones ask a roadmap that kept the earlier answers).
    pub latencies_ms: Vec<f64>,
    /// Query latency without the answer's shortening, milliseconds: until the certified path
    /// was found (OMPL's benchmarks report `time` and `simplify_time` apart); unanswered
    /// requests count whole.
    pub found_ms: Stats,
    /// Each valid request's shortening of its answer, milliseconds, in request order (0
    /// where unanswered).
    pub shorten_ms: Vec<f64>,
    /// Each valid request's intersect calls (the query's and the trees'), in request order.
    pub calls: Vec<u64>,
    /// Lengths of the answered paths as found (joint-space L2, radians).
    pub raw_length: Stats,
    /// Lengths of the answered paths as returned, shortened.
    pub length: Stats,
    /// Answers fed back into the roadmap ([`Roadmap::with_path`]; 0 unless `keep_answers`).
    pub kept: usize,
    /// Nodes of the roadmap after the last request (more than `nodes` where answers were kept).
    pub nodes_after: usize,
    /// Example requests learnt from ([`WorkcellOptions::train`]) valid in the first scene.
    pub train_valid: usize,
    /// Of those, answered, certified and kept.
    pub train_kept: usize,
    /// Seconds of learning from the examples (part of `learn_s`).
    pub train_s: f64,
    /// Nodes of the roadmap as learnt by sampling, before the examples (`nodes` after them).
    pub sampled_nodes: usize,
    /// Edges of the roadmap as learnt by sampling (those the examples added come after them).
    pub sampled_edges: usize,
}

/// How [`run_workcell`] learns its roadmap and asks it.
#[derive(Clone, Debug)]
pub struct WorkcellOptions {
    /// What ends learning.
    pub budget: Budget,
    /// Seed of learning and of the trees.
    pub seed: u64,
    /// Time one request may take.
    pub query_time: Duration,
    /// Two trees where the roadmap gives no answer (after attaching, in half of `query_time`
    /// or beside it: [`Self::trees_from_roadmap`], [`Self::race`]): growing a copy of the roadmap does not
    /// build the fine single-joint staircases into a box or a cage (box 2 of 5, cage 0 of 4
    /// on a 200-node roadmap), the trees do.
    pub trees: Option<TreeParams>,
    /// With `trees`: ask the roadmap (for all of `query_time`) and grow the trees at once on
    /// the rayon pool, the first to answer stopping the other, rather than the trees only
    /// after the roadmap's half: the box's and the cage's requests wait for the trees. The
    /// value is the roadmap's head start alone ([`race`]; zero: none): a query handed to the
    /// pool costs more than a quick answer takes, and a tree's answer is a staircase which,
    /// kept, slows the requests after it, so the roadmap keeps the quick answers to itself.
    pub race: Option<Duration>,
    /// Feed every answer the independent checker passes back into the roadmap before the
    /// next request ([`Roadmap::with_path`], the time it takes not counted as query time): the
    /// next query from the same home pose, or into the same pocket, attaches to it.
    pub keep_answers: bool,
    /// With `keep_answers`: keep the trees that found an answer too, not only its path
    /// ([`Roadmap::with_kept`]): the next goal in the same pocket attaches to one of their
    /// ends rather than growing trees of its own.
    pub keep_trees: bool,
    /// With `trees`: each end that a free direct path attaches to one of its nearest roadmap
    /// nodes grows its tree out of that node's whole component (`RoadmapTrees`), so that
    /// the other end's tree need only reach the roadmap; in turn (no `race`) the query grows
    /// them itself after attaching ([`QueryOptions::trees`], as `viaroad query` does).
    /// `false`: both trees grow from the bare ends, as a single query's would, after the
    /// roadmap's half of the time or beside it.
    pub trees_from_roadmap: bool,
    /// Shorten with straight motions of several joints at once where they are proved free
    /// ([`QueryOptions::straight_shortcuts`], [`Planning::straight`]).
    pub straight: bool,
    /// Example requests the roadmap learns from offline, after sampling and before it is
    /// saved ([`answer_keeping`]): each valid in the first scene is answered as a query would
    /// be, and its path with the trees that found it, once the independent checker passes
    /// the path, is kept. A benchmark takes them from problems it does not ask (held out),
    /// so that no request is answered by its own kept answer.
    pub train: Vec<Problem>,
    /// The queries' [`QueryOptions::exact_shortening_limit`] (0: greedy passes alone).
    pub exact_shortening_limit: usize,
}

/// Learns a roadmap of the family's first scene ([`WorkcellOptions`]), saves it to `save_to`,
/// loads it back, and answers the start/goal pairs of every request of the family that are
/// valid in that scene, re-checking each path. With answers kept, the roadmap as it ends is
/// saved beside `save_to` (`.kept` added to its name).
pub fn run_workcell(
    robot: &Arm,
    problems: &[Problem],
    o: &WorkcellOptions,
    save_to: &Path,
) -> Result<WorkcellResult, Box<dyn std::error::Error + Send + Sync>> {
    let first = problems.first().ok_or("no problems")?;
    let scene = problem_scene(robot, first)?;
    let check = checker(&scene).ok_or("no checker")?;
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let groups = method.groups(&scene.space);
    let planning = Planning {
        scene: &scene,
        oracle: oracle.as_ref(),
        groups: &groups,
        straight: o.straight,
    };
    let options = query_options(o);
    let arm = &check.arm().clone();
    // requests are validated with an oracle of their own: the queries' oracle keeps its
    // answers (static checks among them), and a query must not find its ends checked by the
    // validation outside its time
    let validator = scene.oracle();
    let mut r = WorkcellResult {
        family: first.family.clone(),
        requests: problems.len(),
        ..WorkcellResult::default()
    };
    let workcell = Workcell {
        scene: &scene,
        oracle: oracle.as_ref(),
        validator: validator.as_ref(),
        check: &check,
        options: &options,
    };
    let (roadmap, loads) = workcell.learn_and_load(method.as_ref(), o, save_to, &mut r)?;
    r.nodes = roadmap.node_count();
    r.learn_calls = roadmap.header().counts.intersect_calls();
    r.load_ms = Stats::of(&loads).p50;
    let mut roadmap = roadmap;
    let mut times = Vec::new();
    let (mut raw_lengths, mut lengths) = (Vec::new(), Vec::new());
    let mut next = 0;
    while next < problems.len() {
        // one planner until an answer is to be kept, then a new one over the grown roadmap
        let planner = QueryPlanner::new(&roadmap, oracle.as_ref())?.with_options(options.clone());
        // the landmarks are the roadmap's, computed as it is loaded or grown, not per query
        planner.prepare();
        let mut keep = None;
        while keep.is_none() && next < problems.len() {
            next += 1;
            let Some((s, g)) = valid_request(arm, &scene, validator.as_ref(), &problems[next - 1])
            else {
                continue;
            };
            r.valid += 1;
            let t = Instant::now();
            let a = answer_request(&planner, &planning, o, (&s, &g));
            r.by_trees += a.by_trees;
            let (path, raw, grown) = (a.path, a.raw, a.grown);
            times.push(t.elapsed().as_secs_f64() * 1e3);
            r.shorten_ms.push(a.shorten_s * 1e3);
            r.calls.push(a.calls);
            if let Some(path) = path {
                r.solved += 1;
                raw_lengths.push(path_length(&scene.space, &groups, &raw));
                lengths.push(path_length(&scene.space, &groups, &path));
                let certified = check
                    .check_path(&path, check_step(&check))
                    .is_ok_and(|rep| rep.valid);
                r.certified += usize::from(certified);
                // only what the independent checker passed is kept (all of it, so far)
                let trees = grown.filter(|_| o.keep_trees);
                keep = (o.keep_answers && certified).then_some((path, trees));
            }
        }
        drop(planner);
        if let Some((path, trees)) = keep {
            let trees: Vec<&Rooted> = trees.iter().flat_map(|t| t.iter()).collect();
            roadmap = roadmap.with_kept(&path, &trees)?;
            r.kept += 1;
        }
    }
    r.nodes_after = roadmap.node_count();
    if o.keep_answers {
        let mut kept_name = save_to.as_os_str().to_owned();
        kept_name.push(".kept");
        roadmap.save(Path::new(&kept_name))?;
    }
    r.query_ms = Stats::of(&times);
    let found: Vec<f64> = times
        .iter()
        .zip(&r.shorten_ms)
        .map(|(t, s)| t - s)
        .collect();
    r.found_ms = Stats::of(&found);
    r.raw_length = Stats::of(&raw_lengths);
    r.length = Stats::of(&lengths);
    r.latencies_ms = times;
    Ok(r)
}

/// The workcell's query options: racing or in turn, trees out of the roadmap are the query's
/// own ([`QueryOptions::trees`], [`QueryOptions::race`], as `viaroad query` grows them); trees
/// from the bare ends are grown by [`answer_request`], beside the query or after its half of
/// the time.
fn query_options(o: &WorkcellOptions) -> QueryOptions {
    let in_query = o.trees_from_roadmap;
    let roadmap_time = if o.trees.is_some() && o.race.is_none() && !in_query {
        o.query_time / 2
    } else {
        o.query_time
    };
    QueryOptions {
        time: Some(roadmap_time),
        trees: o.trees.clone().filter(|_| in_query),
        race: o.race.filter(|_| in_query),
        return_trees: o.keep_trees,
        straight_shortcuts: o.straight,
        exact_shortening_limit: o.exact_shortening_limit,
        ..QueryOptions::default()
    }
}

/// What learning and training a workcell's roadmap ask: its first scene, the queries'
/// oracle, the validator's, the independent checker and the query options.
struct Workcell<'w> {
    scene: &'w Scene,
    oracle: &'w dyn CollisionOracle,
    validator: &'w dyn CollisionOracle,
    check: &'w ArmChecker,
    options: &'w QueryOptions,
}

impl Workcell<'_> {
    /// Learns the roadmap of the workcell, trains it on the example requests
    /// ([`WorkcellOptions::train`]), saves it to `save_to` and loads it back five times: the
    /// roadmap as loaded and the load times (ms), since a workcell's roadmap is learnt once
    /// and loaded for every session. Learning's figures go into `r`.
    fn learn_and_load(
        &self,
        method: &dyn LocalMethod,
        o: &WorkcellOptions,
        save_to: &Path,
        r: &mut WorkcellResult,
    ) -> Result<(Roadmap, Vec<f64>), Box<dyn std::error::Error + Send + Sync>> {
        let scene = self.scene;
        let learnt = Learner::for_scene(scene, self.oracle, method).learn(
            &LearnParams::default(),
            &o.budget,
            o.seed,
            &mut |_| {},
        )?;
        r.sampled_nodes = learnt.roadmap.node_count();
        r.sampled_edges = learnt.roadmap.edge_count();
        let began = Instant::now();
        let roadmap = self.train(learnt.roadmap, &o.train, r)?;
        r.train_s = began.elapsed().as_secs_f64();
        r.learn_s = learnt.report.elapsed.as_secs_f64() + r.train_s;
        roadmap.save(save_to)?;
        let mut loads = Vec::new();
        let mut roadmap: Option<Roadmap> = None;
        for _ in 0..5 {
            let t = Instant::now();
            roadmap = Some(Roadmap::load(save_to, scene.fingerprint())?);
            loads.push(t.elapsed().as_secs_f64() * 1e3);
        }
        let roadmap = roadmap.ok_or("not loaded")?;
        Ok((roadmap, loads))
    }

    /// `roadmap` with the answers to the example requests `train` that are valid in the first
    /// scene kept, with the trees that found them, where the independent checker certifies
    /// the path ([`answer_keeping`]).
    fn train(
        &self,
        roadmap: Roadmap,
        train: &[Problem],
        r: &mut WorkcellResult,
    ) -> Result<Roadmap, Box<dyn std::error::Error + Send + Sync>> {
        let arm = self.check.arm();
        let requests: Vec<(Config, Config)> = train
            .iter()
            .filter_map(|p| valid_request(arm, self.scene, self.validator, p))
            .collect();
        r.train_valid = requests.len();
        if requests.is_empty() {
            return Ok(roadmap);
        }
        let check = self.check;
        // the trees in turn, not racing the roadmap on the pool: which side answers first
        // would decide what is kept, and the trained roadmap would depend on the machine
        let in_turn = QueryOptions {
            race: None,
            ..self.options.clone()
        };
        let kept = answer_keeping(
            roadmap,
            self.oracle,
            &in_turn,
            &requests,
            true,
            &Deadline::none(),
            &mut |_, a| {
                a.result.as_ref().is_ok_and(|q| {
                    q.is_solved()
                        && check
                            .check_path(&q.path, check_step(check))
                            .is_ok_and(|rep| rep.valid)
                })
            },
        )?;
        r.train_kept = kept.kept;
        Ok(kept.roadmap)
    }
}

/// One request's answer and what it took.
struct Answered {
    /// The path as shortened, if solved, and as found.
    path: Option<Vec<Config>>,
    raw: Vec<Config>,
    /// The trees that found it, when they did.
    grown: Option<Box<[Rooted; 2]>>,
    shorten_s: f64,
    /// Intersection calls of the query and of the trees.
    calls: u64,
    /// 1 for each time the trees answered (the query's own, or grown here).
    by_trees: usize,
}

/// Answers one request `(s, g)` within `o.query_time`: the roadmap's query, and the trees from
/// the bare ends when they are grown here (racing it, or after it failed, as `o` says).
fn answer_request(
    planner: &QueryPlanner,
    planning: &Planning,
    o: &WorkcellOptions,
    (s, g): (&Config, &Config),
) -> Answered {
    let in_query = o.trees_from_roadmap;
    let mut by_trees = 0;
    let deadline = Deadline::none().within(Some(o.query_time));
    // the head start bounds the roadmap's search; a path it found is shortened within
    // the request's time, not handed back raw when the head start ends
    let ask_roadmap = |search: &Deadline, whole: &Deadline| {
        planner.query_finding_within(s, g, search, whole).ok()
    };
    let answers = |a: &Option<QueryResult>| a.as_ref().is_some_and(|a| a.is_solved());
    let grow_trees =
        |tree: &TreeParams, d: &Deadline| tree_stage(planning, (s, g), tree, o.seed, d, d);
    let (answer, head_start, raced) = match (&o.trees, o.race) {
        (Some(tree), Some(head_start)) if !in_query => {
            let raced = race(
                &deadline,
                head_start,
                ask_roadmap,
                answers,
                |d| grow_trees(tree, d),
                trees_found,
            );
            (raced.first, raced.head_start.flatten(), raced.second)
        }
        _ => (planner.query_within(s, g, &deadline).ok(), None, None),
    };
    let mut calls: u64 = [&head_start, &answer]
        .into_iter()
        .flatten()
        .map(|a| a.counts.intersect_calls())
        .sum();
    // the query's own trees (`QueryOptions::trees`, in turn) count as the trees'
    by_trees += usize::from(
        answer
            .as_ref()
            .is_some_and(|a| a.outcome == QueryOutcome::Trees),
    );
    let (mut path, mut raw, mut grown, mut shorten_s) = match answer.filter(|a| a.is_solved()) {
        Some(a) => (Some(a.path), a.raw_path, a.trees, a.shorten_s),
        None => (None, Vec::new(), None, 0.0),
    };
    let trees = raced.or_else(|| match (&path, &o.trees) {
        (None, Some(tree)) if !in_query => Some(grow_trees(tree, &deadline)),
        _ => None,
    });
    if let Some(Ok(found)) = trees {
        calls += found.counts.intersect_calls();
        if path.is_none() {
            if let Some((found_raw, short)) = found.path {
                path = Some(short);
                raw = found_raw;
            }
            by_trees += usize::from(path.is_some());
            grown = found.trees;
            shorten_s = found.shorten_s;
        }
    }
    Answered {
        path,
        raw,
        grown,
        shorten_s,
        calls,
        by_trees,
    }
}

/// The start and goal of problem `p`'s request, in the group's joint order, if the request
/// loads and both are free in `scene` (the workcell's first scene).
fn valid_request(
    arm: &Arm,
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    p: &Problem,
) -> Option<(Config, Config)> {
    let req = load_motion_plan_request(&p.request).ok()?;
    if !(req.group.is_empty() || req.group == arm.group.name) {
        return None;
    }
    let (s, g) = req.ends(arm).ok()?;
    let s = scene.check_config(oracle, "start", &s).ok()?;
    let g = scene.check_config(oracle, "goal", &g).ok()?;
    Some((s, g))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_interpolate_like_numpy() {
        let s = Stats::of(&[4.0, 1.0, 3.0, 2.0]);
        assert_eq!((s.min, s.max, s.mean), (1.0, 4.0, 2.5));
        assert!((s.p50 - 2.5).abs() < 1e-12);
        assert!((s.p25 - 1.75).abs() < 1e-12);
        assert!((s.p95 - 3.85).abs() < 1e-12);
        assert!((s.std - 1.25f64.sqrt()).abs() < 1e-12);
        assert_eq!(Stats::of(&[]).n, 0);
    }
}
