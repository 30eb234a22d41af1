//! Faults during saves, with the real `viaroad build`:
//!
//! * a full disk — a file size limit (`RLIMIT_FSIZE`, set with `ulimit -f` in a shell that
//!   ignores SIGXFSZ so that the write fails with EFBIG instead of killing the process), and a
//!   real 512 KiB tmpfs where user namespaces allow mounting one — gives one clear error line,
//!   leaves the previous roadmap byte for byte and no temporary file;
//! * two builds writing the same path at once leave one complete, loadable roadmap (one of the
//!   two) and no temporary file;
//! * builds killed with SIGKILL at random moments leave the previous roadmap or the new one,
//!   complete, and a later build cleans whatever temporary a killed one left
//!   (`benches/kill_saves.sh` runs the long version of this loop).

#![cfg(unix)]

use rand::{Rng, SeedableRng};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;
use viaroad::roadmap::Roadmap;

const BIN: &str = env!("CARGO_BIN_EXE_viaroad");

fn scene() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/discs-cluttered.toml")
}

fn tempdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("viaroad-save-faults-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn build(out: &Path, nodes: usize, seed: u64) -> Command {
    let mut c = Command::new(BIN);
    c.arg("build")
        .arg(scene())
        .arg("-o")
        .arg(out)
        .args(["--nodes", &nodes.to_string(), "--seed", &seed.to_string()])
        .env("RAYON_NUM_THREADS", "1");
    c
}

fn run_ok(mut c: Command) {
    let o = c.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Files in `dir` named like a save's temporaries.
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.ends_with(".tmp"))
        .collect()
}

fn loads(path: &Path) -> bool {
    Roadmap::load_any_scene(path).is_ok()
}

fn sh(script: &str, args: &[&Path]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

/// A build whose output would pass the file size limit fails with one clear line (exit 1, not
/// a panic's 101, not a signal), and the previous roadmap stays as it was.
#[test]
fn file_size_limit_keeps_the_previous_roadmap() {
    let dir = tempdir("fsize");
    let out = dir.join("r.bin");
    run_ok(build(&out, 50, 1));
    let before = std::fs::read(&out).unwrap();
    assert!(before.len() < 64 * 1024, "the small roadmap fits the limit");
    // 256 blocks of 512 bytes: 128 KiB; 20 000 nodes take about 1 MB
    let o = sh(
        "trap '' XFSZ; ulimit -f 256 && exec \"$0\" build \"$1\" -o \"$2\" --nodes 20000 --seed 2",
        &[Path::new(BIN), &scene(), &out],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "stderr: {err}");
    assert!(
        err.contains("File too large") || err.contains("too large"),
        "stderr: {err}"
    );
    assert!(!err.contains("panicked"), "stderr: {err}");
    assert_eq!(
        std::fs::read(&out).unwrap(),
        before,
        "the previous roadmap changed"
    );
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The same on a real full file system: a 512 KiB tmpfs mounted in a user and mount namespace
/// (`unshare -rm`). Where the machine forbids those namespaces the test says so and checks
/// nothing more (the size-limit test above covers the same path in the code: a failed write).
#[test]
fn full_tmpfs_keeps_the_previous_roadmap() {
    let dir = tempdir("tmpfs");
    let small = dir.join("small.bin");
    run_ok(build(&small, 50, 1));
    let mnt = dir.join("mnt");
    std::fs::create_dir(&mnt).unwrap();
    let probe = Command::new("unshare")
        .args([
            "-rm",
            "sh",
            "-c",
            "mount -t tmpfs -o size=512k tmpfs \"$0\"",
        ])
        .arg(&mnt)
        .output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("note: cannot mount a tmpfs in a user namespace here; skipped");
        std::fs::remove_dir_all(&dir).unwrap();
        return;
    }
    // inside the namespace: copy the old roadmap in, build a 1 MB one over it, report
    let o = Command::new("unshare")
        .args([
            "-rm",
            "sh",
            "-c",
            r#"mount -t tmpfs -o size=512k tmpfs "$1" || exit 90
cp "$2" "$1/r.bin" || exit 91
"$0" build "$3" -o "$1/r.bin" --nodes 20000 --seed 2 2>"$1/err"
echo "rc=$?"
cmp -s "$2" "$1/r.bin" && echo intact
ls -A "$1" | grep '\.tmp$' && echo stray
cat "$1/err"
"$0" info "$1/r.bin" >/dev/null && echo loads"#,
        ])
        .arg(BIN)
        .arg(&mnt)
        .arg(&small)
        .arg(scene())
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(text.contains("rc=1\n"), "{text}");
    assert!(text.contains("intact"), "{text}");
    assert!(text.contains("No space left on device"), "{text}");
    assert!(!text.contains("stray"), "{text}");
    assert!(text.contains("loads"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Two builds of different roadmaps to the same path at the same moment: both succeed, the
/// file is one of the two, whole, and no temporary is left.
#[test]
fn concurrent_builds_leave_one_valid_roadmap() {
    let dir = tempdir("concurrent");
    let a_ref = dir.join("a.bin");
    let b_ref = dir.join("b.bin");
    run_ok(build(&a_ref, 3000, 1));
    run_ok(build(&b_ref, 3000, 2));
    let (a, b) = (
        std::fs::read(&a_ref).unwrap(),
        std::fs::read(&b_ref).unwrap(),
    );
    assert_ne!(a, b);
    let out = dir.join("r.bin");
    for _ in 0..4 {
        let mut x = build(&out, 3000, 1).stdout(Stdio::null()).spawn().unwrap();
        let mut y = build(&out, 3000, 2).stdout(Stdio::null()).spawn().unwrap();
        assert!(x.wait().unwrap().success());
        assert!(y.wait().unwrap().success());
        let got = std::fs::read(&out).unwrap();
        assert!(got == a || got == b, "the file is neither build's roadmap");
        assert!(loads(&out));
        assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Builds killed at random moments (a few here; `benches/kill_saves.sh` runs hundreds): the
/// file is always the old roadmap or the new one, never a mix, and the next complete build
/// leaves no temporary behind.
#[test]
fn killed_builds_leave_a_whole_roadmap() {
    let dir = tempdir("kill");
    let out = dir.join("r.bin");
    let new_ref = dir.join("new.bin");
    run_ok(build(&out, 200, 1));
    run_ok(build(&new_ref, 20000, 2));
    let old = std::fs::read(&out).unwrap();
    let new = std::fs::read(&new_ref).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(15);
    for _ in 0..6 {
        let mut child = build(&out, 20000, 2)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(rng.random_range(0..400)));
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        let got = std::fs::read(&out).unwrap();
        assert!(got == old || got == new, "a killed build left a mixed file");
        // put the old one back so that every round can show a lost roadmap
        std::fs::write(&out, &old).unwrap();
    }
    run_ok(build(&out, 200, 1));
    assert_eq!(std::fs::read(&out).unwrap(), old);
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A build killed the moment its temporary file appears — during the write — leaves the old
/// roadmap untouched and a half-written temporary, which the next build removes.
#[test]
fn build_killed_during_the_write() {
    let dir = tempdir("kill-write");
    let out = dir.join("r.bin");
    run_ok(build(&out, 200, 1));
    let old = std::fs::read(&out).unwrap();
    let mut caught = 0;
    for _ in 0..3 {
        let mut child = build(&out, 60000, 2)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let prefix = format!(".r.bin.{}-", child.id());
        loop {
            let seen = std::fs::read_dir(&dir).unwrap().any(|e| {
                e.unwrap()
                    .file_name()
                    .to_string_lossy()
                    .starts_with(&prefix)
            });
            if seen || child.try_wait().unwrap().is_some() {
                break;
            }
            std::thread::sleep(Duration::from_micros(50));
        }
        let _ = child.kill();
        let _ = child.wait();
        let got = std::fs::read(&out).unwrap();
        if !temporaries(&dir).is_empty() {
            caught += 1;
            assert_eq!(got, old, "killed during the write, the target changed");
        }
        assert!(loads(&out));
        std::fs::write(&out, &old).unwrap();
    }
    assert!(caught > 0, "no kill landed during the write");
    run_ok(build(&out, 200, 1));
    assert_eq!(std::fs::read(&out).unwrap(), old);
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A temporary left by a killed save (a dead process's id in its name) is removed by the next
/// save; one of a live process (this test's own) is not.
#[test]
fn stale_temporaries_are_cleaned_live_ones_kept() {
    let dir = tempdir("stale");
    let out = dir.join("r.bin");
    // a process id that is not running: a child that has exited and been reaped
    let mut c = Command::new("true").spawn().unwrap();
    let dead = c.id();
    c.wait().unwrap();
    let stale = dir.join(format!(".r.bin.{dead}-0.tmp"));
    let live = dir.join(format!(".r.bin.{}-99.tmp", std::process::id()));
    std::fs::write(&stale, b"half a roadmap").unwrap();
    std::fs::write(&live, b"a save in progress").unwrap();
    run_ok(build(&out, 50, 1));
    assert!(loads(&out));
    assert!(!stale.exists(), "the stale temporary is still there");
    assert!(live.exists(), "a live process's temporary was removed");
    std::fs::remove_dir_all(&dir).unwrap();
}
