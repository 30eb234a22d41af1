//! Rigid bodies' segments (a point among discs, SE(2) polygons, SE(3) meshes) under the
//! space's interpolation. A segment that changes one DOF group (every R^n line, a pure
//! translation or a pure turn) is one exact oracle call. One that translates and turns at once
//! (OMPL's SE(2) line, SE(3)'s translation with a slerp) is proved by conservative
//! advancement on parry's distance between the robot and the obstacles: with clearance `d` at
//! `t₀`, nothing touches before every point of the robot has moved `d`, and no point moves
//! faster than `|Δp| + r·θ` (`r`: the robot's radius about its reference point, `θ`: the
//! turn's angle). Witnesses are configurations where parry finds the shapes touching (the
//! disc's distance for a point).

use super::locate::{locate, Prover};
use super::verdict::{one_group_verdict, CertifyError, Verdict};
use crate::checker::{planar::PlanarChecker, rigid::RigidChecker};
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, CollisionOracle};
use crate::scene::{Obstacle, Robot, Scene};
use crate::space::{rotation, SpaceKind};

/// The finest piece (share of a segment) located when no collision is confirmed.
const FINE: f64 = 1.0 / (1u64 << 30) as f64;

/// The independent shapes of one rigid scene.
pub(super) enum RigidChecks {
    /// Closed balls around a point robot.
    Discs(Vec<(Vec<f64>, f64)>),
    /// SE(2) polygons.
    Planar(PlanarChecker, f64),
    /// SE(3) meshes.
    Rigid(RigidChecker, f64),
}

/// The robot's radius about its reference point.
fn radius(scene: &Scene) -> f64 {
    match &scene.robot {
        Robot::Polygons(parts) => parts
            .iter()
            .flat_map(|p| &p.vertices)
            .map(|v| v.coords.norm())
            .fold(0.0, f64::max),
        Robot::Mesh(m) => m
            .vertices
            .iter()
            .map(|v| v.coords.norm())
            .fold(0.0, f64::max),
        _ => 0.0,
    }
}

impl RigidChecks {
    pub(super) fn new(scene: &Scene) -> Result<RigidChecks, CertifyError> {
        let r = radius(scene) * (1.0 + 1e-9);
        match (&scene.robot, scene.space.kind()) {
            (Robot::Point, _) => Ok(RigidChecks::Discs(
                scene
                    .obstacles
                    .iter()
                    .filter_map(|o| match o {
                        Obstacle::Disc { centre, radius } => Some((centre.clone(), *radius)),
                        _ => None,
                    })
                    .collect(),
            )),
            (Robot::Polygons(_), SpaceKind::Se2) => PlanarChecker::se2(scene)
                .map(|c| RigidChecks::Planar(c, r))
                .map_err(CertifyError::Unsupported),
            (Robot::Mesh(_), SpaceKind::Se3) => RigidChecker::se3(scene)
                .map(|c| RigidChecks::Rigid(c, r))
                .map_err(CertifyError::Unsupported),
            (robot, kind) => Err(CertifyError::Unsupported(format!("{robot:?} in {kind}"))),
        }
    }

    /// Distance between the robot at `q` and the obstacles (≤ 0: touching).
    fn clearance(&self, q: &[f64]) -> f64 {
        let d = match self {
            RigidChecks::Discs(discs) => Ok(discs
                .iter()
                .map(|(c, r)| distance(q, c) - r)
                .fold(f64::INFINITY, f64::min)),
            RigidChecks::Planar(c, _) => c.clearance(q),
            RigidChecks::Rigid(c, _) => c.clearance(q),
        };
        // parry refusing a query: treat as touching, the side of collision
        d.unwrap_or(0.0)
    }

    /// The pairs touching at `q`, `None` if the shapes are apart.
    pub(super) fn witness(&self, q: &[f64]) -> Option<Vec<[String; 2]>> {
        match self {
            RigidChecks::Discs(discs) => {
                let hits: Vec<[String; 2]> = discs
                    .iter()
                    .enumerate()
                    .filter(|(_, (c, r))| distance(q, c) <= *r)
                    .map(|(i, _)| ["point".to_string(), format!("disc {}", i + 1)])
                    .collect();
                (!hits.is_empty()).then_some(hits)
            }
            _ => (self.clearance(q) <= 0.0)
                .then(|| vec![["robot".to_string(), "obstacles".to_string()]]),
        }
    }

    /// The verdict on the interpolated motion from `a` to `b`.
    pub(super) fn interpolated(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        a: &[f64],
        b: &[f64],
        deadline: &Deadline,
        counts: &mut CallCounts,
    ) -> Verdict {
        if let Some(v) = one_group_verdict(scene, oracle, (a, b), counts, |q| self.witness(q)) {
            return v;
        }
        let rate = match self {
            RigidChecks::Planar(_, r) => {
                distance(&a[..2], &b[..2]) + r * rotation::wrap_angle(b[2] - a[2]).abs()
            }
            RigidChecks::Rigid(_, r) => {
                distance(&a[..3], &b[..3]) + r * rotation::rotation_angle(&a[3..7], &b[3..7])
            }
            RigidChecks::Discs(_) => distance(a, b),
        };
        let mut prover = Advancing {
            checks: self,
            scene,
            a,
            b,
            rate: rate * (1.0 + 1e-9),
        };
        locate(&mut prover, FINE, 1 << 20, deadline)
    }
}

/// Euclidean distance.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// A motion translating and turning at once, proved by conservative advancement.
struct Advancing<'a> {
    checks: &'a RigidChecks,
    scene: &'a Scene,
    a: &'a [f64],
    b: &'a [f64],
    rate: f64,
}

impl Prover for Advancing<'_> {
    fn proved_free(&mut self, t0: f64, t1: f64) -> Result<bool, CertifyError> {
        let reach = self.rate * (t1 - t0);
        // from either end: the clearance there covers the whole piece
        Ok(self.checks.clearance(&self.at(t0)) > reach
            || self.checks.clearance(&self.at(t1)) > reach)
    }

    fn witness(&mut self, t: f64) -> Option<Vec<[String; 2]>> {
        self.checks.witness(&self.at(t))
    }

    fn at(&self, t: f64) -> Vec<f64> {
        self.scene.space.interpolate(self.a, self.b, t)
    }
}
