//! Running the `viaroad` binary as users meet it, shared by the command-line test suites.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `viaroad ARGS` from the repository's root.
pub fn viaroad(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// What a run printed on stdout.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// What a run printed on stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A failure as the project promises it: exit status 1, no panic, exactly one `error:` line,
/// naming `needle` (warnings may precede it). Returns the line.
pub fn fails_with(args: &[&str], needle: &str) -> String {
    error_line(args, &viaroad(args), needle)
}

fn error_line(args: &[&str], o: &Output, needle: &str) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(lines.len(), 1, "{args:?}: {err}");
    assert!(
        lines[0].contains(needle),
        "{args:?}: expected `{needle}` in `{}`",
        lines[0]
    );
    lines[0].to_string()
}

/// [`fails_with`], and the `error:` line is all the run printed: nothing on stdout, no other
/// line on stderr (no status line before the error).
pub fn fails_alone_with(args: &[&str], needle: &str) -> String {
    let o = viaroad(args);
    let line = error_line(args, &o, needle);
    let err = stderr(&o);
    assert_eq!(
        err.lines().count(),
        1,
        "{args:?}: one line expected, got: {err}"
    );
    assert_eq!(stdout(&o), "", "{args:?}: status printed before the error");
    line
}

/// A fresh directory for one test: `suite` and `name` keep tests apart, the process id keeps
/// concurrent runs apart.
pub fn temp_dir(suite: &str, name: &str) -> TempDir {
    let d = std::env::temp_dir().join(format!("viaroad-{suite}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    TempDir(d)
}

/// A test's own directory ([`temp_dir`]), removed when the test ends; kept, and named on
/// stderr, when it ends in a panic, so that a failure's files can be looked at.
pub struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("test files kept in {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// Writes `text` to `dir/name` and returns the path as a string for the command line.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}
