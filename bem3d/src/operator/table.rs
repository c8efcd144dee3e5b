//! Real-space influence tables for direct sums over few loads (periodic and mirrored).

use rayon::prelude::*;

/// Below this many loads a direct real-space sum beats an FFT-pair application of a
/// periodic operator (in theory about log2 of the grid size times the FFT's constant;
/// measured break-even 47, 65 and 76 loads at 256^2, 512^2 and 1024^2 on the 2-core
/// development machine, AVX-512 build). Only speed depends on it, never results beyond
/// rounding.
pub(super) const POINT_LOAD_LIMIT: usize = 48;

/// `impl RealSpace for $operator`, whose real-space table is its field `table` (a
/// [`Table`]) with rows of `hs.nx` cells; `$limit` is its point-load limit. The caller
/// has `RealSpace` and `Table` in scope.
macro_rules! real_space_by_table {
    ($operator:ty, $limit:expr) => {
        impl RealSpace for $operator {
            // The table's methods, not the trait's defaults of the same names.
            fn add_point_loads(&mut self, loads: &[(usize, f64)], u: &mut [f64]) {
                Table::add_point_loads(&self.table, self.hs.nx, loads, u);
            }
            fn restricted(&self, cells: &[usize], buffer: Vec<f64>) -> Option<Vec<f64>> {
                Some(Table::restricted(&self.table, self.hs.nx, cells, buffer))
            }
            fn displacements_at(&self, at: &[usize], loads: &[(usize, f64)]) -> Option<Vec<f64>> {
                Some(Table::displacements_at(&self.table, self.hs.nx, at, loads))
            }
            fn point_load_limit(&self) -> usize {
                $limit
            }
        }
    };
}
pub(super) use real_space_by_table;

/// A real-space influence table: the response at cell `(i, j)` of a grid of row length
/// `nx` to a unit load at cell `(ic, jc)`, by value or by row. The direct sums
/// ([`RealSpace::restricted`](super::traits::RealSpace::restricted), [`RealSpace::displacements_at`](super::traits::RealSpace::displacements_at),
/// [`RealSpace::add_point_loads`](super::traits::RealSpace::add_point_loads)) read it.
pub(super) trait Table: Sync {
    /// The response at `(i, j)` to a load at `(ic, jc)`.
    fn value(&self, cell: (usize, usize), load: (usize, usize)) -> f64;

    /// `row += v` times the responses along row `j` (of length `nx`) to a unit load at
    /// `(ic, jc)`: one product and one sum per cell.
    fn add_to_row(&self, row: &mut [f64], j: usize, load: (usize, usize), v: f64);

    /// The table between the listed cells of a grid of row length `nx`: a dense
    /// row-major matrix (see [`RealSpace::restricted`](super::traits::RealSpace::restricted)), in `m`'s storage. Every entry
    /// is written by the rows' fill (in parallel, so a fresh matrix's pages are mapped
    /// by both threads); resizing a reused buffer writes only what it grows by.
    fn restricted(&self, nx: usize, cells: &[usize], mut m: Vec<f64>) -> Vec<f64> {
        let n = cells.len();
        if m.is_empty() {
            m = vec![0.0; n * n];
        } else {
            m.resize(n * n, 0.0);
        }
        let at: Vec<(usize, usize)> = cells.iter().map(|&c| (c % nx, c / nx)).collect();
        m.par_chunks_mut(n.max(1)).zip(&at).for_each(|(row, &a)| {
            for (v, &b) in row.iter_mut().zip(&at) {
                *v = self.value(a, b);
            }
        });
        m
    }

    /// The sums over `loads` at the cells `at` only (see
    /// [`RealSpace::displacements_at`](super::traits::RealSpace::displacements_at)), on a grid of row length `nx`.
    fn displacements_at(&self, nx: usize, at: &[usize], loads: &[(usize, f64)]) -> Vec<f64> {
        let src: Vec<((usize, usize), f64)> =
            loads.iter().map(|&(c, v)| ((c % nx, c / nx), v)).collect();
        at.par_iter()
            .map(|&c| {
                let cell = (c % nx, c / nx);
                src.iter().map(|&(l, v)| self.value(cell, l) * v).sum()
            })
            .collect()
    }

    /// `u += sum over loads` on a grid of row length `nx` (`u.len() / nx` rows). Each
    /// value sums the loads in list order, so the result does not depend on threads.
    fn add_point_loads(&self, nx: usize, loads: &[(usize, f64)], u: &mut [f64]) {
        u.par_chunks_mut(nx * 8).enumerate().for_each(|(b, block)| {
            for (jj, row) in block.chunks_mut(nx).enumerate() {
                let j = 8 * b + jj;
                for &(c, v) in loads {
                    self.add_to_row(row, j, (c % nx, c / nx), v);
                }
            }
        });
    }
}

/// A periodic operator's table on its `py x px` torus: the response at (i, j) to a
/// unit load at (ic, jc) is the value at the offsets `d = (i - ic) mod px` and
/// `r = (j - jc) mod py`. A table even in y (K's symbol even in ky, as every periodic
/// half-space's) is even in x too (a real symbol even in ky is even in kx): it keeps the
/// quarter `r <= py/2`, `d <= px/2` and reads `(min(d, px - d), min(r, py - r))`. The
/// mirrored values differ from the inverse transform's own by rounding only.
pub(super) struct Circulant {
    pub(super) px: usize,
    pub(super) py: usize,
    /// Stored columns per row: `px / 2 + 1` for an even table, else `px`.
    pub(super) cols: usize,
    pub(super) even: bool,
    pub(super) values: Vec<f64>,
}

impl Circulant {
    /// The table of the full `py x px` responses `values` (row offset major); `even`
    /// keeps its quarter.
    pub(super) fn new(px: usize, py: usize, values: Vec<f64>, even: bool) -> Self {
        if !even {
            return Self {
                px,
                py,
                cols: px,
                even,
                values,
            };
        }
        let cols = (px / 2 + 1).min(px);
        let rows = crate::symbol::even_rows(py).min(py);
        // Sized exactly (a collected `flat_map` would grow by doubling: up to twice the
        // address space).
        let mut quarter = Vec::with_capacity(rows * cols);
        for row in values.chunks(px).take(rows) {
            quarter.extend_from_slice(&row[..cols]);
        }
        let values = quarter;
        Self {
            px,
            py,
            cols,
            even,
            values,
        }
    }

    /// The stored row of row offset `r` (in `0..py`).
    fn stored_row(&self, r: usize) -> &[f64] {
        let r = if self.even { r.min(self.py - r) } else { r };
        &self.values[r * self.cols..(r + 1) * self.cols]
    }

    /// `out[k] += v g(d0 + k)`, `g` the full row of offsets `0..px` that `q` stores
    /// (`d0 + out.len() <= px`): the stored columns forwards, the mirrored ones
    /// (`g(d) = q[px - d]`, `d > px / 2`) backwards.
    fn add_offsets(&self, q: &[f64], d0: usize, v: f64, out: &mut [f64]) {
        if out.is_empty() {
            return;
        }
        let end = d0 + out.len();
        let direct = if self.even {
            self.cols.clamp(d0, end)
        } else {
            end
        };
        let (fwd, mirrored) = out.split_at_mut(direct - d0);
        if !fwd.is_empty() {
            crate::wide::add_scaled(fwd, v, &q[d0..direct]);
        }
        if !mirrored.is_empty() {
            // Offsets direct..end read q[px - d], from px - direct down to px + 1 - end.
            let px = self.px;
            crate::wide::add_scaled_reversed(mirrored, v, &q[px + 1 - end..=px - direct]);
        }
    }
}

impl Table for Circulant {
    fn value(&self, (i, j): (usize, usize), (ic, jc): (usize, usize)) -> f64 {
        let d = wrap(i, ic, self.px);
        let d = if self.even { d.min(self.px - d) } else { d };
        self.stored_row(wrap(j, jc, self.py))[d]
    }
    fn add_to_row(&self, row: &mut [f64], j: usize, (ic, jc): (usize, usize), v: f64) {
        let q = self.stored_row(wrap(j, jc, self.py));
        // Columns i >= ic see offsets 0.., columns i < ic wrap around to px - ic...
        let (before, after) = row.split_at_mut(ic);
        self.add_offsets(q, 0, v, after);
        self.add_offsets(q, self.px - ic, v, before);
    }
}

/// A non-periodic operator's table: the response depends on the offsets' magnitudes
/// only (Love's coefficients are even in x and y), so row `|j - jc|` holds the
/// offsets `-(nx - 1)..=nx - 1`: the response at (i, j) to a unit load at (ic, jc) is
/// `values[|j - jc| * (2 nx - 1) + nx - 1 + i - ic]`. Half the values of the padded
/// `2ny x 2nx` grid's circulant, and each row's responses one contiguous stretch.
pub(super) struct Mirrored {
    pub(super) nx: usize,
    pub(super) values: Vec<f64>,
}

impl Mirrored {
    /// The table of the coefficients `quadrant(dx, dy)` at offsets `0..nx` x `0..ny`,
    /// rows in parallel.
    pub(super) fn new(nx: usize, ny: usize, quadrant: impl Fn(usize, usize) -> f64 + Sync) -> Self {
        let len = 2 * nx - 1;
        let mut values = vec![0.0; len * ny];
        values
            .par_chunks_mut(len)
            .enumerate()
            .for_each(|(dy, row)| {
                for dx in 0..nx {
                    let v = quadrant(dx, dy);
                    row[nx - 1 + dx] = v;
                    row[nx - 1 - dx] = v;
                }
            });
        Self { nx, values }
    }

    /// The offsets `-(nx - 1)..=nx - 1` of row offset `dy`.
    pub(super) fn offsets(&self, dy: usize) -> &[f64] {
        let len = 2 * self.nx - 1;
        &self.values[dy * len..(dy + 1) * len]
    }
}

impl Table for Mirrored {
    fn value(&self, (i, j): (usize, usize), (ic, jc): (usize, usize)) -> f64 {
        self.offsets(j.abs_diff(jc))[self.nx - 1 + i - ic]
    }
    fn add_to_row(&self, row: &mut [f64], j: usize, (ic, jc): (usize, usize), v: f64) {
        let nx = row.len();
        let r = &self.offsets(j.abs_diff(jc))[nx - 1 - ic..2 * nx - 1 - ic];
        let (before, after) = r.split_at(ic);
        crate::wide::add_scaled(&mut row[ic..], v, after);
        crate::wide::add_scaled(&mut row[..ic], v, before);
    }
}

/// `(a + period - b) mod period` for `a, b < period`, without a division.
pub(super) fn wrap(a: usize, b: usize, period: usize) -> usize {
    let d = a + period - b;
    if d >= period {
        d - period
    } else {
        d
    }
}
