//! Rough contact: MRD lines from Eq. (76) against 3D (Section 9, Fig. 6; Section 11),
//! and the studies that calibrate lambda(H).

pub mod contact_area;
pub mod hurst_sweep;
pub mod lambda_study;
pub mod rough_sphere;
pub mod rough_stiffness;
