//! Mesh files: Wavefront OBJ, STL (ASCII and binary) and Collada, read into a [`TriMesh`]; and
//! the checked reads of every input file (scene, mesh, robot description). Below both the
//! scenes ([`crate::scene`]) and the robots ([`crate::robot`]) that load meshes.
//!
//! Every loader returns the faces as triangles in the file's frame (for Collada: the frame
//! OMPL.app sees, see [`collada`]) with vertices of equal position welded, so that
//! [`TriMesh::is_closed`] can tell a solid from a surface; triangles of zero area are dropped.
//! Lines and points are not faces and are ignored (SketchUp writes its edges as OBJ `l`
//! elements). Nothing here panics on a malformed file: every failure is a [`MeshError`]
//! naming the mesh file.

pub mod collada;
mod input;
mod weld;

use input::open_input;
pub use input::MeshError;
pub(crate) use input::{read_input_text, read_input_text_within};
use weld::Welder;

use crate::geometry::TriMesh;
use nalgebra::Point3;
use std::path::Path;

/// Reads a mesh, choosing the format by the file extension (`obj`, `stl`, `dae`; any case).
pub fn load_mesh(path: &Path) -> Result<TriMesh, MeshError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => load_obj(path),
        Some("stl") => load_stl(path),
        Some("dae") => Ok(collada::load_collada(path)?.mesh),
        _ => Err(MeshError::Parse {
            path: path.to_path_buf(),
            message: "unknown mesh format; expected a .obj, .stl or .dae file".into(),
        }),
    }
}

/// Whether a path names a Collada file.
pub(crate) fn is_dae(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("dae"))
}

/// Mean of the distinct vertex positions of a mesh (those used by a triangle): the reference
/// point `center = "mean"` chooses for OBJ and STL robots and inline shapes.
pub fn vertex_mean(mesh: &TriMesh) -> Point3<f64> {
    let mut used = vec![false; mesh.vertices.len()];
    mesh.triangles
        .iter()
        .flatten()
        .for_each(|&k| used[k as usize] = true);
    let (sum, n) = mesh
        .vertices
        .iter()
        .zip(&used)
        .filter(|(_, u)| **u)
        .fold((nalgebra::Vector3::zeros(), 0usize), |(s, n), (v, _)| {
            (s + v.coords, n + 1)
        });
    Point3::from(sum / n.max(1) as f64)
}

/// Reads a Wavefront OBJ file: faces triangulated as fans, `l` and `p` elements ignored,
/// materials not read.
pub fn load_obj(path: &Path) -> Result<TriMesh, MeshError> {
    let file = open_input(path)?;
    let options = tobj::LoadOptions {
        triangulate: true,
        ignore_lines: true,
        ignore_points: true,
        single_index: false,
    };
    let mut reader = std::io::BufReader::new(file);
    let parse = |message: String| MeshError::Parse {
        path: path.to_path_buf(),
        message,
    };
    let parsed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut reader, &options, |_| {
            Ok((Vec::new(), Default::default()))
        })
    }))
    .map_err(|_| parse("not a readable OBJ file (the parser gave up)".into()))?;
    let (models, _) = parsed.map_err(|e| parse(format!("not a valid OBJ file: {e}")))?;
    let mut weld = Welder::default();
    for model in &models {
        let m = &model.mesh;
        if m.indices.len() % 3 != 0 {
            return Err(parse("a face is not a triangle after triangulation".into()));
        }
        for face in m.indices.chunks_exact(3) {
            let mut t = [0u32; 3];
            for (slot, &i) in t.iter_mut().zip(face) {
                let i = i as usize;
                let p = m
                    .positions
                    .get(3 * i..3 * i + 3)
                    .ok_or_else(|| parse(format!("face refers to missing vertex {}", i + 1)))?;
                *slot = weld.vertex([p[0], p[1], p[2]].map(f64::from));
            }
            weld.triangles.push(t);
        }
    }
    weld.finish(path)
}

/// Reads an STL file, ASCII or binary.
pub fn load_stl(path: &Path) -> Result<TriMesh, MeshError> {
    let mut file = open_input(path)?;
    let parse = |message: String| MeshError::Parse {
        path: path.to_path_buf(),
        message,
    };
    let parsed =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| stl_io::read_stl(&mut file)))
            .map_err(|_| parse("not a readable STL file (the parser gave up)".into()))?;
    let stl = parsed.map_err(|e| parse(format!("not a valid STL file: {e}")))?;
    let mut weld = Welder::default();
    for face in &stl.faces {
        let mut t = [0u32; 3];
        for (slot, &i) in t.iter_mut().zip(&face.vertices) {
            let v = stl
                .vertices
                .get(i)
                .ok_or_else(|| parse(format!("face refers to missing vertex {i}")))?;
            *slot = weld.vertex([v[0] as f64, v[1] as f64, v[2] as f64]);
        }
        weld.triangles.push(t);
    }
    weld.finish(path)
}
