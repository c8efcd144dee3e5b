//! `tangential_viscoelastic`: Cattaneo-Mindlin on a viscoelastic foundation (Section 8,
//! Eqs. 64-65): the profile pressed to `normal_force` and held long enough for the normal
//! contact to have relaxed (normal springs E* dx, E* the material's), then moved
//! tangentially: a ramp to `amplitude` times the elastic full-slip displacement of the
//! relaxed tangential modulus over `ramp_time`, a hold of `hold_time`, and one cycle
//! (to minus that displacement and back, each over twice `ramp_time`). Tangential
//! springs G*(t) dx = (G*_inf + sum_k G_k exp(-t / tau_k)) dx that stick or slip with
//! Coulomb friction mu (`mrd::viscoelastic::TangentialRow`). Reported per step: the
//! tangential force, the stick zone (fraction of loaded springs and its radius), and the
//! energy: external work Int F dux = stored + viscous + friction dissipation, and the same
//! loop with the relaxed modulus held constant (the elastic Cattaneo-Mindlin /
//! Mindlin-Deresiewicz loop) beside it.
//!
//! With `cells_3d` the same history runs in 3D beside it: the body pressed on the free
//! half-space (E*, a grid of `side_3d` contact radii) and moved tangentially on a
//! viscoelastic half-space of the same G*(t) (`bem3d::tangential::ViscoelasticSlip`:
//! Cerruti's operator, Coulomb's law, the hereditary integral cell by cell; Poisson's
//! ratio from G*_inf / E*, held in time), in a table of its own with MRD's force and
//! stick radius beside the 3D ones.

use crate::checks::{bad, check_springs, default_springs, positive, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::{equivalent_body, AxisymGrid};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::tangential::{CerrutiFree, ViscoelasticSlip};
use bem3d::viscoelastic::Relaxation;
use bem3d::SolverOptions;
use mrd::tangential::TangentialContact;
use mrd::viscoelastic::{Prony, TangentialRow, TangentialRowState};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialViscoelastic {
    /// Coulomb friction coefficient.
    mu: f64,
    /// Normal force F_N [force].
    normal_force: f64,
    /// Relaxed tangential modulus G*_inf.
    g_inf: f64,
    /// [G_k, tau_k] of G*(t) = G*_inf + sum G_k exp(-t / tau_k).
    prony: Vec<[f64; 2]>,
    /// Tangential amplitude as a fraction of the full-slip displacement at G*_inf.
    amplitude: f64,
    /// Duration of the tangential ramp [time].
    ramp_time: f64,
    /// Duration of the hold after the ramp [time].
    hold_time: f64,
    /// Steps per ramp_time.
    #[serde(default = "crate::checks::default_count::<100>")]
    steps: usize,
    /// MRD springs on the half-line.
    #[serde(default = "default_springs")]
    springs: usize,
    /// Cells per side of the 3D side on the free half-space (absent: MRD only).
    #[serde(default)]
    cells_3d: Option<usize>,
    /// The side of the 3D grid in contact radii (> 2: the contact fits; default 2.5).
    #[serde(default)]
    side_3d: Option<f64>,
    /// The 3D solves' tolerance (relative: the partial-slip law and the shift; default
    /// the solvers').
    #[serde(default)]
    tolerance: Option<f64>,
}

impl TangentialViscoelastic {
    fn side_3d(&self) -> f64 {
        self.side_3d.unwrap_or(2.5)
    }

    fn tolerance(&self) -> f64 {
        self.tolerance
            .unwrap_or_else(crate::checks::default_tolerance)
    }

    fn modulus(&self) -> mrd::Result<Prony> {
        Prony::new(
            self.g_inf,
            self.prony.iter().map(|t| (t[0], t[1])).collect(),
        )
    }

    /// Tangential displacement (in units of the amplitude) at the end of each step.
    fn history(&self) -> Vec<f64> {
        let n = self.steps;
        let hold = (self.hold_time / self.ramp_time * n as f64).round() as usize;
        let mut u: Vec<f64> = (1..=n).map(|k| k as f64 / n as f64).collect();
        u.extend(std::iter::repeat_n(1.0, hold));
        u.extend((1..=2 * n).map(|k| 1.0 - 2.0 * k as f64 / (2 * n) as f64));
        u.extend((1..=2 * n).map(|k| -1.0 + 2.0 * k as f64 / (2 * n) as f64));
        u
    }
}

/// Per step: state and stored energy and viscous power after it.
type Track = Vec<(TangentialRowState, f64, f64)>;

fn drive(row: &mut TangentialRow, dt: f64, path: &[f64], scale: f64) -> mrd::Result<Track> {
    path.iter()
        .map(|&u| {
            let s = row.step(dt, u * scale)?;
            Ok((s, row.stored_energy(), row.viscous_power()))
        })
        .collect()
}

impl Output for TangentialViscoelastic {
    fn validate(&self, ctx: &Context) -> Result<()> {
        ctx.profile()?;
        require_positive("friction coefficient mu", self.mu)?;
        require_positive("normal_force", self.normal_force)?;
        require_positive("g_inf", self.g_inf)?;
        // Below 1e-6 the slip annulus is a millionth of the contact radius: the response
        // is the stick one, linear in the amplitude, and the 3D shift search works at
        // forces within the rounding of the normal contact's.
        if !(self.amplitude >= 1e-6 && self.amplitude < 1.0) {
            return bad(format!(
                "amplitude = {} must lie in [1e-6, 1) (a fraction of the full-slip displacement; below, the contact sticks and the response is linear in it)",
                self.amplitude
            ));
        }
        if !(positive(self.ramp_time) && self.hold_time.is_finite() && self.hold_time >= 0.0) {
            return bad("ramp_time must be > 0 and hold_time >= 0");
        }
        if !(2..=100_000).contains(&self.steps) {
            return bad(format!("steps = {} must lie in 2..=100000", self.steps));
        }
        self.modulus().ctx("prony")?;
        let dt = self.ramp_time / self.steps as f64;
        if let Some(tau) = self.prony.iter().map(|t| t[1]).reduce(f64::min) {
            if dt > tau {
                return bad(format!(
                    "the time step ramp_time / steps = {dt:.3e} exceeds the shortest relaxation time {tau:.3e}"
                ));
            }
        }
        // Counted before the history is built, so that no huge hold allocates.
        if (self.hold_time / self.ramp_time + 5.0) * self.steps as f64 > 1e6 {
            return bad("the history has more than 1e6 steps (hold_time / (ramp_time / steps))");
        }
        if self.cells_3d.is_none() && (self.side_3d.is_some() || self.tolerance.is_some()) {
            return bad("side_3d and tolerance set the 3D side: give cells_3d too");
        }
        if let Some(n) = self.cells_3d {
            if !(16..=2048).contains(&n) {
                return bad(format!("cells_3d = {n} must lie in 16..=2048"));
            }
            let side = self.side_3d();
            if !(side.is_finite() && (2.2..=100.0).contains(&side)) {
                return bad(format!(
                    "side_3d = {side} contact radii must lie in [2.2, 100]"
                ));
            }
            let per_radius = n as f64 / side;
            let least = crate::checks::MIN_CELLS_PER_CONTACT_RADIUS;
            if per_radius < least {
                return bad(format!(
                    "cells_3d / side_3d = {n} / {side} = {per_radius:.3} cells per contact radius: the 3D side needs at least {least} (raise cells_3d or lower side_3d)"
                ));
            }
            let (nu, _) = equivalent_body(ctx.material.e_star, self.g_inf);
            if !(0.0..=0.5).contains(&nu) {
                return bad(format!(
                    "g_inf / E* = {} gives Poisson's ratio {nu:.3} outside [0, 0.5] for the 3D side: it must lie in [2/3, 1]",
                    self.g_inf / ctx.material.e_star
                ));
            }
            crate::checks::check_memory(
                (n * n) as f64 * crate::checks::cell_bytes::TANGENTIAL_VISCOELASTIC,
                &format!("cells_3d = {n}"),
            )?;
            crate::checks::check_tolerance(self.tolerance())?;
        }
        check_springs(
            self.springs,
            crate::checks::spring_bytes::tangential_viscoelastic(self.prony.len()),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = hess::stages(Stage::Viscoelastic, false);
        if self.cells_3d.is_some() {
            s.extend([Stage::Bem3d, Stage::Tangential3d]);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let profile = env.ctx.profile()?;
        let e = env.ctx.material.e_star;
        let cm = out
            .stage(Stage::NormalSemiAnalytic, || {
                TangentialContact::new(contact, self.g_inf, self.mu, self.normal_force)
            })
            .ctx("normal contact")?;
        let (d, a) = (cm.normal.depth, cm.normal.radius);
        let (_, dx, gaps) =
            mrd::foundation::half_line(profile, self.springs, 1.2 * a).ctx("springs")?;
        let normal: Vec<f64> = gaps.iter().map(|g| e * dx * (d - g).max(0.0)).collect();
        let scale = self.amplitude * cm.max_displacement();
        let dt = self.ramp_time / self.steps as f64;
        let path = self.history();
        let modulus = self.modulus().ctx("prony")?;
        let relaxed = Prony::new(self.g_inf, vec![]).ctx("prony")?;
        let (ve, el) = out
            .stage(Stage::Viscoelastic, || -> mrd::Result<_> {
                let mut row = TangentialRow::new(&normal, dx, self.mu, &modulus)?;
                let mut row_el = TangentialRow::new(&normal, dx, self.mu, &relaxed)?;
                Ok((
                    drive(&mut row, dt, &path, scale)?,
                    drive(&mut row_el, dt, &path, scale)?,
                ))
            })
            .ctx("tangential springs")?;
        let units = &env.ctx.units;
        let setup = Setup {
            scale,
            dt,
            dx,
            loaded: normal.iter().filter(|&&f| f > 0.0).count().max(1),
            len: units.length.clone(),
            force: units.force(),
        };
        report(self, &setup, &path, &ve, &el, out);
        if let Some(cells) = self.cells_3d {
            let three = self.run_3d(env, out, cells, a, scale, &path)?;
            report_3d(self, &setup, a, &path, &ve, &three, out);
        }
        Ok(())
    }
}

/// Per step of the 3D side: the force, the stick radius and the energy dissipated.
type Track3d = Vec<(f64, f64, f64)>;

impl TangentialViscoelastic {
    /// The 3D side: the body pressed on the free half-space, then the history.
    fn run_3d(
        &self,
        env: &Env,
        out: &mut Section,
        cells: usize,
        a: f64,
        scale: f64,
        path: &[f64],
    ) -> Result<Track3d> {
        let e = env.ctx.material.e_star;
        let grid = AxisymGrid {
            cells,
            side: self.side_3d() * a,
            periodic: false,
        };
        let opts = SolverOptions::new(self.tolerance(), 10_000);
        let profile = env.ctx.profile()?;
        let sol = out
            .stage(Stage::Bem3d, || {
                grid.press(profile, e, self.normal_force, &opts)
            })
            .ctx("3D normal contact")?;
        out.scalar("cells_per_contact_radius_3d", cells as f64 / self.side_3d());
        // The grid's side (side_3d times MRD's contact radius), so that the 3D side can be
        // rebuilt elsewhere (the Python test does, bit for bit).
        out.scalar("grid_side_3d", grid.side);
        // G = G* (2 - nu) / 4 for every term (nu held in time).
        let (nu, _) = equivalent_body(e, self.g_inf);
        let c = (2.0 - nu) / 4.0;
        let dt = self.ramp_time / self.steps as f64;
        let l = grid.side;
        let cell = (l / cells as f64).powi(2);
        out.stage(Stage::Tangential3d, || -> bem3d::Result<Track3d> {
            let modulus = Relaxation::new(
                c * self.g_inf,
                self.prony.iter().map(|t| (c * t[0], t[1])).collect(),
            )?;
            let op = CerrutiFree::new(cells, cells, l, l, 1.0, nu)?;
            let mut slip = ViscoelasticSlip::new(op, &sol.pressure, self.mu, modulus)?;
            path.iter()
                .map(|u| {
                    let s = slip.step(dt, u * scale, self.tolerance())?;
                    let radius = (s.stick_cells as f64 * cell / std::f64::consts::PI).sqrt();
                    Ok((s.force, radius, s.dissipated))
                })
                .collect()
        })
        .ctx("3D viscoelastic partial slip")
    }
}

/// The 3D table beside MRD's force and stick radius, its figure and agreement scalars.
fn report_3d(
    spec: &TangentialViscoelastic,
    setup: &Setup,
    a: f64,
    path: &[f64],
    ve: &Track,
    three: &Track3d,
    out: &mut Section,
) {
    let (len, force) = (&setup.len, &setup.force);
    let mut t = Table::new(
        "tangential_viscoelastic_3d",
        &[
            "time [s]".to_string(),
            format!("ux [{len}]"),
            format!("fx_mrd [{force}]"),
            format!("fx_3d [{force}]"),
            format!("stick_radius_mrd [{len}]"),
            format!("stick_radius_3d [{len}]"),
            format!("friction_dissipation_3d [{force} {len}]"),
        ],
    );
    t.notes.push(format!("3D: the body pressed on the free half-space ({0}^2 cells over {1} contact radii, {2:.1} cells per radius), moved along the same history on a viscoelastic half-space of the same G*(t) (Cerruti's operator with Poisson's ratio from G*_inf / E*, Coulomb mu = {3}, tolerance {4:e}); MRD: the springs of the table tangential_viscoelastic; stick radius 3D from the count of stick cells, sqrt(cells x cell area / pi); friction dissipation summed over steps from t = 0", spec.cells_3d.unwrap_or(0), spec.side_3d(), spec.cells_3d.unwrap_or(0) as f64 / spec.side_3d(), spec.mu, spec.tolerance()));
    let (mut peak, mut dev, mut dev_c, mut fric) = (0.0f64, 0.0f64, 0.0f64, 0.0);
    let cycle_start = path.len() - 4 * spec.steps;
    let (mut w3, mut wm, mut f3_old, mut fm_old, mut u_old) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut force_mrd, mut force_3d, mut diff) = (Vec::new(), Vec::new(), Vec::new());
    for (k, ((s, _, _), (f3, c3, d3))) in ve.iter().zip(three).enumerate() {
        let time = setup.dt * (k + 1) as f64;
        let (fm, ux) = (2.0 * s.force, s.displacement);
        let cm = s.stick_edge.map_or(0.0, |i| (i as f64 + 0.5) * setup.dx);
        fric += d3;
        peak = peak.max(fm.abs());
        dev = dev.max((f3 - fm).abs());
        dev_c = dev_c.max((c3 - cm).abs() / a);
        if k >= cycle_start {
            w3 += 0.5 * (f3 + f3_old) * (ux - u_old);
            wm += 0.5 * (fm + fm_old) * (ux - u_old);
        }
        (f3_old, fm_old, u_old) = (*f3, fm, ux);
        force_mrd.push((time, fm));
        // Every fourth 3D step marked, so that MRD's line shows between the marks.
        if k % 4 == 3 {
            force_3d.push((time, *f3));
        }
        diff.push((time, f3 - fm));
        t.push(vec![time, ux, fm, *f3, cm, *c3, fric]);
    }
    let peak = peak.max(f64::MIN_POSITIVE);
    out.scalar("force_max_abs_dev_3d_vs_mrd_over_peak", dev / peak);
    let diff = diff.into_iter().map(|(t, d)| (t, d / peak)).collect();
    out.scalar("stick_radius_max_abs_dev_3d_vs_mrd_over_a", dev_c);
    out.scalar("cycle_dissipation_3d", w3);
    out.scalar("cycle_dissipation_3d_over_mrd", w3 / wm);
    out.tables.push(t);
    out.figures.push(
        Figure::new(
            "tangential_viscoelastic_3d_force",
            "Tangential force in time (ramp, hold, cycle): 3D viscoelastic half-space and MRD",
            "time t [s]",
            &format!("tangential force Fx [{force}]"),
        )
        .with(Series::new("MRD (Eqs. 64-65)", force_mrd, Style::Line).colored(0))
        .with(
            Series::new(
                "3D boundary elements (every 4th step)",
                force_3d,
                Style::Crosses,
            )
            .colored(2),
        ),
    );
    out.figures.push(
        Figure::new(
            "tangential_viscoelastic_3d_difference",
            "3D force minus MRD's, over MRD's peak force",
            "time t [s]",
            "(Fx 3D - Fx MRD) / max |Fx MRD| [1]",
        )
        .with(Series::new("3D minus MRD", diff, Style::Line).colored(2)),
    );
}

/// What the report needs besides the tracks.
struct Setup {
    /// The amplitude of ux.
    scale: f64,
    dt: f64,
    dx: f64,
    /// Springs under normal load.
    loaded: usize,
    len: String,
    force: String,
}

fn report(
    spec: &TangentialViscoelastic,
    setup: &Setup,
    path: &[f64],
    ve: &Track,
    el: &Track,
    out: &mut Section,
) {
    let Setup { scale, dt, dx, .. } = *setup;
    let (len, force) = (&setup.len, &setup.force);
    let mut t = Table::new(
        "tangential_viscoelastic",
        &[
            "time [s]".to_string(),
            format!("ux [{len}]"),
            format!("fx [{force}]"),
            format!("fx_relaxed_elastic [{force}]"),
            "stick_fraction [1]".to_string(),
            format!("stick_radius [{len}]"),
            format!("work [{force} {len}]"),
            format!("stored [{force} {len}]"),
            format!("viscous_dissipation [{force} {len}]"),
            format!("friction_dissipation [{force} {len}]"),
        ],
    );
    t.notes.push(format!("Eqs. 64-65: tangential springs G*(t) dx with G*_inf = {} and Prony {:?}, Coulomb mu = {}, under the relaxed normal contact at {} (both halves of the spring line counted); ramp to {:.4e} (amplitude {} of the full-slip displacement at G*_inf) in {}, hold {}, one cycle; the column fx_relaxed_elastic is the same with G* = G*_inf held constant (elastic Cattaneo-Mindlin); energies from t = 0: work by trapezoids of F dux, viscous dissipation by trapezoids of its power, friction sum of f (du - dw) per step", spec.g_inf, spec.prony, spec.mu, spec.normal_force, scale, spec.amplitude, spec.ramp_time, spec.hold_time));
    let (mut work, mut visc, mut fric) = (0.0, 0.0, 0.0);
    let (mut f_old, mut p_old, mut u_old) = (0.0, 0.0, 0.0);
    let mut loop_ve = Vec::new();
    let mut loop_el = Vec::new();
    let mut stick = Vec::new();
    let mut residual: f64 = 0.0;
    let cycle_start = path.len() - 4 * spec.steps;
    let (mut w_cycle, mut w_cycle_el, mut f_old_el) = (0.0, 0.0, 0.0);
    for (k, ((s, stored, power), (se, _, _))) in ve.iter().zip(el).enumerate() {
        let time = dt * (k + 1) as f64;
        let (fx, fe) = (2.0 * s.force, 2.0 * se.force);
        let ux = s.displacement;
        work += 0.5 * (fx + f_old) * (ux - u_old);
        visc += 0.5 * dt * (2.0 * power + p_old);
        fric += 2.0 * s.slip_work;
        if k >= cycle_start {
            w_cycle += 0.5 * (fx + f_old) * (ux - u_old);
            w_cycle_el += 0.5 * (fe + f_old_el) * (ux - u_old);
        }
        let radius = s.stick_edge.map_or(0.0, |i| (i as f64 + 0.5) * dx);
        residual = residual.max((work - 2.0 * stored - visc - fric).abs());
        t.push(vec![
            time,
            ux,
            fx,
            fe,
            s.sticking as f64 / setup.loaded as f64,
            radius,
            work,
            2.0 * stored,
            visc,
            fric,
        ]);
        if k >= cycle_start {
            loop_ve.push((ux, fx));
            loop_el.push((ux, fe));
        }
        stick.push((time, radius));
        f_old = fx;
        f_old_el = fe;
        p_old = 2.0 * power;
        u_old = ux;
    }
    out.scalar("cycle_dissipation", w_cycle);
    out.scalar("cycle_dissipation_relaxed_elastic", w_cycle_el);
    out.scalar(
        "energy_balance_max_residual_over_work",
        residual / work.abs().max(f64::MIN_POSITIVE),
    );
    out.tables.push(t);
    out.figures.push(
        Figure::new(
            "tangential_viscoelastic_loop",
            "Tangential force over one cycle: viscoelastic springs and the relaxed elastic loop",
            &format!("tangential displacement ux [{len}]"),
            &format!("tangential force Fx [{force}]"),
        )
        .with(Series::new("viscoelastic (Eqs. 64-65)", loop_ve, Style::Line).colored(0))
        .with(
            Series::new(
                "elastic at G*_inf (Cattaneo-Mindlin)",
                loop_el,
                Style::Dashed,
            )
            .colored(1),
        ),
    );
    out.figures.push(
        Figure::new(
            "tangential_viscoelastic_stick",
            "Stick zone radius in time: ramp, hold, cycle",
            "time t [s]",
            &format!("stick radius c [{len}]"),
        )
        .with(Series::new("viscoelastic", stick, Style::Line).colored(0)),
    );
}
