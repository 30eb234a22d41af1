//! What can be wrong with a scene, and the checked reads of its input files.

use crate::geometry::GeometryError;
use crate::mesh_io::MeshError;
use crate::safe_file::FileError;
use crate::space::{Config, SpaceError};
use std::path::{Path, PathBuf};

/// Everything that can be wrong with a scene or a configuration asked of it.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file cannot be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file (a path written with `--path-out`) cannot be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not a regular file (a device, FIFO, directory), or too large to be a scene.
    #[error(transparent)]
    File(FileError),
    /// The file is not valid TOML / INI / mesh syntax.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What the parser said.
        message: String,
    },
    /// Well-formed but meaningless (unknown space kind, negative radius, wrong dimension …).
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A mesh that cannot be used.
    #[error("mesh {path}: {source}")]
    Geometry {
        /// The mesh file (or the scene file for inline shapes).
        path: PathBuf,
        /// What is wrong.
        source: GeometryError,
    },
    /// A configuration of the wrong shape.
    #[error("{what}: {source}")]
    Config {
        /// Which configuration ("start of query 2" …).
        what: String,
        /// What is wrong.
        source: SpaceError,
    },
    /// A configuration outside the bounds.
    #[error("{what} {} lies outside the scene's bounds", crate::short::config(.config))]
    OutOfBounds {
        /// Which configuration.
        what: String,
        /// The configuration.
        config: Config,
    },
    /// A configuration in collision.
    #[error("{what} {} is in collision", crate::short::config(.config))]
    InCollision {
        /// Which configuration.
        what: String,
        /// The configuration.
        config: Config,
    },
}

/// A mesh's (or another input file's) failure as the scene's, variant for variant.
impl From<MeshError> for SceneError {
    fn from(e: MeshError) -> SceneError {
        match e {
            MeshError::Io { path, source } => SceneError::Io { path, source },
            MeshError::File(e) => SceneError::File(e),
            MeshError::Parse { path, message } => SceneError::Parse { path, message },
            MeshError::Geometry { path, source } => SceneError::Geometry { path, source },
        }
    }
}

/// The text of an input file, if it is a regular file of at most
/// [`crate::limits::MAX_TEXT_FILE_BYTES`]: `/dev/zero` or a FIFO would otherwise be read until
/// memory runs out, or block for ever.
pub(crate) fn read_input_text(path: &Path) -> Result<String, SceneError> {
    Ok(crate::mesh_io::read_input_text(path)?)
}

/// The text of an input file of at most `limit` bytes, its size checked before it is read.
pub(crate) fn read_input_text_within(path: &Path, limit: u64) -> Result<String, SceneError> {
    Ok(crate::mesh_io::read_input_text_within(path, limit)?)
}
