//! The independent validity check for paths of several bodies in the plane (SE(2)^k): the
//! library's checker (`viaroad::checker::bodies`, parry polygons pairwise, body–obstacle
//! and body–body, by conservative advancement along every motion; no code shared with the exact
//! oracle), with the panicking constructor tests want.
#![allow(dead_code)]

use viaroad::checker::bodies;
use viaroad::scene::Scene;

pub struct BodiesChecker(bodies::BodiesChecker);

impl BodiesChecker {
    pub fn new(scene: &Scene) -> BodiesChecker {
        BodiesChecker(bodies::BodiesChecker::new(scene).expect("a scene of several bodies"))
    }

    /// The least distance over all body–obstacle and body–body pairs at `q`.
    pub fn clearance(&self, q: &[f64]) -> f64 {
        self.0.clearance(q).expect("parry answers").0
    }

    /// Certifies one motion (all bodies at once, linearly).
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        self.0.certify_motion(a, b)
    }

    /// Certifies a whole path: bounds and every motion.
    pub fn certify_path(&self, path: &[Vec<f64>]) -> Result<(), String> {
        self.0.certify_path(path)
    }
}
