//! `sliding_friction`: the friction coefficient mu(v) of a rigid rough line sliding over
//! an elastomer with linear rheology on the MRD foundation (Section 10.1, Fig. 7),
//! against the estimate of Eq. (82), mu = xi grad z G''(k v) / |G(k v)|, with xi fitted.
//!
//! The elastomer is the continuous spectrum of Eq. (84) discretised into a Prony series
//! (accuracy: `mrd::rheology`), or a Prony series of G(t) given directly; the springs
//! carry 4 G(t) dx (Eq. 62). Lines: a band-limited "non-fractal" line (flat C2D between
//! k/b and k b, C1D = pi q C2D, Eq. 76 with lambda = pi), a self-affine line, or a
//! sinusoid; scaled to the given rms height. k = rms slope / rms height of the line's
//! spectrum, grad z its rms slope. Every (velocity, line) run is a steady-state
//! simulation (`mrd::sliding`); the ensemble mean and its 95 % interval are reported per
//! velocity, xi by least squares over all velocities with a bootstrap interval over
//! lines. A run that does not reach its steady state is listed and fails the run.

use super::elastomer::{self, Material};
use crate::checks::{bad, positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::rheology::Prony;
use mrd::rough_contact::Stat;
use mrd::roughness::synthesis::{line_from, Amplitudes};
use mrd::sliding::{slide, Line, Sliding, SlidingResult};
use rand::RngExt;
use rayon::prelude::*;
use serde::Deserialize;
use std::f64::consts::{PI, TAU};

/// The rigid line.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(super) enum LineSpec {
    /// Flat C2D for q in [k/band, k band] (non-fractal), `waves` = k L / (2 pi).
    Band { waves: f64, band: f64 },
    /// Self-affine C2D ~ q^(-2H-2) for q from `min_waves` 2 pi / L (default 1) to
    /// `waves` 2 pi / L.
    SelfAffine {
        hurst: f64,
        waves: f64,
        #[serde(default = "one_f")]
        min_waves: f64,
    },
    /// h0 cos(k x + phase), `waves` whole waves over L.
    Sinusoid { waves: usize },
}

impl LineSpec {
    /// The isotropic 2D spectrum C2D(q) of a surface of size `l` (up to a factor), whose
    /// MRD line has C1D = pi q C2D (Eq. 76 with lambda = pi); None for the sinusoid.
    pub(super) fn c2d(&self, l: f64) -> Option<Box<dyn Fn(f64) -> f64 + Send + Sync>> {
        match *self {
            LineSpec::Band { waves, band } => {
                let k = TAU * waves / l;
                let (lo, hi) = (k / band, k * band);
                Some(Box::new(
                    move |q| if (lo..=hi).contains(&q) { 1.0 } else { 0.0 },
                ))
            }
            LineSpec::SelfAffine {
                hurst,
                waves,
                min_waves,
            } => {
                let (q0, q1) = (TAU * min_waves / l, TAU * waves / l);
                Some(Box::new(move |q| {
                    if (q0..=q1).contains(&q) {
                        q.powf(-2.0 * hurst - 2.0)
                    } else {
                        0.0
                    }
                }))
            }
            LineSpec::Sinusoid { .. } => None,
        }
    }

    /// The lowest and highest wavenumber q of the spectrum on a line of length `l`.
    pub(super) fn q_range(&self, l: f64) -> (f64, f64) {
        let q = |waves: f64| TAU * waves / l;
        match *self {
            LineSpec::Band { waves, band } => (q(waves / band), q(waves * band)),
            LineSpec::SelfAffine {
                waves, min_waves, ..
            } => (q(min_waves), q(waves)),
            LineSpec::Sinusoid { waves } => (q(waves as f64), q(waves as f64)),
        }
    }

    /// The highest wave number (waves over L) of the spectrum.
    pub(super) fn max_waves(&self) -> f64 {
        match *self {
            LineSpec::Band { waves, band } => waves * band,
            LineSpec::SelfAffine { waves, .. } => waves,
            LineSpec::Sinusoid { waves } => waves as f64,
        }
    }

    /// `key`: the scene key, named in messages.
    pub(super) fn validate(&self, key: &str) -> Result<()> {
        match *self {
            LineSpec::Band { waves, band } => {
                if !(positive(waves) && band > 1.0 && band.is_finite()) {
                    return bad(format!("{key}: waves must be > 0 and band > 1"));
                }
            }
            LineSpec::SelfAffine {
                hurst,
                waves,
                min_waves,
            } => {
                let ok = (-1.0..=3.0).contains(&hurst)
                    && min_waves >= 1.0
                    && waves >= 2.0 * min_waves
                    && waves.is_finite();
                if !ok {
                    return bad(format!(
                        "{key}: hurst must lie in [-1, 3], min_waves >= 1 and waves >= 2 min_waves"
                    ));
                }
            }
            LineSpec::Sinusoid { waves } => {
                if waves == 0 {
                    return bad(format!("{key}: waves must be >= 1"));
                }
            }
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlidingFriction {
    pub(super) material: Material,
    pub(super) line: LineSpec,
    /// Line length L and rms height h (length units).
    pub(super) length: f64,
    pub(super) rms_height: f64,
    /// Springs along L.
    pub(super) springs: usize,
    /// Line points per spring (the line is synthesised on springs x this).
    #[serde(default = "one")]
    pub(super) refine: usize,
    /// Line points moved per time step.
    #[serde(default = "one")]
    pub(super) stride: usize,
    /// Normal force as F / (4 G(inf) h L), the reduced force of the relaxed (rubbery)
    /// contact (Eq. 77).
    pub(super) reduced_force: f64,
    /// Sliding velocities: `velocities` values log-spaced from `velocity_min` to
    /// `velocity_max` (length units per second).
    pub(super) velocity_min: f64,
    pub(super) velocity_max: f64,
    pub(super) velocities: usize,
    pub(super) realisations: u64,
    #[serde(default)]
    pub(super) seed: u64,
    /// Steady state: mu and the mean approach change by less than this between passes
    /// (relative to mu and to the rms height).
    #[serde(default = "tolerance")]
    pub(super) tolerance: f64,
    #[serde(default = "max_passes")]
    pub(super) max_passes: usize,
    /// A velocity is resolved where the two routes to mu (the friction force and the
    /// dissipated energy per unit distance) agree within this, relatively, on every
    /// line; Eq. (82) is fitted over the resolved velocities only.
    #[serde(default = "error_limit")]
    pub(super) error_limit: f64,
}

fn one() -> usize {
    1
}
fn one_f() -> f64 {
    1.0
}
fn tolerance() -> f64 {
    1e-4
}
fn max_passes() -> usize {
    400
}
fn error_limit() -> f64 {
    0.1
}

/// Runs of one velocity, over the lines.
pub(super) struct AtVelocity {
    pub velocity: f64,
    pub runs: Vec<SlidingResult>,
}

impl SlidingFriction {
    fn points(&self) -> usize {
        self.springs * self.refine
    }

    fn velocity_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(self.velocity_min, self.velocity_max, self.velocities)
    }

    /// Line `r`, scaled to the rms height.
    fn line(&self, r: u64) -> mrd::Result<Line> {
        let (n, l) = (self.points(), self.length);
        let z = if let LineSpec::Sinusoid { waves } = self.line {
            let phase =
                TAU * mrd::roughness::synthesis::realisation_rng(self.seed, r).random::<f64>();
            (0..n)
                .map(|i| (TAU * waves as f64 * i as f64 / n as f64 + phase).cos())
                .collect()
        } else {
            let c2d = self.line.c2d(l);
            line_from(
                &|q: f64| PI * q * c2d.as_ref().map_or(0.0, |c| c(q)),
                n,
                l,
                self.seed,
                r,
                Amplitudes::Deterministic,
            )?
        };
        let h = Line::new(&z, l)?.rms_height;
        let z: Vec<f64> = z.iter().map(|v| v * self.rms_height / h).collect();
        Line::new(&z, l)
    }

    fn setup(&self, shear: &Prony, velocity: f64) -> Sliding {
        let f = self.reduced_force * 4.0 * shear.relaxed * self.rms_height * self.length;
        Sliding {
            modulus: shear.scaled(4.0),
            springs: self.springs,
            stride: self.stride,
            normal_force: f,
            velocity,
            tolerance: self.tolerance,
            max_passes: self.max_passes,
            accelerate: true,
        }
    }
}

impl Output for SlidingFriction {
    fn validate(&self, _: &Context) -> Result<()> {
        let shear = self.material.validate()?;
        self.line.validate("line")?;
        if !(positive(self.length) && positive(self.rms_height)) {
            return bad("length and rms_height must be > 0");
        }
        if !(16..=1 << 20).contains(&self.springs) || self.refine == 0 || self.stride == 0 {
            return bad("springs must lie in 16..=1048576, refine and stride >= 1");
        }
        if !self.points().is_multiple_of(self.stride) {
            return bad(format!(
                "stride = {} must divide springs x refine = {}",
                self.stride,
                self.points()
            ));
        }
        if self.points() > 1 << 22 {
            return bad("springs x refine must be <= 4194304");
        }
        crate::checks::check_memory(
            self.springs as f64
                * (shear.terms.len() as f64 + 4.0)
                * 16.0
                * rayon::current_num_threads() as f64,
            &format!("springs = {}", self.springs),
        )?;
        if !positive(self.reduced_force) {
            return bad("reduced_force must be > 0");
        }
        elastomer::velocities(
            self.velocity_min,
            self.velocity_max,
            self.velocities,
            &shear,
            self.line.q_range(self.length),
        )?;
        if !(2..=10_000).contains(&self.realisations) {
            return bad("realisations must lie in 2..=10000 (for intervals)");
        }
        if !(self.tolerance > 0.0 && self.tolerance < 0.1) || self.max_passes < 2 {
            return bad("tolerance must lie in (0, 0.1) and max_passes be >= 2");
        }
        if !(self.error_limit > 0.0 && self.error_limit <= 1.0) {
            return bad("error_limit must lie in (0, 1]");
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::ViscoelasticSliding]
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let (lines, per_v) = self.simulate(out)?;
        self.report(env, out, &lines, &per_v)
    }
}

impl SlidingFriction {
    /// The lines and every (velocity, line) run, stages recorded in `out`.
    pub(super) fn simulate(&self, out: &mut Section) -> Result<(Vec<Line>, Vec<AtVelocity>)> {
        let shear = self.material.shear().ctx("material")?;
        let lines: Vec<Line> = out
            .stage(Stage::RoughSynthesis, || {
                (0..self.realisations)
                    .map(|r| self.line(r))
                    .collect::<mrd::Result<_>>()
            })
            .ctx("lines")?;
        let vs = self.velocity_grid();
        let jobs: Vec<(usize, usize)> = (0..vs.len())
            .flat_map(|i| (0..lines.len()).map(move |r| (i, r)))
            .collect();
        let runs: Vec<SlidingResult> = out
            .stage(Stage::ViscoelasticSliding, || {
                jobs.par_iter()
                    .with_max_len(1)
                    .map(|&(i, r)| slide(&lines[r], &self.setup(&shear, vs[i])))
                    .collect::<mrd::Result<_>>()
            })
            .ctx("sliding")?;
        let per_v: Vec<AtVelocity> = vs
            .iter()
            .enumerate()
            .map(|(i, &velocity)| AtVelocity {
                velocity,
                runs: runs[i * lines.len()..(i + 1) * lines.len()].to_vec(),
            })
            .collect();
        Ok((lines, per_v))
    }
}

/// Largest |mu - mu_energy| / |mu| over the runs of one velocity: how far the friction
/// force and the dissipated energy per unit distance, equal in the continuum, differ
/// on these springs (NaN counts as unresolved).
pub(super) fn routes_rel_diff(runs: &[SlidingResult]) -> f64 {
    runs.iter()
        .map(|x| ((x.mu - x.mu_energy) / x.mu).abs())
        .fold(0.0, |a: f64, d| {
            if d.is_nan() || a.is_nan() {
                f64::NAN
            } else {
                a.max(d)
            }
        })
}

/// The resolution judgement of [`SlidingFriction::judge_and_fit`].
struct Judged {
    routes: Vec<f64>,
    resolved: Vec<bool>,
    n_resolved: usize,
    fits: Option<(elastomer::XiFit, elastomer::ShiftFit)>,
}

impl SlidingFriction {
    fn report(
        &self,
        env: &Env,
        out: &mut Section,
        lines: &[Line],
        per_v: &[AtVelocity],
    ) -> Result<()> {
        let u = &env.ctx.units;
        // k and grad z: ensemble means of the lines' own values.
        let k = lines.iter().map(Line::wave_vector).sum::<f64>() / lines.len() as f64;
        let grad_z = lines.iter().map(|l| l.rms_slope).sum::<f64>() / lines.len() as f64;
        let vs: Vec<f64> = per_v.iter().map(|p| p.velocity).collect();
        let r = self.material.eq82_over_xi(k, grad_z, &vs)?;
        let Judged {
            routes,
            resolved,
            n_resolved,
            fits,
        } = self.judge_and_fit(out, per_v, &r, k, grad_z)?;
        let xi = fits.as_ref().map_or(f64::NAN, |f| f.0.xi);
        let mut t = Table::new(
            "sliding_friction",
            &[
                format!("velocity [{}/s]", u.length),
                "kv [rad/s]".to_string(),
                "mu_mean [1]".into(),
                "mu_ci95 [1]".into(),
                "mu_energy_mean [1]".into(),
                "contact_fraction_mean [1]".into(),
                "eq82_over_xi [1]".into(),
                "eq82_fitted [1]".into(),
                "passes_max [count]".into(),
                "converged [0/1]".into(),
                "routes_rel_diff_max [1]".into(),
                "resolved [0/1]".into(),
            ],
        );
        t.missing_ok = true;
        t.notes.push(format!(
            "Section 10.1: {} lines of {} springs (line points x{}), stride {}, L = {}, h = {}, k = rms slope / rms height = {k:e}, grad z = {grad_z:e}; reduced force F/(4 G_inf h L) = {}; material {:?}; steady state: mu and mean approach change < {:e} between passes; mu from sum f dz/dx, mu_energy from the dissipated energy per unit distance; eq82_over_xi = grad z G''(kv)/|G(kv)|; routes_rel_diff_max = max over lines of |mu - mu_energy| / |mu|; resolved = 1 where it is <= error_limit = {}; xi fitted over the resolved velocities (eq82_fitted empty where not fitted)",
            lines.len(), self.springs, self.refine, self.stride, self.length, self.rms_height, self.reduced_force, self.material, self.tolerance, self.error_limit
        ));
        let mut runs_t = Table::new(
            "sliding_friction_runs",
            &[
                format!("velocity [{}/s]", u.length),
                "line [count]".into(),
                "mu [1]".into(),
                "mu_energy [1]".into(),
                "contact_fraction [1]".into(),
                format!("mean_approach [{}]", u.length),
                "passes [count]".into(),
                "converged [0/1]".into(),
            ],
        );
        runs_t
            .notes
            .push("every steady-state run; converged = 0: max_passes reached".into());
        let mut energy_dev: f64 = 0.0;
        for (i, p) in per_v.iter().enumerate() {
            let mus: Vec<f64> = p.runs.iter().map(|x| x.mu).collect();
            let st = Stat::of(&mus);
            let me = p.runs.iter().map(|x| x.mu_energy).sum::<f64>() / p.runs.len() as f64;
            let cf = p.runs.iter().map(|x| x.contact_fraction).sum::<f64>() / p.runs.len() as f64;
            let passes = p.runs.iter().map(|x| x.history.len()).max().unwrap_or(0);
            let conv = p.runs.iter().all(|x| x.converged);
            energy_dev = energy_dev.max((me - st.mean).abs() / st.mean.abs().max(1e-300));
            t.push(vec![
                p.velocity,
                k * p.velocity,
                st.mean,
                st.ci95,
                me,
                cf,
                r[i],
                xi * r[i],
                passes as f64,
                conv as u8 as f64,
                routes[i],
                resolved[i] as u8 as f64,
            ]);
            for (line, x) in p.runs.iter().enumerate() {
                runs_t.push(vec![
                    p.velocity,
                    line as f64,
                    x.mu,
                    x.mu_energy,
                    x.contact_fraction,
                    x.depth,
                    x.history.len() as f64,
                    x.converged as u8 as f64,
                ]);
                if !x.converged {
                    out.failures.push(format!(
                        "velocity {:e}, line {line}: no steady state after {} passes (last two mu {:?})",
                        p.velocity,
                        x.history.len(),
                        &x.history[x.history.len().saturating_sub(2)..]
                    ));
                }
            }
        }
        let (imax, peak) = t.column("mu_mean").into_iter().enumerate().fold(
            (0, f64::NEG_INFINITY),
            |m, (i, v)| if v > m.1 { (i, v) } else { m },
        );
        if let Some((f, shift)) = &fits {
            out.scalar("xi", f.xi);
            out.scalar("xi_lo95", f.lo);
            out.scalar("xi_hi95", f.hi);
            out.scalar("eq82_misfit", f.misfit);
            out.scalar("eq82_shift_c", shift.c);
            out.scalar("eq82_shift_c_lo95", shift.c_lo);
            out.scalar("eq82_shift_c_hi95", shift.c_hi);
            out.scalar("eq82_shift_xi", shift.xi);
            out.scalar("eq82_shift_misfit", shift.misfit);
        }
        out.scalar("resolved_velocities", n_resolved as f64);
        out.scalar("wave_vector", k);
        out.scalar("grad_z", grad_z);
        out.scalar("mu_peak", peak);
        out.scalar("velocity_at_peak", per_v[imax].velocity);
        out.scalar("max_rel_dev_energy_vs_slope", energy_dev);
        // Eq. (82) on a fine grid of velocities for the figure.
        let fine_v = mrd::friction::log_space(self.velocity_min, self.velocity_max, 200);
        let fine: Vec<(f64, f64)> = self
            .material
            .eq82_over_xi(k, grad_z, &fine_v)?
            .into_iter()
            .zip(&fine_v)
            .map(|(e, &v)| (v, xi * e))
            .collect();
        let label = match &fits {
            Some((f, _)) => format!(
                "Eq. (82), k = {k:.3} 1/{}, grad z = {grad_z:.3}, xi = {:.3} [{:.3}, {:.3}] (fitted over {n_resolved} resolved velocities)",
                u.length, f.xi, f.lo, f.hi
            ),
            None => "Eq. (82): not fitted (fewer than 2 resolved velocities)".to_string(),
        };
        let fine = if fits.is_some() { fine } else { Vec::new() };
        out.figures.push(self.figure(&t, fine, label, u));
        out.tables.push(t);
        out.tables.push(runs_t);
        Ok(())
    }

    /// Which velocities are resolved (the two routes to mu agree within `error_limit`
    /// on every line; warned otherwise), and the fits of Eq. (82) over them (None,
    /// recorded as a failure, with fewer than two).
    fn judge_and_fit(
        &self,
        out: &mut Section,
        per_v: &[AtVelocity],
        r: &[f64],
        k: f64,
        grad_z: f64,
    ) -> Result<Judged> {
        let vs: Vec<f64> = per_v.iter().map(|p| p.velocity).collect();
        let routes: Vec<f64> = per_v.iter().map(|p| routes_rel_diff(&p.runs)).collect();
        let resolved: Vec<bool> = routes.iter().map(|&d| d <= self.error_limit).collect();
        // Unresolved velocities are left out of the fits.
        let mu: Vec<Vec<f64>> = per_v
            .iter()
            .zip(&resolved)
            .map(|(p, &ok)| {
                p.runs
                    .iter()
                    .map(|x| if ok { x.mu } else { f64::NAN })
                    .collect()
            })
            .collect();
        let n_resolved = resolved.iter().filter(|&&ok| ok).count();
        let unresolved: Vec<String> = vs
            .iter()
            .zip(&routes)
            .filter(|(_, &d)| !(..=self.error_limit).contains(&d))
            .map(|(v, d)| format!("{v:.3e} ({:.0} %)", 100.0 * d))
            .collect();
        if !unresolved.is_empty() {
            out.warn(format!(
                "sliding_friction: {} of {} velocities unresolved (the two routes to mu differ by more than error_limit = {} on some line: {}); left out of the fit of Eq. (82); refine the springs (springs per shortest wave: {:.1})",
                unresolved.len(),
                vs.len(),
                self.error_limit,
                unresolved.join(", "),
                self.springs as f64 / self.line.max_waves()
            ));
        }
        let fits = if n_resolved >= 2 {
            let xi = elastomer::fit_xi(&mu, r, self.seed);
            let shift = elastomer::fit_shift(&mu, &self.material, k, grad_z, &vs, self.seed)?;
            Some((xi, shift))
        } else {
            out.failures.push(format!(
                "only {n_resolved} of {} velocities resolved (error_limit {}): Eq. (82) not fitted, xi missing; refine the springs",
                vs.len(),
                self.error_limit
            ));
            None
        };
        Ok(Judged {
            routes,
            resolved,
            n_resolved,
            fits,
        })
    }

    fn figure(
        &self,
        t: &Table,
        eq82: Vec<(f64, f64)>,
        eq82_label: String,
        u: &crate::context::Units,
    ) -> Figure {
        let mu = t.xy("velocity", "mu_mean");
        let ci95 = t.column("mu_ci95");
        let bars = mu
            .iter()
            .zip(&ci95)
            .map(|(&(v, m), c)| (v, m - c, m + c))
            .collect();
        let mut fig = Figure::new(
            "sliding_friction",
            "Elastomer friction mu(v) by MRD and Eq. (82) (cf. Fig. 7)",
            &format!("sliding velocity v [{}/s]", u.length),
            "friction coefficient mu [1]",
        )
        .with(
            Series::new(
                format!("MRD, mean of {} lines (95% CI)", self.realisations),
                mu,
                Style::Markers,
            )
            .with_bars(bars),
        )
        .with(Series::new(eq82_label, eq82, Style::Line))
        .with(Series::new(
            "MRD, dissipated energy per distance / F_N",
            t.xy("velocity", "mu_energy_mean"),
            Style::Crosses,
        ));
        fig.log_x = true;
        fig
    }
}
