//! `RoughAdhesion3d` as an output kind: its checks, its declared stages and its run.

use super::cycles::{cycle_1d, cycle_3d, unit_rms_scale, Cases};
use super::{report, RoughAdhesion3d, Variant};
use crate::checks::{bad, check_memory_per_thread, check_tolerance, count_in};
use crate::checks::{cell_bytes, check_ensembles};
use crate::context::Context;
use crate::error::Result;
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::progress::Progress;
use crate::experiment::rough_body::{check_cases, check_map, realisations, Body};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use rayon::prelude::*;

/// Largest adhesion length and rms height over `depth_max` (the embedded scenes reach
/// 2.8).
const MAX_LENGTH_OVER_DEPTH_MAX: f64 = 10.0;

/// The stages of the 3D cycles, run together on the pool.
const STAGES_3D: &[Stage] = &[Stage::RoughSynthesis, Stage::Adhesion3d];

impl Output for RoughAdhesion3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        let size = Body::check(self.radius, self.punch_radius)?;
        crate::checks::check_magnitudes(&[
            ("radius or punch_radius", size),
            ("work", self.work),
            ("depth_max", self.depth_max),
            ("side", self.side),
        ])?;
        if self.depth_max > 0.1 * size {
            return bad("depth_max must be <= 0.1 of the body's radius (small slopes)");
        }
        check_cases(
            &self.hurst,
            &self.roughness,
            "the body's adhesion length",
            &self.cells,
            self.bandwidth,
        )?;
        // The contact's radius: Hertz's sqrt(R depth_max), or the punch's.
        let a = match self.body() {
            Body::Sphere(r) => (r * self.depth_max).sqrt(),
            Body::Punch(a) => a,
        };
        check_map(
            self.side,
            a,
            "sqrt(R depth_max) or the punch's",
            &self.cells,
        )?;
        // The cycle walks from first contact, some 5 rms heights above the apex, to
        // depth_max and back past the jump-out, about one adhesion length below it, in
        // steps of depth_max / steps: both lengths within MAX_LENGTH_OVER_DEPTH_MAX of
        // depth_max keep it within about 50 x steps solves.
        let ell = self.adhesion_length(ctx.material.e_star);
        let rms = ell * self.roughness.iter().fold(0.0f64, |m, r| m.max(*r));
        for (what, length) in [
            ("the adhesion length", ell),
            (
                "the roughest case's rms height (roughness x the adhesion length)",
                rms,
            ),
        ] {
            if length > MAX_LENGTH_OVER_DEPTH_MAX * self.depth_max {
                return bad(format!(
                    "{what} {length:.4e} exceeds {MAX_LENGTH_OVER_DEPTH_MAX} x depth_max = {:.4e}: the cycle would take about {:.0} approach steps of depth_max / steps; raise depth_max or lower work or roughness",
                    MAX_LENGTH_OVER_DEPTH_MAX * self.depth_max,
                    (5.0 * length + self.depth_max) / self.step()
                ));
            }
        }
        check_ensembles(self.realisations_3d, self.realisations_1d)?;
        count_in("points_1d_factor", self.points_1d_factor as u64, 1..=64)?;
        count_in("steps", self.steps as u64, 4..=10_000)?;
        check_tolerance(self.tolerance)?;
        if self.mrd_rule.is_empty() || self.rules().len() != self.mrd_rule.len() {
            return bad(format!(
                "mrd_rule = {:?}: give \"outer\", \"cluster\" or both",
                self.mrd_rule
            ));
        }
        LambdaSpec::check_all(&self.lambda, ctx, &self.hurst)?;
        let n = *self.cells.last().unwrap_or(&16) as f64;
        check_memory_per_thread(
            n * n * cell_bytes::ADHESION,
            &format!("3D grids of {n}^2 cells, one per thread"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        [STAGES_3D, &[Stage::AdhesionDiscrete]].concat()
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let e_star = env.ctx.material.e_star;
        let lambdas = LambdaSpec::per_hurst(&self.lambda, env.ctx, &self.hurst)?;
        let variants: Vec<Variant> = self
            .rules()
            .into_iter()
            .flat_map(|rule| {
                lambdas.iter().map(move |l| Variant {
                    rule,
                    lambda: l.clone(),
                })
            })
            .collect();
        let cases = self.cases();
        let total: u64 = cases
            .iter()
            .map(|&(_, rough)| realisations(rough, self.realisations_3d))
            .sum::<u64>()
            * self.cells.len() as u64;
        let bar = Progress::new(
            env.control.progress,
            total as usize,
            "3D adhesive cycles (case x grid x surface)",
            "cycles",
        );
        let all_3d: Cases = out.stages_together(STAGES_3D, || {
            cases
                .iter()
                .map(|&(h, rough)| {
                    let per_grid = self
                        .cells
                        .iter()
                        .map(|&n| {
                            (0..realisations(rough, self.realisations_3d))
                                .into_par_iter()
                                .map(|r| {
                                    let c = cycle_3d(self, h, rough, n, r, e_star);
                                    bar.inc();
                                    c
                                })
                                .collect::<Result<Vec<_>>>()
                        })
                        .collect::<Result<Vec<_>>>()?;
                    Ok(((h, rough), per_grid))
                })
                .collect::<Result<_>>()
        })?;
        bar.finish();
        let all_1d: Cases = out.stage(Stage::AdhesionDiscrete, || {
            cases
                .iter()
                .map(|&(h, rough)| {
                    let hi = self.hurst.iter().position(|&x| x == h).unwrap_or(0);
                    let scale = unit_rms_scale(self, h, rough)?;
                    let per_variant = variants
                        .iter()
                        .map(|v| {
                            let how = (v.rule.edge(), v.lambda[hi]);
                            (0..realisations(rough, self.realisations_1d))
                                .into_par_iter()
                                .map(|r| cycle_1d(self, (h, rough, scale), how, r, e_star))
                                .collect::<Result<Vec<_>>>()
                        })
                        .collect::<Result<Vec<_>>>()?;
                    Ok(((h, rough), per_variant))
                })
                .collect::<Result<_>>()
        })?;
        report::report(self, env, &variants, &all_3d, &all_1d, out)
    }
}
