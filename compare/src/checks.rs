//! The checks and defaults that the output kinds share: scene errors, ranges of counts,
//! memory estimates (bytes per spring and per cell), default sizes.

use crate::error::{CompareError, Result};

/// A scene error (the caller adds which output it is).
pub(crate) fn bad<T>(what: impl Into<String>) -> Result<T> {
    Err(CompareError::Scene(what.into()))
}

pub(crate) fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// A scene key that must be finite and positive: the error names the key and the value
/// the scene gave.
pub(crate) fn require_positive(key: &str, value: f64) -> Result<()> {
    if positive(value) {
        Ok(())
    } else {
        bad(format!("{key} = {value} must be finite and > 0"))
    }
}

/// A count key (`realisations`, `loads`, `f_points`, ...) within `range`: the bounds keep
/// a run's size (tasks, table rows) within what a machine can hold and finish.
pub(crate) fn count_in(key: &str, value: u64, range: std::ops::RangeInclusive<u64>) -> Result<()> {
    if range.contains(&value) {
        Ok(())
    } else {
        bad(format!(
            "{key} = {value} must lie in {}..={}",
            range.start(),
            range.end()
        ))
    }
}

/// A 3D solver tolerance from a scene: the solver's own range and message
/// ([`bem3d::SolverOptions::validate`]).
pub(crate) fn check_tolerance(tolerance: f64) -> Result<()> {
    bem3d::SolverOptions::new(tolerance, 1)
        .validate()
        .or_else(|e| bad(e.to_string()))
}

/// The 3D and MRD ensemble sizes of a comparison: at least 2 each, for intervals.
pub(crate) fn check_ensembles(realisations_3d: u64, realisations_1d: u64) -> Result<()> {
    count_in("realisations_3d", realisations_3d, 2..=MAX_REALISATIONS)?;
    count_in("realisations_1d", realisations_1d, 2..=MAX_REALISATIONS)
}

/// Fewest cells per contact radius of a 3D partial-slip grid: at 3.2 the slip annulus of
/// a cycle at 0.2-0.8 mu F_N held no cell (a dissipation of 0 against Mindlin's 7.8e-5);
/// at 8 the stick radius is within a cell and every amplitude the scenes use slips.
pub(crate) const MIN_CELLS_PER_CONTACT_RADIUS: f64 = 8.0;

/// Most realisations any output computes (tasks are listed before they run).
pub(crate) const MAX_REALISATIONS: u64 = 100_000;
/// Most load points of a force-controlled curve.
pub(crate) const MAX_LOADS: u64 = 10_000;
/// Fewest cells in contact a rough 3D realisation is measured on: one touching cell is
/// no rough contact and has no partial slip (the CI scenes' realisations reach about
/// 40-100, the full scenes' hundreds to thousands).
pub(crate) const MIN_CONTACT_CELLS: usize = 16;

/// The half-length of a spring row: `given` if it covers the largest contact radius
/// `a_max` the output reaches (springs beyond the row cannot touch), else an error
/// naming both; without it `default_factor x a_max`.
pub(crate) fn row_half_length(given: Option<f64>, a_max: f64, default_factor: f64) -> Result<f64> {
    match given {
        None if positive(default_factor * a_max) => Ok(default_factor * a_max),
        None => bad(format!(
            "springs: the largest contact radius is {a_max:e}, so the default half_length ({default_factor} x it) is unusable; give half_length > 0 or a larger max"
        )),
        Some(l) if positive(l) && l > a_max => Ok(l),
        Some(l) => bad(format!(
            "half_length = {l:e} does not cover the largest contact radius this output reaches, {a_max:e}: give half_length > {a_max:e}, or leave it out ({default_factor} x that radius)"
        )),
    }
}

/// `points` of an axisymmetric output.
pub(crate) fn check_points(points: usize) -> Result<()> {
    if !(2..=100_000).contains(&points) {
        return bad(format!("points = {points} must lie in 2..=100000"));
    }
    Ok(())
}

/// Peak bytes per spring of the 1D outputs, for their memory checks: the growth of the
/// peak resident memory of `mrdw run` per spring, raised by about a quarter (measured
/// between 1e6 and 2e6 springs on one thread: force_depth 22, adhesion 196, damping 14,
/// viscoelastic with one Prony term 22, tangential_viscoelastic with one 56, a rough line
/// 60; per further term 8 and 8.3, per further thread 36-37 bytes, between 1e3 and
/// 2e6-4e6 springs; `spring_memory_estimates_hold` in tests/suite/robustness.rs measures
/// the one-term, one-thread figures again). Per grid cell of the 3D scenes:
/// [`cell_bytes`].
pub mod spring_bytes {
    pub const FORCE_DEPTH: f64 = 30.0;
    pub const ADHESION: f64 = 250.0;
    pub const DAMPING: f64 = 18.0;
    pub fn viscoelastic(terms: usize) -> f64 {
        18.0 + 10.0 * terms as f64
    }
    pub fn tangential_viscoelastic(terms: usize) -> f64 {
        56.0 + 11.0 * terms as f64
    }
    /// A rough line's point, with one line per worker thread at a time.
    pub fn rough_line(threads: usize) -> f64 {
        55.0 + 45.0 * threads as f64
    }
}
pub(crate) use bem3d::operator::{BYTES_PER_CELL_NON_PERIODIC, BYTES_PER_CELL_PERIODIC};

/// Peak bytes per cell of the finest 3D grid of each 3D scene, for its memory check: the
/// solver's own figure ([`BYTES_PER_CELL_PERIODIC`], [`BYTES_PER_CELL_NON_PERIODIC`])
/// and the scene's arrays beside it (the synthesis, the maps it keeps, the results).
/// Each is the peak resident memory of a whole `mrdw run --threads 1` over the cells of
/// its finest grid at 1024^2 and 2048^2, raised by a tenth or more, so that it bounds the
/// measured peak from above (bench/HISTORY.md, the two sections "Peak memory of ...";
/// `cell_memory_estimates_hold` in tests/suite/robustness.rs measures them again at
/// 128^2-512^2). A process adds about 11 MB besides, which matters on no machine.
pub mod cell_bytes {
    use super::{BYTES_PER_CELL_NON_PERIODIC as FREE, BYTES_PER_CELL_PERIODIC as PERIODIC};

    /// A rough map on the free half-space with its synthesis and kept results:
    /// `hurst_sweep`, `contact_area`, `calibrate`, `lambda_study`, `rough_sphere` and
    /// `static_friction_3d` on discs (measured 165-242 at 1024^2, 203-210 at 2048^2).
    pub const ROUGH_FREE: f64 = FREE + 80.0;
    /// A rough periodic patch with its synthesis: `static_friction_3d` on squares
    /// (127 at 1024^2, 119 at 2048^2).
    pub const ROUGH_PERIODIC: f64 = PERIODIC + 80.0;
    /// `viscoelastic_rough`: a viscoelastic and an elastic solver per realisation
    /// (383 at 1024^2, 358 at 2048^2).
    pub const VISCOELASTIC_ROUGH: f64 = 2.0 * (FREE + 40.0);
    /// An adhesive cycle on the free half-space: `rough_adhesion_3d` (272 at 1024^2),
    /// `adhesion_3d` (274 at 1024^2) and `tabor_3d` (174 at 512^2); from Python,
    /// `AdhesiveContact` and `CohesiveContact` (275 and 192 at 512^2 above the
    /// interpreter's own memory, the adhesive 221 at 1024^2).
    pub const ADHESION: f64 = FREE + 140.0;
    /// The same on a periodic cell: Python's `AdhesiveContact` and `CohesiveContact`
    /// (121 and 131 at 512^2).
    pub const ADHESION_PERIODIC: f64 = PERIODIC + 100.0;
    /// `rough_slip_3d`: the normal solve, then partial slip on the free half-space
    /// (425 at 1024^2).
    pub const ROUGH_SLIP: f64 = FREE + 300.0;
    /// `rough_partial_slip_3d` on periodic patches (208 at 1024^2, 178 at 2048^2).
    pub const ROUGH_PARTIAL_SLIP: f64 = PERIODIC + 160.0;
    /// `tangential_stiffness_3d`: two-component stick solves (340 at 1024^2, 294 at
    /// 2048^2).
    pub const TANGENTIAL_STIFFNESS: f64 = PERIODIC + 290.0;
    /// `sliding_friction_3d`: the sliding solver's accelerated iteration on `grid` and
    /// the coarse check on `grid / 2` (372 at 1024^2; 398 for each cell added from
    /// 128^2 to 512^2).
    pub const SLIDING: f64 = 9.0 * PERIODIC;
    /// `tangential_3d`'s normal and partial-slip solves (periodic 181 at 1024^2 on two
    /// threads, 111 at 2048^2; free 299 at 1024^2).
    pub fn tangential_3d(periodic: bool) -> f64 {
        if periodic {
            PERIODIC + 120.0
        } else {
            FREE + 184.0
        }
    }
    /// `tangential_viscoelastic`'s 3D side (284 at 512^2).
    pub const TANGENTIAL_VISCOELASTIC: f64 = FREE + 200.0;
}

/// Refuses work whose memory estimate exceeds what this process may allocate
/// ([`sysmem::check_estimate`]: free memory, rlimits, cgroup).
pub fn check_memory(bytes: f64, what: &str) -> Result<()> {
    sysmem::check_estimate(bytes, what).map_err(CompareError::from)
}

/// [`check_memory`] for `bytes` that each worker thread holds at once (one task per
/// thread: a 3D grid, a set of springs).
pub(crate) fn check_memory_per_thread(bytes: f64, what: &str) -> Result<()> {
    check_memory(bytes * rayon::current_num_threads() as f64, what)
}

/// A spring count: at least 2, and within memory at `bytes` per spring
/// ([`spring_bytes`]).
pub(crate) fn check_springs(springs: usize, bytes: f64) -> Result<()> {
    if springs < 2 {
        return bad(format!("springs = {springs} must be >= 2"));
    }
    check_memory(springs as f64 * bytes, &format!("springs = {springs}"))
}

pub(crate) fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

pub(crate) fn default_points() -> usize {
    60
}
pub(crate) fn default_springs() -> usize {
    20_000
}
pub(crate) fn default_realisations() -> u64 {
    100
}
/// The 3D solver tolerance of the comparison kinds.
pub(crate) fn default_tolerance() -> f64 {
    1e-8
}
pub(crate) fn default_force_points() -> usize {
    30
}
/// A count's default written where its key is declared:
/// `#[serde(default = "crate::checks::default_count::<8>")]`.
pub(crate) fn default_count<const N: usize>() -> usize {
    N
}
/// [`default_count`] for the keys counted in `u64` (realisations, lines).
pub(crate) fn default_count_u64<const N: u64>() -> u64 {
    N
}
/// The default of a switch that is on unless the scene turns it off.
pub(crate) fn default_true() -> bool {
    true
}

/// The checks shared by the rough-line outputs.
pub(crate) fn check_line(hurst: f64, points: usize, length: f64, realisations: u64) -> Result<()> {
    if !(-1.0..=3.0).contains(&hurst) {
        return bad(format!("hurst = {hurst} must lie in [-1, 3]"));
    }
    if !(64..=50_000_000).contains(&points) {
        return bad(format!("points = {points} must lie in 64..=5e7"));
    }
    require_positive("length", length)?;
    // At least 2, for intervals.
    count_in("realisations", realisations, 2..=1_000_000)?;
    // One line per worker thread at a time.
    check_memory(
        points as f64 * spring_bytes::rough_line(rayon::current_num_threads()),
        &format!("points = {points} per line"),
    )
}

/// Each (key, value) of `values` must lie in the range of magnitudes the solvers take
/// (`mrd::error::MAGNITUDE_RANGE`); the message names the first key outside it.
pub(crate) fn check_magnitudes(values: &[(&str, f64)]) -> Result<()> {
    let (lo, hi) = mrd::error::MAGNITUDE_RANGE;
    match values.iter().find(|(_, v)| !(lo..=hi).contains(v)) {
        Some((name, v)) => bad(format!("{name} = {v:e} must lie in [{lo:e}, {hi:e}]")),
        None => Ok(()),
    }
}

/// The smallest tangential force over mu F_N a rough partial-slip output takes. The
/// mapped shift is a difference of two normal approaches a fraction apart, so its
/// rounding error relative to it grows as 1 / fraction: on the rough punch of
/// `rough-partial-slip-3d-ci`, against the shift at 1e-4 (scaled), it is off by 4e-6 at
/// 1e-6, by 2e-3 at 1e-9 and by 3 % at 1e-10; below about 1e-20 it is 0/0.
pub(crate) const MIN_FRACTION: f64 = 1e-6;

/// `name` = `v`: tangential forces as fractions of mu F_N in [[`MIN_FRACTION`], 1),
/// increasing if asked.
pub(crate) fn check_fractions(name: &str, v: &[f64], increasing: bool) -> Result<()> {
    if v.is_empty()
        || v.iter().any(|x| !(*x >= MIN_FRACTION && *x < 1.0))
        || (increasing && v.windows(2).any(|w| w[1] <= w[0]))
    {
        return bad(format!(
            "{name} = {v:?}: give{} fractions of mu F_N in [{MIN_FRACTION:e}, 1) (at 1 the \
             body slides; below {MIN_FRACTION:e} the mapped shift is lost to rounding)",
            if increasing { " increasing" } else { "" }
        ));
    }
    Ok(())
}
