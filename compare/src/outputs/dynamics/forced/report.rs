//! `forced_resonance`'s report: the response table of both sweeps at every forcing, its
//! scalars against the linear oscillator and between the sweeps, the response figures.

use super::*;

impl ForcedResonance {
    pub(super) fn report(
        &self,
        out: &mut Section,
        three: &[Run],
        mrd: &[Run],
        (f0, lambda): (f64, f64),
    ) {
        let ladder = self.ladder();
        let stat = |v: Vec<f64>| {
            let s = Stat::of(&v);
            (s.mean, if v.len() > 1 { s.ci95 } else { 0.0 })
        };
        let mut t = Table::new(
            "response",
            &[
                "forcing F1 / F0 [1]",
                "sweep [0 up, 1 down]",
                "frequency over the run's omega0 [1]",
                "amplitude 3D over the run's d0, mean [1]",
                "amplitude 3D ci95 [1]",
                "amplitude MRD over the run's d0, mean [1]",
                "amplitude MRD ci95 [1]",
                "time open 3D, mean [1]",
                "time open MRD, mean [1]",
                "linear amplitude over d0, 3D mean [1]",
                "linear amplitude over d0, MRD mean [1]",
            ],
        );
        t.notes.push(format!(
            "steady forced normal vibration of a unit mass on a rough punch (H = {}, bandwidth {}, {} cells a side) under the preload F0 = {} E* h L = {f0:.4e} and F1 cos(Omega t); each run (a 3D face or an MRD line) in the units of its own linearisation: d0 and k its static approach and stiffness at F0, omega0 = sqrt(k / m), a dashpot c = 2 zeta m omega0 (zeta = {}), Omega and {} steps per period 2 pi / omega0 in those units; 3D: {} faces, each in its own loop (warm-started); MRD: {} rough lines (C1D = lambda q C2D, lambda = {lambda:.4}), each in its own loop; each sweep steps the frequency over {} values, each started from the last one's end (the down sweep from the up sweep's) and run period by period until one period's amplitude (half the range of the approach) is within {:e} of the last one's (at least {MIN_PERIODS}, at most {} periods); intervals 95 % over faces and lines (0 with one face); the linear amplitude (F1 / (k d0)) / sqrt((1 - w^2)^2 + (2 zeta w)^2), averaged over the runs",
            self.hurst, self.bandwidth, CELLS * self.bandwidth, self.preload, self.damping, self.steps, self.realisations_3d, self.lines, self.frequencies, self.settle_tolerance, self.max_periods
        ));
        for (level, &f) in self.forcing.iter().enumerate() {
            for sweep in 0..2 {
                for j in 0..ladder.len() {
                    // The down sweep's j-th frequency is the ladder's j-th from the top.
                    let w = ladder[if sweep == 0 { j } else { ladder.len() - 1 - j }];
                    let at = |runs: &[Run], q: &dyn Fn(&Run, &Steady) -> f64| -> Vec<f64> {
                        runs.iter()
                            .map(|r| q(r, &r.sweeps[level][sweep][j]))
                            .collect()
                    };
                    let amplitude = |r: &Run, s: &Steady| s.amplitude / r.approach;
                    let open = |_: &Run, s: &Steady| s.open;
                    let linear = |r: &Run, _: &Steady| self.linear(r, f0, f, w);
                    let (a3, c3) = stat(at(three, &amplitude));
                    let (a1, c1) = stat(at(mrd, &amplitude));
                    t.push(vec![
                        f,
                        sweep as f64,
                        w,
                        a3,
                        c3,
                        a1,
                        c1,
                        stat(at(three, &open)).0,
                        stat(at(mrd, &open)).0,
                        stat(at(three, &linear)).0,
                        stat(at(mrd, &linear)).0,
                    ]);
                }
            }
        }
        self.scalars(out, (three, mrd), &ladder, f0);
        self.figures(out, &t);
        out.tables.push(t);
    }

    /// The linear check at the smallest forcing, each sweep's peak, and where the sweeps
    /// part, per method; MRD's against the 3D ones.
    fn scalars(&self, out: &mut Section, (three, mrd): (&[Run], &[Run]), ladder: &[f64], f0: f64) {
        let n = ladder.len();
        // Each run against the linear oscillator on its own linearisation, at the first
        // forcing: the largest deviation over both sweeps, over the run's linear peak.
        let linear_dev = |runs: &[Run]| {
            runs.iter()
                .map(|r| {
                    let lin = |w: f64| self.linear(r, f0, self.forcing[0], w);
                    let peak = ladder.iter().map(|&w| lin(w)).fold(0.0, f64::max);
                    let up = (0..n).map(|j| (0, j, ladder[j]));
                    let down = (0..n).map(|j| (1, j, ladder[n - 1 - j]));
                    up.chain(down)
                        .map(|(s, j, w)| {
                            (r.sweeps[0][s][j].amplitude / r.approach - lin(w)).abs() / peak
                        })
                        .fold(0.0, f64::max)
                })
                .fold(0.0, f64::max)
        };
        out.scalar("linear_3d_rel_dev_max", linear_dev(three));
        out.scalar("linear_mrd_rel_dev_max", linear_dev(mrd));
        // The static amplitude's scale: F1 / (k d0) = (F1 / F0) / (d ln F / d ln d) at
        // the preload, the local exponent of each contact's force-approach curve.
        for (name, runs) in [("3d", three), ("mrd", mrd)] {
            let exponent = runs.iter().map(|r| r.stiffness * r.approach / f0);
            out.scalar(
                format!("log_slope_at_preload_{name}"),
                exponent.sum::<f64>() / runs.len() as f64,
            );
        }
        let states = |runs: &[Run]| -> Vec<Steady> {
            runs.iter()
                .flat_map(|r| r.sweeps.iter().flat_map(|p| p.iter().flatten().copied()))
                .collect()
        };
        for (name, runs) in [("3d", three), ("mrd", mrd)] {
            let all = states(runs);
            let unsettled = all.iter().filter(|s| !s.settled).count();
            let periods = all.iter().map(|s| s.periods).sum::<usize>() as f64 / all.len() as f64;
            out.scalar(format!("unsettled_{name}"), unsettled as f64);
            out.scalar(format!("periods_per_frequency_{name}"), periods);
        }
        // Per forcing level, means over the runs: the upward sweep's peak (frequency and
        // amplitude over d0) and the largest gap between the two sweeps over d0 (where
        // they part: the jump).
        for (level, &f) in self.forcing.iter().enumerate() {
            let up = |r: &Run| -> Vec<f64> {
                r.sweeps[level][0]
                    .iter()
                    .map(|s| s.amplitude / r.approach)
                    .collect()
            };
            let peak = |r: &Run| {
                let a = up(r);
                let j = (0..n).fold(0, |b, j| if a[j] > a[b] { j } else { b });
                (ladder[j], a[j])
            };
            let gap = |r: &Run| {
                (0..n)
                    .map(|j| {
                        let (u, d) = (&r.sweeps[level][0][j], &r.sweeps[level][1][n - 1 - j]);
                        (u.amplitude - d.amplitude).abs() / r.approach
                    })
                    .fold(0.0, f64::max)
            };
            let mean = |runs: &[Run], q: &dyn Fn(&Run) -> f64| {
                runs.iter().map(q).sum::<f64>() / runs.len() as f64
            };
            let key = format!("forcing_{}", level + 1);
            out.scalar(format!("{key}_over_preload"), f);
            for (name, runs) in [("3d", three), ("mrd", mrd)] {
                out.scalar(
                    format!("{key}_peak_frequency_{name}"),
                    mean(runs, &|r| peak(r).0),
                );
                out.scalar(
                    format!("{key}_peak_amplitude_{name}"),
                    mean(runs, &|r| peak(r).1),
                );
                out.scalar(format!("{key}_sweeps_gap_{name}"), mean(runs, &gap));
            }
        }
    }

    /// One figure per forcing level: each method's mean amplitude against frequency, up
    /// and down, with intervals; the linear oscillator at the first level.
    fn figures(&self, out: &mut Section, t: &Table) {
        for (level, &f) in self.forcing.iter().enumerate() {
            let rows = |sweep: f64| -> Vec<&Vec<f64>> {
                t.rows
                    .iter()
                    .filter(|r| r[0] == f && r[1] == sweep)
                    .collect()
            };
            let points = |sweep: f64, col: usize| -> Vec<(f64, f64)> {
                rows(sweep).iter().map(|r| (r[2], r[col])).collect()
            };
            let bars = |sweep: f64, col: usize| -> Vec<(f64, f64, f64)> {
                rows(sweep)
                    .iter()
                    .map(|r| (r[2], r[col] - r[col + 1], r[col] + r[col + 1]))
                    .collect()
            };
            let mut fig = Figure::new(
                &format!("response_{}", level + 1),
                &format!("Forced vibration on a rough contact, F1 = {f} F0, both sweeps"),
                "forcing frequency over the run's omega0 [1]",
                "amplitude over the run's static approach d0 [1]",
            )
            .with(
                Series::new(
                    format!("3D up, mean of {} faces (95 %)", self.realisations_3d),
                    points(0.0, 3),
                    Style::Markers,
                )
                .with_bars(bars(0.0, 3)),
            )
            .with(
                Series::new("3D down", points(1.0, 3), Style::Crosses)
                    .with_bars(bars(1.0, 3))
                    .colored(0),
            )
            .with(
                Series::new(
                    format!("MRD up, mean of {} lines (95 %)", self.lines),
                    points(0.0, 5),
                    Style::Line,
                )
                .with_bars(bars(0.0, 5)),
            )
            .with(
                Series::new("MRD down", points(1.0, 5), Style::Dashed)
                    .with_bars(bars(1.0, 5))
                    .colored(2),
            );
            if level == 0 {
                fig = fig
                    .with(
                        Series::new("linear oscillator, 3D faces", points(0.0, 9), Style::Line)
                            .thin(),
                    )
                    .with(
                        Series::new("linear oscillator, MRD lines", points(0.0, 10), Style::Line)
                            .thin(),
                    );
            }
            out.figures.push(fig);
        }
    }
}
