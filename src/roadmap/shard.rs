//! Shards: one of `N` roadmaps learnt apart (on other cores or machines) and merged later
//! ([`super::Learner::merge`]).
//!
//! A shard is a **partition of the sample stream**, not of the space. Shard `I` of `N` with
//! seed `S` learns like any roadmap, from the whole space, with the seed [`Shard::seed`]
//! derives from `(S, I, N)`: its candidates and walks draw from ChaCha streams no other shard
//! uses, so the shards' samples are independent draws of the same distribution, and together
//! they are a sample of what one learner with `N` times the budget would draw. Why streams
//! rather than cells of the space:
//!
//! - every shard is a roadmap of the whole scene, usable alone, and the merge of any subset of
//!   shards is one too (a worker lost is nodes missing, not a hole in the space);
//! - the shards' work is balanced in expectation whatever the obstacles do, where cells with
//!   little free space or narrow passages would make some workers idle and others slow;
//! - obstacle-based samplers and random-bounce walks need no boundary rules, and no node sits
//!   on a boundary with half its neighbours missing;
//! - the merge needs no geometry of its own: joining parts is the learner's nearest-neighbour
//!   connection step, which a spatial split would need at every boundary anyway.
//!
//! A node budget is split between the shards ([`Shard::nodes`]), so that `N` shards of
//! `--nodes M` learn `M` nodes between them, as one build of `--nodes M` would; a time budget
//! is each shard's own (they run side by side).

use std::fmt;
use std::str::FromStr;

/// Shard `index` of `count` (both counted from 1, as in `--shard 2/4`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    index: u32,
    count: u32,
}

/// Why a shard cannot be named so.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not of the form `I/N` with whole numbers.
    #[error("a shard is I/N with whole numbers 1 ≤ I ≤ N, not {0:?}")]
    Syntax(String),
    /// The index is 0 or above the count.
    #[error("shard {index} of {count} does not exist: shards are numbered 1 to {count}")]
    OutOfRange {
        /// The index given.
        index: u64,
        /// The count given.
        count: u64,
    },
}

impl Shard {
    /// The most shards a roadmap may be learnt in.
    pub const MAX_COUNT: u32 = 1 << 20;

    /// Shard `index` of `count`, with `1 ≤ index ≤ count ≤` [`Shard::MAX_COUNT`].
    pub fn new(index: u64, count: u64) -> Result<Shard, ShardError> {
        if index == 0 || index > count || count > u64::from(Self::MAX_COUNT) {
            return Err(ShardError::OutOfRange { index, count });
        }
        Ok(Shard {
            index: index as u32,
            count: count as u32,
        })
    }

    /// The shard's index, from 1.
    pub fn index(&self) -> u32 {
        self.index
    }

    /// How many shards there are.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The seed this shard learns with, for the seed `seed` the shards share: a mix of
    /// `(seed, index, count)` (SplitMix64's finaliser over each word in turn), so shards of one
    /// seed, of other counts or of other seeds draw from unrelated streams. Shard 1 of 1 is not
    /// sharded: it keeps `seed`, so it learns what an unsharded build learns.
    pub fn seed(&self, seed: u64) -> u64 {
        if self.count == 1 {
            return seed;
        }
        let mut h = mix(seed ^ 0x5348_4152_445f_5631); // "SHARD_V1"
        h = mix(h ^ u64::from(self.index));
        mix(h ^ (u64::from(self.count) << 32))
    }

    /// This shard's part of a node budget of `total`: `total / count`, the remainder going one
    /// node each to the first shards, so the shards' budgets add up to `total`. At least one.
    pub fn nodes(&self, total: usize) -> usize {
        let n = self.count as usize;
        let i = self.index as usize - 1;
        (total / n + usize::from(i < total % n)).max(1)
    }
}

/// SplitMix64's finaliser: a bijection of 64-bit words that mixes every bit into every other.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl FromStr for Shard {
    type Err = ShardError;

    /// `I/N`, as `--shard` takes it.
    fn from_str(s: &str) -> Result<Shard, ShardError> {
        let syntax = || ShardError::Syntax(s.to_string());
        let (i, n) = s.split_once('/').ok_or_else(syntax)?;
        let i: u64 = i.trim().parse().map_err(|_| syntax())?;
        let n: u64 = n.trim().parse().map_err(|_| syntax())?;
        Shard::new(i, n)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_refuses() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard::new(2, 4).unwrap()));
        assert!(matches!(
            "0/4".parse::<Shard>(),
            Err(ShardError::OutOfRange { .. })
        ));
        assert!(matches!(
            "5/4".parse::<Shard>(),
            Err(ShardError::OutOfRange { .. })
        ));
        assert!(matches!("2-4".parse::<Shard>(), Err(ShardError::Syntax(_))));
        assert!(matches!("a/4".parse::<Shard>(), Err(ShardError::Syntax(_))));
        assert_eq!(Shard::new(3, 7).unwrap().to_string(), "3/7");
    }

    #[test]
    fn budgets_add_up_and_seeds_differ() {
        for n in 1..9u64 {
            let total: usize = (1..=n).map(|i| Shard::new(i, n).unwrap().nodes(103)).sum();
            assert_eq!(total, 103);
        }
        let seeds: Vec<u64> = (1..=4)
            .map(|i| Shard::new(i, 4).unwrap().seed(7))
            .chain((1..=2).map(|i| Shard::new(i, 2).unwrap().seed(7)))
            .chain([Shard::new(1, 4).unwrap().seed(8), 7])
            .collect();
        for (i, a) in seeds.iter().enumerate() {
            for b in &seeds[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert_eq!(Shard::new(1, 1).unwrap().seed(7), 7);
    }
}
