//! The preconditioner M in real space, truncated: its convolution kernel within
//! [`RADIUS`] cells of the centre, applied only where a small contact set needs it.
//!
//! M is a convolution (the surface stiffness `E* |k| / 2` on the grid, [`crate::operator`]);
//! its kernel decays like `1 / r^3` away from a large positive centre value. The solver
//! needs `y = M q` on the contact cells only, for a residual `q` that is zero off them.
//! On a contact set of a few per cent of the grid the sum over the kernel's nearest
//! values at the contact cells costs far less than M's two transforms (the solver's
//! `LOCAL_MAX_FRACTION`). Dropping the kernel's tail leaves the stencil's sum (its
//! symbol at k = 0) too large by minus the tail's sum (the tail is negative); half of
//! the tail's sum goes back to the centre value ([`TAIL_SHARE`]).
//!
//! Measured on the periodic benchmark surface at 512^2 and 1 % contact (nested start;
//! fine iterations, a prototype that took the kernel from M's single-precision
//! transform of a unit load): 28 with the transforms; radius 1, 2, 4, 8 without the
//! tail's share 35, 35, 33, 30; radius 3, 4, 6 with half of it 29, 28, 29 (at 1024^2:
//! 32 -> 34, 34, 33); radius 4 with all of it 31. This code (radius 4, half): 28 at
//! 512^2, 33 at 1024^2, 29 and 37 on the free half-space against 27 and 34. At 4 %
//! contact 1-6 more iterations than with the transforms (the solver's limit is 2 %).

use crate::symbol::{ColumnBuf, SymbolValue, Symbolic};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Cells of the kernel kept on each side of the centre.
pub const RADIUS: usize = 4;

/// Share of the dropped tail's sum added to the centre value (module docs).
pub const TAIL_SHARE: f64 = 0.5;

/// Values per side of the stencil.
const SIDE: usize = 2 * RADIUS + 1;

/// A convolution kernel's values within [`RADIUS`] cells (row-major, offsets
/// `-RADIUS..=RADIUS` in y then x), on a grid of `nx x ny` cells where it wraps around
/// (circular, as the transforms apply it).
#[derive(Debug, Clone)]
pub struct Stencil {
    values: [f64; SIDE * SIDE],
    nx: usize,
    ny: usize,
}

impl Stencil {
    /// The real-space kernel of the real symbol `symbol` (in the transposed layout of
    /// [`crate::fft::Fft2`]: `(nx/2 + 1) x ny`, values not normalised, as the operators
    /// store them) within [`RADIUS`] cells, the centre given [`TAIL_SHARE`] of the
    /// tail's sum. None if a side is shorter than the stencil's (it would wrap onto
    /// itself), if the symbol is not even in ky (as a function of |k| is; the kernel is
    /// then even in x and y, and cosine sums give it), or if the stencil's circulant is
    /// not positive definite on the grid (its symbol at some wavenumber not positive).
    ///
    /// The symbol may be stored by its even half ([`crate::symbol::halve_if_even`]) and in
    /// single precision (read as f64): the same stencil as from its full f64 form, bit
    /// for bit, without a grid-sized copy.
    pub fn of_symbol<S>(symbol: &(impl Symbolic<S> + ?Sized), nx: usize, ny: usize) -> Option<Self>
    where
        S: SymbolValue + Into<f64>,
    {
        let nc = nx / 2 + 1;
        let columns = symbol.columns(nc, ny);
        let odd = columns
            .full_values()
            .is_some_and(|v| !crate::symbol::is_even_in_ky(v, ny));
        if nx < SIDE || ny < SIDE || odd {
            return None;
        }
        let cosines = |n: usize| {
            (0..n)
                .map(|j| (2.0 * PI * j as f64 / n as f64).cos())
                .collect::<Vec<_>>()
        };
        let (cx, cy) = (cosines(nx), cosines(ny));
        // Per column c of the spectrum and offset dy = 0..=RADIUS: sum over ky of
        // s cos(ky dy) (columns in parallel, each sum in row order; the angle's index
        // advanced by dy modulo ny).
        let per_column: Vec<[f64; RADIUS + 1]> = (0..nc)
            .into_par_iter()
            .map_init(ColumnBuf::default, |buf, c| {
                let (mut v, mut j) = ([0.0; RADIUS + 1], [0; RADIUS + 1]);
                for &s in columns.column(c, buf) {
                    let s: f64 = s.into();
                    for dy in 0..=RADIUS {
                        v[dy] += s * cy[j[dy]];
                        j[dy] += dy;
                        if j[dy] >= ny {
                            j[dy] -= ny;
                        }
                    }
                }
                v
            })
            .collect();
        // The inverse transform over the columns: each but 0 (and nx / 2 for even nx)
        // stands for itself and its mirror.
        let norm = 1.0 / (nx * ny) as f64;
        let quadrant = |dx: usize, dy: usize| {
            let mut v = 0.0;
            for (c, sums) in per_column.iter().enumerate() {
                let weight = if c == 0 || 2 * c == nx { 1.0 } else { 2.0 };
                v += weight * cx[c * dx % nx] * sums[dy];
            }
            v * norm
        };
        let mut values = [0.0; SIDE * SIDE];
        for dy in 0..=RADIUS {
            for dx in 0..=RADIUS {
                let v = quadrant(dx, dy);
                for (sx, sy) in [(RADIUS + dx, RADIUS + dy), (RADIUS - dx, RADIUS + dy)] {
                    values[sy * SIDE + sx] = v;
                    values[(2 * RADIUS - sy) * SIDE + sx] = v;
                }
            }
        }
        // The whole kernel sums to the symbol at k = 0; the part beyond the stencil is
        // that minus the stencil's sum.
        let kept: f64 = values.iter().sum();
        let tail = Into::<f64>::into(columns.column(0, &mut ColumnBuf::default())[0]) - kept;
        values[RADIUS * SIDE + RADIUS] += TAIL_SHARE * tail;
        let stencil = Self { values, nx, ny };
        // Positive definite on any set of cells (the search directions descend), else
        // no stencil.
        (stencil.lowest_eigenvalue(&cx, &cy) > 0.0).then_some(stencil)
    }

    /// The least eigenvalue of the stencil's circulant on the grid: its symbol (a
    /// cosine sum, the stencil being even in x and y) at the grid's wavenumbers, given
    /// the cosines of `2 pi j / nx` and `2 pi j / ny`.
    fn lowest_eigenvalue(&self, cx: &[f64], cy: &[f64]) -> f64 {
        let (nx, ny) = (self.nx, self.ny);
        (0..=ny / 2)
            .into_par_iter()
            .map(|ky| {
                // Per dx = 0..=RADIUS: the column of the stencil against cos(ky dy).
                let by_dx: [f64; RADIUS + 1] = std::array::from_fn(|dx| {
                    (0..SIDE)
                        .map(|sy| {
                            let dy = sy.abs_diff(RADIUS);
                            self.values[sy * SIDE + RADIUS + dx] * cy[ky * dy % ny]
                        })
                        .sum()
                });
                (0..=nx / 2)
                    .map(|kx| {
                        let mut v = by_dx[0];
                        for dx in 1..=RADIUS {
                            v += 2.0 * by_dx[dx] * cx[kx * dx % nx];
                        }
                        v
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .reduce(|| f64::INFINITY, f64::min)
    }

    /// The value at offset `(dx, dy)`, each within `-RADIUS..=RADIUS`.
    pub fn value(&self, dx: i64, dy: i64) -> f64 {
        let r = RADIUS as i64;
        assert!(dx.abs() <= r && dy.abs() <= r, "offset within the stencil");
        self.values[((dy + r) as usize) * SIDE + (dx + r) as usize]
    }

    /// `y = S q` for `q = active (w - shift)` (zero off the active cells, as the
    /// solver's residual), at the active cells of the rows `first_row..` that `y`
    /// covers (whole rows of `nx` cells), 0 at the others of the rows `on` marks (`on`
    /// indexed from `first_row`); the rows `on` leaves out are not written. `active`
    /// and `w` are the whole grid, read around each cell with wrap-around. Each value
    /// sums its products in a fixed order (for each column offset the rows' products,
    /// then the columns' sums), so results do not depend on how the caller splits the
    /// rows.
    pub fn apply_rows(
        &self,
        (active, w, shift): (&[u8], &[f64], f64),
        y: &mut [f64],
        on: &[bool],
        first_row: usize,
    ) {
        let (nx, ny) = (self.nx, self.ny);
        let r = RADIUS as i64;
        for (k, row) in y.chunks_mut(nx).enumerate() {
            if !on[k] {
                continue;
            }
            let iy = first_row + k;
            // The stencil's rows of the grid, wrapped around.
            let rows: [(&[u8], &[f64]); SIDE] = std::array::from_fn(|s| {
                let jy = (iy as i64 + s as i64 - r).rem_euclid(ny as i64) as usize;
                let cells = jy * nx..(jy + 1) * nx;
                (&active[cells.clone()], &w[cells])
            });
            let own = &active[iy * nx..(iy + 1) * nx];
            // Zero first, then the active cells, found 8 cells (one u64) at a time: most
            // blocks hold none on a small contact set.
            row.fill(0.0);
            let blocks = own.chunks_exact(8);
            let tail = 8 * (nx / 8)..nx;
            for (b, block) in blocks.enumerate() {
                let mut bytes = u64::from_le_bytes(block.try_into().expect("8 cells"));
                while bytes != 0 {
                    let j = bytes.trailing_zeros() as usize / 8;
                    bytes &= !(0xff << (8 * j));
                    row[8 * b + j] = self.sum_at(8 * b + j, &rows, shift);
                }
            }
            for ix in tail.filter(|&ix| own[ix] != 0) {
                row[ix] = self.sum_at(ix, &rows, shift);
            }
        }
    }

    /// The stencil's sum at column `ix` over `rows` (the grid's rows around the cell,
    /// wrapped around): one partial sum per column offset, over the rows (independent
    /// chains the compiler keeps in vector registers), then summed in column order.
    fn sum_at(&self, ix: usize, rows: &[(&[u8], &[f64]); SIDE], shift: f64) -> f64 {
        let nx = self.nx;
        let mut sums = [0.0; SIDE];
        let interior = ix >= RADIUS && ix + RADIUS < nx;
        for (weights, (act, w)) in self.values.chunks_exact(SIDE).zip(rows) {
            if interior {
                let near = ix - RADIUS..=ix + RADIUS;
                let cells = act[near.clone()].iter().zip(&w[near]);
                for ((sum, c), (&a, w)) in sums.iter_mut().zip(weights).zip(cells) {
                    *sum += c * (a as f64 * (w - shift));
                }
            } else {
                for (s, (sum, c)) in sums.iter_mut().zip(weights).enumerate() {
                    let jx = (ix + nx + s - RADIUS) % nx;
                    *sum += c * (act[jx] as f64 * (w[jx] - shift));
                }
            }
        }
        sums.iter().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fft::Fft2;

    /// A symbol even in k, not separable: |k| with a mean-mode value, as the solver's M.
    fn stiffness(nx: usize, ny: usize) -> Vec<f64> {
        crate::operator::spectral_grid(nx, ny, 1.0, 1.3, |kx, ky| {
            let k = (kx * kx + ky * ky).sqrt();
            if k > 0.0 {
                0.5 * k
            } else {
                0.5 * 2.0 * PI / 1.3
            }
        })
    }

    #[test]
    fn the_kernel_against_an_inverse_transform() {
        for (nx, ny) in [(16, 16), (32, 24), (30, 18), (12, 40)] {
            let s = stiffness(nx, ny);
            let st = Stencil::of_symbol(&s, nx, ny).unwrap();
            // The whole kernel by the transforms (an independent method).
            let mut full = vec![0.0; nx * ny];
            Fft2::<f64>::new(nx, ny).inverse_of_real(&s, &mut full);
            let at = |dx: i64, dy: i64| {
                full[dy.rem_euclid(ny as i64) as usize * nx + dx.rem_euclid(nx as i64) as usize]
            };
            let peak = at(0, 0);
            let r = RADIUS as i64;
            let mut kept = 0.0;
            for dy in -r..=r {
                for dx in -r..=r {
                    kept += at(dx, dy);
                    if (dx, dy) != (0, 0) {
                        let (a, b) = (st.value(dx, dy), at(dx, dy));
                        assert!(
                            (a - b).abs() <= 1e-13 * peak,
                            "{nx}x{ny} ({dx},{dy}): {a} {b}"
                        );
                    }
                }
            }
            // The centre: the kernel's value plus the tail's share (the tail from the
            // whole kernel, not from the symbol's k = 0 value).
            let tail = full.iter().sum::<f64>() - kept;
            let centre = at(0, 0) + TAIL_SHARE * tail;
            assert!((st.value(0, 0) - centre).abs() <= 1e-13 * peak);
        }
        assert!(Stencil::of_symbol(&stiffness(8, 16), 8, 16).is_none());
        // The symbol stored by its even half, and in single precision: the same
        // stencil as from its full form, bit for bit.
        for (nx, ny) in [(16, 16), (30, 18), (12, 41)] {
            let s = stiffness(nx, ny);
            let half = crate::symbol::halve_if_even(s.clone(), ny);
            assert!(half.len() < s.len());
            let bits = |st: Stencil| st.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            let full = bits(Stencil::of_symbol(&s, nx, ny).unwrap());
            assert_eq!(bits(Stencil::of_symbol(&half, nx, ny).unwrap()), full);
            let (s32, h32): (Vec<f32>, Vec<f32>) = (
                s.iter().map(|&v| v as f32).collect(),
                half.iter().map(|&v| v as f32).collect(),
            );
            let single = bits(Stencil::of_symbol(&s32, nx, ny).unwrap());
            assert_eq!(bits(Stencil::of_symbol(&h32, nx, ny).unwrap()), single);
        }
        // A kernel whose stencil is indefinite (1 at the centre and at (+-2, 0): symbol
        // 1 + 2 cos(2 kx h), -1 at its least): none.
        let n = 32;
        let indefinite = crate::operator::spectral_grid(n, n, 1.0, 1.0, |kx, _| {
            1.0 + 2.0 * (2.0 * kx / n as f64).cos()
        });
        assert!(Stencil::of_symbol(&indefinite, n, n).is_none());
        // A symbol even in k but not in ky alone: no cosine form, no stencil.
        let odd =
            crate::operator::spectral_grid(16, 16, 1.0, 1.0, |kx, ky| 1.0 + (kx * ky).max(0.0));
        assert!(Stencil::of_symbol(&odd, 16, 16).is_none());
    }

    #[test]
    fn the_stencil_is_positive_definite() {
        // Its symbol (a cosine sum) positive at every wavenumber of the grid: M on the
        // contact set is then positive definite, and the solver's iteration a descent.
        let (nx, ny) = (64, 64);
        let st = Stencil::of_symbol(&stiffness(nx, ny), nx, ny).unwrap();
        let r = RADIUS as i64;
        let mut lowest = f64::INFINITY;
        for ky in 0..ny {
            for kx in 0..nx {
                let mut v = 0.0;
                for dy in -r..=r {
                    for dx in -r..=r {
                        let a = 2.0
                            * PI
                            * (kx as f64 * dx as f64 / nx as f64
                                + ky as f64 * dy as f64 / ny as f64);
                        v += st.value(dx, dy) * a.cos();
                    }
                }
                lowest = lowest.min(v);
            }
        }
        assert!(lowest > 0.0, "lowest eigenvalue {lowest}");
        let cos = |n: usize| {
            (0..n)
                .map(|j| (2.0 * PI * j as f64 / n as f64).cos())
                .collect::<Vec<_>>()
        };
        let fast = st.lowest_eigenvalue(&cos(nx), &cos(ny));
        assert!(
            (fast - lowest).abs() <= 1e-12 * st.value(0, 0),
            "{fast} {lowest}"
        );
    }

    #[test]
    fn rows_applied_as_a_dense_sum_and_split_any_way() {
        let (nx, ny) = (20, 14);
        let st = Stencil::of_symbol(&stiffness(nx, ny), nx, ny).unwrap();
        // A sparse contact set (a row without contact) and a gap w - shift.
        let active: Vec<u8> = (0..nx * ny)
            .map(|i| ((i * 7) % 5 == 0 && i / nx != 3) as u8)
            .collect();
        let w: Vec<f64> = (0..nx * ny).map(|i| (i as f64 * 0.37).sin()).collect();
        let shift = 0.2;
        let on: Vec<bool> = (0..ny)
            .map(|r| active[r * nx..(r + 1) * nx].contains(&1))
            .collect();
        let mut y = vec![f64::NAN; nx * ny];
        st.apply_rows((&active, &w, shift), &mut y, &on, 0);
        let r = RADIUS as i64;
        for iy in 0..ny {
            for ix in 0..nx {
                let i = iy * nx + ix;
                if !on[iy] {
                    assert!(y[i].is_nan(), "rows without contact are not written");
                    continue;
                }
                let mut want = 0.0;
                if active[i] == 1 {
                    for dy in -r..=r {
                        for dx in -r..=r {
                            let j = (iy as i64 + dy).rem_euclid(ny as i64) as usize * nx
                                + (ix as i64 + dx).rem_euclid(nx as i64) as usize;
                            want += st.value(dx, dy) * active[j] as f64 * (w[j] - shift);
                        }
                    }
                }
                assert!(
                    (y[i] - want).abs() <= 1e-14 * want.abs().max(1.0),
                    "{ix},{iy}"
                );
            }
        }
        // Split in row blocks: the same bits.
        let mut split = vec![f64::NAN; nx * ny];
        for (b, rows) in split.chunks_mut(3 * nx).enumerate() {
            let on = &on[b * 3..b * 3 + rows.len() / nx];
            st.apply_rows((&active, &w, shift), rows, on, 3 * b);
        }
        assert!(y
            .iter()
            .zip(&split)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}
