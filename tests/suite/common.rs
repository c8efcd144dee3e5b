//! Helpers the test modules share: running the `mrdw` binary and reading its output.

use serde_json::Value;
use std::path::{Path, PathBuf};
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

/// The CSV files of a report folder, (name, bytes), sorted by name; at least one.
pub fn csvs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect();
    v.sort();
    assert!(!v.is_empty(), "no CSV in {}", dir.display());
    v
}

/// The report folder's `summary.json`.
pub fn summary(out: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// Writes the scene `text` as `dir/scene.toml`, runs it into `dir/o` (whose earlier
/// report it replaces) and returns (scene file, report folder, summary); a failed run
/// fails the test with its standard error.
pub fn run_written_scene(dir: &Path, text: &str) -> (PathBuf, PathBuf, Value) {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    ok(&mrdw_in(dir, &["run", "scene.toml", "--out", "o"]));
    let out = dir.join("o");
    let s = summary(&out);
    (scene, out, s)
}
