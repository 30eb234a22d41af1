//! The independent validity check for rigid-body paths (SE(3)): the library's validity
//! checker (`viaroad::bench::validity::rigid`, parry meshes and conservative advancement,
//! sharing no code with the exact oracles — `viaroad bench validity` uses the same one), with
//! the panicking constructors tests want.
#![allow(dead_code)]

use viaroad::bench::validity::rigid;
use viaroad::scene::Scene;

pub struct RigidChecker(rigid::RigidChecker);

impl RigidChecker {
    pub fn se3(scene: &Scene) -> RigidChecker {
        RigidChecker(rigid::RigidChecker::se3(scene).expect("an SE(3) scene of meshes"))
    }

    /// Distance between the robot's surface at `q` and the nearest obstacle surface.
    pub fn clearance(&self, q: &[f64]) -> f64 {
        self.0.clearance(q).expect("parry answers")
    }

    /// Certifies one straight motion (a translation or a turn about one axis).
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        self.0.certify_motion(a, b)
    }

    /// Certifies a whole path: bounds, containment at the start, every motion.
    pub fn certify_path(&self, path: &[Vec<f64>]) -> Result<(), String> {
        self.0.certify_path(path)
    }
}
