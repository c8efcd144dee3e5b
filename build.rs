//! No build step: this script exists so that its build-dependency (see Cargo.toml,
//! `[build-dependencies]`) gives the host-side `syn` the features the Python bindings'
//! macros enable. With them aligned, `cargo build` of the CLI, `cargo test --workspace`
//! and the Python extension's build share every compiled crate instead of each
//! rebuilding the workspace. It reads no file: without the line below, cargo would run
//! it again (and rebuild `mrdw`) whenever any file of the package changed, a scene or
//! figure a user saved in the checkout's root included.
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
}
