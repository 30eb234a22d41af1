//! What certifying says about a path's segment, and why a path cannot be certified at all:
//! the types that the certifier and each of its provers (arms, rigid bodies, located
//! segments) return.

use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::scene::Scene;
use crate::space::Config;
use serde::Serialize;

/// Why a path cannot be certified at all (a blocked or undecided segment is a result).
#[derive(Debug, thiserror::Error)]
pub enum CertifyError {
    /// The path holds no waypoint.
    #[error("the path holds no waypoint")]
    Empty,
    /// A waypoint has the wrong number of values or a value that is not finite.
    #[error("waypoint {index}: {message}")]
    Waypoint {
        /// 0-based.
        index: usize,
        /// What is wrong.
        message: String,
    },
    /// The scene's robot cannot be checked independently.
    #[error("no independent check for this scene: {0}")]
    Unsupported(String),
    /// An oracle or robot model refused a question.
    #[error("oracle: {0}")]
    Oracle(String),
}

/// A collision found on a segment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Collision {
    /// Closed intervals of the segment's parameter `t ∈ [0, 1]` that hold every collision:
    /// exact ([`Self::exact`]), or unions of pieces of width [`Self::resolution`] not proved
    /// free.
    pub intervals: Vec<[f64; 2]>,
    /// Whether the intervals are the oracle's exact collision set.
    pub exact: bool,
    /// The width of the pieces the intervals were located to (0 when exact).
    pub resolution: f64,
    /// A configuration on the segment in collision.
    pub witness: Config,
    /// Its parameter.
    pub witness_t: f64,
    /// The pairs that touch at the witness (link / obstacle names for arms).
    pub pairs: Vec<[String; 2]>,
    /// The segment is proved free over `[0, free_before]`.
    pub free_before: f64,
    /// … and over `[free_after, 1]` (where its end is free).
    pub free_after: f64,
}

/// The verdict on one segment.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "verdict", rename_all = "lowercase")]
pub enum Verdict {
    /// Proved free.
    Free,
    /// Collides.
    Collides(Collision),
    /// Neither proved free nor a collision found.
    Undecided {
        /// Why.
        reason: String,
    },
}

impl Verdict {
    /// The verdict's name (`free`, `collides`, `undecided`).
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::Free => "free",
            Verdict::Collides(_) => "collides",
            Verdict::Undecided { .. } => "undecided",
        }
    }
}

/// A collision from exact intervals: the witness at the middle of the first interval, else
/// at its ends or quarters, where `witness` (the independent check) confirms it; else the
/// verdict is undecided (the oracle's enclosing shapes collide, the true shapes nowhere tried).
pub(crate) fn exact_collision(
    intervals: Vec<[f64; 2]>,
    at: impl Fn(f64) -> Config,
    witness: impl Fn(&[f64]) -> Option<Vec<[String; 2]>>,
) -> Verdict {
    let candidates = intervals.iter().flat_map(|[lo, hi]| {
        [
            0.5 * (lo + hi),
            *lo,
            *hi,
            0.25 * (3.0 * lo + hi),
            0.25 * (lo + 3.0 * hi),
        ]
    });
    for t in candidates {
        let q = at(t);
        if let Some(pairs) = witness(&q) {
            return Verdict::Collides(Collision {
                free_before: intervals[0][0],
                free_after: intervals[intervals.len() - 1][1],
                intervals,
                exact: true,
                resolution: 0.0,
                witness: q,
                witness_t: t,
                pairs,
            });
        }
    }
    Verdict::Undecided {
        reason: format!(
            "the oracle's enclosing shapes collide within {}, the true shapes at no point tried",
            fmt_intervals(&intervals)
        ),
    }
}

/// Intervals as `[a, b] ∪ …`.
pub(crate) fn fmt_intervals(intervals: &[[f64; 2]]) -> String {
    intervals
        .iter()
        .map(|[a, b]| format!("[{a:.6}, {b:.6}]"))
        .collect::<Vec<_>>()
        .join(" ∪ ")
}

/// The verdict on the interpolated motion from `a` to `b` where it changes at most one DOF
/// group: then it is one of the seed's motions, answered by one exact call of the scene's
/// oracle (a collision confirmed by `witness`, the independent check). `None` where several
/// groups change at once, which the caller proves otherwise.
pub(crate) fn one_group_verdict(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    (a, b): (&[f64], &[f64]),
    counts: &mut CallCounts,
    witness: impl Fn(&[f64]) -> Option<Vec<[String; 2]>>,
) -> Option<Verdict> {
    let space = &scene.space;
    let groups = space.groups(false);
    let mut changed = groups.iter().filter(|g| !space.same_in_group(a, b, g));
    let Some(g) = changed.next() else {
        return Some(Verdict::Free);
    };
    if changed.next().is_some() {
        return None;
    }
    let motion = space.group_motion(a, b, g);
    Some(match oracle.intersect(&motion, counts) {
        Ok(list) if list.is_empty() => Verdict::Free,
        Ok(list) => exact_collision(
            list.iter().map(|iv| [iv.lo, iv.hi]).collect(),
            |t| motion.at(t),
            witness,
        ),
        Err(e) => Verdict::Undecided {
            reason: e.to_string(),
        },
    })
}
