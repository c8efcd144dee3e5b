//! `rough_plastic_3d`: the review's Section 11 question on rough surfaces: does MRD in
//! incremental form reproduce an elastic-perfectly plastic rough contact? A rigid flat
//! punch of diameter L with a self-affine rough face (Section 9's rough punch, Pohrt &
//! Popov) is loaded, unloaded and reloaded on a half-space whose pressure saturates at
//! the hardness H, in 3D (`bem3d::plastic`, the face on a free grid) and by MRD (rough
//! lines with C1D = lambda q C2D on springs capped patch by patch,
//! `mrd::plastic_line`), at plasticity indices psi = E* h'_rms / H from elastic to
//! mostly plastic, side by side:
//!
//! - the loading stiffness k = dF/dd (secants of the force ladder) against the force,
//!   its MRD / 3D ratio against psi, beside the elastic case's;
//! - the unloading stiffness at the peak and the approach recovered on unloading;
//! - lambda refitted at each psi (the lambda whose lines give the 3D loading stiffness),
//!   with its interval, against the elastic case's;
//! - the 3D contact and plastic fractions, and `H A / F` (1 in the fully plastic limit).
//!
//! Units: E* = 1, L = 1; forces reduced as f = F / (E* h L), h the face spectrum's rms
//! height over the square (the lattice sum of its modes), psi with its spectral rms
//! slope h'. The pressure-cap model is that of `plastic_3d` (Tamaas' saturated solver's).

use crate::checks::{bad, count_in, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::rough_punch::punch_face;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::plastic::PlasticContact;
use bem3d::{Load, NonPeriodicHalfSpace};
use mrd::plastic_line::PlasticLine;
use mrd::roughness::nested;
use mrd::roughness::synthesis::Grid;
use mrd::roughness::SelfAffine;
use rayon::prelude::*;
use serde::Deserialize;
use std::f64::consts::{FRAC_1_SQRT_2, PI, SQRT_2, TAU};

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughPlastic3d {
    /// Hurst exponent of the self-affine face (no roll-off), in [0, 1].
    #[serde(default = "default_hurst")]
    hurst: f64,
    /// Bandwidth B: the face's wave vectors 1 <= |k| <= B in units of 2 pi / L.
    #[serde(default = "crate::checks::default_count::<16>")]
    bandwidth: usize,
    /// 3D cells per shortest wavelength, coarse to fine (the grid's side is B times it).
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Plasticity indices psi = E* h'_rms / H, increasing (the elastic case, psi = 0,
    /// is always run).
    plasticity: Vec<f64>,
    /// Smallest reduced force f = F / (E* h L) of the first loading.
    #[serde(default = "default_f_min")]
    f_min: f64,
    /// Largest reduced force (the peak of the history).
    #[serde(default = "default_f_max")]
    f_max: f64,
    /// Steps of the first loading, log-spaced from f_min to f_max (then the unloading
    /// to 0.9, 0.7, 0.5, 0.3, 0.2, 0.1, 0.05 and 0.02 of the peak and the reloading to
    /// 0.1, 0.3, 0.5, 0.7 and 1).
    #[serde(default = "crate::checks::default_count::<10>")]
    loads: usize,
    /// 3D punches (realisations of the face) per case.
    #[serde(default = "crate::checks::default_count_u64::<8>")]
    realisations_3d: u64,
    /// MRD lines per case.
    #[serde(default = "crate::checks::default_count_u64::<64>")]
    lines: u64,
    /// Springs of an MRD line.
    #[serde(default = "crate::checks::default_count::<2048>")]
    springs: usize,
    /// lambda of Eq. (76) of the MRD lines (the refit scans 0.5 to 2 times it); default
    /// "calibrated", the embedded table.
    #[serde(default = "calibrated")]
    lambda: LambdaSpec,
    /// Relative force tolerance of every step, 3D and MRD.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
    /// Seed of the faces and lines: the same seed gives the same realisations whatever
    /// the thread count.
    #[serde(default)]
    seed: u64,
}

fn default_hurst() -> f64 {
    0.8
}
fn default_cells() -> Vec<usize> {
    vec![4, 8]
}
fn default_f_min() -> f64 {
    1e-3
}
fn default_f_max() -> f64 {
    0.3
}
fn calibrated() -> LambdaSpec {
    LambdaSpec::Named("calibrated".into())
}

/// The history after the first loading, as fractions of the peak force.
const UNLOAD: [f64; 8] = [0.9, 0.7, 0.5, 0.3, 0.2, 0.1, 0.05, 0.02];
const RELOAD: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 1.0];
/// Factors of lambda the refit scans (the lines' heights scale with its square root).
const REFIT: [f64; 5] = [0.5, FRAC_1_SQRT_2, 1.0, SQRT_2, 2.0];
/// rms slope of the face's spectrum (the pressure-cap problem is scale-free: psi and f
/// are what matter; a small slope keeps the half-space's linearisation honest).
const SLOPE: f64 = 0.1;

/// lambda refitted at one psi: (psi, the fit, its interval's ends), None outside the
/// scanned factors.
type Refit = (f64, Option<f64>, Option<f64>, Option<f64>);

/// One step of one punch or line.
#[derive(Debug, Clone, Copy, Default)]
struct Point {
    approach: f64,
    force: f64,
    /// Contact fraction of the face (3D: area over the disc's; MRD: springs in contact
    /// over all) and the plastic share of the contact (3D: cells at H; MRD: springs at
    /// their cap).
    contact: f64,
    plastic: f64,
}

/// What one history gives, the quantities compared.
#[derive(Debug, Clone)]
struct Reading {
    /// ln of the loading secant stiffness per interval of the first loading.
    ln_k: Vec<f64>,
    /// ln of the unloading stiffness at the peak (secant to 0.9 of it).
    ln_k_unload: f64,
    /// ln of the approach recovered from the peak to 0.02 of it.
    ln_recovery: f64,
    /// ln of the approach at the peak (from the first contact).
    ln_peak: f64,
    /// |d at the reloaded peak - d at the peak| / d at the peak.
    retrace: f64,
    points: Vec<Point>,
}

/// Mean and the half-width of its 95 % interval (1.96 s / sqrt(n)).
fn mean_ci(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, 1.96 * (var / n).sqrt())
}

impl Output for RoughPlastic3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if !(0.0..=1.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [0, 1]", self.hurst));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=128)?;
        if self.cells.is_empty() || self.cells.windows(2).any(|w| w[1] <= w[0]) {
            return bad(format!(
                "cells = {:?}: give increasing cells per shortest wavelength",
                self.cells
            ));
        }
        for &c in &self.cells {
            count_in("cells", c as u64, 3..=64)?;
            count_in("bandwidth x cells", (c * self.bandwidth) as u64, 16..=1024)?;
        }
        if self.plasticity.is_empty()
            || self
                .plasticity
                .iter()
                .any(|p| !(p.is_finite() && *p > 0.0 && *p <= 1e3))
            || self.plasticity.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "plasticity = {:?}: give increasing indices psi = E* h'_rms / H in (0, 1000] (the elastic case is always run)",
                self.plasticity
            ));
        }
        if !(self.f_min.is_finite() && self.f_min > 0.0 && self.f_min < self.f_max) {
            return bad(format!(
                "f_min = {}: must be > 0 and below f_max = {}",
                self.f_min, self.f_max
            ));
        }
        // The largest psi's fully plastic face carries H pi L^2 / 4: f_limit = (h' / h)
        // (pi / 4) / psi. The history must stay clear of it.
        let (h, slope) = self.moments()?;
        let psi = self.plasticity.last().copied().unwrap_or(1.0);
        let limit = slope / h * PI / 4.0 / psi;
        if !(self.f_max.is_finite() && self.f_max <= 0.5 * limit) {
            return bad(format!(
                "f_max = {}: must stay below half the fully plastic force of the largest plasticity = {psi}, f = {limit:.4e} (H pi L^2 / 4 over E* h L)",
                self.f_max
            ));
        }
        count_in("loads", self.loads as u64, 3..=200)?;
        count_in("realisations_3d", self.realisations_3d, 2..=100_000)?;
        count_in("lines", self.lines, 2..=1_000_000)?;
        count_in(
            "springs",
            self.springs as u64,
            (4 * self.bandwidth as u64)..=(1 << 20),
        )?;
        LambdaSpec::check_all(std::slice::from_ref(&self.lambda), ctx, &[self.hurst])?;
        crate::checks::check_tolerance(self.tolerance)?;
        if self.tolerance > 1e-2 {
            return bad(format!(
                "tolerance = {} must be <= 0.01 (the plastic steps' relative force tolerance)",
                self.tolerance
            ));
        }
        let g = self.bandwidth * self.cells.last().copied().unwrap_or(0);
        crate::checks::check_memory(
            (g * g) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("bandwidth x cells = {g}"),
        )
    }

    fn stages(&self, _ctx: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Plastic3d, Stage::PlasticMrd]
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let (h, slope) = self.moments()?;
        let lambda = self.lambda.build(env.ctx)?.at(self.hurst).ctx("lambda")?;
        let spectrum = self.spectrum()?;
        let c2d = |q: f64| spectrum.c2d(q);
        let forces = self.history();
        // psi = 0: the elastic case, H infinite.
        let cases: Vec<f64> = std::iter::once(0.0)
            .chain(self.plasticity.iter().copied())
            .collect();
        let hardness = |psi: f64| {
            if psi == 0.0 {
                f64::INFINITY
            } else {
                slope / psi
            }
        };
        // 3D: every (case, grid, realisation), in order.
        let faces: Vec<(usize, usize, u64)> = (0..cases.len())
            .flat_map(|c| {
                (0..self.cells.len())
                    .flat_map(move |g| (0..self.realisations_3d).map(move |r| (c, g, r)))
            })
            .collect();
        let three = out.stages_together(&[Stage::RoughSynthesis, Stage::Plastic3d], || {
            faces
                .par_iter()
                .map(|&(c, g, r)| {
                    let n = self.bandwidth * self.cells[g];
                    let z = crate::report::clock::time(Stage::RoughSynthesis, || {
                        nested::surface(&c2d, self.bandwidth, &Grid::square(n, 1.0), self.seed, r)
                    })
                    .ctx("3D face")?;
                    crate::report::clock::time(Stage::Plastic3d, || {
                        self.run_3d(&z, n, hardness(cases[c]), h, &forces)
                    })
                })
                .collect::<Result<Vec<Reading>>>()
        })?;
        // MRD: every (case, lambda factor, line), in order.
        let runs: Vec<(usize, usize, u64)> = (0..cases.len())
            .flat_map(|c| {
                (0..REFIT.len()).flat_map(move |k| (0..self.lines).map(move |r| (c, k, r)))
            })
            .collect();
        let c1d = |q: f64| lambda * q * spectrum.c2d(q);
        let mrd = out.stage(Stage::PlasticMrd, || {
            // Each line once: every case and lambda factor loads the same lines, scaled.
            let lines = (0..self.lines)
                .into_par_iter()
                .map(|r| nested::line(&c1d, self.bandwidth, self.springs, 1.0, self.seed, r))
                .collect::<mrd::Result<Vec<Vec<f64>>>>()
                .ctx("MRD line")?;
            runs.par_iter()
                .map(|&(c, k, r)| {
                    let z: Vec<f64> = lines[r as usize]
                        .iter()
                        .map(|v| v * REFIT[k].sqrt())
                        .collect();
                    self.run_mrd(&z, hardness(cases[c]), h, &forces)
                })
                .collect::<Result<Vec<Reading>>>()
        })?;
        let data = Data {
            cases,
            three,
            mrd,
            grids: self.cells.len(),
            faces: self.realisations_3d as usize,
            lines: self.lines as usize,
            lambda,
            h,
            slope,
            forces,
        };
        self.report(out, &data);
        Ok(())
    }
}

impl RoughPlastic3d {
    /// The face's spectrum: self-affine from 2 pi / L to B 2 pi / L, rms slope SLOPE.
    fn spectrum(&self) -> Result<SelfAffine> {
        let q0 = TAU;
        SelfAffine::new(self.hurst, q0, q0, q0 * self.bandwidth as f64)
            .and_then(|s| s.with_rms_slope(SLOPE))
            .ctx("the face's spectrum")
    }

    /// The rms height h and rms slope h' of the face's modes on the square lattice
    /// (every realisation's, the amplitudes being fixed).
    fn moments(&self) -> Result<(f64, f64)> {
        let s = self.spectrum()?;
        let c2d = |q: f64| s.c2d(q);
        let b = self.bandwidth as f64;
        let h2 = nested::surface_mean_square(&c2d, b, 1.0, false);
        let s2 = nested::surface_mean_square(&|q| q * q * c2d(q), b, 1.0, false);
        Ok((h2.sqrt(), s2.sqrt()))
    }

    /// The reduced forces of the history: the first loading, the unloading, the reloading.
    fn history(&self) -> Vec<f64> {
        let mut f = mrd::friction::log_space(self.f_min, self.f_max, self.loads);
        f.extend(UNLOAD.iter().chain(&RELOAD).map(|u| u * self.f_max));
        f
    }

    fn run_3d(
        &self,
        z: &[f64],
        n: usize,
        hardness: f64,
        h: f64,
        forces: &[f64],
    ) -> Result<Reading> {
        let (mask, _) = punch_face(z, n);
        let disc = mask.iter().filter(|&&m| m).count() as f64 / (n * n) as f64;
        let op = NonPeriodicHalfSpace::try_new(n, n, 1.0, 1.0, 1.0).ctx("3D operator")?;
        let mut c = PlasticContact::new(op, z, Some(&mask), hardness).ctx("3D plastic contact")?;
        let mut points = Vec::with_capacity(forces.len());
        for &f in forces {
            let s = c
                .step(Load::Force(f * h), self.tolerance)
                .ctx(format!("3D step to f = {f:.4e} on {n}^2 cells"))?;
            points.push(Point {
                approach: s.approach,
                force: s.force,
                contact: s.contact_area / disc,
                plastic: if s.contact_area > 0.0 {
                    s.plastic_area / s.contact_area
                } else {
                    0.0
                },
            });
        }
        Ok(self.reading(points))
    }

    fn run_mrd(&self, z: &[f64], hardness: f64, h: f64, forces: &[f64]) -> Result<Reading> {
        let mut line = PlasticLine::new(z, 1.0, 1.0, hardness).ctx("MRD line")?;
        let mut points = Vec::with_capacity(forces.len());
        for &f in forces {
            let s = line.step_to_force(f * h, self.tolerance).ctx("MRD step")?;
            points.push(Point {
                approach: s.approach,
                force: s.force,
                contact: s.contacts as f64 / self.springs as f64,
                plastic: if s.contacts > 0 {
                    s.capped as f64 / s.contacts as f64
                } else {
                    0.0
                },
            });
        }
        Ok(self.reading(points))
    }

    fn reading(&self, points: Vec<Point>) -> Reading {
        let secant = |a: &Point, b: &Point| ((b.force - a.force) / (b.approach - a.approach)).ln();
        let first = &points[..self.loads];
        let peak = points[self.loads - 1];
        let unload = points[self.loads];
        let lowest = points[self.loads + UNLOAD.len() - 1];
        let reloaded = points[points.len() - 1];
        Reading {
            ln_k: first.windows(2).map(|w| secant(&w[0], &w[1])).collect(),
            ln_k_unload: secant(&unload, &peak),
            ln_recovery: (peak.approach - lowest.approach).ln(),
            ln_peak: peak.approach.ln(),
            retrace: ((reloaded.approach - peak.approach) / peak.approach).abs(),
            points,
        }
    }

    /// The mean over a case's runs of the mean over the loading intervals of ln k, and
    /// its interval: one number per run, so the interval is the runs' spread.
    fn loading(runs: &[Reading]) -> (f64, f64) {
        let per: Vec<f64> = runs
            .iter()
            .map(|r| r.ln_k.iter().sum::<f64>() / r.ln_k.len() as f64)
            .collect();
        mean_ci(&per)
    }

    fn report(&self, out: &mut Section, d: &Data) {
        let setting = self.setting(d);
        self.stiffness_report(out, d, &setting);
        let (s, refits, retrace) = self.by_plasticity(d, setting);
        let fine = self.scalars(out, &s, &refits, retrace);
        Self::plasticity_figures(out, &fine, &refits, d.lambda);
        out.tables.push(s);
        self.history_report(out, d);
    }

    /// The setting every table states.
    fn setting(&self, d: &Data) -> String {
        let (h, slope, lambda) = (d.h, d.slope, d.lambda);
        format!(
            "rough punch of diameter L = 1 on E* = 1: self-affine face H = {}, wave vectors 1..{} (units 2 pi / L), fixed amplitudes, spectral rms height h = {h:.4e} and slope h' = {slope:.4e} over the square; hardness H = h' / psi; 3D on free grids of {:?} cells per shortest wavelength, {} faces per case; MRD lines of {} springs, C1D = lambda q C2D with lambda = {lambda:.4} (the refit scans 0.5-2 times it), {} lines per case, each spring's line load capped patch by patch at 2 H sqrt(a^2 - (x - c)^2) (mrd::plastic_line); f = F / (E* h L); intervals: 95 % of the mean over faces (3D) and lines (MRD)",
            self.hurst, self.bandwidth, self.cells, self.realisations_3d, self.springs, self.lines
        )
    }

    /// The loading stiffness against the force, per case and grid: table and figure
    /// (finest grid).
    fn stiffness_report(&self, out: &mut Section, d: &Data, setting: &str) {
        let (cases, forces) = (&d.cases[..], &d.forces[..]);
        let finest = self.cells.len() - 1;
        // The loading stiffness against the force, per case, finest grid.
        let mut t = Table::new(
            "loading_stiffness",
            &[
                "psi [1]",
                "cells per wavelength [count]",
                "f [1]",
                "k_3D / (E* L) [1]",
                "k_3D low [1]",
                "k_3D high [1]",
                "k_MRD / (E* L) [1]",
                "k_MRD low [1]",
                "k_MRD high [1]",
            ],
        );
        t.notes.push(setting.to_string());
        t.notes.push(
            "k: the secant dF/dd between successive steps of the first loading, at their geometric mean force; geometric means over the runs with their 95 % intervals; MRD at the scene's lambda".into(),
        );
        let fs = &forces[..self.loads];
        let at = |runs: &[Reading], i: usize| {
            let v: Vec<f64> = runs.iter().map(|r| r.ln_k[i]).collect();
            mean_ci(&v)
        };
        for (c, &psi) in cases.iter().enumerate() {
            for g in 0..self.cells.len() {
                for i in 0..self.loads - 1 {
                    let (m3, e3) = at(d.three(c, g), i);
                    let (m1, e1) = at(d.mrd(c, UNIT), i);
                    t.push(vec![
                        psi,
                        self.cells[g] as f64,
                        (fs[i] * fs[i + 1]).sqrt(),
                        m3.exp(),
                        (m3 - e3).exp(),
                        (m3 + e3).exp(),
                        m1.exp(),
                        (m1 - e1).exp(),
                        (m1 + e1).exp(),
                    ]);
                }
            }
        }
        let mut fig = Figure::new(
            "loading_stiffness",
            "Rough punch, first loading: stiffness against force, 3D (markers) and MRD (lines)",
            "reduced force f = F / (E* h L) [1]",
            "loading stiffness k / (E* L) [1]",
        )
        .log_log();
        for (c, &psi) in cases.iter().enumerate() {
            let rows: Vec<&Vec<f64>> = t
                .rows
                .iter()
                .filter(|r| r[0] == psi && r[1] == self.cells[finest] as f64)
                .collect();
            fig = fig
                .with(
                    Series::new(
                        format!("3D {}", psi_label(psi)),
                        rows.iter().map(|r| (r[2], r[3])).collect(),
                        Style::Markers,
                    )
                    .with_bars(rows.iter().map(|r| (r[2], r[4], r[5])).collect())
                    .colored(c),
                )
                .with(
                    Series::new(
                        format!("MRD {}", psi_label(psi)),
                        rows.iter().map(|r| (r[2], r[6])).collect(),
                        Style::Line,
                    )
                    .colored(c),
                );
        }
        out.tables.push(t);
        out.figures.push(fig);
    }

    /// Per case and grid: the ratios, the fractions, the refit (the table, the refits of
    /// the finest grid, the largest reload retrace).
    fn by_plasticity(&self, d: &Data, setting: String) -> (Table, Vec<Refit>, f64) {
        let (cases, slope, lambda) = (&d.cases[..], d.slope, d.lambda);
        let finest = self.cells.len() - 1;
        // Per case and grid: the ratios, the fractions, the refit.
        let mut s = Table::new(
            "by_plasticity",
            &[
                "psi [1]",
                "hardness H / E* [1]",
                "cells per wavelength [count]",
                "loading k_MRD / k_3D [1]",
                "low [1]",
                "high [1]",
                "unloading k_MRD / k_3D [1]",
                "low [1]",
                "high [1]",
                "recovered approach MRD / 3D [1]",
                "low [1]",
                "high [1]",
                "approach at the peak MRD / 3D [1]",
                "low [1]",
                "high [1]",
                "3D contact fraction at the peak [1]",
                "3D plastic share of the contact at the peak [1]",
                "MRD capped share of the contact at the peak [1]",
                "3D H A / F at the peak [1]",
                "lambda refitted [1]",
                "low [1]",
                "high [1]",
            ],
        );
        s.missing_ok = true;
        s.notes.push(setting);
        s.notes.push(
            "ratios: exp of the difference of the mean logs (loading: each run's mean over the loading intervals), intervals from both sides' 95 % intervals added in quadrature; recovered approach: from the peak to 0.02 of it; approach at the peak: from each run's first contact; empty hardness and H A / F: the elastic case; lambda refitted: where the lines' mean log loading stiffness meets the 3D's, interpolated in ln lambda over the scanned factors (empty: outside 0.5-2 times lambda), its interval from the 3D interval's ends".into(),
        );
        let peak = self.loads - 1;
        let mut retrace: f64 = 0.0;
        let mut refits: Vec<Refit> = vec![];
        for (c, &psi) in cases.iter().enumerate() {
            let hard = if psi == 0.0 {
                f64::INFINITY
            } else {
                slope / psi
            };
            let mrd1 = d.mrd(c, UNIT);
            for g in 0..self.cells.len() {
                let bem = d.three(c, g);
                for r in bem.iter().chain(mrd1) {
                    retrace = retrace.max(r.retrace);
                }
                let ratio = |a: (f64, f64), b: (f64, f64)| {
                    let e = a.1.hypot(b.1);
                    let d = a.0 - b.0;
                    [d.exp(), (d - e).exp(), (d + e).exp()]
                };
                let pick = |runs: &[Reading], q: &dyn Fn(&Reading) -> f64| {
                    mean_ci(&runs.iter().map(q).collect::<Vec<_>>())
                };
                let load = ratio(Self::loading(mrd1), Self::loading(bem));
                let unl = ratio(
                    pick(mrd1, &|r| r.ln_k_unload),
                    pick(bem, &|r| r.ln_k_unload),
                );
                let rec = ratio(
                    pick(mrd1, &|r| r.ln_recovery),
                    pick(bem, &|r| r.ln_recovery),
                );
                let top = ratio(pick(mrd1, &|r| r.ln_peak), pick(bem, &|r| r.ln_peak));
                let mean_at = |runs: &[Reading], q: &dyn Fn(&Point) -> f64| {
                    runs.iter().map(|r| q(&r.points[peak])).sum::<f64>() / runs.len() as f64
                };
                let contact = mean_at(bem, &|p| p.contact);
                let plastic = mean_at(bem, &|p| p.plastic);
                let capped = mean_at(mrd1, &|p| p.plastic);
                let area_ratio = if hard.is_finite() {
                    mean_at(bem, &|p| hard * p.contact * PI / 4.0 / p.force)
                } else {
                    f64::NAN
                };
                // The refit: the lines' mean log loading stiffness against ln(factor).
                let target = Self::loading(bem);
                let curve: Vec<(f64, f64)> = (0..REFIT.len())
                    .map(|k| (REFIT[k].ln(), Self::loading(d.mrd(c, k)).0))
                    .collect();
                let fit = |y: f64| crossing(&curve, y).map(|x| lambda * x.exp());
                let (best, lo, hi) = (
                    fit(target.0),
                    fit(target.0 + target.1),
                    fit(target.0 - target.1),
                );
                if g == finest {
                    refits.push((psi, best, lo, hi));
                }
                s.push(vec![
                    psi,
                    if hard.is_finite() { hard } else { f64::NAN },
                    self.cells[g] as f64,
                    load[0],
                    load[1],
                    load[2],
                    unl[0],
                    unl[1],
                    unl[2],
                    rec[0],
                    rec[1],
                    rec[2],
                    top[0],
                    top[1],
                    top[2],
                    contact,
                    plastic,
                    capped,
                    area_ratio,
                    best.unwrap_or(f64::NAN),
                    lo.unwrap_or(f64::NAN),
                    hi.unwrap_or(f64::NAN),
                ]);
            }
        }
        (s, refits, retrace)
    }

    /// The finest grid's scalars; returns its rows.
    fn scalars(
        &self,
        out: &mut Section,
        s: &Table,
        refits: &[Refit],
        retrace: f64,
    ) -> Vec<Vec<f64>> {
        let finest = self.cells.len() - 1;
        // Scalars: the finest grid's.
        let rows_at = |g: usize| -> Vec<Vec<f64>> {
            s.rows
                .iter()
                .filter(|r| r[2] == self.cells[g] as f64)
                .cloned()
                .collect()
        };
        let fine = rows_at(finest);
        let (first, last) = (&fine[0], &fine[fine.len() - 1]);
        out.scalar("loading_ratio_elastic", first[3]);
        out.scalar("loading_ratio_most_plastic", last[3]);
        out.scalar("unloading_ratio_elastic", first[6]);
        out.scalar("unloading_ratio_most_plastic", last[6]);
        out.scalar("recovery_ratio_most_plastic", last[9]);
        out.scalar("peak_approach_ratio_elastic", first[12]);
        out.scalar("peak_approach_ratio_most_plastic", last[12]);
        out.scalar("plastic_share_3d_most_plastic", last[16]);
        out.scalar("capped_share_mrd_most_plastic", last[17]);
        out.scalar("area_hardness_over_force_most_plastic", last[18]);
        out.scalar("reload_retrace_max", retrace);
        if let (Some((_, Some(e), ..)), Some((_, Some(p), ..))) = (refits.first(), refits.last()) {
            out.scalar("lambda_refit_elastic", *e);
            out.scalar("lambda_refit_most_plastic", *p);
        }
        // The grid's effect: the largest change of ln(loading ratio) from the coarser grid.
        if self.cells.len() > 1 {
            let coarse = rows_at(finest - 1);
            let change = fine
                .iter()
                .zip(&coarse)
                .map(|(a, b)| (a[3] / b[3]).ln().abs())
                .fold(0.0, f64::max);
            out.scalar("loading_ratio_grid_change_max", change);
        }
        fine
    }

    /// The ratios and the refit against psi.
    fn plasticity_figures(out: &mut Section, fine: &[Vec<f64>], refits: &[Refit], lambda: f64) {
        let first = &fine[0];
        // Ratios against psi, each quantity a few per cent apart in psi so that the bars
        // stay apart, with the elastic case's value dashed in its colour.
        let plastic_rows: Vec<&Vec<f64>> = fine.iter().filter(|r| r[0] > 0.0).collect();
        let (x0, x1) = (
            plastic_rows.first().map_or(1.0, |r| r[0]),
            plastic_rows.last().map_or(1.0, |r| r[0]),
        );
        let quantities = [
            (3, "loading stiffness", Style::Markers),
            (6, "unloading stiffness at the peak", Style::Crosses),
            (9, "recovered approach", Style::Markers),
            (12, "approach at the peak", Style::Crosses),
        ];
        let mut ratio_fig = Figure::new(
            "ratio_against_plasticity",
            "MRD over 3D against the plasticity index (dashed: the elastic case's)",
            "plasticity index psi = E* h'_rms / H [1]",
            "MRD / 3D [1]",
        );
        for (k, &(col, label, style)) in quantities.iter().enumerate() {
            let shift = 1.0 + 0.04 * (k as f64 - 1.5);
            ratio_fig = ratio_fig.with(
                Series::new(
                    label,
                    plastic_rows
                        .iter()
                        .map(|r| (r[0] * shift, r[col]))
                        .collect(),
                    style,
                )
                .with_bars(
                    plastic_rows
                        .iter()
                        .map(|r| (r[0] * shift, r[col + 1], r[col + 2]))
                        .collect(),
                )
                .colored(k),
            );
        }
        for (k, &(col, label, _)) in quantities.iter().enumerate() {
            ratio_fig = ratio_fig.with(
                Series::new(
                    format!("{label}, elastic"),
                    vec![(x0, first[col]), (x1, first[col])],
                    Style::Dashed,
                )
                .colored(k),
            );
        }
        ratio_fig.log_x = true;
        out.figures.push(ratio_fig);
        let fitted: Vec<&Refit> = refits
            .iter()
            .filter(|r| r.0 > 0.0 && r.1.is_some())
            .collect();
        let mut lambda_fig = Figure::new(
            "lambda_refit",
            "lambda refitted to the 3D loading stiffness against the plasticity index",
            "plasticity index psi = E* h'_rms / H [1]",
            "lambda of Eq. (76) [1]",
        )
        .with(
            Series::new(
                "refitted at psi",
                fitted
                    .iter()
                    .map(|r| (r.0, r.1.unwrap_or(f64::NAN)))
                    .collect(),
                Style::Markers,
            )
            .with_bars(
                fitted
                    .iter()
                    .filter_map(|r| Some((r.0, r.2?, r.3?)))
                    .collect(),
            ),
        )
        .plot(
            "the scene's lambda",
            vec![(x0, lambda), (x1, lambda)],
            Style::Dashed,
        );
        if let Some((_, Some(e), ..)) = refits.first() {
            lambda_fig =
                lambda_fig.plot("refitted, elastic", vec![(x0, *e), (x1, *e)], Style::Line);
        }
        lambda_fig.log_x = true;
        out.figures.push(lambda_fig);
    }

    /// The mean history of the elastic and the most plastic case, both methods, finest
    /// grid: table and loop figure.
    fn history_report(&self, out: &mut Section, d: &Data) {
        let (cases, forces) = (&d.cases[..], &d.forces[..]);
        let finest = self.cells.len() - 1;
        // The mean history of the most plastic case, both methods, finest grid.
        let c = cases.len() - 1;
        let mut hist = Table::new(
            "history",
            &[
                "psi [1]",
                "step [index]",
                "f [1]",
                "3D approach [length]",
                "3D approach low [length]",
                "3D approach high [length]",
                "MRD approach [length]",
                "3D contact fraction [1]",
                "MRD contact fraction [1]",
                "3D plastic share [1]",
                "MRD capped share [1]",
            ],
        );
        hist.notes.push(format!(
            "means over the runs at each step of the history (first loading, unloading to {UNLOAD:?} and reloading to {RELOAD:?} of the peak); 3D on the finest grid; approaches from each run's first contact; 3D contact fraction: contact area over the face's disc; MRD contact fraction: the share of springs in contact (a length fraction of the line, not an area)"
        ));
        for c in [0, c] {
            let (bem, lines) = (d.three(c, finest), d.mrd(c, UNIT));
            for (k, &f) in forces.iter().enumerate() {
                let m = |runs: &[Reading], q: &dyn Fn(&Point) -> f64| {
                    mean_ci(&runs.iter().map(|r| q(&r.points[k])).collect::<Vec<_>>())
                };
                let (d3, e3) = m(bem, &|p| p.approach);
                hist.push(vec![
                    cases[c],
                    k as f64,
                    f,
                    d3,
                    d3 - e3,
                    d3 + e3,
                    m(lines, &|p| p.approach).0,
                    m(bem, &|p| p.contact).0,
                    m(lines, &|p| p.contact).0,
                    m(bem, &|p| p.plastic).0,
                    m(lines, &|p| p.plastic).0,
                ]);
            }
        }
        let mut loop_fig = Figure::new(
            "loop",
            "Force against approach, mean over the runs (dashed: unloading, reloading)",
            "approach from first contact d / L [1]",
            "reduced force f = F / (E* h L) [1]",
        );
        // The first loading, then the unloading from the peak and the reloading.
        let branches = [(0, self.loads), (self.loads - 1, forces.len())];
        for (i, &c) in [0, c].iter().enumerate() {
            let rows: Vec<&Vec<f64>> = hist.rows.iter().filter(|r| r[0] == cases[c]).collect();
            for (method, col, style) in [("3D", 3, Style::Markers), ("MRD", 6, Style::Line)] {
                for (b, &(from, to)) in branches.iter().enumerate() {
                    let style = match (style, b) {
                        (Style::Line, 1) => Style::Dashed,
                        (Style::Markers, 1) => Style::Crosses,
                        (s, _) => s,
                    };
                    let label = match b {
                        0 => format!("{method} {}, loading", psi_label(cases[c])),
                        _ => format!("{method} {}, unloading and reloading", psi_label(cases[c])),
                    };
                    loop_fig = loop_fig.with(
                        Series::new(
                            label,
                            rows[from..to].iter().map(|r| (r[col], r[2])).collect(),
                            style,
                        )
                        .colored(i),
                    );
                }
            }
        }
        out.figures.push(loop_fig);
        out.tables.push(hist);
    }
}

/// The psi of a case as a label.
fn psi_label(psi: f64) -> String {
    if psi == 0.0 {
        "elastic".to_string()
    } else {
        format!("psi = {psi}")
    }
}

/// The scene's lambda in the refit's scan (factor 1).
const UNIT: usize = 2;

/// What the report reads: the cases (psi, 0 the elastic one), every run of each, and the
/// scales.
struct Data {
    cases: Vec<f64>,
    /// 3D runs by (case, grid, realisation), MRD runs by (case, lambda factor, line).
    three: Vec<Reading>,
    mrd: Vec<Reading>,
    grids: usize,
    faces: usize,
    lines: usize,
    lambda: f64,
    h: f64,
    slope: f64,
    forces: Vec<f64>,
}

impl Data {
    /// The 3D runs of case `c` on grid `g`.
    fn three(&self, c: usize, g: usize) -> &[Reading] {
        let start = (c * self.grids + g) * self.faces;
        &self.three[start..start + self.faces]
    }
    /// The MRD runs of case `c` at lambda factor `k`.
    fn mrd(&self, c: usize, k: usize) -> &[Reading] {
        let start = (c * REFIT.len() + k) * self.lines;
        &self.mrd[start..start + self.lines]
    }
}

/// The x where the piecewise-linear `curve` (x increasing, y monotone) takes `y`.
fn crossing(curve: &[(f64, f64)], y: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        let t = (y - y0) / (y1 - y0);
        (t.is_finite() && (0.0..=1.0).contains(&t)).then_some(x0 + t * (x1 - x0))
    })
}
