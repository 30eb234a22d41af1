//! Triangle meshes (a boundary representation with triangular, hence convex, faces).

use super::GeometryError;
use crate::fast_hash::FastMap;
use nalgebra::{Point3, Vector3};

/// A triangle mesh: vertices and counter-clockwise (seen from outside) triangles.
///
/// Meshes loaded from OMPL.app's files are triangle *soups*: double-sided, open, non-manifold.
/// Such a mesh is a surface only; [`TriMesh::is_closed`] tells whether it bounds a solid, so
/// that containment (one body wholly inside the other) can be decided (CHS §2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Point3<f64>>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Validates indices and coordinates and drops triangles of zero area.
    pub fn new(
        vertices: Vec<Point3<f64>>,
        triangles: Vec<[u32; 3]>,
    ) -> Result<TriMesh, GeometryError> {
        if let Some(i) = vertices
            .iter()
            .position(|v| !v.coords.iter().all(|c| c.is_finite()))
        {
            return Err(GeometryError::NotFinite(i));
        }
        for (face, t) in triangles.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= vertices.len()) {
                return Err(GeometryError::BadIndex {
                    face,
                    index: index as usize,
                    count: vertices.len(),
                });
            }
        }
        let triangles: Vec<[u32; 3]> = triangles
            .into_iter()
            .filter(|t| {
                let [a, b, c] = t.map(|i| vertices[i as usize]);
                (b - a).cross(&(c - a)).norm_squared() > 0.0
            })
            .collect();
        if triangles.is_empty() {
            return Err(GeometryError::Empty);
        }
        Ok(TriMesh {
            vertices,
            triangles,
        })
    }

    /// An axis-aligned box centred at the origin, outward-oriented and closed.
    pub fn cuboid(half_extents: [f64; 3]) -> Result<TriMesh, GeometryError> {
        if !half_extents.iter().all(|h| h.is_finite() && *h > 0.0) {
            return Err(GeometryError::NotPositive("box half extents"));
        }
        let [x, y, z] = half_extents;
        let vertices = (0..8)
            .map(|i| {
                Point3::new(
                    if i & 1 == 0 { -x } else { x },
                    if i & 2 == 0 { -y } else { y },
                    if i & 4 == 0 { -z } else { z },
                )
            })
            .collect();
        let triangles = vec![
            [0, 2, 3],
            [0, 3, 1], // -z
            [4, 5, 7],
            [4, 7, 6], // +z
            [0, 1, 5],
            [0, 5, 4], // -y
            [2, 6, 7],
            [2, 7, 3], // +y
            [0, 4, 6],
            [0, 6, 2], // -x
            [1, 3, 7],
            [1, 7, 5], // +x
        ];
        TriMesh::new(vertices, triangles)
    }

    /// The mesh moved by `offset`.
    pub fn translated(mut self, offset: Vector3<f64>) -> TriMesh {
        self.vertices.iter_mut().for_each(|v| *v += offset);
        self
    }

    /// The three corners of triangle `i`.
    pub fn triangle(&self, i: usize) -> [Point3<f64>; 3] {
        self.triangles[i].map(|k| self.vertices[k as usize])
    }

    /// Axis-aligned bounding box `(min, max)` of the vertices used by triangles.
    pub fn aabb(&self) -> (Point3<f64>, Point3<f64>) {
        let mut lo = Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY);
        let mut hi = -lo;
        for t in &self.triangles {
            for &k in t {
                let v = self.vertices[k as usize];
                lo = lo.inf(&v);
                hi = hi.sup(&v);
            }
        }
        (lo, hi)
    }

    /// Largest distance of a vertex from the origin (the body frame's reference point).
    pub fn radius(&self) -> f64 {
        self.triangles
            .iter()
            .flatten()
            .map(|&k| self.vertices[k as usize].coords.norm())
            .fold(0.0, f64::max)
    }

    /// Signed volume enclosed (divergence theorem over the triangles): positive for a closed
    /// mesh with outward (counter-clockwise seen from outside) triangles; meaningless for an
    /// open one.
    pub fn volume(&self) -> f64 {
        (0..self.triangles.len())
            .map(|i| {
                let [a, b, c] = self.triangle(i);
                a.coords.dot(&b.coords.cross(&c.coords)) / 6.0
            })
            .sum()
    }

    /// Whether the mesh bounds a solid: after setting aside every face that occurs with both
    /// windings (a double-sided sheet, as SketchUp exports every face, bounds nothing), some
    /// faces remain and every oriented edge among them is matched by its reverse as often as it
    /// occurs. Open surfaces and double-sided soups fail this.
    pub fn is_closed(&self) -> bool {
        // faces by their sorted vertex triple: +1 per counter-clockwise (even permutation of the
        // sorted order) occurrence, −1 per clockwise one
        let mut faces: FastMap<[u32; 3], (u32, u32)> = FastMap::default();
        for t in &self.triangles {
            let mut s = *t;
            s.sort_unstable();
            let even = [s, [s[1], s[2], s[0]], [s[2], s[0], s[1]]].contains(t);
            let e = faces.entry(s).or_default();
            if even {
                e.0 += 1;
            } else {
                e.1 += 1;
            }
        }
        let mut balance: FastMap<(u32, u32), i64> = FastMap::default();
        let mut remaining = 0usize;
        for t in &self.triangles {
            let mut s = *t;
            s.sort_unstable();
            let (ccw, cw) = faces[&s];
            if ccw > 0 && cw > 0 {
                continue;
            }
            remaining += 1;
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                *balance.entry(key).or_default() += if a < b { 1 } else { -1 };
            }
        }
        remaining > 0 && balance.values().all(|&v| v == 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuboid_is_closed_and_outward() {
        let m = TriMesh::cuboid([1.0, 2.0, 3.0]).unwrap();
        assert!(m.is_closed());
        // outward: the signed volume is positive
        assert!((m.volume() - 48.0).abs() < 1e-12);
    }

    #[test]
    fn double_sided_sheets_are_not_closed() {
        let sheet = TriMesh::new(
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(1.0, 1.0, 0.0),
            ],
            vec![[0, 1, 2], [1, 3, 2], [0, 2, 1], [1, 2, 3]],
        )
        .unwrap();
        assert!(!sheet.is_closed());
        // a closed box stays closed when a double-sided sheet is added to it
        let cube = TriMesh::cuboid([1.0; 3]).unwrap();
        let mut both = cube.clone();
        both.triangles.extend([[0, 1, 2], [0, 2, 1]]);
        assert!(both.is_closed());
        // a box with one face missing is open
        let mut open = cube;
        open.triangles.truncate(10);
        assert!(!open.is_closed());
    }

    #[test]
    fn bad_index_is_an_error() {
        let e = TriMesh::new(vec![Point3::origin(); 3], vec![[0, 1, 7]]).unwrap_err();
        assert!(matches!(e, GeometryError::BadIndex { index: 7, .. }));
    }
}
