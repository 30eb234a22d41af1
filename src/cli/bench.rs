//! `viaroad bench`: the seed's experiments.

use anyhow::Context;
use clap::{Args, Subcommand};
use std::path::PathBuf;
use viaroad::bench::discs::SEED_RADIUS;
use viaroad::bench::tables;

/// Benchmarks.
#[derive(Subcommand)]
pub enum BenchCommand {
    /// Regenerate the seed's Tables A.1–A.4 on random disc problems.
    Discs(DiscsArgs),
}

/// Arguments of `bench discs`.
#[derive(Args)]
pub struct DiscsArgs {
    /// Number of random problems (the seed used 10 000).
    #[arg(long, default_value_t = 10_000)]
    pub problems: u64,
    /// Seed of the problem generator.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Disc radius (default: the calibrated value, see the README).
    #[arg(long, default_value_t = SEED_RADIUS)]
    pub radius: f64,
    /// Intersect calls one problem may spend (default: 100000 with plain recursion, 200000 with
    /// the tree of subproblems). The seed's largest count was 2·10⁷.
    #[arg(long)]
    pub budget: Option<u64>,
    /// Only these tables, e.g. `A.1,A.4` (default: all four).
    #[arg(long, value_delimiter = ',')]
    pub tables: Vec<String>,
    /// Directory for tables.md, tables.csv and tables.json.
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs a benchmark.
pub fn run(cmd: BenchCommand) -> anyhow::Result<()> {
    match cmd {
        BenchCommand::Discs(a) => discs(a),
    }
}

fn discs(a: DiscsArgs) -> anyhow::Result<()> {
    if !(a.radius.is_finite() && a.radius > 0.0 && a.radius < 0.5) {
        anyhow::bail!("--radius must lie in (0, 0.5), got {}", a.radius);
    }
    if a.problems == 0 {
        anyhow::bail!("--problems must be at least 1");
    }
    let budgets = a
        .budget
        .map_or_else(tables::Budgets::default, tables::Budgets::both);
    let mut rows = tables::rows(budgets);
    if !a.tables.is_empty() {
        let known = ["A.1", "A.2", "A.3", "A.4"];
        if let Some(t) = a.tables.iter().find(|t| !known.contains(&t.as_str())) {
            anyhow::bail!("--tables: unknown table {t}; expected A.1, A.2, A.3 or A.4");
        }
        rows.retain(|r| a.tables.iter().any(|t| t == r.table));
    }
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create {}", a.out.display()))?;
    let bar = super::progress_bar(a.problems * rows.len() as u64, "problems");
    let start = std::time::Instant::now();
    tables::run_rows(&mut rows, a.problems, a.seed, a.radius, &|| bar.inc(1));
    bar.finish_and_clear();
    let md = tables::markdown(&rows);
    println!(
        "{} problems, seed {}, disc radius {}, call budget {} (plain) / {} (re-use), {} threads, {:.1} s wall",
        a.problems,
        a.seed,
        a.radius,
        budgets.plain,
        budgets.reuse,
        rayon::current_num_threads(),
        start.elapsed().as_secs_f64()
    );
    println!("{md}");
    let write = |name: &str, text: String| -> anyhow::Result<()> {
        let p = a.out.join(name);
        std::fs::write(&p, text).with_context(|| format!("cannot write {}", p.display()))
    };
    write("tables.md", md)?;
    write("tables.csv", tables::csv(&rows))?;
    write("tables.json", serde_json::to_string_pretty(&rows)?)?;
    eprintln!(
        "wrote tables.md, tables.csv, tables.json to {}",
        a.out.display()
    );
    Ok(())
}
