//! `viaroad bench local --seed-from plain cones`: learning with and without
//! the seeds of Brooks's freeways, inside the same learner on the same queries. A tiny bench on
//! the shipped corridor: both seedings run, the seeded roadmaps hold the seed nodes, every path
//! returned is re-checked by the independent checker, the counts repeat with any thread count,
//! and scenes the cones cannot represent give a typed error.

use std::ops::ControlFlow;
use std::path::PathBuf;
use viaroad::bench::local::report::SceneInfo;
use viaroad::bench::local::run::path_is_free;
use viaroad::bench::local::BenchError;
use viaroad::bench::local::{
    run_on, Method, Plan, QueryChoice, QuerySet, Report, RunRecord, SceneReport, Schedule,
};
use viaroad::bench::validity::Checker;
use viaroad::global::cones::ConeError;
use viaroad::global::Seeding;
use viaroad::local::LocalSpec;
use viaroad::roadmap::{LearnParams, Learner, Sampler};
use viaroad::scene::{Robot, Scene};
use viaroad::space::Space;

const CORRIDOR: &str = "scenes/se2-corridor.toml";

/// The roadmap method crossed with both seedings (plain first).
fn methods() -> Vec<Method> {
    Method::parse_all_crossed(
        &["viapoint:max=3,calls=1000".to_string()],
        Some(true),
        &[Sampler::default()],
        &[Seeding::Plain, Seeding::Cones { nodes: None }],
    )
    .unwrap()
}

/// A tiny plan: 20 random queries, stages 10, 20, 40, 80, 160; the roadmap alone answers.
fn tiny_plan(scene: &str) -> Plan {
    Plan {
        scenes: vec![scene.parse().unwrap()],
        methods: methods(),
        runs: 1,
        seed: 3,
        schedule: Schedule {
            first: 10,
            growth: 2.0,
            cap: 160,
        },
        time_limit: None,
        queries: QueryChoice::Random { count: 20 },
        target: 0.99,
        direct: false,
        attach: 10,
        escalation: 0,
        query_calls: None,
    }
}

fn run_all(plan: &Plan, scene: &Scene, set: &QuerySet) -> Vec<RunRecord> {
    plan.jobs()
        .into_iter()
        .map(|mut job| {
            job.keep_paths = true;
            run_on(scene, set, &job).unwrap()
        })
        .collect()
}

/// What must repeat with the same seed (no times).
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
        "{} {:?} {:?} {} {}",
        r.method,
        r.seeded
            .as_ref()
            .map(|s| (s.nodes, s.edges, s.components, s.counts)),
        r.path_length,
        r.solved,
        stages.join(" ")
    )
}

/// The fields of a CSV line (quoted fields may hold commas).
fn fields(line: &str) -> Vec<String> {
    let (mut out, mut field, mut quoted) = (Vec::new(), String::new(), false);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut field)),
            c => field.push(c),
        }
    }
    out.push(field);
    out
}

#[test]
fn both_seedings_run_and_every_returned_path_passes_the_checker() {
    let plan = tiny_plan(CORRIDOR);
    plan.validate().unwrap();
    let scene = plan.scenes[0].load().unwrap();
    plan.check_scene(&scene).unwrap();
    let set = QuerySet::build(&scene, &plan.queries, plan.seed).unwrap();
    let records = run_all(&plan, &scene, &set);
    assert_eq!(records.len(), 2);
    let (plain, seeded) = (&records[0], &records[1]);
    assert_eq!(plain.seeding, "plain");
    assert!(plain.seeded.is_none());
    assert_eq!(seeded.seeding, "cones");
    assert!(seeded.method.ends_with(" from cones"), "{}", seeded.method);

    // the seeded run started from the seed roadmap: its first stage is the seeds alone, and
    // every later stage grows it
    let seed = seeded.seeded.as_ref().expect("a seed record");
    assert!(seed.freeways > 0 && seed.nodes > 0, "{seed:?}");
    assert!(seed.nodes <= plan.schedule.cap / 2);
    assert!(seed.edges > 0 && seed.components >= 1);
    assert_eq!(seeded.stages[0].nodes, seed.nodes);
    assert_eq!(seeded.stages[0].rounds, 0, "the first stage learns nothing");
    for s in &seeded.stages {
        assert!(s.nodes >= seed.nodes);
        // the seeds' oracle work and time are counted as learning
        assert!(s.counts.segment_calls >= seed.counts.segment_calls);
        assert!(s.counts.state_checks >= seed.counts.state_checks);
        assert!(s.learn_seconds >= seed.seconds);
    }
    assert!(seed.counts.state_checks >= seed.nodes as u64);
    assert!(seeded.stages.windows(2).all(|w| w[0].nodes < w[1].nodes));

    // the report's numbers are the ones a user reads
    for r in &records {
        assert!(!r.stages.is_empty(), "{}", r.method);
        assert_eq!(r.invalid_paths, 0, "{}", r.method);
        assert!(r.solved > 0, "{}", r.method);
        assert!(r.path_length.is_some_and(|l| l > 0.0), "{}", r.method);
        assert!(r.components >= 1 && r.nodes >= r.components);
    }

    // every path returned, re-checked by the independent checker (parry, conservative
    // advancement), and counted as the bench counts it
    let checker = Checker::for_scene(&scene).unwrap();
    for r in &records {
        let paths = r.paths.as_ref().unwrap();
        assert_eq!(paths.len(), set.len());
        let mut returned = 0;
        for (i, p) in paths.iter().enumerate() {
            let Some(p) = p else { continue };
            returned += 1;
            let (start, goal) = &set.pairs[i];
            assert!(scene.space.distance(&p[0], start) < 1e-9, "{}", r.method);
            assert!(
                scene.space.distance(p.last().unwrap(), goal) < 1e-9,
                "{}",
                r.method
            );
            checker
                .check_path(p)
                .unwrap_or_else(|e| panic!("{} query {i}: {e}", r.method));
        }
        assert_eq!(returned, r.claimed + r.separate_claimed, "{}", r.method);
    }

    // the summary shows both side by side
    let labels: Vec<String> = plan.methods.iter().map(Method::label).collect();
    let src = plan.scenes[0].to_string();
    let report = Report {
        date: "2026-12-02 00:00:00".into(),
        host: "test".into(),
        cpu: "test".into(),
        command: "viaroad bench local (test)".into(),
        version: "0.1.0".into(),
        plan: plan.clone(),
        wall_seconds: 1.0,
        scenes: vec![SceneReport::build(
            SceneInfo::new(&scene.name, &src, &set),
            &labels,
            records.clone(),
            plan.target,
        )],
        failures: Vec::new(),
    };
    assert_eq!(report.scenes[0].seeding_pairs(), vec![(0, 1)]);
    let md = report.markdown();
    assert!(md.contains("What the seeds are worth"), "{md}");
    assert!(
        md.contains("| viapoint:max=3,calls=1000 from cones | cones |"),
        "{md}"
    );
    let csv = report.csv();
    let header = fields(csv.lines().next().unwrap());
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let row = fields(csv.lines().nth(2).unwrap());
    assert_eq!(row.len(), header.len());
    assert_eq!(row[col("method")], seeded.method);
    assert_eq!(row[col("seeding")], "cones");
    assert_eq!(row[col("seed_edges")], seed.edges.to_string());
    assert_eq!(row[col("seed_nodes")], seed.nodes.to_string());
    let json = report.json().unwrap();
    let back: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(
        back["scenes"][0]["runs"][1]["seeded"]["nodes"],
        serde_json::json!(seed.nodes)
    );
}

#[test]
fn the_seeded_roadmaps_hold_the_seed_nodes() {
    let scene = Scene::load(std::path::Path::new(CORRIDOR)).unwrap();
    let oracle = scene.oracle();
    let spec = LocalSpec::roadmap_default();
    let local = spec.build();
    let params = LearnParams::default();
    let seeded = Seeding::Cones { nodes: None }
        .seed_roadmap(&scene, oracle.as_ref(), &params, &spec, 1, 80)
        .unwrap()
        .unwrap();
    let base = &seeded.roadmap;
    assert!(base.node_count() > 0 && base.node_count() <= 80);
    // a seed cap of its own holds
    let few = Seeding::Cones { nodes: Some(7) }
        .seed_roadmap(&scene, oracle.as_ref(), &params, &spec, 1, 80)
        .unwrap()
        .unwrap();
    assert!(few.roadmap.node_count() <= 7);
    assert!(Seeding::Plain
        .seed_roadmap(&scene, oracle.as_ref(), &params, &spec, 1, 80)
        .unwrap()
        .is_none());

    let learner = Learner::for_scene(&scene, oracle.as_ref(), local.as_ref());
    let n = base.node_count();
    let mut sizes = Vec::new();
    let learnt = learner
        .learn_in_stages_from(
            Some(base),
            &params,
            &[n, n + 40, n + 80],
            None,
            1,
            &mut |_| {},
            &mut |l| {
                let r = &l.roadmap;
                // the seed nodes keep their indices, the seed edges stay
                for (i, q) in base.nodes().enumerate() {
                    assert_eq!(r.node(i as u32), q);
                }
                for e in base.edges() {
                    assert!(
                        r.edges().iter().any(|f| (f.a, f.b) == (e.a, e.b)),
                        "seed edge {}–{} lost",
                        e.a,
                        e.b
                    );
                }
                sizes.push(r.node_count());
                ControlFlow::Continue(())
            },
        )
        .unwrap();
    assert_eq!(sizes.first(), Some(&n));
    assert!(learnt.roadmap.node_count() >= n + 80 || sizes.len() < 3);
    let checker = Checker::for_scene(&scene).unwrap();
    for (e, edge) in learnt.roadmap.edges().iter().enumerate() {
        checker
            .check_path(&learnt.roadmap.edge_path(e, edge.a))
            .unwrap();
    }
}

/// Regression: a seed turn of (nearly) half a turn was certified along one of its two
/// "shorter ways" and read from its other end along the other; the bench's exact re-check
/// found colliding raw paths through such edges on se2-translate, Maze and Barriers
/// (the *cones* results, first run). Every seed edge is now free both ways, by
/// the exact oracle and by the independent checker.
#[test]
fn seed_edges_are_free_read_from_either_end() {
    for file in [
        "scenes/se2-translate.toml",
        "scenes/ompl/2D/Barriers.cfg",
        "scenes/ompl/2D/Maze_planar.cfg",
    ] {
        let scene = Scene::load(std::path::Path::new(file)).unwrap();
        let oracle = scene.oracle();
        let spec = LocalSpec::roadmap_default();
        let groups = spec.build().groups(&scene.space);
        let r = Seeding::Cones { nodes: None }
            .seed_roadmap(
                &scene,
                oracle.as_ref(),
                &LearnParams::default(),
                &spec,
                1,
                1600,
            )
            .unwrap()
            .unwrap()
            .roadmap;
        let checker = Checker::for_scene(&scene).unwrap();
        let mut turns = 0;
        for (e, edge) in r.edges().iter().enumerate() {
            turns += usize::from(!edge.corners.is_empty());
            for from in [edge.a, edge.b] {
                let p = r.edge_path(e, from);
                assert!(
                    path_is_free(&scene.space, oracle.as_ref(), &groups, &p).unwrap(),
                    "{file}: seed edge {e} from {from}: {p:?}"
                );
                checker
                    .check_path(&p)
                    .unwrap_or_else(|why| panic!("{file}: seed edge {e} from {from}: {why}"));
            }
        }
        assert!(turns > 0, "{file}: no turn of more than a quarter turn");
    }
}

#[test]
fn seeded_counts_repeat_with_any_thread_count() {
    let plan = tiny_plan(CORRIDOR);
    let scene = plan.scenes[0].load().unwrap();
    let set = QuerySet::build(&scene, &plan.queries, plan.seed).unwrap();
    let in_pool = |threads: usize| -> Vec<String> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run_all(&plan, &scene, &set).iter().map(counts).collect())
    };
    let one = in_pool(1);
    assert_eq!(one, in_pool(2));
    assert_eq!(one, in_pool(1));
}

#[test]
fn scenes_the_cones_cannot_represent_give_a_typed_error() {
    let unsupported = |e: &BenchError| {
        matches!(
            e,
            BenchError::Seeding {
                seeding: Seeding::Cones { .. },
                source: ConeError::Unsupported(_),
                ..
            }
        )
    };
    // SE(3): refused by the plan's check before any run, and by a run itself
    let plan = tiny_plan("scenes/cube-into-box.toml");
    let scene = plan.scenes[0].load().unwrap();
    let e = plan.check_scene(&scene).unwrap_err();
    assert!(unsupported(&e), "{e:?}");
    assert!(e.to_string().contains("planar"), "{e}");
    let set = QuerySet::build(&scene, &plan.queries, plan.seed).unwrap();
    let jobs = plan.jobs();
    assert_eq!(jobs[0].method.seeding, Seeding::Plain);
    let e = run_on(&scene, &set, &jobs[1]).unwrap_err();
    assert!(unsupported(&e), "{e:?}");

    // R³: a point among no obstacles
    let r3 = Scene {
        name: "r3".into(),
        space: Space::euclidean(vec![0.0; 3], vec![1.0; 3]).unwrap(),
        robot: Robot::Point,
        obstacles: Vec::new(),
        queries: Vec::new(),
        source: None,
        warnings: Vec::new(),
    };
    let e = plan.check_scene(&r3).unwrap_err();
    assert!(unsupported(&e), "{e:?}");
    // plain seeding accepts every scene
    let mut plain = plan.clone();
    plain.methods.truncate(1);
    plain.check_scene(&scene).unwrap();
    plain.check_scene(&r3).unwrap();
}

#[test]
fn the_command_line_crosses_seedings_and_refuses_se3_with_cones() {
    let exe = env!("CARGO_BIN_EXE_viaroad");
    let dir: PathBuf =
        std::env::temp_dir().join(format!("viaroad-bench-cones-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let run = |scene: &str, out: &PathBuf| {
        std::process::Command::new(exe)
            .args([
                "bench",
                "local",
                scene,
                "--methods",
                "viapoint:max=3,calls=1000",
                "--seed-from",
                "plain,cones,cones:nodes=5",
                "--runs",
                "1",
                "--nodes",
                "80",
                "--first",
                "10",
                "--growth",
                "2",
                "--queries",
                "10",
                "--no-direct",
                "--in-process",
                "--out",
            ])
            .arg(out)
            .output()
            .unwrap()
    };
    let out = run(CORRIDOR, &dir.join("corridor"));
    let md = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(md.contains("viapoint:max=3,calls=1000 from cones"), "{md}");
    assert!(md.contains("What the seeds are worth"), "{md}");
    // the plain method once in the seeding table, beside both seeded variants
    let plain_rows = md
        .lines()
        .filter(|l| l.starts_with("| viapoint:max=3,calls=1000 | plain |"))
        .count();
    assert_eq!(plain_rows, 1, "{md}");
    assert!(
        md.contains("| viapoint:max=3,calls=1000 from cones:nodes=5 | cones:nodes=5 | 5 |"),
        "{md}"
    );
    let csv = std::fs::read_to_string(dir.join("corridor/runs.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4, "{csv}");

    let out = run("scenes/cube-into-box.toml", &dir.join("cube"));
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("seeding `cones`") && err.contains("planar"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        !dir.join("cube/runs.csv").exists(),
        "refused before any run"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
