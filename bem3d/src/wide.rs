//! The loops whose speed depends on the processor's vector width, compiled for the
//! baseline x86-64 target (SSE2) and again with AVX2 and with AVX-512, the variant
//! chosen once at run time from the processor's features. A binary or wheel built here
//! therefore runs on any x86-64 processor. Every variant performs the same operations in
//! the same order (the compiler never fuses a multiply and an add, nor reorders
//! floating-point sums, on its own), so the results are bit-identical whatever the
//! processor: `bem3d/tests/suite/wide.rs` checks each variant the processor has against the
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

/// A loop `plain` as two public functions, `name` by the variant of this processor
/// ([`width`]) and `with` by a given variant (which the processor must have:
/// [`available`]; the baseline otherwise), and the variants `name::avx2` and
/// `name::avx512` (the same body compiled with wider instructions, inlined into each).
macro_rules! by_width {
    ($(#[$doc:meta])* $name:ident, $with:ident => $plain:ident
     [$($gen:tt)*] ($($arg:ident: $ty:ty),*) $(-> $ret:ty)?) => {
        $(#[$doc])*
        pub fn $name<$($gen)*>($($arg: $ty),*) $(-> $ret)? {
            $with(width(), $($arg),*)
        }

        #[doc = concat!("[`", stringify!($name), "`] by the variant `w`.")]
        pub fn $with<$($gen)*>(w: Width, $($arg: $ty),*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            if available(w) {
                // SAFETY: the processor has the variant's features (checked just above).
                match w {
                    Width::Avx512 => return unsafe { $name::avx512($($arg),*) },
                    Width::Avx2 => return unsafe { $name::avx2($($arg),*) },
                    Width::Baseline => {}
                }
            }
            let _ = w;
            $plain($($arg),*)
        }

        #[cfg(target_arch = "x86_64")]
        mod $name {
            use super::*;
            #[target_feature(enable = "avx2")]
            pub(super) fn avx2<$($gen)*>($($arg: $ty),*) $(-> $ret)? {
                $plain($($arg),*)
            }
            #[target_feature(enable = "avx512f")]
            pub(super) fn avx512<$($gen)*>($($arg: $ty),*) $(-> $ret)? {
                $plain($($arg),*)
            }
        }
    };
}

by_width! {
    /// `sum_k a[k] b[k]` in eight interleaved partial sums (k mod 8), added in order, then
    /// the tail: the dense products' row sums.
    dot, dot_with => dot_plain
    [T: Copy + Into<f64>] (a: &[T], b: &[f64]) -> f64
}

by_width! {
    /// `u[k] += v g[k]`: a point load's row of displacements added.
    add_scaled, add_scaled_with => add_scaled_plain
    [] (u: &mut [f64], v: f64, g: &[f64])
}

by_width! {
    /// `u[k] += v g[len - 1 - k]`: a mirrored stretch of a point load's row.
    add_scaled_reversed, add_scaled_reversed_with => add_scaled_reversed_plain
    [] (u: &mut [f64], v: f64, g: &[f64])
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
