//! The contact inside a time integration (Section 12): macroscopic systems whose contact
//! is evaluated at every time step, by MRD and by the 3D reference (`dynamics`), each
//! against a closed form.

pub mod adhesive_impact;
pub mod forced;
pub mod friction_forced;
pub mod impact;
pub mod oblique_cycle;
pub mod oblique_impact;
pub mod resonance;
pub mod ring_down;
pub mod rough_ring_down;
pub mod viscoelastic_impact;
