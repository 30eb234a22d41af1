//! `viaroad view`: the glTF of `export` in one self-contained HTML page.

use super::export::{export, PlanArgs};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `view`.
#[derive(Args)]
pub struct ViewArgs {
    #[command(flatten)]
    pub plan: PlanArgs,
    /// Output HTML file; it opens from disk with no network.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// Runs `view`.
pub fn run(a: ViewArgs) -> anyhow::Result<()> {
    super::output::check_writable(&a.output)?;
    let e = export(&a.plan)?;
    let page = viaroad::export::html::page(&e.legend, &e.glb);
    super::output::save(&a.output, page.as_bytes())?;
    eprintln!("{}", e.summary);
    eprintln!("wrote {} ({} bytes)", a.output.display(), page.len());
    Ok(())
}
