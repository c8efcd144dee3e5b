//! # dynamics: the contact inside a macroscopic simulation (the review's Section 12)
//!
//! A contact law a time integrator calls at every step ([`ContactLaw`]): it takes the
//! relative motion of the step (normal approach, tangential displacement, time step)
//! and returns the contact forces, keeps its own history (stick and slip of each
//! spring or cell), and lets the integrator try a step and accept it ([`ContactLaw::commit`])
//! or reject it ([`ContactLaw::rollback`]), so implicit and adaptive integrators can
//! use it. One trait, two families behind it:
//!
//! - MRD ([`law::Springs`]): the independent springs of the method of reduction of
//!   dimensionality: a body of revolution by the rule of Hess (Eq. 11), or a rough line
//!   (C1D = lambda q C2D, Eq. 76), normal springs `E* dx` found in O(log N) per step from
//!   sorted gaps and prefix sums; tangential springs `G* dx` with Coulomb slip, each
//!   with its own history (Sections 6-7).
//! - 3D ([`law::Bem3d`]): the boundary-element normal solve of `bem3d`, under the step's
//!   approach, warm-started from the last accepted state.
//! - Tangential, both ways: MRD's springs with Coulomb slip ([`law::Springs::with_friction`])
//!   and the 3D partial slip at a held normal force ([`slip::SlipBem3d`]), each taking the
//!   body's tangential displacement; the 3D contact with both motions free
//!   ([`oblique::ObliqueBem3d`]: the pressure solved at each step, the slip carried over),
//!   whose 1D counterpart is MRD's springs with friction.
//! - Viscoelastic, both ways ([`viscoelastic`]): MRD's springs with the hereditary
//!   integral of a relaxing modulus (Eq. 63) and the 3D transient solve on the same
//!   modulus, whose force depends on the history of the motion.
//! - Adhesive, both ways ([`adhesive`]): MRD's springs with Eq. 33's detachment and the
//!   3D adhesive solve, in the JKR limit (tensile forces negative).
//!
//! The integrator ([`integrate`]) advances one degree of freedom: a mass under an
//! external force and the contact force, by velocity Verlet, with step rejection on a
//! force jump (the rollback in use). `mrd` and `bem3d` know nothing of time stepping;
//! the scenes that use this crate live in `compare`.

pub mod adhesive;
mod held;
pub mod integrate;
pub mod law;
pub mod oblique;
pub mod slip;
pub mod viscoelastic;

pub use adhesive::{AdhesiveBem3d, AdhesiveSprings};
pub use law::{Bem3d, ContactLaw, Forces, Motion, Springs};
pub use oblique::ObliqueBem3d;
pub use slip::SlipBem3d;
pub use viscoelastic::{ViscoelasticBem3d, ViscoelasticSprings};

/// What can go wrong in a contact law or an integration.
#[derive(Debug, thiserror::Error)]
pub enum DynamicsError {
    /// A parameter outside its range; the message names it.
    #[error("{0}")]
    InvalidInput(String),
    #[error("MRD: {0}")]
    Mrd(#[from] mrd::error::MrdError),
    #[error("3D: {0}")]
    Bem(#[from] bem3d::BemError),
}

pub type Result<T> = std::result::Result<T, DynamicsError>;

fn bad<T>(message: impl Into<String>) -> Result<T> {
    Err(DynamicsError::InvalidInput(message.into()))
}
