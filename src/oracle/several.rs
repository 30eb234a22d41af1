//! What the exact oracles of several bodies share, in the plane ([`super::bodies`]) and in
//! space ([`super::bodies3`]): a motion is answered as its parts — one robot's motion against
//! one oracle each (a body among the obstacles, or one body past another in the other's
//! frame) — once the bodies that stand still while one turns are known to be free where they
//! stand. The two oracles differ only in their geometry: the parts of a motion and the
//! standing check.

use super::{CallCounts, CollisionOracle, OracleError};
use crate::interval::IntervalList;
use crate::space::Motion;

/// An oracle of several bodies, as the parts of its motions.
pub(super) trait Parts {
    /// The oracle of one body (or one pair of bodies): a single robot's exact oracle.
    type Part: CollisionOracle;

    /// The body a motion turns, `None` for a translation of all bodies.
    fn turning_body(&self, motion: &Motion) -> Result<Option<usize>, OracleError>;

    /// Whether the bodies other than `moving` collide with the obstacles or with each other
    /// where they stand (`q` a configuration of all bodies).
    fn static_collision(&self, q: &[f64], moving: Option<usize>, counts: &mut CallCounts) -> bool;

    /// The parts `motion` asks: each an oracle and the motion of its one robot, in a fixed
    /// order, the pairs that cannot meet left out.
    fn parts(&self, motion: &Motion) -> Result<Vec<(&Self::Part, Motion)>, OracleError>;
}

/// The collision intervals of `motion`: all of its range where a turn's standing bodies
/// already collide (they collide throughout), else the union of its parts' intervals.
pub(super) fn intervals<B: Parts>(
    bodies: &B,
    motion: &Motion,
    counts: &mut CallCounts,
) -> Result<IntervalList, OracleError> {
    if let Some(body) = bodies.turning_body(motion)? {
        if bodies.static_collision(&motion.origin, Some(body), counts) {
            return Ok(IntervalList::single(motion.range));
        }
    }
    let mut all = Vec::new();
    for (oracle, part) in bodies.parts(motion)? {
        all.extend(oracle.intervals(&part, counts)?.iter().copied());
    }
    Ok(IntervalList::from_unsorted(all))
}

/// Whether `motion` is free: a turn's standing bodies free where they stand, and every part
/// free (the first blocked part ends the question).
pub(super) fn motion_is_free<B: Parts>(
    bodies: &B,
    motion: &Motion,
    counts: &mut CallCounts,
) -> Result<bool, OracleError> {
    if let Some(body) = bodies.turning_body(motion)? {
        if bodies.static_collision(&motion.origin, Some(body), counts) {
            return Ok(false);
        }
    }
    for (oracle, part) in bodies.parts(motion)? {
        if !oracle.motion_is_free(&part, counts)? {
            return Ok(false);
        }
    }
    Ok(true)
}

/// Where the oracle of body `i` moving past body `j` (`i ≠ j`) stands among the `k · (k − 1)`
/// ordered pairs of `k` bodies.
pub(super) fn pair_index(k: usize, i: usize, j: usize) -> usize {
    i * (k - 1) + if j < i { j } else { j - 1 }
}
