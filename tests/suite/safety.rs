//! Nothing lost, nothing hidden: report folders never replace a user's files, runs
//! into one folder do not race, failures leave no debris, every file name is unique,
//! and output errors (closed pipe, full disk) are errors, not panics.

use crate::common::{failed_with, mrdw_in, stderr};
use std::path::Path;
use std::process::{Command, Stdio};

/// Names in `dir` (hidden ones included).
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn a_folder_of_user_files_is_refused_and_kept() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("mine");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("notes.txt"), "precious").unwrap();
    let o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "mine"]);
    failed_with(&o, 2, "holds files mrdw did not write");
    assert_eq!(stderr(&o).trim_end().lines().count(), 1);
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.txt")).unwrap(),
        "precious"
    );
    assert_eq!(names(&dir), ["notes.txt"]);
    assert_eq!(names(tmp.path()), ["mine"], "debris left beside the folder");
    // An empty folder is fine, and afterwards it is a report folder mrdw may replace.
    let empty = tmp.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert!(mrdw_in(tmp.path(), &["run", "hertz", "--out", "empty"])
        .status
        .success());
    assert!(mrdw_in(tmp.path(), &["run", "cone", "--out", "empty"])
        .status
        .success());
    assert!(empty.join("summary.json").exists() && empty.join(".mrdw").exists());
}

#[test]
fn a_file_is_never_replaced_by_a_report() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("data.csv"), "1,2\n").unwrap();
    let o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "data.csv"]);
    failed_with(&o, 2, "a file of that name exists");
    assert_eq!(
        std::fs::read_to_string(tmp.path().join("data.csv")).unwrap(),
        "1,2\n"
    );
    assert_eq!(names(tmp.path()), ["data.csv"]);
}

#[test]
fn out_dot_in_a_user_folder_is_refused_without_debris() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("keep.txt"), "x").unwrap();
    let o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "."]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(names(tmp.path()), ["keep.txt"]);
    let parent = tmp.path().parent().unwrap();
    let base = tmp
        .path()
        .file_name()
        .unwrap()
        .to_string_lossy()
        .into_owned();
    assert!(
        !names(parent)
            .iter()
            .any(|n| n.starts_with(&format!(".{base}.mrdw"))),
        "staging or lock left beside the folder"
    );
}

#[test]
fn stale_staging_from_a_killed_run_is_removed_by_the_next() {
    let tmp = tempfile::tempdir().unwrap();
    for stale in [".r.mrdw-staging-99999", ".r.mrdw-old-99998"] {
        std::fs::create_dir(tmp.path().join(stale)).unwrap();
        std::fs::write(tmp.path().join(stale).join("x.csv"), "half").unwrap();
    }
    // Another report's staging folder is not ours to remove.
    std::fs::create_dir(tmp.path().join(".other.mrdw-staging-1")).unwrap();
    assert!(mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"])
        .status
        .success());
    assert_eq!(names(tmp.path()), [".other.mrdw-staging-1", "r"]);
}

#[test]
fn a_second_run_into_a_locked_folder_is_told_plainly() {
    let tmp = tempfile::tempdir().unwrap();
    let lock = std::fs::File::create(tmp.path().join(".r.mrdw-lock")).unwrap();
    lock.try_lock().unwrap();
    let o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"]);
    failed_with(&o, 5, "in use by another mrdw run");
    assert!(!tmp.path().join("r").exists());
    drop(lock);
    // Released here, the lock can live on for a moment in a child that another test of
    // this binary forks meanwhile (a forked child shares the open file until its exec
    // closes it): a run told "in use" (exit code 5) is retried for up to 2 s.
    let mut o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"]);
    for _ in 0..100 {
        if o.status.code() != Some(5) {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
        o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"]);
    }
    assert!(o.status.success(), "{}", stderr(&o));
    // The lock file goes with the run.
    assert_eq!(names(tmp.path()), ["r"]);
}

#[test]
fn a_failed_run_leaves_nothing_behind() {
    let tmp = tempfile::tempdir().unwrap();
    crate::common::write_nan_map(&tmp.path().join("nan.npy"));
    std::fs::write(
        tmp.path().join("b.toml"),
        "name = \"b\"\n[material]\ne_star = 1.0\n[[outputs]]\nkind = \"bem_contact\"\nheights = \"nan.npy\"\nsize = [1.0, 1.0]\nmean_pressures = [0.1]\n",
    )
    .unwrap();
    let o = mrdw_in(tmp.path(), &["run", "b.toml", "--out", "r"]);
    failed_with(&o, 2, "non-finite height");
    assert_eq!(names(tmp.path()), ["b.toml", "nan.npy"]);
}

#[test]
fn two_outputs_of_one_kind_write_distinct_files() {
    let tmp = tempfile::tempdir().unwrap();
    let n = 16;
    let h = crate::common::wavy(n);
    crate::common::write_map(&tmp.path().join("h.npy"), n, h);
    let one = "[[outputs]]\nkind = \"bem_contact\"\nheights = \"h.npy\"\nsize = [1.0, 1.0]\nfields = true\n";
    std::fs::write(
        tmp.path().join("b.toml"),
        format!(
            "name = \"b\"\n[material]\ne_star = 1.0\n{one}mean_pressures = [0.001]\n{one}mean_pressures = [0.002, 0.003]\n"
        ),
    )
    .unwrap();
    let o = mrdw_in(tmp.path(), &["run", "b.toml", "--out", "r"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = crate::common::summary(&tmp.path().join("r"));
    let files: Vec<String> = s["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect();
    let mut unique = files.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), files.len(), "{files:?}");
    // 1 + 2 loads, pressure and gap each, all on disk.
    let npy: Vec<&String> = files.iter().filter(|f| f.ends_with(".npy")).collect();
    assert_eq!(npy.len(), 6, "{npy:?}");
    for f in &files {
        assert!(tmp.path().join("r").join(f).exists(), "{f}");
    }
    assert!(files.contains(&"bem_contact_2_pressure_2.npy".to_string()));
}

#[test]
fn write_errors_on_stdout_are_one_line_not_a_panic() {
    // A full disk.
    let o = crate::common::mrdw_to_full_disk(&["show", "hertz"], false);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with("error: writing to standard output"),
        "{}",
        stderr(&o)
    );
    assert!(!stderr(&o).contains("panicked"));
    // A closed pipe (the reader is gone before mrdw writes).
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let o = Command::new(env!("CARGO_BIN_EXE_mrdw"))
        .arg("scenes")
        .stdout(Stdio::from(writer))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
    assert_eq!(stderr(&o).trim_end().lines().count(), 1);
}

#[test]
fn absurd_thread_counts_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    for t in ["0", "100000"] {
        let o = mrdw_in(tmp.path(), &["run", "hertz", "--threads", t, "--out", "r"]);
        failed_with(&o, 2, "1..=1024");
    }
    assert_eq!(names(tmp.path()), Vec::<String>::new());
}
