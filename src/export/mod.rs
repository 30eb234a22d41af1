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
//! The glTF frame is Y-up. Z-up scenes (viaroad's TOML, planar problems, MoveIt, and those of
//! OMPL.app's 3D problems that stand on z = 0, see `scene::is_z_up`) sit under a root node turned
//! by −90° about x; the others are written as they are. The robot's node is placed at the reference
//! point with the state's quaternion, which glTF and OMPL both order `[x, y, z, w]`.

pub mod animation;
pub mod arm;
pub mod bodies;
pub mod gltf;
pub mod html;
mod scene;

pub use scene::scene_gltf;

use crate::geometry::TriMesh;
use crate::space::Config;
use gltf::{Gltf, Mode, Trs};
use serde::Serialize;

/// What cannot be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// Only spaces with a picture in three dimensions: R², R³, SE(2), SE(3), arms, several
    /// bodies.
    #[error("cannot draw a {0} scene in 3D: only R², R³, SE(2), SE(3), arms and several bodies")]
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
