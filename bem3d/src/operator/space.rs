//! The grid and modulus every operator shares ([`HalfSpace`]), its checks and memory
//! figures, and the names of a fused application (operand, transform).

use crate::error::{BemError, Result};
use crate::fft::Fft2;
use crate::symbol::Symbolic;

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
    /// nx x ny cells over lx x ly [length], contact modulus E* [stress].
    pub(crate) fn new(nx: usize, ny: usize, lx: f64, ly: f64, e_star: f64) -> Self {
        Self {
            nx,
            ny,
            lx,
            ly,
            e_star,
        }
    }

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
pub(super) fn halved(hs: &HalfSpace) -> Option<HalfSpace> {
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
