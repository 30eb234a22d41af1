//! A handful of sorted, disjoint closed intervals kept on the stack: the value of one
//! predicate of a rigid-body oracle (an edge–edge or point–triangle test in the plane, an
//! edge–face test in space) under a rotation, where every atom gives at most one arc of the
//! turn (CHS §2.3.2) and a conjunction of k arcs inside a window of one turn has at most k + 1
//! pieces.
//!
//! [`crate::interval::IntervalList`] is the general type; this one exists because predicates
//! are evaluated for every pair of primitives that survives culling, and allocating there
//! would dominate the cost. The capacity is a parameter: the polygon oracle's conjunctions
//! have at most five pieces, the polyhedra oracle's seven.

use crate::interval::Interval;

/// At most `N` sorted, disjoint closed intervals.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spans<const N: usize> {
    len: usize,
    items: [Interval; N],
}

impl<const N: usize> Default for Spans<N> {
    fn default() -> Self {
        Spans::EMPTY
    }
}

impl<const N: usize> Spans<N> {
    /// No interval.
    pub const EMPTY: Spans<N> = Spans {
        len: 0,
        items: [Interval { lo: 0.0, hi: 0.0 }; N],
    };

    /// One interval.
    #[inline]
    pub fn single(iv: Interval) -> Spans<N> {
        let mut s = Spans::EMPTY;
        s.push(iv);
        s
    }

    /// Whether there is no interval.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The intervals, sorted.
    #[inline]
    pub fn as_slice(&self) -> &[Interval] {
        &self.items[..self.len]
    }

    /// Appends `iv`, which must not start before the last interval starts; overlapping or
    /// touching intervals merge. Should the capacity ever be exceeded, the last interval is
    /// stretched over `iv` — more collision, never less.
    #[inline]
    pub fn push(&mut self, iv: Interval) {
        if self.len > 0 {
            let last = &mut self.items[self.len - 1];
            if iv.lo <= last.hi || self.len == N {
                last.hi = last.hi.max(iv.hi);
                return;
            }
        }
        self.items[self.len] = iv;
        self.len += 1;
    }

    /// Set intersection (∧), linear time.
    #[inline]
    pub fn intersect(&self, other: &Spans<N>) -> Spans<N> {
        let mut out = Spans::EMPTY;
        let (a, b) = (self.as_slice(), other.as_slice());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            if let Some(m) = a[i].meet(&b[j]) {
                out.push(m);
            }
            if a[i].hi < b[j].hi {
                i += 1;
            } else {
                j += 1;
            }
        }
        out
    }

    /// Set union (∨), linear time.
    #[inline]
    pub fn union(&self, other: &Spans<N>) -> Spans<N> {
        let mut out = Spans::EMPTY;
        let (a, b) = (self.as_slice(), other.as_slice());
        let (mut i, mut j) = (0, 0);
        while i < a.len() || j < b.len() {
            let take_a = j >= b.len() || (i < a.len() && a[i].lo <= b[j].lo);
            if take_a {
                out.push(a[i]);
                i += 1;
            } else {
                out.push(b[j]);
                j += 1;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn iv(lo: f64, hi: f64) -> Interval {
        Interval { lo, hi }
    }

    fn set<const N: usize>(v: &[(f64, f64)]) -> Spans<N> {
        let mut s = Spans::EMPTY;
        for &(lo, hi) in v {
            s.push(iv(lo, hi));
        }
        s
    }

    #[test]
    fn intersect_and_union() {
        let a: Spans<8> = set(&[(0.0, 1.0), (2.0, 3.0)]);
        let b = set(&[(0.5, 2.5), (2.8, 4.0)]);
        let i = a.intersect(&b);
        assert_eq!(i.as_slice(), &[iv(0.5, 1.0), iv(2.0, 2.5), iv(2.8, 3.0)]);
        assert_eq!(a.union(&b).as_slice(), &[iv(0.0, 4.0)]);
        let c: Spans<6> = set(&[(0.0, 1.0), (2.0, 3.0)]);
        let d = set(&[(0.5, 2.0), (4.0, 5.0)]);
        assert_eq!(c.union(&d).as_slice(), &[iv(0.0, 3.0), iv(4.0, 5.0)]);
        assert_eq!(c.intersect(&d).as_slice(), &[iv(0.5, 1.0), iv(2.0, 2.0)]);
        assert!(c.intersect(&Spans::EMPTY).is_empty());
    }

    #[test]
    fn overflow_stretches_the_last_interval() {
        let mut s: Spans<6> = Spans::EMPTY;
        for k in 0..40 {
            s.push(iv(k as f64, k as f64 + 0.5));
        }
        assert_eq!(s.as_slice().len(), 6);
        assert_eq!(s.as_slice()[5].hi, 39.5);
        assert_eq!(s.as_slice()[5].lo, 5.0);
        for k in 0..40 {
            let t = k as f64 + 0.25;
            assert!(s.as_slice().iter().any(|iv| iv.contains(t)));
        }
    }

    fn sorted(raw: Vec<(u8, u8)>) -> Spans<8> {
        let mut v: Vec<(f64, f64)> = raw
            .into_iter()
            .map(|(a, b)| (f64::from(a.min(b)), f64::from(a.max(b))))
            .collect();
        v.sort_by(|x, y| x.0.total_cmp(&y.0));
        set(&v)
    }

    proptest! {
        /// ∧ and ∨ agree with membership at every half-integer and integer point.
        #[test]
        fn operations_match_membership(
            a in prop::collection::vec((0u8..40, 0u8..40), 0..4),
            b in prop::collection::vec((0u8..40, 0u8..40), 0..4),
        ) {
            let (a, b) = (sorted(a), sorted(b));
            let has = |s: &Spans<8>, t: f64| s.as_slice().iter().any(|iv| iv.contains(t));
            let (i, u) = (a.intersect(&b), a.union(&b));
            for k in 0..=80 {
                let t = k as f64 * 0.5;
                prop_assert_eq!(has(&i, t), has(&a, t) && has(&b, t), "∧ at {}", t);
                prop_assert_eq!(has(&u, t), has(&a, t) || has(&b, t), "∨ at {}", t);
            }
        }
    }
}
