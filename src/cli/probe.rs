//! `viaroad probe`: the collision intervals of one straight motion, for users to see what the
//! oracle sees (intersectSegment, CHS §1.2).

use super::config_arg::parse_config;
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use viaroad::oracle::{CallCounts, CountedOracle};
use viaroad::scene::Scene;

/// Arguments of `probe`.
#[derive(Args)]
pub struct ProbeArgs {
    /// Scene file (.toml or OMPL.app .cfg).
    pub scene: PathBuf,
    /// Configuration at t = 0 (numbers separated by commas or spaces).
    #[arg(long, allow_hyphen_values = true)]
    pub from: String,
    /// Configuration at t = 1.
    #[arg(long, allow_hyphen_values = true)]
    pub to: String,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// Runs `probe`.
pub fn run(a: ProbeArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&a.scene)?;
    let mut from = parse_config("--from", &a.from)?;
    let mut to = parse_config("--to", &a.to)?;
    for (what, q) in [("--from", &mut from), ("--to", &mut to)] {
        scene.space.check(q).with_context(|| what.to_string())?;
        scene.space.normalize(q);
    }
    let motion = scene.space.direct_motion(&from, &to).with_context(|| {
        if scene.space.is_joints() {
            "--from and --to differ in more than one joint: an arm's straight motion moves one \
             joint (CHS §1.5)"
        } else {
            "--from and --to differ in both position and orientation: a straight motion either \
             translates (equal orientations) or turns about one axis (equal positions)"
        }
    })?;
    let oracle = scene.oracle();
    let mut counts = CallCounts::default();
    let intervals = oracle.intersect(&motion, &mut counts)?;
    let ivs: Vec<[f64; 2]> = intervals.iter().map(|iv| [iv.lo, iv.hi]).collect();
    if a.json {
        println!(
            "{}",
            json!({ "intervals": ivs, "calls": counts.intersect_calls(), "pairs_tested": counts.pairs_tested })
        );
    } else {
        if ivs.is_empty() {
            println!("free: no collision for t in [0, 1]");
        }
        for [lo, hi] in &ivs {
            println!("collision for t in [{lo:.9}, {hi:.9}]");
        }
        println!(
            "{} call, {} pairs tested",
            counts.intersect_calls(),
            counts.pairs_tested
        );
    }
    Ok(())
}
