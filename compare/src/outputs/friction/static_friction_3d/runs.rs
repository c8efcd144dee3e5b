//! One realisation of each side: a 3D surface pressed at the forces of the f grid, and
//! one MRD line pressed with the same forces.

use super::{Geometry, StaticFriction3d};
use crate::error::{Context as _, Result};
use bem3d::{BemError, ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace};
use bem3d::{SolverOperator, SolverOptions};
use mrd::rough_contact::RoughLine;
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{nested, SelfAffine};
use std::f64::consts::PI;

/// The state of one realisation at one reduced force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// xi = rms slope in contact / rms slope over the apparent area (Eq. 89).
    pub xi: f64,
    /// Fraction of the apparent area (3D) or of the line (MRD) in contact.
    pub area: f64,
    /// Cells (3D) or points (MRD) in contact.
    pub contacts: f64,
}

/// A 3D realisation: its rms height over A and its state at each f (None: the solve did
/// not converge; left out, and counted).
#[derive(Debug, Clone)]
pub struct Run3d {
    pub rms_height: f64,
    pub points: Vec<Option<Point>>,
    pub unconverged: usize,
}

/// The spectrum shared by the surfaces and lines of Hurst exponent `hurst`: a pure power
/// law C2D ~ q^(-2H-2) from the longest wavelength either system holds (Eq. 85: no
/// cut-off but the system size); the band is cut by the synthesis.
fn spectrum(spec: &StaticFriction3d, geometry: Geometry, hurst: f64) -> Result<SelfAffine> {
    let q0 = 2.0 * PI / geometry.line_length().max(1.0);
    let q1 = 2.0 * PI * (spec.bandwidth as f64 + 2.0) * geometry.line_length().max(1.0);
    SelfAffine::new(hurst, q0, q0, q1).ctx("spectrum")
}

/// The squared forward-difference gradient |grad z|^2 of each cell, periodic (Eq. 86 in
/// x and y).
fn squared_gradients(z: &[f64], n: usize) -> Vec<f64> {
    let dx = 1.0 / n as f64;
    (0..n * n)
        .map(|c| {
            let (j, i) = (c / n, c % n);
            let gx = (z[j * n + (i + 1) % n] - z[c]) / dx;
            let gy = (z[((j + 1) % n) * n + i] - z[c]) / dx;
            gx * gx + gy * gy
        })
        .collect()
}

/// Realisation `r` of the 3D system at `cells` per shortest wavelength, at every f.
pub fn solve_3d(
    spec: &StaticFriction3d,
    geometry: Geometry,
    hurst: f64,
    r: u64,
    cells: usize,
    fs: &[f64],
) -> Result<Run3d> {
    let n = spec.grid(cells);
    let sa = spectrum(spec, geometry, hurst)?;
    let z = nested::surface(
        &|q| sa.c2d(q),
        spec.bandwidth,
        &Grid::square(n, 1.0),
        spec.seed,
        r,
    )
    .ctx("3D surface")?;
    let domain = match geometry {
        Geometry::Periodic => vec![true; n * n],
        Geometry::Disc => bem3d::mask::disc(n, n, 1.0, 1.0, 0.5),
    };
    let cells_in = domain.iter().filter(|&&m| m).count() as f64;
    let over = |v: &[f64]| -> f64 {
        v.iter()
            .zip(&domain)
            .filter(|p| *p.1)
            .map(|p| p.0)
            .sum::<f64>()
            / cells_in
    };
    let mean = over(&z);
    let squares: Vec<f64> = z.iter().map(|v| (v - mean).powi(2)).collect();
    let rms_height = over(&squares).sqrt(); // Eq. (87) over A
    let g2 = squared_gradients(&z, n);
    let grad2 = over(&g2); // Eq. (88) squared, over A
                           // Eq. (93): F = f 2 E* h sqrt(A) / sqrt(pi), E* = 1.
    let forces: Vec<f64> = fs
        .iter()
        .map(|f| f * 2.0 * rms_height * geometry.area().sqrt() / PI.sqrt())
        .collect();
    let opts = crate::experiment::solve_options(spec.tolerance, n);
    let slopes = Slopes {
        domain: &domain,
        g2,
        grad2,
        cells_in,
    };
    let (points, unconverged) = match geometry {
        Geometry::Periodic => {
            let op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
            let solver = ContactSolver::new(op, &z, None).ctx("3D solver set-up")?;
            ladder(solver, &forces, &opts, &slopes)?
        }
        Geometry::Disc => {
            let op = NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
            let solver =
                ContactSolver::new(op, &z, Some(domain.clone())).ctx("3D solver set-up")?;
            ladder(solver, &forces, &opts, &slopes)?
        }
    };
    Ok(Run3d {
        rms_height,
        points,
        unconverged,
    })
}

/// What xi of a 3D contact needs: the apparent area's cells, their squared gradients
/// and the mean of those over A.
struct Slopes<'a> {
    domain: &'a [bool],
    g2: Vec<f64>,
    grad2: f64,
    cells_in: f64,
}

impl Slopes<'_> {
    /// The point of a solved pressure field (cells with p > 0 are in contact).
    fn point(&self, pressure: &[f64]) -> Point {
        let (mut sum, mut m) = (0.0, 0usize);
        for (c, &p) in pressure.iter().enumerate() {
            if p > 0.0 && self.domain[c] {
                sum += self.g2[c];
                m += 1;
            }
        }
        Point {
            xi: if m > 0 {
                (sum / m as f64 / self.grad2).sqrt()
            } else {
                0.0
            }, // Eq. (89)
            area: m as f64 / self.cells_in,
            contacts: m as f64,
        }
    }
}

/// The force ladder on one surface, warm-started from the last converged solve.
fn ladder<O: SolverOperator>(
    mut solver: ContactSolver<O>,
    forces: &[f64],
    opts: &SolverOptions,
    slopes: &Slopes,
) -> Result<(Vec<Option<Point>>, usize)> {
    let (mut points, mut unconverged) = (Vec::with_capacity(forces.len()), 0);
    let mut warm: Option<bem3d::Solution> = None;
    for &force in forces {
        match solver.solve(Load::Force(force), opts, warm.as_ref()) {
            Ok(sol) => {
                points.push(Some(slopes.point(&sol.pressure)));
                warm = Some(sol);
            }
            Err(BemError::NoConvergence { .. }) => {
                unconverged += 1;
                points.push(None);
            }
            Err(e) => return Err(e).ctx("3D solve"),
        }
    }
    Ok((points, unconverged))
}

/// The mean rms height over A of a 3D ensemble (sets the forces of the MRD lines).
pub fn mean_rms_height(runs: &[Run3d]) -> f64 {
    runs.iter().map(|r| r.rms_height).sum::<f64>() / runs.len() as f64
}

/// MRD line `r` for (geometry, hurst) with factor `lambda`, pressed with the forces the
/// 3D system of mean rms height `h3` carries at each f.
pub fn press_line(
    spec: &StaticFriction3d,
    geometry: Geometry,
    hurst: f64,
    lambda: f64,
    h3: f64,
    r: u64,
    fs: &[f64],
) -> Result<Vec<Point>> {
    let l1 = geometry.line_length();
    // Same shortest wavelength and sampling as the surface.
    let band = (spec.bandwidth as f64 * l1).floor() as usize;
    let n1 = spec.cells * band;
    let line = spectrum(spec, geometry, hurst)?.to_line(lambda);
    let z = nested::line(&|q| line.c1d(q), band, n1, l1, spec.seed, r).ctx("1D line")?;
    let rl = RoughLine::new(&z, l1, 1.0).ctx("1D line")?;
    let full = rl.at_depth(rl.full_contact_depth()).ctx("1D")?.force;
    fs.iter()
        .map(|&f| {
            let force = f * 2.0 * h3 * geometry.area().sqrt() / PI.sqrt(); // Eq. (93)
            if force >= full {
                return Ok(Point {
                    xi: 1.0,
                    area: 1.0,
                    contacts: n1 as f64,
                });
            }
            let s = rl.at_force(force).ctx("1D")?;
            Ok(Point {
                xi: s.contact_slope / rl.rms_slope, // Eq. (89)
                area: s.contacts as f64 / n1 as f64,
                contacts: s.contacts as f64,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forward_differences_of_a_plane_wave() {
        // z = cos(2 pi (k x + m y)) on n^2 cells: (z(x + dx) - z(x)) / dx has mean square
        // (2 sin(pi k dx) / dx)^2 / 2 in x, the same with m in y.
        let (n, k, m) = (32usize, 3.0, 5.0);
        let dx = 1.0 / n as f64;
        let z: Vec<f64> = (0..n * n)
            .map(|c| {
                let (j, i) = ((c / n) as f64 * dx, (c % n) as f64 * dx);
                (2.0 * PI * (k * i + m * j)).cos()
            })
            .collect();
        let g2 = squared_gradients(&z, n);
        let mean = g2.iter().sum::<f64>() / (n * n) as f64;
        let s = |w: f64| (2.0 * (PI * w * dx).sin() / dx).powi(2) / 2.0;
        assert!((mean / (s(k) + s(m)) - 1.0).abs() < 1e-12, "{mean}");
    }
}
