//! The shipped Panda and its MotionBenchMaker scenes, for the arm tests.

use std::path::{Path, PathBuf};
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{Arm, ArmOptions};

/// `scenes/arms`: the Panda (`panda/`) and the first problems of each family (`mbm/`).
pub fn arms_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms")
}

/// The shipped Panda with its SRDF, planning `group`.
pub fn panda(group: GroupChoice) -> Arm {
    let dir = arms_dir().join("panda");
    Arm::load(
        &dir.join("panda.urdf"),
        Some(&dir.join("panda.srdf")),
        &ArmOptions {
            group,
            ..ArmOptions::default()
        },
    )
    .unwrap()
}
