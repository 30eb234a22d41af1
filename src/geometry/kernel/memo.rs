//! Per-call caches indexed by face or tree node, reset in O(1): a sweep computes a robot
//! face's box in the motion's frame, or a robot node's swept bounds, at most once per call and
//! only for the faces and nodes the obstacle tree actually reaches (CHS §2.2 computes such
//! boxes once per polyhedron and direction; a call has one direction). Kept in a per-thread
//! scratch space, so that a call allocates nothing once the cache has grown to the largest
//! body seen.

/// Values `T` for indices `0..n`, each computed on first use since the last [`Memo::reset`].
#[derive(Clone, Debug)]
pub(crate) struct Memo<T> {
    /// The generation of the current call; a slot is valid iff it carries it.
    stamp: u32,
    slots: Vec<(u32, Option<T>)>,
}

impl<T> Default for Memo<T> {
    fn default() -> Self {
        Memo {
            stamp: 0,
            slots: Vec::new(),
        }
    }
}

impl<T> Memo<T> {
    /// Forgets every value and makes room for indices `0..n`.
    pub fn reset(&mut self, n: usize) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            // after 2³² calls: clear the stamps once rather than confuse generations
            for s in &mut self.slots {
                s.0 = 0;
            }
            self.stamp = 1;
        }
        if self.slots.len() < n {
            self.slots.resize_with(n, || (0, None));
        }
    }

    /// The value at `i`, computed by `f` if not yet this call. `i` must be below the `n` of
    /// the last [`Memo::reset`].
    #[inline]
    pub fn get_or_insert_with(&mut self, i: usize, f: impl FnOnce() -> T) -> &mut T {
        let s = &mut self.slots[i];
        if s.0 != self.stamp {
            s.0 = self.stamp;
            return s.1.insert(f());
        }
        s.1.get_or_insert_with(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_live_for_one_call() {
        let mut m: Memo<u32> = Memo::default();
        let mut computed = 0;
        for call in 0..3u32 {
            m.reset(4);
            for i in [0, 2, 0, 2, 3] {
                let v = *m.get_or_insert_with(i, || {
                    computed += 1;
                    call * 10 + i as u32
                });
                assert_eq!(v, call * 10 + i as u32);
            }
        }
        // three distinct indices per call, each computed once
        assert_eq!(computed, 9);
    }

    #[test]
    fn the_generation_wraps_without_stale_values() {
        let mut m: Memo<u32> = Memo::default();
        m.reset(2);
        m.get_or_insert_with(1, || 7);
        m.stamp = u32::MAX;
        m.slots[0] = (1, Some(99)); // a slot from an old generation 1
        m.reset(2); // wraps to 0 → clears, stamp 1
        assert_eq!(*m.get_or_insert_with(0, || 5), 5);
    }
}
