//! # compare: scenes, plans, comparisons and reports of the MRD workbench
//!
//! Data path: scene file ([`scene`]) -> plan of the stages its outputs need ([`plan`])
//! -> solvers (`mrd`, `bem3d`) -> tables and figures ([`report`]) -> report folder.

pub mod axisym;
pub mod error;
pub mod plan;
pub mod report;
pub mod rough;
pub mod scene;
pub mod scenes;

pub use error::{CompareError, Result};

use std::path::Path;
use std::time::Instant;

/// Tool name and version written into every output.
pub fn tool_version() -> String {
    format!("mrdw {}", env!("CARGO_PKG_VERSION"))
}

/// Runs every output of a scene (only their planned stages) into a report.
pub fn run_scene(scene: &scene::Scene) -> Result<report::Report> {
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
        if scene.file.outputs[i].is_rough() {
            rough::run_output(scene, i, &mut report)?;
        } else {
            axisym::run_output(scene, i, &mut report)?;
        }
    }
    report.dedupe_names();
    report.warnings.dedup();
    Ok(report)
}

/// Runs a scene and writes its report folder; returns the files written.
pub fn run_and_write(
    scene: &scene::Scene,
    out_dir: &Path,
) -> Result<(report::Report, Vec<std::path::PathBuf>)> {
    let t0 = Instant::now();
    let report = run_scene(scene)?;
    let prov = report::Provenance {
        tool: tool_version(),
        scene_name: scene.file.name.clone(),
        scene_origin: scene.origin.clone(),
        scene_text: scene.source.clone(),
        seed: None,
    };
    let files = report::write(&report, &prov, out_dir, t0.elapsed().as_secs_f64())?;
    Ok((report, files))
}
pub mod bench;
