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
    let (o, out) = run_scene_text(dir, text);
    ok(&o);
    let s = summary(&out);
    (dir.join("scene.toml"), out, s)
}

/// Writes the scene `text` as `dir/scene.toml` and runs it into `dir/o`; returns the
/// run (successful or not) and the report folder's path.
pub fn run_scene_text(dir: &Path, text: &str) -> (Output, PathBuf) {
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    (
        mrdw_in(dir, &["run", "scene.toml", "--out", "o"]),
        dir.join("o"),
    )
}

/// `mrdw merge PARTS --out OUT`.
pub fn merge(parts: &[&Path], out: &Path) -> Output {
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(|p| p.to_str().unwrap()));
    args.extend(["--out", out.to_str().unwrap()]);
    mrdw_env(&args, &[])
}

/// Writes the height map of `rows` rows of `heights` (row-major) to `path` (`.npy`).
pub fn write_map(path: &Path, rows: usize, heights: Vec<f64>) {
    mrd::topography::HeightMap {
        rows,
        cols: heights.len() / rows,
        data: heights,
    }
    .write_npy(path)
    .unwrap();
}

/// A smooth n x n map of rms height about 0.005: a sine along x times a cosine along y.
pub fn wavy(n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|k| ((k % n) as f64 * 0.4).sin() * ((k / n) as f64 * 0.3).cos() * 0.01)
        .collect()
}

/// Writes a 4 x 4 height map with a NaN inside to `path` (`.npy`).
pub fn write_nan_map(path: &Path) {
    let mut heights = vec![0.0; 16];
    heights[5] = f64::NAN;
    write_map(path, 4, heights);
}

/// `mrdw ARGS` with `/dev/full` (a full disk) as its standard output or, when `on_stderr`,
/// its standard error.
pub fn mrdw_to_full_disk(args: &[&str], on_stderr: bool) -> Output {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let mut c = Command::new(env!("CARGO_BIN_EXE_mrdw"));
    c.args(args);
    if on_stderr {
        c.stderr(full);
    } else {
        c.stdout(full);
    }
    c.output().unwrap()
}

/// Writes `text` to the file `dir/name` and returns its path.
pub fn write_in(dir: &Path, name: &str, text: &str) -> PathBuf {
    let scene = dir.join(name);
    std::fs::write(&scene, text).unwrap();
    scene
}

/// Writes the scene `text` as `dir/name`, runs it whole into `dir/full` and returns
/// (scene file as text, report folder); a failed run fails the test.
pub fn run_full(dir: &Path, name: &str, text: &str) -> (String, PathBuf) {
    let scene = write_in(dir, name, text);
    let s = scene.to_str().unwrap().to_string();
    let full = dir.join("full");
    ok(&mrdw_env(
        &["run", &s, "--out", full.to_str().unwrap()],
        &[],
    ));
    (s, full)
}

/// Runs `scene` into `out` stopped after `tasks` tasks: the run must exit with code 3
/// and write no report.
pub fn stopped_run(scene: &str, out: &Path, tasks: &str) {
    let o = mrdw_env(
        &["run", scene, "--out", out.to_str().unwrap()],
        &[("MRDW_STOP_AFTER_TASKS", tasks)],
    );
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(!out.exists(), "a stopped run must not write a report");
}

/// Runs `scene` as `threads.len()` shards, shard k on `threads[k]` threads, into
/// `dir/shardK`; returns the shard folders (each run must succeed).
pub fn run_shards(scene: &str, dir: &Path, threads: &[&str]) -> Vec<PathBuf> {
    let count = threads.len();
    let mut folders = Vec::new();
    for (k, t) in threads.iter().enumerate() {
        let folder = dir.join(format!("shard{k}"));
        let shard = format!("{k}/{count}");
        let args = ["run", scene, "--shard", &shard, "--threads", t];
        ok(&mrdw_env(
            &[&args[..], &["--out", folder.to_str().unwrap()]].concat(),
            &[],
        ));
        folders.push(folder);
    }
    folders
}

/// Asserts the run exited with `code` and its standard error contains `needle`,
/// showing the standard error otherwise.
pub fn failed_with(o: &Output, code: i32, needle: &str) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(code), "{needle}: {e}");
    assert!(e.contains(needle), "`{needle}` not in: {e}");
}

/// Every .rs file under `dir`, recursively, sorted.
pub fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(rust_files(&p));
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
    out.sort();
    out
}
