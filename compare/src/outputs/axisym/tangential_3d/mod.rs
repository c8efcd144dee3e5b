//! `tangential_3d`: a body of revolution pressed and then loaded tangentially, in 3D and
//! in MRD side by side (Sections 6 and 7): the stick radius against the tangential force
//! and the energy dissipated per cycle of an oscillating tangential force; for a sphere
//! also against the closed forms (Cattaneo-Mindlin, Eqs. 41-50; Mindlin-Deresiewicz),
//! for other bodies (a cone, a power law) against MRD's exact springs (Jaeger).
//!
//! The 3D side solves the normal contact on a periodic half-space (the sphere at the
//! centre of a cell of `period` contact radii) or, with `periodic = false`, on the free
//! half-space (a grid of side `period` contact radii, no images), and then partial slip
//! under that pressure (`bem3d::tangential`, the operator of the same half-space); the
//! MRD side is the exact tangential springs of the rule of
//! Hess. The 3D tangential operator takes the shear modulus G and Poisson's ratio nu of
//! one body equivalent to the scene's E* and G* (rigid indenter: E* = 2G/(1 - nu),
//! G* = 4G/(2 - nu)); for two elastic bodies that is the uncoupled approximation.

mod report;

use crate::checks::{bad, check_memory, check_tolerance, default_tolerance, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::{equivalent_body, AxisymGrid};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::tangential::{CerrutiFree, CerrutiPeriodic, PartialSlip, TangentialCompliance};
use bem3d::SolverOptions;
use mrd::oscillation::dissipation_semi_analytic;
use mrd::reference::{for_profile, mindlin_damping as md};
use mrd::tangential::TangentialContact;
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tangential3d {
    /// Coulomb friction coefficient.
    mu: f64,
    /// Normal force F_N, held while the tangential load acts [force].
    normal_force: f64,
    /// Cells per side of the 3D grid.
    #[serde(default = "crate::checks::default_count::<128>")]
    cells: usize,
    /// The side of the 3D grid in contact radii: its period on the periodic half-space
    /// (>= 10 keeps the periodic images' effect on the dissipation under 1 %), the
    /// extent of the free one (> 2: the contact fits with a margin).
    #[serde(default = "default_period")]
    period: f64,
    /// The periodic half-space (default) or the free one (`false`: no periodic images,
    /// the shift absolute).
    #[serde(default = "crate::checks::default_true")]
    periodic: bool,
    /// Tangential forces of the stick-radius table, as fractions of mu F_N, increasing;
    /// default 0.1, 0.2, ..., 0.9.
    #[serde(default = "default_fractions")]
    fractions: Vec<f64>,
    /// Force amplitudes of the oscillation, as fractions of mu F_N.
    #[serde(default = "default_amplitudes")]
    amplitudes: Vec<f64>,
    /// Force steps per half cycle of the 3D oscillation.
    #[serde(default = "crate::checks::default_count::<20>")]
    steps: usize,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_period() -> f64 {
    10.0
}
fn default_fractions() -> Vec<f64> {
    (1..10).map(|k| k as f64 / 10.0).collect()
}
fn default_amplitudes() -> Vec<f64> {
    vec![0.2, 0.4, 0.6, 0.8]
}

impl Output for Tangential3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if ctx.profile()?.rim().is_some() {
            return bad("tangential_3d needs a curved body (sphere, cone, power law): a flat punch's tangential traction is proportional to its pressure (Jaeger, uncoupled), so it sticks everywhere until it slides as a whole, with no partial slip or dissipation to compare");
        }
        require_positive("friction coefficient mu", self.mu)?;
        require_positive("normal_force", self.normal_force)?;
        let g = ctx.material.g_star().ctx("tangential_3d")?;
        let (nu, _) = equivalent_body(ctx.material.e_star, g);
        if !(0.0..=0.5).contains(&nu) {
            return bad(format!(
                "G*/E* = {} gives Poisson's ratio {nu:.3} outside [0, 0.5]: G*/E* must lie in [2/3, 1]",
                g / ctx.material.e_star
            ));
        }
        if !(16..=4096).contains(&self.cells) {
            return bad(format!("cells = {} must lie in 16..=4096", self.cells));
        }
        check_memory(
            (self.cells * self.cells) as f64
                * crate::checks::cell_bytes::tangential_3d(self.periodic),
            &format!("cells = {}", self.cells),
        )?;
        let least = if self.periodic { 3.0 } else { 2.2 };
        if !(self.period.is_finite() && (least..=1000.0).contains(&self.period)) {
            return bad(format!(
                "period = {} contact radii must lie in [{least}, 1000] on the {} half-space",
                self.period,
                if self.periodic { "periodic" } else { "free" }
            ));
        }
        let per_radius = self.cells as f64 / self.period;
        if per_radius < crate::checks::MIN_CELLS_PER_CONTACT_RADIUS {
            return bad(format!(
                "cells / period = {} / {} = {per_radius:.3} cells per contact radius: the 3D contact needs at least {} (raise cells or lower period)",
                self.cells,
                self.period,
                crate::checks::MIN_CELLS_PER_CONTACT_RADIUS
            ));
        }
        for (key, v) in [
            ("fractions", &self.fractions),
            ("amplitudes", &self.amplitudes),
        ] {
            if v.is_empty() || v.iter().any(|f| !(*f > 0.0 && *f < 1.0)) {
                return bad(format!("{key} = {v:?}: give fractions of mu F_N in (0, 1)"));
            }
        }
        // The stick radii are read along one monotonic loading (a smaller force after a
        // larger one would be an unloading, with other stick radii).
        if self.fractions.windows(2).any(|w| w[1] <= w[0]) {
            return bad(format!(
                "fractions = {:?} must increase: they are read along one monotonic loading",
                self.fractions
            ));
        }
        if !(2..=1000).contains(&self.steps) {
            return bad(format!(
                "steps = {} per half cycle must lie in 2..=1000",
                self.steps
            ));
        }
        check_tolerance(self.tolerance)
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let mut s = hess::stages(Stage::Tangential, hess::is_sphere(ctx));
        s.extend([Stage::Bem3d, Stage::Tangential3d]);
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let contact = hess::hess(env, out)?;
        let profile = ctx.profile()?.clone();
        let e = ctx.material.e_star;
        let g = ctx.material.g_star().ctx("tangential_3d")?;
        let (mu, fn_) = (self.mu, self.normal_force);
        let tc = out
            .stage(Stage::NormalSemiAnalytic, || {
                TangentialContact::new(contact, g, mu, fn_)
            })
            .ctx("normal contact")?;
        let (a, depth) = (tc.normal.radius, tc.normal.depth);
        let mrd = out
            .stage(
                Stage::Tangential,
                || -> mrd::Result<(Vec<f64>, Vec<f64>)> {
                    let c = self
                        .fractions
                        .iter()
                        .map(|f| Ok(tc.at_force(f * mu * fn_)?.stick_radius / a))
                        .collect::<mrd::Result<Vec<_>>>()?;
                    let w = self
                        .amplitudes
                        .iter()
                        .map(|x| {
                            let amp = tc.at_force(x * mu * fn_)?.displacement;
                            dissipation_semi_analytic(&profile, e, g, mu, depth, amp)
                        })
                        .collect::<mrd::Result<Vec<_>>>()?;
                    Ok((c, w))
                },
            )
            .ctx("MRD tangential springs")?;
        // An amplitude whose slip annulus (MRD's exact stick radius) is thinner than a
        // cell slips in no 3D cell: its dissipation is not resolved.
        let cell = self.period * a / self.cells as f64;
        for x in &self.amplitudes {
            let c = tc
                .at_force(x * mu * fn_)
                .ctx("MRD tangential springs")?
                .stick_radius;
            if a - c < cell {
                out.warn(format!(
                    "amplitude {x} of mu F_N: the slip annulus is {:.2} cells wide ({:.1} cells per contact radius); the 3D dissipation there is not resolved: raise cells",
                    (a - c) / cell,
                    a / cell
                ));
            }
        }
        // Cattaneo-Mindlin and Mindlin-Deresiewicz are the sphere's; other bodies have
        // MRD (exact for bodies of revolution, Jaeger) as their reference.
        let closed = for_profile::sphere_radius(&profile).map(|_| {
            out.stage(Stage::ClosedForm, || {
                let c: Vec<f64> = self.fractions.iter().map(|x| (1.0 - x).cbrt()).collect();
                let w: Vec<f64> = self
                    .amplitudes
                    .iter()
                    .map(|x| md::dissipation_force_amplitude_exact(g, a, mu, fn_, x * mu * fn_))
                    .collect();
                (c, w)
            })
        });
        let pressure = self.normal_3d(env, out, a)?;
        // The one elastic body the 3D tangential operator takes (module docs).
        out.scalar("poisson_3d", equivalent_body(e, g).0);
        let three = out
            .stage(Stage::Tangential3d, || {
                self.partial_slip(&pressure, a, e, g)
            })
            .ctx("3D partial slip")?;
        self.report(
            env,
            out,
            a,
            (&mrd.0, closed.as_ref().map(|c| &c.0[..]), &three.0),
            (&mrd.1, closed.as_ref().map(|c| &c.1[..]), &three.1),
        );
        // Loops where the shift is absolute (the free half-space): a periodic cell's
        // shift is measured from its mean surface displacement.
        if !self.periodic {
            let sphere = closed.is_some().then_some((mu * fn_, g, a));
            self.report_loops(env, out, &tc, sphere, &three.2)
                .ctx("MRD's hysteresis loops")?;
        }
        Ok(())
    }
}

/// Dissipation per cycle: MRD, the closed form (a sphere), and the 3D (dissipation, loop
/// area) per amplitude.
type Dissipations<'a> = (&'a [f64], Option<&'a [f64]>, &'a [(f64, f64)]);

/// The 3D side: stick radii over a, per amplitude the dissipation and the loop's area,
/// and per amplitude the measured cycle's (force, shift) points.
type Results3d = (Vec<f64>, Vec<(f64, f64)>, Vec<Vec<(f64, f64)>>);

impl Tangential3d {
    /// The sphere's pressure on the grid at the normal force.
    fn normal_3d(&self, env: &Env, out: &mut Section, a: f64) -> Result<Vec<f64>> {
        let ctx = env.ctx;
        let profile = ctx.profile()?;
        let (n, l) = (self.cells, self.period * a);
        let h = l / n as f64;
        let grid = AxisymGrid {
            cells: n,
            side: l,
            periodic: self.periodic,
        };
        let opts = SolverOptions::new(self.tolerance, 10_000);
        let sol = out
            .stage(Stage::Bem3d, || {
                grid.press(profile, ctx.material.e_star, self.normal_force, &opts)
            })
            .ctx("3D normal contact")?;
        out.scalar("contact_radius_3d", (sol.contact_area / PI).sqrt());
        out.scalar("cells_per_contact_radius", a / h);
        out.scalar("grid_side_3d", l);
        Ok(sol.pressure)
    }

    /// Monotonic loading through the fractions, then per amplitude a first loading and
    /// two cycles, the second measured.
    fn partial_slip(&self, p: &[f64], a: f64, e: f64, g_star: f64) -> bem3d::Result<Results3d> {
        let (nu, g) = equivalent_body(e, g_star);
        let (n, l) = (self.cells, self.period * a);
        let fresh = || -> bem3d::Result<PartialSlip<Box<dyn TangentialCompliance + Sync>>> {
            let op: Box<dyn TangentialCompliance + Sync> = if self.periodic {
                Box::new(CerrutiPeriodic::new(n, n, l, l, g, nu)?)
            } else {
                Box::new(CerrutiFree::new(n, n, l, l, g, nu)?)
            };
            PartialSlip::new(op, p, self.mu)
        };
        let cell = (l / n as f64).powi(2);
        let tol = self.tolerance;
        let mut ps = fresh()?;
        let limit = ps.friction_limit();
        let mut stick = Vec::new();
        for f in &self.fractions {
            let s = ps.load(f * limit, tol)?;
            stick.push((s.stick_cells as f64 * cell / PI).sqrt() / a);
        }
        let (mut cycles, mut loops) = (Vec::new(), Vec::new());
        for x in &self.amplitudes {
            let amp = x * limit;
            let c = fresh()?.cycle(amp, self.steps, 2, tol)?;
            cycles.push((c.dissipated, c.loop_area));
            loops.push(c.points);
        }
        Ok((stick, cycles, loops))
    }
}
