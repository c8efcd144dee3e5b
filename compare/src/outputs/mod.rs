//! Output kinds, grouped as the paper is: one file per kind, one folder per study. The
//! trait they implement is [`crate::output::Output`]; the list of kinds is
//! [`crate::registry::KINDS`], above every kind, so that no kind imports the module that
//! lists it. Shared pieces live below the kinds: checks and defaults in
//! [`crate::checks`], rough punches, fits and lambda in [`crate::experiment`].

/// Axisymmetric MRD, exact by the rule of Hess (Sections 3-7).
pub mod axisym;
/// The contact inside a time integration (Section 12).
pub mod dynamics;
/// Friction: static (Section 10.2) and sliding (Section 10.1, Fig. 7).
pub mod friction;
/// Published reference results held against MRD and the 3D solvers (all sections).
pub mod literature;
/// 3D boundary-element references on the user's own height maps.
pub mod reference3d;
/// Rough contact: Eq. (76), Fig. 6, the calibration of lambda (Section 9, 11).
pub mod rough;
/// Viscoelasticity (Section 8).
pub mod viscoelastic;
