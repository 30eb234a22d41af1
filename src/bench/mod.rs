//! Benchmarks: the seed's own experiments and comparisons of local methods.
//!
//! - [`discs`]: the random disc problems of CHS Appendix A.1.3 and the runner that regenerates
//!   Tables A.1–A.4 ([`tables`]).

pub mod discs;
pub mod tables;
