//! The non-periodic half-space: Love's coefficients, linear convolution by zero
//! padding (DC-FFT).

use super::periodic::stiffness_kernel;
use super::space::{HalfSpace, Operand, Spectral, Transform};
use super::stiffness::{Precision, Stiffness};
use super::table::{real_space_by_table, Mirrored, Table, POINT_LOAD_LIMIT};
use super::traits::{Compliance, Preconditioner, RealSpace};
use crate::error::Result;
use crate::fft::Fft2;
use crate::love::FarField;
use crate::stencil::Stencil;
use crate::symbol::halve_if_even;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Non-periodic half-space: piecewise-constant pressure cells, Love's influence
/// coefficients, linear convolution by zero-padding to `2nx x 2ny` (DC-FFT,
/// Liu, Wang & Liu 2000).
pub struct NonPeriodicHalfSpace {
    pub(super) hs: HalfSpace,
    pub(super) fft: Fft2,
    pub(super) kernel: Vec<f64>,
    /// Love's coefficients, for direct sums.
    pub(super) table: Mirrored,
    /// Preconditioner: the periodic stiffness on the unpadded grid, with its own
    /// transform.
    pub(super) stiffness: Stiffness,
    /// M's kernel near its centre, made on first use.
    pub(super) local: OnceLock<Option<Stencil>>,
    /// K's padded transform and symbol in single precision
    /// ([`Operand::ComplianceSingle`]), made on first use when the preconditioner is
    /// single precision.
    pub(super) single: Option<Box<(Fft2<f32>, Vec<f32>)>>,
}

impl NonPeriodicHalfSpace {
    /// [`NonPeriodicHalfSpace::new`] after [`HalfSpace::check`].
    pub fn try_new(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Result<Self> {
        let hs = HalfSpace::new(nx, ny, lx, ly, e_star);
        hs.check(false)?;
        Ok(Self::new(nx, ny, lx, ly, e_star))
    }

    pub fn new(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Self {
        // On the pool, as a solve (its parallel loops start in place).
        crate::pool::on_pool(|| {
            let (hx, hy) = (lx / nx as f64, ly / ny as f64);
            // Love's coefficient is even in x and y: one quadrant of offsets (0..nx, 0..ny),
            // rows in parallel, from 20 half-widths on by the cell's far-field expansion
            // (a tenth of the closed form's cost, as exact: crate::love). On a square
            // grid of square cells it is also symmetric in (i, j), so the upper triangle
            // is mirrored.
            let square = nx == ny && hx == hy;
            let (a, b) = (0.5 * hx, 0.5 * hy);
            let far = FarField::new(a, b);
            let mut quadrant = vec![0.0; nx * ny];
            quadrant
                .par_chunks_mut(nx)
                .enumerate()
                .for_each(|(j, row)| {
                    let upto = if square { j + 1 } else { nx };
                    for (i, v) in row[..upto].iter_mut().enumerate() {
                        *v = far.coefficient(i as f64 * hx, j as f64 * hy, a, b) / (PI * e_star);
                    }
                });
            let hs = HalfSpace::new(nx, ny, lx, ly, e_star);
            let table = if square {
                Mirrored::new(nx, ny, |i, j| quadrant[i.max(j) * nx + i.min(j)])
            } else {
                Mirrored::new(nx, ny, |i, j| quadrant[j * nx + i])
            };
            Self::from_table(hs, table, Precision::default())
        })
    }

    /// The operator of its table: K's symbol is the spectrum of the table's
    /// coefficients in the wrap-around layout of the padded grid (offsets nx and ny,
    /// never reached, zero), each padded row written from the table as the transform
    /// reads it (rows 0..=ny: the grid is even in y, rows ny + 1.. mirror them).
    pub(super) fn from_table(hs: HalfSpace, table: Mirrored, precision: Precision) -> Self {
        let (nx, ny) = (hs.nx, hs.ny);
        let mut fft = Fft2::new(2 * nx, 2 * ny);
        let spec = fft.spectrum_of_even(|dy, row| {
            if dy == ny {
                return row.fill(0.0);
            }
            // Offsets 0..nx, then (nx: zero) -(nx - 1) up to -1.
            let offsets = table.offsets(dy);
            row[..nx].copy_from_slice(&offsets[nx - 1..]);
            row[nx] = 0.0;
            row[nx + 1..].copy_from_slice(&offsets[..nx - 1]);
        });
        // The kernel is even in x and y, so its spectrum is real.
        let kernel = halve_if_even(spec.par_iter().map(|c| c.re).collect(), 2 * ny);
        drop(spec);
        Self {
            hs,
            fft,
            kernel,
            table,
            // K lives on the padded grid: M's transform does not serve it.
            stiffness: Stiffness::new(
                nx,
                ny,
                stiffness_kernel(nx, ny, hs.lx, hs.ly, hs.e_star),
                None,
                precision,
            ),
            local: OnceLock::new(),
            single: None,
        }
    }

    /// K's padded transform takes its row buffer back from whichever of the
    /// preconditioner's or K's single-precision transform holds it (the three share one,
    /// [`Fft2::borrow_rows_from`]).
    fn rows_home(&mut self) {
        self.stiffness.return_rows(&mut self.fft);
        if let Some(single) = self.single.as_mut() {
            self.fft.borrow_rows_from(&mut single.0);
        }
    }

    /// The preconditioner's transforms in `precision` (default single).
    pub fn with_preconditioner(mut self, precision: Precision) -> Self {
        let (nx, ny) = (self.hs.nx, self.hs.ny);
        self.rows_home();
        self.stiffness = Stiffness::new(nx, ny, self.stiffness.symbol(), None, precision);
        self.local = OnceLock::new();
        self.single = None;
        self
    }
}

impl Compliance for NonPeriodicHalfSpace {
    fn half_space(&self) -> &HalfSpace {
        &self.hs
    }
    fn is_periodic(&self) -> bool {
        false
    }
    fn apply(&mut self, p: &[f64], u: &mut [f64]) {
        // Pruned DC-FFT: rows ny..2ny of the padded input are zero and not transformed
        // forward; only the first ny rows and nx columns of the result are computed
        // back (the rest carries wrap-around values).
        let (nx, ny) = (self.hs.nx, self.hs.ny);
        self.rows_home();
        self.fft.convolve(p, (nx, ny), &self.kernel, u);
    }
    fn spectral(&mut self, which: Operand) -> Option<Spectral<'_>> {
        let dims = (self.hs.nx, self.hs.ny);
        // The buffer goes to the transform asked for, through K's (a transform that
        // holds it keeps it, with any rows it has loaded).
        if which == Operand::ComplianceSingle && self.stiffness.precision() == Precision::Single {
            self.stiffness.return_rows(&mut self.fft);
            let (px, py) = (2 * dims.0, 2 * dims.1);
            let kernel = &self.kernel;
            let (fft, k) = &mut **self.single.get_or_insert_with(|| {
                Box::new((
                    Fft2::without_rows(px, py),
                    kernel.iter().map(|&v| v as f32).collect(),
                ))
            });
            fft.borrow_rows_from(&mut self.fft);
            return Some(Spectral {
                transform: Transform::Single(fft, k),
                dims,
            });
        }
        if let Some(single) = self.single.as_mut() {
            self.fft.borrow_rows_from(&mut single.0);
        }
        Some(
            self.stiffness
                .pair(which, (&mut self.fft, &self.kernel), dims),
        )
    }
}

impl Preconditioner for NonPeriodicHalfSpace {
    /// The periodic stiffness of the unpadded grid: K's inverse up to the coupling
    /// across the boundary, which the padding removes from K but not from M (a
    /// quarter of the cost of an application of K).
    fn precondition(&mut self, g: &mut [f64]) {
        let dims = (self.hs.nx, self.hs.ny);
        self.rows_home();
        self.stiffness.apply(g, dims, &mut self.fft);
    }
    fn local_stiffness(&mut self) -> Option<&Stencil> {
        self.stiffness
            .stencil(&self.local, (self.hs.nx, self.hs.ny))
    }
}

// A direct sum runs over the n cells, the transforms over the 4n padded ones (measured
// break-even 103, 227 and 191 loads at 256^2, 512^2, 1024^2).
real_space_by_table!(NonPeriodicHalfSpace, 3 * POINT_LOAD_LIMIT);
