//! Numerical building blocks (how things are solved), kept apart from the physics.

pub mod gauss;
pub mod quad;
pub mod roots;

/// Relative difference |a - b| / |b| of a result `a` from the reference `b` (unit tests).
#[cfg(test)]
pub(crate) fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}
