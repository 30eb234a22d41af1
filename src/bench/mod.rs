//! Benchmarks: the seed's own experiments and comparisons of local methods.
//!
//! - [`certify`]: another planner's paths for MotionBenchMaker problems certified and repaired.
//! - [`discs`]: the random disc problems of CHS Appendix A.1.3 and the runner that regenerates
//!   Tables A.1–A.4 ([`tables`]).
//! - [`local`]: local methods compared inside the same learner on the same scenes and queries
//!   (time and nodes to 99 % of the queries, Planner Arena database, plots).
//! - [`mbm`]: MotionBenchMaker problems for robot arms, and the workcell roadmap.
//! - [`validity`]: random queries on every scene kind, every path re-checked by independent
//!   checkers (0 invalid in 100 000).

pub mod certify;
pub mod discs;
pub mod local;
pub mod mbm;
pub mod tables;
pub mod validity;
