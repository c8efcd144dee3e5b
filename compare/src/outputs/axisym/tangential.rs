//! `tangential`: tangential loading at a fixed normal force up to full sliding
//! (Cattaneo-Mindlin / Jager, Eqs. 41-50), and the traction distributions at chosen
//! fractions of mu F_N (Abel transform of Eq. 51); closed forms for a sphere.

use crate::checks::{bad, default_points, rel, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::reference::{cattaneo_mindlin as cm, for_profile, hertz};
use mrd::tangential::{TangentialContact, TangentialState};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tangential {
    /// Coulomb friction coefficient.
    mu: f64,
    /// Normal force F_N [force].
    normal_force: f64,
    /// Points of the output's curves (its sampling).
    #[serde(default = "default_points")]
    points: usize,
    /// Fractions of mu F_N at which the traction is drawn.
    #[serde(default)]
    traction_at: Vec<f64>,
}

impl Output for Tangential {
    fn validate(&self, ctx: &Context) -> Result<()> {
        hess::check_scene(ctx, self.points)?;
        require_positive("friction coefficient mu", self.mu)?;
        require_positive("normal_force", self.normal_force)?;
        if self.traction_at.iter().any(|f| !(0.0..1.0).contains(f)) {
            return bad("traction_at fractions of mu F_N must lie in [0, 1)");
        }
        ctx.material.g_star().ctx("tangential output")?;
        Ok(())
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let mut s = hess::stages(Stage::Tangential, hess::is_sphere(ctx));
        if !self.traction_at.is_empty() {
            s.push(Stage::AbelTraction);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let ctx = env.ctx;
        let profile = ctx.profile()?;
        let e = ctx.material.e_star;
        let g = hess::shear_modulus(env, out, "tangential output")?;
        let (mu, fn_) = (self.mu, self.normal_force);
        let tc = out
            .stage(Stage::NormalSemiAnalytic, || {
                TangentialContact::new(contact, g, mu, fn_)
            })
            .ctx("normal contact")?;
        let n = &tc.normal;
        let fmax = mu * n.force;
        let points = self.points;
        let states: Vec<(f64, TangentialState)> = out
            .stage(Stage::Tangential, || {
                (0..points)
                    .map(|k| {
                        let fx = fmax * k as f64 / points as f64;
                        tc.at_force(fx).map(|s| (fx, s))
                    })
                    .collect::<mrd::Result<_>>()
            })
            .ctx("tangential loading")?;
        let sphere = for_profile::sphere_radius(profile);
        // Closed forms at the same forces: (displacement, stick radius), and the final
        // full-sliding displacement.
        let closed = sphere.map(|_| {
            out.stage(Stage::ClosedForm, || {
                let at: Vec<(f64, f64)> = states
                    .iter()
                    .map(|(fx, _)| {
                        (
                            cm::displacement(mu, e, g, n.depth, *fx, n.force),
                            n.radius * cm::stick_ratio(*fx, mu, n.force),
                        )
                    })
                    .collect();
                (at, cm::max_displacement(mu, e, g, n.depth))
            })
        });
        let u = &ctx.units;
        let (len, force) = (&u.length, u.force());
        let mut cols = vec![
            format!("tangential_force [{force}]"),
            format!("displacement [{len}]"),
            format!("stick_radius [{len}]"),
        ];
        if closed.is_some() {
            cols.extend([
                format!("displacement_closed_form [{len}]"),
                format!("stick_radius_closed_form [{len}]"),
            ]);
        }
        let mut t = Table::new("tangential", &cols);
        t.notes.push(format!("normal force {fn_:e}, mu = {mu}, E* = {e:e}, G* = {g:e}; Jager/Cattaneo-Mindlin (Eqs. 41-50)"));
        let mut dev: f64 = 0.0;
        for (k, (fx, st)) in states.iter().enumerate() {
            let mut row = vec![*fx, st.displacement, st.stick_radius];
            if let Some((at, _)) = &closed {
                let (uc, cc) = at[k];
                if *fx > 0.0 {
                    dev = dev
                        .max(rel(st.displacement, uc))
                        .max(rel(st.stick_radius, cc));
                }
                row.extend([uc, cc]);
            }
            t.push(row);
        }
        let mut last = vec![fmax, tc.max_displacement(), 0.0];
        if let Some((_, umax)) = &closed {
            last.extend([*umax, 0.0]);
        }
        t.push(last);
        out.scalar("max_displacement", tc.max_displacement());
        out.scalar("sliding_force", fmax);
        out.scalar("contact_radius", n.radius);
        if closed.is_some() {
            out.scalar("max_rel_error_vs_cattaneo_mindlin", dev);
        }
        let mut fig = Figure::new(
            "tangential",
            "Tangential force against displacement (Cattaneo-Mindlin / Jager)",
            &format!("tangential displacement u_x [{len}]"),
            &format!("tangential force F_x [{force}]"),
        )
        .plot("MRD", t.xy("displacement", "tangential_force"), Style::Line);
        if closed.is_some() {
            fig = fig.plot(
                "Cattaneo-Mindlin (Mindlin 1949)",
                t.xy("displacement_closed_form", "tangential_force"),
                Style::Dashed,
            );
        }
        out.tables.push(t);
        out.figures.push(fig);
        if !self.traction_at.is_empty() {
            self.tractions(env, out, &tc, sphere)?;
        }
        Ok(())
    }
}

impl Tangential {
    /// The traction table and figure (Abel transform of Eq. 51).
    fn tractions(
        &self,
        env: &Env,
        out: &mut Section,
        tc: &TangentialContact,
        sphere: Option<f64>,
    ) -> Result<()> {
        let ctx = env.ctx;
        let (len, stress) = (&ctx.units.length, &ctx.units.stress);
        let e = ctx.material.e_star;
        let (mu, points) = (self.mu, self.points);
        let n = &tc.normal;
        let fmax = mu * n.force;
        let p0 = hertz::pressure(e, sphere.unwrap_or(1.0), n.depth, 0.0);
        // Per radius: (r, [(traction, closed form or NaN) per fraction]).
        let rows = out
            .stage(Stage::AbelTraction, || -> mrd::Result<Vec<_>> {
                let states = self
                    .traction_at
                    .iter()
                    .map(|f| tc.at_force(f * fmax))
                    .collect::<mrd::Result<Vec<_>>>()?;
                (0..points)
                    .map(|k| {
                        let r = n.radius * (k as f64 + 0.5) / points as f64;
                        let v = states
                            .iter()
                            .map(|st| {
                                let tau = tc.traction(st, r)?;
                                let closed = sphere.map_or(f64::NAN, |_| {
                                    cm::traction(mu, p0, n.radius, st.stick_radius, r)
                                });
                                Ok((tau, closed))
                            })
                            .collect::<mrd::Result<Vec<_>>>()?;
                        Ok((r, v))
                    })
                    .collect()
            })
            .ctx("tangential traction")?;
        let mut cols = vec![format!("r [{len}]")];
        for f in &self.traction_at {
            cols.push(format!("traction_at_{f}_muFN [{stress}]"));
            if sphere.is_some() {
                cols.push(format!("traction_closed_form_at_{f}_muFN [{stress}]"));
            }
        }
        let mut t = Table::new("traction", &cols);
        t.notes.push(
            "tangential traction by the Abel transform (Eq. 26) of the line load of Eq. (51)"
                .into(),
        );
        let mut dev: f64 = 0.0;
        for (r, v) in &rows {
            let mut row = vec![*r];
            for &(tau, tcf) in v {
                row.push(tau);
                if sphere.is_some() {
                    dev = dev.max((tau - tcf).abs() / (mu * p0));
                    row.push(tcf);
                }
            }
            t.push(row);
        }
        if sphere.is_some() {
            out.scalar("traction_max_error_over_mu_p0", dev);
        }
        let mut fig = Figure::new(
            "traction",
            "Tangential traction (Abel transform of Eq. 51)",
            &format!("radius r [{len}]"),
            &format!("traction tau [{stress}]"),
        );
        for f in &self.traction_at {
            fig = fig.plot(
                format!("MRD, F_x = {f} mu F_N"),
                t.xy("r", &format!("traction_at_{f}_muFN")),
                Style::Line,
            );
        }
        if sphere.is_some() {
            for f in &self.traction_at {
                fig = fig.plot(
                    format!("Cattaneo-Mindlin, {f} mu F_N"),
                    t.xy("r", &format!("traction_closed_form_at_{f}_muFN")),
                    Style::Dashed,
                );
            }
        }
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
