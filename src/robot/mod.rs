//! Robot arms: URDF + SRDF models, forward kinematics, collision geometry and an
//! independent collision checker.
//!
//! The seed names "a robot arm whose links may only move one at a time" as a use where the
//! intersection of a line with the configuration obstacle simplifies remarkably (CHS §1.5,
//! §2.3.2): moving one revolute joint turns the distal links rigidly about an axis fixed in the
//! world. This module supplies what every arm feature needs before that oracle exists: the
//! robot itself.
//!
//! | module | concept |
//! |---|---|
//! | [`urdf`] | links, joints (revolute, continuous, prismatic, fixed), origins, axes, collision elements |
//! | [`srdf`] | planning groups, `disable_collisions`, the virtual joint |
//! | [`shapes`] | primitives (box, cylinder, sphere, cone) and the polytopes that contain them; a big mesh's envelope |
//! | [`kinematics`] | the kinematic tree, forward kinematics, planning groups and their bounds |
//! | [`arm`] | a loaded arm: model + link geometry + self-collision pairs + a planning group |
//! | [`objects`] | the world's collision objects: primitives and meshes placed in a frame |
//! | [`oracle`] | exact collision intervals of a single-joint move (the polyhedra oracle's rotations) |
//! | [`inner`] | balls inside the links: a sure collision test ahead of the exact one |
//! | [`cover`] | balls about the links and shapes about the obstacles: a cheap proof of "apart" |
//! | [`checker`] | the independent checker: parry `intersection_test` of every pair, sampled paths |

pub mod arm;
pub mod checker;
mod clearance;
pub mod cover;
pub mod inner;
pub mod kinematics;
pub mod objects;
pub mod oracle;
pub mod shapes;
pub mod srdf;
pub mod urdf;

pub use arm::{Arm, ArmOptions};
pub use checker::{ArmChecker, Collision, Contact, PartPair, PathReport};
pub use kinematics::{Group, Model};
pub use oracle::ArmOracle;
pub use shapes::Primitive;

use crate::mesh_io::MeshError;
use std::path::{Path, PathBuf};

/// Everything that can be wrong with a robot description or a configuration asked of it.
#[derive(Debug, thiserror::Error)]
pub enum RobotError {
    /// A file (URDF, SRDF, mesh) cannot be read or a mesh cannot be used.
    #[error(transparent)]
    Input(#[from] MeshError),
    /// The file is not well-formed XML.
    #[error("{path}: not valid XML: {message}")]
    Xml {
        /// The file.
        path: PathBuf,
        /// What the parser said.
        message: String,
    },
    /// Well-formed but meaningless: an unknown joint type, a missing attribute, a number that
    /// is not finite, a link with two parents, a group naming an unknown joint …
    #[error("{path}: {message}")]
    Invalid {
        /// The file (URDF or SRDF).
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A joint vector of the wrong length or with a non-finite value.
    #[error("{what}: {message}")]
    Config {
        /// Which configuration.
        what: String,
        /// What is wrong.
        message: String,
    },
    /// An oracle call gave up at the deadline watched on its thread
    /// ([`crate::deadline::watching`]).
    #[error("interrupted: the deadline passed during a joint move")]
    Interrupted,
}

/// Parses a finite number, refusing magnitudes beyond [`crate::limits::MAX_COORDINATE`]
/// (later products must not overflow).
pub(crate) fn parse_number(text: &str) -> Option<f64> {
    let v: f64 = text.trim().parse().ok()?;
    (v.is_finite() && v.abs() <= crate::limits::MAX_COORDINATE).then_some(v)
}

/// Parses `n` whitespace-separated finite numbers (URDF's `xyz="0 0 0.333"`).
pub(crate) fn parse_numbers<const N: usize>(text: &str) -> Option<[f64; N]> {
    let mut out = [0.0; N];
    let mut it = text.split_whitespace();
    for slot in &mut out {
        *slot = parse_number(it.next()?)?;
    }
    it.next().is_none().then_some(out)
}

/// Parses URDF or SRDF text and checks that its root is `<robot>` (both formats share it);
/// `path` names the file in errors. The parser stops at [`crate::limits::MAX_XML_NODES`]
/// nodes, so a huge file is refused before its tree is built.
pub(crate) fn robot_xml<'t>(
    text: &'t str,
    path: &Path,
) -> Result<roxmltree::Document<'t>, RobotError> {
    let options = roxmltree::ParsingOptions {
        nodes_limit: crate::limits::MAX_XML_NODES,
        ..roxmltree::ParsingOptions::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| match e {
        roxmltree::Error::NodesLimitReached => RobotError::Invalid {
            path: path.to_path_buf(),
            message: format!(
                "more than {} XML nodes, far more than any robot description has",
                crate::limits::MAX_XML_NODES
            ),
        },
        e => RobotError::Xml {
            path: path.to_path_buf(),
            message: e.to_string(),
        },
    })?;
    let root = doc.root_element();
    if !root.has_tag_name("robot") {
        return Err(RobotError::Invalid {
            path: path.to_path_buf(),
            message: format!(
                "the root element is <{}>, not <robot>",
                root.tag_name().name()
            ),
        });
    }
    Ok(doc)
}
