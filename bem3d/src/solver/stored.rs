//! How the iteration's direction vectors (`t` and `y_prev`) are stored: in single
//! precision, or, on memory-lean grids, as 16-bit integers times one power-of-two scale
//! per row chunk of the sweeps (solver module docs, "Scaled directions").
//!
//! A scaled chunk's scale is chosen from the largest magnitude the chunk is about to
//! hold, so that it maps to at most 2^14: every value keeps 13 bits or more relative to
//! its chunk's largest. A power of two makes scaling exact: the only rounding is to the
//! integer, and what the iteration reads back (`get`) is what it uses everywhere (K's
//! input, the update, the sums), as with single precision.

use rayon::prelude::*;

/// A stored value of a direction vector.
pub(super) trait Cell: Copy + Default + Send + Sync + 'static {
    /// Whether a chunk's values carry a scale chosen before they are written.
    const SCALED: bool;
    /// The value of a stored cell in a chunk of scale `scale`.
    fn get(self, scale: f64) -> f64;
    /// `v` stored in a chunk of scale `1 / inv_scale`.
    fn put(v: f64, inv_scale: f64) -> Self;
}

impl Cell for f32 {
    const SCALED: bool = false;
    #[inline(always)]
    fn get(self, _: f64) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn put(v: f64, _: f64) -> Self {
        v as f32
    }
}

impl Cell for i16 {
    const SCALED: bool = true;
    #[inline(always)]
    fn get(self, scale: f64) -> f64 {
        self as f64 * scale
    }
    #[inline(always)]
    fn put(v: f64, inv_scale: f64) -> Self {
        // Rounded to the nearest integer, ties to even, by adding and removing 1.5 x
        // 2^52 (exact for magnitudes below 2^51; plain arithmetic, so it vectorizes where
        // `round_ties_even` is a library call). Within the range by the choice of the
        // scale (`as` saturates regardless; NaN gives 0, the scale keeps it visible).
        const SHIFT: f64 = 6755399441055744.0;
        ((v * inv_scale + SHIFT) - SHIFT) as i32 as i16
    }
}

/// Largest stored magnitude of a scaled chunk: 2^14 (a power of two below `i16::MAX`,
/// so a chunk's largest value, rounded, stays in range).
const SCALED_MAX: f64 = 16384.0;

/// The power-of-two scale of a chunk whose largest magnitude is `max`: `max / scale` in
/// (2^13, 2^14]. 1 for an empty or all-zero chunk; NaN for a non-finite `max` (the
/// chunk then reads back NaN, so a breakdown stays visible).
pub(super) fn scale_for(max: f64) -> f64 {
    if max == 0.0 {
        return 1.0;
    }
    if !max.is_finite() {
        return f64::NAN;
    }
    // The smallest power of two >= max / 2^14 (exact: powers of two in range).
    let mut scale = 2f64.powi((max / SCALED_MAX).log2().ceil() as i32);
    // log2 rounds: settle the boundary exactly.
    while max / scale > SCALED_MAX {
        scale *= 2.0;
    }
    while scale > f64::MIN_POSITIVE && max / (scale / 2.0) <= SCALED_MAX {
        scale /= 2.0;
    }
    scale
}

/// A direction vector: its cells in chunks of `chunk` cells (the sweeps' row chunks),
/// each chunk with its scale (1 for single precision).
pub(super) struct Stored<C: Cell> {
    values: Vec<C>,
    scales: Vec<f64>,
    chunk: usize,
}

impl<C: Cell> Stored<C> {
    /// `n` zero cells in chunks of `chunk`.
    pub(super) fn zeros(n: usize, chunk: usize) -> Self {
        Self {
            values: vec![C::default(); n],
            scales: vec![1.0; n.div_ceil(chunk.max(1))],
            chunk: chunk.max(1),
        }
    }

    /// Every cell zero, every scale 1, written in parallel (each page of a fresh buffer
    /// gets its own frame now, not on a later first write: solver `begin`).
    pub(super) fn clear(&mut self) {
        self.values.par_iter_mut().for_each(|v| *v = C::default());
        self.scales.fill(1.0);
    }

    /// The chunks with their scales, for reading.
    pub(super) fn chunks(&self) -> impl IndexedParallelIterator<Item = (&[C], f64)> {
        let scales = self.scales.par_iter().copied();
        self.values.par_chunks(self.chunk).zip(scales)
    }

    /// The chunks with their scales, for writing.
    pub(super) fn chunks_mut(
        &mut self,
    ) -> impl IndexedParallelIterator<Item = (&mut [C], &mut f64)> {
        let scales = self.scales.par_iter_mut();
        self.values.par_chunks_mut(self.chunk).zip(scales)
    }
}

/// The pair of direction vectors in one of the two storages.
pub(super) enum Directions {
    /// Single precision (4 + 4 bytes per cell).
    Single { t: Stored<f32>, y: Stored<f32> },
    /// 16-bit integers scaled per chunk (2 + 2 bytes per cell).
    Scaled { t: Stored<i16>, y: Stored<i16> },
}

impl Directions {
    /// Zero vectors of `n` cells in chunks of `chunk`, scaled or not.
    pub(super) fn zeros(n: usize, chunk: usize, scaled: bool) -> Self {
        if scaled {
            Directions::Scaled {
                t: Stored::zeros(n, chunk),
                y: Stored::zeros(n, chunk),
            }
        } else {
            Directions::Single {
                t: Stored::zeros(n, chunk),
                y: Stored::zeros(n, chunk),
            }
        }
    }

    pub(super) fn scaled(&self) -> bool {
        matches!(self, Directions::Scaled { .. })
    }

    /// Zero vectors in the storage asked for: the same buffers cleared, or the other
    /// storage's (the old one released first).
    pub(super) fn reset(&mut self, n: usize, chunk: usize, scaled: bool) {
        if self.scaled() != scaled {
            *self = Directions::zeros(0, chunk, false);
            *self = Directions::zeros(n, chunk, scaled);
        }
        match self {
            Directions::Single { t, y } => {
                t.clear();
                y.clear();
            }
            Directions::Scaled { t, y } => {
                t.clear();
                y.clear();
            }
        }
    }
}

/// Runs `$body` with `$t` and `$y` bound to the direction vectors of `$dirs` (a
/// `&Directions` or `&mut Directions`), compiled once per storage.
macro_rules! with_directions {
    ($dirs:expr, |$t:ident, $y:ident| $body:expr) => {
        match $dirs {
            $crate::solver::stored::Directions::Single { t: $t, y: $y } => $body,
            $crate::solver::stored::Directions::Scaled { t: $t, y: $y } => $body,
        }
    };
}
pub(super) use with_directions;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scale_maps_the_largest_magnitude_into_the_top_binade_exactly() {
        for max in [1e-300, 3e-9, 0.1, 1.0, 16384.0, 16385.0, 2.5e7, 1e300] {
            let s = scale_for(max);
            assert_eq!(s.log2().fract(), 0.0, "{max}: {s} not a power of two");
            let top = max / s;
            assert!(top > 8192.0 && top <= 16384.0, "{max}: {top}");
            // Stored and read back: within half a unit, and in range.
            let q = i16::put(max, 1.0 / s);
            assert!((q.get(s) - max).abs() <= 0.5 * s && q > 0, "{max}: {q}");
            assert_eq!(i16::put(-max, 1.0 / s), -q);
        }
        assert_eq!(scale_for(0.0), 1.0);
        assert!(scale_for(f64::INFINITY).is_nan() && scale_for(f64::NAN).is_nan());
        assert!(i16::put(1.0, 1.0 / f64::NAN).get(f64::NAN).is_nan());
    }

    #[test]
    fn single_precision_cells_ignore_the_scale() {
        for v in [0.1f64, -3.7e-12, 1e30] {
            assert_eq!(f32::put(v, 0.25).get(8.0), v as f32 as f64);
        }
    }
}
