//! `viaroad solve` without a mode flag picks its planners: the via-point planner's cheap try,
//! then trees and a grown roadmap raced. Every path it prints is re-checked by the independent
//! rigid-body checker (parry, sampled finely), a node budget gives the same answer on one thread
//! and on two, `[benchmark] time_limit` is read from `.cfg` files, and `view`/`export` plan as
//! `solve` does.

use crate::common;

use common::cli::{fails_with, stderr, stdout, temp_dir, viaroad, write};
use common::rigid::RigidChecker;
use std::path::Path;
use std::process::Command;
use viaroad::scene::ompl_cfg::time_limit;
use viaroad::scene::Scene;

const CUBE: &str = "scenes/cube-into-box.toml";

/// The JSON lines of a run of `viaroad solve ARGS` with `threads` rayon threads.
fn solve_json(args: &[&str], threads: &str) -> Vec<serde_json::Value> {
    let o = Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .arg("solve")
        .args(args)
        .arg("--json")
        .env("RAYON_NUM_THREADS", threads)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    stdout(&o)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn path(v: &serde_json::Value) -> Vec<Vec<f64>> {
    serde_json::from_value(v.clone()).unwrap()
}

#[test]
fn the_default_answers_the_cube_into_the_box_with_certified_paths_on_any_thread_count() {
    let scene = Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(CUBE)).unwrap();
    let checker = RigidChecker::se3(&scene);
    let one = solve_json(&[CUBE, "--nodes", "3000"], "1");
    assert_eq!(one.len(), scene.queries.len());
    let mut methods = Vec::new();
    for (v, q) in one.iter().zip(&scene.queries) {
        assert_eq!(v["solved"], true, "{v}");
        methods.push(v["method"].as_str().unwrap().to_string());
        for key in ["path", "shortened"] {
            let p = path(&v[key]);
            assert_eq!(p.first(), Some(&q.start), "{key} starts at the start");
            assert_eq!(p.last(), Some(&q.goal), "{key} ends at the goal");
            checker
                .certify_path(&p)
                .unwrap_or_else(|e| panic!("{key}: {e}"));
        }
        assert!(v["length"].as_f64().unwrap() <= v["raw_length"].as_f64().unwrap() + 1e-9);
    }
    // the first query is open enough for the cheap try; the second needs a grown planner
    assert_eq!(methods[0], "direct", "{methods:?}");
    assert_ne!(methods[1], "direct", "{methods:?}");
    // without a time limit the race stops neither side: the same answer on two threads
    let two = solve_json(&[CUBE, "--nodes", "3000"], "2");
    for (a, b) in one.iter().zip(&two) {
        for key in ["method", "path", "shortened", "calls", "nodes"] {
            assert_eq!(a[key], b[key], "{key} differs between 1 and 2 threads");
        }
    }
}

#[test]
fn one_planner_alone_stays_one_flag_away() {
    let local = solve_json(&[CUBE, "--local-only"], "1");
    assert!(local
        .iter()
        .all(|v| v.get("depth").is_some() && v.get("method").is_none()));
    let trees = solve_json(&[CUBE, "--tree", "--nodes", "3000"], "1");
    assert!(trees.iter().all(|v| v.get("extends").is_some()));
    // a node budget means nothing to the local method alone
    let o = viaroad(&["solve", CUBE, "--local-only", "--nodes", "5"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn a_cfg_files_benchmark_time_limit_is_the_default_budget() {
    let d = temp_dir("solve_default", "cfg");
    let cfg =
        |benchmark: &str| format!("[problem]\nworld = env.dae\nrobot = robot.dae\n{benchmark}");
    let with = write(
        &d,
        "with.cfg",
        &cfg("[benchmark]\ntime_limit=20.0\nrun_count=10\n"),
    );
    assert_eq!(time_limit(Path::new(&with)).unwrap(), Some(20.0));
    let without = write(&d, "without.cfg", &cfg(""));
    assert_eq!(time_limit(Path::new(&without)).unwrap(), None);
    let untimed = write(&d, "untimed.cfg", &cfg("[benchmark]\nrun_count=10\n"));
    assert_eq!(time_limit(Path::new(&untimed)).unwrap(), None);
    let bad = write(&d, "bad.cfg", &cfg("[benchmark]\ntime_limit=-3\n"));
    let e = time_limit(Path::new(&bad)).unwrap_err().to_string();
    assert!(e.contains("time_limit"), "{e}");
    // the shipped problems carry theirs
    let twisty = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/ompl/3D/Twistycool.cfg");
    assert_eq!(time_limit(&twisty).unwrap(), Some(20.0));
    // and `solve` refuses a bad one before planning, in one line (the meshes by full path)
    let dir = twisty.parent().unwrap().display().to_string();
    let text = std::fs::read_to_string(&twisty)
        .unwrap()
        .replace("time_limit=20.0", "time_limit=0")
        .replace("= Twistycool_", &format!("= {dir}/Twistycool_"));
    let scene = write(&d, "scene.cfg", &text);
    fails_with(&["solve", &scene], "time_limit");
    // an explicit --time is the user's word over the file's
    let o = viaroad(&["solve", &scene, "--time", "20"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn export_plans_an_arm_scene_as_solve_does() {
    let d = temp_dir("solve_default", "export");
    let out = d.join("cage.glb");
    let o = viaroad(&[
        "export",
        "scenes/arms/panda-cage-1.toml",
        "--nodes",
        "3000",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("planned as `solve` plans"),
        "{}",
        stderr(&o)
    );
    assert!(std::fs::metadata(&out).unwrap().len() > 1000);
}
