//! # compare: scenes, plans, outputs and reports of the MRD workbench
//!
//! ## Architecture
//!
//! The data path, with the names a newcomer will meet:
//!
//! ```text
//! scene file --scene::Scene::parse--> Context + [Entry { kind, label, Box<dyn Output> }]
//!      |                                   (each [[outputs]] table parsed by its Kind
//!      |                                    from registry::KINDS, then Output::validate)
//!      v
//! run::plan       -> Plan: Output::stages of every output, declared before running
//! run::run_in     -> Output::run(&Env, &mut Section) per output; Section::stage records
//!      |             (and times) each stage; ran == declared is checked
//!      v
//! report::Report  -> report::write::Destination::write_report: one CSV per Table,
//!                    one PNG per Figure, summary.json (plan, results, failures)
//! ```
//!
//! ## Layers, bottom to top
//!
//! No file imports a file above it and no two files import each other (the workspace's
//! `tests/suite/architecture.rs` checks both, file by file):
//!
//! | layer | modules | what |
//! |---|---|---|
//! | floor | `error`, `files`, `plan`, `report`, `context` | errors, safe files, stages, tables and figures, the scene's context |
//! | kind interface | `output` | the [`output::Output`] trait, [`output::Env`], [`output::RunControl`], checkpointed work |
//! | shared checks | `checks` | scene errors, count ranges, memory per spring and per cell, defaults |
//! | experiment layer | `experiment` | what studies share: lambda as scenes give it and its table, its one meaning, fits and intervals of ensemble curves |
//! | kinds | `outputs::{axisym, rough, friction, viscoelastic, dynamics, reference3d, literature}` | one file per kind, one folder per study, grouped by the paper's sections (and the published references, `literature`) |
//! | registry | `registry` | the one list of kinds ([`registry::KINDS`]) |
//! | driver | `scene`, `run`, `shards` | parse, plan, execute, write; split sweeps |
//!
//! `scenes` (embedded scene texts) stands apart. The benchmarks of `mrdw bench` live in
//! the command-line crate (`src/bench/`), not here.
//!
//! **A new output kind** is one file in its group under `outputs/` implementing
//! [`output::Output`] plus one line in [`registry::KINDS`]; it reads the scene through
//! [`context::Context`] and writes only into its [`report::Section`]. **A new study** is
//! a folder: `mod.rs` holds its parameters (the scene keys, their defaults and checks),
//! `kind.rs` its `Output` impl, which calls the study's parts (tasks, analysis, report);
//! the parts import the parameters and each other downwards only. What two studies both
//! need goes into `experiment`, never into one of them.
//!
//! **Tests.** Unit tests sit beside their code when they reach no output registry and
//! no 3D solver. A test that parses a scene, runs one or calls a study's 3D solves goes
//! into `tests/pipeline.rs`, against the built library: beside the code it would make
//! the unit-test binary compile every output kind and every solver a second time
//! (docs/architecture.md, "Where a test goes").

pub mod checks;
pub mod context;
pub mod error;
pub mod experiment;
mod files;
pub mod output;
pub mod outputs;
pub mod plan;
pub mod registry;
pub mod report;
pub mod run;
pub mod scene;
pub mod scenes;
pub mod shards;

pub use error::{CompareError, Result};
pub use output::RunControl;
pub use run::{run, run_to_folder, tool_version};
pub use scene::Scene;
