//! `viaroad view`: the glTF of `export` in one self-contained HTML page (issue 13).

use super::export::{glb, plan, PlanArgs};
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
    viaroad::safe_file::resolve_target(&a.output)?;
    let planned = plan(&a.plan)?;
    let (bytes, summary) = glb(&planned)?;
    let page = viaroad::export::html::page(&planned.scene.name, &bytes);
    super::output::save(&a.output, page.as_bytes())?;
    eprintln!("{summary}");
    eprintln!("wrote {} ({} bytes)", a.output.display(), page.len());
    Ok(())
}
