//! Seeing a plan in 3D: a scene, its robot and a path as a glTF 2.0 binary, and a
//! self-contained HTML page that plays it.
//!
//! | module | concept |
//! |---|---|
//! | [`gltf`] | the small `.glb` writer: buffer, accessors, TRS nodes, linear animations |
//! | [`animation`] | a path as keyframes that move one DOF group at a time, as the planner does |
//! | [`arm`] | a robot arm's links animated by forward kinematics |
//! | [`bodies`] | several bodies, each in its own colour, animated together |
//! | [`html`] | the viewer page: three.js (vendored, pinned) and the `.glb`, both inline |
//!
//! The glTF frame is Y-up. Z-up scenes (viaroad's TOML, planar problems, MoveIt, and those
//! of OMPL.app's 3D problems that stand on z = 0, see `is_z_up`) sit under a root node turned
//! by −90° about x; the others are written as they are. The robot's node is placed at the reference point
//! with the state's quaternion, which glTF and OMPL both order `[x, y, z, w]`.

pub mod animation;
pub mod arm;
pub mod bodies;
pub mod gltf;
pub mod html;

use crate::geometry::TriMesh;
use crate::roadmap::Roadmap;
use crate::scene::{Obstacle, Robot, Scene};
use crate::space::{Config, Group, Space, SpaceKind};
use gltf::{Gltf, Mode, Track, Trs};
use serde::Serialize;

/// What cannot be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// Only spaces with a picture in three dimensions: R², R³, SE(2), SE(3), arms, several
    /// bodies in the plane.
    #[error(
        "cannot draw a {0} scene in 3D: only R², R³, SE(2), SE(3), arms and several bodies in the plane"
    )]
    Unsupported(String),
    /// A path state that does not fit the scene.
    #[error("state {index} of the {which} path: {message}")]
    Path {
        /// "raw" or "shortened".
        which: &'static str,
        /// 0-based index of the state.
        index: usize,
        /// What is wrong.
        message: String,
    },
}

/// What the viewer's legend shows; stored in the `.glb` as `asset.extras.legend`.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Legend {
    /// The scene's name.
    pub scene: String,
    /// The configuration space (`se3`, `r2`, `arm 7 joints` …).
    pub space: String,
    /// How the path was found ("local method", "roadmap file …", "path file …").
    pub source: String,
    /// Length of the raw path in the space's metric.
    pub raw_length: Option<f64>,
    /// Length of the shortened path.
    pub length: Option<f64>,
    /// Oracle calls spent finding (and shortening) the path.
    pub calls: Option<u64>,
    /// One row per path trace drawn, in the trace's colour ([`Legend::set_paths`]).
    pub paths: Vec<PathRow>,
    /// The moving bodies of a scene of several bodies, each in its colour
    /// ([`Legend::set_bodies`]); empty for one robot.
    pub bodies: Vec<BodyRow>,
}

/// A moving body as the legend names it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct BodyRow {
    /// The body's name in the scene.
    pub name: String,
    /// Its colour (CSS, `#rrggbb`).
    pub colour: String,
}

/// A path trace as the legend names it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct PathRow {
    /// What the row says: "shortened path", "given path — collides in segment 3 at t = 0.410".
    pub label: String,
    /// The trace's colour (CSS, `#rrggbb`): the key beside the label.
    pub colour: String,
    /// The path's length in the space's metric.
    pub length: f64,
    /// The path collides: the row is a warning, in the warning colour.
    pub collides: bool,
}

impl Legend {
    /// Names the traces of `plan` (as [`scene_gltf`] and [`arm::arm_gltf`] draw them): where
    /// there is a shortened path, it (blue) and the raw path called `raw_name` (red); else
    /// the raw path alone, blue, or in the warning colour with `collision` (where and how it
    /// collides) said. Only a path checked free is ever shortened, so a collision is the raw
    /// path's. Lengths are in the space's metric.
    pub fn set_paths(
        &mut self,
        plan: &Plan,
        raw_name: &str,
        raw_length: f64,
        length: f64,
        collision: Option<&str>,
    ) {
        let row = |label: String, hex: u32, length: f64, collides: bool| PathRow {
            label,
            colour: colour::css(hex),
            // `+ 0.0` turns a `-0.0` into `0.0`: a length is never negative
            length: length + 0.0,
            collides,
        };
        let raw = match collision {
            Some(c) => row(
                format!("{raw_name} — {c}"),
                colour::WARNING,
                raw_length,
                true,
            ),
            None if plan.shortened.is_empty() => {
                row(raw_name.to_string(), colour::SHORT_PATH, raw_length, false)
            }
            None => row(raw_name.to_string(), colour::RAW_PATH, raw_length, false),
        };
        self.paths = if plan.shortened.is_empty() {
            vec![raw]
        } else {
            vec![
                row("shortened path".into(), colour::SHORT_PATH, length, false),
                raw,
            ]
        };
        self.raw_length = Some(raw_length + 0.0);
        self.length = Some(length + 0.0);
    }

    /// Names the bodies of a scene of several bodies in the colours [`bodies::bodies_gltf`]
    /// draws them in (nothing for a scene of one robot).
    pub fn set_bodies(&mut self, scene: &Scene) {
        self.bodies = match &scene.robot {
            Robot::Bodies(b) => b
                .iter()
                .enumerate()
                .map(|(i, b)| BodyRow {
                    name: b.name.clone(),
                    colour: colour::css(bodies::body_colour(i)),
                })
                .collect(),
            _ => Vec::new(),
        };
    }

    /// The colour of the trace of `plan`'s raw path (sRGB hex): red beside a shortened path;
    /// alone, blue, or the warning colour where the legend says it collides.
    pub(crate) fn raw_colour(&self, plan: &Plan) -> u32 {
        if !plan.shortened.is_empty() {
            colour::RAW_PATH
        } else if self.paths.iter().any(|r| r.collides) {
            colour::WARNING
        } else {
            colour::SHORT_PATH
        }
    }
}

/// The paths to draw: the planner's raw path and its shortened version (either may be empty).
/// The robot follows the shortened path, or the raw one where there is no shortened path.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// Corners of the path as found.
    pub raw: Vec<Config>,
    /// Corners of the shortened path.
    pub shortened: Vec<Config>,
}

impl Plan {
    /// The path the robot follows.
    pub fn animated(&self) -> &[Config] {
        if self.shortened.is_empty() {
            &self.raw
        } else {
            &self.shortened
        }
    }
}

/// Colours (sRGB hex, as in [`crate::render`]'s SVG) turned into glTF's linear factors.
mod colour {
    pub const OBSTACLE: u32 = 0x9aa5b1;
    pub const ROBOT: u32 = 0x3ebd93;
    pub const RAW_PATH: u32 = 0xe12d39;
    pub const SHORT_PATH: u32 = 0x0967d2;
    pub const ROADMAP: u32 = 0x7b8794;
    pub const BOUNDS: u32 = 0x1f2933;
    /// A path that collides: orange, apart from the raw path's red and the valid path's blue.
    pub const WARNING: u32 = 0xe8590c;

    /// `hex` as CSS.
    pub fn css(hex: u32) -> String {
        format!("#{hex:06x}")
    }

    /// `hex` as linear RGBA with opacity `alpha`.
    pub fn linear(hex: u32, alpha: f32) -> [f32; 4] {
        let c = |shift: u32| {
            let s = ((hex >> shift) & 0xff) as f32 / 255.0;
            if s <= 0.04045 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            }
        };
        [c(16), c(8), c(0), alpha]
    }
}

/// Node names the viewer and the browser test look for.
pub mod names {
    /// The root node (turns Z-up scenes to glTF's Y-up).
    pub const WORLD: &str = "world";
    /// The obstacles.
    pub const ENVIRONMENT: &str = "environment";
    /// The moving robot (for an arm: the parent of its links).
    pub const ROBOT: &str = "robot";
    /// The raw path's trace.
    pub const RAW_PATH: &str = "raw path";
    /// The shortened path's trace.
    pub const SHORT_PATH: &str = "shortened path";
    /// The roadmap's nodes and edges.
    pub const ROADMAP: &str = "roadmap";
    /// The scene's bounds.
    pub const BOUNDS: &str = "bounds";
}

/// A triangle soup being assembled: f32 positions and u32 indices.
#[derive(Default)]
pub(crate) struct Soup {
    pub positions: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
}

impl Soup {
    /// Appends a mesh placed by `f` (vertex → world).
    pub fn mesh(&mut self, m: &TriMesh, f: impl Fn([f64; 3]) -> [f64; 3]) {
        let base = self.positions.len() as u32;
        self.positions.extend(
            m.vertices
                .iter()
                .map(|v| f([v.x, v.y, v.z]).map(|c| c as f32)),
        );
        self.indices
            .extend(m.triangles.iter().flatten().map(|i| base + i));
    }

    /// Appends the prism over the counter-clockwise polygon `poly` between heights `z0 < z1`.
    pub fn prism(&mut self, poly: &[[f64; 2]], z0: f64, z1: f64) {
        let n = poly.len() as u32;
        if n < 3 {
            return;
        }
        let base = self.positions.len() as u32;
        for z in [z0, z1] {
            self.positions
                .extend(poly.iter().map(|p| [p[0] as f32, p[1] as f32, z as f32]));
        }
        for t in crate::geometry::triangulate::triangulate(poly) {
            let [a, b, c] = t.map(|i| i as u32);
            self.indices
                .extend([base + n + a, base + n + b, base + n + c]);
            self.indices.extend([base + a, base + c, base + b]);
        }
        for i in 0..n {
            let j = (i + 1) % n;
            self.indices.extend([
                base + i,
                base + j,
                base + n + j,
                base + i,
                base + n + j,
                base + n + i,
            ]);
        }
    }

    /// Appends a sphere (a UV sphere of 16 × 8 quads).
    pub fn sphere(&mut self, c: [f64; 3], r: f64) {
        let (slices, bands) = (16u32, 8u32);
        let base = self.positions.len() as u32;
        for b in 0..=bands {
            let phi = std::f64::consts::PI * b as f64 / bands as f64;
            for s in 0..slices {
                let th = std::f64::consts::TAU * s as f64 / slices as f64;
                self.positions.push(
                    [
                        c[0] + r * phi.sin() * th.cos(),
                        c[1] + r * phi.sin() * th.sin(),
                        c[2] + r * phi.cos(),
                    ]
                    .map(|v| v as f32),
                );
            }
        }
        for b in 0..bands {
            for s in 0..slices {
                let t = (s + 1) % slices;
                let (a0, a1) = (base + b * slices + s, base + b * slices + t);
                let (b0, b1) = (a0 + slices, a1 + slices);
                if b > 0 {
                    self.indices.extend([a0, b0, a1]);
                }
                if b + 1 < bands {
                    self.indices.extend([a1, b0, b1]);
                }
            }
        }
    }

    /// Adds the soup to `g` as a mesh under a new node.
    pub fn add(&self, g: &mut Gltf, name: &str, material: usize, parent: usize) -> usize {
        let mesh = g.mesh(
            name,
            &self.positions,
            Some(&self.indices),
            Mode::Triangles,
            material,
        );
        g.node(name, mesh, Trs::IDENTITY, Some(parent))
    }
}

/// A regular polygon of `sides` corners approximating the circle (`centre`, `r`).
fn circle(centre: [f64; 2], r: f64, sides: usize) -> Vec<[f64; 2]> {
    (0..sides)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / sides as f64;
            [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
        })
        .collect()
}

/// The root node and the rotation that makes a Z-up scene Y-up (OMPL.app's 3D problems are
/// Y-up already).
pub(crate) fn world_node(g: &mut Gltf, z_up: bool) -> usize {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let trs = if z_up {
        Trs {
            translation: [0.0; 3],
            rotation: [-h, 0.0, 0.0, h],
        }
    } else {
        Trs::IDENTITY
    };
    g.node(names::WORLD, None, trs, None)
}

/// Whether the scene's coordinates are Z-up. viaroad's own scenes and planar problems are;
/// OMPL.app's 3D problems state no up axis (assimp turns SketchUp's Z-up into Y-up, yet Home
/// and Apartment stand on z = 0): the one of y and z along which the volume is flatter is
/// taken as up (z for Home, Apartment, cubicles; y for Easy, Twistycool).
fn is_z_up(scene: &Scene) -> bool {
    let from_cfg = scene
        .source
        .as_ref()
        .and_then(|p| p.extension())
        .is_some_and(|e| e == "cfg");
    if !(from_cfg && scene.space.kind() == SpaceKind::Se3) {
        return true;
    }
    let (lo, hi) = (scene.space.lower(), scene.space.upper());
    hi[2] - lo[2] < hi[1] - lo[1]
}

/// The box `lower..upper` (z from `z` where the space is planar) as 12 line segments.
pub(crate) fn bounds_lines(lo: [f64; 3], hi: [f64; 3]) -> Vec<[f32; 3]> {
    let corner = |i: usize| {
        [0, 1, 2].map(|k| {
            if i >> k & 1 == 1 {
                hi[k] as f32
            } else {
                lo[k] as f32
            }
        })
    };
    let mut out = Vec::new();
    for i in 0..8usize {
        for k in 0..3 {
            if i >> k & 1 == 0 {
                out.push(corner(i));
                out.push(corner(i | 1 << k));
            }
        }
    }
    out
}

/// Checks that every state of the paths has the space's dimension and finite coordinates.
fn check_plan(space: &Space, plan: &Plan) -> Result<(), ExportError> {
    for (which, path) in [("raw", &plan.raw), ("shortened", &plan.shortened)] {
        for (index, q) in path.iter().enumerate() {
            space.check(q).map_err(|e| ExportError::Path {
                which,
                index,
                message: e.to_string(),
            })?;
        }
    }
    Ok(())
}

/// The scene, its robot following the plan, the traces of both paths and optionally a
/// roadmap, as a glTF document (see the module doc for frames and conventions).
pub fn scene_gltf(
    scene: &Scene,
    groups: &[Group],
    plan: &Plan,
    roadmap: Option<&Roadmap>,
    legend: &Legend,
) -> Result<Gltf, ExportError> {
    let space = &scene.space;
    let kind = space.kind();
    check_plan(space, plan)?;
    match (&scene.robot, kind) {
        (Robot::Arm(a), SpaceKind::Joints { continuous, .. }) => {
            return arm::arm_gltf(&a.arm, &a.objects, plan, continuous, legend);
        }
        (Robot::Bodies(_), _) => return bodies::bodies_gltf(scene, groups, plan, roadmap, legend),
        (_, SpaceKind::Euclidean(2..=3) | SpaceKind::Se2 | SpaceKind::Se3) => {}
        _ => return Err(ExportError::Unsupported(kind.to_string())),
    }
    let planar = space.position_dim() == 2;
    let (lo, hi) = (space.lower(), space.upper());
    let span = (0..space.position_dim())
        .map(|i| hi[i] - lo[i])
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    // planar scenes stand on z = 0: obstacles this high, the robot a little lower, the traces
    // just above everything
    let height = 0.04 * span;
    let robot_height = 0.6 * height;
    let trace_z = if planar { 1.05 * height } else { 0.0 };

    let mut g = Gltf::new();
    let world = world_node(&mut g, is_z_up(scene));
    // in 3D the robot passes behind walls and into rooms: translucent obstacles keep it in
    // sight; planar obstacles are low prisms seen from above, opaque
    let opacity = if planar { 1.0 } else { 0.55 };
    let m_obstacle = g.material("obstacle", colour::linear(colour::OBSTACLE, opacity), false);
    let m_robot = g.material("robot", colour::linear(colour::ROBOT, 1.0), false);

    let mut env = Soup::default();
    for o in &scene.obstacles {
        match o {
            Obstacle::Disc { centre, radius } if planar => {
                env.prism(&circle([centre[0], centre[1]], *radius, 48), 0.0, height)
            }
            Obstacle::Disc { centre, radius } => {
                env.sphere([centre[0], centre[1], centre[2]], *radius)
            }
            Obstacle::Polygon(p) => {
                let v: Vec<[f64; 2]> = p.vertices.iter().map(|v| [v.x, v.y]).collect();
                env.prism(&v, 0.0, height);
            }
            Obstacle::Mesh(m) => env.mesh(m, |v| v),
        }
    }
    env.add(&mut g, names::ENVIRONMENT, m_obstacle, world);

    let (blo, bhi) = if planar {
        ([lo[0], lo[1], 0.0], [hi[0], hi[1], height])
    } else {
        ([lo[0], lo[1], lo[2]], [hi[0], hi[1], hi[2]])
    };
    let m_bounds = g.material("bounds", colour::linear(colour::BOUNDS, 1.0), true);
    let b = g.mesh(
        names::BOUNDS,
        &bounds_lines(blo, bhi),
        None,
        Mode::Lines,
        m_bounds,
    );
    g.node(names::BOUNDS, b, Trs::IDENTITY, Some(world));

    // the robot in its body frame, the reference point at the origin
    let mut body = Soup::default();
    match &scene.robot {
        Robot::Point if planar => {
            body.prism(&circle([0.0, 0.0], 0.012 * span, 24), 0.0, robot_height)
        }
        Robot::Point => body.sphere([0.0; 3], 0.012 * span),
        Robot::Polygons(parts) => {
            for p in parts {
                let v: Vec<[f64; 2]> = p.vertices.iter().map(|v| [v.x, v.y]).collect();
                body.prism(&v, 0.0, robot_height);
            }
        }
        Robot::Mesh(m) => body.mesh(m, |v| v),
        Robot::Arm(_) => unreachable!("arms are drawn by arm::arm_gltf"),
        Robot::Bodies(_) => unreachable!("drawn by bodies::bodies_gltf"),
    }
    let path = plan.animated();
    let start = path.first().map_or(Trs::IDENTITY, |q| {
        let (translation, rotation) = animation::pose(space, q);
        Trs {
            translation,
            rotation,
        }
    });
    let mesh = g.mesh(
        names::ROBOT,
        &body.positions,
        Some(&body.indices),
        Mode::Triangles,
        m_robot,
    );
    let robot = g.node(names::ROBOT, mesh, start, Some(world));
    let keys = animation::keyframes(space, groups, path);
    let mut rotations: Vec<[f64; 4]> = keys
        .iter()
        .map(|k| animation::pose(space, &k.config).1)
        .collect();
    animation::continuous(&mut rotations);
    let track = Track {
        times: keys.iter().map(|k| k.time as f32).collect(),
        translations: keys
            .iter()
            .map(|k| animation::pose(space, &k.config).0.map(|v| v as f32))
            .collect(),
        rotations: rotations.iter().map(|r| r.map(|v| v as f32)).collect(),
    };
    g.animate(robot, &track);

    // traces of the reference point
    let trace = |p: &[Config]| -> Vec<[f32; 3]> {
        p.iter()
            .map(|q| {
                let (mut t, _) = animation::pose(space, q);
                if planar {
                    t[2] = trace_z;
                }
                t.map(|v| v as f32)
            })
            .collect()
    };
    for (name, path, hex) in [
        (names::RAW_PATH, &plan.raw, legend.raw_colour(plan)),
        (names::SHORT_PATH, &plan.shortened, colour::SHORT_PATH),
    ] {
        if path.len() >= 2 {
            let m = g.material(name, colour::linear(hex, 1.0), true);
            let mesh = g.mesh(name, &trace(path), None, Mode::LineStrip, m);
            g.node(name, mesh, Trs::IDENTITY, Some(world));
        }
    }

    if let Some(r) = roadmap {
        let m = g.material(names::ROADMAP, colour::linear(colour::ROADMAP, 1.0), true);
        let node = g.node(names::ROADMAP, None, Trs::IDENTITY, Some(world));
        let nodes: Vec<Config> = r.nodes().map(<[f64]>::to_vec).collect();
        let points = g.mesh("roadmap nodes", &trace(&nodes), None, Mode::Points, m);
        g.node("roadmap nodes", points, Trs::IDENTITY, Some(node));
        let mut segments = Vec::new();
        for (e, edge) in r.edges().iter().enumerate() {
            let corners = trace(&r.edge_path(e, edge.a));
            for w in corners.windows(2) {
                segments.extend_from_slice(w);
            }
        }
        let lines = g.mesh("roadmap edges", &segments, None, Mode::Lines, m);
        g.node("roadmap edges", lines, Trs::IDENTITY, Some(node));
    }

    g.set_extras(serde_json::json!({
        "legend": legend,
        "duration": animation::DURATION,
        "up": if is_z_up(scene) { "z" } else { "y" },
    }));
    Ok(g)
}
