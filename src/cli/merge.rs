//! `viaroad merge`: join roadmaps of one scene learnt apart (shards of `build --shard`, other
//! merges) into one, or grow a deployed roadmap by parts learnt later.

use anyhow::Context;
use clap::Args;
use std::path::{Path, PathBuf};
use viaroad::deadline::Deadline;
use viaroad::roadmap::{Learner, MergeError, MergeProgress, Merged, Roadmap};
use viaroad::scene::Scene;

/// Arguments of `merge`.
#[derive(Args)]
pub struct MergeArgs {
    /// Roadmap files to merge, all learnt for --scene with one local method. Their order does
    /// not matter: the same parts give the same roadmap.
    #[arg(required_unless_present = "into")]
    pub parts: Vec<PathBuf>,
    /// The scene the parts were learnt for.
    #[arg(long)]
    pub scene: PathBuf,
    /// Grow this roadmap: it keeps its nodes with their indices, the parts are added to it, and
    /// it is replaced (atomically) unless -o names another file. A part that is also -o is
    /// taken as --into.
    #[arg(long, value_name = "BASE")]
    pub into: Option<PathBuf>,
    /// Where to save the merged roadmap (default: --into).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Stop connecting parts after this many seconds and save what is joined (not
    /// reproducible; without it the merge tries every node and is).
    #[arg(long)]
    pub time: Option<f64>,
}

/// The same file (both exist and resolve to one path).
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// The base (if any), the other parts and the output, as the flags name them.
fn resolve(a: &MergeArgs) -> anyhow::Result<(Option<PathBuf>, Vec<PathBuf>, PathBuf)> {
    let output = match (&a.output, &a.into) {
        (Some(o), _) => o.clone(),
        (None, Some(base)) => base.clone(),
        (None, None) => anyhow::bail!("where to save? give -o FILE, or --into BASE to grow BASE"),
    };
    let base = a
        .into
        .clone()
        .or_else(|| a.parts.iter().find(|p| same_file(p, &output)).cloned());
    let parts: Vec<PathBuf> = a
        .parts
        .iter()
        .filter(|p| base.as_ref().is_none_or(|b| !same_file(p, b)))
        .cloned()
        .collect();
    Ok((base, parts, output))
}

/// The error with the part's file named.
fn name_part(e: MergeError, files: &[&Path]) -> anyhow::Error {
    let part = match &e {
        MergeError::ForeignScene { part, .. }
        | MergeError::OtherSpace { part }
        | MergeError::OtherLocalMethod { part, .. } => Some(*part),
        _ => None,
    };
    match part.and_then(|i| files.get(i)) {
        Some(f) => anyhow::Error::new(e).context(format!("merging {}", f.display())),
        None => anyhow::Error::new(e).context("merging"),
    }
}

/// Runs `merge`.
pub fn run(a: MergeArgs) -> anyhow::Result<()> {
    let (base_file, part_files, output) = resolve(&a)?;
    let time = super::limits::optional_seconds("--time", a.time)?;
    let scene = Scene::load(&a.scene)?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    viaroad::safe_file::resolve_target(&output)?;
    let fp = scene.fingerprint();
    let load =
        |f: &PathBuf| Roadmap::load(f, fp).with_context(|| format!("reading part {}", f.display()));
    let base = base_file.as_ref().map(load).transpose()?;
    let parts = part_files
        .iter()
        .map(load)
        .collect::<anyhow::Result<Vec<_>>>()?;
    let first = base
        .as_ref()
        .or(parts.first())
        .context("nothing to merge")?;
    // the parts' own local method: every part is checked against it
    let method = first.header().local_spec.build();
    let oracle = scene.oracle();
    let learner = Learner::for_scene(&scene, oracle.as_ref(), method.as_ref())
        .with_attempt_cap(time.map(Learner::attempt_cap_for));
    let deadline = super::interrupt::on_ctrl_c(Deadline::after_opt(time));
    let total = parts
        .iter()
        .chain(&base)
        .map(Roadmap::node_count)
        .sum::<usize>();
    let bar = super::progress::progress_bar(total as u64, "candidates");
    let refs: Vec<&Roadmap> = parts.iter().collect();
    let files: Vec<&Path> = base_file
        .iter()
        .chain(&part_files)
        .map(PathBuf::as_path)
        .collect();
    let merged = learner
        .merge(base.as_ref(), &refs, &deadline, &mut |p: &MergeProgress| {
            bar.set_length(p.candidates as u64);
            bar.set_position(p.tried as u64);
            bar.set_message(format!("{} components", p.components));
        })
        .map_err(|e| name_part(e, &files))?;
    bar.finish_and_clear();
    super::output::create_parent(&output)?;
    merged.roadmap.save(&output)?;
    report(&merged, base_file.as_deref(), &output);
    Ok(())
}

/// Prints what the merge did.
fn report(m: &Merged, base: Option<&Path>, output: &Path) {
    let r = &m.roadmap;
    let rep = &m.report;
    if let Some(b) = base {
        println!("base {} kept its node indices", b.display());
    }
    println!(
        "merged {} parts ({} nodes, {} components together) into {} nodes, {} edges, {} components (largest {}) in {:.3} s ({} rounds, {} connection attempts across parts, {} connected; stopped: {:?})",
        rep.parts,
        rep.part_nodes,
        rep.union_components,
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
    let c = rep.counts;
    println!(
        "oracle (merge alone): {} segment calls, {} line calls, {} pairs tested; saved to {}",
        c.segment_calls,
        c.line_calls,
        c.pairs_tested,
        output.display()
    );
}
