//! `viaroad demo`: the main job end to end on a shipped scene — learn a roadmap, save it,
//! reload it, answer a batch of random queries, summarise, and draw the roadmap with one path.

use super::build::{learn, report};
use super::learn_args::LearnArgs;
use super::local_args::LocalArgs;
use super::query::percentile;
use anyhow::Context;
use clap::Args;
use rand::SeedableRng;
use std::path::{Path, PathBuf};
use std::time::Instant;
use viaroad::limits::MAX_QUERIES;
use viaroad::oracle::{CallCounts, CollisionOracle, CountedOracle};
use viaroad::render::Picture;
use viaroad::roadmap::{QueryPlanner, Roadmap};
use viaroad::scene::{Scene, SceneError};
use viaroad::space::Config;

/// The scene the demo learns unless `--scene` names another.
const DEFAULT_SCENE: &str = "scenes/discs-cluttered.toml";

/// Arguments of `demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// The scene.
    #[arg(long, default_value = DEFAULT_SCENE)]
    pub scene: PathBuf,
    /// Directory for the roadmap and the picture.
    #[arg(long, default_value = "roadmaps")]
    pub out: PathBuf,
    /// Random queries to answer (at most 10⁶).
    #[arg(long, default_value_t = 1000)]
    pub queries: usize,
    #[command(flatten)]
    pub learn: LearnArgs,
    #[command(flatten)]
    pub local: LocalArgs,
}

/// Draws per free configuration before [`random_queries`] gives up: a scene whose free space
/// is (almost) empty would otherwise be sampled for ever.
const MAX_DRAWS: usize = 100_000;

/// `n` random collision-free configurations pairs, from a seeded stream; an error if
/// [`MAX_DRAWS`] draws in a row find no free configuration.
pub fn random_queries(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    n: usize,
    seed: u64,
) -> anyhow::Result<Vec<(Config, Config)>> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut free = || {
        for _ in 0..MAX_DRAWS {
            let mut q = scene.space.sample_uniform(&mut rng);
            scene.space.normalize(&mut q);
            if oracle.is_free(&q, &mut CallCounts::default()) {
                return Ok(q);
            }
        }
        anyhow::bail!("no free configuration in {MAX_DRAWS} random draws: the scene's free space is (almost) empty")
    };
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        out.push((free()?, free()?));
    }
    Ok(out)
}

/// Runs `demo`.
pub fn run(a: DemoArgs) -> anyhow::Result<()> {
    super::limits::count_in_range(
        "--queries",
        a.queries,
        MAX_QUERIES,
        "every query pair is drawn and stored before the first is answered",
    )?;
    let scene = match Scene::load(&a.scene) {
        // the hint only helps with the default scene, not with a file the user named
        Err(SceneError::Io { source, .. })
            if a.scene == Path::new(DEFAULT_SCENE)
                && source.kind() == std::io::ErrorKind::NotFound =>
        {
            anyhow::bail!(
                "cannot read the default scene {DEFAULT_SCENE}: the demo runs from the \
                 repository's root, where scenes/ lives (or give --scene FILE)"
            )
        }
        r => r?,
    };
    // the flags are checked before the first status line, so that none precedes an error
    a.learn.resolve(1000)?;
    a.local
        .spec_or(viaroad::local::LocalSpec::roadmap_default())?;
    let stem = a
        .scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create {}", a.out.display()))?;
    let file = a.out.join(format!("{stem}.bin"));
    let picture = a.out.join(format!("{stem}.svg"));
    // refused before the learning, not after it
    viaroad::safe_file::resolve_target(&file)?;
    viaroad::safe_file::resolve_target(&picture)?;

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
    )?;
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
    super::output::save(&picture, pic.to_svg().as_bytes())?;
    println!(
        "4. wrote {} (roadmap, raw path dashed, shortened path solid)",
        picture.display()
    );
    Ok(())
}
