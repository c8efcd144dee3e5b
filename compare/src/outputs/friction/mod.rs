//! Friction: static friction from the mean slope in contact (Section 10.2, Eq. 93) and
//! elastomer sliding friction (Section 10.1, Eq. 82, Fig. 7), in 1D and 3D.

pub mod sliding_friction;
pub mod sliding_friction_3d;
pub mod static_friction;
pub mod static_friction_3d;
