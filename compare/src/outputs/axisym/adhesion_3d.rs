//! `adhesion_3d`: an adhesive loading-unloading cycle of a body of revolution in 3D and
//! in MRD side by side (Section 5): the force-approach loop, the pull-off force under
//! force control (the smallest force of the approach-controlled branch) and the jump-out
//! under approach control, each on a ladder of grids, against MRD's rule of Hess
//! (Eq. 33, exact for bodies of revolution) and the closed forms where the profile has
//! one (JKR, Kendall's punch Eq. 34, the cone Eq. 37).
//!
//! The 3D side is `bem3d::adhesion` on a non-periodic half-space: zero-range adhesion
//! with Pohrt & Popov's mesh-dependent detachment criterion, the 3D counterpart of
//! Eq. 33, which converges to the Griffith (JKR) limit as the cells shrink. Both sides
//! load without adhesion at a distance (cells and springs join on touching) and unload
//! through the adhesive branch, so their loops are the same construction.

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::{
    check_adhesive_cycle, default_adhesive_extent, default_adhesive_steps,
};
use crate::experiment::hess;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use bem3d::adhesion::AdhesiveContact;
use bem3d::{Load, NonPeriodicHalfSpace};
use mrd::adhesion::{AdhesiveContact as AdhesiveRow, Control, PullOff};
use mrd::reference::for_profile;
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Adhesion3d {
    /// Work of adhesion [energy / length^2].
    gamma: f64,
    /// Depth of the loading [length].
    depth_max: f64,
    /// Cells per side of the 3D grids, coarse to fine (a grid-convergence ladder).
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Side of the 3D grid over the contact diameter at `depth_max` (the free
    /// half-space needs no margin for images; >= 1.1 keeps the rim inside).
    #[serde(default = "default_adhesive_extent")]
    extent: f64,
    /// Approach steps of the loading; the unloading goes down by the same step until
    /// the body separates.
    #[serde(default = "default_adhesive_steps")]
    steps: usize,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_cells() -> Vec<usize> {
    vec![32, 64, 128]
}

/// One grid's cycle: the unloading branch's points and its pull-off measures.
struct Cycle3d {
    cells: usize,
    /// Cell size [length].
    h: f64,
    /// (depth, force, contact radius, unloading).
    curve: Vec<(f64, f64, f64, bool)>,
    /// The smallest force of the unloading branch (force control's pull-off).
    pull_off: f64,
    /// Force and depth of the last step in contact (approach control's jump-out).
    jump_force: f64,
    jump_depth: f64,
    rounds: usize,
    iterations: usize,
}

/// MRD's loop and pull-offs: (loading and unloading curve, force and approach control).
struct Mrd {
    curve: Vec<(f64, f64, f64, bool)>,
    force: PullOff,
    approach: PullOff,
}

impl Output for Adhesion3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        ctx.profile()?;
        check_adhesive_cycle(
            self.gamma,
            self.depth_max,
            &self.cells,
            self.extent,
            self.steps,
            self.tolerance,
        )
    }

    fn stages(&self, ctx: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::AdhesionSemiAnalytic];
        if has_closed_form(ctx) {
            s.push(Stage::ClosedForm);
        }
        s.push(Stage::Adhesion3d);
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let contact = hess::hess(env, out)?;
        let e = env.ctx.material.e_star;
        let gamma = self.gamma;
        let mrd = out
            .stage(Stage::AdhesionSemiAnalytic, || self.mrd(contact))
            .ctx("MRD adhesion")?;
        let profile = env.ctx.profile()?;
        // Bodies without a closed-form pull-off (a power law, a tabulated profile, ...)
        // are compared with MRD alone.
        let closed = if has_closed_form(env.ctx) {
            out.stage(Stage::ClosedForm, || {
                (
                    for_profile::pull_off(profile, e, gamma, true),
                    for_profile::pull_off(profile, e, gamma, false),
                )
            })
        } else {
            (None, None)
        };
        let a_top = mrd.curve.iter().map(|c| c.2).fold(0.0, f64::max);
        self.check_resolution(&mrd, a_top)?;
        let grids = out
            .stage(Stage::Adhesion3d, || {
                self.cells
                    .iter()
                    .map(|&n| self.cycle_3d(env, n, a_top))
                    .collect::<bem3d::Result<Vec<_>>>()
            })
            .ctx("3D adhesive cycle")?;
        self.report(env, out, &mrd, &grids);
        self.report_pull_off(env, out, &mrd, closed, &grids);
        Ok(())
    }
}

/// Whether the scene's body has a closed-form pull-off (under force control; the
/// approach-controlled one exists for the same bodies).
fn has_closed_form(ctx: &Context) -> bool {
    ctx.profile
        .as_ref()
        .and_then(|p| for_profile::pull_off(p, 1.0, 1.0, true))
        .is_some()
}

/// Fewest cells per pull-off radius on the finest grid, and the largest approach step
/// over the jump-out depth, with which the 3D cycle can see the pull-off at all (the
/// embedded scenes have 50-77 cells and steps of 0.002-0.06 jump-out depths).
const MIN_CELLS_PER_PULL_OFF_RADIUS: f64 = 4.0;
const MAX_STEP_OVER_JUMP_OUT_DEPTH: f64 = 0.5;

impl Adhesion3d {
    /// Refuses, before the 3D cycles run, a scene whose grids or approach steps are too
    /// coarse for the pull-off MRD predicts: the grid spans the contact at `depth_max`,
    /// so a deep loading leaves the pull-off radius a fraction of a cell.
    fn check_resolution(&self, mrd: &Mrd, a_top: f64) -> Result<()> {
        let n = *self.cells.last().unwrap_or(&16);
        let h = self.extent * 2.0 * a_top / n as f64;
        let per = mrd.force.radius / h;
        if per.is_nan() || per < MIN_CELLS_PER_PULL_OFF_RADIUS {
            return bad(format!(
                "the finest grid (cells = {n}) spans the contact radius {a_top:e} reached at depth_max = {:e}, so MRD's pull-off radius {:e} covers {per:.3e} cells (at least {MIN_CELLS_PER_PULL_OFF_RADIUS} needed): lower depth_max or raise cells",
                self.depth_max, mrd.force.radius
            ));
        }
        let step = self.depth_max / self.steps as f64;
        let jump = mrd.approach.depth.abs();
        if step.is_nan() || step > MAX_STEP_OVER_JUMP_OUT_DEPTH * jump {
            return bad(format!(
                "one approach step, depth_max / steps = {step:e}, exceeds {MAX_STEP_OVER_JUMP_OUT_DEPTH} of the jump-out depth {jump:e} MRD predicts: the unloading would jump past the pull-off; raise steps or lower depth_max"
            ));
        }
        Ok(())
    }

    /// MRD: loading without adhesion to `depth_max`, unloading by the rule of Hess down
    /// to the jump-out of approach control (the smaller radius of the two controls).
    fn mrd(&self, contact: mrd::normal::AxisymmetricContact) -> mrd::Result<Mrd> {
        let ad = AdhesiveRow::new(contact.clone(), self.gamma)?;
        let top = contact.state_at_depth(self.depth_max)?;
        let a_max = top.radius;
        let force = ad.pull_off(a_max, Control::Force)?;
        let approach = ad.pull_off(a_max, Control::Displacement)?;
        let points = 200;
        let mut curve = Vec::with_capacity(2 * points + 2);
        for k in 0..=points {
            let a = a_max * k as f64 / points as f64;
            let s = contact.state_at_radius(a)?;
            curve.push((s.depth, s.force, a, false));
        }
        curve.push((top.depth, top.force, a_max, true));
        for k in 0..=points {
            let a = a_max - (a_max - approach.radius) * k as f64 / points as f64;
            curve.push((ad.depth_at_radius(a)?, ad.force_at_radius(a)?, a, true));
        }
        Ok(Mrd {
            curve,
            force,
            approach,
        })
    }

    /// The 3D cycle on an `n x n` non-periodic grid of side `extent * 2 a_top`.
    fn cycle_3d(&self, env: &Env, n: usize, a_top: f64) -> bem3d::Result<Cycle3d> {
        let profile = env
            .ctx
            .profile()
            .map_err(|e| bem3d::BemError::InvalidInput(format!("profile: {e}")))?;
        let l = self.extent * 2.0 * a_top;
        let h = l / n as f64;
        let radius = bem3d::mask::centred(n, l, f64::hypot);
        // Cells beyond the rim (a punch) or the profile's table cannot touch.
        let reach = profile.max_contact_radius();
        let mask: Vec<bool> = radius.iter().map(|r| *r < reach).collect();
        let heights: Vec<f64> = (0..n * n)
            .map(|k| if mask[k] { -profile.z(radius[k]) } else { 0.0 })
            .collect();
        // Approaches from the apex (z = 0), as MRD's depths: the solver's are from the
        // highest cell.
        let apex = (0..n * n)
            .filter(|&k| mask[k])
            .map(|k| heights[k])
            .fold(f64::NEG_INFINITY, f64::max);
        let op = NonPeriodicHalfSpace::new(n, n, l, l, env.ctx.material.e_star);
        let mut c = AdhesiveContact::new(op, &heights, Some(&mask), self.gamma)?;
        let dd = self.depth_max / self.steps as f64;
        let mut cycle = Cycle3d {
            cells: n,
            h,
            curve: Vec::new(),
            pull_off: 0.0,
            jump_force: 0.0,
            jump_depth: 0.0,
            rounds: 0,
            iterations: 0,
        };
        let mut record = |d: f64, unloading: bool, c: &mut AdhesiveContact<_>| {
            let s = c.step(Load::Approach(d + apex), self.tolerance)?;
            cycle.rounds += s.rounds;
            cycle.iterations += s.iterations;
            if !s.separated {
                let a = (s.contact_area / PI).sqrt();
                cycle.curve.push((d, s.force, a, unloading));
            }
            Ok::<bool, bem3d::BemError>(s.separated)
        };
        for k in 1..=self.steps {
            record(dd * k as f64, false, &mut c)?;
        }
        // Unloading until separation; a guard far below any jump-out.
        let mut separated = false;
        for k in 0..100 * self.steps {
            if record(self.depth_max - dd * k as f64, true, &mut c)? {
                separated = true;
                break;
            }
        }
        if !separated {
            return Err(bem3d::BemError::Infeasible(format!(
                "the body did not separate within {} approach steps below depth_max",
                100 * self.steps
            )));
        }
        let unloading = cycle.curve.iter().filter(|p| p.3);
        let last = unloading.clone().next_back().copied().unwrap_or_default();
        cycle.pull_off = unloading.map(|p| p.1).fold(f64::INFINITY, f64::min);
        cycle.jump_force = last.1;
        cycle.jump_depth = last.0;
        Ok(cycle)
    }
}

/// The closed-form pull-off magnitudes (force control, approach control) and their
/// sources, where the profile has them.
type ClosedForms<'a> = (Option<(f64, &'a str)>, Option<(f64, &'a str)>);

/// Observed order of convergence between the last two grids of a ladder.
fn observed_order(err: &[(f64, f64)]) -> f64 {
    match err {
        [.., (n1, e1), (n2, e2)] => (e1 / e2).ln() / (n2 / n1).ln(),
        _ => f64::NAN,
    }
}

impl Adhesion3d {
    /// The loops' table and figure (the pull-offs: [`Self::report_pull_off`]).
    fn report(&self, env: &Env, out: &mut Section, mrd: &Mrd, grids: &[Cycle3d]) {
        let u = &env.ctx.units;
        let (len, force) = (&u.length, u.force());
        let mut t = Table::new(
            "cycle",
            &[
                "cells [cells]".to_string(),
                format!("depth [{len}]"),
                format!("force [{force}]"),
                format!("contact_radius [{len}]"),
                "unloading [0/1]".to_string(),
            ],
        );
        t.notes.push(format!(
            "work of adhesion {:e} [{}]; cells = 0: MRD (loading without adhesion, unloading by the rule of Hess, Eq. 33, to the jump-out of approach control); cells = n: 3D, n x n free half-space of side {} contact diameters, approach steps of depth_max / {}, contact radius sqrt(area / pi)",
            self.gamma,
            u.surface_energy(),
            self.extent,
            self.steps
        ));
        for p in &mrd.curve {
            t.push(vec![0.0, p.0, p.1, p.2, p.3 as u8 as f64]);
        }
        for g in grids {
            for p in &g.curve {
                t.push(vec![g.cells as f64, p.0, p.1, p.2, p.3 as u8 as f64]);
            }
        }
        let mut fig = Figure::new(
            "cycle",
            "Adhesive loading and unloading: 3D boundary elements and MRD",
            &format!("depth d [{len}]"),
            &format!("normal force F [{force}]"),
        );
        let branch = |cells: usize, unloading: bool| -> Vec<(f64, f64)> {
            t.rows
                .iter()
                .filter(|r| r[0] == cells as f64 && (r[4] == 1.0) == unloading)
                .map(|r| (r[1], r[2]))
                .collect()
        };
        // 3D first (every few steps, so the lines stay visible), MRD's lines on top.
        let stride = (self.steps / 25).max(1);
        for (k, g) in grids.iter().enumerate() {
            let mut pts = branch(g.cells, false);
            pts.extend(branch(g.cells, true));
            let pts: Vec<(f64, f64)> = pts.into_iter().step_by(stride).collect();
            let style = if k + 1 == grids.len() {
                Style::Markers
            } else {
                Style::Crosses
            };
            fig = fig.plot(
                format!(
                    "3D, {}^2 cells ({:.0} per pull-off radius), every {stride} steps",
                    g.cells,
                    mrd.force.radius / g.h
                ),
                pts,
                style,
            );
        }
        fig = fig
            .plot(
                "MRD loading (springs join on touching)",
                branch(0, false),
                Style::Line,
            )
            .plot(
                "MRD unloading (rule of Hess, Eq. 33)",
                branch(0, true),
                Style::Line,
            );
        // The two ends of an adhesive contact on MRD's unloading branch: the force minimum
        // (the pull-off a force-controlled test reads) and the last contact (the jump-out
        // of an approach-controlled one).
        let unloading = branch(0, true);
        if let (Some(&min), Some(&last)) = (
            unloading.iter().min_by(|a, b| a.1.total_cmp(&b.1)),
            unloading.last(),
        ) {
            // Drawn as a horizontal line at the pull-off force and a vertical one at the
            // jump-out depth, over the branch's range, so that both read at a glance.
            let (x0, x1) = unloading
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p.0), b.max(p.0))
                });
            let span = -min.1;
            fig = fig
                .plot(
                    format!("pull-off under force control: F = {:.4e}", min.1),
                    vec![(x0, min.1), (x1, min.1)],
                    Style::Dashed,
                )
                .plot(
                    format!("jump-out under approach control: d = {:.4e}", last.0),
                    vec![(last.0, min.1 - 0.5 * span), (last.0, 0.5 * span)],
                    Style::Dashed,
                );
        }
        out.tables.push(t);
        out.figures.push(fig);
    }

    /// The pull-off table, its convergence figure and the scalars.
    fn report_pull_off(
        &self,
        env: &Env,
        out: &mut Section,
        mrd: &Mrd,
        (closed_force, closed_approach): ClosedForms,
        grids: &[Cycle3d],
    ) {
        let u = &env.ctx.units;
        let (len, force) = (&u.length, u.force());
        let mut t = Table::new(
            "pull_off",
            &[
                "cells [cells]".to_string(),
                "cells_per_pull_off_radius [1]".to_string(),
                format!("pull_off_force_3d [{force}]"),
                format!("pull_off_force_mrd [{force}]"),
                "pull_off_rel_error_3d [1]".to_string(),
                format!("jump_out_force_3d [{force}]"),
                format!("jump_out_force_mrd [{force}]"),
                format!("jump_out_depth_3d [{len}]"),
                format!("jump_out_depth_mrd [{len}]"),
                "jump_out_depth_rel_error_3d [1]".to_string(),
                "rounds [count]".to_string(),
                "iterations [count]".to_string(),
            ],
        );
        t.notes.push(format!(
            "pull-off: the smallest force of the approach-controlled unloading (force control's pull-off); jump-out: the last step in contact under approach control, its depth within one approach step (depth_max / {}) of the jump (the force there is ill-conditioned: F(d) has a vertical tangent at the jump); errors against MRD (exact for bodies of revolution); cells per pull-off radius: MRD's force-control pull-off radius {:e} [{len}] over the cell size",
            self.steps, mrd.force.radius
        ));
        let (f_po, f_jump) = (mrd.force.force, mrd.approach.force);
        let mut err_po = Vec::new();
        let mut err_jump = Vec::new();
        for g in grids {
            let per = mrd.force.radius / g.h;
            let e1 = g.pull_off / f_po - 1.0;
            let e2 = g.jump_depth / mrd.approach.depth - 1.0;
            err_po.push((per, e1.abs()));
            err_jump.push((per, e2.abs()));
            t.push(vec![
                g.cells as f64,
                per,
                g.pull_off,
                f_po,
                e1,
                g.jump_force,
                f_jump,
                g.jump_depth,
                mrd.approach.depth,
                e2,
                g.rounds as f64,
                g.iterations as f64,
            ]);
        }
        if let Some((v, source)) = closed_force {
            out.scalar("pull_off_rel_error_mrd", (-f_po / v - 1.0).abs());
            t.notes.push(format!(
                "closed form (force control, {source}): {:e} [{force}]",
                -v
            ));
        }
        if let Some((v, source)) = closed_approach {
            out.scalar("jump_out_rel_error_mrd", (-f_jump / v - 1.0).abs());
            t.notes.push(format!(
                "closed form (approach control, {source}): {:e} [{force}]",
                -v
            ));
        }
        let finest = err_po.last().copied().unwrap_or((f64::NAN, f64::NAN));
        out.scalar("cells_per_pull_off_radius", finest.0);
        out.scalar("pull_off_rel_error_3d", finest.1);
        out.scalar("pull_off_order_3d", observed_order(&err_po));
        out.scalar(
            "jump_out_depth_rel_error_3d",
            err_jump.last().map_or(f64::NAN, |e| e.1),
        );
        out.scalar(
            "approach_step_over_jump_out_depth",
            self.depth_max / self.steps as f64 / mrd.approach.depth.abs(),
        );
        let fig = Figure::new(
            "convergence",
            "3D pull-off against MRD: error against the grid",
            "cells per pull-off radius [1]",
            "relative error against MRD [1]",
        )
        .plot("pull-off force (force control)", err_po, Style::Markers)
        .plot(
            "jump-out depth (approach control)",
            err_jump.clone(),
            Style::Crosses,
        )
        .plot(
            "one approach step over the jump-out depth (the depth's resolution)",
            vec![
                (
                    err_jump[0].0,
                    self.depth_max / self.steps as f64 / mrd.approach.depth.abs(),
                ),
                (
                    finest.0,
                    self.depth_max / self.steps as f64 / mrd.approach.depth.abs(),
                ),
            ],
            Style::Dashed,
        )
        .log_log();
        out.tables.push(t);
        out.figures.push(fig);
    }
}
