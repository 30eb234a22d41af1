//! Shards and merges: shards reproducible and distinct, merges independent of the parts'
//! order and of the thread count, merged roadmaps valid (every node and edge re-checked by the
//! independent disc checker) and answering every query a part answers, parts of another scene
//! or local method refused, merges of merges, and a base that keeps its node indices.

use crate::common::cli::{fails_with, stderr, stdout, temp_dir, viaroad};
use crate::roadmap_support;

use roadmap_support::*;
use viaroad::deadline::Deadline;
use viaroad::local::LocalSpec;
use viaroad::roadmap::{
    Budget, LearnParams, Learner, MergeError, MergeStop, Merged, QueryOptions, QueryPlanner,
    Roadmap, Shard,
};
use viaroad::scene::Scene;

fn scene() -> Scene {
    disc_scene(31, 40, 0.06)
}

/// Shard `i` of `n` of seed 4, a node budget of `nodes` between the shards.
fn shard(scene: &Scene, i: u64, n: u64, nodes: usize) -> Roadmap {
    let oracle = scene.oracle();
    let local = LocalSpec::roadmap_default().build();
    Learner::for_scene(scene, oracle.as_ref(), local.as_ref())
        .learn_shard(
            &LearnParams::default(),
            &Budget::nodes(nodes),
            (4, Shard::new(i, n).unwrap()),
            &Deadline::none(),
            &mut |_| {},
        )
        .expect("learning succeeds")
        .roadmap
}

fn merge(scene: &Scene, base: Option<&Roadmap>, parts: &[&Roadmap]) -> Result<Merged, MergeError> {
    let oracle = scene.oracle();
    let local = LocalSpec::roadmap_default().build();
    Learner::for_scene(scene, oracle.as_ref(), local.as_ref()).merge(
        base,
        parts,
        &Deadline::none(),
        &mut |_| {},
    )
}

fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

fn bytes(r: &Roadmap) -> Vec<u8> {
    r.to_bytes().unwrap()
}

/// The same `(seed, I, N)` gives the same shard on any thread count; other shards draw other
/// nodes; the shards' node budgets add up to the whole.
#[test]
fn shards_are_reproducible_and_distinct() {
    let s = scene();
    let a = on_threads(1, || shard(&s, 2, 3, 240));
    let b = on_threads(2, || shard(&s, 2, 3, 240));
    assert_eq!(bytes(&a), bytes(&b));
    let other = shard(&s, 1, 3, 240);
    let wider = shard(&s, 2, 4, 240);
    assert_ne!(a.header().seed, other.header().seed);
    assert_ne!(a.header().seed, wider.header().seed);
    let nodes = |r: &Roadmap| r.nodes().map(<[f64]>::to_vec).collect::<Vec<_>>();
    let shared = nodes(&a)
        .iter()
        .filter(|q| nodes(&other).contains(q))
        .count();
    assert_eq!(shared, 0, "two shards drew the same node");
    assert_eq!(a.header().node_budget, Some(80));
    // shard 1 of 1 is the unsharded build
    assert_eq!(bytes(&shard(&s, 1, 1, 100)), {
        let l = learn(
            &s,
            &LocalSpec::roadmap_default(),
            &LearnParams::default(),
            100,
            4,
        );
        bytes(&l.roadmap)
    });
}

/// Merging the same parts in any order, on any thread count, gives the same bytes; the merged
/// roadmap holds every part's nodes and edges, every node free and every edge free by the
/// independent checker, and its components are those a breadth-first search finds.
#[test]
fn merge_is_order_independent_and_valid() {
    let s = scene();
    let d = discs(&s);
    let parts: Vec<Roadmap> = (1..=3).map(|i| shard(&s, i, 3, 450)).collect();
    let orders = [[0, 1, 2], [2, 0, 1], [1, 2, 0]];
    let mut seen = Vec::new();
    for (k, order) in orders.iter().enumerate() {
        let refs: Vec<&Roadmap> = order.iter().map(|&i| &parts[i]).collect();
        let merged = on_threads(1 + k % 2, || merge(&s, None, &refs).unwrap());
        assert_eq!(merged.report.stop, MergeStop::Complete);
        seen.push((bytes(&merged.roadmap), merged.roadmap.digest().unwrap()));
    }
    assert!(
        seen.windows(2).all(|w| w[0] == w[1]),
        "order changed the merge"
    );

    let refs: Vec<&Roadmap> = parts.iter().collect();
    let m = merge(&s, None, &refs).unwrap();
    let r = &m.roadmap;
    roadmap_valid(r, &d).unwrap();
    assert_eq!(bfs_labels(r), r.component_labels());
    for (p, ids) in parts.iter().zip(&m.node_ids) {
        for (i, q) in p.nodes().enumerate() {
            assert_eq!(r.node(ids[i]), q);
        }
        for e in p.edges() {
            let (a, b) = (ids[e.a as usize], ids[e.b as usize]);
            assert!(
                r.edges()
                    .iter()
                    .any(|f| (f.a, f.b) == (a, b) || (f.a, f.b) == (b, a)),
                "an edge of a part is missing"
            );
        }
    }
    let before = parts.iter().map(Roadmap::component_count).sum::<usize>();
    assert!(
        r.component_count() < before,
        "the merge joined no components ({before} before)"
    );
    assert!(m.report.connected > 0);
    let calls = m.report.counts.intersect_calls();
    let total: u64 = parts
        .iter()
        .map(|p| p.header().counts.intersect_calls())
        .sum();
    assert_eq!(r.header().counts.intersect_calls(), total + calls);
}

/// Every query a part answers through its roadmap, the merged roadmap answers too, with a path
/// the independent checker finds free.
#[test]
fn merged_answers_what_any_part_answers() {
    let s = scene();
    let d = discs(&s);
    let oracle = s.oracle();
    let parts: Vec<Roadmap> = (1..=2).map(|i| shard(&s, i, 2, 300)).collect();
    let refs: Vec<&Roadmap> = parts.iter().collect();
    let merged = merge(&s, None, &refs).unwrap().roadmap;
    let options = QueryOptions {
        try_direct: false,
        grow: false,
        ..QueryOptions::default()
    };
    let planner = |r| {
        QueryPlanner::new(r, oracle.as_ref())
            .unwrap()
            .with_options(options.clone())
    };
    let on_merged = planner(&merged);
    let mut answered = 0;
    for (s0, g0) in random_queries(&s, 60, 12) {
        let by_part = parts
            .iter()
            .any(|p| planner(p).query(&s0, &g0).unwrap().is_solved());
        let r = on_merged.query(&s0, &g0).unwrap();
        if by_part {
            answered += 1;
            assert!(
                r.is_solved(),
                "{s0:?} → {g0:?}: a part answers, the merge not"
            );
        }
        if r.is_solved() {
            for path in [&r.raw_path, &r.path] {
                assert!(path_free(path, &d), "{path:?} collides");
                assert_eq!(path.first(), Some(&s0));
                assert_eq!(path.last(), Some(&g0));
            }
        }
    }
    assert!(answered >= 30, "only {answered} of 60 answered by a part");
}

/// Parts of another scene or another local method are refused, naming the part.
#[test]
fn foreign_parts_are_refused() {
    let s = scene();
    let mine = shard(&s, 1, 2, 100);
    let other_scene = disc_scene(32, 40, 0.06);
    let foreign = shard(&other_scene, 2, 2, 100);
    match merge(&s, None, &[&mine, &foreign]) {
        Err(MergeError::ForeignScene { part: 1, .. }) => {}
        other => panic!("expected ForeignScene for part 1, got {other:?}"),
    }
    let straight = learn(&s, &LocalSpec::Straight, &LearnParams::default(), 100, 3).roadmap;
    match merge(&s, Some(&mine), &[&straight]) {
        Err(MergeError::OtherLocalMethod { part: 1, .. }) => {}
        other => panic!("expected OtherLocalMethod for part 1, got {other:?}"),
    }
    assert!(matches!(merge(&s, None, &[]), Err(MergeError::NoParts)));
}

/// A merge of merges is a roadmap like any other: valid, holding every shard's nodes, the same
/// whichever order its two halves come in; merging a part that is already in is a no-op on the
/// graph.
#[test]
fn merges_of_merges() {
    let s = scene();
    let d = discs(&s);
    let parts: Vec<Roadmap> = (1..=4).map(|i| shard(&s, i, 4, 480)).collect();
    let left = merge(&s, None, &[&parts[0], &parts[1]]).unwrap().roadmap;
    let right = merge(&s, None, &[&parts[2], &parts[3]]).unwrap().roadmap;
    let top = merge(&s, None, &[&left, &right]).unwrap();
    let swapped = merge(&s, None, &[&right, &left]).unwrap();
    assert_eq!(bytes(&top.roadmap), bytes(&swapped.roadmap));
    roadmap_valid(&top.roadmap, &d).unwrap();
    for p in &parts {
        for q in p.nodes() {
            assert!(
                top.roadmap.nodes().any(|n| n == q),
                "a shard's node is lost"
            );
        }
    }
    let again = merge(&s, Some(&top.roadmap), &[&parts[2]]).unwrap();
    assert_eq!(again.roadmap.node_count(), top.roadmap.node_count());
    assert_eq!(again.roadmap.edges(), top.roadmap.edges());
    assert_eq!(again.report.attempts, 0);
}

/// Merging into a base keeps the base's nodes, indices and edges as a prefix of the result.
#[test]
fn a_base_keeps_its_ids() {
    let s = scene();
    let base = merge(&s, None, &[&shard(&s, 1, 3, 300), &shard(&s, 2, 3, 300)])
        .unwrap()
        .roadmap;
    let later = shard(&s, 3, 3, 300);
    let grown = merge(&s, Some(&base), &[&later]).unwrap();
    let n = base.node_count();
    assert_eq!(grown.node_ids[0], (0..n as u32).collect::<Vec<_>>());
    assert_eq!(
        &grown.roadmap.coords()[..base.coords().len()],
        base.coords()
    );
    assert_eq!(&grown.roadmap.edges()[..base.edge_count()], base.edges());
    assert!(grown.roadmap.node_count() >= n + later.node_count());
    roadmap_valid(&grown.roadmap, &discs(&s)).unwrap();
}

/// The command line: shards by `build --shard`, `merge` in two orders gives the same file,
/// `-o` naming a part grows that part in place, a part of another scene is refused naming it.
#[test]
fn cli_shards_and_merge() {
    let dir = temp_dir("merge", "cli");
    let scene = "scenes/discs-cluttered.toml";
    let part = |i: u32| dir.join(format!("part-{i}.bin")).display().to_string();
    for i in 1..=3 {
        let o = viaroad(&[
            "build",
            scene,
            "--shard",
            &format!("{i}/3"),
            "--seed",
            "5",
            "--nodes",
            "300",
            "-o",
            &part(i),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let out = |n: &str| dir.join(n).display().to_string();
    let o = viaroad(&[
        "merge",
        &part(1),
        &part(2),
        &part(3),
        "--scene",
        scene,
        "-o",
        &out("a.bin"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout(&o).contains("merged 3 parts"), "{}", stdout(&o));
    let o = viaroad(&[
        "merge",
        &part(3),
        &part(1),
        &part(2),
        "--scene",
        scene,
        "-o",
        &out("b.bin"),
    ]);
    assert!(o.status.success());
    assert_eq!(
        std::fs::read(out("a.bin")).unwrap(),
        std::fs::read(out("b.bin")).unwrap()
    );
    let before = std::fs::read(part(1)).unwrap().len();
    let o = viaroad(&[
        "merge",
        &part(1),
        &part(2),
        "--scene",
        scene,
        "-o",
        &part(1),
    ]);
    assert!(
        stdout(&o).contains("kept its node indices"),
        "{}",
        stdout(&o)
    );
    assert!(std::fs::read(part(1)).unwrap().len() > before);
    fails_with(
        &[
            "merge",
            &part(2),
            "--scene",
            "scenes/discs-example.toml",
            "-o",
            &out("c.bin"),
        ],
        "another scene",
    );
    // a usage error, as clap reports them
    let o = viaroad(&["build", scene, "--shard", "4/3", "-o", &out("d.bin")]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("shard 4 of 3 does not exist"));
}

/// A merge stopped before its first attempt (a cancel flag already raised, as Ctrl-C does)
/// still returns the union of the parts, valid, with no oracle call spent.
#[test]
fn a_cancelled_merge_keeps_the_union() {
    let s = scene();
    let parts: Vec<Roadmap> = (1..=2).map(|i| shard(&s, i, 2, 200)).collect();
    let oracle = s.oracle();
    let local = LocalSpec::roadmap_default().build();
    let flag = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
    let merged = Learner::for_scene(&s, oracle.as_ref(), local.as_ref())
        .merge(
            None,
            &[&parts[0], &parts[1]],
            &Deadline::none().with_cancel(flag),
            &mut |_| {},
        )
        .unwrap();
    assert_eq!(merged.report.stop, MergeStop::Cancelled);
    assert_eq!(merged.report.attempts, 0);
    assert_eq!(merged.report.counts.intersect_calls(), 0);
    let n: usize = parts.iter().map(Roadmap::node_count).sum();
    assert_eq!(merged.roadmap.node_count(), n);
    roadmap_valid(&merged.roadmap, &discs(&s)).unwrap();
}
