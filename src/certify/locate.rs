//! Locating what keeps a segment from being proved free, for checks that answer a motion only
//! yes or no (an arm's straight motion of several joints, a rigid body translating and turning
//! at once): the segment is halved where it is not proved, pieces proved free are kept, and
//! the pieces that stay unproved at the finest width hold every collision. A configuration in
//! them that the independent check confirms as colliding makes the verdict a collision; none
//! found leaves it undecided (the bodies pass closer than the proof's margin).

use super::verdict::{fmt_intervals, CertifyError, Collision, Verdict};
use crate::deadline::Deadline;

/// Width (share of the segment) below which an unproved piece with a confirmed collision is
/// not halved further: the located intervals are this fine.
pub const COARSE: f64 = 1.0 / 4096.0;

/// Proof attempts one arm segment may spend locating: near-contacts that no proof separates
/// and no sample finds colliding would otherwise be halved down to the finest width all along
/// (an arm's proof costs up to milliseconds; a rigid body's distance query microseconds).
pub const MAX_PROOFS: usize = 512;

/// What a located segment is asked: a yes/no proof over a piece of its parameter, and whether
/// the configuration at a parameter really collides (with the pairs that touch).
pub(crate) trait Prover {
    /// Whether the motion over `[t0, t1]` is proved free.
    fn proved_free(&mut self, t0: f64, t1: f64) -> Result<bool, CertifyError>;
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
pub(crate) fn locate(
    p: &mut dyn Prover,
    fine: f64,
    max_proofs: usize,
    deadline: &Deadline,
) -> Verdict {
    let mut proofs = 0;
    // first down to the located width everywhere, then finer only where no collision was found
    let coarse = match pass(
        p,
        vec![(0.0, 1.0)],
        COARSE,
        (deadline, max_proofs),
        &mut proofs,
    ) {
        Ok(leaves) => leaves,
        Err(v) => return v,
    };
    if coarse.iter().any(|(_, _, h)| h.is_some()) || coarse.is_empty() {
        return collision(p, &coarse, &[]);
    }
    let mut rest: Vec<(f64, f64)> = coarse.iter().map(|(a, b, _)| (*a, *b)).collect();
    rest.reverse();
    match pass(p, rest, fine, (deadline, max_proofs), &mut proofs) {
        Ok(leaves) => collision(p, &leaves, &[]),
        Err(v) => v,
    }
}

/// Halves the pieces of `stack` (the earliest on top) that are not proved until they are no
/// wider than `floor`: the unproved pieces, each with a colliding parameter if one of a few
/// samples found it. `Err`: the verdict when the deadline or the proofs ran out.
fn pass(
    p: &mut dyn Prover,
    mut stack: Vec<(f64, f64)>,
    floor: f64,
    (deadline, max_proofs): (&Deadline, usize),
    proofs: &mut usize,
) -> Result<Vec<Leaf>, Verdict> {
    let mut leaves: Vec<Leaf> = Vec::new();
    while let Some((t0, t1)) = stack.pop() {
        if deadline.expired() {
            return Err(Verdict::Undecided {
                reason: "the time budget ran out while locating a collision".into(),
            });
        }
        *proofs += 1;
        if *proofs > max_proofs {
            // the piece at hand is not proved either
            stack.push((t0, t1));
            return Err(match leaves.iter().find_map(|(_, _, h)| h.clone()) {
                Some(_) => collision(p, &leaves, &stack),
                None => Verdict::Undecided {
                    reason: format!(
                        "{max_proofs} proofs did not separate the bodies, and no configuration \
                         tried collides"
                    ),
                },
            });
        }
        match p.proved_free(t0, t1) {
            Ok(true) => continue,
            Ok(false) => {}
            Err(e) => {
                return Err(Verdict::Undecided {
                    reason: e.to_string(),
                })
            }
        }
        let w = t1 - t0;
        if w <= floor {
            // a piece not proved: its ends, its middle and a few more samples
            let step = w / 16.0;
            let hit = [t0, 0.5 * (t0 + t1), t1]
                .into_iter()
                .chain((1..16).map(|i| t0 + i as f64 * step))
                .find_map(|t| p.witness(t).map(|pairs| (t, pairs)));
            leaves.push((t0, t1, hit));
            continue;
        }
        let mid = 0.5 * (t0 + t1);
        // the earlier half on top: leaves come out in order
        stack.push((mid, t1));
        stack.push((t0, mid));
    }
    Ok(leaves)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A point on a line colliding over `[0.3, 0.4]`, proved free over a piece only when the
    /// piece stays `margin` away from that interval (a proof that cannot finish near contact).
    struct Line {
        margin: f64,
    }

    impl Prover for Line {
        fn proved_free(&mut self, t0: f64, t1: f64) -> Result<bool, super::super::CertifyError> {
            Ok(t1 < 0.3 - self.margin || t0 > 0.4 + self.margin)
        }
        fn witness(&mut self, t: f64) -> Option<Vec<[String; 2]>> {
            (0.3..=0.4)
                .contains(&t)
                .then(|| vec![["point".into(), "block".into()]])
        }
        fn at(&self, t: f64) -> Vec<f64> {
            vec![t]
        }
    }

    #[test]
    fn the_located_intervals_hold_the_collision_and_the_witness_lies_in_it() {
        let v = locate(
            &mut Line { margin: 1e-3 },
            1e-6,
            MAX_PROOFS,
            &Deadline::none(),
        );
        let Verdict::Collides(c) = v else {
            panic!("not located: {v:?}")
        };
        assert!(
            c.intervals.iter().any(|[a, b]| *a <= 0.3 && *b >= 0.4),
            "{c:?}"
        );
        assert!((0.3..=0.4).contains(&c.witness_t));
        assert!(c.free_before <= 0.3 && c.free_after >= 0.4);
    }

    #[test]
    fn a_near_contact_without_collision_is_undecided_and_never_free() {
        struct Near;
        impl Prover for Near {
            fn proved_free(
                &mut self,
                t0: f64,
                t1: f64,
            ) -> Result<bool, super::super::CertifyError> {
                Ok(t1 < 0.5 || t0 > 0.5)
            }
            fn witness(&mut self, _: f64) -> Option<Vec<[String; 2]>> {
                None
            }
            fn at(&self, t: f64) -> Vec<f64> {
                vec![t]
            }
        }
        let v = locate(&mut Near, 1e-3, MAX_PROOFS, &Deadline::none());
        assert_eq!(v.name(), "undecided", "{v:?}");
    }
}
