//! Solves run on a thread of rayon's pool.
//!
//! An iteration of the solvers is a dozen short parallel loops (sweeps, FFT row and
//! column passes). Started from a thread outside the pool, each loop is injected into
//! the pool and the caller sleeps until it ends: a wake-up of a pool thread and of the
//! caller per loop. Running the whole solve on a pool thread makes each loop start in
//! place. Measured on the periodic benchmark surfaces (Intel Xeon, 2-core VM): 128^2 4.2x,
//! 256^2 1.6x, 512^2 1.24x faster on one thread; 1.4x and 1.3x at 128^2 and 256^2 on two.
//! Results are bit-identical (every reduction has a fixed order whatever the thread).

/// Runs `f` on a thread of the current rayon pool (in place when already on one).
pub(crate) fn on_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| f())
}
