//! `profile_1d`: the 3D profile z(r) and its MRD image z1d(x) by the rule of Hess
//! (Eq. 11), per-shape closed form against independent quadrature.

use crate::checks::{bad, default_points, rel, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile1d {
    /// Largest radius drawn.
    r_max: f64,
    /// Points of the output's curves (its sampling).
    #[serde(default = "default_points")]
    points: usize,
}

impl Profile1d {
    /// The largest radius drawn: r_max, within the profile's contact radii.
    fn largest_radius(&self, profile: &mrd::Profile) -> f64 {
        self.r_max.min(profile.max_contact_radius())
    }
}

impl Output for Profile1d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        hess::check_scene(ctx, self.points)?;
        require_positive("r_max", self.r_max)?;
        // The profile rises with r: its heights at the largest radius drawn bound the
        // table's.
        let profile = ctx.profile()?;
        let limit = self.largest_radius(profile);
        let (z, z1d) = (profile.z(limit), profile.z1d(limit));
        if !(z.is_finite() && z1d.is_finite()) {
            return bad(format!(
                "r_max = {:e}: the profile's height there (z = {z:e}, z1d = {z1d:e}) is not \
                 representable in double precision; give a smaller r_max",
                self.r_max
            ));
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::HessTransform]
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        hess::hess(env, out)?;
        let profile = env.ctx.profile()?;
        let len = &env.ctx.units.length;
        let mut t = Table::new(
            "profile_1d",
            &[
                format!("r_or_x [{len}]"),
                format!("z_3d [{len}]"),
                format!("z1d_closed_form [{len}]"),
                format!("z1d_quadrature [{len}]"),
            ],
        );
        t.notes.push("z1d by the rule of Hess (Eq. 11): per-shape closed form and independent tanh-sinh quadrature".into());
        let limit = self.largest_radius(profile);
        let mut max_dev: f64 = 0.0;
        for k in 0..self.points {
            let x = limit * k as f64 / (self.points - 1) as f64;
            let zc = profile.z1d(x);
            let zq = profile.z1d_numeric(x).ctx("quadrature of Eq. 11")?;
            if zc > 0.0 {
                max_dev = max_dev.max(rel(zq, zc));
            }
            t.push(vec![x, profile.z(x), zc, zq]);
        }
        out.scalar("max_rel_dev_quadrature_vs_closed_form", max_dev);
        let fig = Figure::new(
            "profile_1d",
            "3D profile and its MRD image (rule of Hess, Eq. 11)",
            &format!("r, x [{len}]"),
            &format!("height [{len}]"),
        )
        .plot("3D profile z(r)", t.xy("r_or_x", "z_3d"), Style::Line)
        .plot(
            "1D image z1d(x), closed form",
            t.xy("r_or_x", "z1d_closed_form"),
            Style::Line,
        )
        .plot(
            "1D image z1d(x), quadrature of Eq. 11",
            t.xy_sampled("r_or_x", "z1d_quadrature", 25),
            Style::Markers,
        );
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
