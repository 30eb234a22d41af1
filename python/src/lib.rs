//! `viaroad._viaroad`: the library from Python, through its public API only:
//! [`Scene`], [`Roadmap`], [`QueryPlanner`], [`Learner`]. Long work (learning, queries,
//! sampling) releases the interpreter, so other Python threads run meanwhile, and Ctrl-C stops
//! it ([`interrupt`]); counts are held to [`viaroad::limits`]; errors are exceptions of
//! the `ViaroadError` hierarchy carrying the command line's one-line messages, never a crash
//! of the interpreter.

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyTuple};
use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use viaroad::limits::{MAX_NODES, MAX_QUERIES};
use viaroad::local::LocalSpec;
use viaroad::oracle::{CallCounts, CollisionOracle, CountedOracle};
use viaroad::roadmap::{
    Budget, LearnParams, Learner, Progress, QueryError as RustQueryError, QueryOptions,
    QueryPlanner, QueryResult, Roadmap as RustRoadmap,
};
use viaroad::scene::{Scene as RustScene, SceneError as RustSceneError};
use viaroad::space::Config;

mod certify;
mod interrupt;
mod merge;
use interrupt::{interruptible, interruptible_with};

create_exception!(
    viaroad,
    ViaroadError,
    PyException,
    "Base of every error viaroad raises; its message is the command line's one-line message."
);
create_exception!(
    viaroad,
    SceneError,
    ViaroadError,
    "A scene file that cannot be read or makes no sense."
);
create_exception!(
    viaroad,
    RoadmapError,
    ViaroadError,
    "A roadmap file that cannot be read, written, or belongs to another scene."
);
create_exception!(
    viaroad,
    QueryError,
    ViaroadError,
    "A configuration that cannot be asked about: wrong length, not finite, outside the bounds, in collision."
);
create_exception!(
    viaroad,
    LearnError,
    ViaroadError,
    "Learning could not run: no budget, a parameter out of range, an unknown local method."
);
create_exception!(
    viaroad,
    MotionError,
    ViaroadError,
    "No straight motion joins the two configurations, or the oracle cannot answer it."
);

/// One line: the error and those of its causes its message does not already say (as the
/// command line prints it after `error: `).
fn one_line(e: &(dyn std::error::Error + 'static)) -> String {
    let mut line = String::new();
    let mut cur: Option<&(dyn std::error::Error + 'static)> = Some(e);
    while let Some(c) = cur {
        let s = c.to_string();
        if !line.contains(&s) {
            if !line.is_empty() {
                line.push_str(": ");
            }
            line.push_str(&s);
        }
        cur = c.source();
    }
    line
}

/// A scene and its collision oracle, shared by the roadmaps learnt or loaded for it.
struct SceneData {
    scene: RustScene,
    oracle: Box<dyn CollisionOracle>,
    /// How to load the scene again, for pickling ([`merge::SceneOrigin`]).
    origin: merge::SceneOrigin,
}

/// A configuration from any sequence of numbers or a 1-d array.
fn config(py: Python<'_>, what: &str, q: &Bound<'_, PyAny>) -> PyResult<Config> {
    if let Ok(a) = q.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(a.as_array().to_vec());
    }
    let np = py.import("numpy")?;
    let arr = np
        .call_method1("asarray", (q, "float64"))
        .map_err(|e| QueryError::new_err(format!("{what}: not a sequence of numbers: {e}")))?;
    let a: PyReadonlyArray1<'_, f64> = arr.extract().map_err(|_| {
        let shape = arr
            .getattr("shape")
            .map(|s| s.to_string())
            .unwrap_or_default();
        QueryError::new_err(format!(
            "{what}: expected one configuration (a 1-d sequence of numbers), got shape {shape}"
        ))
    })?;
    Ok(a.as_array().to_vec())
}

/// Configurations from an `(n, dof)` array or a sequence of sequences; more than `max` rows
/// is a `ValueError` (`why` says why there is a bound), before the rows are copied.
fn configs(
    py: Python<'_>,
    what: &str,
    qs: &Bound<'_, PyAny>,
    (max, why): (usize, &str),
) -> PyResult<Vec<Config>> {
    let np = py.import("numpy")?;
    let arr = np
        .call_method1("asarray", (qs, "float64"))
        .map_err(|e| QueryError::new_err(format!("{what}: not an (n, dof) array: {e}")))?;
    let a: PyReadonlyArray2<'_, f64> = arr.extract().map_err(|_| {
        let shape = arr
            .getattr("shape")
            .map(|s| s.to_string())
            .unwrap_or_default();
        QueryError::new_err(format!(
            "{what}: expected an (n, dof) array of configurations, got shape {shape}"
        ))
    })?;
    let rows = a.as_array().nrows();
    if rows > max {
        return Err(PyValueError::new_err(format!(
            "{what}: {rows} rows is more than the {max} viaroad accepts: {why}"
        )));
    }
    Ok(a.as_array()
        .rows()
        .into_iter()
        .map(|r| r.to_vec())
        .collect())
}

/// A path as a `(k, dof)` array.
fn path_array<'py>(py: Python<'py>, path: &[Config], dof: usize) -> PyResult<Py<PyArray2<f64>>> {
    let flat: Vec<f64> = path.iter().flatten().copied().collect();
    let a = PyArray1::from_vec(py, flat).reshape([path.len(), dof])?;
    Ok(a.unbind())
}

/// A file path from `str` or `os.PathLike`.
fn file_path(p: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    p.extract::<PathBuf>()
        .map_err(|_| pyo3::exceptions::PyTypeError::new_err("expected a str or os.PathLike path"))
}

/// A count argument checked against one of [`viaroad::limits`]' bounds before anything is
/// allocated or looped over, as the command line checks its flags: outside `min..=max` (an int
/// too large for any machine included) it is `err` with a message naming the bound and why
/// there is one. Not an int at all is a `TypeError`.
fn count(
    n: &Bound<'_, PyAny>,
    what: &str,
    (min, max): (usize, usize),
    why: &str,
    err: fn(String) -> PyErr,
) -> PyResult<usize> {
    let v = match n.extract::<i128>() {
        Ok(v) => v,
        // an int beyond 128 bits: only its sign matters
        Err(_) if n.is_instance_of::<PyInt>() => {
            if n.lt(0)? {
                i128::MIN
            } else {
                i128::MAX
            }
        }
        Err(e) => return Err(e),
    };
    if v < min as i128 {
        return Err(err(if min == 0 {
            format!("{what} must not be negative, got {n}")
        } else {
            format!("{what} must be at least {min}, got {n}")
        }));
    }
    if v > max as i128 {
        return Err(err(format!(
            "{what} {n} is more than the {max} viaroad accepts: {why}"
        )));
    }
    Ok(v as usize)
}

/// A JSON value as the Python object `json.loads` makes of it.
fn json_to_py(py: Python<'_>, v: &serde_json::Value) -> PyResult<Py<PyAny>> {
    let text = v.to_string();
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// A scene: robot, obstacles and the configuration space (CHS §1.2), loaded from a viaroad
/// TOML file or an OMPL.app `.cfg` problem.
#[pyclass(module = "viaroad", name = "Scene", frozen)]
struct Scene {
    data: Arc<SceneData>,
}

#[pymethods]
impl Scene {
    /// Loads a scene: `.toml` in viaroad's format, `.cfg` as an OMPL.app problem. Warnings
    /// the loader has (queries outside the bounds, …) become Python `UserWarning`s.
    #[staticmethod]
    fn load(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<Scene> {
        let path = file_path(path)?;
        let scene = py
            .detach(|| RustScene::load(&path))
            .map_err(|e| SceneError::new_err(one_line(&e)))?;
        for w in &scene.warnings {
            let msg = std::ffi::CString::new(w.replace('\0', " ")).unwrap_or_default();
            PyErr::warn(
                py,
                &py.get_type::<pyo3::exceptions::PyUserWarning>(),
                &msg,
                1,
            )?;
        }
        let oracle = scene.oracle();
        Ok(Scene {
            data: Arc::new(SceneData {
                scene,
                oracle,
                origin: merge::SceneOrigin::File(std::path::absolute(&path).unwrap_or(path)),
            }),
        })
    }

    /// Pickles as its file: loading it again (the same absolute path must hold the same scene
    /// where it is unpickled; a scene of `load_moveit` names its three files).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        merge::reduce_scene(py, &self.data.origin)
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.data.scene.name.clone()
    }

    /// Degrees of freedom: the length of a configuration.
    #[getter]
    fn dof(&self) -> usize {
        self.data.scene.space.dim()
    }

    /// The space's kind: `r2`, `se2`, `se3`, ….
    #[getter]
    fn space(&self) -> String {
        self.data.scene.space.kind().to_string()
    }

    /// Lower corner of the bounds (a configuration's coordinates each).
    #[getter]
    fn lower<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.data.scene.space.lower())
    }

    /// Upper corner of the bounds.
    #[getter]
    fn upper<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.data.scene.space.upper())
    }

    /// The scene's own queries, checked and normalised: a list of `(start, goal)` arrays.
    fn queries<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        let qs = self
            .data
            .scene
            .checked_queries()
            .map_err(|e| SceneError::new_err(one_line(&e)))?;
        qs.iter()
            .map(|q| {
                PyTuple::new(
                    py,
                    [
                        PyArray1::from_slice(py, &q.start),
                        PyArray1::from_slice(py, &q.goal),
                    ],
                )
            })
            .collect()
    }

    /// Whether `q` lies in the bounds and the robot there touches no obstacle. Raises
    /// `QueryError` for a configuration of the wrong length or not finite.
    fn is_free(&self, py: Python<'_>, q: &Bound<'_, PyAny>) -> PyResult<bool> {
        let q = config(py, "q", q)?;
        let d = &self.data;
        match d.scene.check_config(d.oracle.as_ref(), "q", &q) {
            Ok(_) => Ok(true),
            Err(RustSceneError::OutOfBounds { .. } | RustSceneError::InCollision { .. }) => {
                Ok(false)
            }
            Err(e) => Err(QueryError::new_err(one_line(&e))),
        }
    }

    /// The exact collision intervals of the straight motion from `q_from` (t = 0) to `q_to`
    /// (t = 1), as an `(m, 2)` array of `[lo, hi]` rows, sorted and disjoint: the oracle's
    /// intersectSegment (CHS §1.2), what `viaroad probe` prints. A straight motion either
    /// translates or turns about one axis; anything else raises `MotionError`.
    fn intervals<'py>(
        &self,
        py: Python<'py>,
        q_from: &Bound<'py, PyAny>,
        q_to: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mut from = config(py, "q_from", q_from)?;
        let mut to = config(py, "q_to", q_to)?;
        let space = &self.data.scene.space;
        for (what, q) in [("q_from", &mut from), ("q_to", &mut to)] {
            space
                .check(q)
                .map_err(|e| QueryError::new_err(format!("{what}: {}", one_line(&e))))?;
            space.normalize(q);
        }
        let motion = space.direct_motion(&from, &to).ok_or_else(|| {
            MotionError::new_err(
                "q_from and q_to differ in both position and orientation: a straight motion \
                 either translates (equal orientations) or turns about one axis (equal positions)",
            )
        })?;
        let data = self.data.clone();
        let ivs = py
            .detach(move || {
                let mut counts = CallCounts::default();
                data.oracle
                    .intersect(&motion, &mut counts)
                    .map(|l| l.iter().flat_map(|iv| [iv.lo, iv.hi]).collect::<Vec<f64>>())
            })
            .map_err(|e| MotionError::new_err(one_line(&e)))?;
        let m = ivs.len() / 2;
        PyArray1::from_vec(py, ivs).reshape([m, 2])
    }

    /// Proves each segment of `path` (a `(k, dof)` array or sequence of configurations from
    /// any planner) free, or finds where it collides. `motion`: `"interpolate"` (OMPL's,
    /// MoveIt's, VAMP's: joint-space straight lines, SE(3) slerp) or `"direct"` (viaroad's own
    /// paths); `time`: seconds (segments not reached are undecided). Returns a dict: `status`
    /// (`"free"`, `"collides"`, `"undecided"`), `segments` (per segment `verdict`, and for a
    /// collision `intervals`, `witness`, `pairs`), `defects`, and numpy arrays `codes` (0 free,
    /// 1 collides, 2 undecided) and `witnesses` (NaN rows where none).
    #[pyo3(signature = (path, motion = "interpolate", time = None))]
    fn certify<'py>(
        &self,
        py: Python<'py>,
        path: &Bound<'py, PyAny>,
        motion: &str,
        time: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        certify::certify(self, py, path, motion, time)
    }

    /// Repairs `path`: every proved segment kept, each run of blocked ones replaced by a
    /// certified detour planned within `time` seconds. Returns `(fixed, report)`: the fixed
    /// path as a `(k, dof)` array and a dict (`detours`, `segments_repaired`, lengths,
    /// `seconds`, `certified`, and the fixed path's `certificate`).
    #[pyo3(signature = (path, time = 10.0, motion = "interpolate"))]
    fn repair<'py>(
        &self,
        py: Python<'py>,
        path: &Bound<'py, PyAny>,
        time: f64,
        motion: &str,
    ) -> PyResult<(Py<PyArray2<f64>>, Bound<'py, PyDict>)> {
        certify::repair_path(self, py, path, time, motion)
    }

    /// A MotionBenchMaker-style arm problem: the robot's folder (its `.urdf` and `.srdf`), a
    /// MoveIt PlanningScene `.yaml` and a MotionPlanRequest `.yaml` (the group, and the start
    /// and goal as the scene's query).
    #[staticmethod]
    fn load_moveit(
        py: Python<'_>,
        robot: &Bound<'_, PyAny>,
        scene: &Bound<'_, PyAny>,
        request: &Bound<'_, PyAny>,
    ) -> PyResult<Scene> {
        certify::load_moveit(py, robot, scene, request)
    }

    /// `n` random collision-free configurations as an `(n, dof)` array, drawn uniformly from a
    /// stream seeded with `seed` (reproducible); raises `ViaroadError` if 100 000 draws in a
    /// row find none, and `ValueError` for more than the ends of the most queries
    /// `Roadmap.query_many` answers at once. Ctrl-C stops it.
    #[pyo3(signature = (n, seed = 0))]
    fn sample_free<'py>(
        &self,
        py: Python<'py>,
        n: &Bound<'py, PyAny>,
        seed: u64,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        use rand_free::draw;
        let n = count(
            n,
            "n",
            (0, 2 * MAX_QUERIES),
            "the configurations are all held at once (the ends of the most queries a batch \
             answers)",
            PyValueError::new_err,
        )?;
        let data = &self.data;
        let flat = interruptible(py, |watch| {
            draw(&data.scene, data.oracle.as_ref(), n, seed, &|| {
                watch.cancelled()
            })
        })?
        .map_err(ViaroadError::new_err)?;
        let dof = self.data.scene.space.dim();
        PyArray1::from_vec(py, flat).reshape([n, dof])
    }

    fn __repr__(&self) -> String {
        let s = &self.data.scene;
        format!(
            "<viaroad.Scene {:?}: {} dof, {} obstacles>",
            s.name,
            s.space.dim(),
            s.obstacles.len()
        )
    }
}

/// Seeded uniform draws of free configurations, with the library's own generator.
mod rand_free {
    use super::*;

    /// Draws per free configuration before giving up (an almost empty free space).
    const MAX_DRAWS: usize = 100_000;

    /// `n` free configurations, flat; fewer once `stop` says so (the caller then raises).
    pub fn draw(
        scene: &RustScene,
        oracle: &dyn CollisionOracle,
        n: usize,
        seed: u64,
        stop: &dyn Fn() -> bool,
    ) -> Result<Vec<f64>, String> {
        let mut rng =
            <rand_chacha::ChaCha8Rng as rand_chacha::rand_core::SeedableRng>::seed_from_u64(seed);
        let mut out = Vec::with_capacity(n.saturating_mul(scene.space.dim()).min(1 << 24));
        for _ in 0..n {
            let mut found = false;
            for _ in 0..MAX_DRAWS {
                if stop() {
                    return Ok(out);
                }
                let mut q = scene.space.sample_uniform(&mut rng);
                scene.space.normalize(&mut q);
                if oracle.is_free(&q, &mut CallCounts::default()) {
                    out.extend_from_slice(&q);
                    found = true;
                    break;
                }
            }
            if !found {
                return Err(format!(
                    "no free configuration in {MAX_DRAWS} random draws: the scene's free space is (almost) empty"
                ));
            }
        }
        Ok(out)
    }
}

/// How a query shortens its path (CHS A.1), as `viaroad query --shorten` says.
fn shortening(options: &mut QueryOptions, shorten: &str) -> PyResult<()> {
    match shorten {
        "fast" => {}
        "exact" => options.exact_shortening_limit = usize::MAX,
        "greedy" => options.exact_shortening_limit = 0,
        "off" => options.shorten = false,
        other => {
            return Err(QueryError::new_err(format!(
                "shorten must be \"fast\", \"exact\", \"greedy\" or \"off\", got {other:?}"
            )))
        }
    }
    Ok(())
}

/// A query's time: seconds as the command line accepts them, or none.
fn query_time(time: Option<f64>) -> PyResult<Option<Duration>> {
    time.map(|t| {
        viaroad::limits::duration_from_secs(t).ok_or_else(|| {
            QueryError::new_err(format!(
                "time must be a positive number of seconds of at most {:e}, got {t:?}",
                viaroad::limits::MAX_SECONDS
            ))
        })
    })
    .transpose()
}

/// The answer to one query.
#[pyclass(module = "viaroad", name = "QueryResult", frozen, get_all)]
struct PyQueryResult {
    /// Whether a path was found.
    solved: bool,
    /// How the query ended: `direct`, `roadmap`, `grown`, `not_attached`, `disconnected`,
    /// `timed_out`, or `error` (the query could not be asked: see `error`).
    outcome: String,
    /// The path as found, `(k, dof)`: corners joined by straight motions (empty if unsolved).
    path: Py<PyArray2<f64>>,
    /// The shortened path, `(k, dof)` (CHS A.1; the path itself with `shorten="off"`).
    shortened: Py<PyArray2<f64>>,
    /// Length of `shortened`.
    length: f64,
    /// Length of `path`.
    raw_length: f64,
    /// Collision-interval calls (intersectSegment/intersectLine) the query made.
    calls: u64,
    /// Deepest via-point recursion used in the answer.
    depth: u32,
    /// Nodes the query grew a copy of the roadmap by (0: it did not grow).
    grown_nodes: usize,
    /// Milliseconds the Rust call took (the Python call's own cost is not included).
    ms: f64,
    /// Of `ms`, milliseconds spent shortening the path found.
    shorten_ms: f64,
    /// Why the query could not be asked (only in `query_many`; `query` raises `QueryError`).
    error: Option<String>,
}

impl PyQueryResult {
    fn new(
        py: Python<'_>,
        dof: usize,
        result: &Result<QueryResult, String>,
        ms: f64,
    ) -> PyResult<Self> {
        Ok(match result {
            Ok(r) => PyQueryResult {
                solved: r.is_solved(),
                outcome: outcome_name(r),
                path: path_array(py, &r.raw_path, dof)?,
                shortened: path_array(py, &r.path, dof)?,
                length: r.length,
                raw_length: r.raw_length,
                calls: r.counts.intersect_calls(),
                depth: r.depth,
                grown_nodes: r.grown_nodes,
                ms,
                shorten_ms: r.shorten_s * 1e3,
                error: None,
            },
            Err(e) => PyQueryResult {
                solved: false,
                outcome: "error".into(),
                path: path_array(py, &[], dof)?,
                shortened: path_array(py, &[], dof)?,
                length: 0.0,
                raw_length: 0.0,
                calls: 0,
                depth: 0,
                grown_nodes: 0,
                ms,
                shorten_ms: 0.0,
                error: Some(e.clone()),
            },
        })
    }
}

/// The outcome's name as `query --json` writes it (`not_attached` without its details).
fn outcome_name(r: &QueryResult) -> String {
    match serde_json::to_value(r.outcome) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(serde_json::Value::Object(m)) => m.keys().next().cloned().unwrap_or_default(),
        _ => format!("{:?}", r.outcome),
    }
}

#[pymethods]
impl PyQueryResult {
    fn __repr__(&self) -> String {
        match &self.error {
            Some(e) => format!("<viaroad.QueryResult error: {e}>"),
            None => format!(
                "<viaroad.QueryResult {}: length {:.4}, {} calls, {:.3} ms>",
                self.outcome, self.length, self.calls, self.ms
            ),
        }
    }
}

/// A roadmap learnt for one scene (OS94's learning phase with the via-point planner as local
/// method, CHS §1.6), answering queries in its query phase. Queries never change it, so any
/// number of threads may ask at once.
#[pyclass(module = "viaroad", name = "Roadmap", frozen)]
struct Roadmap {
    scene: Arc<SceneData>,
    roadmap: Arc<RustRoadmap>,
}

impl Roadmap {
    /// A planner with the options of one call.
    fn planner(&self, shorten: &str, time: Option<f64>, grow: bool) -> PyResult<QueryPlanner<'_>> {
        let planner = QueryPlanner::new(&self.roadmap, self.scene.oracle.as_ref())
            .map_err(|e| RoadmapError::new_err(one_line(&e)))?;
        let mut options = planner.options().clone();
        shortening(&mut options, shorten)?;
        options.time = query_time(time)?;
        options.grow = grow;
        // an arm grows trees out of the roadmap, racing its search, as `viaroad query` does
        if grow {
            options = options.with_arm_trees(self.roadmap.space());
        }
        Ok(planner.with_options(options))
    }
}

#[pymethods]
impl Roadmap {
    /// Learns a roadmap of `scene` until `nodes` nodes or `time` seconds (1000 nodes if neither
    /// is given), reproducibly from `seed` (a node budget gives the same roadmap whatever the
    /// thread count). `local` is a local-method spec as `viaroad build --local` takes it
    /// (default: the roadmap's via-point planner). `progress`, if given, is called after each
    /// round with a dict (`rounds`, `nodes`, `edges`, `components`, `seconds`) on the calling
    /// thread; an exception it raises, or Ctrl-C, stops learning and is raised here. The
    /// interpreter is released while learning.
    ///
    /// `shard=(i, n)` learns shard `i` of `n` (1 ≤ i ≤ n) of a roadmap learnt apart and joined
    /// by `Roadmap.merge`, as `viaroad build --shard I/N`: its own random streams, derived from
    /// `seed`, `i` and `n`, and its share of `nodes` (`time` is the shard's own).
    #[staticmethod]
    #[pyo3(signature = (scene, *, time = None, nodes = None, seed = 1, local = None, progress = None, shard = None))]
    #[allow(clippy::too_many_arguments)]
    fn build(
        py: Python<'_>,
        scene: &Scene,
        time: Option<f64>,
        nodes: Option<&Bound<'_, PyAny>>,
        seed: u64,
        local: Option<&str>,
        progress: Option<Py<PyAny>>,
        shard: Option<(u64, u64)>,
    ) -> PyResult<Roadmap> {
        let shard = shard
            .map(|(i, n)| viaroad::roadmap::Shard::new(i, n))
            .transpose()
            .map_err(|e| LearnError::new_err(e.to_string()))?;
        let spec: LocalSpec = match local {
            Some(s) => s
                .parse::<LocalSpec>()
                .map_err(|e| LearnError::new_err(one_line(&e)))?,
            None => LocalSpec::roadmap_default_for(&scene.data.scene.space),
        };
        viaroad::local::check_local_spec(&spec).map_err(LearnError::new_err)?;
        let time = match time {
            None => None,
            Some(t) => Some(viaroad::limits::duration_from_secs(t).ok_or_else(|| {
                LearnError::new_err(format!(
                    "time must be a positive number of seconds of at most {:e}, got {t:?}",
                    viaroad::limits::MAX_SECONDS
                ))
            })?),
        };
        let nodes = nodes
            .map(|n| {
                count(
                    n,
                    "nodes",
                    (1, MAX_NODES),
                    "a roadmap is held in memory",
                    LearnError::new_err,
                )
            })
            .transpose()?;
        let budget = Budget {
            nodes: if nodes.is_none() && time.is_none() {
                Some(1000)
            } else {
                nodes
            },
            time,
        };
        let data = &scene.data;
        let on_progress = |py: Python<'_>, p: Progress| -> PyResult<()> {
            if let Some(cb) = &progress {
                let d = PyDict::new(py);
                d.set_item("rounds", p.rounds)?;
                d.set_item("nodes", p.nodes)?;
                d.set_item("edges", p.edges)?;
                d.set_item("components", p.components)?;
                d.set_item("seconds", p.elapsed.as_secs_f64())?;
                cb.call1(py, (d,))?;
            }
            Ok(())
        };
        let wants_progress = progress.is_some();
        let learnt = interruptible_with(py, on_progress, |watch| {
            let method = spec.build();
            let learner = Learner::for_scene(&data.scene, data.oracle.as_ref(), method.as_ref())
                .with_attempt_cap(budget.time.map(Learner::attempt_cap_for));
            let mut on_round = |p: &Progress| {
                if wants_progress {
                    watch.send(p.clone());
                }
            };
            let params = LearnParams::default();
            let deadline = watch.deadline();
            match shard {
                None => learner.learn_within(&params, &budget, seed, &deadline, &mut on_round),
                Some(shard) => {
                    learner.learn_shard(&params, &budget, (seed, shard), &deadline, &mut on_round)
                }
            }
        })?;
        let learnt = learnt.map_err(|e| LearnError::new_err(one_line(&e)))?;
        Ok(Roadmap {
            scene: scene.data.clone(),
            roadmap: Arc::new(learnt.roadmap),
        })
    }

    /// Reads a roadmap file learnt for `scene` (its fingerprint is checked: a roadmap of
    /// another scene raises `RoadmapError`).
    #[staticmethod]
    fn load(py: Python<'_>, path: &Bound<'_, PyAny>, scene: &Scene) -> PyResult<Roadmap> {
        let path = file_path(path)?;
        let fp = scene.data.scene.fingerprint();
        let roadmap = py
            .detach(|| RustRoadmap::load(&path, fp))
            .map_err(|e| RoadmapError::new_err(one_line(&e)))?;
        Ok(Roadmap {
            scene: scene.data.clone(),
            roadmap: Arc::new(roadmap),
        })
    }

    /// Merges roadmaps of `scene` learnt apart (shards, other merges) into one, as `viaroad
    /// merge`: the union of their nodes and edges, then connections across parts with the
    /// parts' local method. The same parts give the same roadmap in any order. `into`, if
    /// given, is a base that keeps its node indices (a deployed roadmap grown by parts learnt
    /// later). `time` stops connecting after that many seconds (not reproducible). Parts of
    /// another scene or local method raise `RoadmapError`. Releases the interpreter; Ctrl-C
    /// stops the connecting and keeps what is joined.
    #[staticmethod]
    #[pyo3(signature = (parts, scene, *, time = None, into = None))]
    fn merge(
        py: Python<'_>,
        parts: Vec<PyRef<'_, Roadmap>>,
        scene: &Scene,
        time: Option<f64>,
        into: Option<PyRef<'_, Roadmap>>,
    ) -> PyResult<Roadmap> {
        let parts: Vec<Arc<RustRoadmap>> = parts.iter().map(|p| p.roadmap.clone()).collect();
        let base = into.map(|b| b.roadmap.clone());
        let merged = merge::merge(py, &scene.data, base, parts, time)?;
        Ok(Roadmap {
            scene: scene.data.clone(),
            roadmap: Arc::new(merged),
        })
    }

    /// The roadmap file's bytes (what `save` writes).
    fn to_bytes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyBytes>> {
        let bytes = py
            .detach(|| self.roadmap.to_bytes())
            .map_err(|e| RoadmapError::new_err(one_line(&e)))?;
        Ok(pyo3::types::PyBytes::new(py, &bytes))
    }

    /// A roadmap from a file's bytes, checked like `load` (format, checksums, the scene).
    #[staticmethod]
    fn from_bytes(py: Python<'_>, data: &[u8], scene: &Scene) -> PyResult<Roadmap> {
        let fp = scene.data.scene.fingerprint();
        let roadmap = py
            .detach(|| RustRoadmap::from_bytes(data, fp))
            .map_err(|e| RoadmapError::new_err(one_line(&e)))?;
        Ok(Roadmap {
            scene: scene.data.clone(),
            roadmap: Arc::new(roadmap),
        })
    }

    /// Pickles through its bytes and its scene (which pickles as its file), so that Ray and
    /// `multiprocessing` can ship roadmaps.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let bytes = self.to_bytes(py)?;
        let scene = Scene {
            data: self.scene.clone(),
        };
        let rebuild = py.import("viaroad")?.getattr("_roadmap_from_bytes")?;
        PyTuple::new(
            py,
            [
                rebuild,
                PyTuple::new(py, [bytes.into_any(), Bound::new(py, scene)?.into_any()])?.into_any(),
            ],
        )
    }

    /// A digest of the roadmap's content (equal roadmaps, equal digests): how merges order
    /// their parts.
    fn digest(&self, py: Python<'_>) -> PyResult<u64> {
        py.detach(|| self.roadmap.digest())
            .map_err(|e| RoadmapError::new_err(one_line(&e)))
    }

    /// The nodes, an `(n, dof)` array in index order.
    fn nodes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let dof = self.roadmap.dim();
        PyArray1::from_slice(py, self.roadmap.coords()).reshape([self.roadmap.node_count(), dof])
    }

    /// The edges' end nodes, an `(m, 2)` array of node indices.
    fn edge_ends<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let ends: Vec<u32> = self
            .roadmap
            .edges()
            .iter()
            .flat_map(|e| [e.a, e.b])
            .collect();
        PyArray1::from_vec(py, ends).reshape([self.roadmap.edge_count(), 2])
    }

    /// Edge `i`'s path from its first end to its second, corners included, `(k, dof)`; every
    /// consecutive pair is one straight motion of the local method's DOF groups.
    fn edge_path<'py>(&self, py: Python<'py>, i: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let Some(e) = self.roadmap.edges().get(i) else {
            return Err(PyValueError::new_err(format!(
                "edge {i} does not exist: the roadmap has {} edges",
                self.roadmap.edge_count()
            )));
        };
        let path = self.roadmap.edge_path(i, e.a);
        let k = path.len();
        PyArray1::from_vec(py, path.concat()).reshape([k, self.roadmap.dim()])
    }

    /// Saves the roadmap (atomically: a failed save keeps the previous file).
    fn save(&self, py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<()> {
        let path = file_path(path)?;
        py.detach(|| self.roadmap.save(&path))
            .map_err(|e| RoadmapError::new_err(one_line(&e)))
    }

    /// The scene the roadmap answers for.
    #[getter]
    fn scene(&self) -> Scene {
        Scene {
            data: self.scene.clone(),
        }
    }

    /// What `viaroad info --json` prints: nodes, edges, components, learning parameters,
    /// local method, seed, scene fingerprint.
    fn info(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v = serde_json::to_value(self.roadmap.info())
            .map_err(|e| ViaroadError::new_err(e.to_string()))?;
        json_to_py(py, &v)
    }

    /// Answers one query (`start`, `goal`: sequences or 1-d arrays). `shorten` is `"fast"`,
    /// `"exact"` or `"off"` as in `viaroad query`; `time` the seconds it may take (where the
    /// roadmap cannot join start and goal, it grows a copy of the roadmap for the rest of it
    /// if `grow`; for an arm, two trees out of it, racing its search after 2 ms, as
    /// `viaroad query`), `None` for no limit and no growing. Raises `QueryError` for a start or goal
    /// of the wrong length, outside the bounds or in collision. Releases the interpreter;
    /// Ctrl-C stops it.
    #[pyo3(signature = (start, goal, *, shorten = "fast", time = Some(QueryOptions::DEFAULT_TIME.as_secs_f64()), grow = true))]
    fn query(
        &self,
        py: Python<'_>,
        start: &Bound<'_, PyAny>,
        goal: &Bound<'_, PyAny>,
        shorten: &str,
        time: Option<f64>,
        grow: bool,
    ) -> PyResult<PyQueryResult> {
        let start = config(py, "start", start)?;
        let goal = config(py, "goal", goal)?;
        let planner = self.planner(shorten, time, grow)?;
        // landmarks cost a graph search each, repaid over a batch, not by one query
        let mut options = planner.options().clone();
        options.landmarks = 0;
        let planner = planner.with_options(options);
        let (result, ms) = interruptible(py, |watch| {
            let began = Instant::now();
            let r = planner.query_within(&start, &goal, &watch.deadline());
            (r, began.elapsed().as_secs_f64() * 1e3)
        })?;
        let result = result.map_err(|e| QueryError::new_err(one_line(&e)))?;
        PyQueryResult::new(py, self.roadmap.space().dim(), &Ok(result), ms)
    }

    /// Answers `n` queries, `starts` and `goals` `(n, dof)` arrays, in parallel on all cores
    /// (the interpreter released); a list of `QueryResult` in input order. A query that cannot
    /// be asked gets a result with `error` set instead of raising, so one bad row does not
    /// lose the others' answers. More rows than `viaroad.limits`' most queries raise
    /// `ValueError`. Ctrl-C stops the batch within about one query's time: the queries
    /// running give up, those not begun are skipped, and `KeyboardInterrupt` is raised.
    #[pyo3(signature = (starts, goals, *, shorten = "fast", time = Some(QueryOptions::DEFAULT_TIME.as_secs_f64()), grow = true))]
    fn query_many(
        &self,
        py: Python<'_>,
        starts: &Bound<'_, PyAny>,
        goals: &Bound<'_, PyAny>,
        shorten: &str,
        time: Option<f64>,
        grow: bool,
    ) -> PyResult<Vec<PyQueryResult>> {
        let bound = (
            MAX_QUERIES,
            "every answer, paths included, is held until the batch ends",
        );
        let starts = configs(py, "starts", starts, bound)?;
        let goals = configs(py, "goals", goals, bound)?;
        if starts.len() != goals.len() {
            return Err(QueryError::new_err(format!(
                "{} starts but {} goals",
                starts.len(),
                goals.len()
            )));
        }
        let pairs: Vec<(Config, Config)> = starts.into_iter().zip(goals).collect();
        let planner = self.planner(shorten, time, grow)?;
        let answers = interruptible(py, |watch| {
            let deadline = watch.deadline();
            pairs
                .par_iter()
                .map(|(s, g)| {
                    // once interrupted, the queries not begun are skipped
                    if watch.cancelled() {
                        return None;
                    }
                    let began = Instant::now();
                    let r = planner.query_within(s, g, &deadline);
                    Some((r, began.elapsed()))
                })
                .collect::<Vec<Option<(Result<QueryResult, RustQueryError>, Duration)>>>()
        })?;
        let dof = self.roadmap.space().dim();
        answers
            .into_iter()
            .map(|a| {
                let (r, elapsed) = match a {
                    Some((r, elapsed)) => (r.map_err(|e| one_line(&e)), elapsed),
                    None => (
                        Err("not asked: the batch was interrupted".into()),
                        Duration::ZERO,
                    ),
                };
                PyQueryResult::new(py, dof, &r, elapsed.as_secs_f64() * 1e3)
            })
            .collect()
    }

    fn __repr__(&self) -> String {
        format!(
            "<viaroad.Roadmap of {:?}: {} nodes, {} edges, {} components>",
            self.scene.scene.name,
            self.roadmap.node_count(),
            self.roadmap.edge_count(),
            self.roadmap.component_count()
        )
    }
}

/// The extension module.
#[pymodule]
fn _viaroad(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Scene>()?;
    m.add_class::<Roadmap>()?;
    m.add_class::<PyQueryResult>()?;
    m.add("ViaroadError", py.get_type::<ViaroadError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("RoadmapError", py.get_type::<RoadmapError>())?;
    m.add("QueryError", py.get_type::<QueryError>())?;
    m.add("LearnError", py.get_type::<LearnError>())?;
    m.add("MotionError", py.get_type::<MotionError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
