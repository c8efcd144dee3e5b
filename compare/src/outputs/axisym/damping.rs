//! `damping`: an oscillating tangential contact at fixed depth (Section 7),
//! time-stepped on springs through full cycles: energy dissipated per cycle against
//! amplitude, against the semi-analytic MRD result and, for a sphere, Mindlin's Eq. 58,
//! its small-amplitude limit Eq. 61 and the force form.

use crate::checks::{check_springs, default_points, default_springs, rel, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::oscillation::{dissipation_semi_analytic, OscillatingContact};
use mrd::reference::{for_profile, mindlin_damping as md};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Damping {
    /// Coulomb friction coefficient.
    mu: f64,
    /// Normal indentation depth held during the oscillation [length].
    depth: f64,
    /// Largest amplitude as a multiple of A_c0 = mu E*/G* d.
    #[serde(default = "default_amplitude_ratio")]
    max_amplitude_ratio: f64,
    /// Points of the output's curves (its sampling).
    #[serde(default = "default_points")]
    points: usize,
    /// MRD springs on the half-line.
    #[serde(default = "default_springs")]
    springs: usize,
    /// Half-length L of the springs' line [-L, L] [length]; default 1.05 times the contact
    /// radius.
    half_length: Option<f64>,
    /// Steps per oscillation cycle, a multiple of 4 (the turning points are hit exactly).
    #[serde(default = "crate::checks::default_count::<8>")]
    steps_per_cycle: usize,
}

fn default_amplitude_ratio() -> f64 {
    1.0
}

impl Output for Damping {
    fn validate(&self, ctx: &Context) -> Result<()> {
        hess::check_scene(ctx, self.points)?;
        require_positive("friction coefficient mu", self.mu)?;
        require_positive("depth", self.depth)?;
        require_positive("max_amplitude_ratio", self.max_amplitude_ratio)?;
        check_springs(self.springs, crate::checks::spring_bytes::DAMPING)?;
        ctx.material.g_star().ctx("damping output")?;
        Ok(())
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        hess::stages(Stage::OscillationDiscrete, hess::is_sphere(ctx))
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let ctx = env.ctx;
        let profile = ctx.profile()?;
        let e = ctx.material.e_star;
        let g = hess::shear_modulus(env, out, "damping output")?;
        let (mu, depth, points) = (self.mu, self.depth, self.points);
        let s = out
            .stage(Stage::NormalSemiAnalytic, || contact.state_at_depth(depth))
            .ctx("normal contact")?;
        let beta = e / g;
        let ac0 = mu * beta * depth;
        let l = crate::checks::row_half_length(self.half_length, s.radius, 1.05)?;
        // Log-spaced amplitudes over two decades below the maximum.
        let amps: Vec<f64> = (0..points)
            .map(|k| {
                self.max_amplitude_ratio
                    * ac0
                    * 10f64.powf(-2.0 * (1.0 - k as f64 / (points - 1) as f64))
            })
            .collect();
        let sims = out
            .stage(Stage::OscillationDiscrete, || -> mrd::Result<Vec<_>> {
                let osc = OscillatingContact::new(profile, e, g, mu, depth, self.springs, l)?;
                amps.iter()
                    .map(|&amp| {
                        let sim = osc.simulate(amp, 2, self.steps_per_cycle)?;
                        let semi = dissipation_semi_analytic(profile, e, g, mu, depth, amp)?;
                        Ok((sim, semi))
                    })
                    .collect()
            })
            .ctx("oscillating contact")?;
        let sphere = for_profile::sphere_radius(profile);
        let closed: Option<Vec<[f64; 3]>> = sphere.map(|r| {
            out.stage(Stage::ClosedForm, || {
                amps.iter()
                    .zip(&sims)
                    .map(|(&amp, (sim, _))| {
                        [
                            md::dissipation_exact(e, beta, r, mu, depth, amp),
                            md::dissipation_small_amplitude(e, beta, r, mu, depth, amp),
                            md::dissipation_force_amplitude(
                                g,
                                s.radius,
                                mu,
                                s.force,
                                sim.force_amplitude,
                            ),
                        ]
                    })
                    .collect()
            })
        });
        let u = &ctx.units;
        let (len, force, energy) = (&u.length, u.force(), u.energy());
        let mut cols = vec![
            format!("amplitude [{len}]"),
            format!("dissipation_time_stepped [{energy}]"),
            format!("dissipation_semi_analytic [{energy}]"),
            format!("force_amplitude [{force}]"),
        ];
        if closed.is_some() {
            cols.extend([
                format!("dissipation_eq58_exact [{energy}]"),
                format!("dissipation_eq61_small_amplitude [{energy}]"),
                format!("dissipation_mindlin_force [{energy}]"),
            ]);
        }
        let mut t = Table::new("damping", &cols);
        t.notes.push(format!(
            "depth {depth:e}, mu = {mu}, E*/G* = {beta}, A_c0 = mu E*/G* d = {ac0:e}; {} springs on [-{l:e}, {l:e}], {} steps per cycle, 2 cycles (the second is reported)",
            self.springs, self.steps_per_cycle
        ));
        let mut dev: f64 = 0.0;
        for (k, (sim, semi)) in sims.iter().enumerate() {
            let mut row = vec![amps[k], sim.dissipation, *semi, sim.force_amplitude];
            if let Some(c) = &closed {
                dev = dev.max(rel(sim.dissipation, c[k][0]));
                row.extend(c[k]);
            }
            t.push(row);
        }
        out.scalar("critical_amplitude_ac0", ac0);
        if closed.is_some() {
            out.scalar("max_rel_error_time_stepped_vs_eq58", dev);
        }
        let mut fig = Figure::new(
            "damping",
            "Dissipated energy per cycle of an oscillating tangential contact",
            &format!("displacement amplitude A [{len}]"),
            &format!("dissipated energy per cycle W [{energy}]"),
        )
        .plot(
            format!("MRD, time-stepped ({} springs)", self.springs),
            t.xy_sampled("amplitude", "dissipation_time_stepped", 25),
            Style::Markers,
        )
        .plot(
            "MRD, semi-analytic",
            t.xy("amplitude", "dissipation_semi_analytic"),
            Style::Line,
        );
        if closed.is_some() {
            fig = fig
                .plot(
                    "Eq. 58 (Mindlin et al. 1952)",
                    t.xy("amplitude", "dissipation_eq58_exact"),
                    Style::Dashed,
                )
                .plot(
                    "Eq. 61, small-amplitude limit",
                    t.xy("amplitude", "dissipation_eq61_small_amplitude"),
                    Style::Dashed,
                );
        }
        out.tables.push(t);
        out.figures.push(fig.log_log());
        Ok(())
    }
}
