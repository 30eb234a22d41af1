//! The via-point planner on rigid bodies: SE(3) with the exact polyhedral oracle — the seed's
//! showcase problems (CHS A.2: a cube into a box, the piano movers' problem) and OMPL.app's
//! problems — and SE(2) with the exact polygon oracle. Every path is certified collision-free by
//! an independent parry-based check.

use crate::common;

use common::rigid::RigidChecker;
use common::rigid2d::PlanarChecker;
use viaroad::local::viapoint::{Search, ViaPoint, ViaPointOptions};
use viaroad::local::{shorten, LocalMethod, StraightLine};
use viaroad::oracle::CallCounts;
use viaroad::scene::Scene;
use viaroad::space::Space;

fn scene(path: &str) -> Scene {
    Scene::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

/// Corners must change the position or the orientation, never both (CHS §1.5).
fn one_group_at_a_time(space: &Space, path: &[Vec<f64>]) {
    let groups = space.groups(false);
    for w in path.windows(2) {
        let changed = groups
            .iter()
            .filter(|g| !space.same_in_group(&w[0], &w[1], g))
            .count();
        assert!(
            changed <= 1,
            "{:?} → {:?} changes {changed} groups",
            w[0],
            w[1]
        );
    }
}

fn solve_and_certify(path: &str, options: ViaPointOptions, expect_solved: usize) {
    let s = scene(path);
    let oracle = s.oracle();
    let checker = RigidChecker::se3(&s);
    let method = ViaPoint::new(options);
    let groups = method.groups(&s.space);
    let mut solved = 0;
    for (i, q) in s.queries.iter().enumerate() {
        let c = method
            .connect(&s.space, oracle.as_ref(), &q.start, &q.goal)
            .unwrap();
        if !c.is_connected() {
            continue;
        }
        solved += 1;
        one_group_at_a_time(&s.space, &c.path);
        checker
            .certify_path(&c.path)
            .unwrap_or_else(|e| panic!("{path} query {}: {e}", i + 1));
        let short = shorten(
            &s.space,
            oracle.as_ref(),
            &groups,
            &c.path,
            &mut CallCounts::default(),
        )
        .unwrap();
        one_group_at_a_time(&s.space, &short);
        checker
            .certify_path(&short)
            .unwrap_or_else(|e| panic!("{path} query {}, shortened: {e}", i + 1));
        // every certified free segment the planner reported really is free
        for &(a, b) in &c.discoveries.free_segments {
            let (qa, qb) = (
                &c.discoveries.configs[a as usize],
                &c.discoveries.configs[b as usize],
            );
            checker
                .certify_motion(qa, qb)
                .unwrap_or_else(|e| panic!("{path} query {}, discovery: {e}", i + 1));
        }
    }
    assert!(
        solved >= expect_solved,
        "{path}: solved {solved}, expected at least {expect_solved}"
    );
}

#[test]
fn cube_into_box() {
    // CHS A.2.1: "a cube fitting into a square-like box with little clearance"
    solve_and_certify("scenes/cube-into-box.toml", ViaPointOptions::default(), 2);
}

#[test]
fn piano_movers() {
    // CHS A.2.2: the piano must turn 90° around a chair
    solve_and_certify("scenes/piano.toml", ViaPointOptions::default(), 2);
}

#[test]
fn ompl_easy() {
    solve_and_certify("scenes/ompl/3D/Easy.cfg", ViaPointOptions::default(), 1);
}

#[test]
fn breadth_first_on_the_piano() {
    let o = ViaPointOptions {
        search: Search::BreadthFirst,
        ..ViaPointOptions::default()
    };
    solve_and_certify("scenes/piano.toml", o, 1);
}

#[test]
fn the_straight_line_is_blocked_where_the_checker_says_so() {
    for path in [
        "scenes/cube-into-box.toml",
        "scenes/piano.toml",
        "scenes/ompl/3D/Easy.cfg",
    ] {
        let s = scene(path);
        let oracle = s.oracle();
        let checker = RigidChecker::se3(&s);
        let mut blocked = 0;
        for q in &s.queries {
            let c = StraightLine::exact()
                .connect(&s.space, oracle.as_ref(), &q.start, &q.goal)
                .unwrap();
            if c.is_connected() {
                checker
                    .certify_path(&c.path)
                    .unwrap_or_else(|e| panic!("{path}: {e}"));
            } else if s.space.direct_motion(&q.start, &q.goal).is_some() {
                // a single straight motion the exact oracle calls blocked: the independent check
                // must refuse to certify it (this is what makes the check able to fail)
                assert!(
                    checker
                        .certify_path(&[q.start.clone(), q.goal.clone()])
                        .is_err(),
                    "{path}"
                );
                blocked += 1;
            }
        }
        if path.contains("cube") || path.contains("Easy") {
            assert!(blocked > 0, "{path}: expected a blocked straight query");
        }
    }
}

fn solve_and_certify_planar(path: &str, expect_solved: usize) {
    let s = scene(path);
    let oracle = s.oracle();
    let checker = PlanarChecker::se2(&s);
    let method = ViaPoint::default();
    let groups = method.groups(&s.space);
    let mut solved = 0;
    for (i, q) in s.queries.iter().enumerate() {
        let c = method
            .connect(&s.space, oracle.as_ref(), &q.start, &q.goal)
            .unwrap();
        if !c.is_connected() {
            continue;
        }
        solved += 1;
        one_group_at_a_time(&s.space, &c.path);
        checker
            .certify_path(&c.path)
            .unwrap_or_else(|e| panic!("{path} query {}: {e}", i + 1));
        let short = shorten(
            &s.space,
            oracle.as_ref(),
            &groups,
            &c.path,
            &mut CallCounts::default(),
        )
        .unwrap();
        checker
            .certify_path(&short)
            .unwrap_or_else(|e| panic!("{path} query {}, shortened: {e}", i + 1));
    }
    assert!(
        solved >= expect_solved,
        "{path}: solved {solved}, expected at least {expect_solved}"
    );
}

#[test]
fn planar_corridor() {
    solve_and_certify_planar("scenes/se2-corridor.toml", 2);
}

#[test]
fn ompl_planar_problems() {
    for p in ["BugTrap_planar", "Maze_planar", "RandomPolygons_planar"] {
        solve_and_certify_planar(&format!("scenes/ompl/2D/{p}.cfg"), 1);
    }
}

#[test]
fn the_planar_checker_agrees_with_the_exact_oracle() {
    // translations from each start to its goal's position (at the start's angle): the exact
    // oracle and the independent checker must agree, and some must be blocked, so that the
    // checker is seen to fail where it should
    let mut blocked = 0;
    for path in [
        "scenes/se2-corridor.toml",
        "scenes/ompl/2D/BugTrap_planar.cfg",
        "scenes/ompl/2D/Maze_planar.cfg",
        "scenes/ompl/2D/RandomPolygons_planar.cfg",
    ] {
        let s = scene(path);
        let oracle = s.oracle();
        let checker = PlanarChecker::se2(&s);
        for q in &s.queries {
            let end = vec![q.goal[0], q.goal[1], q.start[2]];
            let free = StraightLine::exact()
                .connect(&s.space, oracle.as_ref(), &q.start, &end)
                .unwrap()
                .is_connected();
            let certified = checker.certify_path(&[q.start.clone(), end.clone()]);
            assert_eq!(free, certified.is_ok(), "{path}: {certified:?}");
            blocked += !free as usize;
        }
    }
    assert!(blocked >= 2, "only {blocked} blocked translations");
}
