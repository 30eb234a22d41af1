//! viaroad-fuzz: a mutation fuzzer for viaroad's loaders that runs on the stable toolchain.
//!
//! Every input runs in-process on a worker thread behind `catch_unwind`; the main thread waits
//! at most `--timeout` seconds of CPU time for it (a hang otherwise; see `WorkerClock`), and
//! the global allocator aborts on an allocation over [`alloc::MAX_ONE`] (a loader must refuse a huge count before allocating).
//! Findings are saved under `fuzz/artifacts/`; the exit status is 1 when there are any.
//!
//! ```text
//! cargo run --release -p viaroad-fuzz -- all --execs 30000 --seed 1 --shard 1/2  # CI: half of the smoke
//! cargo run --release -p viaroad-fuzz -- roadmap --execs 10000000      # the long mode
//! cargo run --release -p viaroad-fuzz -- dae --run fuzz/artifacts/FILE # replay one input
//! ```

mod alloc;
mod mutate;
mod targets;

use mutate::Mutator;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use targets::Target;

#[global_allocator]
static ALLOCATOR: alloc::Bounded = alloc::Bounded;

static LAST_PANIC: Mutex<String> = Mutex::new(String::new());

const USAGE: &str =
    "usage: viaroad-fuzz TARGET...|all [--execs N] [--seed S] [--timeout SECS] [--run FILE] [--shard K/N]
targets: toml cfg obj stl dae queries roadmap urdf srdf moveit
--shard K/N: only every N-th of the targets named, from the K-th on (one process per core)";

/// What the worker publishes for the watchdog: the input it runs and how many it has run.
struct Shared {
    current: Mutex<Arc<Vec<u8>>>,
    execs: AtomicU64,
    done: AtomicBool,
    /// The worker's CPU-time clock, once it has started (see [`WorkerClock`]).
    clock: Mutex<Option<WorkerClock>>,
}

/// How long the worker has run on a CPU. A hang is judged by the worker's CPU time, not by the
/// wall clock: on a loaded machine (the fuzzer runs `nice`d beside builds) a worker can wait
/// seconds for a core, and a wall-clock limit then reports inputs that load in milliseconds
/// (seen once: a TOML "hang" that replays in 40 ms). A loader that blocks without
/// burning CPU is still caught, by [`WALL_FACTOR`] times the limit on the wall clock.
#[derive(Clone, Copy)]
struct WorkerClock {
    #[cfg(target_os = "linux")]
    id: libc::clockid_t,
}

/// A stuck input is also a hang after this many times the limit of wall-clock time.
const WALL_FACTOR: u32 = 12;

impl WorkerClock {
    /// The calling thread's CPU clock (`None` where the platform has none: the wall clock
    /// alone then judges).
    fn of_this_thread() -> Option<WorkerClock> {
        #[cfg(target_os = "linux")]
        {
            let mut id: libc::clockid_t = 0;
            // SAFETY: pthread_self is always valid for the calling thread; `id` is written by
            // the call and read only when it succeeded
            let rc = unsafe { libc::pthread_getcpuclockid(libc::pthread_self(), &mut id) };
            (rc == 0).then_some(WorkerClock { id })
        }
        #[cfg(not(target_os = "linux"))]
        {
            None
        }
    }

    /// CPU time the worker has used so far.
    fn now(&self) -> Option<Duration> {
        #[cfg(target_os = "linux")]
        {
            let mut ts = libc::timespec {
                tv_sec: 0,
                tv_nsec: 0,
            };
            // SAFETY: `ts` is a valid timespec to write; the clock id came from
            // pthread_getcpuclockid of a thread that outlives every call (it is joined later)
            let rc = unsafe { libc::clock_gettime(self.id, &mut ts) };
            (rc == 0).then(|| Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32))
        }
        #[cfg(not(target_os = "linux"))]
        {
            None
        }
    }
}

struct Options {
    execs: u64,
    seed: u64,
    timeout: Duration,
    run: Option<PathBuf>,
}

#[derive(Default)]
struct Stats {
    execs: u64,
    loaded: u64,
    panics: u64,
    hangs: u64,
    seconds: f64,
}

fn save(artifacts: &Path, name: &str, ext: &str, what: &str, input: &[u8]) -> PathBuf {
    let _ = std::fs::create_dir_all(artifacts);
    let h = viaroad::roadmap::persist::checksum(input);
    let p = artifacts.join(format!("{name}-{what}-{h:016x}.{ext}"));
    let _ = std::fs::write(&p, input);
    p
}

/// Runs the target on a worker thread (inputs generated there: a hand-off per input would cost
/// a context switch each on a busy machine) while this thread watches for a hang.
fn fuzz(name: &str, opts: &Options, root: &Path, artifacts: &Path) -> Result<Stats, String> {
    let mut target =
        Target::new(name, root).ok_or_else(|| format!("unknown target {name}\n{USAGE}"))?;
    if target.seeds().is_empty() {
        return Err(format!("{name}: no seeds found under {}", root.display()));
    }
    let (tname, ext) = (target.name, target.ext);
    let tmp = if Path::new("/dev/shm").is_dir() {
        PathBuf::from("/dev/shm")
    } else {
        std::env::temp_dir()
    };
    let dir = tmp.join(format!("viaroad-fuzz-{}-{tname}", std::process::id()));
    targets::prepare_dir(&dir, root).map_err(|e| format!("{}: {e}", dir.display()))?;
    alloc::set_save_path(&artifacts.join(format!("{tname}-oom-current.{ext}")));
    let _ = std::fs::create_dir_all(artifacts);
    let fixed: Vec<Vec<u8>> = match &opts.run {
        Some(file) => vec![std::fs::read(file).map_err(|e| format!("{}: {e}", file.display()))?],
        None => target.seeds().to_vec(),
    };
    let total = if opts.run.is_some() {
        1
    } else {
        opts.execs.max(fixed.len() as u64)
    };
    let shared = Arc::new(Shared {
        current: Mutex::new(Arc::new(Vec::new())),
        execs: AtomicU64::new(0),
        done: AtomicBool::new(false),
        clock: Mutex::new(None),
    });
    let replay = opts.run.is_some();
    let (seed, work, artifacts_w) = (opts.seed, dir.clone(), artifacts.to_path_buf());
    let sh = Arc::clone(&shared);
    let start = Instant::now();
    let handle = std::thread::spawn(move || -> Result<Stats, String> {
        *sh.clock.lock().map_err(|_| "poisoned")? = WorkerClock::of_this_thread();
        let mut m = Mutator::new(seed ^ viaroad::roadmap::persist::checksum(tname.as_bytes()));
        let mut stats = Stats::default();
        let mut last_report = Instant::now();
        for k in 0..total {
            let input = Arc::new(match fixed.get(k as usize) {
                Some(f) => f.clone(),
                None => target.generate(&mut m),
            });
            alloc::set_current(&input);
            *sh.current.lock().map_err(|_| "poisoned")? = Arc::clone(&input);
            let outcome = std::panic::catch_unwind(|| targets::run(tname, &work, &input));
            stats.execs += 1;
            sh.execs.store(stats.execs, Ordering::Release);
            match outcome {
                Ok(Ok(true)) => {
                    stats.loaded += 1;
                    if !replay {
                        target.keep(input.to_vec(), &mut m);
                    }
                }
                Ok(Ok(false)) => {}
                Ok(Err(e)) => return Err(format!("{tname}: harness: {e}")),
                Err(_) => {
                    stats.panics += 1;
                    let msg = LAST_PANIC.lock().map(|s| s.clone()).unwrap_or_default();
                    let p = save(&artifacts_w, tname, ext, "panic", &input);
                    eprintln!("{tname}: PANIC ({msg}); input saved to {}", p.display());
                }
            }
            if last_report.elapsed() > Duration::from_secs(60) {
                last_report = Instant::now();
                eprintln!(
                    "{tname}: {} execs, {:.0}/s, {} panics",
                    stats.execs,
                    stats.execs as f64 / start.elapsed().as_secs_f64(),
                    stats.panics
                );
            }
        }
        sh.done.store(true, Ordering::Release);
        Ok(stats)
    });
    // the watchdog: an input that keeps the worker busy longer than the limit (CPU time), or
    // stuck for WALL_FACTOR times the limit, is a hang
    let cpu = || {
        let clock = *shared.clock.lock().ok()?;
        clock?.now()
    };
    let (mut seen, mut since, mut cpu_since) = (u64::MAX, Instant::now(), cpu());
    while !shared.done.load(Ordering::Acquire) && !handle.is_finished() {
        std::thread::sleep(Duration::from_millis(20));
        let now = shared.execs.load(Ordering::Acquire);
        if now != seen {
            (seen, since, cpu_since) = (now, Instant::now(), cpu());
            continue;
        }
        let busy = match (cpu_since, cpu()) {
            (Some(a), Some(b)) => b.saturating_sub(a) > opts.timeout,
            _ => since.elapsed() > opts.timeout, // no CPU clock: the wall clock judges
        };
        if busy || since.elapsed() > opts.timeout * WALL_FACTOR {
            let input = shared
                .current
                .lock()
                .map(|c| c.to_vec())
                .unwrap_or_default();
            let p = save(artifacts, tname, ext, "hang", &input);
            eprintln!(
                "{tname}: HANG (an input ran over {:?}); input saved to {}",
                opts.timeout,
                p.display()
            );
            // the stuck thread cannot be stopped: report and end the process
            println!("{tname:8} HANG after {now} execs");
            let _ = std::fs::remove_dir_all(&dir);
            std::process::exit(1);
        }
    }
    let mut stats = handle
        .join()
        .map_err(|_| format!("{tname}: the worker died"))??;
    stats.seconds = start.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    Ok(stats)
}

fn parse_args() -> Result<(Vec<String>, Options), String> {
    let mut args = std::env::args().skip(1);
    let mut names = Vec::new();
    let mut shard = (1, 1);
    let mut opts = Options {
        execs: 1000,
        seed: 1,
        timeout: Duration::from_secs(5),
        run: None,
    };
    while let Some(a) = args.next() {
        let mut value = |flag: &str| {
            args.next()
                .ok_or_else(|| format!("{flag} needs a value\n{USAGE}"))
        };
        match a.as_str() {
            "--execs" => {
                opts.execs = value("--execs")?
                    .parse()
                    .map_err(|e| format!("--execs: {e}"))?
            }
            "--seed" => {
                opts.seed = value("--seed")?
                    .parse()
                    .map_err(|e| format!("--seed: {e}"))?
            }
            "--timeout" => {
                let s: f64 = value("--timeout")?
                    .parse()
                    .map_err(|e| format!("--timeout: {e}"))?;
                if !(s.is_finite() && s > 0.0 && s < 1e6) {
                    return Err("--timeout: a positive number of seconds".into());
                }
                opts.timeout = Duration::from_secs_f64(s);
            }
            "--run" => opts.run = Some(PathBuf::from(value("--run")?)),
            "--shard" => shard = parse_shard(&value("--shard")?)?,
            "-h" | "--help" => return Err(USAGE.into()),
            "all" => names.extend(targets::NAMES.iter().map(|s| s.to_string())),
            other if other.starts_with('-') => {
                return Err(format!("unknown option {other}\n{USAGE}"))
            }
            other => names.push(other.to_string()),
        }
    }
    let (k, n) = shard;
    let names: Vec<String> = names.into_iter().skip(k - 1).step_by(n).collect();
    if names.is_empty() {
        return Err(USAGE.into());
    }
    Ok((names, opts))
}

/// `K/N` with `1 ≤ K ≤ N`.
fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--shard: K/N with 1 ≤ K ≤ N, not {s:?}");
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (k.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?);
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

fn main() {
    let (names, opts) = match parse_args() {
        Ok(x) => x,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    std::panic::set_hook(Box::new(|info| {
        let msg = match info.location() {
            Some(l) => format!(
                "{} at {}:{}",
                payload_text(info.payload()),
                l.file(),
                l.line()
            ),
            None => payload_text(info.payload()),
        };
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = msg;
        }
    }));
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let artifacts = Path::new(env!("CARGO_MANIFEST_DIR")).join("artifacts");
    let mut failed = false;
    for name in &names {
        match fuzz(name, &opts, &root, &artifacts) {
            Ok(s) => {
                println!(
                    "{name:8} {:>9} execs in {:7.1} s = {:>7.0} execs/s; loaded {:>7}; panics {}; hangs {}",
                    s.execs,
                    s.seconds,
                    s.execs as f64 / s.seconds.max(1e-9),
                    s.loaded,
                    s.panics,
                    s.hangs
                );
                failed |= s.panics + s.hangs > 0;
            }
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(2);
            }
        }
    }
    if failed {
        std::process::exit(1);
    }
}

fn payload_text(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic".into()
    }
}
