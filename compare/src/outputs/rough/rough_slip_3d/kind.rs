//! `RoughSlip3d` as an output kind: its checks, its declared stages and its run.

use super::runs::{run_1d, run_3d, unit_rms_scale, Case};
use super::{report, RoughSlip3d};
use crate::checks::{bad, check_memory_per_thread, check_tolerance, count_in, positive};
use crate::checks::{cell_bytes, check_ensembles};
use crate::context::Context;
use crate::error::Result;
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::progress::Progress;
use crate::experiment::rough_body::{check_cases, check_map, Body};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use rayon::prelude::*;

/// The stages of the 3D realisations, run together on the pool.
const STAGES_3D: &[Stage] = &[
    Stage::RoughSynthesis,
    Stage::Bem3d,
    Stage::Bem3dStiffness,
    Stage::Tangential3d,
];
/// The stages of the MRD lines, after the 3D ones.
const STAGES_MRD: &[Stage] = &[Stage::RoughContact, Stage::Tangential];

impl Output for RoughSlip3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        let size = Body::check(self.radius, self.punch_radius)?;
        crate::checks::check_magnitudes(&[
            ("radius or punch_radius", size),
            ("force", self.force),
            ("side", self.side),
        ])?;
        let e_star = ctx.material.e_star;
        if self.smooth_approach(e_star) > 0.1 * size {
            return bad(format!(
                "force = {:e} presses the smooth body by {:.3e} > 0.1 of its radius: give a smaller force (small slopes)",
                self.force,
                self.smooth_approach(e_star)
            ));
        }
        if !(positive(self.mu) && self.mu <= 10.0) {
            return bad(format!("mu = {} must lie in (0, 10]", self.mu));
        }
        if self.poisson.is_empty() || self.poisson.iter().any(|nu| !(0.0..=0.5).contains(nu)) {
            return bad(format!(
                "poisson = {:?}: give Poisson's ratios in [0, 0.5]",
                self.poisson
            ));
        }
        check_cases(
            &self.hurst,
            &self.roughness,
            "the smooth approach d_0",
            &self.cells,
            self.bandwidth,
        )?;
        let a = self.contact_radius(e_star);
        check_map(self.side, a, "the smooth body's at F_N", &self.cells)?;
        crate::checks::check_fractions("fractions", &self.fractions, true)?;
        crate::experiment::tangential_map::check_amplitudes(&self.amplitudes, self.tolerance)?;
        check_ensembles(self.realisations_3d, self.realisations_1d)?;
        count_in("points_1d_factor", self.points_1d_factor as u64, 1..=64)?;
        count_in("steps", self.steps as u64, 2..=1000)?;
        check_tolerance(self.tolerance)?;
        LambdaSpec::check_all(&self.lambda, ctx, &self.hurst)?;
        let n = *self.cells.last().unwrap_or(&16) as f64;
        check_memory_per_thread(
            n * n * cell_bytes::ROUGH_SLIP,
            &format!("3D grids of {n}^2 cells, one per thread"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        [STAGES_3D, STAGES_MRD].concat()
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let e_star = env.ctx.material.e_star;
        // lambda per scene entry, per Hurst exponent.
        let lambdas = LambdaSpec::per_hurst(&self.lambda, env.ctx, &self.hurst)?;
        let cases = self.cases();
        let total: u64 = cases
            .iter()
            .map(|&(_, rough)| self.realisations(rough, self.realisations_3d))
            .sum::<u64>()
            * self.cells.len() as u64;
        let bar = Progress::new(
            env.control.progress,
            total as usize,
            "3D partial slip (case x grid x surface)",
            "surfaces",
        );
        let mut all: Vec<Case> = out.stages_together(STAGES_3D, || {
            cases
                .iter()
                .map(|&(hurst, roughness)| {
                    let how = (hurst, roughness, unit_rms_scale(self, hurst, roughness)?);
                    let runs_3d = self
                        .cells
                        .iter()
                        .map(|&n| {
                            // The stick map of the first surface on the finest grid.
                            let finest = Some(&n) == self.cells.last();
                            (0..self.realisations(roughness, self.realisations_3d))
                                .into_par_iter()
                                .map(|r| {
                                    let run = run_3d(self, how, (n, finest && r == 0), r, e_star);
                                    bar.inc();
                                    run
                                })
                                .collect::<Result<Vec<_>>>()
                        })
                        .collect::<Result<Vec<_>>>()?;
                    Ok(Case {
                        hurst,
                        roughness,
                        runs_3d,
                        runs_1d: Vec::new(),
                    })
                })
                .collect::<Result<_>>()
        })?;
        bar.finish();
        out.stages_together(STAGES_MRD, || {
            for case in all.iter_mut() {
                let hi = self.hurst.iter().position(|&x| x == case.hurst);
                let how = (
                    case.hurst,
                    case.roughness,
                    unit_rms_scale(self, case.hurst, case.roughness)?,
                );
                case.runs_1d = lambdas
                    .iter()
                    .map(|l| {
                        // The smooth body has no line: any lambda gives it.
                        let lambda = hi.map_or(1.0, |i| l[i]);
                        (0..self.realisations(case.roughness, self.realisations_1d))
                            .into_par_iter()
                            .map(|r| run_1d(self, how, lambda, r, e_star))
                            .collect::<Result<Vec<_>>>()
                    })
                    .collect::<Result<_>>()?;
            }
            Ok::<_, crate::error::CompareError>(())
        })?;
        report::report(self, env, &lambdas, &all, out);
        Ok(())
    }
}
