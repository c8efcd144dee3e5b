//! `sliding_friction_3d`'s 3D side: the surfaces on their grids and the steady sliding
//! solves at every velocity.

use super::{MrdSide, Run, SlidingFriction3d, Solved, Surface3d};
use crate::checks::bad;
use crate::error::{Context as _, Result};
use crate::experiment::progress::Progress;
use crate::experiment::sliding_line::MrdSliding;
use crate::output::Env;
use crate::plan::Stage;
use crate::report::Section;
use bem3d::{BemError, SlidingContact, SlidingSolution, SolverOptions};
use mrd::roughness::stats::surface_moments;
use mrd::roughness::synthesis::{surface_from, upsample, Amplitudes, Grid};
use rayon::prelude::*;

impl SlidingFriction3d {
    pub(super) fn velocity_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(self.velocity_min, self.velocity_max, self.velocities)
    }

    /// The base grid: the smallest power of two (>= 16) whose Nyquist wave number lies
    /// above the spectrum's highest; surfaces are drawn there and upsampled.
    pub(super) fn base_grid(&self) -> usize {
        let m = self.surface.max_waves().floor() as usize + 1;
        (2 * m).next_power_of_two().max(16)
    }

    fn grids(&self) -> Vec<usize> {
        let mut g = vec![self.grid];
        if self.coarse_check {
            g.push(self.grid / 2);
        }
        g
    }

    /// Surface `r` on each grid of `grids`, scaled to the rms height; its k = rms slope
    /// / rms height and rms gradient (exact: the surface is band-limited).
    fn surface(&self, r: u64, grids: &[usize]) -> Result<Surface3d> {
        let (n0, l) = (self.base_grid(), self.length);
        let Some(c2d) = self.surface.c2d(l) else {
            return bad("surface: sinusoid is not available in 3D; use band or self_affine");
        };
        let base = Grid::square(n0, l);
        let h =
            surface_from(&*c2d, &base, self.seed, r, Amplitudes::Deterministic).ctx("surface")?;
        let m = surface_moments(&h, n0, n0, l, l);
        let scale = self.rms_height / m.rms_height;
        let on_grids = grids
            .iter()
            .map(|&n| {
                let fine = upsample(&h, &base, &Grid::square(n, l)).ctx("surface")?;
                Ok(fine.iter().map(|v| v * scale).collect())
            })
            .collect::<Result<_>>()?;
        Ok(Surface3d {
            heights: on_grids,
            k: m.rms_slope / m.rms_height,
            grad_z: m.rms_slope * scale,
        })
    }

    /// E*(omega) = 4 G(omega); NaN where G cannot be evaluated (bem3d refuses it).
    fn contact_modulus(&self, omega: f64) -> (f64, f64) {
        self.material
            .complex(omega)
            .map(|(re, im)| (4.0 * re, 4.0 * im))
            .unwrap_or((f64::NAN, f64::NAN))
    }

    /// One surface on one grid over all velocities, in increasing order, each solve
    /// warm-started from the previous velocity's solution (deterministic: one surface is
    /// one sequential task).
    fn sweep(&self, h: &[f64], n: usize, pressure: f64, bar: &Progress) -> Result<Vec<Run>> {
        let opts = SolverOptions {
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            ..Default::default()
        };
        let modulus = |w: f64| self.contact_modulus(w);
        let l = self.length;
        let mut warm: Option<SlidingSolution> = None;
        let mut runs = Vec::new();
        for v in self.velocity_grid() {
            let mut s = SlidingContact::new(n, n, l, l, h, v, &modulus).ctx("3D sliding")?;
            let run = match s.solve(pressure, &opts, warm.as_ref()) {
                Ok(sol) => {
                    let run = Run::of(&sol, n * n);
                    warm = Some(sol);
                    run
                }
                Err(BemError::NoConvergence {
                    iterations,
                    residual,
                    ..
                }) => Run {
                    mu: f64::NAN,
                    mu_dissipation: f64::NAN,
                    contact_fraction: f64::NAN,
                    mean_gap: f64::NAN,
                    outer: iterations,
                    inner: 0,
                    residual,
                    converged: false,
                },
                Err(e) => return Err(e).ctx(format!("3D sliding at v = {v:e}, grid {n}")),
            };
            runs.push(run);
            bar.inc();
        }
        Ok(runs)
    }

    pub(super) fn solve_3d(&self, env: &Env, out: &mut Section) -> Result<Solved> {
        let shear = self.material.shear().ctx("material")?;
        let pressure = self.reduced_force * 4.0 * shear.relaxed * self.rms_height / self.length;
        let grids = self.grids();
        let surfaces: Vec<Surface3d> = out.stage(Stage::RoughSynthesis, || {
            (0..self.realisations)
                .map(|r| self.surface(r, &grids))
                .collect::<Result<_>>()
        })?;
        let nv = self.velocities;
        let bar = Progress::new(
            env.control.progress,
            surfaces.len() * grids.len() * nv,
            "3D sliding (surface x grid x velocity)",
            "solves",
        );
        let jobs: Vec<(usize, usize)> = (0..grids.len())
            .flat_map(|g| (0..surfaces.len()).map(move |r| (g, r)))
            .collect();
        let swept: Vec<Vec<Run>> = out.stage(Stage::ViscoelasticSliding3d, || {
            jobs.par_iter()
                .with_max_len(1)
                .map(|&(g, r)| self.sweep(&surfaces[r].heights[g], grids[g], pressure, &bar))
                .collect::<Result<_>>()
        })?;
        bar.finish();
        let ns = surfaces.len();
        let runs = (0..grids.len())
            .map(|g| {
                (0..nv)
                    .map(|i| (0..ns).map(|r| swept[g * ns + r][i]).collect())
                    .collect()
            })
            .collect();
        let mean = |f: fn(&Surface3d) -> f64| surfaces.iter().map(f).sum::<f64>() / ns as f64;
        Ok(Solved {
            k: mean(|s| s.k),
            grad_z: mean(|s| s.grad_z),
            pressure,
            grids,
            runs,
        })
    }

    /// The MRD counterpart: the same material, spectrum (C1D = pi q C2D), rms height,
    /// reduced force, velocities, realisations and seed.
    pub(super) fn mrd_counterpart(&self, m: &MrdSide) -> MrdSliding {
        MrdSliding {
            material: self.material.clone(),
            line: self.surface.clone(),
            length: self.length,
            rms_height: self.rms_height,
            springs: m.springs,
            refine: m.refine,
            stride: m.stride,
            reduced_force: self.reduced_force,
            velocity_min: self.velocity_min,
            velocity_max: self.velocity_max,
            velocities: self.velocities,
            realisations: self.realisations,
            seed: self.seed,
            tolerance: m.tolerance,
            max_passes: m.max_passes,
        }
    }
}
