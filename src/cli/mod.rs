//! Sub-commands of the `viaroad` binary, one file each.

mod bench;
mod build;
mod certify;
mod config_arg;
mod demo;
mod export;
mod global;
mod info;
mod interrupt;
mod learn_args;
mod limits;
mod local_args;
mod merge;
mod output;
mod path_out;
mod probe;
mod progress;
mod query;
mod render;
mod serve;
mod solve;
mod solve_args;
mod solver;
mod view;

use clap::{Parser, Subcommand};

/// Multi-query motion planning with a via-point roadmap (Chadzelek–Hotz–Schömer local method,
/// Overmars–Švestka learning).
#[derive(Parser)]
#[command(name = "viaroad", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The main job end to end: learn a roadmap of a shipped scene, save, reload, answer random
    /// queries, draw the roadmap and a path.
    Demo(demo::DemoArgs),
    /// Learn a roadmap of a scene and save it.
    Build(build::BuildArgs),
    /// Join roadmaps of one scene learnt apart (shards, other merges) into one, or grow a
    /// roadmap by parts learnt later.
    Merge(merge::MergeArgs),
    /// Answer queries against a saved roadmap.
    Query(query::QueryArgs),
    /// Show what a roadmap file holds.
    Info(info::InfoArgs),
    /// Plan a scene's queries with no roadmap file: the planners suited to the scene, or one asked for.
    Solve(solve_args::SolveArgs),
    /// Draw a scene, a solved query with the borderlines and via points tried, as SVG.
    Render(render::RenderArgs),
    /// Print the collision intervals of one straight motion (translation or turn).
    Probe(probe::ProbeArgs),
    /// Load a roadmap once and answer queries as JSON lines on stdin/stdout or a TCP port.
    Serve(serve::ServeArgs),
    /// Benchmarks: the seed's disc experiments (Tables A.1–A.4), local methods compared, paths
    /// re-checked, MotionBenchMaker problems, other planners' paths certified.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// Write a scene, its robot and a planned path as a glTF 2.0 binary (.glb).
    Export(export::ExportArgs),
    /// Write a self-contained HTML page that plays a planned path in 3D.
    View(view::ViewArgs),
    /// Prove each segment of a path from any planner free, or find where it collides (exit 0
    /// free, 3 collides, 4 undecided); `--repair` replaces the blocked runs by certified detours.
    Certify(certify::CertifyArgs),
}

/// Runs one command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Demo(a) => demo::run(a),
        Command::Build(a) => build::run(a),
        Command::Merge(a) => merge::run(a),
        Command::Query(a) => query::run(a),
        Command::Info(a) => info::run(a),
        Command::Solve(a) => solve::run(a),
        Command::Render(a) => render::run(a),
        Command::Probe(a) => probe::run(a),
        Command::Serve(a) => serve::run(a),
        Command::Bench(b) => bench::run(b),
        Command::Export(a) => export::run(a),
        Command::View(a) => view::run(a),
        Command::Certify(a) => certify::run(a),
    }
}
