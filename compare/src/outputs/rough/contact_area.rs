//! `contact_area`: the relative real contact area A/A0 and the mean gap against the
//! reduced force for the rough punch of the Hurst sweep (Section 9), in 3D (boundary
//! elements, circular punch face) and by MRD (rough lines with C1D = lambda q C2D,
//! Eq. 76), with 95 % bands over realisations.
//!
//! Section 11 of the paper states that MRD gets the contact area right only in the
//! initial linear regime (A proportional to F) and wrong at larger forces, since the
//! stiffness saturates long before complete contact. This output shows where: per H it
//! reports the ratio A_MRD/A_3D in the initial regime (3D area below 2 %) and the
//! smallest reduced force above it at which the ratio has moved by more than 20 %.
//!
//! Set-up as in the sweep: E* = 1, punch diameter L = 1, self-affine spectrum from
//! q0 = 2 pi/L to q1 = ratio x pi/dx without roll-off; 3D under approach control from
//! 1e-3 of the full-contact approach to full contact; 1D on a fixed grid of reduced
//! forces f = F/(E* h L), h the rms height of the punch face (for the line: the face's
//! that its C1D = lambda q C2D implies, `lambda_meaning`, so lambda moves the MRD
//! curves). MRD's relative area is the fraction of springs in contact; its mean gap
//! (over the line) is max z - mean z - d + F/(E* L), exactly.

use crate::checks::bad;
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::fit::mean_curve;
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::rough_punch::punch_face;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::{BemError, ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use mrd::rough_contact::{RoughLine, Stat};
use mrd::roughness::synthesis::{line, surface, Amplitudes, Grid};
use mrd::roughness::SelfAffine;
use rayon::prelude::*;
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactArea {
    /// Hurst exponents, each in [-1, 3].
    hurst: Vec<f64>,
    /// 3D grid side (cells across the punch diameter).
    grid: usize,
    /// Upper cut-off as a fraction of the 3D grid's Nyquist wavenumber pi/dx.
    #[serde(default = "quarter")]
    upper_cutoff_ratio: f64,
    /// Rough surfaces solved in 3D (independent realisations of the spectrum).
    realisations_3d: u64,
    /// MRD rough lines (independent realisations, C1D = lambda q C2D) behind each MRD
    /// curve.
    realisations_1d: u64,
    /// 1D points per 3D cell across.
    #[serde(default = "crate::checks::default_count::<16>")]
    points_1d_factor: usize,
    /// Approaches per 3D realisation.
    #[serde(default = "crate::checks::default_count::<20>")]
    loads: usize,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// lambda of Eq. (76) for the MRD lines (default pi, Eq. 73).
    #[serde(default)]
    lambda: LambdaSpec,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "tolerance")]
    tolerance: f64,
}

fn quarter() -> f64 {
    0.25
}
fn tolerance() -> f64 {
    1e-8
}

/// One realisation's curves on the f grid: (relative area, mean gap / h).
type Curve = (Vec<Option<f64>>, Vec<Option<f64>>);

/// Ensemble means and 95 % half-widths on the f grid.
struct Ensemble {
    area: Vec<Option<f64>>,
    area_ci: Vec<f64>,
    gap: Vec<Option<f64>>,
    gap_ci: Vec<f64>,
}

impl Ensemble {
    fn of(curves: &[Curve], nf: usize) -> Self {
        let idx: Vec<usize> = (0..curves.len()).collect();
        let stat = |pick: fn(&Curve) -> &Vec<Option<f64>>| {
            let c: Vec<Vec<Option<f64>>> = curves.iter().map(|c| pick(c).clone()).collect();
            let mean = mean_curve(&c, &idx, nf);
            let ci = (0..nf)
                .map(|j| match mean[j] {
                    Some(_) => Stat::of(&c.iter().filter_map(|v| v[j]).collect::<Vec<_>>()).ci95,
                    None => f64::NAN,
                })
                .collect();
            (mean, ci)
        };
        let (area, area_ci) = stat(|c| &c.0);
        let (gap, gap_ci) = stat(|c| &c.1);
        Self {
            area,
            area_ci,
            gap,
            gap_ci,
        }
    }
}

/// Linear interpolation in ln x of a curve given at ascending xs; None outside.
fn interp_logx(xs: &[f64], ys: &[f64], x: f64) -> Option<f64> {
    if xs.len() < 2 || x < xs[0] || x > *xs.last()? {
        return None;
    }
    let k = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
    let (x0, x1) = (xs[k - 1].ln(), xs[k].ln());
    let t = if x1 > x0 {
        (x.ln() - x0) / (x1 - x0)
    } else {
        0.0
    };
    Some(ys[k - 1] + t * (ys[k] - ys[k - 1]))
}

impl ContactArea {
    fn f_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(1e-5, 1e2, 71)
    }

    fn spectrum(&self, hurst: f64) -> mrd::Result<SelfAffine> {
        let q0 = 2.0 * PI;
        SelfAffine::new(
            hurst,
            q0,
            q0,
            self.upper_cutoff_ratio * PI * self.grid as f64,
        )
    }

    /// One 3D realisation: (f, A/A0, gap/h) at each approach with contact, and the
    /// number of unconverged solves.
    fn run_3d(&self, h: usize, r: u64) -> Result<(Vec<[f64; 3]>, usize)> {
        let g = self.grid;
        let sa = self.spectrum(self.hurst[h]).ctx("spectrum")?;
        let id = (3u64 << 60) ^ ((h as u64) << 40) ^ r;
        let heights = surface(
            &sa,
            &Grid::square(g, 1.0),
            self.seed,
            id,
            Amplitudes::Deterministic,
        )
        .ctx("3D surface")?;
        let (mask, full) = punch_face(&heights, g);
        let mut solver = ContactSolver::new(
            NonPeriodicHalfSpace::new(g, g, 1.0, 1.0, 1.0),
            &heights,
            Some(mask),
        )
        .ctx("3D solver set-up")?;
        let rms = solver.h_rms();
        let opts = SolverOptions {
            tolerance: self.tolerance,
            max_iterations: 20 * g + 2000,
            ..Default::default()
        };
        let (mut points, mut failed) = (Vec::new(), 0);
        let mut warm: Option<bem3d::Solution> = None;
        for k in 0..self.loads {
            let d = full * 10f64.powf(-3.0 * (1.0 - k as f64 / (self.loads - 1) as f64));
            let sol = match solver.solve(Load::Approach(d), &opts, warm.as_ref()) {
                Ok(s) => s,
                Err(BemError::NoConvergence { .. }) => {
                    failed += 1;
                    continue;
                }
                Err(e) => return Err(e).ctx("3D solve"),
            };
            if sol.force > 0.0 {
                let area = sol.contact_cells as f64 / sol.domain_cells as f64;
                points.push([sol.force / rms, area, sol.mean_gap / rms]);
            }
            warm = Some(sol);
        }
        Ok((points, failed))
    }

    /// One MRD line on the f grid: C1D = lambda q C2D (Eq. 76), its forces and gaps over
    /// the rms height h3 of the punch face it stands for, which the line carries as
    /// sqrt(pi / l) of its own, l = pi h1^2 / h3^2 the shift lambda implies
    /// ([`super::lambda_meaning`]).
    fn run_1d(&self, h: usize, r: u64, lambda: f64, fs: &[f64]) -> Result<Curve> {
        use crate::experiment::lambda_meaning::{rms_matched, Face};
        let n1 = self.points_1d_factor * self.grid;
        let surface = self.spectrum(self.hurst[h]).ctx("spectrum")?;
        let band = self.upper_cutoff_ratio * self.grid as f64 / 2.0;
        let shift = rms_matched(lambda, &|q| surface.c2d(q), band, 1.0, Face::Disc);
        let spec = surface.to_line(lambda);
        let id = (4u64 << 60) ^ ((h as u64) << 40) ^ r;
        let z = line(&spec, n1, 1.0, self.seed, id, Amplitudes::Deterministic).ctx("1D line")?;
        let rl = RoughLine::new(&z, 1.0, 1.0).ctx("1D line")?;
        let zmax = z.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
        let mean = z.iter().sum::<f64>() / n1 as f64;
        let full = rl.at_depth(rl.full_contact_depth()).ctx("1D")?.force;
        let h3 = rl.rms_height * (PI / shift).sqrt();
        let (mut area, mut gap) = (Vec::new(), Vec::new());
        for &f in fs {
            let force = f * h3;
            if force >= full {
                area.push(Some(1.0));
                gap.push(Some(0.0));
                continue;
            }
            let s = rl.at_force(force).ctx("1D")?;
            area.push(Some(s.contacts as f64 / n1 as f64));
            let g = (zmax - mean - s.depth + s.force).max(0.0);
            gap.push(Some(g / h3));
        }
        Ok((area, gap))
    }
}

impl Output for ContactArea {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if self.hurst.is_empty() {
            return bad("hurst list is empty");
        }
        if let Some(h) = self.hurst.iter().find(|h| !(-1.0..=3.0).contains(*h)) {
            return bad(format!("hurst = {h} must lie in [-1, 3]"));
        }
        if !(16..=4096).contains(&self.grid) {
            return bad(format!("grid = {} must lie in 16..=4096", self.grid));
        }
        if !(self.upper_cutoff_ratio > 0.0 && self.upper_cutoff_ratio <= 1.0) {
            return bad("upper_cutoff_ratio must lie in (0, 1]");
        }
        crate::checks::check_ensembles(self.realisations_3d, self.realisations_1d)?;
        crate::checks::count_in("loads", self.loads as u64, 4..=crate::checks::MAX_LOADS)?;
        crate::checks::count_in("points_1d_factor", self.points_1d_factor as u64, 2..=64)?;
        crate::checks::check_tolerance(self.tolerance)?;
        for &h in &self.hurst {
            self.lambda
                .build(ctx)?
                .at(h)
                .ctx(format!("lambda at H = {h}"))?;
        }
        // One 3D task per worker thread at a time.
        crate::checks::check_memory_per_thread(
            (self.grid * self.grid) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("grid = {}", self.grid),
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
        let nf = fs.len();
        let lambda = self.lambda.build(env.ctx)?;
        let mut per_h = Vec::new();
        // 3D first for every H (synthesis and solves interleaved), then MRD.
        let runs_3d = out.stages_together(&[Stage::RoughSynthesis, Stage::Bem3d], || {
            (0..self.hurst.len())
                .map(|h| {
                    (0..self.realisations_3d)
                        .into_par_iter()
                        .map(|r| self.run_3d(h, r))
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        let runs_1d = out.stage(Stage::RoughContact, || {
            (0..self.hurst.len())
                .map(|h| {
                    let lam = lambda.at(self.hurst[h]).ctx("lambda")?;
                    (0..self.realisations_1d)
                        .into_par_iter()
                        .map(|r| self.run_1d(h, r, lam, &fs))
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()
        })?;
        for (h, (r3, r1)) in runs_3d.iter().zip(&runs_1d).enumerate() {
            let failed: usize = r3.iter().map(|(_, n)| n).sum();
            if failed > 0 {
                out.failures.push(format!(
                    "H = {}: {failed} 3D solves did not converge (left out of the curves)",
                    self.hurst[h]
                ));
            }
            let curves: Vec<Curve> = r3
                .iter()
                .map(|(pts, _)| {
                    let f: Vec<f64> = pts.iter().map(|p| p[0]).collect();
                    let a: Vec<f64> = pts.iter().map(|p| p[1]).collect();
                    let g: Vec<f64> = pts.iter().map(|p| p[2]).collect();
                    (
                        fs.iter().map(|&x| interp_logx(&f, &a, x)).collect(),
                        fs.iter().map(|&x| interp_logx(&f, &g, x)).collect(),
                    )
                })
                .collect();
            per_h.push((Ensemble::of(&curves, nf), Ensemble::of(r1, nf)));
        }
        self.report(out, &fs, &per_h);
        Ok(())
    }
}

impl ContactArea {
    /// Table, findings per H and figures.
    fn report(&self, out: &mut Section, fs: &[f64], per_h: &[(Ensemble, Ensemble)]) {
        let mut t = Table::new(
            "contact_area",
            &[
                "hurst [1]",
                "f = F/(E* h L) [1]",
                "area_3d [A/A0]",
                "area_3d_ci95 [A/A0]",
                "area_mrd [A/A0]",
                "area_mrd_ci95 [A/A0]",
                "gap_3d [mean gap/h]",
                "gap_3d_ci95 [mean gap/h]",
                "gap_mrd [mean gap/h]",
                "gap_mrd_ci95 [mean gap/h]",
            ],
        );
        t.notes.push(format!(
            "circular rough punch, {0}^2 cells, {1} realisations per H; MRD: {2} lines of {3} points per H, lambda {4:?}; A0 = punch face (3D), line length (MRD); h = rms height of the face or line; ci95 = 1.96 s/sqrt(n) of the ensemble mean; rows where both means exist",
            self.grid, self.realisations_3d, self.realisations_1d, self.points_1d_factor * self.grid, self.lambda
        ));
        let mut findings = serde_json::Map::new();
        let mut area_fig = Figure::new(
            "contact_area",
            "Real contact area against force: 3D (95% CI) and MRD",
            "reduced force f = F/(E* h L) [1]",
            "relative contact area A/A0 [1]",
        );
        let mut ratio_fig = Figure::new(
            "contact_area_ratio",
            "MRD contact-length fraction over the 3D area fraction",
            "reduced force f = F/(E* h L) [1]",
            "A_MRD / A_3D [1]",
        );
        let mut gap_fig = Figure::new(
            "contact_area_gap",
            "Mean gap against force: 3D (95% CI) and MRD",
            "reduced force f = F/(E* h L) [1]",
            "mean gap / h [1]",
        );
        for (i, (&hurst, (e3, e1))) in self.hurst.iter().zip(per_h).enumerate() {
            let mut ratio = Vec::new();
            let (mut a3, mut a1, mut g3, mut g1) = (vec![], vec![], vec![], vec![]);
            for (j, &f) in fs.iter().enumerate() {
                if let (Some(a), Some(b)) = (e3.area[j], e1.area[j]) {
                    t.push(vec![
                        hurst,
                        f,
                        a,
                        e3.area_ci[j],
                        b,
                        e1.area_ci[j],
                        e3.gap[j].unwrap_or(f64::NAN),
                        e3.gap_ci[j],
                        e1.gap[j].unwrap_or(f64::NAN),
                        e1.gap_ci[j],
                    ]);
                    a3.push((f, a, e3.area_ci[j]));
                    a1.push((f, b));
                    if a > 0.0 {
                        ratio.push((f, b / a, a));
                    }
                    if let (Some(x), Some(y)) = (e3.gap[j], e1.gap[j]) {
                        g3.push((f, x, e3.gap_ci[j]));
                        g1.push((f, y));
                    }
                }
            }
            findings.insert(
                format!("{hurst}"),
                finding(&ratio, 3.0 / (self.grid * self.grid) as f64),
            );
            let pts3 = |v: &[(f64, f64, f64)]| v.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>();
            let bars3 = |v: &[(f64, f64, f64)]| {
                v.iter()
                    .map(|p| (p.0, p.1 - p.2, p.1 + p.2))
                    .collect::<Vec<_>>()
            };
            area_fig = area_fig
                .with(
                    Series::new(format!("3D, H = {hurst}"), pts3(&a3), Style::Crosses)
                        .with_bars(bars3(&a3))
                        .colored(i),
                )
                .with(Series::new(format!("MRD, H = {hurst}"), a1, Style::Line).colored(i));
            gap_fig = gap_fig
                .with(
                    Series::new(format!("3D, H = {hurst}"), pts3(&g3), Style::Crosses)
                        .with_bars(bars3(&g3))
                        .colored(i),
                )
                .with(Series::new(format!("MRD, H = {hurst}"), g1, Style::Line).colored(i));
            ratio_fig = ratio_fig.with(
                Series::new(
                    format!("H = {hurst}"),
                    ratio.iter().map(|p| (p.0, p.1)).collect(),
                    Style::Line,
                )
                .colored(i),
            );
        }
        let f_data = ratio_fig
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0));
        let span = f_data.fold((f64::INFINITY, 0.0f64), |(a, b), f| (a.min(f), b.max(f)));
        if span.1 > span.0 {
            ratio_fig = ratio_fig.with(
                Series::new(
                    "equal areas",
                    vec![(span.0, 1.0), (span.1, 1.0)],
                    Style::Dashed,
                )
                .colored(5),
            );
        }
        area_fig = area_fig.log_log();
        ratio_fig = ratio_fig.log_log();
        gap_fig.log_x = true;
        out.value("per_hurst", serde_json::Value::Object(findings));
        out.tables.push(t);
        out.figures.extend([area_fig, ratio_fig, gap_fig]);
    }
}

/// Per H: the area ratio in the initial linear regime (3D area between a few cells
/// and 2 %) and the smallest force above it where the ratio moved by over 20 %.
fn finding(ratio: &[(f64, f64, f64)], a_min: f64) -> serde_json::Value {
    let initial: Vec<f64> = ratio
        .iter()
        .filter(|p| p.2 >= a_min && p.2 <= 0.02)
        .map(|p| p.1)
        .collect();
    let mut o = serde_json::Map::new();
    if initial.is_empty() {
        o.insert("note".into(), "no points in the initial regime".into());
        return serde_json::Value::Object(o);
    }
    let r0 = initial.iter().sum::<f64>() / initial.len() as f64;
    o.insert("area_ratio_initial".into(), serde_json::json!(r0));
    if let Some(p) = ratio
        .iter()
        .find(|p| p.2 > 0.02 && (p.1 / r0 - 1.0).abs() > 0.2)
    {
        o.insert("f_ratio_off_20pct".into(), serde_json::json!(p.0));
        o.insert("area_3d_there".into(), serde_json::json!(p.2));
    }
    serde_json::Value::Object(o)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// lambda (Eq. 76) moves the MRD curve: a rougher line (larger lambda) touches with
    /// fewer springs at the same reduced force, by the shift sqrt(pi / l) along f that
    /// lambda_meaning gives; lambda = pi and lambda = 9 differ at every force.
    #[test]
    fn lambda_moves_the_mrd_area() {
        let spec: ContactArea =
            toml::from_str("hurst = [0.5]\ngrid = 32\nrealisations_3d = 2\nrealisations_1d = 2\n")
                .unwrap();
        let fs = [1e-3, 1e-2, 1e-1];
        let (pi_area, _) = spec.run_1d(0, 0, PI, &fs).unwrap();
        let (nine_area, _) = spec.run_1d(0, 0, 9.0, &fs).unwrap();
        for (a, b) in pi_area.iter().zip(&nine_area) {
            assert!(b.unwrap() < a.unwrap(), "{pi_area:?} {nine_area:?}");
        }
    }
}
