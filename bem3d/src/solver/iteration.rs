//! The projected, preconditioned conjugate-gradient iteration (solver module docs).

use super::convergence::STALL_ITERATIONS;
use super::fused::{
    apply_fused, energy_fused, load_fused, reduce, store_fused, sum_parts, with_scratch,
};
use super::options::{Choice, SolverOptions, Target};
use super::state::ContactSolver;
use super::stored::with_directions;
use super::sweeps;
use crate::error::{BemError, Result};
use crate::fft::{copy_in, copy_out, ROWS_PER_CHUNK};
use crate::operator::GridOperator;
use crate::operator::Operand;
use crate::solution::Solution;
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

impl<K: GridOperator> ContactSolver<K> {
    /// The projected, preconditioned conjugate-gradient iteration from the pressure `p`
    /// (on the domain, meeting the load), holding `target` (a force or an approach). One
    /// iteration, in order:
    ///
    /// 1. [`Self::contact_set`] (pass A): `w = K p + z` brought up to date, the contact
    ///    set marked, the approach (force control: the mean gap over the set);
    /// 2. [`Self::criterion_pass`] (pass B): the gap, the criterion and the residual q,
    ///    loaded as M's input;
    /// 3. [`Self::stop_test`]: converged (after a confirmation on a fresh `K p`), or a
    ///    fresh `K p` at the precision schedule's switches, or on;
    /// 4. [`Self::preconditioned_residual`]: `y = M q` (transforms or stencil) and the
    ///    sums of its projection;
    /// 5. [`Self::direction`]: Polak-Ribiere+'s beta and `t = y + beta t`, loaded as K's
    ///    input;
    /// 6. [`Self::step_length`]: `<t, K t>` from K's column pass,
    ///    `tau = <q, t> / <t, K t>`;
    /// 7. [`Self::update`] (pass D): the projected step, `K p` moved along (or recomputed).
    pub(super) fn iterate(
        &mut self,
        mut p: Vec<f64>,
        target: Target,
        opts: &SolverOptions,
        start: Start,
    ) -> Result<Solution> {
        let mut st = self.begin(&p, target, start, opts);
        let (mut approach, mut residual);
        loop {
            let nc;
            (approach, nc) = self.contact_set(&mut p, &mut st);
            // M by its stencil on a small contact set (module docs) instead of its
            // transforms (the same chunks, the same sums).
            let local = match opts.paths.stencil {
                Choice::Forbid => false,
                Choice::Allow => nc <= self.tuning.local_max_fraction * self.op.cells() as f64,
                Choice::Force => true,
            } && self.op.local_stiffness().is_some();
            let [pg, ps, worst, sum_q] = self.criterion_pass(&p, approach, local);
            let h_rms = self.problem.h_rms;
            residual = (if ps > 0.0 { pg / (ps * h_rms) } else { 0.0 }).max(worst / h_rms);
            if !residual.is_finite() {
                return Err(BemError::Breakdown {
                    what: "contact solve",
                    iterations: st.it,
                    residual,
                    reason: "non-finite residual",
                });
            }
            match self.stop_test(&p, approach, (residual, nc, ps), &mut st, opts) {
                Next::Recompute => continue,
                Next::Converged => {
                    self.work.loads = std::mem::take(&mut st.loads);
                    let sol = self.finish(p, approach, st.it, residual);
                    return Ok(st.report(sol));
                }
                Next::Iterate => {}
            }
            if st.it == opts.max_iterations {
                break;
            }
            if opts.interrupted() {
                return Err(BemError::Interrupted {
                    what: "contact solve",
                    iterations: st.it,
                });
            }
            st.it += 1;
            st.single_iterations += st.single as usize;
            st.stencil_iterations += local as usize;
            let sums = self.preconditioned_residual(approach, local);
            let num = self.direction(sums, (nc, sum_q, approach), &mut st);
            // While the contact set still changes in more cells than point loads can
            // follow, K p is recomputed after the update anyway: K t is then needed for
            // its energy only (predicted from the last iteration's changes, module docs).
            let fresh = st.skips && st.changed_last > (2 * self.op.point_load_limit()) as f64;
            let tau = self.step_length(num, fresh, st.kt_op);
            self.update(&mut p, tau, approach, fresh, &mut st);
        }
        self.not_converged(p, approach, residual, st, opts)
    }

    /// The iteration's state before its first step, with `w = K p` (pass A adds z).
    fn begin(&mut self, p: &[f64], target: Target, start: Start, opts: &SolverOptions) -> State {
        // t and y_prev start at zero (y_prev is read before it is written; with beta = 0
        // its values do not matter). Written here, in parallel, each page of a fresh
        // buffer gets its own frame now: a page of `vec![0.0; n]` first read maps the
        // shared zero page, and its first write then copies it and flushes the other
        // threads' TLBs (measured: ~4 % of a two-thread solve at 1024^2).
        let n = self.op.cells();
        let scaled = match opts.paths.scaled_directions {
            Choice::Forbid => false,
            Choice::Allow => n > self.tuning.large_grid_cells,
            Choice::Force => true,
        };
        let chunk = ROWS_PER_CHUNK * self.op.nx();
        self.work.directions.reset(n, chunk, scaled);
        if n > self.tuning.large_grid_cells {
            // The buffers freed before (a nested start's coarse solver, directions of
            // another format) would otherwise stay resident beside this solve's
            // (measured: 1.3-2.3 bytes per cell at 8192^2, docs/performance.md).
            sysmem::release_freed();
        }
        self.work.rows_t.fill(false);
        self.work.rows_p.fill(true);
        self.op.apply(p, &mut self.work.w);
        State {
            target,
            it: 0,
            gy_old: 0.0,
            t_on_set: 0.0,
            single: opts.paths.single_precision.allowed() && self.op.rounds_single(),
            kt_op: if opts.paths.single_precision.allowed() {
                Operand::ComplianceSingle
            } else {
                Operand::Compliance
            },
            refresh_below: f64::NEG_INFINITY,
            scale: 1.0,
            refresh_z: true,
            exact: true,
            stall: (f64::INFINITY, 0),
            loads: std::mem::take(&mut self.work.loads),
            changed_last: if start.warm { 0.0 } else { f64::INFINITY },
            skips: self.op.spectral(Operand::Compliance).is_some(),
            start,
            single_iterations: 0,
            stencil_iterations: 0,
            scaled_directions: scaled,
        }
    }

    /// Step 1 (pass A): `w` brought up to date, the contact set marked; returns the
    /// approach (under force control the mean gap over the contact set) and the number
    /// of contact cells.
    fn contact_set(&mut self, p: &mut [f64], st: &mut State) -> (f64, f64) {
        let refresh = if st.refresh_z {
            Refresh::AddZ
        } else {
            Refresh::Loads(&st.loads)
        };
        let [sum_g, nc] = self.pass_a(p, st.scale, refresh, st.target.base_approach());
        st.refresh_z = false;
        st.loads.clear();
        st.scale = 1.0;
        let gbar = if st.target.force().is_some() && nc > 0.0 {
            sum_g / nc
        } else {
            0.0
        };
        (st.target.base_approach() + gbar, nc)
    }

    /// Step 2 (pass B, fused into M's row pass unless `local`): the gap `g = w -
    /// approach` on the domain, the criterion's terms and the residual `q = [p > 0] g`
    /// as M's input; returns (sum p |g|, sum p, max -g, sum q).
    fn criterion_pass(&mut self, p: &[f64], approach: f64, local: bool) -> [f64; 4] {
        let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
        let residual_of =
            |(p, w, m, on), q: &mut [f64]| sweeps::residual(p, w, m, q, (on, nx), approach);
        let chunks = (
            p.par_chunks(fc),
            self.work.w.par_chunks(fc),
            self.problem.mask.par_chunks(fc),
            self.work.rows_on.par_chunks(ROWS_PER_CHUNK),
        );
        let parts = if local {
            // The stencil reads q from the gap and the contact set: the chunk's q goes
            // to a scratch buffer.
            chunks
                .into_par_iter()
                .map(|item| with_scratch(item.0.len(), |q| residual_of(item, q)))
                .collect()
        } else {
            load_fused(
                &mut self.op,
                Operand::Preconditioner,
                &mut self.work.fallback,
                chunks,
                residual_of,
            )
        };
        sum_parts(&parts, Some(2))
    }

    /// Step 3: whether the iterate is converged (module docs: criterion and certificate
    /// within the tolerance on a freshly computed `K p`), or `K p` is to be recomputed
    /// first (the precision schedule's switches, or to confirm convergence).
    /// `(residual, nc, ps)`: the criterion, contact cells and pressure sum of step 2.
    fn stop_test(
        &mut self,
        p: &[f64],
        approach: f64,
        (residual, nc, ps): (f64, f64, f64),
        st: &mut State,
        opts: &SolverOptions,
    ) -> Next {
        if st.single && residual <= SINGLE_UNTIL || residual <= st.refresh_below {
            // K p in double precision from here on, from a fresh one (the direction is
            // kept), and once more below REFRESH_AGAIN.
            st.refresh_below = if st.single && residual > REFRESH_AGAIN {
                REFRESH_AGAIN
            } else {
                f64::NEG_INFINITY
            };
            st.single = false;
            self.recompute_w(p, st);
            return Next::Recompute;
        }
        if residual < 0.5 * st.stall.0 {
            st.stall = (residual, 0);
        } else {
            st.stall.1 += 1;
        }
        let tolerance =
            if nc as usize == self.problem.domain_cells && st.stall.1 >= STALL_ITERATIONS {
                self.problem
                    .complete_contact_tolerance(&self.op, opts.tolerance, ps)
            } else {
                opts.tolerance
            };
        if residual > tolerance {
            return Next::Iterate;
        }
        if !st.exact {
            // Confirm on a fresh K p (the direction is kept).
            self.recompute_w(p, st);
            return Next::Recompute;
        }
        // Converged when the duality gap is within the tolerance too (module docs); it
        // is at most twice the criterion, so this rarely iterates on.
        if self
            .problem
            .certificate(p, &self.work.w, self.op.nx(), approach)
            <= tolerance
        {
            Next::Converged
        } else {
            Next::Iterate
        }
    }

    /// `w = K p` in double precision, from scratch (pass A adds z).
    fn recompute_w(&mut self, p: &[f64], st: &mut State) {
        self.op.apply(p, &mut self.work.w);
        st.refresh_z = true;
        st.exact = true;
    }

    /// Step 4: the preconditioned residual y = M q (M's transforms, or its stencil on
    /// the contact cells), with the sums of the projected `y = [p > 0] (M q - ybar)`,
    /// ybar its contact mean under force control (the direction keeps the total force);
    /// y replaces y_prev once read. Returns (sum y, <q, y>, <q, y_prev>) over the set.
    fn preconditioned_residual(&mut self, approach: f64, local: bool) -> [f64; 3] {
        let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
        // (The stencil is made only once a set is small.)
        let stencil = if local {
            self.op.local_stiffness()
        } else {
            None
        };
        let parts: Vec<[f64; 3]> = with_directions!(&mut self.work.directions, |_t, y_prev| {
            let chunks = (
                self.work.active.par_chunks(fc),
                self.work.w.par_chunks(fc),
                y_prev.chunks_mut(),
                self.work.rows_on.par_chunks(ROWS_PER_CHUNK),
            );
            let sums_of = |(act, w, y_prev, on), y: &[f64]| {
                sweeps::preconditioned(act, w, y_prev, y, (on, nx), approach)
            };
            match stencil {
                Some(stencil) => {
                    // y = M q on the contact cells of each chunk's rows (in a scratch
                    // buffer), then its sums.
                    let grid = (&self.work.active[..], &self.work.w[..], approach);
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
                _ => {
                    let (op, fallback) = (&mut self.op, &mut self.work.fallback);
                    apply_fused(op, Operand::Preconditioner, fallback, false);
                    let wanted = Some(&self.work.rows_on[..]);
                    store_fused(
                        op,
                        Operand::Preconditioner,
                        fallback,
                        chunks,
                        sums_of,
                        wanted,
                    )
                }
            }
        });
        sum_parts(&parts, None)
    }

    /// Step 5: the conjugate direction `t = y + beta t` (Polak-Ribiere+, module docs),
    /// loaded as K's input (single precision where the operator has it); the projected
    /// y is kept. Under force control the old t is first projected too (its mean over
    /// the contact set removed), so that t sums to zero there. `sums`: step 4's;
    /// `(nc, sum_q, approach)`: the contact cells, the sum of q and the approach.
    /// Returns `<q, t>`.
    fn direction(
        &mut self,
        [sum_y, qy, qy_prev]: [f64; 3],
        (nc, sum_q, approach): (f64, f64, f64),
        st: &mut State,
    ) -> f64 {
        let force_control = st.target.force().is_some();
        let ybar = if force_control && nc > 0.0 {
            sum_y / nc
        } else {
            0.0
        };
        // <q, y>: the preconditioned residual norm (p > 0 implies the mask).
        let gy = qy - ybar * sum_q;
        // Polak-Ribiere+ (module docs): <q, y - y_prev> / <q_prev, y_prev>, >= 0.
        let beta = if st.gy_old > 0.0 {
            ((gy - qy_prev) / st.gy_old).max(0.0)
        } else {
            0.0
        };
        st.gy_old = gy;
        let tbar = if force_control && nc > 0.0 {
            st.t_on_set / nc
        } else {
            0.0
        };
        let dir = sweeps::Direction {
            ybar,
            tbar,
            beta,
            approach,
        };
        let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
        let parts = with_directions!(&mut self.work.directions, |t, y_prev| load_fused(
            &mut self.op,
            st.kt_op,
            &mut self.work.fallback,
            (
                self.work.active.par_chunks(fc),
                self.work.w.par_chunks(fc),
                t.chunks_mut(),
                y_prev.chunks_mut(),
                self.work.rows_on.par_chunks(ROWS_PER_CHUNK),
                self.work.rows_t.par_chunks(ROWS_PER_CHUNK),
            ),
            |(act, w, t, y_prev, on, was), out| {
                sweeps::direction(act, w, t, y_prev, out, (on, was, nx), dir)
            },
        ));
        self.work.rows_t.copy_from_slice(&self.work.rows_on);
        let [num] = sum_parts(&parts, None);
        num
    }

    /// Step 6: the step length `tau = <q, t> / <t, K t>` (`num` = `<q, t>`), with
    /// `<t, K t>` over the whole grid from K's column pass (Parseval); K t's rows follow
    /// in step 7 unless `fresh` (K p recomputed there instead). Under force control t
    /// sums to zero on the contact set, so the step needs no shift of K t by a contact
    /// mean.
    fn step_length(&mut self, num: f64, fresh: bool, kt_op: Operand) -> f64 {
        let tkt = if fresh {
            energy_fused(&mut self.op, kt_op, &mut self.work.fallback)
        } else {
            apply_fused(&mut self.op, kt_op, &mut self.work.fallback, true)
        };
        if tkt > 0.0 && num.is_finite() {
            num / tkt
        } else {
            0.0
        }
    }

    /// Step 7 (pass D): the projected update; interpenetrating cells without pressure
    /// re-enter the contact set (Polonsky & Keer's overlap correction). With `fresh`,
    /// the new p is loaded as the input of a fresh `K p`; else w follows p along t
    /// exactly (K t's rows) and the cells where the projection departs from `p - tau t`
    /// become point loads for pass A (or, beyond the operator's limit, `K p` is
    /// recomputed).
    fn update(&mut self, p: &mut [f64], tau: f64, approach: f64, fresh: bool, st: &mut State) {
        // Re-admitted cells get -step g: the step times the stiffness of the longest
        // wavelength (a small, scale-consistent pressure the next iterations adjust;
        // measured on the benchmark surfaces: the preconditioner's diagonal or the
        // inverse self-compliance as the scale cost 5-9 % more iterations). With unit E*
        // and size this is Polonsky & Keer's -tau g.
        let step = self.problem.overlap_stiffness
            * if tau > 0.0 {
                tau
            } else {
                1.0 / self.problem.domain_cells as f64
            };
        let upd = sweeps::Update {
            tau,
            approach,
            step,
        };
        // A fresh K p in the precision it is carried in (module docs).
        let kp_op = if st.single {
            Operand::ComplianceSingle
        } else {
            Operand::Compliance
        };
        // Per chunk: total pressure, changed cells, t summed over the new contact set.
        let parts = if fresh {
            let parts = self.update_with_fresh_kp(p, upd, kp_op);
            st.refresh_z = true;
            st.exact = !st.single;
            parts
        } else {
            self.update_along_kt(p, upd, kp_op, st)
        };
        let [total, changed, t_set] = sum_parts(&parts, None);
        st.t_on_set = t_set;
        st.changed_last = changed;
        st.scale = match st.target.force() {
            Some(w) if total > 0.0 => w / (total * self.op.cell_area()),
            _ => 1.0,
        };
    }

    /// Step 7 with a fresh `K p`: the update as the input of K in `kp_op`'s precision,
    /// then `w = K p` (pass A adds z). Returns the per-chunk sums of the update.
    fn update_with_fresh_kp(
        &mut self,
        p: &mut [f64],
        upd: sweeps::Update,
        kp_op: Operand,
    ) -> Vec<[f64; 3]> {
        let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
        if kp_op == Operand::Compliance && self.op.cells() > self.tuning.large_grid_cells {
            return self.update_then_kp(p, upd);
        }
        let parts = with_directions!(&self.work.directions, |t, _y| load_fused(
            &mut self.op,
            kp_op,
            &mut self.work.fallback,
            (
                p.par_chunks_mut(fc),
                t.chunks(),
                self.work.w.par_chunks(fc),
                self.problem.mask.par_chunks(fc),
                self.work.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
            ),
            |(p, t, w, m, with_p), values| sweeps::advance(p, t, w, m, values, (with_p, nx), upd),
        ));
        self.finish_into_w(kp_op);
        parts
    }

    /// [`Self::update_with_fresh_kp`] in double precision on a memory-lean grid: the
    /// update on its own (the same chunks, p, flags and sums), then `w = K p` by the
    /// operator's plain application, which needs no double-precision row buffer where
    /// the operator holds the spectra in `w` (the periodic half-space above
    /// [`COMPUTED_SYMBOLS_ABOVE`](crate::operator::COMPUTED_SYMBOLS_ABOVE)); the same
    /// `K p` bit for bit.
    fn update_then_kp(&mut self, p: &mut [f64], upd: sweeps::Update) -> Vec<[f64; 3]> {
        let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
        let parts = with_directions!(&self.work.directions, |t, _y| (
            p.par_chunks_mut(fc),
            t.chunks(),
            self.work.w.par_chunks(fc),
            self.problem.mask.par_chunks(fc),
            self.work.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
        )
            .into_par_iter()
            .map(|(p, t, w, m, with_p)| {
                // The copy of p that the fused form loads goes to a scratch buffer.
                with_scratch(p.len(), |values| {
                    sweeps::advance(p, t, w, m, values, (with_p, nx), upd)
                })
            })
            .collect());
        self.op.apply(p, &mut self.work.w);
        parts
    }

    /// Step 7 along K t: w moves by `-tau K t` (K t's rows, fused with the update), and
    /// the changes `p_new - (p - tau t)` go to the per-chunk lists `changes`, then to the
    /// point loads of the next pass A, or, when more than the operator's point-load
    /// limit, into a fresh `K p` (in `kp_op`'s precision). Returns the per-chunk sums of the update.
    fn update_along_kt(
        &mut self,
        p: &mut [f64],
        upd: sweeps::Update,
        kp_op: Operand,
        st: &mut State,
    ) -> Vec<[f64; 3]> {
        let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
        // A chunk's list stops at the limit: more changes than that in all go to a
        // fresh K p, not to point loads.
        let cap = self.op.point_load_limit() + 1;
        let parts = with_directions!(&self.work.directions, |t, _y| store_fused(
            &mut self.op,
            st.kt_op,
            &mut self.work.fallback,
            (
                p.par_chunks_mut(fc),
                t.chunks(),
                self.work.changes.par_iter_mut().enumerate(),
                self.work.w.par_chunks_mut(fc),
                self.problem.mask.par_chunks(fc),
                self.work.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
            ),
            |(p, t, (b, changes), w, m, with_p), kt| {
                sweeps::update(p, t, (changes, b * fc, cap), (w, kt), m, (with_p, nx), upd)
            },
            None,
        ));
        let changed = sum_parts(&parts, None)[1];
        let too_many = changed > self.op.point_load_limit() as f64;
        // The changes as point loads (unless too many), and the lists emptied.
        self.take_changes((!too_many).then_some(&mut st.loads));
        if too_many {
            // A fresh K p (in K's precision).
            if st.single {
                load_fused(
                    &mut self.op,
                    kp_op,
                    &mut self.work.fallback,
                    p.par_chunks(fc),
                    copy_in,
                );
                self.finish_into_w(kp_op);
            } else {
                self.op.apply(p, &mut self.work.w);
            }
            st.refresh_z = true;
            st.exact = !st.single;
        } else {
            st.exact = false;
        }
        parts
    }

    /// Pass A: brings `w` up to date (`refresh`, then the pending force rescale of p
    /// and K p), marks the contact set (p > 0) in `active` and its rows in `rows_on`, and
    /// sums `w - offset` and the cell count over it. p is read in the rows `rows_p`
    /// marks only.
    pub(super) fn pass_a(
        &mut self,
        p: &mut [f64],
        scale: f64,
        refresh: Refresh,
        offset: f64,
    ) -> [f64; 2] {
        let (nx, ch) = (self.op.nx(), self.chunk());
        let (loads, add_z) = match refresh {
            Refresh::Loads(l) => (l, 0.0),
            Refresh::AddZ => (&[][..], 1.0),
        };
        if !loads.is_empty() {
            self.op.add_point_loads(loads, &mut self.work.w);
        }
        // w = K p + z before, scale K p + z after (with add_z: w = K p before).
        let zf = 1.0 - scale * (1.0 - add_z);
        let zmap = self.problem.z.map;
        reduce(
            (
                p.par_chunks_mut(ch),
                self.problem.z.values().par_chunks(ch),
                self.work.w.par_chunks_mut(ch),
                self.work.active.par_chunks_mut(ch),
                self.work.rows_p.par_chunks(ch / nx),
                self.work.rows_on.par_chunks_mut(ch / nx),
            ),
            |(p, z, w, act, with_p, on)| {
                sweeps::rescale(p, z, zmap, w, act, (with_p, on, nx), (scale, zf), offset)
            },
            None,
        )
    }

    /// The second half of a fresh `K p` (in `k_op`'s precision) whose input is loaded:
    /// K p into `w` (pass A then adds z).
    fn finish_into_w(&mut self, k_op: Operand) {
        let fc = ROWS_PER_CHUNK * self.op.nx();
        let (op, fallback) = (&mut self.op, &mut self.work.fallback);
        apply_fused(op, k_op, fallback, false);
        store_fused(
            op,
            k_op,
            fallback,
            self.work.w.par_chunks_mut(fc),
            copy_out,
            None,
        );
    }

    /// Appends the changes pass D listed, chunk by chunk in cell order, to `loads` when
    /// given, and empties the lists (keeping their storage).
    fn take_changes(&mut self, mut loads: Option<&mut Vec<(usize, f64)>>) {
        for list in &mut self.work.changes {
            if let Some(l) = loads.as_deref_mut() {
                l.extend_from_slice(list);
            }
            list.clear();
        }
    }

    /// The solution without contact: w = z (no pressure), approach `d`.
    pub(super) fn finish_unloaded(&mut self, d: f64) -> Solution {
        let z = &self.problem.z;
        let map = z.map;
        self.work
            .w
            .par_iter_mut()
            .zip(z.values())
            .for_each(|(w, v)| *w = map.of(*v));
        let n = self.op.cells();
        self.finish(vec![0.0; n], d, 0, 0.0)
    }

    /// Collects the solution from p and w = K p + z.
    pub(super) fn finish(
        &mut self,
        p: Vec<f64>,
        approach: f64,
        iterations: usize,
        residual: f64,
    ) -> Solution {
        let area = self.op.cell_area();
        let d = if approach.is_finite() { approach } else { 0.0 };
        let certificate = self.problem.certificate(&p, &self.work.w, self.op.nx(), d);
        let gap_of = |w: f64, m: u8| if m > 0 { (w - d).max(0.0) } else { 0.0 };
        let gap: Vec<f64> = if p.len() > self.tuning.large_grid_cells {
            // Written over w (a solve recomputes w from its start), the solver's w
            // replaced by zeroed pages that cost no memory until the next solve writes
            // them: the same values without a third grid alive.
            let mut gap = std::mem::replace(&mut self.work.w, vec![0.0; p.len()]);
            gap.par_iter_mut()
                .zip(self.problem.mask.par_iter())
                .for_each(|(w, &m)| *w = gap_of(*w, m));
            gap
        } else {
            let w = self.work.w.par_iter().zip(self.problem.mask.par_iter());
            w.map(|(&w, &m)| gap_of(w, m)).collect()
        };
        let cells = self.problem.domain_cells;
        Solution {
            certificate,
            iterations,
            residual,
            ..Solution::full_grid(p, gap, approach, area, cells)
        }
    }

    /// The iteration cap reached: the last iterate, on a fresh `K p`, inside
    /// [`BemError::NoConvergence`].
    fn not_converged(
        &mut self,
        mut p: Vec<f64>,
        mut approach: f64,
        residual: f64,
        mut st: State,
        opts: &SolverOptions,
    ) -> Result<Solution> {
        p.iter_mut().for_each(|v| *v *= st.scale);
        self.op.apply(&p, &mut self.work.w);
        let [sum_g, nc] = self.pass_a(&mut p, 1.0, Refresh::AddZ, st.target.base_approach());
        if st.target.force().is_some() && nc > 0.0 {
            approach = sum_g / nc;
        }
        self.work.loads = std::mem::take(&mut st.loads);
        let last = self.finish(p, approach, opts.max_iterations, residual);
        let last = st.report(last);
        Err(BemError::NoConvergence {
            what: "contact solve",
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(last),
        })
    }
}

/// What the iteration carries from one step to the next, besides the solver's buffers.
struct State {
    /// The force or approach the iteration holds.
    target: Target,
    /// Iterations done.
    it: usize,
    /// `<q, y>` of the previous iteration (0: no direction yet).
    gy_old: f64,
    /// Sum of t over the contact set of the coming iteration (from pass D).
    t_on_set: f64,
    /// Whether `K p` is carried in single precision: while the residual is above
    /// [`SINGLE_UNTIL`], where the operator rounds K so (its transforms; a dense
    /// matrix's copy, whose K t alone is rounded, K p fresh in double precision).
    single: bool,
    /// Residual below which `K p` is recomputed in double precision once more (-inf:
    /// no more).
    refresh_below: f64,
    /// Pending factor of the load constraint: p and `K p` are rescaled lazily in pass A
    /// (K is linear), saving a sweep.
    scale: f64,
    /// Whether `w` holds `K p` alone (pass A adds z) rather than `K p + z` with the
    /// point loads of `loads` pending.
    refresh_z: bool,
    /// Whether `w` holds `K p + z` recomputed from scratch (not updated).
    exact: bool,
    /// Complete contact's floor (module docs): the criterion's best value so far (to a
    /// factor 2) and the iterations since.
    stall: (f64, usize),
    /// Point-load corrections of `K p` pending for pass A (cell, pressure change).
    loads: Vec<(usize, f64)>,
    /// Cells the last update changed against `p - tau t` (a cold start changes many).
    changed_last: f64,
    /// Whether K is a transform whose inverse half an iteration can skip (module docs);
    /// an operator applied as a whole would be applied twice.
    skips: bool,
    /// K's form for the direction's `K t`: single precision where the paths allow it
    /// (the operator falls back to double where it has no single-precision form).
    kt_op: Operand,
    /// What the iteration started from (reported in the [`Solution`]).
    start: Start,
    /// Iterations with `K p` carried in single precision, and with M by its stencil.
    single_iterations: usize,
    stencil_iterations: usize,
    /// Whether t and y_prev are stored scaled to 16 bits.
    scaled_directions: bool,
}

impl State {
    /// `sol` with what the iteration knows of its path: the start and the iterations
    /// per precision and preconditioner form.
    fn report(&self, mut sol: Solution) -> Solution {
        sol.warm_started = self.start.warm;
        sol.nested_start = self.start.nested;
        sol.single_iterations = self.single_iterations;
        sol.stencil_iterations = self.stencil_iterations;
        sol.scaled_directions = self.scaled_directions;
        sol
    }
}

/// What an iteration starts from, besides a cold start.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Start {
    /// A previous solution (warm start).
    pub(super) warm: bool,
    /// The solution on the grid coarsened 2 x 2 (nested start).
    pub(super) nested: bool,
}

/// What the stop test decided.
enum Next {
    /// Converged: report the iterate.
    Converged,
    /// `K p` was recomputed from scratch: evaluate the iterate again.
    Recompute,
    /// Take another iteration.
    Iterate,
}
