//! The periodic half-space: spectral Green's function, surface stiffness E* |k| / 2.

use super::space::{HalfSpace, Operand, Spectral};
use super::stiffness::{halved_symbol, Precision, Stiffness};
use super::table::{real_space_by_table, Circulant, Table, POINT_LOAD_LIMIT};
use super::traits::{Compliance, Preconditioner, RealSpace};
use crate::error::Result;
use crate::fft::Fft2;
use crate::stencil::Stencil;
use crate::symbol::{wavenumber, Radial, Symbol, Symbolic};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Periodic half-space: spectral Green's function, surface stiffness E* |k| / 2
/// (Stanley & Kato 1997), so `u_hat = 2 p_hat / (E* |k|)` for k != 0 and 0 for k = 0.
pub struct PeriodicHalfSpace {
    pub(super) hs: HalfSpace,
    pub(super) fft: Fft2,
    /// K's symbol ([`compliance_law`]): computed as the transforms read it on grids above
    /// [`COMPUTED_SYMBOLS_ABOVE`], else stored; any compliance of
    /// [`Self::with_compliance`] stored.
    pub(super) kernel: Symbol<f64>,
    /// Its inverse, the preconditioner (see [`stiffness_kernel`]).
    pub(super) stiffness: Stiffness,
    /// Whether [`Compliance::apply`] holds its spectra in the output
    /// ([`PeriodicHalfSpace::hosting`]).
    pub(super) hosted: bool,
    /// M's kernel near its centre, made on first use.
    pub(super) local: OnceLock<Option<Stencil>>,
    /// The same operator in real space: `u = table (*) p`, circular.
    pub(super) table: Circulant,
}

/// Spectral surface stiffness `E* |k| / 2` on a periodic `ny x nx` grid of size
/// `lx x ly` (transposed layout of [`Fft2`]), normalised like `Fft2` pairs. K's mean
/// mode is undefined; the stiffness takes its value at the lowest wavenumber there, so
/// that a uniform residual still moves the pressure.
pub(super) fn stiffness_kernel(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Symbol<f64> {
    let computed = nx * ny > COMPUTED_SYMBOLS_ABOVE;
    radial_symbol((nx, ny), (lx, ly), computed, stiffness_law(lx, ly, e_star))
}

/// The surface stiffness `E* |k| / 2` at |k|, at the lowest wavenumber for the mean mode.
pub(super) fn stiffness_law(
    lx: f64,
    ly: f64,
    e_star: f64,
) -> impl Fn(f64) -> f64 + Copy + Send + Sync {
    let k_min = (2.0 * PI / lx).min(2.0 * PI / ly);
    move |k| 0.5 * e_star * if k > 0.0 { k } else { k_min }
}

/// Periodic grids with more cells than this compute their half-space symbols as the
/// transforms read them ([`Radial`]: 4 or more bytes per cell less at a solve's peak, its
/// transforms a few per cent slower: docs/performance.md); smaller grids store them by
/// their even half. The values are the same either way, bit for bit.
pub const COMPUTED_SYMBOLS_ABOVE: usize = 1 << 22;

/// `law(|k|)` on a periodic grid, `computed` as the transforms read it or stored in full
/// (the operator keeps its even half; the same values).
pub(super) fn radial_symbol(
    dims: (usize, usize),
    sizes: (f64, f64),
    computed: bool,
    law: impl Fn(f64) -> f64 + Copy + Send + Sync + 'static,
) -> Symbol<f64> {
    let radial = Radial::new(dims, sizes, move |ks| {
        ks.iter_mut().for_each(|k| *k = law(*k))
    });
    if computed {
        Symbol::Radial(radial)
    } else {
        Symbol::Stored(radial.tabulate())
    }
}

/// The periodic half-space's compliance `2 / (E* |k|)` at |k| (0 for the mean mode,
/// which the load or approach constraint fixes).
pub(super) fn compliance_law(e_star: f64) -> impl Fn(f64) -> f64 + Copy + Send + Sync {
    move |k| if k > 0.0 { 2.0 / (e_star * k) } else { 0.0 }
}

/// `f(|k|)` at every bin of a real 2D FFT of a periodic `ny x nx` grid of size
/// `lx x ly`, in the transposed layout of [`Fft2`] (`(nx/2 + 1) x ny`): the stored form
/// of a [`Radial`] symbol, which the tests compare it with.
#[cfg(test)]
pub(super) fn spectral(
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    f: impl Fn(f64) -> f64 + Sync,
) -> Vec<f64> {
    spectral_grid(nx, ny, lx, ly, |kx, ky| f((kx * kx + ky * ky).sqrt()))
}

/// `f(kx, ky)` (kx >= 0) at every bin of a real 2D FFT of a periodic `ny x nx` grid of
/// size `lx x ly`, in the transposed layout of [`Fft2`] (`(nx/2 + 1) x ny`).
pub fn spectral_grid(
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    f: impl Fn(f64, f64) -> f64 + Sync,
) -> Vec<f64> {
    let nc = nx / 2 + 1;
    let mut s = vec![0.0; nc * ny];
    // Column by column in parallel (each value on its own: the same for any threads).
    s.par_chunks_mut(ny).enumerate().for_each(|(c, col)| {
        let kx = wavenumber(c as f64, lx);
        for (r, v) in col.iter_mut().enumerate() {
            let ky = wavenumber(signed(r, ny), ly);
            *v = f(kx, ky);
        }
    });
    s
}

/// Signed frequency index of bin `r` of an n-point DFT.
pub(super) fn signed(r: usize, n: usize) -> f64 {
    if r <= n / 2 {
        r as f64
    } else {
        r as f64 - n as f64
    }
}

impl PeriodicHalfSpace {
    /// [`PeriodicHalfSpace::new`] after [`HalfSpace::check`]: an error, not an abort or a
    /// NaN, for a grid, size or modulus the solver cannot work with.
    pub fn try_new(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Result<Self> {
        let hs = HalfSpace::new(nx, ny, lx, ly, e_star);
        hs.check(true)?;
        Ok(Self::new(nx, ny, lx, ly, e_star))
    }

    pub fn new(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Self {
        Self::with_symbols(nx, ny, (lx, ly), e_star, nx * ny > COMPUTED_SYMBOLS_ABOVE)
    }

    /// [`Self::new`] with its symbols `computed` or stored ([`COMPUTED_SYMBOLS_ABOVE`]),
    /// and with computed symbols its double-precision convolutions hosted (see
    /// [`Self::hosting`]).
    pub(crate) fn with_symbols(
        nx: usize,
        ny: usize,
        (lx, ly): (f64, f64),
        e_star: f64,
        computed: bool,
    ) -> Self {
        // On the pool, as a solve (its parallel loops start in place).
        crate::pool::on_pool(|| {
            let dims = (nx, ny);
            let kernel = radial_symbol(dims, (lx, ly), computed, compliance_law(e_star));
            let stiffness = radial_symbol(dims, (lx, ly), computed, stiffness_law(lx, ly, e_star));
            let op = Self::from_kernels(nx, ny, lx, ly, e_star, kernel, stiffness);
            op.hosting(computed)
        })
    }

    /// A periodic half-space with any real spectral compliance `c(kx, ky) > 0` for
    /// k != 0, even in k (e.g. |2 / (|k| E*(kx v))| of a sliding viscoelastic body);
    /// the k = 0 mode carries no displacement. `e_scale` is a modulus for the solver's
    /// scales (initial guesses, the preconditioner's mean mode); the preconditioner is
    /// the exact inverse 1 / c.
    pub fn with_compliance(
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        e_scale: f64,
        c: impl Fn(f64, f64) -> f64 + Sync,
    ) -> Self {
        let kernel = spectral_grid(nx, ny, lx, ly, |kx, ky| {
            if kx == 0.0 && ky == 0.0 {
                0.0
            } else {
                c(kx, ky)
            }
        });
        let k_min = (2.0 * PI / lx).min(2.0 * PI / ly);
        let stiffness = kernel
            .iter()
            .map(|&k| {
                if k > 0.0 {
                    1.0 / k
                } else {
                    0.5 * e_scale * k_min
                }
            })
            .collect();
        let (kernel, stiffness) = (Symbol::Stored(kernel), Symbol::Stored(stiffness));
        let mut op = Self::from_kernels(nx, ny, lx, ly, e_scale, kernel, stiffness);
        // Its M need not be a stiffness like |k| (anisotropic, of any sign pattern in
        // real space): no truncated stencil, M by transforms only.
        op.local = OnceLock::from(None);
        op
    }

    /// The operator of a compliance spectrum and its preconditioner (stiffness)
    /// spectrum, with the real-space Green's table for direct sums.
    fn from_kernels(
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        e_star: f64,
        kernel: Symbol<f64>,
        stiffness: Symbol<f64>,
    ) -> Self {
        let kernel = halved_symbol(kernel, ny);
        // A symbol even in ky makes the table even in y (stored by half its rows).
        let even = !kernel.columns(nx / 2 + 1, ny).is_full();
        let mut fft = Fft2::new(nx, ny);
        let mut green = vec![0.0; nx * ny];
        fft.inverse_of_real(&kernel, &mut green);
        let stiffness = Stiffness::new(nx, ny, stiffness, Some(&kernel), Precision::default());
        Self {
            hs: HalfSpace::new(nx, ny, lx, ly, e_star),
            fft,
            kernel,
            stiffness,
            hosted: false,
            local: OnceLock::new(),
            table: Circulant::new(nx, ny, green, even),
        }
    }

    /// With `hosted` and an even row length, K's double-precision convolutions hold
    /// their spectra in the output ([`Fft2::convolve_hosted`], the same values bit for
    /// bit) and its transform keeps a row buffer sized for the single-precision
    /// transforms that borrow it: 4 bytes per cell less at a solve's peak, a few copies
    /// of rows more per application (grids above [`COMPUTED_SYMBOLS_ABOVE`]).
    fn hosting(mut self, hosted: bool) -> Self {
        let (nx, ny) = (self.hs.nx, self.hs.ny);
        self.hosted = hosted && nx.is_multiple_of(2);
        if self.hosted {
            self.stiffness.return_rows(&mut self.fft);
            self.fft = Fft2::with_rows_for::<f32>(nx, ny);
        }
        self
    }

    /// Bytes of the row buffer K's transform holds and lends (taken back first).
    #[cfg(test)]
    pub(crate) fn row_buffer_bytes(&mut self) -> usize {
        self.stiffness.return_rows(&mut self.fft);
        self.fft.row_buffer_bytes()
    }

    /// The preconditioner's transforms in `precision` (default single; single also
    /// gives the solver's early iterations K in single precision,
    /// [`Operand::ComplianceSingle`]).
    pub fn with_preconditioner(mut self, precision: Precision) -> Self {
        let (nx, ny) = (self.hs.nx, self.hs.ny);
        self.stiffness.return_rows(&mut self.fft);
        let symbol = self.stiffness.symbol();
        self.stiffness = Stiffness::new(nx, ny, symbol, Some(&self.kernel), precision);
        self.local = OnceLock::new();
        self
    }
}

impl Compliance for PeriodicHalfSpace {
    fn half_space(&self) -> &HalfSpace {
        &self.hs
    }
    fn is_periodic(&self) -> bool {
        true
    }
    fn apply(&mut self, p: &[f64], u: &mut [f64]) {
        if self.hosted {
            return self.fft.convolve_hosted(p, &self.kernel, u);
        }
        let dims = (self.hs.nx, self.hs.ny);
        self.stiffness.return_rows(&mut self.fft);
        self.fft.convolve(p, dims, &self.kernel, u);
    }
    fn spectral(&mut self, which: Operand) -> Option<Spectral<'_>> {
        let dims = (self.hs.nx, self.hs.ny);
        Some(
            self.stiffness
                .pair(which, (&mut self.fft, &self.kernel), dims),
        )
    }
}

impl Preconditioner for PeriodicHalfSpace {
    /// The exact inverse of K on mean-free fields (Vollebregt 2014 uses the same idea:
    /// an FFT-based approximate inverse, restricted by the solver to the contact set).
    fn precondition(&mut self, g: &mut [f64]) {
        let dims = (self.hs.nx, self.hs.ny);
        self.stiffness.apply(g, dims, &mut self.fft);
    }
    fn local_stiffness(&mut self) -> Option<&Stencil> {
        self.stiffness
            .stencil(&self.local, (self.hs.nx, self.hs.ny))
    }
}

real_space_by_table!(PeriodicHalfSpace, POINT_LOAD_LIMIT);
