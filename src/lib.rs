//! # viaroad
//!
//! Multi-query motion planning: a probabilistic roadmap in the style of Overmars and Švestka
//! whose local method is the recursive **via-point planner** of Chadzelek, Hotz and Schömer
//! (*Heuristic Motion Planning with Many Degrees of Freedom*, 1995; cited as CHS with its
//! section numbers).
//!
//! The local method never samples along a motion: it asks the scene for *all* collision
//! intervals of a straight motion and dodges through via points on a borderline. The via
//! points and certified free segments it discovers are fed back into the roadmap.
//!
//! | module | concept |
//! |---|---|
//! | [`interval`] | sorted disjoint interval lists: the oracle's answers |
//! | [`space`] | R^n, SE(2), SE(3): distance, sampling, DOF groups, straight motions |
//! | [`oracle`] | collision intervals of a motion (discs, polygons, polyhedra, sampled) |
//! | [`local`] | local methods: straight line, via-point planner, path shortening |
//! | [`solve`] | one query planned by a portfolio suited to the scene (what `viaroad solve` runs) |
//! | [`deadline`] | budgets that hold: one deadline checked before every oracle call |
//! | [`roadmap`] | learning, persistence, queries |
//! | [`robot`] | robot arms: URDF + SRDF, forward kinematics, the independent arm checker |
//! | [`export`] | glTF export and the HTML viewer (seeing a plan in 3D) |
//! | [`mesh_io`] | mesh files (OBJ, STL, Collada) and the checked reads of input files |
//! | [`scene`] | TOML scenes, OMPL.app problems, MoveIt scenes and requests, meshes |
//! | [`checker`] | path checkers sharing no code with the oracles (discs, SE(2), SE(3)) |
//! | [`certify`] | other planners' paths proved free, located and repaired |
//! | [`bench`](mod@bench) | the seed's experiments and local-method benchmarks |
//! | [`limits`] | the largest numbers accepted from users |
//! | [`safe_file`] | atomic saves that never replace special files; bounded reads |
//! | [`short`] | numbers and configurations in short form for human messages |
#![warn(missing_docs)]

pub mod bench;
pub mod certify;
pub mod checker;
pub mod deadline;
pub mod export;
mod fast_hash;
pub mod geometry;
pub mod global;
pub mod interval;
pub mod limits;
pub mod local;
pub mod mesh_io;
pub mod oracle;
pub mod portfolio;
pub mod render;
pub mod roadmap;
pub mod robot;
pub mod safe_file;
pub mod scene;
pub mod short;
pub mod solve;
pub mod space;
