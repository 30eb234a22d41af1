//! `viaroad demo`: the main job end to end on a shipped scene — learn a roadmap, save it,
//! reload it, answer a batch of random queries, summarise, and draw the roadmap with one path.

use super::build::{learn, report};
use super::learn_args::LearnArgs;
use super::local_args::LocalArgs;
use super::query::percentile;
use anyhow::Context;
use clap::Args;
use rand::SeedableRng;
use std::path::PathBuf;
use std::time::Instant;
use viaroad::oracle::{CallCounts, CollisionOracle, CountedOracle};
use viaroad::render::Picture;
use viaroad::roadmap::{QueryPlanner, Roadmap};
use viaroad::scene::Scene;
use viaroad::space::Config;

/// Arguments of `demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// The scene.
    #[arg(long, default_value = "scenes/discs-cluttered.toml")]
    pub scene: PathBuf,
    /// Directory for the roadmap and the picture.
    #[arg(long, default_value = "roadmaps")]
    pub out: PathBuf,
    /// Random queries to answer.
    #[arg(long, default_value_t = 1000)]
    pub queries: usize,
    #[command(flatten)]
    pub learn: LearnArgs,
    #[command(flatten)]
    pub local: LocalArgs,
}

/// `n` random collision-free configurations pairs, from a seeded stream.
pub fn random_queries(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    n: usize,
    seed: u64,
) -> Vec<(Config, Config)> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut free = || loop {
        let mut q = scene.space.sample_uniform(&mut rng);
        scene.space.normalize(&mut q);
        if oracle.is_free(&q, &mut CallCounts::default()) {
            return q;
        }
    };
    (0..n).map(|_| (free(), free())).collect()
}

/// Runs `demo`.
pub fn run(a: DemoArgs) -> anyhow::Result<()> {
    if a.queries == 0 {
        anyhow::bail!("--queries must be at least 1");
    }
    let scene = Scene::load(&a.scene).with_context(|| {
        "the demo runs from the repository's root, where scenes/ lives".to_string()
    })?;
    let stem = a
        .scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create {}", a.out.display()))?;
    let file = a.out.join(format!("{stem}.bin"));
    let picture = a.out.join(format!("{stem}.svg"));

    println!(
        "1. learning a roadmap of {} ({} obstacles, {})",
        a.scene.display(),
        scene.obstacles.len(),
        scene.space.kind()
    );
    let learnt = learn(&scene, &a.local, &a.learn, 1000)?;
    learnt.roadmap.save(&file)?;
    report(&learnt, &file);

    let t = Instant::now();
    let roadmap = Roadmap::load(&file, scene.fingerprint())?;
    println!(
        "2. reloaded {} in {:.2} ms: {} nodes, {} edges",
        file.display(),
        t.elapsed().as_secs_f64() * 1e3,
        roadmap.node_count(),
        roadmap.edge_count()
    );

    let oracle = scene.oracle();
    let queries = random_queries(
        &scene,
        oracle.as_ref(),
        a.queries,
        a.learn.seed.wrapping_add(1),
    );
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).context("roadmap")?;
    let t = Instant::now();
    let answers = planner.query_batch(&queries);
    let wall = t.elapsed().as_secs_f64();
    let mut ms: Vec<f64> = answers
        .iter()
        .map(|b| b.elapsed.as_secs_f64() * 1e3)
        .collect();
    ms.sort_by(f64::total_cmp);
    let solved: Vec<_> = answers
        .iter()
        .filter_map(|b| b.result.as_ref().ok())
        .filter(|r| r.is_solved())
        .collect();
    let calls: u64 = solved.iter().map(|r| r.counts.intersect_calls()).sum();
    println!(
        "3. answered {} random queries in {:.3} s ({} threads): {} solved ({:.1} %), latency p50 {:.3} ms, p95 {:.3} ms, {:.1} intersect calls per solved query",
        queries.len(),
        wall,
        rayon::current_num_threads(),
        solved.len(),
        100.0 * solved.len() as f64 / queries.len().max(1) as f64,
        percentile(&ms, 0.5),
        percentile(&ms, 0.95),
        calls as f64 / solved.len().max(1) as f64,
    );

    let mut pic = Picture::new(&scene);
    pic.obstacles(&scene).roadmap(&roadmap);
    // the scene's own first query, if it has one, else the first solved random query
    let shown = match scene.queries.first() {
        Some(q) => planner.query(&q.start, &q.goal).ok(),
        None => solved.first().map(|r| (*r).clone()),
    };
    if let Some(r) = shown.filter(|r| r.is_solved()) {
        pic.path(&scene, &r.raw_path, false)
            .path(&scene, &r.path, true);
    }
    pic.save(&picture)
        .with_context(|| format!("cannot write {}", picture.display()))?;
    println!(
        "4. wrote {} (roadmap, raw path dashed, shortened path solid)",
        picture.display()
    );
    Ok(())
}
