//! Hash maps keyed by our own numbers (vertex ids, welded coordinates' bits, a move's bits).
//!
//! The standard `HashMap` hashes with SipHash, seeded at random to resist flooding by an
//! adversary. Our keys come from meshes and configurations, not from an adversary, and SipHash
//! was the largest single cost of loading an arm's scene (perf of `viaroad query` on
//! table_pick: 17 % of the samples in `hash_one`, 28 % in map entries) and a sixth of a
//! shallow via-point search. These maps hash with `rustc-hash`'s `FxHasher`, the compiler's
//! own: a multiply and a rotation per word, unseeded (see ARCHITECTURE.md, "Dependencies and
//! what we chose not to depend on"). No result may depend on a map's iteration order (with
//! SipHash it changed from run to run, so none does).

/// A map hashed by `FxHasher`.
pub(crate) type FastMap<K, V> = rustc_hash::FxHashMap<K, V>;

/// A set hashed by `FxHasher`.
pub(crate) type FastSet<K> = rustc_hash::FxHashSet<K>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, Hash};

    fn hash<T: Hash>(t: &T) -> u64 {
        rustc_hash::FxBuildHasher.hash_one(t)
    }

    #[test]
    fn keys_that_differ_hash_apart() {
        let mut seen = FastSet::default();
        for a in 0..40u32 {
            for b in 0..40u32 {
                for c in 0..10u32 {
                    assert!(seen.insert(hash(&[a, b, c])), "[{a}, {b}, {c}] collides");
                }
            }
        }
        // a sequence is not its zero-padded self
        assert_ne!(hash(&vec![1u64, 2]), hash(&vec![1u64, 2, 0]));
    }

    #[test]
    fn a_map_finds_what_it_holds() {
        let mut m: FastMap<(u32, u32), usize> = FastMap::default();
        for i in 0..5000u32 {
            m.insert((i % 97, i / 97), i as usize);
        }
        assert_eq!(m.len(), 5000);
        for i in 0..5000u32 {
            assert_eq!(m[&(i % 97, i / 97)], i as usize);
        }
    }
}
