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

/// A [`Load`] resolved on the grid: what an iteration holds fixed, a total force (a
/// mean pressure times the grid's area) or an approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Target {
    Force(f64),
    Approach(f64),
}

impl Target {
    /// The force held under force control (None: an approach is held).
    pub(super) fn force(self) -> Option<f64> {
        match self {
            Target::Force(f) => Some(f),
            Target::Approach(_) => None,
        }
    }

    /// The approach the gaps are measured from: the prescribed one, or 0 under force
    /// control (where the approach is the mean gap over the contact measured from it).
    pub(super) fn base_approach(self) -> f64 {
        match self {
            Target::Force(_) => 0.0,
            Target::Approach(d) => d,
        }
    }
}

#[derive(Debug, Clone)]
pub struct SolverOptions {
    /// Convergence criterion (module docs), in (0, [`MAX_TOLERANCE`]].
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Polled once per iteration: when it is set the solve stops with
    /// [`BemError::Interrupted`] (a caller's Ctrl-C).
    pub interrupt: Option<Interrupt>,
    /// The strategies a solve may or must use (all allowed by default); the
    /// [`Solution`](super::Solution) says which ran.
    pub paths: Paths,
}

/// Whether a solve may, must or must not use one of its strategies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Choice {
    /// Never.
    Forbid,
    /// Where it applies and, by the solver's measured rules, pays (the default).
    #[default]
    Allow,
    /// Wherever it can run, without the rules that judge whether it pays; a solve whose
    /// forced strategy cannot run (the operator lacks it, the load or the grid does not
    /// admit it, or it gives up) fails with [`BemError::PathUnavailable`] instead of
    /// falling back to another path.
    Force,
}

impl std::str::FromStr for Choice {
    type Err = String;

    /// `forbid`, `allow` or `force` (the command line's and the Python package's
    /// spelling).
    fn from_str(name: &str) -> std::result::Result<Self, String> {
        match name {
            "forbid" => Ok(Choice::Forbid),
            "allow" => Ok(Choice::Allow),
            "force" => Ok(Choice::Force),
            other => Err(format!(
                "{other:?}: give \"forbid\", \"allow\" or \"force\""
            )),
        }
    }
}

impl Choice {
    pub fn allowed(self) -> bool {
        self != Choice::Forbid
    }
    pub fn forced(self) -> bool {
        self == Choice::Force
    }
}

/// The solver's strategies (its module docs), each forbidden, allowed where it pays, or
/// forced. Every combination reaches the same fixed point: they change the work, not
/// the answer (beyond the tolerance), which the tests check path against path.
///
/// What forcing one means:
/// - `window`: every solve runs on a window, whatever its size (up to the whole grid)
///   and whatever a warm start offers; needs the non-periodic operator (a zero load
///   needs no solve and is not refused).
/// - `candidate_set`: every solve runs on a candidate set of up to 4096 cells (the
///   dense matrix's memory), whatever its cost against the full grid; needs an operator
///   with a real-space table.
/// - `stencil`: M by its stencil at every iteration of the grid and window paths,
///   whatever the contact fraction; needs an operator with one.
/// - `nested_start`: the start from the coarsened grid on any grid with even sides of
///   at least 2 cells (its coarse solve nests by the usual rule); needs force control,
///   no mask and an operator with a coarse form, and overrides a warm start.
/// - `single_precision`: as allowed (the single-precision phase runs whenever the
///   criterion is above 1e-4), and the operator must have a single-precision form.
/// - `scaled_directions`: on every grid, whatever its size (any operator).
///
/// At most one of `window`, `candidate_set` and `nested_start` can be forced: each is
/// a different way to begin a cold solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Paths {
    /// A window around a compact contact (non-periodic half-space).
    pub window: Choice,
    /// A candidate set of cells for small contact sets.
    pub candidate_set: Choice,
    /// The preconditioner by its stencil on small contact sets.
    pub stencil: Choice,
    /// The start from the grid coarsened 2 x 2 (large grids under force control).
    pub nested_start: Choice,
    /// K's single-precision form while the criterion is above 1e-4, and for the
    /// direction's `K t` throughout (else K in double precision everywhere).
    pub single_precision: Choice,
    /// The direction vectors t and y_prev stored as 16-bit integers with a power-of-two
    /// scale per row chunk instead of single precision (allowed: on grids above 2048^2
    /// cells, where memory decides what fits).
    pub scaled_directions: Choice,
}

impl Paths {
    /// Every strategy except the restricted paths: the iteration on the whole grid.
    pub fn full_grid() -> Self {
        Paths {
            window: Choice::Forbid,
            candidate_set: Choice::Forbid,
            ..Paths::default()
        }
    }

    /// The plainest solve: the whole grid, M by transforms, a cold start, K in double
    /// precision, the directions in single precision.
    pub fn plain() -> Self {
        Paths {
            window: Choice::Forbid,
            candidate_set: Choice::Forbid,
            stencil: Choice::Forbid,
            nested_start: Choice::Forbid,
            single_precision: Choice::Forbid,
            scaled_directions: Choice::Forbid,
        }
    }

    /// The strategies' names, as [`Paths::set`] takes them.
    pub const NAMES: [&'static str; 6] = [
        "window",
        "candidate_set",
        "stencil",
        "nested_start",
        "single_precision",
        "scaled_directions",
    ];

    /// Sets the strategy called `name` (one of [`Paths::NAMES`], the field's name) to
    /// `choice`; an unknown name is an error that lists the known ones.
    pub fn set(&mut self, name: &str, choice: Choice) -> std::result::Result<(), String> {
        let slot = match name {
            "window" => &mut self.window,
            "candidate_set" => &mut self.candidate_set,
            "stencil" => &mut self.stencil,
            "nested_start" => &mut self.nested_start,
            "single_precision" => &mut self.single_precision,
            "scaled_directions" => &mut self.scaled_directions,
            other => {
                return Err(format!(
                    "no strategy {other:?} ({})",
                    Self::NAMES.join(", ")
                ))
            }
        };
        *slot = choice;
        Ok(())
    }

    /// Refuses two forced paths that exclude each other.
    fn validate(&self) -> Result<()> {
        let forced = [
            ("window", self.window),
            ("candidate_set", self.candidate_set),
            ("nested_start", self.nested_start),
        ];
        let names: Vec<&str> = forced
            .iter()
            .filter(|(_, c)| c.forced())
            .map(|(n, _)| *n)
            .collect();
        if names.len() > 1 {
            return Err(BemError::InvalidInput(format!(
                "paths: {} are forced together, but a solve takes one of them",
                names.join(" and ")
            )));
        }
        Ok(())
    }
}

/// Largest load a solve accepts, as a mean pressure over E* or an approach over the map's
/// size.
pub const MAX_LOAD: f64 = 1e10;

/// Refuses a load of a history solver (adhesive, cohesive: its loads may pull) beyond
/// [`MAX_LOAD`] in magnitude, the normal solve's bound: linear elasticity and double
/// precision both end long before it.
pub(crate) fn check_load_magnitude(load: Load, e_star: f64, (lx, ly): (f64, f64)) -> Result<()> {
    let (bound, size) = (MAX_LOAD * e_star, lx.max(ly));
    let too_large = match load {
        Load::Force(f) if (f / (lx * ly)).abs() > bound => format!(
            "load: a force of {f:e} is a mean pressure of {:e}, more than {MAX_LOAD:e} E* = {bound:e} in magnitude",
            f / (lx * ly)
        ),
        Load::MeanPressure(p) if p.abs() > bound => format!(
            "load: a mean pressure of {p:e} is more than {MAX_LOAD:e} E* = {bound:e} in magnitude"
        ),
        Load::Approach(d) if d.abs() > MAX_LOAD * size => format!(
            "approach = {d:e} is more than {MAX_LOAD:e} times the map's size {size:e} in magnitude"
        ),
        _ => return Ok(()),
    };
    Err(BemError::InvalidInput(too_large))
}

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

    /// Refuses a tolerance outside (0, [`MAX_TOLERANCE`]], no iterations or forced paths
    /// that exclude each other; the one check of the command line and the Python
    /// package.
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
        self.paths.validate()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn choices_and_strategies_by_name() {
        for (name, choice) in [
            ("forbid", Choice::Forbid),
            ("allow", Choice::Allow),
            ("force", Choice::Force),
        ] {
            assert_eq!(name.parse::<Choice>(), Ok(choice));
        }
        let e = "Force".parse::<Choice>().unwrap_err();
        assert!(e.contains("\"forbid\", \"allow\" or \"force\""), "{e}");
        // Each name sets its own field and no other.
        for (k, name) in Paths::NAMES.iter().enumerate() {
            let mut paths = Paths::default();
            paths.set(name, Choice::Force).unwrap();
            let fields = [
                paths.window,
                paths.candidate_set,
                paths.stencil,
                paths.nested_start,
                paths.single_precision,
                paths.scaled_directions,
            ];
            for (i, c) in fields.iter().enumerate() {
                assert_eq!(c.forced(), i == k, "{name}");
            }
        }
        let e = Paths::default().set("windows", Choice::Force).unwrap_err();
        assert!(
            e.contains("no strategy \"windows\"") && e.contains("scaled_directions"),
            "{e}"
        );
    }
}
