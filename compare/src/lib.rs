//! # compare: scenes, plans, comparisons and reports of the MRD workbench
//!
//! Data path: scene file ([`scene`]) -> plan of the stages its outputs need ([`plan`])
//! -> solvers (`mrd`, `bem3d`) -> tables and figures ([`report`]) -> report folder.

pub mod axisym;
pub mod bem;
pub mod error;
pub mod plan;
pub mod report;
pub mod rough;
pub mod scene;
pub mod scenes;
pub mod shards;
pub mod sweep;

pub use error::{CompareError, Result};

use std::path::Path;
use std::time::Instant;

/// Tool name and version written into every output.
pub fn tool_version() -> String {
    format!("mrdw {}", env!("CARGO_PKG_VERSION"))
}

/// Where a run keeps its checkpoints and how it divides its work.
#[derive(Debug, Clone, Default)]
pub struct RunContext {
    /// The report folder; sweep checkpoints go next to it (`<out>.work/`).
    pub out_dir: Option<std::path::PathBuf>,
    pub control: sweep::RunControl,
}

impl RunContext {
    fn work_root(&self) -> std::path::PathBuf {
        self.out_dir
            .clone()
            .unwrap_or_else(|| std::env::temp_dir().join("mrdw-run"))
    }
}

/// Runs every output of a scene (only their planned stages) into a report.
pub fn run_scene(scene: &scene::Scene) -> Result<report::Report> {
    run_scene_in(scene, &RunContext::default())
}

/// As [`run_scene`], with checkpoints and work control for sweeps.
pub fn run_scene_in(scene: &scene::Scene, ctx: &RunContext) -> Result<report::Report> {
    let mut report = report::Report::default();
    let mut seen: std::collections::BTreeMap<&str, usize> = Default::default();
    for i in 0..scene.file.outputs.len() {
        let kind = scene.file.outputs[i].kind();
        let k = seen.entry(kind).or_insert(0);
        *k += 1;
        let label = if *k == 1 {
            kind.to_string()
        } else {
            format!("{kind}_{k}")
        };
        report.current = Some((kind.to_string(), label));
        let output = &scene.file.outputs[i];
        match (output.executor(), output) {
            (scene::Executor::Sweep, scene::OutputSpec::HurstSweep(spec)) => {
                let work = sweep::work_dir(&ctx.work_root(), spec);
                sweep::compute(spec, &work, &ctx.control)?;
                let label = report
                    .current
                    .as_ref()
                    .map(|c| c.1.clone())
                    .unwrap_or_default();
                sweep::aggregate(spec, &work, &mut report, &label)?;
            }
            (scene::Executor::Bem, _) => bem::run_output(scene, i, &mut report)?,
            (scene::Executor::RoughLines, _) => rough::run_output(scene, i, &mut report)?,
            (scene::Executor::Axisymmetric, _) => axisym::run_output(scene, i, &mut report)?,
            (scene::Executor::Sweep, _) => unreachable!("only hurst_sweep runs as a sweep"),
        }
    }
    report.dedupe_names();
    report.warnings.dedup();
    Ok(report)
}

/// Runs a scene and writes its report folder; returns the files written. Sweep
/// checkpoints are removed after a successful write.
pub fn run_and_write(
    scene: &scene::Scene,
    out_dir: &Path,
) -> Result<(report::Report, Vec<std::path::PathBuf>)> {
    run_and_write_with(
        scene,
        out_dir,
        &sweep::RunControl {
            progress: true,
            ..Default::default()
        },
    )
}

pub fn run_and_write_with(
    scene: &scene::Scene,
    out_dir: &Path,
    control: &sweep::RunControl,
) -> Result<(report::Report, Vec<std::path::PathBuf>)> {
    let t0 = Instant::now();
    let ctx = RunContext {
        out_dir: Some(out_dir.to_path_buf()),
        control: *control,
    };
    let report = run_scene_in(scene, &ctx)?;
    let prov = report::Provenance {
        tool: tool_version(),
        scene_name: scene.file.name.clone(),
        scene_origin: scene.origin.clone(),
        scene_text: scene.source.clone(),
        seed: scene.seed(),
    };
    let files = report::write(&report, &prov, out_dir, t0.elapsed().as_secs_f64())?;
    for o in &scene.file.outputs {
        if let scene::OutputSpec::HurstSweep(spec) = o {
            let _ = std::fs::remove_dir_all(sweep::work_dir(out_dir, spec));
        }
    }
    let name = out_dir
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("report");
    let _ = std::fs::remove_dir(out_dir.with_file_name(format!("{name}.work"))); // only if empty
    Ok((report, files))
}

pub mod bench;
