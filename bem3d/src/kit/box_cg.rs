//! The projected conjugate gradient of the families: Polonsky & Keer's iteration for the
//! pressures `p` of a set of cells under a prescribed approach `d`, each cell's pressure
//! held in its box `lo_i <= p_i <= hi_i`. It minimises the convex energy
//! `p.K p / 2 + p.(z - d)` over the boxes, whose optimality conditions per cell of the set
//! are, with the gap `g = u + z - d` and `u = K p`:
//!
//! - `lo < p < hi`: `g = 0` (in contact, the pressure free);
//! - `p = lo`: `g >= 0` (held at the lower bound: out of contact, or a cohesive tension);
//! - `p = hi`: `g <= 0` (held at the upper bound: a saturated, plastic cell).
//!
//! A family is a choice of boxes and of the set: the non-adhesive contact has `[0, inf)`,
//! the Maugis-Dugdale zone `[-sigma0, inf)`, the exponential law's tangent problem
//! `[-sigma(g_last), inf)`, the elastic-perfectly plastic contact `[0, H]`; cells off the
//! set keep `p = 0` and are not constrained.
//!
//! **Iteration.** The free cells are those of the set inside their box, or at a bound with
//! the gap pulling them inside (`p = lo, g < 0` or `p = hi, g > 0`). The residual is the
//! gap on the free cells; the direction is `t = y + beta t` on them (0 off them), with `y`
//! the preconditioned residual (the operator's approximate inverse,
//! [`Preconditioner::precondition`]) and Polak-Ribiere+'s
//! `beta = max(0, <r, y - y_prev> / <r_prev, y_prev>)`, as the normal solver's
//! (`solver` module docs): conjugate while the free set holds, a near-restart by itself
//! where it changes; a restart (`t = y`) where `t` would not descend. Restarting at every
//! change of the free set instead (Polonsky & Keer) made the plastic benchmark's 512^2
//! steps take 49.8 iterations against 33.8. The step is the exact one along `t`
//! (`<r, t> / <t, K t>`), then every free cell is clamped into its box. Where no bound
//! cut the step, `u = K p` follows by `-tau K t` without a transform (afresh every
//! [`REFRESH`] such steps and before a stop is accepted). A direction
//! without curvature (the periodic half-space's uniform mode, which K does not see:
//! a flat periodic face under a uniform tension) is followed to the first bound it
//! meets, and is an error where it meets none (the energy falls without bound).
//!
//! **Holding the force.** Where the sum of the pressures over the set is held instead of
//! the approach (a prescribed force), the approach is the multiplier of that constraint:
//! at the solution every cell strictly inside its box has the same `u + z`, which is
//! `d`. Each iteration reads `d` as the mean of `u + z` over those cells (for the free
//! set and the criterion); the residual is the gap less its mean over the free cells
//! (the gradient within the sum's hyperplane, so that the preconditioned direction
//! descends), and the direction is taken less its mean over the free cells, so that a
//! step keeps the sum; where a bound cut the step, the cells the step moved are shifted
//! by one amount, each clamped into its box, until the sum is met again (the force's
//! analogue of Polonsky & Keer's rescaling, which a box's upper bound does not allow).
//! Cells at a bound whose preconditioned step points out of their box can still hold
//! this iteration in a cycle near saturation: a solve that does not halve its criterion
//! in [`STALL`] iterations stops as [`STALLED`], and its caller holds the approach
//! instead.
//!
//! **Criterion** (stated exactly): the largest violation of the conditions above over the
//! set, `|g|` on a free cell, `max(-g, 0)` at the lower bound, `max(g, 0)` at the upper,
//! over the caller's length scale, at most `tolerance`, evaluated on `u = K p` itself.
//!
//! The passes run in chunks on the pool (`kit::chunks`): the same bits whatever the
//! number of threads.

use super::chunks::{dot, max, CHUNK};
use crate::error::{BemError, Result};
use crate::operator::Preconditioner;
use crate::solver::Interrupt;
use rayon::prelude::*;

/// Iterations between computations of `K p` afresh while its running update is used.
pub(crate) const REFRESH: usize = 50;

/// Iterations under a held sum without halving the criterion after which a solve stops as
/// [`STALLED`]: near saturation, cells at a bound whose preconditioned step points out
/// of their box can hold the iteration in a cycle (seen on rough faces at a plasticity
/// index of 3); the caller then holds the approach instead.
pub(crate) const STALL: usize = 400;

/// The reason of a held sum's stalled solve.
pub(crate) const STALLED: &str = "the iteration holding the force stalled";

/// A direction counts as without curvature where `<t, K t>` lies below this fraction of
/// `<r, M r>` (the two are of one size when M approximates K's inverse).
const NO_CURVATURE: f64 = 1e-12;

/// One side of the cells' boxes: one value for every cell, or a value per cell.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Bound<'a> {
    Uniform(f64),
    Cells(&'a [f64]),
}

impl Bound<'_> {
    #[inline(always)]
    pub(crate) fn at(&self, i: usize) -> f64 {
        match self {
            Bound::Uniform(v) => *v,
            Bound::Cells(v) => v[i],
        }
    }
}

/// What a solve holds fixed: the approach, or the sum of the pressures over the set (a
/// force over the cell area), whose multiplier is then the approach.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Hold {
    /// The approach `d` [length].
    Approach(f64),
    /// `sum p` over the set [stress]; `start` is the approach to read the gaps at while
    /// no cell lies inside its box [length].
    Sum { sum: f64, start: f64 },
}

/// The problem of one solve: the set, its boxes, the surface and what is held, and how
/// to stop.
pub(crate) struct BoxProblem<'a> {
    /// The cells that take part (the others keep `p = 0`).
    pub set: &'a [bool],
    pub lo: Bound<'a>,
    pub hi: Bound<'a>,
    /// `max(h) - h` [length].
    pub z: &'a [f64],
    pub hold: Hold,
    /// The criterion's length scale [length].
    pub scale: f64,
    pub tolerance: f64,
    pub max_iterations: usize,
    /// The family's name in errors.
    pub what: &'static str,
    pub interrupt: Option<&'a Interrupt>,
}

/// What a finished solve reached.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reached {
    pub iterations: usize,
    /// The criterion at the stop (at most the tolerance).
    pub residual: f64,
    /// The approach: the one held, or the multiplier of the held sum [length].
    pub approach: f64,
}

/// The conjugate gradient's vectors, asked for once per family and reused.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    t: Vec<f64>,
    kt: Vec<f64>,
    y: Vec<f64>,
    y_prev: Vec<f64>,
    free: Vec<bool>,
}

impl Scratch {
    fn fit(&mut self, n: usize) {
        for v in [&mut self.t, &mut self.kt, &mut self.y, &mut self.y_prev] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.free.clear();
        self.free.resize(n, false);
    }
}

/// Solves the problem from the pressures `p` (inside their boxes on the set, 0 off it);
/// `u` is set to `K p` and kept so. Under [`Hold::Sum`] the pressures are first brought
/// to the sum (module docs). Returns the iterations, the criterion and the approach
/// reached, or [`BemError::Breakdown`] with what it reached.
pub(crate) fn solve<O: Preconditioner>(
    op: &mut O,
    pb: &BoxProblem,
    p: &mut [f64],
    u: &mut [f64],
    w: &mut Scratch,
) -> Result<Reached> {
    let n = pb.z.len();
    w.fit(n);
    let mut rho_old = 0.0;
    let mut d = match pb.hold {
        Hold::Approach(d) => d,
        Hold::Sum { sum, start } => {
            meet_sum(pb, p, sum, None)?;
            start
        }
    };
    op.apply(p, u);
    // Iterations since `u` was last computed as `K p` (0: it is `K p` itself).
    let mut followed = 0;
    let mut residual = f64::NAN;
    // Under a held sum: the best criterion so far and when it was reached.
    let mut best = (f64::INFINITY, 0);
    for it in 0..pb.max_iterations {
        if let Hold::Sum { .. } = pb.hold {
            d = multiplier(pb, p, u).unwrap_or(d);
        }
        let (worst, free_g, count) = free_set(pb, d, p, u, &mut w.free, &mut w.y);
        residual = worst / pb.scale;
        if residual <= pb.tolerance {
            if followed == 0 {
                return Ok(Reached {
                    iterations: it,
                    residual,
                    approach: d,
                });
            }
            // Stop only on `u = K p` itself, not on its running update.
            op.apply(p, u);
            followed = 0;
            continue;
        }
        if pb.interrupt.is_some_and(Interrupt::is_set) {
            return Err(BemError::Interrupted {
                what: pb.what,
                iterations: it,
            });
        }
        if let Hold::Sum { .. } = pb.hold {
            if residual < 0.5 * best.0 {
                best = (residual, it);
            } else if it - best.1 > STALL {
                return Err(BemError::Breakdown {
                    what: pb.what,
                    iterations: it,
                    residual,
                    reason: STALLED,
                });
            }
        }
        // Under a held sum the residual is the gap less its mean over the free cells (the
        // gradient within the sum's hyperplane): then `<r, M r> > 0` and the direction
        // descends whatever the multiplier's value. The residual r is in `y` then.
        let held_sum = matches!(pb.hold, Hold::Sum { .. });
        let mean = |v: f64| {
            if held_sum && count > 0 {
                v / count as f64
            } else {
                0.0
            }
        };
        let r_y_prev = residual_pass(&w.free, mean(free_g), &mut w.y, &w.y_prev);
        op.precondition(&mut w.y);
        let sums = Sums::of(pb, d, u, &w.free, &w.y, &w.t);
        // `y` and `t` less their means over the free cells (under a held sum, so that a
        // step keeps it), zero off them; `rho = <r, y>`, and `<r, t>` for the new `t`.
        let (mean_y, mean_t) = (mean(sums.y), mean(sums.t));
        let rho = sums.gy - mean_y * sums.g;
        let mut beta = if rho_old > 0.0 {
            ((rho - r_y_prev) / rho_old).max(0.0)
        } else {
            0.0
        };
        let mut slope = rho + beta * (sums.gt - mean_t * sums.g);
        // A restart (`t = y`) where the conjugate direction does not descend.
        if slope.is_nan() || slope <= 0.0 {
            beta = 0.0;
            slope = rho;
        }
        rho_old = rho;
        direction(&w.free, (mean_y, mean_t), beta, &mut w.y, &mut w.t);
        std::mem::swap(&mut w.y, &mut w.y_prev);
        op.apply(&w.t, &mut w.kt);
        let curvature = dot(&w.t, &w.kt);
        let tau = if curvature > NO_CURVATURE * slope && slope.is_finite() {
            slope / curvature
        } else {
            match to_first_bound(pb, &w.free, &w.t, p) {
                Some(tau) if slope > 0.0 => tau,
                _ => {
                    return Err(BemError::Breakdown {
                        what: pb.what,
                        iterations: it,
                        residual,
                        reason: "a direction without curvature that meets no bound",
                    })
                }
            }
        };
        let mut cut = project(pb, &w.free, &w.t, tau, p);
        // A step along a direction of zero sum keeps the sum but where a bound cut it,
        // and to rounding: the sum is met again then and with every fresh `K p`.
        if let Hold::Sum { sum, .. } = pb.hold {
            if cut || followed + 1 >= REFRESH {
                meet_sum(pb, p, sum, Some(&w.free))?;
                cut = true;
            }
        }
        // A step no bound cut moves K p by -tau K t: no transform (afresh every
        // `REFRESH` iterations against rounding).
        if cut || followed + 1 >= REFRESH {
            op.apply(p, u);
            followed = 0;
        } else {
            follow(&w.kt, tau, u);
            followed += 1;
        }
    }
    Err(BemError::Breakdown {
        what: pb.what,
        iterations: pb.max_iterations,
        residual,
        reason: "the solve did not converge within the iteration limit",
    })
}

/// The approach as the multiplier of the held sum: the mean of `u + z` over the cells of
/// the set strictly inside their boxes (their gaps vanish at the solution); without
/// such a cell, the largest `u + z` of the cells at the upper bound (so that none of
/// them is pushed further). `None` where neither exists.
fn multiplier(pb: &BoxProblem, p: &[f64], u: &[f64]) -> Option<f64> {
    let parts: Vec<(f64, usize, f64)> = p
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(k, p)| {
            let first = k * CHUNK;
            let (mut sum, mut count, mut top) = (0.0, 0, f64::NEG_INFINITY);
            for (j, &pj) in p.iter().enumerate() {
                let i = first + j;
                if !pb.set[i] {
                    continue;
                }
                let level = u[i] + pb.z[i];
                if pj > pb.lo.at(i) && pj < pb.hi.at(i) {
                    sum += level;
                    count += 1;
                } else if pj >= pb.hi.at(i) {
                    top = max(top, level);
                }
            }
            (sum, count, top)
        })
        .collect();
    let (sum, count, top) = parts
        .into_iter()
        .fold((0.0, 0, f64::NEG_INFINITY), |(s, c, t), (ps, pc, pt)| {
            (s + ps, c + pc, max(t, pt))
        });
    if count > 0 {
        Some(sum / count as f64)
    } else {
        top.is_finite().then_some(top)
    }
}

/// Which cells a shift moves.
type Eligible<'a> = &'a (dyn Fn(usize) -> bool + Sync);

/// The cells a shift moves, gathered in cell order (index, pressure, box), and the sum of
/// the set's other pressures: the sum under a shift is then a pass over these alone.
#[derive(Default)]
struct Movable {
    cells: Vec<(usize, f64, f64, f64)>,
    fixed: f64,
}

impl Movable {
    /// The eligible cells of the set and the sum of the others (both in chunk order).
    fn gather(pb: &BoxProblem, p: &[f64], eligible: Eligible) -> Self {
        type Part = (Vec<(usize, f64, f64, f64)>, f64);
        let parts: Vec<Part> = p
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(k, p)| {
                let first = k * CHUNK;
                let (mut cells, mut fixed) = (vec![], 0.0);
                for (j, &pj) in p.iter().enumerate() {
                    let i = first + j;
                    if !pb.set[i] {
                        continue;
                    }
                    if eligible(i) {
                        cells.push((i, pj, pb.lo.at(i), pb.hi.at(i)));
                    } else {
                        fixed += pj;
                    }
                }
                (cells, fixed)
            })
            .collect();
        let mut out = Self::default();
        for (cells, fixed) in parts {
            out.cells.extend(cells);
            out.fixed += fixed;
        }
        out
    }

    /// The set's sum of pressures with these cells shifted by `mu` and clamped into
    /// their boxes, and how many of them the shift leaves strictly inside.
    fn shifted_sum(&self, mu: f64) -> (f64, usize) {
        let parts: Vec<(f64, usize)> = self
            .cells
            .par_chunks(CHUNK)
            .map(|cells| {
                let (mut s, mut slope) = (0.0, 0);
                for &(_, pj, lo, hi) in cells {
                    let v = pj + mu;
                    slope += usize::from(v > lo && v < hi);
                    s += v.max(lo).min(hi);
                }
                (s, slope)
            })
            .collect();
        parts
            .into_iter()
            .fold((self.fixed, 0), |(s, c), (ps, pc)| (s + ps, c + pc))
    }
}

/// The set's pressures brought to `sum` by one shift `mu` of the cells that `moved`
/// (the free cells of the step just taken: the shift completes the step's projection
/// onto the boxes and the sum) or, without a step, of the cells strictly inside their
/// boxes, each clamped into its box: the sum is continuous and non-decreasing in `mu`,
/// and its root is found by Newton's steps on its slope (the number of cells the shift
/// leaves inside) kept in a bracket, bisection where a step leaves it. Where those cells
/// cannot carry the sum (all would meet a bound first), every cell of the set is
/// shifted. The bracket is the widest box of the set (every box finite: the family that
/// holds a sum, the plastic one, has `[0, H]`) or else the sum's and the pressures' size.
/// The search runs on the gathered cells ([`Movable`]), not on the grid.
fn meet_sum(pb: &BoxProblem, p: &mut [f64], sum: f64, moved: Option<&[bool]>) -> Result<()> {
    let computed: Vec<bool>;
    let inside: &[bool] = match moved {
        Some(m) => m,
        None => {
            computed = (0..p.len())
                .map(|i| pb.set[i] && p[i] > pb.lo.at(i) && p[i] < pb.hi.at(i))
                .collect();
            &computed
        }
    };
    let widest = match (pb.lo, pb.hi) {
        (Bound::Uniform(lo), Bound::Uniform(hi)) => hi - lo,
        _ => (0..p.len())
            .filter(|&i| pb.set[i])
            .map(|i| pb.hi.at(i) - pb.lo.at(i))
            .fold(0.0, f64::max),
    };
    let span = if widest.is_finite() {
        widest
    } else {
        sum.abs() + p.iter().map(|v| v.abs()).sum::<f64>()
    };
    let carries = |m: &Movable| m.shifted_sum(-span).0 <= sum && sum <= m.shifted_sum(span).0;
    let mut movable = Movable::gather(pb, p, &|i| inside[i]);
    if !carries(&movable) {
        movable = Movable::gather(pb, p, &|_| true);
    }
    // The size of the sum's terms: the held sum, and the pressures of the cells that may
    // pull (a held sum near zero may balance large tensions and pressures).
    // (No pass over the cells where no bound lets a cell pull: the plastic hot path.)
    let may_pull = !matches!(pb.lo, Bound::Uniform(lo) if lo >= 0.0);
    let pulling = |i: usize| pb.set[i] && pb.lo.at(i) < 0.0;
    let size = sum.abs()
        + if may_pull {
            (0..p.len())
                .filter(|&i| pulling(i))
                .map(|i| p[i].abs())
                .sum::<f64>()
        } else {
            0.0
        };
    // Far above the rounding of a sum of cells (about 1e-16 of it per square root of
    // their number), far below the held force's use.
    let tol = 1e-13 * size.max(f64::MIN_POSITIVE);
    let (mut a, mut b) = (-span, span);
    let mut mu = 0.0;
    for _ in 0..200 {
        let (s, slope) = movable.shifted_sum(mu);
        let miss = s - sum;
        if miss.abs() <= tol || b - a <= f64::EPSILON * span {
            break;
        }
        if miss < 0.0 {
            a = mu;
        } else {
            b = mu;
        }
        let newton = mu - miss / slope as f64;
        mu = if slope > 0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
    }
    for &(i, pj, lo, hi) in &movable.cells {
        p[i] = (pj + mu).max(lo).min(hi);
    }
    let s = set_sum(pb, p);
    let miss = (s - sum).abs() / size.max(f64::MIN_POSITIVE);
    if miss > 1e-12 {
        return Err(BemError::Breakdown {
            what: pb.what,
            iterations: 0,
            residual: miss,
            reason: "the pressures could not be brought to the held force inside their boxes",
        });
    }
    Ok(())
}

/// The sum of the set's pressures (in chunk order).
fn set_sum(pb: &BoxProblem, p: &[f64]) -> f64 {
    let parts: Vec<f64> = p
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(k, p)| {
            let set = &pb.set[k * CHUNK..k * CHUNK + p.len()];
            p.iter()
                .zip(set)
                .filter(|(_, s)| **s)
                .map(|(v, _)| v)
                .sum::<f64>()
        })
        .collect();
    parts.into_iter().sum()
}

/// The free cells into `free`, `y = g` on them (0 elsewhere). Returns the criterion's
/// largest term, and the sum of `g` over the free cells and their number.
fn free_set(
    pb: &BoxProblem,
    d: f64,
    p: &[f64],
    u: &[f64],
    free: &mut [bool],
    y: &mut [f64],
) -> (f64, f64, usize) {
    let parts: Vec<(f64, f64, usize)> = free
        .par_chunks_mut(CHUNK)
        .zip(y.par_chunks_mut(CHUNK))
        .enumerate()
        .map(|(k, (free, y))| {
            let first = k * CHUNK;
            let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0);
            for (j, (f, y)) in free.iter_mut().zip(y.iter_mut()).enumerate() {
                let i = first + j;
                let g = u[i] + pb.z[i] - d;
                let (lo, hi) = (pb.lo.at(i), pb.hi.at(i));
                *f = pb.set[i] && (p[i] > lo || g < 0.0) && (p[i] < hi || g > 0.0);
                if *f {
                    worst = max(worst, g.abs());
                    sum += g;
                    count += 1;
                } else if pb.set[i] {
                    let off = if p[i] <= lo {
                        (-g).max(0.0)
                    } else {
                        g.max(0.0)
                    };
                    worst = max(worst, off);
                }
                *y = if *f { g } else { 0.0 };
            }
            (worst, sum, count)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0, 0), |(w, s, c), (pw, ps, pc)| {
            (max(w, pw), s + ps, c + pc)
        })
}

/// The residual: `y` less `mean` on the free cells (it is 0 off them). Returns
/// `<y, y_prev>` after.
fn residual_pass(free: &[bool], mean: f64, y: &mut [f64], y_prev: &[f64]) -> f64 {
    let parts: Vec<f64> = y
        .par_chunks_mut(CHUNK)
        .enumerate()
        .map(|(k, y)| {
            let first = k * CHUNK;
            let mut s = 0.0;
            for (j, y) in y.iter_mut().enumerate() {
                let i = first + j;
                if free[i] {
                    *y -= mean;
                }
                s += *y * y_prev[i];
            }
            s
        })
        .collect();
    parts.into_iter().sum()
}

/// Sums over the free cells of the preconditioned residual `y`, the last direction `t`
/// and the gap `g`: what the new direction and its step need, in one pass.
struct Sums {
    /// `sum y`, `sum t`, `sum g`, `sum g y`, `sum g t`.
    y: f64,
    t: f64,
    g: f64,
    gy: f64,
    gt: f64,
}

impl Sums {
    fn of(pb: &BoxProblem, d: f64, u: &[f64], free: &[bool], y: &[f64], t: &[f64]) -> Self {
        let parts: Vec<[f64; 5]> = y
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(k, y)| {
                let first = k * CHUNK;
                let mut s = [0.0; 5];
                for (j, &yi) in y.iter().enumerate() {
                    let i = first + j;
                    if free[i] {
                        let (g, ti) = (u[i] + pb.z[i] - d, t[i]);
                        s[0] += yi;
                        s[1] += ti;
                        s[2] += g;
                        s[3] += g * yi;
                        s[4] += g * ti;
                    }
                }
                s
            })
            .collect();
        let s = parts.into_iter().fold([0.0; 5], |mut a, p| {
            a.iter_mut().zip(p).for_each(|(a, p)| *a += p);
            a
        });
        Self {
            y: s[0],
            t: s[1],
            g: s[2],
            gy: s[3],
            gt: s[4],
        }
    }
}

/// The largest step along `-t` before a free cell meets a bound (`None`: it meets none).
fn to_first_bound(pb: &BoxProblem, free: &[bool], t: &[f64], p: &[f64]) -> Option<f64> {
    let tau = (0..p.len())
        .filter(|&i| free[i] && t[i] != 0.0)
        .map(|i| {
            if t[i] > 0.0 {
                (p[i] - pb.lo.at(i)) / t[i]
            } else {
                (pb.hi.at(i) - p[i]) / -t[i]
            }
        })
        .fold(f64::INFINITY, f64::min);
    tau.is_finite().then_some(tau.max(0.0))
}

/// `p = min(max(p - tau t, lo), hi)` on the free cells. Returns whether a bound cut any
/// cell's step.
fn project(pb: &BoxProblem, free: &[bool], t: &[f64], tau: f64, p: &mut [f64]) -> bool {
    p.par_chunks_mut(CHUNK)
        .enumerate()
        .map(|(k, p)| {
            let first = k * CHUNK;
            let mut cut = false;
            for (j, p) in p.iter_mut().enumerate() {
                let i = first + j;
                if free[i] {
                    let step = *p - tau * t[i];
                    *p = step.max(pb.lo.at(i)).min(pb.hi.at(i));
                    cut |= *p != step;
                }
            }
            cut
        })
        .reduce(|| false, |a, b| a || b)
}

/// `u -= tau kt` on every cell: `u = K p` after a step `-tau t` that no bound cut.
fn follow(kt: &[f64], tau: f64, u: &mut [f64]) {
    u.par_chunks_mut(CHUNK).enumerate().for_each(|(k, u)| {
        let kt = &kt[k * CHUNK..k * CHUNK + u.len()];
        for (u, kt) in u.iter_mut().zip(kt) {
            *u -= tau * kt;
        }
    });
}

/// On the free cells `y <- y - mean_y` and `t <- y + beta (t - mean_t)`; both 0 off them.
fn direction(free: &[bool], (mean_y, mean_t): (f64, f64), beta: f64, y: &mut [f64], t: &mut [f64]) {
    t.par_chunks_mut(CHUNK)
        .zip(y.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(k, (t, y))| {
            let free = &free[k * CHUNK..k * CHUNK + t.len()];
            for ((t, y), &f) in t.iter_mut().zip(y.iter_mut()).zip(free) {
                if f {
                    *y -= mean_y;
                    *t = *y + beta * (*t - mean_t);
                } else {
                    *y = 0.0;
                    *t = 0.0;
                }
            }
        });
}
