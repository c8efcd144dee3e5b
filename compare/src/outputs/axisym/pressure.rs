//! `pressure`: the contact pressure p(r) at one depth by the Abel transform of the 1D
//! line load (Eq. 26), with its equilibrium check and the closed form where one exists.

use crate::checks::{default_points, rel, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::pressure::{abel_pressure, integrate_force};
use mrd::reference::for_profile;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pressure {
    /// Indentation depth at which the pressure is computed [length].
    depth: f64,
    /// Points of the output's curves (its sampling).
    #[serde(default = "default_points")]
    points: usize,
}

impl Output for Pressure {
    fn validate(&self, ctx: &Context) -> Result<()> {
        hess::check_scene(ctx, self.points)?;
        require_positive("depth", self.depth)?;
        Ok(())
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let closed_form = ctx.profile.as_ref().is_some_and(for_profile::has_pressure);
        hess::stages(Stage::AbelPressure, closed_form)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let profile = env.ctx.profile()?;
        let e = env.ctx.material.e_star;
        let (len, stress) = (&env.ctx.units.length, &env.ctx.units.stress);
        let depth = self.depth;
        let s = out
            .stage(Stage::NormalSemiAnalytic, || contact.state_at_depth(depth))
            .ctx("semi-analytic solve")?;
        let a = s.radius;
        // Samples at cell centres; exactly on a slope jump the pressure is log-singular
        // and not sampled.
        let (samples, total) = out.stage(Stage::AbelPressure, || -> Result<_> {
            let mut v = Vec::new();
            for k in 0..self.points {
                let r = a * (k as f64 + 0.5) / self.points as f64;
                let p = abel_pressure(profile, e, depth, a, 0.0, r).ctx("Abel transform")?;
                if p.is_finite() {
                    v.push((r, p));
                }
            }
            let total = integrate_force(
                |r| abel_pressure(profile, e, depth, a, 0.0, r),
                a,
                &profile.breaks(),
            )
            .ctx("pressure integral")?;
            Ok((v, total))
        })?;
        let closed: Option<Vec<f64>> = for_profile::has_pressure(profile).then(|| {
            out.stage(Stage::ClosedForm, || {
                samples
                    .iter()
                    .map(|&(r, _)| {
                        for_profile::pressure(profile, e, depth, s.force, r).unwrap_or(f64::NAN)
                    })
                    .collect()
            })
        });
        let mut cols = vec![format!("r [{len}]"), format!("pressure [{stress}]")];
        if closed.is_some() {
            cols.push(format!("pressure_closed_form [{stress}]"));
        }
        let mut t = Table::new("pressure", &cols);
        t.notes.push(format!("Abel transform (Eq. 26) at depth {depth:e}, contact radius {a:e}; samples at cell centres r = a (k + 1/2)/N"));
        let mut dev: f64 = 0.0;
        for (k, &(r, p)) in samples.iter().enumerate() {
            let mut row = vec![r, p];
            if let Some(c) = &closed {
                dev = dev.max(rel(p, c[k]));
                row.push(c[k]);
            }
            t.push(row);
        }
        if profile
            .shapes()
            .iter()
            .any(|s| matches!(s, mrd::Shape::Table(_)))
        {
            out.warn(
                "pressure: a piecewise-linear table has slope jumps at its nodes, under which the exact \
                 pressure is log-singular (peaks at node radii); use a finer table or analytic shapes \
                 for a smooth pressure",
            );
        }
        out.scalar("contact_radius", a);
        out.scalar("force_1d", s.force);
        out.scalar("force_from_pressure_integral", total);
        out.scalar("equilibrium_rel_error", rel(total, s.force));
        if closed.is_some() {
            out.scalar("max_rel_error_vs_closed_form", dev);
        }
        let mut fig = Figure::new(
            "pressure",
            "Contact pressure from the 1D line load (Abel transform, Eq. 26)",
            &format!("radius r [{len}]"),
            &format!("pressure p [{stress}]"),
        )
        .plot("MRD + Abel transform", t.xy("r", "pressure"), Style::Line);
        if let (Some(name), true) = (for_profile::name(profile), closed.is_some()) {
            fig = fig.plot(name, t.xy("r", "pressure_closed_form"), Style::Dashed);
        }
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
