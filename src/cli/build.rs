//! `viaroad build`: learn a roadmap of a scene offline and save it.

use super::learn_args::LearnArgs;
use super::local_args::LocalArgs;
use anyhow::Context;
use clap::Args;
use std::path::{Path, PathBuf};
use viaroad::deadline::Deadline;
use viaroad::global::Seeding;
use viaroad::local::LocalSpec;
use viaroad::roadmap::{Learner, Learnt, Progress, Shard};
use viaroad::scene::Scene;

/// Arguments of `build`.
#[derive(Args)]
pub struct BuildArgs {
    /// Scene file (.toml or OMPL.app .cfg).
    pub scene: PathBuf,
    /// Where to save the roadmap.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub learn: LearnArgs,
    #[command(flatten)]
    pub local: LocalArgs,
    /// Start the roadmap from a global method's output: `cones`, the spine points of
    /// Brooks's freeways with their legal orientations (planar scenes; at most half
    /// the node budget, `cones:nodes=N` at most N), or `plain` (from nothing, the default).
    #[arg(long, value_name = "SEEDING", help_heading = "Tuning")]
    pub seed_from: Option<viaroad::global::Seeding>,
    /// Learn shard I of N (1 ≤ I ≤ N) of a roadmap learnt apart and joined by `viaroad merge`:
    /// the shard draws from its own random streams, derived from --seed, I and N, and learns
    /// its share of --nodes (a --time budget is each shard's own).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<Shard>,
}

/// Learns a roadmap of `scene` with a progress bar.
pub fn learn(
    scene: &Scene,
    local: &LocalArgs,
    learn: &LearnArgs,
    default_nodes: usize,
) -> anyhow::Result<Learnt> {
    learn_part(scene, local, learn, default_nodes, None)
}

/// [`learn`], or one shard of it.
fn learn_part(
    scene: &Scene,
    local: &LocalArgs,
    learn: &LearnArgs,
    default_nodes: usize,
    shard: Option<Shard>,
) -> anyhow::Result<Learnt> {
    let spec = local.spec_or(LocalSpec::roadmap_default_for(&scene.space))?;
    if matches!(&spec, LocalSpec::ViaPoint(o) if o.sidestep.is_some()) {
        anyhow::bail!(
            "--local {spec}: roadmap files do not record sidestep; build without it \
             (solve, render and bench local take it)"
        );
    }
    let (params, budget) = learn.resolve(default_nodes)?;
    let method = spec.build();
    let oracle = scene.oracle();
    // under a time budget, no one connection attempt may take more than a share of it
    let learner = Learner::for_scene(scene, oracle.as_ref(), method.as_ref())
        .with_attempt_cap(budget.time.map(Learner::attempt_cap_for));
    let bar = match budget.nodes {
        Some(n) => super::progress::progress_bar(shard.map_or(n, |s| s.nodes(n)) as u64, "nodes"),
        None => {
            super::progress::progress_bar(budget.time.map_or(0, |t| t.as_secs().max(1)), "seconds")
        }
    };
    let by_nodes = budget.nodes.is_some();
    // the time budget holds inside every connection attempt; Ctrl-C stops learning the same way
    let deadline = super::interrupt::on_ctrl_c(Deadline::none());
    let mut on_progress = |p: &Progress| {
        if by_nodes {
            bar.set_position(p.nodes as u64);
        } else {
            bar.set_position(p.elapsed.as_secs());
        }
        bar.set_message(format!("{} components", p.components));
    };
    let learnt = match shard {
        None => learner.learn_within(&params, &budget, learn.seed, &deadline, &mut on_progress),
        Some(shard) => learner.learn_shard(
            &params,
            &budget,
            (learn.seed, shard),
            &deadline,
            &mut on_progress,
        ),
    }
    .context("learning")?;
    bar.finish_and_clear();
    Ok(learnt)
}

/// Prints what learning did.
pub fn report(learnt: &Learnt, output: &Path) {
    let r = &learnt.roadmap;
    let rep = &learnt.report;
    let c = r.header().counts;
    println!(
        "learnt {} nodes, {} edges, {} components (largest {}) in {:.3} s ({} rounds, {} connection attempts, {} connected; stopped: {:?})",
        r.node_count(),
        r.edge_count(),
        r.component_count(),
        r.largest_component(),
        rep.elapsed.as_secs_f64(),
        rep.rounds,
        rep.attempts,
        rep.connected,
        rep.stop,
    );
    println!(
        "oracle: {} segment calls, {} line calls, {} state checks, {} pairs tested; saved to {}",
        c.segment_calls,
        c.line_calls,
        c.state_checks,
        c.pairs_tested,
        output.display()
    );
}

/// Runs `build`.
pub fn run(a: BuildArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    // a target that cannot be saved to is refused before the learning, not after it
    viaroad::safe_file::resolve_target(&a.output)?;
    let learnt = match a.seed_from.unwrap_or_default() {
        Seeding::Plain => learn_part(&scene, &a.local, &a.learn, 1000, a.shard)?,
        _ if a.shard.is_some() => {
            anyhow::bail!("--shard learns from nothing: it cannot be combined with --seed-from")
        }
        seeding => super::global::learn_seeded(&scene, seeding, &a.local, &a.learn, 1000)?,
    };
    super::output::create_parent(&a.output)?;
    learnt.roadmap.save(&a.output)?;
    if let Some(shard) = a.shard {
        println!(
            "shard {shard} of seed {}: learnt with seed {}",
            a.learn.seed,
            learnt.roadmap.header().seed
        );
    }
    report(&learnt, &a.output);
    if learnt.roadmap.node_count() == 0 {
        eprintln!("warning: {}", empty_hint(&scene));
    }
    Ok(())
}

/// Why a roadmap can come out empty, and what to do about it: a query still grows a roadmap
/// from its own ends, so an empty one is no dead end.
fn empty_hint(scene: &Scene) -> String {
    let what = if scene.space.body_count() > 1 {
        "the bodies fill the space too tightly for uniform draws (`--sampler bodies` places \
         them one at a time)"
    } else {
        "the free space is too small for uniform draws (`--sampler gap:sigma=0.1` finds the gaps \
         between colliding draws)"
    };
    format!(
        "no free configuration was drawn: {what}; `query` grows the roadmap from its own start \
         and goal, and `query --keep-answers` saves what it found"
    )
}
