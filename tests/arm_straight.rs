//! Straight motions of several joints at once (`ArmOracle::straight_free`, conservative
//! advancement): every motion the oracle proves free is free under the independent
//! [`ArmChecker`] (parry, exact primitives, sampled at 1/10 of OMPL's resolution), the proof
//! is not vacuous (short motions in the open are proved, motions through the box are not),
//! and a query's answer shortened with them is certified and shorter than with staircases
//! alone.

use crate::common;

use common::arms::certify;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;
use viaroad::local::{path_length, LocalSpec};
use viaroad::oracle::CallCounts;
use viaroad::roadmap::tree::TreeParams;
use viaroad::roadmap::{Budget, LearnParams, Learner, QueryOptions, QueryPlanner};
use viaroad::robot::{ArmChecker, PathReport};
use viaroad::scene::{Robot, Scene};

fn box_scene() -> Scene {
    Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda-box-1.toml"))
        .unwrap()
}

/// `count` straight motions of the box scene, from free samples to free `target(index, q0,
/// rng)`: every one the oracle proves free must pass the independent checker. How many it
/// proved, and the checker's report of each one it refused.
fn proofs_under_the_checker(
    seed: u64,
    count: usize,
    target: impl Fn(usize, &Scene, &[f64], &mut ChaCha8Rng) -> Vec<f64>,
) -> (usize, Vec<PathReport>) {
    let scene = box_scene();
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    let oracle = a.arm_oracle();
    let checker = ArmChecker::new(&a.arm, &a.objects).unwrap();
    let step = 0.001 * checker.arm().group.max_extent();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut proved, mut refused) = (0, Vec::new());
    let mut counts = CallCounts::default();
    // free and within the checker's joint limits
    let free = |q: &[f64]| {
        let at = [q.to_vec(), q.to_vec()];
        checker.check_path(&at, step).unwrap().valid
    };
    while proved + refused.len() < count {
        let q0 = scene.space.sample_uniform(&mut rng);
        if !free(&q0) {
            continue;
        }
        let q1 = target(proved + refused.len(), &scene, &q0, &mut rng);
        if !free(&q1) {
            continue;
        }
        let path = [q0.clone(), q1.clone()];
        let report = checker.check_path(&path, step).unwrap();
        if oracle.straight_free(&q0, &q1, &mut counts).unwrap() {
            assert!(
                report.valid,
                "proved free, the checker refuses it: {path:?} {report:?}"
            );
            proved += 1;
        } else {
            refused.push(report);
        }
    }
    assert_eq!(counts.segment_calls, count as u64);
    (proved, refused)
}

#[test]
fn a_straight_motion_proved_free_is_free_under_the_independent_checker() {
    // motions of every length: a few hundredths of a radian to across the space
    let (proved, refused) = proofs_under_the_checker(7, 240, |i, scene, q0, rng| {
        common::arms::near(scene, q0, [0.05, 0.2, 0.8, 3.0][i % 4], rng)
    });
    let blocked_refused = refused.iter().filter(|r| !r.valid).count();
    assert!(proved >= 40, "only {proved} of 240 motions proved free");
    assert!(
        blocked_refused >= 10,
        "only {blocked_refused} blocked motions met"
    );
}

/// Motions of the wrist alone bring the hand and the last links against the fifth link: a
/// self pair's proof grows its covers only by how far the joints between the two links move
/// them, so it meets near contacts here. Every motion proved free is free under the checker,
/// and self collisions are met and refused.
#[test]
fn a_wrist_motion_proved_free_keeps_the_hand_off_the_forearm() {
    // the last three joints anywhere in their ranges, the others as they are
    let (proved, refused) = proofs_under_the_checker(11, 160, |_, scene, q0, rng| {
        let (lo, hi) = (scene.space.lower(), scene.space.upper());
        let mut q1 = q0.to_vec();
        for i in 4..7 {
            q1[i] = rng.random_range(lo[i]..=hi[i]);
        }
        q1
    });
    let own = |name: &str| name.starts_with("panda_");
    let self_blocked = refused
        .iter()
        .filter_map(|r| r.first_invalid.as_ref())
        .filter(|(_, _, c)| c.iter().any(|c| own(&c.a) && own(&c.b)))
        .count();
    assert!(
        proved >= 30,
        "only {proved} of 160 wrist motions proved free"
    );
    assert!(self_blocked >= 5, "only {self_blocked} self collisions met");
}

#[test]
fn an_answer_shortened_with_straight_motions_is_certified_and_shorter() {
    let scene = box_scene();
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let roadmap = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(60), 1, &mut |_| {})
        .unwrap()
        .roadmap;
    let groups = method.groups(&scene.space);
    let q = &scene.checked_queries().unwrap()[0];
    let answer = |straight: bool| {
        let options = QueryOptions {
            straight_shortcuts: straight,
            trees: Some(TreeParams {
                max_nodes: Some(3000),
                ..TreeParams::for_space(&scene.space)
            }),
            max_calls: Some(20_000),
            landmarks: 0,
            ..QueryOptions::default()
        };
        let asked = scene.oracle();
        let planner = QueryPlanner::new(&roadmap, asked.as_ref())
            .unwrap()
            .with_options(options);
        let a = planner.query(&q.start, &q.goal).unwrap();
        assert!(a.is_solved(), "{:?}", a.outcome);
        certify(&scene, &a.path);
        a.path
    };
    let stairs = answer(false);
    let straight = answer(true);
    let moving = |p: &[Vec<f64>]| {
        p.windows(2)
            .map(|w| w[0].iter().zip(&w[1]).filter(|(a, b)| a != b).count())
            .max()
            .unwrap_or(0)
    };
    assert_eq!(moving(&stairs), 1, "staircases move one joint at a time");
    assert!(moving(&straight) > 1, "no straight shortcut taken");
    let (ls, lt) = (
        path_length(&scene.space, &groups, &stairs),
        path_length(&scene.space, &groups, &straight),
    );
    assert!(lt < ls, "straight {lt} is not shorter than staircases {ls}");
}

#[test]
fn tree_extends_go_straight_where_proved_and_the_tree_path_is_certified() {
    // the box's query (the goal inside the box) by the two trees alone, with straight extends
    // of all joints (`TreeParams::straight`, the default) and with staircases only: both raw
    // paths pass the independent checker, only the first moves several joints at once, and
    // it costs fewer calls and nodes
    let scene = box_scene();
    let oracle = scene.oracle();
    let groups = scene.space.groups(false);
    let q = &scene.checked_queries().unwrap()[0];
    let grow = |straight: bool| {
        let params = TreeParams {
            max_nodes: Some(20_000),
            straight,
            ..TreeParams::for_space(&scene.space)
        };
        let found = viaroad::roadmap::tree::rrt_connect(
            &scene.space,
            oracle.as_ref(),
            &groups,
            &q.start,
            &q.goal,
            &params,
            1,
            &viaroad::deadline::Deadline::none(),
        )
        .unwrap();
        let path = found.path.clone().expect("the trees connect");
        certify(&scene, &path);
        (found, path)
    };
    let moving = |p: &[Vec<f64>]| {
        p.windows(2)
            .map(|w| w[0].iter().zip(&w[1]).filter(|(a, b)| a != b).count())
            .max()
            .unwrap_or(0)
    };
    let (stairs, stairs_path) = grow(false);
    let (straight, straight_path) = grow(true);
    assert_eq!(
        moving(&stairs_path),
        1,
        "staircases move one joint at a time"
    );
    assert!(moving(&straight_path) > 1, "no straight extend on the path");
    let size = |o: &viaroad::roadmap::tree::TreeOutcome| o.nodes[0] + o.nodes[1];
    assert!(
        size(&straight) < size(&stairs),
        "straight extends grew {} nodes, staircases {}",
        size(&straight),
        size(&stairs)
    );
}

/// Asserts that every edge of `path` that moves several joints is a straight motion the
/// scene's arm oracle proves free; how many such edges there are.
fn straight_edges_are_proved(scene: &Scene, path: &[Vec<f64>]) -> usize {
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    let arm_oracle = a.arm_oracle();
    let mut counts = CallCounts::default();
    let mut several = 0;
    for w in path.windows(2) {
        let moved = w[0].iter().zip(&w[1]).filter(|(x, y)| x != y).count();
        several += usize::from(moved > 1);
        assert!(
            moved <= 1 || arm_oracle.straight_free(&w[0], &w[1], &mut counts).unwrap(),
            "an edge of several joints is not a proved straight motion: {w:?}"
        );
    }
    several
}

#[test]
fn without_staircases_every_tree_edge_is_one_proved_straight_motion() {
    // the box's query by the two trees alone, an extend whose straight motion is not proved
    // given up (`TreeParams::staircase` off, as the arm portfolio's trees): the raw path passes
    // the independent checker, and each of its edges is one straight motion the oracle proves
    // free (no staircase corners between the extends' ends)
    let scene = box_scene();
    let params = TreeParams {
        max_nodes: Some(20_000),
        staircase: false,
        ..TreeParams::for_space(&scene.space)
    };
    let found = common::tree::grow(&scene, &params, 1);
    let path = found.path.expect("the trees connect");
    certify(&scene, &path);
    assert!(
        straight_edges_are_proved(&scene, &path) > 0,
        "no straight edge on the path"
    );
}

#[test]
fn a_straight_proof_stops_at_a_watched_deadline() {
    // a query's deadline reaches into a proof in progress (as into an exact sweep): an
    // interrupted proof is an error, not a "not proved" to be kept as the motion's answer
    let scene = box_scene();
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    let oracle = a.arm_oracle();
    let q = &scene.checked_queries().unwrap()[0];
    // a short motion from the start, inside the box: nothing surely hit, a proof to run
    let near: Vec<f64> = q.start.iter().map(|x| x + 0.02).collect();
    let mut counts = CallCounts::default();
    let passed = viaroad::deadline::Deadline::none().within(Some(std::time::Duration::ZERO));
    let stopped = viaroad::deadline::watching(&passed, || {
        oracle.straight_free(&q.start, &near, &mut counts)
    });
    assert!(
        matches!(stopped, Err(viaroad::robot::RobotError::Interrupted)),
        "{stopped:?}"
    );
    assert!(oracle.straight_free(&q.start, &near, &mut counts).unwrap());
}

#[test]
fn dynamic_domains_keep_tree_paths_certified_and_draw_samples_again_without_calls() {
    // the cage's query by the arm's trees alone (`TreeParams::for_space`: proved straight
    // extends, dynamic domains), seeds 1–6, against the same trees without domains: every raw
    // path passes the independent checker, a seed gives the same path twice, and the samples a
    // domain draws again cost no calls (fewer calls over the seeds)
    use viaroad::roadmap::tree::TreeOutcome;
    let scene =
        Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda-cage-1.toml"))
            .unwrap();
    let arm = TreeParams {
        max_nodes: Some(20_000),
        ..TreeParams::for_space(&scene.space)
    };
    assert!(arm.domain.is_some(), "an arm's trees sample in domains");
    let grow = |params: &TreeParams, seed: u64| -> TreeOutcome {
        let found = common::tree::grow(&scene, params, seed);
        certify(&scene, found.path.as_ref().expect("the trees connect"));
        found
    };
    let everywhere = TreeParams {
        domain: None,
        ..arm.clone()
    };
    let (mut with, mut without) = (0, 0);
    for seed in 1..=6 {
        let a = grow(&arm, seed);
        assert_eq!(a.path, grow(&arm, seed).path, "seed {seed}");
        with += a.counts.intersect_calls();
        without += grow(&everywhere, seed).counts.intersect_calls();
    }
    assert!(
        with < without,
        "{with} calls with domains, {without} without"
    );
}

#[test]
fn arm_trees_out_of_a_roadmap_attach_by_proved_straight_motions() {
    // trees out of a sparse roadmap of the box scene, as an arm's queries grow them (no
    // staircases): the path passes the independent checker and every edge of several joints,
    // the ends' attachments among them, is a straight motion the oracle proves free
    use viaroad::roadmap::rooted::RoadmapTrees;
    let scene = box_scene();
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(&LearnParams::default(), &Budget::nodes(30), 1, &mut |_| {})
        .unwrap();
    let groups = method.groups(&scene.space);
    let q = &scene.checked_queries().unwrap()[0];
    let params = TreeParams {
        max_nodes: Some(20_000),
        ..TreeParams::for_space(&scene.space)
    };
    let found = RoadmapTrees::new(&learnt.roadmap, oracle.as_ref(), &groups)
        .connect(
            &q.start,
            &q.goal,
            &params,
            1,
            &viaroad::deadline::Deadline::none(),
        )
        .unwrap();
    let path = found.path.expect("the trees connect");
    certify(&scene, &path);
    let (first, last) = (&path[..2], &path[path.len() - 2..]);
    assert!(
        straight_edges_are_proved(&scene, &path) > 0,
        "no straight edge on the path"
    );
    let straight = |w: &[Vec<f64>]| w[0].iter().zip(&w[1]).filter(|(x, y)| x != y).count() > 1;
    assert!(
        straight(first) || straight(last),
        "neither end attached or grew by a straight motion"
    );
}
