//! What a query along the freeways returns, and what the method cannot do.

use crate::oracle::OracleError;
use crate::space::Config;

/// What the freeway method cannot do.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConeError {
    /// The scene is not planar (SE(3), R³ …) or its robot is not a polygon or a point.
    #[error("generalized cones need a planar scene (se2 or r2): {0}")]
    Unsupported(String),
    /// The oracle refused a motion while start or goal were joined or the path re-checked.
    #[error("oracle: {0}")]
    Oracle(#[from] OracleError),
    /// A configuration of the wrong dimension.
    #[error("configuration of {got} coordinates; the scene has {expected}")]
    Dimension {
        /// Coordinates given.
        got: usize,
        /// Coordinates expected.
        expected: usize,
    },
}

/// A path found along the freeways.
#[derive(Clone, Debug, PartialEq)]
pub struct ConePath {
    /// Configurations; consecutive ones differ by a pure translation or a pure rotation of at
    /// most a quarter turn.
    pub path: Vec<Config>,
    /// Length in the space's metric.
    pub length: f64,
    /// Cones the path follows (in order, repeats removed).
    pub cones: Vec<usize>,
    /// A* states expanded.
    pub expanded: usize,
}

/// How a query ended.
#[derive(Clone, Debug, PartialEq)]
pub enum ConeOutcome {
    /// A path along the freeways, re-checked by the oracle.
    Solved(ConePath),
    /// No path: why (start or goal cannot reach a freeway, or the graph does not join them).
    NotFound(String),
}

impl ConeOutcome {
    /// The path, if solved.
    pub fn path(&self) -> Option<&ConePath> {
        match self {
            ConeOutcome::Solved(p) => Some(p),
            ConeOutcome::NotFound(_) => None,
        }
    }
}
