//! The straight-line local method: the direct path or nothing.

use super::{check_direct, Connection, LocalMethod, LocalSpec};
use crate::deadline::Deadline;
use crate::oracle::sampled::Sampled;
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::space::Space;

/// Checks the direct path (one segment in R^n; translation then rotation for a rigid body), in
/// one question per piece. With `resolution` set it samples states like OMPL's
/// `DiscreteMotionValidator` instead of asking the exact oracle — the benchmark baseline.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StraightLine {
    /// `None`: exact oracle. `Some(r)`: sample states at resolution `r` (fraction of the
    /// space's extent).
    pub resolution: Option<f64>,
}

impl StraightLine {
    /// Exact checking.
    pub fn exact() -> Self {
        StraightLine { resolution: None }
    }

    /// Sampled checking at `resolution` (OMPL's default is 0.01).
    pub fn sampled(resolution: f64) -> Self {
        StraightLine {
            resolution: Some(resolution),
        }
    }
}

impl LocalMethod for StraightLine {
    fn spec(&self) -> LocalSpec {
        match self.resolution {
            None => LocalSpec::Straight,
            Some(resolution) => LocalSpec::Sampled { resolution },
        }
    }

    fn connect_within(
        &self,
        space: &Space,
        oracle: &dyn CollisionOracle,
        a: &[f64],
        z: &[f64],
        deadline: &Deadline,
    ) -> Result<Connection, OracleError> {
        if deadline.expired() {
            return Ok(Connection::interrupted(a, z));
        }
        let groups = self.groups(space);
        let mut counts = CallCounts::default();
        let corners = match self.resolution {
            None => check_direct(space, oracle, &groups, a, z, &mut counts)?,
            Some(r) => {
                let sampled = Sampled::new(space.clone(), oracle, r);
                check_direct(space, &sampled, &groups, a, z, &mut counts)?
            }
        };
        Ok(Connection::from_corners(a, z, corners, counts))
    }
}
