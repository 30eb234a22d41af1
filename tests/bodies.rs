//! Several bodies moving at once in the plane (SE(2)^k): the exact oracle of the seed's
//! motions (all bodies translate, or one turns) against the independent parry checker, the
//! shipped swaps in a corridor solved by `solve` and by `build` + `query` with every path
//! certified, and scene files that are refused.

use crate::common;

use common::bodies::BodiesChecker;
use common::cli::{fails_with, stdout, temp_dir, viaroad, write};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use viaroad::oracle::{CallCounts, CountedOracle};
use viaroad::scene::toml_format;
use viaroad::scene::Scene;
use viaroad::space::{Change, Config, Motion};

fn shipped(k: usize) -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/bodies");
    Scene::load(&dir.join(format!("swap-corridor-{k}.toml"))).unwrap()
}

/// Three bodies (a square, an L, a triangle) in a room with two pillars.
const ROOM: &str = r#"
[space]
kind = "se2"
lower = [0.0, 0.0]
upper = [6.0, 4.0]

[[body]]
name = "square"
box = { half_extents = [0.4, 0.4] }

[[body]]
name = "ell"
polygon = { vertices = [[-0.5, -0.5], [0.5, -0.5], [0.5, -0.2], [-0.2, -0.2], [-0.2, 0.6], [-0.5, 0.6]] }

[[body]]
name = "triangle"
polygon = { vertices = [[-0.4, -0.3], [0.5, -0.3], [0.0, 0.5]] }
center = "mean"

[[obstacle]]
box = { center = [2.0, 2.0], half_extents = [0.3, 0.8] }
[[obstacle]]
box = { center = [4.2, 1.5], half_extents = [0.6, 0.3] }
"#;

fn room() -> Scene {
    toml_format::from_str(ROOM, std::path::Path::new("room.toml")).unwrap()
}

/// A random motion of the seed's kinds from `q`: all bodies translate (each by its own vector)
/// or one body turns.
fn seed_motion(q: &[f64], rng: &mut ChaCha8Rng) -> Motion {
    let k = q.len() / 3;
    let mut delta = vec![0.0; q.len()];
    if rng.random_bool(0.5) {
        for i in 0..k {
            delta[3 * i] = rng.random_range(-1.5..1.5);
            delta[3 * i + 1] = rng.random_range(-1.5..1.5);
        }
    } else {
        let i = rng.random_range(0..k);
        delta[3 * i + 2] = rng.random_range(-3.0..3.0);
    }
    Motion::segment(q.to_vec(), Change::Linear(delta))
}

#[test]
fn the_exact_oracle_agrees_with_the_independent_checker() {
    let scene = room();
    let oracle = scene.oracle();
    let checker = BodiesChecker::new(&scene);
    let mut rng = ChaCha8Rng::seed_from_u64(47);
    let (mut free, mut blocked, mut motions) = (0, 0, 0);
    while motions < 40 {
        let q = scene.space.sample_uniform(&mut rng);
        if !oracle.is_free(&q, &mut CallCounts::default()) {
            continue;
        }
        motions += 1;
        let m = seed_motion(&q, &mut rng);
        let hits = oracle.intersect(&m, &mut CallCounts::default()).unwrap();
        // every free section is certified free by the checker, a little inside its ends
        for gap in hits.complement_within(m.range).iter() {
            let (lo, hi) = (gap.lo, gap.hi);
            if hi - lo < 1e-6 {
                continue;
            }
            let pad = 1e-6 * (hi - lo);
            let (a, b) = (m.at(lo + pad), m.at(hi - pad));
            checker
                .certify_motion(&a, &b)
                .unwrap_or_else(|e| panic!("the oracle calls {a:?} → {b:?} free: {e}"));
            free += 1;
        }
        // inside every collision interval the bodies touch something (or leave the bounds)
        for iv in hits.iter() {
            let c = m.at(iv.centre());
            let inside = scene.space.in_bounds(&c);
            assert!(
                !inside || checker.clearance(&c) < 1e-6,
                "the oracle calls {c:?} a collision, the checker finds clearance {}",
                checker.clearance(&c)
            );
            blocked += 1;
        }
    }
    assert!(free > 20 && blocked > 10, "{free} free, {blocked} blocked");
}

/// The path printed under `key` in a `--json` line.
fn path_of(line: &str, key: &str) -> Vec<Config> {
    let v: serde_json::Value = serde_json::from_str(line).unwrap();
    serde_json::from_value(v[key].clone()).unwrap_or_else(|_| panic!("no {key} in {line}"))
}

fn certified(scene: &Scene, path: &[Config], what: &str) {
    assert!(path.len() >= 2, "{what}: {path:?}");
    let q = &scene.queries[0];
    let close = |a: &[f64], b: &[f64]| scene.space.distance(a, b) < 1e-9;
    assert!(close(&path[0], &q.start) && close(path.last().unwrap(), &q.goal));
    BodiesChecker::new(scene)
        .certify_path(path)
        .unwrap_or_else(|e| panic!("{what}: {e}"));
}

#[test]
fn swaps_in_a_corridor_are_solved_by_solve() {
    // node budgets: the same answer on any machine; the roadmap's default local method for
    // two squares, the deep via-point planner (fewer nodes, more calls each) for three
    for (k, local, nodes) in [
        (2, "viapoint:max=3,calls=1000", "8000"),
        (3, "viapoint", "1000"),
    ] {
        let file = format!("scenes/bodies/swap-corridor-{k}.toml");
        let args = [
            "solve",
            &file,
            "--roadmap",
            "--nodes",
            nodes,
            "--local",
            local,
            "--json",
        ];
        let o = viaroad(&args);
        let out = stdout(&o);
        assert!(o.status.success(), "{args:?}: {}", common::cli::stderr(&o));
        assert!(out.contains("\"solved\":true"), "{args:?}: {out}");
        let scene = shipped(k);
        for key in ["path", "shortened"] {
            certified(
                &scene,
                &path_of(out.trim(), key),
                &format!("k = {k}, {key}"),
            );
        }
    }
}

#[test]
fn swaps_in_a_corridor_are_solved_by_a_saved_roadmap() {
    let dir = temp_dir("bodies", "roadmap");
    let file = "scenes/bodies/swap-corridor-2.toml";
    let map = dir.join("swap2.bin").to_string_lossy().into_owned();
    let o = viaroad(&["build", file, "-o", &map, "--nodes", "3000", "--seed", "1"]);
    assert!(o.status.success(), "{}", common::cli::stderr(&o));
    let o = viaroad(&["query", &map, "--scene", file, "--json"]);
    let out = stdout(&o);
    assert!(out.contains("\"solved\":true"), "{out}");
    certified(&shipped(2), &path_of(out.trim(), "path"), "query");
}

#[test]
fn bad_scenes_of_several_bodies_are_refused() {
    let dir = temp_dir("bodies", "refused");
    let body = "[[body]]\nname = \"a\"\nbox = { half_extents = [0.4, 0.4] }\n";
    let space = "[space]\nkind = \"se2\"\nlower = [0.0, 0.0]\nupper = [4.0, 4.0]\n";
    let cases = [
        (format!("{space}{body}{body}"), "the name \"a\" is taken"),
        (
            format!("{space}[robot]\nbox = {{ half_extents = [0.4, 0.4] }}\n{body}"),
            "not both",
        ),
        (
            format!("{space}[[body]]\nbox = {{ half_extents = [0.4, 0.4] }}\n"),
            "give it a name",
        ),
        (
            "[space]\nkind = \"se3\"\nlower = [0.0, 0.0, 0.0]\nupper = [4.0, 4.0, 4.0]\n"
                .to_string()
                + body,
            "half_extents has 2 numbers, the space needs 3",
        ),
        (
            format!("{space}{body}[[query]]\nstart = [1.0, 1.0, 0.0]\ngoal = [2.0, 2.0]\n"),
            "coordinates",
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let path = write(&dir, &format!("bad{i}.toml"), text);
        fails_with(&["solve", &path], needle);
    }
}

#[test]
fn the_bodies_sampler_places_crowded_bodies_one_at_a_time() {
    // four squares in a corridor barely wider than they are: a uniform draw of all four at
    // once is almost never free, a body-by-body placement often is
    let scene = shipped(4);
    let oracle = scene.oracle();
    let checker = BodiesChecker::new(&scene);
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let mut counts = CallCounts::default();
    let mut free = 0;
    for _ in 0..40 {
        let q = viaroad::roadmap::Sampler::Bodies
            .sample(&scene.space, &*oracle, 1, &mut rng, &mut counts)
            .unwrap();
        if let Some(q) = q {
            assert!(scene.space.in_bounds(&q));
            assert!(checker.clearance(&q) > 0.0, "{q:?}");
            free += 1;
        }
    }
    assert!(free >= 3, "{free} of 40 attempts placed all four squares");
    assert!(counts.state_checks >= 40 && counts.intersect_calls() == 0);
    // with the command line's sampler flag, a roadmap of four squares gets nodes
    let dir = temp_dir("bodies", "sampler");
    let map = dir.join("swap4.bin").to_string_lossy().into_owned();
    let file = "scenes/bodies/swap-corridor-4.toml";
    let o = viaroad(&[
        "build",
        file,
        "-o",
        &map,
        "--nodes",
        "50",
        "--sampler",
        "bodies",
    ]);
    assert!(o.status.success(), "{}", common::cli::stderr(&o));
    let out = stdout(&o);
    assert!(
        out.starts_with("learnt ") && !out.starts_with("learnt 0 "),
        "{out}"
    );
}
