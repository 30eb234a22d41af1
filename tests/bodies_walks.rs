//! The random-bounce walks of several bodies (one body at a time, slides of every body in
//! turn): every step is one certified free motion of one DOF group, re-checked by the
//! independent checker; the walks reach the corridor's niche; a swap is solved through a
//! roadmap grown by them; the same seed gives the same roadmap on any thread count.

use crate::common;

use common::bodies::BodiesChecker;
use common::cli::{stdout, viaroad};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use viaroad::deadline::Deadline;
use viaroad::local::LocalSpec;
use viaroad::oracle::CallCounts;
use viaroad::roadmap::bounce::random_bounce;
use viaroad::roadmap::{Budget, LearnParams, Learner};
use viaroad::scene::Scene;
use viaroad::space::Config;

fn shipped(k: usize) -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/bodies");
    Scene::load(&dir.join(format!("swap-corridor-{k}.toml"))).unwrap()
}

/// Which coordinates differ between `a` and `b` (bit for bit).
fn changed(a: &[f64], b: &[f64]) -> Vec<usize> {
    (0..a.len()).filter(|&i| a[i] != b[i]).collect()
}

/// Walks whose every step the independent checker re-checks (conservative advancement along a
/// slide across the corridor takes many steps); the rest are only counted.
const CERTIFIED_WALKS: u64 = 3;

#[test]
fn walks_of_several_bodies_are_certified_single_group_steps() {
    let scene = shipped(3);
    let oracle = scene.oracle();
    let groups = scene.space.groups(false);
    let checker = BodiesChecker::new(&scene);
    let start = scene.queries[0].start.clone();
    let (mut one_body, mut several, mut turns, mut in_niche) = (0, 0, 0, 0);
    for seed in 0..40 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut counts = CallCounts::default();
        let corners = random_bounce(
            &scene.space,
            oracle.as_ref(),
            &groups,
            &start,
            8,
            &mut rng,
            &mut counts,
            &Deadline::none(),
        )
        .unwrap();
        assert!(counts.line_calls > 0);
        let mut prev: Config = start.clone();
        for q in &corners {
            assert!(scene.space.in_bounds(q), "{q:?}");
            if seed < CERTIFIED_WALKS {
                checker
                    .certify_motion(&prev, q)
                    .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            }
            let c = changed(&prev, q);
            assert!(!c.is_empty());
            if c.iter().all(|i| i % 3 == 2) {
                // a turn: one body's angle
                assert_eq!(c.len(), 1, "{c:?}");
                turns += 1;
            } else {
                // a translation: positions only
                assert!(c.iter().all(|i| i % 3 != 2), "{c:?}");
                let bodies: std::collections::BTreeSet<usize> = c.iter().map(|i| i / 3).collect();
                if bodies.len() == 1 {
                    one_body += 1;
                } else {
                    several += 1;
                }
            }
            // the last square above the corridor, in the niche
            if q[7] > 1.2 {
                in_niche += 1;
            }
            prev = q.clone();
        }
    }
    assert!(
        one_body > 50 && several > 0 && turns > 0,
        "{one_body} {several} {turns}"
    );
    assert!(in_niche > 0, "no walk reached the niche");
}

#[test]
fn a_swap_of_four_is_solved_through_a_roadmap_of_slides() {
    // a node budget: the same answer on any machine
    let file = "scenes/bodies/swap-corridor-4.toml";
    let args = ["solve", file, "--roadmap", "--nodes", "3000", "--json"];
    let o = viaroad(&args);
    let out = stdout(&o);
    assert!(o.status.success(), "{args:?}: {}", common::cli::stderr(&o));
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["solved"], true, "{out}");
    assert_eq!(v["stop"], "Connected", "{out}");
    let scene = shipped(4);
    let q = &scene.queries[0];
    let checker = BodiesChecker::new(&scene);
    for key in ["path", "shortened"] {
        let path: Vec<Config> = serde_json::from_value(v[key].clone()).unwrap();
        assert!(scene.space.distance(&path[0], &q.start) < 1e-9);
        assert!(scene.space.distance(path.last().unwrap(), &q.goal) < 1e-9);
        checker
            .certify_path(&path)
            .unwrap_or_else(|e| panic!("{key}: {e}"));
    }
}

/// The roadmap grown between the swap of three's start and goal, as bytes, on `threads`
/// threads.
fn grown(scene: &Scene, threads: usize) -> (bool, Vec<u8>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let oracle = scene.oracle();
        let method = LocalSpec::roadmap_default().build();
        let q = &scene.queries[0];
        let pair = Learner::for_scene(scene, oracle.as_ref(), method.as_ref())
            .connect_pair(
                &LearnParams::default(),
                None,
                (&q.start, &q.goal),
                &Budget::nodes(2000),
                3,
                &Deadline::none(),
                &mut |_| {},
            )
            .unwrap();
        (pair.connected, pair.learnt.roadmap.to_bytes().unwrap())
    })
}

#[test]
fn walks_of_several_bodies_give_the_same_roadmap_on_any_thread_count() {
    let scene = shipped(3);
    let (connected, one) = grown(&scene, 1);
    assert!(connected, "the swap of three was not joined in 2000 nodes");
    for threads in [2, 3] {
        assert!(grown(&scene, threads).1 == one, "{threads} threads");
    }
}
