//! Numerical building blocks (how things are solved), kept apart from the physics.

pub mod gauss;
pub mod quad;
pub mod roots;
