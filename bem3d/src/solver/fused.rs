//! The plumbing of the iteration's sweeps: deterministic chunked reductions, a scratch
//! buffer per thread, and operator applications fused with the sweeps that produce
//! their input or consume their output (the transforms' row passes,
//! [`Fft2::load_rows`](crate::fft::Fft2::load_rows)); an operator without a spectral
//! form goes through a plain buffer (`fallback`) with the same chunks and sums.

use crate::fft::ROWS_PER_CHUNK;
use crate::operator::GridOperator;
use crate::operator::{Operand, Transform};
use rayon::prelude::*;

thread_local! {
    /// A chunk's worth of values for passes that need a buffer only while they run.
    static SCRATCH: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// `f` on this thread's scratch buffer, `len` values long (their contents left from
/// earlier use: `f` writes before it reads).
pub(super) fn with_scratch<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        if s.len() < len {
            s.resize(len, 0.0);
        }
        f(&mut s[..len])
    })
}

/// Maps each chunk with `f` (in parallel) and sums the `N` partial results with
/// [`sum_parts`].
pub(super) fn reduce<const N: usize, I, F>(iter: I, f: F, max_slot: Option<usize>) -> [f64; N]
where
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item) -> [f64; N] + Sync + Send,
{
    let parts: Vec<[f64; N]> = iter.into_par_iter().map(f).collect();
    sum_parts(&parts, max_slot)
}

pub(super) fn combine<const N: usize>(acc: &mut [f64; N], p: &[f64; N], max_slot: Option<usize>) {
    for k in 0..N {
        if Some(k) == max_slot {
            acc[k] = acc[k].max(p[k]);
        } else {
            acc[k] += p[k];
        }
    }
}

/// Sums per-chunk partial results in chunk order (deterministic for any thread count);
/// `max_slot` combines that entry by max instead of sum.
pub(super) fn sum_parts<const N: usize>(parts: &[[f64; N]], max_slot: Option<usize>) -> [f64; N] {
    let mut acc = [0.0f64; N];
    for p in parts {
        combine(&mut acc, p, max_slot);
    }
    acc
}

/// First half of a fused application of K or M
/// ([`Fft2::load_rows`](crate::fft::Fft2::load_rows)): `load(item, values)` produces
/// the input a chunk of [`ROWS_PER_CHUNK`] rows at a time from the caller's items.
/// Operators without a spectral form collect the input in `fallback` instead (same
/// chunks, same sums).
pub(super) fn load_fused<K, I, F, const A: usize>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    items: I,
    load: F,
) -> Vec<[f64; A]>
where
    K: GridOperator,
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item, &mut [f64]) -> [f64; A] + Sync,
{
    let (n, chunk) = (op.cells(), ROWS_PER_CHUNK * op.nx());
    if let Some(s) = op.spectral(which) {
        return match s.transform {
            Transform::Double(fft, _) => fft.load_rows(s.dims, items, load),
            Transform::Single(fft, _) => fft.load_rows(s.dims, items, load),
        };
    }
    fallback[0].resize(n, 0.0);
    fallback[0]
        .par_chunks_mut(chunk)
        .zip(items)
        .map(|(values, item)| load(item, values))
        .collect()
}

/// The second half's first step: the operator applied to the loaded input x (the
/// transforms' column pass,
/// [`Fft2::convolve_columns`](crate::fft::Fft2::convolve_columns); an operator without
/// a spectral form applies itself into `fallback`). With `energy` (K only), returns
/// `<x, K x>` (Parseval,
/// [`Fft2::transform_columns`](crate::fft::Fft2::transform_columns); the fallback sums
/// in a fixed order) for a caller that needs it before the rows, else 0; the rows
/// follow with [`store_fused`].
pub(super) fn apply_fused<K: GridOperator>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    energy: bool,
) -> f64 {
    debug_assert!(!energy || which != Operand::Preconditioner);
    if let Some(s) = op.spectral(which) {
        return match (s.transform, energy) {
            (Transform::Double(fft, symbol), true) => fft.transform_columns(symbol),
            (Transform::Single(fft, symbol), true) => fft.transform_columns(symbol),
            (Transform::Double(fft, symbol), false) => {
                fft.convolve_columns(symbol);
                0.0
            }
            (Transform::Single(fft, symbol), false) => {
                fft.convolve_columns(symbol);
                0.0
            }
        };
    }
    let n = op.cells();
    let [input, output] = fallback;
    match which {
        Operand::Compliance => {
            output.resize(n, 0.0);
            op.apply(input, output);
        }
        Operand::ComplianceSingle => {
            output.resize(n, 0.0);
            op.apply_single(input, output);
        }
        Operand::Preconditioner => {
            op.precondition(input);
            std::mem::swap(input, output);
        }
    }
    if energy {
        input.iter().zip(output.iter()).map(|(a, b)| a * b).sum()
    } else {
        0.0
    }
}

/// `<x, K x>` of the loaded input x alone, as [`apply_fused`] with `energy` returns it
/// (bit for bit, [`Fft2::column_energy`](crate::fft::Fft2::column_energy)), without K x:
/// no rows follow.
pub(super) fn energy_fused<K: GridOperator>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
) -> f64 {
    debug_assert!(which != Operand::Preconditioner);
    if let Some(s) = op.spectral(which) {
        return match s.transform {
            Transform::Double(fft, symbol) => fft.column_energy(symbol),
            Transform::Single(fft, symbol) => fft.column_energy(symbol),
        };
    }
    apply_fused(op, which, fallback, true)
}

/// The second half's second step (after [`apply_fused`]): the result handed to
/// `store(item, values)` a chunk at a time.
pub(super) fn store_fused<K, I, F, const B: usize>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    items: I,
    store: F,
    wanted: Option<&[bool]>,
) -> Vec<[f64; B]>
where
    K: GridOperator,
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
{
    let chunk = ROWS_PER_CHUNK * op.nx();
    if let Some(s) = op.spectral(which) {
        return match s.transform {
            Transform::Double(fft, _) => fft.store_some_rows(items, store, wanted),
            Transform::Single(fft, _) => fft.store_some_rows(items, store, wanted),
        };
    }
    fallback[1]
        .par_chunks(chunk)
        .zip(items)
        .map(|(values, item)| store(item, values))
        .collect()
}
