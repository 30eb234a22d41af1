//! The largest (or smallest) numbers viaroad accepts from users, in one place.
//!
//! A number past these limits is refused with one clear message *before* anything is allocated
//! or looped over (issue 16): a time of 10³⁰⁰ s cannot become a [`std::time::Duration`], 10¹¹
//! generated discs do not fit in memory, a sampling resolution of 10⁻³⁰⁰ never finishes a
//! motion, and bounds of ±10³⁰⁸ overflow every distance. The limits are far beyond any useful
//! run, so they only ever catch typos and hostile input.

use std::time::Duration;

/// Longest time budget, in seconds (about 31 years): anything longer is a typo, and far longer
/// values (10³⁰⁰) do not fit a [`Duration`].
pub const MAX_SECONDS: f64 = 1e9;

/// Most roadmap nodes one learning run may be asked for. A node costs at least its
/// coordinates, its neighbour lists and its edges (hundreds of bytes), so ten million nodes
/// already take gigabytes; with no `--time` a larger count would run until memory runs out.
pub const MAX_NODES: usize = 10_000_000;

/// Most random queries generated at once (`demo --queries`, `bench local --queries`): each
/// pair of configurations is stored before the first is answered.
pub const MAX_QUERIES: usize = 1_000_000;

/// Most discs of a generated scene (`gen:discs:n=…`): 10⁵ discs of any useful radius already
/// cover the unit square.
pub const MAX_GENERATED_DISCS: usize = 100_000;

/// Most runs per scene and method of `bench local`.
pub const MAX_RUNS: u32 = 100_000;

/// Smallest resolution of the sampled local method (a fraction of the space's extent, OMPL's
/// convention): a motion is checked at up to `1 / resolution` states, so 10⁻⁹ is already a
/// billion checks per motion, and 10⁻³⁰⁰ never ends.
pub const MIN_SAMPLED_RESOLUTION: f64 = 1e-9;

/// Largest magnitude of a position bound. Distances, squared distances and valuations of
/// configurations inside bounds of ±10¹⁰⁰ stay finite; ±10³⁰⁰ gives infinite edge lengths and
/// ±10³⁰⁸ overflows even the width of the box.
pub const MAX_COORDINATE: f64 = 1e100;

/// Most clients `viaroad serve --listen` keeps connected at once (`--max-clients` can only
/// lower it). Each holds a reader thread and three descriptors, so 256 stay well inside the
/// usual limit of 1024 open files.
pub const MAX_SERVE_CLIENTS: usize = 256;

/// Most bytes read from a scene, mesh or query file: a file this large is not a scene (and
/// `/dev/zero` would otherwise be read until memory runs out).
pub const MAX_TEXT_FILE_BYTES: u64 = 1 << 30;

/// `seconds` as a [`Duration`] if it is a positive, finite number of at most [`MAX_SECONDS`].
pub fn duration_from_secs(seconds: f64) -> Option<Duration> {
    if seconds.is_finite() && seconds > 0.0 && seconds <= MAX_SECONDS {
        Duration::try_from_secs_f64(seconds).ok()
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_in_range_only() {
        assert_eq!(duration_from_secs(1.5), Some(Duration::from_millis(1500)));
        assert_eq!(
            duration_from_secs(MAX_SECONDS),
            Some(Duration::from_secs(1_000_000_000))
        );
        for bad in [
            0.0,
            -1.0,
            1e300,
            f64::INFINITY,
            f64::NAN,
            MAX_SECONDS * 1.01,
        ] {
            assert_eq!(duration_from_secs(bad), None, "{bad}");
        }
    }
}
