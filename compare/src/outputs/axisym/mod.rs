//! Axisymmetric MRD, exact by the rule of Hess (Eq. 11): profile, force-depth, pressure,
//! adhesion, tangential loading and damping (Sections 3-7).

pub mod adhesion;
pub mod adhesion_3d;
pub mod damping;
pub mod force_depth;
pub mod plastic_3d;
pub mod pressure;
pub mod profile_1d;
pub mod tabor_3d;
pub mod tangential;
pub mod tangential_3d;
