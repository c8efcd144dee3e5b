//! `rough_ring_down`: frictional damping of a rough interface in time (Sections 7 and 12
//! on a rough contact): a mass held on a rough circular punch by a constant normal force
//! F0 is released from a tangential force and rings down on the contact alone, MRD's
//! rough lines with tangential springs `G* dx` and Coulomb slip (C1D = lambda q C2D,
//! Eq. 76) and the 3D partial slip of the punch (`dynamics::SlipBem3d`) each evaluated
//! at every step.
//!
//! **The closed form every run is held against.** Under a held normal force the
//! tangential problem is a difference of two normal ones (Ciavarella 1998, Jaeger 1998)
//! and its cycles follow Masing's rule, so a contact's loss per cycle at the force
//! amplitude Q* follows from its own normal curve F(d) alone
//! (`mrd::reference::masing`): exact for MRD's springs on any line, and in 3D for
//! Mindlin's model where the tangential compliance is the normal one scaled (G* = E*,
//! nu = 0, the embedded scenes' choice). Each cycle's loss in the loop is set against it
//! (each half-cycle, turning point to turning point, a Masing branch whose loss is half
//! the symmetric cycle's at half its force range), for every line and face; then MRD's
//! loss and damping ratio
//! against the 3D ones on a ladder of amplitudes, means with 95 % intervals over lines
//! and faces: MRD's frictional damping is as good as its normal curve near F0.
//!
//! Set-up: the faces and lines of `contact_resonance` (`experiment::punch_loop`: units of
//! the punch diameter L, a self-affine face of bandwidth B on 8 B cells, the disc
//! inscribed; lines of 16 points per cell); at each of the `preloads`, F0 = preload
//! E* h L (h the faces' mean rms height); the mass released at rest from `amplitude` mu F0 after a quasi-static virgin
//! loading (`experiment::ring`), velocity Verlet at `steps` steps per period of each
//! contact's initial tangential stiffness `(G* / E*) dF/dd`. The 3D faces' cells outside
//! the disc are lowered far below the face (the partial-slip law takes no mask).

mod report;

use crate::checks::{bad, count_in, default_tolerance, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::experiment::punch_loop::{
    calibrated, check_preload, check_punch_memory, default_lines, ensemble, CELLS,
};
use crate::experiment::ring::{cycles, ring, Release};
use crate::experiment::rough_punch::punch_face;
use crate::experiment::solve_options;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, Solution};
use dynamics::integrate::{Axis, Sample};
use dynamics::{ContactLaw, SlipBem3d, Springs};
use mrd::reference::masing;
use mrd::rough_contact::Stat;
use mrd::roughness::synthesis::{upsample, Grid};
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughRingDown {
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// Bandwidth B = L / lambda_min of the face (the grid has 8 B cells a side).
    #[serde(default = "default_bandwidth")]
    bandwidth: usize,
    /// The normal forces as reduced forces F0 / (E* h L), 1 to 8 of them.
    #[serde(default = "default_preloads")]
    preloads: Vec<f64>,
    /// Coulomb friction coefficient.
    mu: f64,
    /// The starting tangential force over mu F0, in (0, 1).
    #[serde(default = "default_amplitude")]
    amplitude: f64,
    /// MRD lines, each in its own loop.
    #[serde(default = "default_lines")]
    lines: usize,
    /// 3D punch faces, each in its own loop.
    #[serde(default = "default_faces")]
    realisations_3d: usize,
    /// lambda of Eq. (76) for the lines; default "calibrated".
    #[serde(default = "calibrated")]
    lambda: LambdaSpec,
    /// Periods of MRD's runs.
    #[serde(default = "default_periods")]
    periods: usize,
    /// Time steps per period of MRD's runs (of each line's initial tangential stiffness).
    #[serde(default = "default_steps")]
    steps: usize,
    /// Periods of the 3D runs.
    #[serde(default = "default_periods_3d")]
    periods_3d: usize,
    /// Time steps per period of the 3D runs.
    #[serde(default = "default_steps_3d")]
    steps_3d: usize,
    /// Seed of the faces and lines (the same seed, the same realisations).
    #[serde(default)]
    seed: u64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
    /// Also run the 3D faces on `refine_factor_3d` times the cells a side (the same
    /// faces, band-limited interpolation) and report how far the 3D losses move (table
    /// `grid_check`).
    #[serde(default)]
    refine_3d: bool,
    /// The refined grid's cells a side over the scene's (2 to 8; default 2: 16 cells per
    /// shortest wavelength); only with `refine_3d`.
    #[serde(default)]
    refine_factor_3d: Option<usize>,
}

fn default_bandwidth() -> usize {
    8
}
fn default_preloads() -> Vec<f64> {
    vec![0.03, 0.1, 0.3, 1.0]
}
fn default_amplitude() -> f64 {
    0.9
}
fn default_faces() -> usize {
    3
}
fn default_periods() -> usize {
    30
}
fn default_steps() -> usize {
    400
}
fn default_periods_3d() -> usize {
    4
}
fn default_steps_3d() -> usize {
    100
}

/// The force amplitudes (over mu F0) of the damping ladder.
const LADDER: [f64; 6] = [0.1, 0.2, 0.3, 0.5, 0.7, 0.9];

/// One line's or face's run and its own damping curve.
struct Damping {
    /// The held approach carrying F0, and the initial tangential stiffness.
    d0: f64,
    k_t: f64,
    period: f64,
    samples: Vec<Sample>,
    /// Per cycle: [time over period, Q* / (mu F0), loss, closed form, ratio].
    cycles: Vec<[f64; 5]>,
    /// Per ladder amplitude: (loss, damping ratio) of the closed form.
    ladder: Vec<(f64, f64)>,
}

impl Output for RoughRingDown {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if !(0.0..=1.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [0, 1]", self.hurst));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=32)?;
        count_in("lines", self.lines as u64, 2..=1000)?;
        count_in("realisations_3d", self.realisations_3d as u64, 1..=100)?;
        count_in("periods", self.periods as u64, 2..=10_000)?;
        count_in("steps", self.steps as u64, 50..=100_000)?;
        count_in("periods_3d", self.periods_3d as u64, 2..=1000)?;
        count_in("steps_3d", self.steps_3d as u64, 50..=10_000)?;
        if !(1..=8).contains(&self.preloads.len()) {
            return bad(format!(
                "preloads = {:?}: give 1 to 8 reduced forces F0 / (E* h L)",
                self.preloads
            ));
        }
        if let Some(p) = self.preloads.iter().find(|p| check_preload(**p).is_err()) {
            return bad(format!(
                "preloads holds {p}: each must lie in (1e-4, 10) (F0 / (E* h L))"
            ));
        }
        require_positive("mu", self.mu)?;
        if self.mu > 1e6 {
            return bad(format!("mu = {} must lie in (0, 1e6]", self.mu));
        }
        if !(self.amplitude > 0.0 && self.amplitude < 1.0) {
            return bad(format!(
                "amplitude = {} must lie in (0, 1) (a fraction of mu F0; at 1 the body slides)",
                self.amplitude
            ));
        }
        let ratio = ctx.material.g_star().ctx("rough_ring_down")? / ctx.material.e_star;
        if !(2.0 / 3.0..=1.0).contains(&ratio) {
            return bad(format!(
                "G* / E* = {ratio}: the 3D partial slip takes one elastic body, G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5]; the closed form is exact in 3D at G* = E*)"
            ));
        }
        LambdaSpec::check_all(std::slice::from_ref(&self.lambda), ctx, &[self.hurst])?;
        crate::checks::check_tolerance(self.tolerance)?;
        if let Some(k) = self.refine_factor_3d {
            if !self.refine_3d {
                return bad(format!(
                    "refine_factor_3d = {k} is set but refine_3d is false: set refine_3d = true to run the refined grid"
                ));
            }
            count_in("refine_factor_3d", k as u64, 2..=8)?;
        }
        let g = CELLS
            * self.bandwidth
            * if self.refine_3d {
                self.refine_factor()
            } else {
                1
            };
        check_punch_memory(g)
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Dynamics, Stage::Dynamics3d]
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let (e, g) = (
            ctx.material.e_star,
            ctx.material.g_star().ctx("rough_ring_down")?,
        );
        let counts = (self.realisations_3d, self.lines);
        let (lambda, faces, lines, rms) = ensemble(
            out,
            ctx,
            (&self.lambda, self.hurst),
            self.bandwidth,
            counts,
            self.seed,
        )?;
        let f0s: Vec<f64> = self.preloads.iter().map(|p| p * e * rms).collect();
        let mrd = out
            .stage(
                Stage::Dynamics,
                || -> dynamics::Result<Vec<Vec<Damping>>> {
                    f0s.iter()
                        .map(|&f0| lines.iter().map(|z| self.line(z, (e, g), f0)).collect())
                        .collect()
                },
            )
            .ctx("MRD in the loop")?;
        let three = out
            .stage(
                Stage::Dynamics3d,
                || -> dynamics::Result<Vec<Vec<Damping>>> {
                    f0s.iter()
                        .map(|&f0| {
                            faces
                                .iter()
                                .map(|(h, mask, _)| self.face(h, mask, (e, g), f0))
                                .collect()
                        })
                        .collect()
                },
            )
            .ctx("3D in the loop")?;
        self.report(out, (&mrd, &three), (e, g, rms, lambda));
        if self.refine_3d {
            let fine = out
                .stage(
                    Stage::Dynamics3d,
                    || -> dynamics::Result<Vec<Vec<Damping>>> {
                        let (n, fine) = (CELLS * self.bandwidth, self.fine_cells());
                        let faces = faces
                            .iter()
                            .map(|(h, _, _)| -> dynamics::Result<_> {
                                let h2 =
                                    upsample(h, &Grid::square(n, 1.0), &Grid::square(fine, 1.0))?;
                                let (mask, _) = punch_face(&h2, fine);
                                Ok((h2, mask))
                            })
                            .collect::<dynamics::Result<Vec<_>>>()?;
                        f0s.iter()
                            .map(|&f0| {
                                faces
                                    .iter()
                                    .map(|(h, mask)| self.face(h, mask, (e, g), f0))
                                    .collect()
                            })
                            .collect()
                    },
                )
                .ctx("3D in the loop, refined grid")?;
            self.grid_check(out, &three, &fine);
        }
        Ok(())
    }
}

impl RoughRingDown {
    /// The refined grid's cells a side over the scene's.
    fn refine_factor(&self) -> usize {
        self.refine_factor_3d.unwrap_or(2)
    }

    /// Cells a side of the refined grid.
    fn fine_cells(&self) -> usize {
        CELLS * self.bandwidth * self.refine_factor()
    }

    /// A line: its springs in the loop, its normal curve from a second copy without
    /// friction.
    fn line(&self, z: &[f64], (e, g): (f64, f64), f0: f64) -> dynamics::Result<Damping> {
        let springs = || Springs::rough_line(z, 1.0, e, PI / 4.0);
        let mut normal = springs()?;
        let mut law = springs()?.with_friction(g, self.mu)?;
        let d0 = law.approach_at(f0)?;
        let mut force = |d: f64| -> f64 {
            let f = normal.trial(dynamics::Motion {
                normal: d,
                tangential: 0.0,
                dt: 1.0,
            });
            normal.rollback();
            f.map_or(f64::NAN, |f| f.normal)
        };
        let samples = self.run_law(&mut law, d0, &mut force, (e, g), self.periods, self.steps)?;
        self.damping(samples, &mut force, (e, g, f0))
    }

    /// A face: the 3D partial slip in the loop, its normal curve from the free solve of
    /// the same heights (warm-started from the last approach).
    fn face(
        &self,
        h: &[f64],
        mask: &[bool],
        (e, g): (f64, f64),
        f0: f64,
    ) -> dynamics::Result<Damping> {
        let n = (h.len() as f64).sqrt().round() as usize;
        let inside = || h.iter().zip(mask).filter(|p| *p.1).map(|p| *p.0);
        let (lo, hi) = (
            inside().fold(f64::INFINITY, f64::min),
            inside().fold(f64::NEG_INFINITY, f64::max),
        );
        let z: Vec<f64> = h
            .iter()
            .zip(mask)
            .map(|(h, m)| if *m { *h } else { lo - 10.0 * (hi - lo) })
            .collect();
        let mut law = SlipBem3d::new(&z, (n, n), (1.0, 1.0), (e, g), self.mu, f0, self.tolerance)?;
        let d0 = law.approach();
        let op = NonPeriodicHalfSpace::try_new(n, n, 1.0, 1.0, e)?;
        let mut solver = ContactSolver::new(op, &z, None)?;
        let opts = solve_options(self.tolerance, n);
        let mut last: Option<Solution> = None;
        let mut failed: Option<bem3d::BemError> = None;
        let mut force = |d: f64| -> f64 {
            if d <= 0.0 {
                return 0.0;
            }
            match solver.solve(Load::Approach(d), &opts, last.as_ref()) {
                Ok(s) => {
                    let f = s.force;
                    last = Some(s);
                    f
                }
                Err(err) => {
                    failed.get_or_insert(err);
                    f64::NAN
                }
            }
        };
        let samples = self.run_law(
            &mut law,
            d0,
            &mut force,
            (e, g),
            self.periods_3d,
            self.steps_3d,
        )?;
        let damping = self.damping(samples, &mut force, (e, g, f0));
        match failed {
            Some(err) => Err(err.into()),
            None => damping,
        }
    }

    /// The run of `law` at the approach `d0`: the initial tangential stiffness from the
    /// normal curve's slope there, the release from `amplitude` mu F0.
    #[allow(clippy::too_many_arguments)]
    fn run_law(
        &self,
        law: &mut dyn ContactLaw,
        d0: f64,
        force: &mut dyn FnMut(f64) -> f64,
        (e, g): (f64, f64),
        periods: usize,
        steps: usize,
    ) -> dynamics::Result<(f64, f64, f64, Vec<Sample>)> {
        let h = 1e-4 * d0;
        let k_t = g / e * (force(d0 + h) - force(d0 - h)) / (2.0 * h);
        let f0 = force(d0);
        let period = 2.0 * PI * (1.0 / k_t).sqrt();
        let release = Release {
            mass: 1.0,
            target: self.amplitude * self.mu * f0,
            k_t,
            period,
            periods,
            steps,
            force_scale: self.mu * f0,
        };
        let s = ring(law, d0, Axis::Tangential { approach: d0 }, &release)?;
        Ok((d0, k_t, period, s))
    }

    /// Each cycle against the closed form of the contact's own normal curve, and the
    /// closed form on the ladder of amplitudes.
    fn damping(
        &self,
        (d0, k_t, period, samples): (f64, f64, f64, Vec<Sample>),
        force: &mut dyn FnMut(f64) -> f64,
        (e, g, f0): (f64, f64, f64),
    ) -> dynamics::Result<Damping> {
        let (mu, kappa) = (self.mu, self.mu * e / g);
        let mut closed = |q: f64| -> dynamics::Result<(f64, f64)> {
            masing::loss_per_cycle(force, (0.0, d0), mu, kappa, q).ok_or_else(|| {
                dynamics::DynamicsError::InvalidInput(format!(
                    "a force amplitude of {q:e} is beyond the contact's mu F0"
                ))
            })
        };
        // A branch from a turning point is twice the virgin loading in every spring or
        // cell that slips on it (each slipped on the branch before, which was larger):
        // a branch of force range dQ dissipates half the symmetric cycle's loss at the
        // amplitude dQ / 2, however fast the amplitude decays.
        let mut rows = Vec::new();
        for c in cycles(&samples) {
            let [a, b, d] = c.extremes;
            let w = 0.5 * (closed(0.5 * (a + b))?.0 + closed(0.5 * (b + d))?.0);
            rows.push([c.t / period, c.force / (mu * f0), c.loss, w, c.loss / w]);
        }
        let ladder = LADDER
            .iter()
            .map(|x| {
                let q = x * mu * f0;
                let (w, u) = closed(q)?;
                Ok((w, w / (2.0 * PI * q * u)))
            })
            .collect::<dynamics::Result<Vec<_>>>()?;
        Ok(Damping {
            d0,
            k_t,
            period,
            samples,
            cycles: rows,
            ladder,
        })
    }
}
