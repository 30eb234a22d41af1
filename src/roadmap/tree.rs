//! Bidirectional trees for one query: RRT-Connect (Kuffner–LaValle 2000) whose *extend* is a
//! staircase of single-group motions, each as far as it is free.
//!
//! A sampling RRT-Connect checks states along a coupled straight motion at a fixed resolution
//! to find the last valid state of an extend. The exact oracle answers that in one call per
//! DOF group (CHS §1.2: the free section containing the motion's start is exactly the part
//! it can reach), but only for single-group motions (CHS §1.5). An extend towards a target at
//! most `range` away is therefore cut into stairs of at most `stair` length; each stair moves
//! the position group, then the orientation group, to the stair's end, each as far as it is
//! free. A short stair follows the coupled motion closely (alpha-1.5's passage needs turning
//! while moving); a long one costs fewer calls. Every tree edge — and every edge of the
//! returned path — is one certified free single-group motion, or for an arm one certified
//! straight motion of all joints (below).
//!
//! In a joint space without continuous joints (an arm) each extend is first asked as one
//! straight motion of all joints to its end, proved free by conservative advancement
//! ([`TreeParams::straight`], `crate::robot::ArmOracle::straight_free`): a yes/no proof
//! instead of up to a stair per joint per 1 % of the extent; the staircase only where the
//! straight motion is not proved. Such a tree edge is that straight motion.
//!
//! Two trees grow from start and goal; after each extend of one tree towards a uniform sample,
//! the other tree *connects* (extends repeatedly) towards the new node, as in OMPL's
//! `RRTConnect`. How an extend walks its stairs is [`TreeParams::stairs`]: each group's piece as
//! far as it is free, stopping at the first blocked one ([`Stairs::Prefix`]); sliding past a
//! blocked group ([`Stairs::Slide`]); or each stair whole or not at all, only the extend's end
//! indexed for nearest-node queries ([`Stairs::Whole`], the default: OMPL's extend in steps of
//! one stair). With [`TreeParams::centre`] (prefix or sliding stairs) a blocked stair first
//! moves its node to the middle of its free chords across the stair
//! ([`crate::roadmap::centre`]) and is tried again: in a funnel (bugtrap) that lines the robot
//! up with the funnel's axis. The stream of samples comes from one seeded generator, so with a
//! node budget and no deadline the answer is the same on every machine.

use crate::deadline::Deadline;
use crate::local::{check_direct_known, KnownPieces};
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::roadmap::bounce::SECTION_MARGIN;
use crate::roadmap::centre::{centre_round, Across};
use crate::roadmap::nn::NearestNeighbours;
use crate::space::{Config, Group, GroupKind, Space};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;

/// Shortest partial stair kept, as a share of the stair length: shorter free prefixes end the
/// extend without a node (RRT's frontier nodes would otherwise creep towards the obstacle).
pub const MIN_PROGRESS: f64 = 0.1;

/// Half-length of the chords a centring round asks about, as a share of the extent: centring
/// is local (a funnel's mouth), and shorter lines are cheaper calls on big meshes.
pub const CENTRE_REACH: f64 = 0.05;

/// Half-angle of the turns a centring round asks about, in turns (0.05: 18°): a long robot
/// sweeps much of the scene in a full turn, and only narrow arcs are centred anyway.
pub const CENTRE_TURN: f64 = 0.05;

/// Corners ahead that a greedy shortcut pass of a tree path tries from each corner
/// ([`shortcut_passes`]; as `solve --tree`).
pub const SHORTCUT_WINDOW: usize = 32;

/// Longest piece of a straight tree edge ([`TreeParams::straight`]) between the corners the
/// trees' shortening adds along it, as a share of the extent: a shortcut can only start and end
/// at corners, and an extend's one straight edge of up to [`TreeParams::range`] left the paths
/// 20 % longer (first 15 Panda problems of each family, length p50 of the returned paths;
/// with 5 %: per family 6 % shorter to 13 % longer than staircases, 2 % and 1 % no shorter;
/// all 700: +3 %).
pub const STRAIGHT_PIECE: f64 = 0.05;

/// Most streams of [`TreeParams::streams`].
pub const MAX_STREAMS: usize = 64;

/// How an extend finds the free prefix of one single-group stair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prefix {
    /// One interval call: the free section containing the start (CHS §1.2).
    Intervals,
    /// A yes/no call first (it stops at the first collision found, cheaper on big meshes),
    /// the interval call only when the stair is blocked.
    YesNoFirst,
    /// One first-collision call ([`CollisionOracle::first_collision`]): the same free prefix
    /// as `Intervals`, without the collisions beyond it.
    FirstHit,
}

impl std::str::FromStr for Prefix {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "intervals" => Ok(Prefix::Intervals),
            "yesno" => Ok(Prefix::YesNoFirst),
            "first" => Ok(Prefix::FirstHit),
            _ => Err(format!(
                "unknown prefix mode {s:?} (intervals | yesno | first)"
            )),
        }
    }
}

/// How an extend walks its staircase ([`TreeParams::stairs`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stairs {
    /// Each group's piece of a stair as far as it is free ([`TreeParams::prefix`]); the first
    /// blocked group ends the extend. Every corner is a tree node.
    Prefix,
    /// As `Prefix`, but a blocked group does not end the extend: the stair's other groups
    /// still move, later stairs try the blocked group again, and the extend ends only when a
    /// whole stair moves no group (after the last stair, rounds towards the extend's end go
    /// on while some group moves). With one group per joint an extend that stops at its first
    /// blocked joint moves almost nowhere in clutter — about 2 oracle calls per extend on cage
    /// 1 — although the other joints could carry on.
    Slide,
    /// Each stair whole or not at all: its group pieces are asked yes/no in turn, the first
    /// blocked one ends the extend, and the complete stairs before it are kept — Kuffner and
    /// LaValle's EXTEND in steps of one stair (OMPL's `RRTConnect` keeps a step only if all of
    /// its straight motion is valid). Only the extend's end becomes a candidate nearest node;
    /// the corners on the way stay on the path. The trees do not pile corners against
    /// obstacles and their nearest-node queries see one node per extend, as OMPL's do: over the
    /// first 15 Panda problems of each family, 104 / 105 solved at p50 90 ms where sliding
    /// solves 97 at 183 ms; alpha-1.5 seeds 1–4 all solved in 2.9–6.4 s where prefixes solve 3
    /// in 6.3–8.6 s, Twistycool seeds 1–2 in 6.3–6.8 s where prefixes solve none in 30 s
    /// (with the smaller tree extending). The default.
    Whole,
}

impl std::str::FromStr for Stairs {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "prefix" => Ok(Stairs::Prefix),
            "slide" => Ok(Stairs::Slide),
            "whole" => Ok(Stairs::Whole),
            _ => Err(format!(
                "unknown stairs mode {s:?} (prefix | slide | whole)"
            )),
        }
    }
}

/// Parameters of [`rrt_connect`].
#[derive(Clone, Debug, PartialEq)]
pub struct TreeParams {
    /// Longest extend, as a share of the space's extent (OMPL's `RRTConnect` default: 0.2 of
    /// its maximum extent).
    pub range: f64,
    /// Longest stair of an extend, as a share of the extent: the staircase's approximation of
    /// a coupled motion.
    pub stair: f64,
    /// How a stair's free prefix is found ([`Stairs::Prefix`] and [`Stairs::Slide`]; a whole
    /// stair asks yes/no).
    pub prefix: Prefix,
    /// Try each extend as one stair first (a yes/no call per group), the staircase only when
    /// that is blocked ([`Stairs::Prefix`] and [`Stairs::Slide`]).
    pub coarse: bool,
    /// Extend the smaller tree each time (Kuffner–LaValle's balanced variant; the default)
    /// instead of alternating: an entangled end whose extends are mostly trapped gets the
    /// effort. With [`Stairs::Whole`] a trapped extend costs a call or two and adds nothing, so
    /// the tree of an end in a pocket (a goal in a shelf) gets almost every extend until it is
    /// out, while alternating lets the other tree's connects grow it by 10⁵ corners: over the
    /// 700 Panda problems, whole stairs solve 698 balanced against 689 alternating (trees
    /// alone).
    pub balance: bool,
    /// Centring rounds per blocked stair (0: off, the default): a blocked stair moves the
    /// node to the middle of its free chords across the stair (`roadmap::centre`, a
    /// first-collision call each way per direction) and tries again, at most this many times —
    /// a funnel lines the robot up with its axis on the way in ([`Stairs::Prefix`] and
    /// [`Stairs::Slide`]).
    pub centre: usize,
    /// Half-angle of the turns a centring round asks about, in turns (default
    /// [`CENTRE_TURN`]; at most 0.45).
    pub centre_turn: f64,
    /// Most nodes of both trees together (a budget that gives the same answer on any machine;
    /// every corner counts, indexed for nearest-node queries or not); with restarts, of all
    /// attempts together.
    pub max_nodes: Option<usize>,
    /// How an extend walks its staircase (default [`Stairs::Whole`]; centring needs
    /// [`Stairs::Prefix`] or [`Stairs::Slide`]).
    pub stairs: Stairs,
    /// Restarts (`None`: one attempt, the default): the first attempt gets this many nodes,
    /// and each attempt that runs out starts afresh from the two ends with a new random stream
    /// and twice the nodes of the one before. RRT run times are heavy-tailed — the same problem
    /// is solved in 5 s from one seed and not in minutes from another, as on alpha-1.5 and
    /// bugtrap — and geometric restarts bound the expected time by a small multiple of the
    /// best fixed cut-off without knowing it (Luby, Sinclair, Zuckerman 1993; for RRTs, Wedge
    /// and Branicky 2008).
    pub restart: Option<usize>,
    /// Independent streams (1, the default: one). With more, as many pairs of trees grow at
    /// once on the rayon pool from the same ends with different random streams, and the first
    /// to connect answers (the others stop). The solved set of hard problems follows the random
    /// stream more than any extend policy (two runs of the 700 Panda problems with different
    /// policies solve 676 and 679, 691 together), and threads buy streams, not a faster one.
    /// Without a time limit every stream runs to its node budget and the first in stream order
    /// that connected answers, so the answer is the same on any machine and thread count; with
    /// one thread the streams run one after another, each until the deadline.
    pub streams: usize,
    /// Try each extend first as one straight motion of all joints to its end (where the space
    /// has one, [`Space::straight_group`]: an arm without continuous joints), proved free by
    /// conservative advancement (one yes/no call); the staircase only where it is not proved.
    /// The tree edge is then that straight motion. A stair is 1 % of the extent and a joint
    /// per piece, so a free extend of 20 % costs up to 140 calls as a staircase: over the
    /// first 15 Panda problems of each family, the portfolio's p50 20.5 → 9–10 ms.
    /// On by default; `--no-straight` turns it off with the straight shortcuts.
    pub straight: bool,
    /// With [`Self::straight`]: where an extend's straight motion is not proved, walk it as a
    /// staircase ([`Self::stairs`]; on by default). Off, that extend is trapped and the next
    /// sample is drawn, as VAMP's RRT-Connect keeps a motion whole or not at all: every call is
    /// one straight proof, and a blocked extend costs a single call instead of its stairs'
    /// single-joint sweeps. The arm portfolio's trees run so ([`crate::portfolio::Portfolio`]).
    pub staircase: bool,
    /// Dynamic-domain sampling ([`Domain`]; `None`, the default: every sample extends). On for
    /// arms ([`Self::for_space`]), as in VAMP's RRT-Connect.
    pub domain: Option<Domain>,
}

/// Dynamic-domain sampling (Yershova, Jaillet, Siméon, LaValle 2005; adaptive radii as in
/// Jaillet, Yershova, LaValle, Siméon 2005, and VAMP's RRT-Connect): a node whose extend
/// failed gets a radius, and a sample farther from its nearest node than that node's radius is
/// drawn again without a call. A node against an obstacle stops sending extends towards the far
/// side of the space, and a tree trapped in a pocket (a goal in a shelf) spends its calls on
/// samples about it. Radii are in extends ([`TreeParams::range`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Domain {
    /// A node's radius after its first failed extend.
    pub radius: f64,
    /// The least radius: each later failure shrinks it by `alpha`, each success grows it.
    pub least: f64,
    /// The share a radius shrinks by on a failure and grows by on a success.
    pub alpha: f64,
}

impl Domain {
    /// VAMP's radii for the Panda, whose extend is 1 rad (ours: 1.04): 4 rad at first, at
    /// least 1, α = 10⁻⁴. Over the 700 Panda problems (one thread, 5 s each) the arm portfolio's
    /// calls fell from 325 to 186 per problem and its mean time by a sixth, the cage's median
    /// by a seventh.
    pub const ARM: Domain = Domain {
        radius: 4.0,
        least: 1.0,
        alpha: 1e-4,
    };

    /// [`Self::ARM`] with a first radius of `radius` extends (its least radius no larger);
    /// `None` for 0: no domains.
    pub fn with_radius(radius: f64) -> Option<Domain> {
        (radius != 0.0).then(|| Domain {
            radius,
            least: Domain::ARM.least.min(radius),
            ..Domain::ARM
        })
    }

    /// Checks the radii are positive and finite, the least at most the first, and `alpha` in
    /// [0, 1).
    pub fn validate(&self) -> Result<(), String> {
        let Domain {
            radius,
            least,
            alpha,
        } = *self;
        if !(least.is_finite() && least > 0.0 && radius.is_finite() && radius >= least) {
            return Err(format!(
                "tree domain radii must be finite with 0 < least ≤ radius, got {least} and {radius}"
            ));
        }
        if !(0.0..1.0).contains(&alpha) {
            return Err(format!("tree domain alpha must be in [0, 1), got {alpha}"));
        }
        Ok(())
    }
}

impl Default for TreeParams {
    fn default() -> Self {
        TreeParams {
            range: 0.2,
            stair: 0.01,
            prefix: Prefix::Intervals,
            coarse: false,
            balance: true,
            centre: 0,
            centre_turn: CENTRE_TURN,
            max_nodes: None,
            restart: None,
            stairs: Stairs::Whole,
            streams: 1,
            straight: true,
            staircase: true,
            domain: None,
        }
    }
}

impl TreeParams {
    /// The defaults for `space`: one first-collision call per stair for arms (the sweep of a
    /// joint stops at the first hit, `joint_move_first_hit`), one interval call otherwise; an
    /// arm's extends are proved straight motions or given up ([`Self::staircase`] off), as
    /// the arm portfolio's trees, so that queries on a roadmap grow the same trees.
    pub fn for_space(space: &Space) -> TreeParams {
        let joints = space.is_joints();
        TreeParams {
            prefix: if joints {
                Prefix::FirstHit
            } else {
                Prefix::Intervals
            },
            staircase: !joints,
            domain: joints.then_some(Domain::ARM),
            ..TreeParams::default()
        }
    }

    /// Checks the shares are positive and finite.
    pub fn validate(&self) -> Result<(), String> {
        for (name, v) in [("range", self.range), ("stair", self.stair)] {
            if !(v.is_finite() && v > 0.0 && v <= 10.0) {
                return Err(format!("tree {name} must be a share in (0, 10], got {v}"));
            }
        }
        if self.streams == 0 || self.streams > MAX_STREAMS {
            return Err(format!(
                "tree streams must be 1 to {MAX_STREAMS}, got {}",
                self.streams
            ));
        }
        if self.restart == Some(0) {
            return Err("tree restarts need a first attempt of at least one node".into());
        }
        if self.stairs == Stairs::Whole && self.centre > 0 {
            return Err("tree centring needs prefix or slide stairs, not whole ones".into());
        }
        if let Some(d) = &self.domain {
            d.validate()?;
        }
        if self.stairs == Stairs::Whole && self.coarse {
            return Err("a coarse first try needs prefix or slide stairs, not whole ones".into());
        }
        let t = self.centre_turn;
        if !(t.is_finite() && t > 0.0 && t <= crate::roadmap::bounce::MAX_TURN) {
            return Err(format!(
                "tree centre turn must be in (0, 0.45] turns, got {t}"
            ));
        }
        Ok(())
    }
}

/// Why [`rrt_connect`] gave no outcome: parameters it cannot run with, or the oracle's error.
#[derive(Debug, thiserror::Error)]
pub enum TreeError {
    /// The parameters fail [`TreeParams::validate`] (a range that is not a positive share, no
    /// streams, …), checked before any tree grows.
    #[error("invalid tree parameters: {0}")]
    Params(String),
    /// The oracle refused a motion.
    #[error(transparent)]
    Oracle(#[from] OracleError),
}

/// Why [`rrt_connect`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TreeStop {
    /// The trees met: a path exists.
    Connected,
    /// The deadline passed (or Ctrl-C).
    TimedOut,
    /// The node budget is spent.
    NodeBudget,
}

/// What [`rrt_connect`] found.
#[derive(Clone, Debug)]
pub struct TreeOutcome {
    /// Start to goal, consecutive corners joined by free single-group motions, if the trees met.
    pub path: Option<Vec<Config>>,
    /// Nodes of the start tree and the goal tree.
    pub nodes: [usize; 2],
    /// Extends tried (connect steps included).
    pub extends: u64,
    /// Oracle calls made.
    pub counts: CallCounts,
    /// Why it stopped.
    pub stop: TreeStop,
    /// Attempts made (1 without restarts); `nodes` are those of the last one, `extends` and
    /// `counts` those of all (with [`TreeParams::streams`]: `path`, `nodes`, `stop`, `trees`
    /// and `attempts` of the answering stream, else of stream 0; `extends` and `counts` of all).
    pub attempts: u32,
    /// The start tree and the goal tree as they ended (of the last attempt), every branch a
    /// chain of certified free single-group motions: what a roadmap may keep
    /// ([`crate::roadmap::Roadmap::with_kept`]). `None` where no tree grew.
    pub trees: Option<Box<[Rooted; 2]>>,
}

/// Where one tree of [`rrt_connect_rooted`] begins: its end alone ([`Rooted::at`]), or its end
/// with certified free corners around it already (a roadmap's component,
/// [`super::rooted::RoadmapTrees`]), each joined to its parent by free single-group motions in
/// the groups' order. The end is node 0.
#[derive(Clone, Debug)]
pub struct Rooted {
    /// Every node's coordinates, node after node (one allocation to copy: a tree out of a
    /// roadmap's component starts every query from the kept tree's hundreds of nodes).
    coords: Vec<f64>,
    /// Coordinates per node.
    dim: usize,
    parent: Vec<u32>,
    /// Whether each node is a corner on the way to a grown node rather than an extend's end
    /// ([`Stairs::Whole`] indexes only the ends).
    corner: Vec<bool>,
    /// Nodes the tree began with, the end included ([`Self::given`]).
    given: usize,
    /// The nodes' nearest-neighbour index, where it was built once for the queries that begin
    /// from this tree ([`Self::indexed`]): a tree out of a roadmap's component copies it
    /// instead of indexing the component's hundreds of nodes again.
    index: Option<Arc<NearestNeighbours>>,
}

/// The same tree: the same nodes, joined the same way (an index is only how they are found).
impl PartialEq for Rooted {
    fn eq(&self, other: &Self) -> bool {
        (
            self.dim,
            &self.coords,
            &self.parent,
            &self.corner,
            self.given,
        ) == (
            other.dim,
            &other.coords,
            &other.parent,
            &other.corner,
            other.given,
        )
    }
}

impl Rooted {
    /// A tree of the end `end` alone.
    pub fn at(end: &[f64]) -> Rooted {
        Rooted {
            coords: end.to_vec(),
            dim: end.len(),
            parent: vec![u32::MAX],
            corner: vec![false],
            given: 1,
            index: None,
        }
    }

    /// The tree with its nodes indexed for nearest-neighbour queries in `space`, for trees
    /// grown from it again and again (the same start of a workcell's queries).
    pub fn indexed(mut self, space: &Space) -> Rooted {
        self.index = Some(Arc::new(index_of(space, &self)));
        self
    }

    /// Nodes the tree began with, the end included: nodes `0..given` were given (a roadmap's
    /// component, [`super::rooted::RoadmapTrees`]), the rest grown by the extends.
    pub fn given(&self) -> usize {
        self.given
    }

    /// Whether node `i` is a corner on the way to a grown node (never a nearest node of an
    /// extend) rather than an extend's end or a given node.
    ///
    /// # Panics
    /// If `i` is not a node index.
    pub fn is_corner(&self, i: u32) -> bool {
        self.corner[i as usize]
    }

    /// The node that node `i` was grown from (`None` for the end).
    ///
    /// # Panics
    /// If `i` is not a node index.
    pub fn parent(&self, i: u32) -> Option<u32> {
        let p = self.parent[i as usize];
        (p != u32::MAX).then_some(p)
    }

    /// The end (node 0).
    pub fn end(&self) -> &[f64] {
        self.node(0)
    }

    /// Nodes, the end included.
    pub fn node_count(&self) -> usize {
        self.parent.len()
    }

    /// Whether the tree is its end alone (no nodes given).
    pub fn is_bare(&self) -> bool {
        self.node_count() <= 1
    }

    /// Configuration of node `i`.
    ///
    /// # Panics
    /// If `i` is not a node index.
    pub fn node(&self, i: u32) -> &[f64] {
        let at = i as usize * self.dim;
        &self.coords[at..at + self.dim]
    }

    /// Adds `q`, joined to node `parent` by free single-group motions (the caller's
    /// certificate), and returns its index.
    pub(crate) fn add(&mut self, q: Config, parent: u32) -> u32 {
        self.push(q, parent, false)
    }

    fn push(&mut self, q: Config, parent: u32, corner: bool) -> u32 {
        debug_assert!((parent as usize) < self.node_count());
        debug_assert_eq!(q.len(), self.dim);
        self.coords.extend_from_slice(&q);
        self.parent.push(parent);
        self.corner.push(corner);
        self.node_count() as u32 - 1
    }

    /// The corners from the end to node `id`: the end first, `id` last.
    pub fn branch(&self, id: u32) -> Vec<Config> {
        let mut out = Vec::new();
        let mut i = id;
        while i != u32::MAX {
            out.push(self.node(i).to_vec());
            i = self.parent[i as usize];
        }
        out.reverse();
        out
    }
}

/// A nearest-neighbour index of the tree's nodes, each by its position.
fn index_of(space: &Space, tree: &Rooted) -> NearestNeighbours {
    let mut nn = NearestNeighbours::new(space);
    for id in 0..tree.node_count() as u32 {
        nn.insert(id, tree.node(id));
    }
    nn
}

/// A growing tree: its nodes (a [`Rooted`]) with a nearest-neighbour index.
struct Tree {
    base: Rooted,
    nn: NearestNeighbours,
    /// Dynamic-domain radii by node ([`Domain`]; a node beyond the end has none yet).
    radius: Vec<f64>,
}

impl Tree {
    fn new(space: &Space, root: &Rooted) -> Tree {
        let nn = match &root.index {
            Some(index) if index.len() == root.node_count() => NearestNeighbours::clone(index),
            _ => index_of(space, root),
        };
        let mut base = root.clone();
        base.index = None;
        base.given = root.node_count();
        Tree {
            base,
            nn,
            radius: Vec::new(),
        }
    }

    /// Node `i`'s dynamic-domain radius (infinite until an extend from it failed).
    fn radius(&self, i: u32) -> f64 {
        self.radius
            .get(i as usize)
            .copied()
            .unwrap_or(f64::INFINITY)
    }

    /// After an extend from node `i`: a failure gives it `domain`'s radius or shrinks the one it
    /// has, a success grows a radius it has.
    fn adapt_radius(&mut self, i: u32, domain: &Domain, range: f64, extended: bool) {
        let r = self.radius(i);
        let next = match (extended, r.is_finite()) {
            (false, false) => domain.radius * range,
            (false, true) => (r * (1.0 - domain.alpha)).max(domain.least * range),
            (true, true) => r * (1.0 + domain.alpha),
            (true, false) => return,
        };
        if self.radius.len() <= i as usize {
            self.radius.resize(i as usize + 1, f64::INFINITY);
        }
        self.radius[i as usize] = next;
    }

    /// Nodes grown (the end counts as one, given nodes do not).
    fn grown(&self) -> usize {
        self.base.node_count() + 1 - self.base.given
    }

    fn node(&self, id: u32) -> &[f64] {
        self.base.node(id)
    }

    fn add(&mut self, q: Config, parent: u32) -> u32 {
        let id = self.base.node_count() as u32;
        self.nn.insert(id, &q);
        self.base.add(q, parent)
    }

    /// Adds a corner on the way to a node: on the path, never the nearest node.
    fn add_corner(&mut self, q: Config, parent: u32) -> u32 {
        self.base.push(q, parent, true)
    }

    fn nearest(&self, q: &[f64]) -> u32 {
        self.nn
            .nearest_one(q, |id| self.node(id))
            .map_or(0, |(id, _)| id)
    }
}

enum Extend {
    Trapped,
    Advanced(u32),
    Reached(u32),
}

/// Where a stair can go.
enum Reach {
    Blocked,
    Partial(f64),
    Full,
}

/// An extend's plan ([`Grower::step`]).
struct Step {
    /// The tree's node nearest to the target, where the extend starts.
    near: u32,
    from: Config,
    /// The target, or the point `range` towards it.
    aim: Config,
    /// Whether `aim` is the target itself.
    full: bool,
    /// Stairs from `from` to `aim` (0: the target is `near`).
    stairs: usize,
}

impl Step {
    /// Where stair `i` (from 1) ends: `i / stairs` of the way to `aim`, `aim` itself from the
    /// last stair on (sliding rounds beyond it aim there too).
    fn stair_end(&self, space: &Space, i: usize) -> Config {
        if i >= self.stairs {
            self.aim.clone()
        } else {
            space.interpolate(&self.from, &self.aim, i as f64 / self.stairs as f64)
        }
    }
}

struct Grower<'a> {
    space: &'a Space,
    oracle: &'a dyn CollisionOracle,
    groups: &'a [Group],
    params: &'a TreeParams,
    deadline: &'a Deadline,
    counts: CallCounts,
    extends: u64,
    /// Centring rounds spent in the current extend (at most `params.centre` per extend).
    centred: usize,
}

impl Grower<'_> {
    fn reach(&mut self, motion: &crate::space::Motion) -> Result<Reach, OracleError> {
        if self.params.prefix == Prefix::FirstHit {
            // the free section containing the start is [range.lo, first collision]
            let lo = motion.range.lo;
            return Ok(match self.oracle.first_hit(motion, &mut self.counts)? {
                None => Reach::Full,
                Some(hit) if hit <= lo => Reach::Blocked,
                Some(hit) => {
                    let t = hit - SECTION_MARGIN * (hit - lo);
                    if t > 0.0 {
                        Reach::Partial(t)
                    } else {
                        Reach::Blocked
                    }
                }
            });
        }
        if self.params.prefix == Prefix::YesNoFirst
            && self.oracle.check_motion(motion, &mut self.counts)?
        {
            return Ok(Reach::Full);
        }
        let hits = self.oracle.intersect(motion, &mut self.counts)?;
        let Some(section) = hits
            .complement_within(motion.range)
            .iter()
            .find(|s| s.contains(0.0))
            .copied()
        else {
            return Ok(Reach::Blocked);
        };
        if section.hi >= motion.range.hi {
            return Ok(Reach::Full);
        }
        let t = section.hi - SECTION_MARGIN * section.length();
        Ok(if t > 0.0 {
            Reach::Partial(t)
        } else {
            Reach::Blocked
        })
    }

    /// Where an extend of `tree` towards `target` goes: from the nearest node towards
    /// `target`, at most `range` far, in `stairs` stairs (0: `target` is that node).
    fn step(&self, tree: &Tree, target: &[f64]) -> Step {
        let near = tree.nearest(target);
        let d = self.space.distance(tree.node(near), target);
        self.step_from(tree, near, d, target)
    }

    /// [`Self::step`] from node `near`, `d` away from `target`.
    fn step_from(&self, tree: &Tree, near: u32, d: f64, target: &[f64]) -> Step {
        let from = tree.node(near).to_vec();
        let range = self.params.range * self.space.extent();
        let full = d <= range;
        let aim = if full {
            target.to_vec()
        } else {
            self.space.interpolate(&from, target, range / d)
        };
        let stair = self.params.stair * self.space.extent();
        let stairs = if d == 0.0 {
            0
        } else {
            (d.min(range) / stair).ceil().clamp(1.0, 1e6) as usize
        };
        Step {
            near,
            from,
            aim,
            full,
            stairs,
        }
    }

    /// Extends `tree` from its node nearest to `target` towards it, at most `range` far.
    fn extend(&mut self, tree: &mut Tree, target: &[f64]) -> Result<Extend, OracleError> {
        let step = self.step(tree, target);
        self.extend_step(tree, step)
    }

    /// [`Self::extend`] along a planned `step`.
    fn extend_step(&mut self, tree: &mut Tree, step: Step) -> Result<Extend, OracleError> {
        self.extends += 1;
        if step.stairs == 0 {
            return Ok(Extend::Reached(step.near));
        }
        if let Some(end) = self.straight(tree, &step)? {
            return Ok(end);
        }
        if self.params.straight && !self.params.staircase {
            return Ok(Extend::Trapped);
        }
        if self.params.stairs == Stairs::Whole {
            return self.extend_whole(tree, &step);
        }
        self.centred = 0;
        let Step {
            near,
            ref from,
            ref aim,
            full,
            stairs,
        } = step;
        if self.params.coarse && stairs > 1 {
            if let Some(end) = self.extend_coarse(tree, near, from, aim, full)? {
                return Ok(end);
            }
        }
        let mut current = from.clone();
        let mut parent = near;
        let mut moved = false;
        // sliding: after the last stair, at most as many rounds again towards `aim`
        let slide = self.params.stairs == Stairs::Slide;
        let rounds = if slide { 2 * stairs } else { stairs };
        for i in 1..=rounds {
            let w = step.stair_end(self.space, i);
            if i > stairs && current == *aim {
                break;
            }
            let mut stair_moved = false;
            'groups: for (gi, g) in self.groups.iter().enumerate() {
                let mut centred = 0;
                loop {
                    if self.deadline.expired() {
                        return Ok(if moved {
                            Extend::Advanced(parent)
                        } else {
                            Extend::Trapped
                        });
                    }
                    if self.space.same_in_group(&current, &w, g) {
                        break;
                    }
                    let goal = self.space.with_group_of(&current, &w, g);
                    let motion = self.space.group_motion(&current, &goal, g);
                    let (next, blocked) = match self.reach(&motion)? {
                        Reach::Full => (goal, false),
                        Reach::Partial(t) => {
                            let mut q = motion.at(t);
                            if g.kind != GroupKind::Linear {
                                self.space.normalize(&mut q);
                            }
                            (q, true)
                        }
                        Reach::Blocked => (current.clone(), true),
                    };
                    // a partial stair that barely moves only piles nodes against the obstacle
                    let stair = self.params.stair * self.space.extent();
                    let worth =
                        !blocked || self.space.distance(&current, &next) >= MIN_PROGRESS * stair;
                    if worth && next != current {
                        parent = tree.add(next.clone(), parent);
                        current = next;
                        moved = true;
                        stair_moved = true;
                    }
                    if !blocked {
                        break;
                    }
                    if centred < self.params.centre && self.centred < self.params.centre {
                        // centre across the blocked stair, then try it again (module `centre`)
                        centred += 1;
                        self.centred += 1;
                        let across = across_of(&motion, gi, g);
                        if self.centre_across(tree, &across, &mut current, &mut parent)? {
                            moved = true;
                            stair_moved = true;
                            continue;
                        }
                    }
                    if slide {
                        // the other groups of the stair may still move
                        continue 'groups;
                    }
                    return Ok(if moved {
                        Extend::Advanced(parent)
                    } else {
                        Extend::Trapped
                    });
                }
            }
            if slide && !stair_moved {
                break;
            }
        }
        // without sliding every group reached `aim` here; sliding may have stopped short
        let arrived = !slide || current == *aim;
        Ok(if !moved {
            Extend::Trapped
        } else if full && arrived {
            Extend::Reached(parent)
        } else {
            Extend::Advanced(parent)
        })
    }

    /// One stair all the way, yes/no: in open space the staircase buys nothing. The end of the
    /// extend when the direct motion from `from` to `aim` is free, its corners added after
    /// `near`.
    fn extend_coarse(
        &mut self,
        tree: &mut Tree,
        near: u32,
        from: &Config,
        aim: &Config,
        full: bool,
    ) -> Result<Option<Extend>, OracleError> {
        let Some(corners) = crate::local::check_direct(
            self.space,
            self.oracle,
            self.groups,
            from,
            aim,
            &mut self.counts,
        )?
        else {
            return Ok(None);
        };
        let mut parent = near;
        for c in corners {
            parent = tree.add(c, parent);
        }
        Ok(Some(if full {
            Extend::Reached(parent)
        } else {
            Extend::Advanced(parent)
        }))
    }

    /// Centres `current` across a blocked stair (module `centre`), adding the corners after
    /// `parent` (both moved along); whether it moved, so that the stair is tried again.
    fn centre_across(
        &mut self,
        tree: &mut Tree,
        across: &Across,
        current: &mut Config,
        parent: &mut u32,
    ) -> Result<bool, OracleError> {
        let reach = CENTRE_REACH * self.space.extent();
        let corners = centre_round(
            self.space,
            self.oracle,
            self.groups,
            current,
            across,
            reach,
            self.params.centre_turn,
            &mut self.counts,
            self.deadline,
        )?;
        if corners.is_empty() {
            return Ok(false);
        }
        for c in corners {
            *parent = tree.add(c.clone(), *parent);
            *current = c;
        }
        Ok(true)
    }
}

impl Grower<'_> {
    /// [`TreeParams::straight`]: `step` as one straight motion of all joints
    /// ([`crate::local::straight_connection`]: asked where it moves more than one joint), its
    /// end a node if the motion is proved free; `None` where it is not asked or not proved.
    fn straight(&mut self, tree: &mut Tree, step: &Step) -> Result<Option<Extend>, OracleError> {
        if !self.params.straight
            || self.deadline.expired()
            || crate::local::straight_connection(
                self.space,
                self.oracle,
                self.groups,
                &step.from,
                &step.aim,
                &mut self.counts,
            )?
            .is_none()
        {
            return Ok(None);
        }
        let end = tree.add(step.aim.clone(), step.near);
        Ok(Some(if step.full {
            Extend::Reached(end)
        } else {
            Extend::Advanced(end)
        }))
    }

    /// [`Stairs::Whole`]: `step` stair by stair, each stair whole (a yes/no call per group
    /// piece) or not at all; the first blocked stair ends the extend with the complete stairs
    /// before it. Only the extend's end is indexed for nearest-node queries. With
    /// [`TreeParams::straight`] each stair is first asked as one straight motion of all joints
    /// (one call where the staircase asks one per joint), its pieces only where that is not
    /// proved: an extend whose whole straight motion was not proved is mostly free stairs
    /// before the one that meets the obstacle.
    fn extend_whole(&mut self, tree: &mut Tree, step: &Step) -> Result<Extend, OracleError> {
        let mut corners: Vec<Config> = Vec::new();
        // corners of the complete stairs
        let mut whole = 0;
        let mut current = step.from.clone();
        'stairs: for i in 1..=step.stairs {
            let w = step.stair_end(self.space, i);
            if self.params.straight
                && step.stairs > 1
                && !self.deadline.expired()
                && crate::local::straight_connection(
                    self.space,
                    self.oracle,
                    self.groups,
                    &current,
                    &w,
                    &mut self.counts,
                )?
                .is_some()
            {
                corners.push(w.clone());
                current = w;
                whole = corners.len();
                continue;
            }
            for g in self.groups {
                if self.deadline.expired() {
                    break 'stairs;
                }
                if self.space.same_in_group(&current, &w, g) {
                    continue;
                }
                let next = self.space.with_group_of(&current, &w, g);
                let motion = self.space.group_motion(&current, &next, g);
                if !self.oracle.check_motion(&motion, &mut self.counts)? {
                    break 'stairs;
                }
                corners.push(next.clone());
                current = next;
            }
            whole = corners.len();
        }
        let reached = step.full && whole == corners.len() && current == step.aim;
        corners.truncate(whole);
        let Some(last) = corners.pop() else {
            return Ok(Extend::Trapped);
        };
        let mut parent = step.near;
        for c in corners {
            parent = tree.add_corner(c, parent);
        }
        let end = tree.add(last, parent);
        Ok(if reached {
            Extend::Reached(end)
        } else {
            Extend::Advanced(end)
        })
    }
}

/// What a blocked stair `motion` in group `g` (index `gi`) was doing, for [`centre_round`].
fn across_of(motion: &crate::space::Motion, gi: usize, g: &Group) -> Across {
    use crate::space::Change;
    match (&motion.change, g.kind) {
        (Change::Rotation { axis, .. } | Change::BodyRotation { axis, .. }, _) => Across::Turn {
            group: gi,
            axis: Some(*axis),
        },
        (Change::Linear(delta), GroupKind::Linear) => {
            let d: Vec<f64> = g.indices().map(|i| delta[i]).collect();
            let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            Across::Translation {
                group: gi,
                dir: if norm > 0.0 {
                    d.iter().map(|x| x / norm).collect()
                } else {
                    d
                },
            }
        }
        (Change::Linear(_), _) => Across::Turn {
            group: gi,
            axis: None,
        },
    }
}

/// RRT-Connect between the free configurations `start` and `goal` with exact single-group
/// extends (see the module docs), until the trees meet, `params.max_nodes` is spent or
/// `deadline` passes. `groups` are the DOF groups each stair moves in turn. With
/// `params.restart` the attempts are seeded `seed`, then streams derived from it, so the first
/// attempt is the run without restarts cut at its node budget. With `params.streams` above 1,
/// that many such runs race on the rayon pool ([`TreeParams::streams`]). Parameters that fail
/// [`TreeParams::validate`] are refused before anything grows ([`TreeError::Params`]).
#[allow(clippy::too_many_arguments)]
pub fn rrt_connect(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    start: &[f64],
    goal: &[f64],
    params: &TreeParams,
    seed: u64,
    deadline: &Deadline,
) -> Result<TreeOutcome, TreeError> {
    let roots = [&Rooted::at(start), &Rooted::at(goal)];
    rrt_connect_rooted(space, oracle, groups, roots, params, seed, deadline)
}

/// [`rrt_connect`] from two [`Rooted`] trees: the start tree and the goal tree begin with their
/// given nodes (a restart begins with them again), and only grown nodes count towards
/// `params.max_nodes` and [`TreeOutcome::nodes`]. Where only one tree was given nodes, the
/// other does all the extending towards samples and the given one only connects. The path
/// runs from the start tree's end to the goal tree's.
pub fn rrt_connect_rooted(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    roots: [&Rooted; 2],
    params: &TreeParams,
    seed: u64,
    deadline: &Deadline,
) -> Result<TreeOutcome, TreeError> {
    params.validate().map_err(TreeError::Params)?;
    if params.streams <= 1 {
        return Ok(one_stream(
            space, oracle, groups, roots, params, seed, deadline,
        )?);
    }
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    // with a time limit the first stream to connect stops the others; without one each runs
    // to its node budget, so that the answer does not depend on which finished first
    let won = std::sync::Arc::new(AtomicBool::new(false));
    let racing = deadline.remaining().is_some();
    let outcomes: Vec<Result<TreeOutcome, OracleError>> = (0..params.streams)
        .into_par_iter()
        .map(|k| {
            let d = if racing {
                deadline.or_cancelled_by(won.clone())
            } else {
                deadline.clone()
            };
            let out = one_stream(
                space,
                oracle,
                groups,
                roots,
                params,
                stream_seed(seed, k),
                &d,
            );
            if matches!(&out, Ok(o) if o.path.is_some()) {
                won.store(true, Ordering::Relaxed);
            }
            out
        })
        .collect();
    let outcomes = outcomes.into_iter().collect::<Result<Vec<_>, _>>()?;
    let (mut counts, mut extends) = (CallCounts::default(), 0);
    for o in &outcomes {
        counts += o.counts;
        extends += o.extends;
    }
    let pick = outcomes.iter().position(|o| o.path.is_some()).unwrap_or(0);
    let mut out = outcomes.into_iter().nth(pick).expect("at least one stream");
    // a stream stopped by another's win reports what stopped the race
    if out.path.is_none() && deadline.expired() {
        out.stop = TreeStop::TimedOut;
    }
    out.counts = counts;
    out.extends = extends;
    Ok(out)
}

/// The random stream of portfolio stream `k` (stream 0: `seed` itself, so one stream is the
/// run without streams).
pub fn stream_seed(seed: u64, k: usize) -> u64 {
    if k == 0 {
        return seed;
    }
    // splitmix64 of (seed, k): far from the restarts' streams `seed ^ k · φ`
    let mut z = seed.wrapping_add((k as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// [`rrt_connect_rooted`] for one stream: with `params.restart`, its attempts one after another.
fn one_stream(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    roots: [&Rooted; 2],
    params: &TreeParams,
    seed: u64,
    deadline: &Deadline,
) -> Result<TreeOutcome, OracleError> {
    let Some(first) = params.restart else {
        return grow_once(
            space,
            oracle,
            groups,
            roots,
            params,
            seed,
            params.max_nodes,
            deadline,
        );
    };
    let (mut counts, mut extends, mut spent) = (CallCounts::default(), 0, 0usize);
    let mut k = 0u32;
    loop {
        let budget = first.saturating_mul(1usize << k.min(40));
        let cap = match params.max_nodes {
            Some(m) => budget.min(m.saturating_sub(spent)),
            None => budget,
        };
        // attempt k's stream: `seed` itself first, then well-mixed others
        let seed_k = seed ^ u64::from(k).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let mut out = grow_once(
            space,
            oracle,
            groups,
            roots,
            params,
            seed_k,
            Some(cap),
            deadline,
        )?;
        counts += out.counts;
        extends += out.extends;
        spent += out.nodes[0] + out.nodes[1];
        let exhausted = params.max_nodes.is_some_and(|m| spent >= m);
        if out.stop != TreeStop::NodeBudget || exhausted {
            out.counts = counts;
            out.extends = extends;
            out.attempts = k + 1;
            return Ok(out);
        }
        k = k.saturating_add(1);
    }
}

/// One attempt of [`rrt_connect_rooted`]: `max_nodes` instead of the parameters' budget.
#[allow(clippy::too_many_arguments)]
fn grow_once(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    roots: [&Rooted; 2],
    params: &TreeParams,
    seed: u64,
    max_nodes: Option<usize>,
    deadline: &Deadline,
) -> Result<TreeOutcome, OracleError> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut trees = [Tree::new(space, roots[0]), Tree::new(space, roots[1])];
    // a tree given a roadmap's component covers the space already, and extending it towards
    // samples sweeps long free turns there: where one tree was given nodes and the other was
    // not, the bare one does all the extending and the given one only connects
    let only = match (roots[0].is_bare(), roots[1].is_bare()) {
        (false, true) => Some(1),
        (true, false) => Some(0),
        _ => None,
    };
    let mut g = Grower {
        space,
        oracle,
        groups,
        params,
        deadline,
        counts: CallCounts::default(),
        extends: 0,
        centred: 0,
    };
    let finish = |trees: [Tree; 2], g: &Grower, path, stop| TreeOutcome {
        path,
        nodes: [trees[0].grown(), trees[1].grown()],
        extends: g.extends,
        counts: g.counts,
        stop,
        attempts: 1,
        trees: Some(Box::new(trees.map(|t| t.base))),
    };
    // the ends themselves first: often the straight staircase is free
    let mut a = only.unwrap_or(0);
    let mut target = Some(roots[1 - a].end().to_vec());
    loop {
        if deadline.expired() {
            return Ok(finish(trees, &g, None, TreeStop::TimedOut));
        }
        if max_nodes.is_some_and(|m| trees[0].grown() + trees[1].grown() >= m) {
            return Ok(finish(trees, &g, None, TreeStop::NodeBudget));
        }
        // the ends are aimed at whatever the domains say; samples only within them
        let domain = params.domain.filter(|_| target.is_none());
        let q_rand = target
            .take()
            .unwrap_or_else(|| space.sample_uniform(&mut rng));
        let (first, second) = trees.split_at_mut(1);
        let (ta, tb) = if a == 0 {
            (&mut first[0], &mut second[0])
        } else {
            (&mut second[0], &mut first[0])
        };
        let near = ta.nearest(&q_rand);
        let d = space.distance(ta.node(near), &q_rand);
        let new = if domain.is_some() && d > ta.radius(near) {
            // outside the nearest node's domain: drawn again, no call
            None
        } else {
            let step = g.step_from(ta, near, d, &q_rand);
            let new = match g.extend_step(ta, step)? {
                Extend::Trapped => None,
                Extend::Advanced(n) | Extend::Reached(n) => Some(n),
            };
            if let Some(domain) = &domain {
                ta.adapt_radius(near, domain, params.range * space.extent(), new.is_some());
            }
            new
        };
        if let Some(n) = new {
            let q_new = ta.node(n).to_vec();
            // with centring an extend may move without getting closer: the connect stops then
            let mut closest = f64::INFINITY;
            let min_gain = MIN_PROGRESS * params.stair * space.extent();
            loop {
                let full = max_nodes.is_some_and(|m| ta.grown() + tb.grown() >= m);
                if deadline.expired() || full {
                    break;
                }
                match g.extend(tb, &q_new)? {
                    Extend::Reached(m) => {
                        let (s, t) = if a == 0 { (n, m) } else { (m, n) };
                        let mut path = trees[0].base.branch(s);
                        let back = trees[1].base.branch(t);
                        // the meeting node is in both branches (as the same pose)
                        path.extend(back.into_iter().rev().skip(1));
                        return Ok(finish(trees, &g, Some(path), TreeStop::Connected));
                    }
                    Extend::Advanced(m) => {
                        if params.centre > 0 {
                            let d = space.distance(tb.node(m), &q_new);
                            if d > closest - min_gain {
                                break;
                            }
                            closest = d;
                        }
                    }
                    Extend::Trapped => break,
                }
            }
        }
        a = if let Some(only) = only {
            only
        } else if params.balance {
            usize::from(trees[1].grown() < trees[0].grown())
        } else {
            1 - a
        };
    }
}

/// Shortcuts a path of single-group corners greedily: from each corner, the farthest of the
/// next `window` corners that a free direct path reaches (yes/no calls), until `deadline`.
/// The result again has consecutive corners joined by free single-group motions.
pub fn shortcut(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    window: usize,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    let mut known = KnownPieces::new();
    known.certify_path(space, groups, path);
    let mut motions = (0..path.len().saturating_sub(1) as u32).collect();
    shortcut_known(
        space,
        oracle,
        groups,
        path,
        &mut motions,
        window,
        &mut known,
        counts,
        deadline,
    )
}

/// [`shortcut`] with the pieces and corners known so far ([`KnownPieces`]: `path`'s own pieces
/// certified by the caller): the same answer, and a pair's piece or corner asked before, in this
/// pass or an earlier one, costs no call. `motions[k]` names the motion segment `k` of `path`
/// is a piece of (equal for consecutive pieces of one straight motion, as
/// [`crate::local::straight_corners_of_motions`] cut them): a shortcut across pieces of one
/// motion would only walk it again, and is taken along the path itself without a call (a
/// goal's last extend past a shelf's board cost 0.1 ms to prove again). Updated to the
/// result's segments (a shortcut's its own).
#[allow(clippy::too_many_arguments)]
pub fn shortcut_known(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    motions: &mut Vec<u32>,
    window: usize,
    known: &mut KnownPieces,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    if path.len() <= 2 {
        return Ok(path.to_vec());
    }
    debug_assert_eq!(motions.len(), path.len() - 1);
    let mut fresh = motions.iter().max().map_or(0, |m| m + 1);
    let mut out = vec![path[0].clone()];
    let mut out_motions = Vec::with_capacity(motions.len());
    let mut i = 0;
    while i + 1 < path.len() {
        // the last corner on the straight motion segment `i` is a piece of
        let along = i + motions[i..]
            .iter()
            .take_while(|&&m| m == motions[i])
            .count();
        let mut jumped = None;
        if !deadline.expired() {
            for j in ((i + 2)..(i + 1 + window).min(path.len())).rev() {
                if j <= along {
                    // the path itself is that straight motion from `i` to `j`
                    out.extend(path[i + 1..=j].iter().cloned());
                    out_motions.extend_from_slice(&motions[i..j]);
                    i = j;
                    jumped = Some(None);
                    break;
                }
                if deadline.expired() {
                    break;
                }
                if let Some(c) = check_direct_known(
                    space,
                    oracle,
                    groups,
                    &path[i],
                    &path[j],
                    Some(&mut *known),
                    counts,
                )? {
                    jumped = Some(Some((j, c)));
                    break;
                }
            }
        }
        match jumped {
            // walked along the path's own straight motion
            Some(None) => {}
            Some(Some((j, c))) => {
                // the shortcut's segments: a motion of their own
                out_motions.extend(std::iter::repeat_n(fresh, c.len()));
                fresh += 1;
                out.extend(c);
                i = j;
            }
            None => {
                out.push(path[i + 1].clone());
                out_motions.push(motions[i]);
                i += 1;
            }
        }
    }
    *motions = out_motions;
    Ok(out)
}

/// [`shortcut`] passes of `window` corners until one drops no corner or `deadline` passes.
/// On an oracle error the path shortened so far (certified free corner to corner, as the
/// input) comes back with the error.
pub fn shortcut_passes(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    window: usize,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> (Vec<Config>, Option<OracleError>) {
    // corners along the straight extends, for shortcuts to start and end between them
    let (path, mut motions) =
        crate::local::straight_corners_of_motions(space, path, STRAIGHT_PIECE * space.extent());
    let mut short = path.clone();
    // one record for all passes: a pass asks again most pairs the one before found blocked
    let mut known = KnownPieces::new();
    known.certify_path(space, groups, &path);
    loop {
        match shortcut_known(
            space,
            oracle,
            groups,
            &short,
            &mut motions,
            window,
            &mut known,
            counts,
            deadline,
        ) {
            Ok(p) => {
                let better = p.len() < short.len();
                short = p;
                if !better || deadline.expired() {
                    return (short, None);
                }
            }
            Err(e) => return (short, Some(e)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node gets its domain at its first failed extend, each later failure shrinks it down to
    /// the least radius, a success grows a radius it has and leaves a node without one alone.
    #[test]
    fn a_failed_extend_gives_its_node_a_domain_that_shrinks_to_the_least() {
        let space = Space::joints(vec![0.0; 2], vec![1.0; 2], &[false; 2]).unwrap();
        let mut tree = Tree::new(&space, &Rooted::at(&[0.5, 0.5]));
        let d = Domain {
            radius: 4.0,
            least: 1.0,
            alpha: 0.5,
        };
        let range = 0.1;
        assert_eq!(tree.radius(0), f64::INFINITY);
        tree.adapt_radius(0, &d, range, true);
        assert_eq!(tree.radius(0), f64::INFINITY, "a success gives no domain");
        tree.adapt_radius(0, &d, range, false);
        assert!((tree.radius(0) - 0.4).abs() < 1e-12);
        tree.adapt_radius(0, &d, range, false);
        assert!((tree.radius(0) - 0.2).abs() < 1e-12);
        tree.adapt_radius(0, &d, range, true);
        assert!((tree.radius(0) - 0.3).abs() < 1e-12);
        for _ in 0..10 {
            tree.adapt_radius(0, &d, range, false);
        }
        assert!(
            (tree.radius(0) - 0.1).abs() < 1e-12,
            "never below the least"
        );
        // a node added later has none until its own extend fails
        let n = tree.add(vec![0.6, 0.5], 0);
        assert_eq!(tree.radius(n), f64::INFINITY);
    }
}
