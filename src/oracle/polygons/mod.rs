//! A polygonal robot among polygons in SE(2). (In progress.)

use super::{CallCounts, CollisionOracle, OracleError};
use crate::geometry::Polygon;
use crate::interval::IntervalList;
use crate::space::Motion;

/// Exact collision intervals of a polygonal robot among polygons.
pub struct Polygons {
    robot: Vec<Polygon>,
    obstacles: Vec<Polygon>,
}

impl Polygons {
    /// `robot` parts in the body frame (reference point at the origin), obstacles in the world.
    pub fn new(robot: Vec<Polygon>, obstacles: Vec<Polygon>) -> Polygons {
        Polygons { robot, obstacles }
    }
}

impl CollisionOracle for Polygons {
    fn intervals(
        &self,
        _motion: &Motion,
        _counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let _ = (&self.robot, &self.obstacles);
        Err(OracleError::Unsupported("polygons: not yet".into()))
    }
    fn collides(&self, _q: &[f64], _counts: &mut CallCounts) -> bool {
        false
    }
}
