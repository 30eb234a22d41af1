//! What a space is made of: its kind, its DOF groups, its errors, and the space itself, whose
//! methods live in the parent module and, for one kind each, in [`joints`](super::joints) and
//! [`bodies`](super::bodies).

use crate::short;
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// A configuration: one `f64` per coordinate, in the space's layout.
pub type Config = Vec<f64>;

/// Which configuration space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SpaceKind {
    /// R^n: a point robot (or any robot whose configuration is n independent reals).
    Euclidean(usize),
    /// SE(2): `[x, y, θ]`, θ in radians, wrapped into `[-π, π)`.
    Se2,
    /// SE(3): `[x, y, z, qx, qy, qz, qw]`, a unit quaternion in OMPL's order.
    Se3,
    /// The joint values of an arm's planning group, in group order (see
    /// [`joints`](crate::space::joints)): one DOF group per joint, because moving one joint turns
    /// the distal part rigidly about a fixed axis (CHS §1.5, §2.3.2).
    Joints {
        /// Number of joints.
        dof: usize,
        /// Bit `i` set: joint `i` is continuous (wraps like SE(2)'s angle, has no limits).
        continuous: u64,
    },
    /// SE(2)^k: several polygonal bodies in the plane, `[x₀, y₀, θ₀, x₁, y₁, θ₁, …]`, the bodies'
    /// poses concatenated (see [`bodies`](crate::space::bodies)). Groups: all bodies translate at
    /// once, or one body turns about its reference point (CHS Chapter 2).
    Se2Bodies(usize),
    /// SE(3)^k: several rigid bodies in space, the bodies' SE(3) poses concatenated (see
    /// [`bodies3`](super::bodies3)). Groups: all bodies translate at once, or one body turns about a fixed
    /// axis through its reference point (CHS Chapter 2).
    Se3Bodies(usize),
}

impl std::fmt::Display for SpaceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SpaceKind::Euclidean(2) => write!(f, "r2"),
            SpaceKind::Euclidean(n) => write!(f, "r{n}"),
            SpaceKind::Se2 => write!(f, "se2"),
            SpaceKind::Se3 => write!(f, "se3"),
            SpaceKind::Joints { dof, .. } => write!(f, "arm{dof}"),
            SpaceKind::Se2Bodies(k) => write!(f, "se2x{k}"),
            SpaceKind::Se3Bodies(k) => write!(f, "se3x{k}"),
        }
    }
}

/// What a group of coordinates is (CHS §1.5: a configuration is a tuple of DOF groups, and a
/// path changes one group at a time).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum GroupKind {
    /// Coordinates that move linearly (R^n, or the position of a rigid body).
    Linear,
    /// One angle (SO(2)): turns about the robot's reference point.
    Angle,
    /// A unit quaternion (SO(3)): rotations about axes through the reference point.
    Quaternion,
}

/// A group of coordinates that changes together.
///
/// Most groups are one run of coordinates, `coords`. The translation of several bodies at once
/// repeats a run once per body: the coordinates are `coords` shifted by `b · stride` for every
/// `b < repeats` (see [`indices`](Self::indices)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Group {
    /// What the coordinates are.
    pub kind: GroupKind,
    /// Their indices in a configuration (the first run of them, if the group repeats).
    pub coords: Range<usize>,
    /// Distance between repeated runs (0 for a group of one run).
    pub stride: usize,
    /// Number of runs (1 for a group of one run).
    pub repeats: usize,
}

impl Group {
    /// A group of the one run of coordinates `coords`.
    pub fn run(kind: GroupKind, coords: Range<usize>) -> Group {
        Group {
            kind,
            coords,
            stride: 0,
            repeats: 1,
        }
    }

    /// Number of coordinates.
    pub fn len(&self) -> usize {
        self.coords.len() * self.repeats
    }

    /// Whether the group has no coordinates (never, for groups a space hands out).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The group's coordinate indices in increasing order.
    pub fn indices(&self) -> impl Iterator<Item = usize> + Clone + '_ {
        (0..self.repeats).flat_map(move |b| {
            let shift = b * self.stride;
            (self.coords.start + shift)..(self.coords.end + shift)
        })
    }

    /// Copies the group's coordinates of `src` into `dst`.
    pub fn copy_coords(&self, dst: &mut [f64], src: &[f64]) {
        for i in self.indices() {
            dst[i] = src[i];
        }
    }
}

/// Invalid space definitions and configurations.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpaceError {
    /// Bounds of the wrong length, NaN, lower ≥ upper (zero width leaves the via-point planner
    /// no room beside a motion), or beyond [`crate::limits::MAX_COORDINATE`] (where distances
    /// overflow).
    #[error("invalid bounds: {0}")]
    Bounds(String),
    /// A configuration with the wrong number of coordinates.
    #[error("configuration has {got} coordinates, the {kind} space needs {want}")]
    Dimension {
        /// The space.
        kind: SpaceKind,
        /// Expected length.
        want: usize,
        /// Actual length.
        got: usize,
    },
    /// NaN or infinite coordinate.
    #[error("configuration coordinate {index} is not a finite number ({value})")]
    NotFinite {
        /// Index of the coordinate.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// An SE(3) quaternion of (almost) zero length.
    #[error("quaternion (qx, qy, qz, qw) has length {}, cannot be normalised", short::num(*.0))]
    Quaternion(f64),
    /// Rotation scale not positive.
    #[error("rotation scale must be a positive number, got {}", short::num(*.0))]
    RotationScale(f64),
}

/// A configuration space with bounds on the position.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Space {
    pub(super) kind: SpaceKind,
    pub(super) lower: Vec<f64>,
    pub(super) upper: Vec<f64>,
    pub(super) rotation_scale: f64,
}

/// Appends a configuration's few numbers one by one: for vectors this short a call of the
/// library's `memmove` cost more than the copy itself (perf of `bench discs`).
#[inline]
pub fn extend_small(dst: &mut Vec<f64>, src: &[f64]) {
    dst.reserve(src.len());
    for &x in src {
        dst.push(x);
    }
}
