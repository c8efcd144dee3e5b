//! `plastic_3d`'s report: the load history (force-approach loop) by MRD and in 3D, the
//! imprint, the grid convergence, and Kogut and Etsion's finite-element fits.

use super::*;

impl Plastic3d {
    pub(super) fn report(
        &self,
        out: &mut Section,
        mrd: &[Run],
        three: &[Run],
        reference: Option<&Run>,
        side: f64,
    ) {
        let runs: Vec<&Run> = three.iter().chain(mrd).collect();
        // The history, one row per step.
        let mut cols = vec!["step [index]".to_string(), "force [force]".to_string()];
        for r in &runs {
            for q in [
                "approach [length]",
                "contact_radius [length]",
                "plastic_radius [length]",
                "plastic_depth [length]",
            ] {
                cols.push(format!("{} {q}", r.label));
            }
        }
        let mut t = Table::new("history", &cols);
        t.notes.push(format!(
            "pressure-cap model, hardness H = {}: 3D on free grids of side {side:.6e} (extent {} x the largest contact diameter), contact and plastic radii from the areas (sqrt(A/pi)); MRD on {} rings: incremental_hess (the rule of Hess applied to the plastically deformed profile at each increment: exact for bodies of revolution), spring_cap (each spring capped at the fully plastic line load 2 H sqrt(a^2 - x^2)); approaches from the undeformed apex; plastic_depth: the largest plastic displacement so far; a cell or ring within 1e-6 of its cap counts as plastic",
            self.hardness, self.extent, self.rings
        ));
        for (k, &f) in self.forces.iter().enumerate() {
            let mut row = vec![k as f64, f];
            for r in &runs {
                let s = &r.states[k];
                row.extend([
                    s.approach,
                    s.contact_radius,
                    s.plastic_radius,
                    s.plastic_depth,
                ]);
            }
            t.push(row);
        }
        out.tables.push(t);
        let loop_fig = runs.iter().enumerate().fold(
            Figure::new(
                "loop",
                &format!(
                    "Force against approach, pressure cap H = {}: 3D and MRD",
                    self.hardness
                ),
                "approach d [length]",
                "force F [force]",
            ),
            |fig, (i, r)| {
                let style = marker(i, three.len());
                fig.plot(
                    r.label.clone(),
                    r.states.iter().map(|s| (s.approach, s.force)).collect(),
                    style,
                )
            },
        );
        out.figures.push(loop_fig);
        // The imprint after the last step.
        let mut fig = Figure::new(
            "imprint",
            "Plastic displacement of the surface after the history (the imprint)",
            "radius r [length]",
            "plastic displacement u_p [length]",
        );
        for (i, r) in runs.iter().enumerate() {
            fig = fig.plot(r.label.clone(), r.imprint.clone(), marker(i, three.len()));
        }
        out.figures.push(fig);
        // The 3D ladder against MRD's incremental rule.
        let Some(refr) = reference else { return };
        let worst = |r: &Run| -> f64 {
            r.states
                .iter()
                .zip(&refr.states)
                .filter(|(_, b)| b.force > 0.0)
                .map(|(a, b)| (a.approach / b.approach - 1.0).abs())
                .fold(0.0, f64::max)
        };
        let mut c = Table::new(
            "convergence",
            &[
                "cells [count]",
                "cells per largest contact radius [1]",
                "largest |d_3D / d_MRD - 1| [1]",
                "largest |depth_3D / depth_MRD - 1| [1]",
            ],
        );
        c.notes.push(format!(
            "the 3D grids against MRD's incremental rule (incremental_hess, {} rings) over the loaded steps of the history; the observed order of the 3D approach at the largest force, from the last three grids alone, is in summary.json (plastic_3d.observed_order)",
            self.rings
        ));
        let reach = side / (2.0 * self.extent);
        let depth = refr.states.last().map_or(0.0, |s| s.plastic_depth);
        let mut errs = vec![];
        for (r, &n) in three.iter().zip(&self.cells) {
            let e = worst(r);
            errs.push((n, e));
            let d3 = r.states.last().map_or(0.0, |s| s.plastic_depth);
            let depth_err = if depth > 0.0 {
                (d3 / depth - 1.0).abs()
            } else {
                0.0
            };
            c.push(vec![n as f64, n as f64 * reach / side, e, depth_err]);
        }
        out.tables.push(c);
        if let Some((_, e)) = errs.last() {
            out.scalar("approach_3d_vs_incremental_hess", *e);
        }
        // The observed order from the 3D ladder alone (the last three grids, each twice
        // the last): the approach at the largest force, Richardson's ratio of successive
        // differences.
        let at_peak = |r: &Run| {
            r.states
                .iter()
                .fold((0.0f64, 0.0), |(f, d), s| {
                    if s.force > f {
                        (s.force, s.approach)
                    } else {
                        (f, d)
                    }
                })
                .1
        };
        let k = three.len();
        if k >= 3 && self.cells[k - 3..].windows(2).all(|w| w[1] == 2 * w[0]) {
            let (d1, d2, d3) = (
                at_peak(&three[k - 3]),
                at_peak(&three[k - 2]),
                at_peak(&three[k - 1]),
            );
            let ratio = (d1 - d2) / (d2 - d3);
            if ratio > 0.0 && ratio.is_finite() {
                out.scalar("observed_order", ratio.log2());
            }
        }
        for r in mrd.iter().filter(|r| !std::ptr::eq(*r, refr)) {
            let e = worst(r);
            out.scalar(
                format!(
                    "approach_{}_vs_incremental_hess",
                    r.label.trim_start_matches("MRD ")
                ),
                e,
            );
        }
    }

    /// Kogut & Etsion's finite-element fits beside the pressure-cap model's first
    /// loading (sphere of radius `r`): the cap's hardness is their fully plastic
    /// `H = 2.8 Y`, so `Y = H / 2.8`. Each run is read at its own interference (the
    /// history is force-controlled: every run carries the same force at a step).
    pub(super) fn kogut_etsion(
        &self,
        runs: &[&Run],
        e: f64,
        r: f64,
    ) -> (Table, Figure, Option<f64>) {
        let y = self.hardness / 2.8;
        let wc = ke::critical_interference(e, r, y, self.poisson);
        let pc = 4.0 / 3.0 * e * r.sqrt() * wc.powf(1.5);
        let mut cols = vec!["P/P_c [1]".to_string()];
        for run in runs {
            cols.push(format!("w/w_c {} [1]", run.label));
            cols.push(format!(
                "P/P_c Kogut-Etsion at the {} interference [1]",
                run.label
            ));
        }
        let mut t = Table::new("kogut_etsion", &cols);
        t.missing_ok = true;
        t.notes.push(format!(
            "Kogut & Etsion (J. Appl. Mech. 69 (2002) 657), finite elements with J2 plasticity (Y = H / 2.8 = {y:.6e}, nu = {}): w_c = {wc:.6e}, P_c = {pc:.6e}; the pressure-cap runs' first loading (the steps before the force first falls), each at its own interference w (approach); empty: w/w_c outside the fits' range [1, 110]; the cap yields at p0 = H, the finite elements at p0 = K H = {:.3} H",
            self.poisson,
            ke::k(self.poisson)
        ));
        // The first loading: the steps before the force first falls.
        let peak = self
            .forces
            .windows(2)
            .position(|w| w[1] < w[0])
            .unwrap_or(self.forces.len() - 1);
        let mut worst: f64 = 0.0;
        for k in 0..=peak {
            let mut row = vec![self.forces[k] / pc];
            for (i, run) in runs.iter().enumerate() {
                let x = run.states[k].approach / wc;
                let p = ke::load_ratio(x).unwrap_or(f64::NAN);
                row.extend([x, p]);
                if i + 1 == runs.len() && p.is_finite() {
                    worst = worst.max((row[0] / p - 1.0).abs());
                }
            }
            t.push(row);
        }
        let inside = t
            .rows
            .iter()
            .any(|row| row.iter().skip(2).step_by(2).any(|p| p.is_finite()));
        let xs: Vec<f64> = t
            .rows
            .iter()
            .map(|row| row[1])
            .filter(|x| *x > 0.0)
            .collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
        let curve: Vec<(f64, f64)> =
            mrd::friction::log_space(lo.max(1.0), hi.clamp(1.0, 110.0), 60)
                .into_iter()
                .filter_map(|x| ke::load_ratio(x).map(|p| (x, p)))
                .collect();
        let mut fig = Figure::new(
            "kogut_etsion",
            "Sphere, first loading: pressure cap (3D, MRD) against Kogut-Etsion's finite elements",
            "interference over its critical value w/w_c [1]",
            "load over its critical value P/P_c [1]",
        )
        .log_log()
        .plot(
            "Kogut & Etsion 2002 (FEM, J2 plasticity)",
            curve,
            Style::Dashed,
        );
        for (i, run) in runs.iter().enumerate() {
            fig = fig.plot(
                format!("{} (pressure cap)", run.label),
                t.rows
                    .iter()
                    .filter(|row| row[1 + 2 * i] > 0.0)
                    .map(|row| (row[1 + 2 * i], row[0]))
                    .collect(),
                if run.label.starts_with("3D") {
                    Style::Markers
                } else {
                    Style::Line
                },
            );
        }
        (t, fig, inside.then_some(worst))
    }
}
