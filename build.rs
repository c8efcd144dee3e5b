//! No build step: this script exists so that its build-dependency (see Cargo.toml,
//! `[build-dependencies]`) gives the host-side `syn` the features the Python bindings'
//! macros enable. With them aligned, `cargo build` of the CLI, `cargo test --workspace`
//! and the Python extension's build share every compiled crate instead of each
//! rebuilding the workspace.
fn main() {}
