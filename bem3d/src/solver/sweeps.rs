//! The per-cell work of the solver's passes over the grid, one function per pass, each
//! over one chunk of cells (the caller splits the grid and sums the chunks' results in
//! order).
//!
//! Each function states its per-cell work once, as a closure, and runs it over blocks of
//! [`LANES`] cells (`as_chunks`: no bounds checks, so the compiler emits vector code),
//! then over the chunk's last `len % LANES` cells. Cell j of a block adds to lane j of
//! every sum, the last cells to lane 0, and the lanes are added in order ([`Sums`]):
//! results do not depend on how the work is split. Written inline in the transforms'
//! row loops with indexed cells, the same work stayed scalar (measured at 1024^2 on
//! the development machine: a quarter of an iteration's time, about 1.7x the vector
//! form's).

use super::state::ZMap;
use super::stored::{scale_for, Cell};
use std::ops::Range;

/// Lanes of the sums (four f64: one 256-bit vector).
const LANES: usize = 4;

/// `N` sums over [`LANES`] lanes each.
struct Sums<const N: usize>([[f64; LANES]; N]);

impl<const N: usize> Sums<N> {
    fn new() -> Self {
        Sums([[0.0; LANES]; N])
    }

    /// Runs `cell` on lane `l` of every sum.
    #[inline(always)]
    fn lane(&mut self, l: usize, cell: impl FnOnce(&mut [f64; N])) {
        let mut s = [0.0; N];
        for (v, lanes) in s.iter_mut().zip(&self.0) {
            *v = lanes[l];
        }
        cell(&mut s);
        for (v, lanes) in s.iter().zip(&mut self.0) {
            lanes[l] = *v;
        }
    }

    /// The lanes added in order (sum `max_slot` combined by max instead; the solver's
    /// [`combine`](super::fused::combine)).
    fn total(self, max_slot: Option<usize>) -> [f64; N] {
        let lane = |l: usize| -> [f64; N] { std::array::from_fn(|k| self.0[k][l]) };
        let mut out = lane(0);
        for l in 1..LANES {
            super::fused::combine(&mut out, &lane(l), max_slot);
        }
        out
    }
}

/// Runs of consecutive rows (of `width` cells, the grid's last one may be short) with
/// the same `flag(row)`, over `rows` rows and `len` cells: (flag, cells).
fn row_runs(
    rows: usize,
    width: usize,
    len: usize,
    flag: impl Fn(usize) -> bool,
) -> impl Iterator<Item = (bool, Range<usize>)> {
    let mut r = 0;
    std::iter::from_fn(move || {
        if r >= rows {
            return None;
        }
        let (start, f) = (r, flag(r));
        while r < rows && flag(r) == f {
            r += 1;
        }
        Some((f, (start * width).min(len)..(r * width).min(len)))
    })
}

/// Pass A: applies the pending force rescale (`p *= scale`, `w = scale w + zf z`),
/// marks the contact set (p > 0) in `active` and its rows in `on`; returns the sum of
/// `w - offset` and the cell count over the set. p is read only in the rows (of `width`
/// cells) that `with_p` marks: the others hold no pressure (pass D's flags). With
/// `scale = 1` and `zf = 0` (no rescale pending) p and w are read, not written. z is
/// `zmap` of the values `z` (the heights, or z itself).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn rescale(
    p: &mut [f64],
    z: &[f64],
    zmap: ZMap,
    w: &mut [f64],
    active: &mut [u8],
    (with_p, on, width): (&[bool], &mut [bool], usize),
    (scale, zf): (f64, f64),
    offset: f64,
) -> [f64; 2] {
    let cell = |p: &mut f64, z: f64, w: &mut f64, act: &mut u8, s: &mut [f64; 2]| {
        let pi = *p * scale;
        *p = pi;
        let wi = scale * *w + zf * z;
        *w = wi;
        *act = (pi > 0.0) as u8;
        let a = if pi > 0.0 { 1.0 } else { 0.0 };
        s[0] += a * (wi - offset);
        s[1] += a;
    };
    let kept = |p: f64, w: f64, act: &mut u8, s: &mut [f64; 2]| {
        *act = (p > 0.0) as u8;
        let a = if p > 0.0 { 1.0 } else { 0.0 };
        s[0] += a * (w - offset);
        s[1] += a;
    };
    let unchanged = scale == 1.0 && zf == 0.0;
    let n = p.len();
    let mut sums = Sums::new();
    for (any_p, cells) in row_runs(with_p.len(), width, n, |r| with_p[r]) {
        let (z, w, act) = (
            &z[cells.clone()],
            &mut w[cells.clone()],
            &mut active[cells.clone()],
        );
        if !any_p {
            // No pressure in these rows: w only.
            if !unchanged {
                for (w, z) in w.iter_mut().zip(z) {
                    *w = scale * *w + zf * zmap.of(*z);
                }
            }
            act.fill(0);
            continue;
        }
        let p = &mut p[cells];
        let (pb, pt) = p.as_chunks_mut::<LANES>();
        let (zb, zt) = z.as_chunks::<LANES>();
        let (wb, wt) = w.as_chunks_mut::<LANES>();
        let (ab, at) = act.as_chunks_mut::<LANES>();
        if unchanged {
            for ((p, w), a) in pb.iter().zip(wb.iter()).zip(ab.iter_mut()) {
                for l in 0..LANES {
                    sums.lane(l, |s| kept(p[l], w[l], &mut a[l], s));
                }
            }
            for ((p, w), a) in pt.iter().zip(wt.iter()).zip(at.iter_mut()) {
                sums.lane(0, |s| kept(*p, *w, a, s));
            }
            continue;
        }
        for (((p, z), w), a) in pb.iter_mut().zip(zb).zip(wb.iter_mut()).zip(ab.iter_mut()) {
            for l in 0..LANES {
                sums.lane(l, |s| {
                    cell(&mut p[l], zmap.of(z[l]), &mut w[l], &mut a[l], s)
                });
            }
        }
        for (((p, z), w), a) in pt.iter_mut().zip(zt).zip(wt.iter_mut()).zip(at.iter_mut()) {
            sums.lane(0, |s| cell(p, zmap.of(*z), w, a, s));
        }
    }
    for ((on, act), &any_p) in on.iter_mut().zip(active[..n].chunks(width)).zip(with_p) {
        *on = any_p && act.contains(&1);
    }
    sums.total(None)
}

/// The convergence criterion's terms of `p` with the gap `g = mask (w - approach)`:
/// sum p |g|, sum p and max -g (slot 2, combined by max).
#[inline(never)]
pub(super) fn criterion_terms(p: &[f64], w: &[f64], mask: &[u8], approach: f64) -> [f64; 3] {
    let cell = |p: f64, w: f64, m: u8, s: &mut [f64; 3]| {
        let gi = m as f64 * (w - approach);
        s[0] += p * gi.abs();
        s[1] += p;
        s[2] = max(s[2], -gi);
    };
    let n = p.len();
    let (pb, pt) = p.as_chunks::<LANES>();
    let (wb, wt) = w[..n].as_chunks::<LANES>();
    let (mb, mt) = mask[..n].as_chunks::<LANES>();
    let mut sums = Sums::new();
    for ((p, w), m) in pb.iter().zip(wb).zip(mb) {
        for l in 0..LANES {
            sums.lane(l, |s| cell(p[l], w[l], m[l], s));
        }
    }
    for ((p, w), m) in pt.iter().zip(wt).zip(mt) {
        sums.lane(0, |s| cell(*p, *w, *m, s));
    }
    sums.total(Some(2))
}

/// The duality gap's terms over the domain cells of a chunk: `sum p g`, `sum p`, and
/// the largest `-g` (slot 2, so that `min g = -slot 2`), with `g = w - approach`.
pub(super) fn certificate_terms(p: &[f64], w: &[f64], mask: &[u8], approach: f64) -> [f64; 3] {
    let mut s = [0.0, 0.0, f64::NEG_INFINITY];
    for ((&p, &w), &m) in p.iter().zip(w).zip(mask) {
        if m > 0 {
            let g = w - approach;
            s[0] += p * g;
            s[1] += p;
            s[2] = s[2].max(-g);
        }
    }
    s
}

/// Pass B: the criterion's terms (as [`criterion_terms`]) and the residual
/// `q = [p > 0] g`, M's input, with its sum (slot 3). p is read only in the rows (of
/// `width` cells) that `on` marks (pass A's: the rows of the contact set); the others'
/// q is 0 and only their gaps count (the largest interpenetration).
#[inline(never)]
pub(super) fn residual(
    p: &[f64],
    w: &[f64],
    mask: &[u8],
    q: &mut [f64],
    (on, width): (&[bool], usize),
    approach: f64,
) -> [f64; 4] {
    let cell = |p: f64, w: f64, m: u8, q: &mut f64, s: &mut [f64; 4]| {
        let gi = m as f64 * (w - approach);
        let a = if p > 0.0 { 1.0 } else { 0.0 };
        s[0] += p * gi.abs();
        s[1] += p;
        s[2] = max(s[2], -gi);
        *q = a * gi;
        s[3] += a * gi;
    };
    let off = |w: f64, m: u8, q: &mut f64, s: &mut [f64; 4]| {
        let gi = m as f64 * (w - approach);
        s[2] = max(s[2], -gi);
        *q = 0.0;
    };
    let n = p.len();
    let mut sums = Sums::new();
    for (set, cells) in row_runs(on.len(), width, n, |r| on[r]) {
        let (wb, wt) = w[cells.clone()].as_chunks::<LANES>();
        let (mb, mt) = mask[cells.clone()].as_chunks::<LANES>();
        let (qb, qt) = q[cells.clone()].as_chunks_mut::<LANES>();
        if !set {
            for ((w, m), q) in wb.iter().zip(mb).zip(qb.iter_mut()) {
                for l in 0..LANES {
                    sums.lane(l, |s| off(w[l], m[l], &mut q[l], s));
                }
            }
            for ((w, m), q) in wt.iter().zip(mt).zip(qt.iter_mut()) {
                sums.lane(0, |s| off(*w, *m, q, s));
            }
            continue;
        }
        let (pb, pt) = p[cells].as_chunks::<LANES>();
        for (((p, w), m), q) in pb.iter().zip(wb).zip(mb).zip(qb.iter_mut()) {
            for l in 0..LANES {
                sums.lane(l, |s| cell(p[l], w[l], m[l], &mut q[l], s));
            }
        }
        for (((p, w), m), q) in pt.iter().zip(wt).zip(mt).zip(qt.iter_mut()) {
            sums.lane(0, |s| cell(*p, *w, *m, q, s));
        }
    }
    sums.total(Some(2))
}

/// After M: with `y = M q` and q recomputed from `active` and `w`, the sums of y over
/// the contact set, `<q, y>` and `<q, y_prev>`; y then replaces `y_prev` (stored as
/// [`Cell`] stores: single precision, as M computes it, or scaled, the chunk's scale
/// then set from its largest y). Only the rows (of `width` cells) that `on` marks are
/// read, each run of consecutive ones as one stretch: the others hold no contact cell,
/// so they add nothing, and M was not computed there (their `y_prev`, zero off the set
/// since the direction pass, stays).
#[inline(never)]
pub(super) fn preconditioned<C: Cell>(
    active: &[u8],
    w: &[f64],
    (y_prev, scale): (&mut [C], &mut f64),
    y: &[f64],
    (on, width): (&[bool], usize),
    approach: f64,
) -> [f64; 3] {
    let runs = || row_runs(on.len(), width, active.len(), |r| on[r]).filter(|(set, _)| *set);
    let old = *scale;
    if C::SCALED {
        let mut m = Largest::new();
        for (_, cells) in runs() {
            let (yb, yt) = y[cells].as_chunks::<LANES>();
            for y in yb {
                for l in 0..LANES {
                    m.add(l, [y[l]]);
                }
            }
            yt.iter().for_each(|&y| m.add(0, [y]));
        }
        *scale = scale_for(m.total()[0]);
    }
    let inv = 1.0 / *scale;
    let cell = |act: u8, w: f64, y_prev: &mut C, y: f64, s: &mut [f64; 3]| {
        let a = act as f64;
        let q = a * (w - approach);
        s[0] += a * y;
        s[1] += q * y;
        s[2] += q * y_prev.get(old);
        *y_prev = C::put(y, inv);
    };
    let mut sums = Sums::new();
    for (_, cells) in runs() {
        let (ab, at) = active[cells.clone()].as_chunks::<LANES>();
        let (wb, wt) = w[cells.clone()].as_chunks::<LANES>();
        let (pb, pt) = y_prev[cells.clone()].as_chunks_mut::<LANES>();
        let (yb, yt) = y[cells].as_chunks::<LANES>();
        for (((a, w), yp), y) in ab.iter().zip(wb).zip(pb.iter_mut()).zip(yb) {
            for l in 0..LANES {
                sums.lane(l, |s| cell(a[l], w[l], &mut yp[l], y[l], s));
            }
        }
        for (((a, w), yp), y) in at.iter().zip(wt).zip(pt.iter_mut()).zip(yt) {
            sums.lane(0, |s| cell(*a, *w, yp, *y, s));
        }
    }
    sums.total(None)
}

/// Largest magnitudes of `N` quantities over [`LANES`] lanes, and whether any was NaN
/// (max as a select, so the blocks vectorize; the flag keeps a NaN visible).
struct Largest<const N: usize> {
    lanes: [[f64; LANES]; N],
    nan: bool,
}

impl<const N: usize> Largest<N> {
    fn new() -> Self {
        Largest {
            lanes: [[0.0; LANES]; N],
            nan: false,
        }
    }

    #[inline(always)]
    fn add(&mut self, l: usize, v: [f64; N]) {
        for (lanes, v) in self.lanes.iter_mut().zip(v) {
            lanes[l] = max(lanes[l], v.abs());
            self.nan |= v.is_nan();
        }
    }

    /// The largest of each quantity (NaN if any value was).
    fn total(self) -> [f64; N] {
        self.lanes.map(|lanes| match self.nan {
            true => f64::NAN,
            false => lanes.into_iter().fold(0.0, max),
        })
    }
}

/// Scalars of the direction pass: the contact means of y and of the old t removed
/// (force control), the conjugation factor and the approach.
#[derive(Clone, Copy)]
pub(super) struct Direction {
    pub ybar: f64,
    pub tbar: f64,
    pub beta: f64,
    pub approach: f64,
}

/// The direction pass: y projected (`[p > 0] (y - ybar)`, kept in `y_prev`), the new
/// conjugate direction `t = y + beta [p > 0] (t - tbar)` as stored (single precision,
/// or scaled: each chunk's new scales set from its largest new values first), also
/// written to `out` (K's input); returns `<t, w - approach>` (of t as stored).
/// Rows (of `width` cells) that neither `on` (the contact rows) nor `was` (those of the
/// last direction pass) marks get `out = 0` only: their t and y_prev are already zero.
#[inline(never)]
pub(super) fn direction<C: Cell>(
    active: &[u8],
    w: &[f64],
    (t, t_scale): (&mut [C], &mut f64),
    (y_prev, y_scale): (&mut [C], &mut f64),
    out: &mut [f64],
    (on, was, width): (&[bool], &[bool], usize),
    d: Direction,
) -> [f64; 1] {
    let n = active.len();
    let live = |r: usize| on[r] || was[r];
    let (t_old, y_old) = (*t_scale, *y_scale);
    // The new values of a cell: projected y and t before storage.
    let new = |act: u8, t: C, y_prev: C| {
        let a = act as f64;
        let yi = a * (y_prev.get(y_old) - d.ybar);
        (yi, yi + a * d.beta * (t.get(t_old) - d.tbar))
    };
    if C::SCALED {
        let mut m = Largest::new();
        for (_, cells) in row_runs(on.len(), width, n, live).filter(|(l, _)| *l) {
            let (ab, at) = active[cells.clone()].as_chunks::<LANES>();
            let (tb, tt) = t[cells.clone()].as_chunks::<LANES>();
            let (yb, yt) = y_prev[cells].as_chunks::<LANES>();
            for ((a, t), y) in ab.iter().zip(tb).zip(yb) {
                for l in 0..LANES {
                    let (yi, ti) = new(a[l], t[l], y[l]);
                    m.add(l, [yi, ti]);
                }
            }
            for ((&a, &t), &y) in at.iter().zip(tt).zip(yt) {
                let (yi, ti) = new(a, t, y);
                m.add(0, [yi, ti]);
            }
        }
        let [ym, tm] = m.total();
        (*t_scale, *y_scale) = (scale_for(tm), scale_for(ym));
    }
    let (t_inv, y_inv, t_new) = (1.0 / *t_scale, 1.0 / *y_scale, *t_scale);
    let cell = |act: u8, w: f64, t: &mut C, y_prev: &mut C, out: &mut f64, s: &mut [f64; 1]| {
        let (yi, ti) = new(act, *t, *y_prev);
        *y_prev = C::put(yi, y_inv);
        // t as stored: K's input, the update and <q, t> all see the same direction.
        *t = C::put(ti, t_inv);
        let ti = t.get(t_new);
        *out = ti;
        s[0] += ti * (w - d.approach);
    };
    let mut sums = Sums::new();
    for (live, cells) in row_runs(on.len(), width, n, live) {
        if !live {
            out[cells].fill(0.0);
            continue;
        }
        let (ab, at) = active[cells.clone()].as_chunks::<LANES>();
        let (wb, wt) = w[cells.clone()].as_chunks::<LANES>();
        let (tb, tt) = t[cells.clone()].as_chunks_mut::<LANES>();
        let (pb, pt) = y_prev[cells.clone()].as_chunks_mut::<LANES>();
        let (ob, ot) = out[cells].as_chunks_mut::<LANES>();
        let blocks = ab
            .iter()
            .zip(wb)
            .zip(tb.iter_mut())
            .zip(pb.iter_mut())
            .zip(ob.iter_mut());
        for ((((a, w), t), yp), o) in blocks {
            for l in 0..LANES {
                sums.lane(l, |s| cell(a[l], w[l], &mut t[l], &mut yp[l], &mut o[l], s));
            }
        }
        let last = at
            .iter()
            .zip(wt)
            .zip(tt.iter_mut())
            .zip(pt.iter_mut())
            .zip(ot.iter_mut());
        for ((((a, w), t), yp), o) in last {
            sums.lane(0, |s| cell(*a, *w, t, yp, o, s));
        }
    }
    sums.total(None)
}

/// Scalars of the update pass: the step length, the approach and the pressure step of
/// re-admitted cells per unit of interpenetration.
#[derive(Clone, Copy)]
pub(super) struct Update {
    pub tau: f64,
    pub approach: f64,
    pub step: f64,
}

/// Pass D: the projected update `p = max(p - tau t, 0)` on the contact set, cells of
/// the domain (`mask`) without pressure and with negative gap re-admitted at
/// `-step g`, `w -= tau K t`; each non-zero change against `p - tau t` is appended to
/// `changes` as (cell index + `first`, change), in cell order, while the list holds
/// fewer than `cap` (a list, not a grid-sized array: few cells change once the contact
/// set has formed, and a caller uses the changes only when they are at most `cap` in
/// all; the count returned is always complete). Marks in `with_p` the rows
/// (of `width` cells) where the new p is positive. Returns the total pressure, the number
/// of changed cells and the sum of t over the new set.
#[inline(never)]
pub(super) fn update<C: Cell>(
    p: &mut [f64],
    (t, t_scale): (&[C], f64),
    (changes, first, cap): (&mut Vec<(usize, f64)>, usize, usize),
    (w, kt): (&mut [f64], &[f64]),
    mask: &[u8],
    (with_p, width): (&mut [bool], usize),
    u: Update,
) -> [f64; 3] {
    let cell = |p: &mut f64, t: C, w: &mut f64, m: u8, kt: f64, s: &mut [f64; 3]| {
        let change = project(p, t.get(t_scale), *w, m, u, s);
        *w -= u.tau * kt;
        change
    };
    let n = p.len();
    let (pb, pt) = p.as_chunks_mut::<LANES>();
    let (tb, tt) = t[..n].as_chunks::<LANES>();
    let (wb, wt) = w[..n].as_chunks_mut::<LANES>();
    let (mb, mt) = mask[..n].as_chunks::<LANES>();
    let (kb, kt) = kt[..n].as_chunks::<LANES>();
    let mut sums = Sums::new();
    let blocks = pb.iter_mut().zip(tb).zip(wb.iter_mut()).zip(mb).zip(kb);
    for (b, ((((p, t), w), m), k)) in blocks.enumerate() {
        let mut change = [0.0; LANES];
        for l in 0..LANES {
            sums.lane(l, |s| {
                change[l] = cell(&mut p[l], t[l], &mut w[l], m[l], k[l], s);
            });
        }
        // One branch per block, rarely taken.
        if change != [0.0; LANES] && changes.len() < cap {
            let at = first + b * LANES;
            let cells = change.iter().enumerate().filter(|(_, &c)| c != 0.0);
            changes.extend(cells.map(|(l, &c)| (at + l, c)));
        }
    }
    let at = first + pb.len() * LANES;
    let last = pt.iter_mut().zip(tt).zip(wt.iter_mut()).zip(mt).zip(kt);
    for (i, ((((p, t), w), m), k)) in last.enumerate() {
        sums.lane(0, |s| {
            let change = cell(p, *t, w, *m, *k, s);
            if change != 0.0 && changes.len() < cap {
                changes.push((at + i, change));
            }
        });
    }
    mark_rows_with_pressure(p, with_p, width);
    sums.total(None)
}

/// Pass D without K t, for an iteration whose `K p` is recomputed from scratch: the
/// projected update of [`update`] (the same p, flags and sums, bit for bit), p also
/// written to `values` (the fresh `K p`'s input); w is read for the gap, neither w nor
/// r written.
#[inline(never)]
pub(super) fn advance<C: Cell>(
    p: &mut [f64],
    (t, t_scale): (&[C], f64),
    w: &[f64],
    mask: &[u8],
    values: &mut [f64],
    (with_p, width): (&mut [bool], usize),
    u: Update,
) -> [f64; 3] {
    let cell = |p: &mut f64, t: C, w: f64, m: u8, v: &mut f64, s: &mut [f64; 3]| {
        project(p, t.get(t_scale), w, m, u, s);
        *v = *p;
    };
    let n = p.len();
    let (pb, pt) = p.as_chunks_mut::<LANES>();
    let (tb, tt) = t[..n].as_chunks::<LANES>();
    let (wb, wt) = w[..n].as_chunks::<LANES>();
    let (mb, mt) = mask[..n].as_chunks::<LANES>();
    let (vb, vt) = values[..n].as_chunks_mut::<LANES>();
    let mut sums = Sums::new();
    let blocks = pb.iter_mut().zip(tb).zip(wb).zip(mb).zip(vb.iter_mut());
    for ((((p, t), w), m), v) in blocks {
        for l in 0..LANES {
            sums.lane(l, |s| cell(&mut p[l], t[l], w[l], m[l], &mut v[l], s));
        }
    }
    let last = pt.iter_mut().zip(tt).zip(wt).zip(mt).zip(vt.iter_mut());
    for ((((p, t), w), m), v) in last {
        sums.lane(0, |s| cell(p, *t, *w, *m, v, s));
    }
    mark_rows_with_pressure(p, with_p, width);
    sums.total(None)
}

/// Marks the rows (of `width` cells) of `p` that hold a positive value (pass D's
/// flags for the next pass A; read while p is still in cache).
fn mark_rows_with_pressure(p: &[f64], with_p: &mut [bool], width: usize) {
    // Blocks of eight compared at once (vector code), stopping at one with a positive.
    let positive = |b: &[f64]| b.iter().fold(false, |any, &v| any | (v > 0.0));
    for (f, row) in with_p.iter_mut().zip(p.chunks(width)) {
        let (blocks, tail) = row.as_chunks::<8>();
        *f = blocks.iter().any(|b| positive(b)) || positive(tail);
    }
}

/// One cell of pass D: `p` becomes `max(p - tau t, 0)` on the contact set, `-step g` on
/// a re-admitted cell (in the domain, without pressure, gap `g = w - approach < 0`), 0
/// elsewhere; adds the new p, whether it departs from `p - tau t` and t where the new p
/// is positive to the sums; returns the departure (the new p minus `p - tau t`).
#[inline(always)]
fn project(p: &mut f64, t: f64, w: f64, m: u8, u: Update, s: &mut [f64; 3]) -> f64 {
    let gi = w - u.approach;
    let act = *p > 0.0;
    let raw = *p - u.tau * t;
    let enter = !act & (m > 0) & (gi < 0.0);
    // Inactive cells have p = t = 0, so raw = 0 there.
    // (max(raw, 0) as a select: vectorizes; a NaN raw gives 0, as f64::max would.)
    let clipped = if raw > 0.0 { raw } else { 0.0 };
    let pi = if act {
        clipped
    } else if enter {
        -u.step * gi
    } else {
        0.0
    };
    let change = pi - raw;
    *p = pi;
    s[0] += pi;
    s[1] += if change != 0.0 { 1.0 } else { 0.0 };
    s[2] += if pi > 0.0 { t } else { 0.0 };
    change
}

/// `max(a, b)` as a select (vectorizes); a NaN `b` leaves `a`, as `f64::max` would.
#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pass A on z itself (the identity map).
    fn rescale_on_z(
        p: &mut [f64],
        z: &[f64],
        w: &mut [f64],
        a: &mut [u8],
        rows: (&[bool], &mut [bool], usize),
        sf: (f64, f64),
        offset: f64,
    ) -> [f64; 2] {
        rescale(p, z, ZMap::IDENTITY, w, a, rows, sf, offset)
    }

    /// Pass A on heights through z's map gives the bits of pass A on a stored
    /// `top - h`, signed zeros included (heights of both signs of zero, a top of -0).
    #[test]
    fn pass_a_on_heights_is_pass_a_on_z() {
        let n = 37;
        let h: Vec<f64> = (0..n)
            .map(|i| match i % 5 {
                0 => 0.0,
                1 => -0.0,
                _ => ((i * 7919) % 101) as f64 * -1e-3,
            })
            .collect();
        for top in [-0.0, 0.0, 0.25] {
            let z: Vec<f64> = h.iter().map(|v| top - v).collect();
            let map = ZMap {
                offset: top,
                sign: -1.0,
            };
            let p0: Vec<f64> = (0..n).map(|i| (i as f64 - 12.0) * 0.1).collect();
            let run = |z: &[f64], map: ZMap| {
                let (mut p, mut w, mut a, mut on) =
                    (p0.clone(), vec![0.5; n], vec![0u8; n], [false]);
                let rows = (&[true][..], &mut on[..], n);
                let sums = rescale(&mut p, z, map, &mut w, &mut a, rows, (1.5, -0.25), 0.1);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                (bits(&p), bits(&w), a, sums.map(f64::to_bits))
            };
            assert_eq!(run(&h, map), run(&z, ZMap::IDENTITY), "top {top}");
            for (v, zi) in h.iter().zip(&z) {
                assert_eq!(map.of(*v).to_bits(), zi.to_bits());
                assert_eq!(ZMap::IDENTITY.of(*zi).to_bits(), zi.to_bits());
            }
        }
    }

    /// The documented order: cell i of the blocks to lane i % LANES, the last
    /// `len % LANES` cells to lane 0, lanes added in order.
    fn in_lane_order<const N: usize>(cells: &[[f64; N]], max_slot: Option<usize>) -> [f64; N] {
        let blocks = cells.len() / LANES * LANES;
        let mut lanes = [[0.0f64; N]; LANES];
        for (i, c) in cells.iter().enumerate() {
            let l = if i < blocks { i % LANES } else { 0 };
            for k in 0..N {
                lanes[l][k] = if Some(k) == max_slot {
                    lanes[l][k].max(c[k])
                } else {
                    lanes[l][k] + c[k]
                };
            }
        }
        let mut out = lanes[0];
        for lane in &lanes[1..] {
            for k in 0..N {
                out[k] = if Some(k) == max_slot {
                    out[k].max(lane[k])
                } else {
                    out[k] + lane[k]
                };
            }
        }
        out
    }

    /// Pseudo-random values in [-1, 1), a third of them zero (cells out of contact).
    fn field(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let v = (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
                if s.is_multiple_of(3) {
                    0.0
                } else {
                    v
                }
            })
            .collect()
    }

    /// [`in_lane_order`] over several stretches in turn (each its blocks, then its
    /// last cells to lane 0), into the same lanes.
    fn in_stretches<const N: usize>(stretches: &[Vec<[f64; N]>]) -> [f64; N] {
        let mut lanes = [[0.0f64; N]; LANES];
        for cells in stretches {
            let blocks = cells.len() / LANES * LANES;
            for (i, c) in cells.iter().enumerate() {
                let l = if i < blocks { i % LANES } else { 0 };
                for k in 0..N {
                    lanes[l][k] += c[k];
                }
            }
        }
        let mut out = lanes[0];
        for lane in &lanes[1..] {
            for k in 0..N {
                out[k] += lane[k];
            }
        }
        out
    }

    fn bits<const N: usize>(v: [f64; N]) -> [u64; N] {
        v.map(f64::to_bits)
    }

    /// The pass after M reads only the marked rows: the others' `y_prev` stays, and the
    /// sums are those of the marked rows' cells alone, in lane order (rows of a
    /// multiple of [`LANES`] cells: runs of rows as one stretch).
    #[test]
    fn pass_after_m_skips_unmarked_rows() {
        let (width, on) = (8, [true, false, true, true, false]);
        let n = width * on.len();
        let row_on = |i: usize| on[i / width];
        // The solver's invariant: no contact cell in an unmarked row.
        let act: Vec<u8> = field(n, 1)
            .iter()
            .enumerate()
            .map(|(i, &v)| (v > 0.0 && row_on(i)) as u8)
            .collect();
        let (w0, y, approach) = (field(n, 3), field(n, 5), 0.1);
        let mut yp: Vec<f32> = field(n, 7).iter().map(|&v| v as f32).collect();
        let yp0 = yp.clone();
        let got = preconditioned(&act, &w0, (&mut yp, &mut 1.0), &y, (&on, width), approach);
        let cells: Vec<[f64; 3]> = (0..n)
            .filter(|&i| row_on(i))
            .map(|i| {
                let a = act[i] as f64;
                let q = a * (w0[i] - approach);
                [a * y[i], q * y[i], q * yp0[i] as f64]
            })
            .collect();
        assert_eq!(bits(got), bits(in_lane_order(&cells, None)));
        for i in 0..n {
            let want = if row_on(i) { y[i] as f32 } else { yp0[i] };
            assert_eq!(yp[i].to_bits(), want.to_bits(), "cell {i}");
        }
    }

    /// Passes A, B and the direction skip what their row flags rule out: values planted
    /// in the skipped rows (which the solver keeps at zero) are neither read nor
    /// written, the sums are those of the other rows in lane order (rows of a multiple
    /// of [`LANES`] cells), and pass B still counts the skipped rows' gaps.
    #[test]
    fn passes_skip_rows_without_contact() {
        let (width, flags) = (8, [true, false, false, true, false, true]);
        let n = width * flags.len();
        let row = |i: usize| i / width;
        let kept = |i: usize| flags[row(i)];
        let (approach, scale, zf) = (0.1, 1.3, -0.2);
        // Positive pressure everywhere but in a third of the cells, also in the rows the
        // flags rule out (planted: a pass that reads them counts them).
        let p0: Vec<f64> = field(n, 1).iter().map(|v| v.abs()).collect();
        let (z, w0, mask) = (field(n, 4), field(n, 3), vec![1u8; n]);

        // Pass A: p read and rescaled in the marked rows only; w everywhere.
        let (mut p, mut w, mut a, mut on) = (p0.clone(), w0.clone(), vec![9u8; n], [true; 6]);
        let rows = (&flags[..], &mut on[..], width);
        let got = rescale_on_z(&mut p, &z, &mut w, &mut a, rows, (scale, zf), approach);
        let mut cells = vec![];
        for i in 0..n {
            let wi = scale * w0[i] + zf * z[i];
            assert_eq!(w[i], wi, "cell {i}");
            if !kept(i) {
                assert_eq!((p[i], a[i]), (p0[i], 0), "cell {i}");
                continue;
            }
            let pi = p0[i] * scale;
            assert_eq!((p[i], a[i]), (pi, (pi > 0.0) as u8), "cell {i}");
            let set = if pi > 0.0 { 1.0 } else { 0.0 };
            cells.push([set * (wi - approach), set]);
        }
        assert_eq!(bits(got), bits(in_lane_order(&cells, None)));
        for (r, &f) in flags.iter().enumerate() {
            assert_eq!(on[r], f && a[r * width..(r + 1) * width].contains(&1));
        }
        // Without a pending rescale p and w are left as they are.
        let (mut p, mut w, mut on) = (p0.clone(), w0.clone(), [true; 6]);
        let rows = (&flags[..], &mut on[..], width);
        rescale_on_z(&mut p, &z, &mut w, &mut a, rows, (1.0, 0.0), approach);
        assert_eq!((p, w), (p0.clone(), w0.clone()));

        // Pass B: p read in the marked rows only, q = 0 elsewhere, every gap counted.
        let mut q = vec![9.0; n];
        let got = residual(&p0, &w0, &mask, &mut q, (&flags, width), approach);
        let mut cells = vec![];
        for i in 0..n {
            let g = w0[i] - approach;
            let pi = if kept(i) { p0[i] } else { 0.0 };
            let set = if pi > 0.0 { 1.0 } else { 0.0 };
            assert_eq!(q[i], set * g, "cell {i}");
            if kept(i) {
                cells.push([pi * g.abs(), pi, -g, set * g]);
            } else {
                cells.push([0.0, 0.0, -g, 0.0]);
            }
        }
        assert_eq!(bits(got), bits(in_lane_order(&cells, Some(2))));

        // The direction: rows marked by neither flag get out = 0 and keep t and y_prev.
        let was = [false, true, false, false, false, false];
        let act: Vec<u8> = (0..n).map(|i| (kept(i) && p0[i] > 0.0) as u8).collect();
        let t0: Vec<f32> = field(n, 2).iter().map(|&v| v as f32).collect();
        let yp0: Vec<f32> = field(n, 7).iter().map(|&v| v as f32).collect();
        let (mut t, mut yp, mut out) = (t0.clone(), yp0.clone(), vec![9.0; n]);
        let d = Direction {
            ybar: 0.05,
            tbar: -0.03,
            beta: 0.7,
            approach,
        };
        let got = direction(
            &act,
            &w0,
            (&mut t, &mut 1.0),
            (&mut yp, &mut 1.0),
            &mut out,
            (&flags, &was, width),
            d,
        );
        let mut cells = vec![];
        for i in 0..n {
            if !(kept(i) || was[row(i)]) {
                assert_eq!((t[i], yp[i], out[i]), (t0[i], yp0[i], 0.0), "cell {i}");
                continue;
            }
            let a = act[i] as f64;
            let yi = a * (yp0[i] as f64 - d.ybar);
            let ti = (yi + a * d.beta * (t0[i] as f64 - d.tbar)) as f32;
            assert_eq!(
                (yp[i], t[i], out[i]),
                (yi as f32, ti, ti as f64),
                "cell {i}"
            );
            cells.push([ti as f64 * (w0[i] - approach)]);
        }
        assert_eq!(bits(got), bits(in_lane_order(&cells, None)));
    }

    /// Pass D's list of changes stops at its cap (past it by at most a block's
    /// changes): the first changes in cell order, with the same pressures, gaps and sums
    /// (the count of changes complete) as without a cap.
    #[test]
    fn update_lists_changes_up_to_its_cap() {
        for n in [13, 64, 67] {
            // Large directions: most cells of the set leave it (clipped at zero).
            let p0: Vec<f64> = field(n, 1).iter().map(|v| v.max(0.0)).collect();
            let t0: Vec<f32> = p0
                .iter()
                .zip(field(n, 2))
                .map(|(&p, v)| if p > 0.0 { 10.0 * v.abs() as f32 } else { 0.0 })
                .collect();
            let (w0, kt) = (field(n, 3), field(n, 6));
            let mask = vec![1u8; n];
            let u = Update {
                tau: 0.4,
                approach: 0.1,
                step: 2.0,
            };
            let run = |cap: usize| {
                let (mut p, mut w, mut list, mut flag) = (p0.clone(), w0.clone(), vec![], [false]);
                let rows = (&mut flag[..], n);
                let sums = update(
                    &mut p,
                    (&t0, 1.0),
                    (&mut list, 7, cap),
                    (&mut w, &kt),
                    &mask,
                    rows,
                    u,
                );
                (bits(sums), p, w, list)
            };
            let (sums, p, w, all) = run(n + 1);
            assert!(all.len() > 2, "n = {n}: too few changes to cap");
            let (capped_sums, q, v, capped) = run(2);
            assert_eq!((capped_sums, &q, &v), (sums, &p, &w), "n = {n}");
            assert!(capped.len() >= 2 && capped.len() <= 1 + LANES, "n = {n}");
            assert!(all.starts_with(&capped), "n = {n}");
        }
    }

    /// Every pass against a plain cell-by-cell form of its formulas, summed in the
    /// documented lane order: outputs and sums bit for bit, on lengths with and without
    /// a partial last block.
    #[test]
    fn passes_match_their_cell_by_cell_form() {
        for n in [0, 1, 3, 4, 5, 8, 13, 64, 67] {
            let p0: Vec<f64> = field(n, 1).iter().map(|v| v.max(0.0)).collect();
            let t0: Vec<f32> = p0
                .iter()
                .zip(field(n, 2))
                .map(|(&p, v)| if p > 0.0 { v as f32 } else { 0.0 })
                .collect();
            let w0 = field(n, 3);
            let z = field(n, 4);
            let y = field(n, 5);
            let kt = field(n, 6);
            let mask: Vec<u8> = (0..n).map(|i| (i % 7 != 3) as u8).collect();
            let act: Vec<u8> = p0.iter().map(|&p| (p > 0.0) as u8).collect();
            let (approach, scale, zf) = (0.1, 1.3, -0.2);

            // Pass A.
            let (mut p, mut w, mut a, mut on) = (p0.clone(), w0.clone(), vec![9u8; n], [false]);
            let all = (&[true][..], &mut on[..], n.max(1));
            let got = rescale_on_z(&mut p, &z, &mut w, &mut a, all, (scale, zf), approach);
            let mut cells = vec![];
            for i in 0..n {
                let (pi, wi) = (p0[i] * scale, scale * w0[i] + zf * z[i]);
                assert_eq!((p[i], w[i], a[i]), (pi, wi, (pi > 0.0) as u8));
                let on = if pi > 0.0 { 1.0 } else { 0.0 };
                cells.push([on * (wi - approach), on]);
            }
            assert_eq!(
                bits(got),
                bits(in_lane_order(&cells, None)),
                "rescale, n = {n}"
            );
            assert_eq!(on[0], a.contains(&1), "rescale's row flag, n = {n}");

            // Pass B and the criterion.
            let mut q = vec![9.0; n];
            let got = residual(&p0, &w0, &mask, &mut q, (&[true], n.max(1)), approach);
            let crit = criterion_terms(&p0, &w0, &mask, approach);
            let mut cells = vec![];
            for i in 0..n {
                let g = mask[i] as f64 * (w0[i] - approach);
                let on = if p0[i] > 0.0 { 1.0 } else { 0.0 };
                assert_eq!(q[i], on * g);
                cells.push([p0[i] * g.abs(), p0[i], -g, on * g]);
            }
            let want = in_lane_order(&cells, Some(2));
            assert_eq!(bits(got), bits(want), "residual, n = {n}");
            assert_eq!(
                bits(crit),
                bits([want[0], want[1], want[2]]),
                "criterion, n = {n}"
            );

            // After M.
            let mut yp: Vec<f32> = field(n, 7).iter().map(|&v| v as f32).collect();
            let yp0 = yp.clone();
            let ys = &mut 1.0;
            let got = preconditioned(&act, &w0, (&mut yp, ys), &y, (&[true], n.max(1)), approach);
            let cells: Vec<[f64; 3]> = (0..n)
                .map(|i| {
                    let on = act[i] as f64;
                    let q = on * (w0[i] - approach);
                    [on * y[i], q * y[i], q * yp0[i] as f64]
                })
                .collect();
            let y32: Vec<f32> = y.iter().map(|&v| v as f32).collect();
            assert_eq!(yp, y32);
            assert_eq!(
                bits(got),
                bits(in_lane_order(&cells, None)),
                "after M, n = {n}"
            );

            // The direction.
            let d = Direction {
                ybar: 0.05,
                tbar: -0.03,
                beta: 0.7,
                approach,
            };
            let (mut t, mut yp, mut out) = (t0.clone(), yp0.clone(), vec![9.0; n]);
            let rows = (&[true][..], &[false][..], n.max(1));
            let (ts, ys) = (&mut 1.0, &mut 1.0);
            let got = direction(&act, &w0, (&mut t, ts), (&mut yp, ys), &mut out, rows, d);
            let mut cells = vec![];
            for i in 0..n {
                let on = act[i] as f64;
                let yi = on * (yp0[i] as f64 - d.ybar);
                let ti = (yi + on * d.beta * (t0[i] as f64 - d.tbar)) as f32;
                assert_eq!((yp[i], t[i], out[i]), (yi as f32, ti, ti as f64));
                cells.push([ti as f64 * (w0[i] - approach)]);
            }
            assert_eq!(
                bits(got),
                bits(in_lane_order(&cells, None)),
                "direction, n = {n}"
            );

            // Pass D.
            let u = Update {
                tau: 0.4,
                approach,
                step: 2.0,
            };
            let (mut p, mut w, mut changes, mut with_p) = (p0.clone(), w0.clone(), vec![], [false]);
            let (flag, list) = ((&mut with_p[..], n.max(1)), (&mut changes, 7, n + 1));
            let got = update(&mut p, (&t0, 1.0), list, (&mut w, &kt), &mask, flag, u);
            let (mut listed, mut cells) = (vec![], vec![]);
            for i in 0..n {
                let g = w0[i] - approach;
                let raw = p0[i] - u.tau * t0[i] as f64;
                let pi = if p0[i] > 0.0 {
                    raw.max(0.0)
                } else if mask[i] > 0 && g < 0.0 {
                    -u.step * g
                } else {
                    0.0
                };
                assert_eq!(p[i], pi);
                listed.extend((pi != raw).then_some((7 + i, pi - raw)));
                assert_eq!(w[i], w0[i] - u.tau * kt[i]);
                let changed = if pi != raw { 1.0 } else { 0.0 };
                cells.push([pi, changed, if pi > 0.0 { t0[i] as f64 } else { 0.0 }]);
            }
            assert_eq!(
                bits(got),
                bits(in_lane_order(&cells, None)),
                "update, n = {n}"
            );
            assert_eq!(changes, listed, "update's changes, n = {n}");
            assert_eq!(
                with_p[0],
                p.iter().any(|&v| v > 0.0),
                "update's flag, n = {n}"
            );

            // Pass D without K t: the same pressures and sums, p also in the output.
            // (The flag starts wrong, but for n = 0: no row.)
            let (mut q, mut out, mut again_p) = (p0.clone(), vec![9.0; n], [with_p[0] ^ (n > 0)]);
            let flag = (&mut again_p[..], n.max(1));
            let again = advance(&mut q, (&t0, 1.0), &w0, &mask, &mut out, flag, u);
            assert_eq!(again_p, with_p, "advance's flag, n = {n}");
            assert_eq!((&q, &out), (&p, &p), "advance, n = {n}");
            assert_eq!(bits(again), bits(got), "advance, n = {n}");
        }
    }

    /// The passes on scaled directions (16-bit cells, one scale per chunk) against
    /// their cell-by-cell form: M's output stored at the scale of its largest value in
    /// the marked rows, the new y and t at the scales of theirs, everything read back
    /// as stored (K's input, the sums, the update); rows of 7 cells (blocks and tails
    /// across rows), unmarked rows left alone.
    #[test]
    fn scaled_passes_match_their_cell_by_cell_form() {
        let (width, on, was) = (
            7,
            [true, false, true, true, false],
            [false, true, false, true, false],
        );
        let n = width * on.len();
        let row = |i: usize| i / width;
        let act: Vec<u8> = field(n, 1)
            .iter()
            .enumerate()
            .map(|(i, &v)| (v > 0.0 && on[row(i)]) as u8)
            .collect();
        let (w0, approach) = (field(n, 3), 0.1);
        // M's output, large in one unmarked row (which must not set the scale).
        let y: Vec<f64> = (0..n)
            .map(|i| field(n, 5)[i] * if on[row(i)] { 3.0 } else { 1e6 })
            .collect();
        let (y_old, t_old) = (0.125, 2.0f64.powi(-12));
        let yp0: Vec<i16> = field(n, 7)
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                if on[row(i)] || was[row(i)] {
                    (v * 9000.0) as i16
                } else {
                    0
                }
            })
            .collect();
        let t0: Vec<i16> = field(n, 2)
            .iter()
            .enumerate()
            .map(|(i, &v)| if was[row(i)] { (v * 12000.0) as i16 } else { 0 })
            .collect();

        // After M.
        let (mut yp, mut ys) = (yp0.clone(), y_old);
        let got = preconditioned(&act, &w0, (&mut yp, &mut ys), &y, (&on, width), approach);
        let largest = (0..n)
            .filter(|&i| on[row(i)])
            .fold(0.0f64, |m, i| m.max(y[i].abs()));
        assert_eq!(ys, scale_for(largest));
        // The stretches of marked rows: row 0, rows 2-3.
        let stretch = |i: usize| if row(i) == 0 { 0 } else { 1 };
        let mut cells = vec![vec![], vec![]];
        for i in (0..n).filter(|&i| on[row(i)]) {
            let a = act[i] as f64;
            let q = a * (w0[i] - approach);
            cells[stretch(i)].push([a * y[i], q * y[i], q * yp0[i] as f64 * y_old]);
            assert_eq!(yp[i], i16::put(y[i], 1.0 / ys), "cell {i}");
            assert!((yp[i].get(ys) - y[i]).abs() <= 0.5 * ys, "cell {i}");
        }
        for i in (0..n).filter(|&i| !on[row(i)]) {
            assert_eq!(yp[i], yp0[i], "cell {i}");
        }
        assert_eq!(bits(got), bits(in_stretches(&cells)), "after M");

        // The direction: new scales from the new values, then the values as stored.
        let d = Direction {
            ybar: 0.05,
            tbar: -0.03,
            beta: 0.7,
            approach,
        };
        let (mut t, mut ts, mut yq, mut ys2, mut out) =
            (t0.clone(), t_old, yp.clone(), ys, vec![9.0; n]);
        let got = direction(
            &act,
            &w0,
            (&mut t, &mut ts),
            (&mut yq, &mut ys2),
            &mut out,
            (&on, &was, width),
            d,
        );
        let live = |i: usize| on[row(i)] || was[row(i)];
        let new = |i: usize| {
            let a = act[i] as f64;
            let yi = a * (yp[i] as f64 * ys - d.ybar);
            (yi, yi + a * d.beta * (t0[i] as f64 * t_old - d.tbar))
        };
        let (ym, tm) = (0..n)
            .filter(|&i| live(i))
            .fold((0.0f64, 0.0f64), |(a, b), i| {
                let (yi, ti) = new(i);
                (a.max(yi.abs()), b.max(ti.abs()))
            });
        assert_eq!((ys2, ts), (scale_for(ym), scale_for(tm)));
        // The live rows: 0-3, one stretch.
        let mut cells = vec![];
        for i in 0..n {
            if !live(i) {
                assert_eq!((t[i], yq[i], out[i]), (t0[i], yp[i], 0.0), "cell {i}");
                continue;
            }
            let (yi, ti) = new(i);
            assert_eq!(
                (yq[i], t[i]),
                (i16::put(yi, 1.0 / ys2), i16::put(ti, 1.0 / ts)),
                "cell {i}"
            );
            assert_eq!(out[i], t[i] as f64 * ts, "cell {i}");
            assert!((out[i] - ti).abs() <= 0.5 * ts, "cell {i}");
            cells.push([out[i] * (w0[i] - approach)]);
        }
        assert_eq!(bits(got), bits(in_stretches(&[cells])), "direction");
    }

    /// Pass D and its form without K t on scaled directions: the same as on the values
    /// they stand for (exact in single precision: 15 bits times a power of two).
    #[test]
    fn scaled_updates_read_t_as_stored() {
        type Out = ([u64; 3], Vec<f64>, Vec<f64>, Vec<(usize, f64)>, [bool; 2]);
        fn run<C: Cell>(t: (&[C], f64), (p0, w0, kt): (&[f64], &[f64], &[f64]), u: Update) -> Out {
            let (mut p, mut w, mut changes, mut with_p) =
                (p0.to_vec(), w0.to_vec(), vec![], [false; 2]);
            let (list, mask) = ((&mut changes, 0, p0.len() + 1), vec![1u8; p0.len()]);
            let got = update(&mut p, t, list, (&mut w, kt), &mask, (&mut with_p, 19), u);
            (bits(got), p, w, changes, with_p)
        }
        let n = 37;
        let (w0, kt, ts) = (field(n, 3), field(n, 6), 2.0f64.powi(-9));
        let p0: Vec<f64> = field(n, 8).iter().map(|v| v.max(0.0)).collect();
        let t: Vec<i16> = field(n, 2).iter().map(|&v| (v * 12000.0) as i16).collect();
        let t32: Vec<f32> = t.iter().map(|&v| (v as f64 * ts) as f32).collect();
        let u = Update {
            tau: 0.4,
            approach: 0.1,
            step: 2.0,
        };
        let got = run((&t, ts), (&p0, &w0, &kt), u);
        assert_eq!(got, run((&t32, 1.0), (&p0, &w0, &kt), u));
        assert!(got.3.len() > 2 && got.1.iter().any(|&v| v > 0.0));
        let (mut q, mut vals, mut with_q, mask) =
            (p0.clone(), vec![9.0; n], [false; 2], vec![1u8; n]);
        let again = advance(
            &mut q,
            (&t, ts),
            &w0,
            &mask,
            &mut vals,
            (&mut with_q, 19),
            u,
        );
        assert_eq!(
            (bits(again), &q, &vals, with_q),
            (got.0, &got.1, &got.1, got.4)
        );
    }
}
