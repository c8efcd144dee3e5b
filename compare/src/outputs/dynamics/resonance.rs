//! `contact_resonance`: a rough interface inside a time integration (Section 12): a mass
//! on a rough circular punch under a static preload F0 vibrates freely in the normal
//! direction, the contact evaluated at every step by MRD's rough lines (C1D = lambda q
//! C2D, Eq. 76) and by the 3D boundary-element solve of the punch (warm-started). At
//! small amplitude the frequency is the contact stiffness's, `omega0 = sqrt(k(F0) / m)`
//! (Eq. 77's regime); at larger amplitudes the contact softens and, past the static
//! approach, opens for part of each period (contact loss). Per method the measured
//! small-amplitude frequency against its own k(F0), the backbone omega(A) / omega0, and
//! MRD's omega0 and backbone against the 3D ones; and the cost of one time step of each,
//! on a ladder of 3D grids with MRD lines of as many points per cell, with the fitted
//! growth of each with the grid and the grid at which their ratio reaches 1e6 (measured
//! or extrapolated: stated).
//!
//! Set-up (units of the punch diameter L and E* = 1, as the lambda study): a self-affine
//! face without roll-off (`hurst`, `bandwidth` B: wave vectors 2 pi / L to 2 pi B / L,
//! 8 cells per shortest wavelength: a grid of 8 B cells), the disc inscribed in it; the
//! preload `f0 = F0 / (E* h L)` (h the face's rms height); the mass 1; each amplitude A
//! the start's distance above the static approach d0, over the approach from first
//! contact d0; velocity Verlet at `steps` steps per small-amplitude period, `periods`
//! periods; the frequency from the mean time between upper turning points. MRD: `lines`
//! lines of 16 points per 3D cell, each in its own loop.

use crate::checks::{bad, count_in, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::punch_loop::{
    calibrated, check_preload, check_punch_memory, default_lines, default_preload, ensemble,
    face_law, line_law, rms_on, static_stiffness, synthesise, CELLS,
};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use dynamics::integrate::{Axis, Oscillator, Sample, Stop};
use dynamics::ContactLaw;
use mrd::rough_contact::Stat;
use serde::Deserialize;
use std::f64::consts::PI;
use std::time::Instant;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactResonance {
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// Bandwidth B = L / lambda_min of the face (the grid has 8 B cells a side).
    #[serde(default = "default_bandwidth")]
    bandwidth: usize,
    /// The preload as a reduced force F0 / (E* h L).
    #[serde(default = "default_preload")]
    preload: f64,
    /// Starting distances above the static approach, over the static approach.
    #[serde(default = "default_amplitudes")]
    amplitudes: Vec<f64>,
    /// MRD lines, each in its own loop (their frequencies' mean and 95 % interval).
    #[serde(default = "default_lines")]
    lines: usize,
    /// 3D punch faces, each in its own loop (mean and 95 % interval; one: no interval).
    #[serde(default = "default_realisations_3d")]
    realisations_3d: usize,
    /// lambda of Eq. (76) for the lines (a number, "pi", "cut", "calibrated" or a
    /// table's path); default "calibrated".
    #[serde(default = "calibrated")]
    lambda: LambdaSpec,
    /// Periods integrated per amplitude, and time steps per period.
    #[serde(default = "default_periods")]
    periods: usize,
    /// Time steps per small-amplitude period.
    #[serde(default = "default_steps")]
    steps: usize,
    /// Bandwidths of the cost ladder (one face each, 8 cells per shortest wavelength),
    /// time steps timed per grid.
    #[serde(default = "default_cost_bandwidths")]
    cost_bandwidths: Vec<usize>,
    /// Time steps timed per grid of the cost ladder.
    #[serde(default = "default_cost_steps")]
    cost_steps: usize,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_bandwidth() -> usize {
    8
}
fn default_amplitudes() -> Vec<f64> {
    vec![0.02, 0.3, 0.6, 0.9, 1.2, 1.6]
}
fn default_realisations_3d() -> usize {
    3
}
fn default_periods() -> usize {
    4
}
fn default_steps() -> usize {
    200
}
fn default_cost_bandwidths() -> Vec<usize> {
    vec![4, 8, 16, 32]
}
fn default_cost_steps() -> usize {
    40
}

/// One method in the loop at one amplitude.
#[derive(Debug, Clone, Copy)]
struct Vibration {
    omega: f64,
    /// Share of the time the contact was open (force 0).
    open: f64,
}

impl Output for ContactResonance {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if !(-1.0..=3.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [-1, 3]", self.hurst));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=64)?;
        count_in("lines", self.lines as u64, 2..=1000)?;
        count_in("realisations_3d", self.realisations_3d as u64, 1..=100)?;
        count_in("periods", self.periods as u64, 2..=1000)?;
        count_in("steps", self.steps as u64, 50..=100_000)?;
        count_in("cost_steps", self.cost_steps as u64, 5..=10_000)?;
        check_preload(self.preload)?;
        if self.amplitudes.is_empty()
            || self
                .amplitudes
                .iter()
                .any(|a| !(a.is_finite() && *a > 0.0 && *a <= 10.0))
        {
            return bad(format!(
                "amplitudes = {:?}: give distances above the static approach over it, in (0, 10]",
                self.amplitudes
            ));
        }
        if self.cost_bandwidths.iter().any(|b| !(2..=256).contains(b))
            || self.cost_bandwidths.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "cost_bandwidths = {:?}: give increasing bandwidths in 2..=256",
                self.cost_bandwidths
            ));
        }
        LambdaSpec::check_all(std::slice::from_ref(&self.lambda), ctx, &[self.hurst])?;
        crate::checks::check_tolerance(self.tolerance)?;
        let g = CELLS
            * self
                .bandwidth
                .max(self.cost_bandwidths.last().copied().unwrap_or(0));
        check_punch_memory(g)
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Dynamics, Stage::Dynamics3d]
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
        let full = faces.iter().map(|f| f.2).fold(f64::INFINITY, f64::min);
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Backbone>> {
                lines
                    .iter()
                    .map(|z| self.backbone(&mut line_law(z)?, f0, full))
                    .collect()
            })
            .ctx("MRD in the loop")?;
        let three = out
            .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Backbone>> {
                faces
                    .iter()
                    .map(|(h, mask, full)| {
                        let mut law = face_law((h, mask), g, self.tolerance)?;
                        self.backbone(&mut law, f0, *full)
                    })
                    .collect()
            })
            .ctx("3D in the loop")?;
        self.report(out, &three, &mrd, lambda);
        let cost = out
            .stage(Stage::Dynamics3d, || self.cost_ladder(lambda))
            .ctx("cost ladder")?;
        report_cost(out, &cost);
        Ok(())
    }
}

/// A method's small-amplitude frequency from its own stiffness at the preload and its
/// vibrations at each amplitude.
struct Backbone {
    omega_static: f64,
    runs: Vec<Vibration>,
}

impl ContactResonance {
    /// The static approach carrying `f0`, the stiffness there (a centred difference of
    /// two static solves 1e-4 of the approach apart), and the vibration at each amplitude.
    fn backbone(&self, law: &mut dyn ContactLaw, f0: f64, full: f64) -> dynamics::Result<Backbone> {
        let d0 = law.approach_at(f0)?;
        let omega_static = static_stiffness(law, d0)?.sqrt();
        let period = 2.0 * PI / omega_static;
        let runs = self
            .amplitudes
            .iter()
            .map(|&a| {
                let x0 = (d0 * (1.0 + a)).min(full);
                let drive = move |_t: f64| f0;
                let osc = Oscillator {
                    mass: 1.0,
                    damping: 0.0,
                    drive: &drive,
                    axis: Axis::Normal { tangential: 0.0 },
                    dt: period / self.steps as f64,
                    dt_min: period / (100.0 * self.steps as f64),
                    max_jump: 0.2,
                    force_scale: f0 * (1.0 + a),
                };
                // Until `periods` upper turning points have passed (a vibration that loses
                // contact takes longer than omega0's period), at most 20 times as long.
                let last_v = std::cell::Cell::new(0.0);
                let turns = std::cell::Cell::new(0usize);
                let until = |s: &Sample| {
                    if last_v.get() > 0.0 && s.v <= 0.0 {
                        turns.set(turns.get() + 1);
                    }
                    last_v.set(s.v);
                    turns.get() > self.periods
                };
                let stop = Stop::When {
                    until: &until,
                    t_max: 20.0 * self.periods as f64 * period,
                };
                let (s, _) = osc.run(law, (x0, 0.0), stop, 1)?;
                Ok(Vibration {
                    omega: frequency(&s),
                    open: s.iter().filter(|s| s.normal == 0.0).count() as f64 / s.len() as f64,
                })
            })
            .collect::<dynamics::Result<Vec<_>>>()?;
        Ok(Backbone { omega_static, runs })
    }

    fn report(&self, out: &mut Section, three: &[Backbone], mrd: &[Backbone], lambda: f64) {
        let mut t = Table::new(
            "backbone",
            &[
                "amplitude over the static approach [1]",
                "omega 3D over the 3D omega0, mean [1]",
                "omega 3D ci95 [1]",
                "omega MRD over the 3D omega0, mean [1]",
                "omega MRD ci95 [1]",
                "omega 3D over its own static omega0, mean [1]",
                "omega MRD over its own static omega0, mean [1]",
                "time open 3D, mean [1]",
                "time open MRD, mean [1]",
            ],
        );
        t.notes.push(format!(
            "free normal vibration of a unit mass on a rough punch (H = {}, bandwidth {}, {} cells a side) under the preload F0 = {} E* h L (h the faces' mean rms height), each amplitude the start above the static approach over the static approach; 3D: {} faces, each in its own loop (warm-started); MRD: {} rough lines (C1D = lambda q C2D, lambda = {lambda:.4}), each in its own loop; omega from the mean time between upper turning points over {} periods at {} steps per small-amplitude period; omega0 = sqrt(k(F0) / m), k from two static solves 1e-4 of the approach apart; the 3D omega0 the faces' mean; intervals 95 % over faces and lines (0 with one face)",
            self.hurst, self.bandwidth, CELLS * self.bandwidth, self.preload, self.realisations_3d, self.lines, self.periods, self.steps
        ));
        let w3 = Stat::of(&three.iter().map(|b| b.omega_static).collect::<Vec<_>>()).mean;
        let stat = |v: Vec<f64>| {
            let s = Stat::of(&v);
            (s.mean, if v.len() > 1 { s.ci95 } else { 0.0 })
        };
        for (i, a) in self.amplitudes.iter().enumerate() {
            let (m3, c3) = stat(three.iter().map(|b| b.runs[i].omega / w3).collect());
            let (m1, c1) = stat(mrd.iter().map(|b| b.runs[i].omega / w3).collect());
            let own3 = stat(
                three
                    .iter()
                    .map(|b| b.runs[i].omega / b.omega_static)
                    .collect(),
            )
            .0;
            let own1 = stat(
                mrd.iter()
                    .map(|b| b.runs[i].omega / b.omega_static)
                    .collect(),
            )
            .0;
            let open3 = stat(three.iter().map(|b| b.runs[i].open).collect()).0;
            let open1 = stat(mrd.iter().map(|b| b.runs[i].open).collect()).0;
            t.push(vec![*a, m3, c3, m1, c1, own3, own1, open3, open1]);
        }
        // The small-amplitude frequency: each method against its own k(F0), and MRD's
        // against the 3D one.
        let dev = |b: &[Backbone]| {
            b.iter()
                .map(|b| (b.runs[0].omega / b.omega_static - 1.0).abs())
                .fold(0.0, f64::max)
        };
        out.scalar("omega0_3d_rel_dev_from_static_stiffness_max", dev(three));
        out.scalar("omega0_mrd_rel_dev_from_static_stiffness_max", dev(mrd));
        let mrd0 = Stat::of(&mrd.iter().map(|b| b.omega_static / w3).collect::<Vec<_>>());
        out.scalar("omega0_mrd_over_3d", mrd0.mean);
        out.scalar("omega0_mrd_over_3d_ci95", mrd0.ci95);
        let last = t.rows.len() - 1;
        out.scalar("omega_largest_amplitude_over_omega0_3d", t.rows[last][1]);
        out.scalar("omega_largest_amplitude_over_omega0_mrd", t.rows[last][3]);
        let band = |col: usize, ci: usize| -> Vec<(f64, f64, f64)> {
            t.rows
                .iter()
                .map(|r| (r[0], r[col] - r[ci], r[col] + r[ci]))
                .collect()
        };
        let fig = Figure::new(
            "backbone",
            "Free vibration on a rough contact: frequency against amplitude (3D and MRD in the loop)",
            "amplitude over the static approach [1]",
            "frequency over the 3D small-amplitude omega0 [1]",
        )
        .with(
            crate::report::Series::new(
                format!("3D in the loop, mean of {} faces (95 % interval)", self.realisations_3d),
                t.rows.iter().map(|r| (r[0], r[1])).collect(),
                Style::Markers,
            )
            .with_bars(band(1, 2)),
        )
        .with(
            crate::report::Series::new(
                format!("MRD in the loop, mean of {} lines (95 % interval)", self.lines),
                t.rows.iter().map(|r| (r[0], r[3])).collect(),
                Style::Line,
            )
            .with_bars(band(3, 4)),
        );
        out.tables.push(t);
        out.figures.push(fig);
    }

    /// Seconds per time step of each method on faces of each cost bandwidth: a small
    /// vibration (amplitude 0.1) of `cost_steps` steps, warm-started.
    fn cost_ladder(&self, lambda: f64) -> dynamics::Result<Vec<(usize, f64, f64, f64)>> {
        self.cost_bandwidths
            .iter()
            .map(|&band| {
                let g = CELLS * band;
                let (mut faces, lines) = synthesise(self.hurst, band, lambda, (1, 1), self.seed)?;
                let (h, mask, full) = faces.remove(0);
                let f0 = self.preload * rms_on(&h, &mask);
                let mut law3 = face_law((&h, &mask), g, self.tolerance)?;
                let mut law1 = line_law(&lines[0])?;
                let time = |law: &mut dyn ContactLaw| -> dynamics::Result<(f64, f64)> {
                    let d0 = law.approach_at(f0)?;
                    let drive = move |_t: f64| f0;
                    let osc = Oscillator {
                        mass: 1.0,
                        damping: 0.0,
                        drive: &drive,
                        axis: Axis::Normal { tangential: 0.0 },
                        dt: 1e-3,
                        dt_min: 1e-3,
                        max_jump: 1e300,
                        force_scale: f0,
                    };
                    // A step of a twentieth of a small vibration's period.
                    let period = 2.0 * PI / static_stiffness(law, d0)?.sqrt();
                    let osc = Oscillator {
                        dt: period / 20.0,
                        dt_min: period / 20.0,
                        ..osc
                    };
                    let x0 = (1.1 * d0).min(full);
                    let t0 = Instant::now();
                    let (s, c) = osc.run(
                        law,
                        (x0, 0.0),
                        Stop::At(self.cost_steps as f64 * period / 20.0),
                        1,
                    )?;
                    let it: usize = s.iter().map(|s| s.iterations).sum();
                    let n = c.accepted.max(1) as f64;
                    Ok((t0.elapsed().as_secs_f64() / n, it as f64 / n))
                };
                let (t3, it3) = time(&mut law3)?;
                let (t1, _) = time(&mut law1)?;
                Ok((g, t3, t1, it3))
            })
            .collect()
    }
}

/// The mean time between upper turning points (velocity from + to -) gives omega; NaN
/// with fewer than two.
fn frequency(s: &[Sample]) -> f64 {
    let turns: Vec<f64> = s
        .windows(2)
        .filter(|w| w[0].v > 0.0 && w[1].v <= 0.0)
        .map(|w| {
            let f = w[0].v / (w[0].v - w[1].v);
            w[0].t + f * (w[1].t - w[0].t)
        })
        .collect();
    if turns.len() < 2 {
        return f64::NAN;
    }
    let period = (turns[turns.len() - 1] - turns[0]) / (turns.len() - 1) as f64;
    2.0 * PI / period
}

/// The cost ladder's table, its fitted growth with the grid and the grid of a 1e6 ratio.
fn report_cost(out: &mut Section, cost: &[(usize, f64, f64, f64)]) {
    let mut t = Table::new(
        "cost",
        &[
            "grid [cells a side]",
            "3D seconds per step [s]",
            "MRD seconds per step (one line of 16 points per cell) [s]",
            "ratio 3D / MRD [1]",
            "3D iterations per step, mean [1]",
        ],
    );
    t.notes.push(
        "one time step of a small normal vibration (amplitude 0.1 of the static approach, a twentieth of a period per step) on a rough punch of the grid's bandwidth, 3D warm-started from the last step, MRD on one line of 16 points per 3D cell (O(log N) per step); this machine, one run each; the power laws in summary.json (cost_exponent_3d, cost_exponent_mrd in the grid side) and the grid side at which the ratio reaches 1e6 (grid_for_ratio_1e6; extrapolated beyond the ladder: grid_for_ratio_1e6_extrapolated = 1)".into(),
    );
    for &(g, t3, t1, it) in cost {
        t.push(vec![g as f64, t3, t1, t3 / t1, it]);
    }
    // Power laws in the grid side from the last two rungs.
    if cost.len() >= 2 {
        let (a, b) = (cost[cost.len() - 2], cost[cost.len() - 1]);
        let span = (b.0 as f64 / a.0 as f64).ln();
        let p3 = (b.1 / a.1).ln() / span;
        let p1 = (b.2 / a.2).ln() / span;
        out.scalar("cost_exponent_3d", p3);
        out.scalar("cost_exponent_mrd", p1);
        let ratio = b.1 / b.2;
        out.scalar("cost_ratio_at_largest_grid", ratio);
        let measured = cost.iter().find(|c| c.1 / c.2 >= 1e6).map(|c| c.0 as f64);
        match measured {
            Some(g) => {
                out.scalar("grid_for_ratio_1e6", g);
                out.scalar("grid_for_ratio_1e6_extrapolated", 0.0);
            }
            None if p3 > p1 => {
                let g = b.0 as f64 * (1e6 / ratio).powf(1.0 / (p3 - p1));
                out.scalar("grid_for_ratio_1e6", g);
                out.scalar("grid_for_ratio_1e6_extrapolated", 1.0);
            }
            None => {}
        }
    }
    let fig = Figure::new(
        "cost",
        "Cost of one time step: the 3D contact against MRD's line, by grid",
        "grid side [cells]",
        "seconds per step [s]",
    )
    .log_log()
    .plot(
        "3D, warm-started",
        cost.iter().map(|c| (c.0 as f64, c.1)).collect(),
        Style::Markers,
    )
    .plot(
        "MRD line, 16 points per cell",
        cost.iter().map(|c| (c.0 as f64, c.2)).collect(),
        Style::Crosses,
    );
    out.tables.push(t);
    out.figures.push(fig);
}
