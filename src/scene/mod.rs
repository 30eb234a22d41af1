//! Scenes: bounds, robot, obstacles and queries, from a TOML file or an OMPL.app `.cfg`.
//!
//! A scene turns into the oracle for its space ([`Scene::oracle`]): a point among discs in
//! R^n, a polygonal robot among polygons in SE(2), a polyhedral robot among polyhedra in SE(3),
//! always with "outside the bounds is obstacle".
//!
//! | module | reads |
//! |---|---|
//! | [`toml_format`] | viaroad's TOML scenes (the format is documented there) |
//! | [`arm`] | arm scenes: a URDF robot's planning group in a MoveIt scene (`kind = "arm"`) |
//! | [`ompl_cfg`] | OMPL.app problems (`.cfg`), OMPL path files and query-pair files |
//! | [`mesh_io`] | meshes: Wavefront OBJ, STL |
//! | [`moveit`] | MoveIt PlanningScene and MotionPlanRequest YAML (robot arms) |
//! | [`collada`] | Collada meshes as OMPL.app sees them through assimp (frame, robot centre) |
//! | [`shapes`] | convex hulls, 2D footprints of prism meshes, simple-polygon check |

pub mod arm;
pub mod collada;
pub mod mesh_io;
pub mod moveit;
pub mod ompl_cfg;
pub mod toml_format;
mod yaml_depth;

pub use crate::geometry::hull as shapes;
use crate::geometry::{GeometryError, Polygon, TriMesh};
use crate::mesh_io::MeshError;
use crate::oracle::bodies::PlanarBodies;
use crate::oracle::bodies3::SolidBodies;
use crate::oracle::discs::Discs;
use crate::oracle::polygons::Polygons;
use crate::oracle::polyhedra::Polyhedra;
use crate::oracle::{Bounded, CallCounts, CollisionOracle, CountedOracle};
use crate::safe_file::FileError;
use crate::space::{Config, Space, SpaceError, SpaceKind};
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

/// Refuses robot and obstacle coordinates beyond [`crate::limits::MAX_COORDINATE`] (and disc
/// radii beyond it): the oracles square and multiply coordinates, which would overflow into
/// infinities and NaNs. The bounds are checked by [`Space`] itself.
pub(crate) fn check_magnitudes(scene: &Scene) -> Result<(), SceneError> {
    let max = crate::limits::MAX_COORDINATE;
    let too_big = |what: String| SceneError::Invalid {
        path: scene.source.clone().unwrap_or_default(),
        message: format!("{what} has a coordinate beyond ±{max:e}, where distances overflow"),
    };
    let big = |v: f64| v.is_nan() || v.abs() > max;
    match &scene.robot {
        // the robot's own files refuse such numbers as they are read
        Robot::Point | Robot::Arm(_) => {}
        Robot::Polygons(parts) => {
            if parts
                .iter()
                .flat_map(|p| &p.vertices)
                .any(|v| big(v.x) || big(v.y))
            {
                return Err(too_big("the robot".into()));
            }
        }
        Robot::Mesh(m) => {
            if m.vertices.iter().any(|v| big(v.x) || big(v.y) || big(v.z)) {
                return Err(too_big("the robot".into()));
            }
        }
        Robot::Bodies(bodies) => {
            for b in bodies {
                if b.parts
                    .iter()
                    .flat_map(|p| &p.vertices)
                    .any(|v| big(v.x) || big(v.y))
                {
                    return Err(too_big(format!("body \"{}\"", b.name)));
                }
            }
        }
        Robot::MeshBodies(bodies) => {
            for b in bodies {
                if b.mesh
                    .vertices
                    .iter()
                    .any(|v| big(v.x) || big(v.y) || big(v.z))
                {
                    return Err(too_big(format!("body \"{}\"", b.name)));
                }
            }
        }
    }
    for (i, o) in scene.obstacles.iter().enumerate() {
        let bad = match o {
            Obstacle::Disc { centre, radius } => centre.iter().any(|&c| big(c)) || big(*radius),
            Obstacle::Polygon(p) => p.vertices.iter().any(|v| big(v.x) || big(v.y)),
            Obstacle::Mesh(m) => m.vertices.iter().any(|v| big(v.x) || big(v.y) || big(v.z)),
        };
        if bad {
            return Err(too_big(format!("obstacle {}", i + 1)));
        }
    }
    Ok(())
}

/// Checks the scene's queries as it loads. A malformed query (wrong length, not a number, a
/// zero quaternion) is an error of the file; a well-formed one outside the bounds or in
/// collision only stops the commands that answer it ([`Scene::checked_queries`]): a roadmap
/// of the scene does not need its queries, so for `build` it is a warning.
pub(crate) fn check_queries_on_load(scene: &mut Scene) -> Result<(), SceneError> {
    match toml_format::checked_queries(scene) {
        Ok(queries) => scene.queries = queries,
        Err(e @ SceneError::Config { .. }) => return Err(e),
        Err(e) => scene
            .warnings
            .push(format!("{e}: the scene's queries cannot be answered")),
    }
    Ok(())
}

/// The name a scene gets when its file gives none: the file name without extension.
pub(crate) fn default_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into())
}

/// Warnings for the scene's SE(3) queries whose quaternion is not of unit length (within
/// 10⁻⁶): they are normalised, as OMPL's `SO3StateSpace::enforceBounds` does, but a length far
/// from 1 may be a typo, so it is said rather than corrected silently.
pub(crate) fn quaternion_warnings(scene: &Scene) -> Vec<String> {
    let bodies = match scene.space.kind() {
        SpaceKind::Se3 => 1,
        SpaceKind::Se3Bodies(k) => k,
        _ => return Vec::new(),
    };
    let mut out = Vec::new();
    for (i, q) in scene.queries.iter().enumerate() {
        for (what, c) in [("start", &q.start), ("goal", &q.goal)] {
            for b in 0..bodies {
                let Some(quat) = c.get(7 * b + 3..7 * b + 7) else {
                    continue;
                };
                let n = quat.iter().map(|v| v * v).sum::<f64>().sqrt();
                if n.is_finite() && n >= 1e-9 && (n - 1.0).abs() > 1e-6 {
                    let whose = if bodies > 1 {
                        format!("body {}'s quaternion", b + 1)
                    } else {
                        "quaternion".into()
                    };
                    out.push(format!(
                        "{what} of query {}: {whose} of length {n} normalised to length 1",
                        i + 1
                    ));
                }
            }
        }
    }
    out
}

/// The moving body.
#[derive(Clone, Debug, PartialEq)]
pub enum Robot {
    /// A point (R^n scenes).
    Point,
    /// The union of polygons in the body frame (SE(2) scenes); the reference point is the origin.
    Polygons(Vec<Polygon>),
    /// A triangle mesh in the body frame (SE(3) scenes); the reference point is the origin.
    Mesh(TriMesh),
    /// A robot arm's planning group among a MoveIt environment (joint-space scenes);
    /// the environment lives here, not in [`Scene::obstacles`].
    Arm(Box<arm::ArmRobot>),
    /// Several bodies that move concurrently (SE(2)^k scenes, [`crate::space::bodies`]), in
    /// the order of their poses in a configuration.
    Bodies(Vec<Body>),
    /// Several rigid bodies that move concurrently in space (SE(3)^k scenes,
    /// [`crate::space::bodies3`]), in the order of their poses in a configuration.
    MeshBodies(Vec<MeshBody>),
}

/// One of several moving bodies in space.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshBody {
    /// Its name in the scene file (unique within the scene).
    pub name: String,
    /// A triangle mesh in its body frame; its reference point is the origin.
    pub mesh: TriMesh,
}

/// One of several moving bodies.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Its name in the scene file (unique within the scene).
    pub name: String,
    /// The union of polygons in its body frame; its reference point is the origin.
    pub parts: Vec<Polygon>,
}

/// A fixed obstacle.
#[derive(Clone, Debug, PartialEq)]
pub enum Obstacle {
    /// A closed ball (a disc in the plane).
    Disc {
        /// Centre.
        centre: Vec<f64>,
        /// Radius (≥ 0).
        radius: f64,
    },
    /// A polygon (SE(2) scenes; boxes become rectangles).
    Polygon(Polygon),
    /// A triangle mesh (SE(3) scenes; boxes become closed cuboids).
    Mesh(TriMesh),
}

/// A start and a goal.
#[derive(Clone, Debug, PartialEq)]
pub struct Query {
    /// Start configuration.
    pub start: Config,
    /// Goal configuration.
    pub goal: Config,
}

/// A motion planning scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Name (from the file).
    pub name: String,
    /// Configuration space with bounds.
    pub space: Space,
    /// The moving body.
    pub robot: Robot,
    /// The fixed obstacles.
    pub obstacles: Vec<Obstacle>,
    /// The scene's own queries.
    pub queries: Vec<Query>,
    /// The file it was read from, if any.
    pub source: Option<PathBuf>,
    /// Things worth telling the user (open meshes whose containment cannot be decided …).
    pub warnings: Vec<String>,
}

impl Scene {
    /// Reads a scene: `.toml` in viaroad's format, `.cfg` as an OMPL.app problem.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        match path.extension().and_then(|e| e.to_str()) {
            Some("cfg") => ompl_cfg::load(path),
            _ => toml_format::load(path),
        }
    }

    /// The scene's own queries, checked (shape, bounds, collision) and normalised: what the
    /// commands that answer them use. Loading accepts a scene whose queries lie outside the
    /// bounds or in collision (with a warning: a roadmap does not need them); this is where
    /// that becomes an error.
    pub fn checked_queries(&self) -> Result<Vec<Query>, SceneError> {
        toml_format::checked_queries(self)
    }

    /// The polygonal obstacles of a planar scene (none in other scenes).
    pub fn polygon_obstacles(&self) -> Vec<Polygon> {
        self.obstacles
            .iter()
            .filter_map(|o| match o {
                Obstacle::Polygon(p) => Some(p.clone()),
                _ => None,
            })
            .collect()
    }

    /// The mesh obstacles of a scene in space (none in other scenes).
    pub fn mesh_obstacles(&self) -> Vec<TriMesh> {
        self.obstacles
            .iter()
            .filter_map(|o| match o {
                Obstacle::Mesh(m) => Some(m.clone()),
                _ => None,
            })
            .collect()
    }

    /// The collision oracle of this scene, with "outside the bounds is obstacle".
    pub fn oracle(&self) -> Box<dyn CollisionOracle> {
        match (&self.robot, self.space.kind()) {
            (Robot::Point, SpaceKind::Euclidean(n)) => {
                let (centres, radii): (Vec<Vec<f64>>, Vec<f64>) = self
                    .obstacles
                    .iter()
                    .filter_map(|o| match o {
                        Obstacle::Disc { centre, radius } => Some((centre.clone(), *radius)),
                        _ => None,
                    })
                    .unzip();
                Box::new(Bounded::new(
                    self.space.clone(),
                    Discs::new(n, &centres, &radii),
                ))
            }
            (Robot::Polygons(parts), _) => {
                let obstacles = self.polygon_obstacles();
                Box::new(Bounded::new(
                    self.space.clone(),
                    Polygons::new(parts.clone(), obstacles),
                ))
            }
            (Robot::Mesh(mesh), _) => {
                let obstacles = self
                    .obstacles
                    .iter()
                    .filter_map(|o| match o {
                        Obstacle::Mesh(m) => Some(m.clone()),
                        _ => None,
                    })
                    .collect();
                Box::new(Bounded::new(
                    self.space.clone(),
                    Polyhedra::new(mesh.clone(), obstacles),
                ))
            }
            (Robot::Bodies(bodies), _) => {
                let obstacles = self.polygon_obstacles();
                let parts = bodies.iter().map(|b| b.parts.clone()).collect();
                Box::new(Bounded::new(
                    self.space.clone(),
                    PlanarBodies::new(parts, obstacles),
                ))
            }
            (Robot::MeshBodies(bodies), _) => {
                let meshes = bodies.iter().map(|b| b.mesh.clone()).collect();
                Box::new(Bounded::new(
                    self.space.clone(),
                    SolidBodies::new(meshes, self.mesh_obstacles()),
                ))
            }
            (Robot::Arm(a), _) => Box::new(Bounded::new(
                self.space.clone(),
                arm::ArmCollision::new(a.arm_oracle().clone()),
            )),
            (Robot::Point, _) => unreachable!("the loaders only pair a point robot with R^n"),
        }
    }

    /// Checks a configuration given by a user: shape, finiteness, bounds and freedom from
    /// collision. Returns it normalised (angle wrapped, quaternion unit length).
    pub fn check_config(
        &self,
        oracle: &dyn CollisionOracle,
        what: &str,
        q: &[f64],
    ) -> Result<Config, SceneError> {
        self.space.check(q).map_err(|source| SceneError::Config {
            what: what.to_string(),
            source,
        })?;
        let mut q = q.to_vec();
        self.space.normalize(&mut q);
        if !self.space.in_bounds(&q) {
            return Err(SceneError::OutOfBounds {
                what: what.to_string(),
                config: q,
            });
        }
        if !oracle.is_free(&q, &mut CallCounts::default()) {
            return Err(SceneError::InCollision {
                what: what.to_string(),
                config: q,
            });
        }
        Ok(q)
    }

    /// A 64-bit fingerprint of what decides collisions: space kind, bounds, rotation scale,
    /// robot and obstacle geometry (not the name, not the queries). A roadmap records it and is
    /// refused for any other scene.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Fnv::new();
        h.str(&self.space.kind().to_string());
        h.floats(self.space.lower());
        h.floats(self.space.upper());
        h.floats(&[self.space.rotation_scale()]);
        match &self.robot {
            Robot::Point => h.str("point"),
            Robot::Polygons(parts) => {
                h.str("polygons");
                parts.iter().for_each(|p| h.polygon(p));
            }
            Robot::Mesh(m) => {
                h.str("mesh");
                h.mesh(m);
            }
            Robot::Arm(a) => h.bytes(&a.digest().to_le_bytes()),
            Robot::Bodies(bodies) => {
                h.str("bodies");
                for b in bodies {
                    h.bytes(&(b.parts.len() as u64).to_le_bytes());
                    b.parts.iter().for_each(|p| h.polygon(p));
                }
            }
            Robot::MeshBodies(bodies) => {
                h.str("mesh bodies");
                bodies.iter().for_each(|b| h.mesh(&b.mesh));
            }
        }
        for o in &self.obstacles {
            match o {
                Obstacle::Disc { centre, radius } => {
                    h.str("disc");
                    h.floats(centre);
                    h.floats(&[*radius]);
                }
                Obstacle::Polygon(p) => {
                    h.str("polygon");
                    h.polygon(p);
                }
                Obstacle::Mesh(m) => {
                    h.str("mesh");
                    h.mesh(m);
                }
            }
        }
        h.finish()
    }
}

/// FNV-1a, 64 bit: stable across platforms and versions (unlike `std`'s hasher).
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= x as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn str(&mut self, s: &str) {
        self.bytes(&(s.len() as u64).to_le_bytes());
        self.bytes(s.as_bytes());
    }
    fn floats(&mut self, v: &[f64]) {
        self.bytes(&(v.len() as u64).to_le_bytes());
        v.iter()
            .for_each(|x| self.bytes(&x.to_bits().to_le_bytes()));
    }
    fn polygon(&mut self, p: &Polygon) {
        let v: Vec<f64> = p.vertices.iter().flat_map(|v| [v.x, v.y]).collect();
        self.floats(&v);
    }
    fn mesh(&mut self, m: &TriMesh) {
        let v: Vec<f64> = m.vertices.iter().flat_map(|v| [v.x, v.y, v.z]).collect();
        self.floats(&v);
        self.bytes(&(m.triangles.len() as u64).to_le_bytes());
        m.triangles
            .iter()
            .flatten()
            .for_each(|i| self.bytes(&i.to_le_bytes()));
    }
    fn finish(&self) -> u64 {
        self.0
    }
}
