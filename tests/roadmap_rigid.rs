//! The roadmap is generic over the space: learning, saving and querying in SE(2) and SE(3),
//! with a test oracle for a rigid body whose collision depends on its position only (a
//! "round" robot among balls), so that rotations are free and translations are not.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use viaroad::interval::{Interval, IntervalList};
use viaroad::local::LocalSpec;
use viaroad::oracle::{Bounded, CallCounts, CollisionOracle, OracleError};
use viaroad::roadmap::{Budget, LearnParams, Learner, QueryPlanner, Roadmap};
use viaroad::space::{Change, Motion, Space, SpaceKind};

/// Balls around the robot's reference point: collides when the position is in a ball.
struct PositionBalls {
    dim: usize,
    balls: Vec<(Vec<f64>, f64)>,
}

impl CollisionOracle for PositionBalls {
    fn intervals(&self, m: &Motion, counts: &mut CallCounts) -> Result<IntervalList, OracleError> {
        counts.pairs_tested += self.balls.len() as u64;
        let v: Vec<f64> = match &m.change {
            Change::Linear(d) => d[..self.dim].to_vec(),
            Change::Rotation { .. } | Change::BodyRotation { .. } => vec![0.0; self.dim],
        };
        let mut hits = Vec::new();
        for (c, r) in &self.balls {
            let w: Vec<f64> = (0..self.dim).map(|k| m.origin[k] - c[k]).collect();
            let a: f64 = v.iter().map(|x| x * x).sum();
            let b: f64 = v.iter().zip(&w).map(|(x, y)| x * y).sum();
            let e: f64 = w.iter().map(|x| x * x).sum::<f64>() - r * r;
            let iv = if a == 0.0 {
                (e <= 0.0).then_some(Interval::ALL)
            } else {
                let disc = b * b - a * e;
                (disc >= 0.0).then(|| Interval {
                    lo: (-b - disc.sqrt()) / a,
                    hi: (-b + disc.sqrt()) / a,
                })
            };
            if let Some(iv) = iv.and_then(|iv| iv.meet(&m.range)) {
                hits.push(iv);
            }
        }
        Ok(IntervalList::from_unsorted(hits))
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        counts.pairs_tested += self.balls.len() as u64;
        self.balls
            .iter()
            .any(|(c, r)| c.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum::<f64>() <= r * r)
    }
}

fn setup(kind: SpaceKind) -> (Space, Bounded<PositionBalls>) {
    let space = match kind {
        SpaceKind::Se2 => Space::se2([0.0; 2], [1.0; 2], 0.1).unwrap(),
        _ => Space::se3([0.0; 3], [1.0; 3], 0.1).unwrap(),
    };
    let dim = space.position_dim();
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let balls = (0..25)
        .map(|_| ((0..dim).map(|_| rng.random::<f64>()).collect(), 0.1))
        .collect();
    (
        space.clone(),
        Bounded::new(space, PositionBalls { dim, balls }),
    )
}

/// Independent check of a straight single-group step: a pure rotation keeps the position
/// (which must be free); a translation keeps the orientation and its segment keeps clear of
/// every ball (closest point on the segment).
fn step_free(space: &Space, oracle: &Bounded<PositionBalls>, a: &[f64], b: &[f64]) -> bool {
    let p = space.position_dim();
    let balls = &oracle.inner().balls;
    let inside = |x: &[f64]| x[..p].iter().all(|v| (0.0..=1.0).contains(v));
    let clear = |x: &[f64], y: &[f64]| {
        balls.iter().all(|(c, r)| {
            let d: Vec<f64> = (0..p).map(|k| y[k] - x[k]).collect();
            let len2: f64 = d.iter().map(|v| v * v).sum();
            let s = if len2 == 0.0 {
                0.0
            } else {
                ((0..p).map(|k| (c[k] - x[k]) * d[k]).sum::<f64>() / len2).clamp(0.0, 1.0)
            };
            let dist2: f64 = (0..p).map(|k| (x[k] + s * d[k] - c[k]).powi(2)).sum();
            dist2.sqrt() > r * (1.0 - 1e-9)
        })
    };
    let same_position = a[..p] == b[..p];
    let same_orientation = a[p..] == b[p..];
    inside(a) && inside(b) && clear(a, b) && (same_position || same_orientation)
}

#[test]
fn se2_and_se3_roadmaps_learn_save_and_answer() {
    for kind in [SpaceKind::Se2, SpaceKind::Se3] {
        let (space, oracle) = setup(kind);
        for (spec, feedback) in [(LocalSpec::Straight, true), (LocalSpec::default(), false)] {
            let local = spec.build();
            let learner = Learner::new(&space, &oracle, local.as_ref(), 0xfeed);
            let params = LearnParams {
                feedback,
                round_size: 16,
                ..LearnParams::default()
            };
            let run = |threads: usize| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| learner.learn(&params, &Budget::nodes(400), 3, &mut |_| {}))
                    .unwrap()
            };
            let learnt = run(2);
            let r = &learnt.roadmap;
            assert_eq!(r.to_bytes().unwrap(), run(1).roadmap.to_bytes().unwrap());
            assert!(r.node_count() >= 400);
            assert!(r.header().counts.line_calls > 0);
            for q in r.nodes() {
                assert!(!oracle.inner().collides(q, &mut CallCounts::default()));
                if kind == SpaceKind::Se3 {
                    let n: f64 = q[3..].iter().map(|v| v * v).sum();
                    assert!((n - 1.0).abs() < 1e-9);
                }
            }
            for (i, e) in r.edges().iter().enumerate() {
                let path = r.edge_path(i, e.a);
                for w in path.windows(2) {
                    assert!(
                        step_free(&space, &oracle, &w[0], &w[1]),
                        "{kind:?} edge {i}: {w:?}"
                    );
                }
            }
            // turns were taken: some edge step changes the orientation only
            assert!(r.edges().iter().enumerate().any(|(i, _)| {
                r.edge_path(i, r.edges()[i].a)
                    .windows(2)
                    .any(|w| w[0][..space.position_dim()] == w[1][..space.position_dim()])
            }));
            let loaded = Roadmap::from_bytes(&r.to_bytes().unwrap(), 0xfeed).unwrap();
            let planner = QueryPlanner::new(&loaded, &oracle).unwrap();
            let mut rng = ChaCha8Rng::seed_from_u64(8);
            let mut solved = 0;
            for _ in 0..40 {
                let mut free = || loop {
                    let mut q = space.sample_uniform(&mut rng);
                    space.normalize(&mut q);
                    if !oracle.collides(&q, &mut CallCounts::default()) {
                        return q;
                    }
                };
                let (s, g) = (free(), free());
                let answer = planner.query(&s, &g).unwrap();
                if answer.is_solved() {
                    solved += 1;
                    for w in answer.path.windows(2) {
                        assert!(step_free(&space, &oracle, &w[0], &w[1]), "{kind:?}: {w:?}");
                    }
                    assert!(space.distance(answer.path.last().unwrap(), &g) < 1e-9);
                }
            }
            assert!(solved >= 30, "{kind:?} {spec}: {solved} of 40");
        }
    }
}
