//! Mesh files for scenes: the loaders of [`crate::mesh_io`] with their failures as
//! [`SceneError`]s.

use super::error::SceneError;
use crate::geometry::TriMesh;
pub(crate) use crate::mesh_io::is_dae;
pub use crate::mesh_io::vertex_mean;
use std::path::Path;

/// Reads a mesh, choosing the format by the file extension (`obj`, `stl`, `dae`; any case).
pub fn load_mesh(path: &Path) -> Result<TriMesh, SceneError> {
    Ok(crate::mesh_io::load_mesh(path)?)
}

/// Reads a Wavefront OBJ file: faces triangulated as fans, `l` and `p` elements ignored,
/// materials not read.
pub fn load_obj(path: &Path) -> Result<TriMesh, SceneError> {
    Ok(crate::mesh_io::load_obj(path)?)
}

/// Reads an STL file, ASCII or binary.
pub fn load_stl(path: &Path) -> Result<TriMesh, SceneError> {
    Ok(crate::mesh_io::load_stl(path)?)
}

/// The warning a scene carries for a mesh that does not bound a solid.
pub(crate) fn open_mesh_warning(file: &str) -> String {
    format!(
        "mesh {file} is not closed: containment cannot be decided, only surface contact is \
         detected"
    )
}
