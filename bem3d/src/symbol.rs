//! Symbols (the multipliers of a spectrum) as a column pass of [`crate::fft::Fft2`]
//! reads them: `nc = nx/2 + 1` columns of `ny` values (the spectrum's transposed
//! layout).
//!
//! A symbol is stored in full, stored by rows `0..=ny/2` of each column if it is even in
//! ky (row r equal to row ny - r, bit for bit: any function of |k|; [`halve_if_even`]),
//! or, for a function of |k| on a periodic grid, not stored at all: [`Radial`] computes
//! each column as the pass reads it, with the same operations on the same values as the
//! stored form ([`Radial::tabulate`]), so the products and results are bit-identical
//! either way.

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::num_traits::Zero;
use std::f64::consts::PI;
use std::sync::Arc;

/// The wavenumber `2 pi index / length` of a DFT bin of signed `index` on a periodic
/// side of `length` (the one formula every periodic symbol's bins are computed by).
pub fn wavenumber(index: f64, length: f64) -> f64 {
    2.0 * PI * index / length
}

/// Rows stored per column of a symbol even in ky: `0..=ny/2`.
pub fn even_rows(ny: usize) -> usize {
    ny / 2 + 1
}

/// `symbol` (`nc` columns of `ny` values, the spectrum's layout) by its rows `0..=ny/2`
/// per column if every column is even in ky bit for bit (row r equal to row ny - r),
/// else unchanged: the form a column pass reads with the least memory.
pub fn halve_if_even(symbol: Vec<f64>, ny: usize) -> Vec<f64> {
    let half = even_rows(ny);
    if half >= ny || !is_even_in_ky(&symbol, ny) {
        return symbol;
    }
    symbol
        .par_chunks(ny)
        .flat_map_iter(|col| col[..half].iter().copied())
        .collect()
}

/// Whether every column of `symbol` (stored in full, `ny` values per column) is even in
/// ky bit for bit as f64: row r equal to row ny - r.
pub(crate) fn is_even_in_ky<S: Copy + Into<f64> + Sync>(symbol: &[S], ny: usize) -> bool {
    let bits = |v: S| Into::<f64>::into(v).to_bits();
    symbol
        .par_chunks(ny)
        .all(|col| (1..ny).all(|r| bits(col[r]) == bits(col[ny - r])))
}

/// A symbol of `nc` columns of `ny` rows in its full form (`nc x ny`), however it is
/// held.
pub fn full_symbol<S: SymbolValue>(
    symbol: &(impl Symbolic<S> + ?Sized),
    nc: usize,
    ny: usize,
) -> Vec<S> {
    let columns = symbol.columns(nc, ny);
    let mut full = vec![S::of_f64(0.0); nc * ny];
    full.par_chunks_mut(ny)
        .enumerate()
        .for_each_init(ColumnBuf::default, |buf, (c, col)| {
            col.copy_from_slice(columns.column(c, buf))
        });
    full
}

/// A symbol's value type: real (f64, f32: a function of |k| can give it) or complex.
pub trait SymbolValue: Copy + Send + Sync {
    /// The value of a real `x`, rounded as `as` rounds.
    fn of_f64(x: f64) -> Self;
}

impl SymbolValue for f64 {
    fn of_f64(x: f64) -> Self {
        x
    }
}

impl SymbolValue for f32 {
    fn of_f64(x: f64) -> Self {
        x as f32
    }
}

impl<T: SymbolValue + Zero> SymbolValue for Complex<T> {
    fn of_f64(x: f64) -> Self {
        Complex::new(T::of_f64(x), T::zero())
    }
}

/// Maps a column's |k| values to a symbol's values in place.
type Law = Arc<dyn Fn(&mut [f64]) + Send + Sync>;

/// `law(|k|)` on the wave vectors of a periodic `nx x ny` grid of size `lx x ly`: bin
/// `(c, r)` has kx = 2 pi c / lx and ky = 2 pi r' / ly, r' the signed index of row r.
/// `law` maps a column's |k| values to the symbol's in place (one call per column, so
/// its loop is compiled where the law is defined).
#[derive(Clone)]
pub struct Radial {
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    law: Law,
}

impl Radial {
    pub fn new(
        (nx, ny): (usize, usize),
        (lx, ly): (f64, f64),
        law: impl Fn(&mut [f64]) + Send + Sync + 'static,
    ) -> Self {
        Self {
            nx,
            ny,
            lx,
            ly,
            law: Arc::new(law),
        }
    }

    /// The squared ky of rows `0..=ny/2` (the others are their mirrors).
    fn ky_squared(&self) -> Vec<f64> {
        (0..even_rows(self.ny))
            .map(|r| {
                let ky = wavenumber(r as f64, self.ly);
                ky * ky
            })
            .collect()
    }

    /// Column `c`'s values on rows `0..=ny/2` into `out` (f64).
    fn half_column(&self, c: usize, ky2: &[f64], out: &mut Vec<f64>) {
        let kx = wavenumber(c as f64, self.lx);
        let kx2 = kx * kx;
        out.clear();
        out.extend(ky2.iter().map(|&y| (kx2 + y).sqrt()));
        (self.law)(out);
    }

    /// The whole symbol, `nc x ny` (the stored form its columns reproduce bit for bit).
    pub fn tabulate(&self) -> Vec<f64> {
        full_symbol(&Symbol::Radial(self.clone()), self.nx / 2 + 1, self.ny)
    }
}

/// A symbol held stored (in full or by its even half) or computed ([`Radial`]).
#[derive(Clone)]
pub enum Symbol<S> {
    Stored(Vec<S>),
    Radial(Radial),
}

impl<S: SymbolValue> Symbol<S> {
    /// The same symbol with values of another type (stored values converted by
    /// `convert`, a computed one computed in the new type).
    pub fn map<U>(&self, convert: impl Fn(S) -> U + Sync + Send) -> Symbol<U>
    where
        U: Send,
    {
        match self {
            Self::Stored(v) => Symbol::Stored(v.par_iter().map(|&s| convert(s)).collect()),
            Self::Radial(r) => Symbol::Radial(r.clone()),
        }
    }
}

/// What a column pass can read a symbol from: a stored slice or vector (in full or by
/// its even half, told apart by the length), or a [`Symbol`].
pub trait Symbolic<S>: Sync {
    fn columns(&self, nc: usize, ny: usize) -> SymbolColumns<'_, S>;
}

impl<S: SymbolValue> Symbolic<S> for [S] {
    fn columns(&self, nc: usize, ny: usize) -> SymbolColumns<'_, S> {
        SymbolColumns::stored(self, nc, ny)
    }
}

impl<S: SymbolValue> Symbolic<S> for Vec<S> {
    fn columns(&self, nc: usize, ny: usize) -> SymbolColumns<'_, S> {
        SymbolColumns::stored(self, nc, ny)
    }
}

impl<S: SymbolValue> Symbolic<S> for Symbol<S> {
    fn columns(&self, nc: usize, ny: usize) -> SymbolColumns<'_, S> {
        match self {
            Self::Stored(v) => SymbolColumns::stored(v, nc, ny),
            Self::Radial(r) => {
                assert_eq!(
                    (r.nx / 2 + 1, r.ny),
                    (nc, ny),
                    "a computed symbol on another grid"
                );
                SymbolColumns {
                    ny,
                    source: Source::Radial(r, r.ky_squared()),
                }
            }
        }
    }
}

/// A thread's buffers for [`SymbolColumns::column`].
pub struct ColumnBuf<S> {
    values: Vec<S>,
    radial: Vec<f64>,
}

impl<S> Default for ColumnBuf<S> {
    fn default() -> Self {
        Self {
            values: Vec::new(),
            radial: Vec::new(),
        }
    }
}

enum Source<'a, S> {
    /// Values, `stored` rows per column (`ny`, or `ny/2 + 1`).
    Stored { values: &'a [S], stored: usize },
    /// Computed; the squared ky of rows `0..=ny/2`.
    Radial(&'a Radial, Vec<f64>),
}

/// A symbol's columns as a column pass reads them, `ny` rows each.
pub struct SymbolColumns<'a, S> {
    ny: usize,
    source: Source<'a, S>,
}

impl<'a, S: SymbolValue> SymbolColumns<'a, S> {
    /// The `nc` columns of `values`, full or even-half by its length.
    fn stored(values: &'a [S], nc: usize, ny: usize) -> Self {
        let half = even_rows(ny);
        let stored = if values.len() == nc * ny {
            ny
        } else {
            assert_eq!(
                values.len(),
                nc * half,
                "symbol length against the spectrum's (nx/2 + 1) * ny or its even half"
            );
            half
        };
        Self {
            ny,
            source: Source::Stored { values, stored },
        }
    }

    /// Whether every row is held in full (else the even half, or computed: even in ky).
    pub(crate) fn is_full(&self) -> bool {
        matches!(self.source, Source::Stored { stored, .. } if stored == self.ny)
    }

    /// The values of a full stored symbol (None otherwise).
    pub(crate) fn full_values(&self) -> Option<&'a [S]> {
        match self.source {
            Source::Stored { values, stored } if stored == self.ny => Some(values),
            _ => None,
        }
    }

    /// Column `c`'s `ny` values: the stored column, or `buf` filled from the stored half
    /// or computed (rows past ny/2 from their mirror).
    pub fn column<'b>(&self, c: usize, buf: &'b mut ColumnBuf<S>) -> &'b [S]
    where
        'a: 'b,
    {
        let ny = self.ny;
        let half = even_rows(ny);
        let out = &mut buf.values;
        out.clear();
        match &self.source {
            Source::Stored { values, stored } => {
                let col = &values[c * stored..(c + 1) * stored];
                if *stored == ny {
                    return col;
                }
                out.extend_from_slice(col);
            }
            Source::Radial(r, ky2) => {
                r.half_column(c, ky2, &mut buf.radial);
                out.extend(buf.radial.iter().map(|&v| S::of_f64(v)));
            }
        }
        let mirrored = ny - half.min(ny);
        out.extend_from_within(1..=mirrored);
        out[half..].reverse();
        out
    }
}
