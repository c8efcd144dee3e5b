//! The sweep's checkpointed work: one task per 3D realisation (per H and grid) and one
//! per H for the whole 1D ensemble (1D is cheap). Each task's result is written
//! atomically to its own JSON file; a task whose file exists is not recomputed.

use super::HurstSweep;
use crate::error::{Context as _, Result};
use crate::experiment::rough_punch::{line_stiffness, punch_curve, BemCurve, MrdEnsemble};
use crate::experiment::tasks::json;
use crate::output::RunControl;
use crate::plan::Stage;
use crate::report::clock;
use mrd::rough_contact::RoughLine;
use mrd::roughness::synthesis::{line, surface, Amplitudes, Grid};
use mrd::roughness::SelfAffine;
use rayon::prelude::*;
use serde::Deserialize;
use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

/// One unit of checkpointed work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Task {
    /// 3D realisation `r` at Hurst index `h` on grid `g`.
    Bem { h: usize, g: usize, r: u64 },
    /// The whole 1D ensemble at Hurst index `h`.
    Mrd { h: usize },
}

impl Task {
    /// Checkpoint file name of the task.
    pub fn file_name(&self) -> String {
        match self {
            Task::Bem { h, g, r } => format!("bem_h{h}_g{g}_r{r}.json"),
            Task::Mrd { h } => format!("mrd_h{h}.json"),
        }
    }
}

/// All tasks of a sweep in a fixed global order (shards take every N-th).
pub fn all(spec: &HurstSweep) -> Vec<Task> {
    let mut t = Vec::new();
    for h in 0..spec.hurst.len() {
        for g in spec.grids() {
            for r in 0..spec.realisations_3d {
                t.push(Task::Bem { h, g, r });
            }
        }
        t.push(Task::Mrd { h });
    }
    t
}

/// The random stream of a task: (seed, stream id).
fn stream(seed: u64, task_kind: u64, h: usize, g: usize, r: u64) -> (u64, u64) {
    (
        seed,
        (task_kind << 60) ^ ((h as u64) << 40) ^ ((g as u64) << 24) ^ r,
    )
}

/// pi h1^2 / h3^2 per unit lambda for the sweep's lines and punch faces at (H, grid):
/// the calibrated shift of the reduced curves is lambda (Eq. 76) times this
/// ([`crate::experiment::lambda_meaning`]).
pub fn rms_factor(spec: &HurstSweep, hurst: f64, grid: usize) -> Result<f64> {
    use crate::experiment::lambda_meaning::{rms_matched, Face};
    let s = spectrum(spec, hurst, grid).ctx("sweep spectrum")?;
    let band = spec.upper_cutoff_ratio * PI * grid as f64 / (2.0 * PI);
    Ok(rms_matched(1.0, &|q| s.c2d(q), band, 1.0, Face::Disc))
}

fn spectrum(spec: &HurstSweep, hurst: f64, grid: usize) -> mrd::Result<SelfAffine> {
    let q0 = 2.0 * PI;
    let q1 = spec.upper_cutoff_ratio * PI * grid as f64;
    SelfAffine::new(hurst, q0, q0, q1)
}

fn run_bem(spec: &HurstSweep, h: usize, g: usize, r: u64) -> Result<BemCurve> {
    let t0 = Instant::now();
    let sa = spectrum(spec, spec.hurst[h], g).ctx("sweep spectrum")?;
    let (seed, id) = stream(spec.seed, 1, h, g, r);
    let heights = clock::time(Stage::RoughSynthesis, || {
        surface(
            &sa,
            &Grid::square(g, 1.0),
            seed,
            id,
            Amplitudes::Deterministic,
        )
    })
    .ctx("3D surface")?;
    let mut out = punch_curve(&heights, g, spec.loads, spec.tolerance)?;
    out.seconds = t0.elapsed().as_secs_f64();
    Ok(out)
}

fn run_mrd(spec: &HurstSweep, h: usize) -> Result<MrdEnsemble> {
    let t0 = Instant::now();
    let n1 = spec.points_1d_factor * spec.grid;
    let line_spec = spectrum(spec, spec.hurst[h], spec.grid)
        .ctx("sweep spectrum")?
        .to_line(PI);
    let fs = spec.f_grid();
    let stiffness: Vec<Vec<f64>> = (0..spec.realisations_1d)
        .into_par_iter()
        .map(|r| -> Result<Vec<f64>> {
            let (seed, id) = stream(spec.seed, 2, h, spec.grid, r);
            let z = clock::time(Stage::RoughSynthesis, || {
                line(&line_spec, n1, 1.0, seed, id, Amplitudes::Deterministic)
            })
            .ctx("1D line")?;
            line_stiffness(&RoughLine::new(&z, 1.0, 1.0).ctx("1D line")?, &fs)
        })
        .collect::<Result<_>>()?;
    Ok(MrdEnsemble {
        stiffness,
        seconds: t0.elapsed().as_secs_f64(),
        points: n1,
    })
}

/// Computes the missing tasks of `spec` (of this shard) into `work`.
pub fn compute(spec: &HurstSweep, work: &Path, control: &RunControl) -> Result<()> {
    let list = all(spec);
    let names: Vec<String> = list.iter().map(Task::file_name).collect();
    crate::experiment::tasks::compute(
        work,
        "hurst sweep",
        &names,
        names.len(),
        true,
        control,
        &|i| match list[i] {
            Task::Bem { h, g, r } => json(&run_bem(spec, h, g, r)?),
            Task::Mrd { h } => json(&run_mrd(spec, h)?),
        },
    )
}

/// Reads one task's checkpoint.
pub fn load<T: for<'de> Deserialize<'de>>(work: &Path, t: &Task) -> Result<T> {
    crate::experiment::tasks::load(work, &t.file_name())
}
