//! `force_depth`: normal force, contact radius and stiffness against depth (Eqs. 20,
//! 24, 25), semi-analytic; optionally on N discrete springs; the closed form where the
//! profile has one; the electrical conductance for a resistivity sum.

use crate::checks::{check_springs, default_points, rel};
use crate::context::{Context, Drive};
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::discrete::DiscreteAxisymmetric;
use mrd::reference::for_profile;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceDepth {
    /// Largest depth (drive = "depth") or force (drive = "force").
    max: f64,
    /// What drives the curve: "depth" (default) or "force".
    #[serde(default)]
    drive: Drive,
    /// Points of the output's curves (its sampling).
    #[serde(default = "default_points")]
    points: usize,
    /// Springs of the discrete foundation on [-half_length, half_length] (optional).
    springs: Option<usize>,
    /// Half-length L of the MRD springs' line [-L, L] [length]; default 1.5 times the final
    /// contact radius.
    half_length: Option<f64>,
    /// rho1 + rho2, the two bodies' electrical resistivities summed: adds the column
    /// electrical_conductance, 2 k / (E* (rho1 + rho2)) (end of Section 8).
    resistivity_sum: Option<f64>,
}

impl Output for ForceDepth {
    fn validate(&self, ctx: &Context) -> Result<()> {
        hess::check_scene(ctx, self.points)?;
        crate::checks::check_magnitudes(&[("max", self.max)])?;
        if let Some(rho) = self.resistivity_sum {
            crate::checks::check_magnitudes(&[("resistivity_sum", rho)])?;
        }
        if let Some(n) = self.springs {
            check_springs(n, crate::checks::spring_bytes::FORCE_DEPTH)?;
        }
        Ok(())
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::NormalSemiAnalytic];
        if self.springs.is_some() {
            s.push(Stage::NormalDiscrete);
        }
        if ctx.profile.as_ref().and_then(for_profile::name).is_some() {
            s.push(Stage::ClosedForm);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let profile = env.ctx.profile()?;
        let e = env.ctx.material.e_star;
        let u = &env.ctx.units;
        let (len, force, stiff) = (&u.length, u.force(), u.stiffness());
        let (max, points) = (self.max, self.points);
        let states = out
            .stage(Stage::NormalSemiAnalytic, || {
                (1..=points)
                    .map(|k| {
                        let v = max * k as f64 / points as f64;
                        match self.drive {
                            Drive::Depth => contact.state_at_depth(v),
                            Drive::Force => contact.state_at_force(v),
                        }
                    })
                    .collect::<std::result::Result<Vec<_>, _>>()
            })
            .ctx("semi-analytic solve")?;
        let discrete = match self.springs {
            Some(n) => Some(out.stage(Stage::NormalDiscrete, || -> Result<_> {
                let a_top = states.last().map_or(1.0, |s| s.radius);
                // A rim holds the row at the rim radius (the half-length is not used).
                let l = match profile.rim() {
                    Some(_) => self.half_length.unwrap_or(1.5 * a_top),
                    None => crate::checks::row_half_length(self.half_length, a_top, 1.5)?,
                };
                let d = DiscreteAxisymmetric::new(profile, e, n, l).ctx("discrete springs")?;
                let has_rim = profile.rim().is_some();
                let st = states
                    .iter()
                    .map(|s| d.state_at_depth(s.depth, has_rim))
                    .collect::<std::result::Result<Vec<_>, _>>()
                    .ctx("discrete springs")?;
                Ok((d.dx(), st))
            })?),
            None => None,
        };
        let closed: Option<Vec<f64>> = for_profile::name(profile).map(|_| {
            out.stage(Stage::ClosedForm, || {
                states
                    .iter()
                    .map(|s| for_profile::force(profile, e, s.depth).unwrap_or(f64::NAN))
                    .collect()
            })
        });
        let mut cols = vec![
            format!("depth [{len}]"),
            format!("force [{force}]"),
            format!("contact_radius [{len}]"),
            format!("stiffness [{stiff}]"),
        ];
        if discrete.is_some() {
            cols.extend([
                format!("force_discrete [{force}]"),
                format!("contact_radius_discrete [{len}]"),
            ]);
        }
        if closed.is_some() {
            cols.push(format!("force_closed_form [{force}]"));
        }
        if self.resistivity_sum.is_some() {
            cols.push("electrical_conductance [1/(resistivity unit * length unit)]".into());
        }
        let mut t = Table::new("force_depth", &cols);
        t.notes.push(format!(
            "drive: {:?}; MRD semi-analytic (Eqs. 20, 24, 25), relative tolerance 1e-9",
            self.drive
        ));
        let (mut dev_cf, mut dev_disc): (f64, f64) = (0.0, 0.0);
        for (k, s) in states.iter().enumerate() {
            let mut row = vec![s.depth, s.force, s.radius, s.stiffness];
            if let Some((_, ds)) = &discrete {
                dev_disc = dev_disc.max(rel(ds[k].force, s.force));
                row.extend([ds[k].force, ds[k].radius]);
            }
            if let Some(fc) = &closed {
                dev_cf = dev_cf.max(rel(s.force, fc[k]));
                row.push(fc[k]);
            }
            if let Some(rho) = self.resistivity_sum {
                row.push(s.electrical_conductance(e, rho));
            }
            t.push(row);
        }
        if closed.is_some() {
            out.scalar("max_rel_error_vs_closed_form", dev_cf);
        }
        if let Some((dx, _)) = &discrete {
            let n = self.springs.unwrap_or(0);
            out.scalar("max_rel_dev_discrete_vs_semi_analytic", dev_disc);
            out.scalar("springs", n as f64);
            out.scalar("spring_spacing", *dx);
            t.notes
                .push(format!("discrete foundation: {n} springs, dx = {dx:e}"));
        }
        let last = states.last().expect("points >= 2");
        out.scalar("final_depth", last.depth);
        out.scalar("final_force", last.force);
        out.scalar("final_contact_radius", last.radius);
        let mut fig = Figure::new(
            "force_depth",
            "Normal force against indentation depth",
            &format!("depth d [{len}]"),
            &format!("normal force F [{force}]"),
        )
        .plot("MRD, semi-analytic", t.xy("depth", "force"), Style::Line);
        if let Some(n) = self.springs {
            fig = fig.plot(
                format!("MRD, {n} discrete springs"),
                t.xy_sampled("depth", "force_discrete", 20),
                Style::Markers,
            );
        }
        if let Some(name) = for_profile::name(profile) {
            fig = fig.plot(name, t.xy("depth", "force_closed_form"), Style::Dashed);
        }
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
