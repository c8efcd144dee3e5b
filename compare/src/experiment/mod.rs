//! The shared experiment layer that the studies stand on instead of on each other:
//! lambda as scenes give it and its calibrated table ([`lambda`]), its one meaning
//! ([`lambda_meaning`]), and the fits and intervals of ensemble curves ([`fit`]).

pub mod fit;
pub mod lambda;
pub mod lambda_meaning;
