//! From the checkpoints of a complete sweep to typed per-H results: ensemble curves on
//! the common f grid, fits of Eq. (77) with bootstrap intervals, the calibrated lambda,
//! the finite-size study and the MRD speed-up at equal statistical error.
//!
//! One random generator, seeded from the sweep's seed, draws every bootstrap resample
//! in a fixed order (per H: each grid's 3D resamples, then, on the main grid, the 1D
//! ones and the paired lambda ones), so results are reproducible bit for bit.

use super::tasks::{load, Task};
use super::HurstSweep;
use crate::error::Result;
use crate::experiment::fit::{
    calibrate_lambda_at, fit_points, fit_window, interp_loglog, interval, mean_curve, resample,
    window_points, Estimate,
};
use crate::experiment::rough_punch::{BemCurve, MrdEnsemble, SolveRecord};
use mrd::rough_contact::Stat;
use mrd::roughness::lambda_cut;
use rand::SeedableRng;
use std::path::Path;

/// Bootstrap resamples per interval.
const RESAMPLES: usize = 200;

/// The range of k/(E* L) lambda is fitted over: the lambda study's, so that the sweep's
/// estimate and the shipped calibration are one quantity.
pub const LAMBDA_WINDOW: (f64, f64) = (0.02, 0.5);

/// Curves of one ensemble on the f grid (`None` outside a realisation's range).
pub type Curves = Vec<Vec<Option<f64>>>;

/// Results at one Hurst exponent on the main grid.
#[derive(Debug, Clone)]
pub struct PerHurst {
    pub hurst: f64,
    pub alpha_3d: Estimate,
    pub alpha_mrd: Estimate,
    pub zeta_3d: Estimate,
    pub zeta_mrd: Estimate,
    /// lambda of Eq. (76) (C1D = lambda q C2D on the same C2D), with its interval.
    pub lambda: Estimate,
    /// The shift of the reduced MRD curve it implies, pi h1^2 / h3^2 (what the fit
    /// finds: `lambda` times the rms factor of the spectrum on the line and the face).
    pub lambda_shift: f64,
    /// Straight-cut lambda (NaN for H <= -1/2).
    pub lambda_cut: f64,
    /// The fitted 3D power law (alpha, zeta), if the window held 3 points.
    pub fit_3d: Option<(f64, f64)>,
    /// Fit window in k/(E* L).
    pub window: (f64, f64),
    /// Ensemble means and their 95 % half-widths on the f grid.
    pub mean_3d: Vec<Option<f64>>,
    pub ci_3d: Vec<f64>,
    pub mean_mrd: Vec<Option<f64>>,
    pub ci_mrd: Vec<f64>,
    pub realisations_3d: usize,
    pub realisations_mrd: usize,
    pub unconverged_3d: usize,
}

/// The 3D alpha at a coarser grid (finite-size study).
#[derive(Debug, Clone)]
pub struct Convergence {
    pub hurst: f64,
    pub grid: usize,
    pub alpha_3d: Estimate,
}

#[derive(Debug, Clone, Default)]
pub struct Results {
    /// The common grid of reduced forces f = F/(E* h L).
    pub f: Vec<f64>,
    pub per_hurst: Vec<PerHurst>,
    pub convergence: Vec<Convergence>,
    pub seconds_3d: f64,
    pub seconds_mrd: f64,
    pub realisations_3d: usize,
    pub realisations_mrd: usize,
    /// Per H: cost ratio of 3D to MRD at equal statistical error of alpha.
    pub speedups: Vec<f64>,
    /// Every 3D solve: (H, grid, realisation, load index, record).
    pub solves: Vec<(f64, usize, usize, usize, SolveRecord)>,
}

/// Ensemble mean's 95 % half-width at each f where the mean exists.
fn half_widths(curves: &Curves, mean: &[Option<f64>]) -> Vec<f64> {
    (0..mean.len())
        .map(|j| match mean[j] {
            Some(_) => Stat::of(&curves.iter().filter_map(|c| c[j]).collect::<Vec<_>>()).ci95,
            None => f64::NAN,
        })
        .collect()
}

/// The 3D curves of one H and grid, interpolated onto the f grid.
/// One component of each bootstrap fit, NaN where the fit failed (counted by `interval`).
fn component(boot: &[Option<(f64, f64)>], pick: fn(&(f64, f64)) -> f64) -> Vec<f64> {
    boot.iter()
        .map(|x| x.as_ref().map_or(f64::NAN, pick))
        .collect()
}

fn curves_3d(
    spec: &HurstSweep,
    work: &Path,
    h: usize,
    g: usize,
) -> Result<(Curves, Vec<BemCurve>)> {
    let fs = spec.f_grid();
    let bem: Vec<BemCurve> = (0..spec.realisations_3d)
        .map(|r| load(work, &Task::Bem { h, g, r }))
        .collect::<Result<_>>()?;
    let k3 = bem
        .iter()
        .map(|c| {
            let f: Vec<f64> = c.force.iter().map(|&x| x / c.rms_height).collect();
            fs.iter()
                .map(|&x| interp_loglog(&f, &c.stiffness, x))
                .collect()
        })
        .collect();
    Ok((k3, bem))
}

pub fn aggregate(spec: &HurstSweep, work: &Path) -> Result<Results> {
    let fs = spec.f_grid();
    let nf = fs.len();
    let mut res = Results {
        f: fs.clone(),
        ..Default::default()
    };
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(spec.seed ^ 0xB007);
    for (hi_idx, &hurst) in spec.hurst.iter().enumerate() {
        let ens: MrdEnsemble = load(work, &Task::Mrd { h: hi_idx })?;
        res.seconds_mrd += ens.seconds;
        res.realisations_mrd += ens.stiffness.len();
        let k1: Curves = ens
            .stiffness
            .iter()
            .map(|v| v.iter().map(|&x| Some(x)).collect())
            .collect();
        let all1: Vec<usize> = (0..k1.len()).collect();
        let m1 = mean_curve(&k1, &all1, nf);
        let (lo, hi) = spec.window(spec.grid);
        let fit1 = fit_window(&fs, &m1, lo, hi);
        for g in spec.grids() {
            let (k3, bem) = curves_3d(spec, work, hi_idx, g)?;
            for (r, c) in bem.iter().enumerate() {
                for (k, s) in c.solves.iter().enumerate() {
                    res.solves.push((hurst, g, r, k, s.clone()));
                }
            }
            let all3: Vec<usize> = (0..k3.len()).collect();
            let m3 = mean_curve(&k3, &all3, nf);
            let (glo, ghi) = spec.window(g);
            // The resamples keep the full-sample means' points (see `window_points`).
            let p3 = window_points(&m3, glo, ghi);
            let fit3 = fit_points(&fs, &m3, &p3);
            let boot3: Vec<Option<(f64, f64)>> = (0..RESAMPLES)
                .map(|_| {
                    let idx = resample(&mut rng, k3.len());
                    fit_points(&fs, &mean_curve(&k3, &idx, nf), &p3)
                })
                .collect();
            let ci_a3 = interval(component(&boot3, |x| x.0));
            if g != spec.grid {
                res.convergence.push(Convergence {
                    hurst,
                    grid: g,
                    alpha_3d: Estimate {
                        value: fit3.map_or(f64::NAN, |x| x.0),
                        lo: ci_a3.0,
                        hi: ci_a3.1,
                    },
                });
                continue;
            }
            res.seconds_3d += bem.iter().map(|c| c.seconds).sum::<f64>();
            res.realisations_3d += bem.len();
            let p1 = window_points(&m1, glo, ghi);
            let boot1: Vec<Option<(f64, f64)>> = (0..RESAMPLES)
                .map(|_| {
                    let idx = resample(&mut rng, k1.len());
                    fit_points(&fs, &mean_curve(&k1, &idx, nf), &p1)
                })
                .collect();
            // lambda over the calibration's force range (LAMBDA_WINDOW), not the alpha
            // window: below k/(E* L) = 0.02 a few contact cells set k and the 3D curve
            // has its discretisation plateau.
            let pl = window_points(&m3, LAMBDA_WINDOW.0, LAMBDA_WINDOW.1);
            let boot_lam: Vec<f64> = (0..RESAMPLES)
                .map(|_| {
                    let i3 = resample(&mut rng, k3.len());
                    let i1 = resample(&mut rng, k1.len());
                    let (m3, m1) = (mean_curve(&k3, &i3, nf), mean_curve(&k1, &i1, nf));
                    calibrate_lambda_at(&fs, &m3, &m1, &pl).unwrap_or(f64::NAN)
                })
                .collect();
            // Fitted as the shift of the reduced curves, reported as lambda of Eq. (76).
            let shift = calibrate_lambda_at(&fs, &m3, &m1, &pl);
            let factor = super::tasks::rms_factor(spec, hurst, g)?;
            let lam = shift.map(|v| v / factor);
            let boot_lam: Vec<f64> = boot_lam.into_iter().map(|v| v / factor).collect();
            let ci_z3 = interval(component(&boot3, |x| x.1));
            let ci_a1 = interval(component(&boot1, |x| x.0));
            let ci_z1 = interval(component(&boot1, |x| x.1));
            let ci_l = interval(boot_lam);
            let est = |v: Option<f64>, ci: (f64, f64)| Estimate {
                value: v.unwrap_or(f64::NAN),
                lo: ci.0,
                hi: ci.1,
            };
            // Speed-up at equal statistical error: per-realisation alpha scatter (sigma)
            // and cost per realisation; n needed ~ sigma^2 for a given interval width.
            let per3: Vec<f64> = k3
                .iter()
                .filter_map(|c| fit_window(&fs, c, glo, ghi).map(|x| x.0))
                .collect();
            let per1: Vec<f64> = k1
                .iter()
                .filter_map(|c| fit_window(&fs, c, glo, ghi).map(|x| x.0))
                .collect();
            let s3 = Stat::of(&per3).std;
            let s1 = Stat::of(&per1).std;
            let c3 = bem.iter().map(|c| c.seconds).sum::<f64>() / bem.len() as f64;
            let c1 = ens.seconds / ens.stiffness.len() as f64;
            if s3 > 0.0 && s1 > 0.0 && c1 > 0.0 {
                res.speedups.push(c3 * s3 * s3 / (c1 * s1 * s1));
            }
            res.per_hurst.push(PerHurst {
                hurst,
                alpha_3d: est(fit3.map(|x| x.0), ci_a3),
                alpha_mrd: est(fit1.map(|x| x.0), ci_a1),
                zeta_3d: est(fit3.map(|x| x.1), ci_z3),
                zeta_mrd: est(fit1.map(|x| x.1), ci_z1),
                lambda: est(lam, ci_l),
                lambda_shift: shift.unwrap_or(f64::NAN),
                lambda_cut: lambda_cut(hurst).unwrap_or(f64::NAN),
                fit_3d: fit3,
                window: (glo, ghi),
                ci_3d: half_widths(&k3, &m3),
                ci_mrd: half_widths(&k1, &m1),
                mean_3d: m3,
                mean_mrd: m1.clone(),
                realisations_3d: k3.len(),
                realisations_mrd: k1.len(),
                unconverged_3d: bem.iter().map(|c| c.unconverged).sum(),
            });
        }
    }
    Ok(res)
}
