//! Helpers the test modules share: running the `mrdw` binary and reading its output.

use std::path::Path;
use std::process::{Command, Output};

/// `mrdw ARGS` run in `dir`.
pub fn mrdw_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mrdw"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("mrdw runs")
}

/// `mrdw ARGS` with the environment variables `env` set.
pub fn mrdw_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_mrdw"));
    c.args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("mrdw runs")
}

/// The run's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts the run succeeded, showing its standard error otherwise.
pub fn ok(o: &Output) {
    assert!(o.status.success(), "{}", stderr(o));
}
