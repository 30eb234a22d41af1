//! An arm's segments: the straight line in joint space, all joints at once, each linearly
//! between the values as written (as OMPL, MoveIt and VAMP interpolate within a joint's range).
//! One joint moving: the exact oracle's intervals. Several: conservative advancement
//! ([`ArmOracle::straight_free`]), located by halving where it does not finish; a collision
//! is reported only with a configuration the independent [`ArmChecker`] (parry on the true
//! meshes and primitives) finds colliding.
//!
//! The oracle works on polytopes that contain the true shapes (a sphere's circumscribed
//! polytope, a big mesh's envelope), so near a curved shape it cannot prove what is free: the
//! Fetch's head is a sphere of 0.2 m whose polytope stands up to ~8 mm off it, and some of its
//! MotionBenchMaker goals leave the upper arm 0.2–3 mm from the true sphere. Where the oracle
//! leaves a segment undecided, a second proof runs on the true shapes: conservative
//! advancement on parry's distances between every pair of solids the checker tests, each pair
//! stepping by its distance over a bound on how fast the two can approach
//! ([`ArmOracle::point_speeds`]). It proves, never finds: a collision is still reported only
//! with a witness.

use super::locate::{locate, Prover};
use super::verdict::{exact_collision, CertifyError, Verdict};
use crate::deadline::Deadline;
use crate::oracle::CallCounts;
use crate::robot::{ArmChecker, ArmOracle};
use crate::scene::arm::ArmRobot;
use crate::space::Config;
use std::sync::Arc;

/// The finest piece (share of a segment) located when no collision is confirmed: below it an
/// unproved piece is left undecided.
const FINE: f64 = 1.0 / 65536.0;

/// Steps (parry distances) the proof on the true shapes may take over all pairs of one segment
/// before the segment is left undecided: a pair that grazes at 1e-7 would creep on for ever,
/// and a distance between two big meshes costs up to milliseconds.
const MAX_STEPS: usize = 20_000;

/// A distance below which the proof on the true shapes gives up: contact, as far as parry's
/// rounding can tell.
const CONTACT: f64 = 1e-9;

/// The checks of one arm scene.
pub(super) struct ArmChecks {
    oracle: Arc<ArmOracle>,
    checker: ArmChecker,
}

impl ArmChecks {
    pub(super) fn new(robot: &ArmRobot) -> Result<ArmChecks, CertifyError> {
        let checker = ArmChecker::new(&robot.arm, &robot.objects)
            .map_err(|e| CertifyError::Unsupported(e.to_string()))?;
        Ok(ArmChecks {
            oracle: Arc::clone(robot.arm_oracle()),
            checker,
        })
    }

    /// The pairs touching at `q` by the independent checker.
    pub(super) fn witness(&self, q: &[f64]) -> Option<Vec<[String; 2]>> {
        let hits = self.checker.collisions(q);
        (!hits.is_empty()).then(|| hits.into_iter().map(|c| [c.a, c.b]).collect())
    }

    /// The verdict on the straight motion from `a` to `b`.
    pub(super) fn straight(
        &self,
        a: &[f64],
        b: &[f64],
        deadline: &Deadline,
        counts: &mut CallCounts,
    ) -> Verdict {
        let at = |t: f64| -> Vec<f64> { a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect() };
        let moving: Vec<usize> = (0..a.len()).filter(|&i| a[i] != b[i]).collect();
        if let [k] = moving[..] {
            counts.segment_calls += 1;
            return match self.oracle.joint_move(a, k, b[k] - a[k], counts) {
                Ok(list) if list.is_empty() => Verdict::Free,
                Ok(list) => self.or_on_true_shapes(
                    exact_collision(list.iter().map(|iv| [iv.lo, iv.hi]).collect(), at, |q| {
                        self.witness(q)
                    }),
                    a,
                    b,
                    deadline,
                ),
                Err(e) => Verdict::Undecided {
                    reason: e.to_string(),
                },
            };
        }
        let mut prover = Straight {
            checks: self,
            a,
            b,
            counts,
        };
        let verdict = locate(&mut prover, FINE, super::locate::MAX_PROOFS, deadline);
        self.or_on_true_shapes(verdict, a, b, deadline)
    }

    /// `verdict`, or free where it is undecided and the proof on the true shapes succeeds.
    pub(super) fn or_on_true_shapes(
        &self,
        verdict: Verdict,
        a: &[f64],
        b: &[f64],
        deadline: &Deadline,
    ) -> Verdict {
        match verdict {
            Verdict::Undecided { .. } if self.free_on_true_shapes(a, b, deadline) => Verdict::Free,
            v => v,
        }
    }

    /// Whether the straight motion from `a` to `b` is proved free on the true shapes: both
    /// ends free for the checker (surfaces and containment), then, pair by pair, conservative
    /// advancement on parry's distance `d`, stepping `t` by `d / v` (`v`: the two solids'
    /// speed bounds added, or the link's against an obstacle), which no point can close.
    pub(super) fn free_on_true_shapes(&self, a: &[f64], b: &[f64], deadline: &Deadline) -> bool {
        if self.witness(a).is_some() || self.witness(b).is_some() {
            return false;
        }
        let speeds = self.oracle.point_speeds(a, b);
        let arm = self.checker.arm();
        let at = |t: f64| -> Config {
            if t >= 1.0 {
                return b.to_vec();
            }
            a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect()
        };
        let mut steps = 0;
        for pair in self.checker.part_pairs() {
            let v = speeds[pair.link] + pair.other_link.map_or(0.0, |l| speeds[l]);
            if v == 0.0 {
                continue; // neither moves: apart as at `a`
            }
            let mut t = 0.0;
            while t < 1.0 {
                steps += 1;
                if steps > MAX_STEPS || deadline.expired() || crate::deadline::watched_expired() {
                    return false;
                }
                let poses = arm.link_poses(&at(t));
                let d = self.checker.pair_distance(&pair, &poses, v * (1.0 - t));
                if d <= CONTACT {
                    return false;
                }
                t += d * (1.0 - 1e-9) / v;
            }
        }
        true
    }
}

/// A straight motion being located.
struct Straight<'a> {
    checks: &'a ArmChecks,
    a: &'a [f64],
    b: &'a [f64],
    counts: &'a mut CallCounts,
}

impl Prover for Straight<'_> {
    fn proved_free(&mut self, t0: f64, t1: f64) -> Result<bool, CertifyError> {
        let (q0, q1) = (self.at(t0), self.at(t1));
        self.checks
            .oracle
            .straight_free(&q0, &q1, self.counts)
            .map_err(|e| CertifyError::Oracle(e.to_string()))
    }

    fn witness(&mut self, t: f64) -> Option<Vec<[String; 2]>> {
        self.checks.witness(&self.at(t))
    }

    fn at(&self, t: f64) -> Vec<f64> {
        if t == 1.0 {
            return self.b.to_vec();
        }
        self.a
            .iter()
            .zip(self.b)
            .map(|(x, y)| x + t * (y - x))
            .collect()
    }
}
