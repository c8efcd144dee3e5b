//! # compare: scenes, plans, outputs and reports of the MRD workbench
//!
//! ## Architecture
//!
//! The data path, with the names a newcomer will meet:
//!
//! ```text
//! scene file --scene::Scene::parse--> Context + [Entry { kind, label, Box<dyn Output> }]
//!      |                                   (each [[outputs]] table parsed by its Kind
//!      |                                    from outputs::KINDS, then Output::validate)
//!      v
//! run::plan       -> Plan: Output::stages of every output, declared before running
//! run::run_in     -> Output::run(&Env, &mut Section) per output; Section::stage records
//!      |             (and times) each stage; ran == declared is checked
//!      v
//! report::Report  -> report::write::Destination::write_report: one CSV per Table,
//!                    one PNG per Figure, summary.json (plan, results, failures)
//! ```
//!
//! A new output kind is one new file in `outputs/` implementing [`outputs::Output`] plus
//! one line in [`outputs::KINDS`]; it reads the scene through [`context::Context`] and
//! writes only into its [`report::Section`]. Module order, bottom to top (no cycles;
//! the workspace's `tests/suite/architecture.rs` checks it): `error`, `files`, `plan`,
//! `report`, `context`, `outputs`, `scene`, `run`, `shards`; `scenes` (embedded scene
//! texts) and `bench` stand apart.

pub mod bench;
pub mod context;
pub mod error;
mod files;
pub mod outputs;
pub mod plan;
pub mod report;
pub mod run;
pub mod scene;
pub mod scenes;
pub mod shards;

pub use error::{CompareError, Result};
pub use outputs::RunControl;
pub use run::{run, run_to_folder, tool_version};
pub use scene::Scene;
