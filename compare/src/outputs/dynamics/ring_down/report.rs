//! `ring_down`'s cycles (turning point to turning point) and the held approach's report:
//! each cycle's loss against Mindlin-Deresiewicz's, MRD's run against the 3D one.

use super::{RingDown, SIDE_3D};
use crate::error::Result;
use crate::experiment::ring::cycles;
use crate::report::{Figure, Section, Style, Table};
use dynamics::integrate::Sample;
use mrd::reference::mindlin_damping as md;
use std::f64::consts::PI;

impl RingDown {
    /// Per cycle of a run (from a turning point to the second after it, same sign):
    /// [cycle, time over period, force amplitude over mu F_N (the mean of its three
    /// extremes' magnitudes), loss, Mindlin-Deresiewicz's loss at that amplitude, their
    /// ratio, zeta, zeta of Mindlin-Deresiewicz].
    pub(super) fn cycles(&self, s: &[Sample], (g, a, period): (f64, f64, f64)) -> Vec<Vec<f64>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        cycles(s)
            .into_iter()
            .enumerate()
            .map(|(c, cy)| {
                let (q, xa, loss) = (cy.force, cy.x, cy.loss);
                let exact = md::dissipation_force_amplitude_exact(g, a, mu, fn_, q);
                let stored = 0.5 * q * xa;
                let exact_stored = 0.5 * q * self.md_displacement(g, a, q);
                vec![
                    c as f64,
                    cy.t / period,
                    q / (mu * fn_),
                    loss,
                    exact,
                    loss / exact,
                    loss / (4.0 * PI * stored),
                    exact / (4.0 * PI * exact_stored),
                ]
            })
            .collect()
    }

    /// The columns of a cycles table of one method (`who`: "MRD" or "3D"), as
    /// [`Self::cycles`] gives them.
    fn cycle_columns(who: &str) -> Vec<String> {
        vec![
            "cycle [index]".into(),
            "time over period [1]".into(),
            "force_amplitude over mu F_N [1]".into(),
            format!("loss per cycle, {who} in the loop [force x length]"),
            "loss per cycle, Mindlin-Deresiewicz [force x length]".into(),
            format!("loss ratio {who} / MD [1]"),
            "damping ratio zeta [1]".into(),
            "damping ratio zeta, MD [1]".into(),
        ]
    }

    /// The cycles table of one method (`who`: "MRD" or "3D"), `lead` columns before the
    /// cycles' own (each row starting with their values).
    pub(super) fn cycles_table(
        name: &str,
        who: &str,
        lead: &[&str],
        rows: Vec<Vec<f64>>,
        note: String,
    ) -> Table {
        let own = Self::cycle_columns(who);
        let columns: Vec<&str> = lead
            .iter()
            .copied()
            .chain(own.iter().map(String::as_str))
            .collect();
        let mut t = Table::new(name, &columns);
        t.notes.push(note);
        for r in rows {
            t.push(r);
        }
        t
    }

    pub(super) fn report(
        &self,
        out: &mut Section,
        s: &[Sample],
        three: Option<&[Sample]>,
        (g, a, k_t, period): (f64, f64, f64, f64),
    ) -> Result<()> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let common = format!(
            "sphere under F_N = {fn_} with mu = {mu}, G* = {g}, contact radius a = {a:.6e}; mass {} released at rest from {} mu F_N (virgin loading)",
            self.mass, self.amplitude
        );
        let tail = format!("velocity Verlet at STEPS steps per period 2 pi sqrt(m / k_t) = {period:.6e} (k_t = 2 a G*); loss per cycle: the slip energy between turning points two apart, against Johnson's Eq. 7.59 at the mean of the cycle's three force extremes; zeta = W / (4 pi U), U = Q*^2 / (2 k_sec) with the secant stiffness of the cycle's extremes");
        let rows = self.cycles(s, (g, a, period));
        if rows.is_empty() {
            out.failures.push("the motion made no full cycle".into());
            return Ok(());
        }
        let worst = |rows: &[Vec<f64>]| rows.iter().fold(0.0f64, |w, r| w.max((r[5] - 1.0).abs()));
        out.scalar(
            "loss_per_cycle_max_rel_dev_vs_mindlin_deresiewicz",
            worst(&rows),
        );
        out.scalar("initial_tangential_stiffness", k_t);
        out.scalar(
            "amplitude_decay_first_to_last_cycle",
            rows[rows.len() - 1][2] / rows[0][2],
        );
        let t = Self::cycles_table(
            "cycles",
            "MRD",
            &[],
            rows,
            format!(
                "{common}; MRD's {} springs with Coulomb slip, {}",
                self.springs,
                tail.replace("STEPS", &self.steps.to_string())
            ),
        );
        let rows_3d = three.map(|s3| self.cycles(s3, (g, a, period)));
        let mut fig = Figure::new(
            "ring_down",
            "Frictional ring-down on a sphere: tangential force, MRD and 3D in the loop",
            "time over the stick period t / T [1]",
            "tangential force over mu F_N [1]",
        )
        .plot(
            format!("MRD, {} springs, Coulomb slip", self.springs),
            s.iter()
                .step_by((s.len() / 2000).max(1))
                .map(|p| (p.t / period, p.force / (mu * fn_)))
                .collect(),
            Style::Line,
        );
        if let Some(s3) = three {
            fig = fig.plot(
                format!(
                    "3D partial slip, {0}^2 cells, {1} steps per period",
                    self.cells_3d, self.steps_3d
                ),
                s3.iter()
                    .map(|p| (p.t / period, p.force / (mu * fn_)))
                    .collect(),
                Style::Dashed,
            );
        }
        out.figures.push(fig);
        let mut zeta = Figure::new(
            "damping",
            "Loss per cycle over Mindlin-Deresiewicz's, and damping ratio, against amplitude",
            "force amplitude over mu F_N [1]",
            "[1]",
        )
        .plot(
            "loss per cycle: MRD in the loop / Mindlin-Deresiewicz",
            t.rows.iter().map(|r| (r[2], r[5])).collect(),
            Style::Markers,
        )
        .plot(
            "damping ratio zeta, MRD in the loop",
            t.rows.iter().map(|r| (r[2], r[6])).collect(),
            Style::Crosses,
        )
        .plot(
            "damping ratio zeta, Mindlin-Deresiewicz",
            t.rows.iter().map(|r| (r[2], r[7])).collect(),
            Style::Line,
        );
        let mrd_rows = t.rows.clone();
        out.tables.push(t);
        if let Some(rows) = rows_3d {
            if rows.is_empty() {
                out.failures.push("the 3D run made no full cycle".into());
            } else {
                out.scalar(
                    "loss_per_cycle_max_rel_dev_3d_vs_mindlin_deresiewicz",
                    worst(&rows),
                );
                // Cycle by cycle against MRD's run: the amplitude and the loss.
                let (mut amp, mut loss) = (0.0f64, 0.0f64);
                for (r3, rm) in rows.iter().zip(&mrd_rows) {
                    amp = amp.max((r3[2] / rm[2] - 1.0).abs());
                    loss = loss.max((r3[3] / rm[3] - 1.0).abs());
                }
                out.scalar("amplitude_max_rel_dev_3d_vs_mrd", amp);
                out.scalar("loss_per_cycle_max_rel_dev_3d_vs_mrd", loss);
                zeta = zeta.plot(
                    "loss per cycle: 3D in the loop / Mindlin-Deresiewicz",
                    rows.iter().map(|r| (r[2], r[5])).collect(),
                    Style::Markers,
                );
                let t3 = Self::cycles_table(
                    "cycles_3d",
                    "3D",
                    &[],
                    rows,
                    format!(
                        "{common}; 3D partial slip on the free half-space, {0}^2 cells over {SIDE_3D} contact radii (the normal pressure of F_N held, Poisson's ratio of the one body equivalent to E* and G*), {1}",
                        self.cells_3d,
                        tail.replace("STEPS", &self.steps_3d.to_string())
                    ),
                );
                out.tables.push(t3);
            }
        }
        out.figures.push(zeta);
        Ok(())
    }

    /// Mindlin's tangential displacement at the force `q` on the virgin loading:
    /// `3 mu F_N / (8 G* a) ... ` in MRD's terms `(3 mu F_N / (4 a G*)) (1 - (1 - q /
    /// (mu F_N))^(2/3))` (Eq. 45 with G* the composite tangential modulus).
    fn md_displacement(&self, g: f64, a: f64, q: f64) -> f64 {
        let (mu, fn_) = (self.mu, self.normal_force);
        3.0 * mu * fn_ / (4.0 * a * g) * (1.0 - (1.0 - q / (mu * fn_)).powf(2.0 / 3.0))
    }
}
