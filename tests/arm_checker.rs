//! The Panda and the shipped MotionBenchMaker problems (scenes/arms/): MoveIt YAML loading,
//! and the independent arm checker against the OMPL peer's verdicts (OMPL 1.5.2 + FCL 0.7,
//! recorded by tests/data/arms/peer_verdicts.py): start/goal validity of all 21 problems and
//! 280 seeded uniform configurations, with their colliding pairs; and the peer's RRTConnect
//! paths in tests/data/arms/paths/, from `ompl_peer arm URDF SRDF SCENE REQUEST --planner
//! rrtconnect --time 10 --seed 1 --save-path P` (run 0), checked by the peer with
//! `ompl_peer armcheck … --resolution 0.001 --request REQUEST`.

use serde::Deserialize;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{Arm, ArmChecker, Contact};
use viaroad::scene::moveit::{
    load_motion_plan_request, load_planning_scene, ObjectShape, PlanningScene,
};

use crate::common;
use common::arms::arms_dir;

fn panda() -> Arm {
    common::arms::panda(GroupChoice::Srdf("panda_arm".into()))
}

/// The arm put into a scene, and the checker of both.
fn in_scene(scene: &str) -> (PlanningScene, Arm, ArmChecker) {
    let s = load_planning_scene(&arms_dir().join(scene)).unwrap();
    let mut arm = panda();
    s.apply_to(&mut arm).unwrap();
    let checker = ArmChecker::new(&arm, &s.objects).unwrap();
    (s, arm, checker)
}

#[derive(Deserialize)]
struct Verdicts {
    problems: Vec<Problem>,
    states: Vec<State>,
}

#[derive(Deserialize)]
struct Problem {
    scene: String,
    request: String,
    start_valid: bool,
    start_collisions: Vec<String>,
    goal_valid: bool,
    goal_collisions: Vec<String>,
}

#[derive(Deserialize)]
struct State {
    scene: String,
    q: Vec<f64>,
    valid: bool,
    collisions: Vec<String>,
}

fn verdicts() -> Verdicts {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/arms/peer_verdicts.json"),
    )
    .unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Pairs as unordered `a~b` strings, the peer's spelling.
fn pair_set<'a>(pairs: impl IntoIterator<Item = (&'a str, &'a str)>) -> BTreeSet<String> {
    pairs
        .into_iter()
        .map(|(a, b)| {
            if a < b {
                format!("{a}~{b}")
            } else {
                format!("{b}~{a}")
            }
        })
        .collect()
}

fn peer_set(pairs: &[String]) -> BTreeSet<String> {
    pair_set(pairs.iter().map(|p| p.split_once('~').unwrap()))
}

#[test]
fn shipped_scenes_and_requests_load() {
    let families = [
        "table_pick",
        "table_under_pick",
        "box",
        "bookshelf_small",
        "bookshelf_tall",
        "bookshelf_thin",
        "cage",
    ];
    for f in families {
        for i in 1..=3 {
            let scene =
                load_planning_scene(&arms_dir().join(format!("mbm/{f}/scene{i:04}.yaml"))).unwrap();
            assert!(!scene.objects.is_empty(), "{f} {i}");
            assert_eq!(
                scene.allowed.len(),
                34,
                "{f} {i}: the ACM allows the SRDF's 34 pairs"
            );
            let req =
                load_motion_plan_request(&arms_dir().join(format!("mbm/{f}/request{i:04}.yaml")))
                    .unwrap();
            assert_eq!(req.group, "panda_arm");
            let mut arm = panda();
            scene.apply_to(&mut arm).unwrap();
            let (start, goal) = req.start_goal(&mut arm).unwrap();
            assert_eq!((start.len(), goal.len()), (7, 7));
            assert!(
                arm.group.in_bounds(&start) && arm.group.in_bounds(&goal),
                "{f} {i}"
            );
        }
    }
    // table_pick 1: 12 objects, 10 boxes and 2 cylinders (the peer's arminfo)
    let s = load_planning_scene(&arms_dir().join("mbm/table_pick/scene0001.yaml")).unwrap();
    let parts: Vec<&ObjectShape> = s
        .objects
        .iter()
        .flat_map(|o| o.parts.iter().map(|p| &p.1))
        .collect();
    assert_eq!(parts.len(), 12);
    let cylinders = parts
        .iter()
        .filter(|p| {
            matches!(
                p,
                ObjectShape::Primitive(viaroad::robot::Primitive::Cylinder { .. })
            )
        })
        .count();
    assert_eq!(cylinders, 2);
}

#[test]
fn start_and_goal_validity_agree_with_the_ompl_peer() {
    let v = verdicts();
    assert_eq!(v.problems.len(), 21);
    for p in &v.problems {
        let (_, mut arm, _) = in_scene(&p.scene);
        let req = load_motion_plan_request(&arms_dir().join(&p.request)).unwrap();
        let (start, goal) = req.start_goal(&mut arm).unwrap();
        // the request's start state may move non-group joints: check with that arm
        let scene = load_planning_scene(&arms_dir().join(&p.scene)).unwrap();
        let checker = ArmChecker::new(&arm, &scene.objects).unwrap();
        for (q, valid, pairs, what) in [
            (&start, p.start_valid, &p.start_collisions, "start"),
            (&goal, p.goal_valid, &p.goal_collisions, "goal"),
        ] {
            let ours = checker.collisions(q);
            assert_eq!(
                pair_set(ours.iter().map(|c| (c.a.as_str(), c.b.as_str()))),
                peer_set(pairs),
                "{} {what}",
                p.request
            );
            assert_eq!(checker.is_valid(q), valid, "{} {what}", p.request);
        }
    }
}

#[test]
fn uniform_configurations_agree_with_the_ompl_peer() {
    let v = verdicts();
    let mut checkers: HashMap<String, ArmChecker> = HashMap::new();
    let (mut invalid, mut self_hits, mut world_hits) = (0, 0, 0);
    let mut contained = Vec::new();
    for s in &v.states {
        let checker = checkers
            .entry(s.scene.clone())
            .or_insert_with(|| in_scene(&s.scene).2);
        let ours = checker.collisions(&s.q);
        // surface contacts are what FCL sees; a containment (one solid wholly inside the
        // other) is a collision FCL's surface-only meshes miss
        let surface = pair_set(
            ours.iter()
                .filter(|c| c.contact == Contact::Surface)
                .map(|c| (c.a.as_str(), c.b.as_str())),
        );
        assert_eq!(surface, peer_set(&s.collisions), "{} {:?}", s.scene, s.q);
        let held: Vec<_> = ours
            .iter()
            .filter(|c| c.contact == Contact::Containment)
            .collect();
        if !held.is_empty() {
            contained.push((
                s.q.clone(),
                held.iter()
                    .map(|c| format!("{}~{}", c.a, c.b))
                    .collect::<Vec<_>>(),
            ));
        }
        assert_eq!(
            checker.is_valid(&s.q),
            s.valid && held.is_empty(),
            "{} {:?}",
            s.scene,
            s.q
        );
        if !s.valid {
            invalid += 1;
            let links = checker.arm().model.urdf.links.len();
            let is_link = |n: &str| (0..links).any(|l| checker.arm().model.urdf.links[l].name == n);
            self_hits += ours.iter().filter(|c| is_link(&c.b)).count();
            world_hits += ours.iter().filter(|c| !is_link(&c.b)).count();
        }
    }
    // the sample holds both kinds of collision, so agreement is not agreement on "free"
    assert!(invalid >= 40, "{invalid}");
    assert!(self_hits > 0 && world_hits > 0, "{self_hits} {world_hits}");
    // the containments of the sample: the left finger folded wholly inside link 5 or link 2
    // (surfaces apart, so the peer reports the state free of that pair); confirmed below by
    // ray parity, sharing nothing with parry's containment test
    let found: Vec<_> = contained.iter().map(|(_, p)| p.clone()).collect();
    assert_eq!(
        found,
        [
            ["panda_link5~panda_leftfinger"],
            ["panda_link2~panda_leftfinger"]
        ]
    );
    let (_, arm, _) = in_scene("mbm/box/scene0001.yaml");
    for (q, pairs) in &contained {
        let (outer, inner) = pairs[0].split_once('~').unwrap();
        let poses = arm.link_poses(q);
        let mesh_of = |name: &str| {
            let l = arm.model.link(name).unwrap();
            let s = arm.shapes.iter().find(|s| s.link == l).unwrap();
            (poses[l] * s.origin, s.polytope.clone())
        };
        let (po, mo) = mesh_of(outer);
        let (pi, mi) = mesh_of(inner);
        for v in &mi.vertices {
            let local = po.inverse() * (pi * v);
            assert!(inside_by_parity(&mo, &local), "{pairs:?} {v:?}");
        }
    }
}

/// Whether `p` lies inside a closed mesh: the number of triangles a ray from `p` crosses is
/// odd (Möller–Trumbore; the direction is skewed so that it meets no edge of these meshes).
fn inside_by_parity(mesh: &viaroad::geometry::TriMesh, p: &nalgebra::Point3<f64>) -> bool {
    let dir = nalgebra::Vector3::new(0.5771, 0.5774, 0.5779);
    let crossings = (0..mesh.triangles.len())
        .filter(|&k| {
            let [a, b, c] = mesh.triangle(k);
            let (e1, e2) = (b - a, c - a);
            let h = dir.cross(&e2);
            let det = e1.dot(&h);
            if det.abs() < 1e-15 {
                return false;
            }
            let s = p - a;
            let u = s.dot(&h) / det;
            let qv = s.cross(&e1);
            let v = dir.dot(&qv) / det;
            let t = e2.dot(&qv) / det;
            (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && t > 0.0
        })
        .count();
    crossings % 2 == 1
}

#[test]
fn paths_are_checked_segment_by_segment() {
    let (_, arm, checker) = in_scene("mbm/cage/scene0001.yaml");
    let v = verdicts();
    let free: Vec<&State> = v
        .states
        .iter()
        .filter(|s| s.scene == "mbm/cage/scene0001.yaml" && s.valid)
        .collect();
    let hit = v
        .states
        .iter()
        .find(|s| s.scene == "mbm/cage/scene0001.yaml" && !s.valid)
        .unwrap();
    // free → colliding: the first bad sample lies on segment 0, at the latest at its end
    let path = vec![free[0].q.clone(), hit.q.clone()];
    let r = checker.check_path(&path, 0.0134).unwrap();
    assert!(!r.valid);
    let (seg, t, pairs) = r.first_invalid.unwrap();
    assert_eq!(seg, 0);
    assert!(t > 0.0 && t <= 1.0 && !pairs.is_empty());
    // a path that stays at one free configuration is valid
    let r = checker
        .check_path(&[free[0].q.clone(), free[0].q.clone()], 0.0134)
        .unwrap();
    assert!(r.valid && r.samples == 2);
    // a path leaving the bounds is invalid without collisions
    let mut out = free[0].q.clone();
    out[3] = arm.group.upper[3] + 0.5;
    let r = checker.check_path(&[out], 0.0134).unwrap();
    assert_eq!(r.first_invalid, Some((0, 0.0, Vec::new())));
    // bad input is an error
    assert!(checker.check_path(&[vec![0.0; 6]], 0.01).is_err());
    assert!(checker.check_path(&path, 0.0).is_err());
}

/// RRTConnect paths of the OMPL peer (`ompl_peer arm --planner rrtconnect --seed 1`, saved
/// with 17 digits) re-checked along every segment. At OMPL's default resolution (1 % of the
/// extent) all pass, as they did for the peer; at 1/10 of it the cage 3 path fails on segment
/// 8 near t = 0.478 (the right finger through `side_frontA`), exactly where the peer's
/// `armcheck --resolution 0.001` puts it: the check the issue asks every returned path to pass.
#[test]
fn peer_paths_pass_at_ompl_resolution_and_one_fails_at_a_tenth() {
    let read = |name: &str| -> Vec<Vec<f64>> {
        let p = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/arms/paths")
            .join(name);
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
            .collect()
    };
    for (name, scene, fine_valid) in [
        (
            "table_pick_0001_rrtconnect.path",
            "mbm/table_pick/scene0001.yaml",
            true,
        ),
        (
            "bookshelf_thin_0002_rrtconnect.path",
            "mbm/bookshelf_thin/scene0002.yaml",
            true,
        ),
        ("box_0001_rrtconnect.path", "mbm/box/scene0001.yaml", true),
        (
            "cage_0003_rrtconnect.path",
            "mbm/cage/scene0003.yaml",
            false,
        ),
    ] {
        let (_, arm, checker) = in_scene(scene);
        let path = read(name);
        let extent = arm.group.max_extent();
        let coarse = checker.check_path(&path, 0.01 * extent).unwrap();
        assert!(coarse.valid, "{name}: {:?}", coarse.first_invalid);
        let fine = checker.check_path(&path, 0.001 * extent).unwrap();
        assert_eq!(fine.valid, fine_valid, "{name}: {:?}", fine.first_invalid);
        assert!(fine.samples > 5 * coarse.samples, "{name}");
        if !fine_valid {
            let (seg, t, pairs) = fine.first_invalid.unwrap();
            assert_eq!(seg, 8);
            assert!((t - 0.478).abs() < 0.01, "{t}");
            assert_eq!(
                pair_set(pairs.iter().map(|c| (c.a.as_str(), c.b.as_str()))),
                peer_set(&["panda_rightfinger~side_frontA".to_string()])
            );
        }
    }
}

/// The convex-hull cull changes no verdict: at the peer's sampled configurations, and along
/// the segments between consecutive ones (where links graze obstacles and each other), the
/// checker finds exactly the collisions, surface or containment, that it finds testing every
/// pair's shapes themselves ([`ArmChecker::without_hulls`]).
#[test]
fn the_hull_cull_changes_no_verdict() {
    let v = verdicts();
    let mut checkers: HashMap<String, (ArmChecker, ArmChecker)> = HashMap::new();
    let (mut asked, mut colliding) = (0, 0);
    for w in v.states.windows(2) {
        let (culled, reference) = checkers.entry(w[0].scene.clone()).or_insert_with(|| {
            let c = in_scene(&w[0].scene).2;
            (c.clone(), c.without_hulls())
        });
        let steps = if w[0].scene == w[1].scene { 8 } else { 0 };
        for k in 0..=steps {
            let t = k as f64 / 8.0;
            let q: Vec<f64> = w[0]
                .q
                .iter()
                .zip(&w[1].q)
                .map(|(a, b)| a + t * (b - a))
                .collect();
            let ours = culled.collisions(&q);
            assert_eq!(ours, reference.collisions(&q), "{} {q:?}", w[0].scene);
            asked += 1;
            colliding += usize::from(!ours.is_empty());
        }
    }
    assert!(
        asked >= 300 && colliding >= 50 && colliding < asked,
        "{colliding} of {asked}"
    );
}
