//! The Minkowski C-obstacle oracle (LaValle 3.3.2) against the edge-pair polygon oracle: two
//! independent derivations of a translating polygon's collision intervals must agree to 1e-9
//! (as sets: each lies within 1e-9 of the other) on random convex polygons — in a proptest and
//! on 10 000 seeded cases — and on the shipped non-convex robot.

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use viaroad::geometry::Polygon;
use viaroad::interval::{Interval, IntervalList};
use viaroad::oracle::minkowski::{convex_hull, minkowski_difference, CObstacle, Minkowski};
use viaroad::oracle::polygons::Polygons;
use viaroad::oracle::{CallCounts, CollisionOracle};
use viaroad::space::{Change, Motion};

/// Agreement asked for.
const EPS: f64 = 1e-9;

fn polygon(v: &[[f64; 2]]) -> Polygon {
    Polygon::new(
        v.iter()
            .map(|p| nalgebra::Point2::new(p[0], p[1]))
            .collect(),
    )
    .unwrap()
}

/// A random convex polygon: the hull of 3–8 points within `r` of `centre`, at least a
/// triangle of some area.
fn random_convex(rng: &mut ChaCha8Rng, centre: [f64; 2], r: f64) -> Polygon {
    loop {
        let k = rng.random_range(3..=8);
        let pts: Vec<[f64; 2]> = (0..k)
            .map(|_| {
                let a = rng.random_range(0.0..2.0 * PI);
                let d = r * rng.random_range(0.2..1.0);
                [centre[0] + d * a.cos(), centre[1] + d * a.sin()]
            })
            .collect();
        let hull = convex_hull(&pts);
        if hull.len() >= 3 {
            let p = polygon(&hull);
            if p.area() > 1e-3 * r * r {
                return p;
            }
        }
    }
}

/// `a ⊆ b` grown by `EPS` on both sides (the grown intervals merged).
fn within(a: &IntervalList, b: &IntervalList) -> bool {
    let grown = IntervalList::from_unsorted(
        b.iter()
            .map(|iv| Interval {
                lo: iv.lo - EPS,
                hi: iv.hi + EPS,
            })
            .collect(),
    );
    a.iter()
        .all(|iv| grown.iter().any(|g| g.lo <= iv.lo && iv.hi <= g.hi))
}

/// The two answers are within `EPS` of each other as sets.
fn agree(a: &IntervalList, b: &IntervalList) -> bool {
    within(a, b) && within(b, a)
}

struct Case {
    robot: Vec<Polygon>,
    obstacles: Vec<Polygon>,
    theta: f64,
    motion: Motion,
}

fn random_case(rng: &mut ChaCha8Rng) -> Case {
    let centre = [rng.random_range(-0.5..0.5), rng.random_range(-0.5..0.5)];
    let r = rng.random_range(0.3..2.0);
    let robot = vec![random_convex(rng, centre, r)];
    let mut obstacles = Vec::new();
    for _ in 0..rng.random_range(1..=3) {
        let centre = [rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0)];
        let r = rng.random_range(0.3..3.0);
        obstacles.push(random_convex(rng, centre, r));
    }
    let theta = rng.random_range(-PI..PI);
    let origin = vec![
        rng.random_range(-6.0..6.0),
        rng.random_range(-6.0..6.0),
        theta,
    ];
    let change = Change::Linear(vec![
        rng.random_range(-8.0..8.0),
        rng.random_range(-8.0..8.0),
        0.0,
    ]);
    let motion = if rng.random_bool(0.8) {
        Motion::segment(origin, change)
    } else {
        Motion::line(origin, change)
    };
    Case {
        robot,
        obstacles,
        theta,
        motion,
    }
}

/// Both oracles' answers for a case: (edge-pair, Minkowski).
fn answers(c: &Case) -> (IntervalList, IntervalList) {
    let edge_pair = Polygons::new(c.robot.clone(), c.obstacles.clone());
    let mink = Minkowski::new(&c.robot, &c.obstacles, c.theta);
    let mut counts = CallCounts::default();
    let a = edge_pair.intervals(&c.motion, &mut counts).unwrap();
    let b = mink.intervals(&c.motion, &mut counts).unwrap();
    (a, b)
}

#[test]
fn ten_thousand_random_cases_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    let (mut hit, mut missed, mut states) = (0, 0, 0);
    for case in 0..10_000 {
        let c = random_case(&mut rng);
        let (a, b) = answers(&c);
        assert!(
            agree(&a, &b),
            "case {case}: edge-pair {a:?} vs minkowski {b:?}"
        );
        if a.is_empty() {
            missed += 1;
        } else {
            hit += 1;
        }
        // the static test at the motion's start agrees too
        let edge_pair = Polygons::new(c.robot.clone(), c.obstacles.clone());
        let mink = Minkowski::new(&c.robot, &c.obstacles, c.theta);
        let q = &c.motion.origin;
        let mut counts = CallCounts::default();
        if edge_pair.collides(q, &mut counts) == mink.collides(q, &mut counts) {
            states += 1;
        }
    }
    // both outcomes are exercised, so agreement is not vacuous
    assert!(hit > 2_000 && missed > 2_000, "{hit} hit, {missed} missed");
    // a start exactly on a contact boundary has probability zero
    assert_eq!(states, 10_000);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn random_convex_polygons_agree(seed in any::<u64>()) {
        let c = random_case(&mut ChaCha8Rng::seed_from_u64(seed));
        let (a, b) = answers(&c);
        prop_assert!(agree(&a, &b), "edge-pair {:?} vs minkowski {:?}", a, b);
    }

    /// The C-obstacle is exactly the set where the placed robot meets the obstacle: a point is
    /// inside iff the polygon oracle says the robot collides there (away from the boundary).
    #[test]
    fn c_obstacle_is_the_collision_set(seed in any::<u64>(), x in -8.0..8.0f64, y in -8.0..8.0f64) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let robot = random_convex(&mut rng, [0.0, 0.0], 1.5);
        let obstacle = random_convex(&mut rng, [1.0, -1.0], 2.0);
        let pts = |p: &Polygon| p.vertices.iter().map(|v| [v.x, v.y]).collect::<Vec<_>>();
        let cob = CObstacle::new(minkowski_difference(&pts(&robot), &pts(&obstacle)));
        let oracle = Polygons::new(vec![robot], vec![obstacle]);
        let mut counts = CallCounts::default();
        let inside = cob.contains([x, y], 0.0);
        let near = cob.contains([x, y], 1e-7) != cob.contains([x, y], -1e-7);
        if !near {
            prop_assert_eq!(inside, oracle.collides(&[x, y, 0.0], &mut counts));
        }
    }
}

#[test]
fn the_shipped_l_shaped_robot_agrees() {
    // se2-corridor's robot (non-convex: split into triangles) among random convex obstacles
    let robot = vec![polygon(&[
        [-1.2, -0.2],
        [1.2, -0.2],
        [1.2, 1.0],
        [0.8, 1.0],
        [0.8, 0.2],
        [-1.2, 0.2],
    ])];
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..500 {
        let mut c = random_case(&mut rng);
        c.robot = robot.clone();
        let (a, b) = answers(&c);
        assert!(agree(&a, &b), "edge-pair {a:?} vs minkowski {b:?}");
    }
}

#[test]
fn turns_and_other_orientations_are_unsupported() {
    let robot = vec![Polygon::rectangle([0.0, 0.0], [0.5, 0.5]).unwrap()];
    let wall = vec![Polygon::rectangle([4.0, 0.0], [1.0, 1.0]).unwrap()];
    let oracle = Minkowski::new(&robot, &wall, 0.0);
    let mut counts = CallCounts::default();
    let turn = Motion::segment(vec![0.0, 0.0, 0.0], Change::Linear(vec![0.0, 0.0, 1.0]));
    assert!(oracle.intervals(&turn, &mut counts).is_err());
    let other = Motion::segment(vec![0.0, 0.0, 0.3], Change::Linear(vec![1.0, 0.0, 0.0]));
    assert!(oracle.intervals(&other, &mut counts).is_err());
    // never "free" by mistake
    assert!(oracle.collides(&[0.0, 0.0, 0.3], &mut counts));
    assert!(!oracle.collides(&[0.0, 0.0], &mut counts));
    assert!(oracle.collides(&[4.0, 0.5], &mut counts));
}
