//! Numbers from the command line checked against [`viaroad::limits`] before anything is
//! allocated or looped over: one clear message instead of a panic, an abort or a run that
//! never ends.

use std::time::Duration;
use viaroad::limits::{duration_from_secs, MAX_SECONDS};

/// A `--time`-like flag as a [`Duration`]: refuses NaN, infinities, zero, negative values
/// and more than [`MAX_SECONDS`] (which also cannot be converted: 1e300 s).
pub fn parse_seconds(flag: &str, seconds: f64) -> anyhow::Result<Duration> {
    duration_from_secs(seconds).ok_or_else(|| {
        anyhow::anyhow!(
            "{flag} must be a positive number of seconds of at most {MAX_SECONDS:e}, got {seconds:?}"
        )
    })
}

/// [`parse_seconds`] for an optional flag.
pub fn optional_seconds(flag: &str, seconds: Option<f64>) -> anyhow::Result<Option<Duration>> {
    seconds.map(|s| parse_seconds(flag, s)).transpose()
}

/// Refuses a count outside `1..=max` with a message naming the flag and why there is a limit.
pub fn count_in_range(flag: &str, n: usize, max: usize, why: &str) -> anyhow::Result<usize> {
    if n == 0 {
        anyhow::bail!("{flag} must be at least 1");
    }
    if n > max {
        anyhow::bail!("{flag} {n} is more than the {max} viaroad accepts: {why}");
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seconds_refuse_absurd_values_with_the_flag_named() {
        assert_eq!(
            parse_seconds("--time", 2.5).unwrap(),
            Duration::from_millis(2500)
        );
        for bad in [1e300, f64::NAN, -1.0, 0.0, f64::INFINITY] {
            let e = parse_seconds("--time", bad).unwrap_err().to_string();
            assert!(e.starts_with("--time must be"), "{e}");
        }
        assert!(count_in_range("--nodes", 0, 10, "x").is_err());
        assert!(count_in_range("--nodes", 11, 10, "x").is_err());
        assert_eq!(count_in_range("--nodes", 10, 10, "x").unwrap(), 10);
    }
}
