//! `sliding_friction_3d`'s report: MRD's side in the 3D layout, the fits of Eq. (82),
//! the accuracy per velocity, tables and figures.

use super::{SlidingFriction3d, Solved};
use crate::error::Result;
use crate::experiment::elastomer;
use crate::experiment::sliding_line::AtVelocity;
use crate::output::Env;
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::rough_contact::Stat;

type Points = Vec<(f64, f64)>;
type Bars = Vec<(f64, f64, f64)>;

/// Mean, 95 % interval and count of the finite values.
fn stat(values: impl Iterator<Item = f64>) -> Stat {
    let v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    Stat::of(&v)
}

/// The MRD side's results in the layout of the 3D ones.
struct MrdResults {
    k: f64,
    grad_z: f64,
    /// mu[velocity][line], NaN where no steady state was reached.
    mu: Vec<Vec<f64>>,
    contact: Vec<f64>,
}

impl MrdResults {
    fn of(lines: &[mrd::sliding::Line], per_v: &[AtVelocity], out: &mut Section) -> Self {
        let n = lines.len() as f64;
        let mut mu = Vec::new();
        for p in per_v {
            mu.push(
                p.runs
                    .iter()
                    .enumerate()
                    .map(|(line, x)| {
                        if !x.converged {
                            out.failures.push(format!(
                                "MRD at velocity {:e}, line {line}: no steady state after {} passes",
                                p.velocity,
                                x.history.len()
                            ));
                        }
                        if x.converged {
                            x.mu
                        } else {
                            f64::NAN
                        }
                    })
                    .collect(),
            );
        }
        Self {
            k: lines.iter().map(|l| l.wave_vector()).sum::<f64>() / n,
            grad_z: lines.iter().map(|l| l.rms_slope).sum::<f64>() / n,
            mu,
            contact: per_v
                .iter()
                .map(|p| stat(p.runs.iter().map(|x| x.contact_fraction)).mean)
                .collect(),
        }
    }
}

/// Scalars of one side's fits, as `<name>_<side>`.
fn record_fits(out: &mut Section, side: &str, xi: &elastomer::XiFit, s: &elastomer::ShiftFit) {
    out.scalar(format!("xi_{side}"), xi.xi);
    out.scalar(format!("xi_{side}_lo95"), xi.lo);
    out.scalar(format!("xi_{side}_hi95"), xi.hi);
    out.scalar(format!("eq82_misfit_{side}"), xi.misfit);
    out.scalar(format!("eq82_shift_c_{side}"), s.c);
    out.scalar(format!("eq82_shift_c_{side}_lo95"), s.c_lo);
    out.scalar(format!("eq82_shift_c_{side}_hi95"), s.c_hi);
    out.scalar(format!("eq82_shift_xi_{side}"), s.xi);
    out.scalar(format!("eq82_shift_misfit_{side}"), s.misfit);
}

/// Largest mean and its velocity.
/// The velocity and value of the largest finite mean mu; None where no mean exists.
fn peak(vs: &[f64], mean: &[f64]) -> Option<(f64, f64)> {
    vs.iter().zip(mean).filter(|(_, m)| m.is_finite()).fold(
        None,
        |b: Option<(f64, f64)>, (&v, &m)| match b {
            Some((_, bm)) if bm >= m => b,
            _ => Some((v, m)),
        },
    )
}

/// Discretisation measures of one velocity.
#[derive(Debug, Clone, Copy)]
struct Accuracy {
    /// Largest |mu - mu_dissipation| / |mu| over the converged surfaces.
    routes: f64,
    /// |mean mu(grid) - mean mu(grid / 2)| / |mean mu(grid)| (NaN without the check).
    grid_change: f64,
    resolved: bool,
}

/// Fits of Eq. (82) to one side over the resolved velocities.
struct SideFit {
    /// Eq. (82) over xi at each velocity.
    r: Vec<f64>,
    xi: elastomer::XiFit,
}

impl SlidingFriction3d {
    fn accuracy(&self, s: &Solved) -> Vec<Accuracy> {
        (0..self.velocities)
            .map(|i| {
                let row = &s.runs[0][i];
                let routes = row
                    .iter()
                    .filter(|r| r.converged)
                    .map(|r| ((r.mu - r.mu_dissipation) / r.mu).abs())
                    .fold(f64::NAN, f64::max);
                let mean = stat(row.iter().map(|r| r.mu)).mean;
                let grid_change = if self.coarse_check {
                    let coarse = stat(s.runs[1][i].iter().map(|r| r.mu)).mean;
                    ((mean - coarse) / mean).abs()
                } else {
                    f64::NAN
                };
                let resolved = routes <= self.error_limit
                    && (!self.coarse_check || grid_change / 3.0 <= self.error_limit);
                Accuracy {
                    routes,
                    grid_change,
                    resolved,
                }
            })
            .collect()
    }

    /// Fits Eq. (82) (xi, and xi with c) to `mu[velocity][surface]` over the resolved
    /// velocities; records them as `<name>_<side>`. None with fewer than two.
    #[allow(clippy::too_many_arguments)]
    fn fit_side(
        &self,
        out: &mut Section,
        side: &str,
        mu: &[Vec<f64>],
        acc: &[Accuracy],
        k: f64,
        grad_z: f64,
        vs: &[f64],
    ) -> Result<Option<SideFit>> {
        if acc.iter().filter(|a| a.resolved).count() < 2 {
            return Ok(None);
        }
        let masked: Vec<Vec<f64>> = mu
            .iter()
            .zip(acc)
            .map(|(row, a)| {
                if a.resolved {
                    row.clone()
                } else {
                    vec![f64::NAN; row.len()]
                }
            })
            .collect();
        let r = self.material.eq82_over_xi(k, grad_z, vs)?;
        let xi = elastomer::fit_xi(&masked, &r, self.seed);
        let shift = elastomer::fit_shift(&masked, &self.material, k, grad_z, vs, self.seed)?;
        record_fits(out, side, &xi, &shift);
        Ok(Some(SideFit { r, xi }))
    }

    pub(super) fn report(
        &self,
        env: &Env,
        out: &mut Section,
        s: &Solved,
        mrd: Option<(&[mrd::sliding::Line], &[AtVelocity])>,
    ) -> Result<()> {
        let vs = self.velocity_grid();
        let acc = self.accuracy(s);
        let resolved: Vec<f64> = vs
            .iter()
            .zip(&acc)
            .filter(|(_, a)| a.resolved)
            .map(|(v, _)| *v)
            .collect();
        if resolved.len() < 2 {
            out.failures.push(format!(
                "only {} of {} velocities resolved (error_limit {}): Eq. (82) not fitted, xi missing; refine the grid",
                resolved.len(), vs.len(), self.error_limit
            ));
        }
        let mu3: Vec<Vec<f64>> = s.runs[0]
            .iter()
            .map(|row| row.iter().map(|r| r.mu).collect())
            .collect();
        let fit3 = self.fit_side(out, "3d", &mu3, &acc, s.k, s.grad_z, &vs)?;
        let m = mrd.map(|(lines, per_v)| MrdResults::of(lines, per_v, out));
        let fit_m = match &m {
            Some(m) => self.fit_side(out, "mrd", &m.mu, &acc, m.k, m.grad_z, &vs)?,
            None => None,
        };
        for (g, grid) in s.runs.iter().enumerate() {
            for (i, row) in grid.iter().enumerate() {
                for (surface, r) in row.iter().enumerate() {
                    if !r.converged {
                        out.failures.push(format!(
                            "3D at velocity {:e}, surface {surface}, grid {}: no convergence after {} outer iterations (residual {:e} > {:e})",
                            vs[i], s.grids[g], r.outer, r.residual, self.tolerance
                        ));
                    }
                }
            }
        }
        let t = self.table(env, s, &vs, &acc, fit3.as_ref(), m.as_ref(), fit_m.as_ref());
        let peak3 = peak(&vs, &t.column("mu_3d_mean"));
        if let Some((v3, p3)) = peak3 {
            out.scalar("mu_peak_3d", p3);
            out.scalar("velocity_at_peak_3d", v3);
        }
        out.scalar("wave_vector", s.k);
        out.scalar("grad_z", s.grad_z);
        out.scalar("mean_pressure", s.pressure);
        out.scalar("resolved_velocities", resolved.len() as f64);
        if let Some(v) = resolved.last() {
            out.scalar("velocity_resolved_max", *v);
        }
        if m.is_some() {
            let peak_m = peak(&vs, &t.column("mu_mrd_mean"));
            if let Some((vm, pm)) = peak_m {
                out.scalar("mu_peak_mrd", pm);
                out.scalar("velocity_at_peak_mrd", vm);
            }
            if let (Some((_, pm)), Some((_, p3))) = (peak_m, peak3) {
                out.scalar("peak_ratio_mrd_over_3d", pm / p3);
            }
        }
        let fig = self.friction_figure(
            env,
            &t,
            s,
            fit3.as_ref().map(|f| f.xi),
            m.as_ref(),
            fit_m.as_ref().map(|f| f.xi),
        )?;
        out.figures.push(fig);
        out.figures.push(self.contact_figure(env, &t, m.is_some()));
        out.tables.push(t);
        out.tables.push(self.runs_table(env, s, &vs));
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    fn table(
        &self,
        env: &Env,
        s: &Solved,
        vs: &[f64],
        acc: &[Accuracy],
        fit3: Option<&SideFit>,
        m: Option<&MrdResults>,
        fit_m: Option<&SideFit>,
    ) -> Table {
        let u = &env.ctx.units;
        let mut cols = vec![
            format!("velocity [{}/s]", u.length),
            "kv [rad/s]".to_string(),
            "mu_3d_mean [1]".into(),
            "mu_3d_ci95 [1]".into(),
            "mu_3d_dissipation_mean [1]".into(),
            "routes_rel_diff_max [1]".into(),
        ];
        if self.coarse_check {
            cols.push("mu_3d_coarse_mean [1]".into());
            cols.push("grid_rel_change [1]".into());
        }
        cols.push("resolved [0/1]".into());
        cols.push("contact_area_fraction_3d_mean [1]".into());
        if m.is_some() {
            cols.push("mu_mrd_mean [1]".into());
            cols.push("mu_mrd_ci95 [1]".into());
            cols.push("contact_length_fraction_mrd_mean [1]".into());
        }
        cols.push("eq82_over_xi_3d [1]".into());
        cols.push("eq82_fitted_3d [1]".into());
        if m.is_some() {
            cols.push("eq82_fitted_mrd [1]".into());
        }
        cols.push("outer_iterations_max [count]".into());
        cols.push("solves_converged [count]".into());
        let mut t = Table::new("sliding_friction_3d", &cols);
        t.missing_ok = true;
        t.notes.push(format!(
            "3D: {} periodic surfaces of {}^2 cells (grid / 2 = coarse check: {}), side L = {}, rms height h = {}, k = rms slope / rms height = {:e}, grad z = {:e}, mean pressure {:e} (reduced force p L/(4 G_inf h) = {}), E*(omega) = 4 G(omega); steady sliding solved to tolerance {:e} (bem3d::sliding); mu = -<p dh/dx>/p, mu_3d_dissipation from the dissipated power; resolved = 1 where routes_rel_diff_max and grid_rel_change / 3 are <= {}; Eq. (82) fitted to each side over the resolved velocities; empty cells: nothing converged or not fitted; material {:?}",
            self.realisations, self.grid, self.coarse_check, self.length, self.rms_height, s.k, s.grad_z, s.pressure, self.reduced_force, self.tolerance, self.error_limit, self.material
        ));
        if let Some(m) = &self.mrd {
            t.notes.push(format!(
                "MRD: lines with C1D = pi q C2D on {} springs (refine {}, stride {}), same h, material, force F = p L^2, velocities and seeds; steady state to {:e}",
                m.springs, m.refine, m.stride, m.tolerance
            ));
        }
        let r3 = self
            .material
            .eq82_over_xi(s.k, s.grad_z, vs)
            .unwrap_or_else(|_| vec![f64::NAN; vs.len()]);
        for (i, &v) in vs.iter().enumerate() {
            let row = &s.runs[0][i];
            let st = stat(row.iter().map(|r| r.mu));
            let mut values = vec![v, s.k * v, st.mean, st.ci95];
            values.push(stat(row.iter().map(|r| r.mu_dissipation)).mean);
            values.push(acc[i].routes);
            if self.coarse_check {
                values.push(stat(s.runs[1][i].iter().map(|r| r.mu)).mean);
                values.push(acc[i].grid_change);
            }
            values.push(acc[i].resolved as u8 as f64);
            values.push(stat(row.iter().map(|r| r.contact_fraction)).mean);
            if let Some(m) = m {
                let sm = stat(m.mu[i].iter().copied());
                values.extend([sm.mean, sm.ci95, m.contact[i]]);
            }
            values.push(r3[i]);
            values.push(fit3.map_or(f64::NAN, |f| f.xi.xi * f.r[i]));
            if m.is_some() {
                values.push(fit_m.map_or(f64::NAN, |f| f.xi.xi * f.r[i]));
            }
            let all = s.runs.iter().flat_map(|g| g[i].iter());
            values.push(all.clone().map(|r| r.outer).max().unwrap_or(0) as f64);
            values.push(all.filter(|r| r.converged).count() as f64);
            t.push(values);
        }
        t
    }

    fn runs_table(&self, env: &Env, s: &Solved, vs: &[f64]) -> Table {
        let u = &env.ctx.units;
        let mut t = Table::new(
            "sliding_friction_3d_runs",
            &[
                format!("velocity [{}/s]", u.length),
                "surface [count]".into(),
                "grid [cells]".into(),
                "mu [1]".into(),
                "mu_dissipation [1]".into(),
                "contact_area_fraction [1]".into(),
                format!("mean_gap [{}]", u.length),
                "outer_iterations [count]".into(),
                "inner_iterations [count]".into(),
                "residual [1]".into(),
                "converged [0/1]".into(),
            ],
        );
        t.missing_ok = true;
        t.notes.push("every 3D solve; converged = 0: max_iterations reached (results empty, residual reached given)".into());
        for (g, grid) in s.runs.iter().enumerate() {
            for (i, row) in grid.iter().enumerate() {
                for (surface, r) in row.iter().enumerate() {
                    t.push(vec![
                        vs[i],
                        surface as f64,
                        s.grids[g] as f64,
                        r.mu,
                        r.mu_dissipation,
                        r.contact_fraction,
                        r.mean_gap,
                        r.outer as f64,
                        r.inner as f64,
                        r.residual,
                        r.converged as u8 as f64,
                    ]);
                }
            }
        }
        t
    }

    fn friction_figure(
        &self,
        env: &Env,
        t: &Table,
        s: &Solved,
        fit3: Option<elastomer::XiFit>,
        m: Option<&MrdResults>,
        fit_m: Option<elastomer::XiFit>,
    ) -> Result<Figure> {
        let u = &env.ctx.units;
        let with_bars = |mean: &str, ci: &str| -> (Points, Bars) {
            let pts = t.xy("velocity", mean);
            let bars = pts
                .iter()
                .zip(t.column(ci))
                .filter(|((_, m), c)| m.is_finite() && c.is_finite())
                .map(|(&(v, m), c)| (v, m - c, m + c))
                .collect();
            (pts.into_iter().filter(|p| p.1.is_finite()).collect(), bars)
        };
        let fine_v = mrd::friction::log_space(self.velocity_min, self.velocity_max, 200);
        let curve = |k: f64, gz: f64, xi: f64| -> Result<Vec<(f64, f64)>> {
            Ok(self
                .material
                .eq82_over_xi(k, gz, &fine_v)?
                .into_iter()
                .zip(&fine_v)
                .map(|(e, &v)| (v, xi * e))
                .collect())
        };
        let (p3, b3) = with_bars("mu_3d_mean", "mu_3d_ci95");
        let resolved = t.column("resolved");
        let keep = |pts: &[(f64, f64)], want: bool| -> Vec<(f64, f64)> {
            pts.iter()
                .filter(|(v, _)| {
                    let i = t.column("velocity").iter().position(|x| x == v);
                    i.is_some_and(|i| (resolved[i] == 1.0) == want)
                })
                .copied()
                .collect()
        };
        let bars_of = |pts: &[(f64, f64)]| -> Vec<(f64, f64, f64)> {
            b3.iter()
                .filter(|b| pts.iter().any(|p| p.0 == b.0))
                .copied()
                .collect()
        };
        let (good, poor) = (keep(&p3, true), keep(&p3, false));
        let mut fig = Figure::new(
            "sliding_friction_3d",
            "Elastomer friction mu(v): 3D boundary elements, MRD and Eq. (82) (cf. Fig. 7)",
            &format!("sliding velocity v [{}/s]", u.length),
            "friction coefficient mu [1]",
        );
        // Series 0 sets the 3D colour; empty series stay out of the legend.
        for (pts, label, style) in [
            (
                good,
                format!(
                    "3D, {}^2 cells, mean of {} surfaces (95% CI)",
                    self.grid, self.realisations
                ),
                Style::Markers,
            ),
            (
                poor,
                format!(
                    "3D, discretisation error > {:.0}% (not fitted)",
                    100.0 * self.error_limit
                ),
                Style::Crosses,
            ),
        ] {
            if !pts.is_empty() {
                let bars = bars_of(&pts);
                fig = fig.with(Series::new(label, pts, style).with_bars(bars).colored(0));
            }
        }
        if let Some(f) = fit3 {
            fig = fig.with(
                Series::new(
                    format!(
                        "Eq. (82) fitted to 3D, xi = {:.3} [{:.3}, {:.3}]",
                        f.xi, f.lo, f.hi
                    ),
                    curve(s.k, s.grad_z, f.xi)?,
                    Style::Line,
                )
                .colored(0),
            );
        }
        if let Some(m) = m {
            let (pm, bm) = with_bars("mu_mrd_mean", "mu_mrd_ci95");
            // MRD in palette colour 1 here and in the contact figure.
            fig = fig.with(
                Series::new(
                    format!("MRD, mean of {} lines (95% CI)", self.realisations),
                    pm,
                    Style::Markers,
                )
                .with_bars(bm)
                .colored(1),
            );
            if let Some(f) = fit_m {
                fig = fig.with(
                    Series::new(
                        format!(
                            "Eq. (82) fitted to MRD, xi = {:.3} [{:.3}, {:.3}]",
                            f.xi, f.lo, f.hi
                        ),
                        curve(m.k, m.grad_z, f.xi)?,
                        Style::Dashed,
                    )
                    .colored(1),
                );
            }
        }
        fig.log_x = true;
        Ok(fig)
    }

    fn contact_figure(&self, env: &Env, t: &Table, with_mrd: bool) -> Figure {
        let u = &env.ctx.units;
        let finite = |c: &str| -> Vec<(f64, f64)> {
            t.xy("velocity", c)
                .into_iter()
                .filter(|p| p.1.is_finite() && p.1 > 0.0)
                .collect()
        };
        let mut fig = Figure::new(
            "sliding_friction_3d_contact",
            "Real contact while sliding: 3D area fraction and MRD length fraction",
            &format!("sliding velocity v [{}/s]", u.length),
            "contact fraction [1]",
        )
        .plot(
            "3D, contact area / L^2",
            finite("contact_area_fraction_3d_mean"),
            Style::Markers,
        );
        if with_mrd {
            fig = fig.with(
                Series::new(
                    "MRD, contact length / L",
                    finite("contact_length_fraction_mrd_mean"),
                    Style::Crosses,
                )
                .colored(1),
            );
        }
        fig.log_log()
    }
}

#[cfg(test)]
mod tests {
    use super::peak;

    #[test]
    fn a_peak_needs_a_finite_mean() {
        // Without any 3D mean there is no peak (and no ratio of peaks, where the old
        // fold gave -inf and a ratio of -0.0).
        assert_eq!(peak(&[1.0, 2.0], &[f64::NAN, f64::NAN]), None);
        assert_eq!(peak(&[], &[]), None);
        // The first of equal maxima, NaN skipped.
        assert_eq!(
            peak(&[1.0, 2.0, 3.0, 4.0], &[0.1, f64::NAN, 0.3, 0.3]),
            Some((3.0, 0.3))
        );
    }
}
