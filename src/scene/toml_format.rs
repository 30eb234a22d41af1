//! viaroad's TOML scene format.
//!
//! A scene file names a configuration space with position bounds, the moving robot, the
//! fixed obstacles and any number of queries:
//!
//! ```toml
//! name = "cube-into-box"              # optional; default: the file name without extension
//!
//! [space]
//! kind = "se3"                        # "r2", "rn" (or "r3", "r4" …), "se2", "se3"
//! lower = [-10.0, -10.0, -10.0]       # position bounds: n numbers for rn, 2 for se2, 3 for se3
//! upper = [10.0, 10.0, 10.0]
//! rotation_scale = 0.5                # se2/se3 only, optional: the length one radian of turning
//!                                     # counts as; default: the robot's radius about its
//!                                     # reference point (largest distance of a vertex from it)
//!
//! [robot]                             # se2/se3 only (r2/rn scenes move a point); one shape:
//! box = { half_extents = [0.5, 0.5, 0.5] }   # se3: 3 numbers; se2: 2 (a rectangle);
//!                                     # optional center = [...] (default: the origin)
//! # mesh = "meshes/piano.obj"         # OBJ, STL or Collada (.dae), relative to this file;
//! #                                   # in se2 the mesh's footprint in the xy-plane is used
//! # polygon = { vertices = [[x, y], ...] }             # se2: a simple polygon
//! # polygons = [{ vertices = [...] }, { vertices = [...] }]   # se2: a union of polygons
//! # convex = { points = [[x, y, z], ...] }             # the convex hull (se2: [x, y] points)
//! center = "mean"                     # optional: the robot's reference point (the point a
//!                                     # configuration places and turns about). "mean": the
//!                                     # mean of the vertices (for .dae meshes exactly
//!                                     # OMPL.app's centre, see `collada`); [x, y(, z)]: this
//!                                     # point. Default: the shape's own origin.
//!
//! [[obstacle]]                        # any number; one shape each:
//! box = { center = [3.0, 0.0, 0.0], half_extents = [1.0, 1.0, 1.0] }   # se2: 2 numbers each
//! [[obstacle]]
//! mesh = "meshes/room.obj"            # se2/se3; optional offset = [x, y(, z)] moves it
//! offset = [0.0, 0.0, 0.0]
//! [[obstacle]]
//! convex = { points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]] }    # se2/se3
//! # polygon = { vertices = [[0, 0], [1, 0], [0, 1]] }  # se2
//! # disc = { center = [0.3, 0.4], radius = 0.05 }      # r2/rn: a closed ball
//!
//! [[query]]                           # any number
//! start = [0, 0, 0, 0, 0, 0, 1]       # se3: x y z qx qy qz qw (OMPL's order, scalar last);
//! goal  = [1, 0, 0, 0, 0, 0, 1]       # se2: x y theta (radians); rn: n coordinates
//! ```
//!
//! Rules, each enforced with its own error message naming the file: every key is known
//! (misspellings are errors), every number is finite, dimensions match the space, radii and
//! half extents are positive (a radius may be 0), polygons are simple, an obstacle or robot
//! table holds exactly one shape, the shape suits the space (discs only in r2/rn; polygons only
//! in se2), and every query's start and goal lie inside the bounds and free of collision.
//! Quaternions are normalised and angles wrapped into `[-π, π)` on loading. A mesh that is not
//! closed is accepted with a warning in [`Scene::warnings`]: containment cannot be decided for
//! it, only surface contact is detected.
//!
//! Boxes become closed cuboids ([`TriMesh::cuboid`]) in se3 and rectangles
//! ([`Polygon::rectangle`]) in se2; meshes in se2 become their footprints (OMPL.app's 2D
//! problems are prisms extruded along z).

mod bodies;
mod bodies3;
mod spec;

pub use super::checks::{checked_queries, validate_queries};
use super::collada;
use super::mesh_io::{self, is_dae, open_mesh_warning, vertex_mean};

use super::checks::{check_magnitudes, check_queries_on_load, default_name, quaternion_warnings};
use super::error::{read_input_text, SceneError};
use super::types::{Obstacle, Query, Robot, Scene};
use crate::geometry::hull::{convex_hull_2d, convex_hull_3d, is_simple};
use crate::geometry::{GeometryError, Polygon, TriMesh};
use crate::oracle::polygons::footprint_polygons;
use crate::space::Space;
use nalgebra::{Point2, Point3, Vector2, Vector3};
use spec::{BoxSpec, ConvexSpec, DiscSpec, File, ObstacleSpec, PolygonSpec, RobotSpec, SpaceSpec};
use std::path::{Path, PathBuf};

/// The most vertices of one polygon, or points of one convex hull, a scene may give. The
/// simplicity test and the triangulation of a polygon take time quadratic in its vertices and
/// parry's 3D hull of 10 000 points asked for 377 MB (found by fuzzing, see
/// `tests/fuzz_regressions.rs`); shapes this detailed belong in mesh files.
pub const MAX_SHAPE_POINTS: usize = 2_000;

/// Reads and validates a TOML scene file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = read_input_text(path)?;
    from_str(&text, path)
}

/// Parses a TOML scene; `path` names the file in errors and anchors relative mesh paths.
pub fn from_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
    if super::arm::is_arm_scene(text) {
        return super::arm::from_str(text, path);
    }
    let file: File = toml::from_str(text).map_err(|e| SceneError::Parse {
        path: path.to_path_buf(),
        message: e.to_string().trim_end().replace('\n', " "),
    })?;
    let mut reader = Reader {
        path,
        warnings: Vec::new(),
    };
    let mut scene = reader.scene(file)?;
    check_magnitudes(&scene)?;
    scene.warnings.extend(quaternion_warnings(&scene));
    check_queries_on_load(&mut scene)?;
    Ok(scene)
}

/// Reading state: the file for messages and relative paths, and the warnings so far.
struct Reader<'a> {
    path: &'a Path,
    warnings: Vec<String>,
}

/// Space kinds as the format names them.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Euclidean,
    Se2,
    Se3,
}

impl Reader<'_> {
    fn invalid(&self, message: String) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            message,
        }
    }

    fn scene(&mut self, file: File) -> Result<Scene, SceneError> {
        let (kind, n) = self.kind(&file.space)?;
        let check_finite = |what: &str, v: &[f64]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(self.invalid(format!("[space] {what} has a value that is not finite")))
            }
        };
        check_finite("lower", &file.space.lower)?;
        check_finite("upper", &file.space.upper)?;
        for (what, v) in [("lower", &file.space.lower), ("upper", &file.space.upper)] {
            if v.len() != n {
                return Err(self.invalid(format!(
                    "[space] {what} has {} numbers, a {} space needs {n}",
                    v.len(),
                    file.space.kind
                )));
            }
        }
        if !file.bodies.is_empty() {
            return self.bodies_scene(file, kind);
        }
        let (robot, obstacles, space) = match kind {
            Kind::Euclidean => {
                if file.space.rotation_scale.is_some() {
                    return Err(self.invalid(
                        "[space] rotation_scale applies to se2 and se3 spaces only".into(),
                    ));
                }
                if file.robot.is_some() {
                    return Err(self.invalid(format!(
                        "a {} scene moves a point; remove [robot]",
                        file.space.kind
                    )));
                }
                let space = Space::euclidean(file.space.lower.clone(), file.space.upper.clone())
                    .map_err(|e| self.invalid(format!("[space] {e}")))?;
                let obstacles = file
                    .obstacles
                    .iter()
                    .enumerate()
                    .map(|(i, o)| self.disc_obstacle(i + 1, o, n))
                    .collect::<Result<_, _>>()?;
                (Robot::Point, obstacles, space)
            }
            Kind::Se2 | Kind::Se3 => {
                let Some(spec) = &file.robot else {
                    return Err(self.invalid(format!(
                        "a {} scene needs a [robot] with one shape (box, mesh, {}convex)",
                        file.space.kind,
                        if kind == Kind::Se2 {
                            "polygon, polygons, "
                        } else {
                            ""
                        }
                    )));
                };
                let robot = if kind == Kind::Se2 {
                    Robot::Polygons(self.robot_2d("[robot]", spec)?)
                } else {
                    Robot::Mesh(self.robot_3d("[robot]", spec)?)
                };
                let obstacles = self.rigid_obstacles(&file, kind)?;
                let radius = match &robot {
                    Robot::Polygons(parts) => parts.iter().map(Polygon::radius).fold(0.0, f64::max),
                    Robot::Mesh(m) => m.radius(),
                    Robot::Point | Robot::Arm(_) | Robot::Bodies(_) | Robot::MeshBodies(_) => 1.0,
                };
                let max = crate::limits::MAX_COORDINATE;
                if !(radius.is_finite() && radius <= max) {
                    return Err(self.invalid(format!(
                        "the robot is too large: its radius about its reference point is \
                         {radius:?}, more than {max:e}, where distances overflow"
                    )));
                }
                let scale =
                    self.rotation_scale(file.space.rotation_scale, radius, "the robot's")?;
                let (lo, hi) = (&file.space.lower, &file.space.upper);
                let space = if kind == Kind::Se2 {
                    Space::se2([lo[0], lo[1]], [hi[0], hi[1]], scale)
                } else {
                    Space::se3([lo[0], lo[1], lo[2]], [hi[0], hi[1], hi[2]], scale)
                }
                .map_err(|e| self.invalid(format!("[space] {e}")))?;
                (robot, obstacles, space)
            }
        };
        Ok(self.assemble(file, space, robot, obstacles))
    }

    /// The scene of `file` with its space, robot and obstacles read: its name (the file's stem
    /// by default), queries and the warnings gathered on the way.
    fn assemble(
        &mut self,
        file: File,
        space: Space,
        robot: Robot,
        obstacles: Vec<Obstacle>,
    ) -> Scene {
        Scene {
            name: file.name.unwrap_or_else(|| default_name(self.path)),
            space,
            robot,
            obstacles,
            queries: file
                .queries
                .into_iter()
                .map(|q| Query {
                    start: q.start,
                    goal: q.goal,
                })
                .collect(),
            source: Some(self.path.to_path_buf()),
            warnings: std::mem::take(&mut self.warnings),
        }
    }

    /// The obstacles of a rigid-body scene, each `[[obstacle]]` one or more.
    fn rigid_obstacles(&mut self, file: &File, kind: Kind) -> Result<Vec<Obstacle>, SceneError> {
        Ok(file
            .obstacles
            .iter()
            .enumerate()
            .map(|(i, o)| self.rigid_obstacle(i + 1, o, kind))
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .flatten()
            .collect())
    }

    /// The weight of a turn against a translation: as given, else the robot's radius about its
    /// reference point (so a turn costs what its farthest point travels).
    /// `whose` names the radius in the error ("the robot's").
    fn rotation_scale(
        &self,
        given: Option<f64>,
        radius: f64,
        whose: &str,
    ) -> Result<f64, SceneError> {
        match given {
            Some(s) if !(s.is_finite() && s > 0.0) => Err(self.invalid(format!(
                "[space] rotation_scale must be a positive number, got {s}"
            ))),
            Some(s) => Ok(s),
            None if radius > 0.0 => Ok(radius),
            None => Err(self.invalid(format!(
                "{whose} radius about its reference point is 0; give [space] rotation_scale"
            ))),
        }
    }

    /// The kind and the number of position bounds it needs.
    fn kind(&self, space: &SpaceSpec) -> Result<(Kind, usize), SceneError> {
        let k = space.kind.as_str();
        Ok(match k {
            "r2" => (Kind::Euclidean, 2),
            "rn" => (Kind::Euclidean, space.lower.len().max(2)),
            "se2" => (Kind::Se2, 2),
            "se3" => (Kind::Se3, 3),
            _ => match k.strip_prefix('r').and_then(|d| d.parse::<usize>().ok()) {
                Some(n) if n >= 2 => (Kind::Euclidean, n),
                _ => {
                    let expected = "r2, rn (or r3, r4 …, n ≥ 2), se2 or se3";
                    return Err(self.invalid(format!(
                        "[space] kind = \"{k}\" is not known; expected {expected}"
                    )));
                }
            },
        })
    }

    /// The one shape of an obstacle or robot table.
    fn one_shape<'s>(
        &self,
        what: &str,
        owner: &str,
        shapes: Vec<Shape<'s>>,
        hint: &str,
    ) -> Result<Shape<'s>, SceneError> {
        let mut shapes = shapes;
        match shapes.len() {
            1 => Ok(shapes.remove(0)),
            0 => Err(self.invalid(format!("{what}: no shape; give {hint}"))),
            _ => Err(self.invalid(format!(
                "{what}: one shape per {owner}, found {}",
                shapes
                    .iter()
                    .map(Shape::name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ))),
        }
    }

    fn disc_obstacle(&self, i: usize, o: &ObstacleSpec, n: usize) -> Result<Obstacle, SceneError> {
        let what = format!("obstacle {i}");
        let hint = "disc = { center, radius }";
        let d = match self.one_shape(&what, "obstacle", o.shapes(), hint)? {
            Shape::Disc(d) => d,
            other => {
                return Err(self.invalid(format!(
                    "{what}: a {} does not belong in an r{n} scene (a point robot among discs); \
                     give {hint}",
                    other.name()
                )))
            }
        };
        if o.offset.is_some() {
            return Err(self.invalid(format!("{what}: offset applies to mesh obstacles only")));
        }
        if d.center.len() != n {
            return Err(self.invalid(format!(
                "{what}: disc center has {} coordinates, the space has {n}",
                d.center.len()
            )));
        }
        if !d.center.iter().all(|c| c.is_finite()) {
            return Err(self.invalid(format!("{what}: disc center is not finite")));
        }
        if !(d.radius.is_finite() && d.radius >= 0.0) {
            return Err(self.invalid(format!(
                "{what}: disc radius must be a non-negative number, got {}",
                d.radius
            )));
        }
        Ok(Obstacle::Disc {
            centre: d.center.clone(),
            radius: d.radius,
        })
    }

    /// A polygon or polyhedron obstacle (several polygons for a mesh footprint).
    fn rigid_obstacle(
        &mut self,
        i: usize,
        o: &ObstacleSpec,
        kind: Kind,
    ) -> Result<Vec<Obstacle>, SceneError> {
        let what = format!("obstacle {i}");
        let (space, hint) = match kind {
            Kind::Se2 => ("se2", "box, mesh, convex or polygon"),
            _ => ("se3", "box, mesh or convex"),
        };
        let shape = self.one_shape(&what, "obstacle", o.shapes(), hint)?;
        if o.offset.is_some() && !matches!(shape, Shape::Mesh(_)) {
            return Err(self.invalid(format!("{what}: offset applies to mesh obstacles only")));
        }
        let misplaced = |name: &str| {
            self.invalid(format!(
                "{what}: a {name} does not belong in a {space} scene{}; use {hint}",
                if name == "disc" {
                    " (discs are obstacles for a point robot in r2/rn)"
                } else {
                    ""
                }
            ))
        };
        if kind == Kind::Se3 {
            let mesh = match shape {
                Shape::Box(b) => self.cuboid(&what, b)?,
                Shape::Convex(c) => self.convex_3d(&what, c)?,
                Shape::Mesh(file) => {
                    let offset = self.vector(&what, "offset", o.offset.as_deref(), 3)?;
                    let mesh = self.mesh_3d(file)?;
                    mesh.translated(Vector3::new(offset[0], offset[1], offset[2]))
                }
                other => return Err(misplaced(other.name())),
            };
            return Ok(vec![Obstacle::Mesh(mesh)]);
        }
        let polygons = match shape {
            Shape::Box(b) => vec![self.rectangle(&what, b)?],
            Shape::Convex(c) => vec![self.convex_2d(&what, c)?],
            Shape::Polygon(p) => vec![self.polygon(&what, p)?],
            Shape::Mesh(file) => {
                let offset = self.vector(&what, "offset", o.offset.as_deref(), 2)?;
                let mesh = mesh_io::load_mesh(&self.resolve(file))?;
                self.footprint(file, &mesh)?
                    .into_iter()
                    .map(|p| p.translated(Vector2::new(offset[0], offset[1])))
                    .collect()
            }
            other => return Err(misplaced(other.name())),
        };
        Ok(polygons.into_iter().map(Obstacle::Polygon).collect())
    }

    /// A polyhedral robot (`what` names it in errors: "[robot]", a body) in its body frame.
    fn robot_3d(&mut self, what: &str, r: &RobotSpec) -> Result<TriMesh, SceneError> {
        let shape = self.one_shape(what, "robot", r.shapes(), "box, mesh or convex")?;
        let (mesh, mean) = match shape {
            Shape::Box(b) => {
                let m = self.cuboid(what, b)?;
                let c = vertex_mean(&m);
                (m, c)
            }
            Shape::Convex(c) => {
                let m = self.convex_3d(what, c)?;
                let c = vertex_mean(&m);
                (m, c)
            }
            Shape::Mesh(file) => {
                let path = self.resolve(file);
                if is_dae(&path) {
                    let dae = collada::load_collada(&path)?;
                    self.warn_if_open(file, &dae.mesh);
                    let c = dae.assimp_centre.map(f64::from);
                    (dae.mesh, Point3::new(c[0], c[1], c[2]))
                } else {
                    let m = self.mesh_3d(file)?;
                    let c = vertex_mean(&m);
                    (m, c)
                }
            }
            Shape::Polygon(_) | Shape::Polygons(_) => {
                return Err(self.invalid(format!(
                    "{what}: polygons describe se2 robots; in a se3 scene use box, convex or \
                     mesh"
                )))
            }
            Shape::Disc(_) => unreachable!("a robot table has no disc"),
        };
        let centre = self.centre(what, r.center.as_ref(), 3, mean.coords.as_slice())?;
        Ok(mesh.translated(-Vector3::new(centre[0], centre[1], centre[2])))
    }

    fn robot_2d(&mut self, what: &str, r: &RobotSpec) -> Result<Vec<Polygon>, SceneError> {
        let hint = "box, mesh, polygon(s) or convex";
        let shape = self.one_shape(what, "robot", r.shapes(), hint)?;
        let parts = match shape {
            Shape::Box(b) => vec![self.rectangle(what, b)?],
            Shape::Convex(c) => vec![self.convex_2d(what, c)?],
            Shape::Polygon(p) => vec![self.polygon(what, p)?],
            Shape::Polygons(ps) => {
                if ps.is_empty() {
                    return Err(self.invalid(format!("{what}: polygons = [] is empty")));
                }
                ps.iter()
                    .enumerate()
                    .map(|(k, p)| self.polygon(&format!("{what} polygon {}", k + 1), p))
                    .collect::<Result<Vec<_>, _>>()?
            }
            Shape::Mesh(file) => {
                let path = self.resolve(file);
                let (mesh, centre) = if is_dae(&path) {
                    let dae = collada::load_collada(&path)?;
                    let c = dae.assimp_centre;
                    (dae.mesh, Point2::new(c[0] as f64, c[1] as f64))
                } else {
                    let m = mesh_io::load_mesh(&path)?;
                    let c = vertex_mean(&m);
                    (m, Point2::new(c.x, c.y))
                };
                let parts = self.footprint(file, &mesh)?;
                let offset = self.centre(what, r.center.as_ref(), 2, centre.coords.as_slice())?;
                let shift = -Vector2::new(offset[0], offset[1]);
                return Ok(parts.into_iter().map(|p| p.translated(shift)).collect());
            }
            Shape::Disc(_) => unreachable!("a robot table has no disc"),
        };
        let mean = polygon_mean(&parts);
        let centre = self.centre(what, r.center.as_ref(), 2, mean.coords.as_slice())?;
        let shift = -Vector2::new(centre[0], centre[1]);
        Ok(parts.into_iter().map(|p| p.translated(shift)).collect())
    }

    /// The reference point: the shape's origin, the mean of its vertices, or a given point.
    fn centre(
        &self,
        what: &str,
        spec: Option<&toml::Value>,
        dim: usize,
        mean: &[f64],
    ) -> Result<Vec<f64>, SceneError> {
        match spec {
            None => Ok(vec![0.0; dim]),
            Some(toml::Value::String(s)) if s == "mean" => Ok(mean[..dim].to_vec()),
            Some(toml::Value::Array(a)) => {
                let v: Option<Vec<f64>> = a
                    .iter()
                    .map(|x| match x {
                        toml::Value::Float(f) => Some(*f),
                        toml::Value::Integer(i) => Some(*i as f64),
                        _ => None,
                    })
                    .collect();
                match v {
                    Some(v) => self.vector(what, "center", Some(&v), dim),
                    None => Err(self.invalid(format!("{what} center must hold numbers"))),
                }
            }
            Some(other) => Err(self.invalid(format!(
                "{what} center = {other} is neither \"mean\" nor a point [x, y{}]",
                if dim == 3 { ", z" } else { "" }
            ))),
        }
    }

    /// A vector of `dim` finite numbers (zero if absent).
    fn vector(
        &self,
        what: &str,
        key: &str,
        v: Option<&[f64]>,
        dim: usize,
    ) -> Result<Vec<f64>, SceneError> {
        let Some(v) = v else {
            return Ok(vec![0.0; dim]);
        };
        if v.len() != dim {
            return Err(self.invalid(format!(
                "{what}: {key} has {} numbers, the space needs {dim}",
                v.len()
            )));
        }
        if !v.iter().all(|x| x.is_finite()) {
            return Err(self.invalid(format!("{what}: {key} has a value that is not finite")));
        }
        Ok(v.to_vec())
    }

    fn geometry(&self, what: &str, e: GeometryError) -> SceneError {
        self.invalid(format!("{what}: {e}"))
    }

    fn cuboid(&self, what: &str, b: &BoxSpec) -> Result<TriMesh, SceneError> {
        let h = self.vector(what, "box half_extents", Some(&b.half_extents), 3)?;
        let c = self.vector(what, "box center", b.center.as_deref(), 3)?;
        TriMesh::cuboid([h[0], h[1], h[2]])
            .map(|m| m.translated(Vector3::new(c[0], c[1], c[2])))
            .map_err(|e| self.geometry(what, e))
    }

    fn rectangle(&self, what: &str, b: &BoxSpec) -> Result<Polygon, SceneError> {
        let h = self.vector(what, "box half_extents", Some(&b.half_extents), 2)?;
        let c = self.vector(what, "box center", b.center.as_deref(), 2)?;
        Polygon::rectangle([c[0], c[1]], [h[0], h[1]]).map_err(|e| self.geometry(what, e))
    }

    fn points<const N: usize>(
        &self,
        what: &str,
        key: &str,
        v: &[Vec<f64>],
    ) -> Result<Vec<[f64; N]>, SceneError> {
        if v.len() > MAX_SHAPE_POINTS {
            return Err(self.invalid(format!(
                "{what}: {} {key}s; at most {MAX_SHAPE_POINTS} are accepted (use a mesh for \
                 more detailed shapes)",
                v.len()
            )));
        }
        v.iter()
            .enumerate()
            .map(|(k, p)| {
                let p = self.vector(what, &format!("{key} {}", k + 1), Some(p), N)?;
                let mut a = [0.0; N];
                a.copy_from_slice(&p);
                Ok(a)
            })
            .collect()
    }

    fn polygon(&self, what: &str, p: &PolygonSpec) -> Result<Polygon, SceneError> {
        let v = self.points::<2>(what, "polygon vertex", &p.vertices)?;
        let vertices: Vec<Point2<f64>> = v.iter().map(|[x, y]| Point2::new(*x, *y)).collect();
        // crossing edges first: a bow tie has zero signed area, and "needs a positive area"
        // would not say what is wrong with it
        // (vertices all on one line have no area in any sense: that message stays theirs)
        let spread = vertices.windows(2).skip(1).any(|w| {
            let (a, b) = (w[0] - vertices[0], w[1] - vertices[0]);
            a.x * b.y - a.y * b.x != 0.0
        });
        let crosses = spread
            && !is_simple(&Polygon {
                vertices: vertices.clone(),
            });
        let polygon = if crosses {
            None
        } else {
            Some(Polygon::new(vertices).map_err(|e| self.geometry(what, e))?)
        };
        let Some(polygon) = polygon.filter(is_simple) else {
            return Err(self.invalid(format!(
                "{what}: the polygon's edges cross or touch; give a simple polygon (or several)"
            )));
        };
        Ok(polygon)
    }

    fn convex_2d(&self, what: &str, c: &ConvexSpec) -> Result<Polygon, SceneError> {
        let v = self.points::<2>(what, "convex point", &c.points)?;
        let pts: Vec<Point2<f64>> = v.iter().map(|[x, y]| Point2::new(*x, *y)).collect();
        convex_hull_2d(&pts).map_err(|_| {
            self.invalid(format!(
                "{what}: the convex hull of the points has no area (give at least 3 points \
                 not on a line)"
            ))
        })
    }

    fn convex_3d(&self, what: &str, c: &ConvexSpec) -> Result<TriMesh, SceneError> {
        let v = self.points::<3>(what, "convex point", &c.points)?;
        let pts: Vec<Point3<f64>> = v.iter().map(|p| Point3::from(*p)).collect();
        convex_hull_3d(&pts).map_err(|_| {
            self.invalid(format!(
                "{what}: the convex hull of the points has no volume (give at least 4 points \
                 not in a plane)"
            ))
        })
    }

    fn resolve(&self, file: &str) -> PathBuf {
        self.path
            .parent()
            .unwrap_or_else(|| Path::new("."))
            .join(file)
    }

    fn mesh_3d(&mut self, file: &str) -> Result<TriMesh, SceneError> {
        let mesh = mesh_io::load_mesh(&self.resolve(file))?;
        self.warn_if_open(file, &mesh);
        Ok(mesh)
    }

    fn warn_if_open(&mut self, file: &str, mesh: &TriMesh) {
        if !mesh.is_closed() {
            self.warnings.push(open_mesh_warning(file));
        }
    }

    fn footprint(&self, file: &str, mesh: &TriMesh) -> Result<Vec<Polygon>, SceneError> {
        let f = footprint_polygons(mesh);
        if f.is_empty() {
            return Err(SceneError::Geometry {
                path: self.resolve(file),
                source: GeometryError::Empty,
            });
        }
        Ok(f)
    }
}

/// The shape given in a robot or obstacle table.
enum Shape<'a> {
    Box(&'a BoxSpec),
    Mesh(&'a str),
    Polygon(&'a PolygonSpec),
    Polygons(&'a [PolygonSpec]),
    Convex(&'a ConvexSpec),
    Disc(&'a DiscSpec),
}

impl Shape<'_> {
    fn name(&self) -> &'static str {
        match self {
            Shape::Box(_) => "box",
            Shape::Mesh(_) => "mesh",
            Shape::Polygon(_) => "polygon",
            Shape::Polygons(_) => "polygons",
            Shape::Convex(_) => "convex",
            Shape::Disc(_) => "disc",
        }
    }
}

impl ObstacleSpec {
    fn shapes(&self) -> Vec<Shape<'_>> {
        let mut v = Vec::new();
        v.extend(self.cuboid.as_ref().map(Shape::Box));
        v.extend(self.mesh.as_deref().map(Shape::Mesh));
        v.extend(self.polygon.as_ref().map(Shape::Polygon));
        v.extend(self.convex.as_ref().map(Shape::Convex));
        v.extend(self.disc.as_ref().map(Shape::Disc));
        v
    }
}

impl RobotSpec {
    fn shapes(&self) -> Vec<Shape<'_>> {
        let mut v = Vec::new();
        v.extend(self.cuboid.as_ref().map(Shape::Box));
        v.extend(self.mesh.as_deref().map(Shape::Mesh));
        v.extend(self.polygon.as_ref().map(Shape::Polygon));
        v.extend(self.polygons.as_deref().map(Shape::Polygons));
        v.extend(self.convex.as_ref().map(Shape::Convex));
        v
    }
}

/// Mean of the distinct vertices of some polygons.
fn polygon_mean(parts: &[Polygon]) -> Point2<f64> {
    let mut seen = std::collections::HashSet::new();
    let (mut sum, mut n) = (Vector2::zeros(), 0usize);
    for v in parts.iter().flat_map(|p| &p.vertices) {
        if seen.insert([v.x.to_bits(), v.y.to_bits()]) {
            sum += v.coords;
            n += 1;
        }
    }
    Point2::from(sum / n.max(1) as f64)
}
