//! Files and stdout written by the sub-commands: every file goes through
//! [`viaroad::safe_file::write_atomically`] (special files are refused, never replaced; a
//! killed save's temporaries are cleaned by the next), and missing parent directories are
//! created for every output alike (`build -o`, `--path-out`, `render -o`; see the README).

use anyhow::Context;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Creates the missing directories above `file`.
pub fn create_parent(file: &Path) -> anyhow::Result<()> {
    if let Some(dir) = file.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    Ok(())
}

/// Writes `bytes` to `file` atomically (parents created); returns the file written (where a
/// symbolic link leads).
pub fn save(file: &Path, bytes: &[u8]) -> anyhow::Result<PathBuf> {
    create_parent(file)?;
    Ok(viaroad::safe_file::write_atomically(file, |w| {
        w.write_all(bytes)
    })?)
}

/// Refuses, before a long run, a file that could not be saved at its end: a special file, or
/// one in a directory where no file can be created (read-only, or under a regular file). A
/// save writes a temporary file beside the target and renames it, so that is what is tried:
/// missing parent directories are created (as the save would), a temporary file is created
/// and removed again.
pub fn check_writable(file: &Path) -> anyhow::Result<()> {
    let target = viaroad::safe_file::resolve_target(file)?;
    create_parent(&target)?;
    let probe = viaroad::safe_file::temp_path(&target);
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .with_context(|| {
            format!(
                "cannot save {}: no file can be created in {}",
                file.display(),
                dir.display()
            )
        })?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Refuses, before a long run, the outputs `names` in `dir` that could not be saved at its end
/// (special files).
pub fn check_targets(dir: &Path, names: &[&str]) -> anyhow::Result<()> {
    for name in names {
        viaroad::safe_file::resolve_target(&dir.join(name))?;
    }
    Ok(())
}

/// Ignores SIGPIPE again (Rust's default, undone in `main`): for commands that write to
/// their children's pipes, where a child that died must be an error, not the parent's end.
pub fn ignore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition; done before the command starts threads.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_IGN);
    }
}

/// Prints `text` and a newline on stdout; a closed pipe is not an error (the reader has
/// what it wanted), other failures are.
pub fn print_quietly(text: &str) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(e).context("cannot write to stdout")
        }
        _ => Ok(()),
    }
}
