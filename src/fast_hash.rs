//! Hash maps keyed by our own numbers (vertex ids, welded coordinates' bits, a move's bits).
//!
//! The standard `HashMap` hashes with SipHash, seeded at random to resist flooding by an
//! adversary. Our keys come from meshes and configurations, not from an adversary, and SipHash
//! was the largest single cost of loading an arm's scene (perf of `viaroad query` on
//! table_pick: 17 % of the samples in `hash_one`, 28 % in map entries) and a sixth of a
//! shallow via-point search. [`MixHasher`] is one multiply and a fold per
//! word. No result may depend on a map's iteration order (with SipHash it changed from run to
//! run, so none does).

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A map hashed by [`MixHasher`].
pub(crate) type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<MixHasher>>;

/// A set hashed by [`MixHasher`].
pub(crate) type FastSet<K> = HashSet<K, BuildHasherDefault<MixHasher>>;

/// A multiply-and-fold hasher over 64-bit words (bytes are taken eight at a time).
#[derive(Default, Clone, Copy)]
pub(crate) struct MixHasher(u64);

impl Hasher for MixHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.write_u64(u64::from_le_bytes(c.try_into().expect("chunks of eight")));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut last = [0u8; 8];
            last[..rest.len()].copy_from_slice(rest);
            // the length tells "ab" from "ab\0"
            self.write_u64(u64::from_le_bytes(last) ^ ((rest.len() as u64) << 59));
        }
    }

    fn write_u64(&mut self, x: u64) {
        let h = (self.0 ^ x).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 = h ^ (h >> 32);
    }

    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, Hash};

    fn hash<T: Hash>(t: &T) -> u64 {
        BuildHasherDefault::<MixHasher>::default().hash_one(t)
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
        // a short tail is not its zero-padded self
        let written = |bytes: &[u8]| {
            let mut h = MixHasher::default();
            h.write(bytes);
            h.finish()
        };
        assert_ne!(written(&[1, 2]), written(&[1, 2, 0]));
        assert_ne!(written(&[1; 9]), written(&[1; 8]));
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
