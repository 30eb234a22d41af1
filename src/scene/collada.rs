//! Collada (`.dae`) meshes for scenes, read the way OMPL.app reads them through assimp
//! ([`crate::mesh_io::collada`]), with their failures as [`SceneError`]s.

use super::error::SceneError;
pub use crate::mesh_io::collada::ColladaMesh;
use std::path::Path;

/// Reads a Collada file (see [`crate::mesh_io::collada`] for the conventions).
pub fn load_collada(path: &Path) -> Result<ColladaMesh, SceneError> {
    Ok(crate::mesh_io::collada::load_collada(path)?)
}
