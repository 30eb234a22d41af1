//! The recursive via-point planner (CHS §1.2–1.5). (In progress.)

mod options;

pub use options::{BasePoint, Depth, Directions, Search, ViaLimit, ViaPointOptions};

use super::{Connection, LocalMethod};
use crate::oracle::{CollisionOracle, OracleError};
use crate::space::{Group, Space};

/// The via-point local method.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViaPoint {
    /// Its parameters.
    pub options: ViaPointOptions,
}

impl ViaPoint {
    /// A planner with these options.
    pub fn new(options: ViaPointOptions) -> Self {
        ViaPoint { options }
    }
}

impl LocalMethod for ViaPoint {
    fn spec(&self) -> String {
        super::LocalSpec::ViaPoint(self.options.clone()).to_string()
    }

    fn connect(
        &self,
        space: &Space,
        oracle: &dyn CollisionOracle,
        a: &[f64],
        z: &[f64],
    ) -> Result<Connection, OracleError> {
        super::StraightLine::exact().connect(space, oracle, a, z)
    }

    fn groups(&self, space: &Space) -> Vec<Group> {
        space.groups(self.options.split_axes)
    }
}
