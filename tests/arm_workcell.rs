//! The workcell mode of `bench mbm`: one roadmap of a family's first scene,
//! saved and loaded back, answering every request valid in that scene; where the roadmap does
//! not answer in half the query time, two trees do (out of the roadmap, or from the bare
//! ends), or they race it from the start. Every
//! answer is re-checked by the independent [`viaroad::robot::ArmChecker`] inside
//! `run_workcell`; this test holds it to that. With answers kept, every edge they add to the
//! roadmap is re-checked here by the same checker.

use std::path::{Path, PathBuf};
use std::time::Duration;
use viaroad::bench::mbm::{
    check_step, checker, find_problems, load_robot, problem_scene, run_workcell, Problem,
    WorkcellOptions,
};
use viaroad::roadmap::tree::{Prefix, Stairs, TreeParams};
use viaroad::roadmap::{Budget, Roadmap};
use viaroad::robot::Arm;

/// The shipped Panda, the shipped problems of `family`, and a fresh directory for the files of
/// the test `test` (tests run at once and remove their directories).
fn family(family: &str, test: &str) -> (Arm, Vec<Problem>, PathBuf) {
    let arms = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let robot = load_robot(&arms.join("panda")).unwrap();
    let problems = find_problems(&arms.join("mbm").join(family), None).unwrap();
    let dir = std::env::temp_dir().join(format!(
        "viaroad-arm-workcell-{family}-{test}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    (robot, problems, dir)
}

#[test]
fn every_workcell_answer_is_certified_with_the_trees_behind_or_beside_the_roadmap() {
    // the box: its requests need the trees (the 40-node roadmap grown for half the query time
    // did not reach in), which answer each in ≈ 1.4 s of their 4 s on the 2-core VM;
    // the cage needed ≈ 5 s of trees, more than a test should spend
    let (robot, problems, dir) = family("box", "modes");
    let trees = TreeParams {
        prefix: Prefix::FirstHit,
        stairs: Stairs::Whole,
        balance: true,
        max_nodes: Some(3000),
        ..TreeParams::default()
    };
    let modes = [(None, true), (Some(Duration::ZERO), true), (None, false)];
    for (race, trees_from_roadmap) in modes {
        let options = WorkcellOptions {
            budget: Budget::nodes(40),
            seed: 1,
            query_time: Duration::from_secs(8),
            trees: Some(trees.clone()),
            race,
            keep_answers: false,
            keep_trees: false,
            trees_from_roadmap,
            straight: true,
            train: Vec::new(),
            exact_shortening_limit: 32,
        };
        let r = run_workcell(&robot, &problems, &options, &dir.join("box.roadmap")).unwrap();
        assert_eq!(r.requests, 3);
        assert!(r.valid >= 1, "the first request is valid in its own scene");
        assert!(r.solved <= r.valid && r.by_trees <= r.solved);
        assert!(r.solved >= 1, "the box is answered (race {race:?}): {r:?}");
        assert_eq!(r.certified, r.solved, "race {race:?}: {r:?}");
        // the 40-node roadmap does not reach into the box: the trees answer (in turn out of
        // the roadmap inside the query, `QueryOptions::trees`; racing; from the bare ends)
        assert!(
            r.by_trees >= 1,
            "race {race:?}, from roadmap {trees_from_roadmap}: {r:?}"
        );
        assert_eq!(r.query_ms.n, r.valid);
        assert_eq!((r.latencies_ms.len(), r.calls.len()), (r.valid, r.valid));
        // the time found is the latency less the answer's shortening
        assert_eq!((r.found_ms.n, r.shorten_ms.len()), (r.valid, r.valid));
        for (t, s) in r.latencies_ms.iter().zip(&r.shorten_ms) {
            assert!((0.0..=*t).contains(s), "shortening {s} ms of {t} ms");
        }
        assert!(
            r.shorten_ms.iter().any(|&s| s > 0.0),
            "answers are shortened"
        );
        assert!(r.found_ms.p50 <= r.query_ms.p50);
        // every answer's length as found and as returned, never longer once shortened
        assert_eq!((r.raw_length.n, r.length.n), (r.solved, r.solved));
        assert!(r.length.min > 0.0 && r.length.p50 <= r.raw_length.p50 + 1e-9);
        assert!(r.length.max <= r.raw_length.max + 1e-9, "{r:?}");
        assert_eq!(
            (r.kept, r.nodes_after),
            (0, r.nodes),
            "nothing kept unless asked"
        );
        assert!(dir.join("box.roadmap").exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn every_edge_a_kept_answer_adds_is_certified() {
    let (robot, problems, dir) = family("table_pick", "kept");
    let options = WorkcellOptions {
        budget: Budget::nodes(40),
        seed: 1,
        query_time: Duration::from_secs(4),
        trees: None,
        race: None,
        keep_answers: true,
        keep_trees: false,
        trees_from_roadmap: true,
        straight: true,
        train: Vec::new(),
        exact_shortening_limit: 32,
    };
    let r = run_workcell(&robot, &problems, &options, &dir.join("table_pick.roadmap")).unwrap();
    assert_eq!((r.latencies_ms.len(), r.calls.len()), (r.valid, r.valid));
    assert!(
        r.solved >= 2,
        "the shipped table_pick requests are answered: {r:?}"
    );
    assert_eq!(r.certified, r.solved, "{r:?}");
    assert_eq!(r.kept, r.solved, "every answer is kept");
    let scene = problem_scene(&robot, &problems[0]).unwrap();
    let learnt = Roadmap::load(&dir.join("table_pick.roadmap"), scene.fingerprint()).unwrap();
    let kept = Roadmap::load(&dir.join("table_pick.roadmap.kept"), scene.fingerprint()).unwrap();
    assert_eq!(kept.node_count(), r.nodes_after);
    assert!(kept.node_count() > learnt.node_count() && kept.edge_count() > learnt.edge_count());
    assert_eq!(&kept.coords()[..learnt.coords().len()], learnt.coords());
    let check = checker(&scene).unwrap();
    for (e, edge) in kept.edges().iter().enumerate().skip(learnt.edge_count()) {
        let report = check
            .check_path(&kept.edge_path(e, edge.a), check_step(&check))
            .unwrap();
        assert!(report.valid, "kept edge {e}: {report:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn kept_trees_add_certified_edges_beyond_the_answer() {
    // the box's requests are answered by trees out of the 40-node roadmap (above); kept with
    // their trees, every extend's end becomes a node and every edge is certified
    let (robot, problems, dir) = family("box", "kept-trees");
    let trees = TreeParams {
        max_nodes: Some(3000),
        ..TreeParams::default()
    };
    let run = |keep_trees: bool| {
        let options = WorkcellOptions {
            budget: Budget::nodes(40),
            seed: 1,
            query_time: Duration::from_secs(8),
            trees: Some(trees.clone()),
            race: None,
            keep_answers: true,
            keep_trees,
            trees_from_roadmap: true,
            straight: true,
            train: Vec::new(),
            exact_shortening_limit: 32,
        };
        let name = format!("box-{keep_trees}.roadmap");
        let r = run_workcell(&robot, &problems, &options, &dir.join(&name)).unwrap();
        assert!(r.by_trees >= 1, "keep trees {keep_trees}: {r:?}");
        assert_eq!(r.certified, r.solved, "keep trees {keep_trees}: {r:?}");
        (r, dir.join(name + ".kept"))
    };
    let (paths_only, _) = run(false);
    let (with_trees, kept_file) = run(true);
    // the first request is asked of the same roadmap either way, so its trees are the same
    assert!(
        with_trees.nodes_after > paths_only.nodes_after,
        "the trees' ends are kept beside the answers: {with_trees:?} against {paths_only:?}"
    );
    let scene = problem_scene(&robot, &problems[0]).unwrap();
    let learnt = Roadmap::load(&dir.join("box-true.roadmap"), scene.fingerprint()).unwrap();
    let kept = Roadmap::load(&kept_file, scene.fingerprint()).unwrap();
    assert_eq!(kept.node_count(), with_trees.nodes_after);
    assert_eq!(&kept.coords()[..learnt.coords().len()], learnt.coords());
    let check = checker(&scene).unwrap();
    let mut with_corners = 0;
    for (e, edge) in kept.edges().iter().enumerate().skip(learnt.edge_count()) {
        let path = kept.edge_path(e, edge.a);
        with_corners += usize::from(path.len() > 2);
        let report = check.check_path(&path, check_step(&check)).unwrap();
        assert!(report.valid, "kept edge {e}: {report:?}");
    }
    assert!(
        with_corners > 0,
        "an extend's stairs are kept as one edge through their corners"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_workcell_trained_on_example_requests_keeps_certified_edges_and_answers_them() {
    // the box's goals lie inside it: the 40-node roadmap reaches none, trees answer them.
    // Trained on the family's requests (offline, before the roadmap is saved), the saved
    // roadmap holds their answers and trees, every added edge certified, and a request asked
    // again attaches inside the box: no tree grows for it.
    let (robot, problems, dir) = family("box", "train");
    let options = WorkcellOptions {
        budget: Budget::nodes(40),
        seed: 1,
        query_time: Duration::from_secs(8),
        trees: Some(TreeParams {
            max_nodes: Some(3000),
            ..TreeParams::default()
        }),
        race: Some(Duration::from_millis(2)),
        keep_answers: false,
        keep_trees: false,
        trees_from_roadmap: true,
        straight: true,
        train: problems.clone(),
        exact_shortening_limit: 0,
    };
    let r = run_workcell(&robot, &problems, &options, &dir.join("box.roadmap")).unwrap();
    assert!(r.train_valid >= 1, "{r:?}");
    assert_eq!(r.train_kept, r.train_valid, "every example answered: {r:?}");
    assert_eq!(r.train_valid, r.valid, "the same requests: {r:?}");
    assert!(r.nodes > r.sampled_nodes, "{r:?}");
    assert_eq!((r.solved, r.certified), (r.valid, r.valid), "{r:?}");
    assert_eq!(
        r.by_trees, 0,
        "each request attaches to its kept answer: {r:?}"
    );
    let scene = problem_scene(&robot, &problems[0]).unwrap();
    let trained = Roadmap::load(&dir.join("box.roadmap"), scene.fingerprint()).unwrap();
    assert_eq!(trained.node_count(), r.nodes);
    let check = checker(&scene).unwrap();
    assert!(trained.edge_count() > r.sampled_edges);
    for (e, edge) in trained.edges().iter().enumerate().skip(r.sampled_edges) {
        let report = check
            .check_path(&trained.edge_path(e, edge.a), check_step(&check))
            .unwrap();
        assert!(report.valid, "trained edge {e}: {report:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
