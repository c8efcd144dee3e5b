//! A dense influence matrix: tests, tiny grids, and K between a restricted solve's cells.

use super::periodic::signed;
use super::space::HalfSpace;
use super::traits::{Compliance, Preconditioner, RealSpace};
use crate::love::love_coefficient;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Fewest cells for which [`DenseCompliance::from_matrix`] makes the single-precision
/// copy: a smaller matrix (below 8 MiB) stays in cache, where halving its bytes saves
/// less than the copy and the double-precision refreshes cost (measured, see
/// `solver::restricted`).
pub(super) const SINGLE_COPY_MIN: usize = 1024;

/// A dense influence matrix (row-major n x n), for tests and tiny grids, and K between
/// the cells of a restricted solve (with a single-precision copy from
/// `SINGLE_COPY_MIN` cells on).
pub struct DenseCompliance {
    pub(super) hs: HalfSpace,
    pub(super) periodic: bool,
    pub matrix: Vec<f64>,
    /// The matrix rounded to single precision ([`Compliance::apply_single`]), or empty.
    pub(super) single: Vec<f32>,
}

/// `u = matrix p` (row-major, rows in parallel; each row's sum in double precision,
/// the matrix in single or double: [`crate::wide::dot`]).
pub(super) fn dense_product<T: Copy + Into<f64> + Sync>(matrix: &[T], p: &[f64], u: &mut [f64]) {
    let n = p.len();
    u.par_iter_mut()
        .zip(matrix.par_chunks(n.max(1)))
        .for_each(|(ua, row)| *ua = crate::wide::dot(row, p));
}

impl DenseCompliance {
    /// `n` cells of size `hx x hy` in one row with the given row-major `n x n` matrix (e.g.
    /// [`RealSpace::restricted`] of a larger operator; crate-internal: the size is
    /// asserted, not a user input), and its copy in single precision, written into
    /// `single`'s storage (reused, e.g. the last such copy; contents do not matter): the
    /// solver's K t then reads half the bytes ([`Compliance::apply_single`]; `K p` stays in
    /// double precision).
    pub(crate) fn from_matrix(
        n: usize,
        (hx, hy): (f64, f64),
        e_star: f64,
        matrix: Vec<f64>,
        mut single: Vec<f32>,
    ) -> Self {
        assert_eq!(matrix.len(), n * n, "matrix must be n x n");
        if n < SINGLE_COPY_MIN {
            single = Vec::new();
        } else if single.is_empty() {
            // As the matrix's fill: a fresh copy's pages mapped by both threads.
            single = vec![0.0; n * n];
        } else {
            single.resize(n * n, 0.0);
        }
        single
            .par_chunks_mut(n.max(1))
            .zip(matrix.par_chunks(n.max(1)))
            .for_each(|(s, m)| s.iter_mut().zip(m).for_each(|(s, &m)| *s = m as f32));
        Self {
            hs: HalfSpace {
                nx: n,
                ny: 1,
                lx: n as f64 * hx,
                ly: hy,
                e_star,
            },
            periodic: false,
            matrix,
            single,
        }
    }

    /// Non-periodic matrix straight from Love's formula.
    pub fn love(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Self {
        let (hx, hy) = (lx / nx as f64, ly / ny as f64);
        let n = nx * ny;
        let mut matrix = vec![0.0; n * n];
        for a in 0..n {
            for b in 0..n {
                let (ia, ja, ib, jb) = (a % nx, a / nx, b % nx, b / nx);
                let x = (ia as f64 - ib as f64) * hx;
                let y = (ja as f64 - jb as f64) * hy;
                matrix[a * n + b] = love_coefficient(x, y, 0.5 * hx, 0.5 * hy) / (PI * e_star);
            }
        }
        Self {
            hs: HalfSpace::new(nx, ny, lx, ly, e_star),
            periodic: false,
            matrix,
            single: Vec::new(),
        }
    }

    /// Periodic matrix by a naive inverse DFT of 2/(E*|k|) (independent of the FFT).
    pub fn periodic(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Self {
        let n = nx * ny;
        let mut green = vec![0.0; n];
        for dj in 0..ny {
            for di in 0..nx {
                let mut s = 0.0;
                for r in 0..ny {
                    for c in 0..nx {
                        let (fx, fy) = (signed(c, nx), signed(r, ny));
                        let k = 2.0 * PI * ((fx / lx).powi(2) + (fy / ly).powi(2)).sqrt();
                        if k > 0.0 {
                            let ph = 2.0
                                * PI
                                * (fx * di as f64 / nx as f64 + fy * dj as f64 / ny as f64);
                            s += 2.0 / (e_star * k) * ph.cos();
                        }
                    }
                }
                green[dj * nx + di] = s / n as f64;
            }
        }
        let mut matrix = vec![0.0; n * n];
        for a in 0..n {
            for b in 0..n {
                let di = (a % nx + nx - b % nx) % nx;
                let dj = (a / nx + ny - b / nx) % ny;
                matrix[a * n + b] = green[dj * nx + di];
            }
        }
        Self {
            hs: HalfSpace::new(nx, ny, lx, ly, e_star),
            periodic: true,
            matrix,
            single: Vec::new(),
        }
    }

    /// The matrix and its single-precision copy, as storage for the next one.
    pub(crate) fn into_storage(self) -> (Vec<f64>, Vec<f32>) {
        (self.matrix, self.single)
    }
}

impl Compliance for DenseCompliance {
    fn half_space(&self) -> &HalfSpace {
        &self.hs
    }
    fn is_periodic(&self) -> bool {
        self.periodic
    }
    fn apply(&mut self, p: &[f64], u: &mut [f64]) {
        dense_product(&self.matrix, p, u);
    }
    fn apply_single(&mut self, p: &[f64], u: &mut [f64]) {
        if self.single.is_empty() {
            dense_product(&self.matrix, p, u);
        } else {
            dense_product(&self.single, p, u);
        }
    }
    fn rounds_single(&mut self) -> bool {
        !self.single.is_empty()
    }
}

impl Preconditioner for DenseCompliance {}

impl RealSpace for DenseCompliance {
    /// Row by row in parallel (each row's entries read in the loads' order, one row at
    /// a time in cache), each value summing the loads in list order as a column-wise
    /// sweep would: the same sums bit for bit, for any thread count. Column by column
    /// (one cache line per row and load) the changes of a restricted solve's first
    /// iterations (a few hundred loads on a few thousand cells) cost five times an
    /// application of the matrix.
    fn add_point_loads(&mut self, loads: &[(usize, f64)], u: &mut [f64]) {
        let n = u.len();
        u.par_iter_mut()
            .zip(self.matrix.par_chunks(n.max(1)))
            .for_each(|(ua, row)| {
                for &(c, v) in loads {
                    *ua += row[c] * v;
                }
            });
    }
    fn point_load_limit(&self) -> usize {
        self.cells()
    }
}
