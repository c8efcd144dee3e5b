//! `RoughSphere` as an output kind: its checks, its declared stages and its run, which
//! calls the study's parts; the parameters and their defaults are in the parent module.

use super::RoughSphere;
use super::{report, runs};
use crate::checks::{bad, cell_bytes, check_memory_per_thread, count_in};
use crate::context::Context;
use crate::error::Result;
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::rough_body::MIN_CELLS_PER_CONTACT_RADIUS;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use rayon::prelude::*;

/// The stages of the 3D realisations, run together on the pool.
const STAGES_3D: &[Stage] = &[Stage::RoughSynthesis, Stage::Bem3d, Stage::Bem3dStiffness];

impl Output for RoughSphere {
    fn validate(&self, ctx: &Context) -> Result<()> {
        crate::checks::check_magnitudes(&[
            ("radius", self.radius),
            ("hertz_depth", self.hertz_depth),
        ])?;
        if self.hertz_depth > 0.1 * self.radius {
            return bad(format!(
                "hertz_depth = {} must be <= 0.1 radius = {} (Hertz: small slopes)",
                self.hertz_depth,
                0.1 * self.radius
            ));
        }
        if !(-1.0..=3.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [-1, 3]", self.hurst));
        }
        if self.alpha.is_empty() || self.alpha.iter().any(|a| !(0.0..=100.0).contains(a)) {
            return bad(format!(
                "alpha = {:?}: give at least one rms height over the Hertz depth in [0, 100] (0: the smooth sphere)",
                self.alpha
            ));
        }
        if !(self.side.is_finite() && (2.5..=100.0).contains(&self.side)) {
            return bad(format!(
                "side = {} must lie in [2.5, 100] (units of the Hertz radius)",
                self.side
            ));
        }
        count_in("grid", self.grid as u64, 16..=4096)?;
        let per = self.grid as f64 / self.side;
        if per < MIN_CELLS_PER_CONTACT_RADIUS {
            return bad(format!(
                "grid = {} over side = {} puts {per:.3} cells on the Hertz radius, at least {MIN_CELLS_PER_CONTACT_RADIUS} needed: give grid >= {} or a smaller side",
                self.grid,
                self.side,
                (MIN_CELLS_PER_CONTACT_RADIUS * self.side).ceil()
            ));
        }
        count_in(
            "bandwidth",
            self.bandwidth as u64,
            1..=(self.grid as u64 - 1) / 2,
        )?;
        crate::checks::check_ensembles(self.realisations_3d, self.realisations_1d)?;
        count_in("points_1d_factor", self.points_1d_factor as u64, 1..=64)?;
        count_in("loads", self.loads as u64, 3..=crate::checks::MAX_LOADS)?;
        crate::checks::check_tolerance(self.tolerance)?;
        LambdaSpec::check_all(&self.lambda, ctx, &[self.hurst])?;
        let n = self.grid as f64;
        check_memory_per_thread(
            n * n * cell_bytes::ROUGH_FREE,
            &format!("3D grids of {n}^2 cells, one per thread"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        [STAGES_3D, &[Stage::RoughContact]].concat()
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let lambdas = LambdaSpec::at_hurst(&self.lambda, env.ctx, self.hurst)?;
        let scale = runs::roughness_scale(self)?;
        let all_3d = out.stages_together(STAGES_3D, || {
            self.alpha
                .iter()
                .map(|&a| {
                    (0..self.realisations(a, self.realisations_3d))
                        .into_par_iter()
                        .map(|r| runs::press_3d(self, a, scale, r))
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        let all_1d = out.stage(Stage::RoughContact, || {
            self.alpha
                .iter()
                .map(|&a| {
                    lambdas
                        .iter()
                        .map(|&lam| {
                            (0..self.realisations(a, self.realisations_1d))
                                .into_par_iter()
                                .map(|r| runs::press_1d(self, a, scale, lam, r))
                                .collect::<Result<Vec<_>>>()
                        })
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        report::report(self, &lambdas, &all_3d, &all_1d, out);
        Ok(())
    }
}
