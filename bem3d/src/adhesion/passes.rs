//! The per-cell passes of a round's conjugate gradient (`solve_set`), each one sweep over
//! the cells, run on the pool's threads in chunks of [`CHUNK`] cells whose results are
//! combined in chunk order: the sums do not depend on the number of threads.
//!
//! Between its transforms an iteration reads and writes eight vectors of the box, a
//! cost set by memory traffic: the passes are few (the update of `p` and `u` and the
//! next residual are one pass, as are the restriction of the preconditioned residual
//! and the new direction) and use every thread of the pool, which would otherwise wait
//! for the next transform (measurements: bench/HISTORY.md).

use crate::kit::chunks::{max, CHUNK};
use rayon::prelude::*;

/// The residual of a round on its set: `r = d - u - z` on the set (0 off it), `y = r`,
/// after the update `p += alpha t`, `u += alpha kt` when `alpha` is given. Returns the
/// largest `|r|` and the largest `|u|` on the set.
#[allow(clippy::too_many_arguments)]
pub(super) fn residual(
    on: &[bool],
    z: &[f64],
    p: &mut [f64],
    u: &mut [f64],
    step: Option<(f64, &[f64], &[f64])>,
    d: f64,
    r: &mut [f64],
    y: &mut [f64],
) -> (f64, f64) {
    let n = on.len();
    let (t, kt, alpha) = match step {
        Some((alpha, t, kt)) => (t, kt, alpha),
        None => (&[][..], &[][..], 0.0),
    };
    let moves = step.is_some();
    let parts: Vec<(f64, f64)> = p[..n]
        .par_chunks_mut(CHUNK)
        .zip(u[..n].par_chunks_mut(CHUNK))
        .zip(r[..n].par_chunks_mut(CHUNK))
        .zip(y[..n].par_chunks_mut(CHUNK))
        .enumerate()
        .map(|(k, (((p, u), r), y))| {
            let lo = k * CHUNK;
            let (on, z) = (&on[lo..lo + p.len()], &z[lo..lo + p.len()]);
            if moves {
                let (t, kt) = (&t[lo..lo + p.len()], &kt[lo..lo + p.len()]);
                for i in 0..p.len() {
                    p[i] += alpha * t[i];
                    u[i] += alpha * kt[i];
                }
            }
            let (mut worst, mut largest) = (0.0f64, 0.0f64);
            for i in 0..p.len() {
                let v = if on[i] {
                    let v = d - u[i] - z[i];
                    worst = max(worst, v.abs());
                    largest = max(largest, u[i].abs());
                    v
                } else {
                    0.0
                };
                r[i] = v;
                y[i] = v;
            }
            (worst, largest)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0), |(a, b), (w, l)| (max(a, w), max(b, l)))
}

/// `p += alpha t`, `u += alpha kt`.
pub(super) fn advance(p: &mut [f64], u: &mut [f64], alpha: f64, t: &[f64], kt: &[f64]) {
    let n = t.len();
    p[..n]
        .par_chunks_mut(CHUNK)
        .zip(u[..n].par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(k, (p, u))| {
            let lo = k * CHUNK;
            for i in 0..p.len() {
                p[i] += alpha * t[lo + i];
                u[i] += alpha * kt[lo + i];
            }
        });
}

/// The sums on the set of `r y`, `y` and `r` (the restriction's terms).
pub(super) fn products(on: &[bool], r: &[f64], y: &[f64]) -> (f64, f64, f64) {
    let parts: Vec<(f64, f64, f64)> = on
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(k, on)| {
            let lo = k * CHUNK;
            let (r, y) = (&r[lo..lo + on.len()], &y[lo..lo + on.len()]);
            let (mut ry, mut sy, mut sr) = (0.0, 0.0, 0.0);
            for i in 0..on.len() {
                if on[i] {
                    ry += r[i] * y[i];
                    sy += y[i];
                    sr += r[i];
                }
            }
            (ry, sy, sr)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0, 0.0), |(a, b, c), (x, y, z)| {
            (a + x, b + y, c + z)
        })
}

/// The new direction `t = (y - mean) + beta t` on the set, 0 off it.
pub(super) fn direction(on: &[bool], y: &[f64], mean: f64, beta: f64, t: &mut [f64]) {
    let n = on.len();
    t[..n].par_chunks_mut(CHUNK).enumerate().for_each(|(k, t)| {
        let lo = k * CHUNK;
        let (on, y) = (&on[lo..lo + t.len()], &y[lo..lo + t.len()]);
        for i in 0..t.len() {
            t[i] = if on[i] {
                (y[i] - mean) + beta * t[i]
            } else {
                0.0
            };
        }
    });
}
