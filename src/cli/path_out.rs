//! `--path-out`: solved paths written as OMPL state files, so that OMPL's tools (and the peer's
//! `check` mode) can validate or replay them without conversion.
//!
//! No stale output is ever left: before the first path is written, the files an
//! earlier run may have left under the same name (every numbered `base-K.ext`, and for a
//! single query the base file) are removed, so the files present afterwards are exactly those this run wrote
//! — one per solved query — and [`PathOut::finish`] lists them.

use std::path::{Path, PathBuf};
use viaroad::scene::ompl_cfg;
use viaroad::space::Config;

/// The file for query `index` (0-based) of `total`: `base` itself for a single query, otherwise
/// `base` with `-K` (1-based) before the extension (`out.path` → `out-1.path`, `out-2.path`).
pub fn file_for(base: &Path, index: usize, total: usize) -> PathBuf {
    if total <= 1 {
        return base.to_path_buf();
    }
    let stem = stem_of(base);
    let name = match base.extension() {
        Some(ext) => format!("{stem}-{}.{}", index + 1, ext.to_string_lossy()),
        None => format!("{stem}-{}", index + 1),
    };
    base.with_file_name(name)
}

fn stem_of(base: &Path) -> String {
    base.file_stem()
        .map_or_else(|| "path".into(), |s| s.to_string_lossy().into_owned())
}

/// Whether `name` is one of the numbered files of `base` (`stem-K.ext`, K ≥ 1 without
/// leading zeros).
fn is_numbered(base: &Path, name: &str) -> bool {
    let rest = match base.extension() {
        Some(ext) => name.strip_suffix(&format!(".{}", ext.to_string_lossy())),
        None => Some(name),
    };
    let Some(k) = rest.and_then(|r| r.strip_prefix(&format!("{}-", stem_of(base)))) else {
        return false;
    };
    !k.is_empty() && !k.starts_with('0') && k.bytes().all(|b| b.is_ascii_digit())
}

/// The path files of one run.
pub struct PathOut {
    base: PathBuf,
    total: usize,
    written: Vec<PathBuf>,
    removed: Vec<PathBuf>,
}

impl PathOut {
    /// Prepares writing the paths of `total` queries under `base`: refuses a special file as
    /// `base` and a directory no file can be created in, creates missing directories (as
    /// `build -o` does) and removes the regular files earlier runs left under the names this
    /// run may write.
    pub fn new(base: &Path, total: usize) -> anyhow::Result<PathOut> {
        viaroad::safe_file::resolve_target(base)?;
        // a directory no file can be created in is refused now, not at the first answer
        super::output::check_writable(&file_for(base, 0, total))?;
        let mut removed = Vec::new();
        let mut remove = |p: PathBuf| {
            let regular = std::fs::symlink_metadata(&p).is_ok_and(|m| m.is_file());
            if regular && std::fs::remove_file(&p).is_ok() {
                removed.push(p);
            }
        };
        if total <= 1 {
            // the single query's own file; with several queries `base` itself is not an
            // output, so it is left alone
            remove(base.to_path_buf());
        }
        let dir = match base.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        if let Ok(entries) = std::fs::read_dir(dir) {
            for e in entries.flatten() {
                if let Some(n) = e.file_name().to_str().filter(|n| is_numbered(base, n)) {
                    // named like file_for's names, so that finish can tell them apart
                    remove(base.with_file_name(n));
                }
            }
        }
        Ok(PathOut {
            base: base.to_path_buf(),
            total,
            written: Vec::new(),
            removed,
        })
    }

    /// Writes one solved path (nothing for an unsolved query) and says where on stderr.
    pub fn write(&mut self, index: usize, path: &[Config]) -> anyhow::Result<()> {
        if path.is_empty() {
            return Ok(());
        }
        let file = file_for(&self.base, index, self.total);
        ompl_cfg::write_states(&file, path)?;
        eprintln!("wrote {} ({} states)", file.display(), path.len());
        self.written.push(file);
        Ok(())
    }

    /// Says on stderr how many path files were written and which stale ones were removed.
    pub fn finish(self) {
        let names = |v: &[PathBuf]| {
            v.iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let stale: Vec<PathBuf> = self
            .removed
            .into_iter()
            .filter(|p| !self.written.contains(p))
            .collect();
        if !stale.is_empty() {
            eprintln!(
                "removed stale path files of an earlier run: {}",
                names(&stale)
            );
        }
        eprintln!(
            "{} of {} queries have a path file{}",
            self.written.len(),
            self.total,
            if self.written.len() < self.total {
                " (unsolved queries have none)"
            } else {
                ""
            }
        );
    }
}

#[cfg(test)]
mod tests {
    use super::{file_for, is_numbered};
    use std::path::{Path, PathBuf};

    #[test]
    fn several_queries_get_numbered_files() {
        let b = Path::new("dir/out.path");
        assert_eq!(file_for(b, 0, 1), PathBuf::from("dir/out.path"));
        assert_eq!(file_for(b, 0, 3), PathBuf::from("dir/out-1.path"));
        assert_eq!(file_for(b, 2, 3), PathBuf::from("dir/out-3.path"));
        assert_eq!(file_for(Path::new("p"), 1, 2), PathBuf::from("p-2"));
    }

    #[test]
    fn numbered_names_are_recognised_exactly() {
        let b = Path::new("dir/out.path");
        assert!(is_numbered(b, "out-1.path"));
        assert!(is_numbered(b, "out-12.path"));
        for other in [
            "out.path",
            "out-0.path",
            "out-01.path",
            "out-x.path",
            "out-1.txt",
            "o-1.path",
        ] {
            assert!(!is_numbered(b, other), "{other}");
        }
        assert!(is_numbered(Path::new("p"), "p-3"));
    }
}
