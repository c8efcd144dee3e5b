//! Running a scene: plan -> execute -> report.
//!
//! [`plan`] asks every output for its stages; [`run_in`] runs the outputs in order, each
//! into its own [`Section`], and checks that the stages each one ran are exactly those
//! it declared (a mismatch is an internal error: the recorded plan is the true one);
//! [`run_to_folder`] claims the report folder (lock, safety checks), runs, writes the
//! report atomically and removes the checkpoints of resumable outputs.

use crate::error::{CompareError, Result};
use crate::output::{Env, RunControl};
use crate::plan::Plan;
use crate::report::write::Destination;
use crate::report::{Provenance, Report, Section};
use crate::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use crate::report::tool_version;

/// The stages every output of `scene` will run.
pub fn plan(scene: &Scene) -> Plan {
    Plan {
        outputs: scene
            .outputs
            .iter()
            .map(|e| (e.label.clone(), e.output.stages(&scene.context)))
            .collect(),
    }
}

/// Runs every output of `scene` (checkpoints of resumable outputs under `work_root`).
pub fn run_in(scene: &Scene, work_root: &Path, control: &RunControl) -> Result<Report> {
    let mut report = Report {
        plan: plan(scene),
        sections: Vec::new(),
    };
    let env = Env {
        ctx: &scene.context,
        work_root,
        control,
    };
    for (i, e) in scene.outputs.iter().enumerate() {
        let mut sec = Section::new(e.kind, e.label.clone());
        e.output
            .run(&env, &mut sec)
            .map_err(|err| err.within(&format!("outputs[{i}] ({})", e.kind)))?;
        let declared = &report.plan.outputs[i].1;
        if sec.stages() != *declared {
            return Err(CompareError::Internal(format!(
                "outputs[{i}] ({}) declared stages {declared:?} but ran {:?}",
                e.kind,
                sec.stages()
            )));
        }
        report.sections.push(sec);
    }
    report.dedupe_names();
    Ok(report)
}

/// Runs `scene` in memory: no report folder; checkpoints go to a temporary folder.
pub fn run(scene: &Scene) -> Result<Report> {
    let tmp = crate::files::ScratchDir::new()?;
    run_in(scene, tmp.path(), &RunControl::default())
}

/// The provenance block of a scene's outputs.
pub fn provenance(scene: &Scene) -> Provenance {
    Provenance {
        tool: tool_version(),
        scene_name: scene.name.clone(),
        scene_origin: scene.origin().to_string(),
        scene_text: scene.source.clone(),
        seed: scene.seed(),
    }
}

/// Runs `scene` and writes its report folder `out` (see [`Destination`] for what may be
/// replaced); returns the report and the files written.
/// `work`: a checkpoint folder of the caller's (e.g. checkpoints committed as data),
/// read and written and kept; without it they live beside the report (`<out>.work`) and
/// are removed once the report is written.
pub fn run_to_folder(
    scene: &Scene,
    out: &Path,
    work: Option<&Path>,
    control: &RunControl,
) -> Result<(Report, Vec<PathBuf>)> {
    let t0 = Instant::now();
    if let Some(work) = work {
        check_work_outside(work, out)?;
    }
    let dest = Destination::claim(out)?;
    let work_root = work.map_or_else(|| dest.work_root(), Path::to_path_buf);
    let report = match run_in(scene, &work_root, control) {
        Ok(r) => r,
        // A failure leaves no folder behind that holds nothing to resume from.
        Err(e) if work.is_none() && !matches!(e, CompareError::Stopped { .. }) => {
            remove_unfinished_checkpoints(scene, &work_root);
            return Err(e);
        }
        Err(e) => return Err(e),
    };
    let files = dest.write_report(&report, &provenance(scene), t0.elapsed().as_secs_f64())?;
    if work.is_none() {
        remove_checkpoints(scene, &work_root);
    }
    Ok((report, files))
}

/// Refuses a `--work` folder that is the `--out` folder or inside it, before anything
/// is computed: the report replaces `--out` as a whole, checkpoints included.
pub fn check_work_outside(work: &Path, out: &Path) -> Result<()> {
    let (w, o) = (resolved(work), resolved(out));
    if w.starts_with(&o) {
        return Err(CompareError::Scene(format!(
            "--work {} is {} --out {}: the report replaces that folder as a whole, so the \
             checkpoints must live elsewhere (e.g. --work {}.work)",
            work.display(),
            if w == o {
                "the same folder as"
            } else {
                "inside"
            },
            out.display(),
            out.display()
        )));
    }
    Ok(())
}

/// `path` made absolute with `.` and `..` resolved, through the nearest existing
/// ancestor's real path (symbolic links included).
fn resolved(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut clean = PathBuf::new();
    for c in abs.components() {
        match c {
            std::path::Component::ParentDir => {
                clean.pop();
            }
            std::path::Component::CurDir => {}
            other => clean.push(other),
        }
    }
    // The longest existing prefix, canonicalised, and the rest appended.
    let mut head = clean.clone();
    let mut tail = Vec::new();
    while !head.exists() {
        match head.file_name() {
            Some(name) => tail.push(name.to_os_string()),
            None => break,
        }
        head.pop();
    }
    let mut real = head.canonicalize().unwrap_or(head);
    real.extend(tail.iter().rev());
    real
}

/// Removes the checkpoint folders of the scene's resumable outputs (and the work root
/// if that leaves it empty).
pub(crate) fn remove_checkpoints(scene: &Scene, work_root: &Path) {
    for e in &scene.outputs {
        if let Some(c) = e.output.checkpointed() {
            let _ = std::fs::remove_dir_all(work_root.join(c.key()));
        }
    }
    let _ = std::fs::remove_dir(work_root); // only if empty
}

/// Removes the checkpoint folders of the scene's resumable outputs that hold no finished
/// task (and the work root if that leaves it empty); a folder with finished tasks is
/// kept: the same command resumes from it.
fn remove_unfinished_checkpoints(scene: &Scene, work_root: &Path) {
    for e in &scene.outputs {
        if let Some(c) = e.output.checkpointed() {
            let dir = work_root.join(c.key());
            if !c.task_files().iter().any(|f| dir.join(f).exists()) {
                let _ = std::fs::remove_dir_all(dir);
            }
        }
    }
    let _ = std::fs::remove_dir(work_root); // only if empty
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--work` at or inside `--out` is refused (through `..` and symbolic links too);
    /// beside it, or holding it, is not.
    #[test]
    fn work_folder_outside_the_report() {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("report");
        std::fs::create_dir(&out).unwrap();
        let refused = |work: &Path| check_work_outside(work, &out).unwrap_err().to_string();
        assert!(refused(&out).contains("the same folder as"));
        assert!(refused(&out.join("cp")).contains("inside"));
        assert!(refused(&out.join("new/../cp/deeper")).contains("inside"));
        #[cfg(unix)]
        {
            let link = tmp.path().join("link");
            std::os::unix::fs::symlink(&out, &link).unwrap();
            assert!(refused(&link.join("cp")).contains("inside"));
        }
        check_work_outside(&tmp.path().join("report.work"), &out).unwrap();
        check_work_outside(tmp.path(), &out.join("sub")).unwrap();
    }
}
