//! `ViscoelasticRough` as an output kind: its checks, its declared stages and its run, which
//! calls the study's parts; the parameters and their defaults are in the parent module.

use super::{radok, report, runs};
use super::{ViscoelasticRough, MAX_STEPS};
use crate::checks::{bad, cell_bytes, check_memory_per_thread, count_in};
use crate::context::Context;
use crate::error::Result;
use crate::experiment::lambda::LambdaSpec;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use rayon::prelude::*;

/// The stages of the 3D histories, run together on the pool.
const STAGES_3D: &[Stage] = &[Stage::RoughSynthesis, Stage::Viscoelastic3d, Stage::Bem3d];

impl Output for ViscoelasticRough {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if !(-1.0..=3.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [-1, 3]", self.hurst));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=512)?;
        count_in("cells", self.cells as u64, 3..=32)?;
        count_in("points_1d_per_cell", self.points_1d_per_cell as u64, 1..=64)?;
        crate::checks::check_ensembles(self.realisations_3d, self.realisations_1d)?;
        self.relaxation()?;
        if self.modulus.relaxed <= 0.0 {
            return bad("modulus.relaxed must be > 0 (the forces are in its units)");
        }
        match (self.force, self.approach) {
            (Some(v), None) | (None, Some(v)) if v.is_finite() && v > 0.0 => {}
            (Some(_), Some(_)) | (None, None) => {
                return bad("give either force (f = F/(E_relaxed h L)) or approach (d/h), not both")
            }
            _ => return bad("force or approach must be finite and > 0"),
        }
        if !(self.ramp.is_finite() && self.ramp > 0.0 && self.hold.is_finite() && self.hold >= 0.0)
        {
            return bad("ramp must be > 0 and hold >= 0, both finite");
        }
        if !(self.unload.is_finite() && (0.0..1.0).contains(&self.unload)) {
            return bad("unload must lie in [0, 1) (a fraction of the force or approach)");
        }
        count_in("steps", self.steps as u64, 2..=MAX_STEPS)?;
        // The integration is exact for piecewise-linear displacement at any step, but a
        // step longer than a relaxation time cannot resolve that term's response.
        let tau_min = self
            .modulus
            .terms
            .iter()
            .map(|t| t[1])
            .fold(f64::INFINITY, f64::min);
        if self.dt() > tau_min {
            let needed = (self.ramp / tau_min).ceil();
            let advice = if needed <= MAX_STEPS as f64 {
                format!("give steps >= {needed}")
            } else {
                format!(
                    "steps would need {needed:.3e}, past the largest, {MAX_STEPS}: lengthen \
                     the shortest relaxation time or shorten the ramp"
                )
            };
            return bad(format!(
                "the time step ramp / steps = {:.3e} exceeds the shortest relaxation time \
                 modulus.terms tau = {tau_min:.3e}: {advice}",
                self.dt(),
            ));
        }
        // Counted before the history is built, so that no huge hold allocates.
        if self.hold / self.dt() + 3.0 * self.steps as f64 > 1e6 {
            return bad("the history has more than 1e6 steps (hold / (ramp / steps))");
        }
        crate::checks::check_tolerance(self.tolerance)?;
        LambdaSpec::check_all(&self.lambda, ctx, &[self.hurst])?;
        let g = self.grid() as f64;
        // Two solvers (viscoelastic, elastic) per realisation, one realisation per thread.
        check_memory_per_thread(
            g * g * cell_bytes::VISCOELASTIC_ROUGH,
            &format!("3D grids of {g}^2 cells, two per thread"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        [STAGES_3D, &[Stage::Viscoelastic]].concat()
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let lambdas = LambdaSpec::at_hurst(&self.lambda, env.ctx, self.hurst)?;
        let (relaxation, prony) = (self.relaxation()?, self.prony()?);
        let runs_3d = out.stages_together(STAGES_3D, || {
            (0..self.realisations_3d)
                .into_par_iter()
                .map(|r| runs::run_3d(self, &relaxation, r))
                .collect::<Result<Vec<_>>>()
        })?;
        let runs_1d = out.stage(Stage::Viscoelastic, || {
            lambdas
                .iter()
                .map(|&lam| {
                    (0..self.realisations_1d)
                        .into_par_iter()
                        .map(|r| runs::run_1d(self, &prony, lam, r))
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        let runs = runs::Runs {
            lambdas,
            d3: runs_3d,
            d1: runs_1d,
        };
        report::report(self, &runs, out);
        radok::report(self, &runs, out);
        Ok(())
    }
}
