//! Regression tests of hostile robot and MoveIt inputs: a URDF of thousands of joints, a robot
//! of too many self-collision pairs, a PlanningScene of millions of objects or hundreds of
//! megabytes, YAML nested tens of thousands deep. Each is refused with one clear error before
//! the heavy work (the kinematic model, meshes, oracles, the YAML scan); the messages about a
//! joint cycle and about SRDF links the URDF lacks name what is wrong. The hostile files are
//! generated in a temporary directory; every test stays fast.

use crate::common;

use common::cli::{fails_with, temp_dir, write};
use std::path::Path;
use std::time::{Duration, Instant};
use viaroad::limits::{
    MAX_COLLISION_ELEMENTS, MAX_MOVEIT_YAML_BYTES, MAX_SCENE_OBJECTS, MAX_SCENE_SHAPES,
    MAX_SELF_PAIRS, MAX_URDF_ELEMENTS, MAX_YAML_DEPTH,
};
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{Arm, ArmOptions};
use viaroad::scene::moveit::{
    load_planning_scene, parse_motion_plan_request, parse_planning_scene,
};
use viaroad::scene::{Scene, SceneError};

/// Far more than any of these refusals takes, far less than the minutes they used to take.
const FAST: Duration = Duration::from_secs(2);

/// A chain of `n` revolute joints `j0 … j{n-1}` between links `l0 … l{n}`; each link carries
/// `collision` (empty for none).
fn chain_urdf(n: usize, collision: &str) -> String {
    let mut s = String::from("<robot name=\"chain\">\n");
    for i in 0..=n {
        s += &format!("<link name=\"l{i}\">{collision}</link>\n");
    }
    for i in 0..n {
        s += &format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
             <origin xyz=\"0 0 0.1\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\"/></joint>\n",
            i + 1
        );
    }
    s + "</robot>\n"
}

/// An SRDF whose one group is the whole chain `l0 → l{n}`, exempting `disabled` pairs.
fn chain_srdf(n: usize, disabled: &[(&str, &str)]) -> String {
    let mut s = format!(
        "<robot name=\"chain\"><group name=\"arm\"><chain base_link=\"l0\" tip_link=\"l{n}\"/></group>\n"
    );
    for (a, b) in disabled {
        s += &format!("<disable_collisions link1=\"{a}\" link2=\"{b}\" reason=\"Never\"/>\n");
    }
    s + "</robot>\n"
}

/// An arm scene of these files (relative to its directory), with one query of `dof` zeros.
fn arm_toml(urdf: &str, srdf: Option<&str>, group: Option<&str>, scene: Option<&str>) -> String {
    let mut s = format!("[space]\nkind = \"arm\"\n[robot]\nurdf = \"{urdf}\"\n");
    if let Some(srdf) = srdf {
        s += &format!("srdf = \"{srdf}\"\n");
    }
    if let Some(g) = group {
        s += &format!("group = {g}\n");
    }
    if let Some(scene) = scene {
        s += &format!("[environment]\nmoveit_scene = \"{scene}\"\n");
    }
    s
}

/// A link geometry whose mesh does not exist: reading it is an error of its own, so a refusal
/// that names something else came before any mesh was read.
const MISSING_MESH: &str =
    "<collision><geometry><mesh filename=\"package://nowhere/missing.stl\"/></geometry></collision>";

const SPHERE: &str = "<collision><geometry><sphere radius=\"0.01\"/></geometry></collision>";

fn load_err(path: &Path) -> String {
    match Scene::load(path) {
        Ok(_) => panic!("{} loaded", path.display()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_urdf_of_5000_joints_is_refused_before_the_model_is_built() {
    let dir = temp_dir("defects_inputs", "urdf5000");
    write(&dir, "chain.urdf", &chain_urdf(5000, SPHERE));
    write(&dir, "chain.srdf", &chain_srdf(5000, &[]));
    let toml = write(
        &dir,
        "chain.toml",
        &arm_toml("chain.urdf", Some("chain.srdf"), None, None),
    );
    let began = Instant::now();
    let line = fails_with(&["solve", &toml, "--time", "10"], "10001 links and joints");
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(line.contains(&MAX_URDF_ELEMENTS.to_string()), "{line}");
    // probe reads the scene the same way
    fails_with(
        &["probe", &toml, "--from=0", "--to=1"],
        "10001 links and joints",
    );
}

#[test]
fn a_urdf_of_too_many_collision_elements_is_refused_before_any_is_built() {
    // two joints, one link of many spheres: each sphere used to cost a polytope (10 ms)
    let spheres = SPHERE.repeat(MAX_COLLISION_ELEMENTS + 1);
    let text = format!(
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\">{spheres}</link>\
         <joint name=\"j0\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>\
         <joint name=\"j1\" type=\"continuous\"><parent link=\"b\"/><child link=\"c\"/></joint></robot>"
    );
    let dir = temp_dir("defects_inputs", "collisions");
    let urdf = write(&dir, "r.urdf", &text);
    let options = ArmOptions {
        group: GroupChoice::Joints(vec!["j0".into(), "j1".into()]),
        ..ArmOptions::default()
    };
    let began = Instant::now();
    let e = Arm::load(Path::new(&urdf), None, &options)
        .unwrap_err()
        .to_string();
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(
        e.contains(&format!(
            "{} collision elements",
            MAX_COLLISION_ELEMENTS + 1
        )),
        "{e}"
    );
    // at the limit the elements are read (and the first missing mesh is the error)
    let text = text
        .replacen(SPHERE, "", 1)
        .replacen(SPHERE, MISSING_MESH, 1);
    let urdf = write(&dir, "r.urdf", &text);
    let e = Arm::load(Path::new(&urdf), None, &options)
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.stl"), "{e}");
}

#[test]
fn a_planning_group_of_1000_joints_is_refused_before_any_mesh_is_read() {
    // the root link's mesh is missing: the group's size must be the error, found first
    let dir = temp_dir("defects_inputs", "group1000");
    let urdf = chain_urdf(1000, "").replacen(
        "<link name=\"l0\"></link>",
        &format!("<link name=\"l0\">{MISSING_MESH}</link>"),
        1,
    );
    assert!(urdf.contains("missing.stl"));
    write(&dir, "chain.urdf", &urdf);
    write(&dir, "chain.srdf", &chain_srdf(1000, &[]));
    let toml = write(
        &dir,
        "chain.toml",
        &arm_toml("chain.urdf", Some("chain.srdf"), None, None),
    );
    let began = Instant::now();
    let line = fails_with(
        &["solve", &toml, "--time", "10"],
        "a joint space needs 2 to 64 joints",
    );
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(line.contains("group arm has 1000 joints"), "{line}");
    assert!(!line.contains("missing.stl"), "{line}");
    // a group named joint by joint is counted before the names are looked up
    let names: Vec<String> = (0..1000).map(|i| format!("\"j{i}\"")).collect();
    let toml = write(
        &dir,
        "named.toml",
        &arm_toml(
            "chain.urdf",
            None,
            Some(&format!("[{}]", names.join(", "))),
            None,
        ),
    );
    let e = load_err(Path::new(&toml));
    assert!(e.contains("a joint space needs 2 to 64 joints"), "{e}");
}

#[test]
fn a_robot_of_too_many_self_collision_pairs_is_refused_before_any_mesh_is_read() {
    // 201 links with geometry: 20 100 pairs, 3 joints planned
    let dir = temp_dir("defects_inputs", "pairs");
    let urdf = write(&dir, "chain.urdf", &chain_urdf(200, MISSING_MESH));
    let options = ArmOptions {
        group: GroupChoice::Joints(vec!["j0".into(), "j1".into(), "j2".into()]),
        ..ArmOptions::default()
    };
    let began = Instant::now();
    let e = Arm::load(Path::new(&urdf), None, &options)
        .unwrap_err()
        .to_string();
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(e.contains("20100 self-collision pairs"), "{e}");
    assert!(e.contains(&MAX_SELF_PAIRS.to_string()), "{e}");
    assert!(!e.contains("missing.stl"), "{e}");
    // exempting all but a few pairs makes the same robot acceptable to the count (its meshes
    // are then read, and missing)
    let mut disabled = Vec::new();
    let names: Vec<String> = (0..=200).map(|i| format!("l{i}")).collect();
    for a in 0..=200 {
        for b in a + 1..=200 {
            if b > 3 {
                disabled.push((names[a].as_str(), names[b].as_str()));
            }
        }
    }
    let srdf = write(&dir, "chain.srdf", &chain_srdf(200, &disabled));
    let e = Arm::load(Path::new(&urdf), Some(Path::new(&srdf)), &options)
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.stl"), "{e}");
}

#[test]
fn a_robot_description_of_a_million_xml_nodes_is_refused_while_parsing() {
    let dir = temp_dir("defects_inputs", "nodes");
    let text = format!(
        "<robot name=\"r\"><link name=\"a\"/>{}</robot>",
        "<x/>".repeat(1_100_000)
    );
    let urdf = write(&dir, "big.urdf", &text);
    let began = Instant::now();
    let e = Arm::load(Path::new(&urdf), None, &ArmOptions::default())
        .unwrap_err()
        .to_string();
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(e.contains("XML nodes"), "{e}");
}

#[test]
fn a_joint_cycle_names_its_links_and_joints() {
    let p = Path::new("cycle.urdf");
    let model = |text: &str| {
        viaroad::robot::urdf::parse_urdf(text, p)
            .and_then(|u| viaroad::robot::Model::new(u, p))
            .unwrap_err()
            .to_string()
    };
    // every link has a parent: no root at all
    let e = model(
        r#"<robot><link name="a"/><link name="b"/>
           <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
           <joint name="k" type="fixed"><parent link="b"/><child link="a"/></joint></robot>"#,
    );
    assert!(
        e.contains("cycle through links a → b → a (joints j, k)")
            || e.contains("cycle through links b → a → b (joints k, j)"),
        "{e}"
    );
    assert!(!e.contains("[]"), "{e}");
    // a root, and a cycle beside its tree
    let e = model(
        r#"<robot><link name="root"/><link name="t"/><link name="c1"/><link name="c2"/><link name="c3"/>
           <joint name="r" type="fixed"><parent link="root"/><child link="t"/></joint>
           <joint name="x" type="fixed"><parent link="c1"/><child link="c2"/></joint>
           <joint name="y" type="fixed"><parent link="c2"/><child link="c3"/></joint>
           <joint name="z" type="fixed"><parent link="c3"/><child link="c1"/></joint></robot>"#,
    );
    assert!(e.contains("cycle through links c"), "{e}");
    for name in ["c1", "c2", "c3", "x", "y", "z"] {
        assert!(e.contains(name), "{name} not in {e}");
    }
    assert!(!e.contains("root"), "{e}");
    // a joint from a link to itself
    let e = model(
        r#"<robot><link name="a"/><joint name="j" type="fixed"><parent link="a"/><child link="a"/></joint></robot>"#,
    );
    assert!(e.contains("cycle through links a → a (joints j)"), "{e}");
}

/// Three links with boxes under two revolute joints.
const SMALL_URDF: &str = r#"<robot name="small">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.1 0.8"/></geometry></collision></link>
  <link name="lower"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.1 0.8"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/></joint>
  <joint name="j2" type="revolute"><parent link="upper"/><child link="lower"/><origin xyz="0 0 1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/></joint>
</robot>"#;

#[test]
fn srdf_disable_collisions_of_unknown_links_warn_once_and_are_ignored() {
    let dir = temp_dir("defects_inputs", "srdf");
    write(&dir, "small.urdf", SMALL_URDF);
    write(
        &dir,
        "small.srdf",
        r#"<robot name="small"><group name="arm"><chain base_link="base" tip_link="lower"/></group>
           <disable_collisions link1="base" link2="upper" reason="Adjacent"/>
           <disable_collisions link1="upper" link2="lower" reason="Adjacent"/>
           <disable_collisions link1="base" link2="l_wheel_link" reason="Adjacent"/>
           <disable_collisions link1="r_wheel_link" link2="l_wheel_link" reason="Never"/>
           <disable_collisions link1="lower" link2="r_wheel_link" reason="Never"/></robot>"#,
    );
    let toml = write(
        &dir,
        "small.toml",
        &(arm_toml("small.urdf", Some("small.srdf"), None, None)
            + "[[query]]\nstart = [0, 0]\ngoal = [0.5, -0.5]\n"),
    );
    let scene = Scene::load(Path::new(&toml)).unwrap();
    let about: Vec<&String> = scene
        .warnings
        .iter()
        .filter(|w| w.contains("disable_collisions"))
        .collect();
    assert_eq!(about.len(), 1, "{:?}", scene.warnings);
    assert!(
        about[0].contains("2 link(s)") && about[0].contains("l_wheel_link, r_wheel_link"),
        "{}",
        about[0]
    );
    // the known pairs are still exempt: only base–lower is checked
    let viaroad::scene::Robot::Arm(robot) = &scene.robot else {
        panic!("not an arm")
    };
    assert_eq!(robot.arm.self_pairs, [(0, 2)]);
    // and the command line prints it once, as a warning, then plans
    let o = common::cli::viaroad(&["solve", &toml, "--time", "5"]);
    let err = common::cli::stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert_eq!(
        err.lines()
            .filter(|l| l.starts_with("warning:") && l.contains("disable_collisions"))
            .count(),
        1,
        "{err}"
    );
}

#[test]
fn a_moveit_scene_larger_than_the_limit_is_refused_before_it_is_read() {
    let dir = temp_dir("defects_inputs", "bigyaml");
    let path = dir.join("scene.yaml");
    // a sparse file of zeros: its size is all there is to check
    std::fs::File::create(&path)
        .unwrap()
        .set_len(MAX_MOVEIT_YAML_BYTES + 1)
        .unwrap();
    let began = Instant::now();
    let e = load_planning_scene(&path).unwrap_err();
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(matches!(e, SceneError::File(_)), "{e}");
    assert!(
        e.to_string().contains(&MAX_MOVEIT_YAML_BYTES.to_string()),
        "{e}"
    );
    // through an arm scene too, before the robot is loaded (its mesh is missing)
    write(&dir, "r.urdf", &chain_urdf(2, MISSING_MESH));
    let toml = write(
        &dir,
        "s.toml",
        &arm_toml("r.urdf", None, Some("[\"j0\", \"j1\"]"), Some("scene.yaml")),
    );
    fails_with(&["solve", &toml, "--time", "10"], "bytes, more than the");
}

#[test]
fn a_moveit_scene_of_too_many_objects_or_shapes_is_refused() {
    let p = Path::new("scene.yaml");
    let box_part = "{type: box, dimensions: [0.1, 0.1, 0.1]}";
    let pose = "{position: [0, 0, 5], orientation: [0, 0, 0, 1]}";
    // objects with nothing in them: only their number counts
    let objects: Vec<String> = (0..=MAX_SCENE_OBJECTS)
        .map(|i| format!("{{id: o{i}}}"))
        .collect();
    let text = format!("world:\n  collision_objects: [{}]\n", objects.join(", "));
    let began = Instant::now();
    let e = parse_planning_scene(&text, p).unwrap_err();
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(matches!(e, SceneError::Invalid { .. }), "{e}");
    let e = e.to_string();
    assert!(e.contains("collision_objects"), "{e}");
    assert!(
        e.contains(&format!("more than {MAX_SCENE_OBJECTS} items")),
        "{e}"
    );
    // the limit itself is accepted
    let text = format!(
        "world:\n  collision_objects: [{}]\n",
        objects[..MAX_SCENE_OBJECTS].join(", ")
    );
    assert_eq!(
        parse_planning_scene(&text, p).unwrap().objects.len(),
        MAX_SCENE_OBJECTS
    );
    // one object of too many primitives
    let n = MAX_SCENE_SHAPES + 1;
    let text = format!(
        "world:\n  collision_objects:\n    - id: many\n      primitives: [{}]\n      primitive_poses: [{}]\n",
        vec![box_part; n].join(", "),
        vec![pose; n].join(", ")
    );
    let e = parse_planning_scene(&text, p).unwrap_err().to_string();
    assert!(e.contains("primitives") && e.contains("more than"), "{e}");
    // two objects, each within the limit, together beyond it
    let half = MAX_SCENE_SHAPES / 2 + 1;
    let object = |id: &str| {
        format!(
            "    - id: {id}\n      primitives: [{}]\n      primitive_poses: [{}]\n",
            vec![box_part; half].join(", "),
            vec![pose; half].join(", ")
        )
    };
    let text = format!(
        "world:\n  collision_objects:\n{}{}",
        object("a"),
        object("b")
    );
    let e = parse_planning_scene(&text, p).unwrap_err().to_string();
    assert!(
        e.contains(&format!("{} primitives and meshes", 2 * half)),
        "{e}"
    );
}

#[test]
fn yaml_nested_tens_of_thousands_deep_is_refused_at_once() {
    let p = Path::new("deep.yaml");
    let flow_seq = format!("world: {}{}\n", "[".repeat(80_000), "]".repeat(80_000));
    let flow_map = format!("world: {}x{}\n", "{a: ".repeat(50_000), "}".repeat(50_000));
    // unclosed: the parse would fail at the end, after the quadratic scan
    let unclosed = format!("world: {}", "[".repeat(80_000));
    let block_seq = format!("world:\n  {}x\n", "- ".repeat(200));
    let mut block_map = String::from("world:\n");
    for i in 0..200 {
        block_map += &format!("{}a{i}:\n", " ".repeat(i + 2));
    }
    for text in [&flow_seq, &flow_map, &unclosed, &block_seq, &block_map] {
        let began = Instant::now();
        let e = parse_planning_scene(text, p).unwrap_err().to_string();
        assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
        assert!(
            e.contains(&format!("nested deeper than {MAX_YAML_DEPTH}")),
            "{e}"
        );
    }
    // requests are read the same way
    let request = format!(
        "group_name: arm\ngoal_constraints: {}{}\n",
        "[".repeat(80_000),
        "]".repeat(80_000)
    );
    let began = Instant::now();
    let e = parse_motion_plan_request(&request, p)
        .unwrap_err()
        .to_string();
    assert!(began.elapsed() < FAST, "{:?}", began.elapsed());
    assert!(e.contains("nested deeper than"), "{e}");
}

#[test]
fn brackets_inside_quoted_and_block_scalars_are_not_nesting() {
    let p = Path::new("s.yaml");
    let deep = "[{".repeat(200);
    let text = format!(
        "name: '{deep}'\n# {deep}\nworld:\n  collision_objects:\n    - id: \"{deep}\"\n      \
         primitives: [{{type: sphere, dimensions: [0.1]}}]\n      \
         primitive_poses: [{{position: [0, 0, 5], orientation: [0, 0, 0, 1]}}]\n    \
         - id: plain{deep}\n"
    );
    let s = parse_planning_scene(&text, p).unwrap();
    assert_eq!(s.name, deep);
    assert_eq!(s.objects[0].id, deep);
    assert_eq!(s.objects[1].id, format!("plain{deep}"));
}

#[test]
fn every_shipped_moveit_file_and_arm_scene_still_loads() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let mut yamls = 0;
    for family in std::fs::read_dir(root.join("mbm")).unwrap() {
        for f in std::fs::read_dir(family.unwrap().path()).unwrap() {
            let f = f.unwrap().path();
            let name = f.file_name().unwrap().to_string_lossy().into_owned();
            if name.starts_with("scene") {
                load_planning_scene(&f).unwrap();
            } else if name.starts_with("request") {
                viaroad::scene::moveit::load_motion_plan_request(&f).unwrap();
            } else {
                continue;
            }
            yamls += 1;
        }
    }
    assert!(yamls >= 14, "{yamls}");
    let mut scenes = 0;
    for f in std::fs::read_dir(&root).unwrap() {
        let f = f.unwrap().path();
        if f.extension().is_some_and(|e| e == "toml") {
            let scene = Scene::load(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            // the Panda's SRDF names only links of its URDF
            assert!(
                scene
                    .warnings
                    .iter()
                    .all(|w| !w.contains("disable_collisions")),
                "{:?}",
                scene.warnings
            );
            scenes += 1;
        }
    }
    assert!(scenes >= 4, "{scenes}");
    // the SRDF still exempts the Panda's 34 pairs
    let dir = root.join("panda");
    let arm = Arm::load(
        &dir.join("panda.urdf"),
        Some(&dir.join("panda.srdf")),
        &ArmOptions::default(),
    )
    .unwrap();
    assert!(arm.warnings.is_empty(), "{:?}", arm.warnings);
    assert_eq!(arm.self_pairs.len(), 55 - 34);
}
