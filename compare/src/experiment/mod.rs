//! The shared experiment layer that the studies stand on instead of on each other:
//! lambda as scenes give it and its calibrated table ([`lambda`]), its one meaning
//! ([`lambda_meaning`]), the fits and intervals of ensemble curves ([`fit`]), and the
//! periodic self-affine patches of the 3D rough studies ([`periodic`]).

pub mod fit;
pub mod lambda;
pub mod lambda_meaning;
pub mod periodic;
