//! Regression tests of defects found by trying the command line: one test per defect,
//! per message mended and per decision taken. Every failure must be one `error:` line with
//! exit status 1 (no panic), reached within seconds; special files are never replaced; no
//! stale numbered outputs; no stray temporaries after a killed save.

use crate::common;

use common::cli::{fails_alone_with as fails_with, stderr, stdout, viaroad};

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};

fn s(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

const EXAMPLE: &str = "scenes/discs-example.toml";
const CLUTTERED: &str = "scenes/discs-cluttered.toml";

fn r2_scene(lower: &str, upper: &str, extra: &str) -> String {
    format!(
        "name = \"t\"\n[space]\nkind = \"r2\"\nlower = {lower}\nupper = {upper}\n{extra}\
         [[obstacle]]\ndisc = {{ center = [0.3, 0.4], radius = 0.05 }}\n\
         [[query]]\nstart = [0.02, 0.98]\ngoal = [0.98, 0.02]\n"
    )
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    use std::os::unix::ffi::OsStrExt;
    let c = std::ffi::CString::new(path.as_os_str().as_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0, "mkfifo");
}

#[cfg(unix)]
fn is_char_device(p: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_char_device())
}

#[cfg(unix)]
fn is_fifo(p: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_fifo())
}

// ---- row 1: special files are never replaced -------------------------------------------

#[cfg(unix)]
#[test]
fn save_refuses_device_node() {
    let null = Path::new("/dev/null");
    assert!(is_char_device(null));
    let e = fails_with(
        &["build", EXAMPLE, "-o", "/dev/null", "--nodes", "50"],
        "/dev/null",
    );
    assert!(e.contains("character device"), "{e}");
    fails_with(
        &["solve", EXAMPLE, "--path-out", "/dev/null"],
        "character device",
    );
    fails_with(&["render", EXAMPLE, "-o", "/dev/null"], "character device");
    assert!(is_char_device(null), "/dev/null is still a device");
    // nothing was left next to it either
    let stray = std::fs::read_dir("/dev")
        .unwrap()
        .flatten()
        .any(|e| e.file_name().to_string_lossy().starts_with(".null."));
    assert!(!stray, "a temporary was left in /dev");
}

#[cfg(unix)]
#[test]
fn save_refuses_fifo() {
    let dir = temp_dir("fifo");
    let fifo = dir.join("map.bin");
    mkfifo(&fifo);
    let f = s(&fifo);
    fails_with(&["build", EXAMPLE, "-o", &f, "--nodes", "50"], "FIFO");
    fails_with(&["solve", EXAMPLE, "--path-out", &f], "FIFO");
    fails_with(&["render", EXAMPLE, "-o", &f], "FIFO");
    assert!(is_fifo(&fifo), "the FIFO is still a FIFO");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "nothing else written"
    );
    // a benchmark refuses its special outputs before it runs, not after
    let out = dir.join("out");
    std::fs::create_dir(&out).unwrap();
    mkfifo(&out.join("summary.md"));
    fails_with(
        &[
            "bench",
            "local",
            EXAMPLE,
            "--methods",
            "straight",
            "--runs",
            "1",
            "--out",
            &s(&out),
        ],
        "FIFO",
    );
    assert!(is_fifo(&out.join("summary.md")));
    assert_eq!(
        std::fs::read_dir(&out).unwrap().count(),
        1,
        "nothing else written"
    );
}

#[cfg(unix)]
#[test]
fn save_writes_through_symlink() {
    let dir = temp_dir("symlink");
    let real_dir = dir.join("real");
    std::fs::create_dir(&real_dir).unwrap();
    let real = real_dir.join("map.bin");
    std::fs::write(&real, b"old").unwrap();
    let link = dir.join("link.bin");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let o = viaroad(&["build", EXAMPLE, "-o", &s(&link), "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // the link is still a link, and the file it leads to holds the roadmap
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read(&real).unwrap().starts_with(b"VIAROADM"));
    let o = viaroad(&["info", &s(&link)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // a link to a device is refused like the device
    let to_null = dir.join("null.bin");
    std::os::unix::fs::symlink("/dev/null", &to_null).unwrap();
    fails_with(
        &["build", EXAMPLE, "-o", &s(&to_null), "--nodes", "50"],
        "character device",
    );
    assert!(std::fs::symlink_metadata(&to_null)
        .unwrap()
        .file_type()
        .is_symlink());
    // a dangling link is refused
    let dangling = dir.join("dangling.bin");
    std::os::unix::fs::symlink(dir.join("none"), &dangling).unwrap();
    fails_with(
        &["build", EXAMPLE, "-o", &s(&dangling), "--nodes", "50"],
        "does not exist",
    );
}

// ---- row 2: a closed pipe ends the program quietly -------------------------------------

/// Reads one line of `args`' stdout, closes the pipe, and checks the program ended without a
/// word on stderr: by SIGPIPE or normally.
#[cfg(unix)]
fn ends_quietly_on_closed_pipe(args: &[&str]) {
    use std::os::unix::process::ExitStatusExt;
    let mut child = Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    // the reader is dropped here: the pipe is closed with most of the output unread
    let o = child.wait_with_output().unwrap();
    let err = stderr(&o);
    assert!(!line.is_empty(), "{args:?}: no output");
    assert!(
        o.status.success() || o.status.signal() == Some(libc::SIGPIPE),
        "{args:?}: {:?} {err}",
        o.status
    );
    assert!(
        !err.contains("panicked") && !err.contains("error"),
        "{args:?}: {err}"
    );
}

#[cfg(unix)]
#[test]
fn closed_pipe_ends_quietly() {
    let dir = temp_dir("pipe");
    let map = s(&dir.join("map.bin"));
    let o = viaroad(&["build", EXAMPLE, "-o", &map, "--nodes", "100"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // 3000 queries: over a megabyte of JSON, far more than a pipe buffers
    let text = "0.02 0.98 0.98 0.02\n".repeat(3000);
    let queries = write(&dir, "many.txt", &text);
    ends_quietly_on_closed_pipe(&[
        "query",
        &map,
        "--scene",
        EXAMPLE,
        "--queries",
        &queries,
        "--json",
    ]);
    ends_quietly_on_closed_pipe(&["query", &map, "--scene", EXAMPLE, "--queries", &queries]);
    ends_quietly_on_closed_pipe(&["solve", CLUTTERED, "--json"]);
    ends_quietly_on_closed_pipe(&["info", &map]);
}

// ---- row 3: bounds whose distances overflow are a scene error --------------------------

#[test]
fn bounds_1e308_is_a_scene_error() {
    let dir = temp_dir("bounds");
    let out = s(&dir.join("o"));
    for big in ["1e308", "1e300", "1e101"] {
        let scene = write(
            &dir,
            &format!("b{big}.toml"),
            &r2_scene(&format!("[-{big}, -{big}]"), &format!("[{big}, {big}]"), ""),
        );
        fails_with(
            &[
                "build",
                &scene,
                "-o",
                &s(&dir.join("m.bin")),
                "--nodes",
                "50",
            ],
            "overflow",
        );
        fails_with(&["solve", &scene], "overflow");
        fails_with(&["demo", "--scene", &scene, "--out", &out], "overflow");
        fails_with(
            &[
                "bench",
                "local",
                &scene,
                "--methods",
                "straight",
                "--runs",
                "1",
                "--out",
                &out,
            ],
            "overflow",
        );
    }
    let se3 = write(
        &dir,
        "se3.toml",
        "[space]\nkind = \"se3\"\nlower = [-1e308, -1e308, -1e308]\nupper = [1e308, 1e308, 1e308]\n\
         [robot]\nbox = { half_extents = [0.1, 0.1, 0.1] }\n",
    );
    fails_with(
        &["build", &se3, "-o", &s(&dir.join("m.bin")), "--nodes", "50"],
        "overflow",
    );
    // the limit itself is fine, and learning there gives finite lengths
    let ok = write(
        &dir,
        "ok.toml",
        &r2_scene("[-1e100, -1e100]", "[1e100, 1e100]", ""),
    );
    let o = viaroad(&["build", &ok, "-o", &s(&dir.join("ok.bin")), "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // and the library refuses such a space whoever builds it
    assert!(viaroad::space::Space::euclidean(vec![-1e308, 0.0], vec![1e308, 1.0]).is_err());
}

// ---- row 4: absurd times --------------------------------------------------------------

#[test]
fn time_1e300_is_refused() {
    let dir = temp_dir("time");
    let out = dir.join("o");
    let m = s(&dir.join("m.bin"));
    for t in ["1e300", "1e10", "inf", "NaN", "-1", "0"] {
        let time = format!("--time={t}");
        fails_with(&["build", EXAMPLE, "-o", &m, &time], "--time");
        fails_with(
            &["demo", "--scene", EXAMPLE, "--out", &s(&out), &time],
            "--time",
        );
        fails_with(
            &[
                "bench",
                "local",
                EXAMPLE,
                "--methods",
                "straight",
                "--runs",
                "1",
                "--out",
                &s(&out),
                &time,
            ],
            "time limit",
        );
    }
    // bench local wrote no summary with a panic in it: it wrote nothing at all
    assert!(!out.join("summary.md").exists());
}

// ---- row 5 ----------------------------------------------------------------------------

#[test]
fn demo_queries_u64_max_is_refused() {
    let dir = temp_dir("demo_queries");
    let out = s(&dir.join("o"));
    fails_with(
        &[
            "demo",
            "--scene",
            EXAMPLE,
            "--out",
            &out,
            "--queries",
            "18446744073709551615",
        ],
        "--queries",
    );
    fails_with(
        &[
            "bench",
            "local",
            EXAMPLE,
            "--methods",
            "straight",
            "--runs",
            "1",
            "--out",
            &out,
            "--random-queries",
            "--queries",
            "18446744073709551615",
        ],
        "--queries",
    );
}

// ---- row 6 ----------------------------------------------------------------------------

#[test]
fn huge_generated_disc_scene_is_refused() {
    let dir = temp_dir("gen");
    let out = s(&dir.join("o"));
    fails_with(
        &[
            "bench",
            "local",
            "gen:discs:n=100000000000,r=0.01,seed=1",
            "--methods",
            "straight",
            "--runs",
            "1",
            "--out",
            &out,
        ],
        "n=100000000000",
    );
    fails_with(
        &[
            "bench",
            "local",
            EXAMPLE,
            "--methods",
            "straight",
            "--runs",
            "4294967295",
            "--out",
            &out,
        ],
        "--runs",
    );
    fails_with(
        &[
            "bench",
            "local",
            EXAMPLE,
            "--methods",
            "straight",
            "--growth",
            "1.0000000000001",
            "--out",
            &out,
        ],
        "stages",
    );
}

// ---- row 7 ----------------------------------------------------------------------------

#[test]
fn sampled_resolution_1e_300_is_refused() {
    let dir = temp_dir("res");
    let out = s(&dir.join("o"));
    let local = "sampled:res=1e-300";
    fails_with(&["solve", EXAMPLE, "--local", local], "resolution");
    fails_with(
        &[
            "render",
            EXAMPLE,
            "-o",
            &s(&dir.join("x.svg")),
            "--local",
            local,
        ],
        "resolution",
    );
    fails_with(
        &["demo", "--scene", EXAMPLE, "--out", &out, "--local", local],
        "resolution",
    );
    fails_with(
        &[
            "build",
            EXAMPLE,
            "-o",
            &s(&dir.join("m.bin")),
            "--local",
            local,
        ],
        "resolution",
    );
    fails_with(
        &[
            "bench",
            "local",
            EXAMPLE,
            "--methods",
            local,
            "--runs",
            "1",
            "--out",
            &out,
        ],
        "resolution",
    );
    // the limit itself is accepted by the spec check
    let spec: viaroad::local::LocalSpec = "sampled:res=1e-9".parse().unwrap();
    assert!(viaroad::local::check_local_spec(&spec).is_ok());
}

// ---- row 8 ----------------------------------------------------------------------------

#[test]
fn bench_discs_radius_0_2_is_an_error() {
    let dir = temp_dir("discs");
    let out = s(&dir.join("o"));
    fails_with(
        &[
            "bench",
            "discs",
            "--problems",
            "5",
            "--radius",
            "0.2",
            "--out",
            &out,
        ],
        "smaller radius",
    );
    fails_with(
        &[
            "bench",
            "discs",
            "--problems",
            "18446744073709551615",
            "--out",
            &out,
        ],
        "--problems",
    );
    assert!(!dir.join("o").exists(), "nothing written");
}

// ---- row 9: reading is bounded --------------------------------------------------------

#[cfg(unix)]
#[test]
fn info_refuses_dev_zero() {
    fails_with(&["info", "/dev/zero"], "character device");
    fails_with(&["info", "/dev/urandom"], "character device");
    let dir = temp_dir("info_fifo");
    let fifo = dir.join("f.bin");
    mkfifo(&fifo);
    // opening a FIFO with no writer would block: the refusal comes before the open
    fails_with(&["info", &s(&fifo)], "FIFO");
    fails_with(
        &[
            "query",
            &s(&fifo),
            "--scene",
            EXAMPLE,
            "--from",
            "0.1,0.9",
            "--to",
            "0.9,0.1",
        ],
        "FIFO",
    );
    // scene and query files too
    fails_with(&["solve", "/dev/zero"], "character device");
    fails_with(&["solve", &s(&fifo)], "FIFO");
}

/// A file that announces a small payload but is a terabyte long (sparse: no disk used) is
/// refused from its size; a non-roadmap of that size is refused after its first bytes.
#[test]
fn roadmap_read_stops_at_what_the_header_announces() {
    let dir = temp_dir("sparse");
    let map = dir.join("map.bin");
    let o = viaroad(&["build", EXAMPLE, "-o", &s(&map), "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let len = std::fs::metadata(&map).unwrap().len();
    let f = std::fs::OpenOptions::new().write(true).open(&map).unwrap();
    f.set_len(1 << 40).unwrap();
    drop(f);
    let e = fails_with(&["info", &s(&map)], "unexpected bytes");
    assert!(e.contains(&((1u64 << 40) - len).to_string()), "{e}");
    let junk = dir.join("junk.bin");
    std::fs::File::create(&junk)
        .unwrap()
        .set_len(1 << 40)
        .unwrap();
    fails_with(&["info", &s(&junk)], "not a viaroad roadmap");
}

// ---- row 10: no stale numbered outputs -------------------------------------------------

#[test]
fn stale_numbered_path_files_are_removed() {
    let dir = temp_dir("stale");
    let map = s(&dir.join("map.bin"));
    let o = viaroad(&["build", EXAMPLE, "-o", &map, "--nodes", "100"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let base = dir.join("q.path");
    // an earlier run with three solved queries
    let three = write(
        &dir,
        "three.txt",
        "0.02 0.98 0.98 0.02\n0.02 0.98 0.9 0.9\n0.9 0.9 0.1 0.1\n",
    );
    let o = viaroad(&[
        "query",
        &map,
        "--scene",
        EXAMPLE,
        "--queries",
        &three,
        "--path-out",
        &s(&base),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for k in 1..=3 {
        assert!(dir.join(format!("q-{k}.path")).exists());
    }
    // now two queries, the second with its goal inside the disc: unsolvable
    let two = write(&dir, "two.txt", "0.02 0.98 0.98 0.02\n0.02 0.98 0.3 0.4\n");
    let o = viaroad(&[
        "query",
        &map,
        "--scene",
        EXAMPLE,
        "--queries",
        &two,
        "--path-out",
        &s(&base),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("wrote") && err.contains("q-1.path"), "{err}");
    assert!(err.contains("1 of 2 queries have a path file"), "{err}");
    assert!(
        err.contains("stale") && err.contains("q-2.path") && err.contains("q-3.path"),
        "{err}"
    );
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("q"))
        .collect();
    left.sort();
    assert_eq!(left, vec!["q-1.path".to_string()]);
    // solve with five queries: exactly the numbered files written are present, and the
    // base name (not an output of a run of several queries) is left alone
    std::fs::write(&base, "kept").unwrap();
    let o = viaroad(&[
        "solve",
        CLUTTERED,
        "--local",
        "straight",
        "--path-out",
        &s(&base),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = stderr(&o).matches("wrote").count();
    let files = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with("q-"))
        .count();
    assert_eq!(files, written, "exactly the files written are present");
    assert_eq!(std::fs::read(&base).unwrap(), b"kept");
    // a single query, unsolved by the straight line: its old file goes
    let blocked = write(
        &dir,
        "blocked.toml",
        "[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n\
         [[obstacle]]\ndisc = { center = [0.5, 0.5], radius = 0.1 }\n\
         [[query]]\nstart = [0.02, 0.98]\ngoal = [0.98, 0.02]\n",
    );
    let o = viaroad(&[
        "solve",
        &blocked,
        "--local",
        "straight",
        "--path-out",
        &s(&base),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("0 of 1 queries have a path file"),
        "{}",
        stderr(&o)
    );
    assert!(!base.exists(), "the stale single file is removed");
}

// ---- row 11: stale temporaries of killed saves ------------------------------------------

#[test]
fn killed_save_temporaries_are_cleaned() {
    let dir = temp_dir("temporaries");
    let map = dir.join("map.bin");
    // the pid of a process that has ended
    let mut child = Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .arg("--version")
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let stale = dir.join(format!(".map.bin.{dead}-0.tmp"));
    std::fs::write(&stale, vec![0u8; 3 << 20]).unwrap();
    // a temporary of a running save (this test process), and unrelated files, are kept
    let live = dir.join(format!(".map.bin.{}-0.tmp", std::process::id()));
    std::fs::write(&live, b"busy").unwrap();
    let other = dir.join(format!(".other.bin.{dead}-0.tmp"));
    std::fs::write(&other, b"not ours").unwrap();
    let o = viaroad(&["build", EXAMPLE, "-o", &s(&map), "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stale.exists(), "the dead save's temporary is removed");
    assert!(live.exists() && other.exists());
    assert!(std::fs::read(&map).unwrap().starts_with(b"VIAROADM"));
}

/// A save really killed with SIGKILL while its temporary exists leaves the old roadmap
/// intact, and the next save removes the temporary.
#[cfg(unix)]
#[test]
fn a_save_killed_mid_write_is_cleaned_by_the_next() {
    let dir = temp_dir("sigkill");
    let map = dir.join("map.bin");
    let o = viaroad(&["build", EXAMPLE, "-o", &s(&map), "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(&map).unwrap();
    // a temporary only exists for a moment: emulate the instant of the kill with a child
    // that is stopped by SIGKILL while it holds a temporary of its own name
    let mut child = Command::new("sleep").arg("30").spawn().unwrap();
    let pid = child.id();
    let tmp = dir.join(format!(".map.bin.{pid}-0.tmp"));
    std::fs::write(&tmp, &before[..before.len() / 2]).unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(std::fs::read(&map).unwrap(), before, "old roadmap intact");
    let o = viaroad(&["build", EXAMPLE, "-o", &s(&map), "--nodes", "60"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!tmp.exists());
}

// ---- messages mended ------------------------------------------------------------------

#[test]
fn demo_scene_error_names_the_file_without_the_repository_hint() {
    let dir = temp_dir("demo_msg");
    let e = fails_with(
        &["demo", "--scene", "no-such-scene.toml", "--out", &s(&dir)],
        "no-such-scene.toml",
    );
    assert!(!e.contains("repository"), "{e}");
    let bad = write(
        &dir,
        "bad.toml",
        "[space]\nkind = \"r9z\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n",
    );
    let e = fails_with(&["demo", "--scene", &bad, "--out", &s(&dir)], "r9z");
    assert!(!e.contains("repository"), "{e}");
}

#[test]
fn huge_robot_is_reported_as_too_large() {
    let dir = temp_dir("robot");
    for (kind, he, lo, hi) in [
        ("se2", "[1e300, 1e300]", "[0.0, 0.0]", "[10.0, 10.0]"),
        (
            "se3",
            "[1e300, 1e300, 1e300]",
            "[0.0, 0.0, 0.0]",
            "[10.0, 10.0, 10.0]",
        ),
    ] {
        let scene = write(
            &dir,
            &format!("{kind}.toml"),
            &format!("[space]\nkind = \"{kind}\"\nlower = {lo}\nupper = {hi}\n[robot]\nbox = {{ half_extents = {he} }}\n"),
        );
        let e = fails_with(&["solve", &scene], "robot is too large");
        assert!(!e.contains("rotation scale"), "{e}");
    }
    // an obstacle far out is refused too, not turned into infinities
    let far = write(
        &dir,
        "far.toml",
        "[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n\
         [[obstacle]]\ndisc = { center = [1e300, 0.5], radius = 0.1 }\n",
    );
    fails_with(&["build", &far, "-o", &s(&dir.join("m.bin"))], "obstacle 1");
}

#[test]
fn self_crossing_polygon_is_reported_as_crossing() {
    let dir = temp_dir("bowtie");
    let scene = write(
        &dir,
        "bow.toml",
        "[space]\nkind = \"se2\"\nlower = [0.0, 0.0]\nupper = [10.0, 10.0]\n\
         [robot]\nbox = { half_extents = [0.1, 0.1] }\n\
         [[obstacle]]\npolygon = { vertices = [[1.0, 1.0], [2.0, 2.0], [2.0, 1.0], [1.0, 2.0]] }\n",
    );
    let e = fails_with(&["solve", &scene], "cross");
    assert!(!e.contains("positive area"), "{e}");
    // too few vertices still says so
    let two = write(
        &dir,
        "two.toml",
        "[space]\nkind = \"se2\"\nlower = [0.0, 0.0]\nupper = [10.0, 10.0]\n\
         [robot]\nbox = { half_extents = [0.1, 0.1] }\n\
         [[obstacle]]\npolygon = { vertices = [[1.0, 1.0], [2.0, 2.0]] }\n",
    );
    fails_with(&["solve", &two], "3 vertices");
}

#[test]
fn render_and_query_print_no_status_before_an_error() {
    let dir = temp_dir("status");
    // render: the output's directory cannot exist (a regular file is in the way)
    let blocker = write(&dir, "file", "x");
    fails_with(
        &["render", EXAMPLE, "-o", &format!("{blocker}/x.svg")],
        "file",
    );
    // query: a single query whose start is in collision
    let map = s(&dir.join("map.bin"));
    let o = viaroad(&["build", EXAMPLE, "-o", &map, "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    fails_with(
        &[
            "query", &map, "--scene", EXAMPLE, "--from", "0.3,0.4", "--to", "0.9,0.1",
        ],
        "collision",
    );
}

// ---- decisions ----------------------------------------------------------------------------

/// Zero-radius discs are point obstacles: allowed, reported by the oracle as a degenerate
/// interval, and avoided by solved paths (checked by the independent segment–disc test).
#[test]
fn zero_radius_discs_are_point_obstacles() {
    let dir = temp_dir("zero_radius");
    let scene = write(
        &dir,
        "z.toml",
        "[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n\
         [[obstacle]]\ndisc = { center = [0.5, 0.5], radius = 0.0 }\n\
         [[query]]\nstart = [0.1, 0.5]\ngoal = [0.9, 0.5]\n",
    );
    let o = viaroad(&[
        "probe", &scene, "--from", "0.1,0.5", "--to", "0.9,0.5", "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    let iv = v["intervals"][0].as_array().unwrap();
    assert!((iv[0].as_f64().unwrap() - 0.5).abs() < 1e-12);
    assert!((iv[1].as_f64().unwrap() - 0.5).abs() < 1e-12);
    let o = viaroad(&["solve", &scene, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).lines().next().unwrap()).unwrap();
    assert!(v["solved"].as_bool().unwrap());
    let path: Vec<Vec<f64>> = serde_json::from_value(v["shortened"].clone()).unwrap();
    common::check_disc_path(
        &path,
        &[vec![0.5, 0.5]],
        &[0.0],
        &[0.0, 0.0],
        &[1.0, 1.0],
        1e-12,
    )
    .unwrap();
}

#[test]
fn zero_width_bounds_are_a_scene_error() {
    let dir = temp_dir("flat");
    let scene = write(&dir, "flat.toml", &r2_scene("[0.0, 0.5]", "[1.0, 0.5]", ""));
    fails_with(&["solve", &scene], "no width");
    fails_with(&["build", &scene, "-o", &s(&dir.join("m.bin"))], "no width");
}

#[test]
fn quaternions_are_normalised_with_a_warning() {
    let dir = temp_dir("quat");
    let scene = write(
        &dir,
        "q.toml",
        "[space]\nkind = \"se3\"\nlower = [-5.0, -5.0, -5.0]\nupper = [5.0, 5.0, 5.0]\n\
         [robot]\nbox = { half_extents = [0.1, 0.1, 0.1] }\n\
         [[query]]\nstart = [0, 0, 0, 0, 0, 0, 2]\ngoal = [1, 1, 1, 0, 0, 0, 1]\n",
    );
    let o = viaroad(&["solve", &scene, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning: start of query 1: quaternion of length 2"),
        "{err}"
    );
    assert!(!err.contains("goal of query 1"), "{err}");
    let v: serde_json::Value = serde_json::from_str(stdout(&o).lines().next().unwrap()).unwrap();
    let first: Vec<f64> = serde_json::from_value(v["path"][0].clone()).unwrap();
    assert_eq!(first[3..7], [0.0, 0.0, 0.0, 1.0]);
}

#[test]
fn from_with_empty_field_is_refused() {
    let dir = temp_dir("from");
    let map = s(&dir.join("map.bin"));
    let o = viaroad(&["build", EXAMPLE, "-o", &map, "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    fails_with(
        &[
            "query", &map, "--scene", EXAMPLE, "--from", "0.1,,0.1", "--to", "0.9,0.1",
        ],
        "empty",
    );
    fails_with(
        &["probe", EXAMPLE, "--from", "0.1,0.1", "--to", "0.9,,0.1"],
        "empty",
    );
    // spaces may repeat, and commas with spaces are fine
    let o = viaroad(&[
        "query",
        &map,
        "--scene",
        EXAMPLE,
        "--from",
        "0.1,  0.9",
        "--to",
        "0.9  0.1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn outputs_create_their_directories() {
    let dir = temp_dir("dirs");
    let map = dir.join("a/b/map.bin");
    let o = viaroad(&["build", EXAMPLE, "-o", &s(&map), "--nodes", "50"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(map.exists());
    let path = dir.join("c/d/p.path");
    let o = viaroad(&["solve", EXAMPLE, "--path-out", &s(&path)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(path.exists());
    let svg = dir.join("e/x.svg");
    let o = viaroad(&["render", EXAMPLE, "-o", &s(&svg)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(svg.exists());
}

#[test]
fn nodes_u64_max_without_time_is_refused() {
    let dir = temp_dir("nodes");
    let m = s(&dir.join("m.bin"));
    let e = fails_with(
        &[
            "build",
            EXAMPLE,
            "-o",
            &m,
            "--nodes",
            "18446744073709551615",
        ],
        "--nodes",
    );
    assert!(
        e.contains("--time"),
        "the message says what to do instead: {e}"
    );
    fails_with(
        &[
            "build", EXAMPLE, "-o", &m, "--nodes", "10000001", "--time", "1",
        ],
        "--nodes",
    );
    fails_with(
        &[
            "bench",
            "local",
            EXAMPLE,
            "--methods",
            "straight",
            "--nodes",
            "18446744073709551615",
            "--out",
            &s(&dir),
        ],
        "node cap",
    );
}

// ---- the library's side of the same guarantees ---------------------------------------------

#[cfg(unix)]
#[test]
fn library_refuses_special_files_with_typed_errors() {
    use viaroad::roadmap::persist::RoadmapError;
    use viaroad::roadmap::Roadmap;
    use viaroad::safe_file::FileError;
    let r = Roadmap::load_any_scene(Path::new("/dev/zero"));
    assert!(
        matches!(
            r,
            Err(RoadmapError::File(FileError::NotRegular {
                kind: "character device",
                ..
            }))
        ),
        "{r:?}"
    );
    let r = viaroad::safe_file::write_atomically(Path::new("/dev/null"), |_| Ok(()));
    assert!(matches!(r, Err(FileError::NotRegular { .. })), "{r:?}");
    assert!(is_char_device(Path::new("/dev/null")));
    let r = viaroad::scene::Scene::load(Path::new("/dev/zero"));
    assert!(
        matches!(
            r,
            Err(viaroad::scene::SceneError::File(
                FileError::NotRegular { .. }
            ))
        ),
        "{r:?}"
    );
    // bounds: zero width and overflowing magnitudes are typed space errors
    use viaroad::space::{Space, SpaceError};
    for (lo, hi) in [([0.0, 0.5], [1.0, 0.5]), ([-1e300, 0.0], [1e300, 1.0])] {
        let r = Space::se2(lo, hi, 1.0);
        assert!(matches!(r, Err(SpaceError::Bounds(_))), "{r:?}");
    }
    assert!(Space::se2([-1e100, 0.0], [1e100, 1.0], 1.0).is_ok());
}

fn temp_dir(name: &str) -> common::cli::TempDir {
    common::cli::temp_dir("defects", name)
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    common::cli::write(dir, name, text)
}
