//! The Cerruti compliance of the free (non-periodic) half-space: piecewise-constant
//! x traction on rectangular cells, its x displacement by closed-form cell integrals,
//! linear convolution by zero padding (as the normal non-periodic operator does with
//! Love's coefficients).
//!
//! A point force `Q` along x on the surface of a half-space of shear modulus `G` and
//! Poisson's ratio `nu` displaces the surface along x by
//! `u = Q / (2 pi G) [(1 - nu) / r + nu x^2 / r^3]` (Cerruti; the inverse transform of
//! the periodic operator's symbol `(1 - nu kx^2/|k|^2) / (G |k|)`). Over a cell of
//! half-widths `a x b` centred at `(x, y)` from the field point, with
//! `int int 1/r = [X asinh(Y/|X|) + Y asinh(X/|Y|)]` and
//! `int int X^2/r^3 = [Y asinh(X/|Y|)]` (both taken at the four corners, `+ - - +`),
//! the coefficient is `[(1 - nu) X asinh(Y/|X|) + Y asinh(X/|Y|)] / (2 pi G)`. At
//! `nu = 0` it is Love's normal coefficient with `E* = 2G` (a unit test holds them
//! equal). The kernel is even in x and y, so its spectrum is real.
//!
//! Rounding: the corner sum cancels as (cell / distance)^2, so a coefficient at `d`
//! cells carries an absolute error of about `d ln d` ulps of the cell size; at
//! 2048 cells that is 1e-8 of the self-coefficient, below the partial-slip solver's
//! tolerances.

use super::cerruti::{check_grid, inverse_symbol};
use super::compliance::TangentialCompliance;
use crate::error::Result;
use crate::fft::Fft2;
use crate::symbol::halve_if_even;
use rayon::prelude::*;
use std::f64::consts::PI;

/// The Cerruti compliance (x traction to x displacement) of the free half-space of shear
/// modulus `G` and Poisson's ratio `nu` on an `ny x nx` grid of size `lx x ly`
/// (the traction vanishes outside it).
pub struct CerrutiFree {
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    fft: Fft2,
    /// The padded kernel's real spectrum.
    kernel: Vec<f64>,
    /// The preconditioner: the inverse of the periodic operator's symbol on the grid
    /// itself, `G |k| / (1 - nu kx^2 / |k|^2)`, with its transform.
    inverse: Vec<f64>,
    grid_fft: Fft2,
}

/// `(1 - nu) X asinh(Y/|X|) + Y asinh(X/|Y|)` at one corner (each product 0 where its
/// factor is 0: the limits).
fn corner(x: f64, y: f64, nu: f64) -> f64 {
    let first = if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    };
    let second = if y == 0.0 {
        0.0
    } else {
        y * (x / y.abs()).asinh()
    };
    (1.0 - nu) * first + second
}

/// The x displacement at the origin per unit x traction on the cell of half-widths
/// `a x b` centred at `(x, y)`, times `2 pi G`.
fn cell_coefficient(x: f64, y: f64, a: f64, b: f64, nu: f64) -> f64 {
    corner(x + a, y + b, nu) - corner(x - a, y + b, nu) - corner(x + a, y - b, nu)
        + corner(x - a, y - b, nu)
}

impl CerrutiFree {
    pub fn new(
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        shear_modulus: f64,
        poisson: f64,
    ) -> Result<Self> {
        check_grid((nx, ny, lx, ly), shear_modulus, poisson)?;
        let (hx, hy) = (lx / nx as f64, ly / ny as f64);
        let scale = 1.0 / (2.0 * PI * shear_modulus);
        // One quadrant of offsets (the kernel is even in both), in cell units of x so
        // that the corner sums cancel on numbers of order one near the source.
        let (a, b) = (0.5, 0.5 * hy / hx);
        let mut quadrant = vec![0.0; nx * ny];
        quadrant
            .par_chunks_mut(nx)
            .enumerate()
            .for_each(|(j, row)| {
                for (i, v) in row.iter_mut().enumerate() {
                    let (x, y) = (i as f64, j as f64 * hy / hx);
                    *v = cell_coefficient(x, y, a, b, poisson) * hx * scale;
                }
            });
        let mut fft = Fft2::new(2 * nx, 2 * ny);
        // The padded grid in wrap-around order: offsets 0..nx, nx (never reached: zero),
        // then -(nx - 1)..-1; rows likewise (the transform reads rows 0..=ny).
        let spec = fft.spectrum_of_even(|dy, row| {
            if dy == ny {
                return row.fill(0.0);
            }
            let q = &quadrant[dy * nx..(dy + 1) * nx];
            row[..nx].copy_from_slice(q);
            row[nx] = 0.0;
            for (k, v) in row[nx + 1..].iter_mut().enumerate() {
                *v = q[nx - 1 - k];
            }
        });
        let kernel = halve_if_even(spec.par_iter().map(|c| c.re).collect(), 2 * ny);
        let inverse = inverse_symbol((nx, ny, lx, ly), shear_modulus, poisson);
        Ok(Self {
            nx,
            ny,
            lx,
            ly,
            fft,
            kernel,
            inverse,
            grid_fft: Fft2::new(nx, ny),
        })
    }
}

impl TangentialCompliance for CerrutiFree {
    fn grid(&self) -> (usize, usize, f64, f64) {
        (self.nx, self.ny, self.lx, self.ly)
    }

    fn is_periodic(&self) -> bool {
        false
    }

    fn apply(&mut self, q: &[f64], u: &mut [f64]) {
        self.fft.convolve(q, (self.nx, self.ny), &self.kernel, u);
    }

    /// The periodic operator's inverse on the grid itself: a quarter of the padded
    /// transform's cost.
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        self.grid_fft
            .convolve(r, (self.nx, self.ny), &self.inverse, z);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operator::{Compliance, NonPeriodicHalfSpace};

    /// At nu = 0 Cerruti's kernel is Boussinesq's with E* = 2G: the two operators agree
    /// to rounding on a grid of non-square cells.
    #[test]
    fn at_nu_zero_it_is_the_normal_free_operator() {
        let (nx, ny, lx, ly, g) = (24, 16, 1.0, 0.8, 0.7);
        let mut t = CerrutiFree::new(nx, ny, lx, ly, g, 0.0).unwrap();
        let mut n = NonPeriodicHalfSpace::new(nx, ny, lx, ly, 2.0 * g);
        let q: Vec<f64> = (0..nx * ny)
            .map(|k| ((k * 37 % 101) as f64 / 101.0) - 0.3)
            .collect();
        let (mut ut, mut un) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        t.apply(&q, &mut ut);
        n.apply(&q, &mut un);
        let scale = un.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = ut
            .iter()
            .zip(&un)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-12 * scale, "{err:e} of {scale:e}");
    }

    /// The cell integral against a midpoint sum of the point-force kernel on a fine
    /// sub-grid (error O(h^2)), near and far, for nu = 0.5; and the kernel's anisotropy:
    /// a cell along x displaces more than the same cell along y.
    #[test]
    fn cell_integral_matches_quadrature() {
        let nu = 0.5;
        let kernel = |x: f64, y: f64| {
            let r = x.hypot(y);
            (1.0 - nu) / r + nu * x * x / (r * r * r)
        };
        for (x, y) in [
            (1.0, 0.0),
            (0.0, 1.0),
            (2.0, 3.0),
            (7.0, -2.0),
            (40.0, 25.0),
        ] {
            let m = 400;
            let h = 1.0 / m as f64;
            let mut sum = 0.0;
            for i in 0..m {
                for j in 0..m {
                    sum += kernel(
                        x - 0.5 + (i as f64 + 0.5) * h,
                        y - 0.5 + (j as f64 + 0.5) * h,
                    );
                }
            }
            sum *= h * h;
            let exact = cell_coefficient(x, y, 0.5, 0.5, nu);
            assert!(
                (exact - sum).abs() < 1e-6 * exact,
                "({x}, {y}): {exact} vs {sum}"
            );
        }
        assert!(
            cell_coefficient(3.0, 0.0, 0.5, 0.5, nu)
                > 1.2 * cell_coefficient(0.0, 3.0, 0.5, 0.5, nu)
        );
    }

    /// Cattaneo-Mindlin on the free half-space (Hertz pressure held, nu = 0.5, the
    /// contact radius 0.4 of the grid's side: no periodic images): under Q = mu P / 2 the
    /// body's absolute shift against Mindlin's
    /// `delta = 3 mu P (2 - nu) / (16 G a) [1 - (1 - Q/(mu P))^(2/3)]` (which a periodic
    /// surface cannot check: it has no absolute shift) and the stick radius against
    /// (1 - Q/(mu P))^(1/3), at 25.6, 51.2 and 102.4 cells per radius. Measured shift
    /// errors +1.3e-4, -3.4e-5, -1e-7 (and -1.0e-5 at 204.8: two edge effects of
    /// opposite sign, so no clean order; every one below 2e-4); stick radius 0.12 %,
    /// 0.38 %, 0.12 % (a count of cells). Then Mindlin-Deresiewicz's energy per cycle
    /// at 51.2 cells per radius, amplitudes 0.3 and 0.7 mu P, 40 steps per half cycle:
    /// within 0.5 % (measured +0.13 %, +0.04 %; a periodic cell of 5 radii is off by
    /// 4 %), and the loop's area equal to it within 2e-3 (measured 6.5e-4; 2.4e-3 with
    /// 20 steps: the trapezoids of the work).
    #[test]
    fn cattaneo_mindlin_on_the_free_half_space() {
        use crate::tangential::PartialSlip;
        let (a, mu, nu, g, ratio) = (0.4, 0.3, 0.5, 1.0, 0.5);
        let hertz = |n: usize| {
            crate::mask::centred(n, 1.0, |x, y| {
                (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt()
            })
        };
        let (mut shift, mut radius) = (Vec::new(), Vec::new());
        for n in [64usize, 128, 256] {
            let p = hertz(n);
            let op = CerrutiFree::new(n, n, 1.0, 1.0, g, nu).unwrap();
            let mut ps = PartialSlip::new(op, &p, mu).unwrap();
            let q = ratio * ps.friction_limit();
            let step = ps.load(q, 1e-9).unwrap();
            assert!(!step.sliding && step.residual <= 1e-9);
            // The closed forms for the discrete total force.
            let h2 = 1.0 / (n * n) as f64;
            let big_p = p.iter().sum::<f64>() * h2;
            let x = q / (mu * big_p);
            let exact =
                3.0 * mu * big_p * (2.0 - nu) / (16.0 * g * a) * (1.0 - (1.0 - x).powf(2.0 / 3.0));
            shift.push(step.shift / exact - 1.0);
            let c = (step.stick_cells as f64 * h2 / PI).sqrt();
            radius.push(c / a / (1.0 - x).cbrt() - 1.0);
        }
        assert!(shift.iter().all(|e| e.abs() < 2e-4), "shift {shift:?}");
        assert!(radius.iter().all(|e| e.abs() < 5e-3), "c/a {radius:?}");
        let n = 128;
        let p = hertz(n);
        let big_p = p.iter().sum::<f64>() / (n * n) as f64;
        for x in [0.3, 0.7] {
            let op = CerrutiFree::new(n, n, 1.0, 1.0, g, nu).unwrap();
            let mut ps = PartialSlip::new(op, &p, mu).unwrap();
            let cycle = ps.cycle(x * ps.friction_limit(), 40, 2, 1e-9).unwrap();
            let exact = 9.0 * (mu * big_p).powi(2) * (2.0 - nu) / (10.0 * g * a)
                * (1.0
                    - (1.0 - x).powf(5.0 / 3.0)
                    - 5.0 * x / 6.0 * (1.0 + (1.0 - x).powf(2.0 / 3.0)));
            let err = cycle.dissipated / exact - 1.0;
            let balance = cycle.loop_area / cycle.dissipated - 1.0;
            assert!(
                err.abs() < 5e-3,
                "x = {x}: W {:e} against {exact:e}",
                cycle.dissipated
            );
            assert!(
                balance.abs() < 2e-3,
                "x = {x}: loop area against dissipation {balance:e}"
            );
        }
    }
}
