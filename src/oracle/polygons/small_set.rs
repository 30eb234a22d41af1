//! Small interval lists on the stack, for evaluating one pair's predicate under rotation.
//!
//! The predicate of one (edge, edge) or (point, triangle) pair is a boolean combination of at
//! most a dozen atomic inequalities, each solved by at most two intervals of the window; every
//! end of the combined set is a root of an atom, so the lists stay short. They are evaluated
//! here like the seed's interval lists (∧ = intersection, ∨ = union, CHS §2.2) without touching
//! the heap — this is the oracle's hot path. Should a list ever outgrow its capacity, its last
//! interval is stretched instead: a conservative answer (more collision, never less).

use crate::interval::Interval;

const CAPACITY: usize = 6;

/// Sorted, disjoint closed intervals, at most [`CAPACITY`] of them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SmallSet {
    len: usize,
    items: [Interval; CAPACITY],
}

impl Default for SmallSet {
    fn default() -> Self {
        SmallSet::new()
    }
}

impl SmallSet {
    /// The empty set.
    #[inline]
    pub fn new() -> SmallSet {
        SmallSet {
            len: 0,
            items: [Interval { lo: 0.0, hi: 0.0 }; CAPACITY],
        }
    }

    /// The intervals, sorted.
    #[inline]
    pub fn as_slice(&self) -> &[Interval] {
        &self.items[..self.len]
    }

    /// No interval.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Appends `iv`, which must not start before the last interval starts; touching or
    /// overlapping intervals merge. When full, the last interval is stretched to cover `iv`.
    #[inline]
    pub fn push(&mut self, iv: Interval) {
        if self.len > 0 {
            let last = &mut self.items[self.len - 1];
            if iv.lo <= last.hi || self.len == CAPACITY {
                last.hi = last.hi.max(iv.hi);
                return;
            }
        }
        self.items[self.len] = iv;
        self.len += 1;
    }

    /// `a ∩ b`.
    #[inline]
    pub fn intersection(a: &SmallSet, b: &SmallSet) -> SmallSet {
        let mut out = SmallSet::new();
        let (x, y) = (a.as_slice(), b.as_slice());
        let (mut i, mut j) = (0, 0);
        while i < x.len() && j < y.len() {
            if let Some(m) = x[i].meet(&y[j]) {
                out.push(m);
            }
            if x[i].hi < y[j].hi {
                i += 1;
            } else {
                j += 1;
            }
        }
        out
    }

    /// `a ∪ b`.
    #[inline]
    pub fn union(a: &SmallSet, b: &SmallSet) -> SmallSet {
        let mut out = SmallSet::new();
        let (x, y) = (a.as_slice(), b.as_slice());
        let (mut i, mut j) = (0, 0);
        while i < x.len() || j < y.len() {
            let take_x = match (x.get(i), y.get(j)) {
                (Some(p), Some(q)) => p.lo <= q.lo,
                (Some(_), None) => true,
                _ => false,
            };
            if take_x {
                out.push(x[i]);
                i += 1;
            } else {
                out.push(y[j]);
                j += 1;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(v: &[(f64, f64)]) -> SmallSet {
        let mut s = SmallSet::new();
        for &(lo, hi) in v {
            s.push(Interval { lo, hi });
        }
        s
    }

    #[test]
    fn union_and_intersection() {
        let a = set(&[(0.0, 1.0), (2.0, 3.0)]);
        let b = set(&[(0.5, 2.0), (4.0, 5.0)]);
        let u = SmallSet::union(&a, &b);
        assert_eq!(
            u.as_slice(),
            &[Interval { lo: 0.0, hi: 3.0 }, Interval { lo: 4.0, hi: 5.0 }]
        );
        let i = SmallSet::intersection(&a, &b);
        assert_eq!(
            i.as_slice(),
            &[Interval { lo: 0.5, hi: 1.0 }, Interval { lo: 2.0, hi: 2.0 }]
        );
        assert!(SmallSet::intersection(&a, &SmallSet::new()).is_empty());
    }

    #[test]
    fn overflow_stretches_the_last_interval() {
        let mut s = SmallSet::new();
        for k in 0..40 {
            s.push(Interval {
                lo: k as f64,
                hi: k as f64 + 0.5,
            });
        }
        assert_eq!(s.as_slice().len(), CAPACITY);
        assert_eq!(s.as_slice()[CAPACITY - 1].hi, 39.5);
        // every pushed interval is still covered
        for k in 0..40 {
            let t = k as f64 + 0.25;
            assert!(s.as_slice().iter().any(|iv| iv.contains(t)));
        }
    }
}
