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

use crate::checks::bad;
use crate::context::Context;
use crate::error::Result;
use crate::experiment::elastomer::{self, Material};
use crate::experiment::sliding_line::{routes_rel_diff, AtVelocity, LineSpec, MrdSliding};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::rough_contact::Stat;
use mrd::sliding::Line;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlidingFriction {
    /// The elastomer's modulus, e.g. { kind = "eq84", g0, g1, tau1, tau2, s, terms } (Eq.
    /// 84).
    pub(super) material: Material,
    /// The rigid rough line, e.g. { kind = "band", waves, band }: a flat C2D from k / band
    /// to k band.
    pub(super) line: LineSpec,
    /// Line length L and rms height h (length units).
    pub(super) length: f64,
    /// Rms height h of the line [length].
    pub(super) rms_height: f64,
    /// Springs along L.
    pub(super) springs: usize,
    /// Line points per spring (the line is synthesised on springs x this).
    #[serde(default = "crate::checks::default_count::<1>")]
    pub(super) refine: usize,
    /// Line points moved per time step.
    #[serde(default = "crate::checks::default_count::<1>")]
    pub(super) stride: usize,
    /// Normal force as F / (4 G(inf) h L), the reduced force of the relaxed (rubbery)
    /// contact (Eq. 77).
    pub(super) reduced_force: f64,
    /// Sliding velocities: `velocities` values log-spaced from `velocity_min` to
    /// `velocity_max` (length units per second).
    pub(super) velocity_min: f64,
    /// Largest sliding velocity [length / time].
    pub(super) velocity_max: f64,
    /// Velocities, log-spaced from velocity_min to velocity_max.
    pub(super) velocities: usize,
    /// Rough lines averaged.
    pub(super) realisations: u64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    pub(super) seed: u64,
    /// Steady state: mu and the mean approach change by less than this between passes
    /// (relative to mu and to the rms height).
    #[serde(default = "crate::experiment::sliding_line::default_line_tolerance")]
    pub(super) tolerance: f64,
    /// Most passes of the steady-state sliding iteration per velocity.
    #[serde(default = "crate::experiment::sliding_line::default_max_passes")]
    pub(super) max_passes: usize,
    /// A velocity is resolved where the two routes to mu (the friction force and the
    /// dissipated energy per unit distance) agree within this, relatively, on every
    /// line; Eq. (82) is fitted over the resolved velocities only.
    #[serde(default = "crate::experiment::sliding_line::default_error_limit")]
    pub(super) error_limit: f64,
}

impl SlidingFriction {
    /// The ensemble these keys describe (all but the error limit).
    pub(crate) fn ensemble(&self) -> MrdSliding {
        MrdSliding {
            material: self.material.clone(),
            line: self.line.clone(),
            length: self.length,
            rms_height: self.rms_height,
            springs: self.springs,
            refine: self.refine,
            stride: self.stride,
            reduced_force: self.reduced_force,
            velocity_min: self.velocity_min,
            velocity_max: self.velocity_max,
            velocities: self.velocities,
            realisations: self.realisations,
            seed: self.seed,
            tolerance: self.tolerance,
            max_passes: self.max_passes,
        }
    }
}

impl Output for SlidingFriction {
    fn validate(&self, _: &Context) -> Result<()> {
        self.ensemble().validate()?;
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
        let (lines, per_v) = self.ensemble().simulate(out)?;
        self.report(env, out, &lines, &per_v)
    }
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
        .plot(eq82_label, eq82, Style::Line)
        .plot(
            "MRD, dissipated energy per distance / F_N",
            t.xy("velocity", "mu_energy_mean"),
            Style::Crosses,
        );
        fig.log_x = true;
        fig
    }
}
