//! `sliding_friction_3d`: the 3D reference for Fig. 7. A rigid periodic rough surface
//! slides in steady state over a viscoelastic half-space (`bem3d::sliding`: exact for
//! the discretised surface, frictionless interface, mean pressure prescribed); its
//! friction coefficient mu(v) is put next to MRD's on lines with the matching spectrum
//! (`sliding_friction`, C1D = pi q C2D, the same rms height, material, force and
//! velocities) and next to Eq. (82) with xi fitted separately to each.
//!
//! Section 10.1 of the paper leaves open whether MRD or Eq. (82) is off, for want of a
//! 3D calculation; this output is that calculation. Its accuracy is shown per velocity:
//! mu by two routes (slopes, dissipated power) and on two grids (the surfaces are
//! band-limited and drawn on a base grid, so the same surface is solved at `grid` and
//! `grid / 2`). Eq. (82)'s form is tested by a second fit in which the frequency k v
//! becomes c k v (c = 1 is the paper's form).
//!
//! Load: the mean pressure p = F / L^2 for the reduced force F / (4 G(inf) h L) of
//! `sliding_friction` (G(inf) the relaxed modulus). The half-space's contact modulus is
//! E*(omega) = 4 G(omega) (incompressible), G(omega) exact for Eq. (84).

mod report;
mod solve;

use crate::checks::{bad, require_positive};
use crate::context::Context;
use crate::error::Result;
use crate::experiment::elastomer::{self, Material};
use crate::experiment::sliding_line::LineSpec;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use bem3d::SlidingSolution;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlidingFriction3d {
    /// The elastomer's modulus, e.g. { kind = "eq84", g0, g1, tau1, tau2, s, terms } (Eq.
    /// 84).
    material: Material,
    /// The surface's spectrum: `band` or `self_affine` (as `sliding_friction`'s `line`).
    surface: LineSpec,
    /// Side L of the periodic square and rms height h (length units).
    length: f64,
    /// Rms height h of the surface [length].
    rms_height: f64,
    /// Cells per side.
    grid: usize,
    /// Also solve every surface on grid / 2 and report the change (default true).
    #[serde(default = "crate::checks::default_true")]
    coarse_check: bool,
    /// Mean pressure as p L / (4 G(inf) h): `sliding_friction`'s reduced force with
    /// F = p L^2.
    reduced_force: f64,
    /// Sliding velocities: `velocities` values log-spaced from `velocity_min` to
    /// `velocity_max` (length units per second).
    velocity_min: f64,
    /// Largest sliding velocity [length / time].
    velocity_max: f64,
    /// Velocities, log-spaced from velocity_min to velocity_max.
    velocities: usize,
    /// Rough surfaces averaged.
    realisations: u64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// Convergence criterion of the 3D solver (see `bem3d::solver`).
    #[serde(default = "tolerance")]
    tolerance: f64,
    /// Outer iterations per solve (and inner iterations per outer one).
    #[serde(default = "max_iterations")]
    max_iterations: usize,
    /// A velocity is resolved where both discretisation measures stay below this: the
    /// largest relative difference of the two routes to mu over the surfaces, and a third
    /// of the relative change of mean mu from grid / 2 to grid (the fine grid's error by
    /// Richardson for the measured order 2). Eq. (82) is fitted, to both sides, over the
    /// resolved velocities only.
    #[serde(default = "crate::experiment::sliding_line::default_error_limit")]
    error_limit: f64,
    /// The MRD side; omitted: 3D and Eq. (82) only.
    mrd: Option<MrdSide>,
}

/// MRD settings (the rest is shared with the 3D side).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct MrdSide {
    springs: usize,
    #[serde(default = "crate::checks::default_count::<1>")]
    refine: usize,
    #[serde(default = "crate::checks::default_count::<1>")]
    stride: usize,
    #[serde(default = "crate::experiment::sliding_line::default_line_tolerance")]
    tolerance: f64,
    #[serde(default = "crate::experiment::sliding_line::default_max_passes")]
    max_passes: usize,
}

fn tolerance() -> f64 {
    1e-6
}
fn max_iterations() -> usize {
    2000
}

/// One steady 3D solve; NaN results where it did not converge.
#[derive(Debug, Clone, Copy)]
struct Run {
    mu: f64,
    mu_dissipation: f64,
    contact_fraction: f64,
    mean_gap: f64,
    outer: usize,
    inner: usize,
    residual: f64,
    converged: bool,
}

impl Run {
    fn of(s: &SlidingSolution, cells: usize) -> Self {
        Self {
            mu: s.mu,
            mu_dissipation: s.mu_dissipation,
            contact_fraction: s.contact.contact_cells as f64 / cells as f64,
            mean_gap: s.contact.mean_gap,
            outer: s.contact.iterations,
            inner: s.inner_iterations,
            residual: s.contact.residual,
            converged: true,
        }
    }
}

/// One surface on each grid, with its k = rms slope / rms height and rms gradient.
struct Surface3d {
    heights: Vec<Vec<f64>>,
    k: f64,
    grad_z: f64,
}

/// The surfaces' statistics and the 3D runs: `runs[grid][velocity][surface]`.
struct Solved {
    k: f64,
    grad_z: f64,
    pressure: f64,
    grids: Vec<usize>,
    runs: Vec<Vec<Vec<Run>>>,
}

impl Output for SlidingFriction3d {
    fn validate(&self, _: &Context) -> Result<()> {
        let shear = self.material.validate()?;
        self.surface.validate("surface")?;
        if matches!(self.surface, LineSpec::Sinusoid { .. }) {
            return bad("surface: sinusoid is not available in 3D; use band or self_affine");
        }
        require_positive("length", self.length)?;
        require_positive("rms_height", self.rms_height)?;
        require_positive("reduced_force", self.reduced_force)?;
        let least = self.base_grid() * if self.coarse_check { 2 } else { 1 };
        if !(least..=4096).contains(&self.grid) {
            return bad(format!(
                "grid = {} must lie in {least}..=4096: the surface has wave numbers up to {:.2} (over L){}",
                self.grid,
                self.surface.max_waves(),
                if self.coarse_check { " and coarse_check solves on grid / 2 too" } else { "" }
            ));
        }
        crate::checks::check_memory_per_thread(
            (self.grid * self.grid) as f64 * crate::checks::cell_bytes::SLIDING,
            &format!("grid = {}", self.grid),
        )?;
        elastomer::velocities(
            self.velocity_min,
            self.velocity_max,
            self.velocities,
            &shear,
            self.surface.q_range(self.length),
        )?;
        if !(2..=1000).contains(&self.realisations) {
            return bad("realisations must lie in 2..=1000 (for intervals)");
        }
        if !(self.tolerance > 0.0 && self.tolerance < 0.1) || self.max_iterations == 0 {
            return bad("tolerance must lie in (0, 0.1) and max_iterations be >= 1");
        }
        if !(self.error_limit > 0.0 && self.error_limit <= 1.0) {
            return bad("error_limit must lie in (0, 1]");
        }
        // The MRD side is checked as the `sliding_friction` output's ensemble.
        if let Some(m) = &self.mrd {
            self.mrd_counterpart(m)
                .validate()
                .map_err(|e| e.within("mrd"))?;
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::RoughSynthesis, Stage::ViscoelasticSliding3d];
        if self.mrd.is_some() {
            s.push(Stage::ViscoelasticSliding);
        }
        s
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let solved = self.solve_3d(env, out)?;
        let mrd = match &self.mrd {
            Some(m) => Some(self.mrd_counterpart(m).simulate(out)?),
            None => None,
        };
        self.report(
            env,
            out,
            &solved,
            mrd.as_ref().map(|(l, p)| (l.as_slice(), p.as_slice())),
        )
    }
}
