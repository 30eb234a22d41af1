//! Locating what keeps a segment from being proved free, for checks that answer a motion only
//! yes or no (an arm's straight motion of several joints, a rigid body translating and turning
//! at once): the segment is halved where it is not proved, pieces proved free are kept, and
//! the pieces that stay unproved at the finest width hold every collision. A configuration in
//! them that the independent check confirms as colliding makes the verdict a collision; none
//! found leaves it undecided (the bodies pass closer than the proof's margin).

use super::{Collision, Verdict};
use crate::deadline::Deadline;

/// Width (share of the segment) below which an unproved piece with a confirmed collision is
/// not halved further: the located intervals are this fine.
pub const COARSE: f64 = 1.0 / 4096.0;

/// Proof attempts one segment may spend locating: near-contacts that no proof separates and
/// no sample finds colliding would otherwise be halved down to the finest width all along.
pub const MAX_PROOFS: usize = 512;

/// What a located segment is asked: a yes/no proof over a piece of its parameter, and whether
/// the configuration at a parameter really collides (with the pairs that touch).
pub(crate) trait Prover {
    /// Whether the motion over `[t0, t1]` is proved free.
    fn proved_free(&mut self, t0: f64, t1: f64) -> Result<bool, super::CertifyError>;
    /// The touching pairs at `t` if the configuration there collides, `None` if it is free.
    fn witness(&mut self, t: f64) -> Option<Vec<[String; 2]>>;
    /// The configuration at `t`.
    fn at(&self, t: f64) -> Vec<f64>;
}

/// An unproved piece and, if found, a colliding parameter in it with its pairs.
type Leaf = (f64, f64, Option<(f64, Vec<[String; 2]>)>);

/// Locates the collisions of a segment that is not proved free as a whole (see the module's
/// text): pieces are halved down to [`COARSE`] where a collision is confirmed and down to
/// `fine` where none is yet. Undecided if `deadline` passes.
pub(crate) fn locate(p: &mut dyn Prover, fine: f64, deadline: &Deadline) -> Verdict {
    let mut stack = vec![(0.0f64, 1.0f64)];
    let mut leaves: Vec<Leaf> = Vec::new();
    let mut proofs = 0;
    while let Some((t0, t1)) = stack.pop() {
        if deadline.expired() {
            return Verdict::Undecided {
                reason: "the time budget ran out while locating a collision".into(),
            };
        }
        proofs += 1;
        if proofs > MAX_PROOFS {
            return match leaves.iter().find_map(|(_, _, h)| h.clone()) {
                Some(_) => collision(p, &leaves, &stack),
                None => Verdict::Undecided {
                    reason: format!(
                        "{MAX_PROOFS} proofs did not separate the bodies, and no configuration \
                         tried collides"
                    ),
                },
            };
        }
        match p.proved_free(t0, t1) {
            Ok(true) => continue,
            Ok(false) => {}
            Err(e) => {
                return Verdict::Undecided {
                    reason: e.to_string(),
                }
            }
        }
        let w = t1 - t0;
        if w <= COARSE {
            let mid = 0.5 * (t0 + t1);
            let hit = [t0, mid, t1]
                .into_iter()
                .find_map(|t| p.witness(t).map(|pairs| (t, pairs)));
            if hit.is_some() || w <= fine {
                leaves.push((t0, t1, hit));
                continue;
            }
        }
        let mid = 0.5 * (t0 + t1);
        if w <= COARSE {
            // a piece not proved, with no collision at its ends and middle: a few more samples
            // before it is halved below the located width
            let step = w / 16.0;
            if let Some(hit) = (1..16)
                .map(|i| t0 + i as f64 * step)
                .find_map(|t| p.witness(t).map(|pairs| (t, pairs)))
            {
                leaves.push((t0, t1, Some(hit)));
                continue;
            }
        }
        // the earlier half on top: leaves come out in order
        stack.push((mid, t1));
        stack.push((t0, mid));
    }
    collision(p, &leaves, &stack)
}

/// The verdict from the unproved pieces found (and the pieces not yet looked at, in `rest`,
/// which may hold collisions too).
fn collision(p: &mut dyn Prover, leaves: &[Leaf], rest: &[(f64, f64)]) -> Verdict {
    let mut pieces: Vec<(f64, f64)> = leaves.iter().map(|(a, b, _)| (*a, *b)).collect();
    pieces.extend(rest.iter().copied());
    pieces.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut intervals: Vec<[f64; 2]> = Vec::new();
    for (lo, hi) in &pieces {
        match intervals.last_mut() {
            Some(last) if last[1] >= *lo => last[1] = last[1].max(*hi),
            _ => intervals.push([*lo, *hi]),
        }
    }
    let Some((t, pairs)) = leaves.iter().find_map(|(_, _, h)| h.clone()) else {
        return if intervals.is_empty() {
            Verdict::Free
        } else {
            Verdict::Undecided {
                reason: format!(
                    "not proved free within {} of the segment, yet no configuration there collides: \
                     the bodies pass closer than the proof's margin",
                    fmt_intervals(&intervals)
                ),
            }
        };
    };
    Verdict::Collides(Collision {
        free_before: intervals.first().map_or(0.0, |i| i[0]),
        free_after: intervals.last().map_or(1.0, |i| i[1]),
        intervals,
        exact: false,
        resolution: COARSE,
        witness: p.at(t),
        witness_t: t,
        pairs,
    })
}

/// Intervals as `[a, b] ∪ …`.
pub(crate) fn fmt_intervals(intervals: &[[f64; 2]]) -> String {
    intervals
        .iter()
        .map(|[a, b]| format!("[{a:.6}, {b:.6}]"))
        .collect::<Vec<_>>()
        .join(" ∪ ")
}
