//! The roadmap: Overmars and Švestka's learning approach (OS94) with the via-point planner as
//! its local method and what that method discovers fed back into the graph (CHS §1.6).
//!
//! | file | concept |
//! |---|---|
//! | [`params`] | learning parameters (recorded in the file) and the budget |
//! | [`sampler`] | where new nodes are drawn: uniform, obstacle-based, Gaussian, bridge test |
//! | [`nn`] | nearest neighbours: an incremental kd-tree over the space's embeddings |
//! | [`graph`] | nodes, edges, components: the [`Roadmap`] |
//! | [`header`] | how a roadmap was learnt and for which scene: the [`Header`] |
//! | [`bounce`] | random-bounce walks driven by exact free sections |
//! | [`bodies_walk`] | walks of several bodies: one body at a time, slides of all in turn |
//! | [`learn`] | construction and expansion in reproducible parallel rounds; answers kept ([`Roadmap::with_path`]); merges ([`Learner::merge`]) |
//! | [`shard`] | one of N roadmaps learnt apart, from its own random streams |
//! | [`persist`] | the file: magic, version, header, checksum, atomic save |
//! | [`query`] | attach, A*, shorten; batches in parallel |
//! | [`landmarks`] | landmark lower bounds that guide A* around obstacles |
//! | [`tree`] | RRT-Connect for one query, with exact single-group extends |
//! | [`rooted`] | trees grown out of a roadmap's components, for ends it cannot join |
//! | [`info`] | the summary `viaroad info` prints |
//!
//! ```no_run
//! use viaroad::local::LocalSpec;
//! use viaroad::roadmap::{Budget, LearnParams, Learner, QueryPlanner, Roadmap};
//! use viaroad::scene::Scene;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let scene = Scene::load("scenes/discs.toml".as_ref())?;
//! let oracle = scene.oracle();
//! let local = LocalSpec::default().build();
//! let learnt = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref()).learn(
//!     &LearnParams::default(),
//!     &Budget::nodes(2000),
//!     7,
//!     &mut |_progress| {},
//! )?;
//! learnt.roadmap.save("roadmaps/discs.bin".as_ref())?;
//!
//! let roadmap = Roadmap::load("roadmaps/discs.bin".as_ref(), scene.fingerprint())?;
//! let planner = QueryPlanner::new(&roadmap, oracle.as_ref())?;
//! let answer = planner.query(&[0.02, 0.98], &[0.98, 0.02])?;
//! println!("{:?}: length {}", answer.outcome, answer.length);
//! # Ok(())
//! # }
//! ```

pub mod bodies_walk;
pub mod bounce;
pub mod centre;
pub mod graph;
pub mod header;
pub mod info;
pub mod landmarks;
pub mod learn;
pub mod nn;
pub mod params;
pub mod persist;
pub mod query;
pub mod rooted;
pub mod sampler;
pub mod shard;
mod step;
pub mod tree;

pub use graph::{Edge, Roadmap};
pub use header::Header;
pub use info::RoadmapInfo;
pub use landmarks::Landmarks;
pub use learn::{
    LearnError, LearnReport, Learner, Learnt, MergeError, MergeProgress, MergeReport, MergeStop,
    Merged, Phase, Progress, StopReason,
};
pub use nn::{KdTree, NearestNeighbours};
pub use params::{Budget, LearnParams};
pub use persist::{RoadmapError, FORMAT_VERSION, MAGIC};
pub use query::{
    BatchAnswer, Endpoint, QueryError, QueryOptions, QueryOutcome, QueryPlanner, QueryResult,
    ATTACH_SHARE, TREES_ATTACH_SHARE,
};
pub use sampler::Sampler;
pub use shard::{Shard, ShardError};
