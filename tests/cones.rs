//! Brooks's freeways (generalized cones, `src/global/cones`): the cones against the scene's
//! geometry (an independent point-in-polygon test), the legal orientations against the robot
//! placed in the cone, and every path — of the search and of the seed roadmap — re-checked by
//! the independent checker (`bench::validity::Checker`).

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::Path;
use viaroad::bench::validity::Checker;
use viaroad::global::cones::seeds::seed_roadmap;
use viaroad::global::cones::{ConeOutcome, Freeways, RadiusFunction};
use viaroad::local::LocalSpec;
use viaroad::roadmap::LearnParams;
use viaroad::scene::{Obstacle, Robot, Scene};

fn load(path: &str) -> Scene {
    Scene::load(Path::new(path)).unwrap()
}

/// Crossing-number point-in-polygon, written here (closed: a point on an edge is inside).
fn in_polygon(p: [f64; 2], v: &[[f64; 2]]) -> bool {
    let n = v.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        let on = cross.abs() < 1e-12
            && p[0] >= a[0].min(b[0]) - 1e-12
            && p[0] <= a[0].max(b[0]) + 1e-12
            && p[1] >= a[1].min(b[1]) - 1e-12
            && p[1] <= a[1].max(b[1]) + 1e-12;
        if on {
            return true;
        }
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Whether a point lies in an obstacle of the scene (discs exactly).
fn in_obstacle(scene: &Scene, p: [f64; 2]) -> bool {
    scene.obstacles.iter().any(|o| match o {
        Obstacle::Disc { centre, radius } => (p[0] - centre[0]).hypot(p[1] - centre[1]) <= *radius,
        Obstacle::Polygon(poly) => {
            let v: Vec<[f64; 2]> = poly.vertices.iter().map(|v| [v.x, v.y]).collect();
            in_polygon(p, &v)
        }
        Obstacle::Mesh(_) => unreachable!("planar scenes only"),
    })
}

/// Checks a freeway path: ends at the query's, pure translations or rotations of at most a
/// quarter turn, and free by the independent checker.
fn check(scene: &Scene, path: &[Vec<f64>], start: &[f64], goal: &[f64]) {
    assert_eq!(path.first().map(Vec::as_slice), Some(start));
    assert_eq!(path.last().map(Vec::as_slice), Some(goal));
    for w in path.windows(2) {
        let moved = w[0][0] != w[1][0] || w[0][1] != w[1][1];
        if w[0].len() == 3 {
            let turn = scene
                .space
                .distance(&[0.0, 0.0, w[0][2]], &[0.0, 0.0, w[1][2]]);
            assert!(!(moved && turn > 0.0), "a move that turns: {w:?}");
            assert!(turn <= FRAC_PI_2 * scene.space.rotation_scale() + 1e-9);
        }
    }
    Checker::for_scene(scene)
        .unwrap()
        .check_path(path)
        .unwrap_or_else(|e| panic!("{}: {e}", scene.name));
}

#[test]
fn shipped_queries_solved_along_the_freeways_pass_the_checker() {
    // the queries the method solves today: a regression in the cones or the search shows here
    for (file, expect) in [
        ("scenes/se2-corridor.toml", 2),
        ("scenes/discs-example.toml", 1),
        ("scenes/discs-cluttered.toml", 5),
    ] {
        let scene = load(file);
        let fw = Freeways::build(&scene).unwrap();
        let oracle = scene.oracle();
        let mut solved = 0;
        for q in scene.checked_queries().unwrap() {
            if let ConeOutcome::Solved(p) = fw
                .solve(&scene, oracle.as_ref(), &q.start, &q.goal)
                .unwrap()
            {
                check(&scene, &p.path, &q.start, &q.goal);
                let direct = scene.space.distance(&q.start, &q.goal);
                assert!(p.length >= direct - 1e-9, "{file}: shorter than straight");
                solved += 1;
            }
        }
        assert_eq!(solved, expect, "{file}");
    }
}

#[test]
fn ompl_queries_are_solved_correctly_or_reported_unsolved() {
    for file in [
        "scenes/ompl/2D/BugTrap_planar.cfg",
        "scenes/ompl/2D/Maze_planar.cfg",
        "scenes/ompl/2D/RandomPolygons_planar.cfg",
        "scenes/ompl/2D/Barriers.cfg",
        "scenes/ompl/2D/UniqueSolutionMaze.cfg",
        "scenes/se2-translate.toml",
    ] {
        let scene = load(file);
        let fw = Freeways::build(&scene).unwrap();
        assert!(!fw.cones().is_empty(), "{file}");
        let oracle = scene.oracle();
        for q in scene.checked_queries().unwrap() {
            match fw
                .solve(&scene, oracle.as_ref(), &q.start, &q.goal)
                .unwrap()
            {
                ConeOutcome::Solved(p) => check(&scene, &p.path, &q.start, &q.goal),
                ConeOutcome::NotFound(why) => assert!(!why.is_empty()),
            }
        }
    }
}

#[test]
fn cones_lie_in_free_space() {
    let mut rng = ChaCha8Rng::seed_from_u64(1982);
    for file in [
        "scenes/se2-corridor.toml",
        "scenes/discs-cluttered.toml",
        "scenes/ompl/2D/Maze_planar.cfg",
        "scenes/ompl/2D/RandomPolygons_planar.cfg",
    ] {
        let scene = load(file);
        let fw = Freeways::build(&scene).unwrap();
        for c in fw.cones() {
            // a cone may taper to its apex at one end
            assert!(c.lo < c.hi && c.radius(c.lo).min(c.radius(c.hi)) > -1e-9);
            assert!(c.radius(c.lo).max(c.radius(c.hi)) > 0.0);
            let perp = [-c.dir[1], c.dir[0]];
            for _ in 0..20 {
                let s = rng.random_range(c.lo..=c.hi);
                let u = c.radius(s).max(0.0) * rng.random_range(-0.999..0.999);
                let p = c.point(s);
                let x = [p[0] + u * perp[0], p[1] + u * perp[1]];
                assert!(!in_obstacle(&scene, x), "{file}: cone {c:?} holds {x:?}");
            }
        }
    }
}

#[test]
fn legal_orientations_keep_the_robot_in_the_cone() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let scene = load("scenes/se2-corridor.toml");
    let Robot::Polygons(parts) = &scene.robot else {
        unreachable!()
    };
    let vertices: Vec<[f64; 2]> = parts
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| [v.x, v.y]))
        .collect();
    let fw = Freeways::build(&scene).unwrap();
    let mut checked = 0;
    for c in fw.cones() {
        for _ in 0..50 {
            let a = rng.random_range(c.lo..=c.hi);
            let b = rng.random_range(c.lo..=c.hi);
            for arc in fw.legal(c, a, b).arcs() {
                let phi = arc.lo + arc.len * rng.random_range(0.0..=1.0);
                let (sn, cs) = phi.sin_cos();
                for k in 0..=10 {
                    let s = a + (b - a) * k as f64 / 10.0;
                    for v in &vertices {
                        // the vertex in the cone's frame: along the spine and across it
                        let w = [cs * v[0] - sn * v[1], sn * v[0] + cs * v[1]];
                        let along = s + w[0] * c.dir[0] + w[1] * c.dir[1];
                        let across = -w[0] * c.dir[1] + w[1] * c.dir[0];
                        assert!(along >= c.lo - 1e-9 && along <= c.hi + 1e-9);
                        assert!(across.abs() <= c.radius(along) + 1e-9);
                    }
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "only {checked} legal stretches");
}

#[test]
fn seed_roadmap_edges_pass_the_checker() {
    for file in ["scenes/se2-corridor.toml", "scenes/discs-example.toml"] {
        let scene = load(file);
        let fw = Freeways::build(&scene).unwrap();
        let oracle = scene.oracle();
        let spec = LocalSpec::roadmap_default();
        let r = seed_roadmap(
            &fw,
            &scene,
            oracle.as_ref(),
            &LearnParams::default(),
            &spec,
            1,
            1000,
        )
        .unwrap();
        assert!(r.node_count() > 10 && r.edge_count() > 10, "{file}");
        let checker = Checker::for_scene(&scene).unwrap();
        for (e, edge) in r.edges().iter().enumerate() {
            // both ways: a turn read from its other end takes the same arc
            checker.check_path(&r.edge_path(e, edge.a)).unwrap();
            checker.check_path(&r.edge_path(e, edge.b)).unwrap();
        }
    }
}

#[test]
fn the_same_scene_gives_the_same_freeways_and_paths() {
    let scene = load("scenes/se2-corridor.toml");
    let (a, b) = (
        Freeways::build(&scene).unwrap(),
        Freeways::build(&scene).unwrap(),
    );
    assert_eq!(a.cones(), b.cones());
    let oracle = scene.oracle();
    let q = &scene.queries[0];
    assert_eq!(
        a.solve(&scene, oracle.as_ref(), &q.start, &q.goal).unwrap(),
        b.solve(&scene, oracle.as_ref(), &q.start, &q.goal).unwrap()
    );
}

proptest! {
    /// `R⁻¹(r)` is exactly where `R ≤ r` (Brooks §3.1), on random convex robots.
    #[test]
    fn radius_inverse_is_the_sublevel_set(seed in any::<u64>(), r in -0.5..3.0f64) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let pts: Vec<[f64; 2]> = (0..rng.random_range(1..8))
            .map(|_| [rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0)])
            .collect();
        let f = RadiusFunction::new(&pts);
        let set = f.inverse(r);
        for k in 0..360 {
            let xi = k as f64 * TAU / 360.0 - PI;
            let v = f.at(xi);
            if (v - r).abs() > 1e-9 {
                prop_assert_eq!(set.contains(xi), v <= r, "ξ {} R {} r {}", xi, v, r);
            }
        }
    }
}
