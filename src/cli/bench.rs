//! `viaroad bench`: the seed's experiments, and local methods compared inside the same
//! learner (`bench local`, see [`viaroad::bench::local`]).

use anyhow::Context;
use clap::{Args, Subcommand, ValueEnum};
use std::io::{Read, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use viaroad::bench::discs::SEED_RADIUS;
use viaroad::bench::local::report::SceneInfo;
use viaroad::bench::local::{
    machine, plots, sqlite, Method, Plan, QueryChoice, QuerySet, Report, RunJob, RunRecord,
    SceneReport, SceneSource, Schedule,
};
use viaroad::bench::tables;

/// Most problems of `bench discs`: ten times the seed's 10 000; all are generated and kept
/// (about 5 kB each) before the first is solved.
const MAX_DISC_PROBLEMS: usize = 100_000;

/// Benchmarks.
#[derive(Subcommand)]
pub enum BenchCommand {
    /// Regenerate the seed's Tables A.1–A.4 on random disc problems.
    Discs(DiscsArgs),
    /// Compare local methods (and samplers, and seedings) inside the same learner on the same scenes and
    /// queries: time and nodes to 99 % of the queries, oracle calls, memory; Markdown on
    /// stdout, CSV, JSON, an SQLite database in OMPL's benchmark schema (Planner Arena) and SVG
    /// box plots in --out.
    Local(BenchLocalArgs),
    /// Random queries on roadmaps of the given scenes, every path (raw and shortened)
    /// re-checked by independent checkers (segment–ball distances, parry with conservative
    /// advancement); prints queries, solved, invalid (must be 0) and times. Exits with an
    /// error if any path is invalid.
    Validity(ValidityArgs),
    /// MotionBenchMaker problems for an arm: per problem valid start/goal, solved,
    /// time, roadmap size, oracle calls, raw and shortened length, the path re-checked by the
    /// independent arm checker; a summary like VAMP's `evaluate_mbm` ("Solved / Valid /
    /// Total"). `--workcell`: one roadmap per family answering all its requests.
    Mbm(MbmArgs),
    /// Another planner's paths for MotionBenchMaker problems (JSON lines as the VAMP peer
    /// writes them, or a folder of `<family>_<NNNN>.path` files) certified segment by segment
    /// and, with `--repair`, repaired: proved free, colliding, undecided, repairs, times.
    Certify(BenchCertifyArgs),
    /// One run of `bench local` (internal): reads the job as JSON on stdin and prints the
    /// record as JSON on stdout.
    #[command(hide = true)]
    LocalRun,
}

/// Feedback of via points for methods without a `+feedback` / `+nofeedback` suffix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FeedbackChoice {
    /// Feedback on (the default of `LearnParams`).
    On,
    /// Feedback off.
    Off,
    /// Both variants of every method.
    Both,
}

/// Arguments of `bench local`.
#[derive(Args)]
pub struct BenchLocalArgs {
    /// Scenes: TOML or OMPL.app `.cfg` files, or generated discs such as
    /// `gen:discs:n=200,r=0.035,seed=2026`. Give them before --methods.
    #[arg(required = true)]
    pub scenes: Vec<String>,
    /// Methods: spec strings such as `straight`, `sampled:res=0.01`,
    /// `viapoint:depth=deepen-reuse,beta=0.667,via=2`, or grids like
    /// `viapoint:beta=0,0.5,0.667,1`; a suffix `+nofeedback`, `+feedback` or `+both` picks
    /// the feedback variants of one method.
    #[arg(long, num_args = 1.., default_values = ["straight", "sampled:res=0.01", "viapoint:max=3,calls=1000+both", "viapoint"])]
    pub methods: Vec<String>,
    /// Samplers of construction, each crossed with every method: `uniform`, `obstacle`,
    /// `gaussian:sigma=0.1`, `bridge:sigma=0.1`, `gap:sigma=0.1`, `bodies`,
    /// `mix:uniform=1,bridge=1,gaussian=1` (default:
    /// the learner's default sampler only).
    #[arg(long, num_args = 1.., value_name = "SPEC")]
    pub samplers: Vec<viaroad::roadmap::Sampler>,
    /// What each roadmap starts from, crossed with every method and sampler: `plain` (from
    /// nothing) or `cones` (the spine points of Brooks's freeways, planar scenes only, at most
    /// half the node cap; `cones:nodes=N` keeps at most N), e.g. `--seed-from plain cones`
    /// (default: plain only).
    #[arg(long, num_args = 1.., value_delimiter = ',', value_name = "SEEDING")]
    pub seed_from: Vec<viaroad::global::Seeding>,
    /// Runs per scene and method (run r learns with seed S + r).
    #[arg(long, default_value_t = 5)]
    pub runs: u32,
    /// Benchmark seed S; also the seed of random query sets.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Directory for summary.md, runs.csv, report.json, results.db and the SVG plots.
    #[arg(long)]
    pub out: PathBuf,
    /// Learning-time limit per run in seconds (counts then depend on the machine).
    #[arg(long)]
    pub time: Option<f64>,
    /// Node cap: the last stage of a run.
    #[arg(long, default_value_t = 10_000)]
    pub nodes: usize,
    /// Nodes of the first stage.
    #[arg(long, default_value_t = 25, help_heading = "Tuning")]
    pub first: usize,
    /// Factor between stages (default √2: two stages per doubling).
    #[arg(long, default_value_t = std::f64::consts::SQRT_2, help_heading = "Tuning")]
    pub growth: f64,
    /// Size of a random query set (scenes without an OMPL query file).
    #[arg(long, default_value_t = 100)]
    pub queries: usize,
    /// Random queries even for scenes that have an OMPL query file.
    #[arg(long, help_heading = "Tuning")]
    pub random_queries: bool,
    /// Query pairs from this file for every scene (one pair per line, OMPL's layout).
    #[arg(long, conflicts_with = "random_queries", help_heading = "Tuning")]
    pub query_file: Option<PathBuf>,
    /// Share of the scored queries at which a run stops.
    #[arg(long, default_value_t = 0.99, help_heading = "Tuning")]
    pub target: f64,
    /// Queries use the roadmap only: no try of the local method straight from start to goal
    /// (which the via-point planner often wins on its own).
    #[arg(long, help_heading = "Tuning")]
    pub no_direct: bool,
    /// Nearest nodes a query tries to attach start and goal to (each side).
    #[arg(long, default_value_t = viaroad::roadmap::QueryOptions::default().attach_candidates, help_heading = "Tuning")]
    pub attach: usize,
    /// Nearest nodes a side a via-point roadmap's query retries with the deep via-point
    /// planner when the roadmap's own method fails (`viaroad query` uses 3). 0 keeps every
    /// query to the run's own method, so methods are compared on their roadmaps alone.
    #[arg(long, default_value_t = 0, help_heading = "Tuning")]
    pub escalation: usize,
    /// The intersect calls one query may spend after each stage (attaching, direct and deeper
    /// tries; default: no limit). Bounds the evaluation of deep via-point settings on SE(3)
    /// scenes reproducibly; a query that spends it counts as unsolved.
    #[arg(long, value_name = "CALLS", help_heading = "Tuning")]
    pub query_calls: Option<u64>,
    /// Feedback for methods without a suffix.
    #[arg(long, value_enum, default_value_t = FeedbackChoice::On, help_heading = "Tuning")]
    pub feedback: FeedbackChoice,
    /// Runs at once, each in its own process with cores / J rayon threads (J > 1: more
    /// throughput, the same counts, but the runs share the machine, so times are not fair).
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Run everything in this process, one run after another (no child processes; the peak
    /// memory of a run is then measured by resetting the process's high-water mark).
    #[arg(long, help_heading = "Tuning")]
    pub in_process: bool,
}

/// Arguments of `bench discs`.
#[derive(Args)]
pub struct DiscsArgs {
    /// Number of random problems (the seed used 10 000; at most 100 000).
    #[arg(long, default_value_t = 10_000)]
    pub problems: u64,
    /// Seed of the problem generator.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Disc radius (default: the value calibrated to the seed's recursion depths, see
    /// docs/benchmarks.md).
    #[arg(long, default_value_t = SEED_RADIUS, help_heading = "Tuning")]
    pub radius: f64,
    /// Intersect calls one problem may spend (default: 100000 with plain recursion, 200000 with
    /// the tree of subproblems). The seed's largest count was 2·10⁷.
    #[arg(long, help_heading = "Tuning")]
    pub budget: Option<u64>,
    /// Only these tables, e.g. `A.1,A.4` (default: all four).
    #[arg(long, value_delimiter = ',')]
    pub tables: Vec<String>,
    /// Directory for tables.md, tables.csv and tables.json.
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs a benchmark.
pub fn run(cmd: BenchCommand) -> anyhow::Result<()> {
    match cmd {
        BenchCommand::Discs(a) => discs(a),
        BenchCommand::Local(a) => local(a),
        BenchCommand::LocalRun => local_run(),
        BenchCommand::Validity(a) => validity(a),
        BenchCommand::Mbm(a) => mbm(a),
        BenchCommand::Certify(a) => certify(a),
    }
}

/// Arguments of `bench mbm`.
#[derive(Args)]
pub struct MbmArgs {
    /// A MotionBenchMaker family directory (`sceneNNNN.yaml` + `requestNNNN.yaml`), or a
    /// directory of them (every family, in name order).
    pub dir: PathBuf,
    /// The robot's folder: its `.urdf` and `.srdf` (the SRDF's first group plans).
    #[arg(long)]
    pub robot: PathBuf,
    /// Planning seconds per problem.
    #[arg(long, default_value_t = 10.0)]
    pub time: f64,
    /// Oracle calls the via-point planner alone may spend (after the trees' first share,
    /// `--trees-first`; with `--trees-first 0` before the trees, or a roadmap, take over;
    /// racing, beside them). Its calls sweep whole joint ranges (≈ 1–3 ms each on the Panda
    /// problems against ≈ 50 µs for a tree's stair), so it is kept for what the trees do not
    /// solve soon. 0: the direct path only, then the trees.
    #[arg(long, default_value_t = 300, help_heading = "Tuning")]
    pub direct_calls: u64,
    /// At most this many problems per family.
    #[arg(long)]
    pub limit: Option<usize>,
    /// Seed of the grown roadmaps or trees (and of the workcell roadmaps).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// What plans after the via-point planner alone: `tree` (default: two trees of sliding
    /// single-joint stairs, as `solve --tree`; they build the fine staircases into the cage and
    /// the box) or `roadmap` (grown from start and goal, as `solve --roadmap`).
    #[arg(long, value_name = "PLANNER", default_value = "tree")]
    pub planner: viaroad::bench::mbm::Planner,
    /// `--planner tree`: longest extend, as a share of the joint space's extent (about 1 rad
    /// on the Panda).
    #[arg(long, value_name = "SHARE", default_value_t = viaroad::portfolio::TREE_RANGE, help_heading = "Tuning")]
    pub tree_range: f64,
    /// `--planner tree`: longest stair of an extend, as a share of the extent.
    #[arg(long, value_name = "SHARE", default_value_t = viaroad::portfolio::TREE_STAIR, help_heading = "Tuning")]
    pub tree_stair: f64,
    /// `--planner tree`: how a stair finds its free prefix (`first`, default: one first-hit
    /// call; `intervals`; `yesno`). Sliding asks blocked joints again at every stair, and the
    /// first hit (`joint_move_first_hit`) answers those without the collisions beyond it.
    #[arg(
        long,
        value_name = "MODE",
        default_value = "first",
        help_heading = "Tuning"
    )]
    pub tree_prefix: viaroad::roadmap::tree::Prefix,
    /// `--planner tree`: how an extend walks its stairs (as `solve --tree-stairs`): `whole`
    /// (the default: each stair all of it or not at all, only the extend's end a candidate
    /// nearest node), `slide` (each joint as far as it is free, a blocked joint letting the
    /// others go on) or `prefix`.
    #[arg(
        long,
        value_name = "MODE",
        default_value = "whole",
        help_heading = "Tuning"
    )]
    pub tree_stairs: viaroad::roadmap::tree::Stairs,
    /// `--planner tree`: extend the smaller tree each time (`true`, default) instead of
    /// alternating (`false`). With whole stairs a trapped extend adds nothing, and the tree of
    /// a goal in a pocket gets the effort until it is out.
    #[arg(long, value_name = "BOOL", default_value_t = true, action = clap::ArgAction::Set, help_heading = "Tuning")]
    pub tree_balance: bool,
    /// `--planner tree`: try each extend as one stair first (a yes/no call per joint), the
    /// staircase only when that is blocked (as `solve --tree-coarse`).
    #[arg(long, value_name = "BOOL", default_value_t = false, action = clap::ArgAction::Set, help_heading = "Tuning")]
    pub tree_coarse: bool,
    /// `--planner tree`: where an extend's straight motion is not proved, walk it as a
    /// staircase (`true`, as `solve --tree`) instead of giving the extend up (`false`, the
    /// default, as the portfolio that `solve` plans arm scenes with: one proof per extend).
    #[arg(long, value_name = "BOOL", default_value_t = false, action = clap::ArgAction::Set, help_heading = "Tuning")]
    pub tree_staircase: bool,
    /// `--planner tree`: restart both trees when an attempt has grown this many nodes, each
    /// later attempt with a new random stream and twice the nodes (as `solve --tree-restart`).
    /// Default: no restarts.
    #[arg(long, value_name = "NODES", help_heading = "Tuning")]
    pub tree_restart: Option<usize>,
    /// `--planner tree`: pairs of trees racing from the same ends with different random
    /// streams, on the rayon pool (`RAYON_NUM_THREADS`); the first to connect answers. 1: one.
    #[arg(long, value_name = "N", default_value_t = 1, help_heading = "Tuning")]
    pub tree_streams: usize,
    /// `--planner tree`: dynamic-domain sampling, a node's radius after its first failed
    /// extend, in extends (`--tree-range`): a sample farther from its nearest node than that is
    /// drawn again without a call (as VAMP's RRT-Connect: 4). 0: off
    #[arg(long, value_name = "EXTENDS", default_value_t = viaroad::roadmap::tree::Domain::ARM.radius, help_heading = "Tuning")]
    pub tree_domain: f64,
    /// `--planner tree`: run the via-point planner (`--direct-calls`) and the trees at once on
    /// the rayon pool, the first to connect answering, instead of one after the other; in
    /// workcell mode, the roadmap's query and the trees. With a value, the via-point planner
    /// (the roadmap's query) first runs alone for MS milliseconds and the race starts only if
    /// it has not answered: a short head start (2 ms) keeps quick answers off the pool. With
    /// no free pool thread (one thread, or a busy batch) the two run in turn.
    #[arg(long, value_name = "MS", num_args = 0..=1, default_missing_value = "0", help_heading = "Tuning")]
    pub race: Option<f64>,
    /// `--planner tree`, not racing: the direct path, then the trees alone for this share of
    /// `--time`, then the via-point planner (`--direct-calls`), then the trees afresh for the
    /// rest. `0`: the via-point planner first, the trees after it.
    #[arg(
        long,
        value_name = "SHARE",
        default_value_t = 0.2,
        help_heading = "Tuning"
    )]
    pub trees_first: f64,
    /// Plan against every link mesh as it is: without this, a mesh of more than 4 000
    /// triangles is planned against its enveloping polytope (a few hundred faces that contain
    /// it, standing off it by at most a quarter of its radius; the UR5's gripper base and
    /// force–torque sensor). The independent checker always uses the meshes.
    #[arg(long, help_heading = "Tuning")]
    pub exact_meshes: bool,
    /// Workcell mode: per family, learn one roadmap of the first scene
    /// (`--nodes`), save it in --out, load it and answer every request valid in that scene.
    #[arg(long)]
    pub workcell: bool,
    /// Nodes of each workcell roadmap.
    #[arg(long, default_value_t = 1000)]
    pub nodes: usize,
    /// Seconds one workcell query may take (it may grow the roadmap meanwhile; with `--planner
    /// tree`, half of it, and two trees from start to goal the other half where the roadmap
    /// did not answer).
    #[arg(long, default_value_t = 5.0)]
    pub query_time: f64,
    /// Workcell mode: feed every answer the independent checker passes back into the roadmap
    /// before the next request (`Roadmap::with_path`: its corners become nodes, its
    /// single-joint pieces edges), as a workcell that keeps learning from its queries would;
    /// the grown roadmap is saved as `FAMILY.roadmap.kept`. Off: every request asks the
    /// roadmap as learnt.
    #[arg(long)]
    pub keep_answers: bool,
    /// Workcell mode with `--keep-answers`: keep the trees that found an answer too
    /// (`Roadmap::with_kept`: every extend's end a node, joined to the node it grew from), so
    /// that the next goal in the same pocket attaches to them.
    #[arg(long, requires = "keep_answers", help_heading = "Tuning")]
    pub keep_trees: bool,
    /// Workcell mode: learn each roadmap from the family's last N problems too (held out: they
    /// are not asked), offline after sampling: each request valid in the first scene answered
    /// as a query, its certified path and the trees that found it kept in the roadmap before
    /// it is saved. The requests asked are the first `--limit` of the others.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub train: usize,
    /// Workcell mode: how the queries shorten their paths, as `viaroad query --shorten`
    /// (`fast`, `exact`, `greedy`; `greedy` suits a roadmap trained with `--train`).
    #[arg(long, value_enum, default_value_t = super::query::Shortening::Fast, help_heading = "Tuning")]
    pub shorten: super::query::Shortening,
    /// Workcell mode, `--planner tree`: where the trees grow from. `roadmap` (default): each
    /// end that a free direct path attaches to one of its 5 nearest roadmap nodes brings that
    /// node's component along as its tree, so the other end's tree need only reach the roadmap;
    /// `ends`: both trees grow from the bare start and goal, as a single problem's do.
    #[arg(long, value_enum, default_value_t = TreesFrom::Roadmap, help_heading = "Tuning")]
    pub trees_from: TreesFrom,
    /// Single-joint staircases only: no straight motions of several joints at once (by
    /// default they are tried where conservative advancement proves them free — start to
    /// goal, attaching, the trees' extends, shortening; `QueryOptions::straight_shortcuts`,
    /// `Planning::straight`, `TreeParams::straight`).
    #[arg(long, help_heading = "Tuning")]
    pub no_straight: bool,
    /// Directory for summary.md, problems.csv (or workcell.md) and report.json.
    #[arg(long)]
    pub out: PathBuf,
    /// Write every solved problem's path into this directory, one configuration per line in
    /// the group's joint order: `FAMILY_NNNN.path` as returned (shortened) and
    /// `FAMILY_NNNN_raw.path` as found, so that another checker (`ompl_peer armcheck`) can
    /// judge them. A problem's old files are removed before it runs, so that the files of the
    /// problems this run asked are its own (an unsolved problem leaves none).
    #[arg(long, value_name = "DIR", conflicts_with = "workcell")]
    pub paths_out: Option<PathBuf>,

    /// Plan each problem N times more after the measured run (not timed, not reported): for a
    /// profiler, which then sees planning rather than scene loading
    #[arg(long, default_value_t = 0, help_heading = "Tuning")]
    pub repeat: usize,
}

/// Where a workcell's trees grow from (`bench mbm --trees-from`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum TreesFrom {
    /// The roadmap components the ends attach to.
    Roadmap,
    /// The bare ends.
    Ends,
}

/// Runs `bench mbm`.
fn mbm(a: MbmArgs) -> anyhow::Result<()> {
    use viaroad::bench::mbm;
    let time = super::limits::parse_seconds("--time", a.time)?;
    let robot = mbm::load_robot_with(
        &a.robot,
        &viaroad::robot::ArmOptions {
            exact_meshes: a.exact_meshes,
            ..Default::default()
        },
    )?;
    for w in &robot.warnings {
        eprintln!("warning: {w}");
    }
    // held-out training problems come from the end of each family, beyond any --limit
    let limit = a.limit.filter(|_| !(a.workcell && a.train > 0));
    let problems = mbm::find_problems(&a.dir, limit)?;
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let options = mbm_options(&a, time)?;
    options.tree.validate().map_err(anyhow::Error::msg)?;
    if a.workcell {
        return mbm_workcells(&a, &robot, &problems, &options);
    }
    mbm_problems(&a, &robot, &problems, &options)
}

/// `bench mbm`'s options of each problem's planning, from the arguments.
fn mbm_options(
    a: &MbmArgs,
    time: std::time::Duration,
) -> anyhow::Result<viaroad::bench::mbm::MbmOptions> {
    use viaroad::bench::mbm;
    let race = match a.race {
        Some(ms) if !(0.0..=1e9).contains(&ms) => {
            anyhow::bail!("--race takes milliseconds from 0 to 1e9, got {ms}")
        }
        ms => ms.map(|ms| std::time::Duration::from_secs_f64(ms / 1000.0)),
    };
    if !(0.0..=1.0).contains(&a.trees_first) {
        anyhow::bail!(
            "--trees-first takes a share from 0 to 1, got {}",
            a.trees_first
        );
    }
    Ok(mbm::MbmOptions {
        time,
        direct_calls: a.direct_calls,
        trees_first: (a.trees_first > 0.0).then_some(a.trees_first),
        seed: a.seed,
        limit: a.limit,
        planner: a.planner,
        tree: viaroad::roadmap::tree::TreeParams {
            range: a.tree_range,
            stair: a.tree_stair,
            prefix: a.tree_prefix,
            stairs: a.tree_stairs,
            balance: a.tree_balance,
            coarse: a.tree_coarse,
            restart: a.tree_restart,
            streams: a.tree_streams,
            staircase: a.tree_staircase,
            domain: viaroad::roadmap::tree::Domain::with_radius(a.tree_domain),
            ..viaroad::roadmap::tree::TreeParams::default()
        },
        race,
        straight: !a.no_straight,
        repeat: a.repeat,
    })
}

/// `bench mbm --workcell`: one roadmap per family answering all its requests; a table row per
/// family, `workcell.md` and `workcell.json` in `--out`.
fn mbm_workcells(
    a: &MbmArgs,
    robot: &viaroad::robot::Arm,
    problems: &[viaroad::bench::mbm::Problem],
    options: &viaroad::bench::mbm::MbmOptions,
) -> anyhow::Result<()> {
    use super::query::Shortening;
    use viaroad::bench::mbm;
    let race = options.race;
    let workcell = mbm::WorkcellOptions {
        budget: viaroad::roadmap::Budget::nodes(a.nodes),
        seed: a.seed,
        query_time: super::limits::parse_seconds("--query-time", a.query_time)?,
        trees: (a.planner == mbm::Planner::Tree).then(|| options.tree.clone()),
        race,
        keep_answers: a.keep_answers,
        keep_trees: a.keep_trees,
        trees_from_roadmap: a.trees_from == TreesFrom::Roadmap,
        straight: !a.no_straight,
        train: Vec::new(),
        exact_shortening_limit: match a.shorten {
            Shortening::Fast => viaroad::roadmap::QueryOptions::default().exact_shortening_limit,
            Shortening::Exact => usize::MAX,
            Shortening::Greedy => 0,
            Shortening::Off => {
                anyhow::bail!("bench mbm --workcell shortens: --shorten off is not offered")
            }
        },
    };
    let mut families: Vec<String> = problems.iter().map(|p| p.family.clone()).collect();
    families.dedup();
    let mut md = String::from(
        "| family | nodes | trained on (kept) | learn s | learn calls | load ms | requests | valid in scene 1 | solved | by trees | certified | kept (nodes after) | query p50 ms | p95 ms | max ms | found p50 ms | found p95 ms | raw length p50 | length p50 |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut all = Vec::new();
    for f in &families {
        let mut ps: Vec<mbm::Problem> = problems
            .iter()
            .filter(|p| &p.family == f)
            .cloned()
            .collect();
        let train = ps.split_off(ps.len().saturating_sub(a.train));
        if ps.is_empty() {
            anyhow::bail!("{f}: --train {} leaves no problem to ask", a.train);
        }
        ps.truncate(a.limit.unwrap_or(usize::MAX));
        let workcell = mbm::WorkcellOptions {
            train,
            ..workcell.clone()
        };
        let save = a.out.join(format!("{f}.roadmap"));
        let r = mbm::run_workcell(robot, &ps, &workcell, &save)
            .map_err(|e| anyhow::anyhow!("{f}: {e}"))?;
        let line = format!(
            "| {} | {} | {} ({}) | {:.1} | {} | {:.2} | {} | {} | {} | {} | {} | {} ({}) | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |\n",
            r.family,
            r.nodes,
            r.train_valid,
            r.train_kept,
            r.learn_s,
            r.learn_calls,
            r.load_ms,
            r.requests,
            r.valid,
            r.solved,
            r.by_trees,
            r.certified,
            r.kept,
            r.nodes_after,
            r.query_ms.p50,
            r.query_ms.p95,
            r.query_ms.max,
            r.found_ms.p50,
            r.found_ms.p95,
            r.raw_length.p50,
            r.length.p50
        );
        eprint!("{line}");
        md.push_str(&line);
        all.push(r);
    }
    print!("{md}");
    super::output::save(&a.out.join("workcell.md"), md.as_bytes())?;
    super::output::save(
        &a.out.join("workcell.json"),
        serde_json::to_string_pretty(&all)?.as_bytes(),
    )?;
    Ok(())
}

/// `bench mbm`: each problem planned alone; a line per problem, `problems.csv` as it goes,
/// `summary.md` and `report.json` in `--out`, the paths in `--paths-out`.
fn mbm_problems(
    a: &MbmArgs,
    robot: &viaroad::robot::Arm,
    problems: &[viaroad::bench::mbm::Problem],
    options: &viaroad::bench::mbm::MbmOptions,
) -> anyhow::Result<()> {
    use viaroad::bench::mbm;
    if let Some(dir) = &a.paths_out {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    let mut results = Vec::new();
    for p in problems {
        let files = a.paths_out.as_ref().map(|dir| {
            let name = format!("{}_{}", p.family, p.id);
            (
                dir.join(format!("{name}.path")),
                dir.join(format!("{name}_raw.path")),
            )
        });
        if let Some((short, raw)) = &files {
            remove_stale(short)?;
            remove_stale(raw)?;
        }
        let r = mbm::run_problem(robot, p, options);
        if let (Some((short, raw)), true) = (&files, r.solved) {
            viaroad::scene::ompl_cfg::write_states(short, &r.path)?;
            viaroad::scene::ompl_cfg::write_states(raw, &r.raw_path)?;
        }
        eprintln!(
            "{} {}: valid {} solved {} ({}) {:.3} s, {} calls, {} nodes, length {:.3} → {:.3}, certified {:?}{}",
            r.family,
            r.id,
            r.valid,
            r.solved,
            r.stage,
            r.time_s,
            r.calls,
            r.nodes,
            r.raw_length,
            r.length,
            r.certified,
            if r.error.is_empty() { String::new() } else { format!(" ({})", r.error) }
        );
        results.push(r);
        // written as it goes: a long run interrupted keeps what it did
        super::output::save(&a.out.join("problems.csv"), mbm::csv(&results).as_bytes())?;
    }
    let md = mbm::summary_markdown(&results);
    print!("{md}");
    super::output::save(&a.out.join("summary.md"), md.as_bytes())?;
    super::output::save(
        &a.out.join("report.json"),
        serde_json::to_string_pretty(&results)?.as_bytes(),
    )?;
    Ok(())
}

/// Removes a regular file an earlier run left at `path` (nothing else: a directory or a device
/// of that name is an error when the file is written).
fn remove_stale(path: &std::path::Path) -> anyhow::Result<()> {
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        std::fs::remove_file(path).with_context(|| format!("removing {}", path.display()))?;
    }
    Ok(())
}

/// Arguments of `bench validity`.
#[derive(Args)]
pub struct ValidityArgs {
    /// Scenes: files (TOML, OMPL.app `.cfg`) or `gen:discs:dim=D,n=N,r=R,seed=S`.
    #[arg(required = true)]
    pub scenes: Vec<String>,
    /// Roadmap nodes per scene.
    #[arg(long, default_value_t = 500)]
    pub nodes: usize,
    /// Random queries per scene.
    #[arg(long, default_value_t = 1000)]
    pub queries: usize,
    /// Seed of the roadmaps and the queries.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Seconds one query may take.
    #[arg(long, default_value_t = 10.0)]
    pub query_time: f64,
    /// Also write the reports as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Write the raw and shortened paths of this many solved queries per OMPL.app scene as
    /// OMPL state files into `--paths-out`, for the peer's independent `check`
    /// (`benches/peer_check.sh` runs the sweep and the checks).
    #[arg(long, default_value_t = 0, requires = "paths_out")]
    pub sample: usize,
    /// Directory for the sampled paths (`SCENE-qQUERY-raw.path`, `-short.path`) and an index
    /// `paths.tsv` (cfg file, path file) of what was written.
    #[arg(long)]
    pub paths_out: Option<PathBuf>,
}

/// Writes a report's sampled paths for an OMPL.app scene; returns the index lines written.
fn write_sampled_paths(
    scene: &viaroad::scene::Scene,
    report: &viaroad::bench::validity::ValidityReport,
    dir: &std::path::Path,
) -> anyhow::Result<Vec<String>> {
    let Some(cfg) = scene
        .source
        .as_ref()
        .filter(|p| p.extension().is_some_and(|e| e == "cfg"))
    else {
        return Ok(Vec::new()); // the peer reads OMPL.app problems only
    };
    let mut lines = Vec::new();
    for s in &report.sample {
        for (what, path) in [("raw", &s.raw), ("short", &s.shortened)] {
            let file = dir.join(format!("{}-q{}-{what}.path", report.scene, s.query));
            viaroad::scene::ompl_cfg::write_states(&file, path)?;
            lines.push(format!("{}\t{}", cfg.display(), file.display()));
        }
    }
    Ok(lines)
}

fn validity(a: ValidityArgs) -> anyhow::Result<()> {
    use viaroad::bench::validity;
    let nodes = super::limits::count_in_range(
        "--nodes",
        a.nodes,
        viaroad::limits::MAX_NODES,
        "a roadmap is held in memory",
    )?;
    let queries = super::limits::count_in_range(
        "--queries",
        a.queries,
        viaroad::limits::MAX_QUERIES,
        "the queries are held in memory",
    )?;
    if !(a.query_time.is_finite() && a.query_time > 0.0 && a.query_time <= 3600.0) {
        anyhow::bail!(
            "--query-time must lie in (0, 3600] seconds, got {}",
            a.query_time
        );
    }
    let cfg = validity::ValidityConfig {
        nodes,
        queries,
        seed: a.seed,
        query_time: std::time::Duration::from_secs_f64(a.query_time),
        sample: a.sample,
    };
    if let Some(dir) = &a.paths_out {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", dir.display()))?;
    }
    let mut index = Vec::new();
    let scenes = a
        .scenes
        .iter()
        .map(|s| validity::load_scene(s))
        .collect::<Result<Vec<_>, _>>()?;
    let mut reports = Vec::new();
    for scene in &scenes {
        let r = validity::run_scene(scene, &cfg)?;
        eprintln!(
            "{}: {} queries, {} solved, {} invalid, {} errors ({:.1} s learn, {:.1} s query, {:.1} s check)",
            r.scene, r.queries, r.solved, r.invalid, r.errors, r.learn_secs, r.query_secs, r.check_secs
        );
        for f in &r.failures {
            eprintln!("  {f}");
        }
        if let Some(dir) = &a.paths_out {
            index.extend(write_sampled_paths(scene, &r, dir)?);
        }
        reports.push(r);
    }
    print!("{}", validity::table(&reports));
    let total: usize = reports.iter().map(|r| r.queries).sum();
    let solved: usize = reports.iter().map(|r| r.solved).sum();
    let invalid: usize = reports.iter().map(|r| r.invalid).sum();
    println!(
        "total: {total} queries, {solved} solved, {invalid} invalid; {} threads, {}",
        rayon::current_num_threads(),
        machine::utc_now()
    );
    if let Some(p) = &a.json {
        super::output::save(p, serde_json::to_string_pretty(&reports)?.as_bytes())?;
    }
    if let Some(dir) = &a.paths_out {
        let mut text = index.join("\n");
        text.push('\n');
        super::output::save(&dir.join("paths.tsv"), text.as_bytes())?;
    }
    if invalid > 0 {
        anyhow::bail!("{invalid} invalid paths");
    }
    Ok(())
}

fn discs(a: DiscsArgs) -> anyhow::Result<()> {
    if !(a.radius.is_finite() && a.radius > 0.0 && a.radius < 0.5) {
        anyhow::bail!("--radius must lie in (0, 0.5), got {}", a.radius);
    }
    let problems = super::limits::count_in_range(
        "--problems",
        usize::try_from(a.problems).unwrap_or(usize::MAX),
        MAX_DISC_PROBLEMS,
        "every problem is generated and kept before the first is solved",
    )? as u64;
    // the first problem says within a second whether the radius leaves solvable problems
    viaroad::bench::discs::try_problem(a.seed, 0, a.radius)?;
    let budgets = a
        .budget
        .map_or_else(tables::Budgets::default, tables::Budgets::both);
    let mut rows = tables::rows(budgets);
    if !a.tables.is_empty() {
        let known = ["A.1", "A.2", "A.3", "A.4"];
        if let Some(t) = a.tables.iter().find(|t| !known.contains(&t.as_str())) {
            anyhow::bail!("--tables: unknown table {t}; expected A.1, A.2, A.3 or A.4");
        }
        rows.retain(|r| a.tables.iter().any(|t| t == r.table));
    }
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create {}", a.out.display()))?;
    super::output::check_targets(&a.out, &["tables.md", "tables.csv", "tables.json"])?;
    let bar = super::progress::progress_bar(problems * rows.len() as u64, "problems");
    let start = std::time::Instant::now();
    tables::run_rows(&mut rows, problems, a.seed, a.radius, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let md = tables::markdown(&rows);
    println!(
        "{} problems, seed {}, disc radius {}, call budget {} (plain) / {} (re-use), {} threads, {:.1} s wall",
        a.problems,
        a.seed,
        a.radius,
        budgets.plain,
        budgets.reuse,
        rayon::current_num_threads(),
        start.elapsed().as_secs_f64()
    );
    println!("{md}");
    let write = |name: &str, text: String| -> anyhow::Result<()> {
        super::output::save(&a.out.join(name), text.as_bytes()).map(drop)
    };
    write("tables.md", md)?;
    write("tables.csv", tables::csv(&rows))?;
    write("tables.json", serde_json::to_string_pretty(&rows)?)?;
    eprintln!(
        "wrote tables.md, tables.csv, tables.json to {}",
        a.out.display()
    );
    Ok(())
}

fn local_run() -> anyhow::Result<()> {
    let mut input = String::new();
    std::io::stdin()
        .read_to_string(&mut input)
        .context("reading the job from stdin")?;
    let job: RunJob = serde_json::from_str(&input).context("the job is not valid JSON")?;
    let record = viaroad::bench::local::run_job(&job)?;
    let mut out = std::io::stdout().lock();
    serde_json::to_writer(&mut out, &record)?;
    writeln!(out)?;
    Ok(())
}

/// Runs one job in a child process (`viaroad bench local-run`), with `threads` rayon threads
/// if given.
fn run_child(job: &RunJob, threads: Option<usize>) -> anyhow::Result<RunRecord> {
    let exe = std::env::current_exe().context("cannot find the viaroad executable")?;
    let mut cmd = std::process::Command::new(exe);
    cmd.args(["bench", "local-run"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    if let Some(t) = threads {
        cmd.env("RAYON_NUM_THREADS", t.to_string());
    }
    let mut child = cmd.spawn().context("cannot start a child process")?;
    let input = serde_json::to_vec(job)?;
    if let Some(mut stdin) = child.stdin.take() {
        stdin
            .write_all(&input)
            .context("writing the job to the child")?;
    }
    let output = child.wait_with_output().context("waiting for the child")?;
    if !output.status.success() {
        let err = String::from_utf8_lossy(&output.stderr);
        let line = err
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .unwrap_or("no message");
        anyhow::bail!("{} ({})", line.trim(), output.status);
    }
    serde_json::from_slice(&output.stdout).context("the child's record is not valid JSON")
}

fn local(a: BenchLocalArgs) -> anyhow::Result<()> {
    // this process writes jobs to its children's pipes: a child that died is an error of
    // that run, not a reason for the whole benchmark to end by SIGPIPE
    super::output::ignore_sigpipe();
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let date = machine::utc_now();
    let began = std::time::Instant::now();
    let plan = local_plan(&a)?;
    // outputs that could not be saved are refused before the scenes load and the runs run
    super::output::check_targets(
        &a.out,
        &["summary.md", "runs.csv", "report.json", "results.db"],
    )?;
    let loaded = load_scenes(&plan)?;
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create {}", a.out.display()))?;
    let jobs = plan.jobs();
    let results = run_jobs(&a, &plan, &jobs, &loaded);
    let (records, failures) = records_and_failures(&jobs, results);
    let scenes = scene_reports(&plan, &loaded, &records);
    let report = Report {
        date,
        host: machine::hostname(),
        cpu: machine::cpu_info(),
        command,
        version: env!("CARGO_PKG_VERSION").to_string(),
        plan,
        wall_seconds: began.elapsed().as_secs_f64(),
        scenes,
        failures,
    };
    write_local_report(&a, &report)?;
    if !report.failures.is_empty() {
        anyhow::bail!(
            "{} run(s) failed (listed in summary.md)",
            report.failures.len()
        );
    }
    Ok(())
}

/// The benchmark's plan from the arguments: scenes, the methods crossed with the samplers
/// and seedings, the query sets, the stages; validated.
fn local_plan(a: &BenchLocalArgs) -> anyhow::Result<Plan> {
    let scenes: Vec<SceneSource> = a
        .scenes
        .iter()
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    let feedback = match a.feedback {
        FeedbackChoice::On => Some(true),
        FeedbackChoice::Off => Some(false),
        FeedbackChoice::Both => None,
    };
    let samplers = if a.samplers.is_empty() {
        vec![viaroad::roadmap::Sampler::default()]
    } else {
        a.samplers.clone()
    };
    let seedings = if a.seed_from.is_empty() {
        vec![viaroad::global::Seeding::Plain]
    } else {
        a.seed_from.clone()
    };
    let methods = Method::parse_all_crossed(&a.methods, feedback, &samplers, &seedings)?;
    let queries = match (&a.query_file, a.random_queries) {
        (Some(f), _) => QueryChoice::File(f.clone()),
        (None, true) => QueryChoice::Random { count: a.queries },
        (None, false) => QueryChoice::Auto { count: a.queries },
    };
    let plan = Plan {
        scenes,
        methods,
        runs: a.runs,
        seed: a.seed,
        schedule: Schedule {
            first: a.first,
            growth: a.growth,
            cap: a.nodes,
        },
        time_limit: a.time,
        queries,
        target: a.target,
        direct: !a.no_direct,
        attach: a.attach,
        escalation: a.escalation,
        query_calls: a.query_calls,
    };
    plan.validate()?;
    if a.jobs == 0 {
        anyhow::bail!("--jobs must be at least 1");
    }
    Ok(plan)
}

/// Every scene of the plan with its query set, loaded before any run so that errors show
/// before hours of running.
fn load_scenes(plan: &Plan) -> anyhow::Result<Vec<(viaroad::scene::Scene, QuerySet)>> {
    let mut loaded = Vec::new();
    for source in &plan.scenes {
        let scene = source.load().with_context(|| format!("scene {source}"))?;
        plan.check_scene(&scene)?;
        let set = QuerySet::build(&scene, &plan.queries, plan.seed)
            .with_context(|| format!("query set of {source}"))?;
        eprintln!(
            "{}: {} queries from {} ({} scored, {} apart, {} invalid)",
            scene.name,
            set.len(),
            set.source,
            set.scored().len(),
            set.separate().len(),
            set.invalid().len()
        );
        loaded.push((scene, set));
    }
    Ok(loaded)
}

/// What each job ended with, in job order (`None`: not run).
type JobResults = Vec<Mutex<Option<Result<RunRecord, String>>>>;

/// Runs the jobs under a progress bar: in this process one after another (`--in-process`),
/// else in child processes, `--jobs` at a time.
fn run_jobs(
    a: &BenchLocalArgs,
    plan: &Plan,
    jobs: &[RunJob],
    loaded: &[(viaroad::scene::Scene, QuerySet)],
) -> JobResults {
    let bar = super::progress::progress_bar(jobs.len() as u64, "runs");
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{prefix:>12} [{bar:40}] {pos}/{len} {elapsed_precise} eta {eta} {msg}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    let label = |job: &RunJob| format!("{} / {} / run {}", job.scene, job.method.label(), job.run);
    let results: JobResults = jobs.iter().map(|_| Mutex::new(None)).collect();
    if a.in_process {
        for (k, job) in jobs.iter().enumerate() {
            bar.set_message(label(job));
            let (scene, set) = &loaded[plan
                .scenes
                .iter()
                .position(|s| *s == job.scene)
                .unwrap_or(0)];
            let r = viaroad::bench::local::run_on(scene, set, job).map_err(|e| e.to_string());
            *results[k].lock().expect("no poisoned lock") = Some(r);
            bar.inc(1);
        }
    } else {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let threads = (a.jobs > 1).then(|| (cores / a.jobs).max(1));
        let next = AtomicUsize::new(0);
        std::thread::scope(|scope| {
            for _ in 0..a.jobs.min(jobs.len()) {
                scope.spawn(|| loop {
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    let Some(job) = jobs.get(k) else { break };
                    bar.set_message(label(job));
                    let r = run_child(job, threads).map_err(|e| format!("{e:#}"));
                    *results[k].lock().expect("no poisoned lock") = Some(r);
                    bar.inc(1);
                });
            }
        });
    }
    bar.finish_and_clear();
    results
}

/// The records of the runs that ended, and a line for each run that failed or did not run.
fn records_and_failures(jobs: &[RunJob], results: JobResults) -> (Vec<RunRecord>, Vec<String>) {
    let mut failures = Vec::new();
    let mut records: Vec<RunRecord> = Vec::new();
    for (job, r) in jobs.iter().zip(results) {
        match r.into_inner().expect("no poisoned lock") {
            Some(Ok(rec)) => records.push(rec),
            Some(Err(e)) => failures.push(format!(
                "{} / {} / run {}: {e}",
                job.scene,
                job.method.label(),
                job.run
            )),
            None => failures.push(format!(
                "{} / {} / run {}: not run",
                job.scene,
                job.method.label(),
                job.run
            )),
        }
    }
    (records, failures)
}

/// One report per scene, of its runs by method.
fn scene_reports(
    plan: &Plan,
    loaded: &[(viaroad::scene::Scene, QuerySet)],
    records: &[RunRecord],
) -> Vec<SceneReport> {
    let labels: Vec<String> = plan.methods.iter().map(Method::label).collect();
    plan.scenes
        .iter()
        .zip(loaded)
        .map(|(source, (scene, set))| {
            let src = source.to_string();
            let runs: Vec<RunRecord> = records
                .iter()
                .filter(|r| r.scene_source == src)
                .cloned()
                .collect();
            SceneReport::build(
                SceneInfo::new(&scene.name, &src, set),
                &labels,
                runs,
                plan.target,
            )
        })
        .collect()
}

/// The summary on stdout, and every output file in `--out`.
fn write_local_report(a: &BenchLocalArgs, report: &Report) -> anyhow::Result<()> {
    let md = report.markdown();
    super::output::print_quietly(&md)?;
    let write = |name: &str, text: String| -> anyhow::Result<()> {
        super::output::save(&a.out.join(name), text.as_bytes()).map(drop)
    };
    write("summary.md", md)?;
    write("runs.csv", report.csv())?;
    write("report.json", report.json()?)?;
    sqlite::write_database(&a.out.join("results.db"), report)?;
    let svgs = plots::write_plots(&a.out, report)?;
    eprintln!(
        "wrote summary.md, runs.csv, report.json, results.db (OMPL benchmark schema) and {} plots to {}",
        svgs.len(),
        a.out.display()
    );
    Ok(())
}

/// Arguments of `bench certify`.
#[derive(Args)]
pub struct BenchCertifyArgs {
    /// The paths: a JSON lines file (`family`, `index`, `path` per line) or a folder of
    /// `<family>_<NNNN>.path` files (OMPL state files in the group's joint order).
    pub input: PathBuf,
    /// The robot's folder: its `.urdf` and `.srdf`.
    #[arg(long)]
    pub robot: PathBuf,
    /// The MotionBenchMaker problems: a folder of family folders (`<family>_<robot>` or
    /// `<family>`, each with `sceneNNNN.yaml` and `requestNNNN.yaml`).
    #[arg(long)]
    pub problems: PathBuf,
    /// Repair the paths not proved free, within this many seconds each (0: no repair).
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0)]
    pub repair: f64,
    /// Seconds to certify one path.
    #[arg(long, value_name = "SECONDS", default_value_t = 60.0)]
    pub time: f64,
    /// At most this many paths.
    #[arg(long)]
    pub limit: Option<usize>,
    /// Only this family (the planner's name, e.g. `table_pick`).
    #[arg(long)]
    pub family: Option<String>,
    /// The robot's big meshes exactly rather than enveloped (as `bench mbm`).
    #[arg(long)]
    pub exact_meshes: bool,
    /// One JSON object per path to this file (witnesses and repaired paths included).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

fn certify(a: BenchCertifyArgs) -> anyhow::Result<()> {
    use std::io::Write;
    use viaroad::bench::certify as bc;
    let time = super::limits::parse_seconds("--time", a.time)?;
    let repair = if a.repair > 0.0 {
        Some(super::limits::parse_seconds("--repair", a.repair)?)
    } else {
        None
    };
    let arm = viaroad::bench::mbm::load_robot_with(
        &a.robot,
        &viaroad::robot::ArmOptions {
            exact_meshes: a.exact_meshes,
            ..Default::default()
        },
    )?;
    let robot_name = arm.model.urdf.name.clone();
    let mut entries = bc::read_entries(&a.input)?;
    if let Some(f) = &a.family {
        entries.retain(|e| &e.family == f);
    }
    entries.truncate(a.limit.unwrap_or(usize::MAX));
    let options = bc::BenchCertifyOptions {
        repair: repair.map(|t| viaroad::certify::RepairOptions {
            time: Some(t),
            ..Default::default()
        }),
        time: Some(time),
    };
    let mut out = match &a.out {
        Some(p) => Some(std::io::BufWriter::new(
            std::fs::File::create(p).with_context(|| format!("creating {}", p.display()))?,
        )),
        None => None,
    };
    let bar = super::progress::progress_bar(entries.len() as u64, "certify");
    let mut results = Vec::with_capacity(entries.len());
    for e in &entries {
        let r = bc::run_entry(&arm, &robot_name, &a.problems, e, &options);
        if let Some(w) = out.as_mut() {
            writeln!(w, "{}", serde_json::to_string(&r)?)?;
        }
        results.push(r);
        bar.inc(1);
    }
    bar.finish_and_clear();
    if let Some(mut w) = out {
        w.flush()?;
    }
    print!("{}", bc::summary_markdown(&results));
    Ok(())
}
