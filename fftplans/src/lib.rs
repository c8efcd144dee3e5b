//! FFT plans for the workspace, compiled once.
//!
//! rustfft's and realfft's planners are generic over the float type, so a release build
//! compiles them again in every crate that calls them: every butterfly and every SIMD
//! variant, some 40 s of CPU per crate on two cores (measured by building a crate that
//! only plans). `mrd`, `bem3d`, their unit-test binaries and the benchmarks each did.
//! Here the planners are called by non-generic functions, one per float type and
//! direction, which every caller links to; a plan is a trait object whose transforms
//! already live in this crate. The algorithm a planner picks for a length does not
//! depend on the planner instance, so a plan from here is the plan the caller's own
//! planner would have made: the same transform, bit for bit (`scripts/same-outputs.sh`
//! compares every scene's CSVs across such a change).
//!
//! The crate has no tests of its own: a unit-test binary would compile the planners
//! again. The transforms are tested where they are used, against the discrete Fourier
//! sum (`bem3d::fft`'s tests) and the closed forms of `mrd`'s spectra.
use std::sync::Arc;

pub use realfft::{ComplexToReal, RealToComplex};
pub use rustfft::{Fft, FftDirection, FftNum};

/// A float type with plans compiled in this crate (f64 and f32).
pub trait Planned: FftNum {
    /// The complex transform of `len` points in `direction` (unnormalised).
    fn complex(len: usize, direction: FftDirection) -> Arc<dyn Fft<Self>>;
    /// The forward real-to-complex transform of `len` real points (`len / 2 + 1` out).
    fn real_forward(len: usize) -> Arc<dyn RealToComplex<Self>>;
    /// The inverse complex-to-real transform to `len` real points (unnormalised).
    fn real_inverse(len: usize) -> Arc<dyn ComplexToReal<Self>>;
}

impl Planned for f64 {
    fn complex(len: usize, direction: FftDirection) -> Arc<dyn Fft<f64>> {
        rustfft::FftPlanner::<f64>::new().plan_fft(len, direction)
    }
    fn real_forward(len: usize) -> Arc<dyn RealToComplex<f64>> {
        realfft::RealFftPlanner::<f64>::new().plan_fft_forward(len)
    }
    fn real_inverse(len: usize) -> Arc<dyn ComplexToReal<f64>> {
        realfft::RealFftPlanner::<f64>::new().plan_fft_inverse(len)
    }
}

impl Planned for f32 {
    fn complex(len: usize, direction: FftDirection) -> Arc<dyn Fft<f32>> {
        rustfft::FftPlanner::<f32>::new().plan_fft(len, direction)
    }
    fn real_forward(len: usize) -> Arc<dyn RealToComplex<f32>> {
        realfft::RealFftPlanner::<f32>::new().plan_fft_forward(len)
    }
    fn real_inverse(len: usize) -> Arc<dyn ComplexToReal<f32>> {
        realfft::RealFftPlanner::<f32>::new().plan_fft_inverse(len)
    }
}

/// The forward complex transform of `len` points.
pub fn forward<T: Planned>(len: usize) -> Arc<dyn Fft<T>> {
    T::complex(len, FftDirection::Forward)
}

/// The inverse complex transform of `len` points (unnormalised).
pub fn inverse<T: Planned>(len: usize) -> Arc<dyn Fft<T>> {
    T::complex(len, FftDirection::Inverse)
}
