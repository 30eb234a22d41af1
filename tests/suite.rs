//! The integration tests, one binary: each file beside this one is a module of it, so the
//! library's generic code is instantiated and linked once rather than once per file (the build
//! of `cargo test --release` is mostly linking and monomorphising otherwise).
//!
//! `alloc_free.rs` and `alloc_free_rigid.rs` stay binaries of their own (`Cargo.toml`): they
//! install a counting global allocator, which would count every other test's allocations here.
//! A new test file is a `mod` line below; [`every_test_file_is_built`] fails when one is neither
//! a module here nor a `[[test]]` target, since `autotests = false` would skip it silently.

mod common;
mod roadmap_support;

mod arm_checker;
mod arm_cover;
mod arm_envelope;
mod arm_mbm;
mod arm_moveit;
mod arm_oracle;
mod arm_plan;
mod arm_query_race;
mod arm_recorded;
mod arm_solve;
mod arm_straight;
mod arm_sure;
mod arm_tree;
mod arm_workcell;
mod bench_cones;
mod bench_local;
mod bodies;
mod bodies3;
mod bodies_commands;
mod bodies_walks;
mod budgets;
mod certify;
mod cli;
mod cli_budgets;
mod cones;
mod defects;
mod defects_inputs;
mod defects_output;
mod degenerate;
mod determinism;
mod directed_walk;
mod doc_commands;
mod export_gltf;
mod fuzz_regressions;
mod graph_digest;
mod house_rules;
mod minkowski;
mod oracle_polygons;
mod oracle_polyhedra;
mod roadmap_learn;
mod roadmap_merge;
mod roadmap_nn;
mod roadmap_persist;
mod roadmap_query;
mod roadmap_rigid;
mod rooted_trees;
mod samplers;
mod save_faults;
mod scene_loading;
mod serve;
mod shipped_roadmaps;
mod shortening;
mod solve_default;
mod tree;
mod validity;
mod viapoint_discs;
mod viapoint_rigid;
mod view_browser;

/// Every `tests/*.rs` file is compiled: a module of this binary, or a `[[test]]` of its own.
#[test]
fn every_test_file_is_built() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let suite = std::fs::read_to_string(dir.join("suite.rs")).unwrap();
    let manifest = std::fs::read_to_string(dir.parent().unwrap().join("Cargo.toml")).unwrap();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let Some(stem) = name.strip_suffix(".rs") else {
            continue;
        };
        let module = suite.lines().any(|l| l == format!("mod {stem};"));
        let target = manifest.contains(&format!("path = \"tests/{name}\""));
        assert!(
            module || target,
            "tests/{name} is not built: add `mod {stem};` to tests/suite.rs"
        );
    }
}
