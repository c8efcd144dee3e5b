//! Where an iteration starts: the overlap of the heights with a plane (cold start under
//! force control or at an approach), uniform pressure, or the solution of the grid
//! coarsened 2 x 2 (nested start); solver module docs.

use super::state::{chunk_cells, Problem};
use crate::operator::GridOperator;
use rayon::prelude::*;

/// Cold start under force control: the initial overlap covers this many times
/// `p / (E* h')` of the domain (module docs).
pub(super) const FULL_GRID_START_AREA: f64 = 6.0;

/// Nested start (module docs): grids with at least this many cells per side (and
/// even sides) start from their 2 x 2 coarsening's solution.
pub(super) const NESTED_MIN: usize = 512;

/// A coarse grid's own cold start nests again from this many cells per side: cheap at
/// that size, and on the 512^2 benchmark surface at 1 % contact the fine iterations
/// went from 32 to 28 (1024^2 and 20 % contact: the same iterations as with 512).
pub(super) const COARSE_NESTED_MIN: usize = 256;

/// Tolerance of the nested start's coarse solve: the fine iteration starts from about
/// the same residual whether the coarse solve stops at 1e-2, 1e-3 or 1e-10 (the coarse
/// grid cannot resolve the fine contact set; measured on the 1024^2 benchmark surface
/// at 1 % contact: 4.0e-2 in each case).
pub(super) const NESTED_TOLERANCE: f64 = 1e-3;

/// Iteration cap of the nested start's coarse solve (it takes 10-30 on the benchmark
/// surfaces); a coarse solve that does not converge leaves the cold start.
pub(super) const NESTED_MAX_ITERATIONS: usize = 200;

impl Problem {
    /// Cold start under force control (module docs): p = (d - z)+ on the domain, d the
    /// height quantile whose overlap covers `start_area p / (E* h')` of it
    /// ([`FULL_GRID_START_AREA`]
    /// for the full iteration); the rescale to the force follows. Uniform pressure when
    /// the heights have no slope.
    pub(super) fn cold_start<K: GridOperator>(
        &self,
        op: &K,
        p: &mut [f64],
        force: f64,
        start_area: f64,
    ) {
        let nm = self.domain_cells;
        let fraction = self.start_fraction(op, force, start_area);
        if nm >= 2 && fraction.is_finite() && fraction < 1.0 {
            let k = ((fraction * nm as f64).ceil() as usize).clamp(1, nm - 1);
            let d = self.kth_height(k, chunk_cells(op.nx()));
            let map = self.z.map;
            p.par_iter_mut()
                .zip(self.mask.par_iter())
                .zip(self.z.values())
                .for_each(|((v, &m), z)| *v = m as f64 * (d - map.of(*z)).max(0.0));
        }
        if p.iter().all(|&v| v == 0.0) {
            self.uniform_start(p);
        }
    }

    /// The k-th smallest (from 0) of z over the domain cells, as a sort would give it
    /// (bit for bit): a histogram of the values, made in parallel, finds the bin that
    /// holds rank k (bins are monotone in z), and the selection runs among that bin's
    /// values only (a serial selection over a 1024^2 grid's copy costs about 20 ms).
    /// `ch`: the sweeps' chunk, in cells.
    pub(super) fn kth_height(&self, k: usize, ch: usize) -> f64 {
        const BINS: usize = 4096;
        // The domain's heights, a chunk at a time in parallel.
        let domain = || {
            let map = self.z.map;
            let chunks = self.z.values().par_chunks(ch).zip(self.mask.par_chunks(ch));
            chunks.map(move |(z, m)| {
                z.iter()
                    .zip(m)
                    .filter(|(_, &m)| m > 0)
                    .map(move |(&v, _)| map.of(v))
            })
        };
        let wide = (f64::INFINITY, f64::NEG_INFINITY);
        let (lo, hi) = domain()
            .map(|vals| vals.fold(wide, |(a, b), v| (a.min(v), b.max(v))))
            .reduce(|| wide, |a, b| (a.0.min(b.0), a.1.max(b.1)));
        let scale = (BINS - 1) as f64 / (hi - lo);
        let bin = |v: f64| match scale.is_finite() {
            true => ((v - lo) * scale) as usize,
            false => 0,
        };
        let counts = domain()
            .map(|vals| {
                let mut c = vec![0usize; BINS];
                vals.for_each(|v| c[bin(v)] += 1);
                c
            })
            .reduce(
                || vec![0usize; BINS],
                |mut a, b| {
                    a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                    a
                },
            );
        // The bin of rank k and the ranks below it.
        let (mut target, mut before) = (BINS - 1, 0);
        for (b, &c) in counts.iter().enumerate() {
            if before + c > k {
                target = b;
                break;
            }
            before += c;
        }
        let mut vals: Vec<f64> = domain()
            .flat_map_iter(|vals| vals.filter(move |&v| bin(v) == target))
            .collect();
        *vals.select_nth_unstable_by(k - before, f64::total_cmp).1
    }

    /// Uniform pressure (one per domain cell; the load's rescale follows).
    pub(super) fn uniform_start(&self, p: &mut [f64]) {
        p.par_iter_mut()
            .zip(self.mask.par_iter())
            .for_each(|(v, &m)| *v = m as f64);
    }

    /// The fraction of the domain the cold start's overlap covers (may be >= 1 or not
    /// finite: then the start is uniform).
    pub(super) fn start_fraction<K: GridOperator>(
        &self,
        op: &K,
        force: f64,
        start_area: f64,
    ) -> f64 {
        let mean_pressure = force / (self.domain_cells as f64 * op.cell_area());
        start_area * mean_pressure / (op.e_star() * self.slope_rms)
    }

    /// Start at the approach `d`: the overlap `(d - z)+` times the stiffness of the
    /// longest wavelength.
    pub(super) fn overlap_start<K: GridOperator>(&self, op: &K, p: &mut [f64], d: f64) {
        let scale = op.e_star() / (op.lx() * op.ly()).sqrt();
        let map = self.z.map;
        p.par_iter_mut()
            .zip(self.mask.par_iter())
            .zip(self.z.values())
            .for_each(|((v, &m), z)| *v = m as f64 * (d - map.of(*z)).max(0.0) * scale);
    }
}
