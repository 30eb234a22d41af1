//! The independent validity check for planar rigid-body paths (SE(2)): the library's validity
//! checker (`viaroad::bench::validity::planar`, parry polygons and conservative advancement,
//! sharing no code with the exact oracles), with the panicking constructors tests want.
#![allow(dead_code)]

use viaroad::bench::validity::planar;
use viaroad::scene::Scene;

pub struct PlanarChecker(planar::PlanarChecker);

impl PlanarChecker {
    pub fn se2(scene: &Scene) -> PlanarChecker {
        PlanarChecker(planar::PlanarChecker::se2(scene).expect("an SE(2) scene of polygons"))
    }

    /// Distance between the robot and the nearest obstacle at `q`.
    pub fn clearance(&self, q: &[f64]) -> f64 {
        self.0.clearance(q).expect("parry answers")
    }

    /// Certifies one straight motion (a translation or a turn).
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        self.0.certify_motion(a, b)
    }

    /// Certifies a whole path: bounds and every motion.
    pub fn certify_path(&self, path: &[Vec<f64>]) -> Result<(), String> {
        self.0.certify_path(path)
    }
}
