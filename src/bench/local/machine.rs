//! The machine a benchmark ran on, the date, and peak resident memory — what OMPL's benchmark
//! log records about its host (`hostname`, `cpuinfo`, `date`, `memory`).
//!
//! Linux only where `/proc` is needed; elsewhere the values are `None` or `"unknown"`.

use std::time::{SystemTime, UNIX_EPOCH};

/// The host name (`/proc/sys/kernel/hostname`, then `$HOSTNAME`).
pub fn hostname() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "unknown".into())
}

/// The CPU model and the number of logical cores, e.g. `AMD EPYC, 2 cores`.
pub fn cpu_info() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo").ok().and_then(|s| {
        s.lines()
            .find(|l| l.starts_with("model name"))
            .and_then(|l| l.split_once(':'))
            .map(|(_, m)| m.trim().to_string())
    });
    let cores = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    format!(
        "{}, {cores} cores",
        model.unwrap_or_else(|| "unknown CPU".into())
    )
}

/// The current time in UTC as `YYYY-MM-DD HH:MM:SS` (SQLite's DATETIME text).
pub fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    utc_datetime(secs)
}

/// `secs` after the Unix epoch as `YYYY-MM-DD HH:MM:SS` (proleptic Gregorian calendar).
pub fn utc_datetime(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    // days since 1970-01-01 to a civil date (Howard Hinnant's algorithm)
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1_460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02}",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// Peak resident set size of this process in MiB (`VmHWM` in `/proc/self/status`).
pub fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line
        .trim_start_matches("VmHWM:")
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kib / 1024.0)
}

/// Resets the peak resident set size to the current one (writing `5` to
/// `/proc/self/clear_refs`, Linux ≥ 4.0), so that [`peak_rss_mib`] measures from here on.
/// Returns whether it worked.
pub fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_civil() {
        assert_eq!(utc_datetime(0), "1970-01-01 00:00:00");
        assert_eq!(utc_datetime(951_782_400), "2000-02-29 00:00:00");
        assert_eq!(utc_datetime(1_795_000_000), "2026-11-18 11:06:40");
        assert_eq!(utc_datetime(4_107_542_399), "2100-02-28 23:59:59");
    }

    #[test]
    fn peak_rss_is_read_where_proc_exists() {
        if std::path::Path::new("/proc/self/status").exists() {
            let before = peak_rss_mib().unwrap();
            assert!(before > 0.0);
            let block = vec![1u8; 64 << 20];
            std::hint::black_box(&block);
            assert!(peak_rss_mib().unwrap() >= before);
        }
    }
}
