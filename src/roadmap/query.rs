//! Answering queries against a learnt roadmap (OS94's query phase).
//!
//! A query first tries start to goal quickly: the direct path (one yes/no call per DOF group;
//! for an arm first the straight motion of all joints, [`QueryOptions::straight_shortcuts`]),
//! or the via-point planner on a small call budget ([`QueryOptions::direct_calls`]).
//! Otherwise start and goal are *attached*: the local method connects each to its nearest
//! nodes, nearest first, at most one node per component and side, alternating between the two
//! sides, until both are attached to one component. A* ([`petgraph::algo::astar()`]; the
//! admissible heuristic is the space's distance or a landmark bound, [`super::Landmarks`])
//! finds the way through that component, and the path is shortened over its corners (CHS A.1,
//! [`crate::local::shorten()`]; long paths lose corners greedily first,
//! [`QueryOptions::exact_shortening_limit`]). Only when the roadmap cannot join the two ends
//! does the local method try start to goal, and then a deeper via-point search
//! ([`QueryOptions::escalation_candidates`]).
//!
//! With a time limit ([`QueryOptions::time`]) a query whose ends the roadmap cannot join grows
//! a *copy* of the roadmap around them for the rest of its time ([`QueryOptions::grow`], as
//! OMPL's PRM does) and says so ([`QueryOutcome::Grown`]); how far it gets depends on the
//! machine, like any time budget.
//!
//! Queries never change the roadmap, so answers do not depend on the order queries are asked
//! in, and a batch runs in parallel, streaming its answers as they come
//! ([`QueryPlanner::query_each`]).

use super::graph::Roadmap;
use super::landmarks::Landmarks;
use super::learn::{LearnError, Learner};
use super::params::Budget;
use super::persist::check_local_spec;
use super::persist::RoadmapError;
use super::rooted::{KeptTree, RoadmapTrees, ATTACH_CANDIDATES};
use super::tree::{Rooted, TreeError, TreeParams, TreeStop};
use crate::deadline::Deadline;
use crate::local::{
    direct_connection, direct_pieces, drop_corners_known, path_length, shorten_known,
    straight_connection, surely_blocked, Connection, KnownPieces, LocalMethod, LocalSpec, Outcome,
};
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::space::{Config, Group, SpaceError};
use petgraph::graph::NodeIndex;
use rayon::prelude::*;
use serde::Serialize;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

pub mod keep;
mod race;
#[cfg(test)]
mod tests;

/// A query that may grow the roadmap spends at most 1/`ATTACH_SHARE` of its time attaching
/// start and goal with the roadmap's local method; the rest is the growing's.
pub const ATTACH_SHARE: u32 = 2;

/// An answer still longer than this many times [`QueryOptions::exact_shortening_limit`]
/// corners after a greedy pass (a tree answer, or a roadmap answer through kept staircases) is
/// shortened by greedy passes alone, not by the visibility graph. Roadmap answers
/// too: in the cage workcell one of 230 corners took the visibility graph 0.9 s for 18 %
/// fewer corners (query p95 0.75–1.09 s → 0.27–0.36 s, length p50 3–4 % longer).
pub const TREE_SHORTENING_FACTOR: usize = 4;

/// A query that may grow trees out of the roadmap ([`QueryOptions::trees`]) spends at most
/// 1/`TREES_ATTACH_SHARE` of its time attaching with the roadmap's local method: the trees
/// attach what a direct path reaches themselves, and where the local method's search fails
/// (a goal inside MotionBenchMaker's box or cage) the trees answer in a fraction of the time
/// it spends failing. The MotionBenchMaker workcell with 5 s queries, in turn, two runs each
/// (README § Robot arms): a tenth solved 107–110 of 110 with a sum of latencies of 28–34 s,
/// a 25th 110 in 24–25 s, a 50th 110 in 20 s (box p50 15–20 ms instead of 80–100, cage
/// 0.4 s instead of 1.2–1.4; bookshelf_thin 12–15 ms instead of 4.5–5.6, where searches
/// that would have attached in a few hundred milliseconds are cut short).
pub const TREES_ATTACH_SHARE: u32 = 50;

/// Knobs of the query phase.
#[derive(Clone, Debug, PartialEq)]
pub struct QueryOptions {
    /// Nearest nodes considered for attaching each of start and goal.
    pub attach_candidates: usize,
    /// Of those, for a via-point roadmap, the nearest this many (default: all) are first tried
    /// with the direct path alone (a yes/no call per DOF group it changes, stopping at the first
    /// blocked one; in an arm's space the straight motion, [`Self::straight_shortcuts`]),
    /// before any is tried with the local method: a free straight motion to the
    /// second-nearest node is cheaper than a search to the nearest that fails (OMPL.app's
    /// Home, query 17: 268 calls failing for the nearest node, 2 for the next; the 50 Home
    /// queries on a 10 000-node roadmap: 0.71× the instructions). 0: the local method from
    /// the first candidate on.
    pub attach_direct_candidates: usize,
    /// Try start to goal quickly before using the roadmap ([`Self::direct_calls`]), and with
    /// the full local method where the roadmap cannot join them.
    pub try_direct: bool,
    /// The call budget of the quick try from start to goal before the roadmap, for via-point
    /// roadmaps: 0 checks the direct path only, a yes/no call per piece; `n` runs the
    /// via-point planner for at most `n` intersect calls. Where calls are cheap, the planner
    /// often joins random pairs directly (80 discs, 10 000 nodes: p50 0.27 → 0.035 ms with
    /// 32); where they are dear it mostly fails there and the roadmap would have been quicker
    /// (OMPL.app's Home: p50 12 → 27 ms).
    pub direct_calls: u64,
    /// Shorten the path over its corners (CHS A.1).
    pub shorten: bool,
    /// Paths with more corners than this per two DOF groups first go through one greedy pass
    /// ([`crate::local::drop_corners`], at most two checks per corner) before the visibility
    /// graph over what is left: the full graph over a long roadmap path costs up to `m²/2`
    /// checks. `usize::MAX` shortens every path over all its corners. On OMPL.app's Home
    /// (a 32 803-node roadmap, its 50 queries) the default answered at p50 12 ms against 23 ms
    /// with 4.2× fewer intersect calls, for paths 1.7 % longer on average.
    ///
    /// Per two groups because a path that moves `g` groups one at a time turns `g` corners
    /// per diagonal step, and the visibility graph does not check a pair that only reorders a
    /// step (no gain, [`crate::local::shorten::UNCHECKED`]) while the greedy pass does: with
    /// 32 corners for the Panda's 7 joints, the greedy pass cost more than it saved (the box
    /// workcell's query p50 2.5–2.7 → 2.0–2.2 ms with 112, the same lengths; bookshelf_thin
    /// and the cage within their noise). Spaces of one or two groups (Home) keep
    /// 32 corners.
    ///
    /// 0: greedy passes alone, until one drops no corner, never the visibility graph. Where
    /// a roadmap's answers run along answers it kept, already shortened (a workcell trained on
    /// example requests, [`keep::answer_keeping`]), the visibility graph's extra pairs mostly
    /// fail: the Panda's cage workcell trained on 40 held-out requests answered 19 requests at
    /// p50 0.39–0.41 ms against 0.51–0.57 with 32, their length p50 the same (13.5–13.7 rad).
    pub exact_shortening_limit: usize,
    /// Landmarks for A*'s heuristic ([`super::Landmarks`]): the space's distance, or the
    /// landmarks' lower bound where it is larger. Computed at the planner's first A* search;
    /// 0 uses the space's distance alone.
    pub landmarks: usize,
    /// When the roadmap's own local method can neither connect start and goal directly nor
    /// attach both, try the direct connection and then this many nearest nodes per end again
    /// with the via-point planner searching deeper (at least the depth and
    /// call budget of the defaults, [`crate::local::LocalSpec::deeper`]). A roadmap is learnt with a shallow, cheap
    /// local method; a query calls it only twice, so it can afford the deep search where the
    /// roadmap did not reach ("the local method can be tuned … to be quite effective in path
    /// planning for the cost of increased running time", CHS §1.6). Only for via-point
    /// roadmaps; 0 turns it off.
    pub escalation_candidates: usize,
    /// The time one query may take ([`QueryPlanner::query`]; a batch gives each query its
    /// own). Every local-method attempt checks it before each oracle call; a query that runs
    /// out answers [`QueryOutcome::TimedOut`]. `None` (the library's default: answers
    /// reproducible, unanswerable queries fail fast): no limit and no growing. `viaroad query`
    /// sets [`Self::DEFAULT_TIME`].
    pub time: Option<Duration>,
    /// Where the roadmap cannot join start and goal, grow it around them for the rest of the
    /// query's time (OMPL's PRM does this in `solve`): a copy of the roadmap with start and
    /// goal as nodes, construction and expansion rounds until they meet
    /// ([`super::Learner::connect_pair`]; the saved roadmap is not changed). Needs
    /// [`Self::time`]. Off: the deeper local search of
    /// [`Self::escalation_candidates`] instead.
    pub grow: bool,
    /// Where the roadmap cannot join start and goal, grow two trees *out of it* for the rest
    /// of the query's time instead of a copy of it ([`super::rooted::RoadmapTrees`]: each end
    /// the direct path attaches to a nearby node brings that node's component as its tree, so
    /// the other end's tree need only reach the roadmap), answering
    /// [`QueryOutcome::Trees`]. Needs [`Self::time`] or the trees' own node budget. A grown
    /// copy does not build the fine single-joint staircases into a box or a cage; trees do
    /// (README, § Robot arms: MotionBenchMaker's cage 9 of 9 workcell requests). Trees that
    /// spend their node budget without meeting answer [`QueryOutcome::Disconnected`]. `None`
    /// (the default): [`Self::grow`] decides.
    pub trees: Option<TreeParams>,
    /// The intersect calls one query may spend on its local-method attempts (the quick try,
    /// attaching, the direct and the deeper search); `None`: no limit. Each attempt runs the
    /// method limited to what is left ([`crate::local::LocalSpec::budgeted`]; the via-point
    /// search checks its budget between via points, so a query may overrun it by one walk),
    /// and a query that spends it all before start and goal meet answers
    /// [`QueryOutcome::OutOfCalls`]. Shortening a path found is not limited; growing stops once
    /// the budget is spent. Unlike [`Self::time`] it does not depend on the machine, so
    /// benchmarks of deep local methods can bound the query phase reproducibly
    /// (`viaroad bench local --query-calls`).
    pub max_calls: Option<u64>,
    /// Hand the trees [`Self::trees`] grew to the answer ([`QueryResult::trees`]) for a caller
    /// that keeps them ([`Roadmap::with_kept`]). Off by default: trees can hold 10⁵ nodes, and
    /// a batch holds every answer until it ends.
    pub return_trees: bool,
    /// With [`Self::trees`]: ask the roadmap alone for at most this head start, then, unless it
    /// answered, its whole search beside the trees out of it on the rayon pool, the first to
    /// answer stopping the other ([`crate::deadline::race_after`]), rather than growing the
    /// trees only after attaching failed. In a workcell whose goals the roadmap rarely reaches
    /// (the Panda's cage) attaching costs tens of milliseconds before the trees start: query
    /// p50 92 → 17 ms with 2 ms; the head start keeps the quick answers off the pool. An arm's
    /// head start asks the direct paths alone (the quick try, attaching each end by direct
    /// paths to its five nearest nodes) and
    /// ends where they fail: the staircase from start to goal and the local method's searches,
    /// whole-range sweeps on an arm, cost a millisecond before trees that mostly answer
    /// first.
    /// The trees' path is shortened by greedy shortcut passes
    /// ([`super::tree::shortcut_passes`]). `None` (the default): in turn.
    pub race: Option<Duration>,
    /// In an arm's space, try straight motions of several joints at once where conservative
    /// advancement proves them free ([`crate::robot::ArmOracle::straight_free`],
    /// [`crate::space::Space::straight_group`]), not only staircases of single-joint moves:
    /// start to goal before the roadmap and each end to its nearest nodes, in place of their
    /// direct staircase (the local method's search still follows where they fail), the trees'
    /// extends ([`TreeParams::straight`], which this turns off too), and
    /// between corners when shortening. The answer then moves several joints
    /// per pair of corners where it cuts across (every pair of corners is one straight motion,
    /// [`crate::local::path_pieces`]). On by default; no effect in other spaces (or with
    /// continuous joints). The Panda's workcells (seed 1): half the path length in
    /// six of seven families, and the cage's query p50 13.4 → 1.3 ms (a goal inside attaches
    /// straight to a kept answer's corner where every staircase swings into the bars).
    pub straight_shortcuts: bool,
}

impl QueryOptions {
    /// The head start of [`Self::race`] the command line uses where trees grow: what the
    /// Panda's workcells were measured with (`bench mbm --workcell --race 2`).
    pub const DEFAULT_HEAD_START: Duration = Duration::from_millis(2);

    /// These options with the trees the command line grows where the roadmap of an arm
    /// cannot join the ends ([`Self::trees`], [`Self::race`] with
    /// [`Self::DEFAULT_HEAD_START`]); other spaces keep them as they are (a grown copy of
    /// the roadmap).
    pub fn with_arm_trees(mut self, space: &crate::space::Space) -> Self {
        if space.is_joints() {
            self.trees = Some(TreeParams::for_space(space));
            self.race = Some(Self::DEFAULT_HEAD_START);
        }
        self
    }

    /// The command line's default time of one query: long enough for a grown roadmap to cross a hard
    /// passage, short enough that a batch of unanswerable queries ends.
    pub const DEFAULT_TIME: Duration = Duration::from_secs(10);
}

impl Default for QueryOptions {
    fn default() -> Self {
        QueryOptions {
            attach_candidates: 30,
            attach_direct_candidates: 30,
            try_direct: true,
            direct_calls: 0,
            shorten: true,
            exact_shortening_limit: 32,
            landmarks: 8,
            escalation_candidates: 3,
            time: None,
            grow: true,
            trees: None,
            max_calls: None,
            return_trees: false,
            race: None,
            straight_shortcuts: true,
        }
    }
}

/// Start or goal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Endpoint {
    /// The start configuration.
    Start,
    /// The goal configuration.
    Goal,
}

impl std::fmt::Display for Endpoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Endpoint::Start => "start",
            Endpoint::Goal => "goal",
        })
    }
}

/// A query that cannot be asked.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QueryError {
    /// Wrong number of coordinates, not finite, or an SE(3) quaternion of length zero.
    #[error("{endpoint}: {source}")]
    InvalidConfig {
        /// Which end.
        endpoint: Endpoint,
        /// What is wrong.
        source: SpaceError,
    },
    /// Outside the bounds of the space.
    #[error("{endpoint} {config:?} lies outside the bounds")]
    OutOfBounds {
        /// Which end.
        endpoint: Endpoint,
        /// The configuration (normalised).
        config: Config,
    },
    /// In collision.
    #[error("{endpoint} {config:?} is in collision")]
    InCollision {
        /// Which end.
        endpoint: Endpoint,
        /// The configuration (normalised).
        config: Config,
    },
    /// The oracle cannot answer a motion asked about.
    #[error("collision oracle: {0}")]
    Oracle(#[from] OracleError),
    /// The trees' parameters fail [`TreeParams::validate`].
    #[error("invalid tree parameters: {0}")]
    TreeParams(String),
}

impl From<TreeError> for QueryError {
    fn from(e: TreeError) -> Self {
        match e {
            TreeError::Params(m) => QueryError::TreeParams(m),
            TreeError::Oracle(o) => QueryError::Oracle(o),
        }
    }
}

/// How a query ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum QueryOutcome {
    /// The local method connected start and goal directly.
    Direct,
    /// Through the roadmap.
    Roadmap,
    /// Start or goal could not be attached to any node.
    NotAttached {
        /// Whether the start was attached to some node.
        start_attached: bool,
        /// Whether the goal was attached to some node.
        goal_attached: bool,
    },
    /// Both were attached, but never to the same component.
    Disconnected,
    /// Through a roadmap grown around start and goal within the query's time
    /// ([`QueryOptions::grow`]); [`QueryResult::grown_nodes`] says by how much.
    Grown,
    /// Through trees grown out of the roadmap within the query's time
    /// ([`QueryOptions::trees`]); [`QueryResult::grown_nodes`] says how many nodes they grew.
    Trees,
    /// The query's time ran out before an answer ([`QueryOptions::time`]).
    TimedOut,
    /// The query's call budget ran out before an answer ([`QueryOptions::max_calls`]).
    OutOfCalls,
}

/// The answer to one query (serialisable, for `--json` output). Two answers are equal when
/// all but their timing ([`Self::shorten_s`]) is: the same query asked twice gets an equal
/// answer.
#[derive(Clone, Debug, Serialize)]
pub struct QueryResult {
    /// How it ended; the paths are empty unless it is [`Direct`](QueryOutcome::Direct) or
    /// [`Roadmap`](QueryOutcome::Roadmap).
    pub outcome: QueryOutcome,
    /// The start, normalised.
    pub start: Config,
    /// The goal, normalised.
    pub goal: Config,
    /// The path before shortening: corners joined by single-group straight motions.
    pub raw_path: Vec<Config>,
    /// The shortened path (the raw path if shortening is off).
    pub path: Vec<Config>,
    /// Length of the raw path.
    pub raw_length: f64,
    /// Length of the path.
    pub length: f64,
    /// Oracle work of this query (checks, attaching, shortening).
    pub counts: CallCounts,
    /// Deepest recursion of the local connections used in the answer.
    pub depth: u32,
    /// Local-method calls made to attach start and goal.
    pub attach_attempts: u32,
    /// The node the start was attached to (for a roadmap answer).
    pub start_node: Option<u32>,
    /// The node the goal was attached to (for a roadmap answer).
    pub goal_node: Option<u32>,
    /// Roadmap nodes on the A* path.
    pub roadmap_nodes: usize,
    /// Nodes the query added to a copy of the roadmap while growing it, or grew as trees (0:
    /// it did neither).
    pub grown_nodes: usize,
    /// The trees grown out of the roadmap ([`QueryOptions::trees`]) as they ended, for a
    /// workcell to keep with the answer ([`Roadmap::with_kept`]); `None` where none grew or
    /// [`QueryOptions::return_trees`] is off.
    #[serde(skip)]
    pub trees: Option<Box<[Rooted; 2]>>,
    /// Of the query's time, seconds spent shortening the path found (the rest found it):
    /// OMPL's benchmarks report the two apart, as `time` and `simplify_time`.
    pub shorten_s: f64,
}

impl PartialEq for QueryResult {
    fn eq(&self, other: &Self) -> bool {
        // every field named, so that a new one is not left out by accident
        let QueryResult {
            outcome,
            start,
            goal,
            raw_path,
            path,
            raw_length,
            length,
            counts,
            depth,
            attach_attempts,
            start_node,
            goal_node,
            roadmap_nodes,
            grown_nodes,
            trees,
            shorten_s: _,
        } = self;
        *outcome == other.outcome
            && *start == other.start
            && *goal == other.goal
            && *raw_path == other.raw_path
            && *path == other.path
            && *raw_length == other.raw_length
            && *length == other.length
            && *counts == other.counts
            && *depth == other.depth
            && *attach_attempts == other.attach_attempts
            && *start_node == other.start_node
            && *goal_node == other.goal_node
            && *roadmap_nodes == other.roadmap_nodes
            && *grown_nodes == other.grown_nodes
            && *trees == other.trees
    }
}

impl QueryResult {
    /// A query between `start` and `goal` not answered yet, with the oracle work `counts` of
    /// checking its ends.
    fn unanswered(start: Config, goal: Config, counts: CallCounts) -> Self {
        QueryResult {
            outcome: QueryOutcome::Disconnected,
            start,
            goal,
            raw_path: Vec::new(),
            path: Vec::new(),
            raw_length: 0.0,
            length: 0.0,
            counts,
            depth: 0,
            attach_attempts: 0,
            start_node: None,
            goal_node: None,
            roadmap_nodes: 0,
            grown_nodes: 0,
            trees: None,
            shorten_s: 0.0,
        }
    }

    /// If connection `c` from start to goal connected, the answer is [`QueryOutcome::Direct`]
    /// along the returned path.
    fn take_direct(&mut self, c: Connection) -> Option<Vec<Config>> {
        if !c.is_connected() {
            return None;
        }
        self.outcome = QueryOutcome::Direct;
        self.depth = c.depth;
        Some(c.path)
    }

    /// The answer's paths as found (`raw`) and as returned (`path`), with their lengths.
    fn set_paths(
        &mut self,
        space: &crate::space::Space,
        groups: &[Group],
        raw: Vec<Config>,
        path: Vec<Config>,
    ) {
        self.raw_length = path_length(space, groups, &raw);
        self.length = path_length(space, groups, &path);
        self.raw_path = raw;
        self.path = path;
    }

    /// Whether a path was found.
    pub fn is_solved(&self) -> bool {
        matches!(
            self.outcome,
            QueryOutcome::Direct
                | QueryOutcome::Roadmap
                | QueryOutcome::Grown
                | QueryOutcome::Trees
        )
    }
}

/// One answer of a batch, with the wall-clock time it took.
#[derive(Clone, Debug)]
pub struct BatchAnswer {
    /// The answer.
    pub result: Result<QueryResult, QueryError>,
    /// Time spent on this query.
    pub elapsed: Duration,
}

/// Answers queries against one roadmap with the scene's oracle and the roadmap's own local
/// method (rebuilt from the spec recorded in the file, so that the groups of its edges and of
/// the attaching paths agree).
pub struct QueryPlanner<'a> {
    roadmap: &'a Roadmap,
    oracle: &'a dyn CollisionOracle,
    local: Box<dyn LocalMethod>,
    /// The deeper search for ends the roadmap's method cannot attach
    /// ([`crate::local::LocalSpec::deeper`]).
    escalation: Option<Box<dyn LocalMethod>>,
    /// The quick try from start to goal ([`QueryOptions::direct_calls`],
    /// [`crate::local::LocalSpec::budgeted`]); `None` where the roadmap's method is such a
    /// check already.
    quick: Option<Box<dyn LocalMethod>>,
    groups: Vec<Group>,
    /// The groups shortening checks pairs of corners with: [`Self::groups`], or the straight
    /// group of all joints ([`QueryOptions::straight_shortcuts`]).
    shortcut_groups: Vec<Group>,
    options: QueryOptions,
    landmarks: OnceLock<Landmarks>,
    /// The tree out of the roadmap the last query's start (or goal) brought along
    /// ([`RoadmapTrees::keeping`]).
    kept_tree: KeptTree,
}

/// How far a query's search goes where the roadmap cannot join the ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stages {
    /// The direct paths alone: the quick try and attaching each end by direct paths to its
    /// [`ATTACH_CANDIDATES`] nearest nodes. What answers most
    /// of a trained workcell's queries in a fraction of a millisecond, and an arm's race's
    /// head start ([`QueryOptions::race`]): the staircase from start to goal and the local
    /// method's searches that follow sweep whole joint ranges on an arm (about 0.5 ms a call),
    /// and where the direct paths fail the trees mostly answer first.
    Direct,
    /// Every stage: the local method's attaching, its search from start to goal, the deeper
    /// search, the trees or the growing.
    All,
}

/// What the deeper search of [`QueryPlanner::escalate`] found.
enum Escalated {
    /// A direct path from start to goal.
    Direct(Vec<Config>),
    /// The start and goal attachments that meet, if any.
    Attached(Option<(usize, usize)>),
}

/// How a query the roadmap could not join ended: out of time or calls (`calls_left`), an end
/// not attached, or the two ends attached only to different components.
fn unjoined(
    deadline: &Deadline,
    calls_left: Option<u64>,
    (at_start, at_goal): &(Vec<Attached>, Vec<Attached>),
) -> QueryOutcome {
    if deadline.expired() {
        QueryOutcome::TimedOut
    } else if calls_left == Some(0) {
        QueryOutcome::OutOfCalls
    } else if at_start.is_empty() || at_goal.is_empty() {
        QueryOutcome::NotAttached {
            start_attached: !at_start.is_empty(),
            goal_attached: !at_goal.is_empty(),
        }
    } else {
        QueryOutcome::Disconnected
    }
}

/// The nearest nodes of one end with their distances, nearest first.
type Near = Vec<(u32, f64)>;

/// One way of trying to attach an end: from the first configuration to the second, counted in
/// the result.
type Connect<'c> =
    dyn FnMut(&[f64], &[f64], &mut QueryResult) -> Result<Connection, QueryError> + 'c;

/// A seed of the query's own (from the roadmap's seed and the query's ends), so that a query
/// asked twice grows the same way as far as its time allows.
fn query_seed(roadmap_seed: u64, result: &QueryResult) -> u64 {
    result
        .start
        .iter()
        .chain(&result.goal)
        .fold(roadmap_seed ^ 0x6772_6f77, |h, v| {
            (h ^ v.to_bits()).wrapping_mul(0x0000_0100_0000_01b3)
        })
}

/// An attachment of one end to a node.
struct Attached {
    component: u32,
    node: u32,
    connection: Connection,
}

impl<'a> QueryPlanner<'a> {
    /// A planner for `roadmap`; `oracle` must be the oracle of the roadmap's scene (loading with
    /// the scene's fingerprint checks that the scene is the right one).
    pub fn new(
        roadmap: &'a Roadmap,
        oracle: &'a dyn CollisionOracle,
    ) -> Result<QueryPlanner<'a>, RoadmapError> {
        let spec = &roadmap.header().local_spec;
        check_local_spec(spec)?;
        let local = spec.build();
        let groups = local.groups(roadmap.space());
        let options = QueryOptions::default();
        Ok(QueryPlanner {
            roadmap,
            oracle,
            local,
            escalation: spec.deeper().map(|s| s.build()),
            quick: spec.budgeted(options.direct_calls).map(|s| s.build()),
            shortcut_groups: Vec::new(),
            groups,
            options: options.clone(),
            landmarks: OnceLock::new(),
            kept_tree: KeptTree::default(),
        }
        .with_options(options))
    }

    /// The same planner with other options.
    pub fn with_options(mut self, options: QueryOptions) -> Self {
        let spec = &self.roadmap.header().local_spec;
        self.quick = spec.budgeted(options.direct_calls).map(|s| s.build());
        let straight = self.roadmap.space().straight_group();
        self.shortcut_groups = match straight.filter(|_| options.straight_shortcuts) {
            Some(whole) => vec![whole],
            None => self.groups.clone(),
        };
        self.options = options;
        self.landmarks = OnceLock::new();
        self
    }

    /// Computes now what the first A* search would ([`QueryOptions::landmarks`]: a graph
    /// search per landmark), so that a planner kept for many queries (a workcell's server, a
    /// roadmap just grown by a kept answer) does not charge it to the first query.
    pub fn prepare(&self) {
        self.landmarks();
    }

    /// The landmarks of A*'s heuristic ([`QueryOptions::landmarks`]), computed at the first
    /// call; `None` where there are none to compute.
    fn landmarks(&self) -> Option<&Landmarks> {
        (self.options.landmarks > 0 && self.roadmap.node_count() > 0).then(|| {
            self.landmarks
                .get_or_init(|| Landmarks::new(self.roadmap, self.options.landmarks))
        })
    }

    /// The options in use.
    pub fn options(&self) -> &QueryOptions {
        &self.options
    }

    /// The roadmap asked.
    pub fn roadmap(&self) -> &Roadmap {
        self.roadmap
    }

    fn check_endpoint(
        &self,
        endpoint: Endpoint,
        q: &[f64],
        counts: &mut CallCounts,
    ) -> Result<Config, QueryError> {
        let space = self.roadmap.space();
        space
            .check(q)
            .map_err(|source| QueryError::InvalidConfig { endpoint, source })?;
        let mut q = q.to_vec();
        space.normalize(&mut q);
        if !space.in_bounds(&q) {
            return Err(QueryError::OutOfBounds {
                endpoint,
                config: q,
            });
        }
        if !self.oracle.is_free(&q, counts) {
            return Err(QueryError::InCollision {
                endpoint,
                config: q,
            });
        }
        Ok(q)
    }

    /// Answers one query within [`QueryOptions::time`].
    pub fn query(&self, start: &[f64], goal: &[f64]) -> Result<QueryResult, QueryError> {
        self.query_within(start, goal, &Deadline::none())
    }

    /// Answers one query within [`QueryOptions::time`] and `outer` (a batch's deadline, a
    /// cancel flag), whichever ends first.
    pub fn query_within(
        &self,
        start: &[f64],
        goal: &[f64],
        outer: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        match (self.options.race, &self.options.trees) {
            (Some(head_start), Some(tree)) => self.racing(start, goal, outer, head_start, tree),
            _ => self.query_finding_within(start, goal, outer, outer),
        }
    }

    /// [`Self::query_within`] whose search for a path ends at `finding`, a deadline within
    /// `outer` (`outer.within(head_start)`), while the path found is shortened until `outer`:
    /// a portfolio's head start ([`crate::deadline::race`]) bounds the search, and a path found
    /// at its end is still an answer worth shortening, not one to hand back raw.
    pub fn query_finding_within(
        &self,
        start: &[f64],
        goal: &[f64],
        finding: &Deadline,
        outer: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        let trees = self.options.trees.as_ref();
        self.search(start, goal, (finding, outer), trees, Stages::All)
    }

    /// [`Self::query_finding_within`] with the trees it grows in turn where the roadmap cannot
    /// join the ends (`None` beside a race's trees), through `stages`.
    fn search(
        &self,
        start: &[f64],
        goal: &[f64],
        (finding, outer): (&Deadline, &Deadline),
        trees: Option<&TreeParams>,
        stages: Stages,
    ) -> Result<QueryResult, QueryError> {
        let deadline = finding.within(self.options.time);
        let shortening = outer.within(self.options.time);
        let mut counts = CallCounts::default();
        let start = self.check_endpoint(Endpoint::Start, start, &mut counts)?;
        let goal = self.check_endpoint(Endpoint::Goal, goal, &mut counts)?;
        let mut result = QueryResult::unanswered(start.clone(), goal.clone(), counts);
        // a quick try first (the direct path, or a budgeted via-point search)
        let mut retry_direct = self.options.try_direct;
        let mut staircase_left = false;
        if self.options.try_direct {
            let (quick, retry, left) = self.quick_try(&start, &goal, &mut result, &deadline)?;
            if let Some(path) = result.take_direct(quick) {
                return self.finish(result, path, &shortening);
            }
            (retry_direct, staircase_left) = (retry, left);
        }
        // attach both ends, alternating, one node per component and side
        let mut ends = (Vec::new(), Vec::new());
        let ends_q = (&start[..], &goal[..]);
        let k = self.options.attach_candidates;
        let local = self.local.as_ref();
        // a query that may grow the roadmap gives attaching at most half of its time: deep
        // searches from ends the roadmap cannot reach would otherwise spend what the growing
        // needs (alpha-1.5: 30 attaching attempts took all of a 10 s query)
        let timed = deadline.remaining().is_some();
        let share = match (trees, self.options.grow) {
            (Some(_), _) => Some(TREES_ATTACH_SHARE),
            (None, true) => Some(ATTACH_SHARE),
            (None, false) => None,
        };
        let attaching = match (share, deadline.remaining()) {
            (Some(share), Some(left)) => deadline.within(Some(left / share)),
            _ => deadline.clone(),
        };
        let direct = self.options.attach_direct_candidates;
        let mut meeting = self.attach(
            local,
            (k, direct),
            stages,
            ends_q,
            &mut ends,
            &mut result,
            &attaching,
        )?;
        // where the quick try asked an arm's straight motion and it was not proved, the
        // staircase from start to goal only now, for the queries the roadmap cannot join, and
        // not in a race's head start: in clutter it mostly collides, and its exact sweeps are
        // dear (a bookshelf_tall workcell: it answered one request, which the trees answer as
        // fast, and cost two others 0.3 ms before their trees)
        if meeting.is_none() && staircase_left && stages == Stages::All {
            let c = self.direct_check(&start, &goal, &mut result, &deadline)?;
            if let Some(path) = result.take_direct(c) {
                return self.finish(result, path, &shortening);
            }
        }
        if meeting.is_none() && stages == Stages::Direct {
            result.outcome = unjoined(&deadline, self.calls_left(&result), &ends);
            return Ok(result);
        }
        // only where the roadmap cannot join the two ends, the local method from start to goal:
        // across a large scene it mostly fails, and tried first it cost most of a query's time
        // (Home, 32 803 nodes: 25–60 ms of a 30–60 ms answer)
        if meeting.is_none() && retry_direct {
            let c = self.attempt(local, (&start, &goal), &mut result, &attaching)?;
            if let Some(path) = result.take_direct(c) {
                return self.finish(result, path, &shortening);
            }
        }
        // where the roadmap cannot join them, grow it around them for the rest of the time
        // (only with a time limit: a cancel flag alone would let it grow until cancelled)
        let spent = self.calls_left(&result) == Some(0);
        if let (None, Some(tree)) = (meeting, trees) {
            let bounded = timed || tree.max_nodes.is_some();
            if bounded && !deadline.expired() && !spent {
                return self.trees(result, tree, &deadline, &shortening);
            }
        }
        if meeting.is_none() && self.options.grow && timed && !deadline.expired() && !spent {
            return self.grow(result, &deadline, &shortening);
        }
        if meeting.is_none() {
            match self.escalate(ends_q, &mut ends, &mut result, &deadline)? {
                Escalated::Direct(path) => return self.finish(result, path, &shortening),
                Escalated::Attached(m) => meeting = m,
            }
        }
        match meeting {
            Some((si, gi)) => self.through_roadmap(result, &ends.0[si], &ends.1[gi], &shortening),
            None => {
                result.outcome = unjoined(&deadline, self.calls_left(&result), &ends);
                Ok(result)
            }
        }
    }

    /// The space of the roadmap's scene.
    fn space(&self) -> &crate::space::Space {
        self.roadmap.space()
    }

    /// Where the roadmap's own method could not join the ends: the deeper search
    /// ([`QueryOptions::escalation_candidates`]) from start to goal, then attaching again.
    fn escalate(
        &self,
        (start, goal): (&[f64], &[f64]),
        ends: &mut (Vec<Attached>, Vec<Attached>),
        result: &mut QueryResult,
        deadline: &Deadline,
    ) -> Result<Escalated, QueryError> {
        let k = self.options.escalation_candidates;
        let Some(deep) = self.escalation.as_deref().filter(|_| k > 0) else {
            return Ok(Escalated::Attached(None));
        };
        // the deep search straight from start to goal first: one attempt, and the planner's
        // own strength where the roadmap has not reached (a narrow goal)
        if self.options.try_direct {
            let c = self.attempt(deep, (start, goal), result, deadline)?;
            if let Some(path) = result.take_direct(c) {
                return Ok(Escalated::Direct(path));
            }
        }
        // the direct paths were tried when attaching with the roadmap's method
        let meeting = self.attach(
            deep,
            (k, 0),
            Stages::All,
            (start, goal),
            ends,
            result,
            deadline,
        )?;
        Ok(Escalated::Attached(meeting))
    }

    /// The answer through the roadmap from the start's attachment `s` to the goal's `g` (in
    /// one component): A* between their nodes, then the path shortened until `shortening`.
    fn through_roadmap(
        &self,
        mut result: QueryResult,
        s: &Attached,
        g: &Attached,
        shortening: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        let Some(nodes) = self.astar(s.node, g.node) else {
            // attached to one component, so a path exists; kept as a typed outcome regardless
            result.outcome = QueryOutcome::Disconnected;
            return Ok(result);
        };
        result.outcome = QueryOutcome::Roadmap;
        result.start_node = Some(s.node);
        result.goal_node = Some(g.node);
        result.depth = s.connection.depth.max(g.connection.depth);
        result.roadmap_nodes = nodes.len();
        let mut raw = s.connection.path.clone();
        raw.extend(self.node_path(&nodes));
        raw.extend(g.connection.path.iter().skip(1).cloned());
        self.finish(result, raw, shortening)
    }

    /// The corners along roadmap nodes `nodes` (adjacent pairs joined by their cheapest edge),
    /// the first node left out.
    fn node_path(&self, nodes: &[u32]) -> Vec<Config> {
        let mut raw = Vec::new();
        for w in nodes.windows(2) {
            let edge = self.cheapest_edge(w[0], w[1]);
            raw.extend(self.roadmap.edge_path(edge, w[0]).into_iter().skip(1));
        }
        raw
    }

    /// Grows a copy of the roadmap around the query's ends until they meet or `deadline`
    /// passes ([`QueryOptions::grow`]), and answers through it, shortened until `shortening`.
    fn grow(
        &self,
        mut result: QueryResult,
        deadline: &Deadline,
        shortening: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        let header = self.roadmap.header();
        let learner = Learner::new(
            self.roadmap.space(),
            self.oracle,
            self.local.as_ref(),
            header.fingerprint,
        )
        .with_attempt_cap(deadline.remaining().map(Learner::attempt_cap_for));
        let seed = query_seed(header.seed, &result);
        let grown = learner
            .connect_pair(
                &header.params,
                Some(self.roadmap),
                (&result.start, &result.goal),
                &Budget::default(),
                seed,
                deadline,
                &mut |_| {},
            )
            .map_err(|e| match e {
                LearnError::Oracle(o) => QueryError::Oracle(o),
                other => QueryError::Oracle(OracleError::Unsupported(other.to_string())),
            })?;
        let roadmap = &grown.learnt.roadmap;
        result.counts += roadmap.header().counts;
        result.grown_nodes = roadmap.node_count() - self.roadmap.node_count();
        if !grown.connected {
            result.outcome = QueryOutcome::TimedOut;
            return Ok(result);
        }
        let inner = QueryPlanner {
            roadmap,
            oracle: self.oracle,
            local: header.local_spec.build(),
            escalation: None,
            quick: None,
            groups: self.groups.clone(),
            shortcut_groups: self.shortcut_groups.clone(),
            options: QueryOptions {
                landmarks: 0,
                ..self.options.clone()
            },
            landmarks: OnceLock::new(),
            kept_tree: KeptTree::default(),
        };
        let Some(nodes) = inner.astar(grown.start, grown.goal) else {
            result.outcome = QueryOutcome::Disconnected;
            return Ok(result);
        };
        result.outcome = QueryOutcome::Grown;
        result.roadmap_nodes = nodes.len();
        let mut raw = vec![result.start.clone()];
        raw.extend(inner.node_path(&nodes));
        self.finish(result, raw, shortening)
    }

    /// Grows two trees out of the roadmap from the query's ends until they meet or
    /// `deadline` passes ([`QueryOptions::trees`]), and answers along them, shortened until
    /// `shortening`.
    fn trees(
        &self,
        mut result: QueryResult,
        params: &TreeParams,
        deadline: &Deadline,
        shortening: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        let seed = query_seed(self.roadmap.header().seed, &result);
        let found = RoadmapTrees::new(self.roadmap, self.oracle, &self.groups)
            .keeping(&self.kept_tree)
            .connect(
                &result.start,
                &result.goal,
                &self.tree_params(params),
                seed,
                deadline,
            )?;
        result.counts += found.counts;
        result.grown_nodes = found.nodes[0] + found.nodes[1];
        result.trees = found.trees.filter(|_| self.options.return_trees);
        let Some(mut raw) = found.path else {
            result.outcome = match found.stop {
                TreeStop::NodeBudget => QueryOutcome::Disconnected,
                _ => QueryOutcome::TimedOut,
            };
            return Ok(result);
        };
        result.outcome = QueryOutcome::Trees;
        raw.dedup();
        // a tree path has hundreds of corners: greedy passes first (at most a check per
        // corner and pass), so that `finish`'s visibility graph runs over tens, not hundreds
        // (their answers go on to `finish`'s visibility graph)
        let mut known = KnownPieces::new();
        let mut fewer = raw.clone();
        if self.options.shorten {
            let began = Instant::now();
            // corners along the straight extends, for shortcuts to start and end at
            let piece = crate::roadmap::tree::STRAIGHT_PIECE * self.space().extent();
            let dense = crate::local::straight_corners(self.space(), &raw, piece);
            known.certify_path(self.space(), &self.shortcut_groups, &dense);
            fewer = self.greedy_passes(&dense, &mut known, &mut result.counts, shortening)?;
            result.shorten_s += began.elapsed().as_secs_f64();
        }
        // the visibility graph costs up to m²/2 checks: not over what is still hundreds
        let exact = fewer.len() <= self.long_path();
        let mut answer = self.finish_with(result, fewer, shortening, exact, known)?;
        answer.raw_length = path_length(self.space(), &self.groups, &raw);
        answer.raw_path = raw;
        Ok(answer)
    }

    /// The trees' parameters as this query grows them: staircases only where the straight
    /// motions are off ([`QueryOptions::straight_shortcuts`]).
    fn tree_params(&self, params: &TreeParams) -> TreeParams {
        TreeParams {
            straight: params.straight && self.options.straight_shortcuts,
            ..params.clone()
        }
    }

    /// The quick try from start to goal before the roadmap: for a via-point roadmap the direct
    /// path ([`Self::direct_check`]; an arm's straight motion where it is asked,
    /// [`Self::straight_or_blocked`]) or the planner limited to [`QueryOptions::direct_calls`];
    /// any other roadmap's method is such a check already. With it, whether the roadmap's
    /// method from start to goal may still succeed where the roadmap cannot join them: not
    /// where the quick try was that method, or a search that ran out of alternatives before
    /// any budget or depth limit; and whether the staircase was left for then (an arm's
    /// straight motion not proved).
    fn quick_try(
        &self,
        start: &[f64],
        goal: &[f64],
        result: &mut QueryResult,
        deadline: &Deadline,
    ) -> Result<(Connection, bool, bool), QueryError> {
        if self.quick.is_some() && self.options.direct_calls == 0 {
            if let Some(c) = self.straight_or_blocked(start, goal, result, deadline)? {
                let left = !c.is_connected();
                return Ok((c, true, left));
            }
            return Ok((
                self.direct_check(start, goal, result, deadline)?,
                true,
                false,
            ));
        }
        let method = self.quick.as_deref().unwrap_or(self.local.as_ref());
        let c = self.attempt(method, (start, goal), result, deadline)?;
        let retry = self.quick.is_some() && c.outcome != Outcome::Blocked;
        Ok((c, retry, false))
    }

    /// The direct path from `a` to `z` in the roadmap method's groups, one yes/no question per
    /// piece (what the via-point planner at depth 0 decides, in the same order and with the
    /// same corners): at depth 0 the collision intervals of a blocked piece are never used,
    /// and a yes/no question stops at the first collision it finds where the intervals sweep
    /// the whole motion (an arm's long turn through clutter: 1.3 against 17 ms on average,
    /// README § Robot arms). The deadline and the call budget are checked before each piece.
    fn direct_check(
        &self,
        a: &[f64],
        z: &[f64],
        result: &mut QueryResult,
        deadline: &Deadline,
    ) -> Result<Connection, QueryError> {
        let mut corners = Vec::new();
        let pieces = direct_pieces(self.space(), &self.groups, 0, a, z);
        if surely_blocked(self.oracle, &pieces) {
            return Ok(Connection::from_corners(a, z, None, CallCounts::default()));
        }
        for (motion, end) in pieces {
            if deadline.expired() || self.calls_left(result) == Some(0) {
                return Ok(Connection::interrupted(a, z));
            }
            if !self.oracle.check_motion(&motion, &mut result.counts)? {
                return Ok(Connection::from_corners(a, z, None, CallCounts::default()));
            }
            corners.push(end);
        }
        if corners.is_empty() {
            corners.push(z.to_vec());
        }
        Ok(Connection::from_corners(
            a,
            z,
            Some(corners),
            CallCounts::default(),
        ))
    }

    /// The straight motion of several joints from `a` to `z` as the direct path, where shortcuts
    /// take them ([`QueryOptions::straight_shortcuts`]): one call, the connection if it is
    /// proved free (no staircase to shorten after it), else blocked. The single-joint staircase
    /// is not swept then: between an arm's distant configurations in clutter it mostly
    /// collides, and its exact sweeps cost most of a query the roadmap answers after all (the
    /// bookshelf_thin workcell's p50: a third); the roadmap's method still searches where the
    /// direct paths do not join. `None` where the straight motion is not asked (the staircase
    /// is the direct path) or time or calls ran out.
    fn straight_or_blocked(
        &self,
        a: &[f64],
        z: &[f64],
        result: &mut QueryResult,
        deadline: &Deadline,
    ) -> Result<Option<Connection>, QueryError> {
        let (space, groups) = (self.space(), &self.groups);
        if !self.options.straight_shortcuts
            || deadline.expired()
            || self.calls_left(result) == Some(0)
            || !crate::local::goes_straight(space, groups, a, z)
        {
            return Ok(None);
        }
        let proved = straight_connection(space, self.oracle, groups, a, z, &mut result.counts)?;
        Ok(Some(proved.unwrap_or_else(|| {
            Connection::from_corners(a, z, None, CallCounts::default())
        })))
    }

    /// The intersect calls the query may still spend ([`QueryOptions::max_calls`]; `None`: no
    /// limit).
    fn calls_left(&self, result: &QueryResult) -> Option<u64> {
        self.options
            .max_calls
            .map(|m| m.saturating_sub(result.counts.intersect_calls()))
    }

    /// One local-method attempt of the query from `a` to `z`, within `deadline` and what is
    /// left of the call budget, counted in `result`.
    fn attempt(
        &self,
        method: &dyn LocalMethod,
        (a, z): (&[f64], &[f64]),
        result: &mut QueryResult,
        deadline: &Deadline,
    ) -> Result<Connection, QueryError> {
        let space = self.space();
        let c = match self.calls_left(result) {
            None => method.connect_within(space, self.oracle, a, z, deadline)?,
            Some(0) => Connection::interrupted(a, z),
            Some(left) => match method.spec().budgeted(left) {
                Some(spec) => spec
                    .build()
                    .connect_within(space, self.oracle, a, z, deadline)?,
                // a method that does not search costs a few calls: it runs as it is
                None => method.connect_within(space, self.oracle, a, z, deadline)?,
            },
        };
        result.counts += c.counts;
        Ok(c)
    }

    /// Attaches start and goal to their `k` nearest nodes, alternating sides, one node per
    /// component and side (components already attached on a side are skipped): first the
    /// nearest `direct` by the direct path alone ([`QueryOptions::attach_direct_candidates`];
    /// an arm's straight motion where it is asked, [`Self::straight_or_blocked`]),
    /// then all `k` with `method` (not in the [`Stages::Direct`] of a method that searches).
    /// Returns the indices of a start and a goal attachment in one component, if any.
    #[allow(clippy::too_many_arguments)]
    fn attach(
        &self,
        method: &dyn LocalMethod,
        (k, direct): (usize, usize),
        stages: Stages,
        ends: (&[f64], &[f64]),
        attached: &mut (Vec<Attached>, Vec<Attached>),
        result: &mut QueryResult,
        deadline: &Deadline,
    ) -> Result<Option<(usize, usize)>, QueryError> {
        // a race's head start tries only the nodes the trees out of the roadmap would attach
        // each end to first ([`ATTACH_CANDIDATES`], the answers remembered for them): in the
        // Panda's trained workcells every end the head start attaches takes one of its five
        // nearest nodes, while a goal under a shelf's board fails every candidate, and thirty
        // such failures cost 0.2–0.4 ms before its trees start
        let k = match stages {
            Stages::Direct => k.min(ATTACH_CANDIDATES),
            Stages::All => k,
        };
        let near = (
            self.roadmap.nearest(ends.0, k, None),
            self.roadmap.nearest(ends.1, k, None),
        );
        // only a method that searches gains by it: `straight` and `sampled` are the direct
        // check themselves (a first pass would ask each candidate twice), and a sampled
        // roadmap's queries must not be answered by exact checks
        let searches = matches!(method.spec(), LocalSpec::ViaPoint(_));
        let direct = if searches { direct.min(k) } else { 0 };
        if direct > 0 {
            let space = self.space();
            let mut straight = |a: &[f64], z: &[f64], result: &mut QueryResult| {
                if let Some(c) = self.straight_or_blocked(a, z, result, deadline)? {
                    return Ok(c);
                }
                let c = direct_connection(space, self.oracle, &self.groups, a, z)?;
                result.counts += c.counts;
                Ok(c)
            };
            let met = self.attach_pass(
                direct,
                &near,
                ends,
                attached,
                result,
                deadline,
                &mut straight,
            )?;
            if met.is_some() {
                return Ok(met);
            }
        }
        if searches && stages == Stages::Direct {
            return Ok(None);
        }
        let mut local = |a: &[f64], z: &[f64], result: &mut QueryResult| {
            self.attempt(method, (a, z), result, deadline)
        };
        self.attach_pass(k, &near, ends, attached, result, deadline, &mut local)
    }

    /// One pass of [`Self::attach`] over the first `k` of the `near` nodes of each side, each
    /// tried with `connect`.
    #[allow(clippy::too_many_arguments)]
    fn attach_pass(
        &self,
        k: usize,
        (near_start, near_goal): &(Near, Near),
        (start, goal): (&[f64], &[f64]),
        (at_start, at_goal): &mut (Vec<Attached>, Vec<Attached>),
        result: &mut QueryResult,
        deadline: &Deadline,
        connect: &mut Connect<'_>,
    ) -> Result<Option<(usize, usize)>, QueryError> {
        for i in 0..k.min(near_start.len().max(near_goal.len())) {
            for side in [Endpoint::Start, Endpoint::Goal] {
                let (near, mine, theirs) = match side {
                    Endpoint::Start => (near_start, &mut *at_start, &*at_goal),
                    Endpoint::Goal => (near_goal, &mut *at_goal, &*at_start),
                };
                let Some(&(node, _)) = near.get(i) else {
                    continue;
                };
                let component = self.roadmap.component(node);
                if mine.iter().any(|a| a.component == component) {
                    continue;
                }
                if deadline.expired() || self.calls_left(result) == Some(0) {
                    return Ok(None);
                }
                let q = self.roadmap.node(node);
                let (a, z) = match side {
                    Endpoint::Start => (start, q),
                    Endpoint::Goal => (q, goal),
                };
                let connection = connect(a, z, result)?;
                result.attach_attempts += 1;
                if !connection.is_connected() {
                    continue;
                }
                mine.push(Attached {
                    component,
                    node,
                    connection,
                });
                if let Some(j) = theirs.iter().position(|a| a.component == component) {
                    let m = mine.len() - 1;
                    return Ok(Some(match side {
                        Endpoint::Start => (m, j),
                        Endpoint::Goal => (j, m),
                    }));
                }
            }
        }
        Ok(None)
    }

    /// A* from node `s` to node `g`: the nodes on the way, both ends included.
    fn astar(&self, s: u32, g: u32) -> Option<Vec<u32>> {
        let goal = self.roadmap.node(g);
        let space = self.roadmap.space();
        // each node's estimate once: A* asks again at every improvement of a node's cost, and
        // an SE(3) distance costs a rotation angle
        let mut estimate = vec![f64::NAN; self.roadmap.node_count()];
        let landmarks = self.landmarks();
        petgraph::algo::astar(
            self.roadmap.graph(),
            NodeIndex::new(s as usize),
            |n| n.index() == g as usize,
            |e| *e.weight(),
            |n| {
                let h = &mut estimate[n.index()];
                if h.is_nan() {
                    let v = n.index() as u32;
                    *h = space.distance(self.roadmap.node(v), goal);
                    if let Some(l) = landmarks {
                        *h = h.max(l.lower_bound(v, g));
                    }
                }
                *h
            },
        )
        .map(|(_, path)| path.into_iter().map(|n| n.index() as u32).collect())
    }

    /// The shortest edge between adjacent nodes `u` and `v`.
    fn cheapest_edge(&self, u: u32, v: u32) -> usize {
        use petgraph::visit::EdgeRef;
        self.roadmap
            .graph()
            .edges_connecting(NodeIndex::new(u as usize), NodeIndex::new(v as usize))
            .min_by(|a, b| a.weight().total_cmp(b.weight()).then(a.id().cmp(&b.id())))
            .map(|e| e.id().index())
            .expect("A* only steps along edges")
    }

    /// Drops repeated corners, shortens, measures.
    /// Shortening stops when the query's time is up (before each check of a pair): what it
    /// had shortened (the greedy pass's prefix, the visibility graph's best over the pairs it
    /// found free), or the raw path, is a valid answer.
    fn finish(
        &self,
        result: QueryResult,
        raw: Vec<Config>,
        deadline: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        self.finish_with(result, raw, deadline, true, KnownPieces::new())
    }

    /// [`Self::finish`], shortening only if `shorten` too, with the pieces `known` so far.
    fn finish_with(
        &self,
        mut result: QueryResult,
        mut raw: Vec<Config>,
        deadline: &Deadline,
        shorten: bool,
        mut known: KnownPieces,
    ) -> Result<QueryResult, QueryError> {
        let space = self.roadmap.space();
        raw.dedup();
        let path = if self.options.shorten && shorten && !deadline.expired() {
            let shortening = Instant::now();
            // the pieces of the raw path are free (roadmap edges and attachments), and the
            // greedy pass's answers are shared with the visibility graph
            known.certify_path(space, &self.shortcut_groups, &raw);
            let fewer;
            let corners = if raw.len() > self.greedy_above() {
                fewer = drop_corners_known(
                    space,
                    self.oracle,
                    &self.shortcut_groups,
                    &raw,
                    &mut known,
                    &mut result.counts,
                    deadline,
                )?;
                &fewer
            } else {
                &raw
            };
            // the visibility graph costs up to m²/2 checks and an A* search per blocked pair:
            // not over what is still hundreds of corners (an answer through kept staircases in
            // the cage: 230 corners, 0.9 s), which greedy passes shorten instead
            let path = if corners.len() > self.long_path() {
                self.greedy_passes(corners, &mut known, &mut result.counts, deadline)?
            } else {
                shorten_known(
                    space,
                    self.oracle,
                    &self.shortcut_groups,
                    corners,
                    &mut known,
                    &mut result.counts,
                    deadline,
                )?
            };
            result.shorten_s += shortening.elapsed().as_secs_f64();
            path
        } else {
            raw.clone()
        };
        result.set_paths(space, &self.groups, raw, path);
        Ok(result)
    }

    /// A path still longer than this after a greedy pass is shortened by greedy passes alone,
    /// not the visibility graph ([`TREE_SHORTENING_FACTOR`] times
    /// [`QueryOptions::exact_shortening_limit`] corners).
    fn long_path(&self) -> usize {
        TREE_SHORTENING_FACTOR.saturating_mul(self.options.exact_shortening_limit)
    }

    /// Greedy passes over `path` ([`drop_corners_known`]) until one drops no corner or
    /// `deadline` passes.
    fn greedy_passes(
        &self,
        path: &[Config],
        known: &mut KnownPieces,
        counts: &mut CallCounts,
        deadline: &Deadline,
    ) -> Result<Vec<Config>, QueryError> {
        let mut fewer = path.to_vec();
        loop {
            let next = drop_corners_known(
                self.space(),
                self.oracle,
                &self.shortcut_groups,
                &fewer,
                known,
                counts,
                deadline,
            )?;
            let better = next.len() < fewer.len();
            fewer = next;
            if !better || deadline.expired() {
                return Ok(fewer);
            }
        }
    }

    /// The most corners a path may have for the visibility graph to run over all of them
    /// ([`QueryOptions::exact_shortening_limit`] per two DOF groups).
    fn greedy_above(&self) -> usize {
        let groups = self.groups.len().max(2);
        self.options.exact_shortening_limit.saturating_mul(groups) / 2
    }

    /// Answers many queries in parallel on the current rayon pool; answers in input order.
    pub fn query_batch(&self, queries: &[(Config, Config)]) -> Vec<BatchAnswer> {
        let answers: Vec<std::sync::Mutex<Option<BatchAnswer>>> =
            queries.iter().map(|_| Default::default()).collect();
        self.query_each(queries, &Deadline::none(), &|i, a| {
            *answers[i].lock().unwrap_or_else(|p| p.into_inner()) = Some(a);
        });
        answers
            .into_iter()
            .map(|m| {
                m.into_inner()
                    .unwrap_or_else(|p| p.into_inner())
                    .expect("every query is answered")
            })
            .collect()
    }

    /// Answers many queries in parallel, handing each answer to `on_answer` (with its index
    /// in `queries`) as soon as it is ready, so that a long batch streams its answers and an
    /// interrupted one keeps those it had. Each query has its own [`QueryOptions::time`];
    /// `outer` stops the whole batch (queries not begun then answer
    /// [`QueryOutcome::TimedOut`]).
    pub fn query_each(
        &self,
        queries: &[(Config, Config)],
        outer: &Deadline,
        on_answer: &(dyn Fn(usize, BatchAnswer) + Sync),
    ) {
        queries.par_iter().enumerate().for_each(|(i, (s, g))| {
            let began = Instant::now();
            let result = self.query_within(s, g, outer);
            on_answer(
                i,
                BatchAnswer {
                    result,
                    elapsed: began.elapsed(),
                },
            );
        });
    }
}
