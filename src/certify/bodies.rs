//! Segments of several bodies moving at once (SE(2)^k) under the space's interpolation. A
//! segment of one of the seed's motions — all bodies translating, each by its own vector, or
//! one body turning — is one call of the exact [`crate::oracle::bodies::PlanarBodies`] oracle.
//! Any other (bodies that translate and turn at once, or two that turn together, as a planner
//! interpolating every coordinate moves them) is proved by conservative advancement on the
//! independent checker's distances ([`BodiesChecker::clearance`], every body against the
//! obstacles and every pair of bodies): no point of body `i` moves faster than
//! `vᵢ = |Δpᵢ| + rᵢ·|Δθᵢ|`, so two bodies close in at most `2 · maxᵢ vᵢ`. Witnesses are
//! configurations where the checker finds two shapes touching, with the pair's names.

use super::locate::{locate, Prover};
use super::verdict::{exact_collision, CertifyError, Verdict};
use crate::checker::bodies::BodiesChecker;
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::scene::{Robot, Scene};
use crate::space::rotation::wrap_angle;

/// The finest piece (share of a segment) located when no collision is confirmed.
const FINE: f64 = 1.0 / (1u64 << 30) as f64;

/// The independent shapes of a scene of several bodies.
pub(super) struct BodiesChecks {
    checker: BodiesChecker,
    /// Each body's radius about its reference point (a hair larger).
    radii: Vec<f64>,
}

impl BodiesChecks {
    pub(super) fn new(scene: &Scene) -> Result<BodiesChecks, CertifyError> {
        let Robot::Bodies(bodies) = &scene.robot else {
            return Err(CertifyError::Unsupported(
                "not a scene of several bodies".into(),
            ));
        };
        let radii = bodies
            .iter()
            .map(|b| {
                let r = b
                    .parts
                    .iter()
                    .flat_map(|p| &p.vertices)
                    .map(|v| v.coords.norm())
                    .fold(0.0, f64::max);
                r * (1.0 + 1e-9)
            })
            .collect();
        Ok(BodiesChecks {
            checker: BodiesChecker::new(scene).map_err(CertifyError::Unsupported)?,
            radii,
        })
    }

    /// The least distance between two shapes at `q` (≤ 0: touching) and their names.
    fn clearance(&self, q: &[f64]) -> (f64, String) {
        // parry refusing a query: treat as touching, the side of collision
        self.checker
            .clearance(q)
            .unwrap_or_else(|e| (0.0, format!("parry: {e}")))
    }

    /// The pair touching at `q` (the nearest), `None` if every shape is apart.
    pub(super) fn witness(&self, q: &[f64]) -> Option<Vec<[String; 2]>> {
        let (d, pair) = self.clearance(q);
        (d <= 0.0).then(|| vec![split_pair(&pair)])
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
        let space = &scene.space;
        let groups = space.groups(false);
        let changed: Vec<_> = groups
            .iter()
            .filter(|g| !space.same_in_group(a, b, g))
            .collect();
        match changed[..] {
            [] => Verdict::Free,
            [g] => {
                let motion = space.group_motion(a, b, g);
                match oracle.intersect(&motion, counts) {
                    Ok(list) if list.is_empty() => Verdict::Free,
                    Ok(list) => exact_collision(
                        list.iter().map(|iv| [iv.lo, iv.hi]).collect(),
                        |t| motion.at(t),
                        |q| self.witness(q),
                    ),
                    Err(e) => Verdict::Undecided {
                        reason: e.to_string(),
                    },
                }
            }
            _ => {
                let fastest = a
                    .chunks_exact(3)
                    .zip(b.chunks_exact(3))
                    .zip(&self.radii)
                    .map(|((p, q), r)| {
                        (q[0] - p[0]).hypot(q[1] - p[1]) + r * wrap_angle(q[2] - p[2]).abs()
                    })
                    .fold(0.0, f64::max);
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
