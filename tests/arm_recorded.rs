//! The arm oracle's answers against answers recorded with the oracle of commit 3f1de36 (before
//! the per-call bounds of obstacle nodes and faces and the leaf-level cull of the rotation sweep):
//! the same single-joint moves must get the same intervals, yes/no and first hit,
//! bit for bit. Those changes only compute the same bounds once per call, or skip pairs of faces
//! that a later test would have skipped too, so nothing may move, not even in the last bit.
//!
//! The moves are seeded: in scene 3 of each of the 7 shipped MotionBenchMaker families, from
//! random configurations (two thirds collision-free), a random joint moved to a random value
//! or over its whole range (the via-point search's borderlines). Recording (with the oracle
//! to compare against):
//! `VIAROAD_RECORD_ARM_ANSWERS=tests/data/arms/joint_moves_3f1de36.txt cargo test --release --test arm_recorded`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write as _;
use std::path::Path;
use viaroad::oracle::CallCounts;
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::{ArmChecker, ArmOracle};
use viaroad::scene::moveit::load_planning_scene;

const FAMILIES: [&str; 7] = [
    "table_pick",
    "table_under_pick",
    "bookshelf_small",
    "bookshelf_tall",
    "bookshelf_thin",
    "box",
    "cage",
];

/// Moves per family.
const MOVES: usize = 30;

use crate::common;
use common::arms::{arms_dir, panda};

/// One line per move: the move, then the three answers (floats in Rust's round-trip format).
fn answers() -> String {
    let mut out = String::new();
    for (s, family) in FAMILIES.iter().enumerate() {
        let mut arm = panda(GroupChoice::FirstSrdfGroup);
        let scene =
            load_planning_scene(&arms_dir().join(format!("mbm/{family}/scene0003.yaml"))).unwrap();
        scene.apply_to(&mut arm).unwrap();
        let checker = ArmChecker::new(&arm, &scene.objects).unwrap();
        let oracle = ArmOracle::new(&arm, &scene.objects).unwrap();
        let g = arm.group.clone();
        let mut rng = ChaCha8Rng::seed_from_u64(7000 + s as u64);
        let mut m = 0;
        while m < MOVES {
            let q: Vec<f64> = (0..g.dof())
                .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
                .collect();
            if m % 3 != 2 && !checker.is_valid(&q) {
                continue;
            }
            let j = rng.random_range(0..g.dof());
            let (q, delta) = if m % 2 == 0 {
                let to = rng.random_range(g.lower[j]..=g.upper[j]);
                (q.clone(), to - q[j])
            } else {
                let mut q = q;
                q[j] = g.lower[j];
                (q, g.upper[j] - g.lower[j])
            };
            m += 1;
            let c = &mut CallCounts::default();
            let all = oracle.joint_move(&q, j, delta, c).unwrap();
            let free = oracle.joint_move_free(&q, j, delta, c).unwrap();
            let first = oracle.joint_move_first_hit(&q, j, delta, c).unwrap();
            let ivs: Vec<String> = all
                .iter()
                .map(|iv| format!("{:?}:{:?}", iv.lo, iv.hi))
                .collect();
            writeln!(
                out,
                "{family} joint {j} by {delta:?} from {q:?} | intervals [{}] free {free} first {first:?}",
                ivs.join(" ")
            )
            .unwrap();
        }
    }
    out
}

#[test]
fn joint_moves_answer_as_recorded_bit_for_bit() {
    let got = answers();
    if let Ok(path) = std::env::var("VIAROAD_RECORD_ARM_ANSWERS") {
        std::fs::write(&path, &got).unwrap();
        return;
    }
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/arms/joint_moves_3f1de36.txt");
    let want = std::fs::read_to_string(&path).unwrap();
    let (mut lines, mut colliding) = (0, 0);
    for (g, w) in got.lines().zip(want.lines()) {
        assert_eq!(g, w);
        lines += 1;
        colliding += usize::from(!w.contains("intervals []"));
    }
    assert_eq!(lines, want.lines().count());
    assert_eq!(lines, FAMILIES.len() * MOVES);
    // the comparison means something: many moves collide somewhere
    assert!(colliding >= 60, "{colliding}");
}
