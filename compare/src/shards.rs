//! Running a sweep beyond one machine: `mrdw run SCENE --shard K/N --out DIR` computes a
//! deterministic slice of the tasks (every N-th, from K) into `DIR/work/`, with the scene
//! text and its origin; `mrdw merge DIR...` checks that the shards cover the same scene
//! and all tasks, gathers their checkpoints and writes exactly the report a single run
//! writes (same bytes in every CSV).

use crate::error::{io_err, CompareError, Result};
use crate::output::{Checkpointed, RunControl};
use crate::report::write::{marker_text, Destination, MARKER, SHARD_ENTRIES};
use crate::report::Report;
use crate::run::{provenance, remove_checkpoints, run_in, tool_version};
use crate::scene::Scene;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Debug, Serialize, Deserialize)]
struct Manifest {
    tool: String,
    scene_origin: String,
    shard: usize,
    shards: usize,
}

/// The checkpointed outputs of a scene whose outputs are all checkpointed.
fn checkpointed(scene: &Scene) -> Result<Vec<&dyn Checkpointed>> {
    let v: Vec<&dyn Checkpointed> = scene
        .outputs
        .iter()
        .filter_map(|e| e.output.checkpointed())
        .collect();
    if v.is_empty() || v.len() != scene.outputs.len() {
        return Err(CompareError::Scene(format!(
            "{}: only scenes whose outputs are all resumable (`hurst_sweep`) can be sharded",
            scene.origin()
        )));
    }
    Ok(v)
}

/// Computes one shard of a sweep scene into `out` (resumable: finished tasks are kept).
pub fn run_shard(scene: &Scene, out: &Path, control: &RunControl) -> Result<()> {
    let outputs = checkpointed(scene)?;
    let (k, n) = control
        .shard
        .ok_or_else(|| CompareError::Internal("run_shard without a shard".into()))?;
    let dest = Destination::claim(out)?;
    let dir = dest.dir();
    std::fs::create_dir_all(dir).map_err(io_err(format!("creating {}", dir.display())))?;
    std::fs::write(dir.join(MARKER), marker_text(&SHARD_ENTRIES))
        .map_err(io_err(format!("writing {MARKER}")))?;
    std::fs::write(dir.join("scene.toml"), &scene.source).map_err(io_err("writing scene.toml"))?;
    let m = Manifest {
        tool: tool_version(),
        scene_origin: scene.origin().to_string(),
        shard: k,
        shards: n,
    };
    let text =
        serde_json::to_string_pretty(&m).map_err(|e| CompareError::Internal(e.to_string()))?;
    std::fs::write(dir.join("shard.json"), text).map_err(io_err("writing shard.json"))?;
    for c in outputs {
        c.compute(&scene.context, &dir.join("work").join(c.key()), control)?;
    }
    Ok(())
}

/// Merges shard folders; returns the scene, the report and the files written.
pub fn merge(shards: &[PathBuf], out: Option<&Path>) -> Result<(Scene, Report, Vec<PathBuf>)> {
    let mut text: Option<String> = None;
    let mut origin = String::new();
    let mut seen = Vec::new();
    let mut total = 0;
    for d in shards {
        let t = std::fs::read_to_string(d.join("scene.toml")).map_err(io_err(format!(
            "{}: not a shard folder (no scene.toml)",
            d.display()
        )))?;
        let m: Manifest = serde_json::from_str(
            &std::fs::read_to_string(d.join("shard.json"))
                .map_err(io_err(format!("{}: no shard.json", d.display())))?,
        )
        .map_err(|e| CompareError::Scene(format!("{}/shard.json: {e}", d.display())))?;
        match &text {
            None => {
                text = Some(t);
                origin = m.scene_origin.clone();
                total = m.shards;
            }
            Some(t0) if *t0 != t || m.shards != total => {
                return Err(CompareError::Scene(format!(
                    "{}: shard of a different scene or split",
                    d.display()
                )))
            }
            _ => {}
        }
        seen.push(m.shard);
    }
    seen.sort_unstable();
    seen.dedup();
    if seen != (0..total).collect::<Vec<_>>() {
        return Err(CompareError::Scene(format!(
            "shards {seen:?} given, but the split has {total}: all are needed"
        )));
    }
    let text = text.ok_or_else(|| CompareError::Scene("no shard folders given".into()))?;
    // The scene's data files (maps, tables) are relative to the scene file the shards
    // ran from, when it is still there.
    let from = Path::new(&origin);
    let base = from.is_file().then(|| from.parent()).flatten();
    let scene = Scene::parse(&text, &origin, base)?;
    let out = out
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("reports").join(&scene.name));
    let t0 = std::time::Instant::now();
    let dest = Destination::claim(&out)?;
    for c in checkpointed(&scene)? {
        let to = dest.work_root().join(c.key());
        std::fs::create_dir_all(&to).map_err(io_err(format!("creating {}", to.display())))?;
        for d in shards {
            let from = d.join("work").join(c.key());
            if let Ok(entries) = std::fs::read_dir(&from) {
                for e in entries.flatten() {
                    let name = e.file_name();
                    if name.to_string_lossy().ends_with(".json") {
                        std::fs::copy(e.path(), to.join(&name))
                            .map_err(io_err("copying checkpoints"))?;
                    }
                }
            }
        }
        let missing = c
            .task_files()
            .iter()
            .filter(|t| !to.join(t).exists())
            .count();
        if missing > 0 {
            return Err(CompareError::Scene(format!(
                "{missing} tasks missing from the shards (did a shard stop early?)"
            )));
        }
    }
    let report = run_in(&scene, &dest.work_root(), &RunControl::default())?;
    let files = dest.write_report(&report, &provenance(&scene), t0.elapsed().as_secs_f64())?;
    remove_checkpoints(&scene, &dest.work_root());
    Ok((scene, report, files))
}
