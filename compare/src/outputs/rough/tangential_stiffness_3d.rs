//! `tangential_stiffness_3d`: MRD's tangential springs on a rough contact, against 3D.
//!
//! MRD gives every normal spring E* dx a tangential partner G* dx (Eqs. 3 and 6), so a
//! contact held in stick has k_t / k_n = G* / E* = 2 (1 - nu) / (2 - nu) whatever its
//! shape: Mindlin's ratio for one circle, and the ratio Campana, Persson & Mueser
//! (J. Phys.: Condens. Matter 23, 085001, 2011) derived for randomly rough interfaces.
//! In 3D, many small contacts interact through Cerruti's anisotropic kernel, so the
//! ratio is a measurement. Here:
//!
//! - 3D: rigid self-affine surfaces (C2D ~ q^(-2H-2) from the period L = 1 to the
//!   shortest wavelength L / `bandwidth`, nested synthesis: a finer grid samples the same
//!   surface) pressed on the periodic half-space, force controlled at mean pressures
//!   p = `pressures` x E* h' (h' the rms slope of the band, the same for every
//!   realisation); k_n = dF/dd with the contact set held
//!   ([`bem3d::ContactSolver::tangent_stiffness`]), k_t the stick stiffness of that set
//!   from Cerruti's whole tensor along x and along y ([`bem3d::tangential::StickStiffness`],
//!   both measured from the mean surface displacement), for each Poisson's ratio; the
//!   normal contact does not depend on nu (E* fixed; the normal-tangential coupling
//!   vanishes at nu = 0.5 and is neglected otherwise, as MRD does).
//! - MRD: G* / E* of a rigid indenter on the substrate of that nu (Eqs. 2 and 5).
//!
//! Each point is the mean over realisations of k_t / k_n (x and y averaged), with the 95 %
//! interval of that mean (normal approximation); each grid of the `cells` ladder is a
//! refinement of the same surfaces.

use crate::checks::{bad, cell_bytes, check_tolerance, positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::periodic::{Ensemble, Ladder};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::tangential::CerrutiPeriodic;
use mrd::material::{ElasticBody, Material};
use mrd::rough_contact::Stat;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialStiffness3d {
    /// Hurst exponents, each in [0, 1].
    hurst: Vec<f64>,
    /// Poisson's ratios of the substrate, each in [0, 0.5].
    poisson: Vec<f64>,
    /// Shortest wavelength L / bandwidth; the period L is 1.
    bandwidth: usize,
    /// Cells per shortest wavelength, coarse to fine (a refinement ladder).
    cells: Vec<usize>,
    /// Mean pressures over E* h' (h' the rms slope), increasing.
    pressures: Vec<f64>,
    /// Rough surfaces per Hurst exponent.
    realisations: u64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "crate::checks::default_tolerance")]
    tolerance: f64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
}

/// One realisation on one grid: per pressure, the contact fraction, k_n and k_t / k_n
/// per Poisson's ratio (x and y averaged; and along x with q_y = 0).
struct Run {
    area: Vec<f64>,
    kn: Vec<f64>,
    ratio: Vec<Vec<f64>>,
    ratio_along_only: Vec<Vec<f64>>,
}

/// The stages of the 3D realisations, run together on the pool.
const STAGES_3D: &[Stage] = &[Stage::RoughSynthesis, Stage::Bem3d, Stage::Bem3dStiffness];

impl Output for TangentialStiffness3d {
    fn validate(&self, _: &Context) -> Result<()> {
        // Beside the normal solver: the stick solves on the Cerruti tensor (two
        // components per cell). Measured peaks of one realisation (process included):
        // 340 bytes per cell at 1024^2, 294 at 2048^2; each further Poisson's ratio adds
        // under 2.
        self.ladder().check(cell_bytes::TANGENTIAL_STIFFNESS)?;
        if self.pressures.is_empty() {
            return bad("pressures needs at least one entry");
        }
        if self.pressures.iter().any(|p| !(positive(*p) && *p <= 10.0))
            || self.pressures.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "pressures = {:?}: give increasing mean pressures over E* h' in (0, 10]",
                self.pressures
            ));
        }
        check_tolerance(self.tolerance)?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        [STAGES_3D, &[Stage::Tangential]].concat()
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let e_star = env.ctx.material.e_star;
        let runs = out.stages_together(STAGES_3D, || {
            self.ladder()
                .run(|h, cells, r| self.run_3d(h, cells, r, e_star))
        })?;
        let mrd = out.stage(Stage::Tangential, || {
            self.poisson
                .iter()
                .map(|&nu| mrd_ratio(e_star, nu))
                .collect::<Result<Vec<_>>>()
        })?;
        self.report(out, &runs, &mrd);
        Ok(())
    }
}

/// MRD's k_t / k_n: G* / E* of a rigid indenter on a substrate of modulus E* and `nu`.
fn mrd_ratio(e_star: f64, nu: f64) -> Result<f64> {
    let rigid = ElasticBody::new(f64::INFINITY, nu).ctx("indenter")?;
    let substrate = ElasticBody::new(e_star * (1.0 - nu * nu), nu).ctx("substrate")?;
    let m = Material::from_bodies(rigid, substrate).ctx("material")?;
    Ok(m.g_star().ctx("G*")? / m.e_star)
}

impl TangentialStiffness3d {
    fn ladder(&self) -> Ladder<'_> {
        Ladder {
            hurst: &self.hurst,
            poisson: &self.poisson,
            bandwidth: self.bandwidth,
            cells: &self.cells,
            realisations: self.realisations,
            seed: self.seed,
        }
    }

    fn run_3d(&self, hurst: f64, cells: usize, r: u64, e_star: f64) -> Result<Run> {
        let mut real = self
            .ladder()
            .realise(hurst, cells, r, e_star, self.tolerance)?;
        let (n, slope) = (real.n, real.patch.rms_slope);
        let mut cerruti: Vec<CerrutiPeriodic> = self
            .poisson
            .iter()
            .map(|&nu| CerrutiPeriodic::new(n, n, 1.0, 1.0, e_star * (1.0 - nu) / 2.0, nu))
            .collect::<bem3d::Result<_>>()
            .ctx("Cerruti operator")?;
        let np = self.pressures.len();
        let mut run = Run {
            area: Vec::with_capacity(np),
            kn: Vec::with_capacity(np),
            ratio: vec![Vec::with_capacity(np); self.poisson.len()],
            ratio_along_only: vec![Vec::with_capacity(np); self.poisson.len()],
        };
        let mut warm: Option<bem3d::Solution> = None;
        for &p in &self.pressures {
            let (sol, kn) = real.normal_at(p * e_star * slope, warm.as_ref())?;
            let contact: Vec<bool> = sol.pressure.iter().map(|&p| p > 0.0).collect();
            run.area
                .push(contact.iter().filter(|c| **c).count() as f64 / (n * n) as f64);
            run.kn.push(kn);
            for (k, op) in cerruti.iter_mut().enumerate() {
                let kt = op
                    .stick_stiffness(&contact, self.tolerance, real.opts.max_iterations)
                    .ctx("3D stick stiffness")?;
                run.ratio[k].push(0.5 * (kt.x + kt.y) / kn);
                run.ratio_along_only[k].push(kt.x_along_only / kt.x);
            }
            warm = Some(sol);
        }
        Ok(run)
    }

    fn report(&self, out: &mut Section, runs: &[Ensemble<Run>], mrd: &[f64]) {
        let cols = [
            "hurst [1]",
            "poisson [1]",
            "cells_per_shortest_wavelength [1]",
            "grid [cells]",
            "pressure_over_e_star_rms_slope [1]",
            "area_fraction_mean [1]",
            "kn_mean [force/length]",
            "kt_over_kn_mean [1]",
            "kt_over_kn_ci95_low [1]",
            "kt_over_kn_ci95_high [1]",
            "kt_over_kn_mrd [1]",
            "rel_dev_3d_vs_mrd [1]",
            "kt_along_only_over_kt_mean [1]",
        ];
        let mut t = Table::new("stiffness_ratio", &cols);
        t.notes.push(format!(
            "periodic self-affine surfaces, period 1, bandwidth {}, {} realisations (nested: each grid of a hurst samples the same surfaces); kt: Cerruti stick stiffness along x and y averaged; kn: dF/dd with the contact set held; interval: mean +- 1.96 standard errors over realisations; MRD: G*/E* (Eqs. 2, 5); kt_along_only: traction along x only (q_y = 0)",
            self.bandwidth, self.realisations
        ));
        let finest = *self.cells.last().unwrap_or(&0);
        let (mut worst, mut along_worst) = (0.0f64, 0.0f64);
        let mean_of = |h: f64, cells: usize, k: usize, j: usize| -> Option<f64> {
            runs.iter()
                .find(|(hh, c, _)| *hh == h && *c == cells)
                .map(|(_, _, ens)| {
                    Stat::of(&ens.iter().map(|r| r.ratio[k][j]).collect::<Vec<_>>()).mean
                })
        };
        let mut grid_change = 0.0f64;
        for (h, cells, ens) in runs {
            for (k, &nu) in self.poisson.iter().enumerate() {
                for (j, &p) in self.pressures.iter().enumerate() {
                    let of =
                        |f: &dyn Fn(&Run) -> f64| Stat::of(&ens.iter().map(f).collect::<Vec<_>>());
                    let ratio = of(&|r| r.ratio[k][j]);
                    let along = of(&|r| r.ratio_along_only[k][j]);
                    let dev = ratio.mean / mrd[k] - 1.0;
                    if *cells == finest {
                        worst = worst.max(dev.abs());
                        along_worst = along_worst.max((along.mean - 1.0).abs());
                        if self.cells.len() > 1 {
                            let coarse = self.cells[self.cells.len() - 2];
                            if let Some(c) = mean_of(*h, coarse, k, j) {
                                grid_change = grid_change.max((ratio.mean / c - 1.0).abs());
                            }
                        }
                    }
                    t.push(vec![
                        *h,
                        nu,
                        *cells as f64,
                        (*cells * self.bandwidth) as f64,
                        p,
                        of(&|r| r.area[j]).mean,
                        of(&|r| r.kn[j]).mean,
                        ratio.mean,
                        ratio.mean - ratio.ci95,
                        ratio.mean + ratio.ci95,
                        mrd[k],
                        dev,
                        along.mean,
                    ]);
                }
            }
        }
        out.scalar("kt_over_kn_max_rel_dev_3d_vs_mrd", worst);
        out.scalar("kt_over_kn_max_rel_change_last_refinement", grid_change);
        out.scalar("kt_along_only_max_rel_dev", along_worst);
        out.figures.push(self.figure(&t, mrd, finest));
        out.tables.push(t);
    }

    fn figure(&self, t: &Table, mrd: &[f64], finest: usize) -> Figure {
        let mut fig = Figure::new(
            "stiffness_ratio",
            "Tangential over normal stiffness of rough contacts: 3D against MRD's G*/E*",
            "contact area fraction [1]",
            "k_t / k_n [1]",
        );
        let (lo, hi) = t
            .column("area_fraction_mean [1]")
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
        // One colour per Poisson's ratio (its MRD line and its 3D points), one marker per
        // Hurst exponent.
        for (k, &nu) in self.poisson.iter().enumerate() {
            fig = fig.with(
                Series::new(
                    format!("MRD and Mindlin, nu = {nu}: 2 (1 - nu) / (2 - nu)"),
                    vec![(lo, mrd[k]), (hi, mrd[k])],
                    Style::Dashed,
                )
                .colored(k),
            );
            for (i, &h) in self.hurst.iter().enumerate() {
                let rows: Vec<&Vec<f64>> = t
                    .rows
                    .iter()
                    .filter(|r| r[0] == h && r[1] == nu && r[2] == finest as f64)
                    .collect();
                let style = if i % 2 == 0 {
                    Style::Markers
                } else {
                    Style::Crosses
                };
                fig = fig.with(
                    Series::new(
                        format!(
                            "3D, H = {h}, nu = {nu}: mean of {} surfaces on {}^2 cells, 95 % interval",
                            self.realisations,
                            finest * self.bandwidth
                        ),
                        rows.iter().map(|r| (r[5], r[7])).collect(),
                        style,
                    )
                    .with_bars(rows.iter().map(|r| (r[5], r[8], r[9])).collect())
                    .colored(k),
                );
            }
        }
        fig.log_x = true;
        fig
    }
}
