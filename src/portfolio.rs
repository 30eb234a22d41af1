//! One query planned by a portfolio of the crate's planners, in the order the arm benchmark
//! measures best (the trees-first results in `benches/results/`): the direct path, two trees
//! for a share of the time, the via-point planner (a search bounded in
//! oracle calls), then the trees afresh for what is left — or the via-point planner and the
//! trees racing on the rayon pool ([`Portfolio::race`]). The path found is shortened within the
//! same deadline.
//!
//! Why this order: on the 700 Panda problems the trees answer most queries in a few tens of
//! milliseconds, while the via-point search's calls sweep whole joint ranges (≈ 1–3 ms each)
//! and it alone fails in the cage (depth exhausted); it waits for what the trees do not solve
//! soon (a goal deep in a narrow shelf), where its dodging through a gap is what answers.
//! `viaroad solve` plans an arm scene's queries so, and `viaroad bench mbm` every problem.
//!
//! The trees extend by straight motions of all joints, each proved free by conservative
//! advancement or the extend given up ([`TreeParams::staircase`] off), as VAMP's RRT-Connect
//! keeps a motion whole or not at all: a blocked extend costs one proof, where a staircase
//! asked up to four straight stairs and their single-joint sweeps. On the first 6 Panda problems
//! of each family (one thread, CPU time of planning) the mean fell from 26.6 to 3.7 ms and the
//! median from 7.7 to 2.0 ms, all 42 solved.

use crate::deadline::{race, Deadline};
use crate::local::{
    direct_connection, shorten_known, straight_connection, Connection, KnownPieces, LocalSpec,
};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::roadmap::tree::{
    rrt_connect, shortcut_passes, stream_seed, Domain, Prefix, Rooted, Stairs, TreeError,
    TreeOutcome, TreeParams, SHORTCUT_WINDOW,
};
use crate::scene::Scene;
use crate::space::{Config, Group};
use std::time::{Duration, Instant};

/// What every stage of one query plans in: the scene, the oracle the stages share (its kept
/// answers serve them all) and the local method's DOF groups.
#[derive(Clone, Copy)]
pub struct Planning<'a> {
    /// The query's scene.
    pub scene: &'a Scene,
    /// The oracle every stage asks.
    pub oracle: &'a dyn CollisionOracle,
    /// The DOF groups single-group motions move (one per joint for an arm).
    pub groups: &'a [Group],
    /// Straight motions of several joints at once where they are proved free
    /// ([`Space::straight_group`](crate::space::Space::straight_group)), not only single-joint
    /// staircases: start to goal, the trees' extends ([`TreeParams::straight`], which this
    /// turns off too) and shortening (as [`crate::roadmap::QueryOptions::straight_shortcuts`]).
    pub straight: bool,
}

impl Planning<'_> {
    /// The groups shortening checks pairs of corners with ([`Self::straight`]).
    pub fn shortcut_groups(&self) -> Vec<Group> {
        match self.scene.space.straight_group().filter(|_| self.straight) {
            Some(whole) => vec![whole],
            None => self.groups.to_vec(),
        }
    }
}

/// The trees' longest extend, as a share of the joint space's extent: about 1 rad on the
/// Panda, as far as VAMP's RRT-Connect extends. Shorter extends are proved straight more
/// often, and a blocked one wastes less: on the first 8 Panda problems of each family against
/// OMPL's 0.2, the cage's mean fell 2.4× and the other families' by 1.5–2×.
pub const TREE_RANGE: f64 = 0.08;

/// The trees' longest stair, as a share of the extent, where they walk an extend whose
/// straight motion is not proved as a staircase ([`TreeParams::staircase`], off in
/// [`Portfolio::default`]): each stair is asked as one straight motion, then joint by joint. Against 0.01,
/// on the first 8 Panda problems of the box, table_under_pick, cage and bookshelf_small
/// families, the mean fell 1.3–2× with half the oracle calls; 0.04 let the cage's tail grow.
pub const TREE_STAIR: f64 = 0.02;

/// The stages and their budgets. The default is `viaroad bench mbm`'s.
#[derive(Clone, Debug)]
pub struct Portfolio {
    /// Oracle calls the via-point planner may spend (0: the direct path only, then the trees).
    pub direct_calls: u64,
    /// The trees' parameters; `None`: the via-point planner alone.
    pub tree: Option<TreeParams>,
    /// Not racing, with a via-point budget: the trees' first share of the time, before the
    /// via-point planner; `None`: the via-point planner first, the trees after it. Without a
    /// time limit the first trees grow until they connect or their node budget ends.
    pub trees_first: Option<f64>,
    /// The via-point planner and the trees at once on the rayon pool, the first to connect
    /// stopping the other, rather than one after the other; the value is the via-point
    /// planner's head start alone ([`race`]; zero: none).
    pub race: Option<Duration>,
    /// Seed of the trees (the second trees of the staged order take the next stream).
    pub seed: u64,
}

impl Default for Portfolio {
    fn default() -> Self {
        Portfolio {
            direct_calls: 300,
            tree: Some(TreeParams {
                range: TREE_RANGE,
                stair: TREE_STAIR,
                prefix: Prefix::FirstHit,
                stairs: Stairs::Whole,
                balance: true,
                staircase: false,
                domain: Some(Domain::ARM),
                ..TreeParams::default()
            }),
            trees_first: Some(0.2),
            race: None,
            seed: 1,
        }
    }
}

/// The stage that answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The direct path or the via-point planner.
    Direct,
    /// The trees.
    Tree,
}

impl Stage {
    /// The stage's name as the benchmark's tables write it.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Direct => "direct",
            Stage::Tree => "tree",
        }
    }
}

/// A stage that failed; the stages after it still ran.
#[derive(Debug, thiserror::Error)]
pub enum PortfolioError {
    /// The direct path or the via-point planner.
    #[error("local method: {0}")]
    Local(OracleError),
    /// The trees.
    #[error("trees: {0}")]
    Trees(TreeError),
    /// Shortening the path found (the path shortened so far is kept).
    #[error("shortening: {0}")]
    Shortening(OracleError),
}

/// What [`Portfolio::plan`] found.
#[derive(Debug, Default)]
pub struct Answer {
    /// The stage that answered; `None`: unsolved.
    pub stage: Option<Stage>,
    /// The path as found and as shortened, if solved: corners joined by single-group motions.
    pub path: Option<(Vec<Config>, Vec<Config>)>,
    /// Oracle work of every stage that ran.
    pub counts: CallCounts,
    /// Nodes of the trees that ran (0 when none did).
    pub nodes: usize,
    /// Until the direct path or the via-point planner answered or gave up, seconds.
    pub direct_s: f64,
    /// Growing the trees, seconds.
    pub grow_s: f64,
    /// Shortening the path found, seconds.
    pub shorten_s: f64,
    /// The last stage that failed, if any.
    pub error: Option<PortfolioError>,
}

impl Portfolio {
    /// Plans from `start` to `goal` (both free) until `deadline`.
    pub fn plan(
        &self,
        p: &Planning,
        (start, goal): (&Config, &Config),
        deadline: &Deadline,
    ) -> Answer {
        let began = Instant::now();
        let mut a = Answer::default();
        let direct = LocalSpec::default()
            .budgeted(self.direct_calls)
            .unwrap_or_default();
        let method = direct.build();
        // the via-point planner's answer and when it came (its stage time, racing or not)
        // (the path it finds is shortened after the race, within the query's deadline)
        let via_points = |d: &Deadline, _: &Deadline| {
            let c = method.connect_within(&p.scene.space, p.oracle, start, goal, d);
            (c, began.elapsed().as_secs_f64())
        };
        let connects = |(c, _): &(Result<Connection, OracleError>, f64)| {
            c.as_ref().is_ok_and(|c| c.is_connected())
        };
        // the trees searching until `search`, a path they found shortened until `whole`
        let trees_seeded = |tree: &TreeParams, search: &Deadline, whole: &Deadline, seed: u64| {
            tree_stage(p, (start, goal), tree, seed, search, whole)
        };
        let trees = |tree: &TreeParams, d: &Deadline| trees_seeded(tree, d, d, self.seed);
        let trees_first = self.trees_first.filter(|_| self.direct_calls > 0);
        let (connected, raced) = match (&self.tree, self.race, trees_first) {
            (None, _, _) => (via_points(deadline, deadline), None),
            (Some(tree), Some(head_start), _) => {
                let raced = race(
                    deadline,
                    head_start,
                    via_points,
                    connects,
                    |d| trees(tree, d),
                    trees_found,
                );
                // the head start's calls count too
                if let Some((Ok(c), _)) = &raced.head_start {
                    a.counts += c.counts;
                }
                (raced.first, raced.second)
            }
            // the direct path alone, then the trees for their share of the time, then the
            // via-point search, then the trees afresh (another random stream) for the rest
            (Some(tree), None, Some(share)) => 'stages: {
                let path = straight_or_direct(p, start, goal);
                let path_s = began.elapsed().as_secs_f64();
                let blocked = matches!(&path, Ok(c) if !c.is_connected());
                if !blocked || deadline.expired() {
                    break 'stages ((path, path_s), None);
                }
                let slice = deadline.within(deadline.remaining().map(|t| t.mul_f64(share)));
                let first = trees_seeded(tree, &slice, deadline, self.seed);
                if trees_found(&first) || first.is_err() || deadline.expired() {
                    break 'stages ((path, path_s), Some(first));
                }
                if let Ok(c) = &path {
                    a.counts += c.counts;
                }
                let searching = Instant::now();
                let (searched, _) = via_points(deadline, deadline);
                let direct_s = path_s + searching.elapsed().as_secs_f64();
                if matches!(&searched, Ok(c) if c.is_connected()) || deadline.expired() {
                    break 'stages ((searched, direct_s), Some(first));
                }
                let again = trees_seeded(tree, deadline, deadline, stream_seed(self.seed, 1));
                (
                    (searched, direct_s),
                    Some(first.and_then(|f| again.map(|a| a.after(f)))),
                )
            }
            (Some(_), None, None) => (via_points(deadline, deadline), None),
        };
        let (connected, direct_s) = connected;
        a.direct_s = direct_s;
        a.take_direct(p, connected, deadline);
        let raced = raced.or_else(|| {
            let tree = self.tree.as_ref()?;
            (a.path.is_none() && !deadline.expired()).then(|| trees(tree, deadline))
        });
        a.take_trees(raced);
        a
    }
}

impl Answer {
    /// Takes the direct stage's answer (the direct path or the via-point planner's) and, when
    /// it connects, shortens its path within the query's time, as every stage (the shortest
    /// path over the pairs found free when it ends).
    fn take_direct(
        &mut self,
        p: &Planning,
        connected: Result<Connection, OracleError>,
        deadline: &Deadline,
    ) {
        match connected {
            Ok(c) => {
                self.counts += c.counts;
                if c.is_connected() {
                    let shortening = Instant::now();
                    // within the query's time, as every stage (the shortest path over the
                    // pairs found free when it ends)
                    let mut known = KnownPieces::new();
                    let groups = p.shortcut_groups();
                    known.certify_path(&p.scene.space, &groups, &c.path);
                    let short = shorten_known(
                        &p.scene.space,
                        p.oracle,
                        &groups,
                        &c.path,
                        &mut known,
                        &mut self.counts,
                        deadline,
                    );
                    self.shorten_s = shortening.elapsed().as_secs_f64();
                    match short {
                        Ok(s) => self.path = Some((c.path, s)),
                        Err(e) => self.error = Some(PortfolioError::Shortening(e)),
                    }
                    self.stage = Some(Stage::Direct);
                }
            }
            Err(e) => self.error = Some(PortfolioError::Local(e)),
        }
    }

    /// Takes the trees' answer, if they ran: their work always, their path only when the
    /// direct stage found none.
    fn take_trees(&mut self, raced: Option<Result<TreeStage, TreeError>>) {
        match raced {
            Some(Ok(found)) => {
                self.nodes = found.nodes;
                self.counts += found.counts;
                self.grow_s = found.grow_s;
                if self.path.is_none() {
                    self.shorten_s = found.shorten_s;
                    if let Some(e) = found.shortening_error {
                        self.error = Some(PortfolioError::Shortening(e));
                    }
                    if found.path.is_some() {
                        self.path = found.path;
                        self.stage = Some(Stage::Tree);
                    }
                }
            }
            Some(Err(e)) => self.error = Some(PortfolioError::Trees(e)),
            None => {}
        }
    }
}

/// What [`tree_stage`] found.
pub struct TreeStage {
    /// Nodes of both trees.
    pub nodes: usize,
    /// Oracle work of the trees and the shortcuts.
    pub counts: CallCounts,
    /// The raw tree path and its shortcut version, if the trees met.
    pub path: Option<(Vec<Config>, Vec<Config>)>,
    /// Why shortcutting stopped early (the path shortened so far is kept).
    pub shortening_error: Option<OracleError>,
    /// Growing the trees, seconds.
    pub grow_s: f64,
    /// Shortcutting their path, seconds.
    pub shorten_s: f64,
    /// The trees as they ended ([`TreeOutcome::trees`]).
    pub trees: Option<Box<[Rooted; 2]>>,
}

impl TreeStage {
    /// This stage after an `earlier` one that found nothing: the work of both (nodes, calls,
    /// growing time), this one's trees and path.
    pub fn after(mut self, earlier: TreeStage) -> TreeStage {
        self.nodes += earlier.nodes;
        self.counts += earlier.counts;
        self.grow_s += earlier.grow_s;
        self
    }
}

/// Whether the trees of a [`tree_stage`] found a path (a side of a [`race`] that answered).
pub fn trees_found(stage: &Result<TreeStage, TreeError>) -> bool {
    stage.as_ref().is_ok_and(|t| t.path.is_some())
}

/// Two trees from `start` and `goal` ([`rrt_connect`]) growing until `search`, their path
/// shortened by greedy shortcut passes until `whole` (a slice of a query's time bounds the
/// search, not the finishing of what it found): the visibility-graph `shorten` of the other
/// stages checks long multi-joint pairs of a tree path's hundreds of corners for seconds (cage
/// 4: 8 s over a 5 s budget), so it is not run here.
pub fn tree_stage(
    p: &Planning,
    (start, goal): (&Config, &Config),
    tree: &TreeParams,
    seed: u64,
    search: &Deadline,
    whole: &Deadline,
) -> Result<TreeStage, TreeError> {
    let growing = Instant::now();
    // staircases only where the straight motions are off; domains where they were measured,
    // in an arm's joints
    let tree = &TreeParams {
        straight: tree.straight && p.straight,
        domain: tree.domain.filter(|_| p.scene.space.is_joints()),
        ..tree.clone()
    };
    let found = rrt_connect(
        &p.scene.space,
        p.oracle,
        p.groups,
        start,
        goal,
        tree,
        seed,
        search,
    )?;
    Ok(shortened(p, found, growing, whole))
}

/// The straight motion of several joints from `start` to `goal` where it is proved free
/// ([`Planning::straight`]: one call, nothing to shorten), else the direct path.
fn straight_or_direct(
    p: &Planning,
    start: &[f64],
    goal: &[f64],
) -> Result<Connection, OracleError> {
    let space = &p.scene.space;
    let mut counts = CallCounts::default();
    if p.straight {
        if let Some(mut c) =
            straight_connection(space, p.oracle, p.groups, start, goal, &mut counts)?
        {
            c.counts = counts;
            return Ok(c);
        }
    }
    let mut c = direct_connection(space, p.oracle, p.groups, start, goal)?;
    c.counts += counts;
    Ok(c)
}

/// The trees' outcome `found` (grown since `growing`) as a [`TreeStage`], its path shortened
/// by greedy shortcut passes within `deadline` ([`tree_stage`]).
fn shortened(p: &Planning, found: TreeOutcome, growing: Instant, deadline: &Deadline) -> TreeStage {
    let mut stage = TreeStage {
        nodes: found.nodes[0] + found.nodes[1],
        counts: found.counts,
        path: None,
        shortening_error: None,
        grow_s: growing.elapsed().as_secs_f64(),
        shorten_s: 0.0,
        trees: found.trees,
    };
    if let Some(raw) = found.path {
        let shortening = Instant::now();
        let (short, error) = shortcut_passes(
            &p.scene.space,
            p.oracle,
            &p.shortcut_groups(),
            &raw,
            SHORTCUT_WINDOW,
            &mut stage.counts,
            deadline,
        );
        // what was shortened before an error is certified free corner to corner
        stage.shortening_error = error;
        stage.shorten_s = shortening.elapsed().as_secs_f64();
        stage.path = Some((raw, short));
    }
    stage
}
