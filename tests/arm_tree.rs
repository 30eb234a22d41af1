//! Two trees for an arm (`roadmap::tree` with whole stairs, and sliding ones): on shipped Panda
//! problems the tree path and its shortcut are chains of single-joint motions (and straight
//! motions of all joints where conservative advancement proved them free) that the
//! independent `ArmChecker` (parry, exact primitives, no code shared with the exact oracle)
//! certifies at 1/10 of OMPL's default resolution, and the same seed and node budget give the
//! same path. Cage 1 is the problem neither the via-point planner nor the roadmap solves: its
//! way in is free only as a fine single-joint staircase.

use crate::common;

use std::path::{Path, PathBuf};
use viaroad::deadline::Deadline;
use viaroad::oracle::CallCounts;
use viaroad::roadmap::tree::{shortcut, Prefix, Stairs, TreeOutcome, TreeParams};
use viaroad::scene::Scene;
use viaroad::space::Config;

fn arms(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/arms")
        .join(p)
}

/// The parameters `bench mbm --planner tree` uses by default: whole stairs, the smaller tree
/// extending (first-hit prefixes where a mode asks for them); a node budget instead of a
/// deadline (the same answer on every machine).
fn params(max_nodes: usize) -> TreeParams {
    TreeParams {
        prefix: Prefix::FirstHit,
        max_nodes: Some(max_nodes),
        ..TreeParams::default()
    }
}

fn grow(scene: &Scene, seed: u64) -> TreeOutcome {
    common::tree::grow(scene, &params(4000), seed)
}

fn shortcut_of(scene: &Scene, path: &[Config]) -> Vec<Config> {
    let oracle = scene.oracle();
    // as the portfolio shortens: the tree's edges may be straight motions of all joints (its
    // extends and stairs), which a single-joint shortcut could only replace by staircases
    let groups = match scene.space.straight_group() {
        Some(whole) => vec![whole],
        None => scene.space.groups(false),
    };
    let mut counts = CallCounts::default();
    shortcut(
        &scene.space,
        oracle.as_ref(),
        &groups,
        path,
        32,
        &mut counts,
        &Deadline::none(),
    )
    .unwrap()
}

#[test]
fn whole_balanced_stairs_are_the_default_and_centring_needs_partial_ones() {
    let d = TreeParams::default();
    assert_eq!((d.stairs, d.balance), (Stairs::Whole, true));
    assert_eq!("slide".parse::<Stairs>(), Ok(Stairs::Slide));
    assert!("sideways".parse::<Stairs>().is_err());
    let centring = TreeParams {
        centre: 2,
        ..TreeParams::default()
    };
    assert!(centring.validate().unwrap_err().contains("whole"));
    assert!(TreeParams {
        stairs: Stairs::Prefix,
        ..centring
    }
    .validate()
    .is_ok());
}

/// Sliding stairs (the arms' default before whole stairs) still find certified paths.
#[test]
fn sliding_tree_path_is_certified() {
    let scene = Scene::load(&arms("panda-box-1.toml")).unwrap();
    let p = TreeParams {
        stairs: Stairs::Slide,
        ..params(4000)
    };
    let out = common::tree::grow(&scene, &p, 1);
    common::arms::certify(
        &scene,
        &out.path.expect("box 1 not solved within 4000 nodes"),
    );
}

#[test]
fn cage_tree_path_is_certified() {
    let scene = Scene::load(&arms("panda-cage-1.toml")).unwrap();
    // whole stairs count every corner as a node: about 17 000 of them on the way into the cage
    let out = common::tree::grow(&scene, &params(20_000), 1);
    let path = out.path.expect("cage 1 not solved within 20 000 nodes");
    common::arms::certify(&scene, &path);
    let short = shortcut_of(&scene, &path);
    assert!(short.len() <= path.len());
    common::arms::certify(&scene, &short);
}

#[test]
fn box_tree_path_is_certified_and_the_same_seed_gives_the_same_path() {
    let scene = Scene::load(&arms("panda-box-1.toml")).unwrap();
    let a = grow(&scene, 1);
    let b = grow(&scene, 1);
    let path = a.path.clone().expect("box 1 not solved within 4000 nodes");
    assert_eq!(a.path, b.path);
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(a.counts.intersect_calls(), b.counts.intersect_calls());
    common::arms::certify(&scene, &path);
    common::arms::certify(&scene, &shortcut_of(&scene, &path));
}
