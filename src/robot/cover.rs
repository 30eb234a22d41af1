//! Outer sphere covers: a few balls per link whose union holds the link's whole solid, and the
//! obstacles as convex shapes that hold their polytopes, so that a few distances between
//! centres and shapes prove a link and an obstacle (or two links) apart.
//!
//! The seed's enveloping (CHS §2.4) puts a ball about each body so that far pairs are never
//! asked; one ball about a long link stands far off it, so a finger beside a shelf is never
//! proved apart that way. A row of balls along the link stands off it by little, and the
//! distance from a ball to a box, a cylinder or a ball is a handful of flops. The oracle
//! ([`super::oracle`]) asks the covers before the separating planes: a static test skips the
//! planes and the exact test of every pair whose covers stand apart, and a straight motion
//! hands a pair to the planes only over the pieces of time in which its covers, grown by how
//! far the links' points may move in half a piece, come near.
//!
//! **Exact by construction.** The link is cut into slabs across one of its principal axes.
//! The part of the link's surface inside a slab is a union of convex polygons (each triangle
//! cut by the slab's two planes), whose corners are the mesh's vertices inside the slab and the
//! points where its edges cross the slab's planes; the part of the solid inside the slab is
//! bounded by that surface and by its sections with the two planes, which lie in the hull of
//! the surface's crossings. So the ball about those points holds the link's solid in the slab,
//! and the balls of all slabs hold the whole link. Radii carry a relative margin for rounding.
//! Each obstacle shape ([`Outer`]) holds the polytope the exact oracle uses for it (a
//! circumscribed cylinder about the 16-gon prism, a ball about the sphere's polytope, the
//! polytope's box otherwise), so a pair the balls prove apart is apart in the exact oracle's
//! geometry too: the verdicts do not change, only the work.

use super::shapes::{Primitive, CIRCLE_SIDES};
use crate::geometry::TriMesh;
use nalgebra::{Isometry3, Point3, SymmetricEigen, Vector3};

/// Most balls in a collision element's cover: each costs a distance per obstacle and test.
pub const MOST_BALLS: usize = 8;

/// A cover with more balls is taken only if its balls' total volume is below this share of
/// the best cover of fewer balls: a ball must earn its cost.
const WORTH: f64 = 0.85;

/// A ball of a cover: centre and radius, in the link's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoverBall {
    /// Centre.
    pub centre: Point3<f64>,
    /// Radius (with a relative margin for rounding).
    pub radius: f64,
}

/// Balls whose union holds every point of the solid (or surface) that `mesh` bounds, in its
/// frame (see the module's text): the mesh cut into slabs across one of its principal axes,
/// one ball per slab, the axis and the number of slabs (at most [`MOST_BALLS`]) chosen for the
/// smallest total volume that a further ball no longer cuts by much.
pub fn cover(mesh: &TriMesh) -> Vec<CoverBall> {
    let (lo, hi) = mesh.aabb();
    let scale = (hi - lo).norm().max(f64::MIN_POSITIVE);
    let mut edges: Vec<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let mut best: Option<(f64, Vec<CoverBall>)> = None;
    for axis in principal_axes(&mesh.vertices) {
        let mut own: Option<(f64, Vec<CoverBall>)> = None;
        for k in 1..=MOST_BALLS {
            let balls = slabs(mesh, &edges, &axis, k, scale);
            let volume: f64 = balls.iter().map(|b| b.radius.powi(3)).sum();
            if own.as_ref().is_none_or(|(v, _)| volume < WORTH * v) {
                own = Some((volume, balls));
            }
        }
        if let Some((v, balls)) = own {
            if best.as_ref().is_none_or(|(b, _)| v < *b) {
                best = Some((v, balls));
            }
        }
    }
    best.map(|(_, b)| b).unwrap_or_default()
}

/// The unit eigenvectors of the vertices' covariance (the coordinate axes where it has none).
fn principal_axes(points: &[Point3<f64>]) -> Vec<Vector3<f64>> {
    let n = points.len().max(1) as f64;
    let mean = points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / n;
    let cov = points
        .iter()
        .map(|p| (p.coords - mean) * (p.coords - mean).transpose())
        .sum::<nalgebra::Matrix3<f64>>()
        / n;
    let eigen = SymmetricEigen::new(cov);
    let axes: Vec<Vector3<f64>> = (0..3)
        .filter_map(|i| eigen.eigenvectors.column(i).try_normalize(1e-12))
        .collect();
    if axes.len() == 3 && axes.iter().all(|a| a.iter().all(|c| c.is_finite())) {
        axes
    } else {
        vec![Vector3::x(), Vector3::y(), Vector3::z()]
    }
}

/// One ball per slab of `k` equal slabs across `axis`: about the mesh's vertices inside the
/// slab and its edges' crossings with the slab's planes. Empty slabs get no ball.
fn slabs(
    mesh: &TriMesh,
    edges: &[(u32, u32)],
    axis: &Vector3<f64>,
    k: usize,
    scale: f64,
) -> Vec<CoverBall> {
    let along: Vec<f64> = mesh.vertices.iter().map(|v| axis.dot(&v.coords)).collect();
    let (z0, z1) = along
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    let h = (z1 - z0) / k as f64;
    let plane = |j: usize| if j == k { z1 } else { z0 + h * j as f64 };
    let mut points: Vec<Vec<Point3<f64>>> = vec![Vec::new(); k];
    let slab_of = |z: f64| {
        if h > 0.0 {
            (((z - z0) / h).floor().max(0.0) as usize).min(k - 1)
        } else {
            0
        }
    };
    for (v, &z) in mesh.vertices.iter().zip(&along) {
        let s = slab_of(z);
        points[s].push(*v);
        // a vertex on (or rounding onto) a plane belongs to both slabs beside it
        if s > 0 && z <= plane(s) {
            points[s - 1].push(*v);
        }
        if s + 1 < k && z >= plane(s + 1) {
            points[s + 1].push(*v);
        }
    }
    for &(a, b) in edges {
        let (za, zb) = (along[a as usize], along[b as usize]);
        let (pa, pb) = (mesh.vertices[a as usize], mesh.vertices[b as usize]);
        for j in 1..k {
            let z = plane(j);
            if (za - z) * (zb - z) < 0.0 {
                let s = (z - za) / (zb - za);
                let p = pa + (pb - pa) * s;
                points[j - 1].push(p);
                points[j].push(p);
            }
        }
    }
    points
        .iter()
        .filter(|p| !p.is_empty())
        .map(|p| ball_about(p, scale))
        .collect()
}

/// A ball about `points`: the centre of their box, the farthest point's distance (with a
/// relative margin for the rounding of the crossings and of later placements).
fn ball_about(points: &[Point3<f64>], scale: f64) -> CoverBall {
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let centre = nalgebra::center(&lo, &hi);
    let radius = points
        .iter()
        .map(|p| (p - centre).norm())
        .fold(0.0, f64::max);
    CoverBall {
        centre,
        radius: radius * (1.0 + 1e-9) + 1e-9 * scale,
    }
}

/// An obstacle as a convex shape that holds the polytope the exact oracle uses for it, placed
/// in the world: the distance from a point to it bounds the distance to the polytope from
/// below.
#[derive(Clone, Copy, Debug)]
pub struct Outer {
    /// From the world into the shape's frame.
    into: Isometry3<f64>,
    shape: OuterShape,
}

/// [`Outer`]'s shape, centred at its frame's origin.
#[derive(Clone, Copy, Debug)]
enum OuterShape {
    /// A box of these half sides.
    Box(Vector3<f64>),
    /// A cylinder along z: radius, half length.
    Cylinder(f64, f64),
    /// A ball of this radius.
    Ball(f64),
}

impl Outer {
    /// The shape that holds `polytope` (in its own frame, as built from `primitive` where it
    /// came from one), placed at `pose`: a box stays a box, a cylinder becomes the cylinder
    /// through its prism's corners, a sphere the ball through its polytope's farthest corner,
    /// and anything else the polytope's own box.
    pub fn of(primitive: Option<&Primitive>, polytope: &TriMesh, pose: &Isometry3<f64>) -> Outer {
        let grow = |v: f64| v * (1.0 + 1e-9);
        let shape = match primitive {
            Some(Primitive::Box { size }) => {
                OuterShape::Box(Vector3::from(*size).map(|s| grow(s / 2.0)))
            }
            Some(Primitive::Cylinder { radius, length }) => OuterShape::Cylinder(
                grow(radius / (std::f64::consts::PI / CIRCLE_SIDES as f64).cos()),
                grow(length / 2.0),
            ),
            Some(Primitive::Sphere { .. }) => OuterShape::Ball(grow(
                polytope
                    .vertices
                    .iter()
                    .map(|v| v.coords.norm())
                    .fold(0.0, f64::max),
            )),
            _ => {
                let (lo, hi) = polytope.aabb();
                let centre = nalgebra::center(&lo, &hi);
                let half = (hi - lo).map(|s| grow(s / 2.0)) + Vector3::repeat(1e-12);
                return Outer {
                    into: (pose * Isometry3::translation(centre.x, centre.y, centre.z)).inverse(),
                    shape: OuterShape::Box(half),
                };
            }
        };
        Outer {
            into: pose.inverse(),
            shape,
        }
    }

    /// The distance from the world point `p` to the shape (0 inside).
    #[inline]
    pub fn distance(&self, p: &Point3<f64>) -> f64 {
        self.local_offset(p).norm()
    }

    /// `p` (in the world) less the shape's nearest point to it, in the shape's frame (zero
    /// inside).
    #[inline]
    fn local_offset(&self, p: &Point3<f64>) -> Vector3<f64> {
        let p = self.into * p;
        match self.shape {
            OuterShape::Box(h) => {
                let nearest = p.coords.sup(&-h).inf(&h);
                p.coords - nearest
            }
            OuterShape::Cylinder(r, h) => {
                let radial = (p.x * p.x + p.y * p.y).sqrt();
                let axial = p.z - p.z.clamp(-h, h);
                let out = (radial - r).max(0.0);
                let (x, y) = if radial > 0.0 {
                    (p.x * out / radial, p.y * out / radial)
                } else {
                    (0.0, 0.0)
                };
                Vector3::new(x, y, axial)
            }
            OuterShape::Ball(r) => {
                let d = p.coords.norm();
                if d > r {
                    p.coords * ((d - r) / d)
                } else {
                    Vector3::zeros()
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Every vertex and random points on every triangle of a mesh lie in some ball.
    pub(crate) fn assert_covers(mesh: &TriMesh, balls: &[CoverBall], what: &str) {
        let inside = |p: &Point3<f64>| balls.iter().any(|b| (p - b.centre).norm() <= b.radius);
        for v in &mesh.vertices {
            assert!(inside(v), "{what}: vertex {v:?} outside the cover");
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for t in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(t);
            for _ in 0..8 {
                let (mut u, mut v) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
                if u + v > 1.0 {
                    (u, v) = (1.0 - u, 1.0 - v);
                }
                let p = a + (b - a) * u + (c - a) * v;
                assert!(inside(&p), "{what}: point {p:?} of triangle {t} outside");
            }
        }
    }

    #[test]
    fn a_long_box_gets_a_row_of_balls_that_hold_it() {
        let m = TriMesh::cuboid([0.5, 0.05, 0.05]).unwrap();
        let balls = cover(&m);
        assert!(balls.len() > 3, "{balls:?}");
        assert_covers(&m, &balls, "box");
        // tighter than the one ball about the box
        let most = balls.iter().map(|b| b.radius).fold(0.0, f64::max);
        assert!(most < 0.2, "{most}");
    }

    #[test]
    fn outer_shapes_hold_their_polytopes() {
        let pose = Isometry3::new(Vector3::new(0.3, -0.2, 1.0), Vector3::new(0.2, 0.5, -0.1));
        for p in [
            Primitive::Box {
                size: [0.2, 0.4, 0.6],
            },
            Primitive::Cylinder {
                radius: 0.1,
                length: 0.5,
            },
            Primitive::Sphere { radius: 0.2 },
            Primitive::Cone {
                radius: 0.1,
                length: 0.3,
            },
        ] {
            let local = p.polytope().unwrap();
            let outer = Outer::of(Some(&p), &local, &pose);
            for v in &local.vertices {
                assert_eq!(outer.distance(&(pose * v)), 0.0, "{p:?} {v:?}");
            }
            // a point well outside is far
            let far = pose * Point3::new(0.0, 0.0, 2.0);
            assert!(outer.distance(&far) > 1.0, "{p:?}");
        }
    }
}
