//! Budgets on the command line: `solve --roadmap` (single-query roadmap), `--time` on `build`,
//! `query` and `solve`, numbered streaming answers, and a scene whose own query is invalid
//! (a warning for `build`, an error for `solve`). Paths are re-checked by the independent
//! segment–disc test.

use crate::common;

use common::cli::{fails_with, stderr, stdout, viaroad};

use std::path::PathBuf;
use viaroad::scene::{Obstacle, Scene};

const CLUTTERED: &str = "scenes/discs-cluttered.toml";

fn discs(path: &str) -> (Vec<Vec<f64>>, Vec<f64>) {
    let scene = Scene::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap();
    scene
        .obstacles
        .iter()
        .map(|o| match o {
            Obstacle::Disc { centre, radius } => (centre.clone(), *radius),
            _ => panic!("a disc scene"),
        })
        .unzip()
}

fn path_of(v: &serde_json::Value) -> Vec<Vec<f64>> {
    serde_json::from_value(v.clone()).unwrap()
}

#[test]
fn solve_roadmap_grows_from_start_and_goal_to_a_checked_path() {
    let o = viaroad(&["solve", CLUTTERED, "--roadmap", "--time", "60", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (centres, radii) = discs(CLUTTERED);
    let lines: Vec<serde_json::Value> = stdout(&o)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert!(!lines.is_empty());
    for v in &lines {
        assert_eq!(v["solved"], true, "{v}");
        assert_eq!(v["stop"], "Connected");
        assert!(v["nodes"].as_u64().unwrap() >= 2);
        for key in ["path", "shortened"] {
            let p = path_of(&v[key]);
            common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9).unwrap();
        }
    }
}

#[test]
fn solve_roadmap_with_a_node_budget_is_reproducible_and_shares_are_checked() {
    let run = |share: &str| {
        let o = viaroad(&[
            "solve",
            CLUTTERED,
            "--roadmap",
            "--nodes",
            "400",
            "--seed",
            "3",
            "--directed-share",
            share,
            "--json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        // the timing field is the only one that may differ between two runs
        let mut v: serde_json::Value =
            serde_json::from_str(stdout(&o).lines().next().unwrap()).unwrap();
        v.as_object_mut().unwrap().remove("seconds");
        v
    };
    let (centres, radii) = discs(CLUTTERED);
    for share in ["0", "0.5", "1"] {
        let a = run(share);
        assert_eq!(a, run(share), "share {share}: two runs differ");
        assert!(a["nodes"].as_u64().unwrap() <= 400 + 64, "{a}");
        if a["solved"] == true {
            for key in ["path", "shortened"] {
                let p = path_of(&a[key]);
                common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9)
                    .unwrap();
            }
        }
    }
    for bad in ["-0.1", "1.5", "nan"] {
        let bad = format!("--directed-share={bad}");
        fails_with(&["solve", CLUTTERED, "--roadmap", &bad], "directed_share");
    }
    // a node budget belongs to grown trees and roadmaps, not to the local method alone (a
    // usage error: clap's exit status 2)
    let o = viaroad(&["solve", CLUTTERED, "--local-only", "--nodes", "100"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--local-only"), "{}", stderr(&o));
}

#[test]
fn time_budgets_are_checked_and_answers_are_numbered() {
    let d = temp_dir("time");
    let rm = d.join("rm.bin").to_string_lossy().into_owned();
    // a build stopped by its time budget still saves a roadmap
    let o = viaroad(&["build", CLUTTERED, "-o", &rm, "--time", "0.2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("stopped: TimeBudget"), "{}", stdout(&o));
    assert!(viaroad(&["info", &rm]).status.success());
    for bad in ["0", "-1", "nan", "inf", "1e300"] {
        let bad = &format!("--time={bad}");
        fails_with(&["build", CLUTTERED, "-o", &rm, bad], "--time");
        fails_with(
            &[
                "query",
                &rm,
                "--scene",
                CLUTTERED,
                "--from",
                "0.02,0.98",
                "--to",
                "0.98,0.02",
                bad,
            ],
            "--time",
        );
        fails_with(&["solve", CLUTTERED, bad], "--time");
    }
    let queries = d.join("q.txt");
    std::fs::write(
        &queries,
        "0.02 0.98 0.98 0.02\n0.5 0.97 0.5 0.03\n0.03 0.5 0.97 0.5\n",
    )
    .unwrap();
    let o = viaroad(&[
        "query",
        &rm,
        "--scene",
        CLUTTERED,
        "--queries",
        &queries.to_string_lossy(),
        "--json",
        "--time",
        "30",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (centres, radii) = discs(CLUTTERED);
    let mut numbers: Vec<u64> = Vec::new();
    for line in stdout(&o).lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        numbers.push(v["query"].as_u64().unwrap());
        assert_eq!(v["solved"], true, "{v}");
        let p = path_of(&v["shortened"]);
        common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9).unwrap();
    }
    numbers.sort_unstable();
    assert_eq!(numbers, vec![1, 2, 3]);
}

#[test]
fn an_invalid_scene_query_warns_build_and_stops_solve() {
    let d = temp_dir("invalid-query");
    let scene = d.join("blocked.toml");
    std::fs::write(
        &scene,
        "[space]\nkind = \"r2\"\nlower = [0, 0]\nupper = [1, 1]\n\
         [[obstacle]]\ndisc = { center = [0.5, 0.5], radius = 0.2 }\n\
         [[query]]\nstart = [0.1, 0.1]\ngoal = [0.5, 0.5]\n",
    )
    .unwrap();
    let scene = scene.to_string_lossy().into_owned();
    let rm = d.join("rm.bin").to_string_lossy().into_owned();
    let o = viaroad(&["build", &scene, "-o", &rm, "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let warned: Vec<String> = stderr(&o)
        .lines()
        .filter(|l| l.starts_with("warning:") && l.contains("goal of query 1"))
        .map(str::to_string)
        .collect();
    assert_eq!(warned.len(), 1, "{}", stderr(&o));
    assert!(warned[0].contains("in collision"));
    fails_with(&["solve", &scene], "goal of query 1");
    fails_with(&["solve", &scene, "--roadmap"], "goal of query 1");
}

fn temp_dir(name: &str) -> common::cli::TempDir {
    common::cli::temp_dir("budgets", name)
}
