//! Several bodies in the plane through the commands around planning: `certify` (per segment
//! free, colliding with a witness, or proved by advancement; `--repair`), `serve` (a query
//! answered over stdin), `solve --tree --check`, and the movers in a room solved. Every path
//! that comes back is re-checked by the independent checker (`common::bodies`).

use crate::common;

use common::bodies::BodiesChecker;
use common::cli::{stderr, stdout, temp_dir, viaroad, write};
use std::io::Write;
use std::process::{Command, Stdio};
use viaroad::scene::Scene;
use viaroad::space::Config;

const SWAP2: &str = "scenes/bodies/swap-corridor-2.toml";

fn load(file: &str) -> Scene {
    Scene::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file)).unwrap()
}

fn json(line: &str) -> serde_json::Value {
    serde_json::from_str(line.trim()).unwrap_or_else(|e| panic!("{e}: {line}"))
}

fn path_of(v: &serde_json::Value) -> Vec<Config> {
    serde_json::from_value(v.clone()).unwrap_or_else(|_| panic!("not a path: {v}"))
}

fn state_file(path: &[[f64; 6]]) -> String {
    path.iter()
        .map(|q| q.map(|v| v.to_string()).join(" ") + "\n")
        .collect()
}

#[test]
fn certify_gives_each_segment_a_verdict_and_repairs_the_blocked_ones() {
    let dir = temp_dir("bodies_commands", "certify");
    // s1 runs right while s2 rises: they meet (exact, one call); s2 comes down (free); both
    // translate left together (free); one waypoint pair moves and turns both at once (proved by
    // advancement)
    let path = [
        [0.5, 0.5, 0.0, 1.5, 0.5, 0.0],
        [2.5, 0.5, 0.0, 1.5, 1.5, 0.0],
        [2.5, 0.5, 0.0, 1.5, 0.5, 0.0],
        [1.5, 0.5, 0.0, 0.5, 0.5, 0.0],
        [1.45, 0.52, 0.05, 0.55, 0.48, -0.05],
        [1.5, 0.5, 0.0, 0.5, 0.5, 0.0],
    ];
    let file = write(&dir, "swap.path", &state_file(&path));
    let o = viaroad(&["certify", SWAP2, &file, "--json"]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let v = json(&stdout(&o));
    let segments = v["certificate"]["segments"].as_array().unwrap();
    let verdicts: Vec<&str> = segments
        .iter()
        .map(|s| s["verdict"].as_str().unwrap())
        .collect();
    assert_eq!(
        verdicts,
        ["collides", "free", "free", "free", "free"],
        "{v}"
    );
    let hit = &segments[0];
    assert_eq!(hit["exact"], true);
    assert_eq!(hit["pairs"], serde_json::json!([["s1", "s2"]]));
    // the witness collides by the independent checker too
    let checker = BodiesChecker::new(&load(SWAP2));
    let witness: Config = serde_json::from_value(hit["witness"].clone()).unwrap();
    assert!(checker.clearance(&witness) <= 1e-9, "{witness:?}");
    // the free segments are free by the checker
    let free: Vec<Config> = path[1..].iter().map(|q| q.to_vec()).collect();
    checker.certify_path(&free).unwrap();
    // --repair replaces the blocked segment by a certified detour
    let fixed = dir.join("fixed.path").to_string_lossy().into_owned();
    let o = viaroad(&["certify", SWAP2, &file, "--repair", "-o", &fixed]);
    assert!(o.status.success(), "{}", stderr(&o));
    let space = load(SWAP2).space;
    let repaired =
        viaroad::scene::ompl_cfg::read_states(std::path::Path::new(&fixed), &space).unwrap();
    assert!(repaired.len() > path.len());
    assert_eq!(repaired[0], path[0].to_vec());
    checker.certify_path(&repaired).unwrap();
}

#[test]
fn serve_answers_a_query_of_several_bodies() {
    let dir = temp_dir("bodies_commands", "serve");
    let map = dir.join("swap2.bin").to_string_lossy().into_owned();
    let o = viaroad(&["build", SWAP2, "-o", &map, "--nodes", "3000", "--seed", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let scene = load(SWAP2);
    let q = &scene.queries[0];
    let line = serde_json::json!({ "id": 7, "start": q.start, "goal": q.goal }).to_string();
    let mut child = Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .args(["serve", &map, "--scene", SWAP2])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // one line, then end of input: the server answers and stops
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(line.as_bytes()).unwrap();
    stdin.write_all(b"\n").unwrap();
    drop(stdin);
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reply = json(String::from_utf8_lossy(&out.stdout).lines().next().unwrap());
    assert_eq!(reply["id"], 7, "{reply}");
    assert_eq!(reply["solved"], true, "{reply}");
    let checker = BodiesChecker::new(&scene);
    for key in ["path", "shortened"] {
        let p = path_of(&reply[key]);
        assert_eq!(p[0], q.start);
        assert_eq!(p.last().unwrap(), &q.goal);
        checker
            .certify_path(&p)
            .unwrap_or_else(|e| panic!("{key}: {e}"));
    }
}

/// Two squares that trade places in an open room.
const OPEN: &str = r#"
[space]
kind = "se2"
lower = [0.0, 0.0]
upper = [4.0, 3.0]

[[body]]
name = "a"
box = { half_extents = [0.4, 0.4] }

[[body]]
name = "b"
box = { half_extents = [0.4, 0.3] }

[[obstacle]]
box = { center = [2.0, 1.5], half_extents = [0.3, 0.3] }

[[query]]
start = [0.6, 1.5, 0.0, 3.4, 1.5, 0.0]
goal  = [3.4, 1.5, 1.0, 0.6, 1.5, 0.0]
"#;

#[test]
fn solve_tree_check_certifies_several_bodies() {
    let dir = temp_dir("bodies_commands", "tree");
    let file = write(&dir, "open.toml", OPEN);
    let o = viaroad(&[
        "solve", &file, "--tree", "--nodes", "5000", "--check", "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&stdout(&o));
    assert_eq!(v["solved"], true, "{v}");
    assert_eq!(v["certified"], true, "{v}");
    let scene = Scene::load(std::path::Path::new(&file)).unwrap();
    let checker = BodiesChecker::new(&scene);
    for key in ["path", "shortened"] {
        checker.certify_path(&path_of(&v[key])).unwrap();
    }
}

#[test]
fn movers_in_a_room_pass_each_other_through_the_door() {
    // a node budget: the same answer on any machine
    let file = "scenes/bodies/movers-room.toml";
    let o = viaroad(&["solve", file, "--roadmap", "--nodes", "500", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&stdout(&o));
    assert_eq!(v["solved"], true, "{v}");
    let scene = load(file);
    let checker = BodiesChecker::new(&scene);
    for key in ["path", "shortened"] {
        let p = path_of(&v[key]);
        assert_eq!(p[0], scene.queries[0].start);
        checker
            .certify_path(&p)
            .unwrap_or_else(|e| panic!("{key}: {e}"));
        // the piano ends in the right room, the chairs in the left one
        let end = p.last().unwrap();
        assert!(end[0] > 5.0 && end[3] < 5.0 && end[6] < 5.0, "{end:?}");
    }
}
