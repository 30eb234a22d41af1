//! The arguments of `solve` and what its planners share (`solve` dispatches to them; they are
//! below it): one query solved by the local method, the set-up of a single-query planner.

use super::local_args::LocalArgs;
use anyhow::Context;
use clap::Args;
use std::path::PathBuf;
use viaroad::deadline::Deadline;
use viaroad::local::{shorten, LocalSpec};
use viaroad::oracle::CollisionOracle;
use viaroad::scene::Scene;

/// Arguments of `solve`.
#[derive(Args)]
pub struct SolveArgs {
    /// Scene file (.toml or OMPL.app .cfg).
    pub scene: PathBuf,
    /// One JSON object per query on stdout.
    #[arg(long)]
    pub json: bool,
    /// Write each solved query's shortened path as an OMPL state file (one state per line);
    /// several queries get `-1`, `-2`, … before the extension.
    #[arg(long, value_name = "FILE")]
    pub path_out: Option<PathBuf>,
    /// Re-check every solved path, raw and shortened, with the scene's independent checker
    /// (as `query --check`), outside the query's time: each solved query says `certified` or
    /// why not (JSON: `"certified"`, `"check_error"`).
    #[arg(long)]
    pub check: bool,
    /// Seconds each query may take (checked before every oracle call). Default: the `.cfg`
    /// file's `[benchmark] time_limit`, else 60 s; no limit for the local method alone.
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Most nodes of the trees and roadmaps a query grows: a budget that gives the same answer
    /// on any machine. With `--nodes` and no `--time` there is no time limit.
    #[arg(long, conflicts_with = "local_only")]
    pub nodes: Option<usize>,
    /// Seed of the trees and roadmaps a query grows.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The local method alone (the via-point planner unless `--local` names another): no trees,
    /// no roadmap; it ends at its recursion depth. Implied by `--local`, `--beta`, `--via` and
    /// `--depth` without `--roadmap`.
    #[arg(long, group = "mode")]
    pub local_only: bool,
    /// A roadmap grown from start and goal alone (OMPL's PRM `solve`) with the roadmap's local
    /// method (`--local` picks another), answered through once they meet.
    #[arg(long, group = "mode")]
    pub roadmap: bool,
    /// Two trees alone (OMPL's RRTConnect `solve`) whose extends are staircases of
    /// single-group motions, each as far as it is free.
    #[arg(long, group = "mode")]
    pub tree: bool,
    #[command(flatten, next_help_heading = "Local method")]
    pub local: LocalArgs,
    /// Answer with a global method instead: `cones`, Brooks's freeways (generalized cones
    /// searched with A*; planar scenes; incomplete by design, see docs/freeways.md).
    #[arg(
        long,
        value_name = "METHOD",
        conflicts_with = "mode",
        help_heading = "Other planners"
    )]
    pub global: Option<String>,
    /// Collision oracle: `minkowski` answers through the C-obstacles of a robot that keeps
    /// each query's orientation and only translates (se2 scenes whose queries do not turn).
    #[arg(long, value_name = "ORACLE", conflicts_with_all = ["roadmap", "tree", "global"], help_heading = "Other planners")]
    pub oracle: Option<String>,
    /// Keep to single-joint (single-group) staircases: no straight motions of several joints
    /// at once, neither as the trees' extends nor as shortcuts (as `query --no-straight`).
    #[arg(long, help_heading = "Tuning")]
    pub no_straight: bool,
    /// Where the grown roadmap draws new nodes (`--roadmap`, and the roadmap the default races
    /// against the trees; as `build --sampler`): `uniform`, `obstacle`, `gaussian:sigma=0.1`,
    /// `bridge:sigma=0.1`, `gap:sigma=0.1`, `bodies` (several bodies placed one at a time), or a
    /// mix such as `mix:uniform=1,bridge=1`. Default: the learner's.
    #[arg(long, value_name = "SPEC", conflicts_with_all = ["tree", "local_only", "global", "oracle"], help_heading = "Tuning")]
    pub sampler: Option<viaroad::roadmap::Sampler>,
    /// Share of the grown roadmap's expansion walks that are directed, RRT-Connect style
    /// (`--roadmap`; 0: random bounces only). Default: the learner's.
    #[arg(long, value_name = "SHARE", help_heading = "Tuning")]
    pub directed_share: Option<f64>,
    /// Longest extend of `--tree`, as a share of the space's extent (OMPL's RRTConnect: 0.2).
    #[arg(
        long,
        value_name = "SHARE",
        default_value_t = 0.2,
        requires = "tree",
        help_heading = "Tuning"
    )]
    pub tree_range: f64,
    /// Dynamic-domain sampling of `--tree`: a node's radius after its first failed extend, in
    /// extends (`--tree-range`); a sample farther from its nearest node than that is drawn
    /// again without a call. 0: off. Default: 4 for arms (as VAMP's RRT-Connect), off for
    /// other robots
    #[arg(
        long,
        value_name = "EXTENDS",
        requires = "tree",
        help_heading = "Tuning"
    )]
    pub tree_domain: Option<f64>,
    /// Longest stair of a `--tree` extend (one position move, then one turn), as a share of
    /// the extent: shorter stairs follow coupled motions more closely, for more calls.
    #[arg(
        long,
        value_name = "SHARE",
        default_value_t = 0.01,
        requires = "tree",
        help_heading = "Tuning"
    )]
    pub tree_stair: f64,
    /// How a `--tree` stair finds its free prefix: `intervals` (one interval call), `yesno`
    /// (a yes/no call first, intervals only when blocked) or `first` (one first-collision
    /// call: the same prefix, without the collisions beyond it).
    #[arg(
        long,
        value_name = "MODE",
        default_value = "intervals",
        requires = "tree",
        help_heading = "Tuning"
    )]
    pub tree_prefix: viaroad::roadmap::tree::Prefix,
    /// `--tree`: try each extend as one stair first (yes/no), the staircase only when blocked.
    #[arg(long, requires = "tree", help_heading = "Tuning")]
    pub tree_coarse: bool,
    /// `--tree`: extend the smaller tree each time (`true`) instead of alternating (`false`).
    /// Default: balanced with whole stairs, alternating otherwise.
    #[arg(long, value_name = "BOOL", num_args = 0..=1, default_missing_value = "true", requires = "tree", help_heading = "Tuning")]
    pub tree_balance: Option<bool>,
    /// `--tree`: centring rounds per blocked stair (0: off). A blocked stair moves the node to
    /// the middle of its free chords across the stair (a first-collision call each way per
    /// direction) and is tried again, up to N times: lines a robot up with a funnel (bugtrap).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 0,
        requires = "tree",
        help_heading = "Tuning"
    )]
    pub tree_centre: usize,
    /// `--tree-centre`: half-angle of the turns a centring round asks about, in turns (at most
    /// 0.45): only free arcs narrower than this are centred.
    #[arg(long, value_name = "TURNS", default_value_t = viaroad::roadmap::tree::CENTRE_TURN, requires = "tree", help_heading = "Tuning")]
    pub tree_centre_turn: f64,
    /// `--tree`: restart both trees when an attempt has grown this many nodes, each later
    /// attempt with a new random stream and twice the nodes (RRT run times are heavy-tailed;
    /// the first attempt is the run without restarts). Default: no restarts.
    #[arg(long, value_name = "NODES", requires = "tree", help_heading = "Tuning")]
    pub tree_restart: Option<usize>,
    /// `--tree`: pairs of trees racing from the same ends with different random streams, on
    /// the rayon pool; the first to connect answers (without a time limit: the first in stream
    /// order, the same on any thread count). Default 1.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        requires = "tree",
        help_heading = "Tuning"
    )]
    pub tree_streams: usize,
    /// `--tree`: how an extend walks its stairs: `whole` (each stair all of it or not at all,
    /// only the extend's end a candidate nearest node: OMPL's extend in steps of one stair),
    /// `prefix` (each DOF group's piece as far as it is free, the first blocked group ends the
    /// extend) or `slide` (a blocked group lets the stair's other groups go on). Default:
    /// `whole`, `prefix` with `--tree-centre` or `--tree-coarse` (which need it).
    #[arg(long, value_name = "MODE", requires = "tree", help_heading = "Tuning")]
    pub tree_stairs: Option<viaroad::roadmap::tree::Stairs>,
}

impl SolveArgs {
    /// Whether the local method alone answers: asked for, or implied by naming a local method
    /// outside `--roadmap` (whose own local method it then is).
    pub fn local_alone(&self) -> bool {
        self.local_only || (self.local.given() && !self.roadmap && !self.tree)
    }
}

/// One solved query, as printed.
pub struct Solved {
    pub connection: viaroad::local::Connection,
    pub shortened: Vec<viaroad::space::Config>,
}

/// Solves one query with the local method and shortens the path.
pub fn solve_query(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    spec: &LocalSpec,
    start: &[f64],
    goal: &[f64],
    deadline: &Deadline,
) -> anyhow::Result<Solved> {
    let method = spec.build();
    let mut connection = method
        .connect_within(&scene.space, oracle, start, goal, deadline)
        .context("local method")?;
    let shortened = if connection.is_connected() {
        let groups = method.groups(&scene.space);
        shorten(
            &scene.space,
            oracle,
            &groups,
            &connection.path,
            &mut connection.counts,
        )
        .context("shortening")?
    } else {
        Vec::new()
    };
    Ok(Solved {
        connection,
        shortened,
    })
}

/// What every planner of `solve` but the local method alone needs before its first query: the
/// time of each query (the `.cfg` file's `time_limit` or 60 s by default; none with `--nodes` alone),
/// `--nodes` checked (`too_big` says why there is a limit), the scene's checked queries (at least
/// one), its warnings printed, and the `--path-out` files.
pub struct SingleQuery {
    /// The time each query may take.
    pub time: Option<std::time::Duration>,
    /// The scene's queries, checked.
    pub queries: Vec<viaroad::scene::Query>,
    /// Where solved paths are written.
    pub path_out: Option<super::path_out::PathOut>,
}

impl SingleQuery {
    /// The set-up of `a`'s single-query planner on `scene`.
    pub fn prepare(a: &SolveArgs, scene: &Scene, too_big: &str) -> anyhow::Result<SingleQuery> {
        let time = match (a.time, a.nodes) {
            (None, Some(_)) => None,
            (Some(t), _) => Some(super::limits::parse_seconds("--time", t)?),
            (None, None) => Some(super::limits::parse_seconds(
                "[benchmark] time_limit",
                default_seconds(&a.scene)?,
            )?),
        };
        if let Some(n) = a.nodes {
            super::limits::count_in_range("--nodes", n, viaroad::limits::MAX_NODES, too_big)?;
        }
        let queries = scene.checked_queries()?;
        if queries.is_empty() {
            anyhow::bail!("{} has no [[query]]", a.scene.display());
        }
        for w in &scene.warnings {
            eprintln!("warning: {w}");
        }
        let path_out = match &a.path_out {
            Some(base) => Some(super::path_out::PathOut::new(base, queries.len())?),
            None => None,
        };
        Ok(SingleQuery {
            time,
            queries,
            path_out,
        })
    }
}

/// A query's time unless `--time` says otherwise: an OMPL.app problem's own benchmark limit, so
/// that it is judged on the terms it was published with, else a minute.
pub fn default_seconds(scene: &std::path::Path) -> anyhow::Result<f64> {
    // the extension decides as in `Scene::load`
    let limit = match scene.extension().and_then(|e| e.to_str()) {
        Some("cfg") => viaroad::scene::ompl_cfg::time_limit(scene)?,
        _ => None,
    };
    Ok(limit.unwrap_or(60.0))
}

/// The independent checker's verdict on a raw path and its shortened version.
pub(super) fn check_both(
    checker: &viaroad::bench::validity::Checker,
    raw: &[viaroad::space::Config],
    shortened: &[viaroad::space::Config],
) -> Result<(), String> {
    checker
        .check_path(raw)
        .map_err(|e| format!("raw path: {e}"))?;
    checker
        .check_path(shortened)
        .map_err(|e| format!("shortened path: {e}"))
}

/// `--check`'s verdict as the end of a line of text.
pub(super) fn verdict_text(verdict: Option<&Result<(), String>>) -> String {
    match verdict {
        None => String::new(),
        Some(Ok(())) => ", certified".into(),
        Some(Err(e)) => format!(", NOT certified: {e}"),
    }
}
