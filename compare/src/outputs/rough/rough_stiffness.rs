//! `rough_stiffness`: the ensemble stiffness-force law of MRD rough lines (Eq. 77) and
//! its exponent alpha, with C1D = lambda q C2D (Eq. 76) from a self-affine spectrum or
//! from the radially averaged PSD of a measured topography; the reduction of Table 1 to
//! a power-law profile n = H for comparison of slopes.

use crate::checks::{bad, check_line, default_force_points, default_realisations, positive};
use crate::context::Context;
use crate::error::{CompareError, Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::friction::log_space;
use mrd::rough_contact::{ensemble, fit_line, RoughLine, Stat};
use mrd::roughness::synthesis::Amplitudes;
use mrd::roughness::{SelfAffine, TabulatedSpectrum};
use serde::Deserialize;
use std::f64::consts::PI;

/// A height map on disk and its physical size.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MeasuredSurface {
    /// `.npy` or text matrix, relative to the scene.
    pub heights: String,
    /// [lx, ly] in length units.
    pub size: [f64; 2],
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughStiffness {
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// A measured topography whose radially averaged PSD replaces the self-affine
    /// spectrum: C1D = lambda q C2D_measured (Eq. 76).
    measured: Option<MeasuredSurface>,
    /// Points of each rough line.
    points: usize,
    /// Length L of each rough line [length].
    length: f64,
    /// Upper cut-off as a fraction of the Nyquist wavenumber pi N / L.
    #[serde(default = "default_cutoff_ratio")]
    upper_cutoff_ratio: f64,
    /// lambda of Eq. 76 as written, C1D = lambda q C2D of the same C2D: a number, "pi",
    /// "cut", "calibrated" or a table's path; default "pi".
    #[serde(default)]
    lambda: LambdaSpec,
    /// Rough lines averaged.
    #[serde(default = "default_realisations")]
    realisations: u64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// Smallest dimensionless force F/(E* h L).
    f_min: f64,
    /// Largest dimensionless force F/(E* h L).
    f_max: f64,
    /// Forces, log-spaced from f_min to f_max.
    #[serde(default = "default_force_points")]
    f_points: usize,
}

fn default_cutoff_ratio() -> f64 {
    0.5
}

impl Output for RoughStiffness {
    fn validate(&self, ctx: &Context) -> Result<()> {
        check_line(self.hurst, self.points, self.length, self.realisations)?;
        if !(self.upper_cutoff_ratio > 0.0 && self.upper_cutoff_ratio <= 1.0) {
            return bad("upper_cutoff_ratio must lie in (0, 1]");
        }
        if !(positive(self.f_min) && positive(self.f_max) && self.f_max > self.f_min) {
            return bad("need 0 < f_min < f_max");
        }
        crate::checks::count_in(
            "f_points",
            self.f_points as u64,
            3..=crate::checks::MAX_LOADS,
        )?;
        if let LambdaSpec::Value(v) = self.lambda {
            if !positive(v) {
                return bad(format!("lambda = {v} must be > 0"));
            }
        }
        self.lambda.build(ctx)?.at(self.hurst).ctx("lambda")?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = Vec::new();
        if self.measured.is_some() {
            s.push(Stage::Psd);
        }
        s.extend([Stage::RoughSynthesis, Stage::RoughContact]);
        s
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let e = env.ctx.material.e_star;
        let (hurst, points, length) = (self.hurst, self.points, self.length);
        let lam = self.lambda.build(env.ctx)?.at(hurst).ctx("lambda")?;
        let q0 = 2.0 * PI / length;
        let q1 = PI * points as f64 / length * self.upper_cutoff_ratio;
        // f = F/(E* h L) with h the rms height of the surface the lines stand for (Eq. 76:
        // C1D = lambda q C2D of that surface's C2D, so lambda moves the curve): the
        // self-affine spectrum scaled to h = 1, or the measured map's own h.
        let surf = SelfAffine::new(hurst, q0, q0, q1)
            .and_then(|s| s.with_rms_height(1.0))
            .ctx("spectrum")?;
        let spec = surf.to_line(lam);
        let (tab, h_surface) = match &self.measured {
            Some(m) => {
                let (tab, h) = self.measured_psd(env, out, m)?;
                (Some(tab), h)
            }
            None => (None, 1.0),
        };
        let c1d = |q: f64| match &tab {
            Some(t) => lam * q * t.c2d(q),
            None => spec.c1d(q),
        };
        let fs = log_space(self.f_min, self.f_max, self.f_points);
        let (realisations, seed) = (self.realisations, self.seed);
        let per: Vec<Vec<f64>> = out
            .stages_together(&[Stage::RoughSynthesis, Stage::RoughContact], || {
                ensemble(realisations, |r| {
                    let h = mrd::roughness::synthesis::line_from(
                        &c1d,
                        points,
                        length,
                        seed,
                        r,
                        Amplitudes::Deterministic,
                    )?;
                    let rl = RoughLine::new(&h, length, e)?;
                    fs.iter()
                        .map(|&f| {
                            Ok(rl.reduced_stiffness(
                                rl.at_force(f * e * h_surface * length)?.stiffness,
                            ))
                        })
                        .collect()
                })
            })
            .ctx("rough lines")?;
        let stats: Vec<Stat> = (0..fs.len())
            .map(|k| Stat::of(&per.iter().map(|v| v[k]).collect::<Vec<_>>()))
            .collect();
        // Power-law regime: k/(E*L) between 2 contact points and 10 % of full stiffness.
        let k_lo = 2.0 / points as f64;
        let sel: Vec<usize> = (0..fs.len())
            .filter(|&k| stats[k].mean > k_lo && stats[k].mean < 0.1)
            .collect();
        if sel.len() < 3 {
            return Err(CompareError::Scene(
                "fewer than 3 loads in the power-law regime; widen f_min..f_max".into(),
            ));
        }
        let fit = fit_line(
            &sel.iter().map(|&k| fs[k].ln()).collect::<Vec<_>>(),
            &sel.iter().map(|&k| stats[k].mean.ln()).collect::<Vec<_>>(),
        )
        .ctx("fit of Eq. 77")?;
        let mut t = Table::new(
            "rough_stiffness",
            &[
                "f = F/(E* h L) [1]",
                "k/(E* L) mean [1]",
                "k/(E* L) std [1]",
                "k/(E* L) ci95 [1]",
                "in_fit_range [0/1]",
            ],
        );
        let ratio = self.upper_cutoff_ratio;
        t.notes.push(match &self.measured {
            Some(m) => format!("Eq. (77) on {realisations} MRD rough lines: N = {points}, L = {length}, C1D = lambda q C2D with lambda = {lam} (at H = {hurst}) and C2D the radially averaged PSD of {} ({} x {}); f = F/(E* h L), h = {h_surface:.6e} the map's rms height", m.heights, m.size[0], m.size[1]),
            None => format!("Eq. (77) on {realisations} MRD rough lines: N = {points}, L = {length}, H = {hurst}, C1D = lambda q C2D with lambda = {lam} (Eq. 76), q from 2 pi/L to {ratio} x Nyquist; f = F/(E* h L), h the rms height of the surface with that C2D (continuum, Eq. 70)"),
        });
        for (k, s) in stats.iter().enumerate() {
            t.push(vec![
                fs[k],
                s.mean,
                s.std,
                s.ci95,
                sel.contains(&k) as u8 as f64,
            ]);
        }
        out.scalar("alpha", fit.b);
        out.scalar("alpha_ci95", 1.96 * fit.se_b);
        out.scalar("zeta", fit.a.exp());
        if hurst > -1.0 {
            out.scalar("alpha_scaling_eq80", 1.0 / (1.0 + hurst)); // Eq. (80)
        }
        out.scalar("lambda", lam);
        let fig = self.figure(out, &t, &sel, fit);
        out.figures.push(fig);
        out.tables.push(t);
        Ok(())
    }
}

impl RoughStiffness {
    /// The radially averaged PSD of the measured map, as a tabulated spectrum.
    fn measured_psd(
        &self,
        env: &Env,
        out: &mut Section,
        m: &MeasuredSurface,
    ) -> Result<(TabulatedSpectrum, f64)> {
        let path = env.ctx.resolve(&m.heights);
        let (tab, h) = out.stage(Stage::Psd, || -> Result<_> {
            let map = mrd::topography::HeightMap::read(&path).ctx("measured topography")?;
            let psd = mrd::roughness::stats::surface_psd(
                &map.data, map.cols, map.rows, m.size[0], m.size[1], 40,
            );
            let n = map.data.len() as f64;
            let mean = map.data.iter().sum::<f64>() / n;
            let h = (map.data.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
            let tab = TabulatedSpectrum::new(&psd)
                .ctx(format!("PSD of {}", path.display()))?
                .with_lowest_wavenumber(2.0 * PI / m.size[0].max(m.size[1]));
            Ok((tab, h))
        })?;
        // A power-law exponent needs at least 8 bins over a decade of q, and a value
        // the self-affine spectra cover (Eq. 70).
        let (bins, span) = tab.extent();
        let hurst = tab.fitted_hurst();
        if bins >= 8 && span >= 10.0 && (-1.0..=3.0).contains(&hurst) {
            out.scalar("measured_fitted_hurst", hurst);
        } else {
            out.warn(format!(
                "measured topography {}: its PSD has {bins} bins over a factor {span:.1} in q and a fitted Hurst exponent of {hurst:.2}; not reported (a fit needs >= 8 bins over a decade and H in [-1, 3]: use a larger map)",
                path.display()
            ));
        }
        Ok((tab, h))
    }

    fn figure(
        &self,
        out: &mut Section,
        t: &Table,
        sel: &[usize],
        fit: mrd::rough_contact::LineFit,
    ) -> Figure {
        let hurst = self.hurst;
        let f = t.column("f = F/(E* h L)");
        let k = t.column("k/(E* L) mean");
        let mut fig = Figure::new(
            "rough_stiffness",
            &format!("Stiffness-force law (Eq. 77), H = {hurst}"),
            "reduced force F/(E* h L) [1]",
            "reduced stiffness k/(E* L) [1]",
        )
        .plot(
            format!("MRD rough lines ({})", self.realisations),
            t.xy("f = F/(E* h L)", "k/(E* L) mean"),
            Style::Markers,
        )
        .plot(
            format!("fit: alpha = {:.3} +/- {:.3}", fit.b, 1.96 * fit.se_b),
            sel.iter()
                .map(|&j| (f[j], (fit.a + fit.b * f[j].ln()).exp()))
                .collect(),
            Style::Line,
        );
        // Table 1, dashed arrows: a power-law profile z = c r^n with n = H has
        // k ~ F^(1/(1+n)) exactly (Eqs. 20-21); drawn through the fit's centre.
        if hurst > 0.0 {
            let alpha = 1.0 / (1.0 + hurst);
            let mid = sel[sel.len() / 2];
            let c = k[mid] / f[mid].powf(alpha);
            out.scalar("alpha_power_law_profile_n_eq_H", alpha);
            fig = fig.plot(
                format!("power-law profile n = H: alpha = 1/(1+H) = {alpha:.3}"),
                sel.iter().map(|&j| (f[j], c * f[j].powf(alpha))).collect(),
                Style::Dashed,
            );
        }
        fig.log_log()
    }
}
