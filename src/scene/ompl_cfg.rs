//! OMPL.app problems (`.cfg`), and OMPL's path and query files, loaded as OMPL.app reads them.
//!
//! A `.cfg` is INI. Only `[problem]` is read, leniently: other sections may repeat keys (the
//! `[planner]` lists of Home and cubicles_opt do), `#` starts a comment, and a later key
//! overrides an earlier one. From `[problem]`:
//!
//! - `robot`, `world`: mesh files relative to the cfg (any format [`load_mesh`] reads; OMPL.app
//!   ships Collada);
//! - `start.x start.y [start.z] start.theta [start.axis.x start.axis.y start.axis.z]` and the
//!   same for `goal.*`. The problem is 2D (SE(2)) when there is no `start.z` and no
//!   `start.axis.*`. In 3D the orientation is `q = (sin(θ/2)·a/|a|, cos(θ/2))`
//!   ([`ompl_axis_angle`]); in 2D θ is wrapped into `[-π, π)`. A missing θ is 0;
//! - `volume.min.x … volume.max.z`: the position bounds, grown to contain the start and goal
//!   positions (OMPL.app's `InferProblemDefinitionBounds`); without a complete volume, the
//!   bounding box of the world mesh (OMPL.app's `inferEnvironmentBounds`), grown likewise;
//! - `control = …`: a kinematic/dynamic car problem, loaded as a geometric SE(2) problem with a
//!   warning (viaroad plans geometric paths only).
//!
//! The robot mesh is shifted so that OMPL.app's centre is its reference point: for Collada the
//! mean of assimp's imported vertices ([`ColladaMesh::assimp_centre`], z zeroed in 2D); for
//! other formats the mean of the distinct vertices (an approximation of assimp's, which OMPL.app
//! does not ship). The world is not moved. In 2D both meshes are prisms along z; they become
//! their xy footprints ([`crate::oracle::polygons::footprint_polygons`]). The rotation scale is the robot's radius about its
//! reference point. The scene's one query is (start, goal).
//!
//! [`ColladaMesh::assimp_centre`]: super::collada::ColladaMesh::assimp_centre

use super::checks::{check_magnitudes, check_queries_on_load, default_name, quaternion_warnings};
use super::collada;
use super::error::{read_input_text, SceneError};
use super::mesh_io::{is_dae, load_mesh, vertex_mean};
use super::types::{Obstacle, Query, Robot, Scene};
use crate::geometry::{GeometryError, Polygon, TriMesh};
use crate::oracle::polygons::footprint_polygons;
use crate::safe_file::FileError;
use crate::space::rotation::{ompl_axis_angle, wrap_angle};
use crate::space::{Config, Space, SpaceError};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Loads an OMPL.app problem (see the module documentation).
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = read_input_text(path)?;
    let problem = Problem::parse(&text, path, "problem")?;
    let mut warnings = Vec::new();
    if let Some(control) = problem.text("control") {
        warnings.push(format!(
            "{}: control = {control} is a control problem; loaded as a geometric SE(2) problem \
             (the car's dynamics are ignored)",
            path.display()
        ));
    }
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    let robot_file = dir.join(problem.required_text("robot")?);
    let world_file = dir.join(problem.required_text("world")?);
    let planar = !problem.has("start.z") && !problem.has_prefix("start.axis.");
    let dim = if planar { 2 } else { 3 };
    let robot_mesh = centred_robot(&robot_file, planar)?;
    let world = load_mesh(&world_file)?;
    let start = state(&problem, "start", planar)?;
    let goal = state(&problem, "goal", planar)?;
    let (lower, upper) = bounds(&problem, dim, &world, [&start, &goal])?;

    // geometry per kind
    let (robot, obstacles, space) = if planar {
        planar_geometry(
            &robot_mesh,
            &world,
            [&robot_file, &world_file],
            &lower,
            &upper,
        )?
    } else {
        // OMPL.app's meshes are double-sided SketchUp soups and OMPL.app decides validity by
        // surface contact alone (FCL, see scenes/ompl/CONVENTIONS.md): that is the convention of
        // these problems, not a defect worth a warning, so open meshes are not reported here.
        let radius = robot_mesh.radius();
        let space = Space::se3(
            [lower[0], lower[1], lower[2]],
            [upper[0], upper[1], upper[2]],
            radius.max(1e-9),
        );
        (Robot::Mesh(robot_mesh), vec![Obstacle::Mesh(world)], space)
    };
    let space = space.map_err(|e| problem.invalid(format!("bounds: {e}")))?;
    let mut scene = Scene {
        name: problem
            .text("name")
            .map(str::to_string)
            .unwrap_or_else(|| default_name(path)),
        space,
        robot,
        obstacles,
        queries: vec![Query { start, goal }],
        source: Some(path.to_path_buf()),
        warnings,
    };
    check_magnitudes(&scene)?;
    scene.warnings.extend(quaternion_warnings(&scene));
    check_queries_on_load(&mut scene)?;
    Ok(scene)
}

/// The robot's mesh, shifted by OMPL.app's centre (z zeroed in 2D): assimp's for a Collada
/// file, the vertices' mean otherwise.
fn centred_robot(robot_file: &Path, planar: bool) -> Result<TriMesh, SceneError> {
    let (robot_mesh, centre) = if is_dae(robot_file) {
        let dae = collada::load_collada(robot_file)?;
        let c = dae.assimp_centre.map(f64::from);
        (dae.mesh, Vector3::new(c[0], c[1], c[2]))
    } else {
        let m = load_mesh(robot_file)?;
        let c = vertex_mean(&m).coords;
        (m, c)
    };
    let centre = if planar {
        Vector3::new(centre.x, centre.y, 0.0)
    } else {
        centre
    };
    Ok(robot_mesh.translated(-centre))
}

/// The problem's `which` state (`start` or `goal`): the position, then the angle in the plane
/// or OMPL's axis–angle turned into a quaternion.
fn state(problem: &Problem, which: &str, planar: bool) -> Result<Config, SceneError> {
    let axes = ["x", "y", "z"];
    let dim = if planar { 2 } else { 3 };
    let mut q: Vec<f64> = axes[..dim]
        .iter()
        .map(|a| problem.number(&format!("{which}.{a}")))
        .collect::<Result<_, _>>()?;
    let theta = problem
        .optional_number(&format!("{which}.theta"))?
        .unwrap_or(0.0);
    if planar {
        q.push(wrap_angle(theta));
    } else {
        let axis: Vec<Option<f64>> = axes
            .iter()
            .map(|a| problem.optional_number(&format!("{which}.axis.{a}")))
            .collect::<Result<_, _>>()?;
        let axis = match axis.as_slice() {
            [Some(x), Some(y), Some(z)] => [*x, *y, *z],
            [None, None, None] if theta == 0.0 => [1.0, 0.0, 0.0],
            _ => {
                return Err(problem.invalid(format!(
                    "{which}.theta needs all of {which}.axis.x, {which}.axis.y, {which}.axis.z"
                )))
            }
        };
        q.extend_from_slice(&ompl_axis_angle(axis, theta));
    }
    Ok(q)
}

/// The position bounds: the problem's `volume` if it gives all of it, else the world's box;
/// grown to hold the start and the goal.
fn bounds(
    problem: &Problem,
    dim: usize,
    world: &TriMesh,
    ends: [&Config; 2],
) -> Result<(Vec<f64>, Vec<f64>), SceneError> {
    let axes = ["x", "y", "z"];
    let volume: Vec<Option<f64>> = ["min", "max"]
        .iter()
        .flat_map(|m| axes[..dim].iter().map(move |a| format!("volume.{m}.{a}")))
        .map(|k| problem.optional_number(&k))
        .collect::<Result<_, _>>()?;
    let (mut lower, mut upper): (Vec<f64>, Vec<f64>) = if volume.iter().all(Option::is_some) {
        let v: Vec<f64> = volume.into_iter().flatten().collect();
        (v[..dim].to_vec(), v[dim..].to_vec())
    } else {
        let (lo, hi) = world.aabb();
        (
            lo.coords.as_slice()[..dim].to_vec(),
            hi.coords.as_slice()[..dim].to_vec(),
        )
    };
    for q in ends {
        for i in 0..dim {
            lower[i] = lower[i].min(q[i]);
            upper[i] = upper[i].max(q[i]);
        }
    }
    Ok((lower, upper))
}

/// A problem's robot, obstacles and space (its bounds not yet checked).
type Geometry = (Robot, Vec<Obstacle>, Result<Space, SpaceError>);

/// A 2D problem's robot and obstacles: the footprints of their prisms (`files` name them in
/// errors), and its SE(2) space.
fn planar_geometry(
    robot_mesh: &TriMesh,
    world: &TriMesh,
    files: [&PathBuf; 2],
    lower: &[f64],
    upper: &[f64],
) -> Result<Geometry, SceneError> {
    let parts = footprint_polygons(robot_mesh);
    let env = footprint_polygons(world);
    for (parts, file) in [(&parts, files[0]), (&env, files[1])] {
        if parts.is_empty() {
            return Err(SceneError::Geometry {
                path: file.clone(),
                source: GeometryError::Empty,
            });
        }
    }
    let radius = parts.iter().map(Polygon::radius).fold(0.0, f64::max);
    let space = Space::se2([lower[0], lower[1]], [upper[0], upper[1]], radius.max(1e-9));
    let obstacles = env.into_iter().map(Obstacle::Polygon).collect();
    Ok((Robot::Polygons(parts), obstacles, space))
}

/// Reads an OMPL path file (or any list of states): one state per line, whitespace-separated,
/// in the space's layout (`x y z qx qy qz qw`, `x y θ`, or n coordinates). Blank lines and `#`
/// comments are skipped. States are normalised (angles wrapped, quaternions of unit length);
/// bounds and collisions are not checked.
pub fn read_states(path: &Path, space: &Space) -> Result<Vec<Config>, SceneError> {
    read_rows(path, space, 1).map(|rows| rows.into_iter().map(|mut r| r.remove(0)).collect())
}

/// Writes states in the layout [`read_states`] reads and OMPL.app's `.path` files use: one state
/// per line, coordinates separated by spaces, printed so that they read back exactly. A path
/// written here can be checked by OMPL's own tools (the peer's `check` mode) with no conversion.
/// The file is written atomically and never replaces a special file
/// ([`crate::safe_file::write_atomically`]).
pub fn write_states(path: &Path, states: &[Config]) -> Result<(), SceneError> {
    let mut text = String::new();
    for q in states {
        let row: Vec<String> = q.iter().map(|x| format!("{x:?}")).collect();
        text.push_str(&row.join(" "));
        text.push('\n');
    }
    crate::safe_file::write_atomically(path, |w| w.write_all(text.as_bytes()))
        .map(drop)
        .map_err(|e| match e {
            FileError::Io { source, .. } => SceneError::Write {
                path: path.to_path_buf(),
                source,
            },
            other => SceneError::File(other),
        })
}

/// Reads query pairs: on each line a start state followed by a goal state (the format of
/// `scenes/ompl/queries/*.txt`). Normalised like [`read_states`]; validity is up to the caller
/// ([`Scene::check_config`]).
pub fn read_query_pairs(path: &Path, space: &Space) -> Result<Vec<Query>, SceneError> {
    read_rows(path, space, 2).map(|rows| {
        rows.into_iter()
            .map(|mut r| {
                let goal = r.pop().expect("two states per row");
                let start = r.pop().expect("two states per row");
                Query { start, goal }
            })
            .collect()
    })
}

/// Rows of `per_line` states each.
fn read_rows(path: &Path, space: &Space, per_line: usize) -> Result<Vec<Vec<Config>>, SceneError> {
    let text = read_input_text(path)?;
    let parse = |line: usize, message: String| SceneError::Parse {
        path: path.to_path_buf(),
        message: format!("line {line}: {message}"),
    };
    let dim = space.dim();
    let mut rows = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line_no = k + 1;
        let content = line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let numbers: Vec<f64> = content
            .split_whitespace()
            .map(|w| {
                w.parse::<f64>()
                    .map_err(|_| parse(line_no, format!("'{w}' is not a number")))
            })
            .collect::<Result<_, _>>()?;
        if numbers.len() != per_line * dim {
            return Err(parse(
                line_no,
                format!(
                    "{} numbers; a line holds {per_line} {} state{} of {dim} numbers",
                    numbers.len(),
                    space.kind(),
                    if per_line == 1 { "" } else { "s" }
                ),
            ));
        }
        let mut row = Vec::with_capacity(per_line);
        for chunk in numbers.chunks(dim) {
            space
                .check(chunk)
                .map_err(|e| parse(line_no, e.to_string()))?;
            let mut q = chunk.to_vec();
            space.normalize(&mut q);
            row.push(q);
        }
        rows.push(row);
    }
    Ok(rows)
}

/// The time OMPL.app's benchmark gives the problem (`[benchmark] time_limit`, seconds), if the
/// file names a positive one: what `viaroad solve` plans a `.cfg` within unless told otherwise,
/// so that it is judged on the terms the problem was published with.
pub fn time_limit(path: &Path) -> Result<Option<f64>, SceneError> {
    let text = read_input_text(path)?;
    let benchmark = match Problem::parse(&text, path, "benchmark") {
        Ok(b) => b,
        Err(SceneError::Parse { message, .. }) if message.starts_with("no [benchmark]") => {
            return Ok(None)
        }
        Err(e) => return Err(e),
    };
    match benchmark.optional_number("time_limit")? {
        Some(t) if t > 0.0 => Ok(Some(t)),
        Some(t) => Err(benchmark.invalid(format!(
            "[benchmark] time_limit = {t}: expected a positive number of seconds"
        ))),
        None => Ok(None),
    }
}

/// One section of the INI file (`[problem]`, `[benchmark]`): key → (value, line number).
struct Problem<'a> {
    path: &'a Path,
    keys: HashMap<String, (String, usize)>,
}

impl<'a> Problem<'a> {
    fn parse(text: &str, path: &'a Path, wanted: &str) -> Result<Problem<'a>, SceneError> {
        let mut keys = HashMap::new();
        let mut section = String::new();
        let mut seen_problem = false;
        for (k, line) in text.lines().enumerate() {
            let content = line.split('#').next().unwrap_or("").trim();
            if content.is_empty() {
                continue;
            }
            if let Some(name) = content.strip_prefix('[') {
                let Some(name) = name.strip_suffix(']') else {
                    return Err(SceneError::Parse {
                        path: path.to_path_buf(),
                        message: format!("line {}: unterminated section header", k + 1),
                    });
                };
                section = name.trim().to_string();
                seen_problem |= section == wanted;
                continue;
            }
            if section != wanted {
                continue; // other sections are not ours to judge
            }
            let Some((key, value)) = content.split_once('=') else {
                return Err(SceneError::Parse {
                    path: path.to_path_buf(),
                    message: format!("line {}: expected key = value in [{wanted}]", k + 1),
                });
            };
            keys.insert(key.trim().to_string(), (value.trim().to_string(), k + 1));
        }
        if !seen_problem {
            return Err(SceneError::Parse {
                path: path.to_path_buf(),
                message: match wanted {
                    "problem" => "no [problem] section: not an OMPL.app problem".into(),
                    _ => format!("no [{wanted}] section"),
                },
            });
        }
        Ok(Problem { path, keys })
    }

    fn invalid(&self, message: String) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            message,
        }
    }

    fn has(&self, key: &str) -> bool {
        self.keys.contains_key(key)
    }

    fn has_prefix(&self, prefix: &str) -> bool {
        self.keys.keys().any(|k| k.starts_with(prefix))
    }

    fn text(&self, key: &str) -> Option<&str> {
        self.keys
            .get(key)
            .map(|(v, _)| v.as_str())
            .filter(|v| !v.is_empty())
    }

    fn required_text(&self, key: &str) -> Result<&str, SceneError> {
        self.text(key)
            .ok_or_else(|| self.invalid(format!("[problem] has no {key}")))
    }

    fn optional_number(&self, key: &str) -> Result<Option<f64>, SceneError> {
        let Some((value, line)) = self.keys.get(key) else {
            return Ok(None);
        };
        match value.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(SceneError::Parse {
                path: self.path.to_path_buf(),
                message: format!("line {line}: {key} = '{value}' is not a finite number"),
            }),
        }
    }

    fn number(&self, key: &str) -> Result<f64, SceneError> {
        self.optional_number(key)?
            .ok_or_else(|| self.invalid(format!("[problem] has no {key}")))
    }
}
