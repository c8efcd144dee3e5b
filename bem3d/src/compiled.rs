//! Every solver family's public entry points, compiled once, in this crate, for each of
//! its operators.
//!
//! Why: a release build instantiates a generic function anew in every crate that calls
//! it, so a solver generic over its operator is compiled again by each caller (the
//! comparison layer, the CLI, the Python module, the test suites), at a minute or more
//! each. Here each public entry of a solver (its constructor and its solve or step)
//! calls a method of its operator's trait, [`SolverOperator`] for the normal families
//! and [`SlipOperator`] for the tangential ones, implemented for the crate's operators
//! by non-generic functions: callers link to the one compiled copy. The generic bodies
//! stay in the solvers' files (the methods named `*_generic`, bound on the operator
//! traits of [`crate::operator`] and [`TangentialCompliance`]); the other public
//! methods (accessors) stay beside them.

use crate::adhesion::{AdhesiveContact, AdhesiveStep};
use crate::cohesive::{CohesiveContact, CohesiveStep};
use crate::error::Result;
use crate::operator::{DenseCompliance, GridOperator, NonPeriodicHalfSpace, PeriodicHalfSpace};
use crate::plastic::{PlasticContact, PlasticStep};
use crate::solution::Solution;
use crate::solver::{ContactSolver, Load, SharedHeights, SolverOptions};
use crate::tangential::{
    CerrutiFree, CerrutiPeriodic, Cycle, PartialSlip, TangentialCompliance, TangentialStep,
    ViscoelasticSlip, ViscoelasticStep,
};
use crate::viscoelastic::{Relaxation, Step, TransientContact};

/// Everything the normal solvers ask of an operator ([`GridOperator`]: K, its
/// preconditioner, real-space sums and grid forms), and their entry points for it.
/// Implemented for [`PeriodicHalfSpace`], [`NonPeriodicHalfSpace`] and
/// [`DenseCompliance`]; the hidden methods are what the public methods of
/// [`ContactSolver`] call ([`HalfSpaceOperator`] adds the other normal families).
pub trait SolverOperator: GridOperator + Sized {
    #[doc(hidden)]
    fn contact_new(
        op: Self,
        heights: &[f64],
        mask: Option<Vec<bool>>,
    ) -> Result<ContactSolver<Self>>;
    #[doc(hidden)]
    fn contact_new_shared(
        op: Self,
        heights: SharedHeights,
        mask: Option<Vec<bool>>,
    ) -> Result<ContactSolver<Self>>;
    #[doc(hidden)]
    fn contact_set_heights(solver: &mut ContactSolver<Self>, heights: &[f64]) -> Result<()>;
    #[doc(hidden)]
    fn contact_solve(
        solver: &mut ContactSolver<Self>,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution>;
    #[doc(hidden)]
    fn contact_tangent_stiffness(
        solver: &mut ContactSolver<Self>,
        sol: &Solution,
        opts: &SolverOptions,
    ) -> Result<f64>;
}

/// A half-space operator (periodic or free) with the entry points of the other normal
/// families: adhesive, cohesive, plastic and transient viscoelastic contact. Implemented
/// for [`PeriodicHalfSpace`] and [`NonPeriodicHalfSpace`]; [`DenseCompliance`] carries
/// only the normal solver (it is that solver's dense reference and the operator of its
/// restricted solve), so that no family is compiled a third time for it. The hidden
/// methods are what the public methods of [`AdhesiveContact`], [`CohesiveContact`],
/// [`PlasticContact`] and [`TransientContact`] call.
pub trait HalfSpaceOperator: SolverOperator {
    #[doc(hidden)]
    fn adhesive_new(
        op: Self,
        heights: &[f64],
        mask: Option<&[bool]>,
        work: f64,
    ) -> Result<AdhesiveContact<Self>>;
    #[doc(hidden)]
    fn adhesive_step(
        contact: &mut AdhesiveContact<Self>,
        load: Load,
        tolerance: f64,
    ) -> Result<AdhesiveStep>;
    #[doc(hidden)]
    fn cohesive_new(
        op: Self,
        heights: &[f64],
        mask: Option<&[bool]>,
        work: f64,
        sigma0: f64,
    ) -> Result<CohesiveContact<Self>>;
    #[doc(hidden)]
    fn cohesive_step(
        contact: &mut CohesiveContact<Self>,
        d: f64,
        tolerance: f64,
    ) -> Result<CohesiveStep>;
    #[doc(hidden)]
    fn plastic_new(
        op: Self,
        heights: &[f64],
        mask: Option<&[bool]>,
        hardness: f64,
    ) -> Result<PlasticContact<Self>>;
    #[doc(hidden)]
    fn plastic_step(
        contact: &mut PlasticContact<Self>,
        load: Load,
        tolerance: f64,
    ) -> Result<PlasticStep>;
    #[doc(hidden)]
    fn transient_step(
        contact: &mut TransientContact<Self>,
        dt: f64,
        load: Load,
        opts: &SolverOptions,
    ) -> Result<Step>;
}

macro_rules! normal_entries {
    ($($op:ty),*) => {$(
        impl SolverOperator for $op {
            fn contact_new(
                op: Self,
                heights: &[f64],
                mask: Option<Vec<bool>>,
            ) -> Result<ContactSolver<Self>> {
                ContactSolver::new_generic(op, heights, mask)
            }
            fn contact_new_shared(
                op: Self,
                heights: SharedHeights,
                mask: Option<Vec<bool>>,
            ) -> Result<ContactSolver<Self>> {
                ContactSolver::new_shared_generic(op, heights, mask)
            }
            fn contact_set_heights(
                solver: &mut ContactSolver<Self>,
                heights: &[f64],
            ) -> Result<()> {
                solver.set_heights_generic(heights)
            }
            fn contact_solve(
                solver: &mut ContactSolver<Self>,
                load: Load,
                opts: &SolverOptions,
                warm: Option<&Solution>,
            ) -> Result<Solution> {
                solver.solve_generic(load, opts, warm)
            }
            fn contact_tangent_stiffness(
                solver: &mut ContactSolver<Self>,
                sol: &Solution,
                opts: &SolverOptions,
            ) -> Result<f64> {
                solver.tangent_stiffness_generic(sol, opts)
            }
        }
    )*};
}

macro_rules! family_entries {
    ($($op:ty),*) => {$(
        impl HalfSpaceOperator for $op {
            fn adhesive_new(
                op: Self,
                heights: &[f64],
                mask: Option<&[bool]>,
                work: f64,
            ) -> Result<AdhesiveContact<Self>> {
                AdhesiveContact::new_generic(op, heights, mask, work)
            }
            fn adhesive_step(
                contact: &mut AdhesiveContact<Self>,
                load: Load,
                tolerance: f64,
            ) -> Result<AdhesiveStep> {
                contact.step_generic(load, tolerance)
            }
            fn cohesive_new(
                op: Self,
                heights: &[f64],
                mask: Option<&[bool]>,
                work: f64,
                sigma0: f64,
            ) -> Result<CohesiveContact<Self>> {
                CohesiveContact::new_generic(op, heights, mask, work, sigma0)
            }
            fn cohesive_step(
                contact: &mut CohesiveContact<Self>,
                d: f64,
                tolerance: f64,
            ) -> Result<CohesiveStep> {
                contact.step_generic(d, tolerance)
            }
            fn plastic_new(
                op: Self,
                heights: &[f64],
                mask: Option<&[bool]>,
                hardness: f64,
            ) -> Result<PlasticContact<Self>> {
                PlasticContact::new_generic(op, heights, mask, hardness)
            }
            fn plastic_step(
                contact: &mut PlasticContact<Self>,
                load: Load,
                tolerance: f64,
            ) -> Result<PlasticStep> {
                contact.step_generic(load, tolerance)
            }
            fn transient_step(
                contact: &mut TransientContact<Self>,
                dt: f64,
                load: Load,
                opts: &SolverOptions,
            ) -> Result<Step> {
                contact.step_generic(dt, load, opts)
            }
        }
    )*};
}

normal_entries!(PeriodicHalfSpace, NonPeriodicHalfSpace, DenseCompliance);
family_entries!(PeriodicHalfSpace, NonPeriodicHalfSpace);

/// A tangential operator (Cerruti's tensor on a grid) with the partial-slip solvers'
/// entry points. Implemented for [`CerrutiPeriodic`], [`CerrutiFree`] and a boxed
/// operator of either kind; the hidden methods are what the public methods of
/// [`PartialSlip`] and [`ViscoelasticSlip`] call.
pub trait SlipOperator: TangentialCompliance + Sized {
    #[doc(hidden)]
    fn slip_new(op: Self, pressure: &[f64], mu: f64) -> Result<PartialSlip<Self>>;
    #[doc(hidden)]
    fn slip_cycle(
        slip: &mut PartialSlip<Self>,
        amplitude: f64,
        steps: usize,
        cycles: usize,
        tolerance: f64,
    ) -> Result<Cycle>;
    #[doc(hidden)]
    fn slip_load(
        slip: &mut PartialSlip<Self>,
        force: f64,
        tolerance: f64,
    ) -> Result<TangentialStep>;
    #[doc(hidden)]
    fn viscoelastic_slip_new(
        op: Self,
        pressure: &[f64],
        mu: f64,
        modulus: Relaxation,
    ) -> Result<ViscoelasticSlip<Self>>;
    #[doc(hidden)]
    fn viscoelastic_slip_step(
        slip: &mut ViscoelasticSlip<Self>,
        dt: f64,
        shift: f64,
        tolerance: f64,
    ) -> Result<ViscoelasticStep>;
}

macro_rules! tangential_entries {
    ($($op:ty),*) => {$(
        impl SlipOperator for $op {
            fn slip_new(op: Self, pressure: &[f64], mu: f64) -> Result<PartialSlip<Self>> {
                PartialSlip::new_generic(op, pressure, mu)
            }
            fn slip_cycle(
                slip: &mut PartialSlip<Self>,
                amplitude: f64,
                steps: usize,
                cycles: usize,
                tolerance: f64,
            ) -> Result<Cycle> {
                slip.cycle_generic(amplitude, steps, cycles, tolerance)
            }
            fn slip_load(
                slip: &mut PartialSlip<Self>,
                force: f64,
                tolerance: f64,
            ) -> Result<TangentialStep> {
                slip.load_generic(force, tolerance)
            }
            fn viscoelastic_slip_new(
                op: Self,
                pressure: &[f64],
                mu: f64,
                modulus: Relaxation,
            ) -> Result<ViscoelasticSlip<Self>> {
                ViscoelasticSlip::new_generic(op, pressure, mu, modulus)
            }
            fn viscoelastic_slip_step(
                slip: &mut ViscoelasticSlip<Self>,
                dt: f64,
                shift: f64,
                tolerance: f64,
            ) -> Result<ViscoelasticStep> {
                slip.step_generic(dt, shift, tolerance)
            }
        }
    )*};
}

tangential_entries!(
    CerrutiPeriodic,
    CerrutiFree,
    Box<dyn TangentialCompliance + Sync>
);

// The public entry points, each one call of its operator's compiled entry; their
// documentation is the solver's.

impl<K: SolverOperator> ContactSolver<K> {
    /// `heights` (`ny x nx`, peaks up, finite); `mask`: cells that may touch (None: all).
    /// The solver keeps a copy of the heights; it is built on the pool, as a solve (its
    /// parallel loops start in place).
    pub fn new(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
        K::contact_new(op, heights, mask)
    }

    /// As [`ContactSolver::new`] on heights the caller keeps: the solver reads them in
    /// place and holds no copy (the gap at zero approach is computed from them where it
    /// is read, bit for bit as from a copy). They must not change while the solver holds
    /// them (from Python: the array is checked before each solve).
    pub fn new_shared(op: K, heights: SharedHeights, mask: Option<Vec<bool>>) -> Result<Self> {
        K::contact_new_shared(op, heights, mask)
    }

    /// Replaces the height map (same grid and mask), keeping the operator and buffers;
    /// the solver keeps a copy.
    pub fn set_heights(&mut self, heights: &[f64]) -> Result<()> {
        K::contact_set_heights(self, heights)
    }

    /// Solves for `load`, starting from a previous solution `warm` where that pays (see
    /// the module docs of [`crate::solver`]; [`Solution::warm_started`] says whether it
    /// was used). A cold solve of a compact contact runs on a window first, one with a
    /// small start set restricted to a candidate set (module docs, [`Solution::path`]);
    /// if the window or the set outgrows its limit or a round does not converge, the
    /// attempt is dropped and the next path (last: the full iteration below) runs from
    /// its own start with `max_iterations` of its own (an attempt spends at most
    /// `max_iterations` iterations, over at most 8 rounds for a window and 24 for a
    /// set).
    ///
    /// Each iteration applies K once, to the conjugate direction t: `K p` moves by
    /// `-tau K t` and, where the projection clips a cell or re-admits an interpenetrating
    /// one, by K of those few point changes (a direct real-space sum below the operator's
    /// [`RealSpace::point_load_limit`](crate::operator::RealSpace::point_load_limit), a
    /// fresh `K p` above it). Before the solver reports convergence, `K p` is recomputed
    /// from scratch and the criterion re-evaluated, so rounding in the updates cannot pass
    /// for a solution.
    pub fn solve(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        K::contact_solve(self, load, opts, warm)
    }

    /// Tangent normal stiffness dF/dd with the contact set held fixed: solves
    /// `K_CC x = 1` on the contact cells C by conjugate gradients (K_CC is symmetric
    /// positive definite; preconditioned by the operator's M restricted to C) to
    /// relative residual `opts.tolerance` within `opts.max_iterations`;
    /// k = sum(x) * cell area.
    ///
    /// No contact: k = 0. Complete contact of an unmasked periodic surface: k = +inf
    /// (K_CC is then K itself, whose mean mode is free: the force grows at a fixed
    /// approach). A non-finite or vanishing step is a
    /// [`BemError::Breakdown`](crate::BemError::Breakdown).
    pub fn tangent_stiffness(&mut self, sol: &Solution, opts: &SolverOptions) -> Result<f64> {
        K::contact_tangent_stiffness(self, sol, opts)
    }
}

impl<C: HalfSpaceOperator> AdhesiveContact<C> {
    /// `heights` (`ny x nx`, finite), an optional `mask` of the cells that may touch, and
    /// the work of adhesion `work` > 0 [energy / length^2]. Starts out of contact.
    pub fn new(op: C, heights: &[f64], mask: Option<&[bool]>, work: f64) -> Result<Self> {
        C::adhesive_new(op, heights, mask, work)
    }

    /// Loads to `load` from the last state (`tolerance` relative, in (0, 0.01]).
    /// `Load::Approach` needs a non-periodic operator (a periodic surface has no
    /// defined mean displacement): prescribe the force there. A load beyond
    /// [`crate::solver::MAX_LOAD`] in magnitude (mean pressure over E*, approach over the
    /// map's size) is refused, as by the normal solve.
    pub fn step(&mut self, load: Load, tolerance: f64) -> Result<AdhesiveStep> {
        C::adhesive_step(self, load, tolerance)
    }
}

impl<C: HalfSpaceOperator> CohesiveContact<C> {
    /// `heights` (`ny x nx`), an optional mask, the work of adhesion `work` > 0 and the
    /// cohesive stress `sigma0` > 0 (the range is `work / sigma0`). On a periodic operator
    /// the approach fixes the mean gap (module docs). Starts out of contact.
    pub fn new(
        op: C,
        heights: &[f64],
        mask: Option<&[bool]>,
        work: f64,
        sigma0: f64,
    ) -> Result<Self> {
        C::cohesive_new(op, heights, mask, work, sigma0)
    }

    /// Loads to the approach `d` (from first contact) from the last state; `tolerance`
    /// relative, in (0, 0.01]; `|d|` at most [`crate::solver::MAX_LOAD`] times the map's
    /// size.
    pub fn step(&mut self, d: f64, tolerance: f64) -> Result<CohesiveStep> {
        C::cohesive_step(self, d, tolerance)
    }
}

impl<C: HalfSpaceOperator> PlasticContact<C> {
    /// `heights` (`ny x nx`, finite), an optional mask of the cells that may touch, and
    /// the hardness `H` > 0 [stress] (`f64::INFINITY`: the elastic contact). Starts out
    /// of contact, the surface undeformed.
    pub fn new(op: C, heights: &[f64], mask: Option<&[bool]>, hardness: f64) -> Result<Self> {
        C::plastic_new(op, heights, mask, hardness)
    }

    /// Loads to `load` from the last state (`tolerance` relative, in (0, 0.01]): an
    /// approach (any finite value: below first contact the body is apart) or a force
    /// or mean pressure in [0, [`Self::force_limit`]).
    pub fn step(&mut self, load: Load, tolerance: f64) -> Result<PlasticStep> {
        C::plastic_step(self, load, tolerance)
    }
}

impl<K: HalfSpaceOperator> TransientContact<K> {
    /// Advances by `dt` to the load `load` at the step's end (force, mean pressure or
    /// approach D, module docs); the load varies linearly over the step.
    pub fn step(&mut self, dt: f64, load: Load, opts: &SolverOptions) -> Result<Step> {
        K::transient_step(self, dt, load, opts)
    }
}

impl<C: SlipOperator> PartialSlip<C> {
    /// `pressure` (`ny x nx`, >= 0, finite) held, friction coefficient `mu` in
    /// (0, 1e6].
    pub fn new(op: C, pressure: &[f64], mu: f64) -> Result<Self> {
        C::slip_new(op, pressure, mu)
    }

    /// An oscillating tangential force of `amplitude` (below the friction limit): from the
    /// current state the force ramps to `amplitude` in `steps` steps, then runs `cycles`
    /// cycles down to `-amplitude` and back (`steps` steps each way); returns the last
    /// cycle (the first after a fresh start is already the steady loop of Masing's rule,
    /// a second one shows it).
    pub fn cycle(
        &mut self,
        amplitude: f64,
        steps: usize,
        cycles: usize,
        tolerance: f64,
    ) -> Result<Cycle> {
        C::slip_cycle(self, amplitude, steps, cycles, tolerance)
    }

    /// Loads to the tangential force `force` from the last state (`tolerance` relative,
    /// in (0, 0.1]).
    pub fn load(&mut self, force: f64, tolerance: f64) -> Result<TangentialStep> {
        C::slip_load(self, force, tolerance)
    }
}

impl<C: SlipOperator> ViscoelasticSlip<C> {
    /// `op` of unit shear modulus (e.g. [`CerrutiFree`] with `G = 1`), the held
    /// `pressure` (`ny x nx`), friction coefficient `mu`, shear relaxation `modulus`.
    /// The glassy modulus G*(0) lies in the operators' [`crate::operator::SCALE_RANGE`].
    pub fn new(op: C, pressure: &[f64], mu: f64, modulus: Relaxation) -> Result<Self> {
        C::viscoelastic_slip_new(op, pressure, mu, modulus)
    }

    /// Moves the body to the shift `shift` over the time `dt` (linearly in time), to
    /// `tolerance` (relative, in (0, 0.1]: the partial-slip solves' and the shift's).
    pub fn step(&mut self, dt: f64, shift: f64, tolerance: f64) -> Result<ViscoelasticStep> {
        C::viscoelastic_slip_step(self, dt, shift, tolerance)
    }
}

// The adhesive unit tests hold the windowed rounds against the same cycle on Love's
// dense matrix.
#[cfg(test)]
family_entries!(DenseCompliance);
