//! One query of an arm planned by the portfolio (`viaroad::portfolio`, the stages `bench mbm`
//! runs), as `viaroad solve` plans an arm scene by default: the path is certified by the
//! independent `ArmChecker` (parry, exact primitives, no code shared with the exact oracle) at
//! 1/10 of OMPL's default resolution, a node budget gives the same path on every run, and the
//! cage, where the via-point planner alone gives up, is answered.

use crate::common;

use common::cli::{stdout, viaroad};
use std::path::PathBuf;
use viaroad::deadline::Deadline;
use viaroad::local::LocalSpec;
use viaroad::portfolio::{Planning, Portfolio, Stage};
use viaroad::scene::Scene;
use viaroad::space::Config;

fn arms(p: &str) -> PathBuf {
    common::arms::arms_dir().join(p)
}

/// The portfolio's answer on `scene`'s query with at most `nodes` per stage of trees and no
/// time limit (the same answer on any machine).
fn plan(scene: &Scene, portfolio: &Portfolio) -> viaroad::portfolio::Answer {
    let q = &scene.checked_queries().unwrap()[0];
    let oracle = scene.oracle();
    let groups = LocalSpec::default().build().groups(&scene.space);
    let planning = Planning {
        scene,
        oracle: oracle.as_ref(),
        groups: &groups,
        straight: true,
    };
    portfolio.plan(&planning, (&q.start, &q.goal), &Deadline::none())
}

fn budgeted(nodes: usize) -> Portfolio {
    let mut p = Portfolio::default();
    p.tree.as_mut().unwrap().max_nodes = Some(nodes);
    p
}

#[test]
fn the_portfolio_answers_the_cage_where_the_via_point_planner_alone_gives_up() {
    let scene = Scene::load(&arms("panda-cage-1.toml")).unwrap();
    let alone = plan(
        &scene,
        &Portfolio {
            tree: None,
            ..Portfolio::default()
        },
    );
    assert!(alone.path.is_none() && alone.stage.is_none(), "{alone:?}");
    assert!(alone.error.is_none(), "{:?}", alone.error);
    assert_eq!(alone.nodes, 0, "no trees without tree parameters");
    // whole stairs count every corner as a node: about 17 000 on the way into the cage
    let a = plan(&scene, &budgeted(20_000));
    assert_eq!(a.stage, Some(Stage::Tree));
    let (raw, short) = a.path.clone().expect("cage 1 not solved");
    common::arms::certify(&scene, &raw);
    common::arms::certify(&scene, &short);
    assert!(short.len() < raw.len());
    assert!(a.counts.intersect_calls() > alone.counts.intersect_calls());
    let b = plan(&scene, &budgeted(20_000));
    assert_eq!(
        b.path, a.path,
        "the same seed and node budget, another path"
    );
    assert_eq!(b.nodes, a.nodes);
}

/// `viaroad solve` on an arm scene runs the arm's portfolio unless the local method is asked for.
#[test]
fn solve_plans_an_arm_scene_by_the_portfolio_unless_the_local_method_is_named() {
    let scene_path = "scenes/arms/panda-box-1.toml";
    let o = viaroad(&["solve", scene_path, "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).lines().next().unwrap()).unwrap();
    assert_eq!(v["solved"], true, "{v}");
    assert!(v["method"] == "trees" || v["method"] == "direct", "{v}");
    let short: Vec<Config> = serde_json::from_value(v["shortened"].clone()).unwrap();
    let scene = Scene::load(&arms("panda-box-1.toml")).unwrap();
    common::arms::certify(&scene, &short);
    assert!(v["length"].as_f64().unwrap() <= v["raw_length"].as_f64().unwrap());
    // the local method alone when named: its own output, no stages
    let o = viaroad(&["solve", scene_path, "--local", "straight", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).lines().next().unwrap()).unwrap();
    assert!(v.get("method").is_none() && v.get("depth").is_some(), "{v}");
    let o = viaroad(&["solve", scene_path, "--local-only", "--nodes", "10"]);
    assert_eq!(o.status.code(), Some(2), "clap refuses the pair");
}
