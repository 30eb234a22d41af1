//! Planning for arms end to end: arm TOML scenes, the joint space, the via-point
//! planner and the roadmap on the Panda, every path re-checked by the independent
//! [`ArmChecker`] (parry, exact primitives, sharing no code with the exact oracle) sampled at
//! 1/10 of OMPL's default motion-check resolution (1 % of the space's extent → 0.1 %).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};
use viaroad::deadline::Deadline;
use viaroad::local::{shorten, LocalSpec};
use viaroad::roadmap::{
    Budget, LearnParams, Learner, QueryError, QueryPlanner, Roadmap, RoadmapError,
};
use viaroad::robot::ArmChecker;
use viaroad::scene::{Robot, Scene, SceneError};
use viaroad::space::SpaceKind;

fn arms(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/arms")
        .join(p)
}

fn checker(scene: &Scene) -> ArmChecker {
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    ArmChecker::new(&a.arm, &a.objects).unwrap()
}

/// Re-checks a path: starts and ends where asked, and free under the independent checker at
/// 1/10 of OMPL's default resolution along the straight line of each segment (one joint per
/// segment, CHS §1.5, or a shortening's straight shortcut of several).
fn certify(scene: &Scene, path: &[Vec<f64>], start: &[f64], goal: &[f64]) {
    assert!(path.len() >= 2);
    assert_eq!(path.first().unwrap().as_slice(), start);
    let end = path.last().unwrap();
    assert!(scene.space.distance(end, goal) < 1e-9, "{end:?} ≠ {goal:?}");
    let c = checker(scene);
    let step = 0.001 * c.arm().group.max_extent();
    let report = c.check_path(path, step).unwrap();
    assert!(report.valid, "the checker refuses the path: {report:?}");
    assert!(report.samples > path.len());
}

#[test]
fn an_arm_scene_loads_into_the_joint_space() {
    let scene = Scene::load(&arms("panda-table_pick-1.toml")).unwrap();
    assert_eq!(
        scene.space.kind(),
        SpaceKind::Joints {
            dof: 7,
            continuous: 0
        }
    );
    assert_eq!(scene.space.groups(false).len(), 7);
    assert_eq!(scene.queries.len(), 1);
    let c = checker(&scene);
    assert!(c.is_valid(&scene.queries[0].start));
    assert!(c.is_valid(&scene.queries[0].goal));
    // the fingerprint tells the environments apart, and is stable across loads
    let again = Scene::load(&arms("panda-table_pick-1.toml")).unwrap();
    let other = Scene::load(&arms("panda-cage-1.toml")).unwrap();
    assert_eq!(scene.fingerprint(), again.fingerprint());
    assert_ne!(scene.fingerprint(), other.fingerprint());
}

#[test]
fn the_viapoint_planner_solves_a_panda_problem_and_the_checker_agrees() {
    let scene = Scene::load(&arms("panda-table_pick-1.toml")).unwrap();
    let q = &scene.checked_queries().unwrap()[0];
    let oracle = scene.oracle();
    let method = LocalSpec::default().build();
    let mut c = method
        .connect_within(
            &scene.space,
            oracle.as_ref(),
            &q.start,
            &q.goal,
            &Deadline::none(),
        )
        .unwrap();
    assert!(c.is_connected());
    certify(&scene, &c.path, &q.start, &q.goal);
    let groups = method.groups(&scene.space);
    let short = shorten(
        &scene.space,
        oracle.as_ref(),
        &groups,
        &c.path,
        &mut c.counts,
    )
    .unwrap();
    certify(&scene, &short, &q.start, &q.goal);
    let len = |p: &[Vec<f64>]| {
        p.windows(2)
            .map(|w| scene.space.distance(&w[0], &w[1]))
            .sum::<f64>()
    };
    assert!(len(&short) <= len(&c.path) + 1e-9);
}

#[test]
fn a_roadmap_round_trips_answers_and_refuses_another_scene() {
    let scene = Scene::load(&arms("panda-table_pick-1.toml")).unwrap();
    let q = scene.checked_queries().unwrap()[0].clone();
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(40), 3, &mut |_| {})
        .unwrap();
    let bytes = learnt.roadmap.to_bytes().unwrap();
    let loaded = Roadmap::from_bytes(&bytes, scene.fingerprint()).unwrap();
    assert_eq!(loaded.to_bytes().unwrap(), bytes);
    // every node is valid for the independent checker
    let c = checker(&scene);
    for n in loaded.nodes() {
        assert!(c.is_valid(n), "roadmap node {n:?} collides");
    }
    let planner = QueryPlanner::new(&loaded, oracle.as_ref()).unwrap();
    let r = planner.query(&q.start, &q.goal).unwrap();
    assert!(r.is_solved(), "{:?}", r.outcome);
    certify(&scene, &r.path, &q.start, &q.goal);
    certify(&scene, &r.raw_path, &q.start, &q.goal);
    // the same roadmap for the cage scene is refused
    let cage = Scene::load(&arms("panda-cage-1.toml")).unwrap();
    assert!(matches!(
        Roadmap::from_bytes(&bytes, cage.fingerprint()),
        Err(RoadmapError::ForeignScene { .. })
    ));
}

#[test]
fn a_start_in_collision_is_a_clear_error() {
    let scene = Scene::load(&arms("panda-table_pick-1.toml")).unwrap();
    let c = checker(&scene);
    let g = &c.arm().group;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    // a configuration the independent checker finds in collision (the oracle's shapes contain
    // the true ones, so it must find it in collision too)
    let bad = loop {
        let q: Vec<f64> = (0..g.dof())
            .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
            .collect();
        if !c.collisions(&q).is_empty() {
            break q;
        }
    };
    let goal = scene.checked_queries().unwrap()[0].goal.clone();
    let oracle = scene.oracle();
    assert!(matches!(
        scene.check_config(oracle.as_ref(), "start", &bad),
        Err(SceneError::InCollision { .. })
    ));
    let text = format!(
        "[space]\nkind = \"arm\"\n[robot]\nurdf = \"panda/panda.urdf\"\nsrdf = \"panda/panda.srdf\"\n\
         [environment]\nmoveit_scene = \"mbm/table_pick/scene0001.yaml\"\n\
         [[query]]\nstart = {bad:?}\ngoal = {goal:?}\n"
    );
    let s = viaroad::scene::toml_format::from_str(&text, &arms("inline.toml")).unwrap();
    let e = s.checked_queries().unwrap_err();
    assert!(matches!(e, SceneError::InCollision { .. }), "{e}");
    assert!(e.to_string().contains("start of query 1"), "{e}");
    // a roadmap query refuses it too
    let method = LocalSpec::roadmap_default().build();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(5), 1, &mut |_| {})
        .unwrap();
    let planner = QueryPlanner::new(&learnt.roadmap, oracle.as_ref()).unwrap();
    assert!(matches!(
        planner.query(&bad, &goal),
        Err(QueryError::InCollision { .. })
    ));
}

#[test]
fn bad_arm_scenes_are_refused() {
    let base = "[space]\nkind = \"arm\"\n[robot]\nurdf = \"panda/panda.urdf\"\nsrdf = \"panda/panda.srdf\"\n";
    for (extra, why) in [
        ("colour = 1\n", "unknown key"),
        ("fixed = { panda_joint1 = 0.1 }\n", "group joint fixed"),
        ("group = [\"nope\"]\n", "unknown joint"),
        ("group = [\"panda_joint1\"]\n", "one joint"),
        (
            "[[query]]\nmoveit_request = \"mbm/table_pick/request0001.yaml\"\nstart = [0]\n",
            "both forms of query",
        ),
        ("[[query]]\nstart = [0, 0]\ngoal = [0, 0]\n", "wrong length"),
        (
            "[environment]\nmoveit_scene = \"missing.yaml\"\n",
            "missing file",
        ),
    ] {
        // bare keys land in [robot]
        let text = format!("{base}{extra}");
        let r = viaroad::scene::toml_format::from_str(&text, &arms("inline.toml"));
        assert!(r.is_err(), "{why}: accepted");
    }
}

#[test]
fn yes_no_and_first_hit_agree_with_the_intervals() {
    let scene = Scene::load(&arms("panda-bookshelf_small-1.toml")).unwrap();
    let oracle = scene.oracle();
    let c = checker(&scene);
    let g = &c.arm().group;
    let groups = scene.space.groups(false);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut free, mut blocked) = (0, 0);
    while free + blocked < 24 {
        let q: Vec<f64> = (0..g.dof())
            .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
            .collect();
        if !c.is_valid(&q) {
            continue;
        }
        let j = rng.random_range(0..g.dof());
        let mut z = q.clone();
        z[j] = rng.random_range(g.lower[j]..=g.upper[j]);
        let mut m = scene.space.group_motion(&q, &z, &groups[j]);
        // every other one a borderline: the unbounded line along the joint, clipped to its limits
        if (free + blocked) % 2 == 1 {
            m = scene.space.line_through(&q, &groups[j], &[1.0]);
        }
        let mut counts = viaroad::oracle::CallCounts::default();
        let all = oracle.intervals(&m, &mut counts).unwrap();
        let yes = oracle.motion_is_free(&m, &mut counts).unwrap();
        let first = oracle.first_collision(&m, &mut counts).unwrap();
        if m.range.is_bounded() {
            assert_eq!(yes, all.is_empty(), "{m:?}");
        }
        match (first, all.first()) {
            (None, None) => free += 1,
            (Some(t), Some(iv)) => {
                assert!(t == iv.lo || (t - iv.lo).abs() < 1e-9, "{t} vs {iv:?}");
                blocked += 1;
            }
            other => panic!("first collision {other:?} for {m:?}"),
        }
    }
    assert!(free > 0 && blocked > 0, "{free} free, {blocked} blocked");
}

/// Kept answers (`ArmCollision` answers a repeated move with what it answered before, the
/// via-point search's repeats) are the arm oracle's answers: the same intervals, yes/no and
/// first hit, bit for bit, on first asking and on every repeat, as an oracle that keeps
/// nothing, in either order of asking (a kept answer of one question that says the move is
/// free answers the others), static checks included; and a move that differs in the last bit
/// is asked anew.
#[test]
fn kept_answers_are_the_oracles_answers() {
    use viaroad::oracle::CollisionOracle;
    use viaroad::scene::arm::ArmCollision;
    let scene = Scene::load(&arms("panda-box-1.toml")).unwrap();
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    let keeping = ArmCollision::new(a.arm_oracle().clone());
    // asked the other way round: a kept yes or "no first hit" answers the other questions
    let reversed = ArmCollision::new(a.arm_oracle().clone());
    let fresh = ArmCollision::new(a.arm_oracle().clone()).with_kept_answers(false);
    let c = checker(&scene);
    let g = &c.arm().group;
    let groups = scene.space.groups(false);
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut motions = Vec::new();
    while motions.len() < 60 {
        let q: Vec<f64> = (0..g.dof())
            .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
            .collect();
        let j = rng.random_range(0..g.dof());
        let (mut q, mut z) = (q.clone(), q);
        if motions.len() % 2 == 0 {
            z[j] = rng.random_range(g.lower[j]..=g.upper[j]);
        } else {
            // the joint over its whole range, as the via-point search's borderlines
            (q[j], z[j]) = (g.lower[j], g.upper[j]);
        }
        motions.push(scene.space.group_motion(&q, &z, &groups[j]));
        // the same move again at once, and one whose end differs in the last bit
        motions.push(scene.space.group_motion(&q, &z, &groups[j]));
        z[j] = f64::from_bits(z[j].to_bits() + 1);
        motions.push(scene.space.group_motion(&q, &z, &groups[j]));
    }
    let mut counts = viaroad::oracle::CallCounts::default();
    let (mut hits, mut static_hits) = (0, 0);
    for round in 0..2 {
        for m in &motions {
            let want = fresh.intervals(m, &mut counts).unwrap();
            hits += usize::from(!want.is_empty() && round == 0);
            assert_eq!(
                keeping.intervals(m, &mut counts).unwrap().as_slice(),
                want.as_slice()
            );
            assert_eq!(
                keeping.motion_is_free(m, &mut counts).unwrap(),
                fresh.motion_is_free(m, &mut counts).unwrap()
            );
            assert_eq!(
                keeping.first_collision(m, &mut counts).unwrap(),
                fresh.first_collision(m, &mut counts).unwrap()
            );
            let first = reversed.first_collision(m, &mut counts).unwrap();
            let free = reversed.motion_is_free(m, &mut counts).unwrap();
            let all = reversed.intervals(m, &mut counts).unwrap();
            assert_eq!(first, fresh.first_collision(m, &mut counts).unwrap());
            assert_eq!(free, want.is_empty());
            assert_eq!(all.as_slice(), want.as_slice());
            // static checks are kept too, by the configuration's bits
            let q = &m.origin;
            let hit = fresh.collides(q, &mut counts);
            static_hits += usize::from(hit && round == 0);
            assert_eq!(keeping.collides(q, &mut counts), hit);
        }
    }
    assert!(hits >= 9, "{hits}");
    assert!(static_hits >= 3, "{static_hits}");
}

/// A path that moves the Panda's 7 joints one at a time turns 7 corners per diagonal step:
/// the greedy pass before the visibility graph starts above 112 corners for it (32 per two
/// groups, `QueryOptions::exact_shortening_limit`), so the answers with up to 112 corners are
/// the exact shortening's, and some of those have more than 32.
#[test]
fn arm_paths_of_up_to_112_corners_are_shortened_exactly() {
    use viaroad::roadmap::QueryOptions;
    let scene = Scene::load(&arms("panda-box-1.toml")).unwrap();
    let oracle = scene.oracle();
    // direct-path edges (a staircase of one move per joint each): answers of many corners
    let method = LocalSpec::Straight.build();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(200), 3, &mut |_| {})
        .unwrap();
    let roadmap = &learnt.roadmap;
    let fast = QueryPlanner::new(roadmap, oracle.as_ref()).unwrap();
    let exact = QueryPlanner::new(roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            exact_shortening_limit: usize::MAX,
            ..QueryOptions::default()
        });
    let nodes: Vec<Vec<f64>> = roadmap.nodes().map(<[f64]>::to_vec).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut above_32 = 0;
    for _ in 0..60 {
        let (s, g) = (
            &nodes[rng.random_range(0..nodes.len())],
            &nodes[rng.random_range(0..nodes.len())],
        );
        if s == g {
            continue;
        }
        let a = fast.query(s, g).unwrap();
        if !a.is_solved() || a.raw_path.len() > 112 {
            continue;
        }
        let b = exact.query(s, g).unwrap();
        assert_eq!(a.raw_path, b.raw_path);
        assert_eq!(a.path, b.path, "{} corners", a.raw_path.len());
        certify(&scene, &a.path, s, g);
        above_32 += usize::from(a.raw_path.len() > 32);
    }
    assert!(above_32 > 0, "no answer of more than 32 corners to compare");
}
