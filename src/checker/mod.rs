//! Path checkers that share no code with the library's exact oracles, for every scene kind: a
//! planner whose oracle misses a collision produces paths that look fine to itself, so every
//! answer that `bench validity`, `query --check`, `serve` and `certify` vouch for is checked
//! again here.
//!
//! * Discs (R^n, closed balls around a point robot): the distance from each segment of the
//!   path to each centre, in closed form, must not be below the radius.
//! * SE(2) polygons and SE(3) meshes: parry shapes (ear-clipped triangles in the plane, parry
//!   trimeshes in space) and *conservative advancement* along every straight motion: with
//!   clearance `d` at `t₀`, nothing can touch before every robot point has moved `d`, and no
//!   point moves faster than `|Δp| + r·|Δθ|` (r = the robot's radius about its reference
//!   point). Pieces are halved until certified; a piece below 1e-10 of the motion that cannot
//!   be certified is a collision (touching counts as collision, the library's convention).
//!   This is stronger than sampling at any resolution: it certifies the whole motion.
//!   SE(3) containment (a robot wholly inside a closed obstacle or holding one) is checked at
//!   the first configuration; surfaces that never touch cannot change it along the path.
//! * Several bodies in the plane ([`bodies`]): the same parry polygons and advancement, over
//!   every body–obstacle and body–body pair.
//! * Several bodies in space ([`bodies3`]): the same parry trimeshes and advancement, over
//!   every body–obstacle and body–body pair, containment at the first corner.

mod advance;
pub mod bodies;
pub mod bodies3;
pub mod planar;
pub mod rigid;

use crate::scene::{Obstacle, Robot, Scene};
use crate::short;
use crate::space::{Config, SpaceKind};
use advance::TOL;

/// An independent path checker for one scene.
pub enum Checker {
    /// A point among closed balls in a box.
    Discs {
        /// Ball centres.
        centres: Vec<Vec<f64>>,
        /// Ball radii.
        radii: Vec<f64>,
        /// Box corners.
        lower: Vec<f64>,
        /// Box corners.
        upper: Vec<f64>,
    },
    /// Polygons in the plane.
    Planar(planar::PlanarChecker),
    /// Meshes in space.
    Rigid(rigid::RigidChecker),
    /// Several polygonal bodies in the plane.
    Bodies(bodies::BodiesChecker),
    /// Several polyhedral bodies in space.
    SolidBodies(bodies3::SolidBodiesChecker),
    /// A jointed arm among MoveIt collision objects: parry on the exact primitives, sampled along
    /// every joint move at `step` (1/10 of OMPL's default resolution, 0.1 % of the joint space's
    /// extent), sharing no code with the exact single-joint oracle.
    Arm {
        /// The checker.
        checker: Box<crate::robot::ArmChecker>,
        /// Sampling step in joint space.
        step: f64,
    },
}

impl Checker {
    /// The checker of `scene`'s kind, or why there is none.
    pub fn for_scene(scene: &Scene) -> Result<Checker, String> {
        match (&scene.robot, scene.space.kind()) {
            (Robot::Point, SpaceKind::Euclidean(_)) => {
                let mut centres = Vec::new();
                let mut radii = Vec::new();
                for o in &scene.obstacles {
                    match o {
                        Obstacle::Disc { centre, radius } => {
                            centres.push(centre.clone());
                            radii.push(*radius);
                        }
                        _ => return Err("a point robot among non-disc obstacles".into()),
                    }
                }
                Ok(Checker::Discs {
                    centres,
                    radii,
                    lower: scene.space.lower().to_vec(),
                    upper: scene.space.upper().to_vec(),
                })
            }
            (Robot::Polygons(_), SpaceKind::Se2) => {
                planar::PlanarChecker::se2(scene).map(Checker::Planar)
            }
            (Robot::Mesh(_), SpaceKind::Se3) => rigid::RigidChecker::se3(scene).map(Checker::Rigid),
            (Robot::Bodies(_), SpaceKind::Se2Bodies(_)) => {
                bodies::BodiesChecker::new(scene).map(Checker::Bodies)
            }
            (Robot::MeshBodies(_), SpaceKind::Se3Bodies(_)) => {
                bodies3::SolidBodiesChecker::new(scene).map(Checker::SolidBodies)
            }
            (Robot::Arm(a), SpaceKind::Joints { .. }) => {
                let checker =
                    crate::robot::ArmChecker::new(&a.arm, &a.objects).map_err(|e| e.to_string())?;
                let step = 0.001 * checker.arm().group.max_extent();
                Ok(Checker::Arm {
                    checker: Box::new(checker),
                    step,
                })
            }
            (r, k) => Err(format!("robot {r:?} in {k}")),
        }
    }

    /// Checks a path: every corner in the bounds, every straight motion free (touching counts
    /// as collision). Returns the first violation.
    pub fn check_path(&self, path: &[Config]) -> Result<(), String> {
        match self {
            Checker::Discs {
                centres,
                radii,
                lower,
                upper,
            } => check_disc_path(path, centres, radii, lower, upper),
            Checker::Planar(c) => c.certify_path(path),
            Checker::Rigid(c) => c.certify_path(path),
            Checker::Bodies(c) => c.certify_path(path),
            Checker::SolidBodies(c) => c.certify_path(path),
            Checker::Arm { checker, step } => {
                let report = checker.check_path(path, *step).map_err(|e| e.to_string())?;
                match report.first_invalid {
                    None => Ok(()),
                    Some((segment, t, hits)) => Err(format!(
                        "segment {segment} at t = {t:.4}: {}",
                        if hits.is_empty() {
                            "outside the joint limits".to_string()
                        } else {
                            format!("{hits:?}")
                        }
                    )),
                }
            }
        }
    }
}

/// Distance from point `c` to the segment `a`–`b` (any dimension).
pub fn segment_point_distance(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
    let ac: Vec<f64> = a.iter().zip(c).map(|(x, y)| y - x).collect();
    let len2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if len2 > 0.0 {
        (ab.iter().zip(&ac).map(|(u, v)| u * v).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a.iter()
        .zip(&ab)
        .zip(c)
        .map(|((x, d), y)| (x + t * d - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn check_disc_path(
    path: &[Config],
    centres: &[Vec<f64>],
    radii: &[f64],
    lower: &[f64],
    upper: &[f64],
) -> Result<(), String> {
    for (k, q) in path.iter().enumerate() {
        if q.len() != lower.len() {
            return Err(format!(
                "corner {k} {} has the wrong dimension",
                short::config(q)
            ));
        }
        for i in 0..q.len() {
            if !(q[i] >= lower[i] - TOL && q[i] <= upper[i] + TOL) {
                return Err(format!(
                    "corner {k} {} outside the bounds",
                    short::config(q)
                ));
            }
        }
    }
    if path.len() == 1 {
        for (c, r) in centres.iter().zip(radii) {
            if segment_point_distance(&path[0], &path[0], c) <= *r {
                return Err(format!(
                    "{} lies in disc {} of radius {}",
                    short::config(&path[0]),
                    short::config(c),
                    short::num(*r)
                ));
            }
        }
    }
    for (k, w) in path.windows(2).enumerate() {
        for (c, r) in centres.iter().zip(radii) {
            let d = segment_point_distance(&w[0], &w[1], c);
            // closed balls: a segment at exactly the radius touches, and touching collides
            if d < r - TOL {
                return Err(format!(
                    "segment {k} {}→{} passes {} from disc {} of radius {}",
                    short::config(&w[0]),
                    short::config(&w[1]),
                    short::num(d),
                    short::config(c),
                    short::num(*r)
                ));
            }
        }
    }
    Ok(())
}
