//! Issue 11, part 2: the polygon and polyhedra oracles allocate nothing per call in steady
//! state but their answer. A counting global allocator counts the allocations of the current
//! thread; after a warm-up that lets the per-thread scratch space (pieces, per-face and
//! per-node caches) grow, `motion_is_free`, `collides` and `intervals_into` must make none,
//! and `intervals` at most one (the answer's list). The answers are compared with the first pass, so a
//! scratch space that leaks state from one call into the next cannot pass either.

use std::f64::consts::PI;
use std::path::Path;

use viaroad::geometry::TriMesh;
use viaroad::interval::IntervalList;
use viaroad::oracle::polygons::Polygons;
use viaroad::oracle::polyhedra::Polyhedra;
use viaroad::oracle::{CallCounts, CollisionOracle, Workspace};
use viaroad::scene::{Obstacle, Robot, Scene};
use viaroad::space::{Change, Motion};

#[path = "common/counting_alloc.rs"]
mod counting_alloc;
use counting_alloc::allocations;

#[global_allocator]
static GLOBAL: counting_alloc::Counting = counting_alloc::Counting;

fn load(file: &str) -> Scene {
    Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(file)).unwrap()
}

/// A low-discrepancy point of the unit cube (deterministic, no RNG needed).
fn halton(i: usize, base: usize) -> f64 {
    let (mut f, mut r, mut i) = (1.0, 0.0, i + 1);
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r
}

/// Translations and turns from poses spread over the scene's bounds: some free, some deep in
/// collision, some grazing.
fn motions(scene: &Scene, n: usize) -> Vec<Motion> {
    let (lo, hi) = (scene.space.lower(), scene.space.upper());
    let dim = lo.len();
    let extent = scene.space.extent();
    let mut out = Vec::new();
    for i in 0..n {
        let at = |k: usize, b: usize| lo[k] + (hi[k] - lo[k]) * halton(i, b);
        let primes = [2, 3, 5, 7, 11, 13];
        let (origin, step, axis) = if dim == 2 {
            let o = vec![at(0, 2), at(1, 3), PI * (2.0 * halton(i, 5) - 1.0)];
            (o, vec![0.0; 3], [0.0, 0.0, 1.0])
        } else {
            let a = [halton(i, 7), halton(i, 11), halton(i, 13)].map(|x| 2.0 * x - 1.0);
            let n2 = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(1e-9);
            let axis = a.map(|x| x / n2);
            let half = PI * halton(i, 5) / 2.0;
            let (s, c) = half.sin_cos();
            let o = vec![
                at(0, primes[0]),
                at(1, primes[1]),
                at(2, primes[2]),
                axis[0] * s,
                axis[1] * s,
                axis[2] * s,
                c,
            ];
            (o, vec![0.0; 7], axis)
        };
        let mut d = step;
        let len = extent * (0.02 + 0.2 * halton(i, 17));
        d[0] = len * (halton(i, 19) - 0.5);
        d[1] = len * (halton(i, 23) - 0.5);
        if dim == 3 {
            d[2] = len * (halton(i, 29) - 0.5);
        }
        if i % 2 == 0 {
            out.push(Motion::segment(origin, Change::Linear(d)));
        } else {
            let change = if dim == 2 {
                let mut w = vec![0.0; 3];
                w[2] = 3.0 * (halton(i, 31) - 0.5);
                Change::Linear(w)
            } else {
                Change::Rotation {
                    axis,
                    angle: 2.0 * halton(i, 31),
                }
            };
            out.push(Motion::segment(origin, change));
        }
    }
    out
}

/// Runs every kind of call twice (the first pass warms the scratch space up), checks that the
/// second pass answers the same and counts its allocations per kind.
fn check(oracle: &dyn CollisionOracle, ms: &[Motion]) -> usize {
    let pass = || {
        let mut c = CallCounts::default();
        ms.iter()
            .map(|m| {
                (
                    oracle.intervals(m, &mut c).unwrap(),
                    oracle.motion_is_free(m, &mut c).unwrap(),
                    oracle.collides(&m.origin, &mut c),
                )
            })
            .collect::<Vec<_>>()
    };
    let first = pass();
    let colliding = first.iter().filter(|a| !a.0.is_empty()).count();
    let mut c = CallCounts::default();
    for (m, want) in ms.iter().zip(&first) {
        let before = allocations();
        let free = oracle.motion_is_free(m, &mut c).unwrap();
        let stat = oracle.collides(&m.origin, &mut c);
        assert_eq!(allocations(), before, "a yes/no call allocated");
        assert_eq!((free, stat), (want.1, want.2));
        let before = allocations();
        let ivs = oracle.intervals(m, &mut c).unwrap();
        assert!(
            allocations() - before <= 1,
            "intervals allocated more than its answer"
        );
        assert_eq!(ivs, want.0);
    }
    // the allocation-free twin: once its buffers have grown (two warm-up passes: a rotation
    // swaps the answer's buffer with the scratch one), nothing at all, and the same answers
    let (mut ws, mut out) = (Workspace::new(), IntervalList::default());
    for _ in 0..2 {
        for m in ms {
            oracle.intervals_into(m, &mut out, &mut ws, &mut c).unwrap();
        }
    }
    for (m, want) in ms.iter().zip(&first) {
        let before = allocations();
        oracle.intervals_into(m, &mut out, &mut ws, &mut c).unwrap();
        assert_eq!(allocations(), before, "intervals_into allocated");
        assert_eq!(out, want.0);
    }
    colliding
}

#[test]
fn polyhedra_calls_allocate_only_their_answer() {
    for file in ["scenes/ompl/3D/Easy.cfg", "scenes/cube-into-box.toml"] {
        let scene = load(file);
        let Robot::Mesh(robot) = &scene.robot else {
            panic!("{file}: not a mesh robot")
        };
        let obstacles: Vec<TriMesh> = scene
            .obstacles
            .iter()
            .filter_map(|o| match o {
                Obstacle::Mesh(m) => Some(m.clone()),
                _ => None,
            })
            .collect();
        let oracle = Polyhedra::new(robot.clone(), obstacles);
        let ms = motions(&scene, 60);
        let colliding = check(&oracle, &ms);
        // both kinds of answer occur, so both paths were exercised
        assert!(colliding > 0 && colliding < ms.len(), "{file}: {colliding}");
    }
}

#[test]
fn polygon_calls_allocate_only_their_answer() {
    let scene = load("scenes/se2-corridor.toml");
    let Robot::Polygons(robot) = &scene.robot else {
        panic!("not a polygon robot")
    };
    let obstacles = scene
        .obstacles
        .iter()
        .filter_map(|o| match o {
            Obstacle::Polygon(p) => Some(p.clone()),
            _ => None,
        })
        .collect();
    let oracle = Polygons::new(robot.clone(), obstacles);
    let ms = motions(&scene, 80);
    let colliding = check(&oracle, &ms);
    assert!(colliding > 0 && colliding < ms.len(), "{colliding}");
}
