//! `plastic_3d`: the review's open question of Section 11 for bodies of revolution:
//! does MRD in incremental form reproduce an elastic-perfectly plastic contact? A body
//! of revolution is loaded, unloaded and reloaded along a force history on a half-space
//! whose pressure saturates at the hardness H (the pressure-cap model), in 3D
//! (`bem3d::plastic`, a ladder of free grids) and by MRD (`mrd::plasticity`: the rule of
//! Hess applied at each increment to the profile as plastically deformed so far, and
//! the local spring cap), side by side: approach, contact and plastic radius, the
//! imprint left by unloading, the grid convergence of the 3D side against MRD's
//! incremental rule; for a sphere also Kogut & Etsion's finite-element fits (J2
//! plasticity, not the pressure cap: the distance between the two models is reported,
//! not a verdict on either).
//!
//! Units: the scene's (E*, H, forces, lengths). The 3D grid's side is `extent` times
//! the largest contact diameter of MRD's incremental rule; approaches are measured from
//! the undeformed apex (the 3D grid's highest cell sits below it by a fraction of a cell:
//! that offset is added back).

mod report;

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use bem3d::plastic::PlasticContact;
use bem3d::{Load, NonPeriodicHalfSpace};
use mrd::plasticity::{AxisymPlastic, PlasticRule, PlasticState};
use mrd::reference::{for_profile, kogut_etsion as ke};
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plastic3d {
    /// The hardness H: the largest contact pressure [stress].
    hardness: f64,
    /// The force history [force]: loading, unloading (0: apart) and reloading.
    forces: Vec<f64>,
    /// Cells per side of the 3D grids, coarse to fine.
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Side of the 3D grid over the largest contact diameter.
    #[serde(default = "default_extent")]
    extent: f64,
    /// Rings (springs) of MRD's radial grid, over `extent` times the largest contact
    /// radius.
    #[serde(default = "default_rings")]
    rings: usize,
    /// MRD's plasticity rules (`incremental_hess`, `spring_cap`).
    #[serde(default = "default_rules")]
    rules: Vec<String>,
    /// Poisson's ratio of Kogut & Etsion's finite-element sphere (their yield onset
    /// depends on it); the pressure-cap model has none.
    #[serde(default = "default_poisson")]
    poisson: f64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_cells() -> Vec<usize> {
    vec![32, 64, 128]
}
fn default_extent() -> f64 {
    1.3
}
fn default_rings() -> usize {
    400
}
fn default_rules() -> Vec<String> {
    vec!["incremental_hess".into(), "spring_cap".into()]
}
fn default_poisson() -> f64 {
    0.3
}

/// How run `i` of `runs` (the first `grids` of them 3D) is drawn: the finest grid as
/// circles, coarser ones as crosses (two grids that agree stay both visible), MRD as
/// lines.
fn marker(i: usize, grids: usize) -> Style {
    match i {
        i if i + 1 == grids => Style::Markers,
        i if i < grids => Style::Crosses,
        _ => Style::Line,
    }
}

/// One method's history: its label and the state after each step.
struct Run {
    label: String,
    states: Vec<PlasticState>,
    /// The imprint against the radius after the last step (radius, depth).
    imprint: Vec<(f64, f64)>,
}

impl Output for Plastic3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        let profile = ctx.profile()?;
        if profile.rim().is_some() {
            return bad("plastic_3d needs a curved body (sphere, cone, power law): a flat punch's edge pressure is singular and saturates at once");
        }
        if !(self.hardness.is_finite() && self.hardness > 0.0) {
            return bad(format!(
                "hardness = {} must be finite and > 0 (the pressure cap, in the scene's stress unit)",
                self.hardness
            ));
        }
        if self.forces.is_empty() || self.forces.len() > 10_000 {
            return bad("forces: give the force history, 1 to 10,000 values");
        }
        if let Some(f) = self.forces.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
            return bad(format!(
                "forces: {f} must be finite and >= 0 (0: the body apart, unloaded)"
            ));
        }
        if self.forces.iter().all(|f| *f == 0.0) {
            return bad("forces: the history never loads the body");
        }
        if self.cells.is_empty()
            || self.cells.iter().any(|n| !(16..=1024).contains(n))
            || self.cells.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "cells = {:?}: give increasing grid sides in 16..=1024",
                self.cells
            ));
        }
        if !(self.extent.is_finite() && (1.1..=10.0).contains(&self.extent)) {
            return bad(format!(
                "extent = {} must lie in [1.1, 10] (grid side over the largest contact diameter)",
                self.extent
            ));
        }
        if !(50..=mrd::plasticity::MAX_RINGS).contains(&self.rings) {
            return bad(format!(
                "rings = {} must lie in 50..={}",
                self.rings,
                mrd::plasticity::MAX_RINGS
            ));
        }
        if self.rules.is_empty() {
            return bad("rules: give at least one of incremental_hess and spring_cap");
        }
        for r in &self.rules {
            PlasticRule::parse(r).ctx("rules")?;
        }
        if !(0.0..=0.5).contains(&self.poisson) {
            return bad(format!("poisson = {} must lie in [0, 0.5]", self.poisson));
        }
        crate::checks::check_tolerance(self.tolerance)?;
        let largest = self.cells.last().copied().unwrap_or(0);
        crate::checks::check_memory(
            (largest * largest) as f64 * crate::checks::cell_bytes::ADHESION,
            &format!("cells = {largest}"),
        )
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::PlasticMrd, Stage::Plastic3d];
        if ctx
            .profile
            .as_ref()
            .and_then(for_profile::sphere_radius)
            .is_some()
        {
            s.push(Stage::ClosedForm);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let e = ctx.material.e_star;
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        // The reach of the contact: MRD's incremental rule on a generous grid first.
        let f_max = self.forces.iter().cloned().fold(0.0, f64::max);
        let reach = out
            .stage(Stage::PlasticMrd, || self.reach(&profile, e, f_max))
            .ctx("MRD plasticity")?;
        let mrd = out
            .stage(Stage::PlasticMrd, || -> mrd::Result<Vec<Run>> {
                self.rules
                    .iter()
                    .map(|r| self.mrd_run(&profile, e, PlasticRule::parse(r)?, reach))
                    .collect()
            })
            .ctx("MRD plasticity")?;
        let side = 2.0 * self.extent * reach;
        let three = out
            .stage(Stage::Plastic3d, || -> bem3d::Result<Vec<Run>> {
                self.cells
                    .iter()
                    .map(|&n| self.run_3d(&profile, e, n, side))
                    .collect()
            })
            .ctx("3D elastic-plastic contact")?;
        let reference = self.reference(&mrd);
        self.report(out, &mrd, &three, reference, side);
        if let Some(radius) = for_profile::sphere_radius(&profile) {
            let runs: Vec<&Run> = mrd.iter().chain(three.last()).collect();
            let (table, figure, worst) =
                out.stage(Stage::ClosedForm, || self.kogut_etsion(&runs, e, radius));
            match worst {
                Some(w) => out.scalar("kogut_etsion_load_deviation_max", w),
                None => out.warn(
                    "plastic_3d: no step of the first loading reaches Kogut & Etsion's range w/w_c in [1, 110]",
                ),
            }
            out.tables.push(table);
            out.figures.push(figure);
        }
        Ok(())
    }
}

impl Plastic3d {
    /// The largest contact radius of the history by MRD's incremental rule (on a grid of
    /// 200 rings out to four times the fully plastic radius or Hertz's, whichever is
    /// larger), widened by `extent`.
    fn reach(&self, profile: &mrd::profile::Profile, e: f64, f_max: f64) -> mrd::Result<f64> {
        let plastic = (f_max / (PI * self.hardness)).sqrt();
        let elastic = mrd::normal::AxisymmetricContact::new(profile.clone(), e)?
            .state_at_force(f_max)?
            .radius;
        let r_max = 4.0 * plastic.max(elastic);
        let mut m = AxisymPlastic::new(
            profile,
            e,
            self.hardness,
            PlasticRule::IncrementalHess,
            200,
            r_max,
        )?;
        let mut a: f64 = 0.0;
        for &f in &self.forces {
            a = a.max(m.step_to_force(f, 1e-6)?.contact_radius);
        }
        Ok(a)
    }

    fn mrd_run(
        &self,
        profile: &mrd::profile::Profile,
        e: f64,
        rule: PlasticRule,
        reach: f64,
    ) -> mrd::Result<Run> {
        let mut m = AxisymPlastic::new(
            profile,
            e,
            self.hardness,
            rule,
            self.rings,
            self.extent * reach,
        )?;
        let states = self
            .forces
            .iter()
            .map(|&f| m.step_to_force(f, self.tolerance.max(1e-10)))
            .collect::<mrd::Result<Vec<_>>>()?;
        let imprint = m.radii().into_iter().zip(m.imprint()).collect();
        Ok(Run {
            label: format!("MRD {}", rule.name()),
            states,
            imprint,
        })
    }

    /// The history on an `n x n` free grid of side `side`.
    fn run_3d(
        &self,
        profile: &mrd::profile::Profile,
        e: f64,
        n: usize,
        side: f64,
    ) -> bem3d::Result<Run> {
        let grid = AxisymGrid {
            cells: n,
            side,
            periodic: false,
        };
        let (z, mask) = grid.heights(profile);
        let top = (0..z.len())
            .filter(|&k| mask.as_ref().is_none_or(|m| m[k]))
            .map(|k| z[k])
            .fold(f64::NEG_INFINITY, f64::max);
        let op = NonPeriodicHalfSpace::try_new(n, n, side, side, e)?;
        let mut c = PlasticContact::new(op, &z, mask.as_deref(), self.hardness)?;
        let mut states = Vec::with_capacity(self.forces.len());
        for &f in &self.forces {
            let s = c.step(Load::Force(f), self.tolerance)?;
            states.push(PlasticState {
                approach: s.approach - top,
                force: s.force,
                contact_radius: (s.contact_area / PI).sqrt(),
                plastic_radius: (s.plastic_area / PI).sqrt(),
                plastic_depth: s.plastic_depth,
            });
        }
        // The imprint along the row through the centre, outwards.
        let h = side / n as f64;
        let row = n / 2;
        let imprint = (n / 2..n)
            .map(|i| {
                let x = (i as f64 + 0.5) * h - 0.5 * side;
                let y = (row as f64 + 0.5) * h - 0.5 * side;
                (x.hypot(y), c.plastic_displacement()[row * n + i])
            })
            .collect();
        Ok(Run {
            label: format!("3D {n}^2"),
            states,
            imprint,
        })
    }

    /// MRD's incremental rule, the reference of the 3D ladder (exact for bodies of
    /// revolution up to its rings).
    fn reference<'a>(&self, mrd: &'a [Run]) -> Option<&'a Run> {
        mrd.iter().find(|r| r.label.ends_with("incremental_hess"))
    }
}
