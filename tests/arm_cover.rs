//! Outer sphere covers (`viaroad::robot::cover`): every collision polytope of the Panda lies in
//! its cover's balls (every vertex and points spread over every triangle), the static test gives
//! the same verdicts with the covers as without them, and every straight motion the oracle
//! proves free with the covers (near the cage's bars, where they decide pairs and windows) is
//! free under the independent [`ArmChecker`] at 1/10 of OMPL's resolution.

use crate::common;

use common::arms::arms_dir;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use viaroad::oracle::CallCounts;
use viaroad::robot::arm::GroupChoice;
use viaroad::robot::ArmChecker;
use viaroad::scene::{Robot, Scene};

fn cage_scene() -> Scene {
    Scene::load(&arms_dir().join("panda-cage-1.toml")).unwrap()
}

#[test]
fn every_panda_polytope_lies_in_its_cover() {
    let arm = common::arms::panda(GroupChoice::FirstSrdfGroup);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut shapes = 0;
    for s in &arm.shapes {
        assert!(!s.cover.is_empty(), "link {} has no cover", s.link);
        assert!(s.cover.len() <= viaroad::robot::cover::MOST_BALLS);
        let inside =
            |p: &nalgebra::Point3<f64>| s.cover.iter().any(|b| (p - b.centre).norm() <= b.radius);
        let m = &s.polytope;
        for v in &m.vertices {
            assert!(inside(v), "link {}: vertex {v:?} outside its cover", s.link);
        }
        for t in 0..m.triangles.len() {
            let [a, b, c] = m.triangle(t);
            for _ in 0..4 {
                let (mut u, mut w) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
                if u + w > 1.0 {
                    (u, w) = (1.0 - u, 1.0 - w);
                }
                let p = a + (b - a) * u + (c - a) * w;
                assert!(inside(&p), "link {}: {p:?} of triangle {t} outside", s.link);
            }
        }
        // not vacuous: the balls stand off the polytope by a fraction of the one ball about it
        let (lo, hi) = m.aabb();
        let one = (hi - lo).norm() / 2.0;
        let most = s.cover.iter().map(|b| b.radius).fold(0.0, f64::max);
        assert!(
            most <= one * (1.0 + 1e-6),
            "link {}: {most} > {one}",
            s.link
        );
        shapes += 1;
    }
    assert!(shapes >= 8, "only {shapes} shapes");
}

#[test]
fn covers_keep_the_static_verdicts_and_every_motion_they_prove_is_free() {
    let scene = cage_scene();
    let Robot::Arm(a) = &scene.robot else {
        panic!("not an arm scene")
    };
    let with = a.arm_oracle();
    let without = (**with).clone().with_covers(false);
    let checker = ArmChecker::new(&a.arm, &a.objects).unwrap();
    let step = 0.001 * checker.arm().group.max_extent();
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let mut counts = CallCounts::default();
    let configs: Vec<_> = (0..400)
        .map(|_| scene.space.sample_uniform(&mut rng))
        .collect();
    // the reference on a thread of its own: the static memo is per thread (and per oracle id,
    // which the clone shares), so no verdict of one is read by the other
    let reference: Vec<bool> = std::thread::scope(|s| {
        s.spawn(|| {
            let mut counts = CallCounts::default();
            configs
                .iter()
                .map(|q| without.collides(q, &mut counts).unwrap())
                .collect()
        })
        .join()
        .unwrap()
    });
    let mut free_configs = Vec::new();
    for (q, expected) in configs.iter().zip(reference) {
        let verdict = with.collides(q, &mut counts).unwrap();
        assert_eq!(verdict, expected, "{q:?}");
        if !verdict {
            free_configs.push(q.clone());
        }
    }
    assert!(free_configs.len() >= 40, "{} free", free_configs.len());
    let (mut proved, mut asked) = (0, 0);
    for (k, q0) in free_configs.iter().enumerate() {
        let reach = [0.05, 0.2, 0.6][k % 3];
        let q1 = common::arms::near(&scene, q0, reach, &mut rng);
        asked += 1;
        if with.straight_free(q0, &q1, &mut counts).unwrap() {
            let path = [q0.clone(), q1];
            let report = checker.check_path(&path, step).unwrap();
            assert!(
                report.valid,
                "proved free, the checker refuses it: {path:?} {report:?}"
            );
            proved += 1;
        }
    }
    assert!(
        proved >= asked / 4,
        "only {proved} of {asked} motions proved free"
    );
}
