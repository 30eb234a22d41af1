//! The direct paths of queries: an arm's, and those a race's head start asks alone.

use super::*;
use crate::roadmap::{Budget, LearnParams, Learner};
use crate::scene::Scene;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The scene at `rel` (from the crate's folder) and a roadmap of it learnt to `nodes` nodes
/// (seed 1) with the roadmap's default local method.
fn scene_and_roadmap(rel: &str, nodes: usize) -> (Scene, Roadmap) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    let scene = Scene::load(&path).unwrap();
    let oracle = scene.oracle();
    let method = LocalSpec::roadmap_default().build();
    let learnt = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .learn(
            &LearnParams::default(),
            &Budget::nodes(nodes),
            1,
            &mut |_| {},
        )
        .unwrap();
    (scene, learnt.roadmap)
}

/// Where an arm's straight motion between two free configurations is asked and not proved, the
/// direct path is that one call: the single-joint staircase, whose corners the sure test does
/// not refuse, is not swept (its exact sweeps cost most of a query the roadmap answers).
#[test]
fn an_arm_direct_path_not_proved_straight_costs_one_call() {
    let (scene, roadmap) = scene_and_roadmap("scenes/arms/panda-cage-1.toml", 5);
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    let space = planner.space();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut free = || loop {
        let q = space.sample_uniform(&mut rng);
        if oracle.is_free(&q, &mut CallCounts::default()) {
            return q;
        }
    };
    let (mut blocked, mut straight) = (0, 0);
    for _ in 0..300 {
        let (a, z) = (free(), free());
        let pieces = direct_pieces(space, &planner.groups, 0, &a, &z);
        if surely_blocked(oracle.as_ref(), &pieces) {
            continue;
        }
        let mut result = QueryResult::unanswered(a.clone(), z.clone(), CallCounts::default());
        let c = planner
            .straight_or_blocked(&a, &z, &mut result, &Deadline::none())
            .unwrap()
            .expect("the straight motion is asked");
        assert_eq!(result.counts.intersect_calls(), 1, "{a:?} → {z:?}");
        if c.is_connected() {
            assert_eq!(c.path, vec![a.clone(), z.clone()], "one straight motion");
            straight += 1;
        } else {
            blocked += 1;
        }
    }
    assert!(
        blocked >= 20,
        "{blocked} not proved straight (and {straight} proved)"
    );
}

/// A race's head start asks the direct paths alone ([`Stages::Direct`]): what they answer is the
/// whole search's answer, and where they do not, the whole search goes on with the local
/// method's searches, which answer some of those queries (a sparse roadmap among discs: half of
/// the sixteen each way).
#[test]
fn the_direct_stages_answer_as_the_whole_search_or_leave_it_the_rest() {
    let (scene, roadmap) = scene_and_roadmap("scenes/discs-cluttered.toml", 12);
    let oracle = scene.oracle();
    let options = QueryOptions {
        time: Some(std::time::Duration::from_millis(300)),
        ..QueryOptions::default()
    };
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(options);
    let space = planner.space();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut free = || loop {
        let q = space.sample_uniform(&mut rng);
        if oracle.is_free(&q, &mut CallCounts::default()) {
            return q;
        }
    };
    let none = Deadline::none();
    let (mut direct, mut searched) = (0, 0);
    for _ in 0..16 {
        let (a, z) = (free(), free());
        let ask = |stages| {
            planner
                .search(&a, &z, (&none, &none), None, stages)
                .unwrap()
        };
        let (d, all) = (ask(Stages::Direct), ask(Stages::All));
        if d.is_solved() {
            assert_eq!(d.path, all.path, "{a:?} → {z:?}");
            direct += 1;
        } else {
            assert!(
                d.counts.intersect_calls() <= all.counts.intersect_calls(),
                "{a:?} → {z:?}"
            );
            searched += usize::from(all.is_solved());
        }
    }
    assert!(direct > 0, "no query answered by the direct paths");
    assert!(searched > 0, "no query left to the local method's searches");
}
