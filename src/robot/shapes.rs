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

use crate::geometry::{GeometryError, TriMesh};
use nalgebra::Point3;
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
