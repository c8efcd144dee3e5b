//! Running a sweep beyond one machine: `mrdw run SCENE --shard K/N --out DIR` computes a
//! deterministic slice of the tasks (every N-th, from K) into `DIR/work/`, with the scene
//! text and its origin; `mrdw merge DIR...` checks that the shards cover the same scene
//! and all tasks, gathers their checkpoints and writes exactly the report a single run
//! writes (same bytes in every CSV).

use crate::error::{io_err, CompareError, Result};
use crate::scene::{OutputSpec, Scene};
use crate::sweep::{self, RunControl};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Debug, Serialize, Deserialize)]
struct Manifest {
    tool: String,
    scene_origin: String,
    shard: usize,
    shards: usize,
}

fn sweeps(scene: &Scene) -> Result<Vec<&sweep::SweepSpec>> {
    let v: Vec<&sweep::SweepSpec> = scene
        .file
        .outputs
        .iter()
        .filter_map(|o| {
            if let OutputSpec::HurstSweep(s) = o {
                Some(s)
            } else {
                None
            }
        })
        .collect();
    if v.is_empty() || v.len() != scene.file.outputs.len() {
        return Err(CompareError::Scene(format!(
            "{}: only scenes whose outputs are all `hurst_sweep` can be sharded",
            scene.origin
        )));
    }
    Ok(v)
}

/// Computes one shard of a sweep scene into `out`.
pub fn run_shard(scene: &Scene, out: &Path, control: &RunControl) -> Result<()> {
    let specs = sweeps(scene)?;
    let (k, n) = control.shard.expect("shard given");
    std::fs::create_dir_all(out).map_err(io_err(format!("creating {}", out.display())))?;
    std::fs::write(out.join("scene.toml"), &scene.source).map_err(io_err("writing scene.toml"))?;
    let m = Manifest {
        tool: crate::tool_version(),
        scene_origin: scene.origin.clone(),
        shard: k,
        shards: n,
    };
    std::fs::write(
        out.join("shard.json"),
        serde_json::to_string_pretty(&m).unwrap(),
    )
    .map_err(io_err("writing shard.json"))?;
    for spec in specs {
        sweep::compute(spec, &out.join("work").join(spec_key(spec)), control)?;
    }
    Ok(())
}

fn spec_key(spec: &sweep::SweepSpec) -> String {
    sweep::work_dir(Path::new("x"), spec)
        .file_name()
        .unwrap()
        .to_string_lossy()
        .into_owned()
}

/// Merges shard folders; returns the scene, the report and the files written.
pub fn merge(
    shards: &[PathBuf],
    out: Option<&Path>,
) -> Result<(Scene, crate::report::Report, Vec<PathBuf>)> {
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
    let scene = Scene::parse(text.as_deref().unwrap(), &origin, None)?;
    let out = out
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("reports").join(&scene.file.name));
    for spec in sweeps(&scene)? {
        let dest = sweep::work_dir(&out, spec);
        std::fs::create_dir_all(&dest).map_err(io_err(format!("creating {}", dest.display())))?;
        for d in shards {
            let src = d.join("work").join(spec_key(spec));
            if let Ok(entries) = std::fs::read_dir(&src) {
                for e in entries.flatten() {
                    let name = e.file_name();
                    if name.to_string_lossy().ends_with(".json") {
                        std::fs::copy(e.path(), dest.join(&name))
                            .map_err(io_err("copying checkpoints"))?;
                    }
                }
            }
        }
        let missing = sweep::tasks(spec)
            .iter()
            .filter(|t| !dest.join(t.file_name()).exists())
            .count();
        if missing > 0 {
            return Err(CompareError::Scene(format!(
                "{missing} tasks missing from the shards (did a shard stop early?)"
            )));
        }
    }
    let (report, files) = crate::run_and_write_with(&scene, &out, &RunControl::default())?;
    Ok((scene, report, files))
}
