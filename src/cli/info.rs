//! `viaroad info`: what a roadmap file holds.

use clap::Args;
use std::path::PathBuf;
use viaroad::roadmap::Roadmap;

/// Arguments of `info`.
#[derive(Args)]
pub struct InfoArgs {
    /// The roadmap file.
    pub roadmap: PathBuf,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `info`.
pub fn run(a: InfoArgs) -> anyhow::Result<()> {
    let roadmap = Roadmap::load_any_scene(&a.roadmap)?;
    let info = roadmap.info();
    if a.json {
        println!("{}", serde_json::to_string_pretty(&info)?);
    } else {
        println!("{}", a.roadmap.display());
        print!("{info}");
    }
    Ok(())
}
