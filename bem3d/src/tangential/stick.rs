//! The tangential stiffness of a contact held in full stick, from Cerruti's whole
//! surface tensor: the periodic half-space displaced rigidly along x on a set of cells
//! C (u = (delta, 0) on C, traction free elsewhere) carries the force Q_x = k_x delta.
//! The tensor's symbol is `(I - nu k k^T / |k|^2) / (G |k|)` for `k != 0` (its xx entry
//! is the partial-slip operator's); the xy entry couples the two directions, so held
//! along y the set needs a traction q_y where nu > 0. [`StickStiffness::x_along_only`]
//! drops it (q_y = 0, u_y free: the model of [`super::PartialSlip`] and of Mindlin's
//! solution), which bounds k_x from below; for a circle the two agree.
//!
//! Each stiffness is one solve on C by [`crate::set_solve`], preconditioned by the
//! tensor's inverse symbol `G |k| (I + nu / (1 - nu) k k^T / |k|^2)`. The rigid shift is
//! measured from the mean surface displacement, as the normal tangent stiffness
//! measures the approach ([`crate::ContactSolver::tangent_stiffness`]): the ratio of
//! the two is the ratio of the interfacial stiffnesses of Campana, Persson & Mueser
//! (2011), which Mindlin's circle and MRD's springs put at 2 (1 - nu) / (2 - nu).

use super::cerruti::CerrutiPeriodic;
use super::compliance::TangentialCompliance;
use crate::error::{BemError, Result};
use crate::fft::Fft2;
use crate::operator::spectral_grid;
use crate::set_solve::{SetEnd, SetOperator, SetSolve};
use crate::solver::Interrupt;

/// The tangential stiffnesses of a contact set held in full stick [force / length].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickStiffness {
    /// Q_x / delta with the set displaced by delta along x and held along y.
    pub x: f64,
    /// Q_y / delta with the set displaced by delta along y and held along x.
    pub y: f64,
    /// Q_x / delta with the traction along x only (q_y = 0, u_y free).
    pub x_along_only: f64,
    /// Conjugate-gradient iterations of the three solves together.
    pub iterations: usize,
}

/// Cerruti's tensor (or its xx entry alone) and its inverse, as convolutions.
struct Tensor<'a> {
    fft: &'a mut Fft2,
    dims: (usize, usize),
    /// Components per cell: 2 (x and y) or 1 (x alone).
    d: usize,
    /// Symbols of the compliance and of the preconditioner, row-major d x d.
    compliance: Vec<Vec<f64>>,
    stiffness: Vec<Vec<f64>>,
    tmp: Vec<f64>,
}

impl Tensor<'_> {
    fn product(&mut self, symbols: &[Vec<f64>], v: &[f64], out: &mut [f64]) {
        let n = self.dims.0 * self.dims.1;
        for a in 0..self.d {
            let o = &mut out[a * n..(a + 1) * n];
            o.fill(0.0);
            for b in 0..self.d {
                let s = &symbols[a * self.d + b];
                self.fft
                    .convolve(&v[b * n..(b + 1) * n], self.dims, s, &mut self.tmp);
                o.iter_mut().zip(&self.tmp).for_each(|(o, t)| *o += t);
            }
        }
    }
}

impl SetOperator for Tensor<'_> {
    fn apply(&mut self, v: &[f64], out: &mut [f64]) {
        let symbols = std::mem::take(&mut self.compliance);
        self.product(&symbols, v, out);
        self.compliance = symbols;
    }
    fn precondition(&mut self, r: &mut [f64]) {
        let symbols = std::mem::take(&mut self.stiffness);
        let v = r.to_vec();
        self.product(&symbols, &v, r);
        self.stiffness = symbols;
    }
}

impl CerrutiPeriodic {
    /// The stick stiffnesses of the cells `contact` (`ny x nx`), each solve to the
    /// relative residual `tolerance` (in (0, 0.1]) within `max_iterations`. No contact:
    /// 0; every cell: +inf (the mean mode is free). Non-convergence is a
    /// [`BemError::Breakdown`] naming the limit.
    pub fn stick_stiffness(
        &mut self,
        contact: &[bool],
        tolerance: f64,
        max_iterations: usize,
    ) -> Result<StickStiffness> {
        self.stick_stiffness_until(contact, tolerance, max_iterations, &Interrupt::default())
    }

    /// [`Self::stick_stiffness`], stopped with [`BemError::Interrupted`] once `interrupt`
    /// is set (from another thread; polled once per iteration).
    pub fn stick_stiffness_until(
        &mut self,
        contact: &[bool],
        tolerance: f64,
        max_iterations: usize,
        interrupt: &Interrupt,
    ) -> Result<StickStiffness> {
        let n = self.cells();
        if contact.len() != n {
            return Err(BemError::InvalidInput(format!(
                "contact has {} cells for a grid of {n} cells",
                contact.len()
            )));
        }
        if !(tolerance > 0.0 && tolerance <= 0.1) {
            return Err(BemError::InvalidInput(format!(
                "tolerance {tolerance} must lie in (0, 0.1]"
            )));
        }
        let nc = contact.iter().filter(|c| **c).count();
        if nc == 0 || nc == n {
            let k = if nc == 0 { 0.0 } else { f64::INFINITY };
            return Ok(StickStiffness {
                x: k,
                y: k,
                x_along_only: k,
                iterations: 0,
            });
        }
        let c: Vec<f64> = contact.iter().map(|&b| b as u8 as f64).collect();
        let (compliance, stiffness, along_x) = self.tensor_symbols();
        let dims = (self.nx, self.ny);
        let area = self.cell_area();
        let mut tensor = Tensor {
            fft: &mut self.fft,
            dims,
            d: 2,
            compliance,
            stiffness,
            tmp: vec![0.0; n],
        };
        let set2 = [c.as_slice(), c.as_slice()].concat();
        let zeros = vec![0.0; n];
        let mut iterations = 0;
        let mut solve = |op: &mut Tensor, set: &[f64], b: &[f64]| -> Result<Vec<f64>> {
            let end = SetSolve {
                what: "stick stiffness",
                op,
                tolerance,
                max_iterations,
                interrupted: &|| interrupt.is_set(),
            }
            .run(set, b)?;
            match end {
                SetEnd::Converged { x, iterations: it } => {
                    iterations += it;
                    Ok(x)
                }
                SetEnd::Limit {
                    iterations,
                    residual,
                } => Err(BemError::Breakdown {
                    what: "stick stiffness",
                    iterations,
                    residual,
                    reason: "no convergence within the iteration limit",
                }),
            }
        };
        let sum = |v: &[f64]| v.iter().sum::<f64>() * area;
        // On a pool thread, so that the solves' short parallel loops start in place
        // (the module docs of `crate::pool`).
        let (qx, qy, q1) = crate::pool::on_pool(|| -> Result<_> {
            let qx = solve(&mut tensor, &set2, &[c.as_slice(), &zeros].concat())?;
            let qy = solve(&mut tensor, &set2, &[zeros.as_slice(), &c].concat())?;
            tensor.d = 1;
            tensor.compliance.truncate(1);
            tensor.stiffness = vec![along_x];
            let q1 = solve(&mut tensor, &c, &c)?;
            Ok((qx, qy, q1))
        })?;
        Ok(StickStiffness {
            x: sum(&qx[..n]),
            y: sum(&qy[n..]),
            x_along_only: sum(&q1),
            iterations,
        })
    }

    /// The symbols of the tensor (xx, xy, yx, yy), of its inverse, and of the inverse
    /// of its xx entry alone; the xy entries zero on the Nyquist row and column of an
    /// even grid (there +k and -k are one mode: an odd entry would make the operator
    /// unsymmetric).
    fn tensor_symbols(&self) -> (Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<f64>) {
        let (g, nu) = (self.shear_modulus, self.poisson);
        let k_min = 2.0 * std::f64::consts::PI / self.lx.max(self.ly);
        let grid = |f: &(dyn Fn(f64, f64, f64) -> f64 + Sync), odd: bool| {
            let mut s = spectral_grid(self.nx, self.ny, self.lx, self.ly, |kx, ky| {
                f(kx, ky, (kx * kx + ky * ky).sqrt())
            });
            if odd {
                zero_nyquist(&mut s, self.nx, self.ny);
            }
            s
        };
        let comp = |a: usize, b: usize| {
            move |kx: f64, ky: f64, k: f64| {
                if k == 0.0 {
                    return 0.0;
                }
                let kk = [kx, ky];
                ((a == b) as u8 as f64 - nu * kk[a] * kk[b] / (k * k)) / (g * k)
            }
        };
        let stiff = |a: usize, b: usize| {
            move |kx: f64, ky: f64, k: f64| {
                let kk = [kx, ky];
                let diag = (a == b) as u8 as f64;
                if k == 0.0 {
                    return g * k_min * diag;
                }
                g * k * (diag + nu / (1.0 - nu) * kk[a] * kk[b] / (k * k))
            }
        };
        let xy = grid(&comp(0, 1), true);
        let compliance = vec![
            grid(&comp(0, 0), false),
            xy.clone(),
            xy,
            grid(&comp(1, 1), false),
        ];
        let sxy = grid(&stiff(0, 1), true);
        let stiffness = vec![
            grid(&stiff(0, 0), false),
            sxy.clone(),
            sxy,
            grid(&stiff(1, 1), false),
        ];
        let along_x = grid(
            &|kx: f64, _: f64, k: f64| {
                if k == 0.0 {
                    g * k_min
                } else {
                    g * k / (1.0 - nu * kx * kx / (k * k))
                }
            },
            false,
        );
        (compliance, stiffness, along_x)
    }
}

/// Zeroes the Nyquist row and column of a half-spectrum (`nx / 2 + 1` columns of `ny`).
fn zero_nyquist(s: &mut [f64], nx: usize, ny: usize) {
    for (c, col) in s.chunks_mut(ny).enumerate() {
        for (r, v) in col.iter_mut().enumerate() {
            if (nx.is_multiple_of(2) && c == nx / 2) || (ny.is_multiple_of(2) && r == ny / 2) {
                *v = 0.0;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operator::PeriodicHalfSpace;

    /// Cells of an `n x n` unit cell within the discs (centre x, centre y, radius).
    fn discs(n: usize, discs: &[(f64, f64, f64)]) -> Vec<bool> {
        let h = 1.0 / n as f64;
        (0..n * n)
            .map(|k| {
                let x = ((k % n) as f64 + 0.5) * h;
                let y = ((k / n) as f64 + 0.5) * h;
                discs
                    .iter()
                    .any(|(cx, cy, r)| (x - cx).powi(2) + (y - cy).powi(2) < r * r)
            })
            .collect()
    }

    /// The normal tangent stiffness of the set on the periodic half-space of modulus E*.
    fn normal(n: usize, e_star: f64, set: &[bool]) -> f64 {
        let mut op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, e_star);
        let c: Vec<f64> = set.iter().map(|&b| b as u8 as f64).collect();
        let end = SetSolve {
            what: "test",
            op: &mut op,
            tolerance: 1e-10,
            max_iterations: 2000,
            interrupted: &|| false,
        }
        .run(&c, &c)
        .unwrap();
        match end {
            SetEnd::Converged { x, .. } => x.iter().sum::<f64>() / (n * n) as f64,
            SetEnd::Limit { .. } => panic!("normal stiffness did not converge"),
        }
    }

    fn stick(n: usize, e_star: f64, nu: f64, set: &[bool]) -> StickStiffness {
        let g = e_star * (1.0 - nu) / 2.0;
        let mut op = CerrutiPeriodic::new(n, n, 1.0, 1.0, g, nu).unwrap();
        op.stick_stiffness(set, 1e-10, 2000).unwrap()
    }

    #[test]
    fn without_poisson_effect_the_tangential_stiffness_is_the_normal_one() {
        // nu = 0: Cerruti's tensor is (1 / (G |k|)) I and 2 / (E* |k|) with E* = 2 G.
        let n = 64;
        let set = discs(n, &[(0.3, 0.4, 0.08), (0.7, 0.6, 0.05), (0.55, 0.2, 0.04)]);
        let kn = normal(n, 2.0, &set);
        let k = stick(n, 2.0, 0.0, &set);
        for (name, v) in [("x", k.x), ("y", k.y), ("along x", k.x_along_only)] {
            assert!((v / kn - 1.0).abs() < 1e-8, "{name}: {v} against {kn}");
        }
    }

    #[test]
    fn a_circle_has_mindlins_ratio() {
        // A bonded circle of radius L / 16 at 4, 8, 16 cells per radius: k_t / k_n ->
        // 2 (1 - nu) / (2 - nu). Measured relative errors: nu = 0.3 5.6e-4, 3.7e-4,
        // 1.8e-4; nu = 0.5 2.0e-3, 1.3e-3, 6.7e-4 (the periodic images cancel in the
        // ratio). By symmetry k_y = k_x, and q_y = 0 gives k_x within 1.5e-3, less with
        // each refinement (Mindlin's traction has no y component).
        for (nu, bound) in [(0.3, 8e-4), (0.5, 2.5e-3)] {
            let mindlin = 2.0 * (1.0 - nu) / (2.0 - nu);
            let (mut err_prev, mut along_prev) = (f64::INFINITY, f64::INFINITY);
            for n in [64, 128, 256] {
                let set = discs(n, &[(0.5, 0.5, 1.0 / 16.0)]);
                let kn = normal(n, 1.0, &set);
                let k = stick(n, 1.0, nu, &set);
                let err = (k.x / kn / mindlin - 1.0).abs();
                let along = (k.x_along_only / k.x - 1.0).abs();
                assert!(err < bound && err < err_prev, "nu {nu}, {n}^2: {err:e}");
                assert!(
                    along < 1.5e-3 && along < along_prev,
                    "nu {nu}, {n}^2: {along:e}"
                );
                assert!((k.y / k.x - 1.0).abs() < 1e-12);
                (err_prev, along_prev) = (err, along);
            }
        }
    }

    #[test]
    fn bad_input_is_refused() {
        let mut op = CerrutiPeriodic::new(8, 8, 1.0, 1.0, 1.0, 0.5).unwrap();
        assert!(matches!(
            op.stick_stiffness(&[true; 10], 1e-8, 100),
            Err(BemError::InvalidInput(_))
        ));
        assert!(matches!(
            op.stick_stiffness(&[true; 64], 0.0, 100),
            Err(BemError::InvalidInput(_))
        ));
        let none = op.stick_stiffness(&[false; 64], 1e-8, 100).unwrap();
        assert_eq!(none.x, 0.0);
        let all = op.stick_stiffness(&[true; 64], 1e-8, 100).unwrap();
        assert!(all.x.is_infinite() && all.y.is_infinite());
        let mut set = [false; 64];
        set[..20].iter_mut().for_each(|c| *c = true);
        assert!(matches!(
            op.stick_stiffness(&set, 1e-14, 1),
            Err(BemError::Breakdown { .. })
        ));
    }

    #[test]
    fn holding_the_set_along_y_stiffens_it() {
        let n = 64;
        let set = discs(n, &[(0.3, 0.4, 0.08), (0.42, 0.5, 0.05), (0.55, 0.2, 0.04)]);
        // q_y = 0 leaves the set free along y: a constraint less, a softer set.
        let k = stick(n, 1.0, 0.5, &set);
        assert!(k.x_along_only < k.x && k.x_along_only > 0.95 * k.x);
    }
}
