//! The projected, preconditioned conjugate-gradient iteration (solver module docs).

use super::fused::{
    apply_fused, energy_fused, finish_fused, load_fused, reduce, store_fused, sum_parts,
    with_scratch,
};
use super::convergence::STALL_ITERATIONS;
use super::{sweeps, ContactSolver, Solution, SolverOptions};
use crate::error::{BemError, Result};
use crate::fft::{copy_in, copy_out, ROWS_PER_CHUNK};
use crate::operator::{Compliance, Operand};
use rayon::prelude::*;

/// Largest contact set, as a fraction of the grid's cells, on which the iteration applies
/// M by its stencil on the contact cells instead of by transforms (module docs).
pub(super) const LOCAL_MAX_FRACTION: f64 = 0.02;

/// Residual below which the displacement `K p` is recomputed in double precision and
/// from then on carried along with K t in single precision only (module docs); before,
/// K's single-precision transforms ([`Operand::ComplianceSingle`]) serve every
/// application. Measured on the 512^2 benchmark surface at 1 % and 20 % contact: the
/// same iterations with 1e-3, 1e-4 and 1e-5 (1e-5 one more at 20 %), against 9 and 16
/// more with K p never recomputed in double precision before the final check.
const SINGLE_UNTIL: f64 = 1e-4;

/// Residual below which `K p` is recomputed in double precision once more (module
/// docs): the single-precision K t moves it by rounding of about 1e-6 of the
/// displacement's change since the last recomputation, which scales with the residual
/// then (1e-4: about 1e-10, at the tolerance; 1e-7: about 1e-13).
const REFRESH_AGAIN: f64 = 1e-7;

/// What pass A adds to `w` before use: point-load corrections (none: w is current), or
/// `z` (when `w` was just recomputed as `K p`).
pub(super) enum Refresh<'a> {
    Loads(&'a [(usize, f64)]),
    AddZ,
}

impl<K: Compliance> ContactSolver<K> {
    /// Pass A: brings `w` up to date (`refresh`, then the pending force rescale of p
    /// and K p), marks the contact set (p > 0) in `active` and its rows in `rows_on`, and
    /// sums `w - offset` and the cell count over it. p is read in the rows `rows_p`
    /// marks only.
    pub(super) fn pass_a(&mut self, p: &mut [f64], scale: f64, refresh: Refresh, offset: f64) -> [f64; 2] {
        let (nx, ch) = (self.op.nx(), self.chunk());
        let (loads, add_z) = match refresh {
            Refresh::Loads(l) => (l, 0.0),
            Refresh::AddZ => (&[][..], 1.0),
        };
        if !loads.is_empty() {
            self.op.add_point_loads(loads, &mut self.w);
        }
        // w = K p + z before, scale K p + z after (with add_z: w = K p before).
        let zf = 1.0 - scale * (1.0 - add_z);
        reduce(
            (
                p.par_chunks_mut(ch),
                self.z.par_chunks(ch),
                self.w.par_chunks_mut(ch),
                self.active.par_chunks_mut(ch),
                self.rows_p.par_chunks(ch / nx),
                self.rows_on.par_chunks_mut(ch / nx),
            ),
            |(p, z, w, act, with_p, on)| {
                sweeps::rescale(p, z, w, act, (with_p, on, nx), (scale, zf), offset)
            },
            None,
        )
    }

    /// The second half of a fresh `K p` (in `k_op`'s precision) whose input is loaded:
    /// K p into `w` (pass A then adds z).
    pub(super) fn finish_into_w(&mut self, k_op: Operand) {
        let fc = ROWS_PER_CHUNK * self.op.nx();
        finish_fused(
            &mut self.op,
            k_op,
            &mut self.fallback,
            self.w.par_chunks_mut(fc),
            copy_out,
            None,
        );
    }

    /// Reads the changes pass D wrote to `r` in the chunks whose sums (`parts`, per
    /// chunk: total, changed cells, ...) count any, appending them to `loads` when
    /// given, and sets them back to zero (r is zero between passes).
    pub(super) fn take_changes(&mut self, parts: &[[f64; 3]], mut loads: Option<&mut Vec<(usize, f64)>>) {
        let fc = ROWS_PER_CHUNK * self.op.nx();
        for (b, part) in parts.iter().enumerate() {
            if part[1] == 0.0 {
                continue;
            }
            let start = b * fc;
            let end = (start + fc).min(self.r.len());
            for (i, r) in self.r[start..end].iter_mut().enumerate() {
                if *r != 0.0 {
                    if let Some(l) = loads.as_deref_mut() {
                        l.push((start + i, *r));
                    }
                    *r = 0.0;
                }
            }
        }
    }

    /// The projected, preconditioned conjugate-gradient iteration from the pressure `p`
    /// (on the domain, meeting the load), under force control (`target_force`) or at
    /// the approach `fixed_approach`.
    pub(super) fn iterate(
        &mut self,
        mut p: Vec<f64>,
        target_force: Option<f64>,
        fixed_approach: f64,
        opts: &SolverOptions,
        warm_started: bool,
    ) -> Result<Solution> {
        let area = self.op.cell_area();
        let nm = self.domain_cells;
        let force_control = target_force.is_some();
        // <q, y> of the previous iteration (0: no direction yet).
        let mut gy_old = 0.0;
        // t and y_prev start at zero (y_prev is read before it is written; with beta = 0
        // its values do not matter). Written here, in parallel, each page of a fresh
        // buffer gets its own frame now: a page of `vec![0.0; n]` first read maps the
        // shared zero page, and its first write then copies it and flushes the other
        // threads' TLBs (measured: ~4 % of a two-thread solve at 1024^2).
        self.t
            .par_iter_mut()
            .zip(self.y_prev.par_iter_mut())
            .for_each(|(t, y)| {
                *t = 0.0;
                *y = 0.0;
            });
        self.rows_t.fill(false);
        self.rows_p.fill(true);
        // Sum of t over the contact set of the coming iteration (pass D).
        let mut t_on_set = 0.0;
        // K p carried along in single precision while the residual is above
        // SINGLE_UNTIL, where the operator rounds K so (its transforms; a dense
        // matrix's copy, whose K t alone is rounded, K p fresh in double precision).
        let mut single = self.op.rounds_single();
        let mut residual;
        // Residual below which K p is recomputed in double precision once more (-inf:
        // no more).
        let mut refresh_below = f64::NEG_INFINITY;
        // Pending factor of the load constraint: p and K p are rescaled lazily in pass A
        // (K is linear), saving a sweep.
        let mut scale = 1.0;
        let h_rms = self.h_rms;
        let limit = self.op.point_load_limit();
        // w = K p: pass A adds z.
        self.op.apply(&p, &mut self.w);
        let mut refresh_z = true;
        // Whether w holds K p + z recomputed from scratch (not updated).
        let mut exact = true;
        // Complete contact's floor (module docs): the criterion's best value so far (to a
        // factor 2) and the iterations since.
        let mut stall = (f64::INFINITY, 0usize);
        let mut loads = std::mem::take(&mut self.loads);
        let mut it = 0;
        let mut approach;
        // Cells the last update changed against p - tau t (a cold start changes many).
        let mut changed_last = if warm_started { 0.0 } else { f64::INFINITY };
        // Whether K is a transform whose inverse half an iteration can skip (module
        // docs); an operator applied as a whole would be applied twice.
        let skips = self.op.spectral(Operand::Compliance).is_some();
        loop {
            let refresh = if refresh_z {
                Refresh::AddZ
            } else {
                Refresh::Loads(&loads)
            };
            let [sum_g, nc] = self.pass_a(&mut p, scale, refresh, fixed_approach);
            refresh_z = false;
            loads.clear();
            scale = 1.0;
            // Force control: the approach is the mean gap over the contact set.
            let gbar = if force_control && nc > 0.0 {
                sum_g / nc
            } else {
                0.0
            };
            approach = fixed_approach + gbar;
            // Pass B, fused into M's row pass: the gap `g = w - approach` on the domain,
            // the criterion's terms (sum p |g|, sum p, max -g) and the residual
            // `q = [p > 0] g`, with its sum, as M's input.
            let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
            // M by its stencil on a small contact set (module docs) instead of its
            // transforms (the same chunks, the same sums).
            let local = nc <= self.local_max_fraction * self.op.cells() as f64
                && self.op.local_stiffness().is_some();
            let residual_of =
                |(p, w, m, on), q: &mut [f64]| sweeps::residual(p, w, m, q, (on, nx), approach);
            let chunks = (
                p.par_chunks(fc),
                self.w.par_chunks(fc),
                self.mask.par_chunks(fc),
                self.rows_on.par_chunks(ROWS_PER_CHUNK),
            );
            let parts = if local {
                // The stencil reads q from the gap and the contact set: the chunk's q
                // goes to a scratch buffer.
                chunks
                    .into_par_iter()
                    .map(|item| with_scratch(item.0.len(), |q| residual_of(item, q)))
                    .collect()
            } else {
                load_fused(
                    &mut self.op,
                    Operand::Preconditioner,
                    &mut self.fallback,
                    chunks,
                    residual_of,
                )
            };
            let [pg, ps, worst, sum_q] = sum_parts(&parts, Some(2));
            residual = (if ps > 0.0 { pg / (ps * h_rms) } else { 0.0 }).max(worst / h_rms);
            if !residual.is_finite() {
                return Err(BemError::Breakdown {
                    what: "contact solve",
                    iterations: it,
                    residual,
                    reason: "non-finite residual",
                });
            }
            if single && residual <= SINGLE_UNTIL || residual <= refresh_below {
                // K p in double precision from here on, from a fresh one (the direction
                // is kept), and once more below REFRESH_AGAIN.
                refresh_below = if single && residual > REFRESH_AGAIN {
                    REFRESH_AGAIN
                } else {
                    f64::NEG_INFINITY
                };
                single = false;
                self.op.apply(&p, &mut self.w);
                refresh_z = true;
                exact = true;
                continue;
            }
            if residual < 0.5 * stall.0 {
                stall = (residual, 0);
            } else {
                stall.1 += 1;
            }
            let tolerance = if nc as usize == self.domain_cells && stall.1 >= STALL_ITERATIONS {
                self.complete_contact_tolerance(opts.tolerance, ps)
            } else {
                opts.tolerance
            };
            if residual <= tolerance {
                if !exact {
                    // Confirm on a fresh K p (the direction is kept).
                    self.op.apply(&p, &mut self.w);
                    refresh_z = true;
                    exact = true;
                    continue;
                }
                // Converged when the duality gap is within the tolerance too (module
                // docs); it is at most twice the criterion, so this rarely iterates on.
                if self.certificate(&p, approach) <= tolerance {
                    self.loads = loads;
                    let mut sol = self.finish(p, approach, it, residual);
                    sol.warm_started = warm_started;
                    return Ok(sol);
                }
            }
            if it == opts.max_iterations {
                break;
            }
            if opts.interrupted() {
                return Err(BemError::Interrupted {
                    what: "contact solve",
                    iterations: it,
                });
            }
            it += 1;
            // Preconditioned residual y = M q, with the sums of the projected
            // y = [p > 0] (M q - ybar), ybar its contact mean under force control (the
            // direction keeps the total force); y replaces y_prev once read.
            let chunks = (
                self.active.par_chunks(fc),
                self.w.par_chunks(fc),
                self.y_prev.par_chunks_mut(fc),
                self.rows_on.par_chunks(ROWS_PER_CHUNK),
            );
            let sums_of = |(act, w, y_prev, on), y: &[f64]| {
                sweeps::preconditioned(act, w, y_prev, y, (on, nx), approach)
            };
            // (The stencil is made only once a set is small.)
            let stencil = if local {
                self.op.local_stiffness()
            } else {
                None
            };
            let parts: Vec<[f64; 3]> = match stencil {
                Some(stencil) => {
                    // y = M q on the contact cells of each chunk's rows (in a scratch
                    // buffer), then its sums.
                    let grid = (&self.active[..], &self.w[..], approach);
                    chunks
                        .into_par_iter()
                        .enumerate()
                        .map(|(b, item)| {
                            let len = item.0.len();
                            with_scratch(len, |y| {
                                stencil.apply_rows(grid, y, item.3, b * ROWS_PER_CHUNK);
                                sums_of(item, y)
                            })
                        })
                        .collect()
                }
                _ => finish_fused(
                    &mut self.op,
                    Operand::Preconditioner,
                    &mut self.fallback,
                    chunks,
                    sums_of,
                    Some(&self.rows_on),
                ),
            };
            let [sum_y, qy, qy_prev] = sum_parts(&parts, None);
            let ybar = if force_control && nc > 0.0 {
                sum_y / nc
            } else {
                0.0
            };
            // <q, y>: the preconditioned residual norm (p > 0 implies the mask).
            let gy = qy - ybar * sum_q;
            // Polak-Ribiere+ (module docs): <q, y - y_prev> / <q_prev, y_prev>, >= 0.
            let beta = if gy_old > 0.0 {
                ((gy - qy_prev) / gy_old).max(0.0)
            } else {
                0.0
            };
            gy_old = gy;
            // Conjugate direction t = y + beta t, with <q, t>, as K's input; the
            // projected y is kept. Under force control the old t is first projected too
            // (its mean over the contact set removed), so that t sums to zero there.
            let tbar = if force_control && nc > 0.0 {
                t_on_set / nc
            } else {
                0.0
            };
            let dir = sweeps::Direction {
                ybar,
                tbar,
                beta,
                approach,
            };
            // A fresh K p in the precision it is carried in; K t in single precision to
            // the end, where the operator has it (module docs).
            let kp_op = if single {
                Operand::ComplianceSingle
            } else {
                Operand::Compliance
            };
            let kt_op = Operand::ComplianceSingle;
            let parts = load_fused(
                &mut self.op,
                kt_op,
                &mut self.fallback,
                (
                    self.active.par_chunks(fc),
                    self.w.par_chunks(fc),
                    self.t.par_chunks_mut(fc),
                    self.y_prev.par_chunks_mut(fc),
                    self.rows_on.par_chunks(ROWS_PER_CHUNK),
                    self.rows_t.par_chunks(ROWS_PER_CHUNK),
                ),
                |(act, w, t, y_prev, on, was), out| {
                    sweeps::direction(act, w, t, y_prev, out, (on, was, nx), dir)
                },
            );
            self.rows_t.copy_from_slice(&self.rows_on);
            let [num] = sum_parts(&parts, None);
            // K t, its rows fused with pass D below: the step length needs <t, K t> over
            // the whole grid first, which K's column pass gives (Parseval). Under force
            // control t sums to zero on the contact set, so the step needs no shift of
            // K t by a contact mean.
            // While the contact set still changes in more cells than point loads can
            // follow, K p is recomputed after the update anyway: K t is then needed for
            // its energy only (predicted from the last iteration's changes, module docs).
            let fresh = skips && changed_last > (2 * limit) as f64;
            let tkt = if fresh {
                energy_fused(&mut self.op, kt_op, &mut self.fallback)
            } else {
                apply_fused(&mut self.op, kt_op, &mut self.fallback, true)
            };
            let tau = if tkt > 0.0 && num.is_finite() {
                num / tkt
            } else {
                0.0
            };
            // Pass D: projected update; interpenetrating cells without pressure re-enter
            // the contact set (Polonsky & Keer's overlap correction). w follows p along
            // t exactly; the cells where the projection departs from p - tau t are
            // collected (up to the limit) for pass A.
            // Re-admitted cells get -step g: the step times the stiffness of the longest
            // wavelength (a small, scale-consistent pressure the next iterations adjust;
            // measured on the benchmark surfaces: the preconditioner's diagonal or the
            // inverse self-compliance as the scale cost 5-9 % more iterations). With unit
            // E* and size this is Polonsky & Keer's -tau g.
            let step = self.overlap_stiffness * if tau > 0.0 { tau } else { 1.0 / nm as f64 };
            // Per chunk: total pressure, changed cells, t summed over the new contact
            // set; without a fresh K p, the change p_new - (p - tau t) goes to r.
            let upd = sweeps::Update {
                tau,
                approach,
                step,
            };
            let parts = if fresh {
                // The update as the input of a fresh K p, in K's precision.
                let parts = load_fused(
                    &mut self.op,
                    kp_op,
                    &mut self.fallback,
                    (
                        p.par_chunks_mut(fc),
                        self.t.par_chunks(fc),
                        self.w.par_chunks(fc),
                        self.mask.par_chunks(fc),
                        self.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
                    ),
                    |(p, t, w, m, with_p), values| {
                        sweeps::advance(p, t, w, m, values, (with_p, nx), upd)
                    },
                );
                self.finish_into_w(kp_op);
                refresh_z = true;
                exact = !single;
                parts
            } else {
                let parts = store_fused(
                    &mut self.op,
                    kt_op,
                    &mut self.fallback,
                    (
                        p.par_chunks_mut(fc),
                        self.t.par_chunks(fc),
                        self.r.par_chunks_mut(fc),
                        self.w.par_chunks_mut(fc),
                        self.mask.par_chunks(fc),
                        self.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
                    ),
                    |(p, t, r, w, m, with_p), kt| {
                        sweeps::update(p, t, r, (w, kt), m, (with_p, nx), upd)
                    },
                    None,
                );
                let changed = sum_parts(&parts, None)[1];
                let too_many = changed > limit as f64;
                // The changes as point loads (unless too many), and r zero again.
                self.take_changes(&parts, (!too_many).then_some(&mut loads));
                if too_many {
                    // A fresh K p (in K's precision).
                    if single {
                        load_fused(
                            &mut self.op,
                            kp_op,
                            &mut self.fallback,
                            p.par_chunks(fc),
                            copy_in,
                        );
                        self.finish_into_w(kp_op);
                    } else {
                        self.op.apply(&p, &mut self.w);
                    }
                    refresh_z = true;
                    exact = !single;
                } else {
                    exact = false;
                }
                parts
            };
            let [total, changed, t_set] = sum_parts(&parts, None);
            t_on_set = t_set;
            changed_last = changed;
            scale = match target_force {
                Some(w) if total > 0.0 => w / (total * area),
                _ => 1.0,
            };
        }
        // Not converged: report the last iterate, on a fresh K p.
        p.iter_mut().for_each(|v| *v *= scale);
        self.op.apply(&p, &mut self.w);
        let [sum_g, nc] = self.pass_a(&mut p, 1.0, Refresh::AddZ, fixed_approach);
        if force_control && nc > 0.0 {
            approach = sum_g / nc;
        }
        self.loads = loads;
        let mut last = self.finish(p, approach, opts.max_iterations, residual);
        last.warm_started = warm_started;
        Err(BemError::NoConvergence {
            what: "contact solve",
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(last),
        })
    }
}
