//! Sorted, disjoint, closed intervals of a motion parameter.
//!
//! The seed (CHS §2.2) evaluates the edge–face predicate *on interval lists*: every atomic
//! inequality yields at most one or two intervals, `∧` becomes [`IntervalList::intersection`]
//! and `∨` becomes [`IntervalList::union`]. Both run in linear time on sorted lists, and neither
//! can increase the total number of intervals beyond the sum of its inputs.
//!
//! The complement of the collision intervals within the parameter range of a motion gives the
//! *free sections* ([`IntervalList::complement_within`]); the via-point planner picks their
//! centres as via points (CHS §1.3).

use serde::{Deserialize, Serialize};

/// A closed interval `[lo, hi]` with `lo <= hi`; either end may be infinite.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Interval {
    /// Lower end (inclusive).
    pub lo: f64,
    /// Upper end (inclusive).
    pub hi: f64,
}

impl Interval {
    /// The whole real line.
    pub const ALL: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };
    /// `[0, 1]`, the parameter range of a bounded motion (intersectSegment).
    pub const UNIT: Interval = Interval { lo: 0.0, hi: 1.0 };

    /// `[lo, hi]`; `None` when `lo > hi` or either end is NaN.
    pub fn new(lo: f64, hi: f64) -> Option<Interval> {
        (lo <= hi).then_some(Interval { lo, hi })
    }

    /// Length `hi - lo` (infinite for unbounded intervals).
    pub fn length(&self) -> f64 {
        self.hi - self.lo
    }

    /// Midpoint; for a half-unbounded interval this is infinite, for the whole line NaN.
    pub fn centre(&self) -> f64 {
        0.5 * (self.lo + self.hi)
    }

    /// `lo <= t <= hi`.
    pub fn contains(&self, t: f64) -> bool {
        self.lo <= t && t <= self.hi
    }

    /// Both ends finite.
    pub fn is_bounded(&self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }

    /// The intersection with `other`, if not empty.
    pub fn meet(&self, other: &Interval) -> Option<Interval> {
        Interval::new(self.lo.max(other.lo), self.hi.min(other.hi))
    }
}

/// Sorted, pairwise disjoint closed intervals. Intervals that touch are merged, so between two
/// consecutive intervals there is always a gap of positive length.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct IntervalList {
    items: Vec<Interval>,
}

impl IntervalList {
    /// The empty list (no collision).
    pub const fn new() -> Self {
        IntervalList { items: Vec::new() }
    }

    /// A list holding one interval.
    pub fn single(iv: Interval) -> Self {
        IntervalList { items: vec![iv] }
    }

    /// A list holding `[lo, hi]`, or the empty list if `lo > hi`.
    pub fn from_bounds(lo: f64, hi: f64) -> Self {
        match Interval::new(lo, hi) {
            Some(iv) => Self::single(iv),
            None => Self::new(),
        }
    }

    /// Builds a list from intervals in any order, overlapping or not: sorts and merges them
    /// (`O(n log n)`). This is the union of all of them.
    pub fn from_unsorted(mut items: Vec<Interval>) -> Self {
        items.retain(|iv| iv.lo <= iv.hi);
        items.sort_unstable_by(|a, b| a.lo.total_cmp(&b.lo));
        // merge in place: `w` is the last interval written
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
        IntervalList { items }
    }

    /// Allocation-free twin of [`from_unsorted`](Self::from_unsorted) for the oracles' hot
    /// path: sorts and merges `items` in place and swaps the buffers, so `self`
    /// holds the union and `items` comes back empty with the old list's allocation. Steady
    /// state: no allocation at all.
    pub fn set_from_unsorted(&mut self, items: &mut Vec<Interval>) {
        items.retain(|iv| iv.lo <= iv.hi);
        sort_by_lo(items);
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
        std::mem::swap(&mut self.items, items);
        items.clear();
    }

    /// The intervals, sorted.
    pub fn as_slice(&self) -> &[Interval] {
        &self.items
    }

    /// Iterates over the intervals in increasing order.
    pub fn iter(&self) -> std::slice::Iter<'_, Interval> {
        self.items.iter()
    }

    /// No interval (the motion is free).
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Number of intervals.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// First interval.
    pub fn first(&self) -> Option<&Interval> {
        self.items.first()
    }

    /// Last interval.
    pub fn last(&self) -> Option<&Interval> {
        self.items.last()
    }

    /// Whether `t` lies in one of the intervals (binary search).
    pub fn contains(&self, t: f64) -> bool {
        let i = self.items.partition_point(|iv| iv.hi < t);
        self.items.get(i).is_some_and(|iv| iv.lo <= t)
    }

    /// Total length of all intervals.
    pub fn measure(&self) -> f64 {
        self.items.iter().map(Interval::length).sum()
    }

    /// Adds `iv` at the end; it must start after the current last interval ends (touching or
    /// overlapping merges). Use it to build a list from an increasing sequence in linear time.
    ///
    /// # Panics
    /// In debug builds, if `iv` starts before the start of the last interval.
    pub fn push(&mut self, iv: Interval) {
        debug_assert!(iv.lo <= iv.hi);
        match self.items.last_mut() {
            Some(last) => {
                debug_assert!(iv.lo >= last.lo, "IntervalList::push out of order");
                if iv.lo <= last.hi {
                    last.hi = last.hi.max(iv.hi);
                } else {
                    self.items.push(iv);
                }
            }
            None => self.items.push(iv),
        }
    }

    /// Removes all intervals, keeping the allocation.
    pub fn clear(&mut self) {
        self.items.clear();
    }

    /// Set union (`∨`), linear time.
    pub fn union(&self, other: &IntervalList) -> IntervalList {
        let mut out = IntervalList::new();
        Self::union_into(self, other, &mut out);
        out
    }

    /// Allocation-free twin of [`union`](Self::union): writes `a ∪ b` into `out`.
    pub fn union_into(a: &IntervalList, b: &IntervalList, out: &mut IntervalList) {
        out.items.clear();
        out.items.reserve(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.items.len() || j < b.items.len() {
            let take_a = match (a.items.get(i), b.items.get(j)) {
                (Some(x), Some(y)) => x.lo <= y.lo,
                (Some(_), None) => true,
                _ => false,
            };
            let iv = if take_a {
                i += 1;
                a.items[i - 1]
            } else {
                j += 1;
                b.items[j - 1]
            };
            out.push(iv);
        }
    }

    /// Set intersection (`∧`), linear time.
    pub fn intersection(&self, other: &IntervalList) -> IntervalList {
        let mut out = IntervalList::new();
        Self::intersection_into(self, other, &mut out);
        out
    }

    /// Allocation-free twin of [`intersection`](Self::intersection).
    pub fn intersection_into(a: &IntervalList, b: &IntervalList, out: &mut IntervalList) {
        out.items.clear();
        let (mut i, mut j) = (0, 0);
        while i < a.items.len() && j < b.items.len() {
            let (x, y) = (a.items[i], b.items[j]);
            if let Some(m) = x.meet(&y) {
                out.items.push(m);
            }
            if x.hi < y.hi {
                i += 1;
            } else {
                j += 1;
            }
        }
    }

    /// Intersection with a single interval (clipping to a motion's parameter range).
    pub fn clip(&self, range: Interval) -> IntervalList {
        IntervalList {
            items: self.items.iter().filter_map(|iv| iv.meet(&range)).collect(),
        }
    }

    /// [`clip`](Self::clip) in place, keeping the allocation.
    pub fn into_clipped(mut self, range: Interval) -> IntervalList {
        self.clip_in_place(range);
        self
    }

    /// [`clip`](Self::clip) on a borrowed list, keeping the allocation.
    pub fn clip_in_place(&mut self, range: Interval) {
        self.items.retain_mut(|iv| match iv.meet(&range) {
            Some(m) => {
                *iv = m;
                true
            }
            None => false,
        });
    }

    /// Copies `other` into `self`, keeping `self`'s allocation.
    pub fn copy_from(&mut self, other: &IntervalList) {
        self.items.clear();
        self.items.extend_from_slice(&other.items);
    }

    /// The closures of the gaps of this list within `range`: the *free sections* when this list
    /// holds collision intervals. Each free section is returned as a closed interval whose ends
    /// are collision times (or the ends of `range`).
    pub fn complement_within(&self, range: Interval) -> IntervalList {
        let mut out = IntervalList {
            items: Vec::with_capacity(self.items.len() + 1),
        };
        self.complement_within_into(range, &mut out);
        out
    }

    /// Allocation-free twin of [`complement_within`](Self::complement_within): writes the free
    /// sections into `out`, keeping its allocation (the via-point search asks for them on
    /// every borderline).
    pub fn complement_within_into(&self, range: Interval, out: &mut IntervalList) {
        let out = &mut out.items;
        out.clear();
        let mut cursor = range.lo;
        // whether `cursor` is still the start of the range rather than the end of a collision
        let mut at_range_start = true;
        for iv in &self.items {
            if iv.hi < range.lo {
                continue;
            }
            if iv.lo > range.hi {
                break;
            }
            if iv.lo > cursor {
                out.push(Interval {
                    lo: cursor,
                    hi: iv.lo,
                });
            }
            cursor = cursor.max(iv.hi);
            at_range_start = false;
        }
        if cursor < range.hi {
            out.push(Interval {
                lo: cursor,
                hi: range.hi,
            });
        } else if at_range_start && cursor == range.hi {
            // a degenerate range [t, t] with no collision is one free point
            out.push(Interval {
                lo: cursor,
                hi: cursor,
            });
        }
    }

    /// Applies `t ↦ scale · t + shift` to every end; a negative `scale` reverses the order.
    pub fn affine(&self, scale: f64, shift: f64) -> IntervalList {
        let mut items: Vec<Interval> = self
            .items
            .iter()
            .map(|iv| {
                let (a, b) = (scale * iv.lo + shift, scale * iv.hi + shift);
                Interval {
                    lo: a.min(b),
                    hi: a.max(b),
                }
            })
            .collect();
        if scale < 0.0 {
            items.reverse();
        }
        IntervalList { items }
    }
}

/// Sorts by lower end (in [`f64::total_cmp`]'s order; stable up to
/// [`INSERTION_SORT_MAX`] intervals, and the merged union does not depend on it). Oracle answers hold a handful
/// of intervals, where an insertion sort beats the general sort's set-up; longer lists take
/// the library sort. (A branch-free counting sort was tried: twice the
/// instructions for the same time on `bench discs`.)
fn sort_by_lo(items: &mut [Interval]) {
    if items.len() > INSERTION_SORT_MAX {
        items.sort_unstable_by(|a, b| a.lo.total_cmp(&b.lo));
        return;
    }
    for i in 1..items.len() {
        let x = items[i];
        let mut j = i;
        while j > 0 && items[j - 1].lo.total_cmp(&x.lo).is_gt() {
            items[j] = items[j - 1];
            j -= 1;
        }
        items[j] = x;
    }
}

/// Longest list [`sort_by_lo`] sorts by insertion.
const INSERTION_SORT_MAX: usize = 16;

impl<'a> IntoIterator for &'a IntervalList {
    type Item = &'a Interval;
    type IntoIter = std::slice::Iter<'a, Interval>;
    fn into_iter(self) -> Self::IntoIter {
        self.items.iter()
    }
}

impl FromIterator<Interval> for IntervalList {
    fn from_iter<I: IntoIterator<Item = Interval>>(iter: I) -> Self {
        Self::from_unsorted(iter.into_iter().collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn list(v: &[(f64, f64)]) -> IntervalList {
        IntervalList::from_unsorted(v.iter().map(|&(lo, hi)| Interval { lo, hi }).collect())
    }

    /// Membership of `t` by brute force over the raw (unmerged) pieces.
    fn raw_contains(v: &[(f64, f64)], t: f64) -> bool {
        v.iter().any(|&(lo, hi)| lo <= t && t <= hi)
    }

    fn arb_raw() -> impl Strategy<Value = Vec<(f64, f64)>> {
        // ends on a coarse grid so that touching and coinciding ends are frequent
        prop::collection::vec((0i32..40, 0i32..8), 0..12).prop_map(|v| {
            v.into_iter()
                .map(|(a, w)| (a as f64 * 0.25, (a + w) as f64 * 0.25))
                .collect()
        })
    }

    /// Probe points: every grid point and every midpoint between grid points.
    fn probes() -> impl Iterator<Item = f64> {
        (-4..=200).map(|k| k as f64 * 0.125)
    }

    fn well_formed(l: &IntervalList) -> bool {
        l.items.iter().all(|iv| iv.lo <= iv.hi) && l.items.windows(2).all(|w| w[0].hi < w[1].lo)
    }

    #[test]
    fn merge_touching_and_nested() {
        let l = list(&[(0.0, 1.0), (1.0, 2.0), (0.5, 0.7), (3.0, 4.0)]);
        assert_eq!(
            l.as_slice(),
            &[Interval { lo: 0.0, hi: 2.0 }, Interval { lo: 3.0, hi: 4.0 }]
        );
    }

    #[test]
    fn free_sections_of_a_unit_segment() {
        let l = list(&[(0.2, 0.3), (0.5, 0.6)]);
        let free = l.complement_within(Interval::UNIT);
        assert_eq!(
            free.as_slice(),
            &[
                Interval { lo: 0.0, hi: 0.2 },
                Interval { lo: 0.3, hi: 0.5 },
                Interval { lo: 0.6, hi: 1.0 }
            ]
        );
        // a collision covering the start leaves no free section there
        let l = list(&[(-1.0, 0.4)]);
        assert_eq!(
            l.complement_within(Interval::UNIT).as_slice(),
            &[Interval { lo: 0.4, hi: 1.0 }]
        );
        // unbounded collision on both sides of a line leaves one bounded free section
        let l = list(&[(f64::NEG_INFINITY, -2.0), (3.0, f64::INFINITY)]);
        assert_eq!(
            l.complement_within(Interval::ALL).as_slice(),
            &[Interval { lo: -2.0, hi: 3.0 }]
        );
        // everything blocked
        let l = list(&[(f64::NEG_INFINITY, f64::INFINITY)]);
        assert!(l.complement_within(Interval::ALL).is_empty());
    }

    #[test]
    fn affine_reverses_for_negative_scale() {
        let l = list(&[(0.0, 1.0), (2.0, 3.0)]);
        let m = l.affine(-1.0, 0.0);
        assert_eq!(
            m.as_slice(),
            &[
                Interval { lo: -3.0, hi: -2.0 },
                Interval { lo: -1.0, hi: 0.0 }
            ]
        );
    }

    proptest! {
        #[test]
        fn from_unsorted_matches_brute_force(raw in arb_raw()) {
            let l = list(&raw);
            prop_assert!(well_formed(&l));
            for t in probes() {
                prop_assert_eq!(l.contains(t), raw_contains(&raw, t), "t = {}", t);
            }
        }

        /// The insertion sort (≤ 16 intervals) and the library sort behind
        /// `set_from_unsorted` against the standard stable sort by `total_cmp`, with equal,
        /// signed zero and infinite lower ends among them.
        #[test]
        fn sort_by_lo_matches_a_stable_sort(
            raw in prop::collection::vec((0usize..7, -5i32..5), 0..24)
        ) {
            const ENDS: [f64; 7] = [f64::NEG_INFINITY, -1.5, -0.0, 0.0, 0.25, 3.0, f64::INFINITY];
            let mut items: Vec<Interval> = raw
                .iter()
                .map(|&(k, h)| Interval { lo: ENDS[k], hi: h as f64 })
                .collect();
            let mut want = items.clone();
            want.sort_by(|a, b| a.lo.total_cmp(&b.lo));
            sort_by_lo(&mut items);
            let bits = |v: &[Interval]| v.iter().map(|iv| iv.lo.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(bits(&items), bits(&want));
            if items.len() <= INSERTION_SORT_MAX {
                // stable: the same intervals in the same order, his included
                prop_assert_eq!(&items, &want);
            }
        }

        #[test]
        fn union_and_intersection_match_brute_force(a in arb_raw(), b in arb_raw()) {
            let (la, lb) = (list(&a), list(&b));
            let u = la.union(&lb);
            let i = la.intersection(&lb);
            prop_assert!(well_formed(&u));
            prop_assert!(well_formed(&i));
            prop_assert!(u.len() <= la.len() + lb.len());
            prop_assert!(i.len() <= la.len() + lb.len());
            for t in probes() {
                let (x, y) = (raw_contains(&a, t), raw_contains(&b, t));
                prop_assert_eq!(u.contains(t), x || y, "union at t = {}", t);
                prop_assert_eq!(i.contains(t), x && y, "intersection at t = {}", t);
            }
        }

        #[test]
        fn complement_matches_brute_force(a in arb_raw(), lo in 0i32..20, w in 0i32..30) {
            let l = list(&a);
            let range = Interval { lo: lo as f64 * 0.25, hi: (lo + w) as f64 * 0.25 };
            let free = l.complement_within(range);
            prop_assert!(free.iter().all(|iv| iv.lo >= range.lo && iv.hi <= range.hi));
            for t in probes() {
                if !range.contains(t) { continue; }
                let collides = raw_contains(&a, t);
                // strictly inside a free section => not colliding; not colliding => in a section
                let strictly_free = free.iter().any(|iv| iv.lo < t && t < iv.hi);
                if strictly_free { prop_assert!(!collides, "t = {} marked free but collides", t); }
                if !collides { prop_assert!(free.contains(t), "t = {} free but not in a section", t); }
            }
        }
    }
}
