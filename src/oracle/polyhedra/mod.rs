//! A polyhedral robot among polyhedral obstacles in SE(3) (CHS Chapter 2). (In progress.)

use super::{CallCounts, CollisionOracle, OracleError};
use crate::geometry::TriMesh;
use crate::interval::IntervalList;
use crate::space::Motion;

/// Exact collision intervals of a triangle-mesh robot among triangle-mesh obstacles.
pub struct Polyhedra {
    robot: TriMesh,
    obstacles: Vec<TriMesh>,
}

impl Polyhedra {
    /// `robot` in its body frame (reference point at the origin), obstacles in the world frame.
    pub fn new(robot: TriMesh, obstacles: Vec<TriMesh>) -> Polyhedra {
        Polyhedra { robot, obstacles }
    }
}

impl CollisionOracle for Polyhedra {
    fn intervals(
        &self,
        _motion: &Motion,
        _counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let _ = (&self.robot, &self.obstacles);
        Err(OracleError::Unsupported("polyhedra: not yet".into()))
    }
    fn collides(&self, _q: &[f64], _counts: &mut CallCounts) -> bool {
        false
    }
}
