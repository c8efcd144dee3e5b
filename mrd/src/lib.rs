//! # mrd: the method of reduction of dimensionality
//!
//! Maps axisymmetric 3D contacts exactly onto a 1D row of independent springs
//! (Winkler foundation with stiffness E* dx, Eq. 3, and G* dx, Eq. 6) carrying the
//! profile transformed by the rule of Hess (Eq. 11). Equation numbers refer to
//! Popov & Hess, "Method of reduction of dimensionality in contact and friction
//! mechanics: A linkage between micro and macro scales", Friction 1 (2013) 41-62.
//!
//! Layout: physics modules (`material`, `profile`, `normal`, `pressure`, `adhesion`,
//! `tangential`, `oscillation`) build on `numerics` (quadrature, root finding);
//! `reference` holds the closed forms the tests compare against; `foundation` is the
//! discretised spring row.

pub mod error;
pub mod hess;
pub mod material;
pub mod numerics;
pub mod profile;
pub mod reference;
pub mod rheology;

pub use error::{MrdError, Result};
pub use material::{ElasticBody, Material};
pub use profile::{Profile, Shape, TabulatedProfile};
pub mod adhesion;
pub mod adhesive_row;
pub mod discrete;
pub mod foundation;
pub mod friction;
pub mod normal;
pub mod oscillation;
pub mod plastic_line;
pub mod plasticity;
pub mod pressure;
pub mod rough_contact;
pub mod roughness;
pub mod sliding;
pub mod tangential;
pub mod topography;
pub mod viscoelastic;
