//! Trees grown out of a roadmap (`roadmap::rooted`): every path joins the two ends and is
//! re-checked by the independent disc checker (closest point of each segment to each centre);
//! both ends in one component answer through it without growing; the roadmap's nodes given to
//! a tree do not count against its node budget; without candidates the trees are exactly
//! those from the bare ends; the same seed gives the same path. A query that cannot join its
//! ends through the roadmap answers along such trees ([`QueryOptions::trees`]), checked the
//! same way.

use crate::roadmap_support;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use roadmap_support::*;
use viaroad::deadline::Deadline;
use viaroad::local::LocalSpec;
use viaroad::roadmap::rooted::RoadmapTrees;
use viaroad::roadmap::tree::{rrt_connect, TreeParams, TreeStop};
use viaroad::roadmap::{LearnParams, QueryOptions, QueryOutcome, QueryPlanner, Roadmap};
use viaroad::scene::Scene;
use viaroad::space::{Config, Group};

/// A cluttered disc scene and a sparse roadmap of it: some ends attach to it, some do not.
fn scene_and_roadmap() -> (Scene, Roadmap, Vec<Group>) {
    let scene = disc_scene(21, 45, 0.06);
    let local = LocalSpec::default();
    let roadmap = learn(&scene, &local, &LearnParams::default(), 40, 5).roadmap;
    let groups = local.build().groups(&scene.space);
    (scene, roadmap, groups)
}

/// Free start/goal pairs drawn uniformly (seeded), checked by the independent disc test.
fn pairs(scene: &Scene, n: usize) -> Vec<(Config, Config)> {
    let d = discs(scene);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut free = || loop {
        let p = vec![rng.random::<f64>(), rng.random::<f64>()];
        if point_free(&p, &d) {
            return p;
        }
    };
    (0..n).map(|_| (free(), free())).collect()
}

fn params(max_nodes: usize) -> TreeParams {
    TreeParams {
        max_nodes: Some(max_nodes),
        ..TreeParams::default()
    }
}

#[test]
fn paths_out_of_the_roadmap_are_free_and_join_the_ends() {
    let (scene, roadmap, groups) = scene_and_roadmap();
    let oracle = scene.oracle();
    let d = discs(&scene);
    let trees = RoadmapTrees::new(&roadmap, oracle.as_ref(), &groups);
    let (mut through, mut grown) = (0, 0);
    for (i, (s, g)) in pairs(&scene, 40).into_iter().enumerate() {
        let out = trees
            .connect(&s, &g, &params(4000), i as u64, &Deadline::none())
            .unwrap();
        let path = out
            .path
            .unwrap_or_else(|| panic!("pair {i} not joined: {:?}", out.stop));
        assert_eq!(out.stop, TreeStop::Connected);
        assert_eq!(
            (path.first(), path.last()),
            (Some(&s), Some(&g)),
            "pair {i}"
        );
        assert!(path_free(&path, &d), "pair {i}: the path collides");
        if out.extends == 0 {
            through += 1;
        } else {
            grown += 1;
        }
        let again = trees
            .connect(&s, &g, &params(4000), i as u64, &Deadline::none())
            .unwrap();
        assert_eq!(
            again.path.as_ref(),
            Some(&path),
            "pair {i}: same seed, same path"
        );
    }
    // both kinds happen on this sparse roadmap, so both are checked above
    assert!(through > 0 && grown > 0, "{through} through, {grown} grown");
}

#[test]
fn given_nodes_do_not_count_against_the_node_budget() {
    let (scene, roadmap, groups) = scene_and_roadmap();
    let oracle = scene.oracle();
    let trees = RoadmapTrees::new(&roadmap, oracle.as_ref(), &groups);
    let budget = 8;
    assert!(roadmap.node_count() > 2 * budget);
    let mut grew = 0;
    for (i, (s, g)) in pairs(&scene, 40).into_iter().enumerate() {
        let out = trees
            .connect(&s, &g, &params(budget), i as u64, &Deadline::none())
            .unwrap();
        // a tree given the roadmap's nodes would be over its budget before its first extend
        assert!(
            !(out.stop == TreeStop::NodeBudget && out.extends == 0),
            "pair {i}: the given nodes ate the budget: {out:?}"
        );
        if out.extends > 0 {
            grew += 1;
            assert!(out.nodes[0] >= 1 && out.nodes[1] >= 1, "pair {i}: {out:?}");
        }
    }
    assert!(grew > 0, "some pair needed the trees");
}

#[test]
fn without_candidates_the_trees_grow_from_the_bare_ends() {
    let (scene, roadmap, groups) = scene_and_roadmap();
    let oracle = scene.oracle();
    let bare = RoadmapTrees::new(&roadmap, oracle.as_ref(), &groups).with_candidates(0);
    for (i, (s, g)) in pairs(&scene, 10).into_iter().enumerate() {
        let p = params(3000);
        let ours = bare.connect(&s, &g, &p, 7, &Deadline::none()).unwrap();
        let plain = rrt_connect(
            &scene.space,
            oracle.as_ref(),
            &groups,
            &s,
            &g,
            &p,
            7,
            &Deadline::none(),
        )
        .unwrap();
        assert_eq!(ours.path, plain.path, "pair {i}");
        assert_eq!(ours.nodes, plain.nodes, "pair {i}");
        assert_eq!(ours.counts, plain.counts, "pair {i}");
    }
}

#[test]
fn queries_the_roadmap_cannot_join_answer_along_trees() {
    // straight lines as the local method: the via-point planner's attaching joins every pair
    // through the 40-node roadmap, straight lines leave some to the trees
    let scene = disc_scene(21, 45, 0.06);
    let straight = LocalSpec::Straight;
    let roadmap = learn(&scene, &straight, &LearnParams::default(), 40, 5).roadmap;
    let oracle = scene.oracle();
    let d = discs(&scene);
    let options = QueryOptions {
        grow: false,
        escalation_candidates: 0,
        trees: Some(params(4000)),
        ..QueryOptions::default()
    };
    let unshortened = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(QueryOptions {
            shorten: false,
            ..options.clone()
        });
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref())
        .unwrap()
        .with_options(options);
    let mut by_trees = 0;
    for (i, (s, g)) in pairs(&scene, 40).into_iter().enumerate() {
        let r = planner.query(&s, &g).unwrap();
        assert!(r.is_solved(), "pair {i}: {:?}", r.outcome);
        for path in [&r.raw_path, &r.path] {
            assert_eq!(
                (path.first(), path.last()),
                (Some(&s), Some(&g)),
                "pair {i}"
            );
            assert!(path_free(path, &d), "pair {i}: {:?} collides", r.outcome);
        }
        assert!(r.length <= r.raw_length + 1e-9, "pair {i}");
        if r.outcome == QueryOutcome::Trees {
            by_trees += 1;
            assert!(r.grown_nodes >= 2, "pair {i}: {r:?}");
            // without shortening the answer is the trees' path itself, and the same one
            let plain = unshortened.query(&s, &g).unwrap();
            assert_eq!(plain.outcome, QueryOutcome::Trees, "pair {i}");
            assert_eq!(plain.path, plain.raw_path, "pair {i}");
            assert_eq!(
                plain.raw_path, r.raw_path,
                "pair {i}: same seed, same trees"
            );
        }
    }
    assert!(
        by_trees > 0,
        "the sparse roadmap leaves some pair to the trees"
    );
}

/// Trees that keep the tree an end brought along answer every query exactly as trees that
/// build it afresh, from one start to many goals (the kept tree found again) and from
/// changing starts (the kept one replaced): the same paths, the same calls.
#[test]
fn a_kept_tree_answers_as_one_built_afresh() {
    use viaroad::roadmap::rooted::KeptTree;
    let (scene, roadmap, groups) = scene_and_roadmap();
    let oracle = scene.oracle();
    let d = discs(&scene);
    let kept = KeptTree::default();
    let keeping = RoadmapTrees::new(&roadmap, oracle.as_ref(), &groups).keeping(&kept);
    let afresh = RoadmapTrees::new(&roadmap, oracle.as_ref(), &groups);
    let all = pairs(&scene, 24);
    let start = all[0].0.clone();
    let mut grown = 0;
    for (i, (s, g)) in all.iter().enumerate() {
        // the first half from one start, the rest from their own
        let s = if i < 12 { &start } else { s };
        let ask = |trees: &RoadmapTrees| {
            trees
                .connect(s, g, &params(4000), i as u64, &Deadline::none())
                .unwrap()
        };
        let (a, b) = (ask(&keeping), ask(&afresh));
        assert_eq!(a.path, b.path, "pair {i}");
        assert_eq!(a.counts, b.counts, "pair {i}");
        if let Some(path) = &a.path {
            assert!(path_free(path, &d), "pair {i}: the path collides");
        }
        grown += usize::from(a.extends > 0);
    }
    assert!(grown > 0, "no pair grew trees");
}
