//! A handful of sorted, disjoint closed intervals kept on the stack: the value of one
//! edge–face predicate under rotation, where every atom gives at most one arc (CHS §2.3.2) and
//! a conjunction of k arcs inside a window of one turn has at most k + 1 pieces.
//!
//! [`crate::interval::IntervalList`] is the general type; this one exists because the predicate
//! is evaluated for every edge–face pair that survives culling, and allocating there would
//! dominate the cost (the allocation-free twin STYLE.md asks for on hot paths).

use crate::interval::Interval;

/// Capacity: more than the k + 1 = 7 pieces a conjunction of six arcs can have.
const CAP: usize = 8;

/// At most [`CAP`] sorted, disjoint closed intervals.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spans {
    len: usize,
    items: [Interval; CAP],
}

impl Default for Spans {
    fn default() -> Self {
        Spans::EMPTY
    }
}

impl Spans {
    /// No interval.
    pub const EMPTY: Spans = Spans {
        len: 0,
        items: [Interval { lo: 0.0, hi: 0.0 }; CAP],
    };

    /// One interval.
    pub fn single(iv: Interval) -> Spans {
        let mut s = Spans::EMPTY;
        s.push(iv);
        s
    }

    /// Whether there is no interval.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The intervals, sorted.
    pub fn as_slice(&self) -> &[Interval] {
        &self.items[..self.len]
    }

    /// Appends `iv`, which must not start before the last interval starts; overlapping or
    /// touching intervals merge. Should the capacity ever be exceeded, the last two intervals
    /// are merged into their hull — more collision, never less.
    pub fn push(&mut self, iv: Interval) {
        if self.len > 0 {
            let last = &mut self.items[self.len - 1];
            if iv.lo <= last.hi {
                last.hi = last.hi.max(iv.hi);
                return;
            }
        }
        if self.len == CAP {
            self.items[CAP - 1].hi = iv.hi;
            return;
        }
        self.items[self.len] = iv;
        self.len += 1;
    }

    /// Set intersection (∧), linear time.
    pub fn intersect(&self, other: &Spans) -> Spans {
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
    pub fn union(&self, other: &Spans) -> Spans {
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

    fn iv(lo: f64, hi: f64) -> Interval {
        Interval { lo, hi }
    }

    #[test]
    fn intersect_and_union() {
        let mut a = Spans::single(iv(0.0, 1.0));
        a.push(iv(2.0, 3.0));
        let mut b = Spans::single(iv(0.5, 2.5));
        b.push(iv(2.8, 4.0));
        let i = a.intersect(&b);
        assert_eq!(i.as_slice(), &[iv(0.5, 1.0), iv(2.0, 2.5), iv(2.8, 3.0)]);
        let u = a.union(&b);
        assert_eq!(u.as_slice(), &[iv(0.0, 4.0)]);
    }

    #[test]
    fn overflow_grows_conservatively() {
        let mut s = Spans::EMPTY;
        for k in 0..12 {
            s.push(iv(k as f64, k as f64 + 0.5));
        }
        assert_eq!(s.as_slice().len(), CAP);
        assert_eq!(s.as_slice().last().unwrap().hi, 11.5);
        assert_eq!(s.as_slice()[CAP - 1].lo, (CAP - 1) as f64);
    }
}
