//! `forced_resonance`: a rough interface driven through its resonance (Section 12: the
//! contact resonance under a superposed harmonic normal force): a mass on a
//! rough circular punch under a static preload F0 and a harmonic force F1 cos(Omega t),
//! with a viscous dashpot, the contact evaluated at every step by MRD's rough lines
//! (C1D = lambda q C2D, Eq. 76) and by the 3D boundary-element solve of the punch
//! (warm-started). The forcing frequency is stepped up through the resonance and back
//! down, each frequency started from the state the last one ended in, and the
//! steady-state amplitude is measured at each.
//!
//! At small forcing the response is the linear oscillator's on the contact stiffness
//! k(F0): `A = F1 / sqrt((k - m Omega^2)^2 + (c Omega)^2)`, checked for each method with
//! its own k. At larger forcing the contact softens as the amplitude grows, the peak
//! bends to lower frequencies, and where the amplitude reaches the static approach the
//! contact opens for part of each period: the upward and the downward sweeps part (the
//! jump phenomenon of a softening oscillator). MRD's curves against the 3D ones: the
//! upward sweep's peak (frequency and amplitude), the largest gap between the sweeps,
//! and the local log slope d ln F / d ln d at the preload that scales the amplitudes.
//!
//! Set-up: `experiment::punch_loop` (units of the punch diameter L, E* = 1; the mass 1).
//! Each run (a face or a line) is put in the units of its own linearisation: its static
//! approach d0 and stiffness k at F0, `omega0 = sqrt(k / m)`, a dashpot of the same
//! damping ratio zeta (`c = 2 zeta m omega0`), forcing frequencies that are the same
//! multiples of omega0, amplitudes over d0. Every run is then the same problem but for the
//! nonlinearity of its contact law (how its stiffness changes with the approach, and where
//! it opens), which is what MRD must reproduce here; how far MRD's omega0 lies from the 3D
//! one is `contact_resonance`'s measure. Velocity Verlet at `steps` steps per period
//! 2 pi / omega0; at each frequency periods of the forcing are run one by one until the
//! amplitude (half the range of the approach over a period) settles; the time open is the
//! share of the last period's steps without contact force.

use crate::checks::{bad, count_in, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::punch_loop::{
    calibrated, check_preload, default_lines, default_preload, face_law, line_law, rms_on,
    static_stiffness, synthesise, CELLS,
};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use dynamics::integrate::{Axis, Oscillator, Stop};
use dynamics::ContactLaw;
use mrd::rough_contact::Stat;
use rayon::prelude::*;
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForcedResonance {
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// Bandwidth B = L / lambda_min of the face (the grid has 8 B cells a side).
    #[serde(default = "default_bandwidth")]
    bandwidth: usize,
    /// The preload as a reduced force F0 / (E* h L).
    #[serde(default = "default_preload")]
    preload: f64,
    /// Amplitudes F1 of the harmonic force, over the preload F0; the first, small, is
    /// checked against the linear oscillator.
    #[serde(default = "default_forcing")]
    forcing: Vec<f64>,
    /// Damping ratio zeta of the dashpot at the 3D small-amplitude frequency, in
    /// (0, 1).
    #[serde(default = "default_damping")]
    damping: f64,
    /// The lowest and highest forcing frequency, over the 3D small-amplitude frequency.
    #[serde(default = "default_band")]
    frequency_band: [f64; 2],
    /// Forcing frequencies of each sweep, evenly spaced over the band.
    #[serde(default = "default_frequencies")]
    frequencies: usize,
    /// MRD lines, each in its own loop (mean and 95 % interval).
    #[serde(default = "default_lines")]
    lines: usize,
    /// 3D punch faces, each in its own loop (mean and 95 % interval; one: no interval).
    #[serde(default = "default_realisations_3d")]
    realisations_3d: usize,
    /// lambda of Eq. (76) for the lines (a number, "pi", "cut", "calibrated" or a
    /// table's path); default "calibrated".
    #[serde(default = "calibrated")]
    lambda: LambdaSpec,
    /// Settling at each frequency: the forcing's periods are run one by one until the
    /// amplitude of one period differs from the last one's by at most this fraction of
    /// it (after at least three periods); the last period's amplitude is the steady one.
    #[serde(default = "default_settle_tolerance")]
    settle_tolerance: f64,
    /// The most periods run at one frequency; a frequency that reaches it unsettled is
    /// counted in the summary (`unsettled_3d`, `unsettled_mrd`).
    #[serde(default = "default_max_periods")]
    max_periods: usize,
    /// Time steps per period 2 pi / omega0 (each run's own).
    #[serde(default = "default_steps")]
    steps: usize,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_bandwidth() -> usize {
    4
}
fn default_forcing() -> Vec<f64> {
    vec![0.005, 0.05, 0.15]
}
fn default_damping() -> f64 {
    0.05
}
fn default_band() -> [f64; 2] {
    [0.6, 1.2]
}
fn default_frequencies() -> usize {
    25
}
fn default_realisations_3d() -> usize {
    2
}
fn default_settle_tolerance() -> f64 {
    1e-3
}
fn default_max_periods() -> usize {
    80
}

/// Periods at each frequency before the settling test may stop.
const MIN_PERIODS: usize = 3;
fn default_steps() -> usize {
    100
}

/// The steady state at one forcing frequency.
#[derive(Debug, Clone, Copy)]
struct Steady {
    amplitude: f64,
    /// Share of the last period's steps without contact force.
    open: f64,
    /// Periods run, and whether the settling test passed within them.
    periods: usize,
    settled: bool,
}

/// One method's run (a face or a line): its static approach and stiffness at F0, and per
/// forcing level its upward and downward sweeps.
struct Run {
    approach: f64,
    stiffness: f64,
    sweeps: Vec<[Vec<Steady>; 2]>,
}

impl Output for ForcedResonance {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if !(0.0..=1.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [0, 1]", self.hurst));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=32)?;
        count_in("lines", self.lines as u64, 2..=1000)?;
        count_in("realisations_3d", self.realisations_3d as u64, 1..=100)?;
        count_in("frequencies", self.frequencies as u64, 3..=1000)?;
        count_in(
            "max_periods",
            self.max_periods as u64,
            MIN_PERIODS as u64..=100_000,
        )?;
        if !(self.settle_tolerance > 0.0 && self.settle_tolerance < 1.0) {
            return bad(format!(
                "settle_tolerance = {} must lie in (0, 1)",
                self.settle_tolerance
            ));
        }
        count_in("steps", self.steps as u64, 20..=100_000)?;
        check_preload(self.preload)?;
        if self.forcing.is_empty()
            || self
                .forcing
                .iter()
                .any(|f| !(f.is_finite() && *f > 0.0 && *f <= 1.0))
        {
            return bad(format!(
                "forcing = {:?}: give harmonic force amplitudes over the preload, in (0, 1]",
                self.forcing
            ));
        }
        if !(self.damping > 0.0 && self.damping < 1.0) {
            return bad(format!(
                "damping = {} must lie in (0, 1) (the damping ratio)",
                self.damping
            ));
        }
        let [lo, hi] = self.frequency_band;
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi > lo && hi <= 10.0) {
            return bad(format!(
                "frequency_band = {:?}: give [lowest, highest] over the small-amplitude frequency, 0 < lowest < highest <= 10",
                self.frequency_band
            ));
        }
        LambdaSpec::check_all(std::slice::from_ref(&self.lambda), ctx, &[self.hurst])?;
        crate::checks::check_tolerance(self.tolerance)?;
        let g = CELLS * self.bandwidth;
        crate::checks::check_memory(
            (g * g) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("a {g} x {g} punch"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Dynamics3d, Stage::Dynamics]
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let lambda =
            LambdaSpec::at_hurst(std::slice::from_ref(&self.lambda), env.ctx, self.hurst)?[0];
        let counts = (self.realisations_3d, self.lines);
        let (faces, lines) = out
            .stage(Stage::RoughSynthesis, || {
                synthesise(self.hurst, self.bandwidth, lambda, counts, self.seed)
            })
            .ctx("rough surfaces")?;
        let g = CELLS * self.bandwidth;
        // One preload for every method: the faces' mean rms height times the reduced force.
        let rms = faces.iter().map(|f| rms_on(&f.0, &f.1)).sum::<f64>() / faces.len() as f64;
        let f0 = self.preload * rms;
        let three = out
            .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Run>> {
                faces
                    .par_iter()
                    .map(|(h, mask, full)| {
                        let mut law = face_law((h, mask), g, self.tolerance)?;
                        self.sweeps(&mut law, f0, *full)
                    })
                    .collect()
            })
            .ctx("3D in the loop")?;
        let full = faces.iter().map(|f| f.2).fold(f64::INFINITY, f64::min);
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Run>> {
                lines
                    .par_iter()
                    .map(|z| self.sweeps(&mut line_law(z)?, f0, full))
                    .collect()
            })
            .ctx("MRD in the loop")?;
        self.report(out, &three, &mrd, (f0, lambda));
        Ok(())
    }
}

impl ForcedResonance {
    /// The forcing frequencies of the upward sweep, over omega0.
    fn ladder(&self) -> Vec<f64> {
        let [lo, hi] = self.frequency_band;
        let n = self.frequencies;
        (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect()
    }

    /// One run's static state at F0 and its sweeps at every forcing level, in the units
    /// of its own linearisation (module docs): up through the ladder from rest at the
    /// static approach, then down from where it ended.
    fn sweeps(&self, law: &mut dyn ContactLaw, f0: f64, full: f64) -> dynamics::Result<Run> {
        let d0 = law.approach_at(f0)?;
        let stiffness = static_stiffness(law, d0)?;
        let omega0 = stiffness.sqrt();
        let up = self.ladder();
        let down: Vec<f64> = up.iter().rev().copied().collect();
        let mut sweeps = Vec::with_capacity(self.forcing.len());
        for &level in &self.forcing {
            let mut state = (d0, 0.0);
            let mut pair = [vec![], vec![]];
            for (k, ladder) in [&up, &down].into_iter().enumerate() {
                for &w in ladder {
                    let (steady, end) =
                        self.steady(law, (f0, level * f0), w * omega0, omega0, state, full)?;
                    pair[k].push(steady);
                    state = end;
                }
            }
            sweeps.push(pair);
        }
        Ok(Run {
            approach: d0,
            stiffness,
            sweeps,
        })
    }

    /// Periods of the forcing `f0 + f1 cos(omega t)` from `start` (approach, speed), one
    /// by one, until the amplitude settles (module docs; each period a whole one, so the
    /// next starts in phase); the steady state and the end state.
    fn steady(
        &self,
        law: &mut dyn ContactLaw,
        (f0, f1): (f64, f64),
        omega: f64,
        omega0: f64,
        start: (f64, f64),
        full: f64,
    ) -> dynamics::Result<(Steady, (f64, f64))> {
        let drive = move |t: f64| f0 + f1 * (omega * t).cos();
        let step = 2.0 * PI / omega0 / self.steps as f64;
        let osc = Oscillator {
            mass: 1.0,
            damping: 2.0 * self.damping * omega0,
            drive: &drive,
            axis: Axis::Normal { tangential: 0.0 },
            dt: step,
            dt_min: step / 100.0,
            max_jump: 0.2,
            force_scale: f0 + f1,
        };
        let period = 2.0 * PI / omega;
        // A start beyond full contact (a face's whole disc touching) is held at it.
        let mut state = (start.0.min(full), start.1);
        let mut last = f64::NAN;
        for k in 1..=self.max_periods {
            let (s, _) = osc.run(law, state, Stop::At(period), 1)?;
            let (lo, hi) = s
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                    (a.min(s.x), b.max(s.x))
                });
            let amplitude = 0.5 * (hi - lo);
            let end = s[s.len() - 1];
            state = (end.x, end.v);
            let settled = (amplitude - last).abs() <= self.settle_tolerance * amplitude;
            if (k >= MIN_PERIODS && settled) || k == self.max_periods {
                let open = s.iter().filter(|s| s.normal == 0.0).count() as f64;
                let steady = Steady {
                    amplitude,
                    open: open / s.len() as f64,
                    periods: k,
                    settled,
                };
                return Ok((steady, state));
            }
            last = amplitude;
        }
        unreachable!("max_periods >= {MIN_PERIODS} (validated)")
    }

    /// A run's linear steady amplitude over its d0 at the forcing `f1` (over F0) and the
    /// frequency `w` (over its omega0): `(F1 / (k d0)) / sqrt((1 - w^2)^2 + (2 zeta w)^2)`.
    fn linear(&self, r: &Run, f0: f64, f1: f64, w: f64) -> f64 {
        let static_amplitude = f1 * f0 / (r.stiffness * r.approach);
        static_amplitude / ((1.0 - w * w).powi(2) + (2.0 * self.damping * w).powi(2)).sqrt()
    }

    fn report(&self, out: &mut Section, three: &[Run], mrd: &[Run], (f0, lambda): (f64, f64)) {
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
