//! OMPL.app `.cfg` problems. (In progress.)
use super::{Scene, SceneError};
use std::path::Path;

/// Loads an OMPL.app problem.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    Err(SceneError::Invalid {
        path: path.into(),
        message: "OMPL .cfg loading not yet".into(),
    })
}
