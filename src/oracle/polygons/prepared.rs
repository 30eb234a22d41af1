//! What the tests work on: the robot prepared in its body frame, the obstacles in the world
//! frame with their search trees, and the plane's small vector helpers that every sweep uses.

use crate::geometry::kernel::bvh;
use crate::geometry::Polygon;

/// A box of the plane.
pub(super) type Aabb = crate::geometry::kernel::aabb::Aabb<2>;
/// The obstacle trees.
pub(super) type Bvh = bvh::Bvh<2>;

/// Relative tolerance of the orientation tests: a point within `TOLERANCE × scale` of an edge
/// counts as touching it, where `scale` is the largest obstacle coordinate or the robot's
/// radius, whichever is larger, plus the largest coordinate of the robot's position. Far above
/// the rounding error of the tests (about `1e-16 × scale`), far below anything a planner can
/// resolve.
pub const TOLERANCE: f64 = 1e-12;

/// A point or vector of the plane.
pub(super) type P = [f64; 2];

#[inline]
pub(super) fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// `a × b`, the z component of the cross product.
#[inline]
pub(super) fn perp_dot(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The map `v ↦ Rot(theta)·v + centre`.
pub(super) fn placement(centre: P, theta: f64) -> impl Fn(P) -> P + Copy {
    let (s, c) = theta.sin_cos();
    move |v: P| {
        [
            centre[0] + c * v[0] - s * v[1],
            centre[1] + s * v[0] + c * v[1],
        ]
    }
}

/// The robot, prepared in its body frame.
#[derive(Clone, Debug, Default)]
pub(super) struct Body {
    /// All vertices (for the swept box of the whole robot).
    pub(super) vertices: Vec<P>,
    /// Edges of all parts, each segment once.
    pub(super) edges: Vec<[P; 2]>,
    /// Length of each edge.
    pub(super) edge_len: Vec<f64>,
    /// Distance range `[min, max]` of each edge from the reference point.
    pub(super) edge_radii: Vec<(f64, f64)>,
    /// Smallest distance of an edge from the reference point.
    pub(super) edge_inner_radius: f64,
    /// Triangles of all parts, counter-clockwise.
    pub(super) tris: Vec<[P; 3]>,
    /// Edge lengths of each triangle.
    pub(super) tri_len: Vec<[f64; 3]>,
    /// Distance range of each triangle from the reference point.
    pub(super) tri_radii: Vec<(f64, f64)>,
    /// Smallest distance of a triangle from the reference point.
    pub(super) tri_inner_radius: f64,
    /// One reference vertex per part (containment).
    pub(super) refs: Vec<P>,
    /// Largest distance of a vertex from the reference point.
    pub(super) radius: f64,
}

/// The obstacles, prepared in the world frame, with their search trees.
#[derive(Clone, Debug, Default)]
pub(super) struct World {
    pub(super) edges: Vec<[P; 2]>,
    pub(super) edge_len: Vec<f64>,
    pub(super) edge_tree: Bvh,
    pub(super) tris: Vec<[P; 3]>,
    pub(super) tri_len: Vec<[f64; 3]>,
    pub(super) tri_tree: Bvh,
    /// One reference vertex per obstacle (containment).
    pub(super) refs: Vec<P>,
    pub(super) ref_tree: Bvh,
}

/// Exact collision intervals of a polygonal robot among polygons (SE(2), translations and
/// rotations about the reference point).
///
/// Supported motions: `Change::Linear(delta)` with three coordinates that is either a pure
/// translation (`delta[2] == 0`, bounded or an unbounded line) or a pure rotation about the
/// reference point (`delta[0] == delta[1] == 0`, a bounded range: a segment or a full turn).
/// Anything else is [`crate::oracle::OracleError::Unsupported`].
///
/// ```
/// use viaroad::geometry::Polygon;
/// use viaroad::oracle::polygons::Polygons;
/// use viaroad::oracle::{CallCounts, CollisionOracle};
/// use viaroad::space::{Change, Motion};
///
/// // a unit square sliding along x from 0 to 10 through the box [3, 5] × [−1, 1]:
/// // it touches the box while its centre is in [2.5, 5.5], i.e. for t ∈ [0.25, 0.55]
/// let robot = vec![Polygon::rectangle([0.0, 0.0], [0.5, 0.5]).unwrap()];
/// let wall = vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()];
/// let oracle = Polygons::new(robot, wall);
/// let motion = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![10.0, 0.0, 0.0]));
/// let hits = oracle.intervals(&motion, &mut CallCounts::default()).unwrap();
/// let iv = hits.as_slice()[0];
/// assert!((iv.lo - 0.25).abs() < 1e-9 && (iv.hi - 0.55).abs() < 1e-9);
/// ```
#[derive(Clone, Debug)]
pub struct Polygons {
    pub(super) robot: Vec<Polygon>,
    pub(super) obstacles: Vec<Polygon>,
    pub(super) enveloping: bool,
    pub(super) body: Body,
    pub(super) world: World,
    /// Largest obstacle coordinate magnitude or robot radius.
    pub(super) scale: f64,
}

impl Polygons {
    /// The tolerance (a length) of tests with the robot at `centre`.
    pub(super) fn tolerance_at(&self, centre: P) -> f64 {
        TOLERANCE * (self.scale + centre[0].abs().max(centre[1].abs()))
    }
}
