//! glTF export: the `.glb` read back by a reader written here (not the writer's),
//! the drawn motion re-checked by the independent validity checkers (parry, conservative
//! advancement), the arm's links against forward kinematics, and every file run through the
//! Khronos glTF validator (npm `gltf-validator`, pinned in tools/js; skipped with a `SKIPPED`
//! line on stderr where node or the package is absent, `cd tools/js && npm ci --omit=dev`,
//! and failed instead where `VIAROAD_REQUIRE_JS` is set: `common::js`).

use crate::common;

use common::cli::{fails_with, temp_dir, viaroad, write};
use common::js::{node_script, skip};
use common::rigid::RigidChecker;
use common::rigid2d::PlanarChecker;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use viaroad::deadline::Deadline;
use viaroad::export::{self, Legend, Plan};
use viaroad::local::{shorten, LocalSpec};
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{Arm, ArmOptions};
use viaroad::scene::moveit::{load_motion_plan_request, load_planning_scene};
use viaroad::scene::{ompl_cfg, Scene};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A GLB read back: the JSON and the binary chunk.
struct Glb {
    doc: Value,
    bin: Vec<u8>,
}

fn u32_at(b: &[u8], o: usize) -> usize {
    u32::from_le_bytes(b[o..o + 4].try_into().unwrap()) as usize
}

impl Glb {
    fn parse(b: &[u8]) -> Glb {
        assert_eq!(&b[..4], b"glTF", "magic");
        assert_eq!(u32_at(b, 4), 2, "version");
        assert_eq!(u32_at(b, 8), b.len(), "total length");
        let jlen = u32_at(b, 12);
        assert_eq!(&b[16..20], b"JSON");
        let doc: Value = serde_json::from_slice(&b[20..20 + jlen]).unwrap();
        let rest = &b[20 + jlen..];
        let bin = if rest.is_empty() {
            Vec::new()
        } else {
            assert_eq!(&rest[4..8], b"BIN\0");
            rest[8..8 + u32_at(rest, 0)].to_vec()
        };
        Glb { doc, bin }
    }

    /// The accessor's components as f64 (floats) — tightly packed, as the writer promises.
    fn floats(&self, accessor: usize) -> Vec<f64> {
        let a = &self.doc["accessors"][accessor];
        assert_eq!(a["componentType"], 5126);
        let v = &self.doc["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let (o, l) = (
            v["byteOffset"].as_u64().unwrap() as usize,
            v["byteLength"].as_u64().unwrap() as usize,
        );
        self.bin[o..o + l]
            .chunks(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()) as f64)
            .collect()
    }

    fn node(&self, name: &str) -> usize {
        self.doc["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .position(|n| n["name"] == name)
            .unwrap_or_else(|| panic!("no node {name}"))
    }

    /// The mesh positions of a node's mesh.
    fn positions(&self, node: usize) -> Vec<[f64; 3]> {
        let mesh = self.doc["nodes"][node]["mesh"].as_u64().unwrap() as usize;
        let acc = self.doc["meshes"][mesh]["primitives"][0]["attributes"]["POSITION"]
            .as_u64()
            .unwrap() as usize;
        self.floats(acc)
            .chunks(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect()
    }

    /// The node's animation keys: (time, translation, rotation [x, y, z, w]).
    fn keys(&self, node: usize) -> Vec<(f64, [f64; 3], [f64; 4])> {
        let anim = &self.doc["animations"][0];
        let mut times = Vec::new();
        let (mut tr, mut rot) = (Vec::new(), Vec::new());
        for ch in anim["channels"].as_array().unwrap() {
            if ch["target"]["node"] != node {
                continue;
            }
            let s = &anim["samplers"][ch["sampler"].as_u64().unwrap() as usize];
            assert_eq!(s["interpolation"], "LINEAR");
            times = self.floats(s["input"].as_u64().unwrap() as usize);
            let out = self.floats(s["output"].as_u64().unwrap() as usize);
            match ch["target"]["path"].as_str().unwrap() {
                "translation" => tr = out.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
                "rotation" => rot = out.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect(),
                p => panic!("unexpected channel {p}"),
            }
        }
        assert_eq!(times.len(), tr.len());
        assert_eq!(times.len(), rot.len());
        assert!(
            times.windows(2).all(|w| w[1] > w[0]),
            "times increase strictly"
        );
        times
            .into_iter()
            .zip(tr.into_iter().zip(rot))
            .map(|(t, (p, r))| (t, p, r))
            .collect()
    }
}

/// Solves the scene's first query with the local method and shortens the path.
fn plan(scene: &Scene) -> Plan {
    let oracle = scene.oracle();
    let q = &scene.checked_queries().unwrap()[0];
    let method = LocalSpec::default().build();
    let mut c = method
        .connect_within(
            &scene.space,
            oracle.as_ref(),
            &q.start,
            &q.goal,
            &Deadline::none(),
        )
        .unwrap();
    assert!(
        c.is_connected(),
        "{}: the local method connects",
        scene.name
    );
    let groups = method.groups(&scene.space);
    let shortened = shorten(
        &scene.space,
        oracle.as_ref(),
        &groups,
        &c.path,
        &mut c.counts,
    )
    .unwrap();
    Plan {
        raw: c.path,
        shortened,
    }
}

/// The scene's `.glb` with the plan, read back.
fn exported(scene: &Scene, plan: &Plan) -> (Vec<u8>, Glb) {
    let groups = scene.space.groups(false);
    let g = export::scene_gltf(scene, &groups, plan, None, &Legend::default()).unwrap();
    let bytes = g.to_glb();
    let glb = Glb::parse(&bytes);
    (bytes, glb)
}

fn normalised(r: [f64; 4]) -> [f64; 4] {
    let n = r.iter().map(|v| v * v).sum::<f64>().sqrt();
    r.map(|v| v / n)
}

/// Every corner of `path` is one of the keyed configurations.
fn corners_are_keys(scene: &Scene, path: &[Vec<f64>], keyed: &[Vec<f64>], tol: f64) {
    for (i, c) in path.iter().enumerate() {
        let d = keyed
            .iter()
            .map(|k| scene.space.distance(c, k))
            .fold(f64::INFINITY, f64::min);
        assert!(d < tol, "corner {i} {c:?} is {d} from every key");
    }
}

#[test]
fn se3_robot_follows_the_shortened_path_through_free_motions() {
    let scene = Scene::load(&root().join("scenes/cube-into-box.toml")).unwrap();
    let plan = plan(&scene);
    assert!(plan.shortened.len() >= 2);
    let (_, glb) = exported(&scene, &plan);
    // Z-up scenes turn by −90° about x into glTF's Y-up
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let world = &glb.doc["nodes"][glb.node("world")]["rotation"];
    let w: Vec<f64> = world
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!((w[0] + h).abs() < 1e-12 && w[1] == 0.0 && w[2] == 0.0 && (w[3] - h).abs() < 1e-12);
    // the robot's mesh is the scene's robot in its body frame
    let robot = glb.node("robot");
    let viaroad::scene::Robot::Mesh(m) = &scene.robot else {
        panic!("a mesh robot")
    };
    let pos = glb.positions(robot);
    assert_eq!(pos.len(), m.vertices.len());
    for (p, v) in pos.iter().zip(&m.vertices) {
        assert_eq!(p.map(|c| c as f32), [v.x, v.y, v.z].map(|c| c as f32));
    }
    // the keys, as configurations, pass through every corner and every motion between two
    // keys (what a viewer draws: lerp, slerp) is certified free by the independent checker
    let keyed: Vec<Vec<f64>> = glb
        .keys(robot)
        .iter()
        .map(|(_, p, r)| {
            let r = normalised(*r);
            vec![p[0], p[1], p[2], r[0], r[1], r[2], r[3]]
        })
        .collect();
    assert!(keyed.len() >= plan.shortened.len());
    corners_are_keys(&scene, &plan.shortened, &keyed, 1e-5);
    RigidChecker::se3(&scene).certify_path(&keyed).unwrap();
    // the traces: raw and shortened, through the reference points of their corners
    for (name, path) in [("raw path", &plan.raw), ("shortened path", &plan.shortened)] {
        let t = glb.positions(glb.node(name));
        assert_eq!(t.len(), path.len());
        for (p, q) in t.iter().zip(path) {
            assert!((0..3).all(|i| (p[i] - q[i]).abs() < 1e-5));
        }
    }
}

#[test]
fn se3_turns_are_keyed_about_one_axis_and_certified() {
    // a turn of the cube in free space, 170° about a tilted axis: sampled into keys of at most
    // 5° each, and the keyed motion is certified (turns included) by the independent checker
    let scene = Scene::load(&root().join("scenes/cube-into-box.toml")).unwrap();
    let axis = nalgebra::Unit::new_normalize(nalgebra::Vector3::new(1.0, 2.0, 0.5));
    let r = nalgebra::UnitQuaternion::from_axis_angle(&axis, 170f64.to_radians());
    let a = vec![2.0, 2.0, 2.5, 0.0, 0.0, 0.0, 1.0];
    let b = vec![2.0, 2.0, 2.5, r.i, r.j, r.k, r.w];
    let plan = Plan {
        raw: Vec::new(),
        shortened: vec![a.clone(), b.clone()],
    };
    let (_, glb) = exported(&scene, &plan);
    let keys = glb.keys(glb.node("robot"));
    assert_eq!(keys.len(), 1 + 34);
    let keyed: Vec<Vec<f64>> = keys
        .iter()
        .map(|(_, p, r)| {
            let r = normalised(*r);
            vec![p[0], p[1], p[2], r[0], r[1], r[2], r[3]]
        })
        .collect();
    for w in keyed.windows(2) {
        let d = scene.space.distance(&w[0], &w[1]);
        assert!(d <= 5f64.to_radians() + 1e-5, "a step of {d}");
    }
    corners_are_keys(&scene, &plan.shortened, &keyed, 1e-5);
    RigidChecker::se3(&scene).certify_path(&keyed).unwrap();
}

#[test]
fn se2_robot_is_an_extruded_footprint_following_free_motions() {
    let scene = Scene::load(&root().join("scenes/se2-corridor.toml")).unwrap();
    let plan = plan(&scene);
    let (_, glb) = exported(&scene, &plan);
    let keyed: Vec<Vec<f64>> = glb
        .keys(glb.node("robot"))
        .iter()
        .map(|(_, p, r)| {
            assert!(
                p[2] == 0.0 && r[0] == 0.0 && r[1] == 0.0,
                "turns about z only"
            );
            vec![p[0], p[1], 2.0 * r[2].atan2(r[3])]
        })
        .collect();
    corners_are_keys(&scene, &plan.shortened, &keyed, 1e-5);
    PlanarChecker::se2(&scene).certify_path(&keyed).unwrap();
    // the prism: every footprint vertex at the bottom and at the top
    let viaroad::scene::Robot::Polygons(parts) = &scene.robot else {
        panic!("a polygonal robot")
    };
    let pos = glb.positions(glb.node("robot"));
    let n: usize = parts.iter().map(|p| p.vertices.len()).sum();
    assert_eq!(pos.len(), 2 * n);
    let top = pos.iter().map(|p| p[2]).fold(0.0, f64::max);
    assert!(top > 0.0 && pos.iter().all(|p| p[2] == 0.0 || p[2] == top));
}

/// Two squares swap places in the shipped corridor: the second rises into the niche, the
/// first passes beneath, the second comes down, and both move left together.
fn swap_by_hand() -> Vec<Vec<f64>> {
    vec![
        vec![0.5, 0.5, 0.0, 1.5, 0.5, 0.0],
        vec![0.5, 0.5, 0.0, 1.5, 1.5, 0.0],
        vec![2.5, 0.5, 0.0, 1.5, 1.5, 0.0],
        vec![2.5, 0.5, 0.0, 1.5, 0.5, 0.0],
        vec![1.5, 0.5, 0.0, 0.5, 0.5, 0.0],
    ]
}

#[test]
fn several_bodies_each_follow_their_own_poses_in_their_own_colours() {
    let scene = Scene::load(&root().join("scenes/bodies/swap-corridor-2.toml")).unwrap();
    let checker = common::bodies::BodiesChecker::new(&scene);
    let path = swap_by_hand();
    checker.certify_path(&path).unwrap();
    let plan = Plan {
        raw: path.clone(),
        shortened: Vec::new(),
    };
    let (_, glb) = exported(&scene, &plan);
    // both bodies under the robot node, each with its own material
    let robot = glb.node("robot");
    let children = glb.doc["nodes"][robot]["children"].as_array().unwrap();
    assert_eq!(children.len(), 2);
    let material = |n: usize| {
        let mesh = glb.doc["nodes"][n]["mesh"].as_u64().unwrap() as usize;
        glb.doc["meshes"][mesh]["primitives"][0]["material"].clone()
    };
    assert_ne!(material(glb.node("s1")), material(glb.node("s2")));
    // the keys of both bodies, put together, are configurations of the path's motions
    let (k1, k2) = (glb.keys(glb.node("s1")), glb.keys(glb.node("s2")));
    assert_eq!(k1.len(), k2.len());
    let keyed: Vec<Vec<f64>> = k1
        .iter()
        .zip(&k2)
        .map(|((t1, p1, r1), (t2, p2, r2))| {
            assert_eq!(t1, t2);
            assert!(p1[2] == 0.0 && p2[2] == 0.0, "planar");
            let angle = |r: &[f64; 4]| 2.0 * r[2].atan2(r[3]);
            vec![p1[0], p1[1], angle(r1), p2[0], p2[1], angle(r2)]
        })
        .collect();
    corners_are_keys(&scene, &path, &keyed, 1e-5);
    checker.certify_path(&keyed).unwrap();
    // one trace per body
    let traces = glb.doc["nodes"][glb.node("raw path")]["children"]
        .as_array()
        .map_or(0, Vec::len);
    assert_eq!(traces, 2);
}

/// Two cubes above their boxes: the red one turns a quarter radian about z and back, then
/// both go down into their boxes together.
fn cubes_by_hand() -> Vec<Vec<f64>> {
    let (s, c) = (0.25f64.sin(), 0.25f64.cos());
    let at = |z: f64, red: [f64; 4]| {
        let mut q = vec![-1.25, 0.0, z];
        q.extend(red);
        q.extend([1.25, 0.0, z, 0.0, 0.0, 0.0, 1.0]);
        q
    };
    let still = [0.0, 0.0, 0.0, 1.0];
    vec![
        at(2.5, still),
        at(2.5, [0.0, 0.0, s, c]),
        at(2.5, still),
        at(0.55, still),
    ]
}

#[test]
fn several_bodies_in_space_each_follow_their_own_poses() {
    let scene = Scene::load(&root().join("scenes/bodies/cubes-into-boxes-2.toml")).unwrap();
    let checker = common::bodies3::SolidBodiesChecker::new(&scene);
    let path = cubes_by_hand();
    checker.certify_path(&path).unwrap();
    let plan = Plan {
        raw: path.clone(),
        shortened: Vec::new(),
    };
    let (_, glb) = exported(&scene, &plan);
    let robot = glb.node("robot");
    let children = glb.doc["nodes"][robot]["children"].as_array().unwrap();
    assert_eq!(children.len(), 2);
    let (k1, k2) = (glb.keys(glb.node("red")), glb.keys(glb.node("blue")));
    assert_eq!(k1.len(), k2.len());
    let keyed: Vec<Vec<f64>> = k1
        .iter()
        .zip(&k2)
        .map(|((t1, p1, r1), (t2, p2, r2))| {
            assert_eq!(t1, t2);
            let mut q: Vec<f64> = p1.iter().chain(&normalised(*r1)).copied().collect();
            q.extend(p2.iter().chain(&normalised(*r2)));
            q
        })
        .collect();
    corners_are_keys(&scene, &path, &keyed, 1e-5);
    checker.certify_path(&keyed).unwrap();
    // the turn is keyed in steps, not one jump
    assert!(keyed.len() > path.len() + 2, "{}", keyed.len());
}

/// Decodes standard base64 (RFC 4648, padded), as the viewer page embeds its model.
fn unbase64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let mut out = Vec::new();
    for chunk in text.trim().as_bytes().chunks(4) {
        let pads = chunk.iter().filter(|&&c| c == b'=').count();
        let n = chunk
            .iter()
            .map(|&c| if c == b'=' { 0 } else { value(c) as u32 })
            .fold(0u32, |n, v| n << 6 | v);
        out.extend_from_slice(&n.to_be_bytes()[1..4 - pads]);
    }
    out
}

/// `view --show-roadmap` on several bodies in space: the page's model holds the roadmap grown
/// from start and goal, drawn at both cubes' reference points; the same roadmap grown here
/// answers with a path the independent checker certifies, and its export draws every node once
/// per body, at that body's reference point.
#[test]
fn several_bodies_in_space_show_their_roadmap() {
    let file = "scenes/bodies/cubes-into-boxes-2.toml";
    let dir = temp_dir("export_gltf", "bodies-roadmap");
    let page = dir.join("cubes.html");
    let o = viaroad(&[
        "view",
        file,
        "--show-roadmap",
        "--nodes",
        "500",
        "-o",
        page.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::cli::stderr(&o));
    let html = std::fs::read_to_string(&page).unwrap();
    let embedded = html
        .split("<script id=\"viaroad-glb\" type=\"application/octet-stream\">")
        .nth(1)
        .and_then(|rest| rest.split("</script>").next())
        .expect("the page embeds its model");
    let glb = Glb::parse(&unbase64(embedded));
    for name in ["red", "blue", "roadmap nodes", "roadmap edges"] {
        glb.node(name);
    }
    assert!(glb.positions(glb.node("roadmap nodes")).len() >= 4);

    let scene = Scene::load(&root().join(file)).unwrap();
    let oracle = scene.oracle();
    let q = &scene.checked_queries().unwrap()[0];
    let solver = viaroad::solve::Solver {
        nodes: Some(500),
        ..viaroad::solve::Solver::default()
    };
    let s = solver
        .plan_by_roadmap(
            &scene,
            oracle.as_ref(),
            (&q.start, &q.goal),
            &Deadline::none(),
        )
        .unwrap();
    assert!(s.is_solved(), "the roadmap joins start and goal");
    let checker = common::bodies3::SolidBodiesChecker::new(&scene);
    checker.certify_path(&s.raw).unwrap();
    checker.certify_path(&s.shortened).unwrap();
    let roadmap = s.roadmap.expect("the roadmap that answered");
    let plan = Plan {
        raw: s.raw,
        shortened: s.shortened,
    };
    let groups = LocalSpec::roadmap_default_for(&scene.space)
        .build()
        .groups(&scene.space);
    let g = export::scene_gltf(&scene, &groups, &plan, Some(&roadmap), &Legend::default()).unwrap();
    let glb = Glb::parse(&g.to_glb());
    let points = glb.positions(glb.node("roadmap nodes"));
    assert_eq!(
        points.len(),
        2 * roadmap.node_count(),
        "each node once per body"
    );
    for (b, drawn) in points.chunks(roadmap.node_count()).enumerate() {
        for (q, p) in roadmap.nodes().zip(drawn) {
            let at = &q[7 * b..7 * b + 3];
            assert!(
                (0..3).all(|i| (at[i] - p[i]).abs() < 1e-5),
                "body {b}: {p:?} is not its reference point {at:?}"
            );
        }
    }
    let edges = glb.positions(glb.node("roadmap edges"));
    assert!(edges.len() % 2 == 0 && edges.len() >= 2 * 2 * roadmap.edge_count());
}

#[test]
fn point_robot_among_discs_stays_clear_of_them() {
    let scene = Scene::load(&root().join("scenes/discs-cluttered.toml")).unwrap();
    let plan = plan(&scene);
    let (_, glb) = exported(&scene, &plan);
    let keyed: Vec<Vec<f64>> = glb
        .keys(glb.node("robot"))
        .iter()
        .map(|(_, p, _)| vec![p[0], p[1]])
        .collect();
    corners_are_keys(&scene, &plan.shortened, &keyed, 1e-5);
    let (centres, radii): (Vec<Vec<f64>>, Vec<f64>) = scene
        .obstacles
        .iter()
        .map(|o| match o {
            viaroad::scene::Obstacle::Disc { centre, radius } => (centre.clone(), *radius),
            _ => panic!("discs only"),
        })
        .unzip();
    common::check_disc_path(
        &keyed,
        &centres,
        &radii,
        scene.space.lower(),
        scene.space.upper(),
        1e-6,
    )
    .unwrap();
}

/// The Panda in table_pick problem 1 with the OMPL peer's RRTConnect path.
fn panda_table_pick() -> (Arm, viaroad::scene::moveit::PlanningScene, Vec<Vec<f64>>) {
    let dir = root().join("scenes/arms");
    let scene = load_planning_scene(&dir.join("mbm/table_pick/scene0001.yaml")).unwrap();
    let req = load_motion_plan_request(&dir.join("mbm/table_pick/request0001.yaml")).unwrap();
    let mut arm = Arm::load(
        &dir.join("panda/panda.urdf"),
        Some(&dir.join("panda/panda.srdf")),
        &ArmOptions {
            group: GroupChoice::Srdf(req.group.clone()),
            ..ArmOptions::default()
        },
    )
    .unwrap();
    scene.apply_to(&mut arm).unwrap();
    req.start_goal(&mut arm).unwrap();
    let space =
        viaroad::space::Space::euclidean(arm.group.lower.clone(), arm.group.upper.clone()).unwrap();
    let path = ompl_cfg::read_states(
        &root().join("tests/data/arms/paths/table_pick_0001_rrtconnect.path"),
        &space,
    )
    .unwrap();
    (arm, scene, path)
}

#[test]
fn arm_links_follow_forward_kinematics_at_every_corner() {
    let (arm, scene, path) = panda_table_pick();
    let plan = Plan {
        raw: Vec::new(),
        shortened: path.clone(),
    };
    let g = export::arm::arm_gltf(&arm, &scene.objects, &plan, 0, &Legend::default()).unwrap();
    let glb = Glb::parse(&g.to_glb());
    let keys = export::arm::joint_keyframes(&path, 0);
    for (i, shape) in arm.shapes.iter().enumerate() {
        let name = format!("{} {}", arm.model.urdf.links[shape.link].name, i);
        let node_keys = glb.keys(glb.node(&name));
        assert_eq!(node_keys.len(), keys.len());
        for ((t, q, corner), (tk, p, r)) in keys.iter().zip(&node_keys) {
            assert!((t - tk).abs() < 1e-5);
            if !corner {
                continue;
            }
            let pose = arm.link_poses(q)[shape.link] * shape.origin;
            let tr = pose.translation.vector;
            assert!((0..3).all(|k| (tr[k] - p[k]).abs() < 1e-5), "{name} at {t}");
            let rq = pose.rotation;
            let dot = (rq.i * r[0] + rq.j * r[1] + rq.k * r[2] + rq.w * r[3]).abs();
            assert!(dot > 1.0 - 1e-6, "{name} turned at {t}");
        }
    }
    // every corner of the path is a key
    let corners: Vec<&Vec<f64>> = keys.iter().filter(|k| k.2).map(|k| &k.1).collect();
    assert_eq!(corners, path.iter().collect::<Vec<_>>());
}

/// `node` and tools/js/node_modules/gltf-validator, or why not.
fn validator() -> Result<PathBuf, String> {
    node_script("gltf-validator", "validate.js")
}

#[test]
fn khronos_validator_finds_no_errors() {
    let script = match validator() {
        Ok(s) => s,
        Err(why) => {
            skip("khronos_validator_finds_no_errors", &why);
            return;
        }
    };
    let dir = temp_dir("export_gltf", "validator");
    let mut files = Vec::new();
    for name in [
        "cube-into-box.toml",
        "se2-corridor.toml",
        "discs-cluttered.toml",
    ] {
        let scene = Scene::load(&root().join("scenes").join(name)).unwrap();
        let plan = plan(&scene);
        let (bytes, _) = exported(&scene, &plan);
        let f = dir.join(format!("{name}.glb"));
        std::fs::write(&f, bytes).unwrap();
        files.push(f);
    }
    let bodies = Scene::load(&root().join("scenes/bodies/swap-corridor-2.toml")).unwrap();
    let plan = Plan {
        raw: swap_by_hand(),
        shortened: Vec::new(),
    };
    let (bytes, _) = exported(&bodies, &plan);
    let f = dir.join("swap-corridor-2.glb");
    std::fs::write(&f, bytes).unwrap();
    files.push(f);
    let (arm, scene, path) = panda_table_pick();
    let plan = Plan {
        raw: path,
        shortened: Vec::new(),
    };
    let g = export::arm::arm_gltf(&arm, &scene.objects, &plan, 0, &Legend::default()).unwrap();
    let f = dir.join("panda.glb");
    std::fs::write(&f, g.to_glb()).unwrap();
    files.push(f);
    // end to end through the CLI on an OMPL.app problem (Y-up, a Collada robot), with the
    // grown roadmap drawn too
    let f = dir.join("easy.glb");
    let o = viaroad(&[
        "export",
        "scenes/ompl/3D/Easy.cfg",
        "--show-roadmap",
        "-o",
        f.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::cli::stderr(&o));
    let glb = Glb::parse(&std::fs::read(&f).unwrap());
    assert!(
        glb.doc["nodes"][glb.node("world")]
            .get("rotation")
            .is_none(),
        "OMPL 3D is Y-up"
    );
    glb.node("roadmap edges");
    files.push(f);
    // an arm scene planned in its joint space: a node per collision element, both hand traces
    let f = dir.join("panda-toml.glb");
    let o = viaroad(&[
        "export",
        "scenes/arms/panda-table_pick-1.toml",
        "-o",
        f.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::cli::stderr(&o));
    let glb = Glb::parse(&std::fs::read(&f).unwrap());
    let links = glb.doc["nodes"][glb.node("robot")]["children"]
        .as_array()
        .unwrap()
        .len();
    assert_eq!(links, panda_table_pick().0.shapes.len());
    glb.node("shortened path");
    files.push(f);
    let out = Command::new("node")
        .arg(&script)
        .args(&files)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let reports: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(reports.len(), files.len());
    for r in &reports {
        assert_eq!(r["errors"], 0, "{r}");
        assert_eq!(r["warnings"], 0, "{r}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cli_errors_are_reported_not_panicked() {
    let dir = temp_dir("export_gltf", "errors");
    let out = dir.join("x.glb");
    let out = out.to_str().unwrap();
    fails_with(
        &[
            "export",
            "scenes/discs-example.toml",
            "--query",
            "3",
            "-o",
            out,
        ],
        "has 1 queries, not 3",
    );
    let bad = write(&dir, "bad.path", "0.5 0.5 0.5\n");
    fails_with(
        &[
            "export",
            "scenes/discs-example.toml",
            "--path",
            &bad,
            "-o",
            out,
        ],
        "bad.path",
    );
    let r4 = write(
        &dir,
        "r4.toml",
        "name = \"r4\"\n[space]\nkind = \"rn\"\nlower = [0, 0, 0, 0]\nupper = [1, 1, 1, 1]\n\
         [[query]]\nstart = [0.1, 0.1, 0.1, 0.1]\ngoal = [0.9, 0.9, 0.9, 0.9]\n",
    );
    fails_with(&["view", &r4, "-o", out], "cannot draw");
    assert!(!Path::new(out).exists(), "nothing written on failure");
    let _ = std::fs::remove_dir_all(&dir);
}
