//! `HurstSweep` as an output kind: its checks, its declared stages and its run, which
//! calls the study's parts; the parameters and their defaults are in the parent module.

use super::HurstSweep;
use super::{aggregate, figures, tasks};
use crate::context::Context;
use crate::error::{CompareError, Result};
use crate::experiment::rough_punch;
use crate::output::{Checkpointed, Env, Output, RunControl};
use crate::plan::Stage;
use crate::report::Section;
use std::path::Path;

impl Output for HurstSweep {
    fn validate(&self, _: &Context) -> Result<()> {
        let bad = |m: String| Err(CompareError::Scene(m));
        if self.hurst.is_empty() {
            return bad("hurst list is empty".into());
        }
        if let Some(h) = self.hurst.iter().find(|h| !(-1.0..=3.0).contains(*h)) {
            return bad(format!("hurst = {h} must lie in [-1, 3]"));
        }
        for &g in std::iter::once(&self.grid).chain(&self.convergence_grids) {
            if !(16..=4096).contains(&g) {
                return bad(format!("grid {g} must lie in 16..=4096"));
            }
        }
        if !(self.upper_cutoff_ratio > 0.0 && self.upper_cutoff_ratio <= 1.0) {
            return bad("upper_cutoff_ratio must lie in (0, 1]".into());
        }
        crate::checks::check_ensembles(self.realisations_3d, self.realisations_1d)?;
        crate::checks::count_in("loads", self.loads as u64, 6..=crate::checks::MAX_LOADS)?;
        crate::checks::count_in("points_1d_factor", self.points_1d_factor as u64, 2..=64)?;
        crate::checks::check_tolerance(self.tolerance)?;
        // One 3D task per worker thread at a time.
        crate::checks::check_memory_per_thread(
            (self.grid * self.grid) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("grid = {}", self.grid),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        rough_punch::study_stages(false)
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn checkpointed(&self) -> Option<&dyn Checkpointed> {
        Some(self)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        // Each 3D task synthesises a surface, solves it and its stiffness at every load;
        // each 1D task synthesises and loads its lines: the stages run interleaved.
        let work = rough_punch::compute_study(self, env, out)?;
        let results = out.stage(Stage::SweepFit, || aggregate::aggregate(self, &work))?;
        figures::report(self, &results, out);
        Ok(())
    }
}

impl Checkpointed for HurstSweep {
    fn key(&self) -> String {
        // FNV-1a of the parameters' debug form (f64 prints round-trip exactly).
        let text = format!("{self:?}");
        crate::output::checkpoint_key(&text)
    }

    fn task_files(&self) -> Vec<String> {
        tasks::all(self).iter().map(|t| t.file_name()).collect()
    }

    fn compute(&self, _: &Context, dir: &Path, control: &RunControl) -> Result<()> {
        tasks::compute(self, dir, control)
    }
}
