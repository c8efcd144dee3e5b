//! The Hurst sweep end to end: fitted exponents in 3D and 1D agree (fig6-ci), a killed
//! run resumes to the same bytes, and shards merge to the same bytes as one run.

use crate::common::{
    csvs, failed_with, merge, mrdw_env as mrdw, ok, run_full, run_scene_text, run_shards,
    run_written_scene, stopped_run, summary, write_in,
};

#[test]
fn fig6_ci_exponents_agree_between_3d_and_mrd() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("fig6-ci");
    ok(&mrdw(
        &["run", "fig6-ci", "--out", out.to_str().unwrap()],
        &[],
    ));
    let s = summary(&out);
    let per = s["results"]["hurst_sweep.per_hurst"].as_object().unwrap();
    let mut mrd_alpha = Vec::new();
    for (h, v) in per {
        let (a3, a1) = (
            v["alpha_3d"].as_f64().unwrap(),
            v["alpha_mrd"].as_f64().unwrap(),
        );
        // Stated tolerance at 64^2 x 6 realisations vs 64 lines: 0.15 (the 95 % bootstrap
        // intervals of alpha_3d are about +/- 0.1 here).
        assert!(
            (a3 - a1).abs() < 0.15,
            "H = {h}: alpha_3d {a3} vs alpha_mrd {a1}"
        );
        assert!(v["lambda"].as_f64().unwrap() > 0.0);
        mrd_alpha.push((h.parse::<f64>().unwrap(), a1));
    }
    mrd_alpha.sort_by(|a, b| a.0.total_cmp(&b.0));
    // alpha falls with H from H = 0 on (Eq. 80's trend).
    let from0: Vec<f64> = mrd_alpha
        .iter()
        .filter(|p| p.0 >= 0.0)
        .map(|p| p.1)
        .collect();
    assert!(from0.windows(2).all(|w| w[1] < w[0]), "{mrd_alpha:?}");
    assert!(s["stages"].as_array().unwrap().iter().any(|v| v == "bem3d"));
    for o in s["outputs"].as_array().unwrap() {
        assert_eq!(o["stages"], o["declared"], "{o}");
    }
    // The stages' times add up to the run and each interleaved stage gets its share
    // (all of the 3D work was booked to the synthesis, 40 ns to the 3D solves).
    let o = &s["outputs"][0];
    let seconds: Vec<f64> = o["stage_seconds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let names: Vec<&str> = o["stages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    let wall = s["wall_time_s"].as_f64().unwrap();
    let total: f64 = seconds.iter().sum();
    assert!(total <= wall && total > 0.5 * wall, "{total} of {wall}");
    let solve = seconds[names.iter().position(|n| *n == "bem3d").unwrap()];
    let synthesis = seconds[names.iter().position(|n| *n == "rough_synthesis").unwrap()];
    assert!(solve > 2.0 * synthesis, "{names:?} {seconds:?}");
    assert!(
        !tmp.path().join("fig6-ci.work").exists(),
        "checkpoints not cleaned up"
    );
}

const SMALL: &str = "name = \"sw\"\n[material]\ne_star = 1.0\n[[outputs]]\nkind = \"hurst_sweep\"\nhurst = [0.0, 1.0]\ngrid = 32\nrealisations_3d = 3\nrealisations_1d = 8\nloads = 8\nseed = 5\n";

/// lambda at `hurst` as written in the shipped table (a row of it).
fn shipped_lambda(hurst: f64) -> f64 {
    include_str!("../../compare/data/lambda_calibrated.csv")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let mut c = l.split(',').map(|v| v.parse::<f64>());
            Some((c.next()?.ok()?, c.next()?.ok()?))
        })
        .find(|r| r.0 == hurst)
        .expect("a row at this H")
        .1
}

#[test]
fn calibrated_lambda_tables_load() {
    // The embedded table and a sweep's own table both load as lambda for rough lines.
    let tmp = tempfile::tempdir().unwrap();
    write_in(
        tmp.path(),
        "lam.csv",
        "# from a sweep\nhurst [1],lambda [1]\n0.0,2.5\n1.0,4.0\n",
    );
    for lam in ["\"calibrated\"", "\"lam.csv\""] {
        let (_, _, s) = run_written_scene(
            tmp.path(),
            &format!("name = \"r\"\n[material]\ne_star = 1.0\n[[outputs]]\nkind = \"rough_stiffness\"\nhurst = 0.5\npoints = 4096\nlength = 1.0\nlambda = {lam}\nrealisations = 4\nf_min = 1e-5\nf_max = 1.0\n"),
        );
        let l = s["results"]["rough_stiffness.lambda"].as_f64().unwrap();
        // H = 0.5: halfway between the file's nodes; a node of the embedded table.
        let expect = if lam.contains("lam.csv") {
            3.25
        } else {
            shipped_lambda(0.5)
        };
        assert!((l - expect).abs() < 1e-4, "{lam}: {l}");
    }
}

#[test]
fn killed_run_resumes_to_identical_csvs() {
    let tmp = tempfile::tempdir().unwrap();
    let (s, full) = run_full(tmp.path(), "sw.toml", SMALL);
    let part = tmp.path().join("part");
    stopped_run(&s, &part, "3");
    let work = tmp.path().join("part.work");
    let done: usize = std::fs::read_dir(&work)
        .unwrap()
        .map(|d| std::fs::read_dir(d.unwrap().path()).unwrap().count())
        .sum();
    assert!(done >= 3, "checkpoints kept: {done}");
    let resumed = mrdw(
        &["run", &s, "--out", part.to_str().unwrap(), "--threads", "1"],
        &[],
    );
    ok(&resumed);
    // The resumed run says what it took from the checkpoints.
    let said = String::from_utf8_lossy(&resumed.stderr);
    assert!(
        said.contains(&format!("resuming: {done} of ")) && said.contains("taken from checkpoints"),
        "{said}"
    );
    assert_eq!(csvs(&full), csvs(&part));
}

#[test]
fn shards_merge_to_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let (s, full) = run_full(tmp.path(), "sw.toml", SMALL);
    let shard = run_shards(&s, tmp.path(), &["1", "2", "1"]);
    // Incomplete: one shard missing.
    let o = merge(&[&shard[0], &shard[1]], &tmp.path().join("bad"));
    failed_with(&o, 2, "all are needed");
    let merged = tmp.path().join("merged");
    ok(&merge(&[&shard[0], &shard[1], &shard[2]], &merged));
    // The origin recorded in the CSVs is the scene path in both runs.
    assert_eq!(csvs(&full), csvs(&merged));
}

#[test]
fn sweep_input_errors() {
    let tmp = tempfile::tempdir().unwrap();
    for (text, needle) in [
        (
            SMALL.replace("hurst = [0.0, 1.0]", "hurst = [0.0, 3.5]"),
            "hurst = 3.5",
        ),
        (SMALL.replace("grid = 32", "grid = 8"), "grid 8"),
        (
            SMALL.replace("realisations_3d = 3", "realisations_3d = 1"),
            "realisations_3d = 1 must lie in 2..=100000",
        ),
        (
            SMALL.replace("seed = 5", "seed = 5\ncolour = 1"),
            "unknown field `colour`",
        ),
    ] {
        failed_with(&run_scene_text(tmp.path(), &text).0, 2, needle);
    }
    let o = mrdw(
        &[
            "run",
            "hertz",
            "--shard",
            "0/2",
            "--out",
            tmp.path().join("s").to_str().unwrap(),
        ],
        &[],
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("can be sharded"));
    let o = mrdw(&["run", "hertz", "--shard", "2/2"], &[]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn unconverged_3d_solves_are_recorded_and_fail_the_run() {
    // A tolerance no solve can reach: the report is written with every solve's status
    // and residual, a warning names the failures, and the exit code is 4.
    let tmp = tempfile::tempdir().unwrap();
    let text = SMALL
        .replace("grid = 32", "grid = 16")
        .replace("seed = 5", "seed = 5\ntolerance = 1e-20");
    let (o, out) = run_scene_text(tmp.path(), &text);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(4), "{err}");
    assert!(err.contains("did not converge"), "{err}");
    assert!(err.lines().last().unwrap().starts_with("error: "), "{err}");
    let text = std::fs::read_to_string(out.join("hurst_sweep_solves.csv")).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let conv = header
        .iter()
        .position(|h| h.starts_with("converged"))
        .unwrap();
    let res = header
        .iter()
        .position(|h| h.starts_with("residual"))
        .unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(!rows.is_empty());
    let unconverged = rows.iter().filter(|r| r[conv] == "0").count();
    assert!(unconverged > 0);
    for r in rows.iter().filter(|r| r[conv] == "0") {
        let v: f64 = r[res].parse().unwrap();
        assert!(v.is_finite() && v > 1e-20, "residual {v}");
    }
    let s = summary(&out);
    assert!(!s["failures"].as_array().unwrap().is_empty());
    assert_eq!(
        s["results"]["hurst_sweep.unconverged_3d_solves"]
            .as_u64()
            .unwrap(),
        unconverged as u64
    );
}

#[test]
fn the_ends_of_the_hurst_range_run_in_3d_and_1d() {
    // H = -1 (flat spectrum) and H = 3 (dominated by the longest wavelength): every solve
    // converges, exponents are finite, no NaN reaches a CSV.
    let tmp = tempfile::tempdir().unwrap();
    let text = SMALL
        .replace("hurst = [0.0, 1.0]", "hurst = [-1.0, 3.0]")
        .replace("grid = 32", "grid = 24");
    let (_, out, s) = run_written_scene(tmp.path(), &text);
    for (h, v) in s["results"]["hurst_sweep.per_hurst"].as_object().unwrap() {
        for k in ["alpha_3d", "alpha_mrd"] {
            let a = v[k].as_f64().unwrap_or(f64::NAN);
            assert!(a.is_finite() && a > 0.0 && a < 1.5, "H = {h}: {k} = {a}");
        }
    }
    assert_eq!(
        s["results"]["hurst_sweep.unconverged_3d_solves"].as_u64(),
        Some(0)
    );
    for (name, bytes) in csvs(&out) {
        let text = String::from_utf8(bytes).unwrap();
        assert!(!text.contains("NaN") && !text.contains("inf"), "{name}");
    }
}
