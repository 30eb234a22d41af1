//! The straight-line local method: the direct path or nothing.

use super::{check_direct, Connection, Discoveries, LocalMethod, Outcome};
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
    fn spec(&self) -> String {
        match self.resolution {
            None => "straight".into(),
            Some(r) => format!("sampled:res={r}"),
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
        let mut discoveries = Discoveries::new(a, z);
        let (outcome, path) = match corners {
            Some(corners) => {
                let mut prev = 0u32;
                for (k, c) in corners.iter().enumerate() {
                    let idx = if k + 1 == corners.len() {
                        1
                    } else {
                        discoveries.add(c.clone())
                    };
                    discoveries.free_segments.push((prev, idx));
                    prev = idx;
                }
                let mut path = vec![a.to_vec()];
                path.extend(corners);
                (Outcome::Connected, path)
            }
            None => (Outcome::Blocked, Vec::new()),
        };
        Ok(Connection {
            outcome,
            path,
            depth: 0,
            counts,
            discoveries,
            borderlines: Vec::new(),
        })
    }
}
