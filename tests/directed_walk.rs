//! Directed walks (RRT-Connect's extend with exact free sections, `roadmap::bounce::
//! directed_walk`): every step is a free single-group motion — re-checked by the independent
//! checkers (segment–disc distances in the plane, parry by conservative advancement in SE(3)) —
//! and in free space a walk reaches its target.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
use viaroad::bench::validity::Checker;
use viaroad::deadline::Deadline;
use viaroad::oracle::{CallCounts, CountedOracle};
use viaroad::roadmap::bounce::directed_walk;
use viaroad::scene::Scene;
use viaroad::space::Config;

fn scene(rel: &str) -> Scene {
    Scene::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
}

/// Walks between random free starts and uniform targets; returns how many reached the target.
fn walks(scene: &Scene, n: usize, seed: u64) -> usize {
    let oracle = scene.oracle();
    let groups = scene.space.groups(false);
    let checker = Checker::for_scene(scene).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut counts = CallCounts::default();
    let mut reached = 0;
    let mut moved = 0;
    for _ in 0..n {
        let start = loop {
            let q = scene.space.sample_uniform(&mut rng);
            if oracle.is_free(&q, &mut counts) {
                break q;
            }
        };
        let target = scene.space.sample_uniform(&mut rng);
        let corners = directed_walk(
            &scene.space,
            oracle.as_ref(),
            &groups,
            &start,
            &target,
            2,
            &mut counts,
            &Deadline::none(),
        )
        .unwrap();
        if corners.is_empty() {
            continue;
        }
        moved += 1;
        let path: Vec<Config> = std::iter::once(start).chain(corners.clone()).collect();
        checker
            .check_path(&path)
            .unwrap_or_else(|e| panic!("{}: a walk's step collides: {e}", scene.name));
        // every step moves in one DOF group
        for w in path.windows(2) {
            let differing = groups
                .iter()
                .filter(|g| !scene.space.same_in_group(&w[0], &w[1], g))
                .count();
            assert_eq!(
                differing, 1,
                "{}: a step moved {differing} groups",
                scene.name
            );
        }
        if corners.last() == Some(&target) {
            reached += 1;
        }
    }
    assert!(
        moved * 2 >= n,
        "{}: only {moved} of {n} walks moved",
        scene.name
    );
    reached
}

#[test]
fn discs_steps_are_free_and_some_reach_their_target() {
    let s = scene("scenes/discs-cluttered.toml");
    let reached = walks(&s, 200, 1);
    // among clutter many targets are blocked, but not all: the walk is not always cut short
    assert!(reached > 0 && reached < 200, "reached {reached} of 200");
}

#[test]
fn se3_steps_are_free() {
    let s = scene("scenes/ompl/3D/Easy.cfg");
    let reached = walks(&s, 30, 2);
    assert!(
        reached < 30,
        "every target reached: the walls were never hit"
    );
}

#[test]
fn free_space_walks_reach_their_targets() {
    let mut s = scene("scenes/discs-cluttered.toml");
    s.obstacles.clear();
    assert_eq!(walks(&s, 50, 3), 50);
}
