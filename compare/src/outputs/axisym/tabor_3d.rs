//! `tabor_3d`: where MRD's adhesion holds as the range of adhesion grows: the pull-off
//! force of a sphere against the Tabor-Maugis parameter lambda, in 3D with the
//! Maugis-Dugdale or the exponential law (`bem3d::cohesive`, key `law`), in Maugis'
//! closed form (the Dugdale law's; for the exponential law a reference, not its answer),
//! and by MRD's rule of Hess with Eq. 33, which is the zero-range (JKR) limit: -3/2 pi w
//! R whatever lambda.
//!
//! Each lambda sets the cohesive stress sigma0 = lambda (2 pi w E*^2 / (9 R))^(1/3) (the
//! exponential law's peak tension) and the range w / sigma0. The 3D grid is free, of
//! side `extent` times the diameter of the cohesive zone at `depth_max` (rigid estimate
//! sqrt(a^2 + 2 R reach), the reach being the range for the Dugdale law and 9.2 ranges,
//! where the tension falls below 1e-4 sigma0, for the exponential law); the cycle is the
//! one of `adhesion_3d` (approach steps in, and out until the cohesive zone is gone);
//! the pull-off is the smallest force of the unloading.

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::{
    check_adhesive_cycle, default_adhesive_extent, default_adhesive_steps,
};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use bem3d::cohesive::{CohesiveContact, CohesiveLaw, RESOLVED_CELLS};
use bem3d::NonPeriodicHalfSpace;
use mrd::adhesion::{AdhesiveContact as AdhesiveRow, Control};
use mrd::reference::{for_profile, maugis_dugdale};
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tabor3d {
    /// Work of adhesion [energy / length^2].
    gamma: f64,
    /// Tabor-Maugis parameters of the 3D runs.
    lambdas: Vec<f64>,
    /// Depth of the loading [length].
    depth_max: f64,
    /// Cells per side of the 3D grids, coarse to fine.
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Side of the grid over the cohesive zone's diameter at `depth_max`.
    #[serde(default = "default_adhesive_extent")]
    extent: f64,
    /// Approach steps of the loading (the unloading goes by the same step).
    #[serde(default = "default_adhesive_steps")]
    steps: usize,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
    /// The traction-gap law of the 3D runs: "dugdale" (Maugis-Dugdale, default) or
    /// "exponential".
    #[serde(default)]
    law: Law,
}

/// `law = "dugdale"` (the default) or `"exponential"`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
enum Law {
    #[default]
    Dugdale,
    Exponential,
}

impl Law {
    /// The figure's title and the 3D series' qualifier.
    fn labels(self) -> (&'static str, &'static str) {
        match self {
            Self::Dugdale => (
                "Pull-off of a sphere against the Tabor-Maugis parameter: 3D, Maugis and MRD",
                "",
            ),
            Self::Exponential => (
                "Sphere pull-off against the Tabor parameter: 3D exponential law, Maugis, MRD",
                " exponential law,",
            ),
        }
    }

    fn solver(self) -> CohesiveLaw {
        match self {
            Self::Dugdale => CohesiveLaw::Dugdale,
            Self::Exponential => CohesiveLaw::Exponential,
        }
    }
}

fn default_cells() -> Vec<usize> {
    vec![64, 128]
}

/// One 3D run: lambda, cells, cell size, Dugdale length, pull-off force.
struct Run {
    lambda: f64,
    cells: usize,
    h: f64,
    dugdale: f64,
    pull_off: f64,
}

impl Output for Tabor3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("tabor_3d needs a sphere (profile = paraboloid): Maugis' closed form is the sphere's");
        }
        if self.lambdas.is_empty() || self.lambdas.iter().any(|l| !(*l >= 0.01 && *l <= 100.0)) {
            return bad(format!(
                "lambdas = {:?}: give Tabor-Maugis parameters in [0.01, 100]",
                self.lambdas
            ));
        }
        check_adhesive_cycle(
            self.gamma,
            self.depth_max,
            &self.cells,
            self.extent,
            self.steps,
            self.tolerance,
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![
            Stage::HessTransform,
            Stage::AdhesionSemiAnalytic,
            Stage::ClosedForm,
            Stage::Adhesion3d,
        ]
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let radius = for_profile::sphere_radius(env.ctx.profile()?).unwrap_or(1.0);
        let e = env.ctx.material.e_star;
        let (mrd, a_top) = out
            .stage(
                Stage::AdhesionSemiAnalytic,
                || -> mrd::Result<(f64, f64)> {
                    let top = contact.state_at_depth(self.depth_max)?;
                    let ad = AdhesiveRow::new(contact.clone(), self.gamma)?;
                    Ok((ad.pull_off(top.radius, Control::Force)?.force, top.radius))
                },
            )
            .ctx("MRD adhesion")?;
        let scale = PI * self.gamma * radius;
        let closed: Vec<f64> = out.stage(Stage::ClosedForm, || {
            self.lambdas
                .iter()
                .map(|l| maugis_dugdale::pull_off(*l))
                .collect()
        });
        let runs = out
            .stage(Stage::Adhesion3d, || {
                let mut runs = Vec::new();
                for &lambda in &self.lambdas {
                    for &n in &self.cells {
                        runs.push(self.run_3d(lambda, n, radius, e, a_top)?);
                    }
                }
                Ok::<_, bem3d::BemError>(runs)
            })
            .ctx("3D cohesive contact")?;
        self.report(env, out, (mrd / scale, &closed), &runs, scale);
        Ok(())
    }
}

impl Tabor3d {
    fn run_3d(&self, lambda: f64, n: usize, r: f64, e: f64, a_top: f64) -> bem3d::Result<Run> {
        let sigma0 = lambda * (2.0 * PI * self.gamma * e * e / (9.0 * r)).cbrt();
        let range = self.gamma / sigma0;
        // The gap over which the law pulls: the range (Dugdale), or where the exponential
        // tension has fallen below 1e-4 sigma0 (ln 1e4 = 9.2 ranges).
        let reach = match self.law {
            Law::Dugdale => range,
            Law::Exponential => range * 1e4f64.ln(),
        };
        let l = self.extent * 2.0 * (a_top * a_top + 2.0 * r * reach).sqrt();
        let h = l / n as f64;
        let heights = bem3d::mask::centred(n, l, |x, y| -(x * x + y * y) / (2.0 * r));
        let apex = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let op = NonPeriodicHalfSpace::new(n, n, l, l, e);
        let mut c = CohesiveContact::new(op, &heights, None, self.gamma, sigma0)?
            .with_law(self.law.solver());
        let dd = self.depth_max / self.steps as f64;
        for k in 1..=self.steps {
            c.step(dd * k as f64 + apex, self.tolerance)?;
        }
        let mut pull_off = f64::INFINITY;
        let mut apart = false;
        for k in 0..100 * self.steps {
            let s = c.step(self.depth_max - dd * k as f64 + apex, self.tolerance)?;
            pull_off = pull_off.min(s.force);
            if s.contact_cells == 0 && s.cohesive_cells == 0 {
                apart = true;
                break;
            }
        }
        if !apart {
            return Err(bem3d::BemError::Infeasible(format!(
                "lambda = {lambda}: the sphere did not come apart within {} approach steps",
                100 * self.steps
            )));
        }
        Ok(Run {
            lambda,
            cells: n,
            h,
            dugdale: c.dugdale_length(),
            pull_off,
        })
    }

    fn report(
        &self,
        env: &Env,
        out: &mut Section,
        (mrd, closed): (f64, &[f64]),
        runs: &[Run],
        scale: f64,
    ) {
        let force = env.ctx.units.force();
        let mut t = Table::new(
            "tabor",
            &[
                "lambda [1]".to_string(),
                "cells [cells]".to_string(),
                "cells_per_dugdale_length [1]".to_string(),
                "resolved [0/1]".to_string(),
                "pull_off_3d_over_pi_w_r [1]".to_string(),
                "pull_off_maugis_over_pi_w_r [1]".to_string(),
                "pull_off_mrd_over_pi_w_r [1]".to_string(),
                "rel_error_3d_vs_maugis [1]".to_string(),
                "rel_error_mrd_vs_maugis [1]".to_string(),
            ],
        );
        t.notes.push(format!(
            "pull-off force over pi w R (pi w R = {scale:e} [{force}]), force control (the smallest force of the approach-controlled unloading); 3D: {} on the free half-space, resolved when the Dugdale length E* w / sigma0^2 spans {RESOLVED_CELLS} cells; MRD: rule of Hess with Eq. 33 (zero range: JKR)",
            match self.law {
                Law::Dugdale => "Maugis-Dugdale law",
                Law::Exponential => "exponential law (tension sigma0 exp(-gap / rho), rho = w / sigma0; the Maugis column is the Dugdale law's closed form, a reference, and rel_error_3d_vs_maugis the departure from it)",
            }
        ));
        // The largest error over the resolved lambdas on the finest grid; with none
        // resolved there is no converged error to report (NaN, null in summary.json).
        let (mut worst, mut unresolved) = (f64::NAN, 0usize);
        let finest = *self.cells.last().unwrap_or(&0);
        for run in runs {
            let k = self
                .lambdas
                .iter()
                .position(|l| *l == run.lambda)
                .unwrap_or(0);
            let per = run.dugdale / run.h;
            let resolved = per >= RESOLVED_CELLS;
            let p3 = run.pull_off / scale;
            let err = p3 / closed[k] - 1.0;
            if run.cells == finest {
                if resolved {
                    worst = worst.max(err.abs());
                } else {
                    unresolved += 1;
                }
            }
            t.push(vec![
                run.lambda,
                run.cells as f64,
                per,
                resolved as u8 as f64,
                p3,
                closed[k],
                mrd,
                err,
                mrd / closed[k] - 1.0,
            ]);
        }
        out.scalar(
            match self.law {
                Law::Dugdale => "rel_error_3d_vs_maugis_max_resolved",
                Law::Exponential => "rel_dev_3d_exponential_vs_maugis_max_resolved",
            },
            worst,
        );
        out.scalar("unresolved_lambdas", unresolved as f64);
        let (lo, hi) = self
            .lambdas
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), l| (a.min(*l), b.max(*l)));
        out.scalar(
            "rel_error_mrd_vs_maugis_at_smallest_lambda",
            mrd / maugis_dugdale::pull_off(lo) - 1.0,
        );
        out.scalar(
            "rel_error_mrd_vs_maugis_at_largest_lambda",
            mrd / maugis_dugdale::pull_off(hi) - 1.0,
        );
        if unresolved > 0 {
            out.warnings.push(format!(
                "tabor_3d: {unresolved} lambda(s) not resolved on the finest grid (the Dugdale length spans fewer than {RESOLVED_CELLS} cells): their 3D pull-off is not converged"
            ));
        }
        let curve: Vec<(f64, f64)> = (0..=60)
            .map(|k| {
                let l = (lo / 3.0) * (9.0 * hi / lo).powf(k as f64 / 60.0);
                (l, -maugis_dugdale::pull_off(l))
            })
            .collect();
        let ends = vec![(curve[0].0, -mrd), (curve[60].0, -mrd)];
        let (title, law) = self.law.labels();
        let mut fig = Figure::new(
            "tabor",
            title,
            "Tabor-Maugis parameter lambda [1]",
            "pull-off force -F / (pi w R) [1]",
        )
        .plot("Maugis-Dugdale (closed form)", curve, Style::Line)
        .plot("MRD (rule of Hess, Eq. 33: JKR)", ends, Style::Dashed);
        for (k, &n) in self.cells.iter().enumerate() {
            let pts = |res: bool| -> Vec<(f64, f64)> {
                t.rows
                    .iter()
                    .filter(|r| r[1] == n as f64 && (r[3] == 1.0) == res)
                    .map(|r| (r[0], -r[4]))
                    .collect()
            };
            let style = if k + 1 == self.cells.len() {
                Style::Markers
            } else {
                Style::Crosses
            };
            let resolved = pts(true);
            if !resolved.is_empty() {
                fig = fig.plot(format!("3D,{law} {n}^2 cells"), resolved, style);
            }
            let rest = pts(false);
            if !rest.is_empty() {
                fig = fig.plot(
                    format!(
                        "3D,{law} {n}^2 cells, unresolved (< {RESOLVED_CELLS} cells per Dugdale length)"
                    ),
                    rest,
                    Style::Crosses,
                );
            }
        }
        fig.log_x = true;
        out.tables.push(t);
        out.figures.push(fig);
    }
}
