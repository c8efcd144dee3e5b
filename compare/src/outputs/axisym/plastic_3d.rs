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

    fn report(
        &self,
        out: &mut Section,
        mrd: &[Run],
        three: &[Run],
        reference: Option<&Run>,
        side: f64,
    ) {
        let runs: Vec<&Run> = three.iter().chain(mrd).collect();
        // The history, one row per step.
        let mut cols = vec!["step [index]".to_string(), "force [force]".to_string()];
        for r in &runs {
            for q in [
                "approach [length]",
                "contact_radius [length]",
                "plastic_radius [length]",
                "plastic_depth [length]",
            ] {
                cols.push(format!("{} {q}", r.label));
            }
        }
        let mut t = Table::new("history", &cols);
        t.notes.push(format!(
            "pressure-cap model, hardness H = {}: 3D on free grids of side {side:.6e} (extent {} x the largest contact diameter), contact and plastic radii from the areas (sqrt(A/pi)); MRD on {} rings: incremental_hess (the rule of Hess applied to the plastically deformed profile at each increment: exact for bodies of revolution), spring_cap (each spring capped at the fully plastic line load 2 H sqrt(a^2 - x^2)); approaches from the undeformed apex; plastic_depth: the largest plastic displacement so far; a cell or ring within 1e-6 of its cap counts as plastic",
            self.hardness, self.extent, self.rings
        ));
        for (k, &f) in self.forces.iter().enumerate() {
            let mut row = vec![k as f64, f];
            for r in &runs {
                let s = &r.states[k];
                row.extend([
                    s.approach,
                    s.contact_radius,
                    s.plastic_radius,
                    s.plastic_depth,
                ]);
            }
            t.push(row);
        }
        out.tables.push(t);
        let loop_fig = runs.iter().enumerate().fold(
            Figure::new(
                "loop",
                &format!(
                    "Force against approach, pressure cap H = {}: 3D and MRD",
                    self.hardness
                ),
                "approach d [length]",
                "force F [force]",
            ),
            |fig, (i, r)| {
                let style = marker(i, three.len());
                fig.plot(
                    r.label.clone(),
                    r.states.iter().map(|s| (s.approach, s.force)).collect(),
                    style,
                )
            },
        );
        out.figures.push(loop_fig);
        // The imprint after the last step.
        let mut fig = Figure::new(
            "imprint",
            "Plastic displacement of the surface after the history (the imprint)",
            "radius r [length]",
            "plastic displacement u_p [length]",
        );
        for (i, r) in runs.iter().enumerate() {
            fig = fig.plot(r.label.clone(), r.imprint.clone(), marker(i, three.len()));
        }
        out.figures.push(fig);
        // The 3D ladder against MRD's incremental rule.
        let Some(refr) = reference else { return };
        let worst = |r: &Run| -> f64 {
            r.states
                .iter()
                .zip(&refr.states)
                .filter(|(_, b)| b.force > 0.0)
                .map(|(a, b)| (a.approach / b.approach - 1.0).abs())
                .fold(0.0, f64::max)
        };
        let mut c = Table::new(
            "convergence",
            &[
                "cells [count]",
                "cells per largest contact radius [1]",
                "largest |d_3D / d_MRD - 1| [1]",
                "largest |depth_3D / depth_MRD - 1| [1]",
            ],
        );
        c.notes.push(format!(
            "the 3D grids against MRD's incremental rule (incremental_hess, {} rings) over the loaded steps of the history; the observed order of the 3D approach at the largest force, from the last three grids alone, is in summary.json (plastic_3d.observed_order)",
            self.rings
        ));
        let reach = side / (2.0 * self.extent);
        let depth = refr.states.last().map_or(0.0, |s| s.plastic_depth);
        let mut errs = vec![];
        for (r, &n) in three.iter().zip(&self.cells) {
            let e = worst(r);
            errs.push((n, e));
            let d3 = r.states.last().map_or(0.0, |s| s.plastic_depth);
            let depth_err = if depth > 0.0 {
                (d3 / depth - 1.0).abs()
            } else {
                0.0
            };
            c.push(vec![n as f64, n as f64 * reach / side, e, depth_err]);
        }
        out.tables.push(c);
        if let Some((_, e)) = errs.last() {
            out.scalar("approach_3d_vs_incremental_hess", *e);
        }
        // The observed order from the 3D ladder alone (the last three grids, each twice
        // the last): the approach at the largest force, Richardson's ratio of successive
        // differences.
        let at_peak = |r: &Run| {
            r.states
                .iter()
                .fold((0.0f64, 0.0), |(f, d), s| {
                    if s.force > f {
                        (s.force, s.approach)
                    } else {
                        (f, d)
                    }
                })
                .1
        };
        let k = three.len();
        if k >= 3 && self.cells[k - 3..].windows(2).all(|w| w[1] == 2 * w[0]) {
            let (d1, d2, d3) = (
                at_peak(&three[k - 3]),
                at_peak(&three[k - 2]),
                at_peak(&three[k - 1]),
            );
            let ratio = (d1 - d2) / (d2 - d3);
            if ratio > 0.0 && ratio.is_finite() {
                out.scalar("observed_order", ratio.log2());
            }
        }
        for r in mrd.iter().filter(|r| !std::ptr::eq(*r, refr)) {
            let e = worst(r);
            out.scalar(
                format!(
                    "approach_{}_vs_incremental_hess",
                    r.label.trim_start_matches("MRD ")
                ),
                e,
            );
        }
    }

    /// Kogut & Etsion's finite-element fits beside the pressure-cap model's first
    /// loading (sphere of radius `r`): the cap's hardness is their fully plastic
    /// `H = 2.8 Y`, so `Y = H / 2.8`. Each run is read at its own interference (the
    /// history is force-controlled: every run carries the same force at a step).
    fn kogut_etsion(&self, runs: &[&Run], e: f64, r: f64) -> (Table, Figure, Option<f64>) {
        let y = self.hardness / 2.8;
        let wc = ke::critical_interference(e, r, y, self.poisson);
        let pc = 4.0 / 3.0 * e * r.sqrt() * wc.powf(1.5);
        let mut cols = vec!["P/P_c [1]".to_string()];
        for run in runs {
            cols.push(format!("w/w_c {} [1]", run.label));
            cols.push(format!(
                "P/P_c Kogut-Etsion at the {} interference [1]",
                run.label
            ));
        }
        let mut t = Table::new("kogut_etsion", &cols);
        t.missing_ok = true;
        t.notes.push(format!(
            "Kogut & Etsion (J. Appl. Mech. 69 (2002) 657), finite elements with J2 plasticity (Y = H / 2.8 = {y:.6e}, nu = {}): w_c = {wc:.6e}, P_c = {pc:.6e}; the pressure-cap runs' first loading (the steps before the force first falls), each at its own interference w (approach); empty: w/w_c outside the fits' range [1, 110]; the cap yields at p0 = H, the finite elements at p0 = K H = {:.3} H",
            self.poisson,
            ke::k(self.poisson)
        ));
        // The first loading: the steps before the force first falls.
        let peak = self
            .forces
            .windows(2)
            .position(|w| w[1] < w[0])
            .unwrap_or(self.forces.len() - 1);
        let mut worst: f64 = 0.0;
        for k in 0..=peak {
            let mut row = vec![self.forces[k] / pc];
            for (i, run) in runs.iter().enumerate() {
                let x = run.states[k].approach / wc;
                let p = ke::load_ratio(x).unwrap_or(f64::NAN);
                row.extend([x, p]);
                if i + 1 == runs.len() && p.is_finite() {
                    worst = worst.max((row[0] / p - 1.0).abs());
                }
            }
            t.push(row);
        }
        let inside = t
            .rows
            .iter()
            .any(|row| row.iter().skip(2).step_by(2).any(|p| p.is_finite()));
        let xs: Vec<f64> = t
            .rows
            .iter()
            .map(|row| row[1])
            .filter(|x| *x > 0.0)
            .collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
        let curve: Vec<(f64, f64)> =
            mrd::friction::log_space(lo.max(1.0), hi.clamp(1.0, 110.0), 60)
                .into_iter()
                .filter_map(|x| ke::load_ratio(x).map(|p| (x, p)))
                .collect();
        let mut fig = Figure::new(
            "kogut_etsion",
            "Sphere, first loading: pressure cap (3D, MRD) against Kogut-Etsion's finite elements",
            "interference over its critical value w/w_c [1]",
            "load over its critical value P/P_c [1]",
        )
        .log_log()
        .plot(
            "Kogut & Etsion 2002 (FEM, J2 plasticity)",
            curve,
            Style::Dashed,
        );
        for (i, run) in runs.iter().enumerate() {
            fig = fig.plot(
                format!("{} (pressure cap)", run.label),
                t.rows
                    .iter()
                    .filter(|row| row[1 + 2 * i] > 0.0)
                    .map(|row| (row[1 + 2 * i], row[0]))
                    .collect(),
                if run.label.starts_with("3D") {
                    Style::Markers
                } else {
                    Style::Line
                },
            );
        }
        (t, fig, inside.then_some(worst))
    }
}
