//! Local methods and roadmaps on OMPL.app's rigid-body problems (SE(3), exact polyhedra oracle):
//! one local-method connection, learning N nodes, loading a saved roadmap, answering a query.
//! The disc scenes have their own benches (`local_discs`, `roadmap`); the oracle calls alone are
//! in `oracle_polyhedra`.
//!
//! Scenes: `scenes/ompl/3D/Easy.cfg` and `cubicles.cfg` (skipped with a message when absent).
//! Inputs come from seeded streams and are built outside the timed loops; connection counts
//! are asserted (the via-point planner solves every pair the straight line solves), so a broken
//! planner cannot look fast.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;
use viaroad::local::LocalSpec;
use viaroad::oracle::{CallCounts, CountedOracle};
use viaroad::roadmap::{Budget, LearnParams, Learner, QueryPlanner, Roadmap};
use viaroad::scene::{ompl_cfg, Scene};
use viaroad::space::Config;

fn scenes() -> Vec<Scene> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/ompl/3D");
    ["Easy.cfg", "cubicles.cfg"]
        .iter()
        .filter_map(|f| match Scene::load(&dir.join(f)) {
            Ok(s) => Some(s),
            Err(e) => {
                eprintln!("local_rigid: {f} skipped ({e})");
                None
            }
        })
        .collect()
}

/// A free configuration drawn uniformly.
fn free(scene: &Scene, rng: &mut ChaCha8Rng) -> Config {
    let oracle = scene.oracle();
    loop {
        let mut q = scene.space.sample_uniform(rng);
        scene.space.normalize(&mut q);
        if oracle.is_free(&q, &mut CallCounts::default()) {
            return q;
        }
    }
}

/// `n` pairs of free configurations about as far apart as a roadmap's neighbours: the goal lies
/// `share` of the way (position and rotation) towards another uniform configuration.
fn near_pairs(scene: &Scene, n: usize, share: f64, seed: u64) -> Vec<(Config, Config)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let oracle = scene.oracle();
    let mut out = Vec::new();
    while out.len() < n {
        let a = free(scene, &mut rng);
        let far = scene.space.sample_uniform(&mut rng);
        let mut b = scene.space.interpolate(&a, &far, share);
        scene.space.normalize(&mut b);
        if oracle.is_free(&b, &mut CallCounts::default()) {
            out.push((a, b));
        }
    }
    out
}

fn connections(c: &mut Criterion) {
    let mut g = c.benchmark_group("rigid_connect_16_pairs");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5));
    for scene in scenes() {
        let oracle = scene.oracle();
        // a fifth of the way across: some pairs are blocked, so the via-point search works
        let pairs = near_pairs(&scene, 16, 0.2, 7);
        let solved = |spec: &LocalSpec| -> (usize, u64) {
            let m = spec.build();
            pairs.iter().fold((0, 0), |(n, calls), (a, b)| {
                let c = m.connect(&scene.space, oracle.as_ref(), a, b).unwrap();
                (
                    n + usize::from(c.is_connected()),
                    calls + c.counts.intersect_calls(),
                )
            })
        };
        let (s_straight, c_straight) = solved(&LocalSpec::Straight);
        let (s_via, c_via) = solved(&LocalSpec::default());
        eprintln!(
            "{}: of 16 pairs straight connects {s_straight} ({c_straight} calls), viapoint {s_via} ({c_via} calls)",
            scene.name
        );
        assert!(
            s_via >= s_straight,
            "the via-point planner starts with the straight path"
        );
        for (name, spec) in [
            ("straight", LocalSpec::Straight),
            ("sampled_0.01", LocalSpec::Sampled { resolution: 0.01 }),
            ("viapoint", LocalSpec::default()),
        ] {
            let m = spec.build();
            g.bench_function(BenchmarkId::new(name, &scene.name), |b| {
                b.iter(|| {
                    for (a, z) in &pairs {
                        black_box(m.connect(&scene.space, oracle.as_ref(), a, z).unwrap());
                    }
                })
            });
        }
    }
    g.finish();
}

fn learn(scene: &Scene, spec: &LocalSpec, nodes: usize) -> Roadmap {
    let oracle = scene.oracle();
    let local = spec.build();
    Learner::for_scene(scene, oracle.as_ref(), local.as_ref())
        .learn(
            &LearnParams::default(),
            &Budget::nodes(nodes),
            1,
            &mut |_| {},
        )
        .expect("learning")
        .roadmap
}

fn learning(c: &mut Criterion) {
    let mut g = c.benchmark_group("rigid_learn");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(10));
    for scene in scenes() {
        // the via-point planner with its default call budget (5000 per attempt) needs seconds
        // (Easy) to minutes (cubicles) for a few dozen nodes: failed attempts use the whole
        // budget; a budget of 200 calls keeps the bench to seconds
        let budgeted: LocalSpec = "viapoint:calls=200".parse().expect("a valid spec");
        for (name, spec, nodes) in [
            ("straight", LocalSpec::Straight, 500),
            ("viapoint_calls200", budgeted, 25),
        ] {
            g.bench_with_input(
                BenchmarkId::new(format!("{name}/{}", scene.name), nodes),
                &nodes,
                |b, &n| b.iter(|| learn(&scene, &spec, n)),
            );
        }
    }
    g.finish();
}

fn load_and_query(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("viaroad-bench-rigid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    for scene in scenes() {
        let roadmap = learn(&scene, &LocalSpec::Straight, 2000);
        let path = dir.join(format!("{}.bin", scene.name));
        roadmap.save(&path).expect("save");
        c.bench_function(&format!("rigid_load/{}/2000", scene.name), |b| {
            b.iter(|| Roadmap::load(&path, scene.fingerprint()).expect("load"))
        });
        // the scene's OMPL query file if it has one, else near pairs
        let file = scene
            .source
            .as_ref()
            .and_then(|p| p.parent()?.parent().map(|d| d.join("queries")))
            .map(|d| d.join(format!("{}_seed1_50.txt", scene.name)));
        let queries: Vec<(Config, Config)> = match file
            .as_ref()
            .filter(|f| f.exists())
            .map(|f| ompl_cfg::read_query_pairs(f, &scene.space))
        {
            Some(Ok(q)) => q.into_iter().map(|q| (q.start, q.goal)).collect(),
            _ => near_pairs(&scene, 16, 0.2, 11),
        };
        let oracle = scene.oracle();
        let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).expect("planner");
        let solved = queries
            .iter()
            .filter(|(s, g)| planner.query(s, g).is_ok_and(|r| r.is_solved()))
            .count();
        eprintln!(
            "{}: a 2000-node straight-line roadmap solves {solved} of {} queries",
            scene.name,
            queries.len()
        );
        let mut i = 0;
        c.bench_function(&format!("rigid_query/{}/2000", scene.name), |b| {
            b.iter(|| {
                let (s, g) = &queries[i % queries.len()];
                i += 1;
                black_box(planner.query(s, g))
            })
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, connections, learning, load_and_query);
criterion_main!(benches);
