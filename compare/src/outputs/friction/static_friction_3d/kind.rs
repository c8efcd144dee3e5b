//! `StaticFriction3d` as an output kind: its checks, its declared stages and its run, which
//! calls the study's parts; the parameters and their defaults are in the parent module.

use super::{report, runs};
use super::{Geometry, StaticFriction3d};
use crate::checks::{
    bad, cell_bytes, check_memory_per_thread, count_in, positive, require_positive,
};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use rayon::prelude::*;

impl Output for StaticFriction3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if self.hurst.is_empty() || self.geometry.is_empty() || self.lambda.is_empty() {
            return bad("hurst, geometry and lambda need at least one entry each");
        }
        if let Some(h) = self.hurst.iter().find(|h| !(0.0..=1.0).contains(*h)) {
            return bad(format!("hurst = {h} must lie in [0, 1]"));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=512)?;
        count_in("cells", self.cells as u64, 4..=64)?;
        let n = self.grid(self.cells) as u64;
        count_in("cells x bandwidth", n, 16..=4096)?;
        crate::checks::check_ensembles(self.realisations_3d, self.realisations_1d)?;
        count_in(
            "f_points",
            self.f_points as u64,
            3..=crate::checks::MAX_LOADS,
        )?;
        if !(positive(self.f_min) && positive(self.f_max) && self.f_max > self.f_min) {
            return bad("need 0 < f_min < f_max");
        }
        if !(self.fit_max_area > 0.0 && self.fit_max_area <= 1.0) {
            return bad("fit_max_area must lie in (0, 1]");
        }
        crate::checks::check_tolerance(self.tolerance)?;
        LambdaSpec::check_all(&self.lambda, ctx, &self.hurst)?;
        if let Some(r) = &self.refine {
            if !self.hurst.contains(&r.hurst) || !self.geometry.contains(&r.geometry) {
                return bad("refine: hurst and geometry must be among the output's");
            }
            require_positive("refine: f", r.f)?;
            count_in("refine: 2 x cells x bandwidth", 2 * n, 16..=4096)?;
        }
        // One solver per worker thread: the largest of the geometries' grids (the
        // refinement's is twice as fine).
        let (bytes, side) = self
            .geometry
            .iter()
            .map(|&g| {
                let refined = self.refine.as_ref().is_some_and(|r| r.geometry == g);
                let side = if refined { 2 * n } else { n } as f64;
                let per_cell = match g {
                    Geometry::Periodic => cell_bytes::ROUGH_PERIODIC,
                    Geometry::Disc => cell_bytes::ROUGH_FREE,
                };
                (side * side * per_cell, side)
            })
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        check_memory_per_thread(
            bytes,
            &format!("3D grids of {side}^2 cells, one per thread"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Bem3d, Stage::RoughContact]
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let fs = self.f_grid();
        let lambdas: Vec<_> = self
            .lambda
            .iter()
            .map(|l| l.build(env.ctx))
            .collect::<Result<_>>()?;
        let mut cases = Vec::new();
        let pairs: Vec<(Geometry, f64)> = self
            .geometry
            .iter()
            .flat_map(|&g| self.hurst.iter().map(move |&h| (g, h)))
            .collect();
        let all_3d = out.stages_together(&[Stage::RoughSynthesis, Stage::Bem3d], || {
            pairs
                .iter()
                .map(|&(g, h)| {
                    (0..self.realisations_3d)
                        .into_par_iter()
                        .map(|r| runs::solve_3d(self, g, h, r, self.cells, &fs))
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        let refined = match &self.refine {
            Some(rf) => {
                let k = self.refine_index(rf);
                let one = [fs[k]];
                let fine = out.stages_together(&[Stage::RoughSynthesis, Stage::Bem3d], || {
                    (0..self.realisations_3d)
                        .into_par_iter()
                        .map(|r| {
                            runs::solve_3d(self, rf.geometry, rf.hurst, r, 2 * self.cells, &one)
                        })
                        .collect::<Result<Vec<_>>>()
                })?;
                Some((rf.clone(), k, fine))
            }
            None => None,
        };
        let all_1d = out.stage(Stage::RoughContact, || {
            pairs
                .iter()
                .zip(&all_3d)
                .map(|(&(g, h), r3)| {
                    let h3 = runs::mean_rms_height(r3);
                    lambdas
                        .iter()
                        .map(|law| {
                            let lam = law.at(h).ctx("lambda")?;
                            (0..self.realisations_1d)
                                .into_par_iter()
                                .map(|r| runs::press_line(self, g, h, lam, h3, r, &fs))
                                .collect::<Result<Vec<_>>>()
                                .map(|lines| (lam, lines))
                        })
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        for ((&(g, h), r3), r1) in pairs.iter().zip(all_3d).zip(all_1d) {
            cases.push(report::Case {
                geometry: g,
                hurst: h,
                runs_3d: r3,
                runs_1d: r1,
            });
        }
        report::report(self, &fs, &cases, refined.as_ref(), out);
        Ok(())
    }
}
