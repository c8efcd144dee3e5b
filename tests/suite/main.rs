//! The workspace's command-line and cross-crate tests in one binary (the workspace is
//! linked once for them): the layering of the code (`architecture`), every command and
//! scene (`cli`), bad and extreme input (`robustness`), report folders and files
//! (`safety`), cases/README.md's key tables written from the scene structs
//! (`key_tables`), the Hurst sweep (`sweep`), the lambda study and the shipped calibration
//! (`lambda_study`), viscoelastic rough contact (`viscoelastic_rough`), lambda for one
//! surface (`calibrate`).

mod architecture;
mod calibrate;
mod cli;
mod common;
mod key_tables;
mod lambda_study;
mod robustness;
mod safety;
mod sweep;
mod viscoelastic_rough;
