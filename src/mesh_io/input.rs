//! The checked reads of every input file (scene, mesh, robot description): regular files of
//! bounded size only, and what goes wrong as a [`MeshError`].

use crate::geometry::GeometryError;
use crate::safe_file::FileError;
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
