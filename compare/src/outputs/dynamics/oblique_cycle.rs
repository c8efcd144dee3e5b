//! `oblique_cycle`: frictional damping of a sphere whose normal and tangential motion
//! oscillate together (Section 7 with the normal force oscillating too). The sphere is
//! pressed to the approach `d0` of a normal force, then moved along
//! `d0 (1 + normal_amplitude sin(wt + phase))` and `A sin(wt)`, cycle by cycle, at each
//! of the normal motion's phase leads `phases` (0: in phase); the energy
//! dissipated by slip in the last cycle against the tangential amplitude A, by MRD's
//! springs (the rule of Hess, tangential springs `G* dx` with Coulomb slip) and by the
//! 3D contact (`dynamics::ObliqueBem3d`: the normal solve at each step's approach, the
//! partial slip under that pressure, the slip carried over), beside the same cycles at a
//! held normal approach, whose energy is Mindlin and Deresiewicz's closed form
//! (`mrd::reference::mindlin_damping::dissipation_exact`, the review's Eq. 58 for any
//! nu). A normal motion in phase lets the contact carry more tangential motion in stick
//! and below an amplitude the contact shakes down: after the first cycles nothing slips;
//! out of phase the contact is loosest when the tangential motion is largest.
//!
//! The amplitudes are in units of `A_s = (2/3) mu d0 E* / G*`, the shift at which a
//! contact stuck at `d0` would carry `mu F0`.

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use dynamics::{ContactLaw, Motion, ObliqueBem3d, Springs};
use mrd::reference::{for_profile, hertz, mindlin_damping as md};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObliqueCycle {
    /// The normal force of the mean approach d0 [force].
    normal_force: f64,
    /// Coulomb's friction coefficient.
    mu: f64,
    /// The normal approach's amplitude over d0, in [0, 0.9].
    normal_amplitude: f64,
    /// The normal motion's phase leads over the tangential one [degrees], each in
    /// [-180, 180], one curve each.
    #[serde(default = "in_phase")]
    phases: Vec<f64>,
    /// Tangential amplitudes over A_s (module docs), increasing, each > 0.
    amplitudes: Vec<f64>,
    /// Cycles run (the energy is the last one's).
    #[serde(default = "default_cycles")]
    cycles: usize,
    /// Steps per cycle.
    #[serde(default = "default_steps")]
    steps: usize,
    /// MRD springs on the half line (over 1.5 contact radii at the largest approach).
    #[serde(default = "default_springs")]
    springs: usize,
    /// Cells per side of the 3D grid, over 2.5 contact radii at the largest approach
    /// (0: MRD alone).
    #[serde(default = "default_cells")]
    cells: usize,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn in_phase() -> Vec<f64> {
    vec![0.0]
}
fn default_cycles() -> usize {
    3
}
fn default_steps() -> usize {
    40
}
fn default_springs() -> usize {
    4000
}
fn default_cells() -> usize {
    48
}

/// The last cycle's slip energy of each amplitude, by one method at one normal motion.
struct Curve {
    label: String,
    /// 0: MRD, else the 3D grid's side.
    cells: usize,
    normal_amplitude: f64,
    /// The normal motion's phase lead [degrees].
    phase: f64,
    energies: Vec<f64>,
}

impl Output for ObliqueCycle {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("oblique_cycle needs a sphere (profile = paraboloid): Mindlin and Deresiewicz's loss per cycle is the reference");
        }
        let g = ctx.material.g_star().ctx("oblique_cycle")?;
        for (key, v) in [("normal_force", self.normal_force), ("mu", self.mu)] {
            if !(v.is_finite() && v > 0.0) {
                return bad(format!("{key} = {v} must be finite and > 0"));
            }
        }
        if !(0.0..=0.9).contains(&self.normal_amplitude) {
            return bad(format!(
                "normal_amplitude = {} must lie in [0, 0.9] (a fraction of the mean approach: the contact stays closed)",
                self.normal_amplitude
            ));
        }
        if self.phases.is_empty()
            || self.phases.len() > 12
            || self.phases.iter().any(|p| !(-180.0..=180.0).contains(p))
            || (1..self.phases.len()).any(|i| self.phases[..i].contains(&self.phases[i]))
        {
            return bad(format!(
                "phases = {:?}: give 1 to 12 distinct phase leads of the normal motion in [-180, 180] degrees",
                self.phases
            ));
        }
        if self.amplitudes.is_empty()
            || self.amplitudes.len() > 100
            || self
                .amplitudes
                .iter()
                .any(|a| !(a.is_finite() && *a > 0.0 && *a <= 100.0))
            || self.amplitudes.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "amplitudes = {:?}: give 1 to 100 increasing tangential amplitudes in (0, 100] (over A_s)",
                self.amplitudes
            ));
        }
        if !(2..=100).contains(&self.cycles) || !(8..=10_000).contains(&self.steps) {
            return bad(format!(
                "cycles = {} must lie in 2..=100 and steps = {} per cycle in 8..=10000",
                self.cycles, self.steps
            ));
        }
        if !(100..=1_000_000).contains(&self.springs) {
            return bad(format!(
                "springs = {} must lie in 100..=1000000",
                self.springs
            ));
        }
        let ratio = g / ctx.material.e_star;
        if self.cells != 0 && !(16..=256).contains(&self.cells) {
            return bad(format!(
                "cells = {} must lie in 16..=256 (0: MRD alone)",
                self.cells
            ));
        }
        if self.cells != 0 && !(2.0 / 3.0..=1.0).contains(&ratio) {
            return bad(format!(
                "G* / E* = {ratio}: the 3D run (cells = {}) takes one elastic body, G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5]); or set cells = 0",
                self.cells
            ));
        }
        crate::checks::check_tolerance(self.tolerance)
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        crate::experiment::impact::stages(self.cells != 0)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let (e, g) = (
            ctx.material.e_star,
            ctx.material.g_star().ctx("oblique_cycle")?,
        );
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let d0 = hertz::depth(e, r, self.normal_force);
        let a_s = 2.0 / 3.0 * self.mu * d0 * e / g;
        let reach = hertz::radius(r, d0 * (1.0 + self.normal_amplitude));
        let exact: Vec<f64> = out.stage(Stage::ClosedForm, || {
            self.amplitudes
                .iter()
                .map(|x| md::dissipation_exact(e, e / g, r, self.mu, d0, x * a_s))
                .collect()
        });
        let scale = (d0, a_s);
        let mrd = out
            .stage(Stage::Dynamics, || {
                let springs = || -> dynamics::Result<Box<dyn ContactLaw>> {
                    let law = Springs::body(&profile, e, self.springs, 1.5 * reach)?;
                    Ok(Box::new(law.with_friction(g, self.mu)?))
                };
                self.curves(format!("MRD, {} springs", self.springs), 0, scale, &springs)
            })
            .ctx("MRD cycles")?;
        let three = if self.cells == 0 {
            Vec::new()
        } else {
            out.stage(Stage::Dynamics3d, || {
                let n = self.cells;
                let side = 2.5 * reach;
                let grid = AxisymGrid {
                    cells: n,
                    side,
                    periodic: false,
                };
                let (z, _) = grid.heights(&profile);
                let three = || -> dynamics::Result<Box<dyn ContactLaw>> {
                    Ok(Box::new(ObliqueBem3d::new(
                        &z,
                        (n, n),
                        (side, side),
                        (e, g),
                        self.mu,
                        self.tolerance,
                    )?))
                };
                self.curves(format!("3D, {n}^2 cells"), n, scale, &three)
            })
            .ctx("3D cycles")?
        };
        self.report(out, &mrd, &three, &exact, a_s);
        Ok(())
    }
}

impl ObliqueCycle {
    /// The last cycle's slip energy at every amplitude, the normal approach held and
    /// oscillating at each phase lead, each run on a fresh law from `law`.
    fn curves(
        &self,
        label: String,
        cells: usize,
        (d0, a_s): (f64, f64),
        law: &dyn Fn() -> dynamics::Result<Box<dyn ContactLaw>>,
    ) -> dynamics::Result<Vec<Curve>> {
        let moving = self.phases.iter().map(|&p| (self.normal_amplitude, p));
        std::iter::once((0.0, 0.0))
            .chain(moving)
            .map(|(b, phase)| {
                let energies = self
                    .amplitudes
                    .iter()
                    .map(|x| self.cycle(law()?.as_mut(), d0, (b, phase), x * a_s))
                    .collect::<dynamics::Result<_>>()?;
                Ok(Curve {
                    label: label.clone(),
                    cells,
                    normal_amplitude: b,
                    phase,
                    energies,
                })
            })
            .collect()
    }

    /// Presses `law` to the cycle's first approach (from apart, in a quarter of a
    /// cycle's steps), then runs the cycles of normal amplitude `b d0` leading the
    /// tangential motion of amplitude `amp` by `phase` degrees; the slip energy of the
    /// last cycle.
    fn cycle(
        &self,
        law: &mut dyn ContactLaw,
        d0: f64,
        (b, phase): (f64, f64),
        amp: f64,
    ) -> dynamics::Result<f64> {
        let lead = phase.to_radians();
        let press = (self.steps / 4).max(2);
        let mut step = |normal: f64, tangential: f64| -> dynamics::Result<f64> {
            let f = law.trial(Motion {
                normal,
                tangential,
                dt: 1.0,
            })?;
            law.commit()?;
            Ok(f.dissipated)
        };
        let start = d0 * (1.0 + b * lead.sin());
        for k in 1..=press {
            step(start * k as f64 / press as f64, 0.0)?;
        }
        let mut last = 0.0;
        for c in 0..self.cycles {
            let mut w = 0.0;
            for k in 1..=self.steps {
                let angle = 2.0 * std::f64::consts::PI * k as f64 / self.steps as f64;
                w += step(d0 * (1.0 + b * (angle + lead).sin()), amp * angle.sin())?;
            }
            if c + 1 == self.cycles {
                last = w;
            }
        }
        Ok(last)
    }

    fn report(&self, out: &mut Section, mrd: &[Curve], three: &[Curve], exact: &[f64], a_s: f64) {
        let curves: Vec<&Curve> = mrd.iter().chain(three).collect();
        let mut t = Table::new(
            "oblique_cycle",
            &[
                "method [0 MRD, else 3D cells a side]",
                "normal amplitude over d0 [1]",
                "normal phase lead [degrees]",
                "tangential amplitude over A_s [1]",
                "slip energy of the last cycle over mu F0 A_s [1]",
                "Mindlin-Deresiewicz at a held normal over mu F0 A_s [1]",
            ],
        );
        let unit = self.mu * self.normal_force * a_s;
        t.notes.push(format!(
            "a sphere pressed to the approach d0 of F0 = {}, then moved along d0 (1 + b sin(wt + phase)) and A sin(wt), {} cycles of {} steps, the last cycle's slip energy; A_s = (2/3) mu d0 E* / G* = {a_s:.6e}; MRD {} springs, 3D {}^2 cells over 2.5 contact radii (solves to {:e}); Mindlin-Deresiewicz: the review's Eq. 58 for any nu at the held approach d0",
            self.normal_force, self.cycles, self.steps, self.springs, self.cells, self.tolerance
        ));
        for c in &curves {
            for ((x, w), w0) in self.amplitudes.iter().zip(&c.energies).zip(exact) {
                t.push(vec![
                    c.cells as f64,
                    c.normal_amplitude,
                    c.phase,
                    *x,
                    w / unit,
                    w0 / unit,
                ]);
            }
        }
        out.tables.push(t);
        let rel = |c: &Curve, x: usize| (c.energies[x] / exact[x] - 1.0).abs();
        // At a held normal each method against the closed form (amplitudes whose loop is
        // above a millionth of the largest one's: below, the energy is at rounding).
        let top = exact.iter().cloned().fold(0.0, f64::max);
        let resolved: Vec<usize> = (0..exact.len())
            .filter(|&x| exact[x] > 1e-6 * top)
            .collect();
        let worst = |c: &Curve| resolved.iter().map(|&x| rel(c, x)).fold(0.0f64, f64::max);
        out.scalar(
            "mrd_held_normal_max_rel_dev_vs_mindlin_deresiewicz",
            worst(&mrd[0]),
        );
        // Scalars of the moving normal at each phase lead: in phase without a suffix.
        let suffix = |p: f64| {
            if p == 0.0 {
                String::new()
            } else {
                format!("_phase_{p}")
            }
        };
        if let Some(held) = three.first() {
            out.scalar(
                "bem3d_held_normal_max_rel_dev_vs_mindlin_deresiewicz",
                worst(held),
            );
        }
        for (k, m) in mrd.iter().enumerate().skip(1) {
            // With the normal moving: 3D against MRD where MRD's loop is resolved.
            if let Some(moving) = three.get(k) {
                let top = m.energies.iter().cloned().fold(0.0, f64::max);
                let dev = (0..exact.len())
                    .filter(|&x| m.energies[x] > 1e-3 * top)
                    .map(|x| (moving.energies[x] / m.energies[x] - 1.0).abs())
                    .fold(0.0f64, f64::max);
                out.scalar(
                    format!("moving_normal_max_rel_dev_3d_vs_mrd{}", suffix(m.phase)),
                    dev,
                );
            }
            // The largest amplitude at which MRD's moving contact shakes down (no slip
            // in the last cycle); NaN where none does.
            let shakedown = self
                .amplitudes
                .iter()
                .zip(&m.energies)
                .filter(|(_, w)| **w == 0.0)
                .map(|(x, _)| *x)
                .fold(f64::NAN, f64::max);
            out.scalar(
                format!(
                    "mrd_shakedown_largest_amplitude_over_a_s{}",
                    suffix(m.phase)
                ),
                shakedown,
            );
            // How MRD's loss grows at the two smallest amplitudes: 3 at a held normal
            // (Mindlin-Deresiewicz), 2 where the moving normal locks tangential
            // displacement into the cells that enter contact; NaN where either is zero.
            if let ([x0, x1, ..], [w0, w1, ..]) =
                (self.amplitudes.as_slice(), m.energies.as_slice())
            {
                out.scalar(
                    format!("mrd_small_amplitude_loss_exponent{}", suffix(m.phase)),
                    if *w0 > 0.0 && *w1 > 0.0 {
                        (w1 / w0).ln() / (x1 / x0).ln()
                    } else {
                        f64::NAN
                    },
                );
            }
        }
        // A normal motion in opposition runs the in-phase path mirrored in the tangential
        // direction and shifted by half a period: the same steady loss (the first
        // cycles differ).
        let at = |p: f64| {
            curves
                .iter()
                .filter(move |c| c.normal_amplitude > 0.0 && c.phase == p)
        };
        let mirrored: Vec<f64> = at(0.0)
            .zip(at(180.0))
            .flat_map(|(a, b)| {
                a.energies.iter().zip(&b.energies).map(|(x, y)| {
                    if *x > 0.0 {
                        (y / x - 1.0).abs()
                    } else if *y == 0.0 {
                        0.0
                    } else {
                        f64::INFINITY
                    }
                })
            })
            .collect();
        if !mirrored.is_empty() {
            out.scalar(
                "loss_max_rel_dev_phase_180_vs_in_phase",
                mirrored.iter().cloned().fold(0.0, f64::max),
            );
        }
        out.figures.push(self.figure(&curves, exact, unit));
    }

    /// The last cycle's slip energy of every curve against the tangential amplitude.
    fn figure(&self, curves: &[&Curve], exact: &[f64], unit: f64) -> Figure {
        let mut fig = Figure::new(
            "oblique_cycle",
            &format!(
                "Slip energy per cycle, normal held and oscillating by +/- {} d0; no point: no slip",
                self.normal_amplitude
            ),
            "tangential amplitude over A_s = (2/3) mu d0 E*/G* [1]",
            "slip energy of the last cycle over mu F0 A_s [1]",
        )
        .log_log();
        let pts = |w: &[f64]| -> Vec<(f64, f64)> {
            self.amplitudes
                .iter()
                .zip(w)
                .filter(|(_, w)| **w > 0.0)
                .map(|(x, w)| (*x, w / unit))
                .collect()
        };
        for c in curves {
            // In opposition the loss is the in-phase one (mirror symmetry): drawn dashed
            // or crossed over it, so that both stay visible.
            let opposed = c.normal_amplitude > 0.0 && c.phase.abs() == 180.0;
            let what = if c.normal_amplitude == 0.0 {
                "normal held".to_string()
            } else if c.phase == 0.0 {
                "normal in phase".to_string()
            } else if opposed {
                "normal in opposition (= in phase: mirror symmetry)".to_string()
            } else {
                format!("normal leading by {} deg", c.phase)
            };
            let style = match (c.cells, c.normal_amplitude == 0.0, opposed) {
                (0, _, true) => Style::Dashed,
                (0, _, false) => Style::Line,
                (_, true, _) | (_, false, true) => Style::Crosses,
                (_, false, false) => Style::Markers,
            };
            fig = fig.plot(format!("{}, {what}", c.label), pts(&c.energies), style);
        }
        // Drawn last: on MRD's held-normal line, which it matches.
        fig = fig.plot(
            "Mindlin-Deresiewicz, normal held",
            pts(exact),
            Style::Dashed,
        );
        fig
    }
}
