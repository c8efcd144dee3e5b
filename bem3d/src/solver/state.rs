//! The solver's state, by job: the operator, the problem (heights, mask and their
//! statistics), the iteration's work buffers, the tuning knobs and the coarse solver
//! of nested starts. Types only: what acts on them lives in the files the solver's
//! module docs list.

use super::{domain, stored};
use crate::operator::GridOperator;
use std::sync::Arc;

/// Solver for one height map on one operator; buffers are allocated once. Its state
/// by job: the operator, the problem (heights, mask and their statistics), the work
/// buffers of the iteration, the tuning knobs, and the coarse solver of nested starts.
pub struct ContactSolver<K: GridOperator> {
    pub(super) op: K,
    pub(super) problem: Problem,
    pub(super) work: Work,
    pub(super) tuning: Tuning,
    /// The solver on the grid coarsened 2 x 2, for nested starts (built on first use;
    /// dropped with the heights).
    pub(super) coarse: Option<Box<ContactSolver<K>>>,
}

/// The problem a solver holds: the heights, the cells that may touch, and the
/// statistics the solve reads.
pub(super) struct Problem {
    /// The gap at zero approach: the highest height minus the heights.
    pub(super) z: Gap0,
    /// The cells that may touch, read as 1 or 0 (numbers: the sweeps are branch-free).
    pub(super) mask: domain::Domain,
    /// Rms of z over the domain (the length scale of the convergence criterion).
    pub(super) h_rms: f64,
    /// Number of domain cells and the mean of z over them (complete-contact approach of
    /// an unmasked periodic surface).
    pub(super) domain_cells: usize,
    pub(super) z_mean: f64,
    /// Rms slope of the heights over the domain (for the cold start under force control).
    pub(super) slope_rms: f64,
    /// Converts an overlap into a pressure [pressure / length] (see
    /// [`ContactSolver::solve`]).
    pub(super) overlap_stiffness: f64,
}

/// Heights the caller keeps and the solver reads in place (a numpy array from Python):
/// rows of y, `ny x nx`, unchanged while the solver holds them.
pub type SharedHeights = Arc<dyn AsRef<[f64]> + Send + Sync>;

/// Where the heights' values live: copied into the solver, or the caller's.
pub(super) enum Values {
    Owned(Vec<f64>),
    Shared(SharedHeights),
}

/// The gap at zero approach `z = offset + sign v` over stored values v: the heights with
/// `offset` the highest height of the domain and `sign` -1 (the solver keeps no copy of
/// z beside the heights), or a part's gathered z with (-0, +1). Both forms give z bit
/// for bit as a stored `top - h` does: `(-1) v` and `1 v` are exact, `top + (-h)` is by
/// definition `top - h`, and `-0 + z = z` for every z, signed zeros included.
pub(super) struct Gap0 {
    pub(super) values: Values,
    pub(super) map: ZMap,
}

/// The affine map from stored values to z (see [`Gap0`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct ZMap {
    pub(super) offset: f64,
    pub(super) sign: f64,
}

impl ZMap {
    /// The values are z themselves.
    pub(super) const IDENTITY: ZMap = ZMap {
        offset: -0.0,
        sign: 1.0,
    };

    #[inline(always)]
    pub(super) fn of(self, v: f64) -> f64 {
        self.offset + self.sign * v
    }
}

impl Values {
    pub(super) fn as_slice(&self) -> &[f64] {
        match self {
            Values::Owned(v) => v,
            Values::Shared(v) => (**v).as_ref(),
        }
    }
}

impl Gap0 {
    /// The stored values (z through [`Gap0::map`]).
    pub(super) fn values(&self) -> &[f64] {
        self.values.as_slice()
    }

    /// z at cell `i`.
    #[inline]
    pub(super) fn at(&self, i: usize) -> f64 {
        self.map.of(self.values()[i])
    }

    /// A part's z, gathered from the grid's.
    pub(super) fn gathered(z: Vec<f64>) -> Self {
        Self {
            values: Values::Owned(z),
            map: ZMap::IDENTITY,
        }
    }
}

/// The work buffers of the iteration (allocated once per solver).
pub(super) struct Work {
    /// `K p + z`: the gap at zero approach, kept up to date incrementally.
    pub(super) w: Vec<f64>,
    /// The conjugate direction `t` and Polak-Ribiere+'s `y_prev` (the previous
    /// iteration's projected preconditioned residual; between M's application and the
    /// next direction, this iteration's raw `M q`), in single precision or scaled to 16
    /// bits (module docs, "Scaled directions"); K's input, the update and the sums read
    /// the stored values.
    pub(super) directions: stored::Directions,
    /// The cells whose projected step departs from `p - tau t` (pass D) and by how much,
    /// one list per row chunk of the sweeps, read for the point-load corrections of
    /// `K p`; empty between iterations.
    pub(super) changes: Vec<Vec<(usize, f64)>>,
    /// 1 where p > 0 (the contact set), written by pass A: the sweeps that need only
    /// the set read one byte per cell instead of p.
    pub(super) active: Vec<u8>,
    /// Per row: whether it holds a cell of the contact set (written by pass A; pass B
    /// reads p only there, and M's output is read on the set only, so the other rows are
    /// not computed).
    pub(super) rows_on: Vec<bool>,
    /// Per row: whether p may be positive there (written by pass D; all rows wherever p
    /// is set otherwise): pass A reads p only in these rows.
    pub(super) rows_p: Vec<bool>,
    /// Per row: whether t and y_prev may be non-zero there (the contact rows of the last
    /// direction pass): the direction pass skips the rows marked neither here nor in
    /// `rows_on`.
    pub(super) rows_t: Vec<bool>,
    /// Per-iteration corrections of the projected step (cell, pressure change).
    pub(super) loads: Vec<(usize, f64)>,
    /// Input and output of fused applications of an operator without a spectral form.
    pub(super) fallback: [Vec<f64>; 2],
}

/// The tuning knobs of the strategies (tests set others).
pub(super) struct Tuning {
    /// Largest contact set, as a fraction of the grid's cells, on which M is applied by
    /// its stencil: [`super::iteration::LOCAL_MAX_FRACTION`] (tests set others).
    pub(super) local_max_fraction: f64,
    /// Grids with more cells than this run memory-lean: [`LARGE_GRID_CELLS`] (tests set
    /// others).
    pub(super) large_grid_cells: usize,
    /// Fewest cells per side for a nested start: [`super::start::NESTED_MIN`], or
    /// [`super::start::COARSE_NESTED_MIN`] for a coarse grid's solver.
    pub(super) nested_min: usize,
}

/// Grids with more cells than this (above 2048^2) trade the speed of repeated solves
/// on one solver for memory: the coarse solver of a nested start is released after the
/// start (its operator and buffers are about a fifth of the fine solve's memory), the
/// solution's gap is written over the solver's w (the next solve maps w's pages again),
/// and a fresh double-precision `K p` after an update is the operator's plain
/// application, not fused with the update (the periodic half-space then holds its
/// spectra in w: no double-precision row buffer). The results are the same either way.
pub(super) const LARGE_GRID_CELLS: usize = 1 << 22;

/// Sweep chunk, in cells (rounded to whole rows): fixed, so that partial sums (and
/// results) do not depend on the thread count.
const CHUNK: usize = 16_384;

/// Sweep chunk of a grid of row length `nx`: [`CHUNK`] cells rounded to whole rows.
pub(super) fn chunk_cells(nx: usize) -> usize {
    (CHUNK / nx).max(1) * nx
}
