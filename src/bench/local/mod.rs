//! Benchmarks of local methods inside the same learner, on the same scenes and the same queries
//! (`viaroad bench local`).
//!
//! The seed proposes the via-point planner as the local method of Overmars and Švestka's
//! learning approach (CHS §1.6). Whether that pays is a question about the whole roadmap: how
//! long learning takes, and how many nodes it needs, before the roadmap answers the queries a
//! user asks. So every *run* learns one roadmap of one scene with one method, in **stages of
//! growing node counts** (25, 35, 50, 71, 100, … up to a cap, see [`Schedule`]), and after
//! each stage answers a fixed query set with the roadmap. The run stops at the first stage that
//! solves the target share (99 %) of the scored queries, or at the cap, the time limit, or when
//! learning stalls. Its **time to 99 %** is the learning time up to that stage (query answering
//! is not learning time) and its **nodes needed** the roadmap's size there
//! ([`crate::roadmap::Learner::learn_in_stages`]).
//!
//! **Samplers** ([`crate::roadmap::Sampler`]: uniform, obstacle-based, Gaussian, bridge test,
//! mixtures) are compared the same way: `--samplers A B C` crosses every method with every
//! sampler, and the label of a run with a non-default sampler ends in ` @SPEC`.
//!
//! **Seedings** ([`crate::global::Seeding`]) too: `--seed-from plain cones` crosses
//! every method and sampler with a roadmap learnt from nothing and one learnt from the seed
//! roadmap of Brooks's freeways (label ` from cones`). A seeded run builds its freeways and
//! checks its seeds first; that time and those oracle calls count as learning (every stage's
//! learning time and counts include them), and its first stage is the seed roadmap alone
//! (stages at or below the seed's node count are skipped). The seeds depend on the scene only,
//! so determinism holds as for plain runs.
//!
//! | file | concept |
//! |---|---|
//! | [`spec`] | what to run: scenes × methods × runs, the node schedule, one self-contained [`RunJob`] |
//! | [`queries`] | the fixed query set of a scene: its OMPL query file, or seeded random queries |
//! | [`run`] | one run: staged learning, query evaluation, exact re-check of every returned path |
//! | [`machine`] | host, CPU, date, peak resident memory |
//! | [`report`] | per scene × method summaries, rankings, Markdown, CSV, JSON |
//! | [`sqlite`] | the database in OMPL's benchmark schema, for Planner Arena |
//! | [`plots`] | SVG box plots |
//!
//! **What counts as solved.** A query counts as solved when the roadmap returns a path *and*
//! every straight piece of that path is free under the scene's exact oracle. The `sampled`
//! baseline checks states at a resolution (OMPL's `DiscreteMotionValidator`) and may return
//! paths through thin obstacles; those are counted as *invalid paths*, not as solved. Exact
//! methods must have none (a non-zero count is a defect worth reporting).
//!
//! **Scored queries.** Queries whose start or goal is not valid under our oracle are set aside
//! (counted as invalid); so are query groups known to be infeasible, such as the 25 queries of
//! OMPL.app's cubicles that join the western basement with the rest of the building (see
//! [`queries::known_separate`]): they are answered once, at the end, and reported apart. After
//! all runs, the queries that *some* run solved form the scene's *solvable* set, and the time
//! to 99 % of that set is reported too — it differs from the plain one only on scenes where no
//! method solves everything.
//!
//! **Determinism.** A run's learning seed is the benchmark seed plus the run index, the same
//! for every method; the query set is drawn from the benchmark seed alone. With a node cap and
//! no `--time`, counts (nodes, edges, components, oracle calls, queries solved) do not depend
//! on the machine, its load or the thread count; times do.
//!
//! **Parallelism and memory.** Learning and query batches run in parallel on the rayon pool.
//! The command line runs each run in a child process of its own (`viaroad bench local-run`),
//! so that its peak resident set (`VmHWM`) is the run's; by default one run at a time, using
//! every core, which is what timing needs. `--jobs J` runs J children at once with
//! `cores / J` threads each: more throughput, same counts, but times then share the machine.

pub mod machine;
pub mod plots;
pub mod queries;
pub mod report;
pub mod run;
pub mod spec;
pub mod sqlite;

pub use queries::{QueryChoice, QuerySet};
pub use report::{MethodSummary, Report, SceneReport};
pub use run::{run_job, run_on, RunRecord, SeedRecord, StageRecord};
pub use spec::{Method, Plan, RunJob, SceneSource, Schedule};

use crate::local::spec::SpecError;
use crate::oracle::OracleError;
use crate::roadmap::{LearnError, QueryError, RoadmapError};
use crate::scene::SceneError;
use std::path::PathBuf;

/// Everything that can stop a benchmark.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// A scene that cannot be loaded.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A method spec that does not parse.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// Learning failed.
    #[error("learning: {0}")]
    Learn(#[from] LearnError),
    /// The roadmap could not serve queries or be encoded.
    #[error("roadmap: {0}")]
    Roadmap(#[from] RoadmapError),
    /// A query could not be answered (other than by "not solved").
    #[error("query: {0}")]
    Query(#[from] QueryError),
    /// The exact oracle could not re-check a returned path.
    #[error("re-checking a path: {0}")]
    Oracle(#[from] OracleError),
    /// A seeding that cannot start a roadmap of a scene (cone seeds on an SE(3) scene, an arm,
    /// R³ …), or that failed while its seeds were checked.
    #[error("seeding `{seeding}` on scene `{scene}`: {source}")]
    Seeding {
        /// The seeding.
        seeding: crate::global::Seeding,
        /// The scene's name.
        scene: String,
        /// Why.
        source: crate::global::cones::ConeError,
    },
    /// A plan that makes no sense (no scenes, zero runs, a bad schedule …).
    #[error("{0}")]
    Invalid(String),
    /// A file that cannot be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An output that is a special file (never replaced), or another unsafe write.
    #[error(transparent)]
    File(#[from] crate::safe_file::FileError),
    /// The benchmark database cannot be written.
    #[error("benchmark database: {0}")]
    Sqlite(#[from] rusqlite::Error),
}
