//! `Scene.certify`, `Scene.repair` and `Scene.load_moveit`: another planner's paths proved free
//! segment by segment, or located where they collide, and repaired
//! ([`viaroad::certify`]).

use super::interrupt::interruptible;
use super::{
    configs, file_path, json_to_py, one_line, path_array, MotionError, QueryError, Scene,
    SceneData, SceneError,
};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use std::time::Duration;
use viaroad::certify::{repair, Certificate, Certifier, MotionModel, RepairOptions, Verdict};
use viaroad::limits::MAX_QUERIES;

/// The motion model named by `motion`.
fn model(motion: &str) -> PyResult<MotionModel> {
    motion
        .parse()
        .map_err(pyo3::exceptions::PyValueError::new_err)
}

fn seconds(time: Option<f64>) -> PyResult<Option<Duration>> {
    time.map(|t| {
        Duration::try_from_secs_f64(t).map_err(|_| {
            pyo3::exceptions::PyValueError::new_err(format!("time {t} is not a number of seconds"))
        })
    })
    .transpose()
}

/// A certificate as a dict: the JSON fields, plus `codes` (0 free, 1 collides, 2 undecided
/// per segment) and `witnesses` (one row per segment, NaN where none) as numpy arrays.
fn certificate_dict<'py>(
    py: Python<'py>,
    c: &Certificate,
    dof: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let value = serde_json::json!({
        "status": c.status(),
        "model": c.model,
        "segments": c.segments,
        "defects": c.defects,
        "calls": c.calls,
        "seconds": c.seconds,
    });
    let d = json_to_py(py, &value)?
        .into_bound(py)
        .cast_into::<PyDict>()?;
    let codes: Vec<i64> = c
        .segments
        .iter()
        .map(|v| match v {
            Verdict::Free => 0,
            Verdict::Collides(_) => 1,
            Verdict::Undecided { .. } => 2,
        })
        .collect();
    let mut witnesses = vec![f64::NAN; c.segments.len() * dof];
    for (i, v) in c.segments.iter().enumerate() {
        if let Verdict::Collides(col) = v {
            witnesses[i * dof..(i + 1) * dof].copy_from_slice(&col.witness);
        }
    }
    d.set_item("codes", PyArray1::from_vec(py, codes))?;
    d.set_item(
        "witnesses",
        PyArray1::from_vec(py, witnesses).reshape([c.segments.len(), dof])?,
    )?;
    Ok(d)
}

/// `Scene.certify`.
pub(super) fn certify<'py>(
    scene: &Scene,
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
    motion: &str,
    time: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let path = configs(
        py,
        "path",
        path,
        (
            MAX_QUERIES,
            "a path longer than the most queries answered at once",
        ),
    )?;
    let model = model(motion)?;
    let time = seconds(time)?;
    let data = scene.data.clone();
    let cert = interruptible(py, move |w| {
        let c = Certifier::new(&data.scene, model)?;
        c.certify(&path, &w.deadline().within(time))
    })?
    .map_err(|e| QueryError::new_err(one_line(&e)))?;
    certificate_dict(py, &cert, scene.data.scene.space.dim())
}

/// `Scene.repair`: the fixed path and the report (with the fixed path's certificate).
pub(super) fn repair_path<'py>(
    scene: &Scene,
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
    time: f64,
    motion: &str,
) -> PyResult<(Py<numpy::PyArray2<f64>>, Bound<'py, PyDict>)> {
    let path = configs(
        py,
        "path",
        path,
        (
            MAX_QUERIES,
            "a path longer than the most queries answered at once",
        ),
    )?;
    let model = model(motion)?;
    let time = seconds(Some(time))?;
    let data = scene.data.clone();
    let fixed = interruptible(py, move |w| {
        let c = Certifier::new(&data.scene, model)?;
        let deadline = w.deadline();
        let cert = c.certify(&path, &deadline)?;
        let options = RepairOptions {
            time,
            ..RepairOptions::default()
        };
        repair(&c, &path, &cert, &options, &deadline)
    })?
    .map_err(|e| MotionError::new_err(one_line(&e)))?;
    let dof = scene.data.scene.space.dim();
    let report = json_to_py(py, &serde_json::to_value(&fixed.report).unwrap_or_default())?
        .into_bound(py)
        .cast_into::<PyDict>()?;
    report.set_item(
        "certificate",
        certificate_dict(py, &fixed.certificate, dof)?,
    )?;
    Ok((path_array(py, &fixed.path, dof)?, report))
}

/// `Scene.load_moveit`: a robot folder (`.urdf`, `.srdf`), a PlanningScene and a
/// MotionPlanRequest (its group, start and goal as the scene's one query).
pub(super) fn load_moveit(
    py: Python<'_>,
    robot: &Bound<'_, PyAny>,
    scene: &Bound<'_, PyAny>,
    request: &Bound<'_, PyAny>,
) -> PyResult<Scene> {
    let (robot, scene, request) = (file_path(robot)?, file_path(scene)?, file_path(request)?);
    let absolute = |p: &std::path::PathBuf| std::path::absolute(p).unwrap_or_else(|_| p.clone());
    let origin =
        super::merge::SceneOrigin::MoveIt(absolute(&robot), absolute(&scene), absolute(&request));
    let loaded = py
        .detach(|| {
            let arm = viaroad::bench::mbm::load_robot(&robot).map_err(|e| one_line(&e))?;
            let problem = viaroad::bench::mbm::Problem {
                family: String::new(),
                id: String::new(),
                scene,
                request,
            };
            viaroad::bench::mbm::problem_scene(&arm, &problem).map_err(|e| one_line(&e))
        })
        .map_err(SceneError::new_err)?;
    let oracle = loaded.oracle();
    Ok(Scene {
        data: Arc::new(SceneData {
            scene: loaded,
            oracle,
            origin,
        }),
    })
}
