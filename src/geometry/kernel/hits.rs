//! One way for both rigid-body oracles to report the collision pieces of a motion.
//!
//! The seed merges the intervals of all pairs of primitives with a balanced ∨-tree (CHS §2.2);
//! here every piece goes into [`Hits`], which keeps them merged (sorted, disjoint, touching
//! closed intervals joined). That costs a binary search per piece and buys two things:
//! - a pair of primitives whose whole window is already known to collide can be skipped
//!   ([`Hits::covers`]): its pieces could not change the union. Deep in collision that is most
//!   pairs;
//! - a yes/no question ([`Hits::first_only`], `motion_is_free`, a static test) stops the sweep
//!   at the first piece: [`Hits::add`] breaks.
//!
//! The buffer is reused between calls ([`Hits::reset`]), so a sweep allocates nothing once it
//! has grown to the largest answer seen.

use super::spans::Spans;
use crate::interval::{Interval, IntervalList};
use std::ops::ControlFlow;

/// The merged collision pieces of one sweep.
#[derive(Clone, Debug, Default)]
pub(crate) struct Hits {
    pieces: Vec<Interval>,
    first_only: bool,
    /// Only the first collision matters ([`Hits::reset_prefix`]).
    prefix: bool,
    /// Whether a sweep narrows the windows it solves to what is not yet known
    /// ([`Hits::uncovered`]); off after every reset.
    clip: bool,
    /// Bumped by every piece added: a sweep re-narrows a window only when this changed.
    generation: u64,
    /// Pairs since the watched deadline was last polled ([`Hits::interrupted`]).
    polls: u32,
    /// The watched deadline passed during the sweep: the pieces are incomplete.
    interrupted: bool,
}

/// Primitive pairs between two polls of the watched deadline: a poll costs a clock read, a
/// pair up to a microsecond.
const PAIRS_PER_POLL: u32 = 64;

impl Hits {
    /// Collects every piece.
    #[cfg(test)]
    pub fn all() -> Hits {
        Hits::default()
    }

    /// Stops at the first piece (a yes/no question).
    #[cfg(test)]
    pub fn first_only() -> Hits {
        Hits {
            pieces: Vec::new(),
            first_only: true,
            prefix: false,
            clip: false,
            generation: 0,
            polls: 0,
            interrupted: false,
        }
    }

    /// Empties the set for the next sweep, keeping the buffer; `first_only` as in
    /// [`Hits::first_only`].
    pub fn reset(&mut self, first_only: bool) {
        self.pieces.clear();
        self.first_only = first_only;
        self.prefix = false;
        self.clip = false;
        self.generation = 0;
        self.polls = 0;
        self.interrupted = false;
    }

    /// Whether the sweep must stop because the deadline watched on this thread
    /// ([`crate::deadline::watching`]) has passed; polled every [`PAIRS_PER_POLL`] calls, and
    /// once true, true until the next reset.
    #[inline]
    pub fn interrupted(&mut self) -> bool {
        if !self.interrupted {
            self.polls += 1;
            if self.polls >= PAIRS_PER_POLL {
                self.polls = 0;
                self.interrupted = crate::deadline::watched_expired();
            }
        }
        self.interrupted
    }

    /// Whether a sweep into this set stopped at the watched deadline.
    pub fn was_interrupted(&self) -> bool {
        self.interrupted
    }

    /// Switches the narrowing of windows ([`Hits::uncovered`]) on or off for this sweep.
    pub fn set_clip(&mut self, on: bool) {
        self.clip = on;
    }

    /// Whether windows are narrowed to what is not yet known ([`Hits::uncovered`]).
    pub fn clips(&self) -> bool {
        self.clip
    }

    /// A number that changes whenever a piece is added (a window narrowed before is stale).
    #[inline]
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The parts of `window` not yet known to collide, each reaching `overlap` into the known
    /// pieces on either side (so that a piece solved in a narrowed window still overlaps the
    /// known one it continues, and is never a sliver): solving a pair only there changes
    /// nothing in the union, since whatever it would find elsewhere is already known. With
    /// [`Hits::reset_prefix`], everything from `overlap` after the earliest piece on counts as
    /// known. Should the capacity of `Spans` not suffice, the last part is stretched — a wider
    /// window, never a narrower one. With clipping off (see [`Hits::set_clip`]): `window`.
    pub fn uncovered<const N: usize>(&self, window: &Spans<N>, overlap: f64) -> Spans<N> {
        if !self.clip || self.pieces.is_empty() {
            return *window;
        }
        let spans = window.as_slice();
        let Some(first) = spans.first() else {
            return *window;
        };
        let cut = if self.prefix {
            self.pieces[0].lo + overlap
        } else {
            f64::INFINITY
        };
        let mut out = Spans::EMPTY;
        let mut i = self.pieces.partition_point(|p| p.hi < first.lo);
        for s in spans {
            let hi = s.hi.min(cut);
            let mut lo = s.lo;
            if lo > hi {
                break;
            }
            while let Some(p) = self.pieces.get(i) {
                if p.lo > hi {
                    break;
                }
                let (kl, kh) = (p.lo + overlap, p.hi - overlap);
                if kl <= kh && kh >= lo && kl <= hi {
                    if kl > lo {
                        out.push(Interval { lo, hi: kl });
                    }
                    lo = lo.max(kh);
                }
                if p.hi > hi {
                    // reaches into the next span too
                    break;
                }
                i += 1;
            }
            if lo <= hi {
                out.push(Interval { lo, hi });
            }
        }
        out
    }

    /// Empties the set for a sweep that wants only the earliest collision (the free prefix of
    /// a motion, `first_collision`): a window that starts at or after the earliest piece found
    /// so far cannot change it, so [`Hits::covers`] lets the sweep skip it. The pieces after
    /// the first may then be incomplete; the first piece's start is exact.
    pub fn reset_prefix(&mut self) {
        self.reset(false);
        self.prefix = true;
    }

    /// Whether only the earliest collision matters.
    pub fn is_prefix(&self) -> bool {
        self.prefix
    }

    /// Whether the sweep stops at the first piece.
    pub fn is_first_only(&self) -> bool {
        self.first_only
    }

    /// Adds a collision piece (an empty or NaN one is ignored); breaks when the sweep should
    /// stop.
    #[inline]
    pub fn add(&mut self, iv: Interval) -> ControlFlow<()> {
        if iv.lo > iv.hi || iv.lo.is_nan() || iv.hi.is_nan() {
            return ControlFlow::Continue(());
        }
        self.generation += 1;
        // pieces [i, j) meet `iv`
        let i = self.pieces.partition_point(|p| p.hi < iv.lo);
        let j = i + self.pieces[i..].partition_point(|p| p.lo <= iv.hi);
        if i == j {
            self.pieces.insert(i, iv);
        } else {
            self.pieces[i] = Interval {
                lo: self.pieces[i].lo.min(iv.lo),
                hi: self.pieces[j - 1].hi.max(iv.hi),
            };
            self.pieces.drain(i + 1..j);
        }
        if self.first_only {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    /// Whether every parameter of `w` is already known to collide.
    #[inline]
    pub fn covers(&self, w: Interval) -> bool {
        if self.prefix && self.pieces.first().is_some_and(|p| w.lo >= p.lo) {
            return true;
        }
        let i = self.pieces.partition_point(|p| p.hi < w.lo);
        self.pieces
            .get(i)
            .is_some_and(|p| p.lo <= w.lo && w.hi <= p.hi)
    }

    /// Whether the sweep should stop.
    #[inline]
    pub fn done(&self) -> bool {
        self.first_only && !self.pieces.is_empty()
    }

    /// The pieces, sorted and disjoint.
    pub fn as_slice(&self) -> &[Interval] {
        &self.pieces
    }

    /// The pieces within `range`, written into `out` (overwriting it; no allocation once `out`
    /// has grown): the answer of `intervals_into`.
    pub fn write_into(&self, out: &mut IntervalList, range: Interval) {
        out.clear();
        for p in &self.pieces {
            if let Some(m) = p.meet(&range) {
                out.push(m);
            }
        }
    }

    /// The pieces within `range`, as a list (the one allocation of a call: the answer).
    pub fn to_list(&self, range: Interval) -> IntervalList {
        IntervalList::from_unsorted(self.pieces.clone()).into_clipped(range)
    }
}

/// Sorts and merges `items` in place (empty and NaN intervals dropped): what
/// [`IntervalList::from_unsorted`] does, without giving up the buffer.
pub(crate) fn merge_in_place(items: &mut Vec<Interval>) {
    items.retain(|iv| iv.lo <= iv.hi);
    items.sort_unstable_by(|a, b| a.lo.total_cmp(&b.lo));
    let mut w = 0;
    for r in 1..items.len() {
        if items[r].lo <= items[w].hi {
            items[w].hi = items[w].hi.max(items[r].hi);
        } else {
            w += 1;
            items[w] = items[r];
        }
    }
    items.truncate((w + 1).min(items.len()));
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Merging on insertion gives the list `IntervalList::from_unsorted` gives, and
        /// `covers` is true exactly for windows inside one merged piece.
        #[test]
        fn merged_pieces_match_from_unsorted(
            raw in prop::collection::vec((0u8..60, 0u8..8), 0..20),
            w in (0u8..60, 0u8..10),
        ) {
            let ivs: Vec<Interval> = raw
                .iter()
                .map(|&(a, l)| Interval { lo: f64::from(a) * 0.5, hi: f64::from(a + l) * 0.5 })
                .collect();
            let mut h = Hits::all();
            for iv in &ivs {
                prop_assert!(h.add(*iv).is_continue());
            }
            let want = IntervalList::from_unsorted(ivs.clone());
            prop_assert_eq!(h.as_slice(), want.as_slice());
            let mut merged = ivs.clone();
            merge_in_place(&mut merged);
            prop_assert_eq!(&merged[..], want.as_slice());
            let w = Interval { lo: f64::from(w.0) * 0.5, hi: f64::from(w.0 + w.1) * 0.5 };
            let inside = want.as_slice().iter().any(|p| p.lo <= w.lo && w.hi <= p.hi);
            prop_assert_eq!(h.covers(w), inside);
        }
    }

    proptest! {
        /// The narrowed window and the known pieces together cover the window, the narrowed
        /// window lies inside it, and with clipping off it is the window itself.
        #[test]
        fn uncovered_and_known_cover_the_window(
            raw in prop::collection::vec((0u8..60, 0u8..8), 0..12),
            win in prop::collection::vec((0u8..60, 0u8..10), 1..5),
            prefix in any::<bool>(),
        ) {
            let mut h = Hits::all();
            if prefix {
                h.reset_prefix();
            }
            h.set_clip(true);
            for &(a, l) in &raw {
                let _ = h.add(Interval { lo: f64::from(a) * 0.5, hi: f64::from(a + l) * 0.5 });
            }
            let mut ws: Vec<Interval> = win
                .iter()
                .map(|&(a, l)| Interval { lo: f64::from(a) * 0.5, hi: f64::from(a + l) * 0.5 })
                .collect();
            merge_in_place(&mut ws);
            let mut w: Spans<8> = Spans::EMPTY;
            for iv in &ws {
                w.push(*iv);
            }
            let overlap = 0.01;
            let u = h.uncovered(&w, overlap);
            let inside = |t: f64, s: &[Interval]| s.iter().any(|p| p.lo <= t && t <= p.hi);
            for k in 0..=700 {
                let t = f64::from(k) * 0.05;
                if inside(t, w.as_slice()) {
                    let known = inside(t, h.as_slice())
                        || (prefix && h.as_slice().first().is_some_and(|p| t >= p.lo));
                    prop_assert!(known || inside(t, u.as_slice()), "{t}: {:?} {:?} {:?}", w, h, u);
                }
                if inside(t, u.as_slice()) {
                    prop_assert!(inside(t, w.as_slice()), "{t}: {:?} {:?}", w, u);
                }
            }
            h.set_clip(false);
            let same = h.uncovered(&w, overlap);
            prop_assert_eq!(same.as_slice(), w.as_slice());
        }
    }

    #[test]
    fn first_only_breaks_and_reset_clears() {
        let mut h = Hits::first_only();
        assert!(!h.done());
        assert!(h.add(Interval { lo: 1.0, hi: 0.0 }).is_continue());
        assert!(h.add(Interval { lo: 0.0, hi: 1.0 }).is_break());
        assert!(h.done());
        h.reset(false);
        assert!(h.as_slice().is_empty() && !h.done());
        assert!(h
            .add(Interval {
                lo: f64::NAN,
                hi: 1.0
            })
            .is_continue());
        assert!(h.as_slice().is_empty());
    }
}
