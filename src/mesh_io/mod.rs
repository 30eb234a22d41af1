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

use crate::fast_hash::FastMap;
use crate::geometry::{GeometryError, TriMesh};
use crate::safe_file::FileError;
use nalgebra::Point3;
use std::path::{Path, PathBuf};

/// Why a mesh, or another input file read with the same checks (a URDF, an SRDF), cannot be
/// used. A scene's [`crate::scene::SceneError`] and a robot's [`crate::robot::RobotError`] carry
/// it with the same message.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file cannot be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not a regular file (a device, FIFO, directory), or too large to be read.
    #[error(transparent)]
    File(FileError),
    /// The file is not valid mesh syntax.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What the parser said.
        message: String,
    },
    /// A mesh that cannot be used.
    #[error("mesh {path}: {source}")]
    Geometry {
        /// The mesh file (or the robot description for a primitive shape).
        path: PathBuf,
        /// What is wrong.
        source: GeometryError,
    },
}

/// Keeps I/O failures in [`MeshError::Io`], the rest (special or huge files) in
/// [`MeshError::File`].
fn input_error(e: FileError) -> MeshError {
    match e {
        FileError::Io { path, source, .. } => MeshError::Io { path, source },
        other => MeshError::File(other),
    }
}

/// Opens an input file (scene, mesh, query list) if it is a regular file of at most
/// [`crate::limits::MAX_TEXT_FILE_BYTES`]: `/dev/zero` or a FIFO would otherwise be read until
/// memory runs out, or block for ever.
pub(crate) fn open_input(path: &Path) -> Result<std::fs::File, MeshError> {
    let (file, size) = crate::safe_file::open_regular(path).map_err(input_error)?;
    let limit = crate::limits::MAX_TEXT_FILE_BYTES;
    if size > limit {
        return Err(MeshError::File(FileError::TooLarge {
            path: path.to_path_buf(),
            size,
            limit,
        }));
    }
    Ok(file)
}

/// The bytes of an input file ([`open_input`]'s checks).
pub(crate) fn read_input(path: &Path) -> Result<Vec<u8>, MeshError> {
    crate::safe_file::read_regular(path, crate::limits::MAX_TEXT_FILE_BYTES).map_err(input_error)
}

/// The text of an input file ([`open_input`]'s checks).
pub(crate) fn read_input_text(path: &Path) -> Result<String, MeshError> {
    crate::safe_file::read_text(path).map_err(input_error)
}

/// The text of an input file of at most `limit` bytes, its size checked before it is read.
pub(crate) fn read_input_text_within(path: &Path, limit: u64) -> Result<String, MeshError> {
    crate::safe_file::read_text_within(path, limit).map_err(input_error)
}

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
