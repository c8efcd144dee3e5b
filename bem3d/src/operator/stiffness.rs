//! The preconditioner M of the FFT-based operators: a surface stiffness on its own
//! transform, in single or double precision.

use super::space::{Operand, Spectral, Transform};
use crate::fft::Fft2;
use crate::stencil::Stencil;
use crate::symbol::{halve_if_even, Symbol, Symbolic};
use std::sync::OnceLock;

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
pub(super) enum Stiffness {
    Single(Fft2<f32>, Symbol<f32>, Option<Symbol<f32>>),
    Double(Fft2<f64>, Symbol<f64>),
}

/// A stored symbol by its even half if it is even in ky ([`halve_if_even`]); a
/// computed one as it is.
pub(super) fn halved_symbol(symbol: Symbol<f64>, ny: usize) -> Symbol<f64> {
    match symbol {
        Symbol::Stored(v) => Symbol::Stored(halve_if_even(v, ny)),
        radial => radial,
    }
}

impl Stiffness {
    /// `symbol` on an `nx x ny` transform in `precision`, with K's symbol `kernel` on
    /// the same grid (None: K lives on another grid).
    pub(super) fn new(
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

    pub(super) fn precision(&self) -> Precision {
        match self {
            Self::Single(..) => Precision::Single,
            Self::Double(..) => Precision::Double,
        }
    }

    /// The symbol in double precision, as stored (for a change of precision).
    pub(super) fn symbol(&self) -> Symbol<f64> {
        match self {
            Self::Single(_, s, _) => s.map(|v| v as f64),
            Self::Double(_, s) => s.clone(),
        }
    }

    /// M's stencil on the grid `dims`, made into `local` on first use
    /// ([`Preconditioner::local_stiffness`]).
    pub(super) fn stencil<'a>(
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
    pub(super) fn apply(&mut self, g: &mut [f64], dims: (usize, usize), home: &mut Fft2) {
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
    pub(super) fn return_rows(&mut self, home: &mut Fft2) {
        match self {
            Self::Single(fft, ..) => home.borrow_rows_from(fft),
            Self::Double(fft, _) => home.borrow_rows_from(fft),
        }
    }

    /// K (its transform and symbol) or this M, as the solver's fused applications take
    /// them.
    pub(super) fn pair<'a>(
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
