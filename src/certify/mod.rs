//! Certifying a path that another planner produced, and repairing what is blocked.
//!
//! A path is a list of waypoints; between two waypoints the robot moves as the path's planner
//! meant ([`MotionModel`]). Each segment gets a [`Verdict`]: **free** (proved), **collides**
//! (the parameter intervals that hold every collision, a witness configuration that the
//! independent check confirms as colliding, and the pairs that touch there), or
//! **undecided** (a time budget ran out, or the bodies pass closer than a proof can
//! separate and no colliding configuration was found). Waypoints outside the bounds and ends
//! that differ from the scene's query are [`Defect`]s.
//!
//! How a segment is proved:
//! - a motion of one DOF group (an R^n straight line, an SE(2)/SE(3) translation or turn, an
//!   arm's single joint): the exact oracle's collision intervals;
//! - an arm's straight motion of several joints: conservative advancement
//!   ([`crate::robot::ArmOracle::straight_free`]), halving where it does not finish
//!   (`locate`), witnesses confirmed by the independent [`crate::robot::ArmChecker`];
//! - several bodies moving otherwise than by the seed's motions (translating and turning at
//!   once, or turning together): conservative advancement on the independent checker's
//!   distances, every body against the obstacles and every pair of bodies (`bodies`);
//! - a rigid body translating and turning at once (OMPL's SE(2)/SE(3) interpolation):
//!   conservative advancement on parry's distances between the robot's and the obstacles'
//!   shapes, halving likewise;
//! - an arm's segment the oracle leaves undecided (its polytopes enclose curved shapes and
//!   big meshes): conservative advancement on parry's distances between the true shapes.
//!
//! [`repair()`] replaces each run of blocked segments by a certified detour.

mod arm;
mod bodies;
mod locate;
pub mod repair;
mod rigid;
mod verdict;

pub use locate::COARSE;
pub use repair::{repair, RepairOptions, RepairReport, Repaired};
pub use verdict::{CertifyError, Collision, Verdict};

use verdict::exact_collision;

use crate::deadline::Deadline;
use crate::local::direct_pieces;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::scene::{Robot, Scene};
use crate::space::{Config, SpaceKind};
use serde::Serialize;
use std::time::Instant;

/// How the robot moves between two waypoints.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MotionModel {
    /// The space's interpolation, as OMPL, MoveIt and VAMP move: a straight line in joint space
    /// (all joints at once) or in R^n, SE(2)'s line with the angle the shorter way round,
    /// SE(3)'s linear translation with a slerp of the rotation.
    #[default]
    Interpolate,
    /// viaroad's own direct path: one DOF group after another (an arm's joints one at a
    /// time, a rigid body's translation, then its turn).
    Direct,
}

impl std::str::FromStr for MotionModel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "interpolate" | "straight" | "ompl" => Ok(MotionModel::Interpolate),
            "direct" => Ok(MotionModel::Direct),
            _ => Err(format!("unknown motion model {s:?} (interpolate | direct)")),
        }
    }
}

/// Something wrong with the path beyond its segments.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "defect", rename_all = "snake_case")]
pub enum Defect {
    /// A waypoint's coordinate (a joint) lies outside the bounds (the limits) by more than
    /// [`BOUNDS_TOLERANCE`].
    OutOfBounds {
        /// The waypoint, 0-based.
        waypoint: usize,
        /// The coordinate (the group's joint).
        coordinate: usize,
        /// Its value.
        value: f64,
        /// The bounds.
        lower: f64,
        /// The bounds.
        upper: f64,
    },
    /// The first waypoint is not the query's start.
    StartDiffers {
        /// The space's distance between them.
        distance: f64,
    },
    /// The last waypoint is not the query's goal.
    GoalDiffers {
        /// The space's distance between them.
        distance: f64,
    },
}

/// How far a waypoint may lie outside the bounds and count as on them (a planner's float32
/// rounding of a limit; checked as if clamped).
pub const BOUNDS_TOLERANCE: f64 = 1e-6;

/// How far, as a share of the space's extent, the path's ends may lie from the query's.
pub const QUERY_TOLERANCE: f64 = 1e-6;

/// A path's certificate.
#[derive(Clone, Debug, Serialize)]
pub struct Certificate {
    /// The motion model the segments were checked under.
    pub model: MotionModel,
    /// One verdict per segment (a path of one waypoint: one, for the waypoint itself).
    pub segments: Vec<Verdict>,
    /// Defects of the waypoints.
    pub defects: Vec<Defect>,
    /// Oracle work.
    pub calls: u64,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// The whole path's status.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Every segment proved free, no defect.
    Free,
    /// A segment collides or a waypoint is defective.
    Collides,
    /// Nothing collides, but some segment is undecided.
    Undecided,
}

impl Certificate {
    /// The path's status.
    pub fn status(&self) -> Status {
        if !self.defects.is_empty() || self.segments.iter().any(|v| v.name() == "collides") {
            Status::Collides
        } else if self.segments.iter().any(|v| v.name() == "undecided") {
            Status::Undecided
        } else {
            Status::Free
        }
    }

    /// Counts of free, colliding and undecided segments.
    pub fn counts(&self) -> [usize; 3] {
        let n = |name| self.segments.iter().filter(|v| v.name() == name).count();
        [n("free"), n("collides"), n("undecided")]
    }
}

/// What checks one segment of a scene's kind.
enum Checks {
    Arm(Box<arm::ArmChecks>),
    Rigid(Box<rigid::RigidChecks>),
    Bodies(Box<bodies::BodiesChecks>),
}

/// A scene prepared for certifying paths: its oracle and its independent checks, built once.
pub struct Certifier<'a> {
    scene: &'a Scene,
    oracle: Box<dyn CollisionOracle>,
    checks: Checks,
    model: MotionModel,
}

impl<'a> Certifier<'a> {
    /// Prepares `scene` for paths moving by `model`.
    pub fn new(scene: &'a Scene, model: MotionModel) -> Result<Certifier<'a>, CertifyError> {
        let checks = match &scene.robot {
            Robot::Arm(a) => Checks::Arm(Box::new(arm::ArmChecks::new(a)?)),
            Robot::Bodies(_) | Robot::MeshBodies(_) => {
                Checks::Bodies(Box::new(bodies::BodiesChecks::new(scene)?))
            }
            _ => Checks::Rigid(Box::new(rigid::RigidChecks::new(scene)?)),
        };
        Ok(Certifier {
            scene,
            oracle: scene.oracle(),
            checks,
            model,
        })
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        self.scene
    }

    /// The scene's oracle (with "outside the bounds is obstacle").
    pub fn oracle(&self) -> &dyn CollisionOracle {
        self.oracle.as_ref()
    }

    /// The motion model.
    pub fn model(&self) -> MotionModel {
        self.model
    }

    /// Certifies `path` until `deadline` (segments not reached are undecided).
    pub fn certify(
        &self,
        path: &[Config],
        deadline: &Deadline,
    ) -> Result<Certificate, CertifyError> {
        let began = Instant::now();
        let (clamped, defects) = self.prepare(path)?;
        let mut counts = CallCounts::default();
        let pairs: Vec<(&Config, &Config)> = if clamped.len() == 1 {
            vec![(&clamped[0], &clamped[0])]
        } else {
            clamped.windows(2).map(|w| (&w[0], &w[1])).collect()
        };
        let segments = pairs
            .into_iter()
            .map(|(a, b)| {
                if deadline.expired() {
                    return Verdict::Undecided {
                        reason: "the time budget ran out before this segment".into(),
                    };
                }
                crate::deadline::watching(deadline, || self.segment(a, b, deadline, &mut counts))
            })
            .collect();
        Ok(Certificate {
            model: self.model,
            segments,
            defects,
            calls: counts.intersect_calls() + counts.state_checks,
            seconds: began.elapsed().as_secs_f64(),
        })
    }

    /// The waypoints checked (shape, finite values), normalised (an SE(2) angle wrapped, an
    /// SE(3) quaternion of unit length; an arm's values as written) and clamped into the bounds,
    /// with the path's defects.
    pub fn prepare(&self, path: &[Config]) -> Result<(Vec<Config>, Vec<Defect>), CertifyError> {
        if path.is_empty() {
            return Err(CertifyError::Empty);
        }
        let space = &self.scene.space;
        let mut clamped = Vec::with_capacity(path.len());
        for (index, q) in path.iter().enumerate() {
            space.check(q).map_err(|e| CertifyError::Waypoint {
                index,
                message: e.to_string(),
            })?;
            let mut q = q.clone();
            if !space.is_joints() {
                space.normalize(&mut q);
            }
            clamped.push(q);
        }
        let defects = self.defects(&mut clamped);
        Ok((clamped, defects))
    }

    /// The verdict on the motion from `a` to `b` (both within the bounds).
    pub fn segment(
        &self,
        a: &[f64],
        b: &[f64],
        deadline: &Deadline,
        counts: &mut CallCounts,
    ) -> Verdict {
        // an end in collision: the segment collides there, exactly
        for (t, q) in [(0.0, a), (1.0, b)] {
            if !self.oracle.is_free(q, counts) {
                let Some(pairs) = self.witness(q) else {
                    // an arm's oracle encloses curved shapes: its model check decides
                    if matches!(self.checks, Checks::Arm(_)) {
                        continue;
                    }
                    return Verdict::Undecided {
                        reason: format!(
                            "the oracle's shapes collide at t = {t}, the true shapes do not"
                        ),
                    };
                };
                return Verdict::Collides(Collision {
                    intervals: vec![[t, t]],
                    exact: false,
                    resolution: 0.0,
                    witness: q.to_vec(),
                    witness_t: t,
                    pairs,
                    free_before: 0.0,
                    free_after: 1.0,
                });
            }
        }
        if a == b {
            // no motion: the waypoint alone, which the oracle finds free or only its enclosing
            // shapes in collision (a colliding one returned above)
            let on_true_shapes = |c: &arm::ArmChecks| c.free_on_true_shapes(a, b, deadline);
            return if self.oracle.is_free(a, counts)
                || matches!(&self.checks, Checks::Arm(c) if on_true_shapes(c))
            {
                Verdict::Free
            } else {
                Verdict::Undecided {
                    reason: "the oracle's shapes collide at this waypoint, the true shapes do not"
                        .into(),
                }
            };
        }
        match self.model {
            MotionModel::Direct => self.direct(a, b, counts),
            MotionModel::Interpolate => match &self.checks {
                Checks::Arm(c) => c.straight(a, b, deadline, counts),
                Checks::Rigid(c) => {
                    c.interpolated(self.scene, self.oracle.as_ref(), a, b, deadline, counts)
                }
                Checks::Bodies(c) => {
                    c.interpolated(self.scene, self.oracle.as_ref(), (a, b), deadline, counts)
                }
            },
        }
    }

    /// The pairs touching at `q` by the independent check, `None` if it finds `q` free.
    pub fn witness(&self, q: &[f64]) -> Option<Vec<[String; 2]>> {
        match &self.checks {
            Checks::Arm(c) => c.witness(q),
            Checks::Rigid(c) => c.witness(q),
            Checks::Bodies(c) => c.witness(q),
        }
    }

    /// viaroad's direct path from `a` to `b`: one exact call per DOF group it changes.
    fn direct(&self, a: &[f64], b: &[f64], counts: &mut CallCounts) -> Verdict {
        let space = &self.scene.space;
        let groups = space.groups(false);
        let pieces = direct_pieces(space, &groups, 0, a, b);
        let n = pieces.len().max(1) as f64;
        for (k, (motion, _)) in pieces.iter().enumerate() {
            match self.oracle.intersect(motion, counts) {
                Err(e) => {
                    return Verdict::Undecided {
                        reason: e.to_string(),
                    }
                }
                Ok(list) if list.is_empty() => {}
                Ok(list) => {
                    let share = |t: f64| (k as f64 + t) / n;
                    let intervals: Vec<[f64; 2]> =
                        list.iter().map(|iv| [share(iv.lo), share(iv.hi)]).collect();
                    return self.exact_collision(intervals, |t| motion.at((t * n) - k as f64));
                }
            }
        }
        Verdict::Free
    }

    /// A collision from exact intervals: the witness at the middle of the first interval
    /// (confirmed by the independent check where it can be; else the interval's ends).
    fn exact_collision(&self, intervals: Vec<[f64; 2]>, at: impl Fn(f64) -> Config) -> Verdict {
        exact_collision(intervals, at, |q| self.witness(q))
    }
}

impl Certifier<'_> {
    /// Waypoints outside the bounds (clamping those within [`BOUNDS_TOLERANCE`]) and ends that
    /// differ from every query's.
    fn defects(&self, path: &mut [Config]) -> Vec<Defect> {
        let space = &self.scene.space;
        let bounded = match space.kind() {
            SpaceKind::Se2 => 2,
            SpaceKind::Se3 => 3,
            _ => space.dim(),
        };
        let wrapping = space.wrapping();
        let (lower, upper) = (space.lower().to_vec(), space.upper().to_vec());
        let mut out = Vec::new();
        for (w, q) in path.iter_mut().enumerate() {
            for i in (0..bounded).filter(|&i| !crate::space::joints::bit(wrapping, i)) {
                let (lo, hi) = (lower[i], upper[i]);
                if q[i] < lo - BOUNDS_TOLERANCE || q[i] > hi + BOUNDS_TOLERANCE {
                    out.push(Defect::OutOfBounds {
                        waypoint: w,
                        coordinate: i,
                        value: q[i],
                        lower: lo,
                        upper: hi,
                    });
                }
                q[i] = q[i].clamp(lo, hi);
            }
        }
        let tol = QUERY_TOLERANCE * space.extent();
        let (first, last) = (&path[0], &path[path.len() - 1]);
        let best = self.scene.queries.iter().min_by(|x, y| {
            let d = |q: &crate::scene::Query| {
                space.distance(first, &q.start) + space.distance(last, &q.goal)
            };
            d(x).total_cmp(&d(y))
        });
        if let Some(q) = best {
            let ds = space.distance(first, &q.start);
            if ds > tol {
                out.push(Defect::StartDiffers { distance: ds });
            }
            let dg = space.distance(last, &q.goal);
            if dg > tol {
                out.push(Defect::GoalDiffers { distance: dg });
            }
        }
        out
    }
}

/// Certifies `path` in `scene` (see [`Certifier`]).
pub fn certify(
    scene: &Scene,
    path: &[Config],
    model: MotionModel,
    deadline: &Deadline,
) -> Result<Certificate, CertifyError> {
    Certifier::new(scene, model)?.certify(path, deadline)
}
