//! `viscoelastic`: viscoelastic indentation (Section 8, Eq. 63): a constant-rate ramp to
//! `depth_max` over `ramp_time`, then a hold until `end_time`, on Prony-series springs,
//! against Radok's (1957) solution by quadrature.

use crate::checks::{bad, check_springs, default_springs, positive, rel, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::viscoelastic::{radok_force, simulate, Prony};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Viscoelastic {
    /// Long-time modulus E*_inf.
    e_inf: f64,
    /// Prony terms [[E_i, tau_i], ...] of E*(t) = E_inf + sum E_i exp(-t/tau_i).
    prony: Vec<[f64; 2]>,
    /// Depth reached by the constant-rate ramp [length].
    depth_max: f64,
    /// Duration of the ramp [time].
    ramp_time: f64,
    /// End of the hold after the ramp [time].
    end_time: f64,
    /// MRD springs on the half-line.
    #[serde(default = "default_springs")]
    springs: usize,
    /// Half-length L of the springs' line [-L, L] [length]; default 1.2 times the largest
    /// contact radius.
    half_length: Option<f64>,
    /// Time steps over [0, end_time].
    #[serde(default = "crate::checks::default_count::<400>")]
    steps: usize,
}

impl Viscoelastic {
    fn modulus(&self) -> mrd::Result<Prony> {
        Prony::new(
            self.e_inf,
            self.prony.iter().map(|t| (t[0], t[1])).collect(),
        )
    }
}

impl Output for Viscoelastic {
    fn validate(&self, ctx: &Context) -> Result<()> {
        ctx.profile()?;
        if !(2..=1_000_000).contains(&self.steps) {
            return bad(format!("steps = {} must lie in 2..=1000000", self.steps));
        }
        if !positive(self.depth_max) {
            return bad(format!("depth_max = {} must be > 0", self.depth_max));
        }
        if !positive(self.end_time) {
            return bad(format!("end_time = {} must be > 0", self.end_time));
        }
        if !(positive(self.ramp_time) && self.ramp_time <= self.end_time) {
            return bad(format!(
                "ramp_time = {} must lie in (0, end_time = {}]",
                self.ramp_time, self.end_time
            ));
        }
        check_springs(
            self.springs,
            crate::checks::spring_bytes::viscoelastic(self.prony.len()),
        )?;
        if let Some(l) = self.half_length {
            require_positive("half_length", l)?;
        }
        self.modulus().ctx("prony")?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        hess::stages(Stage::Viscoelastic, true)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let profile = env.ctx.profile()?;
        let g = self.modulus().ctx("prony")?;
        let (ramp, steps, end) = (self.ramp_time, self.steps, self.end_time);
        let rate = self.depth_max / ramp;
        let depth = move |t: f64| rate * t.min(ramp);
        let depth_rate = move |t: f64| if t < ramp { rate } else { 0.0 };
        let times: Vec<f64> = (0..=steps).map(|k| end * k as f64 / steps as f64).collect();
        let a_max = out
            .stage(Stage::NormalSemiAnalytic, || {
                contact.state_at_depth(self.depth_max)
            })
            .ctx("elastic contact at depth_max")?
            .radius;
        let l = crate::checks::row_half_length(self.half_length, a_max, 1.2)?;
        let f = out
            .stage(Stage::Viscoelastic, || {
                simulate(profile, &g, &depth, &times, self.springs, l)
            })
            .ctx("Prony springs")?;
        // Radok's integrand jumps at the end of the ramp: split there.
        let exact = out
            .stage(Stage::ClosedForm, || {
                times
                    .iter()
                    .map(|&tk| {
                        if tk == 0.0 {
                            Ok(0.0)
                        } else {
                            radok_force(profile, &g, &depth, &depth_rate, &[ramp], tk)
                        }
                    })
                    .collect::<mrd::Result<Vec<f64>>>()
            })
            .ctx("Radok")?;
        let u = &env.ctx.units;
        let (len, force) = (&u.length, u.force());
        let mut t = Table::new(
            "viscoelastic",
            &[
                "time [s]".to_string(),
                format!("depth [{len}]"),
                format!("force [{force}]"),
                format!("force_radok [{force}]"),
            ],
        );
        t.notes.push(format!("Eq. (63) with E*(t) = {} + sum E_i exp(-t/tau_i), Prony {:?}; ramp to {} in {ramp}, hold to {end}; {} springs; Radok (1957) by quadrature (valid while the contact grows; during the hold the contact radius is fixed, so it remains exact)", self.e_inf, self.prony, self.depth_max, self.springs));
        let mut dev: f64 = 0.0;
        for (k, &tk) in times.iter().enumerate() {
            if exact[k] > 0.0 && k > steps / 20 {
                dev = dev.max(rel(f[k], exact[k]));
            }
            t.push(vec![tk, depth(tk), f[k], exact[k]]);
        }
        out.scalar("max_rel_dev_springs_vs_radok", dev);
        out.scalar("peak_force", f.iter().fold(0.0f64, |m, &v| m.max(v)));
        let fig = Figure::new(
            "viscoelastic",
            "Viscoelastic indentation: ramp and hold (Eq. 63)",
            "time t [s]",
            &format!("normal force F [{force}]"),
        )
        .plot(
            format!("MRD, {} Prony springs", self.springs),
            t.xy_sampled("time", "force", 40),
            Style::Markers,
        )
        .plot("Radok (1957)", t.xy("time", "force_radok"), Style::Line);
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
