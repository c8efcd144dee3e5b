//! # bem3d: 3D FFT boundary-element half-space contact
//!
//! Frictionless, non-adhesive normal contact of a rigid body with an arbitrary height
//! map against a linear elastic half-space of modulus E* ([`solver`]); partial slip
//! with Coulomb friction under a held normal pressure, on the periodic or the free
//! half-space, elastic or viscoelastic under a prescribed shift, and the stiffness of a
//! contact held in full stick ([`tangential`]: solvers beside the normal one, on the
//! same transforms, with Cerruti's tensor); adhesive normal contact in the JKR limit
//! ([`adhesion`]: a solver beside the normal one, generic over the same operators) and
//! with a finite-range law, Maugis-Dugdale or exponential ([`cohesive`]). Knows nothing of MRD: it
//! takes plain height arrays (row-major `ny x nx`). Operators ([`operator`]) are apart
//! from the solvers; a linear solve restricted to a set of cells (the tangent and stick
//! stiffnesses) is shared by both kinds of solver.
//!
//! Public modules beyond the solvers and operators, and who needs them: [`fft`] (the
//! real 2D transform: `mrdw bench` times one convolution with it, and bem3d's tests
//! check the transforms), [`wide`] (the SIMD kernels, tested one by one in
//! `bem3d/tests`), [`mask`] (disc masks for scenes and tests). The symbols and the
//! stencil preconditioner are internal. [`ContactSolver::new_shared`] with
//! [`solver::SharedHeights`]: the Python package's `Contact` reads the caller's numpy
//! heights in place instead of keeping a second copy of the map.
//!
//! Each solver's constructor and solve or step is compiled here, once per operator
//! ([`SolverOperator`], [`HalfSpaceOperator`], [`SlipOperator`]: their hidden methods
//! are the entry points), so that a crate calling a solver links to that copy instead
//! of compiling the generic solver again.

// Numerical kernels index several parallel arrays with one index.
#![allow(clippy::needless_range_loop)]

pub mod adhesion;
pub mod cohesive;
mod compiled;
pub mod error;
pub mod fft;
mod kit;
mod love;
pub mod mask;
pub mod operator;
pub mod plastic;
mod pool;
mod set_solve;

pub use compiled::{HalfSpaceOperator, SlipOperator, SolverOperator};
pub use error::{BemError, Result};
pub mod sliding;
pub mod solution;
pub mod solver;
mod stencil;
mod symbol;
pub mod tangential;
pub mod viscoelastic;
pub mod wide;
pub use operator::{
    Compliance, DenseCompliance, GridForms, NonPeriodicHalfSpace, Operand, PeriodicHalfSpace,
    Precision, Preconditioner, RealSpace, Spectral, Transform,
};
pub use sliding::{SlidingContact, SlidingSolution};
pub use solver::{
    Choice, ContactSolver, Interrupt, Load, Path, Paths, Solution, SolverOptions, MAX_TOLERANCE,
};

#[cfg(test)]
mod testing;
