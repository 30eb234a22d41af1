//! `--path-out`: solved paths written as OMPL state files, so that OMPL's tools (and the peer's
//! `check` mode) can validate or replay them without conversion.

use std::path::{Path, PathBuf};
use viaroad::scene::ompl_cfg;
use viaroad::space::Config;

/// The file for query `index` (0-based) of `total`: `base` itself for a single query, otherwise
/// `base` with `-K` (1-based) before the extension (`out.path` → `out-1.path`, `out-2.path`).
pub fn file_for(base: &Path, index: usize, total: usize) -> PathBuf {
    if total <= 1 {
        return base.to_path_buf();
    }
    let stem = base
        .file_stem()
        .map_or_else(|| "path".into(), |s| s.to_string_lossy().into_owned());
    let name = match base.extension() {
        Some(ext) => format!("{stem}-{}.{}", index + 1, ext.to_string_lossy()),
        None => format!("{stem}-{}", index + 1),
    };
    base.with_file_name(name)
}

/// Writes one solved path (nothing for an unsolved query) and says where on stderr.
pub fn write(base: &Path, index: usize, total: usize, path: &[Config]) -> anyhow::Result<()> {
    if path.is_empty() {
        return Ok(());
    }
    let file = file_for(base, index, total);
    ompl_cfg::write_states(&file, path)?;
    eprintln!("wrote {} ({} states)", file.display(), path.len());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::file_for;
    use std::path::{Path, PathBuf};

    #[test]
    fn several_queries_get_numbered_files() {
        let b = Path::new("dir/out.path");
        assert_eq!(file_for(b, 0, 1), PathBuf::from("dir/out.path"));
        assert_eq!(file_for(b, 0, 3), PathBuf::from("dir/out-1.path"));
        assert_eq!(file_for(b, 2, 3), PathBuf::from("dir/out-3.path"));
        assert_eq!(file_for(Path::new("p"), 1, 2), PathBuf::from("p-2"));
    }
}
