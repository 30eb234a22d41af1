//! The random streams of a round's candidates: fixed by `(seed, round, index)`, so that the
//! roadmap does not depend on which thread ran which candidate.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Separates the random streams of the two steps.
pub(super) const SAMPLE_STREAM: u64 = 1;
pub(super) const WALK_STREAM: u64 = 2;

/// The random stream of candidate `index` in round `round`: a ChaCha8 generator keyed by
/// `(seed, round, index, purpose)`, so that every candidate's draws are fixed whatever thread
/// runs it.
pub fn stream(seed: u64, round: u64, index: u64, purpose: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    key[8..16].copy_from_slice(&round.to_le_bytes());
    key[16..24].copy_from_slice(&index.to_le_bytes());
    key[24..].copy_from_slice(&purpose.to_le_bytes());
    ChaCha8Rng::from_seed(key)
}
