//! `viaroad bench local`: a tiny benchmark in seconds. Determinism of the counts, the exact
//! re-check of returned paths against an independent disc checker, staged learning, the
//! database read back in OMPL's schema, and the command line with child processes.

use crate::roadmap_support;

use roadmap_support::{discs, path_free};
use rusqlite::Connection;
use std::collections::BTreeSet;
use std::ops::ControlFlow;
use std::path::PathBuf;
use viaroad::bench::local::report::SceneInfo;
use viaroad::bench::local::run::{hex_to_bits, RunStop};
use viaroad::bench::local::{
    run_on, sqlite, Method, Plan, QueryChoice, QuerySet, Report, RunRecord, SceneReport,
    SceneSource, Schedule,
};
use viaroad::local::LocalSpec;
use viaroad::roadmap::{Budget, LearnParams, Learner};

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("viaroad-bench-local-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn methods(items: &[&str]) -> Vec<Method> {
    let items: Vec<String> = items.iter().map(|s| s.to_string()).collect();
    Method::parse_all(&items, Some(true)).unwrap()
}

/// A tiny plan: one generated disc scene, 20 random queries, stages 10, 20, 40 … 320.
fn tiny_plan(scene: &str, methods: Vec<Method>, runs: u32) -> Plan {
    Plan {
        scenes: vec![scene.parse().unwrap()],
        methods,
        runs,
        seed: 5,
        schedule: Schedule {
            first: 10,
            growth: 2.0,
            cap: 320,
        },
        time_limit: None,
        queries: QueryChoice::Random { count: 20 },
        target: 0.99,
        direct: false,
        attach: 30,
        escalation: 0,
        query_calls: None,
    }
}

/// Runs every job of `plan` in this process (one scene).
fn run_all(plan: &Plan, keep_paths: bool) -> (QuerySet, Vec<RunRecord>) {
    let scene = plan.scenes[0].load().unwrap();
    let set = QuerySet::build(&scene, &plan.queries, plan.seed).unwrap();
    let records = plan
        .jobs()
        .into_iter()
        .map(|mut job| {
            job.keep_paths = keep_paths;
            run_on(&scene, &set, &job).unwrap()
        })
        .collect();
    (set, records)
}

/// What must not change between two runs with the same seed (no times).
fn counts(r: &RunRecord) -> String {
    let stages: Vec<String> = r
        .stages
        .iter()
        .map(|s| {
            format!(
                "{}/{}/{}/{:?}/{}/{}",
                s.nodes, s.edges, s.components, s.counts, s.solved, s.solved_queries
            )
        })
        .collect();
    format!(
        "{} {} {:?} {} {} {} {:?} {} {} {} {:?} {:?}",
        r.method,
        r.run,
        r.stop,
        r.nodes,
        r.edges,
        r.components,
        r.counts,
        r.solved,
        r.invalid_paths,
        r.roadmap_bytes,
        r.query_counts,
        stages
    )
}

#[test]
fn the_same_seed_gives_the_same_counts() {
    let plan = tiny_plan(
        "gen:discs:n=40,r=0.06,seed=3",
        methods(&["straight", "sampled:res=0.05", "viapoint+both"]),
        2,
    );
    let (set, a) = run_all(&plan, false);
    let (_, b) = run_all(&plan, false);
    assert_eq!(a.len(), 8);
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(counts(x), counts(y));
    }
    // the same again on a single thread: learning and queries do not depend on threads
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let c = one.install(|| run_all(&plan, false).1);
    for (x, z) in a.iter().zip(&c) {
        assert_eq!(counts(x), counts(z));
    }
    // the two runs of a method learn with different seeds
    assert_ne!(counts(&a[0]), counts(&a[4]));
    for r in &a {
        assert_eq!(r.queries, set.len());
        assert_eq!(r.scored, 20);
        assert_eq!(r.needed, 20); // ⌈0.99 · 20⌉
        assert!(!r.stages.is_empty());
        let last = r.stages.last().unwrap();
        assert_eq!(
            (r.nodes, r.edges, r.solved),
            (last.nodes, last.edges, last.solved)
        );
        // a stage ends once the roadmap has its node count (or learning stopped)
        for (s, target) in r.stages.iter().zip([10, 20, 40, 80, 160, 320]) {
            assert!(s.nodes >= target || r.stop == RunStop::Stalled, "{r:?}");
        }
        // stages only grow
        assert!(r.stages.windows(2).all(|w| w[0].nodes < w[1].nodes
            && w[0].edges <= w[1].edges
            && w[0].learn_seconds <= w[1].learn_seconds));
        match r.stop {
            RunStop::Target => {
                assert!(r.solved >= r.needed);
                assert_eq!(r.time_to_target, Some(last.learn_seconds));
                assert_eq!(r.nodes_at_target, Some(last.nodes));
                // and no earlier stage got there
                assert!(r.stages[..r.stages.len() - 1]
                    .iter()
                    .all(|s| s.solved < r.needed));
            }
            _ => {
                assert!(r.solved < r.needed);
                assert_eq!(r.time_to_target, None);
                if r.stop == RunStop::NodeCap {
                    assert_eq!(r.stages.len(), 6);
                }
            }
        }
        // the bit mask agrees with the count
        let bits = hex_to_bits(&last.solved_queries, r.queries);
        assert_eq!(bits.iter().filter(|&&b| b).count(), r.solved);
        assert!(r.peak_rss_mib.is_none_or(|m| m > 0.0));
    }
}

/// `--query-calls`: a per-query call budget bounds the evaluations after each stage and nothing
/// else. Learning is the same with and without it (stage for stage), queries that spend it are
/// counted, and the evaluations spend fewer calls (the per-query bound itself is tested in
/// `tests/roadmap_query.rs`).
#[test]
fn a_query_call_budget_bounds_the_evaluations_only() {
    let mut plan = tiny_plan(
        "gen:discs:n=40,r=0.06,seed=3",
        methods(&["viapoint:max=3,calls=1000"]),
        1,
    );
    plan.schedule.cap = 80;
    let (_, free) = run_all(&plan, false);
    let budget = 3;
    plan.query_calls = Some(budget);
    let (_, tight) = run_all(&plan, false);
    let (free, tight) = (&free[0], &tight[0]);
    assert_eq!((free.query_calls, tight.query_calls), (None, Some(budget)));
    assert_eq!(free.out_of_calls, 0);
    assert!(tight.out_of_calls > 0, "{tight:?}");
    assert!(tight.out_of_calls + tight.solved <= tight.scored);
    // learning does not see the budget: the stages both evaluated are the same roadmaps
    for (a, b) in free.stages.iter().zip(&tight.stages) {
        assert_eq!(
            (a.nodes, a.edges, a.components, a.counts),
            (b.nodes, b.edges, b.components, b.counts)
        );
    }
    assert!(
        tight.query_counts.intersect_calls() < free.query_counts.intersect_calls(),
        "{} vs {}",
        tight.query_counts.intersect_calls(),
        free.query_counts.intersect_calls()
    );
}

#[test]
fn returned_paths_are_rechecked_like_an_independent_checker_does() {
    // many small discs and a coarse sampling resolution: the sampled baseline steps over discs
    let plan = tiny_plan(
        "gen:discs:n=150,r=0.012,seed=9",
        methods(&["sampled:res=0.2", "straight", "viapoint"]),
        1,
    );
    let (set, records) = run_all(&plan, true);
    let scene = plan.scenes[0].load().unwrap();
    let d = discs(&scene);
    let mut sampled_invalid = 0;
    for r in &records {
        let paths = r.paths.as_ref().unwrap();
        assert_eq!(paths.len(), set.len());
        let returned: Vec<&Vec<Vec<f64>>> = paths.iter().flatten().collect();
        assert_eq!(returned.len(), r.claimed + r.separate_claimed);
        let bad = returned.iter().filter(|p| !path_free(p, &d)).count();
        assert_eq!(bad, r.invalid_paths, "{}", r.method);
        assert_eq!(r.solved + r.invalid_paths, r.claimed, "{}", r.method);
        // every free path joins its query's start and goal
        for (i, p) in paths.iter().enumerate() {
            if let Some(p) = p {
                assert_eq!(p.first(), Some(&set.pairs[i].0));
                assert_eq!(p.last(), Some(&set.pairs[i].1));
            }
        }
        if r.method.starts_with("sampled") {
            sampled_invalid += r.invalid_paths;
        } else {
            assert_eq!(
                r.invalid_paths, 0,
                "{}: an exact method returned a colliding path",
                r.method
            );
        }
    }
    assert!(
        sampled_invalid > 0,
        "the coarse sampled baseline should miss thin discs"
    );
}

#[test]
fn staged_learning_grows_one_roadmap() {
    let scene: SceneSource = "gen:discs:n=40,r=0.06,seed=4".parse().unwrap();
    let scene = scene.load().unwrap();
    let oracle = scene.oracle();
    for spec in [LocalSpec::Straight, LocalSpec::default()] {
        let local = spec.build();
        let learner = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref());
        let params = LearnParams::default();
        // a single stage is plain learning with a node budget, byte for byte
        let single = learner
            .learn_in_stages(&params, &[150], None, 3, &mut |_| {}, &mut |_| {
                ControlFlow::Continue(())
            })
            .unwrap();
        let plain = learner
            .learn(&params, &Budget::nodes(150), 3, &mut |_| {})
            .unwrap();
        assert_eq!(
            single.roadmap.to_bytes().unwrap(),
            plain.roadmap.to_bytes().unwrap()
        );
        // each stage's roadmap is a subgraph of the next, with the same indices
        let mut seen = Vec::new();
        let last = learner
            .learn_in_stages(&params, &[20, 60, 200], None, 3, &mut |_| {}, &mut |l| {
                seen.push(l.clone());
                ControlFlow::Continue(())
            })
            .unwrap();
        assert_eq!(seen.len(), 3);
        for w in seen.windows(2) {
            let (a, b) = (&w[0].roadmap, &w[1].roadmap);
            assert!(a.node_count() < b.node_count());
            assert_eq!(a.coords(), &b.coords()[..a.coords().len()]);
            assert_eq!(a.edges(), &b.edges()[..a.edge_count()]);
            assert!(w[0].report.rounds < w[1].report.rounds);
            assert!(w[0].report.elapsed <= w[1].report.elapsed);
        }
        assert_eq!(
            last.roadmap.to_bytes().unwrap(),
            seen[2].roadmap.to_bytes().unwrap()
        );
        // breaking stops at that stage
        let mut calls = 0;
        let early = learner
            .learn_in_stages(&params, &[20, 60, 200], None, 3, &mut |_| {}, &mut |_| {
                calls += 1;
                ControlFlow::Break(())
            })
            .unwrap();
        assert_eq!(calls, 1);
        assert_eq!(early.roadmap.coords(), seen[0].roadmap.coords());
        assert!(learner
            .learn_in_stages(&params, &[60, 20], None, 3, &mut |_| {}, &mut |_| {
                ControlFlow::Continue(())
            })
            .is_err());
        assert!(learner
            .learn_in_stages(&params, &[], None, 3, &mut |_| {}, &mut |_| {
                ControlFlow::Continue(())
            })
            .is_err());
    }
}

fn tiny_report(plan: Plan) -> Report {
    let (set, records) = run_all(&plan, false);
    let scene = plan.scenes[0].load().unwrap();
    let labels: Vec<String> = plan.methods.iter().map(Method::label).collect();
    let src = plan.scenes[0].to_string();
    let scene_report = SceneReport::build(
        SceneInfo::new(&scene.name, &src, &set),
        &labels,
        records,
        plan.target,
    );
    Report {
        date: "2026-11-22 00:00:00".into(),
        host: "test".into(),
        cpu: "test".into(),
        command: "viaroad bench local (test)".into(),
        version: "0.1.0".into(),
        plan,
        wall_seconds: 1.0,
        scenes: vec![scene_report],
        failures: Vec::new(),
    }
}

/// Method, run, nodes, edges, intersect calls, solved, status, time, solved queries.
type RunRow = (String, i64, i64, i64, i64, bool, i64, f64, i64);

fn column_names(c: &Connection, table: &str) -> Vec<(String, String)> {
    let mut st = c.prepare(&format!("PRAGMA table_info({table})")).unwrap();
    st.query_map([], |r| Ok((r.get::<_, String>(1)?, r.get::<_, String>(2)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect()
}

#[test]
fn the_database_reads_back_in_ompls_schema() {
    let plan = tiny_plan(
        "gen:discs:n=40,r=0.06,seed=3",
        methods(&["straight", "viapoint+both"]),
        2,
    );
    let report = tiny_report(plan);
    let dir = scratch("db");
    let db = dir.join("results.db");
    std::fs::write(&db, b"an older file that must be replaced").unwrap();
    sqlite::write_database(&db, &report).unwrap();
    let c = Connection::open(&db).unwrap();
    let tables: BTreeSet<String> = c
        .prepare("SELECT name FROM sqlite_master WHERE type IN ('table', 'view')")
        .unwrap()
        .query_map([], |r| r.get(0))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    for t in [
        "experiments",
        "plannerConfigs",
        "enums",
        "runs",
        "progress",
        "bestPlannerConfigs",
        "bestPlannerConfigsPerExperiment",
    ] {
        assert!(tables.contains(t), "{t} missing from {tables:?}");
    }
    // the columns ompl_benchmark_statistics.py creates, in its order
    let exp: Vec<String> = column_names(&c, "experiments")
        .into_iter()
        .map(|c| c.0)
        .collect();
    assert_eq!(
        exp,
        [
            "id",
            "name",
            "totaltime",
            "timelimit",
            "memorylimit",
            "runcount",
            "version",
            "hostname",
            "cpuinfo",
            "date",
            "seed",
            "setup"
        ]
    );
    let pc: Vec<String> = column_names(&c, "plannerConfigs")
        .into_iter()
        .map(|c| c.0)
        .collect();
    assert_eq!(pc, ["id", "name", "settings"]);
    let en: Vec<String> = column_names(&c, "enums").into_iter().map(|c| c.0).collect();
    assert_eq!(en, ["name", "value", "description"]);
    let runs = column_names(&c, "runs");
    assert_eq!(
        runs[..3].iter().map(|c| c.0.as_str()).collect::<Vec<_>>(),
        ["id", "experimentid", "plannerid"]
    );
    for (name, ty) in [
        ("time", "REAL"),
        ("memory", "REAL"),
        ("status", "ENUM"),
        ("solved", "BOOLEAN"),
        ("graph_states", "INTEGER"),
        ("graph_motions", "INTEGER"),
        ("intersect_calls", "INTEGER"),
    ] {
        assert!(
            runs.contains(&(name.to_string(), ty.to_string())),
            "runs.{name} {ty}"
        );
    }
    // Planner Arena plots every INTEGER/REAL/BOOLEAN/ENUM column: nothing else may appear
    assert!(runs[3..]
        .iter()
        .all(|(_, t)| ["INTEGER", "REAL", "BOOLEAN", "ENUM"].contains(&t.as_str())));
    let prog: Vec<String> = column_names(&c, "progress")
        .into_iter()
        .map(|c| c.0)
        .collect();
    assert_eq!(&prog[..2], ["runid", "time"]);
    // rows
    let one = |sql: &str| -> i64 { c.query_row(sql, [], |r| r.get(0)).unwrap() };
    assert_eq!(one("SELECT count(*) FROM experiments"), 1);
    assert_eq!(one("SELECT count(*) FROM plannerConfigs"), 3);
    assert_eq!(one("SELECT count(*) FROM runs"), 6);
    let stages: usize = report.scenes[0].runs.iter().map(|r| r.stages.len()).sum();
    assert_eq!(one("SELECT count(*) FROM progress") as usize, stages);
    assert_eq!(one("SELECT count(*) FROM enums WHERE name = 'status'"), 9);
    assert_eq!(
        c.query_row(
            "SELECT description FROM enums WHERE name = 'status' AND value = 6",
            [],
            |r| r.get::<_, String>(0)
        )
        .unwrap(),
        "Exact solution"
    );
    assert_eq!(one("SELECT count(*) FROM bestPlannerConfigs"), 3);
    // every run row says what its record says
    let mut st = c
        .prepare(
            "SELECT plannerConfigs.name, runs.run, graph_states, graph_motions, intersect_calls, \
             solved, status, time, solved_queries FROM runs JOIN plannerConfigs \
             ON runs.plannerid = plannerConfigs.id ORDER BY runs.id",
        )
        .unwrap();
    let rows: Vec<RunRow> = st
        .query_map([], |r| {
            Ok((
                r.get(0)?,
                r.get(1)?,
                r.get(2)?,
                r.get(3)?,
                r.get(4)?,
                r.get(5)?,
                r.get(6)?,
                r.get(7)?,
                r.get(8)?,
            ))
        })
        .unwrap()
        .map(Result::unwrap)
        .collect();
    assert_eq!(rows.len(), 6);
    for (row, rec) in rows.iter().zip(&report.scenes[0].runs) {
        assert_eq!(row.0, rec.method);
        assert_eq!(row.1, i64::from(rec.run));
        assert_eq!(row.2 as usize, rec.nodes);
        assert_eq!(row.3 as usize, rec.edges);
        assert_eq!(row.4 as u64, rec.counts.intersect_calls());
        assert_eq!(row.5, rec.stop == RunStop::Target);
        assert_eq!(row.6, if row.5 { 6 } else { 4 });
        assert_eq!(row.7, rec.time_to_target.unwrap_or(rec.learn_seconds));
        assert_eq!(row.8 as usize, rec.solved);
    }
    // a progress row per stage, with the stage's nodes, in learning-time order
    let first = &report.scenes[0].runs[0];
    let nodes: Vec<i64> = c
        .prepare("SELECT nodes FROM progress WHERE runid = 1 ORDER BY time")
        .unwrap()
        .query_map([], |r| r.get(0))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    assert_eq!(
        nodes,
        first
            .stages
            .iter()
            .map(|s| s.nodes as i64)
            .collect::<Vec<_>>()
    );
    // Markdown, CSV, JSON and plots come from the same report
    let md = report.markdown();
    assert!(
        md.contains("| rank | method |") && md.contains("What feedback"),
        "{md}"
    );
    assert_eq!(report.csv().lines().count(), 7);
    let json: serde_json::Value = serde_json::from_str(&report.json().unwrap()).unwrap();
    assert_eq!(json["scenes"][0]["runs"].as_array().unwrap().len(), 6);
    let svgs = viaroad::bench::local::plots::write_plots(&dir, &report).unwrap();
    assert_eq!(svgs.len(), 4);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_command_line_runs_children_and_writes_every_output() {
    let exe = env!("CARGO_BIN_EXE_viaroad");
    let run = |dir: &PathBuf, extra: &[&str]| {
        let out = std::process::Command::new(exe)
            .args([
                "bench",
                "local",
                "gen:discs:n=40,r=0.06,seed=3",
                "--methods",
                "straight",
                "viapoint+both",
                "--runs",
                "1",
                "--nodes",
                "160",
                "--first",
                "10",
                "--growth",
                "2",
                "--queries",
                "15",
                "--out",
            ])
            .arg(dir)
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let a = scratch("cli-a");
    let b = scratch("cli-b");
    let md = run(&a, &[]);
    run(&b, &["--jobs", "2"]);
    assert!(md.contains("### discs-n40-r0.06-s3"), "{md}");
    for f in ["summary.md", "runs.csv", "report.json", "results.db"] {
        assert!(a.join(f).exists(), "{f}");
    }
    let svgs = std::fs::read_dir(&a)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "svg")
        })
        .count();
    assert_eq!(svgs, 4);
    // the same counts from one process at a time and from two at once
    let fields = |dir: &PathBuf| -> Vec<String> {
        let csv = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
        let header: Vec<String> = csv
            .lines()
            .next()
            .unwrap()
            .split(',')
            .map(str::to_string)
            .collect();
        let keep = [
            "method",
            "stop",
            "nodes",
            "edges",
            "components",
            "segment_calls",
            "line_calls",
            "state_checks",
            "pairs_tested",
            "solved",
            "invalid_paths",
            "roadmap_bytes",
        ];
        let idx: Vec<usize> = keep
            .iter()
            .map(|k| header.iter().position(|h| h == k).unwrap())
            .collect();
        csv.lines()
            .skip(1)
            .map(|l| {
                // the spec column holds commas inside quotes: split on quotes first
                let cells: Vec<String> = split_csv(l);
                idx.iter()
                    .map(|&i| cells[i].clone())
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect()
    };
    let (fa, fb) = (fields(&a), fields(&b));
    assert_eq!(fa.len(), 3);
    assert_eq!(fa, fb);
    // each run's peak memory was measured in its own process
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("report.json")).unwrap()).unwrap();
    for r in json["scenes"][0]["runs"].as_array().unwrap() {
        if std::path::Path::new("/proc/self/status").exists() {
            assert!(r["peak_rss_mib"].as_f64().unwrap() > 0.0);
        }
    }
    let _ = std::fs::remove_dir_all(&a);
    let _ = std::fs::remove_dir_all(&b);
}

fn split_csv(line: &str) -> Vec<String> {
    let mut cells = vec![String::new()];
    let mut quoted = false;
    for ch in line.chars() {
        match ch {
            '"' => quoted = !quoted,
            ',' if !quoted => cells.push(String::new()),
            c => cells.last_mut().unwrap().push(c),
        }
    }
    cells
}

#[test]
fn bad_arguments_are_one_line_errors() {
    let exe = env!("CARGO_BIN_EXE_viaroad");
    let dir = scratch("bad");
    for (args, says) in [
        (
            vec!["scenes/nowhere.toml", "--methods", "straight"],
            "nowhere.toml",
        ),
        (
            vec!["gen:discs:n=5", "--methods", "curved"],
            "unknown method",
        ),
        (vec!["gen:discs:n=5", "--runs", "0"], "--runs"),
        (vec!["gen:discs:n=5", "--growth", "1"], "growth"),
        (vec!["gen:boxes"], "unknown generator"),
        (vec!["gen:discs:n=5", "--query-calls", "0"], "call budget"),
    ] {
        let out = std::process::Command::new(exe)
            .args(["bench", "local"])
            .args(&args)
            .arg("--out")
            .arg(&dir)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A query set with nothing to score is refused: every run would otherwise "reach" its target
/// share at the first stage.
#[test]
fn a_query_set_without_valid_queries_is_refused() {
    let scene = viaroad::scene::Scene::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/discs-example.toml"
    )))
    .unwrap();
    let dir = scratch("no-queries");
    let empty = dir.join("empty.txt");
    std::fs::write(&empty, "").unwrap();
    // the start lies inside the disc at (0.30, 0.40)
    let colliding = dir.join("colliding.txt");
    std::fs::write(&colliding, "0.30 0.40 0.5 0.5\n").unwrap();
    for file in [empty, colliding] {
        let err = QuerySet::build(&scene, &QueryChoice::File(file.clone()), 1).unwrap_err();
        assert!(
            err.to_string().contains("no valid queries"),
            "{}: {err}",
            file.display()
        );
    }
    let fine = QuerySet::build(&scene, &QueryChoice::Random { count: 5 }, 1).unwrap();
    assert_eq!(fine.scored().len(), 5);
}
