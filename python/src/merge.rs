//! Roadmaps learnt apart: merging them with the interpreter released, and pickling scenes and
//! roadmaps so that Ray or `multiprocessing` can ship them between processes and machines.

use super::interrupt::interruptible;
use super::{one_line, RoadmapError, SceneData, ViaroadError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::path::PathBuf;
use std::sync::Arc;
use viaroad::roadmap::{Learner, MergeError, Roadmap as RustRoadmap};

/// How a scene was loaded, so that unpickling loads it again: a scene is its files (meshes,
/// URDFs), not bytes a process can hand over.
pub(crate) enum SceneOrigin {
    /// `Scene.load(path)`.
    File(PathBuf),
    /// `Scene.load_moveit(robot, scene, request)`.
    MoveIt(PathBuf, PathBuf, PathBuf),
}

/// `(loader, args)` for `Scene.__reduce__`: the package's module-level loaders, which pickle by
/// name.
pub(crate) fn reduce_scene<'py>(
    py: Python<'py>,
    origin: &SceneOrigin,
) -> PyResult<Bound<'py, PyTuple>> {
    let viaroad = py.import("viaroad")?;
    let text = |p: &PathBuf| p.to_string_lossy().into_owned();
    let (loader, args) = match origin {
        SceneOrigin::File(p) => (viaroad.getattr("_scene_from_file")?, vec![text(p)]),
        SceneOrigin::MoveIt(r, s, q) => (
            viaroad.getattr("_scene_from_moveit")?,
            vec![text(r), text(s), text(q)],
        ),
    };
    PyTuple::new(py, [loader, PyTuple::new(py, args)?.into_any()])
}

/// Merges `parts` (and `base`, which keeps its indices) for `scene` with the local method the
/// first of them was learnt with, the interpreter released, Ctrl-C and `time` stopping it.
pub(crate) fn merge(
    py: Python<'_>,
    scene: &Arc<SceneData>,
    base: Option<Arc<RustRoadmap>>,
    parts: Vec<Arc<RustRoadmap>>,
    time: Option<f64>,
) -> PyResult<RustRoadmap> {
    let time = match time {
        None => None,
        Some(t) => Some(viaroad::limits::duration_from_secs(t).ok_or_else(|| {
            super::LearnError::new_err(format!(
                "time must be a positive number of seconds of at most {:e}, got {t:?}",
                viaroad::limits::MAX_SECONDS
            ))
        })?),
    };
    let Some(first) = base.as_ref().or(parts.first()) else {
        return Err(RoadmapError::new_err(MergeError::NoParts.to_string()));
    };
    let spec = first.header().local_spec.clone();
    let merged = interruptible(py, |watch| {
        let method = spec.build();
        let learner = Learner::for_scene(&scene.scene, scene.oracle.as_ref(), method.as_ref())
            .with_attempt_cap(time.map(Learner::attempt_cap_for));
        let refs: Vec<&RustRoadmap> = parts.iter().map(|p| p.as_ref()).collect();
        learner.merge(
            base.as_deref(),
            &refs,
            &watch.deadline().within(time),
            &mut |_| {},
        )
    })?;
    merged.map(|m| m.roadmap).map_err(|e| match e {
        MergeError::Oracle(_) | MergeError::Malformed(_) => ViaroadError::new_err(one_line(&e)),
        _ => RoadmapError::new_err(one_line(&e)),
    })
}
