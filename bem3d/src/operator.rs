//! Surface compliance operators u = K p of an elastic half-space (modulus E*).
//!
//! Physics apart from the solver: the periodic and the non-periodic half-space are two
//! types behind one trait, and a dense matrix (for tests on tiny grids) is a third.
//! Arrays are row-major `ny x nx` (index `j * nx + i`), cell sizes `hx = lx/nx`,
//! `hy = ly/ny`; pressures are cell averages, displacements are taken at cell centres.

use crate::error::{BemError, Result};
use crate::fft::Fft2;
pub use crate::love::love_coefficient;
use crate::love::FarField;
use crate::stencil::Stencil;
use crate::symbol::{halve_if_even, wavenumber, Radial, Symbol, Symbolic};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Grid and modulus shared by every operator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfSpace {
    pub nx: usize,
    pub ny: usize,
    pub lx: f64,
    pub ly: f64,
    pub e_star: f64,
}

/// Range of the lengths and the modulus a solve accepts: any unit system (metres to
/// nanometres, pascals to gigapascals) fits, and the products the solver forms (cell
/// areas, forces of order E* h l) stay finite and normal in double precision.
pub const SCALE_RANGE: (f64, f64) = (1e-100, 1e100);

/// Estimated peak bytes per grid cell of a contact solve, operator, solver, the caller's
/// heights and the solution together, with a margin; a process adds about
/// [`PROCESS_BYTES`]. Measured peaks of whole processes (`mrdw bench large`,
/// `bench-case`, docs/performance.md), with the heights dropped after set-up (8 more
/// with them kept): periodic 35.2 B per cell at 16384^2, 35.3-35.5 at 8192^2 (0.1-20 %
/// contact), 45 at 4096^2 (the nested start's coarse solver sets the peak there) and
/// 70.5 at 2048^2; non-periodic 154.3 at 2048^2 with them.
pub const BYTES_PER_CELL_PERIODIC: f64 = 52.0;
pub const BYTES_PER_CELL_NON_PERIODIC: f64 = 170.0;

/// A process's memory besides its grids (code, thread stacks, allocator), about: added
/// once to a solve's estimate.
pub const PROCESS_BYTES: f64 = 160.0 * 1024.0 * 1024.0;

/// Refuses a size `lx x ly` or a modulus E* outside [`SCALE_RANGE`] (before the grid is
/// known, e.g. while a scene is checked).
pub fn check_scales(lx: f64, ly: f64, e_star: f64) -> Result<()> {
    let (lo, hi) = SCALE_RANGE;
    for (name, v) in [
        ("size[0] (lx, the map's size in x)", lx),
        ("size[1] (ly, the map's size in y)", ly),
        ("e_star (the contact modulus E*)", e_star),
    ] {
        if !(lo..=hi).contains(&v) {
            return Err(BemError::InvalidInput(format!(
                "{name} = {v:e} must lie in [{lo:e}, {hi:e}]"
            )));
        }
    }
    Ok(())
}

impl HalfSpace {
    /// Refuses a grid or modulus the solver cannot work with (fewer than 2 cells a side,
    /// a size or E* outside [`SCALE_RANGE`]); the one check of the command line and the
    /// Python package.
    pub fn validate(&self) -> Result<()> {
        if self.nx < 2 || self.ny < 2 {
            return Err(BemError::InvalidInput(format!(
                "a {} x {} grid is too small: need at least 2 x 2 cells",
                self.ny, self.nx
            )));
        }
        check_scales(self.lx, self.ly, self.e_star)
    }

    /// [`HalfSpace::validate`], and a memory check of a contact solve on this grid
    /// (`periodic` or padded) against what the process may allocate.
    pub fn check(&self, periodic: bool) -> Result<()> {
        self.validate()?;
        let per_cell = if periodic {
            BYTES_PER_CELL_PERIODIC
        } else {
            BYTES_PER_CELL_NON_PERIODIC
        };
        let what = format!("a {} x {} contact", self.ny, self.nx);
        let cells = sysmem::bytes(&[self.nx, self.ny], 1, &what)?;
        sysmem::check_estimate(cells as f64 * per_cell + PROCESS_BYTES, &what)?;
        Ok(())
    }
}

/// The half-space on a grid of half the cells per side, if both sides are even.
fn halved(hs: &HalfSpace) -> Option<HalfSpace> {
    (hs.nx.is_multiple_of(2) && hs.ny.is_multiple_of(2) && hs.nx > 0 && hs.ny > 0).then_some(
        HalfSpace {
            nx: hs.nx / 2,
            ny: hs.ny / 2,
            ..*hs
        },
    )
}

/// Which of an operator's two convolutions a fused application uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Operand {
    /// K itself.
    Compliance,
    /// The preconditioner M.
    Preconditioner,
    /// K with single-precision transforms where the operator has them (else K
    /// itself): for the solver's early iterations, whose rounding (1e-7 relative) its
    /// double-precision iterations and final check remove.
    ComplianceSingle,
}

/// An FFT-based operator's transform and symbol, for fused applications
/// ([`Fft2::load_rows`], [`Fft2::finish_rows`]) on rows of `dims = (width, rows)`.
pub struct Spectral<'a> {
    pub transform: Transform<'a>,
    pub dims: (usize, usize),
}

/// A transform and its symbol (stored or computed), in double or single precision.
pub enum Transform<'a> {
    Double(&'a mut Fft2<f64>, &'a dyn Symbolic<f64>),
    Single(&'a mut Fft2<f32>, &'a dyn Symbolic<f32>),
}

/// The precision of a preconditioner's transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Precision {
    /// f32 transforms (the default): the preconditioner only shapes the search
    /// directions, so its rounding (1e-7 relative) does not reach the solution, which is
    /// judged on K in double precision; an f32 convolution costs 0.68-0.86 of an f64
    /// one (256^2-2048^2, one thread).
    #[default]
    Single,
    /// f64 transforms, as K's (for comparison).
    Double,
}

/// A preconditioner M: a real symbol (a surface stiffness) with its own transform; in
/// single precision also K's symbol on the same grid, if K lives there (else empty).
/// Symbols even in ky are kept by their even half ([`halve_if_even`]). Its transform has
/// no row buffer of its own: it borrows K's ([`Fft2::borrow_rows_from`]; the solver
/// never holds a convolution of K and one of M at the same time).
enum Stiffness {
    Single(Fft2<f32>, Symbol<f32>, Option<Symbol<f32>>),
    Double(Fft2<f64>, Symbol<f64>),
}

/// A stored symbol by its even half if it is even in ky ([`halve_if_even`]); a
/// computed one as it is.
fn halved_symbol(symbol: Symbol<f64>, ny: usize) -> Symbol<f64> {
    match symbol {
        Symbol::Stored(v) => Symbol::Stored(halve_if_even(v, ny)),
        radial => radial,
    }
}

impl Stiffness {
    /// `symbol` on an `nx x ny` transform in `precision`, with K's symbol `kernel` on
    /// the same grid (None: K lives on another grid).
    fn new(
        nx: usize,
        ny: usize,
        symbol: Symbol<f64>,
        kernel: Option<&Symbol<f64>>,
        precision: Precision,
    ) -> Self {
        let symbol = halved_symbol(symbol, ny);
        match precision {
            Precision::Single => Self::Single(
                Fft2::without_rows(nx, ny),
                symbol.map(|v| v as f32),
                kernel.map(|k| k.map(|v| v as f32)),
            ),
            Precision::Double => Self::Double(Fft2::without_rows(nx, ny), symbol),
        }
    }

    fn precision(&self) -> Precision {
        match self {
            Self::Single(..) => Precision::Single,
            Self::Double(..) => Precision::Double,
        }
    }

    /// The symbol in double precision, as stored (for a change of precision).
    fn symbol(&self) -> Symbol<f64> {
        match self {
            Self::Single(_, s, _) => s.map(|v| v as f64),
            Self::Double(_, s) => s.clone(),
        }
    }

    /// M's stencil on the grid `dims`, made into `local` on first use
    /// ([`Preconditioner::local_stiffness`]).
    fn stencil<'a>(
        &self,
        local: &'a OnceLock<Option<Stencil>>,
        (nx, ny): (usize, usize),
    ) -> Option<&'a Stencil> {
        local
            .get_or_init(|| match self {
                Self::Single(_, s, _) => Stencil::of_symbol(s, nx, ny),
                Self::Double(_, s) => Stencil::of_symbol(s, nx, ny),
            })
            .as_ref()
    }

    /// `g <- M g` on rows of `dims`, with the row buffer of K's transform `home`.
    fn apply(&mut self, g: &mut [f64], dims: (usize, usize), home: &mut Fft2) {
        match self {
            Self::Single(fft, s, _) => {
                fft.borrow_rows_from(home);
                fft.convolve_in_place(g, dims, s)
            }
            Self::Double(fft, s) => {
                fft.borrow_rows_from(home);
                fft.convolve_in_place(g, dims, s)
            }
        }
    }

    /// K's transform `home` takes its row buffer back if this one holds it.
    fn return_rows(&mut self, home: &mut Fft2) {
        match self {
            Self::Single(fft, ..) => home.borrow_rows_from(fft),
            Self::Double(fft, _) => home.borrow_rows_from(fft),
        }
    }

    /// K (its transform and symbol) or this M, as the solver's fused applications take
    /// them.
    fn pair<'a>(
        &'a mut self,
        which: Operand,
        (fft, kernel): (&'a mut Fft2, &'a dyn Symbolic<f64>),
        dims: (usize, usize),
    ) -> Spectral<'a> {
        // K in single precision only where the transform carries its symbol.
        let which = match self {
            Self::Single(_, _, Some(_)) => which,
            _ if which == Operand::ComplianceSingle => Operand::Compliance,
            _ => which,
        };
        let home = fft;
        let transform = match (which, self) {
            (Operand::ComplianceSingle, Self::Single(fft, _, Some(k))) => {
                fft.borrow_rows_from(home);
                Transform::Single(fft, k)
            }
            (Operand::Compliance | Operand::ComplianceSingle, this) => {
                this.return_rows(home);
                Transform::Double(home, kernel)
            }
            (Operand::Preconditioner, Self::Single(fft, s, _)) => {
                fft.borrow_rows_from(home);
                Transform::Single(fft, s)
            }
            (Operand::Preconditioner, Self::Double(fft, s)) => {
                fft.borrow_rows_from(home);
                Transform::Double(fft, s)
            }
        };
        Spectral { transform, dims }
    }
}

/// An elastic half-space's compliance on a grid: `u = K p`, the grid's sizes, and K's
/// spectral form where it is a convolution (what an operator is; what the solver's
/// strategies need besides is in [`Preconditioner`], [`RealSpace`] and [`GridForms`]).
pub trait Compliance: Send {
    fn half_space(&self) -> &HalfSpace;
    /// Periodic operators have no defined mean displacement (the k = 0 mode is left to
    /// the load or approach constraint).
    fn is_periodic(&self) -> bool;
    fn nx(&self) -> usize {
        self.half_space().nx
    }
    fn ny(&self) -> usize {
        self.half_space().ny
    }
    fn lx(&self) -> f64 {
        self.half_space().lx
    }
    fn ly(&self) -> f64 {
        self.half_space().ly
    }
    fn e_star(&self) -> f64 {
        self.half_space().e_star
    }
    /// u = K p (both `ny x nx`); `u` is overwritten.
    fn apply(&mut self, p: &[f64], u: &mut [f64]);
    fn cells(&self) -> usize {
        self.nx() * self.ny()
    }
    /// `u = K p` with K's products in single precision where the operator has such a
    /// form without transforms (a dense matrix's copy); the default applies K. The
    /// solver's fused applications of [`Operand::ComplianceSingle`] on an operator
    /// without a spectral form call it.
    fn apply_single(&mut self, p: &[f64], u: &mut [f64]) {
        self.apply(p, u)
    }
    /// Whether [`Operand::ComplianceSingle`] rounds K to single precision (the
    /// single-precision transforms, or [`Self::apply_single`] of a dense copy): the
    /// solver then recomputes `K p` in double precision at set residuals.
    fn rounds_single(&mut self) -> bool {
        matches!(
            self.spectral(Operand::ComplianceSingle),
            Some(Spectral {
                transform: Transform::Single(..),
                ..
            })
        )
    }
    /// The transform and symbol that apply K or M as one convolution, if the operator
    /// is one (the solver then fuses its sweeps into the transform's row passes).
    fn spectral(&mut self, which: Operand) -> Option<Spectral<'_>> {
        let _ = which;
        None
    }
    fn cell_area(&self) -> f64 {
        self.lx() * self.ly() / self.cells() as f64
    }
}

/// An approximate inverse M of K for the solver's search directions (the defaults: the
/// identity, no stencil, which leave the iteration plain Polonsky-Keer).
pub trait Preconditioner: Compliance {
    /// Preconditioner, in place: `g <- M g` with M an approximate inverse of K (a
    /// surface stiffness). The default, the identity, leaves the solver plain
    /// Polonsky-Keer.
    fn precondition(&mut self, g: &mut [f64]) {
        let _ = g;
    }
    /// M's convolution kernel near its centre ([`Stencil`]: the same M as
    /// [`Self::precondition`], truncated), for small contact sets; None if M is no
    /// convolution on this grid (the default) or the grid is smaller than the stencil.
    fn local_stiffness(&mut self) -> Option<&Stencil> {
        None
    }
}

/// K by direct sums over its real-space table: point loads, K between a few cells (the
/// candidate-set path) and at a few cells (the defaults: none, through `apply`).
pub trait RealSpace: Compliance {
    /// `u += K q` for a pressure `q` that is zero except at the listed `(cell, value)`
    /// loads. The default builds `q` and applies `K`.
    fn add_point_loads(&mut self, loads: &[(usize, f64)], u: &mut [f64]) {
        let mut q = vec![0.0; self.cells()];
        for &(c, v) in loads {
            q[c] += v;
        }
        let mut ku = vec![0.0; self.cells()];
        self.apply(&q, &mut ku);
        u.iter_mut().zip(&ku).for_each(|(a, b)| *a += b);
    }
    /// Most loads for which [`Self::add_point_loads`] costs less than [`Compliance::apply`]
    /// (0: never).
    fn point_load_limit(&self) -> usize {
        0
    }
    /// K between the listed cells only, as a dense row-major `n x n` matrix (entry
    /// `(a, b)`: the displacement at `cells[a]` under unit pressure on `cells[b]`), for
    /// solves restricted to a small contact set; None if the operator has no real-space
    /// table. `buffer` is storage to reuse (e.g. the last such matrix, whose pages are
    /// then not mapped afresh; its contents do not matter, may be empty).
    fn restricted(&self, cells: &[usize], buffer: Vec<f64>) -> Option<Vec<f64>> {
        let _ = (cells, buffer);
        None
    }
    /// K of the cell pressures `loads` (cell, pressure) at the listed cells only, by
    /// direct sums over the real-space table (each value sums the loads in list order);
    /// None if the operator has no table. Costs `at.len() * loads.len()` products.
    fn displacements_at(&self, at: &[usize], loads: &[(usize, f64)]) -> Option<Vec<f64>> {
        let _ = (at, loads);
        None
    }
}

/// The same half-space on another grid: a window of this one, or the grid coarsened
/// 2 x 2 (the window path and the nested start; the defaults: none).
pub trait GridForms: Compliance {
    /// The same half-space on a window of `wx x wy` cells of this grid (same cells and
    /// modulus): between cells of the window K is then the same (up to rounding), for
    /// solves restricted to a window that holds the whole contact; None if the operator
    /// has no such restriction (a periodic one couples the window to its images).
    fn window(&self, wx: usize, wy: usize) -> Option<NonPeriodicHalfSpace> {
        let _ = (wx, wy);
        None
    }
    /// The same half-space on a grid of half the cells per side (each cell the union of
    /// 2 x 2 cells of this grid; same size and modulus), for the solver's nested start;
    /// None if the operator has no such form (the default) or a side is odd.
    fn coarse(&self) -> Option<Self>
    where
        Self: Sized,
    {
        None
    }
}

/// Everything the contact solver asks of an operator (implemented for every type with
/// the four traits).
pub trait SolverOperator: Compliance + Preconditioner + RealSpace + GridForms {}

impl<T: Compliance + Preconditioner + RealSpace + GridForms> SolverOperator for T {}

/// Periodic half-space: spectral Green's function, surface stiffness E* |k| / 2
/// (Stanley & Kato 1997), so `u_hat = 2 p_hat / (E* |k|)` for k != 0 and 0 for k = 0.
pub struct PeriodicHalfSpace {
    hs: HalfSpace,
    fft: Fft2,
    /// K's symbol ([`compliance_law`]): computed as the transforms read it on grids above
    /// [`COMPUTED_SYMBOLS_ABOVE`], else stored; any compliance of
    /// [`Self::with_compliance`] stored.
    kernel: Symbol<f64>,
    /// Its inverse, the preconditioner (see [`stiffness_kernel`]).
    stiffness: Stiffness,
    /// Whether [`Compliance::apply`] holds its spectra in the output
    /// ([`PeriodicHalfSpace::hosting`]).
    hosted: bool,
    /// M's kernel near its centre, made on first use.
    local: OnceLock<Option<Stencil>>,
    /// The same operator in real space: `u = table (*) p`, circular.
    table: Circulant,
}

/// Spectral surface stiffness `E* |k| / 2` on a periodic `ny x nx` grid of size
/// `lx x ly` (transposed layout of [`Fft2`]), normalised like `Fft2` pairs. K's mean
/// mode is undefined; the stiffness takes its value at the lowest wavenumber there, so
/// that a uniform residual still moves the pressure.
fn stiffness_kernel(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Symbol<f64> {
    let computed = nx * ny > COMPUTED_SYMBOLS_ABOVE;
    radial_symbol((nx, ny), (lx, ly), computed, stiffness_law(lx, ly, e_star))
}

/// The surface stiffness `E* |k| / 2` at |k|, at the lowest wavenumber for the mean mode.
fn stiffness_law(lx: f64, ly: f64, e_star: f64) -> impl Fn(f64) -> f64 + Copy + Send + Sync {
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
fn radial_symbol(
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
fn compliance_law(e_star: f64) -> impl Fn(f64) -> f64 + Copy + Send + Sync {
    move |k| if k > 0.0 { 2.0 / (e_star * k) } else { 0.0 }
}

/// `f(|k|)` at every bin of a real 2D FFT of a periodic `ny x nx` grid of size
/// `lx x ly`, in the transposed layout of [`Fft2`] (`(nx/2 + 1) x ny`): the stored form
/// of a [`Radial`] symbol, which the tests compare it with.
#[cfg(test)]
fn spectral(nx: usize, ny: usize, lx: f64, ly: f64, f: impl Fn(f64) -> f64 + Sync) -> Vec<f64> {
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
fn signed(r: usize, n: usize) -> f64 {
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
        let hs = HalfSpace {
            nx,
            ny,
            lx,
            ly,
            e_star,
        };
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
            hs: HalfSpace {
                nx,
                ny,
                lx,
                ly,
                e_star,
            },
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

impl RealSpace for PeriodicHalfSpace {
    fn add_point_loads(&mut self, loads: &[(usize, f64)], u: &mut [f64]) {
        self.table.add_point_loads(self.hs.nx, loads, u);
    }
    fn restricted(&self, cells: &[usize], buffer: Vec<f64>) -> Option<Vec<f64>> {
        Some(self.table.restricted(self.hs.nx, cells, buffer))
    }
    fn displacements_at(&self, at: &[usize], loads: &[(usize, f64)]) -> Option<Vec<f64>> {
        Some(self.table.displacements_at(self.hs.nx, at, loads))
    }
    fn point_load_limit(&self) -> usize {
        POINT_LOAD_LIMIT
    }
}

impl GridForms for PeriodicHalfSpace {
    fn coarse(&self) -> Option<Self> {
        let hs = halved(&self.hs)?;
        Some(Self::new(hs.nx, hs.ny, hs.lx, hs.ly, hs.e_star))
    }
}

/// Below this many loads a direct real-space sum beats an FFT-pair application of a
/// periodic operator (in theory about log2 of the grid size times the FFT's constant;
/// measured break-even 47, 65 and 76 loads at 256^2, 512^2 and 1024^2 on the 2-core
/// development machine, AVX-512 build). Only speed depends on it, never results beyond
/// rounding.
const POINT_LOAD_LIMIT: usize = 48;

/// A real-space influence table: the response at cell `(i, j)` of a grid of row length
/// `nx` to a unit load at cell `(ic, jc)`, by value or by row. The direct sums
/// ([`RealSpace::restricted`], [`RealSpace::displacements_at`],
/// [`RealSpace::add_point_loads`]) read it.
trait Table: Sync {
    /// The response at `(i, j)` to a load at `(ic, jc)`.
    fn value(&self, cell: (usize, usize), load: (usize, usize)) -> f64;

    /// `row += v` times the responses along row `j` (of length `nx`) to a unit load at
    /// `(ic, jc)`: one product and one sum per cell.
    fn add_to_row(&self, row: &mut [f64], j: usize, load: (usize, usize), v: f64);

    /// The table between the listed cells of a grid of row length `nx`: a dense
    /// row-major matrix (see [`RealSpace::restricted`]), in `m`'s storage. Every entry
    /// is written by the rows' fill (in parallel, so a fresh matrix's pages are mapped
    /// by both threads); resizing a reused buffer writes only what it grows by.
    fn restricted(&self, nx: usize, cells: &[usize], mut m: Vec<f64>) -> Vec<f64> {
        let n = cells.len();
        if m.is_empty() {
            m = vec![0.0; n * n];
        } else {
            m.resize(n * n, 0.0);
        }
        let at: Vec<(usize, usize)> = cells.iter().map(|&c| (c % nx, c / nx)).collect();
        m.par_chunks_mut(n.max(1)).zip(&at).for_each(|(row, &a)| {
            for (v, &b) in row.iter_mut().zip(&at) {
                *v = self.value(a, b);
            }
        });
        m
    }

    /// The sums over `loads` at the cells `at` only (see
    /// [`RealSpace::displacements_at`]), on a grid of row length `nx`.
    fn displacements_at(&self, nx: usize, at: &[usize], loads: &[(usize, f64)]) -> Vec<f64> {
        let src: Vec<((usize, usize), f64)> =
            loads.iter().map(|&(c, v)| ((c % nx, c / nx), v)).collect();
        at.par_iter()
            .map(|&c| {
                let cell = (c % nx, c / nx);
                src.iter().map(|&(l, v)| self.value(cell, l) * v).sum()
            })
            .collect()
    }

    /// `u += sum over loads` on a grid of row length `nx` (`u.len() / nx` rows). Each
    /// value sums the loads in list order, so the result does not depend on threads.
    fn add_point_loads(&self, nx: usize, loads: &[(usize, f64)], u: &mut [f64]) {
        u.par_chunks_mut(nx * 8).enumerate().for_each(|(b, block)| {
            for (jj, row) in block.chunks_mut(nx).enumerate() {
                let j = 8 * b + jj;
                for &(c, v) in loads {
                    self.add_to_row(row, j, (c % nx, c / nx), v);
                }
            }
        });
    }
}

/// A periodic operator's table on its `py x px` torus: the response at (i, j) to a
/// unit load at (ic, jc) is the value at the offsets `d = (i - ic) mod px` and
/// `r = (j - jc) mod py`. A table even in y (K's symbol even in ky, as every periodic
/// half-space's) is even in x too (a real symbol even in ky is even in kx): it keeps the
/// quarter `r <= py/2`, `d <= px/2` and reads `(min(d, px - d), min(r, py - r))`. The
/// mirrored values differ from the inverse transform's own by rounding only.
struct Circulant {
    px: usize,
    py: usize,
    /// Stored columns per row: `px / 2 + 1` for an even table, else `px`.
    cols: usize,
    even: bool,
    values: Vec<f64>,
}

impl Circulant {
    /// The table of the full `py x px` responses `values` (row offset major); `even`
    /// keeps its quarter.
    fn new(px: usize, py: usize, values: Vec<f64>, even: bool) -> Self {
        if !even {
            return Self {
                px,
                py,
                cols: px,
                even,
                values,
            };
        }
        let cols = (px / 2 + 1).min(px);
        let rows = crate::symbol::even_rows(py).min(py);
        // Sized exactly (a collected `flat_map` would grow by doubling: up to twice the
        // address space).
        let mut quarter = Vec::with_capacity(rows * cols);
        for row in values.chunks(px).take(rows) {
            quarter.extend_from_slice(&row[..cols]);
        }
        let values = quarter;
        Self {
            px,
            py,
            cols,
            even,
            values,
        }
    }

    /// The stored row of row offset `r` (in `0..py`).
    fn stored_row(&self, r: usize) -> &[f64] {
        let r = if self.even { r.min(self.py - r) } else { r };
        &self.values[r * self.cols..(r + 1) * self.cols]
    }

    /// `out[k] += v g(d0 + k)`, `g` the full row of offsets `0..px` that `q` stores
    /// (`d0 + out.len() <= px`): the stored columns forwards, the mirrored ones
    /// (`g(d) = q[px - d]`, `d > px / 2`) backwards.
    fn add_offsets(&self, q: &[f64], d0: usize, v: f64, out: &mut [f64]) {
        if out.is_empty() {
            return;
        }
        let end = d0 + out.len();
        let direct = if self.even {
            self.cols.clamp(d0, end)
        } else {
            end
        };
        let (fwd, mirrored) = out.split_at_mut(direct - d0);
        if !fwd.is_empty() {
            crate::wide::add_scaled(fwd, v, &q[d0..direct]);
        }
        if !mirrored.is_empty() {
            // Offsets direct..end read q[px - d], from px - direct down to px + 1 - end.
            let px = self.px;
            crate::wide::add_scaled_reversed(mirrored, v, &q[px + 1 - end..=px - direct]);
        }
    }
}

impl Table for Circulant {
    fn value(&self, (i, j): (usize, usize), (ic, jc): (usize, usize)) -> f64 {
        let d = wrap(i, ic, self.px);
        let d = if self.even { d.min(self.px - d) } else { d };
        self.stored_row(wrap(j, jc, self.py))[d]
    }
    fn add_to_row(&self, row: &mut [f64], j: usize, (ic, jc): (usize, usize), v: f64) {
        let q = self.stored_row(wrap(j, jc, self.py));
        // Columns i >= ic see offsets 0.., columns i < ic wrap around to px - ic...
        let (before, after) = row.split_at_mut(ic);
        self.add_offsets(q, 0, v, after);
        self.add_offsets(q, self.px - ic, v, before);
    }
}

/// A non-periodic operator's table: the response depends on the offsets' magnitudes
/// only (Love's coefficients are even in x and y), so row `|j - jc|` holds the
/// offsets `-(nx - 1)..=nx - 1`: the response at (i, j) to a unit load at (ic, jc) is
/// `values[|j - jc| * (2 nx - 1) + nx - 1 + i - ic]`. Half the values of the padded
/// `2ny x 2nx` grid's circulant, and each row's responses one contiguous stretch.
struct Mirrored {
    nx: usize,
    values: Vec<f64>,
}

impl Mirrored {
    /// The table of the coefficients `quadrant(dx, dy)` at offsets `0..nx` x `0..ny`,
    /// rows in parallel.
    fn new(nx: usize, ny: usize, quadrant: impl Fn(usize, usize) -> f64 + Sync) -> Self {
        let len = 2 * nx - 1;
        let mut values = vec![0.0; len * ny];
        values
            .par_chunks_mut(len)
            .enumerate()
            .for_each(|(dy, row)| {
                for dx in 0..nx {
                    let v = quadrant(dx, dy);
                    row[nx - 1 + dx] = v;
                    row[nx - 1 - dx] = v;
                }
            });
        Self { nx, values }
    }

    /// The offsets `-(nx - 1)..=nx - 1` of row offset `dy`.
    fn offsets(&self, dy: usize) -> &[f64] {
        let len = 2 * self.nx - 1;
        &self.values[dy * len..(dy + 1) * len]
    }
}

impl Table for Mirrored {
    fn value(&self, (i, j): (usize, usize), (ic, jc): (usize, usize)) -> f64 {
        self.offsets(j.abs_diff(jc))[self.nx - 1 + i - ic]
    }
    fn add_to_row(&self, row: &mut [f64], j: usize, (ic, jc): (usize, usize), v: f64) {
        let nx = row.len();
        let r = &self.offsets(j.abs_diff(jc))[nx - 1 - ic..2 * nx - 1 - ic];
        let (before, after) = r.split_at(ic);
        crate::wide::add_scaled(&mut row[ic..], v, after);
        crate::wide::add_scaled(&mut row[..ic], v, before);
    }
}

/// `(a + period - b) mod period` for `a, b < period`, without a division.
fn wrap(a: usize, b: usize, period: usize) -> usize {
    let d = a + period - b;
    if d >= period {
        d - period
    } else {
        d
    }
}

/// Non-periodic half-space: piecewise-constant pressure cells, Love's influence
/// coefficients, linear convolution by zero-padding to `2nx x 2ny` (DC-FFT,
/// Liu, Wang & Liu 2000).
pub struct NonPeriodicHalfSpace {
    hs: HalfSpace,
    fft: Fft2,
    kernel: Vec<f64>,
    /// Love's coefficients, for direct sums.
    table: Mirrored,
    /// Preconditioner: the periodic stiffness on the unpadded grid, with its own
    /// transform.
    stiffness: Stiffness,
    /// M's kernel near its centre, made on first use.
    local: OnceLock<Option<Stencil>>,
    /// K's padded transform and symbol in single precision
    /// ([`Operand::ComplianceSingle`]), made on first use when the preconditioner is
    /// single precision.
    single: Option<Box<(Fft2<f32>, Vec<f32>)>>,
}

impl NonPeriodicHalfSpace {
    /// [`NonPeriodicHalfSpace::new`] after [`HalfSpace::check`].
    pub fn try_new(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Result<Self> {
        let hs = HalfSpace {
            nx,
            ny,
            lx,
            ly,
            e_star,
        };
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
            let hs = HalfSpace {
                nx,
                ny,
                lx,
                ly,
                e_star,
            };
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
    fn from_table(hs: HalfSpace, table: Mirrored, precision: Precision) -> Self {
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

impl RealSpace for NonPeriodicHalfSpace {
    fn add_point_loads(&mut self, loads: &[(usize, f64)], u: &mut [f64]) {
        self.table.add_point_loads(self.hs.nx, loads, u);
    }
    fn restricted(&self, cells: &[usize], buffer: Vec<f64>) -> Option<Vec<f64>> {
        Some(self.table.restricted(self.hs.nx, cells, buffer))
    }
    fn displacements_at(&self, at: &[usize], loads: &[(usize, f64)]) -> Option<Vec<f64>> {
        Some(self.table.displacements_at(self.hs.nx, at, loads))
    }
    fn point_load_limit(&self) -> usize {
        // A direct sum runs over the n cells, the transforms over the 4n padded ones
        // (measured break-even 103, 227 and 191 loads at 256^2, 512^2, 1024^2).
        3 * POINT_LOAD_LIMIT
    }
}

impl GridForms for NonPeriodicHalfSpace {
    fn coarse(&self) -> Option<Self> {
        let hs = halved(&self.hs)?;
        Some(Self::new(hs.nx, hs.ny, hs.lx, hs.ly, hs.e_star))
    }
    /// Love's coefficients of the window's offsets, copied from this grid's table.
    fn window(&self, wx: usize, wy: usize) -> Option<NonPeriodicHalfSpace> {
        let hs = self.hs;
        if wx == 0 || wy == 0 || wx > hs.nx || wy > hs.ny {
            return None;
        }
        let (hx, hy) = (hs.lx / hs.nx as f64, hs.ly / hs.ny as f64);
        let window = HalfSpace {
            nx: wx,
            ny: wy,
            lx: wx as f64 * hx,
            ly: wy as f64 * hy,
            e_star: hs.e_star,
        };
        let table = Mirrored::new(wx, wy, |i, j| self.table.offsets(j)[hs.nx - 1 + i]);
        let precision = self.stiffness.precision();
        Some(NonPeriodicHalfSpace::from_table(window, table, precision))
    }
}

/// Fewest cells for which [`DenseCompliance::from_matrix`] makes the single-precision
/// copy: a smaller matrix (below 8 MiB) stays in cache, where halving its bytes saves
/// less than the copy and the double-precision refreshes cost (measured, see
/// `solver::restricted`).
const SINGLE_COPY_MIN: usize = 1024;

/// A dense influence matrix (row-major n x n), for tests and tiny grids, and K between
/// the cells of a restricted solve (with a single-precision copy from
/// `SINGLE_COPY_MIN` cells on).
pub struct DenseCompliance {
    hs: HalfSpace,
    periodic: bool,
    pub matrix: Vec<f64>,
    /// The matrix rounded to single precision ([`Compliance::apply_single`]), or empty.
    single: Vec<f32>,
}

/// `u = matrix p` (row-major, rows in parallel; each row's sum in double precision,
/// the matrix in single or double: [`crate::wide::dot`]).
fn dense_product<T: Copy + Into<f64> + Sync>(matrix: &[T], p: &[f64], u: &mut [f64]) {
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
            hs: HalfSpace {
                nx,
                ny,
                lx,
                ly,
                e_star,
            },
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
            hs: HalfSpace {
                nx,
                ny,
                lx,
                ly,
                e_star,
            },
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

impl GridForms for DenseCompliance {}

#[cfg(test)]
mod tests {
    use super::*;

    /// The periodic half-space's symbols, computed as the transforms read them (grids
    /// above [`COMPUTED_SYMBOLS_ABOVE`]) or stored, are those of `spectral` bit for bit (K
    /// in double and single precision, M in single): the same operations on the same
    /// values, so every product and result is the same.
    #[test]
    fn computed_symbols_are_the_stored_ones_bit_for_bit() {
        use crate::symbol::full_symbol;
        let grids = [
            (8, 8, 1.0, 1.0),
            (7, 5, 1.0, 0.8),
            (12, 9, 2.0, 0.7),
            (6, 10, 0.3, 1.0),
        ];
        for (nx, ny, lx, ly) in grids {
            let e_star = 2.5;
            let nc = nx / 2 + 1;
            let stiffness = spectral(nx, ny, lx, ly, stiffness_law(lx, ly, e_star));
            let kernel = spectral(nx, ny, lx, ly, compliance_law(e_star));
            let bits64 = |v: Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let bits32 = |v: Vec<f32>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let to32 = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<_>>();
            for computed in [true, false] {
                let op = PeriodicHalfSpace::with_symbols(nx, ny, (lx, ly), e_star, computed);
                assert_eq!(matches!(op.kernel, Symbol::Radial(_)), computed);
                let got = full_symbol(&op.kernel, nc, ny);
                assert_eq!(bits64(got), bits64(kernel.clone()), "{nx}x{ny}");
                let Stiffness::Single(_, m, Some(k32)) = &op.stiffness else {
                    panic!("single-precision M with K")
                };
                assert_eq!(bits32(full_symbol(m, nc, ny)), bits32(to32(&stiffness)));
                assert_eq!(bits32(full_symbol(k32, nc, ny)), bits32(to32(&kernel)));
            }
        }
    }

    /// `fft` and `reference` applied to the same pressures agree within 1e-12 of the
    /// largest displacement.
    fn check(fft: &mut dyn Compliance, reference: &mut dyn Compliance) {
        let n = fft.cells();
        let p: Vec<f64> = (0..n)
            .map(|k| ((k * 2654435761) % 1000) as f64 / 1000.0)
            .collect();
        let (mut u1, mut u2) = (vec![0.0; n], vec![0.0; n]);
        fft.apply(&p, &mut u1);
        reference.apply(&p, &mut u2);
        let scale = u2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in u1.iter().zip(&u2) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
        }
    }

    /// K (double and single) and M of one operator share one row buffer: applied in
    /// any order, each gives what a fresh operator gives, bit for bit; rows loaded for
    /// one and abandoned when another takes the buffer cannot be finished (a panic,
    /// never the other's values).
    #[test]
    fn shared_row_buffer_changes_no_bit_and_refuses_abandoned_rows() {
        use crate::fft::copy_in;
        // K by its single-precision transform (what the solver's early iterations use).
        fn k_single(op: &mut dyn SolverOperator, p: &[f64]) -> Vec<f64> {
            let mut u = vec![0.0; p.len()];
            let s = op.spectral(Operand::ComplianceSingle).unwrap();
            match s.transform {
                Transform::Single(f, k) => f.convolve(p, s.dims, k, &mut u),
                Transform::Double(..) => panic!("no single-precision K"),
            }
            u
        }
        type Make = fn(usize, usize) -> Box<dyn SolverOperator>;
        // Each from an operator of its own.
        fn each(make: Make, nx: usize, ny: usize, p: &[f64]) -> [Vec<f64>; 3] {
            let (mut k, mut m) = (vec![0.0; p.len()], p.to_vec());
            make(nx, ny).apply(p, &mut k);
            let ks = k_single(&mut *make(nx, ny), p);
            make(nx, ny).precondition(&mut m);
            [k, ks, m]
        }
        for (nx, ny) in [(16usize, 12usize), (9, 14)] {
            let p: Vec<f64> = (0..nx * ny).map(|k| ((k * 37) % 11) as f64 - 5.0).collect();
            let ops: [Make; 2] = [
                |nx, ny| Box::new(PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
                |nx, ny| Box::new(NonPeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
            ];
            for make in ops {
                let want = each(make, nx, ny, &p);
                assert_ne!(want[0], want[1], "K in single precision differs from K");
                let mut shared = make(nx, ny);
                for _ in 0..2 {
                    // M first, then K in single and double precision, and back.
                    let mut m = p.clone();
                    shared.precondition(&mut m);
                    let ks = k_single(&mut *shared, &p);
                    let mut k = vec![0.0; nx * ny];
                    shared.apply(&p, &mut k);
                    assert_eq!([k, ks, m], want, "{nx}x{ny}");
                }
                // Rows loaded for M, the buffer then taken by K: finishing them panics.
                let chunk = nx * crate::fft::ROWS_PER_CHUNK;
                let dims = (nx, ny);
                match shared.spectral(Operand::Preconditioner).unwrap().transform {
                    Transform::Single(f, _) => f.load_rows(dims, p.par_chunks(chunk), copy_in),
                    Transform::Double(f, _) => f.load_rows(dims, p.par_chunks(chunk), copy_in),
                };
                let mut k = vec![0.0; nx * ny];
                shared.apply(&p, &mut k);
                let finish =
                    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        match shared.spectral(Operand::Preconditioner).unwrap().transform {
                            Transform::Single(f, s) => f.convolve_columns(s),
                            Transform::Double(f, s) => f.convolve_columns(s),
                        }
                    }));
                assert!(finish.is_err(), "abandoned rows finished");
            }
        }
    }

    #[test]
    fn fft_operators_match_dense_matrices_to_1e12() {
        for &(nx, ny) in &[(8usize, 8usize), (7, 5), (12, 9)] {
            let mut np = NonPeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0);
            check(&mut np, &mut DenseCompliance::love(nx, ny, 1.0, 0.8, 2.0));
            // Square cells on a square grid: the mirrored table.
            let mut sq = NonPeriodicHalfSpace::new(nx, nx, 1.0, 1.0, 2.0);
            check(&mut sq, &mut DenseCompliance::love(nx, nx, 1.0, 1.0, 2.0));
            let mut pe = PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0);
            check(
                &mut pe,
                &mut DenseCompliance::periodic(nx, ny, 1.0, 0.8, 2.0),
            );
        }
    }

    #[test]
    fn point_loads_match_the_operator_to_1e12() {
        // Loads near every edge and corner exercise the wrap-around of the tables.
        for &(nx, ny) in &[(8usize, 8usize), (7, 5), (12, 9)] {
            let n = nx * ny;
            let loads = vec![(0, 1.5), (n - 1, -0.7), (nx - 1, 2.0), (n / 2 + 1, 0.3)];
            let ly = 0.8 * ny as f64 / nx as f64;
            let ops: Vec<Box<dyn RealSpace>> = vec![
                Box::new(PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
                Box::new(NonPeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
                // Square cells (square grids: the table built from a triangle).
                Box::new(NonPeriodicHalfSpace::new(nx, ny, 0.8, ly, 2.0)),
                Box::new(DenseCompliance::love(nx, ny, 1.0, 0.8, 2.0)),
            ];
            for mut op in ops {
                let mut q = vec![0.0; n];
                for &(c, v) in &loads {
                    q[c] += v;
                }
                let base: Vec<f64> = (0..n).map(|k| k as f64 * 0.01).collect();
                let mut want = vec![0.0; n];
                op.apply(&q, &mut want);
                want.iter_mut().zip(&base).for_each(|(a, b)| *a += b);
                let mut got = base.clone();
                op.add_point_loads(&loads, &mut got);
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for (a, b) in got.iter().zip(&want) {
                    assert!((a - b).abs() <= 1e-12 * scale, "{nx}x{ny}: {a} vs {b}");
                }
                // The same sums at a few cells only (operators with a table).
                let at = [n - 1, 0, nx, n / 2, 1];
                if let Some(u) = op.displacements_at(&at, &loads) {
                    for (&c, u) in at.iter().zip(&u) {
                        let b = want[c] - base[c];
                        assert!(
                            (u - b).abs() <= 1e-12 * scale,
                            "{nx}x{ny} at {c}: {u} vs {b}"
                        );
                    }
                }
            }
        }
        // Both FFT operators have a table.
        let (at, loads) = ([3usize], [(5usize, 1.0)]);
        assert!(PeriodicHalfSpace::new(4, 4, 1.0, 1.0, 1.0)
            .displacements_at(&at, &loads)
            .is_some());
        assert!(NonPeriodicHalfSpace::new(4, 4, 1.0, 1.0, 1.0)
            .displacements_at(&at, &loads)
            .is_some());
    }

    #[test]
    fn a_table_even_in_y_keeps_a_quarter_and_reads_the_full_one_to_rounding() {
        // Every periodic half-space's symbol is even in ky (and, being real, in kx): its
        // table keeps offsets r <= ny/2, d <= nx/2 and reads the mirrors (odd and even
        // sizes). Against the full inverse transform of the symbol: the same responses
        // to rounding (1e-15 of the largest), the stored quarter bit for bit; a single
        // load at every cell against K's transform (the mirrored stretches of each row).
        for &(nx, ny) in &[(8usize, 8usize), (7, 5), (12, 9), (6, 10), (5, 3), (2, 4)] {
            let mut op = PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0);
            assert!(op.table.even);
            assert_eq!(
                op.table.values.len(),
                (ny / 2 + 1).min(ny) * (nx / 2 + 1).min(nx)
            );
            let full_kernel = crate::symbol::full_symbol(&op.kernel, nx / 2 + 1, ny);
            let mut full = vec![0.0; nx * ny];
            Fft2::<f64>::new(nx, ny).inverse_of_real(&full_kernel, &mut full);
            let scale = full.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..ny {
                for i in 0..nx {
                    let (got, want) = (op.table.value((i, j), (0, 0)), full[j * nx + i]);
                    if j <= ny / 2 && i <= nx / 2 {
                        assert_eq!(got.to_bits(), want.to_bits(), "{nx}x{ny} ({i}, {j})");
                    } else {
                        assert!((got - want).abs() <= 1e-15 * scale, "{nx}x{ny} ({i}, {j})");
                    }
                }
            }
            let n = nx * ny;
            for c in 0..n {
                let mut unit = vec![0.0; n];
                unit[c] = -1.5;
                let mut want = vec![0.0; n];
                op.apply(&unit, &mut want);
                let mut got = vec![0.0; n];
                op.add_point_loads(&[(c, -1.5)], &mut got);
                for (k, (a, b)) in got.iter().zip(&want).enumerate() {
                    assert!((a - b).abs() <= 1e-14 * scale, "{nx}x{ny} load {c} at {k}");
                    let v = op.table.value((k % nx, k / nx), (c % nx, c / nx));
                    assert!(-1.5 * v == *a, "{nx}x{ny} {c} {k}");
                }
            }
        }
        // A compliance odd in ky (kx ky terms) keeps its whole table.
        let odd = PeriodicHalfSpace::with_compliance(8, 6, 1.0, 1.0, 1.0, |kx, ky| {
            1.0 / (kx * kx + ky * ky).sqrt() * (1.0 + 0.3 * (kx * ky).tanh())
        });
        assert!(!odd.table.even);
        assert_eq!(odd.table.values.len(), 8 * 6);
    }

    #[test]
    fn restricted_matrices_and_their_single_copies() {
        // K between listed cells, built in a reused buffer (larger, smaller, empty): the
        // same matrix bit for bit as in fresh storage, entry (a, b) K's response at
        // cells[a] to a load at cells[b].
        let mut op = PeriodicHalfSpace::new(48, 32, 1.0, 0.8, 2.0);
        let n = op.cells();
        let sets: [Vec<usize>; 3] = [
            (0..n).filter(|k| k % 4 != 0).collect(),
            (3..n).step_by(2).collect(),
            vec![7, 100, 191],
        ];
        let fresh: Vec<Vec<f64>> = sets
            .iter()
            .map(|c| op.restricted(c, Vec::new()).unwrap())
            .collect();
        let mut buffer = Vec::new();
        for (cells, want) in sets.iter().zip(&fresh) {
            buffer = op.restricted(cells, buffer).unwrap();
            assert_eq!(&buffer, want);
        }
        let cells = &sets[0];
        let m = cells.len();
        let mut unit = vec![0.0; n];
        unit[cells[4]] = 1.0;
        let mut u = vec![0.0; n];
        op.apply(&unit, &mut u);
        for (a, &c) in cells.iter().enumerate() {
            let v = fresh[0][a * m + 4];
            assert!((v - u[c]).abs() <= 1e-12 * u[cells[4]], "{v} vs {}", u[c]);
        }
        // The copy in single precision (1152 cells; storage reused from a larger
        // matrix): K t within 1e-7 of the double-precision product, and exactly the
        // product of the rounded entries (sums in double precision); K p and point
        // loads untouched. None below SINGLE_COPY_MIN cells (767 here) and for tests'
        // matrices.
        let hs = (1.0 / 48.0, 0.8 / 32.0);
        let mut dense =
            DenseCompliance::from_matrix(m, hs, 2.0, fresh[0].clone(), vec![1.0; 2 * m * m]);
        assert!(m >= SINGLE_COPY_MIN && dense.rounds_single());
        let small = sets[1].len();
        assert!(small < SINGLE_COPY_MIN);
        let mut below = DenseCompliance::from_matrix(small, hs, 2.0, fresh[1].clone(), Vec::new());
        assert!(!below.rounds_single());
        assert!(!DenseCompliance::love(3, 3, 1.0, 1.0, 1.0).rounds_single());
        let p: Vec<f64> = (0..m).map(|k| ((k * 37) % 11) as f64 - 4.0).collect();
        let (mut double, mut single) = (vec![0.0; m], vec![0.0; m]);
        dense.apply(&p, &mut double);
        dense.apply_single(&p, &mut single);
        let scale = double.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let rounded: Vec<f64> = fresh[0].iter().map(|&v| v as f32 as f64).collect();
        for a in 0..m {
            let want: f64 = (0..m).map(|b| rounded[a * m + b] * p[b]).sum();
            assert!((single[a] - want).abs() <= 1e-13 * scale);
            assert!((single[a] - double[a]).abs() <= 1e-7 * scale);
            let exact: f64 = (0..m).map(|b| fresh[0][a * m + b] * p[b]).sum();
            assert!((double[a] - exact).abs() <= 1e-13 * scale);
        }
        assert!(single != double, "the copy is rounded");
        // Point loads: the column-wise sums in list order, bit for bit.
        let loads = [(3usize, 0.5), (0, -1.25), (m - 1, 2.0), (3, 0.75)];
        let mut want: Vec<f64> = (0..m).map(|k| k as f64 * 0.01).collect();
        let mut got = want.clone();
        for &(c, v) in &loads {
            for (a, w) in want.iter_mut().enumerate() {
                *w += fresh[0][a * m + c] * v;
            }
        }
        dense.add_point_loads(&loads, &mut got);
        assert_eq!(got, want);
    }

    #[test]
    fn a_window_is_the_half_space_of_its_cells() {
        // The window's operator (coefficients copied from the grid's table) against an
        // operator built for the window's cells: the same convolution and direct sums
        // to rounding (a wrong offset in the copy shows at 1e-2), on square and
        // rectangular cells, square and oblong windows.
        for &(nx, ny, lx, ly, wx, wy) in &[
            (12usize, 12usize, 1.0, 1.0, 5usize, 7usize),
            (12, 9, 1.0, 0.8, 9, 4),
            (8, 8, 1.0, 1.0, 8, 8),
        ] {
            let grid = NonPeriodicHalfSpace::new(nx, ny, lx, ly, 2.0);
            let (hx, hy) = (lx / nx as f64, ly / ny as f64);
            let mut win = grid.window(wx, wy).expect("a window inside the grid");
            let mut fresh = NonPeriodicHalfSpace::new(wx, wy, wx as f64 * hx, wy as f64 * hy, 2.0);
            check(&mut win, &mut fresh);
            let n = wx * wy;
            let loads = [(0, 1.0), (n - 1, 0.5), (wx + 1, -0.25)];
            let at: Vec<usize> = (0..n).collect();
            let (u, v) = (
                win.displacements_at(&at, &loads).unwrap(),
                fresh.displacements_at(&at, &loads).unwrap(),
            );
            let scale = v.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (x, y) in u.iter().zip(&v) {
                assert!((x - y).abs() <= 1e-12 * scale, "{wx}x{wy} sums: {x} vs {y}");
            }
        }
        assert!(NonPeriodicHalfSpace::new(4, 4, 1.0, 1.0, 1.0)
            .window(5, 1)
            .is_none());
    }
}
