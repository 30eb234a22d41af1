//! Welding a mesh's triangles: equal positions become one vertex, so that a closed solid can
//! be told from a surface.

use super::input::MeshError;
use crate::fast_hash::FastMap;
use crate::geometry::TriMesh;
use nalgebra::Point3;
use std::path::Path;

/// Collects triangles, giving equal positions one vertex.
#[derive(Default)]
pub(crate) struct Welder {
    vertices: Vec<Point3<f64>>,
    index: FastMap<[u64; 3], u32>,
    pub(crate) triangles: Vec<[u32; 3]>,
}

impl Welder {
    pub(crate) fn vertex(&mut self, p: [f64; 3]) -> u32 {
        // +0.0 turns −0.0 into 0.0, so that both weld together
        let key = p.map(|c| (c + 0.0).to_bits());
        let next = self.vertices.len() as u32;
        *self.index.entry(key).or_insert_with(|| {
            self.vertices.push(Point3::from(p));
            next
        })
    }

    pub(crate) fn finish(self, path: &Path) -> Result<TriMesh, MeshError> {
        TriMesh::new(self.vertices, self.triangles).map_err(|source| MeshError::Geometry {
            path: path.to_path_buf(),
            source,
        })
    }
}
