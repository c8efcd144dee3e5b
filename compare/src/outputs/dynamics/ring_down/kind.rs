//! `ring_down`'s run: the held approach by MRD and in 3D, then the normal wave's runs.

use super::{RingDown, SIDE_3D};
use crate::checks::{bad, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::experiment::ring::{ring, Release};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use dynamics::integrate::{Axis, Sample};
use dynamics::{ContactLaw, SlipBem3d, Springs};
use mrd::reference::{for_profile, hertz};
use std::f64::consts::PI;

impl Output for RingDown {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("ring_down needs a sphere (profile = paraboloid): Mindlin and Deresiewicz's loss per cycle is the reference");
        }
        ctx.material.g_star().ctx("ring_down")?;
        require_positive("normal_force", self.normal_force)?;
        require_positive("mu", self.mu)?;
        require_positive("mass", self.mass)?;
        if !(self.amplitude > 0.0 && self.amplitude < 1.0) {
            return bad(format!(
                "amplitude = {} must lie in (0, 1) (a fraction of mu F_N; at 1 the body slides)",
                self.amplitude
            ));
        }
        if !(2..=100_000).contains(&self.periods)
            || !(50..=100_000).contains(&self.steps)
            || self.periods * self.steps > 50_000_000
        {
            return bad(format!(
                "periods = {} in 2..=100000 and steps = {} per period in 50..=100000, at most 5e7 steps in all",
                self.periods, self.steps
            ));
        }
        let ratio = ctx.material.g_star().ctx("ring_down")? / ctx.material.e_star;
        if self.cells_3d != 0 && !(2.0 / 3.0..=1.0).contains(&ratio) {
            return bad(format!(
                "G* / E* = {ratio}: the 3D run (cells_3d = {}) takes one elastic body, G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5]); or set cells_3d = 0",
                self.cells_3d
            ));
        }
        if self.cells_3d != 0 && !(16..=512).contains(&self.cells_3d) {
            return bad(format!(
                "cells_3d = {} must be 0 (MRD alone) or lie in 16..=512",
                self.cells_3d
            ));
        }
        if !(2..=1000).contains(&self.periods_3d)
            || !(50..=100_000).contains(&self.steps_3d)
            || self.periods_3d * self.steps_3d > 1_000_000
        {
            return bad(format!(
                "periods_3d = {} in 2..=1000 and steps_3d = {} per period in 50..=100000, at most 1e6 steps in all",
                self.periods_3d, self.steps_3d
            ));
        }
        if !(100..=1_000_000).contains(&self.springs) {
            return bad(format!(
                "springs = {} must lie in 100..=1000000",
                self.springs
            ));
        }
        if let Some(w) = &self.normal_wave {
            w.check(self.amplitude)?;
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::ClosedForm, Stage::Dynamics];
        if self.cells_3d > 0 {
            s.push(Stage::Dynamics3d);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let (e, g) = (ctx.material.e_star, ctx.material.g_star().ctx("ring_down")?);
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        let (mu, fn_) = (self.mu, self.normal_force);
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let a = out.stage(Stage::ClosedForm, || {
            hertz::radius(r, hertz::depth(e, r, fn_))
        });
        let k_t = 2.0 * a * g;
        let period = 2.0 * PI * (self.mass / k_t).sqrt();
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Sample>> {
                let mut law =
                    Springs::body(&profile, e, self.springs, 1.5 * a)?.with_friction(g, mu)?;
                let d = law.approach_at(fn_)?;
                self.ring(&mut law, d, None, (k_t, period), (self.periods, self.steps))
            })
            .ctx("MRD in the loop")?;
        let grid = AxisymGrid {
            cells: self.cells_3d,
            side: SIDE_3D * a,
            periodic: false,
        };
        let three = if self.cells_3d > 0 {
            let (n, side) = (self.cells_3d, grid.side);
            let (z, _) = grid.heights(&profile);
            let s = out
                .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Sample>> {
                    let mut law = SlipBem3d::new(&z, (n, n), (side, side), (e, g), mu, fn_, 1e-8)?;
                    let d = law.approach();
                    self.ring(
                        &mut law,
                        d,
                        None,
                        (k_t, period),
                        (self.periods_3d, self.steps_3d),
                    )
                })
                .ctx("3D in the loop")?;
            out.scalar("cells_per_contact_radius_3d", a / (side / n as f64));
            Some(s)
        } else {
            None
        };
        let waves = match &self.normal_wave {
            Some(w) => self.waves(out, w, &profile, &grid, (e, g), (k_t, period))?,
            None => Vec::new(),
        };
        self.report(out, &mrd, three.as_deref(), (g, a, k_t, period))?;
        if let Some(w) = &self.normal_wave {
            self.report_waves(out, w, (&mrd, &waves), (g, a, period))?;
        }
        Ok(())
    }
}

impl RingDown {
    /// One run in the loop: the virgin loading of `law` at the approach of t = 0 (`d`, or
    /// the wave's `d (1 + b sin(phase))` under `wave` = (b, omega, phase)) to the starting
    /// force, quasi-statically (shifts of a hundredth of its elastic one), then the
    /// release at rest and `periods` periods at `steps` steps each.
    pub(super) fn ring(
        &self,
        law: &mut dyn ContactLaw,
        d: f64,
        wave: Option<(f64, f64, f64)>,
        (k_t, period): (f64, f64),
        (periods, steps): (usize, usize),
    ) -> dynamics::Result<Vec<Sample>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let (axis, d_start) = match wave {
            None => (Axis::Tangential { approach: d }, d),
            Some((amplitude, omega, phase)) => (
                Axis::TangentialWave {
                    approach: d,
                    amplitude,
                    omega,
                    phase,
                },
                d * (1.0 + amplitude * phase.sin()),
            ),
        };
        let release = Release {
            mass: self.mass,
            target: self.amplitude * mu * fn_,
            k_t,
            period,
            periods,
            steps,
            force_scale: mu * fn_,
        };
        ring(law, d_start, axis, &release)
    }
}
