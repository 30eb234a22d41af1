//! The knobs of the via-point planner, each as the seed describes it.

use serde::{Deserialize, Serialize};

/// How the recursion limit `k` is found (CHS §1.3, "Recursion Depth").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Depth {
    /// A fixed limit given by the user (Table A.3).
    Fixed(u32),
    /// Iterative deepening `k = 0, 1, 2, …, max`, starting afresh each time (Table A.1).
    Deepen {
        /// Largest limit tried.
        max: u32,
    },
    /// Iterative deepening that keeps a tree of solved and failed subproblems, so earlier
    /// stages are not recomputed (Table A.2).
    DeepenReuse {
        /// Largest limit tried.
        max: u32,
    },
}

impl Depth {
    /// The largest recursion limit this strategy will try.
    pub fn max(&self) -> u32 {
        match *self {
            Depth::Fixed(k) | Depth::Deepen { max: k } | Depth::DeepenReuse { max: k } => k,
        }
    }
}

/// How many via points per borderline (set of borderlines) are tried (CHS §1.3: "that list is
/// restricted to the best k points"; Appendix A: "≤ 2 via points" or "all via points").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum ViaLimit {
    /// The best `n` by valuation.
    Best(usize),
    /// All of them, best first.
    All,
}

/// Where the borderline crosses the blocked motion (Table A.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum BasePoint {
    /// Start of the first collision interval.
    StartOfFirst,
    /// A random point in the first collision interval.
    RandomInFirst,
    /// Centre of the first collision interval (Fig 1.2; the tables A.1–A.3).
    CentreOfFirst,
    /// Centre of a randomly chosen collision interval.
    CentreOfRandom,
    /// Centre of the middle interval of the list.
    CentreOfMiddle,
    /// Centre of the collision interval whose centre is nearest the centre of (a, z) — the
    /// seed's recommendation (CHS §1.3, "Via Points").
    CentreNearestMiddle,
    /// The centre of (a, z) itself.
    MiddleOfMotion,
    /// A random point of (a, z).
    RandomInMotion,
}

impl BasePoint {
    /// Every strategy, in the order of Table A.4.
    pub const ALL: [BasePoint; 8] = [
        BasePoint::StartOfFirst,
        BasePoint::RandomInFirst,
        BasePoint::CentreOfFirst,
        BasePoint::CentreOfRandom,
        BasePoint::CentreOfMiddle,
        BasePoint::CentreNearestMiddle,
        BasePoint::MiddleOfMotion,
        BasePoint::RandomInMotion,
    ];

    /// Short name used in spec strings and tables.
    pub fn name(&self) -> &'static str {
        match self {
            BasePoint::StartOfFirst => "start-first",
            BasePoint::RandomInFirst => "random-first",
            BasePoint::CentreOfFirst => "centre-first",
            BasePoint::CentreOfRandom => "centre-random",
            BasePoint::CentreOfMiddle => "centre-middle",
            BasePoint::CentreNearestMiddle => "centre-nearest",
            BasePoint::MiddleOfMotion => "middle",
            BasePoint::RandomInMotion => "random",
        }
    }

    /// The seed's wording (Table A.4).
    pub fn description(&self) -> &'static str {
        match self {
            BasePoint::StartOfFirst => "start of 1st interval",
            BasePoint::RandomInFirst => "randomly in 1st interval",
            BasePoint::CentreOfFirst => "centre of 1st interval",
            BasePoint::CentreOfRandom => "centre of random interval",
            BasePoint::CentreOfMiddle => "centre of middle interval (in list)",
            BasePoint::CentreNearestMiddle => "centre next to centre of (a, z)",
            BasePoint::MiddleOfMotion => "centre of (a, z)",
            BasePoint::RandomInMotion => "randomly in (a, z)",
        }
    }

    /// Parses [`name`](Self::name).
    pub fn from_name(s: &str) -> Option<BasePoint> {
        BasePoint::ALL.into_iter().find(|b| b.name() == s)
    }
}

/// How borderline directions are chosen inside the hyperplane perpendicular to a blocked
/// motion, when it has more than one dimension (CHS §1.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Directions {
    /// An orthogonal basis of the hyperplane. With `axis_preference` it is built from the world
    /// axes least aligned with the motion ("real world scenes are full of orthogonal
    /// features"); otherwise from an arbitrary completion. When none of its via points leads
    /// to a path, the basis is rotated about the motion direction up to `rotations` times.
    Basis {
        /// Prefer world axes.
        axis_preference: bool,
        /// Extra rotated bases tried on failure.
        rotations: u32,
    },
    /// `count` random directions in the hyperplane.
    Random {
        /// Number of directions.
        count: u32,
    },
}

/// Order in which the tree of subproblems is searched (CHS A.1.3: "depth-first avoids memory
/// problems, but a breadth-first approach yields better paths").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Search {
    /// Fig 1.3: recursion with backtracking; the first path found is returned.
    DepthFirst,
    /// Level by level: all subproblems of depth `k` are expanded before any of depth `k + 1`;
    /// among the paths of minimal depth the shortest is returned.
    BreadthFirst,
}

/// Every parameter of the via-point planner. `Default` gives the product defaults; the seed's
/// experiments set their own (see [`crate::bench::discs`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ViaPointOptions {
    /// How the recursion limit is found.
    pub depth: Depth,
    /// Valuation exponent β of `V_β(d, l) = d / l^β` (CHS §1.3); 2/3 was best for discs.
    pub beta: f64,
    /// Via points tried per blocked motion.
    pub via: ViaLimit,
    /// Where the borderline crosses the blocked motion.
    pub base_point: BasePoint,
    /// Borderline directions in hyperplanes of more than one dimension.
    pub directions: Directions,
    /// Treat every position axis as a DOF group of its own, so that paths are parallel to the
    /// axes (CHS A.1.1, Fig 1.6).
    pub split_axes: bool,
    /// Also dodge into the *other* DOF groups (for a blocked translation: full turns; for a
    /// blocked rotation: lines), besides perpendicular directions within the blocked group
    /// (CHS §1.5: "the motion must use another coordinate group or be perpendicular within that
    /// group"). Groups with no perpendicular direction (an angle, a single axis) always dodge
    /// into the others.
    pub dodge_other_groups: bool,
    /// Depth-first or breadth-first.
    pub search: Search,
    /// Stop a connection attempt after this many intersect calls (`None`: no budget). Keeps a
    /// roadmap's local method from "excessively long computations" (CHS §1.3).
    pub max_calls: Option<u64>,
    /// Seed of the random choices (random base points and directions); each subproblem derives
    /// its own stream from this and its endpoints, so results do not depend on search order.
    pub seed: u64,
    /// Keep every borderline asked about in [`crate::local::Connection::borderlines`].
    pub trace: bool,
    /// Record via points and free segments in [`crate::local::Connection::discoveries`] (the
    /// roadmap's feedback). Benchmarks of the search alone turn it off: the record grows with
    /// the number of calls.
    pub discoveries: bool,
    /// Borderlines whose reference point lies off the blocked motion (CHS §1.4, Fig 1.4): the
    /// base point steps sideways by this share of the blocked motion's length, along each axis
    /// of every other linear group and both ways, and a line through the stepped point runs
    /// parallel to the blocked motion. Its via points differ from the base point in both
    /// groups at once, which motions along the axes alone (`split`) cannot reach from one
    /// borderline. `None`: only borderlines through the base point. Roadmap files do not
    /// record it, so a roadmap learnt with it is not saved.
    #[serde(skip)]
    pub sidestep: Option<f64>,
}

impl Default for ViaPointOptions {
    fn default() -> Self {
        ViaPointOptions {
            depth: Depth::DeepenReuse { max: 6 },
            beta: 2.0 / 3.0,
            via: ViaLimit::Best(2),
            base_point: BasePoint::CentreNearestMiddle,
            directions: Directions::Basis {
                axis_preference: true,
                rotations: 1,
            },
            split_axes: false,
            dodge_other_groups: true,
            search: Search::DepthFirst,
            max_calls: Some(5000),
            seed: 0,
            trace: false,
            discoveries: true,
            sidestep: None,
        }
    }
}

impl ViaPointOptions {
    /// The settings of the seed's disc experiments (Appendix A.1.3): β = 2/3, at most two via
    /// points, base point at the centre of the first collision interval, minimal depth found by
    /// deepening with re-use, no call budget.
    pub fn seed_experiment() -> Self {
        ViaPointOptions {
            depth: Depth::DeepenReuse { max: 30 },
            base_point: BasePoint::CentreOfFirst,
            max_calls: None,
            ..ViaPointOptions::default()
        }
    }
}
