//! Footprints of OMPL.app's 2D meshes: a prism standing on the plane becomes the triangles of
//! its outline.
//!
//! OMPL.app's planar problems ship robot and environment as 3D meshes — prisms extruded along
//! +z from z ≈ 0, stored as double-sided triangle soups — and check them in 3D. Two such prisms
//! whose z-ranges overlap touch iff their projections onto the plane do, and the projection of
//! a solid is the union of the projections of its faces; faces standing on edge (the walls)
//! project to segments that already bound the others, so they are dropped.

use crate::geometry::{Polygon, TriMesh};
use nalgebra::Point2;
use std::collections::HashSet;

/// Triangles whose projection has less than this fraction of the squared size of the mesh's
/// footprint box count as standing on edge.
const NEGLIGIBLE_AREA: f64 = 1e-12;

/// The counter-clockwise triangles of the xy-projection of `mesh`: every triangle whose
/// projection has non-negligible area, once, whatever its winding (double-sided soups list
/// each face twice). Their union is the mesh's footprint; pass them to
/// [`Polygons::new`](crate::oracle::polygons::Polygons::new) as robot parts or obstacles.
pub fn footprint_polygons(mesh: &TriMesh) -> Vec<Polygon> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for v in &mesh.vertices {
        lo = [lo[0].min(v.x), lo[1].min(v.y)];
        hi = [hi[0].max(v.x), hi[1].max(v.y)];
    }
    let size2 = (hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2);
    let min_area2 = NEGLIGIBLE_AREA * size2;
    let mut seen: HashSet<[u64; 6]> = HashSet::new();
    let mut out = Vec::new();
    for t in &mesh.triangles {
        let Some(corners) = t
            .iter()
            .map(|&i| {
                mesh.vertices
                    .get(i as usize)
                    .map(|v| [v.x + 0.0, v.y + 0.0])
            })
            .collect::<Option<Vec<[f64; 2]>>>()
        else {
            continue;
        };
        let (a, mut b, mut c) = (corners[0], corners[1], corners[2]);
        let area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area2.is_nan() || area2.abs() <= min_area2 {
            continue;
        }
        if area2 < 0.0 {
            std::mem::swap(&mut b, &mut c);
        }
        // the same triangle whatever its first corner: start at the smallest corner
        let mut ring = [a, b, c];
        let first = (0..3)
            .min_by(|&i, &j| {
                let (p, q) = (ring[i], ring[j]);
                p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
            })
            .unwrap_or(0);
        ring.rotate_left(first);
        let key = [
            ring[0][0].to_bits(),
            ring[0][1].to_bits(),
            ring[1][0].to_bits(),
            ring[1][1].to_bits(),
            ring[2][0].to_bits(),
            ring[2][1].to_bits(),
        ];
        if !seen.insert(key) {
            continue;
        }
        let vertices = ring.iter().map(|p| Point2::new(p[0], p[1])).collect();
        if let Ok(p) = Polygon::new(vertices) {
            out.push(p);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point3, Vector3};

    #[test]
    fn a_double_sided_box_prism_becomes_two_triangles() {
        // a closed box standing on z = 0, every face listed twice (both windings)
        let mesh = TriMesh::cuboid([2.0, 1.0, 0.5])
            .unwrap()
            .translated(Vector3::new(3.0, 0.0, 0.5));
        let mut tris = mesh.triangles.clone();
        tris.extend(mesh.triangles.iter().map(|t| [t[0], t[2], t[1]]));
        let soup = TriMesh::new(mesh.vertices.clone(), tris).unwrap();
        let fp = footprint_polygons(&soup);
        assert_eq!(fp.len(), 2, "{fp:?}");
        let area: f64 = fp.iter().map(Polygon::area).sum();
        assert!((area - 8.0).abs() < 1e-12);
        for p in &fp {
            assert!(p.area() > 0.0);
            for v in &p.vertices {
                assert!((1.0..=5.0).contains(&v.x) && (-1.0..=1.0).contains(&v.y));
            }
        }
    }

    #[test]
    fn walls_are_dropped() {
        let v = vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 1.0),
        ];
        let mesh = TriMesh::new(v, vec![[0, 1, 2]]).unwrap();
        assert!(footprint_polygons(&mesh).is_empty());
    }
}
