//! `tangential_3d`'s report: the stick radius and shift against Cattaneo-Mindlin, the
//! dissipation per cycle against Mindlin-Deresiewicz, the hysteresis loops.

use super::*;

impl Tangential3d {
    /// The tables, figures and agreement scalars of both comparisons (the closed-form
    /// columns for the sphere only).
    pub(super) fn report(
        &self,
        env: &Env,
        out: &mut Section,
        a: f64,
        (c_mrd, c_cf, c_3d): (&[f64], Option<&[f64]>, &[f64]),
        (w_mrd, w_cf, w_3d): Dissipations,
    ) {
        let units = &env.ctx.units;
        let energy = format!("{} {}", units.force(), units.length);
        let x = "tangential_force_over_mu_fn";
        let mut cols = vec![format!("{x} [1]")];
        if c_cf.is_some() {
            cols.push("stick_radius_over_a_closed_form [1]".to_string());
        }
        cols.push("stick_radius_over_a_mrd [1]".to_string());
        cols.push("stick_radius_over_a_3d [1]".to_string());
        let mut t = Table::new("stick", &cols);
        t.notes.push(format!(
            "{}MRD: exact tangential springs; 3D: {1}^2 {4} {2} contact radii, {3:.1} cells per radius (stick radius from the count of stick cells)",
            if c_cf.is_some() { "Cattaneo-Mindlin c/a = (1 - F_x/(mu F_N))^(1/3); " } else { "" },
            self.cells, self.period, a * self.cells as f64 / (self.period * a),
            if self.periodic { "periodic cells, period" } else { "cells on the free half-space, side" }
        ));
        let (mut dev_mrd, mut dev_3d, mut dev_3d_mrd) = (0.0f64, 0.0f64, 0.0f64);
        for (k, f) in self.fractions.iter().enumerate() {
            dev_3d_mrd = dev_3d_mrd.max((c_3d[k] - c_mrd[k]).abs() / c_mrd[k]);
            let mut row = vec![*f];
            if let Some(cf) = c_cf {
                dev_mrd = dev_mrd.max((c_mrd[k] - cf[k]).abs() / cf[k]);
                dev_3d = dev_3d.max((c_3d[k] - cf[k]).abs() / cf[k]);
                row.push(cf[k]);
            }
            row.extend([c_mrd[k], c_3d[k]]);
            t.push(row);
        }
        if c_cf.is_some() {
            out.scalar("stick_radius_max_rel_error_mrd", dev_mrd);
            out.scalar("stick_radius_max_rel_error_3d", dev_3d);
        }
        out.scalar("stick_radius_max_rel_dev_3d_vs_mrd", dev_3d_mrd);
        let fig = Figure::new(
            "stick",
            "Stick radius against tangential force: 3D, MRD and Cattaneo-Mindlin",
            "tangential force F_x / (mu F_N) [1]",
            "stick radius c / contact radius a [1]",
        );
        let closed = c_cf.is_some().then_some("Cattaneo-Mindlin (closed form)");
        let without = "Stick radius against tangential force: 3D and MRD (Jaeger)";
        let fig = self.three_ways(fig, &t, (x, "stick_radius_over_a"), closed, without);
        // The agreement is below a marker's size on the figure above: the differences on
        // an axis of their own, against the closed form where there is one, else MRD, and
        // the size of one cell (the 3D stick radius is counted in cells).
        let (reference, name) = match c_cf {
            Some(cf) => (cf, "Cattaneo-Mindlin"),
            None => (c_mrd, "MRD"),
        };
        let diff = |c: &[f64]| -> Vec<(f64, f64)> {
            self.fractions
                .iter()
                .zip(c.iter().zip(reference))
                .map(|(f, (c, r))| (*f, c - r))
                .collect()
        };
        let cell = self.period / self.cells as f64;
        let ends = (
            self.fractions.first().copied(),
            self.fractions.last().copied(),
        );
        let mut residual = Figure::new(
            "stick_residual",
            &format!("Stick radius minus {name}'s, over the contact radius"),
            "tangential force F_x / (mu F_N) [1]",
            &format!("(c - c_{name}) / a [1]"),
        )
        .plot("3D boundary elements", diff(c_3d), Style::Markers);
        if c_cf.is_some() {
            residual = residual.plot("MRD (exact springs)", diff(c_mrd), Style::Crosses);
        }
        if let (Some(f0), Some(f1)) = ends {
            let index = residual.series.len();
            residual = residual
                .plot(
                    format!("+/- one cell ({cell:.3} a)"),
                    vec![(f0, cell), (f1, cell)],
                    Style::Dashed,
                )
                .with(
                    Series::new("", vec![(f0, -cell), (f1, -cell)], Style::Dashed).colored(index),
                );
        }
        out.tables.push(t);
        out.figures.push(fig);
        out.figures.push(residual);
        self.report_dissipation(out, &energy, (w_mrd, w_cf, w_3d));
    }

    /// The dissipation table, figure and scalars.
    fn report_dissipation(
        &self,
        out: &mut Section,
        energy: &str,
        (w_mrd, w_cf, w_3d): Dissipations,
    ) {
        let mut cols = vec!["force_amplitude_over_mu_fn [1]".to_string()];
        if w_cf.is_some() {
            cols.push(format!("dissipation_closed_form [{energy}]"));
        }
        cols.push(format!("dissipation_mrd [{energy}]"));
        cols.push(format!("dissipation_3d [{energy}]"));
        cols.push(format!("loop_area_3d [{energy}]"));
        let mut t = Table::new("dissipation", &cols);
        t.notes.push(format!(
            "energy per cycle of an oscillating tangential force; {}MRD: its springs at the displacement amplitude of the force amplitude; 3D: the second of two cycles, {} force steps per half cycle, the dissipation summed over the steps and the loop's area (work of the force over the shift)",
            if w_cf.is_some() { "closed form: Mindlin-Deresiewicz; " } else { "" },
            self.steps
        ));
        let (mut wd_mrd, mut wd_3d, mut wd_3d_mrd, mut balance) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for (k, x) in self.amplitudes.iter().enumerate() {
            wd_3d_mrd = wd_3d_mrd.max((w_3d[k].0 - w_mrd[k]).abs() / w_mrd[k]);
            balance = balance.max((w_3d[k].1 - w_3d[k].0).abs() / w_3d[k].0);
            let mut row = vec![*x];
            if let Some(cf) = w_cf {
                wd_mrd = wd_mrd.max((w_mrd[k] - cf[k]).abs() / cf[k]);
                wd_3d = wd_3d.max((w_3d[k].0 - cf[k]).abs() / cf[k]);
                row.push(cf[k]);
            }
            row.extend([w_mrd[k], w_3d[k].0, w_3d[k].1]);
            t.push(row);
        }
        if w_cf.is_some() {
            out.scalar("dissipation_max_rel_error_mrd", wd_mrd);
            out.scalar("dissipation_max_rel_error_3d", wd_3d);
        }
        out.scalar("dissipation_max_rel_dev_3d_vs_mrd", wd_3d_mrd);
        out.scalar("energy_balance_max_rel_3d", balance);
        let x = "force_amplitude_over_mu_fn";
        let fig = Figure::new(
            "dissipation",
            "Energy dissipated per cycle: 3D, MRD and Mindlin-Deresiewicz",
            "force amplitude F* / (mu F_N) [1]",
            &format!("dissipation per cycle W [{energy}]"),
        );
        let closed = w_cf
            .is_some()
            .then_some("Mindlin-Deresiewicz (closed form)");
        let without = "Energy dissipated per cycle: 3D and MRD";
        let fig = self
            .three_ways(fig, &t, (x, "dissipation"), closed, without)
            .log_log();
        out.tables.push(t);
        out.figures.push(fig);
    }

    /// The hysteresis loops (force against shift) of the measured cycles: 3D, MRD's
    /// springs by Masing's rule on their exact loading curve (unloading from F*:
    /// `u(F*) - 2 u((F* - F) / 2)`, reloading `-u(F*) + 2 u((F* + F) / 2)`), and for a
    /// sphere Mindlin-Deresiewicz (the same rule on Mindlin's
    /// `u(F) = 3 mu F_N / (4 G* a) [1 - (1 - F / (mu F_N))^(2/3)]`). `sphere`:
    /// (mu F_N, G*, a) of the closed form.
    pub(super) fn report_loops(
        &self,
        env: &Env,
        out: &mut Section,
        tc: &TangentialContact,
        sphere: Option<(f64, f64, f64)>,
        loops: &[Vec<(f64, f64)>],
    ) -> mrd::Result<()> {
        let length = env.ctx.units.length.clone();
        let mu_fn = self.mu * self.normal_force;
        let mindlin = |f: f64| {
            sphere
                .map(|(mp, g, a)| 3.0 * mp / (4.0 * g * a) * (1.0 - (1.0 - f / mp).powf(2.0 / 3.0)))
        };
        // Masing's branches from a loading curve `u`: the cycle's k-th point of 2 steps,
        // at the force the 3D step reached (the prescribed one to rounding: the curve's
        // argument is held in [0, amp]).
        let masing =
            |u: &dyn Fn(f64) -> mrd::Result<f64>, amp: f64, k: usize, f: f64| -> mrd::Result<f64> {
                let on = |x: f64| u(x.clamp(0.0, amp));
                if k <= self.steps {
                    Ok(on(amp)? - 2.0 * on(0.5 * (amp - f))?)
                } else {
                    Ok(-on(amp)? + 2.0 * on(0.5 * (amp + f))?)
                }
            };
        let mut cols = vec![
            "force_amplitude_over_mu_fn [1]".to_string(),
            "reloading [0/1]".to_string(),
            "tangential_force_over_mu_fn [1]".to_string(),
        ];
        if sphere.is_some() {
            cols.push(format!("shift_closed_form [{length}]"));
        }
        cols.push(format!("shift_mrd [{length}]"));
        cols.push(format!("shift_3d [{length}]"));
        let mut t = Table::new("loops", &cols);
        t.notes.push(format!(
            "the measured (second) cycle of each force amplitude, {} force steps per half cycle, from the amplitude down (reloading = 0) and back up (1); shift of the body, absolute (free half-space); {}MRD: Masing's rule on its springs' exact loading curve",
            self.steps,
            if sphere.is_some() { "closed form: Mindlin-Deresiewicz; " } else { "" },
        ));
        let mrd_u = |f: f64| tc.at_force(f).map(|s| s.displacement);
        let cf_u = |f: f64| -> mrd::Result<f64> { Ok(mindlin(f).unwrap_or(f64::NAN)) };
        let (mut dev_cf, mut dev_mrd) = (0.0f64, 0.0f64);
        // The loops are drawn with the elastic part of the shift removed (F_x times MRD's
        // initial compliance): on u_x itself they are slivers along one line, and an
        // affine shear of the axis leaves each loop's area, the energy lost, unchanged.
        let eps = 1e-6 * mu_fn;
        let compliance = mrd_u(eps)? / eps;
        let mut fig = Figure::new(
            "loops",
            "Hysteresis loops: 3D, MRD and Mindlin-Deresiewicz",
            &format!(
                "shift minus its elastic part, u_x - F_x / k_t0 [{length}] (k_t0 = {:.4e} [{}]: MRD's initial stiffness)",
                1.0 / compliance,
                env.ctx.units.stiffness()
            ),
            "tangential force F_x / (mu F_N) [1]",
        );
        if sphere.is_none() {
            fig.title = "Hysteresis loops: 3D and MRD".into();
        }
        let mut drawn = Vec::new();
        for (i, (x, points)) in self.amplitudes.iter().zip(loops).enumerate() {
            let amp = x * mu_fn;
            let (mut p3, mut pm, mut pc) = (Vec::new(), Vec::new(), Vec::new());
            for (k, &(f, u3)) in points.iter().enumerate() {
                let um = masing(&mrd_u, amp, k, f)?;
                let mut row = vec![*x, (k > self.steps) as u8 as f64, f / mu_fn];
                let scale = mrd_u(amp)?;
                if sphere.is_some() {
                    let uc = masing(&cf_u, amp, k, f)?;
                    dev_cf = dev_cf.max((u3 - uc).abs() / scale);
                    row.push(uc);
                    pc.push((uc - compliance * f, f / mu_fn));
                }
                dev_mrd = dev_mrd.max((u3 - um).abs() / scale);
                row.extend([um, u3]);
                t.push(row);
                p3.push((u3 - compliance * f, f / mu_fn));
                pm.push((um - compliance * f, f / mu_fn));
            }
            let mut series = Vec::new();
            if sphere.is_some() {
                let label = format!("Mindlin-Deresiewicz, F* = {x} mu F_N");
                series.push(Series::new(label, pc, Style::Line).colored(i));
            }
            let style = if sphere.is_some() {
                Style::Dashed
            } else {
                Style::Line
            };
            let label = format!("MRD (springs, Masing), F* = {x} mu F_N");
            series.push(Series::new(label, pm, style).colored(i));
            let label = format!("3D boundary elements, F* = {x} mu F_N");
            series.push(Series::new(label, p3, Style::Crosses).colored(i));
            drawn.push(series);
        }
        // The largest loop drawn first, so that the smaller ones inside it stay visible.
        for series in drawn.into_iter().rev().flatten() {
            fig = fig.with(series);
        }
        if sphere.is_some() {
            out.scalar("loop_shift_max_rel_error_3d", dev_cf);
        }
        out.scalar("loop_shift_max_rel_dev_3d_vs_mrd", dev_mrd);
        fig.title.push_str(self.half_space_note());
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }

    /// `fig` with the columns `{stem}_closed_form` (drawn under `closed`'s label where
    /// there is one, else the title becomes `without`), `{stem}_mrd` and `{stem}_3d` of
    /// `t` against the column `x`, and the half-space in the title.
    fn three_ways(
        &self,
        mut fig: Figure,
        t: &Table,
        (x, stem): (&str, &str),
        closed: Option<&str>,
        without: &str,
    ) -> Figure {
        let column = |side: &str| t.xy(x, &format!("{stem}_{side}"));
        let mrd_style = match closed {
            Some(label) => {
                fig = fig.plot(label, column("closed_form"), Style::Line);
                Style::Markers
            }
            None => {
                fig.title = without.into();
                Style::Line
            }
        };
        fig = fig
            .plot("MRD (tangential springs)", column("mrd"), mrd_style)
            .plot("3D boundary elements", column("3d"), Style::Crosses);
        fig.title.push_str(self.half_space_note());
        fig
    }

    /// What a figure's title adds on the free half-space (the periodic one is the default).
    fn half_space_note(&self) -> &'static str {
        if self.periodic {
            ""
        } else {
            " (3D on the free half-space)"
        }
    }
}
