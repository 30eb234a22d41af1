//! The oracle's data, the robot's and the obstacles' faces with their trees, and the paired
//! descent of both trees that every sweep starts from.

use super::body::Body;
use super::pose::Aabb;
use super::predicate::Tolerance;
use crate::geometry::kernel::bvh;
use crate::geometry::kernel::hits::Hits;
use crate::geometry::TriMesh;
use std::sync::Arc;

/// Robots with at most this many faces are tested at a pose and along a translation by querying
/// the obstacle tree with their (swept) box and their own tree per obstacle face (a double descent
/// of both trees costs more than it saves for a few leaves: OMPL.app's Home robot, 60 faces, took
/// 1.9× as long by it at a pose, Twistycool's, 28 faces, 1.5× along translations).
pub(super) const SMALL_ROBOT: usize = 128;

/// Exact collision intervals of a triangle-mesh robot among triangle-mesh obstacles.
///
/// ```
/// use viaroad::geometry::TriMesh;
/// use viaroad::oracle::polyhedra::Polyhedra;
/// use viaroad::oracle::{CallCounts, CollisionOracle};
/// use viaroad::space::{Change, Motion};
///
/// // a unit cube sliding along x from −5 to 5 through a box of half-size 1 at the origin
/// let cube = TriMesh::cuboid([0.5; 3]).unwrap();
/// let oracle = Polyhedra::new(cube, vec![TriMesh::cuboid([1.0; 3]).unwrap()]);
/// let start = vec![-5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
/// let slide = Change::Linear(vec![10.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
/// let hits = oracle.intervals(&Motion::segment(start, slide), &mut CallCounts::default());
/// let iv = hits.unwrap().as_slice()[0];
/// // in contact while |x| ≤ 1.5, i.e. t ∈ [0.35, 0.65]
/// assert!((iv.lo - 0.35).abs() < 1e-9 && (iv.hi - 0.65).abs() < 1e-9);
/// ```
pub struct Polyhedra {
    pub(super) robot_mesh: Arc<TriMesh>,
    pub(super) obstacle_meshes: Arc<Vec<TriMesh>>,
    pub(super) robot: Body,
    /// Shared with the pivoted views of [`Polyhedra::turn_about`].
    pub(super) obstacles: Arc<Body>,
    pub(super) tol: Tolerance,
    pub(super) enveloping: bool,
}

/// The robot's tree against the obstacles' tree for a sweep into `sink`: in a first-collision
/// sweep ([`Hits::is_prefix`]) the earlier window first, and node pairs that start after
/// `cutoff` pruned — `leaves` keeps `cutoff` at the earliest piece ([`note_earliest`]).
/// `start` reads the parameter window out of a node pair's `W`.
#[allow(clippy::too_many_arguments)]
pub(super) fn descend_pairs<W: Copy>(
    robot: &bvh::Bvh<3>,
    obstacles: &bvh::Bvh<3>,
    window: W,
    prefix: bool,
    cutoff: &std::cell::Cell<f64>,
    start: impl Fn(&W) -> f64,
    test: impl FnMut(u32, u32, &Aabb, &Aabb, W) -> Option<W>,
    leaves: impl FnMut(&[u32], &[u32], W) -> bool,
) {
    if prefix {
        robot.visit_pairs_earliest(obstacles, window, test, leaves, &start, |w| {
            start(w) >= cutoff.get()
        });
    } else {
        robot.visit_pairs(obstacles, window, test, leaves);
    }
}

/// After a leaf pair of [`descend_pairs`]: the earliest piece so far is the new cutoff.
pub(super) fn note_earliest(sink: &Hits, cutoff: &std::cell::Cell<f64>) {
    if let Some(p) = sink.as_slice().first() {
        cutoff.set(p.lo);
    }
}
