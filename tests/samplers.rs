//! The samplers of construction: every sample is free under an independent check, the
//! narrow-passage samplers put their samples nearer the obstacles than uniform sampling does,
//! specs round-trip, and the sampler is recorded in the roadmap file (since version 2).

use crate::common;
use crate::roadmap_support;

use common::rigid::RigidChecker;
use common::rigid2d::PlanarChecker;
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use roadmap_support::*;
use std::path::{Path, PathBuf};
use viaroad::local::LocalSpec;
use viaroad::oracle::CallCounts;
use viaroad::roadmap::{LearnParams, Roadmap, RoadmapError, Sampler, FORMAT_VERSION};
use viaroad::scene::Scene;
use viaroad::space::Config;

fn all_samplers() -> Vec<Sampler> {
    [
        "uniform",
        "obstacle",
        "obstacle:margin=0.001",
        "gaussian",
        "gaussian:sigma=0.02",
        "bridge",
        "bridge:sigma=0.03",
        "gap",
        "gap:sigma=0.03",
        "mix:uniform=1,bridge=1,gaussian=1,obstacle=1,gap=1",
    ]
    .iter()
    .map(|s| s.parse().unwrap())
    .collect()
}

/// `n` samples of `sampler` in `scene`, each from its own seeded stream (as the learner does).
fn draw(scene: &Scene, sampler: &Sampler, n: u64, seed: u64) -> (Vec<Config>, CallCounts) {
    let oracle = scene.oracle();
    let mut counts = CallCounts::default();
    let samples = (0..n)
        .filter_map(|i| {
            let mut rng = ChaCha8Rng::seed_from_u64(seed.wrapping_mul(1_000_003).wrapping_add(i));
            sampler
                .sample(&scene.space, oracle.as_ref(), 100, &mut rng, &mut counts)
                .unwrap()
        })
        .collect();
    (samples, counts)
}

/// Distance from a point to the nearest disc or wall of the unit square, computed here.
fn disc_clearance(p: &[f64], discs: &[([f64; 2], f64)]) -> f64 {
    let walls = p[0].min(1.0 - p[0]).min(p[1]).min(1.0 - p[1]);
    discs
        .iter()
        .map(|(c, r)| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt() - r)
        .fold(walls, f64::min)
}

fn load(name: &str) -> Scene {
    Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(name)).unwrap()
}

#[test]
fn every_sample_is_free_under_an_independent_check() {
    let scene = disc_scene(5, 40, 0.07);
    let d = discs(&scene);
    for s in all_samplers() {
        let (samples, counts) = draw(&scene, &s, 300, 1);
        assert!(samples.len() >= 150, "{s}: only {} samples", samples.len());
        assert!(counts.state_checks > 0, "{s}");
        for q in &samples {
            assert!(
                point_free(q, &d) && disc_clearance(q, &d) > 0.0,
                "{s}: {q:?} collides"
            );
        }
    }
    let corridor = load("scenes/se2-corridor.toml");
    let planar = PlanarChecker::se2(&corridor);
    for s in all_samplers() {
        let (samples, _) = draw(&corridor, &s, 60, 2);
        assert!(!samples.is_empty(), "{s}: no samples");
        for q in &samples {
            assert!(corridor.space.in_bounds(q), "{s}: {q:?} out of bounds");
            assert!(planar.clearance(q) > 0.0, "{s}: {q:?} collides");
        }
    }
    let boxed = load("scenes/cube-into-box.toml");
    let rigid = RigidChecker::se3(&boxed);
    for s in all_samplers() {
        let (samples, _) = draw(&boxed, &s, 40, 3);
        assert!(!samples.is_empty(), "{s}: no samples");
        for q in &samples {
            let n = q[3..7].iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!(
                (n - 1.0).abs() < 1e-9,
                "{s}: {q:?} is not a unit quaternion"
            );
            rigid
                .certify_path(std::slice::from_ref(q))
                .unwrap_or_else(|e| panic!("{s}: {e}"));
            assert!(rigid.clearance(q) > 0.0, "{s}: {q:?} touches");
        }
    }
}

#[test]
fn narrow_passage_samplers_sample_near_obstacles() {
    let scene = disc_scene(11, 60, 0.05);
    let d = discs(&scene);
    let mean_clearance = |s: &str| {
        let (samples, _) = draw(&scene, &s.parse().unwrap(), 2000, 7);
        assert!(samples.len() > 1500, "{s}: {} samples", samples.len());
        samples.iter().map(|q| disc_clearance(q, &d)).sum::<f64>() / samples.len() as f64
    };
    let uniform = mean_clearance("uniform");
    for s in [
        "obstacle",
        "gaussian:sigma=0.02",
        "bridge:sigma=0.05",
        "gap:sigma=0.05",
    ] {
        let c = mean_clearance(s);
        eprintln!("{s}: mean clearance {c:.4} (uniform {uniform:.4})");
        // with 2000 samples the means are known to a few per cent; the samplers halve it
        assert!(
            c < 0.6 * uniform,
            "{s}: mean clearance {c} vs uniform {uniform}"
        );
    }
    // the obstacle-based walk stops `margin · extent` before the boundary, or half-way
    let tight = mean_clearance("obstacle:margin=0.001");
    assert!(
        tight < 0.01,
        "obstacle:margin=0.001: mean clearance {tight}"
    );
}

#[test]
fn samples_depend_only_on_their_stream() {
    let scene = disc_scene(5, 40, 0.07);
    for s in all_samplers() {
        assert_eq!(draw(&scene, &s, 50, 9), draw(&scene, &s, 50, 9), "{s}");
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("samplers_{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_sampler_is_recorded_in_the_roadmap_file() {
    let scene = disc_scene(31, 30, 0.06);
    let params = LearnParams {
        sampler: "mix:uniform=1,bridge(sigma=0.05)=2,obstacle=1"
            .parse()
            .unwrap(),
        ..LearnParams::default()
    };
    let roadmap = learn(&scene, &LocalSpec::default(), &params, 300, 4).roadmap;
    let d = discs(&scene);
    roadmap_valid(&roadmap, &d).unwrap();
    let path = scratch("round_trip").join("mix.bin");
    roadmap.save(&path).unwrap();
    let loaded = Roadmap::load(&path, scene.fingerprint()).unwrap();
    assert_eq!(loaded.header().params.sampler, params.sampler);
    assert_eq!(loaded.header(), roadmap.header());
    assert_eq!(loaded.to_bytes().unwrap(), std::fs::read(&path).unwrap());
    assert!(loaded
        .info()
        .to_string()
        .contains("sampler          mix:uniform=1,bridge(sigma=0.05)=2,obstacle(margin=0.01)=1"));
    // another sampler, another roadmap: the sampler is really used
    let uniform = learn(
        &scene,
        &LocalSpec::default(),
        &LearnParams::default(),
        300,
        4,
    )
    .roadmap;
    assert_ne!(uniform.coords(), roadmap.coords());
    // the same seed and sampler give the same bytes with one thread or two
    let bytes = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| learn(&scene, &LocalSpec::default(), &params, 300, 4).roadmap)
            .to_bytes()
            .unwrap()
    };
    assert_eq!(bytes(1), bytes(2));
}

#[test]
fn a_version_1_file_is_refused_with_a_clear_error() {
    assert_eq!(FORMAT_VERSION, 3);
    let scene = disc_scene(31, 30, 0.06);
    let roadmap = learn(
        &scene,
        &LocalSpec::default(),
        &LearnParams::default(),
        50,
        1,
    )
    .roadmap;
    let mut bytes = roadmap.to_bytes().unwrap();
    bytes[8..12].copy_from_slice(&1u32.to_le_bytes());
    let path = scratch("old").join("v1.bin");
    std::fs::write(&path, &bytes).unwrap();
    match Roadmap::load(&path, scene.fingerprint()) {
        Err(
            e @ RoadmapError::WrongVersion {
                found: 1,
                supported: 3,
            },
        ) => {
            let msg = e.to_string();
            assert!(
                msg.contains("version 1") && msg.contains("version 3"),
                "{msg}"
            );
        }
        other => panic!("expected WrongVersion, got {other:?}"),
    }
}

fn sampler_strategy() -> impl Strategy<Value = Sampler> {
    let positive = (1u32..100_000).prop_map(|k| f64::from(k) / 1e4);
    let margin = (1u32..=1000).prop_map(|k| f64::from(k) / 1e3);
    let simple = prop_oneof![
        Just(Sampler::Uniform),
        margin.prop_map(|margin| Sampler::Obstacle { margin }),
        positive
            .clone()
            .prop_map(|sigma| Sampler::Gaussian { sigma }),
        positive.clone().prop_map(|sigma| Sampler::Bridge { sigma }),
        positive.clone().prop_map(|sigma| Sampler::Gap { sigma }),
    ];
    prop_oneof![
        simple.clone(),
        prop::collection::vec((simple, positive), 1..5).prop_map(Sampler::Mix),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn specs_round_trip(s in sampler_strategy()) {
        let text = s.to_string();
        prop_assert_eq!(&text.parse::<Sampler>().unwrap(), &s);
        let json = serde_json::to_string(&s).unwrap();
        prop_assert_eq!(&serde_json::from_str::<Sampler>(&json).unwrap(), &s);
        let cfg = bincode::config::standard();
        let bin = bincode::serde::encode_to_vec(&s, cfg).unwrap();
        let (back, _): (Sampler, usize) = bincode::serde::decode_from_slice(&bin, cfg).unwrap();
        prop_assert_eq!(back, s);
    }

    #[test]
    fn arbitrary_text_never_panics(text in "[a-z():=,.0-9 -]{0,40}") {
        if let Ok(s) = text.parse::<Sampler>() {
            prop_assert!(s.validate().is_ok());
            prop_assert_eq!(s.to_string().parse::<Sampler>().unwrap(), s);
        }
    }
}

fn viaroad(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn build_takes_a_sampler_and_info_shows_it() {
    let dir = scratch("cli_build");
    let out = dir.join("corridor.bin");
    let o = viaroad(&[
        "build",
        "scenes/se2-corridor.toml",
        "-o",
        &out.to_string_lossy(),
        "--nodes",
        "60",
        "--sampler",
        "bridge:sigma=0.05",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let scene = load("scenes/se2-corridor.toml");
    let roadmap = Roadmap::load(&out, scene.fingerprint()).unwrap();
    assert_eq!(
        roadmap.header().params.sampler,
        Sampler::Bridge { sigma: 0.05 }
    );
    let info = viaroad(&["info", &out.to_string_lossy()]);
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(
        text.contains("sampler          bridge:sigma=0.05"),
        "{text}"
    );
    let bad = viaroad(&[
        "build",
        "scenes/se2-corridor.toml",
        "-o",
        &dir.join("bad.bin").to_string_lossy(),
        "--nodes",
        "60",
        "--sampler",
        "bridge:sigma=-1",
    ]);
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("sigma must be a positive number"), "{err}");
    assert!(!dir.join("bad.bin").exists());
}

#[test]
fn bench_local_compares_samplers() {
    let dir = scratch("cli_bench");
    let o = viaroad(&[
        "bench",
        "local",
        "gen:discs:n=40,r=0.06,seed=3",
        "--methods",
        "viapoint",
        "--samplers",
        "uniform",
        "bridge:sigma=0.05",
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
        "--in-process",
        "--out",
        &dir.to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let runs = json["scenes"][0]["runs"].as_array().unwrap();
    let got: Vec<(String, String)> = runs
        .iter()
        .map(|r| {
            (
                r["method"].as_str().unwrap().to_string(),
                r["sampler"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            ("viapoint".to_string(), "uniform".to_string()),
            (
                "viapoint @bridge:sigma=0.05".to_string(),
                "bridge:sigma=0.05".to_string()
            )
        ]
    );
    // the bridge test spends more state checks per node than uniform sampling
    let checks = |r: &serde_json::Value| r["stages"][0]["counts"]["state_checks"].as_u64().unwrap();
    assert!(checks(&runs[1]) > checks(&runs[0]));
    let csv = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
    assert!(csv.lines().next().unwrap().contains(",sampler,"));
    assert_eq!(csv.lines().count(), 3);
}
