//! `bench mbm`'s per-problem pipeline: the via-point planner and then the
//! trees, both at once (`--race`), or the trees first (`--trees-first`, the default).
//! Whichever answers, the path comes back re-checked by the independent
//! [`viaroad::robot::ArmChecker`] inside `run_problem`; this test holds it to that
//! and to the stage times adding up.

use crate::common;

use common::cli::{stderr, temp_dir, viaroad};
use std::path::Path;
use std::time::Duration;
use viaroad::bench::mbm::{
    check_step, checker, find_problems, load_robot, problem_scene, run_problem, MbmOptions, Planner,
};
use viaroad::roadmap::tree::{Prefix, Stairs, TreeParams};

#[test]
fn raced_or_in_turn_every_answer_is_certified() {
    let arms = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let robot = load_robot(&arms.join("panda")).unwrap();
    // box 1 needs the trees (a staircase into the box), table_pick 1 does not
    let mut problems = find_problems(&arms.join("mbm/box"), Some(1)).unwrap();
    problems.extend(find_problems(&arms.join("mbm/table_pick"), Some(1)).unwrap());
    assert_eq!(problems.len(), 2);
    // in turn with the via-point planner first, racing, and in turn with the trees first
    let modes = [
        (None, None),
        (Some(Duration::ZERO), None),
        (None, Some(0.2)),
    ];
    for (race, trees_first) in modes {
        let options = MbmOptions {
            // generous: the node budget, not the clock, ends the trees on a slow machine
            time: Duration::from_secs(30),
            direct_calls: 60,
            seed: 1,
            limit: None,
            planner: Planner::Tree,
            tree: TreeParams {
                prefix: Prefix::FirstHit,
                stairs: Stairs::Whole,
                balance: true,
                max_nodes: Some(4000),
                ..TreeParams::default()
            },
            race,
            trees_first,
            straight: true,
            repeat: 0,
        };
        for p in &problems {
            let r = run_problem(&robot, p, &options);
            let name = format!(
                "{} {} (race {race:?}, trees first {trees_first:?})",
                p.family, p.id
            );
            assert!(r.valid && r.oracle_valid, "{name}: {r:?}");
            assert!(r.solved, "{name}: not solved: {r:?}");
            assert_eq!(r.certified, Some(true), "{name}: {r:?}");
            assert!(r.stage == "direct" || r.stage == "tree", "{name}: {r:?}");
            assert!(r.length <= r.raw_length + 1e-9, "{name}: {r:?}");
            assert!(
                r.direct_s <= r.time_s && r.grow_s <= r.time_s,
                "{name}: {r:?}"
            );
            if r.stage == "tree" {
                assert!(r.nodes > 0, "{name}: {r:?}");
            }
            if race.is_none() {
                // in turn, the stages do not overlap
                assert!(
                    r.direct_s + r.grow_s + r.shorten_s <= r.time_s + 1e-6,
                    "{name}: {r:?}"
                );
            }
        }
    }
}

/// With the trees first, a problem the trees leave unsolved in their share goes to the
/// via-point search: table_pick 1's direct path is blocked, trees cut at one node cannot solve
/// it, and the via-point planner then does (36 calls when measured), after the trees ran.
/// Staircases only: the straight motion of all joints from start to goal is free there (one
/// call, no stage after it).
#[test]
fn trees_first_hand_over_to_the_via_point_search() {
    let arms = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let robot = load_robot(&arms.join("panda")).unwrap();
    let p = &find_problems(&arms.join("mbm/table_pick"), Some(1)).unwrap()[0];
    let options = MbmOptions {
        time: Duration::from_secs(30),
        direct_calls: 300,
        seed: 1,
        limit: None,
        planner: Planner::Tree,
        tree: TreeParams {
            max_nodes: Some(1),
            ..TreeParams::default()
        },
        race: None,
        trees_first: Some(0.2),
        straight: false,
        repeat: 0,
    };
    let with_straight = run_problem(
        &robot,
        p,
        &MbmOptions {
            straight: true,
            ..options.clone()
        },
    );
    assert_eq!(with_straight.calls, 1, "{with_straight:?}");
    assert_eq!(with_straight.corners, 2, "{with_straight:?}");
    assert_eq!(with_straight.certified, Some(true), "{with_straight:?}");
    let r = run_problem(&robot, p, &options);
    assert!(r.solved && r.stage == "direct", "{r:?}");
    assert_eq!(r.certified, Some(true), "{r:?}");
    // the trees ran first and grew their one node; the search's calls come on top of theirs
    assert!(r.grow_s > 0.0 && r.nodes >= 1, "{r:?}");
    assert!(
        r.direct_s + r.grow_s + r.shorten_s <= r.time_s + 1e-6,
        "{r:?}"
    );
}

/// `bench mbm --paths-out` (for the peer's `armcheck`): each solved problem's returned and
/// found paths, read back from the files, run from the request's start to its goal (a
/// configuration per line) and pass the independent checker; a file an earlier run left
/// under the same name is replaced, and the workcell mode refuses the option.
#[test]
fn paths_out_writes_the_returned_and_the_found_path() {
    let dir = temp_dir("arm_mbm", "paths-out");
    let paths = dir.join("paths");
    std::fs::create_dir_all(&paths).unwrap();
    let stale = paths.join("table_pick_0001_raw.path");
    std::fs::write(&stale, "an earlier run's file\n").unwrap();
    let (out, paths_arg) = (dir.join("out"), paths.display().to_string());
    let out = out.display().to_string();
    let args = [
        "bench",
        "mbm",
        "scenes/arms/mbm/table_pick",
        "--robot",
        "scenes/arms/panda",
        "--time",
        "20",
        "--limit",
        "1",
        "--out",
        &out,
        "--paths-out",
        &paths_arg,
    ];
    let o = viaroad(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let arms = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let robot = load_robot(&arms.join("panda")).unwrap();
    let problem = &find_problems(&arms.join("mbm/table_pick"), Some(1)).unwrap()[0];
    let scene = problem_scene(&robot, problem).unwrap();
    let check = checker(&scene).unwrap();
    let query = &scene.queries[0];
    for name in ["table_pick_0001.path", "table_pick_0001_raw.path"] {
        let text = std::fs::read_to_string(paths.join(name)).unwrap();
        let path: Vec<Vec<f64>> = text
            .lines()
            .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect();
        assert!(path.len() >= 2, "{name}: {text}");
        assert_eq!(
            (&path[0], &path[path.len() - 1]),
            (&query.start, &query.goal),
            "{name}"
        );
        // one joint per step, or a straight motion of several (the checker below samples every
        // segment along its straight line)
        let report = check.check_path(&path, check_step(&check)).unwrap();
        assert!(report.valid, "{name}: {report:?}");
    }
    // a usage error, as clap reports them (exit status 2)
    let mut workcell = args.to_vec();
    workcell.push("--workcell");
    let o = viaroad(&workcell);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--paths-out"), "{}", stderr(&o));
    // a share outside [0, 1] (or NaN) is refused in one line, before any problem runs
    for share in ["1.5", "NaN"] {
        let mut bad = args.to_vec();
        bad.extend(["--trees-first", share]);
        let o = viaroad(&bad);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("--trees-first"), "{}", stderr(&o));
        assert_eq!(stderr(&o).trim().lines().count(), 1, "{}", stderr(&o));
    }
}
