//! Rough contact: MRD lines from Eq. (76) against 3D (Section 9, Fig. 6; Section 11),
//! the studies that calibrate lambda(H), and the tangential springs of a rough contact
//! (Section 6 on rough surfaces) and of a rough adhesive sphere (Section 5).

pub mod calibrate;
pub mod contact_area;
pub mod hurst_sweep;
pub mod lambda_study;
pub mod rough_adhesion_3d;
pub mod rough_partial_slip_3d;
pub mod rough_plastic_3d;
pub mod rough_slip_3d;
pub mod rough_sphere;
pub mod rough_stiffness;
pub mod tangential_stiffness_3d;
