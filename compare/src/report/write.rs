//! The report folder on disk: claimed under a lock, written into a staging folder beside
//! it and swapped into place, so that a failed or interrupted run never leaves a partial
//! report and never deletes a user's files.
//!
//! Rules:
//! - a destination may be replaced only if it does not exist, is an empty folder, or is
//!   a folder `mrdw` wrote holding nothing but what it wrote: the marker file
//!   [`MARKER`] lists the entries (the manifest; reports of earlier versions: the
//!   `files` of their `summary.json`), and a file a user added inside is never deleted:
//!   the run is refused with one line naming it;
//! - `--out` may be a symbolic link to a folder: the folder it points to is the
//!   destination (the link keeps pointing to the new report);
//! - the claim takes an advisory lock (`.<name>.mrdw-lock` beside the folder) for the
//!   whole run, so two runs into one folder (or one sweep work folder) cannot race: the
//!   second is told plainly that another run holds it. The lock file is removed when
//!   the run ends (a lock taken on a file that was meanwhile removed is retried);
//! - staging (`.<name>.mrdw-staging-<pid>`) and swapped-out (`.<name>.mrdw-old-<pid>`)
//!   folders are removed on error, and stale ones left by a killed run are removed by
//!   the next run of the same report (under the lock, so they cannot be in use).

use super::csv::csv_text;
use super::plot::render;
use super::{Provenance, Report};
use crate::error::{io_err, CompareError, Result};
use serde_json::json;
use std::fs::File;
use std::path::{Path, PathBuf};

/// Marker file in every folder `mrdw` writes (reports and shard folders).
pub const MARKER: &str = ".mrdw";

/// A claimed destination folder: validated, locked, with stale leftovers removed.
#[derive(Debug)]
pub struct Destination {
    dir: PathBuf,
    parent: PathBuf,
    name: String,
    lock_path: PathBuf,
    _lock: File,
}

impl Drop for Destination {
    fn drop(&mut self) {
        // Unlinked while still locked: a run waiting on this file retries on a new one.
        let _ = std::fs::remove_file(&self.lock_path);
    }
}

impl Destination {
    /// Claims `dir` for a run of `mrdw` (see the module rules).
    pub fn claim(dir: &Path) -> Result<Self> {
        let abs = std::path::absolute(dir).map_err(io_err(format!("--out {}", dir.display())))?;
        let abs = resolve_link(&normalise(&abs), dir)?;
        let (parent, name) = match (abs.parent(), abs.file_name().and_then(|n| n.to_str())) {
            (Some(p), Some(n)) => (p.to_path_buf(), n.to_string()),
            _ => {
                return Err(CompareError::Scene(format!(
                    "--out {}: not a folder that can be created or replaced",
                    dir.display()
                )))
            }
        };
        check_replaceable(&abs, dir)?;
        std::fs::create_dir_all(&parent)
            .map_err(io_err(format!("creating {}", parent.display())))?;
        let lock_path = parent.join(format!(".{name}.mrdw-lock"));
        let lock = take_lock(&lock_path, dir)?;
        let d = Self {
            dir: abs,
            parent,
            name,
            lock_path,
            _lock: lock,
        };
        d.remove_stale();
        Ok(d)
    }

    /// The folder itself (absolute).
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Checkpoints of resumable outputs live here, beside the report (`<name>.work/`).
    pub fn work_root(&self) -> PathBuf {
        self.parent.join(format!("{}.work", self.name))
    }

    fn staging(&self, what: &str) -> PathBuf {
        self.parent
            .join(format!(".{}.mrdw-{what}-{}", self.name, std::process::id()))
    }

    /// Removes staging and swapped-out folders of this destination left by a killed
    /// run (we hold the lock, so no other run is using them).
    fn remove_stale(&self) {
        let prefixes = [
            format!(".{}.mrdw-staging-", self.name),
            format!(".{}.mrdw-old-", self.name),
        ];
        if let Ok(entries) = std::fs::read_dir(&self.parent) {
            for e in entries.flatten() {
                let n = e.file_name().to_string_lossy().into_owned();
                if prefixes.iter().any(|p| n.starts_with(p.as_str())) {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
        }
    }

    /// Writes `report` into the folder (created or replaced as a whole); returns the
    /// files written.
    pub fn write_report(
        &self,
        report: &Report,
        prov: &Provenance,
        wall_time_s: f64,
    ) -> Result<Vec<PathBuf>> {
        self.write_with(|tmp| stage_report(tmp, report, prov, wall_time_s))
    }

    /// Fills a fresh staging folder with `fill` and swaps it into place.
    pub fn write_with(
        &self,
        fill: impl FnOnce(&Path) -> Result<Vec<String>>,
    ) -> Result<Vec<PathBuf>> {
        let tmp = self.staging("staging");
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir(&tmp).map_err(io_err(format!("creating {}", tmp.display())))?;
        let files = fill(&tmp)
            .and_then(|files| {
                std::fs::write(tmp.join(MARKER), marker_text(&files))
                    .map_err(io_err(format!("writing {MARKER}")))?;
                self.swap_in(&tmp)?;
                Ok(files)
            })
            .inspect_err(|_| {
                let _ = std::fs::remove_dir_all(&tmp);
            })?;
        Ok(files.into_iter().map(|f| self.dir.join(f)).collect())
    }

    /// Moves an existing folder aside, renames the staged one in, removes the old one.
    fn swap_in(&self, staged: &Path) -> Result<()> {
        if self.dir.exists() {
            // Checked again under the lock: the folder may have changed since the claim.
            check_replaceable(&self.dir, &self.dir)?;
            let old = self.staging("old");
            std::fs::rename(&self.dir, &old)
                .map_err(io_err(format!("moving aside {}", self.dir.display())))?;
            std::fs::rename(staged, &self.dir)
                .map_err(io_err(format!("renaming into {}", self.dir.display())))?;
            let _ = std::fs::remove_dir_all(&old);
        } else {
            std::fs::rename(staged, &self.dir)
                .map_err(io_err(format!("renaming into {}", self.dir.display())))?;
        }
        Ok(())
    }
}

/// Locks `path` (created if missing) without waiting; `dir` names the folder in
/// messages.
fn take_lock(path: &Path, dir: &Path) -> Result<File> {
    for _ in 0..100 {
        let lock = File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)
            .map_err(io_err(format!("opening {}", path.display())))?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(CompareError::Busy(format!(
                    "{} is in use by another mrdw run (lock {}); wait for it to finish or \
                     choose another --out",
                    dir.display(),
                    path.display()
                )))
            }
            Err(std::fs::TryLockError::Error(e)) => {
                return Err(io_err(format!("locking {}", path.display()))(e))
            }
        }
        // The holder may have removed the file between our open and our lock: the lock
        // counts only if the path still names the file we locked.
        if same_file(path, &lock) {
            return Ok(lock);
        }
    }
    Err(CompareError::Busy(format!(
        "{}: could not take the lock {}",
        dir.display(),
        path.display()
    )))
}

#[cfg(unix)]
fn same_file(path: &Path, file: &File) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(path), file.metadata()) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(path: &Path, _: &File) -> bool {
    path.exists()
}

/// The folder a symbolic link `abs` points to (links to links followed); `abs` itself
/// when it is not a link. A link to anything but a folder is refused.
fn resolve_link(abs: &Path, given: &Path) -> Result<PathBuf> {
    match std::fs::symlink_metadata(abs) {
        Ok(m) if m.file_type().is_symlink() => match std::fs::canonicalize(abs) {
            Ok(target) if target.is_dir() => Ok(target),
            Ok(target) => Err(CompareError::Scene(format!(
                "--out {}: a link to {}, which is not a folder; give a folder path",
                given.display(),
                target.display()
            ))),
            Err(_) => Err(CompareError::Scene(format!(
                "--out {}: a link to a path that does not exist; create the folder it names or give another --out",
                given.display()
            ))),
        },
        _ => Ok(abs.to_path_buf()),
    }
}

/// `a/./b/../c` -> `a/c` without touching the file system (symlinks are kept as given).
fn normalise(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// Whether `abs` may be replaced by a run (`given` is the path as the user wrote it).
fn check_replaceable(abs: &Path, given: &Path) -> Result<()> {
    let meta = match std::fs::symlink_metadata(abs) {
        Ok(m) => m,
        Err(_) => return Ok(()), // does not exist
    };
    if !meta.is_dir() {
        return Err(CompareError::Scene(format!(
            "--out {}: a file of that name exists; give a folder path (mrdw never replaces \
             a file)",
            given.display()
        )));
    }
    let entries: Vec<String> = std::fs::read_dir(abs)
        .map_err(io_err(format!("reading {}", given.display())))?
        .map(|e| e.map(|e| e.file_name().to_string_lossy().into_owned()))
        .collect::<std::io::Result<_>>()
        .map_err(io_err(format!("reading {}", given.display())))?;
    if entries.is_empty() {
        return Ok(());
    }
    let Some(written) = manifest(abs) else {
        return Err(CompareError::Scene(format!(
            "--out {}: the folder exists and holds files mrdw did not write; give a new or empty \
             folder (a report folder of mrdw is replaced as a whole)",
            given.display()
        )));
    };
    let mut foreign: Vec<&String> = entries
        .iter()
        .filter(|e| e.as_str() != MARKER && !written.contains(e))
        .collect();
    if foreign.is_empty() {
        return Ok(());
    }
    foreign.sort();
    let shown: Vec<&str> = foreign.iter().take(5).map(|s| s.as_str()).collect();
    Err(CompareError::Scene(format!(
        "--out {}: this report folder of mrdw also holds files mrdw did not write ({}{}); \
         the report replaces the folder as a whole, so move them out or give another --out",
        given.display(),
        shown.join(", "),
        if foreign.len() > 5 {
            format!(" and {} more", foreign.len() - 5)
        } else {
            String::new()
        }
    )))
}

/// The entries mrdw wrote into `dir`, if mrdw wrote it: the manifest in [`MARKER`];
/// for reports of earlier versions, the `files` of `summary.json` (whose `tool` is mrdw)
/// or a shard folder's fixed entries.
fn manifest(dir: &Path) -> Option<Vec<String>> {
    let summary_files = || -> Option<Vec<String>> {
        let t = std::fs::read_to_string(dir.join("summary.json")).ok()?;
        let v: serde_json::Value = serde_json::from_str(&t).ok()?;
        if !v["tool"].as_str()?.starts_with("mrdw ") {
            return None;
        }
        let mut files: Vec<String> = v["files"]
            .as_array()?
            .iter()
            .filter_map(|f| f.as_str().map(String::from))
            .collect();
        files.push("summary.json".into());
        Some(files)
    };
    match std::fs::read_to_string(dir.join(MARKER)) {
        Ok(text) if text.starts_with(MANIFEST_HEADER) => Some(
            text.lines()
                .skip(1)
                .filter(|l| !l.is_empty())
                .map(String::from)
                .collect(),
        ),
        Ok(_) => {
            summary_files().or_else(|| Some(SHARD_ENTRIES.iter().map(|s| s.to_string()).collect()))
        }
        Err(_) => summary_files(),
    }
}

/// The first line of [`MARKER`]; the entries mrdw wrote follow, one per line.
const MANIFEST_HEADER: &str =
    "written by mrdw: it replaces this folder as a whole while it holds only these entries:";

/// What a shard folder holds besides [`MARKER`].
pub(crate) const SHARD_ENTRIES: [&str; 3] = ["scene.toml", "shard.json", "work"];

/// The text of [`MARKER`] for a folder of `entries` (names, or paths whose first
/// component is the entry).
pub(crate) fn marker_text<S: AsRef<str>>(entries: &[S]) -> String {
    let mut top: Vec<&str> = entries
        .iter()
        .map(|e| e.as_ref().split('/').next().unwrap_or(""))
        .filter(|e| !e.is_empty())
        .collect();
    top.sort_unstable();
    top.dedup();
    let mut text = format!("{MANIFEST_HEADER}\n");
    for e in top {
        text.push_str(e);
        text.push('\n');
    }
    text
}

/// Writes the report's files into `dir`; returns their names.
fn stage_report(
    dir: &Path,
    report: &Report,
    prov: &Provenance,
    wall_time_s: f64,
) -> Result<Vec<String>> {
    let mut files = Vec::new();
    for t in report.tables() {
        let name = format!("{}.csv", t.name);
        std::fs::write(dir.join(&name), csv_text(t, prov)?)
            .map_err(io_err(format!("writing {name}")))?;
        files.push(name);
    }
    for f in report.figures() {
        let name = format!("{}.png", f.name);
        render(f, &dir.join(&name))?;
        files.push(name);
    }
    for (name, bytes) in report.files() {
        std::fs::write(dir.join(name), bytes).map_err(io_err(format!("writing {name}")))?;
        files.push(name.clone());
    }
    let outputs: Vec<serde_json::Value> = report
        .sections
        .iter()
        .zip(&report.plan.outputs)
        .map(|(s, (_, declared))| {
            json!({
                "label": s.label,
                "kind": s.kind,
                "declared": declared.iter().map(|st| st.name()).collect::<Vec<_>>(),
                "stages": s.stages().iter().map(|st| st.name()).collect::<Vec<_>>(),
                "stage_seconds": s.ran.iter().map(|(_, t)| *t).collect::<Vec<_>>(),
            })
        })
        .collect();
    let summary = json!({
        "tool": prov.tool,
        "scene": prov.scene_name,
        "scene_origin": prov.scene_origin,
        "seed": prov.seed,
        "stages": report.stages(),
        "outputs": outputs,
        "results": report.results(),
        "warnings": report.warnings(),
        "failures": report.failures(),
        "files": files,
        "wall_time_s": wall_time_s,
    });
    let text = serde_json::to_string_pretty(&summary)
        .map_err(|e| CompareError::Internal(e.to_string()))?;
    std::fs::write(dir.join("summary.json"), text + "\n")
        .map_err(io_err("writing summary.json"))?;
    files.push("summary.json".into());
    Ok(files)
}
