//! Files written and read the careful way: saves never replace a special file, a
//! killed save leaves nothing behind for long, and reads never take more than they should.
//!
//! * [`write_atomically`] writes a temporary file next to the target and renames it over the
//!   target, so a crash leaves either the old or the new content. A target that exists and is
//!   not a regular file (a device such as `/dev/null`, a FIFO, a socket, a directory) is
//!   refused: renaming over it would replace the special file itself. A symbolic link is
//!   followed: the link stays, the file it points to is replaced, its temporary file sits in
//!   that file's directory.
//! * Durability, in this order: the temporary file is `fsync`ed **before** the rename, and its
//!   directory **after** it. Without the first, a file system with delayed allocation (ext4,
//!   XFS) may commit the rename before the data, so that a power loss right after a save
//!   leaves the target empty or half-written: the old roadmap lost and no new one (the
//!   "zero-length file after crash" problem; SQLite's and PostgreSQL's write-ahead logs sync
//!   the same way). Without the second, the rename itself lives only in the page cache and a
//!   power loss can bring back the old name — never a torn file, but a save the user was told
//!   had succeeded. Syncing the directory before the rename would make only the temporary's
//!   name durable, which nothing needs. A failed directory sync is ignored: the new file is in
//!   place by then, and some platforms cannot open a directory to sync it.
//! * A write that fails (a full disk: ENOSPC; a file size limit: EFBIG) is an error naming the
//!   temporary and the cause; the temporary is removed and the target keeps its content.
//!   (`tests/save_faults.rs` fills a 512 KiB tmpfs and a `ulimit -f` to show it.)
//! * Temporaries are named `.NAME.PID-N.tmp`; every save first removes those of its target
//!   whose process no longer runs (a save killed with `kill -9` cannot clean up after itself).
//! * [`open_regular`] and [`read_regular`] refuse non-regular files (`/dev/zero`, FIFOs) and
//!   files above a size limit, so that reading is bounded in time and memory.

use std::fs::{File, Metadata};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Why a file cannot be written or read safely.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The target exists but is a device, FIFO, socket or directory.
    #[error(
        "{path} is a {kind}, not a regular file; viaroad reads and replaces regular files only"
    )]
    NotRegular {
        /// The file named (or the file its symbolic link leads to).
        path: PathBuf,
        /// What it is ("character device", "FIFO" …).
        kind: &'static str,
    },
    /// A symbolic link whose target does not exist.
    #[error("{path} is a symbolic link to a file that does not exist")]
    DanglingLink {
        /// The link.
        path: PathBuf,
    },
    /// The file is larger than what is read of its kind.
    #[error("{path} has {size} bytes, more than the {limit} read from such a file")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        size: u64,
        /// The limit.
        limit: u64,
    },
    /// The operating system refused.
    #[error("cannot {action} {path}: {source}")]
    Io {
        /// What was being done ("read", "create", "replace" …).
        action: &'static str,
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

fn io(action: &'static str, path: &Path) -> impl FnOnce(std::io::Error) -> FileError {
    let path = path.to_path_buf();
    move |source| FileError::Io {
        action,
        path,
        source,
    }
}

/// What kind of non-regular file `meta` describes, for messages.
fn kind_of(meta: &Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_char_device() {
            return "character device";
        }
        if t.is_block_device() {
            return "block device";
        }
        if t.is_fifo() {
            return "FIFO";
        }
        if t.is_socket() {
            return "socket";
        }
    }
    "special file"
}

/// The file a save to `target` replaces: `target` itself, or where its symbolic links lead.
/// Refuses targets that exist and are not regular files, and dangling links.
pub fn resolve_target(target: &Path) -> Result<PathBuf, FileError> {
    let meta = match std::fs::symlink_metadata(target) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(target.to_path_buf()),
        Err(e) => return Err(io("inspect", target)(e)),
    };
    let (path, meta) = if meta.file_type().is_symlink() {
        match std::fs::canonicalize(target) {
            Ok(p) => {
                let m = std::fs::metadata(&p).map_err(io("inspect", &p))?;
                (p, m)
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Err(FileError::DanglingLink {
                    path: target.to_path_buf(),
                })
            }
            Err(e) => return Err(io("follow", target)(e)),
        }
    } else {
        (target.to_path_buf(), meta)
    };
    if !meta.is_file() {
        return Err(FileError::NotRegular {
            path,
            kind: kind_of(&meta),
        });
    }
    Ok(path)
}

/// Where [`write_atomically`] puts the bytes for `target` before renaming: a hidden file next
/// to it, named after it, the process and a counter (so concurrent saves do not collide).
pub fn temp_path(target: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    target.with_file_name(format!(
        ".{}.{}-{n}.tmp",
        file_name(target),
        std::process::id()
    ))
}

fn file_name(target: &Path) -> String {
    target
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "roadmap".into())
}

/// The process id in a temporary file name of `target` ([`temp_path`]), if `name` is one.
fn temp_owner(target: &Path, name: &str) -> Option<u32> {
    let rest = name
        .strip_prefix(&format!(".{}.", file_name(target)))?
        .strip_suffix(".tmp")?;
    let (pid, n) = rest.split_once('-')?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !digits(pid) || !digits(n) {
        return None;
    }
    pid.parse().ok()
}

/// Whether process `pid` still runs (on platforms that cannot tell: yes, so nothing of a
/// running save is ever removed).
fn process_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else {
            return true;
        };
        if pid <= 0 {
            return true;
        }
        // SAFETY: kill with signal 0 sends nothing; it only asks whether the process exists.
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
    }
    #[cfg(not(unix))]
    {
        true
    }
}

/// Removes the temporaries of saves to `target` whose process no longer runs (left by a save
/// that was killed), and returns them. Only regular files named exactly like [`temp_path`]'s
/// are touched; failures to list or remove are ignored (this is cleaning, not saving).
pub fn clean_stale_temporaries(target: &Path) -> Vec<PathBuf> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut removed = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(|n| temp_owner(target, n)) else {
            continue;
        };
        let regular = entry.file_type().is_ok_and(|t| t.is_file());
        if regular && !process_alive(pid) && std::fs::remove_file(entry.path()).is_ok() {
            removed.push(entry.path());
        }
    }
    removed
}

/// Writes a file the way a crash cannot half-do (module docs): refuses special targets,
/// cleans stale temporaries, lets `write` fill a new temporary file in the target's directory,
/// `fsync`s it *before* renaming it over the target (so no rename publishes unwritten data),
/// then `fsync`s the directory *after* (so the rename survives a power loss) where the platform
/// allows. On any error the temporary file is removed and the target is untouched. Returns
/// the file written (the target, or where its symbolic link leads).
pub fn write_atomically(
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<PathBuf, FileError> {
    let target = resolve_target(target)?;
    clean_stale_temporaries(&target);
    let tmp = temp_path(&target);
    // create_new: never follow or reuse whatever already sits at the temporary's name
    let mut file = File::options()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .map_err(io("create", &tmp))?;
    let written = (|| {
        let mut buffered = std::io::BufWriter::new(&mut file);
        write(&mut buffered)?;
        buffered.flush()?;
        drop(buffered);
        file.sync_all()
    })()
    .map_err(io("write", &tmp));
    drop(file);
    let renamed =
        written.and_then(|()| std::fs::rename(&tmp, &target).map_err(io("replace", &target)));
    if let Err(e) = renamed {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    // Make the rename itself durable (module docs: the data was synced before it, the directory
    // entry is synced after it); failing here leaves the new file in place, which is fine.
    if let Some(dir) = target.parent() {
        let dir = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        if let Ok(d) = File::open(dir) {
            let _ = d.sync_all();
        }
    }
    Ok(target)
}

/// Opens `path` for reading if it is a regular file (after following symbolic links), with
/// its size. Opening a FIFO would block and `/dev/zero` never ends, so both are refused
/// before they are opened.
pub fn open_regular(path: &Path) -> Result<(File, u64), FileError> {
    let meta = std::fs::metadata(path).map_err(io("read", path))?;
    if !meta.is_file() {
        return Err(FileError::NotRegular {
            path: path.to_path_buf(),
            kind: kind_of(&meta),
        });
    }
    let file = File::open(path).map_err(io("read", path))?;
    // the file may have been swapped between the two calls: ask the open handle too
    let meta = file.metadata().map_err(io("read", path))?;
    if !meta.is_file() {
        return Err(FileError::NotRegular {
            path: path.to_path_buf(),
            kind: kind_of(&meta),
        });
    }
    Ok((file, meta.len()))
}

/// Reads a whole regular file of at most `limit` bytes.
pub fn read_regular(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    let (file, size) = open_regular(path)?;
    if size > limit {
        return Err(FileError::TooLarge {
            path: path.to_path_buf(),
            size,
            limit,
        });
    }
    let mut bytes = Vec::with_capacity(size as usize);
    // take: a file that grows while it is read is still read only up to the limit
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(io("read", path))?;
    if bytes.len() as u64 > limit {
        return Err(FileError::TooLarge {
            path: path.to_path_buf(),
            size: bytes.len() as u64,
            limit,
        });
    }
    Ok(bytes)
}

/// [`read_regular`] as UTF-8 text, limited to [`crate::limits::MAX_TEXT_FILE_BYTES`].
pub fn read_text(path: &Path) -> Result<String, FileError> {
    read_text_within(path, crate::limits::MAX_TEXT_FILE_BYTES)
}

/// [`read_regular`] as UTF-8 text of at most `limit` bytes.
pub fn read_text_within(path: &Path, limit: u64) -> Result<String, FileError> {
    let bytes = read_regular(path, limit)?;
    String::from_utf8(bytes).map_err(|e| FileError::Io {
        action: "read",
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporaries_are_recognised_by_name() {
        let t = Path::new("dir/x.bin");
        assert_eq!(temp_owner(t, ".x.bin.123-0.tmp"), Some(123));
        assert_eq!(temp_owner(t, ".x.bin.123-17.tmp"), Some(123));
        for other in [
            ".x.bin.tmp",
            ".y.bin.1-0.tmp",
            ".x.bin.a-0.tmp",
            ".x.bin.1-.tmp",
            "x.bin",
        ] {
            assert_eq!(temp_owner(t, other), None, "{other}");
        }
        let made = temp_path(t);
        let name = made.file_name().unwrap().to_str().unwrap();
        assert_eq!(temp_owner(t, name), Some(std::process::id()));
    }
}
