//! A scene of points, discs, polygons or rigid meshes and its robot following a plan, as a
//! glTF document: obstacles, bounds, the animated robot, the traces of its reference point.
//! Arms are drawn by [`super::arm`].

use super::animation;
use super::arm;
use super::bodies;
use super::gltf::{Gltf, Mode, Track, Trs};
use super::{bounds_lines, colour, names, world_node, ExportError, Legend, Plan, Soup};
use crate::roadmap::Roadmap;
use crate::scene::{Obstacle, Robot, Scene};
use crate::space::{Config, Group, Space, SpaceKind};

/// A regular polygon of `sides` corners approximating the circle (`centre`, `r`).
fn circle(centre: [f64; 2], r: f64, sides: usize) -> Vec<[f64; 2]> {
    (0..sides)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / sides as f64;
            [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
        })
        .collect()
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
/// roadmap, as a glTF document (see [`crate::export`] for frames and conventions).
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
        (Robot::Bodies(_) | Robot::MeshBodies(_), _) => {
            return bodies::bodies_gltf(scene, groups, plan, roadmap, legend)
        }
        (_, SpaceKind::Euclidean(2..=3) | SpaceKind::Se2 | SpaceKind::Se3) => {}
        _ => return Err(ExportError::Unsupported(kind.to_string())),
    }
    let layout = Layout::of(space);
    let mut g = Gltf::new();
    let world = world_node(&mut g, is_z_up(scene));
    // in 3D the robot passes behind walls and into rooms: translucent obstacles keep it in
    // sight; planar obstacles are low prisms seen from above, opaque
    let opacity = if layout.planar { 1.0 } else { 0.55 };
    let m_obstacle = g.material("obstacle", colour::linear(colour::OBSTACLE, opacity), false);
    let m_robot = g.material("robot", colour::linear(colour::ROBOT, 1.0), false);
    environment(&mut g, scene, &layout, m_obstacle, world);
    animated_robot(&mut g, scene, groups, plan, &layout, m_robot, world);
    path_traces(&mut g, space, plan, legend, &layout, world);
    if let Some(r) = roadmap {
        roadmap_traces(&mut g, space, r, &layout, world);
    }
    g.set_extras(serde_json::json!({
        "legend": legend,
        "duration": animation::DURATION,
        "up": if is_z_up(scene) { "z" } else { "y" },
    }));
    Ok(g)
}

/// Sizes of a scene's drawing, from its space's bounds.
struct Layout {
    /// A planar scene, drawn as prisms standing on z = 0.
    planar: bool,
    /// The longest side of the bounds (at least the smallest positive float).
    span: f64,
    /// How high planar obstacles stand.
    height: f64,
    /// How high the planar robot stands: a little lower than the obstacles.
    robot_height: f64,
    /// Where planar traces lie: just above everything.
    trace_z: f64,
}

impl Layout {
    fn of(space: &Space) -> Layout {
        let planar = space.position_dim() == 2;
        let (lo, hi) = (space.lower(), space.upper());
        let span = (0..space.position_dim())
            .map(|i| hi[i] - lo[i])
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        // planar scenes stand on z = 0: obstacles this high, the robot a little lower, the traces
        // just above everything
        let height = 0.04 * span;
        Layout {
            planar,
            span,
            height,
            robot_height: 0.6 * height,
            trace_z: if planar { 1.05 * height } else { 0.0 },
        }
    }

    /// The reference point of each configuration, where its trace is drawn.
    fn trace(&self, space: &Space, p: &[Config]) -> Vec<[f32; 3]> {
        p.iter()
            .map(|q| {
                let (mut t, _) = animation::pose(space, q);
                if self.planar {
                    t[2] = self.trace_z;
                }
                t.map(|v| v as f32)
            })
            .collect()
    }
}

/// The obstacles as one mesh and the space's bounds as lines.
fn environment(g: &mut Gltf, scene: &Scene, layout: &Layout, m_obstacle: usize, world: usize) {
    let Layout { planar, height, .. } = *layout;
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
    env.add(g, names::ENVIRONMENT, m_obstacle, world);

    let (lo, hi) = (scene.space.lower(), scene.space.upper());
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
}

/// The robot in its body frame (the reference point at the origin), placed at the path's
/// start and animated along it.
fn animated_robot(
    g: &mut Gltf,
    scene: &Scene,
    groups: &[Group],
    plan: &Plan,
    layout: &Layout,
    m_robot: usize,
    world: usize,
) {
    let space = &scene.space;
    let Layout {
        planar,
        span,
        robot_height,
        ..
    } = *layout;
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
        Robot::Bodies(_) | Robot::MeshBodies(_) => unreachable!("drawn by bodies::bodies_gltf"),
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
}

/// The traces of the reference point along the raw and the shortened path.
fn path_traces(
    g: &mut Gltf,
    space: &Space,
    plan: &Plan,
    legend: &Legend,
    layout: &Layout,
    world: usize,
) {
    for (name, path, hex) in [
        (names::RAW_PATH, &plan.raw, legend.raw_colour(plan)),
        (names::SHORT_PATH, &plan.shortened, colour::SHORT_PATH),
    ] {
        if path.len() >= 2 {
            let m = g.material(name, colour::linear(hex, 1.0), true);
            let mesh = g.mesh(name, &layout.trace(space, path), None, Mode::LineStrip, m);
            g.node(name, mesh, Trs::IDENTITY, Some(world));
        }
    }
}

/// The roadmap's nodes as points and its edges as lines, traced by the reference point.
fn roadmap_traces(g: &mut Gltf, space: &Space, r: &Roadmap, layout: &Layout, world: usize) {
    let m = g.material(names::ROADMAP, colour::linear(colour::ROADMAP, 1.0), true);
    let node = g.node(names::ROADMAP, None, Trs::IDENTITY, Some(world));
    let nodes: Vec<Config> = r.nodes().map(<[f64]>::to_vec).collect();
    let points = g.mesh(
        "roadmap nodes",
        &layout.trace(space, &nodes),
        None,
        Mode::Points,
        m,
    );
    g.node("roadmap nodes", points, Trs::IDENTITY, Some(node));
    let mut segments = Vec::new();
    for (e, edge) in r.edges().iter().enumerate() {
        let corners = layout.trace(space, &r.edge_path(e, edge.a));
        for w in corners.windows(2) {
            segments.extend_from_slice(w);
        }
    }
    let lines = g.mesh("roadmap edges", &segments, None, Mode::Lines, m);
    g.node("roadmap edges", lines, Trs::IDENTITY, Some(node));
}
