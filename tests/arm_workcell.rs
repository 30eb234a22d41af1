//! The workcell mode of `bench mbm` (issue 10 part 6): one roadmap of a family's first scene,
//! saved and loaded back, answering every request valid in that scene; where the roadmap does
//! not answer in half the query time, two trees do. Every answer is re-checked by the
//! independent [`viaroad::robot::ArmChecker`] inside `run_workcell`; this test holds it to that.

use std::path::Path;
use std::time::Duration;
use viaroad::bench::mbm::{find_problems, load_robot, run_workcell};
use viaroad::roadmap::tree::{Prefix, TreeParams};
use viaroad::roadmap::Budget;

#[test]
fn every_workcell_answer_is_certified_with_the_trees_behind_the_roadmap() {
    let arms = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let robot = load_robot(&arms.join("panda")).unwrap();
    let problems = find_problems(&arms.join("mbm/cage"), None).unwrap();
    let dir = std::env::temp_dir().join(format!("viaroad-arm-workcell-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let trees = TreeParams {
        prefix: Prefix::FirstHit,
        slide: true,
        max_nodes: Some(3000),
        ..TreeParams::default()
    };
    let r = run_workcell(
        &robot,
        &problems,
        &Budget::nodes(40),
        1,
        Duration::from_secs(4),
        Some(&trees),
        &dir.join("cage.roadmap"),
    )
    .unwrap();
    assert_eq!(r.requests, 3);
    assert!(r.valid >= 1, "the first request is valid in its own scene");
    assert!(r.solved <= r.valid && r.by_trees <= r.solved);
    assert_eq!(r.certified, r.solved, "{r:?}");
    assert_eq!(r.query_ms.n, r.valid);
    assert!(dir.join("cage.roadmap").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
