//! An arm's segments: the straight line in joint space, all joints at once, each linearly
//! between the values as written (as OMPL, MoveIt and VAMP interpolate within a joint's range).
//! One joint moving: the exact oracle's intervals. Several: conservative advancement
//! ([`ArmOracle::straight_free`]), located by halving where it does not finish; a collision
//! is reported only with a configuration the independent [`ArmChecker`] (parry on the true
//! meshes and primitives) finds colliding.

use super::locate::{locate, Prover};
use super::{exact_collision, CertifyError, Verdict};
use crate::deadline::Deadline;
use crate::oracle::CallCounts;
use crate::robot::{ArmChecker, ArmOracle};
use crate::scene::arm::ArmRobot;
use std::sync::Arc;

/// The finest piece (share of a segment) located when no collision is confirmed: below it an
/// unproved piece is left undecided.
const FINE: f64 = 1.0 / 65536.0;

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
                Ok(list) => {
                    exact_collision(list.iter().map(|iv| [iv.lo, iv.hi]).collect(), at, |q| {
                        self.witness(q)
                    })
                }
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
        locate(&mut prover, FINE, super::locate::MAX_PROOFS, deadline)
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
