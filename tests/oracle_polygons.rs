//! The polygon oracle (SE(2)) against an independent reference: parry2d's static
//! `intersection_test` on the triangles of an ear clipping written here, sampled densely along
//! every motion; hand-computed cases; regressions.
//!
//! Where the two disagree, the placement must be a near-touching one (parry's signed distance
//! within `NEAR` of zero) — there either answer is right. Every interval endpoint strictly
//! inside the motion's range must be such a touching placement.

use nalgebra::{Point2, Vector2, Vector3};
use parry2d_f64::math::Isometry;
use parry2d_f64::query;
use parry2d_f64::shape::Triangle;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};
use viaroad::geometry::{Polygon, TriMesh};
use viaroad::interval::{Interval, IntervalList};
use viaroad::oracle::polygons::{footprint_polygons, Polygons};
use viaroad::oracle::{CallCounts, CollisionOracle, OracleError};
use viaroad::space::{Change, Motion};

/// Signed distances within this of zero count as touching.
const NEAR: f64 = 1e-7;

// ---------------------------------------------------------------------------------------------
// the reference

/// Ear clipping, written independently of the oracle's: O(n³), for test-sized polygons.
fn ear_clip(poly: &Polygon) -> Vec<[Point2<f64>; 3]> {
    let cross = |o: Point2<f64>, a: Point2<f64>, b: Point2<f64>| (a - o).perp(&(b - o));
    let mut v: Vec<Point2<f64>> = poly.vertices.clone();
    if cross(v[0], v[1], v[2]) == 0.0 && v.len() == 3 {
        return vec![];
    }
    let mut out = Vec::new();
    while v.len() > 3 {
        let n = v.len();
        let ear = (0..n).find(|&i| {
            let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
            cross(a, b, c) > 0.0
                && (0..n).all(|j| {
                    let p = v[j];
                    p == a
                        || p == b
                        || p == c
                        || !(cross(a, b, p) >= 0.0
                            && cross(b, c, p) >= 0.0
                            && cross(c, a, p) >= 0.0)
                })
        });
        let i = ear.expect("test polygons are simple");
        out.push([v[(i + n - 1) % n], v[i], v[(i + 1) % n]]);
        v.remove(i);
    }
    out.push([v[0], v[1], v[2]]);
    out
}

struct Reference {
    robot: Vec<Triangle>,
    obstacles: Vec<Triangle>,
}

fn tri_box(t: &Triangle) -> ([f64; 2], [f64; 2]) {
    let xs = [t.a.x, t.b.x, t.c.x];
    let ys = [t.a.y, t.b.y, t.c.y];
    (
        [
            xs.iter().cloned().fold(f64::INFINITY, f64::min),
            ys.iter().cloned().fold(f64::INFINITY, f64::min),
        ],
        [
            xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
            ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        ],
    )
}

fn boxes_near(a: &([f64; 2], [f64; 2]), b: &([f64; 2], [f64; 2]), margin: f64) -> bool {
    a.0[0] <= b.1[0] + margin
        && b.0[0] <= a.1[0] + margin
        && a.0[1] <= b.1[1] + margin
        && b.0[1] <= a.1[1] + margin
}

impl Reference {
    fn new(robot: &[Polygon], obstacles: &[Polygon]) -> Reference {
        let tris = |ps: &[Polygon]| {
            ps.iter()
                .flat_map(ear_clip)
                .map(|[a, b, c]| Triangle::new(a, b, c))
                .collect()
        };
        Reference {
            robot: tris(robot),
            obstacles: tris(obstacles),
        }
    }

    fn placed(&self, q: &[f64]) -> Vec<Triangle> {
        let iso = Isometry::new(Vector2::new(q[0], q[1]), q[2]);
        self.robot
            .iter()
            .map(|t| Triangle::new(iso * t.a, iso * t.b, iso * t.c))
            .collect()
    }

    /// parry's static test, triangle against triangle.
    fn collides(&self, q: &[f64]) -> bool {
        let id = Isometry::identity();
        self.placed(q).iter().any(|r| {
            let rb = tri_box(r);
            self.obstacles.iter().any(|o| {
                boxes_near(&rb, &tri_box(o), 1e-9)
                    && query::intersection_test(&id, r, &id, o).unwrap()
            })
        })
    }

    /// Smallest distance if free, minus the largest penetration depth if not.
    fn signed_distance(&self, q: &[f64]) -> f64 {
        let id = Isometry::identity();
        let mut best_gap = f64::INFINITY;
        let mut deepest = 0.0f64;
        let mut hit = false;
        for r in &self.placed(q) {
            let rb = tri_box(r);
            for o in &self.obstacles {
                if !boxes_near(&rb, &tri_box(o), 1e-3) {
                    continue;
                }
                if query::intersection_test(&id, r, &id, o).unwrap() {
                    hit = true;
                    if let Some(c) = query::contact(&id, r, &id, o, 0.0).unwrap() {
                        deepest = deepest.max(-c.dist);
                    }
                } else {
                    best_gap = best_gap.min(query::distance(&id, r, &id, o).unwrap());
                }
            }
        }
        if hit {
            -deepest
        } else {
            best_gap
        }
    }

    fn near_touching(&self, q: &[f64]) -> bool {
        self.signed_distance(q).abs() <= NEAR
    }
}

// ---------------------------------------------------------------------------------------------
// random scenes

fn convex(rng: &mut ChaCha8Rng, centre: [f64; 2], radius: f64) -> Polygon {
    let k = rng.random_range(3..8);
    let mut angles: Vec<f64> = (0..k).map(|_| rng.random_range(0.0..TAU)).collect();
    angles.sort_by(f64::total_cmp);
    let pts = angles
        .iter()
        .map(|a| Point2::new(centre[0] + radius * a.cos(), centre[1] + radius * a.sin()))
        .collect();
    Polygon::new(pts).unwrap_or_else(|_| Polygon::rectangle(centre, [radius, radius]).unwrap())
}

/// A star-shaped, usually non-convex polygon around `centre`.
fn star(rng: &mut ChaCha8Rng, centre: [f64; 2], radius: f64) -> Polygon {
    let k = rng.random_range(5..10);
    let pts = (0..k)
        .map(|i| {
            let a = (i as f64 + rng.random_range(0.1..0.9)) * TAU / k as f64;
            let r = radius * rng.random_range(0.3..1.0);
            Point2::new(centre[0] + r * a.cos(), centre[1] + r * a.sin())
        })
        .collect();
    Polygon::new(pts).unwrap()
}

fn shape(rng: &mut ChaCha8Rng, centre: [f64; 2], radius: f64) -> Polygon {
    if rng.random_bool(0.5) {
        convex(rng, centre, radius)
    } else {
        star(rng, centre, radius)
    }
}

struct Scene {
    robot: Vec<Polygon>,
    obstacles: Vec<Polygon>,
}

/// Obstacles in [−10, 10]², sometimes broken into a soup of triangles (as OMPL's footprints
/// are), a robot of one to three parts near its reference point.
fn random_scene(seed: u64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let count = rng.random_range(3..9);
    let mut obstacles: Vec<Polygon> = (0..count)
        .map(|_| {
            let c = [rng.random_range(-9.0..9.0), rng.random_range(-9.0..9.0)];
            let r = rng.random_range(0.5..3.0);
            shape(&mut rng, c, r)
        })
        .collect();
    if rng.random_bool(0.3) {
        obstacles = obstacles
            .iter()
            .flat_map(ear_clip)
            .map(|t| Polygon::new(t.to_vec()).unwrap())
            .collect();
    }
    let parts = rng.random_range(1..4);
    let robot = (0..parts)
        .map(|_| {
            let c = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            let r = rng.random_range(0.3..2.0);
            shape(&mut rng, c, r)
        })
        .collect();
    Scene { robot, obstacles }
}

fn random_config(rng: &mut ChaCha8Rng) -> Vec<f64> {
    vec![
        rng.random_range(-10.0..10.0),
        rng.random_range(-10.0..10.0),
        rng.random_range(-PI..PI),
    ]
}

// ---------------------------------------------------------------------------------------------
// the check

/// The part of the range to sample: all of a bounded range; for a line, the part beyond which
/// the robot is far from every obstacle (asserting that no interval reaches further).
fn checked_range(motion: &Motion, hits: &IntervalList, reach: f64) -> Interval {
    if motion.range.is_bounded() {
        return motion.range;
    }
    let Change::Linear(d) = &motion.change else {
        unreachable!()
    };
    let speed = d[0].hypot(d[1]);
    let t = (motion.origin[0].hypot(motion.origin[1]) + reach) / speed + 1.0;
    let window = Interval { lo: -t, hi: t };
    for iv in hits {
        assert!(
            iv.lo >= window.lo && iv.hi <= window.hi,
            "interval {iv:?} of a line beyond the scene ({window:?})"
        );
    }
    window
}

/// Checks `hits` for `motion` against the reference; `reach` bounds the scene plus the robot.
fn check_motion(reference: &Reference, motion: &Motion, hits: &IntervalList, reach: f64) {
    let range = checked_range(motion, hits, reach);
    let n = 400;
    let h = (range.hi - range.lo) / n as f64;
    let mut probes: Vec<f64> = (0..=n).map(|i| range.lo + h * i as f64).collect();
    for iv in hits {
        for e in [iv.lo, iv.hi] {
            if e > range.lo && e < range.hi {
                // every endpoint strictly inside the range is a touching placement
                let sd = reference.signed_distance(&motion.at(e));
                assert!(
                    sd.abs() <= NEAR,
                    "endpoint {e} of {iv:?}: parry's signed distance there is {sd}\n{motion:?}\n{hits:?}"
                );
            }
            for off in [0.5 * h, 1e-4 * h] {
                probes.extend([e - off, e + off]);
            }
        }
    }
    for t in probes {
        if !range.contains(t) {
            continue;
        }
        let q = motion.at(t);
        let ours = hits.contains(t);
        if ours != reference.collides(&q) && !reference.near_touching(&q) {
            panic!(
                "t = {t}: oracle says {}, parry says {} (signed distance {})\n{motion:?}\n{hits:?}",
                if ours { "collision" } else { "free" },
                if ours { "free" } else { "collision" },
                reference.signed_distance(&q)
            );
        }
    }
}

fn reach_of(scene: &Scene) -> f64 {
    let obstacle_reach = scene
        .obstacles
        .iter()
        .flat_map(|p| p.vertices.iter())
        .map(|v| v.coords.norm())
        .fold(0.0, f64::max);
    let robot_reach = scene.robot.iter().map(Polygon::radius).fold(0.0, f64::max);
    obstacle_reach + robot_reach
}

fn translation(rng: &mut ChaCha8Rng) -> Motion {
    let origin = random_config(rng);
    let a = rng.random_range(0.0..TAU);
    if rng.random_bool(0.25) {
        Motion::line(origin, Change::Linear(vec![a.cos(), a.sin(), 0.0]))
    } else {
        let len = rng.random_range(0.0..16.0);
        Motion::segment(
            origin,
            Change::Linear(vec![len * a.cos(), len * a.sin(), 0.0]),
        )
    }
}

fn rotation(rng: &mut ChaCha8Rng) -> Motion {
    let origin = random_config(rng);
    match rng.random_range(0..5) {
        0 => Motion::turn(origin, Change::Linear(vec![0.0, 0.0, TAU])),
        1 => Motion::segment(
            origin,
            Change::Linear(vec![0.0, 0.0, rng.random_range(-3.0 * TAU..3.0 * TAU)]),
        ),
        _ => Motion::segment(
            origin,
            Change::Linear(vec![0.0, 0.0, rng.random_range(-PI..PI)]),
        ),
    }
}

fn run_motions(seed: u64, make: fn(&mut ChaCha8Rng) -> Motion, motions: usize) {
    let scene = random_scene(seed);
    let reference = Reference::new(&scene.robot, &scene.obstacles);
    let oracle = Polygons::new(scene.robot.clone(), scene.obstacles.clone());
    let reach = reach_of(&scene);
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    for _ in 0..motions {
        let motion = make(&mut rng);
        let mut counts = CallCounts::default();
        let hits = oracle.intervals(&motion, &mut counts).unwrap();
        assert!(hits
            .iter()
            .all(|iv| motion.range.contains(iv.lo) && motion.range.contains(iv.hi)));
        check_motion(&reference, &motion, &hits, reach);
        // the yes/no answer agrees with the intervals
        let free = oracle
            .motion_is_free(&motion, &mut CallCounts::default())
            .unwrap();
        assert_eq!(free, hits.is_empty(), "{motion:?}: {hits:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// 2000 random translations (segments and unbounded lines) in 200 random scenes.
    #[test]
    fn translations_agree_with_parry(seed in any::<u64>()) {
        run_motions(seed, translation, 10);
    }

    /// 2000 random rotations (short turns, full turns, several turns) in 200 random scenes.
    #[test]
    fn rotations_agree_with_parry(seed in any::<u64>()) {
        run_motions(seed, rotation, 10);
    }

    /// Static placements: the oracle's `collides` against parry.
    #[test]
    fn static_checks_agree_with_parry(seed in any::<u64>()) {
        let scene = random_scene(seed);
        let reference = Reference::new(&scene.robot, &scene.obstacles);
        let oracle = Polygons::new(scene.robot.clone(), scene.obstacles.clone());
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..40 {
            let q = random_config(&mut rng);
            let ours = oracle.collides(&q, &mut CallCounts::default());
            prop_assert!(
                ours == reference.collides(&q) || reference.near_touching(&q),
                "q = {:?}: oracle {}, signed distance {}", q, ours, reference.signed_distance(&q)
            );
        }
    }

    /// Enveloping only skips work: the same intervals with and without it, fewer pairs.
    #[test]
    fn enveloping_changes_nothing_but_the_work(seed in any::<u64>()) {
        let scene = random_scene(seed);
        let fast = Polygons::new(scene.robot.clone(), scene.obstacles.clone());
        let slow = fast.clone().with_enveloping(false);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for i in 0..8 {
            let motion = if i % 2 == 0 { translation(&mut rng) } else { rotation(&mut rng) };
            let (mut cf, mut cs) = (CallCounts::default(), CallCounts::default());
            let a = fast.intervals(&motion, &mut cf).unwrap();
            let b = slow.intervals(&motion, &mut cs).unwrap();
            prop_assert_eq!(&a, &b, "{:?}", motion);
            prop_assert!(cf.pairs_tested <= cs.pairs_tested);
        }
    }
}

/// Shrunk proptest cases: turned angles mapped back to `t` missed the ends of the range by
/// rounding (an interval ending at 0.9999999999999999, one starting at 5.6e-17).
#[test]
fn rotations_reach_the_ends_of_the_range_exactly() {
    run_motions(7341538607560776058, rotation, 10);
    run_motions(13628586910948642205, rotation, 10);
}

// ---------------------------------------------------------------------------------------------
// hand-computed cases

fn unit_square() -> Vec<Polygon> {
    vec![Polygon::rectangle([0.0, 0.0], [0.5, 0.5]).unwrap()]
}

fn intervals(oracle: &Polygons, motion: &Motion) -> Vec<Interval> {
    oracle
        .intervals(motion, &mut CallCounts::default())
        .unwrap()
        .as_slice()
        .to_vec()
}

fn assert_intervals(got: &[Interval], want: &[(f64, f64)], tol: f64) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g.lo - w.0).abs() <= tol && (g.hi - w.1).abs() <= tol,
            "{got:?} vs {want:?}"
        );
    }
}

#[test]
fn unit_square_slides_through_a_box() {
    // the box [3, 5] × [−1, 1]; the square's centre from x = 0 to x = 10: contact for
    // x ∈ [2.5, 5.5]
    let oracle = Polygons::new(
        unit_square(),
        vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()],
    );
    let seg = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![10.0, 0.0, 0.0]));
    assert_intervals(&intervals(&oracle, &seg), &[(0.25, 0.55)], 1e-9);
    // the same as an unbounded line at unit speed
    let line = Motion::line(vec![0.0, 0.0, 0.0], Change::Linear(vec![1.0, 0.0, 0.0]));
    assert_intervals(&intervals(&oracle, &line), &[(2.5, 5.5)], 1e-9);
    // turned by 45°, the square is a diamond whose corners lie √½ from its centre on the path:
    // contact while the centre is in [3 − √½, 5 + √½]
    let h = 0.5f64.sqrt();
    let turned = Motion::segment(
        vec![0.0, 0.0, PI / 4.0],
        Change::Linear(vec![10.0, 0.0, 0.0]),
    );
    assert_intervals(
        &intervals(&oracle, &turned),
        &[((3.0 - h) / 10.0, (5.0 + h) / 10.0)],
        1e-9,
    );
}

#[test]
fn unit_square_grazing_along_a_box_touches_all_the_way() {
    // the square's bottom edge y = 1 slides along the box's top edge y = 1 (collinear edges)
    let oracle = Polygons::new(
        unit_square(),
        vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()],
    );
    let touching = Motion::segment(vec![0.0, 1.5, 0.0], Change::Linear(vec![10.0, 0.0, 0.0]));
    assert_intervals(&intervals(&oracle, &touching), &[(0.25, 0.55)], 1e-9);
    let above = Motion::segment(
        vec![0.0, 1.5 + 1e-6, 0.0],
        Change::Linear(vec![10.0, 0.0, 0.0]),
    );
    assert!(intervals(&oracle, &above).is_empty());
}

/// θ* with 2 sin θ + 0.05 cos θ = 1: when the corner (2, 0.05) of the bar reaches y = 1.
fn bar_contact_angle() -> f64 {
    (1.0 / (4.0f64 + 0.0025).sqrt()).asin() - 0.05f64.atan2(2.0)
}

fn bar_and_wall() -> Polygons {
    let bar = Polygon::new(vec![
        Point2::new(0.0, -0.05),
        Point2::new(2.0, -0.05),
        Point2::new(2.0, 0.05),
        Point2::new(0.0, 0.05),
    ])
    .unwrap();
    let wall = Polygon::rectangle([0.0, 1.5], [5.0, 0.5]).unwrap();
    Polygons::new(vec![bar], vec![wall])
}

#[test]
fn a_bar_turning_into_a_wall() {
    let oracle = bar_and_wall();
    let s = bar_contact_angle();
    // half a turn from θ = 0: contact from θ* until the bar, past vertical, leaves at π − θ*
    let half = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, PI]));
    assert_intervals(&intervals(&oracle, &half), &[(s / PI, 1.0 - s / PI)], 1e-9);
    // turning the other way from θ = π: the same placements, the parameter reversed
    let back = Motion::segment(vec![0.0, 0.0, PI], Change::Linear(vec![0.0, 0.0, -PI]));
    assert_intervals(&intervals(&oracle, &back), &[(s / PI, 1.0 - s / PI)], 1e-9);
    // a full turn about θ = 0: t ∈ [−½, ½] covers φ ∈ [−π, π]
    let turn = Motion::turn(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU]));
    assert_intervals(
        &intervals(&oracle, &turn),
        &[(s / TAU, (PI - s) / TAU)],
        1e-9,
    );
    // two full turns: the contact twice
    let twice = Motion::segment(
        vec![0.0, 0.0, 0.0],
        Change::Linear(vec![0.0, 0.0, 2.0 * TAU]),
    );
    let q = 2.0 * TAU;
    assert_intervals(
        &intervals(&oracle, &twice),
        &[(s / q, (PI - s) / q), ((TAU + s) / q, (TAU + PI - s) / q)],
        1e-9,
    );
    // stopping just short of contact is free
    let short = Motion::segment(
        vec![0.0, 0.0, 0.0],
        Change::Linear(vec![0.0, 0.0, s - 1e-6]),
    );
    assert!(intervals(&oracle, &short).is_empty());
    assert!(oracle
        .motion_is_free(&short, &mut CallCounts::default())
        .unwrap());
    assert!(!oracle
        .motion_is_free(&half, &mut CallCounts::default())
        .unwrap());
}

#[test]
fn containment_either_way_is_collision() {
    // a small robot triangle wholly inside a large obstacle triangle: no edges meet
    let small = vec![Polygon::new(vec![
        Point2::new(-0.1, -0.1),
        Point2::new(0.1, -0.1),
        Point2::new(0.0, 0.1),
    ])
    .unwrap()];
    let big = vec![Polygon::new(vec![
        Point2::new(-10.0, -5.0),
        Point2::new(10.0, -5.0),
        Point2::new(0.0, 10.0),
    ])
    .unwrap()];
    let oracle = Polygons::new(small.clone(), big.clone());
    assert!(oracle.collides(&[0.0, 0.0, 1.0], &mut CallCounts::default()));
    assert!(!oracle.collides(&[0.0, -6.0, 1.0], &mut CallCounts::default()));
    // moving out downwards from inside: collision until the top vertex passes y = −5
    let out = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, -10.0, 0.0]));
    assert_intervals(&intervals(&oracle, &out), &[(0.0, 0.51)], 1e-9);
    // spinning in place inside: collision all the time
    let spin = Motion::turn(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU]));
    assert_intervals(&intervals(&oracle, &spin), &[(-0.5, 0.5)], 1e-12);

    // the other way round: a large robot passing over a small obstacle
    let oracle = Polygons::new(
        big,
        vec![small[0].clone().translated(Vector2::new(0.0, 20.0))],
    );
    assert!(oracle.collides(&[0.0, 20.0, 0.0], &mut CallCounts::default()));
    let over = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 40.0, 0.0]));
    // the obstacle's top vertex (0, 20.1) meets the robot's base y = −5 + 40 t at t = 0.6275,
    // its lowest edge y = 19.9 leaves the apex y = 10 + 40 t at t = 0.2475
    assert_intervals(&intervals(&oracle, &over), &[(0.2475, 0.6275)], 1e-9);
    // spinning the big robot at the origin: it reaches √125 ≈ 11.2, the obstacle is at 20
    let spin = Motion::turn(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU]));
    assert!(intervals(&oracle, &spin).is_empty());
}

#[test]
fn far_away_obstacles_cost_nothing() {
    // one box near the path, a thousand small triangles far away
    let mut obstacles = vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()];
    for i in 0..1000 {
        let (x, y) = (100.0 + (i % 40) as f64 * 3.0, 100.0 + (i / 40) as f64 * 3.0);
        obstacles.push(
            Polygon::new(vec![
                Point2::new(x, y),
                Point2::new(x + 1.0, y),
                Point2::new(x, y + 1.0),
            ])
            .unwrap(),
        );
    }
    let fast = Polygons::new(unit_square(), obstacles);
    let slow = fast.clone().with_enveloping(false);
    assert_eq!(fast.obstacle_edge_count(), 4 + 3000);
    for motion in [
        Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![10.0, 0.0, 0.0])),
        Motion::line(vec![0.0, 0.0, 0.0], Change::Linear(vec![1.0, 0.0, 0.0])),
        Motion::turn(vec![2.3, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU])),
    ] {
        let (mut cf, mut cs) = (CallCounts::default(), CallCounts::default());
        let a = fast.intervals(&motion, &mut cf).unwrap();
        let b = slow.intervals(&motion, &mut cs).unwrap();
        assert_eq!(a, b);
        assert!(!a.is_empty());
        // 4 robot edges × 4 box edges, 1 × 2 box triangles, 1001 obstacle refs × 2 robot triangles
        assert!(
            cf.pairs_tested <= 16 + 2 + 2,
            "{motion:?}: {} pairs",
            cf.pairs_tested
        );
        assert!(cs.pairs_tested >= 4 * 3004, "{} pairs", cs.pairs_tested);
    }
}

#[test]
fn unsupported_motions_are_errors_not_panics() {
    let oracle = Polygons::new(
        unit_square(),
        vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()],
    );
    let mut c = CallCounts::default();
    let unsupported =
        |r: Result<IntervalList, OracleError>| matches!(r, Err(OracleError::Unsupported(_)));
    let mixed = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![1.0, 0.0, 1.0]));
    assert!(unsupported(oracle.intervals(&mixed, &mut c)));
    assert!(oracle.motion_is_free(&mixed, &mut c).is_err());
    let se3 = Motion::segment(
        vec![0.0, 0.0, 0.0],
        Change::Rotation {
            axis: [0.0, 0.0, 1.0],
            angle: 1.0,
        },
    );
    assert!(unsupported(oracle.intervals(&se3, &mut c)));
    let short = Motion::segment(vec![0.0, 0.0], Change::Linear(vec![1.0, 0.0]));
    assert!(unsupported(oracle.intervals(&short, &mut c)));
    let spin_line = Motion::line(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, 1.0]));
    assert!(unsupported(oracle.intervals(&spin_line, &mut c)));
    let nan = Motion::segment(
        vec![f64::NAN, 0.0, 0.0],
        Change::Linear(vec![1.0, 0.0, 0.0]),
    );
    assert!(unsupported(oracle.intervals(&nan, &mut c)));
    let endless = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, 1e9]));
    assert!(unsupported(oracle.intervals(&endless, &mut c)));
    // configurations that are not placements are never called free
    assert!(oracle.collides(&[0.0, 0.0], &mut c));
    assert!(oracle.collides(&[f64::NAN, 0.0, 0.0], &mut c));
    assert!(!oracle.collides(&[0.0, 0.0, 0.0], &mut c));
}

#[test]
fn standing_still_is_all_or_nothing() {
    let oracle = Polygons::new(
        unit_square(),
        vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()],
    );
    let still = |x: f64| Motion::line(vec![x, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, 0.0]));
    assert_eq!(intervals(&oracle, &still(4.0)), vec![Interval::ALL]);
    assert!(intervals(&oracle, &still(0.0)).is_empty());
}

/// An L-shaped prism standing on z = 0 as a double-sided soup, like OMPL.app's 2D meshes.
fn l_prism_soup() -> TriMesh {
    let outline = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 1.0],
        [1.0, 1.0],
        [1.0, 4.0],
        [0.0, 4.0],
    ];
    let mut vertices = Vec::new();
    for z in [0.0, 2.0] {
        vertices.extend(outline.iter().map(|p| nalgebra::Point3::new(p[0], p[1], z)));
    }
    // caps: a fan from the corner (0, 0), valid for this L
    let cap = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for t in cap {
        tris.push(t);
        tris.push([t[0] + 6, t[1] + 6, t[2] + 6]);
    }
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        tris.push([i, j, j + 6]);
        tris.push([i, j + 6, i + 6]);
    }
    let both: Vec<[u32; 3]> = tris
        .iter()
        .copied()
        .chain(tris.iter().map(|t| [t[0], t[2], t[1]]))
        .collect();
    TriMesh::new(vertices, both)
        .unwrap()
        .translated(Vector3::new(10.0, 10.0, 0.0))
}

#[test]
fn footprints_of_a_prism_soup() {
    let fp = footprint_polygons(&l_prism_soup());
    // four cap triangles, each once (top and bottom project alike, both windings)
    assert_eq!(fp.len(), 4);
    let area: f64 = fp.iter().map(Polygon::area).sum();
    assert!((area - 7.0).abs() < 1e-12);
    // a tiny robot triangle inside one footprint triangle, far from all their edges
    let tiny = vec![Polygon::new(vec![
        Point2::new(-0.01, -0.01),
        Point2::new(0.01, -0.01),
        Point2::new(0.0, 0.01),
    ])
    .unwrap()];
    let oracle = Polygons::new(tiny, fp);
    let mut c = CallCounts::default();
    assert!(oracle.collides(&[10.3, 12.0, 0.0], &mut c));
    assert!(oracle.collides(&[13.0, 10.5, 2.0], &mut c));
    assert!(!oracle.collides(&[12.0, 12.0, 0.0], &mut c)); // in the notch of the L
                                                           // crossing the notch diagonally: in the L, out, in again
    let m = Motion::segment(vec![10.5, 13.0, 0.0], Change::Linear(vec![3.0, -3.0, 0.0]));
    let hits = intervals(&oracle, &m);
    assert_eq!(hits.len(), 2, "{hits:?}");
}

#[test]
fn turning_through_a_collinear_placement_is_free() {
    // Regression: the textbook segment test reports collinear but disjoint edges as meeting.
    // The bar's lower edge lies on the line y = 0 through the pivot, as does the upper edge of
    // the block beyond its reach, at φ = 0 and φ = π; the bar reaches only √4.01 < 3.
    let bar = Polygon::rectangle([1.25, 0.05], [0.75, 0.05]).unwrap();
    let block = Polygon::rectangle([3.5, -0.5], [0.5, 0.5]).unwrap();
    let fast = Polygons::new(vec![bar], vec![block]);
    // without enveloping too, which would otherwise cull the pair by its distance
    for oracle in [fast.clone(), fast.with_enveloping(false)] {
        let turn = Motion::turn(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU]));
        assert!(intervals(&oracle, &turn).is_empty());
        let half = Motion::segment(vec![0.0, 0.0, -1.0], Change::Linear(vec![0.0, 0.0, PI]));
        assert!(intervals(&oracle, &half).is_empty());
        // sliding along that line, the edges overlap exactly while x ∈ [3 − 2, 4 − 0.5]
        let slide = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![10.0, 0.0, 0.0]));
        assert_intervals(&intervals(&oracle, &slide), &[(0.1, 0.35)], 1e-9);
    }
}

#[test]
fn a_frame_around_a_fan_meets_it_only_at_shared_edges() {
    // Regression (for an optimisation that was tried and dropped): the robot is a square cut
    // into four triangles that share the centre (each triangle's first vertex); the obstacle
    // is a square frame of four trapezoids whose hole lies inside the robot and whose body
    // covers the robot's outline. No two outlines meet and no first vertex lies in the other
    // body: only the edges the triangles share cross the frame's inner edges.
    let p = |x: f64, y: f64| Point2::new(x, y);
    let c = p(0.0, 0.0);
    let corners = [p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)];
    let fan: Vec<Polygon> = (0..4)
        .map(|i| Polygon::new(vec![c, corners[i], corners[(i + 1) % 4]]).unwrap())
        .collect();
    let outer = [p(-2.0, -2.0), p(2.0, -2.0), p(2.0, 2.0), p(-2.0, 2.0)];
    let inner = [p(-0.5, -0.5), p(0.5, -0.5), p(0.5, 0.5), p(-0.5, 0.5)];
    let frame: Vec<Polygon> = (0..4)
        .map(|i| {
            let j = (i + 1) % 4;
            Polygon::new(vec![outer[i], outer[j], inner[j], inner[i]]).unwrap()
        })
        .collect();
    let reference = Reference::new(&fan, &frame);
    assert!(reference.collides(&[0.0, 0.0, 0.0]));
    let oracle = Polygons::new(fan, frame);
    assert!(oracle.collides(&[0.0, 0.0, 0.0], &mut CallCounts::default()));
    let spin = Motion::turn(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU]));
    assert_intervals(&intervals(&oracle, &spin), &[(-0.5, 0.5)], 0.0);
}

#[test]
fn empty_scenes_are_free() {
    let mut c = CallCounts::default();
    let turn = Motion::turn(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, TAU]));
    let line = Motion::line(vec![0.0, 0.0, 0.0], Change::Linear(vec![1.0, 0.0, 0.0]));
    for oracle in [
        Polygons::new(vec![], vec![]),
        Polygons::new(unit_square(), vec![]),
        Polygons::new(vec![], unit_square()),
    ] {
        assert!(!oracle.collides(&[0.0, 0.0, 0.0], &mut c));
        assert!(intervals(&oracle, &turn).is_empty());
        assert!(intervals(&oracle, &line).is_empty());
    }
}

/// A small triangle whose apex is the reference point, opening towards body +y.
fn wedge() -> Vec<Polygon> {
    vec![Polygon::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(0.3, 0.5),
        Point2::new(-0.3, 0.5),
    ])
    .unwrap()]
}

#[test]
fn contacts_survive_rounding() {
    // Regression for the tolerance and the culling slack: a contact computed in floating
    // point (the robot's apex on an obstacle edge, up to rounding) or closer than the
    // documented tolerance must always count as collision, with enveloping on and off.
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut c = CallCounts::default();
    for i in 0..400 {
        // an obstacle triangle; every fourth one axis-aligned at the contact edge
        let (a, b) = if i % 4 == 0 {
            (Point2::new(-3.0, 1.0), Point2::new(-2.0, 1.0))
        } else {
            (
                Point2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0)),
                Point2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0)),
            )
        };
        let e = b - a;
        if e.norm() < 0.5 {
            continue;
        }
        let outward = Vector2::new(e.y, -e.x) / e.norm(); // a → b counter-clockwise: right side
        let apex_in = a + 0.5 * e - 2.0 * outward;
        let obstacle = Polygon::new(vec![a, b, apex_in]).unwrap();
        let s = rng.random_range(0.1..0.9);
        let gap = if i % 2 == 0 {
            0.0
        } else {
            0.25 * viaroad::oracle::polygons::TOLERANCE * 5.0
        };
        let p = a + s * e + gap * outward;
        // body +y along the outward normal
        let theta = outward.y.atan2(outward.x) - PI / 2.0;
        let q = vec![p.x, p.y, theta];
        let fast = Polygons::new(wedge(), vec![obstacle]);
        for oracle in [fast.clone(), fast.with_enveloping(false)] {
            assert!(oracle.collides(&q, &mut c), "case {i}: {q:?}");
            // arriving at the contact along the normal
            let start = vec![p.x + outward.x, p.y + outward.y, theta];
            let arrive = Motion::segment(start, Change::Linear(vec![-outward.x, -outward.y, 0.0]));
            let hits = intervals(&oracle, &arrive);
            assert!(
                hits.last().is_some_and(|iv| iv.hi == 1.0),
                "case {i}: {hits:?}"
            );
            // sliding along the edge, and turning about the apex: touching all the way
            let slide =
                Motion::segment(q.clone(), Change::Linear(vec![0.05 * e.x, 0.05 * e.y, 0.0]));
            assert_eq!(intervals(&oracle, &slide), vec![Interval::UNIT], "case {i}");
            let turn = Motion::segment(
                vec![p.x, p.y, theta - 0.2],
                Change::Linear(vec![0.0, 0.0, 0.4]),
            );
            assert_eq!(intervals(&oracle, &turn), vec![Interval::UNIT], "case {i}");
        }
    }
}

#[test]
fn a_bar_tip_grazing_a_wall() {
    // Regression for the rotation's tolerance and culling slack: the tip (2, 0) of a thin bar
    // turning about the origin grazes a wall whose face x = 2 (+ a gap within the documented
    // tolerance) is tangent to the tip's circle at θ = 0, the middle of the motion.
    let bar = vec![Polygon::new(vec![
        Point2::new(0.0, -0.05),
        Point2::new(2.0, 0.0),
        Point2::new(0.0, 0.05),
    ])
    .unwrap()];
    for gap in [0.0, 0.25 * viaroad::oracle::polygons::TOLERANCE * 3.0] {
        let wall = Polygon::rectangle([2.5 + gap, 0.0], [0.5, 1.0]).unwrap();
        let fast = Polygons::new(bar.clone(), vec![wall]);
        for oracle in [fast.clone(), fast.with_enveloping(false)] {
            let turn = Motion::segment(vec![0.0, 0.0, -0.3], Change::Linear(vec![0.0, 0.0, 0.6]));
            let hits = intervals(&oracle, &turn);
            assert!(!hits.is_empty(), "gap {gap}");
            assert!(
                hits.iter().any(|iv| iv.contains(0.5)),
                "gap {gap}: {hits:?}"
            );
            assert!(hits
                .iter()
                .all(|iv| (iv.lo - 0.5).abs() < 1e-4 && (iv.hi - 0.5).abs() < 1e-4));
        }
    }
}
