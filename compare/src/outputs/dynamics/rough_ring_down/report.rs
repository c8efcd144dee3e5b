//! `rough_ring_down`'s report: every cycle against its closed form, MRD's damping against
//! the 3D one on the ladder of amplitudes at each preload, the grid check, the figures.

use super::*;

/// Mean and 95 % interval (0 with one value).
fn stat(v: &[f64]) -> (f64, f64) {
    let s = Stat::of(v);
    (s.mean, if v.len() > 1 { s.ci95 } else { 0.0 })
}

impl RoughRingDown {
    pub(super) fn report(
        &self,
        out: &mut Section,
        (mrd, three): (&[Vec<Damping>], &[Vec<Damping>]),
        (e, g, rms, lambda): (f64, f64, f64, f64),
    ) {
        let n = CELLS * self.bandwidth;
        let common = format!(
            "rough punch (H = {}, bandwidth {}, {n}^2 cells, diameter L = 1) under F0 = preload x E* h L (h = {rms:.6e} the faces' mean rms height), E* = {e}, G* = {g}, mu = {}; unit mass released at rest from {} mu F0 after a virgin loading; MRD: {} lines of {} springs (C1D = lambda q C2D, lambda = {lambda:.4}), {} periods at {} steps; 3D: {} faces, partial slip on the free half-space under the pressure of F0, {} periods at {} steps, tolerance {:e}",
            self.hurst, self.bandwidth, self.mu, self.amplitude, self.lines, 16 * n,
            self.periods, self.steps, self.realisations_3d, self.periods_3d, self.steps_3d,
            self.tolerance
        );
        // Every cycle of every run against its own closed form.
        let mut t = Table::new(
            "cycles",
            &[
                "preload F0 / (E* h L) [1]",
                "method [0 MRD, 1 3D]",
                "realisation [index]",
                "cycle [index]",
                "time over period [1]",
                "force amplitude over mu F0 [1]",
                "loss per cycle in the loop [force x length]",
                "loss per cycle, closed form of its own normal curve [force x length]",
                "loss ratio in the loop / closed form [1]",
            ],
        );
        t.notes.push(format!(
            "{common}; a cycle from a turning point to the second after it, its amplitude the mean of its three extremes; the closed form: the Ciavarella-Jaeger difference of two normal problems with Masing's rule on the run's own F(d) (mrd::reference::masing), each half-cycle a branch of force range dQ losing half the symmetric cycle's loss at dQ / 2"
        ));
        let mut worst = [0.0f64; 2];
        for (p, preload) in self.preloads.iter().enumerate() {
            for (m, runs) in [&mrd[p], &three[p]].iter().enumerate() {
                for (r, run) in runs.iter().enumerate() {
                    for (c, row) in run.cycles.iter().enumerate() {
                        worst[m] = worst[m].max((row[4] - 1.0).abs());
                        let mut v = vec![*preload, m as f64, r as f64, c as f64];
                        v.extend_from_slice(row);
                        t.push(v);
                    }
                }
            }
        }
        out.scalar("mrd_loss_max_rel_dev_vs_own_closed_form", worst[0]);
        out.scalar("loss_3d_max_rel_dev_vs_own_closed_form", worst[1]);
        let mean =
            |d: &[Damping], f: fn(&Damping) -> f64| stat(&d.iter().map(f).collect::<Vec<_>>()).0;
        let (mut kt, mut d0) = (Vec::new(), Vec::new());
        for p in 0..self.preloads.len() {
            kt.push(mean(&mrd[p], |d| d.k_t) / mean(&three[p], |d| d.k_t));
            d0.push(mean(&mrd[p], |d| d.d0) / mean(&three[p], |d| d.d0));
        }
        let spread = |v: &[f64]| v.iter().fold(0.0f64, |w, x| w.max((x - 1.0).abs()));
        out.scalar(
            "initial_tangential_stiffness_mrd_over_3d_max_rel_dev",
            spread(&kt),
        );
        out.scalar("approach_mrd_over_3d_max_rel_dev", spread(&d0));
        let ladder = self.ladder_table(out, (mrd, three), &common);
        out.figures.push(self.history_figure(&mrd[0], &three[0]));
        out.figures.push(ratio_figure(&t));
        out.figures.push(self.ladder_figure(&ladder));
        out.figures.push(self.over_figure(&ladder));
        out.tables.push(t);
        out.tables.push(ladder);
    }

    /// MRD's closed-form loss and damping ratio against the 3D ones on the ladder, at
    /// each preload.
    fn ladder_table(
        &self,
        out: &mut Section,
        (mrd, three): (&[Vec<Damping>], &[Vec<Damping>]),
        common: &str,
    ) -> Table {
        let mut t = Table::new(
            "damping",
            &[
                "preload F0 / (E* h L) [1]",
                "force amplitude over mu F0 [1]",
                "loss per cycle MRD, mean [force x length]",
                "loss MRD ci95 [force x length]",
                "loss per cycle 3D, mean [force x length]",
                "loss 3D ci95 [force x length]",
                "loss MRD over 3D [1]",
                "loss MRD over 3D ci95 [1]",
                "damping ratio MRD, mean [1]",
                "damping ratio MRD ci95 [1]",
                "damping ratio 3D, mean [1]",
                "damping ratio 3D ci95 [1]",
            ],
        );
        t.notes.push(format!(
            "{common}; each line's and face's loss per cycle from the closed form of its own normal curve (which its run in the loop meets: table cycles), damping ratio zeta = W / (4 pi U), U = Q* u* / 2 with u* the virgin loading's displacement; means and 95 % intervals over lines and faces, the ratio's interval from the two relative intervals in quadrature"
        ));
        let mut worst = 0.0f64;
        for (p, preload) in self.preloads.iter().enumerate() {
            for (i, x) in LADDER.iter().enumerate() {
                let of = |d: &[Damping], k: usize| {
                    stat(
                        &d.iter()
                            .map(|d| [d.ladder[i].0, d.ladder[i].1][k])
                            .collect::<Vec<_>>(),
                    )
                };
                let (w1, w3, z1, z3) = (
                    of(&mrd[p], 0),
                    of(&three[p], 0),
                    of(&mrd[p], 1),
                    of(&three[p], 1),
                );
                let ratio = w1.0 / w3.0;
                let ci = ratio * ((w1.1 / w1.0).powi(2) + (w3.1 / w3.0).powi(2)).sqrt();
                worst = worst.max((ratio - 1.0).abs());
                t.push(vec![
                    *preload, *x, w1.0, w1.1, w3.0, w3.1, ratio, ci, z1.0, z1.1, z3.0, z3.1,
                ]);
            }
        }
        out.scalar("loss_mrd_over_3d_max_rel_dev", worst);
        t
    }

    /// The 3D ladder's mean losses on the scene's grid against the refined one.
    pub(super) fn grid_check(
        &self,
        out: &mut Section,
        coarse: &[Vec<Damping>],
        fine: &[Vec<Damping>],
    ) {
        let n = CELLS * self.bandwidth;
        let mut t = Table::new(
            "grid_check",
            &[
                "preload F0 / (E* h L) [1]",
                "force amplitude over mu F0 [1]",
                "loss per cycle 3D, scene's grid, mean [force x length]",
                "loss per cycle 3D, refined grid, mean [force x length]",
                "relative change [1]",
                "worst cycle in the loop / closed form, refined grid [1]",
            ],
        );
        t.notes.push(format!(
            "the same {} faces on {n}^2 and {}^2 cells (band-limited interpolation; {} and {} cells per shortest wavelength), the closed form of each run's own normal curve on the ladder of force amplitudes",
            self.realisations_3d,
            self.fine_cells(),
            CELLS,
            CELLS * self.refine_factor()
        ));
        let (mut worst, mut in_loop) = (0.0f64, 0.0f64);
        for (p, preload) in self.preloads.iter().enumerate() {
            let loop_dev = fine[p]
                .iter()
                .flat_map(|d| d.cycles.iter().map(|c| (c[4] - 1.0).abs()))
                .fold(0.0f64, f64::max);
            in_loop = in_loop.max(loop_dev);
            for (i, x) in LADDER.iter().enumerate() {
                let mean =
                    |d: &[Damping]| stat(&d.iter().map(|d| d.ladder[i].0).collect::<Vec<_>>()).0;
                let (a, b) = (mean(&coarse[p]), mean(&fine[p]));
                worst = worst.max((b / a - 1.0).abs());
                t.push(vec![*preload, *x, a, b, b / a - 1.0, loop_dev]);
            }
        }
        out.scalar("loss_3d_refined_grid_max_rel_change", worst);
        out.scalar("loss_3d_refined_max_rel_dev_vs_own_closed_form", in_loop);
        out.tables.push(t);
    }

    fn history_figure(&self, mrd: &[Damping], three: &[Damping]) -> Figure {
        let scale = |d: &Damping| self.mu * d.samples.first().map_or(1.0, |s| s.normal);
        let mut fig = Figure::new(
            "rough_ring_down",
            &format!(
                "Frictional ring-down on a rough punch at F0 = {} E* h L: MRD and 3D in the loop",
                self.preloads[0]
            ),
            "time over the contact's stick period t / T [1]",
            "tangential force over mu F0 [1]",
        );
        for (label, d, style) in [
            (
                format!("MRD line 0 ({} periods)", self.periods),
                &mrd[0],
                Style::Line,
            ),
            (
                format!("3D face 0 ({} periods)", self.periods_3d),
                &three[0],
                Style::Dashed,
            ),
        ] {
            let f = scale(d);
            fig = fig.plot(
                label,
                d.samples
                    .iter()
                    .step_by((d.samples.len() / 2000).max(1))
                    .map(|s| (s.t / d.period, s.force / f))
                    .collect(),
                style,
            );
        }
        fig
    }

    /// The rows of one preload as (amplitude, column, interval) points, each preload's
    /// amplitudes shifted by a hundredth of mu F0 from the next so that their intervals
    /// stand apart (a lower end floored at a hundredth of the mean, for a log axis).
    fn series(
        &self,
        t: &Table,
        p: f64,
        (m, c): (usize, usize),
        label: String,
        style: Style,
    ) -> Series {
        let k = self.preloads.iter().position(|q| *q == p).unwrap_or(0) as f64;
        let dx = 0.01 * (k - 0.5 * (self.preloads.len() as f64 - 1.0));
        let rows: Vec<&Vec<f64>> = t.rows.iter().filter(|r| r[0] == p).collect();
        Series::new(
            label,
            rows.iter().map(|r| (r[1] + dx, r[m])).collect(),
            style,
        )
        .with_bars(
            rows.iter()
                .map(|r| (r[1] + dx, (r[m] - r[c]).max(0.01 * r[m]), r[m] + r[c]))
                .collect(),
        )
    }

    fn ladder_figure(&self, t: &Table) -> Figure {
        let mut fig = Figure::new(
            "rough_damping",
            "Damping ratio of a rough contact against the force amplitude: MRD lines and 3D faces",
            "force amplitude over mu F0 [1]",
            "damping ratio zeta = W / (4 pi U) [1] (amplitudes offset by 0.01 per preload)",
        );
        // Each preload's two methods in one colour: the 3D markers, MRD's line.
        for (k, &p) in self.preloads.iter().enumerate() {
            let (faces, lines) = (self.realisations_3d, self.lines);
            fig = fig
                .with(
                    self.series(
                        t,
                        p,
                        (10, 11),
                        format!("3D, F0 = {p} E* h L, {faces} faces (95 %)"),
                        Style::Markers,
                    )
                    .colored(2 * k),
                )
                .with(
                    self.series(
                        t,
                        p,
                        (8, 9),
                        format!("MRD, F0 = {p} E* h L, {lines} lines (95 %)"),
                        Style::Line,
                    )
                    .colored(2 * k),
                );
        }
        fig
    }

    fn over_figure(&self, t: &Table) -> Figure {
        let mut fig = Figure::new(
            "rough_damping_mrd_over_3d",
            "Loss per cycle of a rough contact, MRD over 3D, against the force amplitude",
            "force amplitude over mu F0 [1]",
            "loss per cycle, MRD / 3D [1] (amplitudes offset by 0.01 per preload)",
        );
        for &p in &self.preloads {
            fig =
                fig.with(self.series(t, p, (6, 7), format!("F0 = {p} E* h L (95 %)"), Style::Line));
        }
        fig.log_y = true;
        fig.plot(
            "equal",
            LADDER.iter().map(|x| (*x, 1.0)).collect(),
            Style::Dashed,
        )
    }
}

/// Each cycle's loss in the loop over its closed form, against the amplitude.
fn ratio_figure(t: &Table) -> Figure {
    let of = |m: f64| -> Vec<(f64, f64)> {
        t.rows
            .iter()
            .filter(|r| r[1] == m)
            .map(|r| (r[5], r[8]))
            .collect()
    };
    Figure::new(
        "rough_loss_ratio",
        "Loss per cycle in the loop over the closed form of the contact's own normal curve",
        "force amplitude over mu F0 [1]",
        "loss in the loop / closed form [1]",
    )
    .plot("MRD lines, every cycle", of(0.0), Style::Crosses)
    .plot("3D faces, every cycle", of(1.0), Style::Markers)
}
