//! `LambdaStudy` as an output kind: its checks, its declared stages and its run, which
//! calls the study's parts; the parameters and their defaults are in the parent module.

use super::LambdaStudy;
use super::{analysis, report, scatter, schedule};
use crate::checks::{bad, count_in};
use crate::context::Context;
use crate::error::{CompareError, Result};
use crate::experiment::rough_punch;
use crate::output::{Checkpointed, Env, Output, RunControl};
use crate::plan::Stage;
use crate::report::Section;
use std::path::Path;

impl Output for LambdaStudy {
    fn validate(&self, _: &Context) -> Result<()> {
        if self.hurst.is_empty() {
            return bad("hurst list is empty");
        }
        let in_range = |h: &f64| (-1.0..=3.0).contains(h);
        if let Some(h) = self
            .hurst
            .iter()
            .chain(self.extra.iter().flat_map(|e| &e.hurst))
            .find(|h| !in_range(h))
        {
            return bad(format!("hurst = {h} must lie in [-1, 3]"));
        }
        if !self.bandwidths.contains(&self.calibrate_at) {
            return bad(format!(
                "calibrate_at = {} must be one of bandwidths {:?}",
                self.calibrate_at, self.bandwidths
            ));
        }
        let cells = format!("cells = {}", self.cells);
        for &b in &self.bandwidths {
            self.check_band(b, self.cells, &cells)?;
        }
        for e in &self.extra {
            self.check_band(e.bandwidth, self.cells, &cells)?;
        }
        if let Some(r) = &self.resolution {
            for &c in &r.cells {
                self.check_band(r.bandwidth, c, &format!("resolution.cells entry {c}"))?;
            }
        }
        if let Some(t) = &self.tolerance_check {
            if !in_range(&t.hurst) || !self.hurst.contains(&t.hurst) {
                return bad("tolerance_check.hurst must be one of hurst");
            }
            bem3d::SolverOptions::new(t.tolerance, 1)
                .validate()
                .map_err(|e| crate::error::CompareError::Scene(format!("tolerance_check: {e}")))?;
        }
        bem3d::SolverOptions::new(self.tolerance, 1)
            .validate()
            .map_err(|e| crate::error::CompareError::Scene(e.to_string()))?;
        if let Some(t) = &self.top_check {
            if !self.hurst.contains(&t.hurst) {
                return bad("top_check.hurst must be one of hurst");
            }
            let extra = self
                .extra
                .iter()
                .any(|e| e.bandwidth == t.bandwidth && e.hurst.contains(&t.hurst));
            if !self.bandwidths.contains(&t.bandwidth) && !extra {
                return bad("top_check.bandwidth must be one of bandwidths, or an extra bandwidth of its hurst");
            }
            self.check_band(
                t.bandwidth,
                2 * self.cells,
                &format!(
                    "top_check runs at twice cells = {} (so cells must be at most 16)",
                    self.cells
                ),
            )?;
            bem3d::SolverOptions::new(t.tolerance, 1)
                .validate()
                .map_err(|e| crate::error::CompareError::Scene(format!("top_check: {e}")))?;
            count_in(
                "top_check.realisations",
                t.realisations,
                2..=crate::checks::MAX_REALISATIONS,
            )?;
        }
        if let Some(sc) = &self.scatter {
            if !self.bandwidths.contains(&sc.bandwidth) {
                return bad("scatter.bandwidth must be one of bandwidths");
            }
            count_in(
                "scatter.realisations",
                sc.realisations,
                3..=crate::checks::MAX_REALISATIONS,
            )?;
        }
        self.realisations.validate()?;
        count_in(
            "realisations_1d",
            self.realisations_1d,
            2..=crate::checks::MAX_REALISATIONS,
        )?;
        count_in(
            "control_realisations",
            self.control_realisations,
            2..=crate::checks::MAX_REALISATIONS,
        )?;
        if let Some([side, m]) = self.control_realisations_large {
            count_in("control_realisations_large side", side, 2..=65_536)?;
            count_in(
                "control_realisations_large m",
                m,
                2..=crate::checks::MAX_REALISATIONS,
            )?;
        }
        count_in("loads", self.loads as u64, 6..=crate::checks::MAX_LOADS)?;
        count_in("points_1d_per_cell", self.points_1d_per_cell as u64, 2..=64)?;
        let [lo, hi] = self.window;
        if !(lo > 0.0 && lo < hi && hi <= 1.0) {
            return bad("window must satisfy 0 < window[0] < window[1] <= 1 (k/(E* L))");
        }
        let ok = self.target.windows(2).all(|w| w[0][0] < w[1][0])
            && self.target.iter().all(|t| t[1] > 0.0 && t[1] < 1.0);
        if !ok {
            return bad(
                "target: [H_max, relative half-width] pairs, H_max ascending, widths in (0, 1)",
            );
        }
        Ok(())
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
        let work = rough_punch::compute_study(self, env, out)?;
        let (results, scatter) = out.stage(Stage::SweepFit, || {
            Ok::<_, CompareError>((
                analysis::analyse(self, &work)?,
                scatter::scatter(self, &work)?,
            ))
        })?;
        report::report(self, &results, &scatter, out);
        Ok(())
    }
}

impl Checkpointed for LambdaStudy {
    /// The parameters every task's result depends on besides its own name (H, B, cells,
    /// tolerance, realisation): seed, loads, the 1D ensemble. Lists of H, bandwidths and
    /// the realisation plan may change and keep the checkpoints.
    fn key(&self) -> String {
        let text = format!(
            "lambda_study nested-v1 seed={} loads={} realisations_1d={} points_1d_per_cell={} cells={}",
            self.seed, self.loads, self.realisations_1d, self.points_1d_per_cell, self.cells
        );
        crate::output::checkpoint_key(&text)
    }

    fn task_files(&self) -> Vec<String> {
        Vec::new()
    }

    fn compute(&self, _: &Context, dir: &Path, control: &RunControl) -> Result<()> {
        schedule::compute(self, dir, control)
    }
}
