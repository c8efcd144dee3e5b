//! `static_friction`: the static-friction experiment of Section 10.2 (Fig. 9): the mean
//! slope of the contacting points of MRD rough lines against the reduced force, with
//! the fit xi = a + b ln f of Eq. (91).

use crate::checks::{bad, check_line, default_force_points, default_realisations, positive};
use crate::context::Context;
use crate::error::{CompareError, Context as _, Result};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::friction::{log_space, static_friction, FrictionSetup};
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticFriction {
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// Points N of each rough line.
    points: usize,
    /// Length L of each rough line [length].
    length: f64,
    /// rms height h; or give `contacts_at_max_force` to calibrate h.
    rms_height: Option<f64>,
    /// Sets the rms height h so that about this many points touch at force_max (give this
    /// or rms_height, not both).
    contacts_at_max_force: Option<f64>,
    /// Rough lines averaged.
    #[serde(default = "default_realisations")]
    realisations: u64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// Smallest force [force per length x length].
    force_min: f64,
    /// Largest force [force per length x length].
    force_max: f64,
    /// Forces, log-spaced from force_min to force_max.
    #[serde(default = "default_force_points")]
    force_points: usize,
    /// A published fit xi = a + b ln f to draw and report alongside (optional).
    paper_a: Option<f64>,
    /// Optional: b of a published fit xi = a + b ln f drawn beside (with paper_a).
    paper_b: Option<f64>,
}

impl Output for StaticFriction {
    fn validate(&self, _: &Context) -> Result<()> {
        check_line(self.hurst, self.points, self.length, self.realisations)?;
        if self.rms_height.is_some() == self.contacts_at_max_force.is_some() {
            return bad("give exactly one of rms_height and contacts_at_max_force");
        }
        if self.rms_height.is_some_and(|h| !positive(h))
            || self
                .contacts_at_max_force
                .is_some_and(|c| !(c >= 1.0 && c < self.points as f64))
        {
            return bad("rms_height must be > 0; contacts_at_max_force in [1, points)");
        }
        if !(positive(self.force_min)
            && positive(self.force_max)
            && self.force_max > self.force_min)
        {
            return bad("need 0 < force_min < force_max");
        }
        crate::checks::count_in(
            "force_points",
            self.force_points as u64,
            3..=crate::checks::MAX_LOADS,
        )?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::RoughContact]
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let e = env.ctx.material.e_star;
        let (hurst, points, length, realisations, seed) = (
            self.hurst,
            self.points,
            self.length,
            self.realisations,
            self.seed,
        );
        let mut setup = FrictionSetup {
            hurst,
            points,
            length,
            e_star: e,
            rms_height: self.rms_height.unwrap_or(1.0),
            realisations,
            seed,
            forces: log_space(self.force_min, self.force_max, self.force_points),
        };
        // Each line is synthesised and loaded in one pass.
        let r = out
            .stages_together(
                &[Stage::RoughSynthesis, Stage::RoughContact],
                || -> mrd::Result<_> {
                    if let Some(target) = self.contacts_at_max_force {
                        // Calibrate h on min(realisations, 40) lines so that the mean number
                        // of touching points at F = force_max is the target.
                        setup.rms_height = mrd::friction::calibrate_rms_height(
                            &setup,
                            target,
                            realisations.min(40),
                        )?;
                    }
                    static_friction(&setup)
                },
            )
            .ctx("static friction")?;
        if self.contacts_at_max_force.is_some() {
            out.scalar("calibrated_rms_height", setup.rms_height);
        }
        let fitted = r
            .fit
            .ok_or_else(|| CompareError::Scene("need force_points >= 3".into()))?;
        let mut t = Table::new(
            "static_friction",
            &[
                "force [force unit]",
                "f = F/(E* h L) [1]",
                "xi_mean [1]",
                "xi_std [1]",
                "xi_ci95 [1]",
                "contacts_mean [1]",
            ],
        );
        t.notes.push(format!(
            "Section 10.2: N = {points}, L = {length}, H = {hurst}, h = {:e}, E* = {e}, {realisations} realisations (seed {seed}), band pi/L < q < 0.1 pi/dx (Eq. 85); xi = a + b ln f (Eq. 91)",
            setup.rms_height
        ));
        for p in &r.points {
            t.push(vec![
                p.force,
                p.reduced_force,
                p.xi.mean,
                p.xi.std,
                p.xi.ci95,
                p.contacts.mean,
            ]);
        }
        out.scalar("a", fitted.a);
        out.scalar("b", fitted.b);
        out.scalar("a_ci95", 1.96 * fitted.se_a);
        out.scalar("b_ci95", 1.96 * fitted.se_b);
        out.scalar(
            "contacts_at_max_force",
            r.points.last().expect("force_points >= 3").contacts.mean,
        );
        let f = t.column("f = F/(E* h L)");
        let xi = t.column("xi_mean");
        let ci = t.column("xi_ci95");
        let curve = |g: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
            (0..f.len()).map(|k| (f[k], g(k))).collect()
        };
        let mut fig = Figure::new(
            "static_friction",
            &format!("Mean slope in contact, H = {hurst} (Fig. 9)"),
            "reduced force f = F/(E* h L) [1]",
            "xi = grad z_cont / grad z [1]",
        )
        .plot(
            format!("MRD, mean of {realisations} lines"),
            curve(&|k| xi[k]),
            Style::Markers,
        )
        .plot(
            format!("fit xi = {:.4} + {:.4} ln f", fitted.a, fitted.b),
            curve(&|k| fitted.a + fitted.b * f[k].ln()),
            Style::Line,
        )
        .plot("mean +/- 95% CI", curve(&|k| xi[k] + ci[k]), Style::Dashed)
        .with(Series::new("", curve(&|k| xi[k] - ci[k]), Style::Dashed).colored(2));
        if let (Some(pa), Some(pb)) = (self.paper_a, self.paper_b) {
            out.scalar("paper_a", pa);
            out.scalar("paper_b", pb);
            fig = fig.with(
                Series::new(
                    format!("paper: xi = {pa} + {pb} ln f"),
                    curve(&|k| pa + pb * f[k].ln()),
                    Style::Dashed,
                )
                .colored(5),
            );
        }
        fig.log_x = true;
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
