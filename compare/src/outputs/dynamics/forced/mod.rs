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

mod report;

use crate::checks::{bad, count_in, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::punch_loop::{
    calibrated, check_preload, check_punch_memory, default_lines, default_preload, ensemble,
    face_law, line_law, static_stiffness, CELLS,
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
        check_punch_memory(g)
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Dynamics3d, Stage::Dynamics]
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let counts = (self.realisations_3d, self.lines);
        let (lambda, faces, lines, rms) = ensemble(
            out,
            env.ctx,
            (&self.lambda, self.hurst),
            self.bandwidth,
            counts,
            self.seed,
        )?;
        let g = CELLS * self.bandwidth;
        // One preload for every method: the faces' mean rms height times the reduced force.
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
}
