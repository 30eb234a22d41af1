//! Minkowski C-obstacles of a translating polygon (LaValle ch. 3.3.2, lecture notes 4.3.2).
//!
//! When the robot only translates (its orientation fixed at `θ`), the configurations in which
//! a convex robot piece `A` meets a convex obstacle piece `O` form one convex polygon of the
//! plane, the Minkowski difference `O ⊖ A = O ⊕ (−A)` (the *C-obstacle*). It is built in
//! `O(n + m)` by merging the two polygons' edges sorted by the angle of their outward normals
//! ([`minkowski_difference`]): every edge of the sum is an edge of `O` (a vertex–edge contact
//! of the robot) or of `−A` (an edge–vertex contact), in normal order (notes 4.3.2, "EV and VE
//! contacts").
//!
//! With the C-obstacles in hand, "does the robot at `x` collide" is point-in-convex-polygon
//! ([`CObstacle::contains`]) and "when does the straight translation `x(t) = p + t·d` collide"
//! is one segment clipped against the C-obstacle's half-planes (Cyrus–Beck,
//! [`CObstacle::clip_line`]): one interval per C-obstacle, their union is the answer. This is
//! an independent derivation of what the edge-pair polygon oracle ([`super::polygons`])
//! computes from edge–edge and containment predicates, so each cross-checks the other
//! (`tests/minkowski.rs`), and it is an oracle of its own ([`Minkowski`]) for scenes in which
//! the robot keeps one orientation (`viaroad solve SCENE --oracle minkowski`).
//!
//! Non-convex robots and obstacles are split into convex pieces first: a convex polygon stays
//! whole, any other is triangulated (`geometry/triangulate.rs`, the pieces the polygon oracle
//! uses for containment), so a robot of `a` pieces among obstacles of `b` pieces has `a·b`
//! C-obstacles. Numerics follow the polygon oracle: each half-plane is relaxed by
//! [`super::polygons::TOLERANCE`] times the scene's size in favour of collision.

use super::{CallCounts, CollisionOracle, OracleError, Workspace};
use crate::geometry::kernel::aabb::Aabb;
use crate::geometry::kernel::bvh::Bvh;
use crate::geometry::Polygon;
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Motion};

/// A point or vector of the plane.
pub type P = [f64; 2];

fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1]]
}

fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The convex hull of `points`, counter-clockwise, without collinear or repeated vertices
/// (Andrew's monotone chain). One vertex for a point, two for a segment. Non-finite points
/// are skipped.
pub fn convex_hull(points: &[P]) -> Vec<P> {
    let mut pts: Vec<P> = points
        .iter()
        .copied()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .map(|p| [p[0] + 0.0, p[1] + 0.0])
        .collect();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<P> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &P>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(
                    sub(hull[hull.len() - 1], hull[hull.len() - 2]),
                    sub(p, hull[hull.len() - 2]),
                ) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.len() < 2 {
        // all points collinear and the chain collapsed: the two extremes
        return vec![pts[0], pts[pts.len() - 1]];
    }
    hull
}

/// Index of the lowest vertex (least `y`, then least `x`): where the edge angles of a convex
/// counter-clockwise polygon start at 0 and increase.
fn lowest(v: &[P]) -> usize {
    (0..v.len())
        .min_by(|&i, &j| {
            v[i][1]
                .total_cmp(&v[j][1])
                .then(v[i][0].total_cmp(&v[j][0]))
        })
        .unwrap_or(0)
}

/// The Minkowski sum `P ⊕ Q` of two convex polygons given counter-clockwise without collinear
/// vertices (as [`convex_hull`] returns them; one or two vertices for a point or a segment):
/// the merge of their edge sequences sorted by angle, `O(n + m)` (LaValle 3.3.2, Fig. 3.14).
pub fn minkowski_sum(p: &[P], q: &[P]) -> Vec<P> {
    if p.is_empty() || q.is_empty() {
        return Vec::new();
    }
    if p.len() == 1 {
        return q.iter().map(|&v| add(v, p[0])).collect();
    }
    if q.len() == 1 {
        return p.iter().map(|&v| add(v, q[0])).collect();
    }
    let (ip, iq) = (lowest(p), lowest(q));
    let (n, m) = (p.len(), q.len());
    let pv = |k: usize| p[(ip + k) % n];
    let qv = |k: usize| q[(iq + k) % m];
    let mut out = Vec::with_capacity(n + m);
    let (mut i, mut j) = (0, 0);
    while i < n || j < m {
        out.push(add(pv(i), qv(j)));
        let ep = sub(pv(i + 1), pv(i));
        let eq = sub(qv(j + 1), qv(j));
        let c = if i >= n {
            -1.0
        } else if j >= m {
            1.0
        } else {
            cross(ep, eq)
        };
        if c >= 0.0 {
            i += 1;
        }
        if c <= 0.0 {
            j += 1;
        }
    }
    out
}

/// The C-obstacle of a translating convex robot piece against a convex obstacle piece:
/// `O ⊕ (−A)`, both given in any order (their hulls are taken). `robot` is in the body frame
/// at the orientation of interest, with the reference point at the origin.
pub fn minkowski_difference(robot: &[P], obstacle: &[P]) -> Vec<P> {
    let neg: Vec<P> = robot.iter().map(|v| [-v[0], -v[1]]).collect();
    minkowski_sum(&convex_hull(obstacle), &convex_hull(&neg))
}

/// One convex C-obstacle with its half-planes prepared for the tests.
#[derive(Clone, Debug)]
pub struct CObstacle {
    /// Vertices, counter-clockwise (one or two for a degenerate C-obstacle).
    vertices: Vec<P>,
    /// Per constraint `(n, c)`: inside iff `n · x ≤ c` (relaxed by the tolerance). Edge
    /// half-planes of a polygon; for a segment or a point, the slab and end caps.
    planes: Vec<(P, f64)>,
    bounds: Aabb<2>,
}

impl CObstacle {
    /// A C-obstacle from its convex vertices (counter-clockwise, as [`minkowski_sum`] returns).
    pub fn new(vertices: Vec<P>) -> CObstacle {
        let mut planes = Vec::with_capacity(vertices.len().max(4));
        let k = vertices.len();
        let unit = |v: P| {
            let l = v[0].hypot(v[1]);
            if l > 0.0 {
                [v[0] / l, v[1] / l]
            } else {
                [0.0, 0.0]
            }
        };
        if k >= 3 {
            for i in 0..k {
                let (a, b) = (vertices[i], vertices[(i + 1) % k]);
                let e = sub(b, a);
                // outward normal of a counter-clockwise edge
                let n = unit([e[1], -e[0]]);
                if n != [0.0, 0.0] {
                    planes.push((n, dot(n, a)));
                }
            }
        } else if k == 2 {
            let (a, b) = (vertices[0], vertices[1]);
            let u = unit(sub(b, a));
            let n = [u[1], -u[0]];
            planes.push((n, dot(n, a)));
            planes.push(([-n[0], -n[1]], -dot(n, a)));
            planes.push((u, dot(u, b)));
            planes.push(([-u[0], -u[1]], -dot(u, a)));
        } else if k == 1 {
            let a = vertices[0];
            for (n, c) in [
                ([1.0, 0.0], a[0]),
                ([-1.0, 0.0], -a[0]),
                ([0.0, 1.0], a[1]),
                ([0.0, -1.0], -a[1]),
            ] {
                planes.push((n, c));
            }
        }
        let bounds = Aabb::of_plane_points(&vertices);
        CObstacle {
            vertices,
            planes,
            bounds,
        }
    }

    /// The vertices, counter-clockwise.
    pub fn vertices(&self) -> &[P] {
        &self.vertices
    }

    /// Whether the reference point at `x` puts the robot piece in contact with or inside the
    /// obstacle piece (closed sets; `tol` a length that counts as touching).
    pub fn contains(&self, x: P, tol: f64) -> bool {
        !self.vertices.is_empty() && self.planes.iter().all(|&(n, c)| dot(n, x) <= c + tol)
    }

    /// The parameters `t ∈ range` for which `p + t·d` lies in the C-obstacle (Cyrus–Beck: each
    /// half-plane is one linear inequality in `t`, their meet is at most one interval).
    pub fn clip_line(&self, p: P, d: P, range: Interval, tol: f64) -> Option<Interval> {
        if self.vertices.is_empty() {
            return None;
        }
        let (mut lo, mut hi) = (range.lo, range.hi);
        for &(n, c) in &self.planes {
            // n·p + t n·d ≤ c + tol
            let a = dot(n, d);
            let b = c + tol - dot(n, p);
            if a == 0.0 {
                if b < 0.0 {
                    return None;
                }
            } else if a > 0.0 {
                hi = hi.min(b / a);
            } else {
                lo = lo.max(b / a);
            }
            if lo > hi {
                return None;
            }
        }
        Interval::new(lo, hi)
    }
}

/// Convex pieces of a union of polygons: a convex polygon whole, any other as the triangles
/// of its ear-clipping triangulation.
pub fn convex_pieces(polys: &[Polygon]) -> Vec<Vec<P>> {
    let mut out = Vec::new();
    for poly in polys {
        let mut v: Vec<P> = poly
            .vertices
            .iter()
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .map(|p| [p.x + 0.0, p.y + 0.0])
            .collect();
        v.dedup();
        while v.len() > 1 && v.first() == v.last() {
            v.pop();
        }
        if v.is_empty() {
            continue;
        }
        let n = v.len();
        let area2: f64 = (0..n).map(|i| cross(v[i], v[(i + 1) % n])).sum();
        if area2 < 0.0 {
            v.reverse();
        }
        let convex = n < 4
            || (0..n).all(|i| cross(sub(v[(i + 1) % n], v[i]), sub(v[(i + 2) % n], v[i])) >= 0.0);
        if convex {
            out.push(v);
        } else {
            let tris = crate::geometry::triangulate::triangulate(&v);
            out.extend(tris.iter().map(|t| vec![v[t[0]], v[t[1]], v[t[2]]]));
            if tris.is_empty() {
                out.push(v);
            }
        }
    }
    out
}

/// The robot's body-frame vertices turned by `theta`.
fn turned(piece: &[P], theta: f64) -> Vec<P> {
    let (s, c) = theta.sin_cos();
    piece
        .iter()
        .map(|v| [c * v[0] - s * v[1], s * v[0] + c * v[1]])
        .collect()
}

/// A translating polygonal robot among polygons, answered through its C-obstacles.
///
/// The robot keeps the orientation `theta` given at construction. Configurations are `[x, y]`
/// (a translating robot in R²) or `[x, y, θ]` with `θ` equal to `theta` (an SE(2) scene whose
/// robot does not turn); motions must be translations. Anything else — a turn, another
/// orientation, a dimension other than 2 or 3 — is [`OracleError::Unsupported`].
///
/// ```
/// use viaroad::geometry::Polygon;
/// use viaroad::oracle::minkowski::Minkowski;
/// use viaroad::oracle::{CallCounts, CollisionOracle};
/// use viaroad::space::{Change, Motion};
///
/// // the unit square of the polygon oracle's example, sliding through the same box
/// let robot = vec![Polygon::rectangle([0.0, 0.0], [0.5, 0.5]).unwrap()];
/// let wall = vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()];
/// let oracle = Minkowski::new(&robot, &wall, 0.0);
/// let motion = Motion::segment(vec![0.0, 0.0], Change::Linear(vec![10.0, 0.0]));
/// let hits = oracle.intervals(&motion, &mut CallCounts::default()).unwrap();
/// let iv = hits.as_slice()[0];
/// assert!((iv.lo - 0.25).abs() < 1e-9 && (iv.hi - 0.55).abs() < 1e-9);
/// ```
#[derive(Clone, Debug)]
pub struct Minkowski {
    theta: f64,
    cobs: Vec<CObstacle>,
    tree: Bvh<2>,
    /// Largest obstacle coordinate or robot radius (the tolerance's scale, as in the polygon
    /// oracle).
    scale: f64,
}

impl Minkowski {
    /// The C-obstacles of `robot` (body frame, reference point at the origin) turned by
    /// `theta`, against `obstacles` (world frame).
    pub fn new(robot: &[Polygon], obstacles: &[Polygon], theta: f64) -> Minkowski {
        let robot_pieces: Vec<Vec<P>> = convex_pieces(robot)
            .iter()
            .map(|p| convex_hull(&turned(p, theta)))
            .collect();
        let obstacle_pieces: Vec<Vec<P>> = convex_pieces(obstacles)
            .iter()
            .map(|p| convex_hull(p))
            .collect();
        let radius = robot_pieces
            .iter()
            .flatten()
            .map(|p| p[0].hypot(p[1]))
            .fold(0.0, f64::max);
        let scale = obstacle_pieces
            .iter()
            .flatten()
            .map(|p| p[0].abs().max(p[1].abs()))
            .fold(radius, f64::max);
        let neg: Vec<Vec<P>> = robot_pieces
            .iter()
            .map(|r| convex_hull(&r.iter().map(|v| [-v[0], -v[1]]).collect::<Vec<_>>()))
            .collect();
        let mut cobs = Vec::with_capacity(neg.len() * obstacle_pieces.len());
        for o in &obstacle_pieces {
            for r in &neg {
                cobs.push(CObstacle::new(minkowski_sum(o, r)));
            }
        }
        let tree = Bvh::build(cobs.iter().map(|c| c.bounds).collect());
        Minkowski {
            theta,
            cobs,
            tree,
            scale,
        }
    }

    /// The orientation the robot keeps.
    pub fn theta(&self) -> f64 {
        self.theta
    }

    /// The C-obstacles (one per pair of convex robot and obstacle pieces).
    pub fn c_obstacles(&self) -> &[CObstacle] {
        &self.cobs
    }

    fn tolerance_at(&self, x: P) -> f64 {
        super::polygons::TOLERANCE * (self.scale + x[0].abs().max(x[1].abs()))
    }

    /// Checks the configuration's shape and orientation; returns the position.
    fn position(&self, q: &[f64]) -> Result<P, OracleError> {
        match q.len() {
            2 => {}
            3 if (q[2] - self.theta).abs() <= 1e-12 * (1.0 + self.theta.abs()) => {}
            3 => {
                return Err(OracleError::Unsupported(format!(
                    "minkowski: the robot keeps the orientation {}, asked at {}",
                    self.theta, q[2]
                )))
            }
            n => {
                return Err(OracleError::Unsupported(format!(
                    "minkowski: configurations are [x, y] or [x, y, θ], got {n} coordinates"
                )))
            }
        }
        if !(q[0].is_finite() && q[1].is_finite()) {
            return Err(OracleError::Unsupported(
                "minkowski: a coordinate that is not a finite number".into(),
            ));
        }
        Ok([q[0], q[1]])
    }

    /// Start and direction of a translation.
    fn translation(&self, motion: &Motion) -> Result<(P, P), OracleError> {
        let p = self.position(&motion.origin)?;
        let Change::Linear(d) = &motion.change else {
            return Err(OracleError::Unsupported(
                "minkowski: an SE(3) rotation in the plane".into(),
            ));
        };
        if d.len() != motion.origin.len() {
            return Err(OracleError::Unsupported(
                "minkowski: the change and the origin differ in dimension".into(),
            ));
        }
        if d.len() == 3 && d[2] != 0.0 {
            return Err(OracleError::Unsupported(
                "minkowski: the robot only translates (a turn was asked)".into(),
            ));
        }
        if !(d[0].is_finite() && d[1].is_finite()) {
            return Err(OracleError::Unsupported(
                "minkowski: a change that is not a finite number".into(),
            ));
        }
        let r = motion.range;
        if r.lo.is_nan() || r.hi.is_nan() || r.lo > r.hi {
            return Err(OracleError::Unsupported(
                "minkowski: an empty parameter range".into(),
            ));
        }
        Ok((p, [d[0], d[1]]))
    }

    /// Calls `hit` with the interval of every C-obstacle the translation meets; stops early
    /// when `hit` returns `false`.
    fn sweep(
        &self,
        p: P,
        d: P,
        range: Interval,
        counts: &mut CallCounts,
        mut hit: impl FnMut(Interval) -> bool,
    ) {
        // the tolerance at the farthest point of the motion that matters
        let far = |t: f64| {
            if t.is_finite() {
                let x = [p[0] + t * d[0], p[1] + t * d[1]];
                x[0].abs().max(x[1].abs())
            } else {
                0.0
            }
        };
        let tol = super::polygons::TOLERANCE
            * (self.scale
                + far(range.lo)
                    .max(far(range.hi))
                    .max(p[0].abs().max(p[1].abs())));
        let (o, dir) = (nalgebra::Vector2::from(p), nalgebra::Vector2::from(d));
        let mut tested = 0u64;
        self.tree.visit(
            |b| {
                b.grown(tol)
                    .line_range(&o, &dir)
                    .is_some_and(|iv| iv.meet(&range).is_some())
            },
            |i| {
                tested += 1;
                match self.cobs[i as usize].clip_line(p, d, range, tol) {
                    Some(iv) => hit(iv),
                    None => true,
                }
            },
        );
        counts.pairs_tested += tested;
    }
}

impl CollisionOracle for Minkowski {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let mut out = IntervalList::new();
        self.intervals_into(motion, &mut out, &mut Workspace::new(), counts)?;
        Ok(out)
    }

    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let (p, d) = self.translation(motion)?;
        ws.hits.clear();
        self.sweep(p, d, motion.range, counts, |iv| {
            ws.hits.push(iv);
            true
        });
        out.set_from_unsorted(&mut ws.hits);
        Ok(())
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        // an unsupported configuration is answered as a collision: never "free" by mistake
        let Ok(x) = self.position(q) else {
            return true;
        };
        let tol = self.tolerance_at(x);
        let mut hit = false;
        let v = nalgebra::Vector2::from(x);
        self.tree.visit(
            |b| b.grown(tol).distance_squared_to(&v) == 0.0,
            |i| {
                counts.pairs_tested += 1;
                hit = self.cobs[i as usize].contains(x, tol);
                !hit
            },
        );
        hit
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        let (p, d) = self.translation(motion)?;
        let mut free = true;
        self.sweep(p, d, motion.range, counts, |_| {
            free = false;
            false
        });
        Ok(free)
    }

    fn prefers_unclipped(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(v: &[P]) -> f64 {
        let n = v.len();
        (0..n).map(|i| cross(v[i], v[(i + 1) % n])).sum::<f64>() / 2.0
    }

    #[test]
    fn square_minus_square_is_the_doubled_square() {
        let a = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let o = [[4.0, 0.0], [6.0, 0.0], [6.0, 2.0], [4.0, 2.0]];
        let c = minkowski_difference(&a, &o);
        // the merge keeps the collinear junctions of parallel edges: 8 vertices, area 16
        assert!((area(&c) - 16.0).abs() < 1e-12, "{c:?}");
        let hull = convex_hull(&c);
        assert_eq!(hull.len(), 4);
        let cob = CObstacle::new(c);
        assert!(cob.contains([3.0, -1.0], 0.0) && cob.contains([5.0, 1.0], 0.0));
        assert!(!cob.contains([2.9, 1.0], 1e-12));
    }

    #[test]
    fn sum_with_a_point_or_a_segment() {
        let tri = convex_hull(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(minkowski_sum(&tri, &[[2.0, 3.0]]).len(), 3);
        let seg = convex_hull(&[[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]]);
        assert_eq!(seg.len(), 2);
        let s = minkowski_sum(&tri, &seg);
        assert!((area(&s) - (0.5 + 2.0)).abs() < 1e-12, "{s:?}");
    }
}
