//! Several bodies moving at once in space (SE(3)^k): the exact oracle of the seed's motions
//! (all bodies translate, or one turns about a fixed axis) against the independent parry
//! checker, the shipped two cubes into two boxes solved by `solve` and by `build` + `query`
//! with every path certified, and scene files that are refused.

use crate::common;

use common::bodies3::SolidBodiesChecker;
use common::cli::{fails_with, stderr, stdout, temp_dir, viaroad, write};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use viaroad::oracle::{CallCounts, CountedOracle};
use viaroad::scene::toml_format;
use viaroad::scene::Scene;
use viaroad::space::{Change, Config, Motion};

/// Three bodies (a cube, a slab, a wedge) in a room with a pillar and a table.
const ROOM: &str = r#"
[space]
kind = "se3"
lower = [-3.0, -3.0, -1.0]
upper = [3.0, 3.0, 3.0]

[[body]]
name = "cube"
box = { half_extents = [0.4, 0.4, 0.4] }

[[body]]
name = "slab"
box = { half_extents = [0.6, 0.2, 0.3] }

[[body]]
name = "wedge"
convex = { points = [[-0.5, -0.3, -0.3], [0.5, -0.3, -0.3], [-0.5, 0.4, -0.3], [0.5, 0.4, -0.3], [-0.5, -0.3, 0.5], [0.5, -0.3, 0.5]] }
center = "mean"

[[obstacle]]
box = { center = [0.0, 0.0, 1.0], half_extents = [0.3, 0.3, 1.5] }
[[obstacle]]
box = { center = [1.5, -1.5, 0.2], half_extents = [0.8, 0.8, 0.2] }
"#;

fn room() -> Scene {
    toml_format::from_str(ROOM, std::path::Path::new("room.toml")).unwrap()
}

fn shipped() -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/bodies");
    Scene::load(&dir.join("cubes-into-boxes-2.toml")).unwrap()
}

/// A random motion of the seed's kinds from `q`: all bodies translate (each by its own vector)
/// or one body turns about a random axis through its reference point.
fn seed_motion(q: &[f64], rng: &mut ChaCha8Rng) -> Motion {
    let k = q.len() / 7;
    if rng.random_bool(0.5) {
        let mut delta = vec![0.0; q.len()];
        for i in 0..k {
            for c in 0..3 {
                delta[7 * i + c] = rng.random_range(-1.5..1.5);
            }
        }
        Motion::segment(q.to_vec(), Change::Linear(delta))
    } else {
        let v: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
        let turn = Change::BodyRotation {
            body: rng.random_range(0..k),
            axis: [v[0] / n, v[1] / n, v[2] / n],
            angle: rng.random_range(-2.5..2.5),
        };
        Motion::segment(q.to_vec(), turn)
    }
}

#[test]
fn the_exact_oracle_agrees_with_the_independent_checker_in_space() {
    let scene = room();
    let oracle = scene.oracle();
    let checker = SolidBodiesChecker::new(&scene);
    let mut rng = ChaCha8Rng::seed_from_u64(47);
    let (mut free, mut blocked, mut motions) = (0, 0, 0);
    while motions < 30 {
        let q = scene.space.sample_uniform(&mut rng);
        if !oracle.is_free(&q, &mut CallCounts::default()) {
            continue;
        }
        motions += 1;
        let m = seed_motion(&q, &mut rng);
        let hits = oracle.intersect(&m, &mut CallCounts::default()).unwrap();
        // every free section is certified free by the checker, a little inside its ends
        for gap in hits.complement_within(m.range).iter() {
            let (lo, hi) = (gap.lo, gap.hi);
            if hi - lo < 1e-6 {
                continue;
            }
            let pad = 1e-6 * (hi - lo);
            let (a, b) = (m.at(lo + pad), m.at(hi - pad));
            checker
                .certify_motion(&a, &b)
                .unwrap_or_else(|e| panic!("the oracle calls {a:?} → {b:?} free: {e}"));
            free += 1;
        }
        // inside every collision interval the bodies touch or hold something (or leave the
        // bounds)
        for iv in hits.iter() {
            let c = m.at(iv.centre());
            let inside = scene.space.in_bounds(&c);
            assert!(
                !inside || checker.clearance(&c) < 1e-6 || checker.contained(&c),
                "the oracle calls {c:?} a collision, the checker finds clearance {}",
                checker.clearance(&c)
            );
            blocked += 1;
        }
    }
    assert!(free > 15 && blocked > 8, "{free} free, {blocked} blocked");
}

/// The path printed under `key` in a `--json` line.
fn path_of(line: &str, key: &str) -> Vec<Config> {
    let v: serde_json::Value = serde_json::from_str(line).unwrap();
    serde_json::from_value(v[key].clone()).unwrap_or_else(|_| panic!("no {key} in {line}"))
}

/// Certifies `path` with the independent checker, and that it runs from `start` to `goal`.
fn certified(scene: &Scene, (start, goal): (&[f64], &[f64]), path: &[Config], what: &str) {
    assert!(path.len() >= 2, "{what}: {path:?}");
    let close = |a: &[f64], b: &[f64]| scene.space.distance(a, b) < 1e-9;
    assert!(
        close(&path[0], start) && close(path.last().unwrap(), goal),
        "{what}"
    );
    SolidBodiesChecker::new(scene)
        .certify_path(path)
        .unwrap_or_else(|e| panic!("{what}: {e}"));
}

#[test]
fn two_cubes_into_two_boxes_are_solved_by_solve_and_a_saved_roadmap() {
    let file = "scenes/bodies/cubes-into-boxes-2.toml";
    let args = ["solve", file, "--roadmap", "--nodes", "500", "--json"];
    let o = viaroad(&args);
    let out = stdout(&o);
    assert!(o.status.success(), "{args:?}: {}", common::cli::stderr(&o));
    assert!(out.contains("\"solved\":true"), "{args:?}: {out}");
    let scene = shipped();
    let q = &scene.queries[0];
    for key in ["path", "shortened"] {
        let path = path_of(out.trim(), key);
        certified(&scene, (&q.start, &q.goal), &path, &format!("solve, {key}"));
    }
    // a learnt roadmap holds no configuration with both cubes in their boxes (a narrow
    // passage a query would grow into for seconds): its query ends with the cubes above them
    let dir = temp_dir("bodies3", "roadmap");
    let map = dir.join("boxes2.bin").to_string_lossy().into_owned();
    let o = viaroad(&["build", file, "-o", &map, "--nodes", "300", "--seed", "1"]);
    assert!(o.status.success(), "{}", common::cli::stderr(&o));
    let mut above = q.goal.clone();
    above[2] = 2.0;
    above[9] = 2.0;
    let line: Vec<String> = q.start.iter().chain(&above).map(f64::to_string).collect();
    let queries = write(&dir, "above.txt", &(line.join(" ") + "\n"));
    let o = viaroad(&[
        "query",
        &map,
        "--scene",
        file,
        "--queries",
        &queries,
        "--json",
    ]);
    let out = stdout(&o);
    assert!(out.contains("\"solved\":true"), "{out}");
    certified(
        &scene,
        (&q.start, &above),
        &path_of(out.trim(), "path"),
        "query",
    );
}

#[test]
fn certify_gives_each_segment_of_several_bodies_in_space_a_verdict() {
    let dir = temp_dir("bodies3", "certify");
    let file = "scenes/bodies/cubes-into-boxes-2.toml";
    let pose = |x: f64, z: f64, turn: f64| {
        let h = turn / 2.0;
        vec![x, 0.0, z, 0.0, 0.0, h.sin(), h.cos()]
    };
    let both = |red: Vec<f64>, blue: Vec<f64>| [red, blue].concat();
    // both cubes go down into their boxes and up again (one exact call each), then cross
    // above the boxes and meet halfway (exact), then red rises while it turns (neither of the
    // seed's motions: proved by advancement)
    let path = [
        both(pose(-1.25, 2.5, 0.0), pose(1.25, 2.5, 0.0)),
        both(pose(-1.25, 0.55, 0.0), pose(1.25, 0.55, 0.0)),
        both(pose(-1.25, 2.5, 0.0), pose(1.25, 2.5, 0.0)),
        both(pose(1.25, 2.5, 0.0), pose(-1.25, 2.5, 0.0)),
        both(pose(1.25, 2.8, 0.3), pose(-1.25, 2.5, 0.0)),
    ];
    let lines: String = path
        .iter()
        .map(|q| q.iter().map(f64::to_string).collect::<Vec<_>>().join(" ") + "\n")
        .collect();
    let states = write(&dir, "cubes.path", &lines);
    let o = viaroad(&["certify", file, &states, "--json"]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    let segments = v["certificate"]["segments"].as_array().unwrap();
    let verdicts: Vec<&str> = segments
        .iter()
        .map(|s| s["verdict"].as_str().unwrap())
        .collect();
    assert_eq!(verdicts, ["free", "free", "collides", "free"], "{v}");
    assert_eq!(segments[2]["pairs"], serde_json::json!([["red", "blue"]]));
    let scene = shipped();
    let checker = SolidBodiesChecker::new(&scene);
    let witness: Config = serde_json::from_value(segments[2]["witness"].clone()).unwrap();
    assert!(
        checker.clearance(&witness) <= 1e-9 || checker.contained(&witness),
        "{witness:?}"
    );
    for i in [0, 1, 3] {
        checker.certify_motion(&path[i], &path[i + 1]).unwrap();
    }
}

#[test]
fn bad_scenes_of_several_bodies_in_space_are_refused() {
    let dir = temp_dir("bodies3", "refused");
    let body = |name: &str| {
        format!("[[body]]\nname = \"{name}\"\nbox = {{ half_extents = [0.4, 0.4, 0.4] }}\n")
    };
    let space = "[space]\nkind = \"se3\"\nlower = [0.0, 0.0, 0.0]\nupper = [4.0, 4.0, 4.0]\n";
    let two = format!("{space}{}{}", body("a"), body("b"));
    let pose = |x: f64| format!("{x}, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0");
    let query =
        |start: String, goal: String| format!("[[query]]\nstart = [{start}]\ngoal = [{goal}]\n");
    let apart = format!("{}, {}", pose(1.0), pose(3.0));
    let cases = [
        (format!("{space}{}{}", body("a"), body("a")), "the name \"a\" is taken".to_string()),
        (
            format!("{space}[robot]\nbox = {{ half_extents = [0.4, 0.4, 0.4] }}\n{}", body("a")),
            "not both".into(),
        ),
        (
            format!("{space}[[body]]\nbox = {{ half_extents = [0.4, 0.4, 0.4] }}\n"),
            "give it a name".into(),
        ),
        (
            format!("{space}[[body]]\nname = \"flat\"\npolygon = {{ vertices = [[0, 0], [1, 0], [0, 1]] }}\n"),
            "body \"flat\": polygons describe se2 robots".into(),
        ),
        (
            format!("{space}{}", (0..10).map(|i| body(&format!("b{i}"))).collect::<String>()),
            "at most 9 bodies".into(),
        ),
        (
            format!("{two}{}", query(pose(1.0), apart.clone())),
            "configuration has 7 coordinates, the se3x2 space needs 14".into(),
        ),
        (
            format!("{two}{}", query(apart.replacen("1.0", "nan", 1), apart.clone())),
            "not a finite number".into(),
        ),
        (
            format!("{two}{}", query(format!("{}, {}", pose(1.0), pose(1.5)), apart.clone())),
            "in collision".into(),
        ),
        (
            format!(
                "{two}{}",
                query(apart.clone(), apart.replace("0.0, 0.0, 0.0, 1.0", "0.0, 0.0, 0.0, 0.0"))
            ),
            "quaternion".into(),
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let path = write(&dir, &format!("bad{i}.toml"), text);
        fails_with(&["solve", &path], needle);
    }
}

#[test]
fn oracle_calls_of_several_bodies_in_space_are_counted() {
    let scene = room();
    let oracle = scene.oracle();
    let at = |x: f64, y: f64| [x, y, 1.0, 0.0, 0.0, 0.0, 1.0];
    // beside the pillar and each other: the motions reach them
    let q = [at(-0.8, 0.0), at(1.2, 0.0), at(0.0, 1.2)].concat();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut counts = CallCounts::default();
    for _ in 0..5 {
        let _ = oracle
            .intersect(&seed_motion(&q, &mut rng), &mut counts)
            .unwrap();
    }
    assert_eq!(counts.segment_calls, 5);
    assert!(counts.pairs_tested > 0, "{counts:?}");
}

#[test]
fn quaternions_of_several_bodies_are_normalised_with_a_warning() {
    let text = format!(
        "{ROOM}[[query]]\nstart = [-2, -2, 1, 0, 0, 0, 1, 2, 2, 1, 0, 0, 0, 2, -2, 2, 1, 0, 0, 0, 1]\n\
         goal = [-2, -2, 2, 0, 0, 0, 1, 2, 2, 2, 0, 0, 0, 1, -2, 2, 2, 0, 0, 0, 1]\n"
    );
    let scene = toml_format::from_str(&text, std::path::Path::new("room.toml")).unwrap();
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("start of query 1: body 2's quaternion of length 2")),
        "{:?}",
        scene.warnings
    );
    assert_eq!(scene.queries[0].start[13], 1.0);
}
