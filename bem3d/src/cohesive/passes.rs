//! The per-cell passes of the cohesive solve's projected conjugate gradient, over chunks
//! of cells on the pool, summed in chunk order (as the adhesive rounds' passes, whose
//! chunking and `dot` they share): the same bits whatever the number of threads. The
//! gap `g = u + z - d` is recomputed where a pass needs it, not stored.

use crate::adhesion::passes::{max, CHUNK};
use rayon::prelude::*;

/// What a pass reads of the state: the cohesive set, the bounds, `z`, `u` and the
/// approach.
pub(super) struct Cells<'a> {
    pub cohesive: &'a [bool],
    pub bound: &'a [f64],
    pub z: &'a [f64],
    pub u: &'a [f64],
    pub d: f64,
}

/// The free cells (on the set, above their bound or at it and penetrating) into `free`,
/// `y = g` on them (0 elsewhere). Returns the criterion's largest term (`|g|` on a free
/// cell, the penetration on a bound one) and whether `free` equals `old`.
pub(super) fn free_set(
    c: &Cells,
    p: &[f64],
    old: &[bool],
    free: &mut [bool],
    y: &mut [f64],
) -> (f64, bool) {
    let parts: Vec<(f64, bool)> = free
        .par_chunks_mut(CHUNK)
        .zip(y.par_chunks_mut(CHUNK))
        .enumerate()
        .map(|(k, (free, y))| {
            let lo = k * CHUNK;
            let (mut worst, mut same) = (0.0f64, true);
            for (j, (f, y)) in free.iter_mut().zip(y.iter_mut()).enumerate() {
                let i = lo + j;
                let g = c.u[i] + c.z[i] - c.d;
                *f = c.cohesive[i] && (p[i] > c.bound[i] || g < 0.0);
                if *f {
                    worst = max(worst, g.abs());
                } else if c.cohesive[i] {
                    worst = max(worst, (-g).max(0.0));
                }
                *y = if *f { g } else { 0.0 };
                same &= old[i] == *f;
            }
            (worst, same)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, true), |(w, s), (pw, ps)| (max(w, pw), s && ps))
}

/// `y` zeroed off the free cells; returns `sum g y`.
pub(super) fn restrict(c: &Cells, free: &[bool], y: &mut [f64]) -> f64 {
    let parts: Vec<f64> = y
        .par_chunks_mut(CHUNK)
        .enumerate()
        .map(|(k, y)| {
            let lo = k * CHUNK;
            let mut s = 0.0;
            for (j, y) in y.iter_mut().enumerate() {
                let i = lo + j;
                if !free[i] {
                    *y = 0.0;
                }
                s += (c.u[i] + c.z[i] - c.d) * *y;
            }
            s
        })
        .collect();
    parts.into_iter().sum()
}

/// `p = max(p - tau t, bound)` on the free cells.
/// Returns whether the bound cut any cell's step.
pub(super) fn project(free: &[bool], bound: &[f64], t: &[f64], tau: f64, p: &mut [f64]) -> bool {
    p.par_chunks_mut(CHUNK)
        .enumerate()
        .map(|(k, p)| {
            let lo = k * CHUNK;
            let mut cut = false;
            for (j, p) in p.iter_mut().enumerate() {
                let i = lo + j;
                if free[i] {
                    let step = *p - tau * t[i];
                    *p = step.max(bound[i]);
                    cut |= *p != step;
                }
            }
            cut
        })
        .reduce(|| false, |a, b| a || b)
}

/// `u -= tau kt` on every cell: `u = K p` after a step `-tau t` that no bound cut.
pub(super) fn follow(kt: &[f64], tau: f64, u: &mut [f64]) {
    u.par_chunks_mut(CHUNK).enumerate().for_each(|(k, u)| {
        let kt = &kt[k * CHUNK..k * CHUNK + u.len()];
        for (u, kt) in u.iter_mut().zip(kt) {
            *u -= tau * kt;
        }
    });
}

/// `t = y + beta t` on every cell.
pub(super) fn direction(y: &[f64], beta: f64, t: &mut [f64]) {
    t.par_chunks_mut(CHUNK).enumerate().for_each(|(k, t)| {
        let y = &y[k * CHUNK..k * CHUNK + t.len()];
        for (t, y) in t.iter_mut().zip(y) {
            *t = y + beta * *t;
        }
    });
}
