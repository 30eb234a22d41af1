//! The independent validity check for paths of several bodies in space (SE(3)^k): the
//! library's checker (`viaroad::checker::bodies3`, parry trimeshes pairwise, body–obstacle and
//! body–body, by conservative advancement along every motion, containment at the first corner;
//! no code shared with the exact oracle), with the panicking constructor tests want.
#![allow(dead_code)]

use viaroad::checker::bodies3;
use viaroad::scene::Scene;

pub struct SolidBodiesChecker(bodies3::SolidBodiesChecker);

impl SolidBodiesChecker {
    pub fn new(scene: &Scene) -> SolidBodiesChecker {
        SolidBodiesChecker(
            bodies3::SolidBodiesChecker::new(scene).expect("a scene of several bodies in space"),
        )
    }

    /// The least distance over all body–obstacle and body–body surface pairs at `q`.
    pub fn clearance(&self, q: &[f64]) -> f64 {
        self.0.clearance(q).expect("parry answers").0
    }

    /// Whether a body lies inside an obstacle or another body (or holds one) at `q`.
    pub fn contained(&self, q: &[f64]) -> bool {
        self.0.containment(q).is_some()
    }

    /// Certifies one motion (all bodies at once, linearly, each turning about one axis).
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        self.0.certify_motion(a, b)
    }

    /// Certifies a whole path: bounds, containment at the start and every motion.
    pub fn certify_path(&self, path: &[Vec<f64>]) -> Result<(), String> {
        self.0.certify_path(path)
    }
}
