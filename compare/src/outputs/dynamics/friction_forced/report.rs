//! `friction_forced`'s report: each steady period against Mindlin-Deresiewicz, the
//! stuck contact's linear response, the frequency response and slip-energy figures.

use super::*;

impl FrictionForced {
    /// Per frequency: [Omega / omega_t, amplitude over the drive's static displacement
    /// F1 / k_t, Q* / (mu F_N), slip energy, Mindlin-Deresiewicz's W(Q*), their ratio,
    /// the drive's work over the losses, periods, settled (1 or 0), sliding (1: the
    /// force amplitude at mu F_N, where W(Q*) is no reference)].
    fn rows(&self, s: &[Steady], (g, a, omega_t): (f64, f64, f64)) -> Vec<Vec<f64>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let static_x = self.drive * mu * fn_ / (2.0 * a * g);
        s.iter()
            .map(|p| {
                let q = p.force_amplitude.min(mu * fn_);
                let exact = md::dissipation_force_amplitude_exact(g, a, mu, fn_, q);
                vec![
                    p.omega / omega_t,
                    p.amplitude / static_x,
                    p.force_amplitude / (mu * fn_),
                    p.slip,
                    exact,
                    p.slip / exact,
                    p.work / (p.slip + p.viscous),
                    p.periods as f64,
                    if p.settled { 1.0 } else { 0.0 },
                    if p.force_amplitude >= (1.0 - SLIDING) * mu * fn_ {
                        1.0
                    } else {
                        0.0
                    },
                ]
            })
            .collect()
    }

    /// The linear oscillator on the stuck contact's stiffness k_t with the dashpot alone,
    /// `1 / sqrt((1 - w^2)^2 + (2 zeta w)^2)` over the span of the rows' frequencies.
    fn stuck(&self, rows: &[Vec<f64>]) -> Vec<(f64, f64)> {
        let (lo, hi) = rows.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
            (a.min(r[0]), b.max(r[0]))
        });
        let z = self.damping;
        (0..=400)
            .map(|k| {
                let w = lo + (hi - lo) * k as f64 / 400.0;
                (
                    w,
                    1.0 / ((1.0 - w * w).powi(2) + (2.0 * z * w).powi(2)).sqrt(),
                )
            })
            .collect()
    }

    fn table(&self, name: &str, who: &str, rows: Vec<Vec<f64>>, note: String) -> Table {
        let slip = format!("slip energy per period, {who} [force x length]");
        let ratio = format!("slip energy {who} / MD [1]");
        let mut t = Table::new(
            name,
            &[
                "drive frequency over omega_t [1]",
                "amplitude over F1 / k_t [1]",
                "force amplitude over mu F_N [1]",
                &slip,
                "Mindlin-Deresiewicz W(Q*) [force x length]",
                &ratio,
                "drive work over slip and dashpot losses [1]",
                "periods run [count]",
                "settled [1 or 0]",
                "sliding: force amplitude at mu F_N [1 or 0]",
            ],
        );
        t.notes.push(note);
        for r in rows {
            t.push(r);
        }
        t
    }

    pub(super) fn report(
        &self,
        out: &mut Section,
        mrd: &[Steady],
        three: Option<&[Steady]>,
        (g, a, omega_t): (f64, f64, f64),
    ) -> Result<()> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let common = format!(
            "sphere under F_N = {fn_} with mu = {mu}, G* = {g}, contact radius a = {a:.6e}, k_t = 2 a G* = {:.6e}, omega_t = sqrt(k_t / m) = {omega_t:.6e}; mass {} driven by {} mu F_N cos(Omega t), dashpot zeta = {} at omega_t; {} steps per drive period, each frequency run period by period from the last one's end until the amplitude changes by at most {:e} of itself (at least {MIN_PERIODS}, at most {} periods); the last period's slip energy against Johnson's Eq. 7.59 at its force amplitude (half the force's range), where the contact does not slide (force amplitude below (1 - {SLIDING:e}) mu F_N)",
            2.0 * a * g,
            self.mass,
            self.drive,
            self.damping,
            self.steps,
            self.settle_tolerance,
            self.max_periods
        );
        // The largest deviation from 1 of column `col`; the MD ratio (column 5) over the
        // frequencies that do not slide.
        let worst = |rows: &[Vec<f64>], col: usize| {
            let held = rows.iter().filter(|r| col != 5 || r[9] == 0.0);
            held.fold(0.0f64, |w, r| w.max((r[col] - 1.0).abs()))
        };
        let sliding = |rows: &[Vec<f64>]| rows.iter().filter(|r| r[9] == 1.0).count() as f64;
        let peak = |rows: &[Vec<f64>]| {
            rows.iter().fold((0.0f64, 0.0f64), |(f, x), r| {
                if r[1] > x {
                    (r[0], r[1])
                } else {
                    (f, x)
                }
            })
        };
        let unsettled = |s: &[Steady], who: &str, out: &mut Section| {
            for p in s.iter().filter(|p| !p.settled) {
                out.failures.push(format!(
                    "{who}: the amplitude at {:.4} omega_t did not settle in {} periods (raise max_periods or settle_tolerance)",
                    p.omega / omega_t,
                    p.periods
                ));
            }
        };
        unsettled(mrd, "MRD", out);
        let rows = self.rows(mrd, (g, a, omega_t));
        out.scalar(
            "slip_energy_max_rel_dev_vs_mindlin_deresiewicz",
            worst(&rows, 5),
        );
        out.scalar("energy_balance_max_rel_dev", worst(&rows, 6));
        out.scalar("sliding_frequencies", sliding(&rows));
        let (f_peak, x_peak) = peak(&rows);
        out.scalar("peak_frequency_over_omega_t", f_peak);
        out.scalar("peak_amplitude_over_static", x_peak);
        let mut response = Figure::new(
            "frequency_response",
            "Frictionally damped forced oscillation on a sphere: amplitude against drive frequency",
            "drive frequency Omega / omega_t [1]",
            "amplitude over the drive's static displacement F1 / k_t [1]",
        )
        .plot(
            format!("MRD in the loop, {} springs", self.springs),
            rows.iter().map(|r| (r[0], r[1])).collect(),
            Style::Line,
        )
        .plot(
            "the contact stuck (no slip): the linear oscillator on k_t",
            self.stuck(&rows),
            Style::Dashed,
        );
        let mut losses = Figure::new(
            "slip_energy",
            "Steady slip energy per period over Mindlin-Deresiewicz's at the force amplitude",
            "drive frequency Omega / omega_t [1]",
            "slip energy over W(Q*) [1]",
        )
        .plot(
            format!("MRD in the loop, {} springs", self.springs),
            rows.iter().map(|r| (r[0], r[5])).collect(),
            Style::Markers,
        );
        out.tables.push(self.table(
            "steady",
            "MRD",
            rows.clone(),
            format!("{common}; MRD's {} springs with Coulomb slip", self.springs),
        ));
        if let Some(s3) = three {
            unsettled(s3, "3D", out);
            let rows3 = self.rows(s3, (g, a, omega_t));
            out.scalar(
                "slip_energy_max_rel_dev_3d_vs_mindlin_deresiewicz",
                worst(&rows3, 5),
            );
            out.scalar("energy_balance_max_rel_dev_3d", worst(&rows3, 6));
            out.scalar("sliding_frequencies_3d", sliding(&rows3));
            // The 3D amplitude against MRD's curve at the same frequency (linear between
            // MRD's frequencies; a 3D frequency outside MRD's sweep is left out).
            let mut dev = 0.0f64;
            for r in &rows3 {
                let at = rows
                    .windows(2)
                    .find(|w| (w[0][0] - r[0]) * (w[1][0] - r[0]) <= 0.0 && w[0][0] != w[1][0]);
                if let Some(w) = at {
                    let s = (r[0] - w[0][0]) / (w[1][0] - w[0][0]);
                    let x = w[0][1] + s * (w[1][1] - w[0][1]);
                    dev = dev.max((r[1] / x - 1.0).abs());
                }
            }
            out.scalar("amplitude_max_rel_dev_3d_vs_mrd", dev);
            response = response.plot(
                format!("3D partial slip in the loop, {0}^2 cells", self.cells_3d),
                rows3.iter().map(|r| (r[0], r[1])).collect(),
                Style::Crosses,
            );
            losses = losses.plot(
                format!("3D in the loop, {0}^2 cells", self.cells_3d),
                rows3.iter().map(|r| (r[0], r[5])).collect(),
                Style::Crosses,
            );
            out.tables.push(self.table(
                "steady_3d",
                "3D",
                rows3,
                format!(
                    "{common}; 3D partial slip on the free half-space, {0}^2 cells over {SIDE_3D} contact radii (the normal pressure of F_N held), solves to 1e-8",
                    self.cells_3d
                ),
            ));
        }
        out.figures.push(response);
        out.figures.push(losses);
        Ok(())
    }
}
