//! Real 2D FFT on row-major `ny x nx` arrays, spectrum kept transposed.
//!
//! Forward: real-to-complex FFT of each row (length nx, `nx/2 + 1` outputs) into a row
//! buffer, then the column pass: blocks of columns are gathered (transposed) into the
//! spectrum, `(nx/2 + 1) x ny`, and transformed there while they are in cache. Inverse
//! reverses the steps, the row pass gathering its rows from the spectrum.
//! [`Fft2::convolve`] multiplies each column block by a symbol and transforms it back
//! inside the column pass, writing it back to the row buffer's columns, so a convolution
//! holds one grid-sized buffer (the row spectra) and streams the grid six times (the
//! input; the row buffer written, read and written by the column pass, read by the row
//! pass; the output), without the separate passes of a forward transform, a product and
//! an inverse transform. [`Fft2::convolve_hosted`] holds the row spectra in the output
//! grid's own memory instead (double precision, even row length): a convolution with
//! no grid-sized buffer of the transform's own.
//! A zero input row is not transformed (its spectrum is read as zeros), and an inverse
//! pass can leave out rows its caller does not read ([`Fft2::store_some_rows`]): a
//! solver's inputs and outputs restricted to a small contact set skip most rows.
//! Plans are created once; rows and column blocks are split over rayon threads. Each
//! output value is computed by the same sequence of operations whatever the thread
//! count, so results are bit-identical.
//!
//! The transform computes in double (`Fft2<f64>`, the default) or single precision
//! (`Fft2<f32>`, for the solver's preconditioner); inputs and outputs are f64 either
//! way, converted row by row while in cache.
//!
//! A symbol even in ky (every column's row r equal to row ny - r, bit for bit: any
//! function of |k|) can be stored by its rows `0..=ny/2` per column, half the memory,
//! or computed as the column pass reads it ([`crate::symbol`]); the other rows are read
//! from their mirror, so the products and the results are the same bit for bit.

use fftplans::{ComplexToReal, Fft, Planned, RealToComplex};
use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::num_traits::NumAssign;
use std::ops::MulAssign;
use std::sync::Arc;

use crate::symbol::{ColumnBuf, SymbolColumns, SymbolValue, Symbolic};

/// The precision a transform computes in (f64 or f32); rows arrive and leave as f64
/// (converted by [`SymbolValue::of_f64`] and [`Self::to_f64`]).
pub trait FftFloat: Planned + Default + NumAssign + bytemuck::Pod + SymbolValue {
    fn to_f64(self) -> f64;
    /// `src` as a row of this type: `src` itself for f64, converted into `buf` else.
    fn row<'a>(src: &'a mut [f64], buf: &'a mut [Self]) -> &'a mut [Self];
    /// Where a transform writes a row bound for `dst`: `dst` itself for f64, `buf` else.
    fn out_row<'a>(dst: &'a mut [f64], buf: &'a mut [Self]) -> &'a mut [Self];
    /// `dst = norm * row`, the row written where [`Self::out_row`] said.
    fn finish_row(dst: &mut [f64], buf: &[Self], norm: f64);
    /// `dst = norm * src`.
    fn scaled(dst: &mut [f64], src: &[Self], norm: f64);
}

impl FftFloat for f64 {
    fn to_f64(self) -> f64 {
        self
    }
    fn row<'a>(src: &'a mut [f64], _: &'a mut [f64]) -> &'a mut [f64] {
        src
    }
    fn out_row<'a>(dst: &'a mut [f64], _: &'a mut [f64]) -> &'a mut [f64] {
        dst
    }
    fn finish_row(dst: &mut [f64], _: &[f64], norm: f64) {
        dst.iter_mut().for_each(|v| *v *= norm);
    }
    fn scaled(dst: &mut [f64], src: &[f64], norm: f64) {
        for (o, v) in dst.iter_mut().zip(src) {
            *o = v * norm;
        }
    }
}

impl FftFloat for f32 {
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn row<'a>(src: &'a mut [f64], buf: &'a mut [f32]) -> &'a mut [f32] {
        for (b, v) in buf.iter_mut().zip(src.iter()) {
            *b = *v as f32;
        }
        &mut buf[..src.len()]
    }
    fn out_row<'a>(dst: &'a mut [f64], buf: &'a mut [f32]) -> &'a mut [f32] {
        &mut buf[..dst.len()]
    }
    fn finish_row(dst: &mut [f64], buf: &[f32], norm: f64) {
        Self::scaled(dst, buf, norm);
    }
    fn scaled(dst: &mut [f64], src: &[f32], norm: f64) {
        for (o, v) in dst.iter_mut().zip(src) {
            *o = *v as f64 * norm;
        }
    }
}

pub struct Fft2<T: FftFloat = f64> {
    nx: usize,
    ny: usize,
    nc: usize,
    r2c: Arc<dyn RealToComplex<T>>,
    c2r: Arc<dyn ComplexToReal<T>>,
    fwd_y: Arc<dyn Fft<T>>,
    inv_y: Arc<dyn Fft<T>>,
    /// Row spectra, `ny x nc` values of `Complex<T>` ([`rows_of`]), in a buffer of f64
    /// pairs (aligned for either precision; longer when lent by a bigger transform;
    /// empty while lent out, [`Fft2::borrow_rows_from`]); rows marked in `zero_rows`
    /// are not written.
    rows: Vec<Complex<f64>>,
    /// Per row of `rows`: whether the loaded row was zero (its spectrum is `zero_row`).
    zero_rows: Vec<bool>,
    /// `nc` zeros: the spectrum of a zero row.
    zero_row: Vec<Complex<T>>,
    /// A transposed spectrum (`nc x ny`) for [`Fft2::spectrum_of_even`], which hands it
    /// over; empty otherwise (a convolution's spectrum lives in `rows`).
    work: Vec<Complex<T>>,
    /// Row width and count held in `rows` by [`Fft2::load_rows`].
    loaded: Option<(usize, usize)>,
    /// Row width and count of a convolution held in `rows` (transformed back along
    /// columns) by [`Fft2::convolve_columns`] or [`Fft2::transform_columns`], awaiting
    /// [`Fft2::store_rows`].
    convolved: Option<(usize, usize)>,
}

/// Hooks of a plain transform: a chunk copied in from `src` ...
pub(crate) fn copy_in(src: &[f64], values: &mut [f64]) -> [f64; 0] {
    values.copy_from_slice(src);
    []
}

/// ... and out to `dst`.
pub(crate) fn copy_out(dst: &mut [f64], values: &[f64]) -> [f64; 0] {
    dst.copy_from_slice(values);
    []
}

/// Rows per task of the row passes.
const ROW_CHUNK: usize = 16;

/// Rows per chunk of [`Fft2::load_rows`] and [`Fft2::finish_rows`].
pub const ROWS_PER_CHUNK: usize = ROW_CHUNK;

/// Stretches [`transpose`] reads at a time: each visit of a destination line writes
/// this many consecutive values.
const GATHER: usize = 8;

/// Writes `stretch(j)[i]` to `dst[i * stride + j]` for `j` in `0..m` and every `i` of the
/// stretch (all stretches equally long, `dst` holding that many lines of `stride`):
/// [`GATHER`] stretches at a time, each cut once, instead of one bounds-checked strided
/// read per value.
#[inline(always)]
fn transpose<'s, C: Copy + 's>(
    dst: &mut [C],
    stride: usize,
    m: usize,
    stretch: impl Fn(usize) -> &'s [C],
) {
    let mut j0 = 0;
    while j0 + GATHER <= m {
        let s: [&[C]; GATHER] = std::array::from_fn(|k| stretch(j0 + k));
        for (i, line) in dst.chunks_exact_mut(stride).take(s[0].len()).enumerate() {
            let d: &mut [C; GATHER] = (&mut line[j0..j0 + GATHER])
                .try_into()
                .expect("GATHER values");
            for (d, s) in d.iter_mut().zip(&s) {
                *d = s[i];
            }
        }
        j0 += GATHER;
    }
    for j in j0..m {
        for (line, v) in dst.chunks_exact_mut(stride).zip(stretch(j)) {
            line[j] = *v;
        }
    }
}

/// Whether every value of `row` is zero (either sign; a NaN is not): the bits but the
/// sign's, or-ed over blocks of eight values (vector code), stopping at a block with
/// any set.
fn is_zero(row: &[f64]) -> bool {
    let bits = |m: u64, v: &f64| m | (v.to_bits() << 1);
    let (blocks, tail) = row.as_chunks::<8>();
    blocks.iter().all(|b| b.iter().fold(0, bits) == 0) && tail.iter().fold(0, bits) == 0
}

/// `n` zero values, allocated zeroed (calloc: fresh pages are mapped on first touch,
/// so rows a solve never loads cost no memory).
fn zeroed<T: FftFloat>(n: usize) -> Vec<Complex<T>> {
    bytemuck::zeroed_vec(n)
}

/// `sum |v|^2 weigh(k)` over a column `col` and its symbol values (at least as many),
/// in four lanes (value i to lane i % 4, the last `len % 4` to lane 0, the lanes added
/// as `(l0 + l1) + (l2 + l3)`): independent sums the processor overlaps, in a fixed
/// order.
#[inline(always)]
fn weighed_energy<T: FftFloat, S: Copy>(
    col: &[Complex<T>],
    symbol: &[S],
    weigh: impl Fn(S) -> f64,
) -> f64 {
    let (cb, ct) = col.as_chunks::<4>();
    let (sb, st) = symbol[..col.len()].as_chunks::<4>();
    let mut acc = [0.0f64; 4];
    for (c, s) in cb.iter().zip(sb) {
        for l in 0..4 {
            acc[l] += c[l].norm_sqr().to_f64() * weigh(s[l]);
        }
    }
    for (c, s) in ct.iter().zip(st) {
        acc[0] += c.norm_sqr().to_f64() * weigh(*s);
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// A spectrum a row pass reads: transposed (`nc x ny`, as [`Fft2::forward`] writes
/// it) or in the row buffer's layout (`ny x nc`, after an in-place column pass).
#[derive(Clone, Copy)]
enum Spectrum<'a, T> {
    Transposed(&'a [Complex<T>]),
    Rows(&'a [Complex<T>]),
}

/// The row buffer shared by the tasks of an in-place column pass, each of which reads
/// and writes only its own block of columns.
struct SharedRows<T>(*mut Complex<T>, usize);

// SAFETY: the tasks touch disjoint stretches (see `stretch`); Complex<T> is Send.
unsafe impl<T: Send> Send for SharedRows<T> {}
unsafe impl<T: Send> Sync for SharedRows<T> {}

impl<T> SharedRows<T> {
    /// The `len` values from `start`. SAFETY: no other task writes them meanwhile.
    unsafe fn stretch<'a>(&self, start: usize, len: usize) -> &'a [Complex<T>] {
        assert!(start + len <= self.1, "stretch inside the row buffer");
        unsafe { std::slice::from_raw_parts(self.0.add(start), len) }
    }

    /// The `len` values from `start`, to write. SAFETY: no other task reads or writes
    /// them meanwhile.
    #[allow(clippy::mut_from_ref)]
    unsafe fn stretch_mut<'a>(&self, start: usize, len: usize) -> &'a mut [Complex<T>] {
        assert!(start + len <= self.1, "stretch inside the row buffer");
        unsafe { std::slice::from_raw_parts_mut(self.0.add(start), len) }
    }
}

/// What a column pass does to each block after the forward transform: with a symbol,
/// weigh (`<x, s * x>`) and, with `back`, multiply and transform back.
struct ColumnWork<'a, S, W> {
    symbol: Option<&'a SymbolColumns<'a, S>>,
    weigh: Option<&'a W>,
    back: bool,
}

/// Length of a row buffer ([`Fft2`]'s `rows`, f64 pairs) that holds `values` complex
/// values of precision `T`.
fn buffer_len<T: FftFloat>(values: usize) -> usize {
    (values * std::mem::size_of::<Complex<T>>()).div_ceil(std::mem::size_of::<Complex<f64>>())
}

/// The first `len` values of a row buffer as `Complex<T>`.
fn rows_of<T: FftFloat>(buffer: &[Complex<f64>], len: usize) -> &[Complex<T>] {
    let all: &[Complex<T>] = bytemuck::cast_slice(buffer);
    assert!(all.len() >= len, "the transform's row buffer is lent out");
    &all[..len]
}

/// [`rows_of`], mutable.
fn rows_of_mut<T: FftFloat>(buffer: &mut [Complex<f64>], len: usize) -> &mut [Complex<T>] {
    let all: &mut [Complex<T>] = bytemuck::cast_slice_mut(buffer);
    assert!(all.len() >= len, "the transform's row buffer is lent out");
    &mut all[..len]
}

/// Target size of a column block in complex values (256 KiB: in a core's L2 cache).
const COLUMN_BLOCK: usize = 16_384;

impl<T: FftFloat> Fft2<T> {
    pub fn new(nx: usize, ny: usize) -> Self {
        Self::new_sized(nx, ny, buffer_len::<T>(ny * (nx / 2 + 1)))
    }

    /// A transform with a zeroed row buffer of `buffer` f64 pairs.
    fn new_sized(nx: usize, ny: usize, buffer: usize) -> Self {
        let nc = nx / 2 + 1;
        Self {
            nx,
            ny,
            nc,
            r2c: T::real_forward(nx),
            c2r: T::real_inverse(nx),
            fwd_y: fftplans::forward(ny),
            inv_y: fftplans::inverse(ny),
            rows: zeroed(buffer),
            zero_rows: vec![false; ny],
            zero_row: vec![Complex::default(); nc],
            work: Vec::new(),
            loaded: None,
            convolved: None,
        }
    }

    /// [`Fft2::new`] without a row buffer of its own: it borrows one
    /// ([`Fft2::borrow_rows_from`]) before each use.
    pub fn without_rows(nx: usize, ny: usize) -> Self {
        Self::new_sized(nx, ny, 0)
    }

    /// [`Fft2::new`] with a row buffer sized for spectra of precision `U` (smaller than
    /// its own for a double-precision transform whose convolutions hold their spectra
    /// in the output, [`Fft2::convolve_hosted`], and which lends its buffer to
    /// single-precision transforms). A fused application in its own precision grows the
    /// buffer first.
    pub fn with_rows_for<U: FftFloat>(nx: usize, ny: usize) -> Self {
        Self::new_sized(nx, ny, buffer_len::<U>(ny * (nx / 2 + 1)))
    }

    /// Bytes of the row buffer this transform holds (0 while lent out).
    #[cfg(test)]
    pub(crate) fn row_buffer_bytes(&self) -> usize {
        std::mem::size_of_val(&self.rows[..])
    }

    /// Whether this transform holds a row buffer large enough for its grid.
    fn holds_rows(&self) -> bool {
        self.rows.len() >= buffer_len::<T>(self.ny * self.nc)
    }

    /// A row buffer held but too small for this grid's spectra
    /// ([`Fft2::with_rows_for`]) grown to size (zeros appended); a lent-out one is left.
    fn grow_rows(&mut self) {
        if !self.rows.is_empty() && !self.holds_rows() {
            self.rows
                .resize(buffer_len::<T>(self.ny * self.nc), Complex::default());
        }
    }

    /// Takes `other`'s row buffer unless this transform holds one (or `other` none:
    /// then nothing changes, and a transform without a buffer panics when used): for an
    /// operator's transforms that never need a convolution of both at the same time
    /// (K's and the preconditioner's, in either precision), one grid-sized buffer
    /// instead of one each. Rows `other` had loaded or convolved are abandoned: finishing
    /// them later panics ("without load_rows") instead of reading this transform's
    /// values. Results are the same bit for bit: every value a pass reads was written by
    /// the same convolution. A buffer too small for this grid's spectra is grown when
    /// this transform loads rows ([`Fft2::with_rows_for`]).
    pub fn borrow_rows_from<U: FftFloat>(&mut self, other: &mut Fft2<U>) {
        if self.holds_rows() || other.rows.is_empty() {
            return;
        }
        other.loaded = None;
        other.convolved = None;
        self.rows = std::mem::take(&mut other.rows);
    }

    /// Length of the transposed spectrum, `(nx/2 + 1) * ny`.
    pub fn spectrum_len(&self) -> usize {
        self.nc * self.ny
    }
    pub fn nc(&self) -> usize {
        self.nc
    }

    /// Forward transform of `input` (`ny x nx`, row-major) into `spec` (`nc x ny`).
    pub fn forward(&mut self, input: &[f64], spec: &mut [Complex<T>]) {
        self.forward_padded(input, self.nx, self.ny, spec);
    }

    /// Forward transform of a zero-padded input: the first `rows` rows of the grid
    /// hold `input`'s rows (`width <= nx` values each, the rest of the row zero), the
    /// other rows are zero. Zero rows are not transformed.
    pub fn forward_padded(
        &mut self,
        input: &[f64],
        width: usize,
        rows: usize,
        spec: &mut [Complex<T>],
    ) {
        let chunk = width * ROW_CHUNK;
        self.load_rows((width, rows), input.par_chunks(chunk), copy_in);
        let (_, rows) = self.loaded.take().expect("rows just loaded");
        self.column_pass::<T, fn(T) -> f64>(spec, rows, None, None, false);
    }

    /// Inverse transform of `spec` (`nc x ny`, destroyed) into `output` (`ny x nx`),
    /// normalised so that inverse(forward(x)) = x.
    pub fn inverse(&mut self, spec: &mut [Complex<T>], output: &mut [f64]) {
        self.inverse_cropped(spec, output, self.nx, self.ny);
    }

    /// As [`Self::inverse`] keeping only the first `rows` rows and `width <= nx`
    /// columns (`output` is `rows x width`); discarded rows are not computed.
    pub fn inverse_cropped(
        &mut self,
        spec: &mut [Complex<T>],
        output: &mut [f64],
        width: usize,
        rows: usize,
    ) {
        let ny = self.ny;
        let per = self.columns_per_block();
        let inv = &self.inv_y;
        spec.par_chunks_mut(ny * per).for_each_init(
            || vec![Complex::default(); inv.get_inplace_scratch_len()],
            |scratch, block| inv.process_with_scratch(block, scratch),
        );
        let chunk = width * ROW_CHUNK;
        let items = output[..rows.min(ny) * width].par_chunks_mut(chunk);
        let spec = Spectrum::Transposed(spec);
        self.row_pass_inverse(spec, width, rows.min(ny), items, copy_out, None);
    }

    /// `output = inverse(symbol * forward(input))` (zero-padded input and cropped
    /// output, `(width, rows)`, as in [`Self::forward_padded`] and
    /// [`Self::inverse_cropped`]), `symbol` in the spectrum's layout; the result equals
    /// those three steps bit for bit.
    pub fn convolve<S>(
        &mut self,
        input: &[f64],
        (width, rows): (usize, usize),
        symbol: &(impl Symbolic<S> + ?Sized),
        output: &mut [f64],
    ) where
        S: SymbolValue,
        Complex<T>: MulAssign<S>,
    {
        let chunk = width * ROW_CHUNK;
        self.load_rows((width, rows), input.par_chunks(chunk), copy_in);
        self.finish_rows(symbol, output.par_chunks_mut(chunk), copy_out);
    }

    /// [`Self::convolve`] with the output in place of the input.
    pub fn convolve_in_place<S>(
        &mut self,
        data: &mut [f64],
        dims: (usize, usize),
        symbol: &(impl Symbolic<S> + ?Sized),
    ) where
        S: SymbolValue,
        Complex<T>: MulAssign<S>,
    {
        let chunk = dims.0 * ROW_CHUNK;
        self.load_rows(dims, data.par_chunks(chunk), copy_in);
        self.finish_rows(symbol, data.par_chunks_mut(chunk), copy_out);
    }

    /// First half of a fused convolution: the input of the first `rows` rows (`width`
    /// values each, zero-padded to nx; the other rows zero) is produced chunk by chunk,
    /// [`ROWS_PER_CHUNK`] rows at a time: `load(item, values)` fills the chunk's
    /// values (row-major, `width` per row) from the caller's item for that chunk (e.g.
    /// zipped `par_chunks` of its arrays) and returns partial sums, collected in chunk
    /// order. The rows are transformed at once, while in cache; a caller that reads its
    /// arrays here saves writing the input to memory and reading it back.
    pub fn load_rows<I, F, const A: usize>(
        &mut self,
        (width, rows): (usize, usize),
        items: I,
        load: F,
    ) -> Vec<[f64; A]>
    where
        I: IntoParallelIterator,
        I::Iter: IndexedParallelIterator,
        F: Fn(I::Item, &mut [f64]) -> [f64; A] + Sync,
    {
        let (nx, nc) = (self.nx, self.nc);
        let rows = rows.min(self.ny);
        assert!(width <= nx, "row width {width} exceeds the grid's {nx}");
        self.grow_rows();
        self.loaded = Some((width, rows));
        let items = items.into_par_iter();
        assert_eq!(
            items.len(),
            rows.div_ceil(ROW_CHUNK),
            "one item per row chunk"
        );
        let r2c = &self.r2c;
        rows_of_mut::<T>(&mut self.rows, rows * nc)
            .par_chunks_mut(nc * ROW_CHUNK)
            .zip(self.zero_rows[..rows].par_chunks_mut(ROW_CHUNK))
            .zip(items)
            .map_init(
                // realfft overwrites its input: padded rows are copied first.
                || {
                    (
                        r2c.make_scratch_vec(),
                        vec![0.0; ROW_CHUNK * width],
                        vec![T::default(); nx],
                    )
                },
                |(scratch, values, row), ((out, zero), item)| {
                    let count = out.len() / nc;
                    let sums = load(item, &mut values[..count * width]);
                    let spectra = out.chunks_mut(nc).zip(zero.iter_mut());
                    for ((b, zero), s) in spectra.zip(values.chunks_mut(width)) {
                        // A zero row (e.g. off the contact set) has a zero spectrum: the
                        // column pass reads `zero_row` instead.
                        *zero = is_zero(s);
                        if *zero {
                            continue;
                        }
                        let input = if width == nx {
                            T::row(s, row)
                        } else {
                            for (r, v) in row[..width].iter_mut().zip(s.iter()) {
                                *r = T::of_f64(*v);
                            }
                            row[width..].iter_mut().for_each(|v| *v = T::default());
                            &mut row[..]
                        };
                        r2c.process_with_scratch(input, b, scratch)
                            .expect("row fft");
                    }
                    sums
                },
            )
            .collect()
    }

    /// Second half of a fused convolution: the rows given to [`Self::load_rows`] are
    /// transformed along columns, multiplied by `symbol` (the spectrum's layout) and
    /// transformed back; `store(item, values)` receives each chunk of the result (the
    /// loaded rows and width, row-major, normalised) with the caller's item for that
    /// chunk and returns partial sums, collected in chunk order.
    pub fn finish_rows<S, I, F, const B: usize>(
        &mut self,
        symbol: &(impl Symbolic<S> + ?Sized),
        items: I,
        store: F,
    ) -> Vec<[f64; B]>
    where
        S: SymbolValue,
        Complex<T>: MulAssign<S>,
        I: IntoParallelIterator,
        I::Iter: IndexedParallelIterator,
        F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
    {
        self.convolve_columns(symbol);
        self.store_rows(items, store)
    }

    /// [`Self::finish_rows`] in two steps: this one transforms the loaded rows along
    /// columns, multiplies by `symbol` and transforms back; [`Self::store_rows`] then
    /// hands the rows out.
    pub fn convolve_columns<S>(&mut self, symbol: &(impl Symbolic<S> + ?Sized))
    where
        S: SymbolValue,
        Complex<T>: MulAssign<S>,
    {
        self.column_step(symbol, None::<fn(S) -> f64>, true);
    }

    /// [`Self::convolve_columns`] for a caller that needs a number of the whole
    /// convolution before its rows come back: with a real `symbol`, also returns
    /// `<x, s * x>`, the input x against its convolution (Parseval:
    /// `sum |x_hat|^2 s / (nx ny)` over the spectrum, the conjugate half's columns
    /// counted by doubling), summed in a fixed order; [`Self::store_rows`] then
    /// finishes. The result is the same as [`Self::finish_rows`]'s, bit for bit.
    pub fn transform_columns<S>(&mut self, symbol: &(impl Symbolic<S> + ?Sized)) -> f64
    where
        S: SymbolValue + Into<f64>,
        Complex<T>: MulAssign<S>,
    {
        self.column_step(symbol, Some(|s: S| s.into()), true)
    }

    /// `<x, s * x>` of the loaded rows as [`Self::transform_columns`] returns it (bit
    /// for bit), without the convolution: the column pass stops after the forward
    /// transform, and no rows follow (the loaded rows are consumed).
    pub fn column_energy<S>(&mut self, symbol: &(impl Symbolic<S> + ?Sized)) -> f64
    where
        S: SymbolValue + Into<f64>,
        Complex<T>: MulAssign<S>,
    {
        self.column_step(symbol, Some(|s: S| s.into()), false)
    }

    /// Second step of [`Self::convolve_columns`] or [`Self::transform_columns`]: the
    /// convolution's rows, handed to `store` as [`Self::finish_rows`] hands them.
    pub fn store_rows<I, F, const B: usize>(&mut self, items: I, store: F) -> Vec<[f64; B]>
    where
        I: IntoParallelIterator,
        I::Iter: IndexedParallelIterator,
        F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
    {
        self.store_some_rows(items, store, None)
    }

    /// [`Self::store_rows`] computing only the rows `wanted` marks (one flag per row;
    /// `None`: all): the others are handed to `store` unspecified (zeros or values of
    /// earlier rows), for a `store` that skips them; a chunk without wanted rows does
    /// not read the spectrum. The wanted rows are the same bit for bit.
    pub fn store_some_rows<I, F, const B: usize>(
        &mut self,
        items: I,
        store: F,
        wanted: Option<&[bool]>,
    ) -> Vec<[f64; B]>
    where
        I: IntoParallelIterator,
        I::Iter: IndexedParallelIterator,
        F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
    {
        let (width, rows) = self
            .convolved
            .take()
            .expect("store_rows without convolve_columns");
        let spec = Spectrum::Rows(rows_of(&self.rows, self.ny * self.nc));
        self.row_pass_inverse(spec, width, rows, items, store, wanted)
    }

    /// The column pass of a convolution of the loaded rows, in place in `rows`; with
    /// `weigh` (a real symbol's value), also `<x, s * x>` (see
    /// [`Self::transform_columns`]); without `back`, only that number (the pass stops
    /// after the forward transform).
    fn column_step<S, W>(
        &mut self,
        symbol: &(impl Symbolic<S> + ?Sized),
        weigh: Option<W>,
        back: bool,
    ) -> f64
    where
        S: SymbolValue,
        W: Fn(S) -> f64 + Sync,
        Complex<T>: MulAssign<S>,
    {
        let (width, rows) = self.loaded.take().expect("column step without load_rows");
        let symbol = symbol.columns(self.nc, self.ny);
        let energy = self.column_pass_in_place(rows, &symbol, weigh, back);
        if back {
            self.convolved = Some((width, rows));
        }
        energy
    }

    /// The work buffer (a transposed spectrum), allocated zeroed on first use.
    fn take_work(&mut self) -> Vec<Complex<T>> {
        let work = std::mem::take(&mut self.work);
        if work.len() == self.spectrum_len() {
            work
        } else {
            zeroed(self.spectrum_len())
        }
    }

    /// The spectrum (`nc x ny`, as [`Self::forward`] gives it) of a grid even in y
    /// (row `j` equal to row `ny - j`) whose row `j <= ny / 2` is `fill(j, row)` (all
    /// `nx` values): an operator's symbol without a grid-sized input array. Only rows
    /// `0..=ny/2` are filled and transformed, the others take their mirror's spectrum.
    /// The same values as [`Self::forward`] of that grid, bit for bit.
    pub fn spectrum_of_even(&mut self, fill: impl Fn(usize, &mut [f64]) + Sync) -> Vec<Complex<T>> {
        let (nx, ny, nc) = (self.nx, self.ny, self.nc);
        let half = ny / 2 + 1;
        let chunks = (0..half.div_ceil(ROW_CHUNK)).into_par_iter();
        self.load_rows((nx, half), chunks, |b, values| {
            for (k, row) in values.chunks_mut(nx).enumerate() {
                fill(b * ROW_CHUNK + k, row);
            }
            []
        });
        self.loaded = None;
        let (low, high) = rows_of_mut::<T>(&mut self.rows, ny * nc).split_at_mut(half * nc);
        let (low_zero, high_zero) = self.zero_rows.split_at_mut(half);
        high[..(ny - half) * nc]
            .par_chunks_mut(nc)
            .zip(&mut high_zero[..ny - half])
            .enumerate()
            .for_each(|(r, (row, zero))| {
                let mirror = ny - (half + r);
                row.copy_from_slice(&low[mirror * nc..(mirror + 1) * nc]);
                *zero = low_zero[mirror];
            });
        let mut work = self.take_work();
        self.column_pass::<T, fn(T) -> f64>(&mut work, ny, None, None, false);
        work
    }

    /// [`Self::inverse`] of the real spectrum `symbol` (`nc x ny` values or their even
    /// half, zero imaginary parts) into `output`: a kernel's real-space table.
    pub fn inverse_of_real(&mut self, symbol: &(impl Symbolic<f64> + ?Sized), output: &mut [f64]) {
        let columns = symbol.columns(self.nc, self.ny);
        let mut work = self.take_work();
        work.par_chunks_mut(self.ny).enumerate().for_each_init(
            ColumnBuf::default,
            |buf, (c, col)| {
                for (w, &s) in col.iter_mut().zip(columns.column(c, buf)) {
                    *w = Complex::new(T::of_f64(s), T::default());
                }
            },
        );
        self.inverse(&mut work, output);
    }

    /// Columns per block of the column pass: about [`COLUMN_BLOCK`] values.
    fn columns_per_block(&self) -> usize {
        (COLUMN_BLOCK / self.ny).clamp(1, self.nc)
    }

    /// Column pass: gathers each block of columns of the row buffer (its first `filled`
    /// rows; the others count as zero) into `spec` (`nc x ny`) and transforms it; with
    /// a symbol and `back`, multiplies and transforms back (unnormalised) while in
    /// cache. With a symbol and `weigh`, returns `<x, s * x>` (see
    /// [`Self::transform_columns`]; else 0): per block, then the blocks in order.
    fn column_pass<S, W>(
        &self,
        spec: &mut [Complex<T>],
        filled: usize,
        symbol: Option<&SymbolColumns<'_, S>>,
        weigh: Option<W>,
        back: bool,
    ) -> f64
    where
        S: SymbolValue,
        W: Fn(S) -> f64 + Sync,
        Complex<T>: MulAssign<S>,
    {
        let (ny, nc, per) = (self.ny, self.nc, self.columns_per_block());
        let src = rows_of::<T>(&self.rows, ny * nc);
        let parts: Vec<f64> = spec
            .par_chunks_mut(ny * per)
            .enumerate()
            .map_init(
                || vec![Complex::default(); self.scratch_len()],
                |scratch, (b, block)| {
                    let (c0, width) = (b * per, block.len() / ny);
                    let read = |r: usize| &src[r * nc + c0..r * nc + c0 + width];
                    let to = ColumnWork {
                        symbol,
                        weigh: weigh.as_ref(),
                        back,
                    };
                    self.block_pass(block, scratch, (c0, filled), (read, None), to)
                },
            )
            .collect();
        self.total_energy(&parts)
    }

    /// The column pass of a convolution in place in the row buffer (its first `filled`
    /// rows; the others count as zero): each block of columns is gathered into a block
    /// of the thread's own, transformed, weighed (`<x, s * x>` with `weigh`, as
    /// [`Self::column_pass`]), and with `back` multiplied by `symbol`, transformed back
    /// (unnormalised) and written back to its columns, every row. The same operations
    /// on the same values as [`Self::column_pass`] into a transposed spectrum, without
    /// a second grid-sized buffer.
    fn column_pass_in_place<S, W>(
        &mut self,
        filled: usize,
        symbol: &SymbolColumns<'_, S>,
        weigh: Option<W>,
        back: bool,
    ) -> f64
    where
        S: SymbolValue,
        W: Fn(S) -> f64 + Sync,
        Complex<T>: MulAssign<S>,
    {
        let (ny, nc) = (self.ny, self.nc);
        let view = rows_of_mut::<T>(&mut self.rows, ny * nc);
        let rows = SharedRows(view.as_mut_ptr(), view.len());
        let work = ColumnWork {
            symbol: Some(symbol),
            weigh: weigh.as_ref(),
            back,
        };
        let parts = self.column_blocks((&rows, nc, None), filled, work);
        if back {
            self.zero_rows.fill(false);
        }
        self.total_energy(&parts)
    }

    /// The tasks of an in-place column pass: each block of columns of the row spectra
    /// (`rows`, `stride` values per row; with `nyquist`, the last column in that column
    /// of ny values instead) through [`Self::block_pass`] with `work`, and with
    /// `work.back` written back to where it was read. Returns each block's energy.
    fn column_blocks<S, W>(
        &self,
        (rows, stride, nyquist): (&SharedRows<T>, usize, Option<&SharedRows<T>>),
        filled: usize,
        work: ColumnWork<'_, S, W>,
    ) -> Vec<f64>
    where
        S: SymbolValue,
        W: Fn(S) -> f64 + Sync,
        Complex<T>: MulAssign<S>,
    {
        let (ny, nc, per) = (self.ny, self.nc, self.columns_per_block());
        (0..nc.div_ceil(per))
            .into_par_iter()
            .map_init(
                || {
                    let block = vec![Complex::default(); per * ny];
                    (vec![Complex::default(); self.scratch_len()], block)
                },
                |(scratch, block), b| {
                    let (c0, width) = (b * per, per.min(nc - b * per));
                    let block = &mut block[..width * ny];
                    // The last block ends with the Nyquist column where it lies apart.
                    let side = nyquist.filter(|_| c0 + width == nc);
                    let stretch = width - side.is_some() as usize;
                    // SAFETY: blocks hold disjoint columns; each task reads and writes
                    // only its own columns' stretches, and the last block alone the
                    // Nyquist column.
                    let read = |r: usize| unsafe { rows.stretch(r * stride + c0, stretch) };
                    let column = side.map(|c| unsafe { c.stretch(0, ny) });
                    let to = ColumnWork {
                        symbol: work.symbol,
                        weigh: work.weigh,
                        back: work.back,
                    };
                    let energy = self.block_pass(block, scratch, (c0, filled), (read, column), to);
                    if work.back {
                        for r in 0..ny {
                            // SAFETY: as above.
                            let dst = unsafe { rows.stretch_mut(r * stride + c0, stretch) };
                            for (c, d) in dst.iter_mut().enumerate() {
                                *d = block[c * ny + r];
                            }
                        }
                        if let Some(c) = side {
                            // SAFETY: as above.
                            let dst = unsafe { c.stretch_mut(0, ny) };
                            dst.copy_from_slice(&block[stretch * ny..]);
                        }
                    }
                    energy
                },
            )
            .collect()
    }

    /// Scratch length of the column transforms.
    fn scratch_len(&self) -> usize {
        self.fwd_y
            .get_inplace_scratch_len()
            .max(self.inv_y.get_inplace_scratch_len())
    }

    /// `<x, s * x>` from the column blocks' parts, added in block order.
    fn total_energy(&self, parts: &[f64]) -> f64 {
        parts.iter().sum::<f64>() / (self.nx * self.ny) as f64
    }

    /// One block of columns `c0..` of a column pass, `block` column-major (`ny` per
    /// column): row r's stretch `read(r)` of the row spectra (r < `filled`; a row marked
    /// zero reads zeros, the rows from `filled` on are zero) gathered in, and with
    /// `nyquist` the block's last column from there instead (the stretches one shorter:
    /// spectra hosted in a real grid, [`Fft2::convolve_hosted`]); transformed; with a
    /// symbol, `<x, s * x>` summed over the block's columns (with `weigh`) and, with
    /// `back`, the product transformed back. Returns the block's energy (else 0).
    fn block_pass<'r, S, W>(
        &self,
        block: &mut [Complex<T>],
        scratch: &mut [Complex<T>],
        (c0, filled): (usize, usize),
        (read, nyquist): (impl Fn(usize) -> &'r [Complex<T>], Option<&'r [Complex<T>]>),
        to: ColumnWork<'_, S, W>,
    ) -> f64
    where
        T: 'r,
        S: SymbolValue,
        W: Fn(S) -> f64,
        Complex<T>: MulAssign<S>,
    {
        let (nx, ny, nc) = (self.nx, self.ny, self.nc);
        // Columns 0 and nx/2 (even nx) are their own conjugates; the others stand for
        // two.
        let twice = |c: usize| c > 0 && !(nx % 2 == 0 && c == nc - 1);
        let width = block.len() / ny;
        let stretch = width - nyquist.is_some() as usize;
        let (zero_rows, zero_row) = (&self.zero_rows, &self.zero_row);
        // Row r's stretch of this block's columns becomes entry r of each.
        transpose(block, ny, filled, |r| {
            if zero_rows[r] {
                &zero_row[c0..c0 + stretch]
            } else {
                read(r)
            }
        });
        if let Some(column) = nyquist {
            let last = &mut block[stretch * ny..];
            for (r, v) in last[..filled].iter_mut().enumerate() {
                *v = if zero_rows[r] { zero_row[0] } else { column[r] };
            }
        }
        for col in block.chunks_mut(ny) {
            col[filled..]
                .iter_mut()
                .for_each(|v| *v = Complex::default());
        }
        self.fwd_y.process_with_scratch(block, scratch);
        let mut energy = 0.0;
        if let Some(s) = to.symbol {
            // Each column's energy before its product (the same values either way).
            let mut buf = ColumnBuf::default();
            for (c, col) in block.chunks_mut(ny).enumerate() {
                let k = s.column(c0 + c, &mut buf);
                if let Some(weigh) = to.weigh {
                    let e = weighed_energy(col, k, weigh);
                    energy += if twice(c0 + c) { 2.0 * e } else { e };
                }
                if to.back {
                    for (v, k) in col.iter_mut().zip(k) {
                        *v *= *k;
                    }
                }
            }
            if to.back {
                self.inv_y.process_with_scratch(block, scratch);
            }
        }
        energy
    }

    /// Complex-to-real transforms of the first `rows` rows of `spec` (transformed along
    /// columns), a chunk at a time, normalised, cropped to `width` columns and handed to
    /// `store` with the chunk's item; rows that `wanted` (if given) does not mark are not
    /// computed (their values are left as they were).
    fn row_pass_inverse<I, F, const B: usize>(
        &self,
        spec: Spectrum<'_, T>,
        width: usize,
        rows: usize,
        items: I,
        store: F,
        wanted: Option<&[bool]>,
    ) -> Vec<[f64; B]>
    where
        I: IntoParallelIterator,
        I::Iter: IndexedParallelIterator,
        F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
    {
        let (nx, nc, ny) = (self.nx, self.nc, self.ny);
        let c2r = &self.c2r;
        let norm = 1.0 / (nx * ny) as f64;
        let chunks = rows.div_ceil(ROW_CHUNK);
        let items = items.into_par_iter();
        assert_eq!(items.len(), chunks, "one item per row chunk");
        (0..chunks)
            .into_par_iter()
            .zip(items)
            .map_init(
                || {
                    (
                        c2r.make_scratch_vec(),
                        vec![Complex::default(); ROW_CHUNK * nc],
                        vec![T::default(); nx],
                        vec![0.0; ROW_CHUNK * width],
                    )
                },
                |(scratch, buf, full, values), (b, item)| {
                    let r0 = b * ROW_CHUNK;
                    let count = ROW_CHUNK.min(rows - r0);
                    let want = |k: usize| wanted.is_none_or(|w| w[r0 + k]);
                    if (0..count).any(want) {
                        match spec {
                            // Column c's stretch of this chunk's rows becomes entry c of
                            // each.
                            Spectrum::Transposed(spec) => {
                                transpose(buf, nc, nc, |c| &spec[c * ny + r0..c * ny + r0 + count])
                            }
                            Spectrum::Rows(spec) => {
                                buf[..count * nc].copy_from_slice(&spec[r0 * nc..(r0 + count) * nc])
                            }
                        }
                    }
                    let rows = buf
                        .chunks_mut(nc)
                        .zip(values[..count * width].chunks_mut(width));
                    for (k, (a, o)) in rows.enumerate() {
                        if !want(k) {
                            continue;
                        }
                        // The DC and Nyquist imaginary parts must vanish for c2r; they do
                        // up to rounding for real data, so clear them.
                        a[0].im = T::default();
                        if nx.is_multiple_of(2) {
                            a[nc - 1].im = T::default();
                        }
                        if width == nx {
                            let out = T::out_row(o, full);
                            c2r.process_with_scratch(a, out, scratch).expect("row ifft");
                            T::finish_row(o, full, norm);
                        } else {
                            c2r.process_with_scratch(a, full, scratch)
                                .expect("row ifft");
                            T::scaled(o, full, norm);
                        }
                    }
                    store(item, &values[..count * width])
                },
            )
            .collect()
    }
}

/// Convolutions whose row spectra live in the output grid's own memory: a
/// double-precision convolution without a grid-sized buffer of the transform's own.
///
/// A real row of even length nx has `nx/2 + 1` spectral values; the first `nx/2` fill
/// exactly the row's nx reals, and the last (the Nyquist column) goes to a column of
/// `ny` values beside the grid. Each row pass reads and writes only its own rows of the
/// grid, and the column pass each block of columns, so the output holds the spectrum
/// from the forward row pass to the inverse one.
impl Fft2<f64> {
    /// [`Self::convolve`] of the whole grid (`ny x nx`, nx even), bit for bit, with the
    /// row spectra held in `output` (module docs; the transform's row buffer is neither
    /// read nor written, and may be lent out or sized for single precision only). A
    /// fused application the transform had loaded is abandoned (finishing it panics).
    pub fn convolve_hosted<S>(
        &mut self,
        input: &[f64],
        symbol: &(impl Symbolic<S> + ?Sized),
        output: &mut [f64],
    ) where
        S: SymbolValue,
        Complex<f64>: MulAssign<S>,
    {
        let (nx, ny) = (self.nx, self.ny);
        assert!(
            nx.is_multiple_of(2),
            "hosted spectra need an even row length"
        );
        assert_eq!(input.len(), nx * ny, "input of the grid's size");
        assert_eq!(output.len(), nx * ny, "output of the grid's size");
        self.loaded = None;
        self.convolved = None;
        let mut nyquist = vec![Complex::default(); ny];
        self.hosted_rows_forward(input, output, &mut nyquist);
        let symbol = symbol.columns(self.nc, ny);
        self.hosted_columns(output, &mut nyquist, &symbol);
        self.hosted_rows_inverse(output, &nyquist);
    }

    /// The forward row pass of [`Self::convolve_hosted`]: row r's spectrum into row r of
    /// `host` and `nyquist[r]` (a zero row is marked, not transformed, as in
    /// [`Self::load_rows`]).
    fn hosted_rows_forward(
        &mut self,
        input: &[f64],
        host: &mut [f64],
        nyquist: &mut [Complex<f64>],
    ) {
        let (nx, half) = (self.nx, self.nx / 2);
        let r2c = &self.r2c;
        let chunk = nx * ROW_CHUNK;
        host.par_chunks_mut(chunk)
            .zip(input.par_chunks(chunk))
            .zip(nyquist.par_chunks_mut(ROW_CHUNK))
            .zip(self.zero_rows.par_chunks_mut(ROW_CHUNK))
            .for_each_init(
                || {
                    let spectrum = vec![Complex::default(); half + 1];
                    (r2c.make_scratch_vec(), vec![0.0; nx], spectrum)
                },
                |(scratch, row, spectrum), (((out, input), nyquist), zero)| {
                    let rows = out.chunks_mut(nx).zip(input.chunks(nx));
                    for (((out, input), nyquist), zero) in rows.zip(nyquist).zip(zero) {
                        *zero = is_zero(input);
                        if *zero {
                            continue;
                        }
                        // realfft overwrites its input.
                        row.copy_from_slice(input);
                        r2c.process_with_scratch(row, spectrum, scratch)
                            .expect("row fft");
                        let out: &mut [Complex<f64>] = bytemuck::cast_slice_mut(out);
                        out.copy_from_slice(&spectrum[..half]);
                        *nyquist = spectrum[half];
                    }
                },
            );
    }

    /// The column pass of [`Self::convolve_hosted`], as [`Self::column_pass_in_place`]
    /// runs it (the same blocks), on the spectra in `host` and `nyquist`.
    fn hosted_columns<S>(
        &mut self,
        host: &mut [f64],
        nyquist: &mut [Complex<f64>],
        symbol: &SymbolColumns<'_, S>,
    ) where
        S: SymbolValue,
        Complex<f64>: MulAssign<S>,
    {
        let view: &mut [Complex<f64>] = bytemuck::cast_slice_mut(host);
        let rows = SharedRows(view.as_mut_ptr(), view.len());
        let side = SharedRows(nyquist.as_mut_ptr(), nyquist.len());
        let work = ColumnWork {
            symbol: Some(symbol),
            weigh: None::<&fn(S) -> f64>,
            back: true,
        };
        self.column_blocks((&rows, self.nc - 1, Some(&side)), self.ny, work);
        self.zero_rows.fill(false);
    }

    /// The inverse row pass of [`Self::convolve_hosted`]: each row's spectrum (row r of
    /// `host` and `nyquist[r]`) transformed back into row r, normalised, as
    /// [`Self::store_rows`] computes it.
    fn hosted_rows_inverse(&self, host: &mut [f64], nyquist: &[Complex<f64>]) {
        let (nx, nc) = (self.nx, self.nc);
        let half = nc - 1;
        let c2r = &self.c2r;
        let norm = 1.0 / (nx * self.ny) as f64;
        host.par_chunks_mut(nx * ROW_CHUNK)
            .zip(nyquist.par_chunks(ROW_CHUNK))
            .for_each_init(
                || (c2r.make_scratch_vec(), vec![Complex::default(); nc]),
                |(scratch, spectrum), (out, nyquist)| {
                    for (row, nyquist) in out.chunks_mut(nx).zip(nyquist) {
                        spectrum[..half].copy_from_slice(bytemuck::cast_slice(row));
                        spectrum[half] = *nyquist;
                        // The DC and Nyquist imaginary parts must vanish for c2r (as in
                        // the owned row pass).
                        spectrum[0].im = 0.0;
                        spectrum[half].im = 0.0;
                        c2r.process_with_scratch(spectrum, row, scratch)
                            .expect("row ifft");
                        row.iter_mut().for_each(|v| *v *= norm);
                    }
                },
            );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::symbol::{even_rows, full_symbol, halve_if_even};
    use rustfft::num_complex::Complex64;

    /// Test input: `len` values in [-0.3, 0.7) without a pattern a transform favours.
    fn ramp(len: usize) -> Vec<f64> {
        (0..len)
            .map(|k| ((k * 7919) % 97) as f64 / 97.0 - 0.3)
            .collect()
    }

    /// A real symbol (`nc x ny`, the spectrum's layout) that is a function of the
    /// column and |ky|: even in ky bit for bit.
    fn even_in_ky(nc: usize, ny: usize) -> Vec<f64> {
        (0..nc * ny)
            .map(|b| {
                let (c, r) = (b / ny, (b % ny) as f64);
                1.0 + c as f64 / 3.0 + (r.min(ny as f64 - r)).sqrt()
            })
            .collect()
    }

    /// Test symbol: `len` real values 1..=13.
    fn steps(len: usize) -> Vec<f64> {
        (0..len).map(|k| 1.0 + (k % 13) as f64).collect()
    }

    /// Grids (nx, ny) and the part (w, rows) of them a convolution reads and writes:
    /// odd and even widths (the self-conjugate columns), padded and cropped.
    const PARTS: [(usize, usize, usize, usize); 4] =
        [(8, 6, 8, 6), (7, 5, 7, 5), (9, 12, 9, 12), (64, 48, 40, 30)];

    /// `x`'s rows on the part (w, rows) loaded into `f`.
    fn load<T: FftFloat>(f: &mut Fft2<T>, (w, rows): (usize, usize), x: &[f64]) {
        f.load_rows((w, rows), x.par_chunks(w * ROWS_PER_CHUNK), copy_in);
    }

    fn naive_dft(x: &[f64], nx: usize, ny: usize, kx: usize, ky: usize) -> Complex64 {
        let mut s = Complex64::default();
        for j in 0..ny {
            for i in 0..nx {
                let ph = -2.0
                    * std::f64::consts::PI
                    * ((kx * i) as f64 / nx as f64 + (ky * j) as f64 / ny as f64);
                s += Complex64::from_polar(x[j * nx + i], ph);
            }
        }
        s
    }

    #[test]
    fn matches_naive_dft_and_round_trips() {
        for &(nx, ny) in &[(8usize, 6usize), (7, 5), (16, 16), (9, 12)] {
            let x = ramp(nx * ny);
            let mut f = Fft2::new(nx, ny);
            let mut spec = vec![Complex64::default(); f.spectrum_len()];
            f.forward(&x, &mut spec);
            for kx in 0..f.nc() {
                for ky in 0..ny {
                    let d = naive_dft(&x, nx, ny, kx, ky);
                    assert!(
                        (spec[kx * ny + ky] - d).norm() < 1e-12,
                        "{nx}x{ny} ({kx},{ky})"
                    );
                }
            }
            let mut back = vec![0.0; nx * ny];
            f.inverse(&mut spec, &mut back);
            for (a, b) in x.iter().zip(&back) {
                assert!((a - b).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn convolution_equals_its_three_steps_bit_for_bit() {
        // Odd and even sizes, padded and cropped; at ny = 2048 the 33 columns fall in
        // five blocks of the column pass.
        for &(nx, ny, w, rows) in &[
            (8usize, 6usize, 8usize, 6usize),
            (7, 5, 4, 3),
            (64, 2048, 40, 1500),
        ] {
            let x = ramp(w * rows);
            let mut f = Fft2::new(nx, ny);
            let real: Vec<f64> = steps(f.spectrum_len());
            let complex: Vec<Complex64> =
                real.iter().map(|&v| Complex64::new(v, 0.5 - v)).collect();
            let mut spec = vec![Complex64::default(); f.spectrum_len()];
            let mut expected = vec![0.0; w * rows];
            f.forward_padded(&x, w, rows, &mut spec);
            spec.iter_mut().zip(&real).for_each(|(s, k)| *s *= k);
            f.inverse_cropped(&mut spec, &mut expected, w, rows);
            let mut got = vec![1.0; w * rows];
            f.convolve(&x, (w, rows), &real, &mut got);
            assert_eq!(got, expected, "{nx}x{ny}");
            let mut in_place = x.clone();
            f.convolve_in_place(&mut in_place, (w, rows), &real);
            assert_eq!(in_place, expected, "{nx}x{ny} in place");
            f.forward_padded(&x, w, rows, &mut spec);
            spec.iter_mut().zip(&complex).for_each(|(s, k)| *s *= k);
            f.inverse_cropped(&mut spec, &mut expected, w, rows);
            f.convolve(&x, (w, rows), &complex, &mut got);
            assert_eq!(got, expected, "{nx}x{ny} complex");
        }
    }

    #[test]
    fn zero_rows_and_unwanted_rows() {
        // Zero rows (either sign, a whole chunk of them among them) are not transformed:
        // the spectrum still matches the naive DFT. Rows left out of the output (a whole
        // chunk among them) leave the wanted ones the same bit for bit.
        let (nx, ny) = (24, 40);
        let zero = |r: usize| matches!(r, 3 | 4 | 5 | 16..=31 | 39);
        let mut x = ramp(nx * ny);
        for (r, row) in x.chunks_mut(nx).enumerate() {
            if zero(r) {
                row.fill(if r == 5 { -0.0 } else { 0.0 });
            }
        }
        let mut f = Fft2::new(nx, ny);
        let mut spec = vec![Complex64::default(); f.spectrum_len()];
        // A transform without zero rows first leaves no zeros behind.
        f.forward(&ramp(nx * ny), &mut spec);
        f.forward(&x, &mut spec);
        for kx in 0..f.nc() {
            for ky in 0..ny {
                let d = naive_dft(&x, nx, ny, kx, ky);
                assert!((spec[kx * ny + ky] - d).norm() < 1e-12, "({kx},{ky})");
            }
        }
        let symbol = steps(f.spectrum_len());
        let mut all = vec![0.0; nx * ny];
        f.convolve(&x, (nx, ny), &symbol, &mut all);
        let wanted: Vec<bool> = (0..ny)
            .map(|r| r % 3 != 1 && !(14..34).contains(&r))
            .collect();
        let chunk = nx * ROW_CHUNK;
        let mut got = vec![f64::NAN; nx * ny];
        f.load_rows((nx, ny), x.par_chunks(chunk), copy_in);
        f.convolve_columns(&symbol);
        f.store_some_rows(got.par_chunks_mut(chunk), copy_out, Some(&wanted));
        for r in (0..ny).filter(|&r| wanted[r]) {
            assert_eq!(
                got[r * nx..(r + 1) * nx],
                all[r * nx..(r + 1) * nx],
                "row {r}"
            );
        }
    }

    #[test]
    fn spectra_in_the_work_buffer_match_the_plain_transforms() {
        // spectrum_of_even (rows written by a closure, half of them) against forward of
        // the same grid (even in y; with zero rows), and inverse_of_real against
        // inverse of the symbol as complex values: bit for bit; a convolution after
        // each still matches a fresh transform's. Even and odd row counts.
        for &(nx, ny) in &[(8usize, 6usize), (7, 5), (40, 36), (6, 9)] {
            let x = ramp(nx * ny);
            let mut f = Fft2::<f64>::new(nx, ny);
            let mut want = vec![Complex64::default(); f.spectrum_len()];
            // A grid even in y: row j equal to row ny - j.
            let even: Vec<f64> = (0..nx * ny)
                .map(|k| x[(k % nx) + ((ny - k / nx) % ny).min(k / nx) * nx])
                .collect();
            f.forward(&even, &mut want);
            let got = f.spectrum_of_even(|j, row| row.copy_from_slice(&even[j * nx..(j + 1) * nx]));
            assert_eq!(got, &want[..], "{nx}x{ny}");
            // A zero row among them keeps its flag (the mirror of row 1 is row ny - 1).
            let holed: Vec<f64> = (0..nx * ny)
                .map(|k| {
                    if k / nx == 1 || k / nx == ny - 1 {
                        0.0
                    } else {
                        even[k]
                    }
                })
                .collect();
            f.forward(&holed, &mut want);
            let got =
                f.spectrum_of_even(|j, row| row.copy_from_slice(&holed[j * nx..(j + 1) * nx]));
            assert_eq!(got, &want[..], "{nx}x{ny} with zero rows");
            let symbol = steps(f.spectrum_len());
            let mut spec: Vec<Complex64> = symbol.iter().map(|&s| Complex64::new(s, 0.0)).collect();
            let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
            f.inverse(&mut spec, &mut a);
            f.inverse_of_real(&symbol, &mut b);
            assert_eq!(a, b, "{nx}x{ny}");
            let mut fresh = Fft2::<f64>::new(nx, ny);
            fresh.convolve(&x, (nx, ny), &symbol, &mut a);
            f.convolve(&x, (nx, ny), &symbol, &mut b);
            assert_eq!(a, b, "{nx}x{ny} convolution");
        }
    }

    #[test]
    fn column_step_gives_the_energy_and_the_same_convolution() {
        // <x, s * x> from the spectrum against the direct sum over the grid (odd and
        // even widths: the self-conjugate columns; padded and cropped), and the two
        // steps' rows against convolve bit for bit; in both precisions.
        for (nx, ny, w, rows) in PARTS {
            let x = ramp(w * rows);
            let mut f = Fft2::<f64>::new(nx, ny);
            let symbol: Vec<f64> = steps(f.spectrum_len());
            let mut expected = vec![0.0; w * rows];
            f.convolve(&x, (w, rows), &symbol, &mut expected);
            let direct: f64 = x.iter().zip(&expected).map(|(a, b)| a * b).sum();
            load(&mut f, (w, rows), &x);
            let energy = f.transform_columns(&symbol);
            let mut got = vec![0.0; w * rows];
            f.store_rows(got.par_chunks_mut(w * ROWS_PER_CHUNK), copy_out);
            assert_eq!(got, expected, "{nx}x{ny}");
            assert!(
                (energy - direct).abs() <= 1e-13 * direct.abs(),
                "{nx}x{ny}: {energy} vs {direct}"
            );
            let mut single = Fft2::<f32>::new(nx, ny);
            let symbol32: Vec<f32> = symbol.iter().map(|&v| v as f32).collect();
            load(&mut single, (w, rows), &x);
            let energy32 = single.transform_columns(&symbol32);
            assert!(
                (energy32 - direct).abs() <= 1e-6 * direct.abs(),
                "{nx}x{ny} f32: {energy32} vs {direct}"
            );
            // The energy alone: the same number bit for bit, and the transform is
            // ready for the next convolution.
            load(&mut f, (w, rows), &x);
            assert_eq!(f.column_energy(&symbol).to_bits(), energy.to_bits());
            load(&mut single, (w, rows), &x);
            assert_eq!(
                single.column_energy(&symbol32).to_bits(),
                energy32.to_bits()
            );
            f.convolve(&x, (w, rows), &symbol, &mut got);
            assert_eq!(got, expected, "{nx}x{ny} after the energy alone");
        }
    }

    #[test]
    fn a_symbol_even_in_ky_stored_by_half_gives_the_same_bits() {
        // A symbol of |ky| (and kx): even bit for bit, halved; one that is not even
        // stays full. Convolutions, energies and the real-space table of the halved
        // symbol equal the full symbol's bit for bit, in both precisions, odd and even
        // sizes, padded and cropped.
        for (nx, ny, w, rows) in PARTS {
            let nc = nx / 2 + 1;
            let full = even_in_ky(nc, ny);
            let half = halve_if_even(full.clone(), ny);
            assert_eq!(half.len(), nc * even_rows(ny), "{nx}x{ny}");
            assert_eq!(full_symbol(&half, nc, ny), full);
            let mut odd = full.clone();
            odd[1] += 1.0;
            assert_eq!(halve_if_even(odd.clone(), ny), odd, "not even: kept");
            let x = ramp(w * rows);
            let mut f = Fft2::<f64>::new(nx, ny);
            let (mut a, mut b) = (vec![0.0; w * rows], vec![0.0; w * rows]);
            f.convolve(&x, (w, rows), &full, &mut a);
            f.convolve(&x, (w, rows), &half, &mut b);
            assert_eq!(a, b, "{nx}x{ny}");
            load(&mut f, (w, rows), &x);
            let e_full = f.column_energy(&full);
            load(&mut f, (w, rows), &x);
            assert_eq!(f.column_energy(&half).to_bits(), e_full.to_bits());
            let mut single = Fft2::<f32>::new(nx, ny);
            let full32: Vec<f32> = full.iter().map(|&v| v as f32).collect();
            let half32: Vec<f32> = half.iter().map(|&v| v as f32).collect();
            single.convolve(&x, (w, rows), &full32, &mut a);
            single.convolve(&x, (w, rows), &half32, &mut b);
            assert_eq!(a, b, "{nx}x{ny} f32");
            let (mut ta, mut tb) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
            f.inverse_of_real(&full, &mut ta);
            f.inverse_of_real(&half, &mut tb);
            assert_eq!(ta, tb, "{nx}x{ny} table");
        }
    }

    #[test]
    fn hosted_spectra_give_the_convolution_bit_for_bit() {
        // The output grid holding the row spectra against the transform's own buffer:
        // even row lengths from 2 up, odd and even column lengths, zero rows, a last
        // column block holding the Nyquist column alone (8 x 8192: two columns per
        // block, five columns), complex, full and halved real symbols; the output's
        // previous contents do not matter, and a lent-out row buffer is not needed.
        for &(nx, ny) in &[(2usize, 3usize), (8, 6), (10, 7), (64, 48), (8, 8192)] {
            let nc = nx / 2 + 1;
            let real = even_in_ky(nc, ny);
            let halved = halve_if_even(real.clone(), ny);
            let complex: Vec<Complex64> = (0..nc * ny)
                .map(|b| Complex64::new(1.0 + (b % 5) as f64, (b % 3) as f64 - 1.0))
                .collect();
            let mut x = ramp(nx * ny);
            // Rows 1 and the last but one zero: not transformed either way.
            x[nx..2 * nx].fill(0.0);
            let last = ny.saturating_sub(2) * nx;
            x[last..last + nx].fill(0.0);
            let mut own = Fft2::<f64>::new(nx, ny);
            let mut hosting = Fft2::<f64>::without_rows(nx, ny);
            let (mut a, mut b) = (vec![0.0; nx * ny], steps(nx * ny));
            own.convolve(&x, (nx, ny), &real, &mut a);
            hosting.convolve_hosted(&x, &real, &mut b);
            assert_eq!(a, b, "{nx}x{ny} real");
            own.convolve(&x, (nx, ny), &halved, &mut a);
            hosting.convolve_hosted(&x, &halved, &mut b);
            assert_eq!(a, b, "{nx}x{ny} halved");
            own.convolve(&x, (nx, ny), &complex, &mut a);
            hosting.convolve_hosted(&x, &complex, &mut b);
            assert_eq!(a, b, "{nx}x{ny} complex");
            assert!(a.iter().any(|&v| v != 0.0));
            // One thread and three: the same bits.
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut c = steps(nx * ny);
                pool.install(|| hosting.convolve_hosted(&x, &complex, &mut c));
                assert_eq!(a, c, "{nx}x{ny} on {threads} threads");
            }
        }
    }

    #[test]
    fn single_precision_convolution_matches_double_to_its_rounding() {
        // Padded and cropped too; the f32 result within a few f32 ulps of the output's
        // scale (|symbol| <= 13, inputs O(1)).
        for &(nx, ny, w, rows) in &[(16usize, 12usize, 16usize, 12usize), (64, 48, 40, 30)] {
            let x = ramp(w * rows);
            let mut double = Fft2::<f64>::new(nx, ny);
            let mut single = Fft2::<f32>::new(nx, ny);
            let symbol: Vec<f64> = steps(double.spectrum_len());
            let symbol32: Vec<f32> = symbol.iter().map(|&v| v as f32).collect();
            let (mut a, mut b) = (vec![0.0; w * rows], vec![0.0; w * rows]);
            double.convolve(&x, (w, rows), &symbol, &mut a);
            single.convolve(&x, (w, rows), &symbol32, &mut b);
            let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let diff = a
                .iter()
                .zip(&b)
                .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
            assert!(
                diff <= 1e-6 * scale && diff > 0.0,
                "{nx}x{ny}: {diff:e} of {scale:e}"
            );
        }
    }

    #[test]
    fn padded_and_cropped_transforms_match_full_ones() {
        let (nx, ny, w, rows) = (12usize, 10usize, 5usize, 4usize);
        let small: Vec<f64> = (0..w * rows).map(|k| (k * 31 % 17) as f64 - 8.0).collect();
        let mut full = vec![0.0; nx * ny];
        for j in 0..rows {
            full[j * nx..j * nx + w].copy_from_slice(&small[j * w..(j + 1) * w]);
        }
        let mut f = Fft2::new(nx, ny);
        let (mut s1, mut s2) = (
            vec![Complex64::default(); f.spectrum_len()],
            vec![Complex64::default(); f.spectrum_len()],
        );
        f.forward(&full, &mut s1);
        // Stale values in the buffers must not leak into a padded transform.
        f.forward_padded(&small, w, rows, &mut s2);
        assert_eq!(s1, s2);
        let mut back = vec![0.0; w * rows];
        f.inverse_cropped(&mut s2, &mut back, w, rows);
        for (a, b) in small.iter().zip(&back) {
            assert!((a - b).abs() < 1e-13, "{a} vs {b}");
        }
    }
}
