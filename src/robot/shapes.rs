//! Primitive shapes of URDF collision elements and MoveIt collision objects, and the polytopes
//! that stand for them in the exact oracles.
//!
//! The exact oracles work on polyhedra (CHS §2). A curved primitive becomes a polytope that
//! **contains** it (circumscribed), so a motion certified free against the polytope is free
//! against the true shape; the price is a margin of at most `r·(1/cos(π/n) − 1)` (cylinder,
//! cone: 2.0 % of the radius at n = [`CIRCLE_SIDES`] = 16) and about 3 % of the radius for
//! the sphere ([`SPHERE_BANDS`] × [`CIRCLE_SIDES`] faces, scaled out until every face lies
//! outside the sphere). Boxes are exact. The independent checker ([`super::checker`]) uses
//! parry's exact shapes instead, so it can only be stricter in the right direction: a
//! polytope-certified configuration is free under the checker.
//!
//! A link mesh of thousands of triangles gets the same treatment ([`envelope`]): a convex
//! polytope of a few hundred faces that contains it, where one stands off it by little.

use crate::geometry::hull::convex_hull_3d;
use crate::geometry::{GeometryError, TriMesh};
use nalgebra::{Matrix3, Point3, Vector3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Sides of the polygon that circumscribes a circle (cylinder and cone caps, sphere
/// longitudes).
pub const CIRCLE_SIDES: usize = 16;

/// Latitude bands of the polytope that circumscribes a sphere.
pub const SPHERE_BANDS: usize = 8;

/// A primitive shape centred at its frame's origin (URDF and `shape_msgs/SolidPrimitive`
/// conventions: cylinder and cone along z, centred on the middle of the axis).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Primitive {
    /// A box of full side lengths `size`.
    Box {
        /// Side lengths along x, y, z.
        size: [f64; 3],
    },
    /// A cylinder along z.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Length along z.
        length: f64,
    },
    /// A sphere.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// A cone along z, base at `−length/2`, apex at `+length/2`.
    Cone {
        /// Radius of the base.
        radius: f64,
        /// Length along z.
        length: f64,
    },
}

impl Primitive {
    /// The closed, outward-oriented polytope that contains the shape (exact for boxes; see
    /// the module doc for the tessellation). Fails on sizes that are not positive and finite.
    pub fn polytope(&self) -> Result<TriMesh, GeometryError> {
        let positive = |v: f64, what: &'static str| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(GeometryError::NotPositive(what))
            }
        };
        match *self {
            Primitive::Box { size } => TriMesh::cuboid(size.map(|s| s / 2.0)),
            Primitive::Cylinder { radius, length } => prism(
                positive(radius, "cylinder radius")?,
                positive(length, "cylinder length")?,
                false,
            ),
            Primitive::Cone { radius, length } => prism(
                positive(radius, "cone radius")?,
                positive(length, "cone length")?,
                true,
            ),
            Primitive::Sphere { radius } => sphere(positive(radius, "sphere radius")?),
        }
    }

    /// Radius of the smallest ball about the frame origin that contains the true shape.
    pub fn bounding_radius(&self) -> f64 {
        match *self {
            Primitive::Box { size } => 0.5 * (size[0].hypot(size[1])).hypot(size[2]),
            Primitive::Cylinder { radius, length } | Primitive::Cone { radius, length } => {
                radius.hypot(length / 2.0)
            }
            Primitive::Sphere { radius } => radius,
        }
    }
}

/// A regular `CIRCLE_SIDES`-gon prism (or pyramid, `apex`) whose cap polygons circumscribe
/// the circle of `radius`: the apothem is the radius, the vertices lie at `r / cos(π/n)`.
fn prism(radius: f64, length: f64, apex: bool) -> Result<TriMesh, GeometryError> {
    let n = CIRCLE_SIDES;
    let outer = radius / (PI / n as f64).cos();
    let h = length / 2.0;
    let ring = |z: f64| -> Vec<Point3<f64>> {
        (0..n)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / n as f64;
                Point3::new(outer * a.cos(), outer * a.sin(), z)
            })
            .collect()
    };
    let mut vertices = ring(-h);
    let n32 = n as u32;
    let mut triangles = Vec::new();
    // bottom cap (seen from below: clockwise in xy)
    for i in 1..n32 - 1 {
        triangles.push([0, i + 1, i]);
    }
    if apex {
        vertices.push(Point3::new(0.0, 0.0, h));
        for i in 0..n32 {
            triangles.push([i, (i + 1) % n32, n32]);
        }
    } else {
        vertices.extend(ring(h));
        for i in 1..n32 - 1 {
            triangles.push([n32, n32 + i, n32 + i + 1]);
        }
        for i in 0..n32 {
            let j = (i + 1) % n32;
            triangles.push([i, j, n32 + j]);
            triangles.push([i, n32 + j, n32 + i]);
        }
    }
    TriMesh::new(vertices, triangles)
}

/// A UV polytope (`SPHERE_BANDS` latitude bands, `CIRCLE_SIDES` longitudes; its quads are
/// isosceles trapezoids, hence planar) scaled so that its nearest face plane lies at `radius`.
fn sphere(radius: f64) -> Result<TriMesh, GeometryError> {
    let (n, m) = (CIRCLE_SIDES as u32, SPHERE_BANDS as u32);
    let mut vertices = vec![Point3::new(0.0, 0.0, -1.0)];
    for band in 1..m {
        let polar = PI * band as f64 / m as f64; // from the south pole
        let (z, r) = (-polar.cos(), polar.sin());
        for i in 0..n {
            let a = 2.0 * PI * i as f64 / n as f64;
            vertices.push(Point3::new(r * a.cos(), r * a.sin(), z));
        }
    }
    vertices.push(Point3::new(0.0, 0.0, 1.0));
    let north = vertices.len() as u32 - 1;
    let at = |band: u32, i: u32| 1 + (band - 1) * n + i % n;
    let mut triangles = Vec::new();
    for i in 0..n {
        triangles.push([0, at(1, i + 1), at(1, i)]);
        triangles.push([north, at(m - 1, i), at(m - 1, i + 1)]);
    }
    for band in 1..m - 1 {
        for i in 0..n {
            let (a, b) = (at(band, i), at(band, i + 1));
            let (c, d) = (at(band + 1, i + 1), at(band + 1, i));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    let unit = TriMesh::new(vertices, triangles)?;
    // distance of the nearest face plane from the centre (all faces face outwards)
    let nearest = (0..unit.triangles.len())
        .map(|k| {
            let [a, b, c] = unit.triangle(k);
            let normal = (b - a).cross(&(c - a)).normalize();
            normal.dot(&a.coords)
        })
        .fold(f64::INFINITY, f64::min);
    let scale = radius / nearest;
    Ok(TriMesh {
        vertices: unit.vertices.iter().map(|v| v * scale).collect(),
        triangles: unit.triangles,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// Every face plane lies at least `r` from the axis/centre → the polytope contains the
    /// shape; and it is closed with positive volume.
    fn face_distances(m: &TriMesh) -> Vec<(Vector3<f64>, f64)> {
        (0..m.triangles.len())
            .map(|k| {
                let [a, b, c] = m.triangle(k);
                let normal = (b - a).cross(&(c - a)).normalize();
                (normal, normal.dot(&a.coords))
            })
            .collect()
    }

    #[test]
    fn sphere_polytope_contains_the_sphere_with_a_small_margin() {
        let r = 0.3;
        let m = Primitive::Sphere { radius: r }.polytope().unwrap();
        assert!(m.is_closed());
        let d = face_distances(&m);
        assert!(d.iter().all(|(_, h)| *h >= r * (1.0 - 1e-12)));
        // points on the true sphere in many directions are inside every half-space
        for k in 0..500 {
            let (u, v) = (k as f64 * 0.618_034 % 1.0, k as f64 / 500.0);
            let (theta, z) = (2.0 * PI * u, 2.0 * v - 1.0);
            let p = Vector3::new(
                (1.0 - z * z).sqrt() * theta.cos(),
                (1.0 - z * z).sqrt() * theta.sin(),
                z,
            ) * r;
            assert!(d.iter().all(|(n, h)| n.dot(&p) <= h + 1e-12));
        }
        let far = m
            .vertices
            .iter()
            .map(|v| v.coords.norm())
            .fold(0.0, f64::max);
        assert!(far < 1.1 * r, "margin {far}");
        assert!(m.volume() > 4.0 / 3.0 * PI * r.powi(3));
    }

    #[test]
    fn cylinder_and_cone_polytopes_contain_the_shape() {
        for (prim, apex) in [
            (
                Primitive::Cylinder {
                    radius: 0.05,
                    length: 0.35,
                },
                false,
            ),
            (
                Primitive::Cone {
                    radius: 0.05,
                    length: 0.35,
                },
                true,
            ),
        ] {
            let m = prim.polytope().unwrap();
            assert!(m.is_closed(), "{prim:?}");
            let d = face_distances(&m);
            // sample the true shape's boundary: rim circles and (cylinder) the side
            for k in 0..64 {
                let a = 2.0 * PI * k as f64 / 64.0;
                let rim = Vector3::new(0.05 * a.cos(), 0.05 * a.sin(), -0.175);
                assert!(d.iter().all(|(n, h)| n.dot(&rim) <= h + 1e-12));
                if !apex {
                    let top = Vector3::new(rim.x, rim.y, 0.175);
                    assert!(d.iter().all(|(n, h)| n.dot(&top) <= h + 1e-12));
                }
            }
            let exact = if apex {
                PI * 0.05f64.powi(2) * 0.35 / 3.0
            } else {
                PI * 0.05f64.powi(2) * 0.35
            };
            assert!(
                m.volume() > exact && m.volume() < 1.05 * exact,
                "{prim:?} {}",
                m.volume()
            );
        }
    }

    #[test]
    fn boxes_are_exact_and_bad_sizes_are_errors() {
        let m = Primitive::Box {
            size: [1.0, 2.0, 3.0],
        }
        .polytope()
        .unwrap();
        assert!((m.volume() - 6.0).abs() < 1e-12);
        for bad in [
            Primitive::Sphere { radius: 0.0 },
            Primitive::Cylinder {
                radius: f64::NAN,
                length: 1.0,
            },
            Primitive::Box {
                size: [1.0, -1.0, 1.0],
            },
        ] {
            assert!(bad.polytope().is_err());
        }
    }
}

/// Meshes of more triangles than this are enveloped ([`envelope`]).
pub const ENVELOPE_ABOVE: usize = 4_000;

/// Directions of the enveloping polytope's half-spaces (a Fibonacci sphere).
pub const ENVELOPE_DIRECTIONS: usize = 162;

/// How far an envelope may stand off its mesh anywhere, relative to the mesh's bounding
/// radius (half its bounding box's diagonal).
pub const ENVELOPE_GAP: f64 = 0.25;

/// A convex polytope standing for a link's collision mesh in the exact oracle.
#[derive(Clone, Debug)]
pub struct Envelope {
    /// The polytope: it contains every vertex of the mesh, so the mesh.
    pub polytope: TriMesh,
    /// The largest distance from the polytope's surface (its face centroids and edge
    /// midpoints) to the mesh's.
    pub gap: f64,
}

/// The envelope of a mesh of more than [`ENVELOPE_ABOVE`] triangles: the intersection of the
/// half-spaces bounding it in [`ENVELOPE_DIRECTIONS`] directions (a discrete oriented
/// polytope of a few hundred faces), or, where that stands off the mesh by more than
/// [`ENVELOPE_GAP`] of its radius, its convex hull; `None` where the hull does too, or for a
/// smaller mesh. Each candidate is checked to contain every vertex of the mesh.
///
/// Why: a sweep costs in proportion to the faces it meets, and a polytope that contains the
/// mesh certifies what it certifies against the mesh (as circumscribed primitives do; the
/// independent checker keeps the mesh). VAMP's UR5 carries a Robotiq gripper base and a
/// force–torque sensor of 40 112 and 43 473 triangles, a housing and a puck: enveloped by 564
/// and 636 triangles (gaps 17 and 11 mm), its first 20 problems per family went from 110 to
/// 133 and 131 solved of 140 at 5 s in two runs (the *ur5-fetch* results).
pub fn envelope(mesh: &TriMesh) -> Option<Envelope> {
    if mesh.triangles.len() <= ENVELOPE_ABOVE {
        return None;
    }
    let (lo, hi) = mesh.aabb();
    let most = ENVELOPE_GAP * (hi - lo).norm() / 2.0;
    let surface =
        parry3d_f64::shape::TriMesh::new(mesh.vertices.clone(), mesh.triangles.clone()).ok()?;
    // the hull (thousands of faces on a round part) only where the oriented polytope is too loose
    let candidates: [fn(&TriMesh) -> Option<TriMesh>; 2] =
        [oriented_polytope, |m| convex_hull_3d(&m.vertices).ok()];
    candidates
        .into_iter()
        .filter_map(|make| make(mesh))
        .filter(|p| contains_all(p, &mesh.vertices))
        .map(|polytope| Envelope {
            gap: gap(&polytope, &surface),
            polytope,
        })
        .find(|e| e.gap <= most)
}

/// The intersection of the half-spaces `n · (x − c) ≤ h(n)` that bound `mesh`'s vertices in
/// [`ENVELOPE_DIRECTIONS`] directions `n` about its box's centre `c`. Its corners are the
/// facets of the polar dual, the hull of the points `n / h(n)`.
fn oriented_polytope(mesh: &TriMesh) -> Option<TriMesh> {
    let (lo, hi) = mesh.aabb();
    let c = nalgebra::center(&lo, &hi);
    let k = ENVELOPE_DIRECTIONS;
    let golden = PI * (3.0 - 5f64.sqrt());
    let mut dual = Vec::with_capacity(k);
    for i in 0..k {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / k as f64;
        let r = (1.0 - z * z).sqrt();
        let t = golden * i as f64;
        let n = Vector3::new(r * t.cos(), r * t.sin(), z);
        let h = mesh
            .vertices
            .iter()
            .map(|p| n.dot(&(p - c)))
            .fold(f64::NEG_INFINITY, f64::max);
        // a flat mesh, or one not around its box's centre in some direction: no polytope
        if h <= 1e-9 * (hi - lo).norm() {
            return None;
        }
        dual.push(Point3::from(n / h));
    }
    let (points, facets) = parry3d_f64::transformation::try_convex_hull(&dual).ok()?;
    let mut corners = Vec::with_capacity(facets.len());
    for f in &facets {
        let [a, b, d] = f.map(|i| points[i as usize].coords.transpose());
        let x = Matrix3::from_rows(&[a, b, d])
            .lu()
            .solve(&Vector3::repeat(1.0))?;
        corners.push(Point3::from(x + c.coords));
    }
    convex_hull_3d(&corners).ok()
}

/// Whether every point lies inside (or on) every face plane of the convex, outward `polytope`.
fn contains_all(polytope: &TriMesh, points: &[Point3<f64>]) -> bool {
    let (lo, hi) = polytope.aabb();
    let slack = 1e-9 * (hi - lo).norm();
    (0..polytope.triangles.len()).all(|i| {
        let [a, b, c] = polytope.triangle(i);
        let n = (b - a).cross(&(c - a));
        let norm = n.norm();
        norm == 0.0 || points.iter().all(|p| n.dot(&(p - a)) <= slack * norm)
    })
}

/// The largest distance from a face centroid or edge midpoint of `polytope` to `surface`.
fn gap(polytope: &TriMesh, surface: &parry3d_f64::shape::TriMesh) -> f64 {
    use parry3d_f64::query::PointQuery;
    let mut most = 0.0f64;
    for i in 0..polytope.triangles.len() {
        let [a, b, c] = polytope.triangle(i);
        for p in [
            Point3::from((a.coords + b.coords + c.coords) / 3.0),
            nalgebra::center(&a, &b),
            nalgebra::center(&b, &c),
            nalgebra::center(&c, &a),
        ] {
            most = most.max(surface.distance_to_local_point(&p, false));
        }
    }
    most
}
