//! Scene loading: the TOML format for every space kind, meshes (OBJ, STL, Collada), OMPL.app
//! problems and path/query files, and the shipped example scenes.
//!
//! Validity of the shipped scenes is checked against independent geometry: parry's distance
//! queries on convex pieces (boxes, convex polygons), and for the disc scene a point–disc and
//! segment–disc distance written here. The collision-dependent checks of se2/se3 loading go
//! through the scene's own oracle (the exact polygon and polyhedron oracles).

use nalgebra::{
    Isometry2, Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector2, Vector3,
};
use parry2d_f64::shape::ConvexPolygon;
use parry3d_f64::shape::ConvexPolyhedron;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use std::collections::{BTreeSet, VecDeque};
use std::path::{Path, PathBuf};
use viaroad::geometry::TriMesh;
use viaroad::scene::collada::load_collada;
use viaroad::scene::mesh_io::{load_mesh, load_obj, load_stl};
use viaroad::scene::ompl_cfg::{read_query_pairs, read_states};
use viaroad::scene::toml_format::from_str;
use viaroad::scene::{Obstacle, Robot, Scene, SceneError};
use viaroad::space::{Space, SpaceError, SpaceKind};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn data(name: &str) -> PathBuf {
    root().join("tests/data/scenes").join(name)
}

fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    v.sort();
    v
}

/// Signed volume of a mesh (divergence theorem): positive for a closed outward mesh.
fn volume(m: &TriMesh) -> f64 {
    (0..m.triangles.len())
        .map(|i| {
            let [a, b, c] = m.triangle(i);
            a.coords.dot(&b.coords.cross(&c.coords)) / 6.0
        })
        .sum()
}

/// Triangles as sorted corner triples rounded to 1e-6: comparable across formats.
fn triangle_set(m: &TriMesh) -> BTreeSet<[[i64; 3]; 3]> {
    (0..m.triangles.len())
        .map(|i| {
            let mut t = m
                .triangle(i)
                .map(|p| [p.x, p.y, p.z].map(|c| (c * 1e6).round() as i64));
            t.sort();
            t
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// shipped TOML scenes

#[test]
fn every_shipped_toml_scene_loads() {
    let scenes = files(&root().join("scenes"), "toml");
    let names: Vec<String> = scenes
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    for expected in [
        "cube-into-box",
        "discs-cluttered",
        "discs-example",
        "piano",
        "se2-corridor",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "missing scenes/{expected}.toml"
        );
    }
    for path in &scenes {
        let scene = Scene::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(!scene.queries.is_empty(), "{}: no queries", path.display());
        assert!(
            scene.warnings.is_empty(),
            "{}: {:?}",
            path.display(),
            scene.warnings
        );
        assert_eq!(scene.name, path.file_stem().unwrap().to_string_lossy());
    }
}

#[test]
fn discs_example_is_the_issue_example() {
    let s = Scene::load(&root().join("scenes/discs-example.toml")).unwrap();
    assert_eq!(s.space.kind(), SpaceKind::Euclidean(2));
    assert_eq!(
        s.obstacles,
        vec![Obstacle::Disc {
            centre: vec![0.30, 0.40],
            radius: 0.05
        }]
    );
    assert_eq!(s.queries[0].start, vec![0.02, 0.98]);
    assert_eq!(s.queries[0].goal, vec![0.98, 0.02]);
}

// --- discs-cluttered: generated once from a seed, committed as TOML --------------------------

const CLUTTER_SEED: u64 = 1995;
const CLUTTER_DISCS: usize = 80;
const CLUTTER_QUERIES: [([f64; 2], [f64; 2]); 5] = [
    ([0.03, 0.97], [0.97, 0.03]),
    ([0.05, 0.05], [0.95, 0.95]),
    ([0.50, 0.02], [0.50, 0.98]),
    ([0.02, 0.50], [0.98, 0.50]),
    ([0.25, 0.75], [0.75, 0.25]),
];

/// Cells of a `n × n` grid over the unit square that are certainly free: the cell's centre is
/// farther than `r + half diagonal` from every disc, so no point of the cell is in a disc.
fn free_cells(discs: &[([f64; 2], f64)], n: usize) -> Vec<bool> {
    let h = 1.0 / n as f64;
    let half_diag = h * std::f64::consts::FRAC_1_SQRT_2;
    let mut free = vec![true; n * n];
    for (c, r) in discs {
        let reach = r + half_diag;
        let (i0, i1) = (
            (((c[0] - reach) / h).floor().max(0.0)) as usize,
            (((c[0] + reach) / h).ceil().min(n as f64)) as usize,
        );
        let (j0, j1) = (
            (((c[1] - reach) / h).floor().max(0.0)) as usize,
            (((c[1] + reach) / h).ceil().min(n as f64)) as usize,
        );
        for i in i0..i1 {
            for j in j0..j1 {
                let (x, y) = ((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
                if ((x - c[0]).powi(2) + (y - c[1]).powi(2)).sqrt() <= reach {
                    free[i * n + j] = false;
                }
            }
        }
    }
    free
}

/// Connected components (4-neighbourhood) of the free cells; `usize::MAX` for blocked ones.
fn components(free: &[bool], n: usize) -> Vec<usize> {
    let mut label = vec![usize::MAX; n * n];
    let mut next = 0;
    for s in 0..n * n {
        if !free[s] || label[s] != usize::MAX {
            continue;
        }
        let mut queue = VecDeque::from([s]);
        label[s] = next;
        while let Some(c) = queue.pop_front() {
            let (i, j) = (c / n, c % n);
            let mut push = |k: usize| {
                if free[k] && label[k] == usize::MAX {
                    label[k] = next;
                    queue.push_back(k);
                }
            };
            if i > 0 {
                push(c - n);
            }
            if i + 1 < n {
                push(c + n);
            }
            if j > 0 {
                push(c - 1);
            }
            if j + 1 < n {
                push(c + 1);
            }
        }
        next += 1;
    }
    label
}

fn cell(p: [f64; 2], n: usize) -> usize {
    let i = ((p[0] * n as f64) as usize).min(n - 1);
    let j = ((p[1] * n as f64) as usize).min(n - 1);
    i * n + j
}

/// Whether every query is joined by a chain of certainly free cells (a proof of solvability).
fn all_queries_connected(discs: &[([f64; 2], f64)], queries: &[([f64; 2], [f64; 2])]) -> bool {
    let n = 250;
    let label = components(&free_cells(discs, n), n);
    queries.iter().all(|(a, b)| {
        let (la, lb) = (label[cell(*a, n)], label[cell(*b, n)]);
        la != usize::MAX && la == lb
    })
}

/// The generator of `scenes/discs-cluttered.toml`: random discs (centres uniform in the unit
/// square, radii uniform in [0.03, 0.06], 4 decimals), each kept only if it stays 0.02 away
/// from every query point and every query stays joined by certainly free cells.
fn generate_discs_cluttered() -> String {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(CLUTTER_SEED);
    let round = |x: f64| (x * 1e4).round() / 1e4;
    let mut discs: Vec<([f64; 2], f64)> = Vec::new();
    while discs.len() < CLUTTER_DISCS {
        let c = [
            round(rng.random_range(0.0..1.0)),
            round(rng.random_range(0.0..1.0)),
        ];
        let r = round(rng.random_range(0.03..0.06));
        let near = CLUTTER_QUERIES
            .iter()
            .flat_map(|(a, b)| [a, b])
            .any(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt() < r + 0.02);
        if near {
            continue;
        }
        discs.push((c, r));
        if !all_queries_connected(&discs, &CLUTTER_QUERIES) {
            discs.pop();
        }
    }
    let mut s = String::from(
        "# A cluttered disc scene for the demo: 80 discs (radii 0.03 to 0.06) in the unit square.\n\
         # Generated by `generate_discs_cluttered` in tests/scene_loading.rs (seed 1995); every\n\
         # query is solvable (a chain of certainly free grid cells joins start and goal).\n\
         # Regenerate with: VIAROAD_WRITE_SCENES=1 cargo test --test scene_loading discs_cluttered\n\
         name = \"discs-cluttered\"\n\n[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n",
    );
    for (c, r) in &discs {
        s += &format!(
            "\n[[obstacle]]\ndisc = {{ center = [{:.4}, {:.4}], radius = {:.4} }}\n",
            c[0], c[1], r
        );
    }
    for (a, b) in CLUTTER_QUERIES {
        s += &format!(
            "\n[[query]]\nstart = [{:.2}, {:.2}]\ngoal  = [{:.2}, {:.2}]\n",
            a[0], a[1], b[0], b[1]
        );
    }
    s
}

/// Distance from point `p` to the segment `a`–`b` (independent of the oracle's circle–line
/// algebra).
fn segment_point_distance(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    };
    ((a[0] + t * dx - p[0]).powi(2) + (a[1] + t * dy - p[1]).powi(2)).sqrt()
}

#[test]
fn discs_cluttered_matches_its_generator_and_is_solvable() {
    let path = root().join("scenes/discs-cluttered.toml");
    let generated = generate_discs_cluttered();
    if std::env::var_os("VIAROAD_WRITE_SCENES").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        committed, generated,
        "scenes/discs-cluttered.toml differs from its generator; regenerate with \
         VIAROAD_WRITE_SCENES=1 cargo test --test scene_loading discs_cluttered"
    );
    let scene = Scene::load(&path).unwrap();
    let discs: Vec<([f64; 2], f64)> = scene
        .obstacles
        .iter()
        .map(|o| match o {
            Obstacle::Disc { centre, radius } => ([centre[0], centre[1]], *radius),
            other => panic!("not a disc: {other:?}"),
        })
        .collect();
    assert_eq!(discs.len(), CLUTTER_DISCS);
    assert!(discs.iter().all(|(c, r)| {
        (0.03..=0.06).contains(r) && (0.0..=1.0).contains(&c[0]) && (0.0..=1.0).contains(&c[1])
    }));
    let queries: Vec<([f64; 2], [f64; 2])> = scene
        .queries
        .iter()
        .map(|q| ([q.start[0], q.start[1]], [q.goal[0], q.goal[1]]))
        .collect();
    assert!((4..=6).contains(&queries.len()));
    for (a, b) in &queries {
        for p in [a, b] {
            assert!(discs
                .iter()
                .all(|(c, r)| { ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt() > *r }));
        }
    }
    assert!(
        all_queries_connected(&discs, &queries),
        "a query is not solvable"
    );
    let blocked = queries
        .iter()
        .filter(|(a, b)| {
            discs
                .iter()
                .any(|(c, r)| segment_point_distance(*a, *b, *c) <= *r)
        })
        .count();
    assert!(blocked >= 3, "only {blocked} queries need a detour");
}

// --- se3 example scenes: independent checks with parry on convex pieces -----------------------

/// A convex obstacle or robot part from a mesh's vertices (exact for boxes and hulls).
fn convex3(m: &TriMesh) -> ConvexPolyhedron {
    ConvexPolyhedron::from_convex_hull(&m.vertices).expect("a convex piece")
}

fn pose3(q: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(q[0], q[1], q[2]),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[6], q[3], q[4], q[5])),
    )
}

/// Smallest distance between the placed robot parts and the obstacles.
fn clearance3(parts: &[ConvexPolyhedron], obstacles: &[ConvexPolyhedron], q: &[f64]) -> f64 {
    let at = pose3(q);
    let id = Isometry3::identity();
    parts
        .iter()
        .flat_map(|p| {
            obstacles
                .iter()
                .map(move |o| parry3d_f64::query::distance(&at, p, &id, o).unwrap())
        })
        .fold(f64::INFINITY, f64::min)
}

/// Checks a path given by way points (position + yaw about z) rigorously: between samples no
/// point of the robot moves farther than the clearance found at the samples.
fn path_is_free3(
    parts: &[ConvexPolyhedron],
    radius: f64,
    obstacles: &[ConvexPolyhedron],
    waypoints: &[[f64; 4]],
) -> Result<(), String> {
    let q = |w: [f64; 4]| {
        let r = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), w[3]);
        vec![w[0], w[1], w[2], r.i, r.j, r.k, r.w]
    };
    for pair in waypoints.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let travel = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
            + radius * (b[3] - a[3]).abs();
        let steps = (travel / 0.002).ceil().max(1.0) as usize;
        let moved = travel / steps as f64;
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            let w = [0, 1, 2, 3].map(|i| a[i] + t * (b[i] - a[i]));
            let c = clearance3(parts, obstacles, &q(w));
            if c <= moved {
                return Err(format!("clearance {c} at {w:?}"));
            }
        }
    }
    Ok(())
}

fn obstacles3(scene: &Scene) -> Vec<ConvexPolyhedron> {
    scene
        .obstacles
        .iter()
        .map(|o| match o {
            Obstacle::Mesh(m) => convex3(m),
            other => panic!("not a mesh: {other:?}"),
        })
        .collect()
}

#[test]
fn cube_into_box_is_valid_and_solvable() {
    let scene = Scene::load(&root().join("scenes/cube-into-box.toml")).unwrap();
    assert_eq!(scene.space.kind(), SpaceKind::Se3);
    let Robot::Mesh(cube) = &scene.robot else {
        panic!("the robot is a mesh")
    };
    assert!(cube.is_closed());
    assert!((volume(cube) - 1.0).abs() < 1e-12);
    // the default rotation scale is the radius of the cube about its centre
    assert!((scene.space.rotation_scale() - 0.75f64.sqrt()).abs() < 1e-12);
    let obstacles = obstacles3(&scene);
    assert_eq!(obstacles.len(), 5);
    let parts = [convex3(cube)];
    for q in &scene.queries {
        for c in [&q.start, &q.goal] {
            assert!(clearance3(&parts, &obstacles, c) > 0.0, "{c:?} is not free");
        }
    }
    // the goal is inside the box with little clearance (0.05 to the floor and the walls)
    let goal = &scene.queries[0].goal;
    assert!((clearance3(&parts, &obstacles, goal) - 0.05).abs() < 1e-9);
    // the straight translation from the first start into the box hits the wall's top
    let (s, g) = (&scene.queries[0].start, &scene.queries[0].goal);
    let hits = (0..=1000).any(|k| {
        let t = k as f64 / 1000.0;
        let q: Vec<f64> = s.iter().zip(g).map(|(a, b)| a + t * (b - a)).collect();
        clearance3(&parts, &obstacles, &q) == 0.0
    });
    assert!(hits, "the straight motion should collide");
    // over the box, then down into it
    let r = cube.radius();
    let path = [
        [2.0, 2.0, 2.5, 0.0],
        [0.0, 0.0, 2.5, 0.0],
        [0.0, 0.0, 0.55, 0.0],
    ];
    path_is_free3(&parts, r, &obstacles, &path).unwrap();
    let path = [
        [-2.0, -2.2, 0.8, 0.0],
        [-2.0, -2.2, 2.0, 0.0],
        [0.0, 0.0, 2.0, 0.0],
        [0.0, 0.0, 0.55, 0.0],
    ];
    path_is_free3(&parts, r, &obstacles, &path).unwrap();
}

/// The piano as two boxes: the body and the keyboard shelf (what scenes/meshes/piano.obj
/// bounds).
fn piano_parts() -> Vec<ConvexPolyhedron> {
    let body = TriMesh::cuboid([0.75, 0.3, 0.65]).unwrap();
    let shelf = TriMesh::cuboid([0.75, 0.15, 0.05])
        .unwrap()
        .translated(Vector3::new(0.0, -0.45, 0.1));
    vec![convex3(&body), convex3(&shelf)]
}

#[test]
fn piano_mesh_is_the_body_and_shelf() {
    let m = load_obj(&root().join("scenes/meshes/piano.obj")).unwrap();
    assert!(m.is_closed());
    assert!((volume(&m) - (1.5 * 0.6 * 1.3 + 1.5 * 0.3 * 0.1)).abs() < 1e-12);
    let (lo, hi) = m.aabb();
    assert_eq!(
        (lo, hi),
        (
            Point3::new(-0.75, -0.6, -0.65),
            Point3::new(0.75, 0.3, 0.65)
        )
    );
    // every vertex lies on the boundary of the union of the two boxes
    let inside = |p: &Point3<f64>, c: [f64; 3], h: [f64; 3]| {
        (0..3).all(|i| (p[i] - c[i]).abs() <= h[i] + 1e-12)
    };
    for v in &m.vertices {
        assert!(
            inside(v, [0.0, 0.0, 0.0], [0.75, 0.3, 0.65])
                || inside(v, [0.0, -0.45, 0.1], [0.75, 0.15, 0.05]),
            "{v:?}"
        );
    }
}

#[test]
fn piano_is_valid_and_solvable_with_a_quarter_turn() {
    let scene = Scene::load(&root().join("scenes/piano.toml")).unwrap();
    let Robot::Mesh(piano) = &scene.robot else {
        panic!("the robot is a mesh")
    };
    let parts = piano_parts();
    let obstacles = obstacles3(&scene);
    for q in &scene.queries {
        for c in [&q.start, &q.goal] {
            assert!(clearance3(&parts, &obstacles, c) > 0.05, "{c:?}");
        }
    }
    // the first query turns the piano by 90° about z
    let (s, g) = (&scene.queries[0].start, &scene.queries[0].goal);
    let angle = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(s[6], s[3], s[4], s[5]))
        .angle_to(&UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            g[6], g[3], g[4], g[5],
        )));
    assert!((angle - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    // the chair blocks the straight translation at the start's orientation
    let blocked = (0..=400).any(|k| {
        let t = k as f64 / 400.0;
        let mut q = s.clone();
        q[0] = s[0] + t * (g[0] - s[0]);
        q[1] = s[1] + t * (g[1] - s[1]);
        clearance3(&parts, &obstacles, &q) == 0.0
    });
    assert!(blocked);
    // east along the south wall, north past the chair, turn, west to the west wall
    let pi = std::f64::consts::PI;
    let path = [
        [2.0, 0.4, 0.75, pi],
        [3.5, 0.4, 0.75, pi],
        [3.5, 3.0, 0.75, pi],
        [3.5, 3.0, 0.75, pi / 2.0],
        [0.4, 3.0, 0.75, pi / 2.0],
    ];
    path_is_free3(&parts, piano.radius(), &obstacles, &path).unwrap();
}

// --- se2 example scene --------------------------------------------------------------------

fn convex2(points: &[Point2<f64>]) -> ConvexPolygon {
    ConvexPolygon::from_convex_hull(points).expect("a convex piece")
}

fn clearance2(parts: &[ConvexPolygon], obstacles: &[ConvexPolygon], q: &[f64]) -> f64 {
    let at = Isometry2::new(Vector2::new(q[0], q[1]), q[2]);
    let id = Isometry2::identity();
    parts
        .iter()
        .flat_map(|p| {
            obstacles
                .iter()
                .map(move |o| parry2d_f64::query::distance(&at, p, &id, o).unwrap())
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn se2_corridor_is_valid_and_needs_a_turn() {
    let scene = Scene::load(&root().join("scenes/se2-corridor.toml")).unwrap();
    assert_eq!(scene.space.kind(), SpaceKind::Se2);
    let Robot::Polygons(robot) = &scene.robot else {
        panic!("the robot is polygons")
    };
    let l = [
        (-1.2, -0.2),
        (1.2, -0.2),
        (1.2, 1.0),
        (0.8, 1.0),
        (0.8, 0.2),
        (-1.2, 0.2),
    ]
    .map(|(x, y)| Point2::new(x, y));
    assert_eq!(robot[0].vertices, l.to_vec());
    // the L as two convex parts: the long arm and the short arm
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
        convex2(&[
            Point2::new(x0, y0),
            Point2::new(x1, y0),
            Point2::new(x1, y1),
            Point2::new(x0, y1),
        ])
    };
    let parts = [rect(-1.2, -0.2, 1.2, 0.2), rect(0.8, 0.2, 1.2, 1.0)];
    let obstacles: Vec<ConvexPolygon> = scene
        .obstacles
        .iter()
        .map(|o| match o {
            Obstacle::Polygon(p) => convex2(&p.vertices),
            other => panic!("not a polygon: {other:?}"),
        })
        .collect();
    for q in &scene.queries {
        for c in [&q.start, &q.goal] {
            assert!(clearance2(&parts, &obstacles, c) > 0.05, "{c:?}");
        }
    }
    // standing in the bottom corridor or lying in the north corridor is impossible
    let (s, g) = (&scene.queries[0].start, &scene.queries[0].goal);
    assert_eq!(clearance2(&parts, &obstacles, &[s[0], s[1], g[2]]), 0.0);
    assert_eq!(clearance2(&parts, &obstacles, &[g[0], g[1], s[2]]), 0.0);
    // a path: east along the corridor, up into the corner room, turn, north
    let radius = robot[0].radius();
    let half_pi = std::f64::consts::FRAC_PI_2;
    let path = [
        [2.0, 0.7, 0.0],
        [8.0, 0.7, 0.0],
        [8.0, 2.0, 0.0],
        [8.0, 2.0, half_pi],
        [9.5, 2.5, half_pi],
        [9.5, 6.0, half_pi],
    ];
    for pair in path.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let travel =
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt() + radius * (b[2] - a[2]).abs();
        let steps = (travel / 0.002).ceil() as usize;
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            let q = [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]));
            let c = clearance2(&parts, &obstacles, &q);
            assert!(c > travel / steps as f64, "clearance {c} at {q:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// the TOML format: every space kind, every kind of bad input

fn parse(text: &str) -> Result<Scene, SceneError> {
    from_str(text, &data("inline.toml"))
}

/// A scene whose own queries are to be answered: loading accepts queries outside the bounds
/// or in collision (a roadmap does not need them, so it only warns); answering them refuses.
fn checked(text: &str) -> Result<Scene, SceneError> {
    let scene = parse(text)?;
    match scene.checked_queries() {
        Ok(_) => Ok(scene),
        Err(e) => {
            assert!(
                scene
                    .warnings
                    .iter()
                    .any(|w| w.contains(&e.to_string()) && w.contains("cannot be answered")),
                "the load warned: {:?}",
                scene.warnings
            );
            Err(e)
        }
    }
}

fn invalid_message(text: &str) -> String {
    match parse(text) {
        Err(SceneError::Invalid { path, message }) => {
            assert_eq!(path, data("inline.toml"));
            message
        }
        other => panic!("expected an Invalid error, got {other:?}"),
    }
}

const R2: &str = "[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n";
const SE3: &str = "[space]\nkind = \"se3\"\nlower = [-5.0, -5.0, -5.0]\nupper = [5.0, 5.0, 5.0]\n";
const SE2: &str = "[space]\nkind = \"se2\"\nlower = [-5.0, -5.0]\nupper = [5.0, 5.0]\n";

#[test]
fn rn_scenes_of_any_dimension() {
    let s = parse(
        "[space]\nkind = \"rn\"\nlower = [0, 0, 0, 0]\nupper = [1, 1, 1, 1]\n\
         [[obstacle]]\ndisc = { center = [0.5, 0.5, 0.5, 0.5], radius = 0.1 }\n\
         [[query]]\nstart = [0.1, 0.1, 0.1, 0.1]\ngoal = [0.9, 0.9, 0.9, 0.9]\n",
    )
    .unwrap();
    assert_eq!(s.space.kind(), SpaceKind::Euclidean(4));
    let s = parse("[space]\nkind = \"r3\"\nlower = [0, 0, 0]\nupper = [1, 1, 1]\n").unwrap();
    assert_eq!(s.space.kind(), SpaceKind::Euclidean(3));
    assert_eq!(s.name, "inline");
    assert!(
        invalid_message("[space]\nkind = \"r3\"\nlower = [0, 0]\nupper = [1, 1]\n")
            .contains("lower has 2 numbers")
    );
    // a borderline is perpendicular to a motion: R^1 has none, so it is not a scene
    assert!(
        invalid_message("[space]\nkind = \"rn\"\nlower = [0]\nupper = [1]\n").contains("needs 2")
    );
    assert!(
        invalid_message("[space]\nkind = \"r1\"\nlower = [0]\nupper = [1]\n")
            .contains("is not known")
    );
    assert!(viaroad::space::Space::euclidean(vec![0.0], vec![1.0]).is_err());
}

#[test]
fn se3_inline_shapes_and_quaternion_normalisation() {
    let s = parse(&format!(
        "name = \"inline se3\"\n{SE3}rotation_scale = 2.5\n\
         [robot]\nconvex = {{ points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]] }}\n\
         center = \"mean\"\n\
         [[obstacle]]\nbox = {{ center = [3, 0, 0], half_extents = [1, 1, 1] }}\n\
         [[obstacle]]\nmesh = \"octa.obj\"\noffset = [-3, 0, 0]\n\
         [[query]]\nstart = [0, 0, 2, 0, 0, 0, 2]\ngoal = [0, 0, -2, 0, 0, 1, 1]\n"
    ))
    .unwrap();
    assert_eq!(s.name, "inline se3");
    assert_eq!(s.space.rotation_scale(), 2.5);
    let Robot::Mesh(tet) = &s.robot else { panic!() };
    assert!(tet.is_closed());
    assert!((volume(tet) - 1.0 / 6.0).abs() < 1e-12);
    let mean = tet
        .vertices
        .iter()
        .fold(Vector3::zeros(), |a, v| a + v.coords)
        / 4.0;
    assert!(mean.norm() < 1e-12, "centred on the mean of its vertices");
    let Obstacle::Mesh(b) = &s.obstacles[0] else {
        panic!()
    };
    assert_eq!(
        b.aabb(),
        (Point3::new(2.0, -1.0, -1.0), Point3::new(4.0, 1.0, 1.0))
    );
    let Obstacle::Mesh(o) = &s.obstacles[1] else {
        panic!()
    };
    let octa = load_obj(&data("octa.obj")).unwrap();
    assert!((o.aabb().0 - (octa.aabb().0 + Vector3::new(-3.0, 0.0, 0.0))).norm() < 1e-12);
    // quaternions stored at unit length
    assert_eq!(s.queries[0].start, vec![0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0]);
    let g = &s.queries[0].goal;
    assert!((g[5] - 0.5f64.sqrt()).abs() < 1e-15 && (g[6] - 0.5f64.sqrt()).abs() < 1e-15);
}

#[test]
fn se2_inline_shapes_footprints_and_angle_wrapping() {
    let s = parse(&format!(
        "{SE2}[robot]\nbox = {{ half_extents = [1.0, 0.25], center = [0.5, 0.0] }}\n\
         [[obstacle]]\npolygon = {{ vertices = [[2, 2], [3, 2], [2, 3]] }}\n\
         [[obstacle]]\nconvex = {{ points = [[-3, -3], [-2, -3], [-2, -2], [-3, -2], [-2.5, -2.5]] }}\n\
         [[obstacle]]\nmesh = \"octa_zup.dae\"\noffset = [0, 3.5]\n\
         [[query]]\nstart = [0, 0, 7.0]\ngoal = [1, -1, -3.14159]\n"
    ))
    .unwrap();
    let Robot::Polygons(parts) = &s.robot else {
        panic!()
    };
    // the box's centre is in the body frame: the reference point is its left part
    assert_eq!(parts[0].vertices[0], Point2::new(-0.5, -0.25));
    assert!((s.space.rotation_scale() - (1.5f64.powi(2) + 0.25f64.powi(2)).sqrt()).abs() < 1e-12);
    let polygons: Vec<_> = s
        .obstacles
        .iter()
        .map(|o| match o {
            Obstacle::Polygon(p) => p.clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        polygons[1].vertices.len(),
        4,
        "the hull drops the interior point"
    );
    assert!((polygons[1].area() - 1.0).abs() < 1e-12);
    // the octahedron's footprint: its projection, moved by the offset
    let octa = load_mesh(&data("octa.obj")).unwrap();
    let (lo, _) = octa.aabb();
    let min_x = polygons[2..]
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| v.x))
        .fold(f64::INFINITY, f64::min);
    let min_y = polygons[2..]
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| v.y))
        .fold(f64::INFINITY, f64::min);
    assert!((min_x - lo.x).abs() < 1e-6 && (min_y - (lo.y + 3.5)).abs() < 1e-6);
    // angles wrapped into [-π, π)
    let t = s.queries[0].start[2];
    assert!((t - (7.0 - std::f64::consts::TAU)).abs() < 1e-12);
}

#[test]
fn robot_centre_mean_and_point() {
    let s = parse(&format!(
        "{SE2}[robot]\npolygon = {{ vertices = [[0, 0], [2, 0], [2, 1], [0, 1]] }}\ncenter = \"mean\"\n"
    ))
    .unwrap();
    let Robot::Polygons(p) = &s.robot else {
        panic!()
    };
    assert_eq!(p[0].vertices[0], Point2::new(-1.0, -0.5));
    let s = parse(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\ncenter = [1, 0, 0]\n"
    ))
    .unwrap();
    let Robot::Mesh(m) = &s.robot else { panic!() };
    assert_eq!(m.aabb().0, Point3::new(-2.0, -1.0, -1.0));
    // a Collada robot with center = "mean" uses OMPL.app's (assimp's) centre
    let s = parse(&format!(
        "{SE3}[robot]\nmesh = \"octa_zup.dae\"\ncenter = \"mean\"\n"
    ))
    .unwrap();
    let dae = load_collada(&data("octa_zup.dae")).unwrap();
    let Robot::Mesh(m) = &s.robot else { panic!() };
    let c = dae.assimp_centre.map(f64::from);
    assert!((m.vertices[0] - (dae.mesh.vertices[0] - Vector3::from(c))).norm() < 1e-12);
    assert!(invalid_message(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\ncenter = \"middle\"\n"
    ))
    .contains("neither \"mean\" nor a point"));
    assert!(invalid_message(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\ncenter = [1, 0]\n"
    ))
    .contains("center has 2 numbers"));
}

#[test]
fn missing_file_is_an_io_error() {
    let e = Scene::load(&data("no-such-scene.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }), "{e}");
    assert!(e.to_string().contains("no-such-scene.toml"));
}

#[test]
fn syntax_errors_and_unknown_keys_are_parse_errors() {
    for (text, needle) in [
        ("[space\nkind = 1", "inline.toml"),
        (&format!("{R2}colour = \"red\"\n") as &str, "colour"),
        (
            &format!("{R2}[[obstacle]]\ndisc = {{ center = [0.5, 0.5], radius = 0.1, hue = 3 }}\n"),
            "hue",
        ),
        (
            &format!("{R2}[[query]]\nstart = [0.1, 0.1]\ngoal = [0.2, 0.2]\nvia = [0.3, 0.3]\n"),
            "via",
        ),
        (
            &format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\nscale = 2\n"),
            "scale",
        ),
        ("[space]\nlower = [0, 0]\nupper = [1, 1]\n", "kind"),
    ] {
        match parse(text) {
            Err(e @ SceneError::Parse { .. }) => {
                let m = e.to_string();
                assert!(m.contains(needle) && m.contains("inline.toml"), "{m}");
                assert!(!m.contains('\n'), "one line: {m}");
            }
            other => panic!("{text}: expected a parse error, got {other:?}"),
        }
    }
}

#[test]
fn each_kind_of_bad_input_has_its_own_message() {
    let cases: Vec<(String, &str)> = vec![
        ("[space]\nkind = \"r7d\"\nlower = [0]\nupper = [1]\n".into(), "kind = \"r7d\" is not known"),
        ("[space]\nkind = \"r2\"\nlower = [nan, 0]\nupper = [1, 1]\n".into(), "not finite"),
        ("[space]\nkind = \"r2\"\nlower = [2, 0]\nupper = [1, 1]\n".into(), "lower 2 > upper 1"),
        ("[space]\nkind = \"se3\"\nlower = [0, 0]\nupper = [1, 1]\n".into(), "a se3 space needs 3"),
        (format!("{R2}rotation_scale = 1.0\n"), "rotation_scale applies to se2 and se3"),
        (format!("{R2}[robot]\nbox = {{ half_extents = [1, 1] }}\n"), "moves a point"),
        (format!("{R2}[[obstacle]]\ndisc = {{ center = [0.5, 0.5], radius = -0.1 }}\n"), "radius must be a non-negative"),
        (format!("{R2}[[obstacle]]\ndisc = {{ center = [0.5, nan], radius = 0.1 }}\n"), "center is not finite"),
        (format!("{R2}[[obstacle]]\ndisc = {{ center = [0.5, 0.5, 0.5], radius = 0.1 }}\n"), "3 coordinates, the space has 2"),
        (format!("{R2}[[obstacle]]\nbox = {{ half_extents = [1, 1] }}\n"), "does not belong in an r2 scene"),
        (format!("{R2}[[obstacle]]\n"), "no shape"),
        (SE3.to_string(), "needs a [robot]"),
        (format!("{SE3}[robot]\n"), "[robot]: no shape"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\nmesh = \"octa.obj\"\n"), "one shape per robot, found box, mesh"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, -1, 1] }}\n"), "half extents must be a positive"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1] }}\n"), "half_extents has 2 numbers, the space needs 3"),
        (format!("{SE3}[robot]\npolygon = {{ vertices = [[0, 0], [1, 0], [0, 1]] }}\n"), "polygons describe se2 robots"),
        (format!("{SE3}[robot]\nconvex = {{ points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]] }}\n"), "no volume"),
        (format!("{SE3}rotation_scale = -1\n[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n"), "rotation_scale must be a positive"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n[[obstacle]]\ndisc = {{ center = [0, 0, 0], radius = 1 }}\n"), "a disc does not belong in a se3 scene"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n[[obstacle]]\npolygon = {{ vertices = [[0, 0], [1, 0], [0, 1]] }}\n"), "a polygon does not belong in a se3 scene"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n[[obstacle]]\nbox = {{ half_extents = [1, 1, 1] }}\nconvex = {{ points = [[0, 0, 0]] }}\n"), "one shape per obstacle, found box, convex"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n[[obstacle]]\nbox = {{ half_extents = [1, 1, 1] }}\noffset = [1, 1, 1]\n"), "offset applies to mesh obstacles only"),
        (format!("{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n[[obstacle]]\nmesh = \"octa.obj\"\noffset = [1, 1]\n"), "offset has 2 numbers"),
        (format!("{SE2}[robot]\npolygon = {{ vertices = [[0, 0], [2, 2], [2, 0], [0, 1]] }}\n"), "edges cross or touch"),
        (format!("{SE2}[robot]\npolygon = {{ vertices = [[0, 0], [1, 0], [2, 0]] }}\n"), "at least 3 vertices and a positive area"),
        (format!("{SE2}[robot]\npolygon = {{ vertices = [[0, 0], [1, 0, 5], [0, 1]] }}\n"), "polygon vertex 2 has 3 numbers"),
        (format!("{SE2}[robot]\npolygons = []\n"), "polygons = [] is empty"),
        (format!("{SE2}[robot]\nconvex = {{ points = [[0, 0], [1, 1], [2, 2]] }}\n"), "no area"),
        (format!("{SE2}[robot]\nbox = {{ half_extents = [1, 1] }}\n[[obstacle]]\ndisc = {{ center = [0, 0], radius = 1 }}\n"), "a disc does not belong in a se2 scene"),
    ];
    let mut seen = std::collections::HashSet::new();
    for (text, needle) in &cases {
        let m = invalid_message(text);
        assert!(m.contains(needle), "{text}\n→ {m}\n(expected {needle:?})");
        assert!(seen.insert(m.clone()), "message used twice: {m}");
    }
}

#[test]
fn bad_queries_are_config_errors_naming_the_query() {
    let scene = |q: &str| {
        checked(&format!(
            "{R2}[[obstacle]]\ndisc = {{ center = [0.5, 0.5], radius = 0.1 }}\n{q}"
        ))
    };
    let e = scene("[[query]]\nstart = [0.1, 0.1, 0.1]\ngoal = [0.9, 0.9]\n").unwrap_err();
    assert!(
        matches!(&e, SceneError::Config { what, source: SpaceError::Dimension { got: 3, .. } } if what == "start of query 1"),
        "{e:?}"
    );
    let e = scene("[[query]]\nstart = [0.1, 0.1]\ngoal = [0.9, 0.9]\n[[query]]\nstart = [0.1, 0.1]\ngoal = [nan, 0.9]\n").unwrap_err();
    assert!(
        matches!(&e, SceneError::Config { what, source: SpaceError::NotFinite { index: 0, .. } } if what == "goal of query 2"),
        "{e:?}"
    );
    let e = scene("[[query]]\nstart = [1.5, 0.1]\ngoal = [0.9, 0.9]\n").unwrap_err();
    assert!(
        matches!(&e, SceneError::OutOfBounds { what, .. } if what == "start of query 1"),
        "{e:?}"
    );
    assert!(e.to_string().contains("outside the scene's bounds"));
    let e = scene("[[query]]\nstart = [0.1, 0.1]\ngoal = [0.55, 0.5]\n").unwrap_err();
    assert!(
        matches!(&e, SceneError::InCollision { what, .. } if what == "goal of query 1"),
        "{e:?}"
    );
    // a quaternion of length 0
    let e = checked(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [1, 1, 1] }}\n[[query]]\nstart = [0, 0, 0, 0, 0, 0, 0]\ngoal = [1, 0, 0, 0, 0, 0, 1]\n"
    ))
    .unwrap_err();
    assert!(
        matches!(
            &e,
            SceneError::Config {
                source: SpaceError::Quaternion(_),
                ..
            }
        ),
        "{e:?}"
    );
    let e = checked(&format!(
        "{SE2}[robot]\nbox = {{ half_extents = [1, 1] }}\n[[query]]\nstart = [0, 9, 0]\ngoal = [1, 0, 0]\n"
    ))
    .unwrap_err();
    assert!(matches!(&e, SceneError::OutOfBounds { .. }), "{e:?}");
}

// The two tests below reject a start in collision through the scene's own oracle; they need
// the exact SE(3)/SE(2) oracles (the stubs answer "free").
#[test]

fn se3_start_in_collision_is_rejected() {
    let e = checked(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [0.5, 0.5, 0.5] }}\n\
         [[obstacle]]\nbox = {{ center = [3, 0, 0], half_extents = [1, 1, 1] }}\n\
         [[query]]\nstart = [2.6, 0, 0, 0, 0, 0, 1]\ngoal = [-3, 0, 0, 0, 0, 0, 1]\n"
    ))
    .unwrap_err();
    assert!(
        matches!(&e, SceneError::InCollision { what, .. } if what == "start of query 1"),
        "{e:?}"
    );
    // wholly inside a closed obstacle is a collision too
    let e = checked(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [0.1, 0.1, 0.1] }}\n\
         [[obstacle]]\nbox = {{ center = [3, 0, 0], half_extents = [1, 1, 1] }}\n\
         [[query]]\nstart = [-3, 0, 0, 0, 0, 0, 1]\ngoal = [3, 0, 0, 0, 0, 0, 1]\n"
    ))
    .unwrap_err();
    assert!(
        matches!(&e, SceneError::InCollision { what, .. } if what == "goal of query 1"),
        "{e:?}"
    );
}

#[test]

fn se2_start_in_collision_is_rejected() {
    let e = checked(&format!(
        "{SE2}[robot]\nbox = {{ half_extents = [1.0, 0.2] }}\n\
         [[obstacle]]\nbox = {{ center = [3, 0], half_extents = [1, 1] }}\n\
         [[query]]\nstart = [1.5, 0, 0]\ngoal = [-3, 0, 0]\n"
    ))
    .unwrap_err();
    assert!(
        matches!(&e, SceneError::InCollision { what, .. } if what == "start of query 1"),
        "{e:?}"
    );
    // turned by 90° the same position is free
    checked(&format!(
        "{SE2}[robot]\nbox = {{ half_extents = [1.0, 0.2] }}\n\
         [[obstacle]]\nbox = {{ center = [3, 0], half_extents = [1, 1] }}\n\
         [[query]]\nstart = [1.5, 0, 1.5707963267948966]\ngoal = [-3, 0, 0]\n"
    ))
    .unwrap();
}

#[test]
fn mesh_errors_name_the_mesh_file() {
    let robot = "[robot]\nbox = { half_extents = [0.1, 0.1, 0.1] }\n";
    let with_mesh = |m: &str| parse(&format!("{SE3}{robot}[[obstacle]]\nmesh = \"{m}\"\n"));
    let e = with_mesh("no-such-mesh.obj").unwrap_err();
    assert!(
        matches!(&e, SceneError::Io { path, .. } if path.ends_with("no-such-mesh.obj")),
        "{e:?}"
    );
    for bad in ["garbage.obj", "truncated.stl", "truncated.dae"] {
        let e = with_mesh(bad).unwrap_err();
        assert!(
            matches!(&e, SceneError::Parse { path, .. } if path.ends_with(bad)),
            "{bad}: {e:?}"
        );
        assert!(e.to_string().contains(bad));
    }
    let e = with_mesh("octa.ply").unwrap_err();
    assert!(e.to_string().contains("unknown mesh format"), "{e}");
    // a mesh with no faces of positive area
    let flat = std::env::temp_dir().join(format!("viaroad-flat-{}.obj", std::process::id()));
    std::fs::write(&flat, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").unwrap();
    let e = load_mesh(&flat).unwrap_err();
    assert!(
        matches!(&e, SceneError::Geometry { path, .. } if path == &flat),
        "{e:?}"
    );
    std::fs::remove_file(&flat).unwrap();
}

#[test]
fn an_open_mesh_is_accepted_with_a_warning() {
    let s = parse(&format!(
        "{SE3}[robot]\nbox = {{ half_extents = [0.1, 0.1, 0.1] }}\n[[obstacle]]\nmesh = \"open_sheet.obj\"\n\
         [[obstacle]]\nmesh = \"octa.obj\"\n"
    ))
    .unwrap();
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(s.warnings[0].contains("open_sheet.obj is not closed"));
    assert!(s.warnings[0].contains("containment cannot be decided"));
}

#[test]
fn fingerprint_follows_the_geometry() {
    let path = root().join("scenes/discs-example.toml");
    let a = Scene::load(&path).unwrap();
    let b = Scene::load(&path).unwrap();
    assert_eq!(a.fingerprint(), b.fingerprint());
    let text = std::fs::read_to_string(&path).unwrap();
    let renamed = from_str(
        &text.replace("name = \"discs-example\"", "name = \"other\""),
        &path,
    )
    .unwrap();
    assert_eq!(
        renamed.fingerprint(),
        a.fingerprint(),
        "the name is not geometry"
    );
    let moved = from_str(&text.replace("radius = 0.05", "radius = 0.051"), &path).unwrap();
    assert_ne!(moved.fingerprint(), a.fingerprint());
    let bounds = from_str(
        &text.replace("upper = [1.0, 1.0]", "upper = [1.0, 1.5]"),
        &path,
    )
    .unwrap();
    assert_ne!(bounds.fingerprint(), a.fingerprint());
    // mesh scenes: the same file twice, and a different robot
    let c1 = Scene::load(&root().join("scenes/cube-into-box.toml")).unwrap();
    let c2 = Scene::load(&root().join("scenes/cube-into-box.toml")).unwrap();
    assert_eq!(c1.fingerprint(), c2.fingerprint());
    let t = std::fs::read_to_string(root().join("scenes/cube-into-box.toml")).unwrap();
    let smaller = from_str(
        &t.replace(
            "half_extents = [0.5, 0.5, 0.5]",
            "half_extents = [0.45, 0.5, 0.5]",
        ),
        &root().join("scenes/cube-into-box.toml"),
    )
    .unwrap();
    assert_ne!(smaller.fingerprint(), c1.fingerprint());
    let o1 = Scene::load(&root().join("scenes/ompl/2D/Maze_planar.cfg")).unwrap();
    let o2 = Scene::load(&root().join("scenes/ompl/2D/Maze_planar.cfg")).unwrap();
    assert_eq!(o1.fingerprint(), o2.fingerprint());
    assert_ne!(
        o1.fingerprint(),
        Scene::load(&root().join("scenes/ompl/2D/RandomPolygons_planar.cfg"))
            .unwrap()
            .fingerprint()
    );
}

// ---------------------------------------------------------------------------------------------
// meshes

#[test]
fn obj_stl_and_dae_loaders_agree() {
    let obj = load_mesh(&data("octa.obj")).unwrap();
    assert_eq!(obj.triangles.len(), 8, "the `l` element is not a face");
    assert_eq!(obj.vertices.len(), 6);
    assert!(obj.is_closed());
    assert!((volume(&obj) - 7.0 / 6.0).abs() < 1e-9);
    let reference = triangle_set(&obj);
    for other in [
        "octa_ascii.stl",
        "octa_binary.stl",
        "octa_yup.dae",
        "octa_zup.dae",
    ] {
        let m = load_mesh(&data(other)).unwrap();
        assert!(m.is_closed(), "{other}: vertices are welded");
        assert_eq!(m.vertices.len(), 6, "{other}");
        // STL and Collada store f32: compare at 1e-6 after rounding both
        let set = triangle_set(&m);
        let close = reference.iter().zip(&set).all(|(a, b)| {
            a.iter()
                .zip(b)
                .all(|(p, q)| p.iter().zip(q).all(|(x, y)| (x - y).abs() <= 1))
        });
        assert!(close && set.len() == reference.len(), "{other} differs");
        assert!(
            (volume(&m) - volume(&obj)).abs() < 1e-6,
            "{other}: orientation kept"
        );
    }
    // quads: fans in OBJ, ear clipping of a <polylist> in Collada
    let a = load_mesh(&data("cube_quads.obj")).unwrap();
    let b = load_mesh(&data("cube_polylist.dae")).unwrap();
    for m in [&a, &b] {
        assert_eq!(m.triangles.len(), 12);
        assert!(m.is_closed());
        assert!((volume(m).abs() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn collada_up_axis_and_node_transforms() {
    // the Z_UP file stores (x, -z, y) of the Y_UP one: after assimp's conversion they agree
    let y = load_collada(&data("octa_yup.dae")).unwrap();
    let z = load_collada(&data("octa_zup.dae")).unwrap();
    assert_eq!(triangle_set(&y.mesh), triangle_set(&z.mesh));
    // 8 triangles. The file has no normals, so assimp gives each face its flat normal and
    // joins no vertices across faces: 24 face corners (every tip is in 4 faces), plus the line
    // primitive's 2 vertices (the +x and -x tips again)
    assert_eq!(y.triangles_imported, 8);
    assert_eq!(y.vertices_imported, 26);
    let v = load_obj(&data("octa.obj")).unwrap().vertices;
    let mut mean = v.iter().fold(Vector3::zeros(), |a, p| a + 4.0 * p.coords);
    mean += Vector3::new(1.0, 0.2, 0.1) + Vector3::new(-0.8, 0.1, 0.0); // the file's v 1, v 2
    mean /= 26.0;
    for c in [y.assimp_centre, z.assimp_centre] {
        assert!(
            (Vector3::from(c.map(f64::from)) - mean).norm() < 1e-6,
            "{c:?} vs {mean:?}"
        );
    }
}

#[test]
fn truncated_and_garbage_meshes_are_errors_not_panics() {
    for bad in ["garbage.obj", "truncated.stl", "truncated.dae"] {
        let e = load_mesh(&data(bad)).unwrap_err();
        assert!(matches!(e, SceneError::Parse { .. }), "{bad}: {e:?}");
    }
    // every prefix of a valid file, and random bytes, in each format
    let dir = std::env::temp_dir().join(format!("viaroad-truncated-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    for src in [
        "octa.obj",
        "octa_binary.stl",
        "octa_ascii.stl",
        "octa_zup.dae",
    ] {
        let bytes = std::fs::read(data(src)).unwrap();
        let ext = Path::new(src).extension().unwrap().to_str().unwrap();
        let target = dir.join(format!("cut.{ext}"));
        for cut in (0..bytes.len()).step_by(13) {
            std::fs::write(&target, &bytes[..cut]).unwrap();
            let _ = load_mesh(&target); // an error or a smaller mesh, never a panic
        }
        let noise: Vec<u8> = (0..300).map(|_| rng.random()).collect();
        std::fs::write(&target, &noise).unwrap();
        assert!(load_mesh(&target).is_err(), "random bytes as .{ext}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
    // STL and OBJ readers by name
    assert!(load_stl(&data("truncated.stl")).is_err());
    assert!(load_obj(&data("garbage.obj")).is_err());
}

fn write_mesh_files(dir: &Path, v: &[Point3<f64>], t: &[[u32; 3]]) {
    let mut obj = String::new();
    for p in v {
        obj += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for f in t {
        obj += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&(t.len() as u32).to_le_bytes());
    for f in t {
        stl.extend_from_slice(&[0u8; 12]);
        for &i in f {
            for c in [v[i as usize].x, v[i as usize].y, v[i as usize].z] {
                stl.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        stl.extend_from_slice(&[0, 0]);
    }
    std::fs::write(dir.join("m.stl"), stl).unwrap();
    // Collada with a node matrix that moves by (1, 2, 3): the file stores the mesh moved back
    let pos: Vec<String> = v
        .iter()
        .map(|p| format!("{} {} {}", p.x - 1.0, p.y - 2.0, p.z - 3.0))
        .collect();
    let idx: Vec<String> = t.iter().flatten().map(|i| i.to_string()).collect();
    let dae = format!(
        r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><created>2026-01-01T00:00:00Z</created><modified>2026-01-01T00:00:00Z</modified><up_axis>Y_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="{}">{}</float_array><technique_common><accessor source="#pa" count="{}" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="{}"><input offset="0" semantic="VERTEX" source="#v"/><p>{}</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node><matrix>1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1</matrix><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>"##,
        3 * v.len(),
        pos.join(" "),
        v.len(),
        t.len(),
        idx.join(" ")
    );
    std::fs::write(dir.join("m.dae"), dae).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// The convex hull of random points, written as OBJ, binary STL and Collada (with a node
    /// transform), reads back as the same closed solid in every format.
    #[test]
    fn loaders_agree_on_random_hulls(
        pts in prop::collection::vec((-4.0f64..4.0, -4.0f64..4.0, -4.0f64..4.0), 5..14),
        case in 0u32..1_000_000,
    ) {
        // coordinates on a grid of 1/8 that f32 and decimal text represent exactly
        let pts: Vec<Point3<f64>> = pts
            .iter()
            .map(|(x, y, z)| Point3::new((x * 8.0).round() / 8.0, (y * 8.0).round() / 8.0, (z * 8.0).round() / 8.0))
            .collect();
        let Ok((v, t)) = parry3d_f64::transformation::try_convex_hull(&pts) else {
            return Ok(());
        };
        let reference = TriMesh::new(v.clone(), t.clone());
        prop_assume!(reference.is_ok());
        let reference = reference.unwrap();
        let dir = std::env::temp_dir().join(format!("viaroad-hull-{}-{case}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        write_mesh_files(&dir, &v, &t);
        let want = triangle_set(&reference);
        for f in ["m.obj", "m.stl", "m.dae"] {
            let m = load_mesh(&dir.join(f)).unwrap();
            prop_assert_eq!(&triangle_set(&m), &want, "{}", f);
            prop_assert_eq!(m.is_closed(), reference.is_closed(), "{}", f);
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

// ---------------------------------------------------------------------------------------------
// OMPL.app problems

/// scenes/ompl/README (the OMPL peer's table): triangles assimp imports per .dae, and OMPL.app's
/// robot centre (f32) for the robots.
const OMPL_MESHES: &[(&str, usize, Option<[f64; 3]>)] = &[
    (
        "3D/Easy_robot.dae",
        56,
        Some([270.4043, 160.6562, -297.8234]),
    ),
    ("3D/Easy_env.dae", 176, None),
    (
        "3D/Twistycool_robot.dae",
        56,
        Some([270.4043, 160.6562, -297.8234]),
    ),
    ("3D/Twistycool_env.dae", 176, None),
    (
        "3D/cubicles_robot.dae",
        40,
        Some([-4.9580, -40.6201, 70.5650]),
    ),
    ("3D/cubicles_env.dae", 626, None),
    ("3D/Home_robot.dae", 120, Some([-0.0460, 0.0511, 9.1926])),
    ("3D/Home_env.dae", 696, None),
    (
        "3D/Apartment_robot.dae",
        3364,
        Some([-31.1927, -99.8490, 36.4595]),
    ),
    ("3D/Apartment_env.dae", 37114, None),
    (
        "3D/alpha_robot.dae",
        2016,
        Some([-21.9097, -11.1070, -14.1355]),
    ),
    ("3D/alpha_env-1.5.dae", 2016, None),
    (
        "3D/bugtrap_robot.dae",
        264,
        Some([17.1814, 0.8941, -4.6183]),
    ),
    ("3D/bugtrap_env.dae", 5212, None),
    (
        "3D/Abstract_robot.dae",
        48,
        Some([-8.0194, 0.0000, -7.8353]),
    ),
    ("3D/Abstract_env.dae", 1400, None),
    // 2D robots: OMPL.app zeroes the centre's z; the table lists it so
    ("2D/car1_planar_robot.dae", 28, Some([0.0250, 0.0000, 0.0])),
    ("2D/BugTrap_planar_env.dae", 264, None),
    ("2D/car2_planar_robot.dae", 40, Some([0.0100, -0.1500, 0.0])),
    ("2D/Maze_planar_env.dae", 1892, None),
    ("2D/RandomPolygons_planar_env.dae", 1644, None),
    (
        "2D/UniqueSolutionMaze_robot.dae",
        416,
        Some([-43.9541, -42.7486, 0.0]),
    ),
    ("2D/UniqueSolutionMaze_env.dae", 1100, None),
    (
        "2D/Barriers_easy_robot.dae",
        100,
        Some([35.2027, -169.4159, 0.0]),
    ),
    ("2D/Barriers_easy_env.dae", 632, None),
];

#[test]
fn ompl_meshes_match_the_table() {
    let dir = root().join("scenes/ompl");
    for (name, triangles, centre) in OMPL_MESHES {
        let m = load_collada(&dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.triangles_imported, *triangles, "{name}: triangles");
        // TriMesh drops the triangles of zero area (at most 3 % here: Apartment_robot)
        assert!(
            m.mesh.triangles.len() <= *triangles && m.mesh.triangles.len() * 100 >= triangles * 97,
            "{name}"
        );
        if let Some(c) = centre {
            let planar = name.starts_with("2D");
            for i in 0..if planar { 2 } else { 3 } {
                let got = m.assimp_centre[i] as f64;
                assert!(
                    (got - c[i]).abs() < 1e-3,
                    "{name}: centre {:?} vs {c:?}",
                    m.assimp_centre
                );
            }
        }
    }
    // every shipped .dae loads, including those no problem uses
    let mut all = files(&dir.join("2D"), "dae");
    all.extend(files(&dir.join("3D"), "dae"));
    for p in all {
        let m = load_collada(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        assert!(m.triangles_imported > 0);
    }
}

/// The README's problem table: start (x, y[, z]), rotation, goal, volume.
struct OmplProblem {
    cfg: &'static str,
    start: &'static [f64],
    start_rot: ([f64; 3], f64),
    goal: &'static [f64],
    goal_rot: ([f64; 3], f64),
    lower: &'static [f64],
    upper: &'static [f64],
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
// Abstract's goal angle is the cfg's literal 1.57079632679, not π/2.
#[allow(clippy::approx_constant)]
const OMPL_PROBLEMS: &[OmplProblem] = &[
    OmplProblem {
        cfg: "3D/Easy",
        start: &[270.0, 160.0, -200.0],
        start_rot: (X, 0.0),
        goal: &[270.0, 160.0, -400.0],
        goal_rot: (X, 0.0),
        lower: &[14.4604492188, -24.25, -504.855102539],
        upper: &[457.960449219, 321.25, -72.8550872803],
    },
    OmplProblem {
        cfg: "3D/Twistycool",
        start: &[270.0, 160.0, -200.0],
        start_rot: (X, 0.0),
        goal: &[270.0, 160.0, -400.0],
        goal_rot: (X, 0.0),
        lower: &[53.46, -21.25, -476.86],
        upper: &[402.96, 269.25, -91.0],
    },
    OmplProblem {
        cfg: "3D/cubicles",
        start: &[-4.96, -40.62, 70.57],
        start_rot: (X, 0.0),
        goal: &[200.0, -40.62, 70.57],
        goal_rot: (X, 0.0),
        lower: &[-508.88, -230.13, -123.75],
        upper: &[319.62, 531.87, 101.0],
    },
    OmplProblem {
        cfg: "3D/Home",
        start: &[252.95, -214.95, 46.19],
        start_rot: (X, 0.0),
        goal: &[262.95, 75.05, 46.19],
        goal_rot: (X, 0.0),
        lower: &[-383.802642822, -371.469055176, -0.196851730347],
        upper: &[324.997131348, 337.893371582, 142.332290649],
    },
    OmplProblem {
        cfg: "3D/Apartment",
        start: &[241.81, 106.15, 36.46],
        start_rot: ([0.0, 0.0, -1.0], 3.12413936107),
        goal: &[-31.19, -99.85, 36.46],
        goal_rot: ([0.0, 0.0, -1.0], 3.12413936107),
        lower: &[-73.76, -179.59, -0.03],
        upper: &[295.77, 168.26, 90.39],
    },
    OmplProblem {
        cfg: "3D/alpha-1.5",
        start: &[-21.91, -4.11, -14.14],
        start_rot: (X, 0.0),
        goal: &[-21.91, -4.11, 68.86],
        goal_rot: (X, 0.0),
        lower: &[-281.64, -119.64, -176.86],
        upper: &[189.05, 189.18, 174.86],
    },
    OmplProblem {
        cfg: "3D/bugtrap",
        start: &[17.18, 0.89, -4.62],
        start_rot: (X, 0.0),
        goal: &[45.18, 0.89, -4.62],
        goal_rot: (X, 0.0),
        lower: &[4.04, -44.49, -13.27],
        upper: &[56.99, 19.57, 15.27],
    },
    OmplProblem {
        cfg: "3D/Abstract",
        start: &[84.98, -60.0, 180.16],
        start_rot: (X, 0.0),
        goal: &[-121.02, 12.0, 153.16],
        goal_rot: (X, 1.57079632679),
        lower: &[-233.119232178, -222.197250366, -3.94512939453],
        upper: &[239.919021606, 250.73979187, 468.982696533],
    },
    OmplProblem {
        cfg: "2D/BugTrap_planar",
        start: &[7.02, -12.0],
        start_rot: (X, 0.0),
        goal: &[-36.98, -10.0],
        goal_rot: (X, 2.25147473507),
        lower: &[-55.0, -55.0103187561],
        upper: &[55.0, 55.01],
    },
    OmplProblem {
        cfg: "2D/Maze_planar",
        start: &[0.01, -0.15],
        start_rot: (X, 0.0),
        goal: &[41.01, -0.15],
        goal_rot: (X, 0.802851455917),
        lower: &[-55.0, -55.0],
        upper: &[55.0, 55.0],
    },
    OmplProblem {
        cfg: "2D/RandomPolygons_planar",
        start: &[-32.99, 42.85],
        start_rot: (X, 0.0),
        goal: &[14.01, -43.15],
        goal_rot: (X, 0.802851455917),
        lower: &[-55.0, -55.0006408691],
        upper: &[55.0, 54.9992599487],
    },
    OmplProblem {
        cfg: "2D/UniqueSolutionMaze",
        start: &[-43.95, -42.75],
        start_rot: (X, 0.0),
        goal: &[44.05, 45.25],
        goal_rot: (X, 0.0),
        lower: &[-50.36, -49.75],
        upper: &[49.6377944946, 50.206867218],
    },
    OmplProblem {
        cfg: "2D/Barriers",
        start: &[34.81, -75.0],
        start_rot: (X, 0.0),
        goal: &[620.0, -375.0],
        goal_rot: (X, -std::f64::consts::PI),
        lower: &[0.0, -440.22998046875],
        upper: &[661.0222778320312, 0.4874267578125],
    },
];

#[test]
fn ompl_problems_match_the_table() {
    let dir = root().join("scenes/ompl");
    for p in OMPL_PROBLEMS {
        let s = Scene::load(&dir.join(format!("{}.cfg", p.cfg)))
            .unwrap_or_else(|e| panic!("{}: {e}", p.cfg));
        let planar = p.start.len() == 2;
        assert_eq!(
            s.space.kind(),
            if planar {
                SpaceKind::Se2
            } else {
                SpaceKind::Se3
            },
            "{}",
            p.cfg
        );
        assert!(s.warnings.is_empty(), "{}: {:?}", p.cfg, s.warnings);
        let close = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
        };
        assert!(
            close(s.space.lower(), p.lower),
            "{}: lower {:?}",
            p.cfg,
            s.space.lower()
        );
        assert!(
            close(s.space.upper(), p.upper),
            "{}: upper {:?}",
            p.cfg,
            s.space.upper()
        );
        assert_eq!(s.queries.len(), 1);
        for (q, pos, (axis, theta)) in [
            (&s.queries[0].start, p.start, p.start_rot),
            (&s.queries[0].goal, p.goal, p.goal_rot),
        ] {
            assert!(close(&q[..pos.len()], pos), "{}: position {q:?}", p.cfg);
            if planar {
                // yaw in [-π, π): +π would be out of OMPL's SO(2) range
                let want = if theta >= std::f64::consts::PI {
                    theta - std::f64::consts::TAU
                } else {
                    theta
                };
                assert!((q[2] - want).abs() < 1e-12, "{}: yaw {}", p.cfg, q[2]);
            } else {
                let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
                let s2 = (theta / 2.0).sin() / n;
                let want = [
                    s2 * axis[0],
                    s2 * axis[1],
                    s2 * axis[2],
                    (theta / 2.0).cos(),
                ];
                assert!(close(&q[3..], &want), "{}: quaternion {:?}", p.cfg, &q[3..]);
            }
        }
        // the robot is centred on OMPL.app's centre: its reference point is the origin
        match &s.robot {
            Robot::Mesh(m) => {
                let (lo, hi) = m.aabb();
                assert!(
                    lo.coords.iter().all(|c| *c < 0.0) && hi.coords.iter().all(|c| *c > 0.0),
                    "{}",
                    p.cfg
                );
            }
            Robot::Polygons(parts) => assert!(!parts.is_empty()),
            Robot::Point | Robot::Arm(_) | Robot::Bodies(_) | Robot::MeshBodies(_) => {
                panic!("{}: not a rigid robot", p.cfg)
            }
        }
        assert!(s.space.rotation_scale() > 0.0);
    }
    // the Apartment example of the README: q = (0, 0, −0.99996192, 0.00872654)
    let a = Scene::load(&dir.join("3D/Apartment.cfg")).unwrap();
    let q = &a.queries[0].start[3..];
    assert!((q[2] + 0.99996192).abs() < 1e-8 && (q[3] - 0.00872654).abs() < 1e-8);
}

#[test]
fn every_shipped_cfg_loads_and_car_problems_warn() {
    let dir = root().join("scenes/ompl");
    let mut all = files(&dir.join("2D"), "cfg");
    all.extend(files(&dir.join("3D"), "cfg"));
    assert_eq!(all.len(), 17);
    for p in &all {
        let s = Scene::load(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let car = std::fs::read_to_string(p).unwrap().contains("control =");
        assert_eq!(
            s.warnings.iter().any(|w| w.contains("control problem")),
            car,
            "{}",
            p.display()
        );
        for q in &s.queries {
            assert!(s.space.in_bounds(&q.start) && s.space.in_bounds(&q.goal));
        }
    }
}

#[test]
fn ompl_cfg_conventions_on_a_small_problem() {
    let s = Scene::load(&data("tiny3d.cfg")).unwrap();
    assert_eq!(s.name, "tiny3d");
    assert_eq!(s.space.kind(), SpaceKind::Se3);
    // the volume grows to contain the goal (x = 20) but keeps its other sides
    assert_eq!(s.space.lower(), &[-10.0, -6.0, -10.0]);
    assert_eq!(s.space.upper(), &[20.0, 10.0, 10.0]);
    // axis (0, 0, 2) is normalised; θ = 1.2
    let q = &s.queries[0].start;
    assert!((q[5] - 0.6f64.sin()).abs() < 1e-12 && (q[6] - 0.6f64.cos()).abs() < 1e-12);
    // the robot is moved by assimp's centre
    let dae = load_collada(&data("octa_zup.dae")).unwrap();
    let Robot::Mesh(m) = &s.robot else { panic!() };
    let c = Vector3::from(dae.assimp_centre.map(f64::from));
    assert!((m.vertices[0] - (dae.mesh.vertices[0] - c)).norm() < 1e-12);
    let Obstacle::Mesh(world) = &s.obstacles[0] else {
        panic!()
    };
    assert_eq!(
        world.aabb(),
        (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0))
    );

    // 2D, no volume: the world's bounding box, grown to the start and goal; a car problem
    let s = Scene::load(&data("tiny2d.cfg")).unwrap();
    assert_eq!(s.space.kind(), SpaceKind::Se2);
    assert_eq!(s.name, "tiny2d");
    assert_eq!(s.space.lower(), &[-2.0, 0.0]);
    assert_eq!(s.space.upper(), &[3.0, 1.0]);
    assert!(s.warnings[0].contains("control = kinematic_car"));
    let (st, g) = (&s.queries[0].start, &s.queries[0].goal);
    assert!(
        (st[2] + std::f64::consts::PI).abs() < 1e-12,
        "π wraps to −π"
    );
    assert!((g[2] - (7.0 - std::f64::consts::TAU)).abs() < 1e-12);
    // the robot footprint is shifted by the centre with z zeroed
    let Robot::Polygons(parts) = &s.robot else {
        panic!()
    };
    let min_x = parts
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| v.x))
        .fold(f64::INFINITY, f64::min);
    assert!((min_x - (dae.mesh.aabb().0.x - dae.assimp_centre[0] as f64)).abs() < 1e-9);

    let e = Scene::load(&data("theta_without_axis.cfg")).unwrap_err();
    assert!(
        matches!(&e, SceneError::Invalid { message, .. } if message.contains("start.theta needs all of start.axis")),
        "{e:?}"
    );
    let e = Scene::load(&data("bad_number.cfg")).unwrap_err();
    assert!(
        matches!(&e, SceneError::Parse { message, .. } if message.contains("line 4") && message.contains("start.x")),
        "{e:?}"
    );
    let e = Scene::load(&data("no-such.cfg")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }));
    let e = Scene::load(&data("octa.obj").with_extension("cfg")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }));
}

#[test]
fn ompl_path_and_query_files() {
    let dir = root().join("scenes/ompl");
    for (cfg, path) in [
        ("3D/Easy.cfg", "3D/Easy.path"),
        ("3D/cubicles.cfg", "3D/cubicles.path"),
        ("3D/alpha-1.5.cfg", "3D/alpha-1.5.path"),
        ("2D/Maze_planar.cfg", "2D/Maze_planar.path"),
        ("2D/Barriers.cfg", "2D/Barriers.path"),
    ] {
        let s = Scene::load(&dir.join(cfg)).unwrap();
        let states = read_states(&dir.join(path), &s.space).unwrap();
        let lines = std::fs::read_to_string(dir.join(path))
            .unwrap()
            .lines()
            .filter(|l| !l.trim().is_empty())
            .count();
        assert_eq!(states.len(), lines, "{path}");
        assert!(states.iter().all(|q| s.space.in_bounds(q)), "{path}");
        // paths start at the problem's start
        assert!(
            s.space.distance(&states[0], &s.queries[0].start) < 1e-3,
            "{path}: {:?}",
            states[0]
        );
    }
    // Barriers.path ends at yaw +π, which is normalised to −π
    let s = Scene::load(&dir.join("2D/Barriers.cfg")).unwrap();
    let states = read_states(&dir.join("2D/Barriers.path"), &s.space).unwrap();
    assert!((states.last().unwrap()[2] + std::f64::consts::PI).abs() < 1e-9);
    for (cfg, file) in [
        ("3D/Home.cfg", "queries/Home_seed1_50.txt"),
        ("3D/cubicles.cfg", "queries/cubicles_seed1_50.txt"),
    ] {
        let s = Scene::load(&dir.join(cfg)).unwrap();
        let pairs = read_query_pairs(&dir.join(file), &s.space).unwrap();
        assert_eq!(pairs.len(), 50);
        for q in &pairs {
            assert!(s.space.in_bounds(&q.start) && s.space.in_bounds(&q.goal));
            let n: f64 = q.start[3..].iter().map(|v| v * v).sum();
            assert!((n - 1.0).abs() < 1e-12);
        }
    }
    // an R^3 space and a malformed file
    let r3 = Space::euclidean(vec![0.0; 3], vec![10.0; 3]).unwrap();
    assert_eq!(
        read_states(&data("states_r3.txt"), &r3).unwrap(),
        vec![vec![1.0, 2.0, 3.0], vec![4.0, 5.0, 6.5]]
    );
    let e = read_states(&data("states_bad.txt"), &r3).unwrap_err();
    assert!(
        matches!(&e, SceneError::Parse { message, .. } if message.contains("line 2") && message.contains("five")),
        "{e:?}"
    );
    let e = read_query_pairs(&data("states_r3.txt"), &r3).unwrap_err();
    assert!(
        matches!(&e, SceneError::Parse { message, .. } if message.contains("line 1") && message.contains("2 r3 states")),
        "{e:?}"
    );
}

/// Whether the robot placed at `q` touches the environment, by parry's triangle-mesh
/// intersection test (surfaces, as OMPL.app's FCL mesh–mesh check): independent of viaroad's
/// oracles, it checks the frame, centre and rotation conventions of the loader.
fn ompl_state_collides(scene: &Scene, q: &[f64]) -> bool {
    match &scene.robot {
        Robot::Mesh(robot) => {
            let shape = |m: &TriMesh| {
                parry3d_f64::shape::TriMesh::new(m.vertices.clone(), m.triangles.clone()).unwrap()
            };
            let Obstacle::Mesh(env) = &scene.obstacles[0] else {
                panic!()
            };
            let (r, e) = (shape(robot), shape(env));
            parry3d_f64::query::intersection_test(&pose3(q), &r, &Isometry3::identity(), &e)
                .unwrap()
        }
        Robot::Polygons(parts) => {
            let tri = |p: &viaroad::geometry::Polygon| p.vertices.clone();
            let env: Vec<Point2<f64>> = scene
                .obstacles
                .iter()
                .flat_map(|o| match o {
                    Obstacle::Polygon(p) => tri(p),
                    other => panic!("{other:?}"),
                })
                .collect();
            let indices: Vec<[u32; 3]> = (0..env.len() as u32 / 3)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            let env = parry2d_f64::shape::TriMesh::new(env, indices).unwrap();
            let at = Isometry2::new(Vector2::new(q[0], q[1]), q[2]);
            parts.iter().any(|p| {
                let t =
                    parry2d_f64::shape::Triangle::new(p.vertices[0], p.vertices[1], p.vertices[2]);
                parry2d_f64::query::intersection_test(&at, &t, &Isometry2::identity(), &env)
                    .unwrap()
            })
        }
        Robot::Point | Robot::Arm(_) | Robot::Bodies(_) | Robot::MeshBodies(_) => {
            panic!("not a rigid robot")
        }
    }
}

#[test]
fn ompl_starts_goals_and_path_states_are_free_under_parry() {
    let dir = root().join("scenes/ompl");
    for (cfg, path) in [
        ("3D/Easy.cfg", Some("3D/Easy.path")),
        ("3D/Twistycool.cfg", Some("3D/Twistycool.path")),
        ("3D/cubicles.cfg", Some("3D/cubicles.path")),
        ("3D/Apartment.cfg", Some("3D/Apartment.path")),
        ("3D/alpha-1.5.cfg", Some("3D/alpha-1.5.path")),
        ("3D/Home.cfg", None),
        ("3D/bugtrap.cfg", None),
        ("3D/Abstract.cfg", None),
        ("2D/BugTrap_planar.cfg", Some("2D/BugTrap_planar.path")),
        ("2D/Maze_planar.cfg", Some("2D/Maze_planar.path")),
        (
            "2D/RandomPolygons_planar.cfg",
            Some("2D/RandomPolygons_planar.path"),
        ),
        (
            "2D/UniqueSolutionMaze.cfg",
            Some("2D/UniqueSolutionMaze.path"),
        ),
        ("2D/Barriers.cfg", Some("2D/Barriers.path")),
    ] {
        let s = Scene::load(&dir.join(cfg)).unwrap();
        let mut states = vec![s.queries[0].start.clone(), s.queries[0].goal.clone()];
        if let Some(p) = path {
            states.extend(read_states(&dir.join(p), &s.space).unwrap());
        }
        for q in &states {
            assert!(!ompl_state_collides(&s, q), "{cfg}: {q:?} collides");
        }
        // the check is sensitive: moved by a quarter of the robot's radius, some state collides
        // (for the 3D problems; 2D footprints have room to spare in the open mazes)
        if cfg.starts_with("3D") && path.is_some() {
            let shift = 0.25 * s.space.rotation_scale();
            let collides = states.iter().any(|q| {
                [0, 1, 2].iter().any(|&i| {
                    let mut moved = q.clone();
                    moved[i] += shift;
                    ompl_state_collides(&s, &moved)
                })
            });
            assert!(collides, "{cfg}: no state collides when moved by {shift}");
        }
    }
}
