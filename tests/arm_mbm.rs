//! `bench mbm`'s per-problem pipeline (issue 10 part 5): the via-point planner and then the
//! trees, or both at once (`--race`). Whichever answers, the path comes back re-checked by the
//! independent [`viaroad::robot::ArmChecker`] inside `run_problem`; this test holds it to that
//! and to the stage times adding up.

use std::path::Path;
use std::time::Duration;
use viaroad::bench::mbm::{find_problems, load_robot, run_problem, MbmOptions, Planner};
use viaroad::roadmap::tree::{Prefix, Stairs, TreeParams};

#[test]
fn raced_or_in_turn_every_answer_is_certified() {
    let arms = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms");
    let robot = load_robot(&arms.join("panda")).unwrap();
    // box 1 needs the trees (a staircase into the box), table_pick 1 does not
    let mut problems = find_problems(&arms.join("mbm/box"), Some(1)).unwrap();
    problems.extend(find_problems(&arms.join("mbm/table_pick"), Some(1)).unwrap());
    assert_eq!(problems.len(), 2);
    for race in [None, Some(Duration::ZERO)] {
        let options = MbmOptions {
            // generous: the node budget, not the clock, ends the trees on a slow machine
            time: Duration::from_secs(30),
            direct_calls: 60,
            seed: 1,
            limit: None,
            planner: Planner::Tree,
            tree: TreeParams {
                prefix: Prefix::FirstHit,
                stairs: Stairs::Whole,
                balance: true,
                max_nodes: Some(4000),
                ..TreeParams::default()
            },
            race,
        };
        for p in &problems {
            let r = run_problem(&robot, p, &options);
            let name = format!("{} {} (race {race:?})", p.family, p.id);
            assert!(r.valid && r.oracle_valid, "{name}: {r:?}");
            assert!(r.solved, "{name}: not solved: {r:?}");
            assert_eq!(r.certified, Some(true), "{name}: {r:?}");
            assert!(r.stage == "direct" || r.stage == "tree", "{name}: {r:?}");
            assert!(r.length <= r.raw_length + 1e-9, "{name}: {r:?}");
            assert!(
                r.direct_s <= r.time_s && r.grow_s <= r.time_s,
                "{name}: {r:?}"
            );
            if r.stage == "tree" {
                assert!(r.nodes > 0, "{name}: {r:?}");
            }
            if race.is_none() {
                // in turn, the stages do not overlap
                assert!(
                    r.direct_s + r.grow_s + r.shorten_s <= r.time_s + 1e-6,
                    "{name}: {r:?}"
                );
            }
        }
    }
}
