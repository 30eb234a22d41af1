//! Determinism everywhere: the same seed gives byte-identical roadmap files
//! with 1, 2 and 8 rayon threads, on a 2D, an SE(2) and an SE(3) scene, and the same answers
//! to the same queries. Node budgets only: a time budget is not reproducible (documented on
//! `Budget::time`).

use std::path::PathBuf;
use viaroad::bench::validity::Checker;
use viaroad::local::LocalSpec;
use viaroad::roadmap::{Budget, LearnParams, Learner, QueryPlanner, Roadmap};
use viaroad::scene::Scene;
use viaroad::space::Config;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// What one thread count gives: the saved file's bytes and the answers (outcome and path).
fn run(
    scene: &Scene,
    nodes: usize,
    seed: u64,
    queries: &[(Config, Config)],
    threads: usize,
) -> (Vec<u8>, Vec<String>) {
    pool(threads).install(|| {
        let oracle = scene.oracle();
        let method = LocalSpec::roadmap_default().build();
        let learnt = Learner::for_scene(scene, oracle.as_ref(), method.as_ref())
            .learn(
                &LearnParams::default(),
                &Budget::nodes(nodes),
                seed,
                &mut |_| {},
            )
            .unwrap();
        let dir = std::env::temp_dir().join(format!(
            "viaroad-determinism-{}-{}-{threads}",
            std::process::id(),
            scene.name
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("roadmap.bin");
        learnt.roadmap.save(&file).unwrap();
        let bytes = std::fs::read(&file).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(bytes, learnt.roadmap.to_bytes().unwrap());
        // the file loads back to the same roadmap
        let back = Roadmap::from_bytes(&bytes, scene.fingerprint()).unwrap();
        assert_eq!(back.to_bytes().unwrap(), bytes);
        let planner = QueryPlanner::new(&back, oracle.as_ref()).unwrap();
        let checker = Checker::for_scene(scene).unwrap();
        let answers = planner
            .query_batch(queries)
            .into_iter()
            .map(|a| {
                let r = a.result.unwrap();
                if r.is_solved() {
                    checker.check_path(&r.path).unwrap();
                }
                // bit patterns: "the same" means the same floats, not close ones
                let bits: Vec<Vec<u64>> = r
                    .path
                    .iter()
                    .map(|q| q.iter().map(|x| x.to_bits()).collect())
                    .collect();
                format!("{:?} {:?} {}", r.outcome, bits, r.length.to_bits())
            })
            .collect();
        (bytes, answers)
    })
}

fn same_for_all_thread_counts(
    scene: &Scene,
    nodes: usize,
    seed: u64,
    queries: &[(Config, Config)],
) {
    let (bytes, answers) = run(scene, nodes, seed, queries, 1);
    assert!(
        answers
            .iter()
            .any(|a| !a.starts_with("NotAttached") && !a.starts_with("Disconnected")),
        "{}: no query solved, nothing compared: {answers:?}",
        scene.name
    );
    for threads in [2, 8] {
        let (b, a) = run(scene, nodes, seed, queries, threads);
        assert!(
            b == bytes,
            "{}: the roadmap file differs with {threads} threads",
            scene.name
        );
        assert_eq!(
            a, answers,
            "{}: answers differ with {threads} threads",
            scene.name
        );
    }
    // and another seed gives another roadmap (the comparison above can fail)
    let (other, _) = run(scene, nodes, seed + 1, &[], 2);
    assert_ne!(other, bytes, "{}: the seed changes nothing", scene.name);
}

/// The scene's own queries plus the pairs of them crossed.
fn queries_of(scene: &Scene) -> Vec<(Config, Config)> {
    let q = scene.checked_queries().unwrap();
    let mut out: Vec<(Config, Config)> = q
        .iter()
        .map(|q| (q.start.clone(), q.goal.clone()))
        .collect();
    for a in &q {
        for b in &q {
            out.push((a.goal.clone(), b.start.clone()));
        }
    }
    out
}

#[test]
fn discs_2d() {
    let scene = Scene::load(&root().join("scenes/discs-cluttered.toml")).unwrap();
    let queries = queries_of(&scene);
    same_for_all_thread_counts(&scene, 400, 7, &queries);
}

#[test]
fn se2_corridor() {
    let scene = Scene::load(&root().join("scenes/se2-corridor.toml")).unwrap();
    let queries = queries_of(&scene);
    same_for_all_thread_counts(&scene, 300, 11, &queries);
}

#[test]
fn se3_ompl_easy() {
    let scene = Scene::load(&root().join("scenes/ompl/3D/Easy.cfg")).unwrap();
    let queries = queries_of(&scene);
    same_for_all_thread_counts(&scene, 150, 17, &queries);
}
