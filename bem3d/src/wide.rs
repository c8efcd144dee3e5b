//! The loops whose speed depends on the processor's vector width, compiled for the
//! baseline x86-64 target (SSE2) and again with AVX2 and with AVX-512, the variant
//! chosen once at run time from the processor's features. A binary or wheel built here
//! therefore runs on any x86-64 processor. Every variant performs the same operations in
//! the same order (the compiler never fuses a multiply and an add, nor reorders
//! floating-point sums, on its own), so the results are bit-identical whatever the
//! processor: `bem3d/tests/wide.rs` checks each variant the processor has against the
//! baseline one.
//!
//! Only the dense products of the candidate-set path and the direct point-load sums need
//! it: the transforms choose their own instructions at run time (rustfft), and the
//! solver's sweeps are limited by memory, not by arithmetic (measured: the periodic
//! benchmark solves take the same time built for the baseline as built for this machine's
//! AVX-512; the 1024^2 candidate-set solve 10 % longer without these variants).

use std::sync::OnceLock;

/// The widest set of vector instructions this processor has, among those compiled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Width {
    Baseline,
    Avx2,
    Avx512,
}

/// The variant the loops run, detected once.
pub fn width() -> Width {
    static WIDTH: OnceLock<Width> = OnceLock::new();
    *WIDTH.get_or_init(|| {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f") {
                return Width::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return Width::Avx2;
            }
        }
        Width::Baseline
    })
}

/// Whether this processor can run the variant `w`.
pub fn available(w: Width) -> bool {
    matches!(
        (w, width()),
        (Width::Baseline, _) | (_, Width::Avx512) | (Width::Avx2, Width::Avx2)
    )
}

/// `sum_k a[k] b[k]` in eight interleaved partial sums (k mod 8), added in order, then
/// the tail: the dense products' row sums.
pub fn dot<T: Copy + Into<f64>>(a: &[T], b: &[f64]) -> f64 {
    dot_with(width(), a, b)
}

/// [`dot`] by the variant `w` (which the processor must have: [`available`]; the
/// baseline otherwise).
pub fn dot_with<T: Copy + Into<f64>>(w: Width, a: &[T], b: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if available(w) {
        // SAFETY: the processor has the variant's features (checked just above).
        match w {
            Width::Avx512 => return unsafe { x86::dot_avx512(a, b) },
            Width::Avx2 => return unsafe { x86::dot_avx2(a, b) },
            Width::Baseline => {}
        }
    }
    let _ = w;
    dot_plain(a, b)
}

/// `u[k] += v g[k]`: a point load's row of displacements added.
pub fn add_scaled(u: &mut [f64], v: f64, g: &[f64]) {
    add_scaled_with(width(), u, v, g)
}

/// [`add_scaled`] by the variant `w` (as [`dot_with`]).
pub fn add_scaled_with(w: Width, u: &mut [f64], v: f64, g: &[f64]) {
    #[cfg(target_arch = "x86_64")]
    if available(w) {
        // SAFETY: as in dot_with.
        match w {
            Width::Avx512 => return unsafe { x86::add_scaled_avx512(u, v, g) },
            Width::Avx2 => return unsafe { x86::add_scaled_avx2(u, v, g) },
            Width::Baseline => {}
        }
    }
    let _ = w;
    add_scaled_plain(u, v, g)
}

/// `u[k] += v g[len - 1 - k]`: a mirrored stretch of a point load's row.
pub fn add_scaled_reversed(u: &mut [f64], v: f64, g: &[f64]) {
    add_scaled_reversed_with(width(), u, v, g)
}

/// [`add_scaled_reversed`] by the variant `w` (as [`dot_with`]).
pub fn add_scaled_reversed_with(w: Width, u: &mut [f64], v: f64, g: &[f64]) {
    #[cfg(target_arch = "x86_64")]
    if available(w) {
        // SAFETY: as in dot_with.
        match w {
            Width::Avx512 => return unsafe { x86::add_scaled_reversed_avx512(u, v, g) },
            Width::Avx2 => return unsafe { x86::add_scaled_reversed_avx2(u, v, g) },
            Width::Baseline => {}
        }
    }
    let _ = w;
    add_scaled_reversed_plain(u, v, g)
}

#[inline(always)]
fn add_scaled_reversed_plain(u: &mut [f64], v: f64, g: &[f64]) {
    for (a, g) in u.iter_mut().zip(g.iter().rev()) {
        *a += v * g;
    }
}

#[inline(always)]
fn dot_plain<T: Copy + Into<f64>>(a: &[T], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(&x, y)| x.into() * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k].into() * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

#[inline(always)]
fn add_scaled_plain(u: &mut [f64], v: f64, g: &[f64]) {
    for (a, g) in u.iter_mut().zip(g) {
        *a += v * g;
    }
}

/// The same bodies compiled with wider instructions (inlined into each).
#[cfg(target_arch = "x86_64")]
mod x86 {
    #[target_feature(enable = "avx2")]
    pub(super) fn dot_avx2<T: Copy + Into<f64>>(a: &[T], b: &[f64]) -> f64 {
        super::dot_plain(a, b)
    }
    #[target_feature(enable = "avx512f")]
    pub(super) fn dot_avx512<T: Copy + Into<f64>>(a: &[T], b: &[f64]) -> f64 {
        super::dot_plain(a, b)
    }
    #[target_feature(enable = "avx2")]
    pub(super) fn add_scaled_avx2(u: &mut [f64], v: f64, g: &[f64]) {
        super::add_scaled_plain(u, v, g)
    }
    #[target_feature(enable = "avx512f")]
    pub(super) fn add_scaled_avx512(u: &mut [f64], v: f64, g: &[f64]) {
        super::add_scaled_plain(u, v, g)
    }
    #[target_feature(enable = "avx2")]
    pub(super) fn add_scaled_reversed_avx2(u: &mut [f64], v: f64, g: &[f64]) {
        super::add_scaled_reversed_plain(u, v, g)
    }
    #[target_feature(enable = "avx512f")]
    pub(super) fn add_scaled_reversed_avx512(u: &mut [f64], v: f64, g: &[f64]) {
        super::add_scaled_reversed_plain(u, v, g)
    }
}
