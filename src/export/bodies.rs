//! Several bodies moving at once, as a glTF document: the obstacles, every body in its own
//! colour animated along the plan, the traces of every body's reference point.
//!
//! The drawing is built from a list of `DrawnBody`: a shape in the body's own frame and the
//! coordinates of a configuration that hold its pose (`x y θ` in the plane, `x y z qx qy qz qw`
//! in space, [`body_pose`]). A kind of scene with several bodies needs only to say how its
//! bodies look (`drawn_bodies`); placing, animating and tracing them is shared. Planar bodies
//! are prisms standing on z = 0, like the single planar robot of [`super::scene_gltf`]; bodies
//! in space are their meshes among translucent obstacles, as a single rigid body's scene is.
//!
//! Every body hangs under one node named [`names::ROBOT`], so the viewer (and its browser
//! test) sees all of them as "the robot"; each body's node is named after the body. The
//! keyframes are those of the whole configuration ([`animation::keyframes`]: one DOF group at
//! a time, as the planner checked the motion), so while one body turns the others stand
//! still, and while they translate they all move.

use super::animation;
use super::gltf::{Gltf, Mode, Track, Trs};
use super::{bounds_lines, colour, names, world_node, BodyRow, ExportError, Legend, Plan, Soup};
use crate::roadmap::Roadmap;
use crate::scene::{Robot, Scene};
use crate::space::{Config, Group, Space, SpaceKind};
use nalgebra::UnitQuaternion;
use std::ops::Range;

/// One colour per body, in turn (sRGB hex; the same as the SVG pictures of
/// [`crate::render`]).
pub const BODY_COLOURS: [u32; 8] = [
    0x3ebd93, 0xe12d39, 0x0967d2, 0xf0b429, 0x8719e0, 0xc65d21, 0x27ab83, 0xda127d,
];

/// The colour of body `i` (sRGB hex).
pub fn body_colour(i: usize) -> u32 {
    BODY_COLOURS[i % BODY_COLOURS.len()]
}

/// A moving body as it is drawn.
pub(crate) struct DrawnBody {
    /// Its name in the scene (the node's name).
    pub name: String,
    /// Its shape in its own frame, the reference point at the origin.
    pub shape: Soup,
    /// The coordinates of a configuration that hold its pose.
    pub coords: Range<usize>,
}

/// Sizes of the drawing, from the bounds of the reference points.
struct Layout {
    /// Whether the bodies move in the plane (prisms on z = 0) or in space.
    planar: bool,
    /// The box of the reference points, `[x, y, z]` (z = 0 … obstacle height in the plane).
    lower: [f64; 3],
    upper: [f64; 3],
    /// How high planar obstacles stand; bodies a little lower, traces just above.
    height: f64,
    /// Where traces of planar reference points lie.
    trace_z: f64,
}

impl Layout {
    fn of(space: &Space) -> Layout {
        let (lo, hi) = (space.lower(), space.upper());
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let height = 0.04 * span;
        if matches!(space.kind(), SpaceKind::Se3Bodies(_)) {
            return Layout {
                planar: false,
                lower: [lo[0], lo[1], lo[2]],
                upper: [hi[0], hi[1], hi[2]],
                height,
                trace_z: 0.0,
            };
        }
        Layout {
            planar: true,
            lower: [lo[0], lo[1], 0.0],
            upper: [hi[0], hi[1], height],
            height,
            trace_z: 1.05 * height,
        }
    }
}

/// The bodies of a scene of several bodies, or `None` for any other scene; planar bodies as
/// prisms `height` high.
pub(crate) fn drawn_bodies(scene: &Scene, height: f64) -> Option<Vec<DrawnBody>> {
    let space = &scene.space;
    let drawn = |i: usize, name: &str, shape: Soup| DrawnBody {
        name: name.to_owned(),
        shape,
        coords: space.body_coords(i),
    };
    match &scene.robot {
        Robot::Bodies(bodies) => Some(
            bodies
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let mut shape = Soup::default();
                    for p in &b.parts {
                        let v: Vec<[f64; 2]> = p.vertices.iter().map(|v| [v.x, v.y]).collect();
                        shape.prism(&v, 0.0, height);
                    }
                    drawn(i, &b.name, shape)
                })
                .collect(),
        ),
        Robot::MeshBodies(bodies) => Some(
            bodies
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let mut shape = Soup::default();
                    shape.mesh(&b.mesh, |v| v);
                    drawn(i, &b.name, shape)
                })
                .collect(),
        ),
        _ => None,
    }
}

/// The pose of one body from its own coordinates: `x y θ` (in the plane, z = 0) or
/// `x y z qx qy qz qw`; translation and unit quaternion `[x, y, z, w]`.
pub fn body_pose(pose: &[f64]) -> ([f64; 3], [f64; 4]) {
    match pose {
        [x, y, theta] => {
            let h = theta / 2.0;
            ([*x, *y, 0.0], [0.0, 0.0, h.sin(), h.cos()])
        }
        [x, y, z, qx, qy, qz, qw] => {
            let r = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(*qw, *qx, *qy, *qz));
            ([*x, *y, *z], [r.i, r.j, r.k, r.w])
        }
        _ => ([0.0; 3], [0.0, 0.0, 0.0, 1.0]),
    }
}

/// The scene of several bodies following `plan`, the traces of every body's reference point
/// along both paths, and optionally a roadmap (every node and edge at every reference point).
pub fn bodies_gltf(
    scene: &Scene,
    groups: &[Group],
    plan: &Plan,
    roadmap: Option<&Roadmap>,
    legend: &Legend,
) -> Result<Gltf, ExportError> {
    let space = &scene.space;
    if !matches!(
        space.kind(),
        SpaceKind::Se2Bodies(_) | SpaceKind::Se3Bodies(_)
    ) {
        return Err(ExportError::Unsupported(space.kind().to_string()));
    }
    let layout = Layout::of(space);
    let Some(bodies) = drawn_bodies(scene, 0.6 * layout.height) else {
        return Err(ExportError::Unsupported(space.kind().to_string()));
    };
    let mut g = Gltf::new();
    let world = world_node(&mut g, true);
    environment(&mut g, scene, &layout, world);
    animate(&mut g, space, groups, plan.animated(), &bodies, world);
    for (name, path, hex) in [
        (names::RAW_PATH, &plan.raw, legend.raw_colour(plan)),
        (names::SHORT_PATH, &plan.shortened, colour::SHORT_PATH),
    ] {
        if path.len() >= 2 {
            let m = g.material(name, colour::linear(hex, 1.0), true);
            let node = g.node(name, None, Trs::IDENTITY, Some(world));
            for b in &bodies {
                let line = trace(path, b, layout.trace_z);
                let mesh = g.mesh(&b.name, &line, None, Mode::LineStrip, m);
                g.node(&b.name, mesh, Trs::IDENTITY, Some(node));
            }
        }
    }
    if let Some(r) = roadmap {
        roadmap_traces(&mut g, r, &bodies, layout.trace_z, world);
    }
    g.set_extras(serde_json::json!({
        "legend": legend,
        "duration": animation::DURATION,
        "up": "z",
    }));
    Ok(g)
}

/// The obstacles (prisms in the plane, translucent meshes in space, where bodies pass behind
/// walls and into boxes) and the bounds of the reference points as lines.
fn environment(g: &mut Gltf, scene: &Scene, layout: &Layout, world: usize) {
    let opacity = if layout.planar { 1.0 } else { 0.55 };
    let m_obstacle = g.material("obstacle", colour::linear(colour::OBSTACLE, opacity), false);
    let mut env = Soup::default();
    if layout.planar {
        for p in scene.polygon_obstacles() {
            let v: Vec<[f64; 2]> = p.vertices.iter().map(|v| [v.x, v.y]).collect();
            env.prism(&v, 0.0, layout.height);
        }
    } else {
        for m in scene.mesh_obstacles() {
            env.mesh(&m, |v| v);
        }
    }
    env.add(g, names::ENVIRONMENT, m_obstacle, world);
    let m_bounds = g.material("bounds", colour::linear(colour::BOUNDS, 1.0), true);
    let lines = bounds_lines(layout.lower, layout.upper);
    let b = g.mesh(names::BOUNDS, &lines, None, Mode::Lines, m_bounds);
    g.node(names::BOUNDS, b, Trs::IDENTITY, Some(world));
}

/// Every body under one [`names::ROBOT`] node, placed at the path's start and animated along
/// it, each in its own colour.
fn animate(
    g: &mut Gltf,
    space: &Space,
    groups: &[Group],
    path: &[Config],
    bodies: &[DrawnBody],
    world: usize,
) {
    let robot = g.node(names::ROBOT, None, Trs::IDENTITY, Some(world));
    let keys = animation::keyframes(space, groups, path);
    for (i, b) in bodies.iter().enumerate() {
        let m = g.material(&b.name, colour::linear(body_colour(i), 1.0), false);
        let mesh = g.mesh(
            &b.name,
            &b.shape.positions,
            Some(&b.shape.indices),
            Mode::Triangles,
            m,
        );
        let start = path.first().map_or(Trs::IDENTITY, |q| {
            let (translation, rotation) = body_pose(&q[b.coords.clone()]);
            Trs {
                translation,
                rotation,
            }
        });
        let node = g.node(&b.name, mesh, start, Some(robot));
        let poses: Vec<([f64; 3], [f64; 4])> = keys
            .iter()
            .map(|k| body_pose(&k.config[b.coords.clone()]))
            .collect();
        let mut rotations: Vec<[f64; 4]> = poses.iter().map(|p| p.1).collect();
        animation::continuous(&mut rotations);
        let track = Track {
            times: keys.iter().map(|k| k.time as f32).collect(),
            translations: poses.iter().map(|p| p.0.map(|v| v as f32)).collect(),
            rotations: rotations.iter().map(|r| r.map(|v| v as f32)).collect(),
        };
        g.animate(node, &track);
    }
}

/// Body `b`'s reference point at each configuration of `path` (at height `z` in the plane).
fn trace(path: &[Config], b: &DrawnBody, z: f64) -> Vec<[f32; 3]> {
    path.iter()
        .map(|q| {
            let (mut t, _) = body_pose(&q[b.coords.clone()]);
            if b.coords.len() == 3 {
                t[2] = z;
            }
            t.map(|v| v as f32)
        })
        .collect()
}

/// The roadmap's nodes as points and its edges as lines, at every body's reference point.
fn roadmap_traces(g: &mut Gltf, r: &Roadmap, bodies: &[DrawnBody], z: f64, world: usize) {
    let m = g.material(names::ROADMAP, colour::linear(colour::ROADMAP, 1.0), true);
    let node = g.node(names::ROADMAP, None, Trs::IDENTITY, Some(world));
    let nodes: Vec<Config> = r.nodes().map(<[f64]>::to_vec).collect();
    let mut points = Vec::new();
    let mut segments = Vec::new();
    for b in bodies {
        points.extend(trace(&nodes, b, z));
        for (e, edge) in r.edges().iter().enumerate() {
            let corners = trace(&r.edge_path(e, edge.a), b, z);
            for w in corners.windows(2) {
                segments.extend_from_slice(w);
            }
        }
    }
    let p = g.mesh("roadmap nodes", &points, None, Mode::Points, m);
    g.node("roadmap nodes", p, Trs::IDENTITY, Some(node));
    let lines = g.mesh("roadmap edges", &segments, None, Mode::Lines, m);
    g.node("roadmap edges", lines, Trs::IDENTITY, Some(node));
}

impl Legend {
    /// Names the bodies of a scene of several bodies in the colours [`bodies_gltf`]
    /// draws them in (nothing for a scene of one robot).
    pub fn set_bodies(&mut self, scene: &Scene) {
        let names: Vec<&str> = match &scene.robot {
            Robot::Bodies(b) => b.iter().map(|b| b.name.as_str()).collect(),
            Robot::MeshBodies(b) => b.iter().map(|b| b.name.as_str()).collect(),
            _ => Vec::new(),
        };
        self.bodies = names
            .iter()
            .enumerate()
            .map(|(i, name)| BodyRow {
                name: (*name).to_owned(),
                colour: colour::css(body_colour(i)),
            })
            .collect();
    }
}
