//! Heights that `Contact`'s solver reads in place from numpy's memory, so that a caller
//! who keeps the array (as every user does) does not hold it twice: at 8192^2 the copy
//! would be 8 of the solve's 35 bytes per cell.
//!
//! The solver reads the buffer while the GIL is released, as numpy's own functions that
//! release it do: the array must not be written during a solve. Between solves a change
//! is caught: the bits' fingerprint taken when the `Contact` is built is checked before
//! each solve, and a changed array is refused (its statistics, and the coarse grid of a
//! nested start, were taken from the old heights).

use numpy::ndarray::ArrayView2;
use pyo3::prelude::*;

/// A C-ordered view of a numpy array's data, with the array held so that its memory
/// lives as long as the view.
pub struct PyHeights {
    /// Keeps the buffer alive (numpy refuses to resize an array others refer to).
    _owner: Py<PyAny>,
    ptr: *const f64,
    len: usize,
    fingerprint: u64,
}

// SAFETY: the pointer is into the buffer `_owner` keeps alive; the solver only reads
// it, from any thread (module docs: the caller does not write during a solve).
unsafe impl Send for PyHeights {}
unsafe impl Sync for PyHeights {}

impl PyHeights {
    /// The view's data in place when it is one C-ordered block (rows of y), else None
    /// (the caller then copies).
    pub fn of(owner: &Bound<'_, PyAny>, view: ArrayView2<'_, f64>) -> Option<Self> {
        let slice = view.as_slice()?;
        Some(Self {
            _owner: owner.clone().unbind(),
            ptr: slice.as_ptr(),
            len: slice.len(),
            fingerprint: fingerprint(slice),
        })
    }

    /// Whether the bits are those the view had when it was taken.
    pub fn unchanged(&self) -> bool {
        fingerprint(self.as_ref()) == self.fingerprint
    }
}

impl AsRef<[f64]> for PyHeights {
    fn as_ref(&self) -> &[f64] {
        // SAFETY: `ptr` and `len` describe the live, initialised buffer of `_owner`.
        unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
    }
}

/// A 64-bit fingerprint of the values' bits (FNV-1a-like over four interleaved lanes,
/// so the multiplications do not wait on each other): any changed bit changes it with
/// overwhelming probability; about 30 ms at 8192^2.
fn fingerprint(h: &[f64]) -> u64 {
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let mut lanes = [0xcbf2_9ce4_8422_2325u64, 1, 2, 3];
    let (blocks, tail) = h.as_chunks::<4>();
    for b in blocks {
        for (x, v) in lanes.iter_mut().zip(b) {
            *x = (*x ^ v.to_bits()).wrapping_mul(PRIME);
        }
    }
    for v in tail {
        lanes[0] = (lanes[0] ^ v.to_bits()).wrapping_mul(PRIME);
    }
    lanes
        .iter()
        .fold(h.len() as u64, |a, &x| (a ^ x).wrapping_mul(PRIME))
}
