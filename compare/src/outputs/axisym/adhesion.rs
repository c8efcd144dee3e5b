//! `adhesion`: an adhesive loading-unloading cycle by the rule of Hess (Eq. 33) with
//! pull-off (Eqs. 34-37), optionally on an event-driven row of springs, against JKR,
//! Eq. 37 (cone) and Eq. 34 (flat punch).

use crate::checks::{check_springs, default_points, rel, require_positive};
use crate::context::{Context, ControlSpec};
use crate::error::{Context as _, Result};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use mrd::adhesion::{simulate_cycle, AdhesiveContact, Control};
use mrd::reference::{for_profile, jkr};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Adhesion {
    /// Work of adhesion.
    gamma: f64,
    /// Depth of the loading before the unloading [length].
    depth_max: f64,
    /// Unloading under "force" (default) or "displacement" control.
    #[serde(default)]
    control: ControlSpec,
    /// Optional: springs of an event-driven discrete cycle on the half-line, beside the
    /// continuous solution.
    springs: Option<usize>,
    /// Optional: half-length of the discrete cycle's line [length].
    half_length: Option<f64>,
    /// Points of the output's curves (its sampling).
    #[serde(default = "default_points")]
    points: usize,
}

impl Adhesion {
    fn control(&self) -> Control {
        match self.control {
            ControlSpec::Force => Control::Force,
            ControlSpec::Displacement => Control::Displacement,
        }
    }
}

impl Output for Adhesion {
    fn validate(&self, ctx: &Context) -> Result<()> {
        hess::check_scene(ctx, self.points)?;
        require_positive("gamma (work of adhesion)", self.gamma)?;
        require_positive("depth_max", self.depth_max)?;
        if let Some(n) = self.springs {
            check_springs(n, crate::checks::spring_bytes::ADHESION)?;
        }
        Ok(())
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::AdhesionSemiAnalytic];
        if self.springs.is_some() {
            s.push(Stage::AdhesionDiscrete);
        }
        let fc = self.control() == Control::Force;
        if ctx
            .profile
            .as_ref()
            .and_then(|p| for_profile::pull_off(p, 1.0, 1.0, fc))
            .is_some()
        {
            s.push(Stage::ClosedForm);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let profile = env.ctx.profile()?;
        let u = &env.ctx.units;
        let (len, force) = (&u.length, u.force());
        let (points, gamma, control) = (self.points, self.gamma, self.control());
        // Loading without adhesion (springs attach on touching), then unloading pinned
        // at a_max until the rim spring reaches dl_max, then the adhesive branch.
        let (ad, top, po, loading, unloading) =
            out.stage(Stage::AdhesionSemiAnalytic, || -> Result<_> {
                let ad = AdhesiveContact::new(contact.clone(), gamma).ctx("adhesive contact")?;
                let top = contact
                    .state_at_depth(self.depth_max)
                    .ctx("top of the cycle")?;
                let a_max = top.radius;
                let po = ad.pull_off(a_max, control).ctx("pull-off")?;
                let loading = (0..=points)
                    .map(|k| {
                        let a = a_max * k as f64 / points as f64;
                        contact.state_at_radius(a).map(|s| (a, s))
                    })
                    .collect::<std::result::Result<Vec<_>, _>>()
                    .ctx("loading branch")?;
                let unloading = (0..=points)
                    .map(|k| {
                        let a = a_max - (a_max - po.radius) * k as f64 / points as f64;
                        Ok((ad.depth_at_radius(a)?, ad.force_at_radius(a)?, a))
                    })
                    .collect::<mrd::Result<Vec<_>>>()
                    .ctx("unloading branch")?;
                Ok((ad, top, po, loading, unloading))
            })?;
        let a_max = top.radius;
        let cols = [
            format!("depth [{len}]"),
            format!("force [{force}]"),
            format!("contact_radius [{len}]"),
            "unloading [0/1]".into(),
        ];
        let mut t = Table::new("adhesion", &cols);
        t.notes.push(format!(
            "work of adhesion {gamma:e} [{}]; loading without adhesion (springs attach on touching), unloading by the rule of Hess (Eq. 33), {control:?} control",
            u.surface_energy()
        ));
        for (a, s) in &loading {
            t.push(vec![s.depth, s.force, *a, 0.0]);
        }
        t.push(vec![top.depth, top.force, a_max, 1.0]);
        for &(d, f, a) in &unloading {
            t.push(vec![d, f, a, 1.0]);
        }
        out.scalar("pull_off_force", po.force);
        out.scalar("pull_off_depth", po.depth);
        out.scalar("pull_off_radius", po.radius);
        let branch = |flag: f64| -> Vec<(f64, f64)> {
            t.rows
                .iter()
                .filter(|r| r[t.index("unloading")] == flag)
                .map(|r| (r[t.index("depth")], r[t.index("force")]))
                .collect()
        };
        let mut fig = Figure::new(
            "adhesion",
            &format!("Adhesive loading and unloading ({control:?} control)"),
            &format!("depth d [{len}]"),
            &format!("normal force F [{force}]"),
        )
        .plot(
            "MRD loading (springs attach on touch)",
            branch(0.0),
            Style::Line,
        )
        .plot(
            "MRD unloading (rule of Hess, Eq. 33)",
            branch(1.0),
            Style::Line,
        );
        out.tables.push(t);
        if let Some(n) = self.springs {
            let l = crate::checks::row_half_length(self.half_length, a_max, 1.5)?;
            let cyc = out
                .stage(Stage::AdhesionDiscrete, || {
                    simulate_cycle(&ad, n, l, self.depth_max, control)
                })
                .ctx("spring row")?;
            let mut td = Table::new("adhesion_discrete", &cols);
            td.notes.push(format!(
                "event-driven spring row: {n} springs on the half-line [0, {l:e}] (mirrored)"
            ));
            for p in &cyc.curve {
                td.push(vec![p.depth, p.force, p.radius, p.unloading as u8 as f64]);
            }
            out.scalar("pull_off_force_discrete", cyc.pull_off.force);
            out.scalar(
                "pull_off_rel_dev_discrete_vs_semi_analytic",
                rel(cyc.pull_off.force, po.force),
            );
            fig = fig.plot(
                format!("MRD, {n} discrete springs"),
                td.xy_sampled("depth", "force", 60),
                Style::Markers,
            );
            out.tables.push(td);
        }
        let e = env.ctx.material.e_star;
        if let Some((f_a, source)) =
            for_profile::pull_off(profile, e, gamma, control == Control::Force)
        {
            let jkr_curve = out.stage(Stage::ClosedForm, || {
                for_profile::sphere_radius(profile).map(|radius| {
                    (0..=points)
                        .map(|k| {
                            let a = po.radius + (a_max - po.radius) * k as f64 / points as f64;
                            (
                                jkr::depth(e, radius, gamma, a),
                                jkr::force(e, radius, gamma, a),
                            )
                        })
                        .collect::<Vec<_>>()
                })
            });
            out.scalar("pull_off_force_closed_form", -f_a);
            out.scalar("pull_off_rel_error_vs_closed_form", rel(po.force, -f_a));
            if let Some(pts) = jkr_curve {
                fig = fig.plot("JKR (Johnson et al. 1971)", pts, Style::Dashed);
            }
            fig = fig.plot(
                format!("pull-off, {source}: F = {:.4e}", -f_a),
                vec![(po.depth, -f_a)],
                Style::Crosses,
            );
        }
        out.figures.push(fig);
        Ok(())
    }
}
