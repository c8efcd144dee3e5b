//! Viscoelasticity (Section 8): Radok's indentation, tangential springs of Eqs. (64-65),
//! and a rough punch on a viscoelastic half-space.

pub mod tangential_viscoelastic;
#[allow(clippy::module_inception)]
pub mod viscoelastic;
pub mod viscoelastic_rough;
