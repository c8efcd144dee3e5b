//! What a solve is asked for: the load ([`Load`]) and the options ([`SolverOptions`]:
//! tolerance, iteration cap, an [`Interrupt`] flag).

use crate::error::{BemError, Result};

/// The load prescribed to a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// Total normal force.
    Force(f64),
    /// Mean pressure over the whole grid area lx * ly.
    MeanPressure(f64),
    /// Rigid-body approach d (measured from first contact).
    Approach(f64),
}

#[derive(Debug, Clone)]
pub struct SolverOptions {
    /// Convergence criterion (module docs), in (0, [`MAX_TOLERANCE`]].
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Polled once per iteration: when it is set the solve stops with
    /// [`BemError::Interrupted`] (a caller's Ctrl-C).
    pub interrupt: Option<Interrupt>,
    /// The strategies a solve may use (all by default); the [`Solution`](super::Solution)
    /// says which ran.
    pub paths: Paths,
}

/// The solver's strategies (its module docs), each allowed where it applies or
/// forbidden. Every combination reaches the same fixed point: they change the work, not
/// the answer (beyond the tolerance), which the tests check path against path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Paths {
    /// A window around a compact contact (non-periodic half-space).
    pub window: bool,
    /// A candidate set of cells for small contact sets.
    pub candidate_set: bool,
    /// The preconditioner by its stencil on small contact sets.
    pub stencil: bool,
    /// The start from the grid coarsened 2 x 2 (large grids under force control).
    pub nested_start: bool,
    /// K's single-precision form while the criterion is above 1e-4, and for the
    /// direction's `K t` throughout (else K in double precision everywhere).
    pub single_precision: bool,
}

impl Default for Paths {
    fn default() -> Self {
        Paths {
            window: true,
            candidate_set: true,
            stencil: true,
            nested_start: true,
            single_precision: true,
        }
    }
}

impl Paths {
    /// Every strategy except the restricted paths: the iteration on the whole grid.
    pub fn full_grid() -> Self {
        Paths {
            window: false,
            candidate_set: false,
            ..Paths::default()
        }
    }

    /// The plainest solve: the whole grid, M by transforms, a cold start, K in double
    /// precision.
    pub fn plain() -> Self {
        Paths {
            window: false,
            candidate_set: false,
            stencil: false,
            nested_start: false,
            single_precision: false,
        }
    }
}

/// Largest load a solve accepts, as a mean pressure over E* or an approach over the map's
/// size.
pub const MAX_LOAD: f64 = 1e10;

/// Largest tolerance a solve accepts: beyond it the criterion no longer bounds the
/// answer's error usefully (at 1 the pressures of a rough contact are off by 10 % or
/// more).
pub const MAX_TOLERANCE: f64 = 1e-2;

impl Default for SolverOptions {
    fn default() -> Self {
        Self::new(1e-10, 10_000)
    }
}

impl SolverOptions {
    /// The options of a solve to `tolerance` in at most `max_iterations` iterations.
    pub fn new(tolerance: f64, max_iterations: usize) -> Self {
        Self {
            tolerance,
            max_iterations,
            interrupt: None,
            paths: Paths::default(),
        }
    }

    /// Refuses a tolerance outside (0, [`MAX_TOLERANCE`]] or no iterations; the one
    /// check of the command line and the Python package.
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance > 0.0 && self.tolerance <= MAX_TOLERANCE) {
            return Err(BemError::InvalidInput(format!(
                "tolerance = {:e} must lie in (0, {MAX_TOLERANCE:e}]",
                self.tolerance
            )));
        }
        if self.max_iterations == 0 {
            return Err(BemError::InvalidInput("max_iterations must be >= 1".into()));
        }
        Ok(())
    }

    /// Whether the caller asked the solve to stop.
    pub(super) fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(Interrupt::is_set)
    }
}

/// A flag a caller sets (from another thread) to stop solves that poll it.
#[derive(Debug, Clone, Default)]
pub struct Interrupt(std::sync::Arc<std::sync::atomic::AtomicBool>);

impl Interrupt {
    pub fn set(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }
    pub fn clear(&self) {
        self.0.store(false, std::sync::atomic::Ordering::Relaxed);
    }
    pub fn is_set(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }
}
