//! Segments of several bodies moving at once (SE(2)^k, SE(3)^k) under the space's
//! interpolation. A segment of one of the seed's motions — all bodies translating, each by its
//! own vector, or one body turning — is one call of the exact oracle
//! ([`crate::oracle::bodies::PlanarBodies`], [`crate::oracle::bodies3::SolidBodies`]).
//! Any other (bodies that translate and turn at once, or two that turn together, as a planner
//! interpolating every coordinate moves them) is proved by conservative advancement on the
//! independent checker's distances ([`BodiesChecker::clearance`], every body against the
//! obstacles and every pair of bodies): no point of body `i` moves faster than
//! `vᵢ = |Δpᵢ| + rᵢ·|Δθᵢ|` (`Δθᵢ` the angle it turns through), so two bodies close in at most
//! `2 · maxᵢ vᵢ`. Witnesses are configurations where the checker finds two shapes touching (in
//! space, also one inside another, which distances alone do not show), with the pair's names.

use super::locate::{locate, Prover};
use super::verdict::{one_group_verdict, CertifyError, Collision, Verdict};
use crate::checker::bodies::BodiesChecker;
use crate::checker::bodies3::SolidBodiesChecker;
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, CollisionOracle};
use crate::scene::{Robot, Scene};
use crate::space::rotation::{rotation_angle, wrap_angle};

/// The finest piece (share of a segment) located when no collision is confirmed.
const FINE: f64 = 1.0 / (1u64 << 30) as f64;

/// The independent checker of the scene's kind.
enum Checker {
    Planar(BodiesChecker),
    Solid(SolidBodiesChecker),
}

/// The independent shapes of a scene of several bodies.
pub(super) struct BodiesChecks {
    checker: Checker,
    /// Each body's radius about its reference point (a hair larger).
    radii: Vec<f64>,
}

impl BodiesChecks {
    pub(super) fn new(scene: &Scene) -> Result<BodiesChecks, CertifyError> {
        let unsupported = CertifyError::Unsupported;
        let (checker, radii): (Checker, Vec<f64>) = match &scene.robot {
            Robot::Bodies(bodies) => (
                Checker::Planar(BodiesChecker::new(scene).map_err(unsupported)?),
                bodies
                    .iter()
                    .map(|b| {
                        b.parts
                            .iter()
                            .flat_map(|p| &p.vertices)
                            .map(|v| v.coords.norm())
                            .fold(0.0, f64::max)
                    })
                    .collect(),
            ),
            Robot::MeshBodies(bodies) => (
                Checker::Solid(SolidBodiesChecker::new(scene).map_err(unsupported)?),
                bodies.iter().map(|b| b.mesh.radius()).collect(),
            ),
            _ => {
                return Err(CertifyError::Unsupported(
                    "not a scene of several bodies".into(),
                ))
            }
        };
        Ok(BodiesChecks {
            checker,
            radii: radii.into_iter().map(|r| r * (1.0 + 1e-9)).collect(),
        })
    }

    /// How far a point of body `i` moves at most along the interpolated motion from `a` to `b`.
    fn travel(&self, a: &[f64], b: &[f64]) -> f64 {
        let per = a.len() / self.radii.len().max(1);
        a.chunks_exact(per)
            .zip(b.chunks_exact(per))
            .zip(&self.radii)
            .map(|((p, q), r)| match per {
                3 => (q[0] - p[0]).hypot(q[1] - p[1]) + r * wrap_angle(q[2] - p[2]).abs(),
                _ => {
                    let shift = (0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>().sqrt();
                    shift + r * rotation_angle(&p[3..7], &q[3..7])
                }
            })
            .fold(0.0, f64::max)
    }

    /// The least distance between two shapes at `q` (≤ 0: touching) and their names.
    fn clearance(&self, q: &[f64]) -> (f64, String) {
        // parry refusing a query: treat as touching, the side of collision
        let found = match &self.checker {
            Checker::Planar(c) => c.clearance(q),
            Checker::Solid(c) => c.clearance(q),
        };
        found.unwrap_or_else(|e| (0.0, format!("parry: {e}")))
    }

    /// The pair touching at `q` (the nearest), `None` if every shape is apart.
    pub(super) fn witness(&self, q: &[f64]) -> Option<Vec<[String; 2]>> {
        let (d, pair) = self.clearance(q);
        if d <= 0.0 {
            return Some(vec![split_pair(&pair)]);
        }
        match &self.checker {
            Checker::Solid(c) => c.containment(q).map(|pair| vec![split_pair(&pair)]),
            Checker::Planar(_) => None,
        }
    }

    /// The verdict on the interpolated motion from `a` to `b`.
    pub(super) fn interpolated(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        (a, b): (&[f64], &[f64]),
        deadline: &Deadline,
        counts: &mut CallCounts,
    ) -> Verdict {
        if let Some(v) = one_group_verdict(scene, oracle, (a, b), counts, |q| self.witness(q)) {
            return v;
        }
        // one inside another at the start stays so without a surface meeting: the
        // distances below would not see it
        if let Some(pairs) = self.witness(a) {
            return Verdict::Collides(Collision {
                intervals: vec![[0.0, 1.0]],
                exact: false,
                resolution: 1.0,
                witness: a.to_vec(),
                witness_t: 0.0,
                pairs,
                free_before: 0.0,
                free_after: 1.0,
            });
        }
        let fastest = self.travel(a, b);
        let mut prover = Advancing {
            checks: self,
            scene,
            a,
            b,
            rate: 2.0 * fastest * (1.0 + 1e-9),
        };
        locate(&mut prover, FINE, 1 << 20, deadline)
    }
}

/// The checker's pair (`bodies "a" and "b"`, `body "a" and an obstacle`) as two names.
fn split_pair(pair: &str) -> [String; 2] {
    let names: Vec<&str> = pair.split('"').skip(1).step_by(2).collect();
    match names[..] {
        [x, y, ..] => [x.to_string(), y.to_string()],
        [x] => [x.to_string(), "obstacles".to_string()],
        [] => [pair.to_string(), String::new()],
    }
}

/// A motion of several bodies moving in more than one way at once, proved by conservative
/// advancement.
struct Advancing<'a> {
    checks: &'a BodiesChecks,
    scene: &'a Scene,
    a: &'a [f64],
    b: &'a [f64],
    rate: f64,
}

impl Prover for Advancing<'_> {
    fn proved_free(&mut self, t0: f64, t1: f64) -> Result<bool, CertifyError> {
        let reach = self.rate * (t1 - t0);
        // from either end: the clearance there covers the whole piece
        Ok(self.checks.clearance(&self.at(t0)).0 > reach
            || self.checks.clearance(&self.at(t1)).0 > reach)
    }

    fn witness(&mut self, t: f64) -> Option<Vec<[String; 2]>> {
        self.checks.witness(&self.at(t))
    }

    fn at(&self, t: f64) -> Vec<f64> {
        self.scene.space.interpolate(self.a, self.b, t)
    }
}

#[cfg(test)]
mod tests {
    use super::split_pair;

    #[test]
    fn the_checkers_pairs_split_into_names() {
        assert_eq!(split_pair("bodies \"s1\" and \"s2\""), ["s1", "s2"]);
        assert_eq!(
            split_pair("body \"piano\" and an obstacle"),
            ["piano", "obstacles"]
        );
    }
}
