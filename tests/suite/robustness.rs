//! Bad and extreme input on the command line: sizes and counts that do not fit refuse
//! with one line (never an abort or a panic), process memory limits are honoured,
//! extreme physical parameters are named, unresolved results are flagged and fail the
//! run, report folders keep what a user added, and the benchmark commands refuse what
//! they cannot do.

use crate::common::{mrdw_in, run_scene_text, stderr, summary};
use std::path::Path;
use std::process::{Command, Output};

/// Exit code 2 with one `error:` line containing `needle`; no panic, no abort.
fn refused(o: &Output, needle: &str) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{needle}: {e}");
    assert!(!e.contains("panicked"), "{e}");
    let last = e.trim_end().lines().last().unwrap_or("");
    assert!(
        last.starts_with("error: ") && last.contains(needle),
        "`{needle}` not in: {e}"
    );
}

/// Each scene `head` + body of `cases` is refused before anything runs: exit code 2,
/// one line containing the case's needle, and no report folder.
fn each_refused(head: &str, cases: &[(String, &str)]) {
    let tmp = tempfile::tempdir().unwrap();
    for (body, needle) in cases {
        std::fs::write(tmp.path().join("b.toml"), format!("{head}{body}")).unwrap();
        let o = mrdw_in(tmp.path(), &["run", "b.toml", "--out", "o"]);
        refused(&o, needle);
        assert!(
            !tmp.path().join("o").exists(),
            "{needle}: a report was written"
        );
    }
}

/// Every integer key of every embedded scene, set to 10^15 (counts, sizes, points):
/// refused with one line naming the key or the memory it needs, exit code 2.
#[test]
fn absurd_counts_in_any_scene_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let list = mrdw_in(tmp.path(), &["scenes"]);
    let names: Vec<String> = String::from_utf8_lossy(&list.stdout)
        .lines()
        .filter(|l| !l.starts_with(' ') && !l.is_empty())
        .filter_map(|l| l.split_whitespace().next().map(String::from))
        .collect();
    assert!(names.len() > 20, "{names:?}");
    let mut cases = 0;
    for name in &names {
        let text =
            String::from_utf8_lossy(&mrdw_in(tmp.path(), &["show", name]).stdout).into_owned();
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let Some((key, value)) = line.split_once('=') else {
                continue;
            };
            let (key, value) = (key.trim(), value.split('#').next().unwrap().trim());
            if key == "seed" || key.contains(' ') || value.parse::<u64>().is_err() {
                continue;
            }
            let mut edited: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
            edited[i] = format!("{key} = 1000000000000000");
            let scene = tmp.path().join("s.toml");
            std::fs::write(&scene, edited.join("\n")).unwrap();
            let o = mrdw_in(tmp.path(), &["run", "s.toml", "--out", "o"]);
            let e = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{name}.{key}: {e}");
            assert!(!e.contains("panicked"), "{name}.{key}: {e}");
            assert_eq!(e.trim_end().lines().count(), 1, "{name}.{key}: {e}");
            cases += 1;
        }
    }
    assert!(cases >= 50, "only {cases} integer keys found");
}

/// A 64 x 64 periodic map: a bem_contact scene beside it.
fn bem_scene(dir: &Path, n: usize, extra: &str) {
    let h = crate::common::wavy(n);
    crate::common::write_map(&dir.join("h.npy"), n, h);
    std::fs::write(
        dir.join("b.toml"),
        format!("name = \"b\"\n[material]\ne_star = 1.0\n[[outputs]]\nkind = \"bem_contact\"\nheights = \"h.npy\"\nsize = [1.0, 1.0]\nmean_pressures = [0.01]\n{extra}"),
    )
    .unwrap();
}

/// Under an address-space limit (`ulimit -v`) a map that does not fit is refused with
/// the limit named, before anything is allocated; the same map runs without it.
#[test]
fn the_process_address_space_limit_is_honoured() {
    let tmp = tempfile::tempdir().unwrap();
    bem_scene(tmp.path(), 2048, "");
    let exe = env!("CARGO_BIN_EXE_mrdw");
    let o = Command::new("bash")
        .current_dir(tmp.path())
        .args([
            "-c",
            &format!("ulimit -v 300000 && exec {exe} run b.toml --out r --threads 1"),
        ])
        .output()
        .unwrap();
    refused(&o, "address-space limit");
    assert!(!tmp.path().join("r").exists());
}

#[test]
fn solver_options_and_sizes_share_the_python_checks() {
    let tmp = tempfile::tempdir().unwrap();
    bem_scene(tmp.path(), 16, "tolerance = 1.0\n");
    refused(
        &mrdw_in(tmp.path(), &["run", "b.toml", "--out", "r"]),
        "tolerance = 1e0 must lie in (0, 1e-2]",
    );
    bem_scene(tmp.path(), 16, "");
    let text = std::fs::read_to_string(tmp.path().join("b.toml"))
        .unwrap()
        .replace("size = [1.0, 1.0]", "size = [1e300, 1e300]");
    std::fs::write(tmp.path().join("b.toml"), text).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "b.toml", "--out", "r"]),
        "size[0] (lx, the map's size in x) = 1e300 must lie in [1e-100, 1e100]",
    );
}

/// Every 3D comparison kind refuses a solver tolerance with the solver's own range and
/// message (the one `bem_contact` and the Python package give), before computing.
#[test]
fn comparison_kinds_share_the_solver_tolerance_check() {
    let tmp = tempfile::tempdir().unwrap();
    for scene in [
        "contact-area-ci",
        "rough-sphere-ci",
        "static-friction-3d-ci",
        "viscoelastic-rough-ci",
        "fig6-ci",
    ] {
        let text = String::from_utf8_lossy(&mrdw_in(tmp.path(), &["show", scene]).stdout).replacen(
            "\nkind = \"",
            "\ntolerance = 0.5\nkind = \"",
            1,
        );
        std::fs::write(tmp.path().join("t.toml"), text).unwrap();
        refused(
            &mrdw_in(tmp.path(), &["run", "t.toml", "--out", "r"]),
            "tolerance = 5e-1 must lie in (0, 1e-2]",
        );
        assert!(!tmp.path().join("r").exists(), "{scene}");
    }
}

/// fig7-ci with a line of `waves` waves on 256 springs.
fn coarse_fig7(dir: &Path, waves: f64) -> Output {
    let text = String::from_utf8_lossy(&mrdw_in(dir, &["show", "fig7-ci"]).stdout)
        .replace("waves = 4.0, band", &format!("waves = {waves:.1}, band"))
        .replace("springs = 1024", "springs = 256");
    std::fs::write(dir.join("f.toml"), text).unwrap();
    mrdw_in(dir, &["run", "f.toml", "--out", "r"])
}

/// Too few springs per wave: the two routes to mu disagree; those velocities are
/// flagged, warned about and left out of the fit, and with fewer than two resolved
/// velocities xi is missing and the run fails (exit code 4).
#[test]
fn unresolved_mrd_sliding_is_flagged_and_fails_without_a_fit() {
    let tmp = tempfile::tempdir().unwrap();
    let o = coarse_fig7(tmp.path(), 80.0);
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    let s = summary(&tmp.path().join("r"));
    assert!(s["results"].get("sliding_friction.xi").is_none(), "{s}");
    assert!(s["failures"][0].as_str().unwrap().contains("not fitted"));
    assert!(s["warnings"][0].as_str().unwrap().contains("unresolved"));
    // Some resolved: the fit uses them only, the table says which.
    let o = coarse_fig7(tmp.path(), 20.0);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(tmp.path().join("r/sliding_friction.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert!(rows[0].ends_with("routes_rel_diff_max [1],resolved [0/1]"));
    let flags: Vec<&str> = rows[1..]
        .iter()
        .map(|r| r.rsplit(',').next().unwrap())
        .collect();
    assert!(flags.contains(&"0") && flags.contains(&"1"), "{flags:?}");
    let s = summary(&tmp.path().join("r"));
    let resolved = s["results"]["sliding_friction.resolved_velocities"]
        .as_f64()
        .unwrap();
    assert_eq!(
        resolved as usize,
        flags.iter().filter(|f| **f == "1").count()
    );
    assert!(
        stderr(&o).contains("velocities unresolved"),
        "{}",
        stderr(&o)
    );
}

/// Moduli, times, exponents and velocities outside the range where the physics and the
/// arithmetic hold name the key.
#[test]
fn extreme_viscoelastic_parameters_name_the_key() {
    let tmp = tempfile::tempdir().unwrap();
    let base =
        String::from_utf8_lossy(&mrdw_in(tmp.path(), &["show", "fig7-ci"]).stdout).into_owned();
    let eq84 = "material = { kind = \"eq84\", g0 = 1.0, g1 = 1000.0, tau1 = 1e-2, tau2 = 1e2, s = 2.0, terms = 16 }";
    assert!(base.contains(eq84));
    let prony = |g: &str| format!("material = {{ kind = \"prony\", {g} }}");
    for (from, to, needle) in [
        (
            "velocity_min = 3.5e-6",
            "velocity_min = 1e-300".to_string(),
            "velocity_min = 1e-300",
        ),
        (
            "velocity_max = 35.0",
            "velocity_max = 1e300".to_string(),
            "velocity_max = 1e300",
        ),
        ("s = 2.0", "s = 1e300".to_string(), "material.s = 1e300"),
        ("tau1 = 1e-2", "tau1 = 1e-300".to_string(), "tau2 / tau1"),
        (
            "g1 = 1000.0",
            "g1 = 1e300".to_string(),
            "invalid g1 = 1e300",
        ),
        ("g1 = 1000.0", "g1 = 1e90".to_string(), "G(0)/G(inf) = 9.9"),
        (eq84, prony("g_inf = 1.0, terms = []"), "purely elastic"),
        (
            eq84,
            prony("g_inf = 1.0, terms = [[1e300, 1.0]]"),
            "invalid prony modulus = 1e300",
        ),
        (
            eq84,
            prony("g_inf = 1.0, terms = [[1e9, 1.0]]"),
            "G(0)/G(inf)",
        ),
        (
            eq84,
            prony("g_inf = 1e-300, terms = [[1e-300, 1.0]]"),
            "relaxed modulus",
        ),
        (
            eq84,
            prony("g_inf = 1e-90, terms = [[1.0, 1.0]]"),
            "G(0)/G(inf)",
        ),
    ] {
        std::fs::write(tmp.path().join("v.toml"), base.replace(from, &to)).unwrap();
        refused(
            &mrdw_in(tmp.path(), &["run", "v.toml", "--out", "r"]),
            needle,
        );
    }
}

#[test]
fn one_realisation_is_refused_for_want_of_an_interval() {
    let tmp = tempfile::tempdir().unwrap();
    let text = String::from_utf8_lossy(&mrdw_in(tmp.path(), &["show", "rough-stiffness"]).stdout)
        .replace("realisations = 64", "realisations = 1");
    std::fs::write(tmp.path().join("r.toml"), text).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "r.toml", "--out", "o"]),
        "realisations = 1 must lie in 2..=1000000",
    );
}

/// A 4 x 4 measured map has a PSD of two bins: no fitted Hurst exponent, a warning.
#[test]
fn a_tiny_measured_map_reports_no_hurst_exponent() {
    let tmp = tempfile::tempdir().unwrap();
    let h: Vec<f64> = (0..16).map(|k| ((k * 7 % 5) as f64 - 2.0) * 1e-3).collect();
    crate::common::write_map(&tmp.path().join("m.npy"), 4, h);
    let text = String::from_utf8_lossy(&mrdw_in(tmp.path(), &["show", "rough-stiffness"]).stdout)
        .into_owned();
    let text = format!("{text}measured = {{ heights = \"m.npy\", size = [1.0, 1.0] }}\n");
    std::fs::write(tmp.path().join("r.toml"), text).unwrap();
    let o = mrdw_in(tmp.path(), &["run", "r.toml", "--out", "o"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = summary(&tmp.path().join("o"));
    assert!(
        s["results"]
            .get("rough_stiffness.measured_fitted_hurst")
            .is_none(),
        "{s}"
    );
    assert!(stderr(&o).contains("not reported"), "{}", stderr(&o));
}

/// A file a user added inside a report folder, or beside the files of an earlier
/// version's report (known by its summary.json), is never deleted.
#[test]
fn a_users_file_inside_a_report_folder_is_kept() {
    let tmp = tempfile::tempdir().unwrap();
    assert!(mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"])
        .status
        .success());
    let manifest = std::fs::read_to_string(tmp.path().join("r/.mrdw")).unwrap();
    assert!(manifest.lines().any(|l| l == "summary.json"), "{manifest}");
    std::fs::write(tmp.path().join("r/notes.txt"), "mine").unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"]),
        "holds files mrdw did not write (notes.txt)",
    );
    assert_eq!(
        std::fs::read_to_string(tmp.path().join("r/notes.txt")).unwrap(),
        "mine"
    );
    // An earlier version's report: no manifest, its summary.json lists its files.
    std::fs::remove_file(tmp.path().join("r/.mrdw")).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"]),
        "notes.txt",
    );
    std::fs::remove_file(tmp.path().join("r/notes.txt")).unwrap();
    assert!(mrdw_in(tmp.path(), &["run", "hertz", "--out", "r"])
        .status
        .success());
    // A folder holding only a summary.json that names mrdw is not a report to replace
    // when anything else is there.
    let fake = tmp.path().join("fake");
    std::fs::create_dir(&fake).unwrap();
    std::fs::write(
        fake.join("summary.json"),
        "{\"tool\": \"mrdw 0.1.0\", \"files\": []}",
    )
    .unwrap();
    std::fs::write(fake.join("data.csv"), "1,2\n").unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "hertz", "--out", "fake"]),
        "data.csv",
    );
    assert!(fake.join("data.csv").exists());
}

#[test]
fn a_link_to_a_folder_is_followed() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::create_dir(tmp.path().join("real")).unwrap();
    std::os::unix::fs::symlink("real", tmp.path().join("link")).unwrap();
    for _ in 0..2 {
        let o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "link"]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert!(tmp.path().join("real/summary.json").exists());
    assert!(std::fs::symlink_metadata(tmp.path().join("link"))
        .unwrap()
        .file_type()
        .is_symlink());
    std::os::unix::fs::symlink("nowhere", tmp.path().join("dangling")).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "hertz", "--out", "dangling"]),
        "a link to a path that does not exist",
    );
}

#[test]
fn benchmark_commands_refuse_what_they_cannot_do() {
    let tmp = tempfile::tempdir().unwrap();
    let o = mrdw_in(tmp.path(), &["bench", "sliding", "--max-exp", "9"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o)
        .starts_with("error: invalid value '9' for '--max-exp <MAX_EXP>': 9 is not in 3..=8"));
    refused(
        &mrdw_in(tmp.path(), &["bench-case", "periodic", "0"]),
        "grid side n = 0 must lie in 16..=16384",
    );
    refused(
        &mrdw_in(tmp.path(), &["bench-case", "large", "65536"]),
        "grid side n = 65536 must lie in 16..=16384",
    );
    for p in ["0", "1.5", "NaN"] {
        refused(
            &mrdw_in(
                tmp.path(),
                &["bench-case", "large", "64", "--mean-pressure", p],
            ),
            "must lie in (0, 1) (a fraction of E*)",
        );
    }
    let o = mrdw_in(
        tmp.path(),
        &[
            "bench",
            "bem",
            "--max-n",
            "128",
            "--write-surfaces",
            "/proc/none",
        ],
    );
    refused(&o, "--write-surfaces /proc/none");
    // Any error with a full standard error: still exit code 2.
    let o = crate::common::mrdw_to_full_disk(&["run", "no-such-scene"], true);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn half_lengths_and_scene_names_get_true_messages() {
    let tmp = tempfile::tempdir().unwrap();
    let text = String::from_utf8_lossy(&mrdw_in(tmp.path(), &["show", "hertz"]).stdout)
        .replace("springs = 4000", "springs = 4000\nhalf_length = 1e-9");
    std::fs::write(tmp.path().join("h.toml"), text).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "h.toml", "--out", "o"]),
        "half_length = 1e-9 does not cover the largest contact radius",
    );
    // A folder named like an embedded scene (say, its report) does not hide the scene.
    std::fs::create_dir(tmp.path().join("hertz")).unwrap();
    let o = mrdw_in(tmp.path(), &["run", "hertz", "--out", "o2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::create_dir(tmp.path().join("mine")).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "mine"]),
        "a folder, not a scene file",
    );
}

/// The 3D claims' kinds name a bad value before anything runs.
#[test]
fn static_friction_3d_and_rough_sphere_refuse_bad_values() {
    let head = "name = \"b\"\n[material]\ne_star = 1.0\n[[outputs]]\n";
    let sf = "kind = \"static_friction_3d\"\nbandwidth = 6\nrealisations_3d = 2\nrealisations_1d = 2\nf_max = 1.0\n";
    let rs = "kind = \"rough_sphere\"\nradius = 1.0\nhurst = 0.8\ngrid = 64\nrealisations_3d = 2\nrealisations_1d = 2\n";
    let cases = [
        (format!("{sf}hurst = [1.5]\nf_min = 1e-3\n"), "hurst = 1.5 must lie in [0, 1]"),
        (format!("{sf}hurst = [0.7]\nf_min = 2.0\n"), "need 0 < f_min < f_max"),
        (
            format!("{sf}hurst = [0.7]\nf_min = 1e-3\nlambda = [-1.0]\n"),
            "lambda = -1 must be > 0",
        ),
        (
            format!("{sf}hurst = [0.7]\nf_min = 1e-3\ngeometry = [\"disc\"]\nrefine = {{ hurst = 0.7, geometry = \"periodic\", f = 0.1 }}\n"),
            "refine: hurst and geometry must be among the output's",
        ),
        (
            format!("{rs}hertz_depth = 1e-3\nbandwidth = 8\nalpha = [-1.0]\n"),
            "alpha = [-1.0]: give at least one rms height over the Hertz depth in [0, 100]",
        ),
        (
            format!("{rs}hertz_depth = 0.5\nbandwidth = 8\nalpha = [0.1]\n"),
            "hertz_depth = 0.5 must be <= 0.1 radius",
        ),
        (
            format!("{rs}hertz_depth = 1e-3\nbandwidth = 40\nalpha = [0.1]\n"),
            "bandwidth = 40 must lie in 1..=31",
        ),
        (
            format!("{rs}hertz_depth = 1e-3\nbandwidth = 8\nalpha = [0.1]\nside = 1.0\n"),
            "side = 1 must lie in [2.5, 100]",
        ),
        (
            format!("{rs}hertz_depth = 1e-3\nbandwidth = 8\nalpha = [0.1]\nside = 9.0\n"),
            "grid = 64 over side = 9 puts 7.111 cells on the Hertz radius, at least 8 needed",
        ),
        // The value given, not a wavenumber derived from it.
        (
            format!("{rs}hertz_depth = 1e-3\nbandwidth = 8\nalpha = [0.1]\n")
                .replace("radius = 1.0", "radius = 1e300"),
            "radius = 1e300 must lie in [1e-100, 1e100]",
        ),
    ];
    each_refused(head, &cases);
}

/// The references kind solves the published problems in their own units and bodies: a
/// scene that sets another modulus, a G*, a profile or a resolution out of range is
/// refused by name, never silently ignored.
#[test]
fn references_refuse_what_they_would_not_read() {
    let head = "name = \"b\"\n[material]\n";
    let kind = "[[outputs]]\nkind = \"references\"\n";
    let cases = [
        (
            format!("e_star = 2.0\n{kind}"),
            "set e_star = 1 (the scene gives 2)",
        ),
        (
            format!("e_star = 1.0\ng_star = 0.8\n{kind}"),
            "remove g_star",
        ),
        (
            format!(
                "e_star = 1.0\n[profile]\nshapes = [{{ kind = \"sphere\", radius = 1.0 }}]\n{kind}"
            ),
            "remove [profile]",
        ),
        (
            format!("e_star = 1.0\n{kind}cells = 8\n"),
            "cells = 8 must lie in 32..=512",
        ),
        (
            format!("e_star = 1.0\n{kind}springs = 10\n"),
            "springs = 10 must lie in 200..=1000000",
        ),
        (
            format!("e_star = 1.0\n{kind}steps = 10\n"),
            "steps = 10 must lie in 500..=1000000",
        ),
    ];
    each_refused(head, &cases);
}

/// The lambda study's checks name a bad value before anything runs.
#[test]
fn lambda_study_refuses_bad_checks() {
    let head = "name = \"b\"\n[material]\ne_star = 1.0\n[[outputs]]\n";
    let ls = "kind = \"lambda_study\"\nhurst = [0.0, 1.0]\nbandwidths = [8, 16]\ncells = 4\ncalibrate_at = 16\nrealisations = { min = 4, max = 8, batch = 4 }\nrealisations_1d = 16\n";
    let cases = [
        (
            format!("{ls}top_check = {{ hurst = 0.5, bandwidth = 16, tolerance = 1e-10, realisations = 2 }}\n"),
            "top_check.hurst must be one of hurst",
        ),
        (
            format!("{ls}top_check = {{ hurst = 0.0, bandwidth = 32, tolerance = 1e-10, realisations = 2 }}\n"),
            "top_check.bandwidth must be one of bandwidths",
        ),
        (
            format!("{ls}top_check = {{ hurst = 0.0, bandwidth = 16, tolerance = 1e-10, realisations = 1 }}\n"),
            "top_check.realisations",
        ),
        (
            format!("{ls}top_check = {{ hurst = 0.0, bandwidth = 16, tolerance = 0.5, realisations = 2 }}\n"),
            "top_check",
        ),
        (
            format!("{ls}scatter = {{ bandwidth = 32, realisations = 8 }}\n"),
            "scatter.bandwidth must be one of bandwidths",
        ),
        // top_check runs at twice the study's cells: the message names the key given.
        (
            format!("{ls}top_check = {{ hurst = 0.0, bandwidth = 16, tolerance = 1e-10, realisations = 2 }}\n")
                .replace("cells = 4", "cells = 17"),
            "top_check runs at twice cells = 17 (so cells must be at most 16): 34 cells per wavelength, outside 3..=32",
        ),
    ];
    each_refused(head, &cases);
}

/// The viscoelastic rough punch names a bad value before anything runs.
#[test]
fn viscoelastic_rough_refuses_bad_values() {
    let tmp = tempfile::tempdir().unwrap();
    let head = "name = \"b\"\n[material]\ne_star = 1.0\n[[outputs]]\n";
    let vr = "kind = \"viscoelastic_rough\"\nhurst = 0.8\nbandwidth = 4\ncells = 4\nrealisations_3d = 2\nrealisations_1d = 2\nforce = 0.05\nramp = 1.0\nhold = 1.0\nunload = 0.25\n";
    let cases = [
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.05]] }}\n"),
            "exceeds the shortest relaxation time modulus.terms tau = 5.000e-2: give steps >= 20",
        ),
        // A relaxation time no allowed step count resolves: said so, without a
        // 301-digit step count.
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 1e-300]] }}\n"),
            "steps would need 1.000e300, past the largest, 100000",
        ),
        // An empty lambda list is refused as static_friction_3d refuses it.
        (
            format!("{vr}steps = 10\nlambda = []\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n"),
            "lambda = []: give at least one value",
        ),
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[-4.0, 0.5]] }}\n"),
            "modulus",
        ),
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 0.0, terms = [[4.0, 0.5]] }}\n"),
            "modulus.relaxed must be > 0",
        ),
        // A load that touches a single cell is no rough contact.
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n")
                .replace("force = 0.05", "force = 1e-6"),
            "brings at most 1 cells into contact on the 16^2 grid",
        ),
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, f64::NAN]] }}\n")
                .replace("f64::NAN", "nan"),
            "modulus",
        ),
        // Force and approach both, neither, or a bad approach.
        (
            format!("{vr}approach = 1.0\nsteps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n"),
            "give either force",
        ),
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n")
                .replace("force = 0.05\n", ""),
            "give either force",
        ),
        (
            format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n")
                .replace("force = 0.05", "approach = -1.0"),
            "force or approach must be finite and > 0",
        ),
    ];
    each_refused(head, &cases);
    // A hold of 1e15 ramps: refused before anything is allocated, on both kinds.
    let scene = tmp.path().join("b.toml");
    let body = format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n")
        .replace("hold = 1.0", "hold = 1e15");
    std::fs::write(&scene, format!("{head}{body}")).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "b.toml", "--out", "o"]),
        "more than 1e6 steps",
    );
    let tv = "kind = \"tangential_viscoelastic\"\nmu = 0.3\nnormal_force = 0.1\ng_inf = 0.5\nprony = [[2.0, 0.5]]\namplitude = 0.2\nramp_time = 1.0\nhold_time = 1e15\n";
    let profile = "[profile]\nshapes = [{ kind = \"sphere\", radius = 5.0 }]\n";
    std::fs::write(
        &scene,
        format!(
            "{}{profile}[[outputs]]\n{tv}",
            head.trim_end_matches("[[outputs]]\n")
        ),
    )
    .unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "b.toml", "--out", "o"]),
        "more than 1e6 steps",
    );
    let body = format!("{vr}steps = 10\nmodulus = {{ relaxed = 1.0, terms = [[4.0, 0.5]] }}\n")
        .replace("unload = 0.25", "unload = 1.0");
    std::fs::write(&scene, format!("{head}{body}")).unwrap();
    refused(
        &mrdw_in(tmp.path(), &["run", "b.toml", "--out", "o"]),
        "unload must lie in [0, 1)",
    );
}

/// Peak resident memory [bytes] of `mrdw run` of `scene` on one thread in a fresh
/// process, read from /proc while it runs (VmHWM, the high-water mark).
#[cfg(target_os = "linux")]
fn peak_of_run(dir: &Path, scene: &str) -> f64 {
    use std::process::Stdio;
    std::fs::write(dir.join("m.toml"), scene).unwrap();
    let _ = std::fs::remove_dir_all(dir.join("o"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_mrdw"))
        .current_dir(dir)
        .args(["run", "m.toml", "--out", "o", "--threads", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("mrdw runs");
    let status = format!("/proc/{}/status", child.id());
    let mut peak: f64 = 0.0;
    loop {
        let kib = std::fs::read_to_string(&status).ok().and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        });
        peak = peak.max(kib.unwrap_or(0.0) * 1024.0);
        if let Some(done) = child.try_wait().unwrap() {
            assert!(done.success(), "{scene}");
            return peak;
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
}

/// The memory checks of the 1D outputs hold what a run measures: per spring, the
/// estimate is at least the measured peak (a refusal comes before an allocation fails)
/// and at most twice it (no run that fits is refused for want of memory it does not
/// need). Measured as the difference of the peaks at 2e6 and 1e6 springs (the process's
/// own memory drops out; both runs last long enough for the polls to see their peak).
#[cfg(target_os = "linux")]
#[test]
#[ignore = "slow: the full tier, `cargo test --workspace --release -- --ignored` (.ci/run)"]
fn spring_memory_estimates_hold() {
    use compare::checks::spring_bytes as b;
    let head = "name = \"m\"\n[material]\ne_star = 1.0\ng_star = 0.8\n[profile]\nshapes = [{ kind = \"sphere\", radius = 1.0 }]\n[[outputs]]\n";
    let prony = "prony = [[2.0, 0.5]]\n";
    let cases: [(&str, String, f64); 6] = [
        ("force_depth", "kind = \"force_depth\"\ndrive = \"force\"\nmax = 0.01\nsprings = N\n".into(), b::FORCE_DEPTH),
        ("adhesion", "kind = \"adhesion\"\ngamma = 0.01\ndepth_max = 0.36\ncontrol = \"force\"\nsprings = N\n".into(), b::ADHESION),
        ("damping", "kind = \"damping\"\nmu = 0.3\ndepth = 0.01\nmax_amplitude_ratio = 1.5\npoints = 4\nsprings = N\n".into(), b::DAMPING),
        ("viscoelastic", format!("kind = \"viscoelastic\"\ne_inf = 1.0\n{prony}depth_max = 0.1\nramp_time = 1.0\nend_time = 2.0\nsprings = N\n"), b::viscoelastic(1)),
        ("tangential_viscoelastic", format!("kind = \"tangential_viscoelastic\"\nmu = 0.3\nnormal_force = 0.1\ng_inf = 0.7\n{prony}amplitude = 0.2\nramp_time = 1.0\nhold_time = 1.0\nsteps = 10\nsprings = N\n"), b::tangential_viscoelastic(1)),
        ("static_friction", "kind = \"static_friction\"\nhurst = 0.7\npoints = N\nlength = 1e5\ncontacts_at_max_force = 40.0\nrealisations = 2\nforce_min = 1.0\nforce_max = 500.0\n".into(), b::rough_line(1)),
    ];
    let n = 1_000_000;
    in_two_lanes(&cases, |dir, (kind, body, estimate)| {
        let scene = format!("{head}{body}");
        growth_within(dir, &scene, [n, 2 * n], |s| s as f64, *estimate, kind);
    });
}

/// Runs `check` on every case, two at a time in threads of their own, each lane in its
/// own folder: the runs it measures are single-threaded (`--threads 1`) and each peak is
/// read from its own process, so two lanes on two cores halve the wall time and change
/// no measurement.
#[cfg(target_os = "linux")]
fn in_two_lanes<T: Sync>(cases: &[T], check: impl Fn(&Path, &T) + Sync) {
    std::thread::scope(|scope| {
        let lanes: Vec<_> = (0..2)
            .map(|lane| {
                let check = &check;
                scope.spawn(move || {
                    let dir = tempfile::tempdir().unwrap();
                    for case in cases.iter().skip(lane).step_by(2) {
                        check(dir.path(), case);
                    }
                })
            })
            .collect();
        for lane in lanes {
            if let Err(panic) = lane.join() {
                std::panic::resume_unwind(panic);
            }
        }
    });
}

/// Asserts that the peak memory of `mrdw run` grows from the size `sizes[0]` of `scene`'s
/// key N to `sizes[1]` by at most `estimate` bytes per unit of `units(size)` (springs,
/// cells), and by at least half of it, for the output `what`.
#[cfg(target_os = "linux")]
fn growth_within(
    dir: &Path,
    scene: &str,
    sizes: [usize; 2],
    units: impl Fn(usize) -> f64,
    estimate: f64,
    what: &str,
) {
    let peak = |n: usize| peak_of_run(dir, &scene.replace("N", &n.to_string()));
    let measured = (peak(sizes[1]) - peak(sizes[0])) / (units(sizes[1]) - units(sizes[0]));
    eprintln!("{what}: {measured:.1} bytes per unit measured, {estimate} estimated");
    assert!(
        measured <= estimate && estimate <= 2.0 * measured,
        "{what}: measured {measured:.1} bytes per unit, estimate {estimate}"
    );
}

/// The memory checks of the 3D scenes hold what a run measures: per cell of the finest
/// grid, the estimate ([`compare::checks::cell_bytes`]) is at least the growth of the
/// measured peak from a coarse grid to a fine one, and at most twice it. The grids are
/// small (128^2 to 512^2, seconds each); the estimates were set from 1024^2 and 2048^2,
/// where the growth per cell is lower still.
#[cfg(target_os = "linux")]
#[test]
#[ignore = "slow: the full tier, `cargo test --workspace --release -- --ignored` (.ci/run)"]
fn cell_memory_estimates_hold() {
    use compare::checks::cell_bytes as b;
    let head = "name = \"m\"\n[material]\ne_star = 1.0\n[[outputs]]\n";
    let friction = "kind = \"static_friction_3d\"\nhurst = [0.7]\nbandwidth = 8\ncells = N\nrealisations_3d = 2\nrealisations_1d = 2\nf_min = 1e-3\nf_max = 100.0\nf_points = 3\nlambda = [\"pi\"]\n";
    // (output, its text with N for the size key, the sizes, grid side per unit of N,
    // the estimate)
    let cases: [(&str, String, [usize; 2], usize, f64); 9] = [
        ("rough_sphere", "kind = \"rough_sphere\"\nradius = 1.0\nhertz_depth = 1e-3\nhurst = 0.8\nalpha = [0.1]\nside = 8.0\ngrid = N\nbandwidth = 12\nrealisations_3d = 2\nrealisations_1d = 2\nloads = 3\nlambda = [\"pi\"]\n".into(), [128, 512], 1, b::ROUGH_FREE),
        ("hurst_sweep", "kind = \"hurst_sweep\"\nhurst = [0.5]\ngrid = N\nrealisations_3d = 2\nrealisations_1d = 2\nloads = 6\n".into(), [128, 512], 1, b::ROUGH_FREE),
        ("contact_area", "kind = \"contact_area\"\nhurst = [0.5]\ngrid = N\nrealisations_3d = 2\nrealisations_1d = 2\nloads = 4\n".into(), [128, 512], 1, b::ROUGH_FREE),
        ("calibrate", "kind = \"calibrate\"\nself_affine = { hurst = 0.5 }\nbandwidth = N\ncells = 4\nrealisations = { min = 2, max = 2, batch = 2 }\ntarget = 0.3\nlines = 20\nloads = 6\n".into(), [32, 128], 4, b::ROUGH_FREE),
        ("static_friction_3d periodic", format!("{friction}geometry = [\"periodic\"]\n"), [16, 64], 8, b::ROUGH_PERIODIC),
        ("static_friction_3d disc", format!("{friction}geometry = [\"disc\"]\n"), [16, 64], 8, b::ROUGH_FREE),
        ("viscoelastic_rough", "kind = \"viscoelastic_rough\"\nhurst = 0.8\nbandwidth = 8\ncells = N\nrealisations_3d = 2\nrealisations_1d = 2\nmodulus = { relaxed = 1.0, terms = [[4.0, 0.5]] }\nforce = 0.05\nramp = 1.0\nhold = 1.0\nunload = 0.25\nsteps = 10\nlambda = [\"pi\"]\n".into(), [16, 32], 8, b::VISCOELASTIC_ROUGH),
        ("rough_adhesion_3d", "kind = \"rough_adhesion_3d\"\nradius = 1.0\nwork = 0.002\ndepth_max = 0.06\nhurst = [0.8]\nroughness = [0.2]\nside = 0.8\nbandwidth = 6\ncells = [N]\nrealisations_3d = 2\nrealisations_1d = 2\nsteps = 4\nlambda = [\"pi\"]\n".into(), [64, 256], 1, b::ADHESION),
        ("sliding_friction_3d", "kind = \"sliding_friction_3d\"\nmaterial = { kind = \"eq84\", g0 = 1.0, g1 = 1000.0, tau1 = 1e-2, tau2 = 1e2, s = 2.0, terms = 16 }\nsurface = { kind = \"band\", waves = 4.0, band = 1.4142135623730951 }\nlength = 1.0\nrms_height = 0.002\ngrid = N\nreduced_force = 1.0\nvelocity_min = 3.5e-6\nvelocity_max = 35.0\nvelocities = 3\nerror_limit = 1.0\nrealisations = 2\nmrd = { springs = 512 }\n".into(), [128, 512], 1, b::SLIDING),
    ];
    in_two_lanes(&cases, |dir, (kind, body, sizes, side, estimate)| {
        let cells = |n: usize| ((n * side) * (n * side)) as f64;
        growth_within(
            dir,
            &format!("{head}{body}"),
            *sizes,
            cells,
            *estimate,
            kind,
        );
    });
}

/// `tangential_3d` refuses what it cannot compare, naming the key: a flat punch (no
/// partial slip), fractions out of (0, 1) or not increasing (they are
/// read along one monotonic loading), G*/E* outside what one elastic body can have, a
/// grid too coarse, a free grid that does not hold the contact.
#[test]
fn tangential_3d_bad_input_names_the_key() {
    let tmp = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/tangential-3d.toml"),
    )
    .unwrap();
    let cases = [
        (
            base.replace(
                "{ kind = \"sphere\", radius = 10.0 }",
                "",
            )
            .replace("[profile]\n", "[profile]\nrim = 1.0\n"),
            "needs a curved body",
        ),
        (base.clone() + "fractions = [0.5, 0.2]\n", "must increase"),
        (base.clone() + "amplitudes = [0.5, 1.0]\n", "amplitudes"),
        (base.replace("cells = 256", "cells = 8"), "cells = 8"),
        // 3.2 cells per contact radius: no cell of the slip annulus, a dissipation of 0
        (base.replace("cells = 256", "cells = 32"), "cells per contact radius"),
        (
            base.replace("period = 10.0", "period = 2.0\nperiodic = false"),
            "on the free half-space",
        ),
        (
            base.replace(
                "[material.indenter]\nyoungs_modulus = inf\npoisson_ratio = 0.5\n\n[material.substrate]\nyoungs_modulus = 3.0\npoisson_ratio = 0.5",
                "[material]\ne_star = 1.0\ng_star = 0.1",
            ),
            "Poisson's ratio",
        ),
    ];
    refuses_each(tmp.path(), &base, &cases);
}

/// `tangential_viscoelastic`'s 3D side refuses what it cannot run, naming the key: a grid
/// too coarse, a free grid that does not hold the contact, a G*_inf / E* that no
/// elastic body has, a key of the 3D side given without it.
#[test]
fn tangential_viscoelastic_3d_bad_input_names_the_key() {
    refuses_each_edit(
        "tangential-viscoelastic-3d",
        &[
            ("cells_3d = 64", "cells_3d = 8", "cells_3d = 8"),
            ("side_3d = 2.5", "side_3d = 2.0", "side_3d"),
            (
                "side_3d = 2.5",
                "side_3d = 10.0",
                "cells per contact radius",
            ),
            (
                "amplitude = 0.2",
                "amplitude = 1e-300",
                "amplitude = 1e-300",
            ),
            // A key of the 3D side without the 3D side is refused, not ignored.
            ("cells_3d = 64\n", "", "give cells_3d"),
            (
                "g_inf = 0.6666666666666666",
                "g_inf = 0.5",
                "Poisson's ratio",
            ),
        ],
    );
}

/// `adhesion_3d` refuses what it cannot run, naming the key: no work of adhesion, a
/// ladder that does not refine, a grid too coarse, a domain that cuts the contact.
#[test]
fn adhesion_3d_bad_input_names_the_key() {
    refuses_each_edit(
        "adhesion-3d",
        &[
            ("gamma = 0.002", "gamma = 0.0", "gamma"),
            ("gamma = 0.002", "gamma = -1.0", "gamma"),
            (
                "cells = [32, 64, 128, 256]",
                "cells = [64, 32]",
                "must increase",
            ),
            ("cells = [32, 64, 128, 256]", "cells = [8]", "cells = [8]"),
            ("extent = 1.25", "extent = 0.5", "extent = 0.5"),
            ("steps = 100", "steps = 1", "steps = 1"),
            ("depth_max = 0.155", "depth_max = nan", "depth_max"),
        ],
    );
}

/// `tabor_3d` refuses what it cannot run, naming the key.
#[test]
fn tabor_3d_bad_input_names_the_key() {
    refuses_each_edit(
        "adhesion-tabor",
        &[
            ("lambdas = [0.1, 0.3, 1.0, 3.0]", "lambdas = []", "lambdas"),
            (
                "lambdas = [0.1, 0.3, 1.0, 3.0]",
                "lambdas = [0.0]",
                "lambdas",
            ),
            ("gamma = 0.002", "gamma = 0.0", "gamma"),
            ("cells = [64, 128]", "cells = [128, 64]", "must increase"),
            (
                "{ kind = \"sphere\", radius = 1.0 }",
                "{ kind = \"cone\", slope = 0.2 }",
                "needs a sphere",
            ),
        ],
    );
}

#[test]
fn periodic_patch_studies_bad_input_names_the_key() {
    refuses_each_edit(
        "rough-partial-slip-3d-ci",
        &[
            ("poisson = [0.5, 0.0]", "poisson = [0.6]", "poisson"),
            ("hurst = [0.5]", "hurst = []", "hurst"),
            ("cells = [4, 8]", "cells = [8, 4]", "cells"),
            ("mu = 0.5", "mu = 0.0", "mu"),
            // Too small a force for the mapped shift to keep its digits.
            (
                "fractions = [0.2, 0.5, 0.8]",
                "fractions = [1e-300, 0.5, 0.8]",
                "fractions = [1e-300, 0.5, 0.8]: give increasing fractions of mu F_N in [1e-6, 1)",
            ),
            ("pressure = 0.05", "pressure = 0.0", "pressure"),
            (
                "pressure = 0.05",
                "pressure = 1e-9",
                "leaves 1 cells in contact on the 32^2 grid",
            ),
            (
                "fractions = [0.2, 0.5, 0.8]",
                "fractions = [0.5, 1.0]",
                "fractions",
            ),
            (
                "amplitudes = [0.3, 0.6]",
                "amplitudes = [1.2]",
                "amplitudes",
            ),
            (
                "amplitudes = [0.3, 0.6]",
                "amplitudes = [1e-4]",
                "amplitudes: 0.0001 of mu F_N is below 1.000e-2",
            ),
            ("realisations = 3", "realisations = 1", "realisations"),
        ],
    );
    refuses_each_edit(
        "tangential-stiffness-3d-ci",
        &[
            (
                "pressures = [0.02, 0.1]",
                "pressures = [0.1, 0.02]",
                "pressures",
            ),
            ("bandwidth = 8", "bandwidth = 1", "bandwidth"),
        ],
    );
}

#[test]
fn rough_slip_bad_input_names_the_key() {
    refuses_each_edit(
        "rough-slip-3d-ci",
        &[
            (
                "radius = 1.0",
                "radius = 1.0\npunch_radius = 0.03",
                "punch_radius",
            ),
            ("mu = 0.5", "mu = -1.0", "mu"),
            ("mu = 0.5", "mu = nan", "mu"),
            ("force = 4.2164e-5", "force = 1.0", "force"),
            ("side = 0.13", "side = 0.05", "side"),
            ("side = 0.13", "side = 100.0", "at least 8 needed"),
            ("poisson = [0.0, 0.5]", "poisson = [0.7]", "poisson"),
            ("roughness = [1.0]", "roughness = [0.0]", "roughness"),
            (
                "fractions = [0.2, 0.5, 0.8, 0.95]",
                "fractions = [0.5, 1.0]",
                "fractions",
            ),
            ("amplitudes = [0.25, 0.9]", "amplitudes = []", "amplitudes"),
            (
                "amplitudes = [0.25, 0.9]",
                "amplitudes = [0.005]",
                "sqrt(1e4 x tolerance",
            ),
            ("cells = [64, 128]", "cells = [128, 64]", "cells"),
            (
                "lambda = [\"pi\", \"calibrated\"]",
                "lambda = [-2.0]",
                "lambda",
            ),
        ],
    );
}

#[test]
fn rough_adhesion_bad_input_names_the_key() {
    refuses_each_edit(
        "rough-adhesion-3d-ci",
        &[
            ("work = 0.002", "work = 0.0", "work"),
            ("work = 0.002", "work = -1.0", "work"),
            (
                "radius = 1.0",
                "radius = 1.0\npunch_radius = 0.2",
                "punch_radius",
            ),
            ("roughness = [0.2, 1.0]", "roughness = [0.0]", "roughness"),
            ("hurst = [0.8]", "hurst = [1.5]", "hurst"),
            ("cells = [64, 128]", "cells = [128, 64]", "cells"),
            ("side = 0.8", "side = 0.3", "side"),
            ("side = 0.8", "side = 100.0", "at least 8 needed"),
            ("depth_max = 0.06", "depth_max = 1e-7", "at least 8 needed"),
            (
                "roughness = [0.2, 1.0]",
                "roughness = [20.0]",
                "the roughest case's rms height",
            ),
            ("work = 0.002", "work = 1.0", "the adhesion length"),
            ("bandwidth = 6", "bandwidth = 40", "bandwidth"),
            ("depth_max = 0.06", "depth_max = 0.5", "depth_max"),
            ("steps = 30", "steps = 2", "steps"),
            ("seed = 3", "seed = 3\nmrd_rule = [\"inner\"]", "mrd_rule"),
            ("seed = 3", "seed = 3\nmrd_rule = []", "mrd_rule"),
        ],
    );
}

/// Each edit `(from, to, needle)` of the embedded scene `cases/{case}.toml` (every
/// `from` replaced by `to`; `from` must occur in it) is refused with a message naming
/// `needle`.
fn refuses_each_edit(case: &str, edits: &[(&str, &str, &str)]) {
    let tmp = tempfile::tempdir().unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("cases/{case}.toml"));
    let base = std::fs::read_to_string(path).unwrap();
    let cases: Vec<(String, &str)> = edits
        .iter()
        .map(|&(from, to, needle)| {
            assert!(base.contains(from), "{case}.toml has no `{from}`");
            (base.replace(from, to), needle)
        })
        .collect();
    refuses_each(tmp.path(), &base, &cases);
}

/// Runs each edited scene and checks it is refused with its message (edits must change
/// the scene).
fn refuses_each(dir: &Path, base: &str, cases: &[(String, &str)]) {
    for (k, (text, needle)) in cases.iter().enumerate() {
        assert_ne!(text, base, "case {k} changed nothing");
        let path = dir.join(format!("case{k}.toml"));
        std::fs::write(&path, text).unwrap();
        let o = mrdw_in(
            dir,
            &["run", path.to_str().unwrap(), "--out", &format!("o{k}")],
        );
        refused(&o, needle);
    }
}

/// `adhesion_3d` on a body without a closed-form pull-off (a power law) runs the 3D cycle
/// beside MRD alone: no closed-form columns (it ended in an internal error on the stage
/// it did not declare).
#[test]
fn adhesion_3d_runs_bodies_without_a_closed_form() {
    let tmp = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/adhesion-3d.toml"),
    )
    .unwrap();
    let text = base
        .replace(
            "{ kind = \"sphere\", radius = 1.0 }",
            "{ kind = \"power_law\", c = 0.5, n = 2.5 }",
        )
        .replace("cells = [32, 64, 128, 256]", "cells = [24, 48]")
        .replace("steps = 100", "steps = 30");
    let (o, out) = run_scene_text(tmp.path(), &text);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = summary(&out);
    let stages = s["outputs"][0]["stages"].as_array().unwrap();
    assert!(!stages.iter().any(|v| v == "closed_form"), "{stages:?}");
}

/// `plastic_3d` refuses what it cannot run, naming the key: no hardness or a NaN one, a
/// negative force (a history beyond separation), a ladder that does not refine, a rule
/// that does not exist, a flat punch.
#[test]
fn plastic_3d_bad_input_names_the_key() {
    refuses_each_edit(
        "plastic-sphere-ci",
        &[
            ("hardness = 0.05", "hardness = 0.0", "hardness = 0"),
            ("hardness = 0.05", "hardness = nan", "hardness = NaN"),
            ("forces = [0.001,", "forces = [-0.001,", "forces: -0.001"),
            ("cells = [24, 48]", "cells = [48, 24]", "cells = [48, 24]"),
            (
                "rings = 200",
                "rings = 200\nrules = [\"nope\"]",
                "rule `nope`",
            ),
            (
                "shapes = [{ kind = \"sphere\", radius = 1.0 }]",
                "shapes = [{ kind = \"sphere\", radius = 1.0 }]\nrim = 0.2",
                "flat punch",
            ),
        ],
    );
}

/// `adhesive_impact` refuses what it cannot run, naming the key: no work of adhesion, a
/// mass of zero, speeds not increasing, a speed whose contact leaves small strains.
#[test]
fn adhesive_impact_bad_input_names_the_key() {
    refuses_each_edit(
        "adhesive-impact-ci",
        &[
            ("work = 1e-4", "work = 0.0", "work = 0"),
            ("work = 1e-4", "work = nan", "work = NaN"),
            ("mass = 1e-3", "mass = 0.0", "mass = 0"),
            (
                "speeds = [0.035, 0.105, 0.28]",
                "speeds = [0.1, 0.05]",
                "speeds",
            ),
            (
                "speeds = [0.035, 0.105, 0.28]",
                "speeds = [0.035, 30.0]",
                "small-strain",
            ),
            ("steps_3d = 100", "steps_3d = 3", "steps_3d = 3"),
        ],
    );
}

/// `rough_plastic_3d` refuses what it cannot run, naming the key: a plasticity index of
/// zero, NaN or not increasing, a peak force the most plastic face could not carry, a
/// force ladder upside down, a grid that does not resolve the band, too few springs, a
/// tolerance the plastic step does not take.
#[test]
fn rough_plastic_3d_bad_input_names_the_key() {
    refuses_each_edit(
        "rough-plastic-3d-ci",
        &[
            (
                "plasticity = [1.0, 10.0]",
                "plasticity = [0.0, 10.0]",
                "plasticity",
            ),
            (
                "plasticity = [1.0, 10.0]",
                "plasticity = [nan]",
                "plasticity",
            ),
            (
                "plasticity = [1.0, 10.0]",
                "plasticity = [10.0, 1.0]",
                "plasticity",
            ),
            (
                "plasticity = [1.0, 10.0]",
                "plasticity = [1.0, 300.0]",
                "f_max = 0.3",
            ),
            (
                "seed = 1",
                "seed = 1
f_min = 0.5",
                "f_min = 0.5",
            ),
            ("cells = [8]", "cells = [1]", "cells"),
            ("springs = 1024", "springs = 16", "springs"),
            (
                "seed = 1",
                "seed = 1
tolerance = 0.1",
                "tolerance",
            ),
            (
                "seed = 1",
                "seed = 1
lambda = -1.0",
                "lambda = -1",
            ),
        ],
    );
}

/// The time-integrated scenes refuse what they cannot run, naming the key: no mass, a
/// speed of zero, a time step count out of range, an amplitude at which the body slides.
#[test]
fn dynamics_bad_input_names_the_key() {
    refuses_each_edit(
        "impact",
        &[
            ("mass = 1e-3", "mass = 0.0", "mass = 0"),
            ("speed = 0.05", "speed = nan", "speed = NaN"),
            ("speed = 0.05", "speed = 5.0", "a tenth of its radius"),
            (
                "cells = [32, 64]",
                "cells = [32, 64]\nsteps = 3",
                "steps = 3",
            ),
        ],
    );
    refuses_each_edit(
        "viscoelastic-impact",
        &[
            ("mass = 1e-3", "mass = 0.0", "mass = 0"),
            ("speeds = [", "speeds = [0.5, ", "speeds = "),
            ("prony = [[3.0, 0.5]]", "prony = []", "prony"),
            (
                "prony = [[3.0, 0.5]]",
                "prony = [[3.0, -0.5]]",
                "relaxation time",
            ),
            ("e_inf = 1.0", "e_inf = 0.0", "e_inf = 0"),
            ("cells = [32, 64]", "cells = [64, 32]", "cells = [64, 32]"),
        ],
    );
    refuses_each_edit(
        "ring-down",
        &[
            ("amplitude = 0.9", "amplitude = 1.0", "amplitude = 1"),
            ("mu = 0.3", "mu = -0.3", "mu = -0.3"),
            ("g_star = 1.0", "", "ring_down"),
            ("mass = 1e-3", "mass = 1e-3\ncells_3d = 8", "cells_3d = 8"),
            ("g_star = 1.0", "g_star = 0.5", "G* / E* = 0.5"),
            (
                "mass = 1e-3",
                "mass = 1e-3\nperiods_3d = 1",
                "periods_3d = 1",
            ),
            ("mass = 1e-3", "mass = 1e-3\nsteps_3d = 10", "steps_3d = 10"),
        ],
    );
    refuses_each_edit(
        "friction-forced-ci",
        &[
            ("drive = 0.05", "drive = 1.0", "drive = 1"),
            (
                "frequencies = [0.6,",
                "frequencies = [-0.6,",
                "frequencies holds -0.6",
            ),
            (
                "frequencies_3d = [0.94]",
                "frequencies_3d = [0.94, 20.0]",
                "frequencies_3d holds 20",
            ),
            ("steps = 100", "steps = 10", "steps = 10"),
            (
                "frequencies = [0.6,",
                "frequencies = [0.01, 0.6,",
                "at the lowest frequency 0.01",
            ),
            ("cells_3d = 24", "cells_3d = 8", "cells_3d = 8"),
            ("mass = 1e-3", "mass = 1e-3\ndamping = 1.0", "damping = 1"),
            (
                "mass = 1e-3",
                "mass = 1e-3\nsettle_tolerance = 0.0",
                "settle_tolerance = 0",
            ),
            ("g_star = 1.0", "g_star = 0.5", "G* / E* = 0.5"),
        ],
    );
    refuses_each_edit(
        "rough-ring-down-ci",
        &[
            ("preloads = [0.1, 1.0]", "preloads = []", "preloads = []"),
            (
                "preloads = [0.1, 1.0]",
                "preloads = [0.1, 20.0]",
                "preloads holds 20",
            ),
            ("mu = 0.3", "mu = 0.0", "mu = 0"),
            ("mu = 0.3", "mu = 1e7", "mu = 10000000"),
            ("mu = 0.3", "mu = 0.3\namplitude = 1.0", "amplitude = 1"),
            ("g_star = 1.0", "g_star = 0.5", "G* / E* = 0.5"),
            ("steps = 200", "steps = 10", "steps = 10"),
            ("lines = 8", "lines = 1", "lines = 1"),
            ("bandwidth = 4", "bandwidth = 64", "bandwidth = 64"),
            ("hurst = 0.8", "hurst = 1.5", "hurst = 1.5"),
            (
                "refine_3d = true",
                "refine_3d = true\nrefine_factor_3d = 1",
                "refine_factor_3d = 1",
            ),
            (
                "refine_3d = true",
                "refine_3d = false\nrefine_factor_3d = 4",
                "refine_factor_3d = 4 is set but refine_3d is false",
            ),
        ],
    );
    refuses_each_edit(
        "ring-down-wave-ci",
        &[
            (
                "amplitude = 0.2",
                "amplitude = 1.0",
                "normal_wave.amplitude = 1",
            ),
            (
                "frequencies = [0.5, 1.0, 2.0]",
                "frequencies = []",
                "normal_wave.frequencies has 0 values",
            ),
            (
                "frequencies = [0.5, 1.0, 2.0]",
                "frequencies = [0.5, -1.0]",
                "normal_wave.frequencies holds -1",
            ),
            (
                "frequencies = [0.5, 1.0, 2.0]",
                "frequencies = [1.0]\nphase = -1.5",
                "normal_wave.phase = -1.5",
            ),
            ("frequencies = [", "period = 2.0\nfrequencies = [", "period"),
        ],
    );
}

/// `forced_resonance` refuses keys out of range by name before computing.
#[test]
fn oblique_cycle_bad_input_names_the_key() {
    refuses_each_edit(
        "oblique-cycle-ci",
        &[
            (
                "normal_amplitude = 0.2",
                "normal_amplitude = 1.0",
                "normal_amplitude",
            ),
            (
                "normal_amplitude = 0.2",
                "normal_amplitude = -0.1",
                "normal_amplitude",
            ),
            ("normal_force = 1e-4", "normal_force = 0.0", "normal_force"),
            ("mu = 0.3", "mu = inf", "mu"),
            (
                "amplitudes = [0.1, 0.3, 0.5, 1.0, 2.0]",
                "amplitudes = []",
                "amplitudes",
            ),
            (
                "amplitudes = [0.1, 0.3, 0.5, 1.0, 2.0]",
                "amplitudes = [0.3, 0.1]",
                "amplitudes",
            ),
            ("cells = 24", "cells = 8", "cells"),
            ("springs = 2000", "springs = 10", "springs"),
            ("cells = 24", "cells = 24\ncycles = 1", "cycles"),
            ("cells = 24", "cells = 24\nsteps = 4", "steps"),
            ("g_star = 0.8235294117647058", "g_star = 0.5", "cells"),
            (
                "phases = [0.0, 90.0, 180.0]",
                "phases = [0.0, 270.0]",
                "phases",
            ),
            (
                "phases = [0.0, 90.0, 180.0]",
                "phases = [90.0, 90.0]",
                "phases",
            ),
            ("phases = [0.0, 90.0, 180.0]", "phases = []", "phases"),
        ],
    );
}

#[test]
fn oblique_impact_bad_input_names_the_key() {
    refuses_each_edit(
        "oblique-impact-ci",
        &[
            ("mu = 0.3", "mu = 0.0", "mu"),
            ("mu = 0.3", "mu = nan", "mu"),
            ("mass = 1e-3", "mass = -1e-3", "mass"),
            ("speed = 0.05", "speed = 5.0", "speed"),
            (
                "ratios = [0.5, 0.75, 1.5, 2.0, 4.0]",
                "ratios = []",
                "ratios",
            ),
            (
                "ratios = [0.5, 0.75, 1.5, 2.0, 4.0]",
                "ratios = [0.5, 0.4]",
                "ratios",
            ),
            (
                "ratios = [0.5, 0.75, 1.5, 2.0, 4.0]",
                "ratios = [-1.0]",
                "ratios",
            ),
            ("cells = [24]", "cells = [8]", "cells"),
            ("steps_3d = 200", "steps_3d = 10", "steps_3d"),
            ("g_star = 1.0", "g_star = 0.5", "cells"),
        ],
    );
}

#[test]
fn forced_resonance_bad_input_names_the_key() {
    refuses_each_edit(
        "forced-resonance-ci",
        &[
            ("forcing = [0.005, 0.15]", "forcing = []", "forcing"),
            (
                "forcing = [0.005, 0.15]",
                "forcing = [0.005, nan]",
                "forcing",
            ),
            (
                "forcing = [0.005, 0.15]",
                "forcing = [0.005, 2.0]",
                "forcing",
            ),
            ("steps = 60", "steps = 5", "steps"),
            ("frequencies = 9", "frequencies = 1", "frequencies"),
            ("lines = 4", "lines = 1", "lines"),
            ("bandwidth = 2", "bandwidth = 1", "bandwidth"),
            ("steps = 60", "steps = 60\ndamping = 0.0", "damping"),
            ("steps = 60", "steps = 60\ndamping = 1.5", "damping"),
            (
                "steps = 60",
                "steps = 60\nfrequency_band = [1.2, 0.6]",
                "frequency_band",
            ),
            (
                "steps = 60",
                "steps = 60\nfrequency_band = [0.0, 1.2]",
                "frequency_band",
            ),
            (
                "steps = 60",
                "steps = 60\nsettle_tolerance = 0.0",
                "settle_tolerance",
            ),
            ("steps = 60", "steps = 60\nmax_periods = 2", "max_periods"),
            ("steps = 60", "steps = 60\npreload = -1.0", "preload"),
            ("hurst = 0.8", "hurst = 1.5", "hurst"),
        ],
    );
}
