//! One query planned the way `viaroad solve` plans it unless told otherwise: a portfolio suited
//! to the scene, so that nobody has to know in advance which planner a problem needs.
//!
//! - Arms: [`Portfolio`]'s stages (the direct path, trees, the via-point planner, trees afresh).
//! - Every other space: the via-point planner first, for a few hundred oracle calls (it answers
//!   open scenes at once and costs little where it cannot; where several bodies move, its own
//!   budget of thousands, with their translation split along the axes as every default local
//!   method there, [`LocalSpec::default_for`]), then two trees and a roadmap grown
//!   from start and goal raced on the rayon pool ([`race`]; in turn on a busy or one-thread
//!   pool). On OMPL.app's hard problems the trees answer most soonest, while a roadmap answers
//!   where the trees' random extends keep missing a narrow passage: no single planner wins
//!   everywhere, and a race costs at most the slower of two cores.
//!
//! Every path returned is certified free by the exact oracle, like any other of the crate's.

use crate::deadline::{race, Deadline};
use crate::local::{shorten_known, KnownPieces, LocalSpec};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::portfolio::{tree_stage, trees_found, Planning, Portfolio, PortfolioError, Stage};
use crate::roadmap::tree::{TreeError, TreeParams};
use crate::roadmap::{
    Budget, LearnError, LearnParams, Learner, QueryError, QueryOptions, QueryPlanner, Roadmap,
    RoadmapError, Sampler,
};
use crate::scene::{Robot, Scene};
use crate::space::{Config, Space, SpaceKind};
use std::time::Duration;

/// The planners of one query and their budgets.
#[derive(Clone, Debug)]
pub struct Solver {
    /// Seed of the trees and of the grown roadmap.
    pub seed: u64,
    /// Most nodes of the trees and of the grown roadmap, each: a budget that gives the same
    /// answer on any machine when no time limit cuts it short.
    pub nodes: Option<usize>,
    /// Straight motions of several joints at once where they are proved free (arms).
    pub straight: bool,
    /// Oracle calls of the via-point planner's first try; `None`: suited to the scene
    /// ([`Solver::direct_calls_for`]).
    pub direct_calls: Option<u64>,
    /// Where the grown roadmap draws new nodes; `None`: the learner's default
    /// ([`LearnParams::sampler`]).
    pub sampler: Option<Sampler>,
}

/// Oracle calls of the via-point planner's first try on one body or one arm: it answers open
/// scenes at once and costs little where it cannot.
pub const DIRECT_CALLS: u64 = 300;

/// Oracle calls of the first try where several bodies move: the via-point planner's own budget
/// ([`crate::local::ViaPointOptions::default`]). Split along the axes, the deep planner alone
/// connects both cube scenes (87 and 2 361 calls) and the movers in a room (912), and gives up
/// on the swaps within 4 500 calls (a tenth of a second), where the trees and the roadmap
/// raced after it take seconds.
pub const SEVERAL_BODIES_DIRECT_CALLS: u64 = 5000;

impl Default for Solver {
    fn default() -> Self {
        Solver {
            seed: 1,
            nodes: None,
            straight: true,
            direct_calls: None,
            sampler: None,
        }
    }
}

/// The planner that answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The direct path or the via-point planner.
    Direct,
    /// Two trees (RRT-Connect with exact extends).
    Trees,
    /// A roadmap grown from start and goal.
    Roadmap,
}

impl Method {
    /// The name output and tables use.
    pub fn name(self) -> &'static str {
        match self {
            Method::Direct => "direct",
            Method::Trees => "trees",
            Method::Roadmap => "roadmap",
        }
    }
}

/// A planner that failed.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The via-point planner's first try.
    #[error("local method: {0}")]
    Local(#[from] OracleError),
    /// The trees.
    #[error("trees: {0}")]
    Trees(#[from] TreeError),
    /// Growing the roadmap.
    #[error("growing a roadmap: {0}")]
    Learn(#[from] LearnError),
    /// Answering through the grown roadmap.
    #[error("roadmap query: {0}")]
    Query(#[from] QueryError),
    /// The grown roadmap could not be queried.
    #[error("roadmap: {0}")]
    Roadmap(#[from] RoadmapError),
    /// A stage of the arm's portfolio.
    #[error("{0}")]
    Portfolio(#[from] PortfolioError),
}

/// What [`Solver::plan`] found.
#[derive(Debug, Default)]
pub struct Solution {
    /// The planner that answered; `None`: unsolved within the budget.
    pub method: Option<Method>,
    /// The path as found (empty when unsolved).
    pub raw: Vec<Config>,
    /// The path shortened within the same deadline.
    pub shortened: Vec<Config>,
    /// Oracle work of every planner that ran.
    pub counts: CallCounts,
    /// Nodes of the trees and roadmaps that ran.
    pub nodes: usize,
    /// The roadmap grown, when it answered (what `view --show-roadmap` draws).
    pub roadmap: Option<Roadmap>,
    /// A planner that failed while another answered.
    pub warning: Option<String>,
}

impl Solution {
    /// Whether a path was found.
    pub fn is_solved(&self) -> bool {
        self.method.is_some()
    }
}

impl Solver {
    /// The calls of the via-point planner's first try in `space`: [`Self::direct_calls`] when
    /// set, else [`SEVERAL_BODIES_DIRECT_CALLS`] where several bodies move and
    /// [`DIRECT_CALLS`] elsewhere.
    pub fn direct_calls_for(&self, space: &Space) -> u64 {
        self.direct_calls.unwrap_or(match space.kind() {
            SpaceKind::Se2Bodies(_) | SpaceKind::Se3Bodies(_) => SEVERAL_BODIES_DIRECT_CALLS,
            _ => DIRECT_CALLS,
        })
    }

    /// Plans from `start` to `goal` (both free, as [`Scene::checked_queries`] gives them) until
    /// `deadline`. A planner's error is the answer only when no other planner answered.
    pub fn plan(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        (start, goal): (&Config, &Config),
        deadline: &Deadline,
    ) -> Result<Solution, SolveError> {
        match scene.robot {
            Robot::Arm(_) => self.plan_arm(scene, oracle, (start, goal), deadline),
            _ => self.plan_rigid(scene, oracle, (start, goal), deadline),
        }
    }

    fn plan_arm(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        ends: (&Config, &Config),
        deadline: &Deadline,
    ) -> Result<Solution, SolveError> {
        let mut portfolio = Portfolio {
            seed: self.seed,
            direct_calls: self.direct_calls_for(&scene.space),
            ..Portfolio::default()
        };
        if let Some(tree) = &mut portfolio.tree {
            tree.max_nodes = self.nodes;
        }
        let groups = LocalSpec::default().build().groups(&scene.space);
        let planning = Planning {
            scene,
            oracle,
            groups: &groups,
            straight: self.straight,
        };
        let a = portfolio.plan(&planning, ends, deadline);
        let mut s = Solution {
            counts: a.counts,
            nodes: a.nodes,
            ..Solution::default()
        };
        match (&a.path, a.error) {
            (None, Some(e)) => return Err(e.into()),
            (Some(_), Some(e)) => s.warning = Some(e.to_string()),
            _ => {}
        }
        if let (Some((raw, short)), Some(stage)) = (a.path, a.stage) {
            s.method = Some(match stage {
                Stage::Direct => Method::Direct,
                Stage::Tree => Method::Trees,
            });
            s.raw = raw;
            s.shortened = short;
        }
        Ok(s)
    }

    fn plan_rigid(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        (start, goal): (&Config, &Config),
        deadline: &Deadline,
    ) -> Result<Solution, SolveError> {
        let mut s = self.direct(scene, oracle, (start, goal), deadline)?;
        if s.is_solved() || deadline.expired() {
            return Ok(s);
        }
        let groups = scene.space.groups(false);
        let planning = Planning {
            scene,
            oracle,
            groups: &groups,
            straight: self.straight,
        };
        let tree = TreeParams {
            max_nodes: self.nodes,
            ..TreeParams::for_space(&scene.space)
        };
        // the roadmap is the side a one-thread race gives a short first turn; the trees,
        // which answer most problems, then run to the deadline
        // several bodies: the roadmap's walks (slides, one body at a time) answer, trees rarely
        // do; the roadmap runs alone for half the time, so a busy pool cannot starve it
        let head = (scene.space.body_count() > 1).then(|| deadline.remaining().map(|t| t / 2));
        let raced = race(
            deadline,
            head.flatten().unwrap_or(Duration::ZERO),
            |search, whole| self.grown_roadmap(scene, oracle, (start, goal), search, whole),
            |r| r.as_ref().is_ok_and(Solution::is_solved),
            |d| tree_stage(&planning, (start, goal), &tree, self.seed, d, d),
            trees_found,
        );
        let mut failed = None;
        for r in raced.head_start.into_iter().chain([raced.first]) {
            match r {
                Ok(r) => s.take(r),
                Err(e) => failed = Some(e),
            }
        }
        match raced.second {
            Some(Ok(t)) => {
                s.counts += t.counts;
                s.nodes += t.nodes;
                if let (None, Some((raw, short))) = (s.method, t.path) {
                    s.method = Some(Method::Trees);
                    s.raw = raw;
                    s.shortened = short;
                }
                if let Some(e) = t.shortening_error {
                    s.warning = Some(format!("shortening: {e}"));
                }
            }
            Some(Err(e)) => failed = Some(e.into()),
            None => {}
        }
        match failed {
            Some(e) if !s.is_solved() => Err(e),
            Some(e) => {
                s.warning = Some(e.to_string());
                Ok(s)
            }
            None => Ok(s),
        }
    }

    /// The via-point planner within [`Self::direct_calls_for`], its path shortened.
    fn direct(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        (start, goal): (&Config, &Config),
        deadline: &Deadline,
    ) -> Result<Solution, SolveError> {
        let method = LocalSpec::default_for(&scene.space)
            .budgeted(self.direct_calls_for(&scene.space))
            .unwrap_or_default()
            .build();
        let c = method.connect_within(&scene.space, oracle, start, goal, deadline)?;
        let mut s = Solution {
            counts: c.counts,
            ..Solution::default()
        };
        if c.is_connected() {
            let groups = method.groups(&scene.space);
            let mut known = KnownPieces::new();
            known.certify_path(&scene.space, &groups, &c.path);
            s.shortened = shorten_known(
                &scene.space,
                oracle,
                &groups,
                &c.path,
                &mut known,
                &mut s.counts,
                deadline,
            )?;
            s.raw = c.path;
            s.method = Some(Method::Direct);
        }
        Ok(s)
    }

    /// The grown roadmap alone (what [`Self::plan`] races against the trees): for callers that
    /// want the roadmap itself, as `view --show-roadmap` draws it.
    pub fn plan_by_roadmap(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        ends: (&Config, &Config),
        deadline: &Deadline,
    ) -> Result<Solution, SolveError> {
        self.grown_roadmap(scene, oracle, ends, deadline, deadline)
    }

    /// A roadmap grown from start and goal until they share a component (OMPL's PRM `solve`),
    /// searching until `search`, the path through it shortened until `whole`.
    fn grown_roadmap(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        (start, goal): (&Config, &Config),
        search: &Deadline,
        whole: &Deadline,
    ) -> Result<Solution, SolveError> {
        let method = LocalSpec::roadmap_default_for(&scene.space).build();
        let learner = Learner::for_scene(scene, oracle, method.as_ref())
            .with_attempt_cap(search.remaining().map(Learner::attempt_cap_for));
        let params = LearnParams {
            sampler: self.sampler.clone().unwrap_or_default(),
            ..LearnParams::default()
        };
        let grown = learner.connect_pair(
            &params,
            None,
            (start, goal),
            &Budget {
                nodes: self.nodes,
                time: None,
            },
            self.seed,
            search,
            &mut |_| {},
        )?;
        let roadmap = grown.learnt.roadmap;
        let mut s = Solution {
            counts: roadmap.header().counts,
            nodes: roadmap.node_count(),
            ..Solution::default()
        };
        if grown.connected {
            // start and goal are nodes of one component: the query attaches them to themselves
            let planner = QueryPlanner::new(&roadmap, oracle)?.with_options(QueryOptions {
                landmarks: 0,
                grow: false,
                ..QueryOptions::default()
            });
            let r = planner.query_finding_within(start, goal, whole, whole)?;
            s.counts += r.counts;
            if r.is_solved() {
                s.method = Some(Method::Roadmap);
                s.raw = r.raw_path;
                s.shortened = r.path;
            }
        }
        if s.is_solved() {
            s.roadmap = Some(roadmap);
        }
        Ok(s)
    }
}

impl Solution {
    /// Adds another planner's work, and its path if none was found yet.
    fn take(&mut self, other: Solution) {
        self.counts += other.counts;
        self.nodes += other.nodes;
        if self.method.is_none() && other.method.is_some() {
            self.method = other.method;
            self.raw = other.raw;
            self.shortened = other.shortened;
            self.roadmap = other.roadmap;
        }
        if other.warning.is_some() {
            self.warning = other.warning;
        }
    }
}
