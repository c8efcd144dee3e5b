//! Randomly rough surfaces and lines (Section 9, Eqs. 69-76): spectra, synthesis,
//! statistics; the MRD rough-line contact lives in [`crate::rough_contact`].

pub mod nested;
pub mod spectrum;
pub mod stats;
pub mod synthesis;

pub use spectrum::{
    lambda_cut, Lambda, LambdaTable, LineSpectrum, SelfAffine, SpectralMoments, TabulatedSpectrum,
};
