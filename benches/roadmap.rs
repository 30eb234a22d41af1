//! Roadmap benchmarks on a cluttered disc scene.
//!
//! Criterion groups: learning N nodes, loading a saved roadmap of 10 000 nodes, answering one
//! query against it. Before them (under `cargo bench`, unless `VIAROAD_BENCH_NO_REPORT` is set)
//! a report prints the figures once: learning time and size, load time, the share of
//! 1000 random queries solved, query latency p50/p95, and how many nodes the default local
//! method, `--local straight` and `--no-feedback` need for that share.
//!
//! Scenes: the shipped `scenes/discs-cluttered.toml` (when present) and a denser generated one
//! (seeded: 200 discs of radius 0.035), or the TOML disc scene `VIAROAD_BENCH_SCENE` names;
//! all in the unit square. Queries are drawn uniformly from free space; a grid flood fill
//! (400 × 400) tells which are solvable at all.

#[path = "../tests/roadmap_support/mod.rs"]
mod roadmap_support;

use criterion::{criterion_group, BenchmarkId, Criterion};
use roadmap_support::{disc_scene, random_queries, GridComponents};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};
use viaroad::local::LocalSpec;
use viaroad::roadmap::{Budget, LearnParams, Learner, Learnt, QueryOptions, QueryPlanner, Roadmap};
use viaroad::scene::Scene;

/// The scenes of the report: `VIAROAD_BENCH_SCENE` if set; otherwise the shipped
/// `scenes/discs-cluttered.toml` (if present) and a denser generated one.
fn scenes() -> Vec<Scene> {
    if let Some(p) = std::env::var_os("VIAROAD_BENCH_SCENE") {
        return vec![Scene::load(p.as_ref()).expect("VIAROAD_BENCH_SCENE must be a disc scene")];
    }
    let shipped = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/discs-cluttered.toml");
    let mut out: Vec<Scene> = Scene::load(&shipped).into_iter().collect();
    out.push(disc_scene(2026, 200, 0.035));
    out
}

/// The scene of the criterion groups: the first of [`scenes`].
fn scene() -> Scene {
    scenes().remove(0)
}

fn learn(scene: &Scene, spec: &LocalSpec, params: &LearnParams, nodes: usize, seed: u64) -> Learnt {
    let oracle = scene.oracle();
    let local = spec.build();
    Learner::for_scene(scene, oracle.as_ref(), local.as_ref())
        .learn(params, &Budget::nodes(nodes), seed, &mut |_| {})
        .expect("learning")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("viaroad-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

fn percentile(sorted: &[Duration], p: f64) -> Duration {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Share solved of `queries` (and of the solvable ones), and sequential latencies.
fn answer_all(
    scene: &Scene,
    roadmap: &Roadmap,
    queries: &[(Vec<f64>, Vec<f64>)],
    solvable: &[bool],
    options: QueryOptions,
) -> (f64, f64, Vec<Duration>) {
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(roadmap, oracle.as_ref())
        .expect("planner")
        .with_options(options);
    let mut solved = 0;
    let mut solved_solvable = 0;
    let mut times = Vec::with_capacity(queries.len());
    for ((s, g), &ok) in queries.iter().zip(solvable) {
        let t = Instant::now();
        let r = planner.query(s, g).expect("valid query");
        times.push(t.elapsed());
        if r.is_solved() {
            solved += 1;
            solved_solvable += usize::from(ok);
        }
    }
    times.sort();
    let n_solvable = solvable.iter().filter(|&&b| b).count().max(1);
    (
        solved as f64 / queries.len() as f64,
        solved_solvable as f64 / n_solvable as f64,
        times,
    )
}

fn report(scene: &Scene) {
    let scene = scene.clone();
    let queries = random_queries(&scene, 1000, 99);
    let grid = GridComponents::new(&scene, 400);
    let solvable: Vec<bool> = queries
        .iter()
        .map(|(s, g)| grid.solvable(s, g) != Some(false))
        .collect();
    eprintln!("== viaroad roadmap report ==");
    eprintln!(
        "scene {} ({} obstacles), {} of 1000 random queries solvable by a 400×400 grid flood fill, rayon threads {}",
        scene.name,
        scene.obstacles.len(),
        solvable.iter().filter(|&&b| b).count(),
        rayon::current_num_threads()
    );

    // learning 10 000 nodes, saving, loading
    let params = LearnParams::default();
    let spec = LocalSpec::roadmap_default();
    let learnt = learn(&scene, &spec, &params, 10_000, 1);
    let r = &learnt.roadmap;
    let path = scratch("discs-10k.bin");
    r.save(&path).expect("save");
    let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    let mut loads: Vec<Duration> = (0..15)
        .map(|_| {
            let t = Instant::now();
            black_box(Roadmap::load(&path, scene.fingerprint()).expect("load"));
            t.elapsed()
        })
        .collect();
    loads.sort();
    eprintln!(
        "learn 10k [{}]: {:.2?}, {} nodes, {} edges, {} components (largest {}), {} rounds, {} intersect calls; file {} KiB, load p50 {:.2?} (min {:.2?})",
        r.header().local_spec,
        learnt.report.elapsed,
        r.node_count(),
        r.edge_count(),
        r.component_count(),
        r.largest_component(),
        learnt.report.rounds,
        r.header().counts.intersect_calls(),
        size / 1024,
        percentile(&loads, 0.5),
        loads[0]
    );
    let loaded = Roadmap::load(&path, scene.fingerprint()).expect("load");
    let (share, share_solvable, times) = answer_all(
        &scene,
        &loaded,
        &queries,
        &solvable,
        QueryOptions::default(),
    );
    eprintln!(
        "1000 queries against the loaded 10k roadmap: {:.1} % solved ({:.1} % of the solvable), latency p50 {:.3?} p95 {:.3?} max {:.3?}",
        100.0 * share,
        100.0 * share_solvable,
        percentile(&times, 0.5),
        percentile(&times, 0.95),
        times[times.len() - 1]
    );
    let unshortened = QueryOptions {
        shorten: false,
        ..QueryOptions::default()
    };
    let (_, _, times) = answer_all(&scene, &loaded, &queries, &solvable, unshortened);
    eprintln!(
        "  the same without shortening: latency p50 {:.3?} p95 {:.3?}",
        percentile(&times, 0.5),
        percentile(&times, 0.95)
    );

    // how many nodes each variant needs
    let variants: [(&str, LocalSpec, bool); 4] = [
        (
            "default (viapoint:max=3,calls=1000)",
            LocalSpec::roadmap_default(),
            true,
        ),
        (
            "--local viapoint (depth 6, 5000 calls)",
            LocalSpec::default(),
            true,
        ),
        ("--local straight", LocalSpec::Straight, true),
        ("--no-feedback", LocalSpec::roadmap_default(), false),
    ];
    for (name, spec, feedback) in variants {
        let params = LearnParams {
            feedback,
            ..LearnParams::default()
        };
        let mut line = format!("{name}:");
        for nodes in [25, 50, 100, 250, 500, 1000, 2000, 4000] {
            let learnt = learn(&scene, &spec, &params, nodes, 1);
            let (share, _, times) = answer_all(
                &scene,
                &learnt.roadmap,
                &queries,
                &solvable,
                QueryOptions::default(),
            );
            // the roadmap alone: no direct connection from start to goal
            let roadmap_only = QueryOptions {
                try_direct: false,
                ..QueryOptions::default()
            };
            let (share_roadmap, _, _) =
                answer_all(&scene, &learnt.roadmap, &queries, &solvable, roadmap_only);
            line += &format!(
                "\n    {nodes:>5} nodes ({:>5}): {:5.1} % solved, {:5.1} % without the direct try; \
                 {} components, {} intersect calls, learn {:.0?}, query p50 {:.2?}",
                learnt.roadmap.node_count(),
                100.0 * share,
                100.0 * share_roadmap,
                learnt.roadmap.component_count(),
                learnt.roadmap.header().counts.intersect_calls(),
                learnt.report.elapsed,
                percentile(&times, 0.5)
            );
        }
        eprintln!("{line}");
    }
    let _ = std::fs::remove_file(&path);
}

fn bench_learn(c: &mut Criterion) {
    let scene = scene();
    let mut g = c.benchmark_group("learn");
    g.sample_size(10);
    for nodes in [1000, 4000] {
        for (name, spec) in [
            ("default", LocalSpec::roadmap_default()),
            ("straight", LocalSpec::Straight),
        ] {
            g.bench_with_input(BenchmarkId::new(name, nodes), &nodes, |b, &n| {
                b.iter(|| learn(&scene, &spec, &LearnParams::default(), n, 1))
            });
        }
    }
    g.finish();
}

fn bench_load_and_query(c: &mut Criterion) {
    let scene = scene();
    let roadmap = learn(
        &scene,
        &LocalSpec::roadmap_default(),
        &LearnParams::default(),
        10_000,
        1,
    )
    .roadmap;
    let path = scratch("discs-load.bin");
    roadmap.save(&path).expect("save");
    c.bench_function("load/10000", |b| {
        b.iter(|| Roadmap::load(&path, scene.fingerprint()).expect("load"))
    });
    let bytes = std::fs::read(&path).expect("read");
    c.bench_function("decode/10000", |b| {
        b.iter(|| Roadmap::from_bytes(&bytes, scene.fingerprint()).expect("decode"))
    });
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).expect("planner");
    let queries = random_queries(&scene, 64, 5);
    let mut i = 0;
    c.bench_function("query/10000", |b| {
        b.iter(|| {
            let (s, g) = &queries[i % queries.len()];
            i += 1;
            planner.query(s, g).expect("query")
        })
    });
    let _ = std::fs::remove_file(&path);
}

criterion_group!(benches, bench_learn, bench_load_and_query);

fn main() {
    // criterion runs in test mode unless cargo passed `--bench` (`cargo test --benches`)
    let args: Vec<String> = std::env::args().collect();
    let benching =
        args.iter().any(|a| a == "--bench") && !args.iter().any(|a| a == "--test" || a == "--list");
    if benching && std::env::var_os("VIAROAD_BENCH_NO_REPORT").is_none() {
        for scene in scenes() {
            report(&scene);
        }
    }
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
}
