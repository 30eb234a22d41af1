//! The shipped Panda and its MotionBenchMaker scenes, for the arm tests.

use rand::Rng;
use std::path::{Path, PathBuf};
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{Arm, ArmChecker, ArmOptions};
use viaroad::scene::{Robot, Scene};
use viaroad::space::Config;

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

/// `path` answers `scene`'s first query: from its start to its goal, and free under the
/// independent [`ArmChecker`] (parry, exact primitives, no code shared with the exact oracle) at
/// 1/10 of OMPL's default resolution, each segment checked along the straight line between its
/// ends (one joint moving, or several where shortening took a straight shortcut).
pub fn certify(scene: &Scene, path: &[Config]) {
    let q = &scene.checked_queries().unwrap()[0];
    assert_eq!(path.first(), Some(&q.start));
    assert_eq!(path.last(), Some(&q.goal));
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    let c = ArmChecker::new(&a.arm, &a.objects).unwrap();
    let report = c
        .check_path(path, 0.001 * c.arm().group.max_extent())
        .unwrap();
    assert!(
        report.valid,
        "{}: the checker refuses the path: {report:?}",
        scene.name
    );
    assert!(report.samples > path.len());
}

/// A configuration within `reach` of `q` in every joint, drawn uniformly and clamped to the
/// space's limits: the far end of a random straight motion of every length the tests ask for.
pub fn near<R: Rng>(scene: &Scene, q: &[f64], reach: f64, rng: &mut R) -> Config {
    q.iter()
        .enumerate()
        .map(|(i, x)| {
            let (lo, hi) = (scene.space.lower()[i], scene.space.upper()[i]);
            (x + rng.random_range(-reach..=reach)).clamp(lo, hi)
        })
        .collect()
}
