//! Files written so that an interruption never leaves a half-written one, and scratch
//! folders that remove themselves.
//!
//! Standard library only: a temporary-file crate here would pull in terminal features
//! that differ between the CLI's build and the Python extension's, so `cargo run`,
//! `cargo test` and `pip install ./python` could not share compiled crates.

use crate::error::{io_err, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A name no other call in this process (nor, with the process id, another process)
/// has used: `.tmp-<pid>-<counter>-<tag>`. The leading `.tmp` keeps such files out of
/// listings of results and out of version control (see the repository's .gitignore).
fn unique_name(tag: &str) -> String {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    format!(".tmp-{}-{n}-{tag}", std::process::id())
}

/// Writes `text` to `path` atomically: into a new file in the same folder, then renamed
/// over `path` (a rename within one file system replaces the target in one step).
pub(crate) fn write_atomic(path: &Path, text: &str) -> Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let tmp = dir.join(unique_name("write"));
    let written = std::fs::write(&tmp, text.as_bytes())
        .map_err(io_err(format!("writing {}", tmp.display())))
        .and_then(|()| {
            std::fs::rename(&tmp, path).map_err(io_err(format!("saving {}", path.display())))
        });
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// A new folder under the system's temporary folder, removed with its contents on drop.
pub(crate) struct ScratchDir(PathBuf);

impl ScratchDir {
    pub(crate) fn new() -> Result<Self> {
        let path = std::env::temp_dir().join(unique_name("mrdw"));
        std::fs::create_dir(&path).map_err(io_err(format!("creating {}", path.display())))?;
        Ok(ScratchDir(path))
    }

    pub(crate) fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_and_leaves_no_scratch_file() {
        let dir = ScratchDir::new().unwrap();
        let target = dir.path().join("a.json");
        write_atomic(&target, "one").unwrap();
        write_atomic(&target, "two").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "two");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "only the target remains");
        let kept = dir.path().to_path_buf();
        drop(dir);
        assert!(!kept.exists(), "the scratch folder is removed on drop");
    }

    #[test]
    fn a_failed_write_reports_the_path_and_leaves_nothing() {
        let dir = ScratchDir::new().unwrap();
        let missing = dir.path().join("no-such-folder").join("a.json");
        let err = write_atomic(&missing, "x").unwrap_err().to_string();
        assert!(err.contains("no-such-folder"), "{err}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
