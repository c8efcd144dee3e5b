//! `ring_down` under a normal wave: the normal approach oscillating about the held one,
//! `d0 (1 + b sin(f omega_t t + phase))`, at each frequency f, by MRD's springs and by
//! the 3D contact with both motions free; each cycle's loss against the held approach's
//! at the same force amplitude (the module above has the whole account).

use super::{NormalWave, RingDown, MAX_FREQUENCIES, SIDE_3D};
use crate::checks::bad;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use dynamics::integrate::Sample;
use dynamics::{ObliqueBem3d, Springs};
use mrd::reference::{for_profile, hertz};
use std::f64::consts::PI;

/// One frequency of a normal wave: the frequency, MRD's run and the 3D run.
type WaveRun = (f64, Vec<Sample>, Option<Vec<Sample>>);

impl NormalWave {
    pub(super) fn check(&self, release: f64) -> Result<()> {
        let b = self.amplitude;
        if !(b > 0.0 && b < 1.0) {
            return bad(format!("normal_wave.amplitude = {b} must lie in (0, 1)"));
        }
        if self.frequencies.is_empty() || self.frequencies.len() > MAX_FREQUENCIES {
            return bad(format!(
                "normal_wave.frequencies has {} values; give 1 to {MAX_FREQUENCIES}",
                self.frequencies.len()
            ));
        }
        if let Some(f) = self
            .frequencies
            .iter()
            .find(|f| !(f.is_finite() && **f > 0.0 && **f <= 100.0))
        {
            return bad(format!(
                "normal_wave.frequencies holds {f}: each must lie in (0, 100] (over the ring-down's angular frequency)"
            ));
        }
        if !self.phase.is_finite() {
            return bad(format!("normal_wave.phase = {} must be finite", self.phase));
        }
        // Hertz's F ~ d^(3/2): the stick limit at the release's approach, over mu F_N.
        let limit = (1.0 + b * self.phase.sin()).powf(1.5);
        if release >= 0.95 * limit {
            return bad(format!(
                "amplitude = {release} must lie below 0.95 of the stick limit at the release's approach, (1 + b sin(phase))^(3/2) = {limit:.4} with normal_wave.amplitude = {b} and normal_wave.phase = {}",
                self.phase
            ));
        }
        Ok(())
    }
}

impl RingDown {
    /// The runs under the normal wave `w`, frequency by frequency: MRD's springs and,
    /// with `cells_3d`, the 3D contact with both motions free, both about Hertz's
    /// approach of F_N.
    pub(super) fn waves(
        &self,
        out: &mut Section,
        w: &NormalWave,
        profile: &mrd::profile::Profile,
        grid: &AxisymGrid,
        (e, g): (f64, f64),
        (k_t, period): (f64, f64),
    ) -> Result<Vec<WaveRun>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let r = for_profile::sphere_radius(profile).unwrap_or(1.0);
        let d0 = hertz::depth(e, r, fn_);
        let a = hertz::radius(r, d0);
        let z = (self.cells_3d > 0).then(|| grid.heights(profile).0);
        let mut runs = Vec::new();
        for &f in &w.frequencies {
            let wave = Some((w.amplitude, f * 2.0 * PI / period, w.phase));
            let sm = out
                .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Sample>> {
                    let mut law =
                        Springs::body(profile, e, self.springs, 1.5 * a)?.with_friction(g, mu)?;
                    self.ring(
                        &mut law,
                        d0,
                        wave,
                        (k_t, period),
                        (self.periods, self.steps),
                    )
                })
                .ctx(format!(
                    "MRD in the loop under the normal wave at {f} omega_t"
                ))?;
            let s3 = match &z {
                Some(z) => Some(
                    out.stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Sample>> {
                        let (n, side) = (grid.cells, grid.side);
                        let mut law = ObliqueBem3d::new(z, (n, n), (side, side), (e, g), mu, 1e-8)?;
                        let (periods, steps) = (self.periods_3d, self.steps_3d);
                        self.ring(&mut law, d0, wave, (k_t, period), (periods, steps))
                    })
                    .ctx(format!(
                        "3D in the loop under the normal wave at {f} omega_t"
                    ))?,
                ),
                None => None,
            };
            runs.push((f, sm, s3));
        }
        Ok(runs)
    }

    /// The normal wave's tables and figures: each frequency's cycles by MRD (and in 3D),
    /// their loss against the held approach's at the same amplitude, and the 3D run
    /// against MRD's cycle by cycle.
    pub(super) fn report_waves(
        &self,
        out: &mut Section,
        w: &NormalWave,
        (held_run, runs): (&[Sample], &[WaveRun]),
        (g, a, period): (f64, f64, f64),
    ) -> Result<()> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let with_3d = self.cells_3d > 0;
        let motion = format!(
            "approach d0 (1 + {} sin(f omega_t t + {})) about Hertz's d0 of F_N = {fn_}, omega_t = sqrt(k_t / m) = {:.6e}; released at rest from {} mu F_N (virgin loading at the approach of t = 0); mu = {mu}, G* = {g}",
            w.amplitude,
            w.phase,
            2.0 * PI / period,
            self.amplitude
        );
        let mut summary = self.wave_summary(&motion);
        let mut cycles_m = Vec::new();
        let mut cycles_3 = Vec::new();
        // Summed losses over summed held losses: the large cycles weigh most (a cycle's
        // ratio grows without bound as its amplitude falls under a wave).
        let held = |rows: &[Vec<f64>]| {
            rows.iter().map(|r| r[3]).sum::<f64>() / rows.iter().map(|r| r[4]).sum::<f64>()
        };
        let (mut amp_dev, mut loss_dev, mut held_dev) = (0.0f64, 0.0f64, 0.0f64);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut history = Figure::new(
            "ring_down_wave",
            "Ring-down under an oscillating normal approach: tangential force, MRD and 3D in the loop",
            "time over the stick period t / T [1]",
            "tangential force over mu F_N [1]",
        );
        let end = if with_3d {
            self.periods_3d
        } else {
            self.periods
        } as f64
            * period;
        // A run's tangential force over mu F_N against t / T, up to the time `end`.
        let force = |s: &[Sample], end: f64| -> Vec<(f64, f64)> {
            let kept = s.iter().filter(|p| p.t <= end);
            kept.map(|p| (p.t / period, p.force / (mu * fn_))).collect()
        };
        for (k, (f, sm, s3)) in runs.iter().enumerate() {
            let rows = self.cycles(sm, (g, a, period));
            if rows.is_empty() {
                out.failures.push(format!(
                    "MRD under the normal wave at {f} omega_t made no full cycle"
                ));
                continue;
            }
            let mut row = vec![*f, rows.len() as f64, held(&rows)];
            lo = lo.min(row[2]);
            hi = hi.max(row[2]);
            history = history.with(
                Series::new(format!("MRD, f = {f} omega_t"), force(sm, end), Style::Line)
                    .colored(k)
                    .thin(),
            );
            if let Some(s3) = s3 {
                let rows3 = self.cycles(s3, (g, a, period));
                if rows3.is_empty() {
                    out.failures.push(format!(
                        "the 3D run under the normal wave at {f} omega_t made no full cycle"
                    ));
                    continue;
                }
                let (mut amp, mut loss) = (0.0f64, 0.0f64);
                for (r3, rm) in rows3.iter().zip(&rows) {
                    amp = amp.max((r3[2] / rm[2] - 1.0).abs());
                    loss = loss.max((r3[3] / rm[3] - 1.0).abs());
                }
                let same = rows3.len().min(rows.len());
                let (w3, wm) = (held(&rows3), held(&rows[..same]));
                row.extend([rows3.len() as f64, w3, wm, amp, loss]);
                held_dev = held_dev.max((w3 / wm - 1.0).abs());
                amp_dev = amp_dev.max(amp);
                loss_dev = loss_dev.max(loss);
                history = history.with(
                    Series::new(
                        format!("3D, f = {f} omega_t"),
                        force(s3, f64::INFINITY),
                        Style::Dashed,
                    )
                    .colored(k),
                );
                cycles_3.extend(rows3.into_iter().map(|r| [vec![*f], r].concat()));
            }
            cycles_m.extend(rows.into_iter().map(|r| [vec![*f], r].concat()));
            summary.push(row);
        }
        if summary.rows.is_empty() {
            return Ok(());
        }
        history = history.with(
            Series::new("MRD, held approach", force(held_run, end), Style::Line)
                .colored(runs.len())
                .thin(),
        );
        out.scalar("normal_wave_loss_over_held_mrd_min", lo);
        out.scalar("normal_wave_loss_over_held_mrd_max", hi);
        if with_3d {
            out.scalar("normal_wave_amplitude_max_rel_dev_3d_vs_mrd", amp_dev);
            out.scalar("normal_wave_loss_per_cycle_max_rel_dev_3d_vs_mrd", loss_dev);
            out.scalar("normal_wave_loss_over_held_max_rel_dev_3d_vs_mrd", held_dev);
        }
        let ratio = Self::wave_ratio_figure(runs, &cycles_m, &cycles_3);
        out.tables.push(summary);
        for (name, who, rows) in [
            ("cycles_wave", "MRD", cycles_m),
            ("cycles_wave_3d", "3D", cycles_3),
        ] {
            if rows.is_empty() {
                continue;
            }
            out.tables.push(Self::cycles_table(
                name,
                who,
                &["normal frequency over omega_t [1]"],
                rows,
                format!("{motion}; {who} in the loop; the Mindlin-Deresiewicz columns are the held approach's loss at the cycle's force amplitude, and their ratio the loss over the held approach's"),
            ));
        }
        out.figures.push(history);
        out.figures.push(ratio);
        Ok(())
    }

    /// The normal wave's summary table, one row per frequency (its columns without the
    /// 3D run's where there is none).
    fn wave_summary(&self, motion: &str) -> Table {
        let with_3d = self.cells_3d > 0;
        let mut columns = vec![
            "normal frequency over omega_t [1]".to_string(),
            "cycles, MRD [count]".into(),
            "loss over the held approach's, MRD [1]".into(),
        ];
        if with_3d {
            columns.extend([
                "cycles, 3D [count]".into(),
                "loss over the held approach's, 3D [1]".into(),
                "loss over the held approach's, MRD over the 3D run's cycles [1]".into(),
                "force amplitude max rel dev 3D vs MRD [1]".into(),
                "loss per cycle max rel dev 3D vs MRD [1]".into(),
            ]);
        }
        let names: Vec<&str> = columns.iter().map(String::as_str).collect();
        let mut summary = Table::new("normal_wave", &names);
        summary.notes.push(format!(
            "{motion}; the loss over the held approach's: the cycles' losses (slip energy between turning points two apart) summed, over the sum of Mindlin-Deresiewicz's losses at each cycle's force amplitude (the mean of its three extremes; MRD's held run meets them, table cycles), so the largest cycles weigh most; MRD {} springs at {} steps per period for {} periods{}",
            self.springs,
            self.steps,
            self.periods,
            if with_3d {
                format!(
                    "; 3D: the pressure solved at every step (dynamics' oblique law), {0}^2 cells over {SIDE_3D} contact radii, {1} steps per period for {2} periods, compared with MRD's first cycles",
                    self.cells_3d, self.steps_3d, self.periods_3d
                )
            } else {
                String::new()
            }
        ));
        summary
    }

    /// Each cycle's loss over the held approach's against its force amplitude, every
    /// frequency, by MRD and (where there are rows) in 3D; `cycles_*`: the cycles
    /// tables' rows (the frequency first).
    fn wave_ratio_figure(runs: &[WaveRun], cycles_m: &[Vec<f64>], cycles_3: &[Vec<f64>]) -> Figure {
        // Cycle by cycle against the amplitude: every frequency, both methods.
        let (x0, x1) = cycles_m
            .iter()
            .chain(cycles_3)
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), r| {
                (lo.min(r[3]), hi.max(r[3]))
            });
        let mut ratio = Figure::new(
            "normal_wave",
            "Loss per cycle over the held approach's at the same amplitude, under a normal wave",
            "force amplitude over mu F_N [1]",
            "loss per cycle over the held approach's [1]",
        )
        .plot(
            "held approach (Mindlin-Deresiewicz)",
            vec![(x0, 1.0), (x1, 1.0)],
            Style::Line,
        );
        ratio.log_x = true;
        ratio.log_y = true;
        for (k, (f, _, _)) in runs.iter().enumerate() {
            let of = |rows: &[Vec<f64>]| -> Vec<(f64, f64)> {
                let here = rows.iter().filter(|r| r[0] == *f);
                here.map(|r| (r[3], r[6])).collect()
            };
            ratio = ratio.with(
                Series::new(
                    format!("MRD, f = {f} omega_t"),
                    of(cycles_m),
                    Style::Markers,
                )
                .colored(k + 1),
            );
            if !cycles_3.is_empty() {
                ratio = ratio.with(
                    Series::new(format!("3D, f = {f} omega_t"), of(cycles_3), Style::Crosses)
                        .colored(k + 1),
                );
            }
        }
        ratio
    }
}
