//! The study's tables, figures and summary: every case (lambda, alpha of both sides,
//! residual misfit, realisations against the target), the paired ratios, the curves with
//! their local exponents, lambda and alpha against bandwidth, and the calibrated table in
//! the form `lambda = "<file>"` loads.

use super::analysis::{CaseResult, Results};
use super::scatter::Scatter;
use super::tasks::Role;
use super::LambdaStudy;
use crate::experiment::fit::Estimate;
use crate::report::{number_label, Figure, Section, Series, Style, Table};
use std::f64::consts::PI;

pub fn report(s: &LambdaStudy, r: &Results, sc: &[Scatter], out: &mut Section) {
    let label = out.label.clone();
    out.scalar("cpu_time_3d_s", r.seconds_3d);
    out.scalar("cpu_time_mrd_s", r.seconds_mrd);
    out.scalar("cases_with_data", r.cases.len() as f64);
    out.tables.push(cases_table(s, r, &label));
    out.tables.push(pairs_table(r, &label));
    out.tables.push(curves_table(r, &label));
    out.files.push((
        format!("{label}_lambda_calibrated.csv"),
        calibrated_csv(s, r).into_bytes(),
    ));
    out.figures.push(against_bandwidth(s, r, &label, "lambda"));
    out.figures.push(ratio_against_bandwidth(s, r, &label));
    out.figures.push(against_bandwidth(s, r, &label, "alpha"));
    for h in &s.hurst {
        if let Some(c) = main_case(s, r, *h) {
            out.figures.push(local_exponent_figure(r, c, &label));
        }
    }
    super::scatter::report(sc, &r.f, &label, out);
    for c in r
        .cases
        .iter()
        .filter(|c| c.case.role == Role::Ladder && c.case.band == s.calibrate_at)
    {
        if !(..=c.target).contains(&c.lambda.relative_half_width()) {
            out.warn(format!(
                "H = {}: lambda = {:.3} [{:.3}, {:.3}] from {} realisations misses its target of +/- {:.0} % (bandwidth {})",
                c.case.hurst,
                c.lambda.value,
                c.lambda.lo,
                c.lambda.hi,
                c.realisations,
                100.0 * c.target,
                c.case.band
            ));
        }
    }
}

fn main_case<'a>(s: &LambdaStudy, r: &'a Results, hurst: f64) -> Option<&'a CaseResult> {
    r.cases.iter().find(|c| {
        c.case.hurst == hurst
            && c.case.band == s.calibrate_at
            && c.case.cells == s.cells
            && c.case.tolerance == s.tolerance
    })
}

fn role_code(role: Role) -> f64 {
    match role {
        Role::Ladder => 0.0,
        Role::Above => 1.0,
        Role::Resolution => 2.0,
        Role::Tolerance => 3.0,
    }
}

fn cases_table(s: &LambdaStudy, r: &Results, label: &str) -> Table {
    let cols = [
        "hurst [1]",
        "bandwidth L/lambda_min [1]",
        "cells_per_min_wavelength [count]",
        "tolerance [1]",
        "role [code]",
        "realisations_3d [count]",
        "lambda [1]",
        "lambda_lo95 [1]",
        "lambda_hi95 [1]",
        "lambda_rel_half_width [1]",
        "target_rel_half_width [1]",
        "alpha_3d [1]",
        "alpha_3d_lo95 [1]",
        "alpha_3d_hi95 [1]",
        "alpha_mrd [1]",
        "misfit_max [1]",
        "misfit_rms [1]",
        "f_min [1]",
        "f_max [1]",
        "unconverged_3d_solves [count]",
        "lambda_lower_half [1]",
        "lambda_upper_half [1]",
        "alpha_3d_lower_half [1]",
        "alpha_3d_upper_half [1]",
        "alpha_mrd_lower_half [1]",
        "alpha_mrd_upper_half [1]",
    ];
    let mut t = study_table(label, "cases", &cols, format!(
        "lambda of Eq. (76) calibrated on 3D circular rough punches (E* = 1, L = 1, nested self-affine surfaces C2D ~ q^(-2H-2), |k| <= bandwidth in units of 2 pi/L, on cells x bandwidth cells a side) against {} MRD lines per H and bandwidth (lambda = pi, {} points per cell); calibration and fits over k/(E* L) in [{}, {}] (f_min..f_max: that range in f = F/(E* h L)); lambda as Eq. (76) states it, C1D = lambda q C2D at the line's wavenumbers (the fit shifts the reduced MRD curve by pi h1^2 / h3^2, lambda times the rms factor of the case's spectrum on the line and the punch face: compare::outputs::lambda_meaning); misfit = |ln k3 - ln k1(lambda)| over it; 95 % bootstrap intervals over 3D realisations (200 resamples); role 0 = main ladder (realisations added until the interval meets the target), 1 = bandwidth above calibrate_at = {} (paired check), 2 = resolution check, 3 = tolerance check; lambda_lower_half, lambda_upper_half: lambda calibrated on the lower and upper half of the range's points (its dependence on the forces fitted); alpha_*_half: Eq. (77)'s exponent fitted on the same halves (3D and MRD at the same f)",
        s.realisations_1d, s.points_1d_per_cell, s.window[0], s.window[1], s.calibrate_at
    ));
    for c in &r.cases {
        let mut row = vec![
            c.case.hurst,
            c.case.band as f64,
            c.case.cells as f64,
            c.case.tolerance,
            role_code(c.case.role),
            c.realisations as f64,
        ];
        row.extend(c.lambda.columns());
        row.push(c.lambda.relative_half_width());
        row.push(c.target);
        row.extend(c.alpha_3d.columns());
        row.extend([
            c.alpha_mrd.value,
            c.misfit_max,
            c.misfit_rms,
            c.f_range.0,
            c.f_range.1,
            c.unconverged as f64,
            c.lambda_halves.0,
            c.lambda_halves.1,
        ]);
        row.extend(c.alpha_halves);
        t.push(row.into_iter().map(finite_or_nan).collect());
    }
    t
}

/// The study's table `{label}_{name}` with its note; a cell a case lacks is NaN.
fn study_table(label: &str, name: &str, cols: &[&str], note: String) -> Table {
    let mut t = Table::new(&format!("{label}_{name}"), cols);
    t.missing_ok = true;
    t.notes.push(note);
    t
}

fn finite_or_nan(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        f64::NAN
    }
}

fn pairs_table(r: &Results, label: &str) -> Table {
    let cols = [
        "hurst [1]",
        "bandwidth [1]",
        "cells [count]",
        "tolerance [1]",
        "reference_bandwidth [1]",
        "reference_cells [count]",
        "reference_tolerance [1]",
        "shared_realisations [count]",
        "lambda_ratio [1]",
        "lambda_ratio_lo95 [1]",
        "lambda_ratio_hi95 [1]",
    ];
    let mut t = study_table(label, "pairs", &cols, "lambda(case) / lambda(reference) on the same nested realisations (paired bootstrap, 200 resamples): bandwidth ladder against calibrate_at, other cells per wavelength against the main cells, the second tolerance against the first".into());
    for p in &r.pairs {
        let mut row = vec![
            p.case.hurst,
            p.case.band as f64,
            p.case.cells as f64,
            p.case.tolerance,
            p.reference.band as f64,
            p.reference.cells as f64,
            p.reference.tolerance,
            p.realisations as f64,
        ];
        row.extend(p.ratio.columns());
        t.push(row.into_iter().map(finite_or_nan).collect());
    }
    t
}

fn curves_table(r: &Results, label: &str) -> Table {
    let cols = [
        "hurst [1]",
        "bandwidth [1]",
        "cells [count]",
        "tolerance [1]",
        "f = F/(E* h L) [1]",
        "k3/(E* L) mean [1]",
        "k1/(E* L) mean, lambda = pi [1]",
        "dlnk/dlnf 3d [1]",
        "dlnk/dlnf 3d lo95 [1]",
        "dlnk/dlnf 3d hi95 [1]",
        "dlnk/dlnf mrd [1]",
    ];
    let mut t = study_table(label, "curves", &cols, "ensemble means on the common f grid (a 3D point where every realisation reaches it) and local exponents by central differences (3D band: bootstrap 95 %)".into());
    for c in &r.cases {
        for (j, &f) in r.f.iter().enumerate() {
            if c.mean_3d[j].is_none() && c.mean_mrd[j].is_none() {
                continue;
            }
            let s3 = c.slope_3d[j].unwrap_or(Estimate::NONE);
            let row = vec![
                c.case.hurst,
                c.case.band as f64,
                c.case.cells as f64,
                c.case.tolerance,
                f,
                c.mean_3d[j].unwrap_or(f64::NAN),
                c.mean_mrd[j].unwrap_or(f64::NAN),
                s3.value,
                s3.lo,
                s3.hi,
                c.slope_mrd[j].unwrap_or(f64::NAN),
            ];
            t.push(row.into_iter().map(finite_or_nan).collect());
        }
    }
    t
}

/// The shipped table: one row per H at `calibrate_at`, header and provenance.
fn calibrated_csv(s: &LambdaStudy, r: &Results) -> String {
    let mut text = format!(
        "# {} -- lambda(H) of Eq. (76), C1D = lambda q C2D at the line's wavenumbers 2 pi k / L, the line synthesised from the same C2D as the surface (no rescaling: mrdw.line(lam=...), line_spectrum, every scene's lambda), calibrated by lambda_study on 3D circular rough punches, faces and lines with fixed amplitudes (|H(q)| as Eqs. 71-72 write them, random phases; calibrate's amplitudes = \"gaussian\" gives the other choice):\n# bandwidth L/lambda_min = {}, {} cells per shortest wavelength, solver tolerance {:e}, seed {}, {} MRD lines per H,\n# fit range k/(E* L) in [{}, {}] (the whole common range of the curves); 95 % bootstrap intervals over 3D realisations;\n# misfit_max, misfit_rms: |ln k3D - ln kMRD| after calibration over that range.\n",
        crate::report::tool_version(), s.calibrate_at, s.cells, s.tolerance, s.seed, s.realisations_1d, s.window[0], s.window[1]
    );
    text.push_str(&format!(
        "# compute: {:.1} h of 3D solves (every case of the study; task wall times summed, one task per core) and {:.2} h of MRD ensembles (wall, all cores)\n",
        r.seconds_3d / 3600.0,
        r.seconds_mrd / 3600.0
    ));
    // How lambda depends on the forces it is fitted over.
    for h in &s.hurst {
        if let Some(c) = main_case(s, r, *h) {
            text.push_str(&format!(
                "# H = {h}: lambda fitted on the lower / upper half of the range's forces = {:.3} / {:.3}\n",
                c.lambda_halves.0, c.lambda_halves.1
            ));
        }
    }
    // How lambda moves above calibrate_at: the paired ratios of the main ladder.
    for p in r.pairs.iter().filter(|p| {
        p.reference.band == s.calibrate_at
            && p.case.band > s.calibrate_at
            && p.case.cells == s.cells
            && p.case.tolerance == s.tolerance
    }) {
        text.push_str(&format!(
            "# H = {}: lambda at bandwidth {} / lambda here = {:.3} [{:.3}, {:.3}] (95 %, {} paired realisations)\n",
            p.case.hurst, p.case.band, p.ratio.value, p.ratio.lo, p.ratio.hi, p.realisations
        ));
    }
    text.push_str("hurst,lambda,lambda_lo95,lambda_hi95,misfit_max,misfit_rms,bandwidth,realisations_3d,cells_per_min_wavelength\n");
    for h in &s.hurst {
        if let Some(c) = main_case(s, r, *h) {
            if c.lambda.value.is_finite() {
                text.push_str(&format!(
                    "{},{:.6},{:.6},{:.6},{:.4},{:.4},{},{},{}\n",
                    h,
                    c.lambda.value,
                    c.lambda.lo,
                    c.lambda.hi,
                    c.misfit_max,
                    c.misfit_rms,
                    c.case.band,
                    c.realisations,
                    c.case.cells
                ));
            }
        }
    }
    text
}

/// lambda or alpha (3D with bars, MRD) against bandwidth, one series per H.
fn against_bandwidth(s: &LambdaStudy, r: &Results, label: &str, what: &str) -> Figure {
    let (title, y) = if what == "lambda" {
        (
            "lambda (Eq. 76) vs bandwidth, each fitted on its own force range (95 %)",
            "lambda [1]",
        )
    } else {
        (
            "alpha of Eq. (77) against bandwidth: 3D (markers, 95 % intervals) and MRD (lines)",
            "alpha [1]",
        )
    };
    let mut fig = Figure::new(
        &format!("{label}_{what}_vs_bandwidth"),
        title,
        &format!(
            "bandwidth L / lambda_min [1] ({} cells per shortest wavelength; each H offset a little)",
            s.cells
        ),
        y,
    );
    fig.log_x = true;
    fig.log_y = what == "lambda";
    fig.x_keys = Some(bandwidth_keys(s));
    for (i, h) in s.hurst.iter().enumerate() {
        let dodge = dodge(s, i);
        let mut cs: Vec<&CaseResult> = r
            .cases
            .iter()
            .filter(|c| {
                c.case.hurst == *h && c.case.cells == s.cells && c.case.tolerance == s.tolerance
            })
            .collect();
        cs.sort_by_key(|c| c.case.band);
        let pick = |c: &CaseResult| {
            if what == "lambda" {
                c.lambda
            } else {
                c.alpha_3d
            }
        };
        let pts: Vec<(f64, f64)> = cs
            .iter()
            .map(|c| (c.case.band as f64 * dodge, pick(c).value))
            .filter(|p| p.1.is_finite())
            .collect();
        if pts.is_empty() {
            continue;
        }
        let bars = cs
            .iter()
            .map(|c| (c.case.band as f64 * dodge, pick(c).lo, pick(c).hi))
            .filter(|b| b.1.is_finite() && b.2.is_finite())
            .collect();
        let n: usize = cs.iter().map(|c| c.realisations).min().unwrap_or(0);
        fig = fig.with(
            Series::new(
                format!("H = {h} (3D, >= {n} realisations)"),
                pts,
                Style::Markers,
            )
            .with_bars(bars)
            .colored(i),
        );
        if what == "alpha" {
            let m: Vec<(f64, f64)> = cs
                .iter()
                .map(|c| (c.case.band as f64 * dodge, c.alpha_mrd.value))
                .filter(|p| p.1.is_finite())
                .collect();
            fig = fig.with(Series::new(format!("H = {h} (MRD)"), m, Style::Line).colored(i));
        }
    }
    if what == "lambda" {
        // Over the bandwidths with data (the axis keeps every bandwidth of the study).
        let with_data: Vec<f64> = r
            .cases
            .iter()
            .filter(|c| matches!(c.case.role, Role::Ladder | Role::Above))
            .map(|c| c.case.band as f64)
            .collect();
        let bands: Vec<f64> = if with_data.is_empty() {
            s.bandwidths.iter().map(|&b| b as f64).collect()
        } else {
            with_data
        };
        let (b0, b1) = (
            bands.iter().copied().fold(f64::INFINITY, f64::min),
            bands.iter().copied().fold(0.0, f64::max),
        );
        fig = fig.plot(
            "lambda = pi (Eq. 73)",
            vec![(b0, PI), (b1, PI)],
            Style::Dashed,
        );
    }
    fig
}

/// The study's bandwidths (powers of 2), the extra ones included: where the data are.
fn bandwidth_keys(s: &LambdaStudy) -> Vec<f64> {
    let mut keys: Vec<usize> = s.bandwidths.clone();
    keys.extend(s.extra.iter().map(|e| e.bandwidth));
    keys.sort_unstable();
    keys.dedup();
    keys.into_iter().map(|b| b as f64).collect()
}

/// The factor on the bandwidth that sets H number `i`'s points a little apart from the
/// others', so that no interval hides another's.
fn dodge(s: &LambdaStudy, i: usize) -> f64 {
    1.0 + 0.025 * (i as f64 - 0.5 * (s.hurst.len() as f64 - 1.0))
}

/// lambda(B) / lambda(calibrate_at) on the same nested realisations against B, per H
/// (the paired ratios of `pairs_table`: how lambda moves with bandwidth without the
/// scatter the cases share, and fitted on common forces), with the first interval target
/// drawn around 1.
fn ratio_against_bandwidth(s: &LambdaStudy, r: &Results, label: &str) -> Figure {
    let b0 = s.calibrate_at;
    let mut fig = Figure::new(
        &format!("{label}_lambda_ratio_vs_bandwidth"),
        &format!("lambda(B) / lambda({b0}) on the same realisations and forces (paired, 95 %)"),
        &format!(
            "bandwidth L / lambda_min [1] ({} cells per shortest wavelength; each H offset a little)",
            s.cells
        ),
        "lambda ratio [1]",
    );
    fig.log_x = true;
    fig.x_keys = Some(bandwidth_keys(s));
    let main = |c: &super::tasks::Case| c.cells == s.cells && c.tolerance == s.tolerance;
    for (i, h) in s.hurst.iter().enumerate() {
        let mut ps: Vec<_> = r
            .pairs
            .iter()
            .filter(|p| p.case.hurst == *h && main(&p.case) && main(&p.reference))
            .filter(|p| p.reference.band == b0 && p.case.band != b0)
            .filter(|p| p.ratio.value.is_finite())
            .collect();
        if ps.is_empty() {
            continue;
        }
        ps.sort_by_key(|p| p.case.band);
        let x = |band: usize| band as f64 * dodge(s, i);
        let mut pts: Vec<(f64, f64)> = ps.iter().map(|p| (x(p.case.band), p.ratio.value)).collect();
        pts.push((x(b0), 1.0));
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let bars = ps
            .iter()
            .map(|p| (x(p.case.band), p.ratio.lo, p.ratio.hi))
            .filter(|b| b.1.is_finite() && b.2.is_finite())
            .collect();
        let n = ps.iter().map(|p| p.realisations).min().unwrap_or(0);
        fig = fig.with(
            Series::new(
                format!("H = {h} (>= {n} paired realisations)"),
                pts,
                Style::Markers,
            )
            .with_bars(bars)
            .colored(i),
        );
    }
    if let Some(&[h_max, t]) = s.target.first() {
        let keys = bandwidth_keys(s);
        let (lo, hi) = (keys[0], keys[keys.len() - 1]);
        let line = |v: f64| vec![(lo, v), (hi, v)];
        let name = format!(
            "1 +/- {:.0} % (the interval target for H <= {h_max})",
            100.0 * t
        );
        let k = s.hurst.len();
        fig = fig
            .with(Series::new(name, line(1.0 + t), Style::Dashed).colored(k))
            .with(Series::new("", line(1.0 - t), Style::Dashed).colored(k));
    }
    fig
}

fn local_exponent_figure(r: &Results, c: &CaseResult, label: &str) -> Figure {
    let h = c.case.hurst;
    let pick = |f: &dyn Fn(&Estimate) -> f64| -> Vec<(f64, f64)> {
        r.f.iter()
            .zip(&c.slope_3d)
            .filter_map(|(&x, e)| e.map(|e| (x, f(&e))))
            .filter(|p| p.1.is_finite())
            .collect()
    };
    let mrd: Vec<(f64, f64)> =
        r.f.iter()
            .zip(&c.slope_mrd)
            .filter_map(|(&x, v)| v.map(|v| (x, v)))
            .collect();
    let mut fig = Figure::new(
        &format!("{label}_local_exponent_h{}", number_label(h)),
        &format!(
            "Local exponent d ln k / d ln f, H = {}, bandwidth {} ({} cells per shortest wavelength)",
            number_label(h),
            c.case.band, c.case.cells
        ),
        "reduced force f = F/(E* h L) [1]",
        "d ln k / d ln f [1]",
    )
    .with(
        Series::new(
            format!("3D mean of {} realisations", c.realisations),
            pick(&|e| e.value),
            Style::Line,
        )
        .colored(0),
    )
    .with(Series::new("3D 95 % band", pick(&|e| e.lo), Style::Dashed).colored(0))
    .with(Series::new("3D 95 % band (upper)", pick(&|e| e.hi), Style::Dashed).colored(0))
    .with(Series::new("MRD, lambda = pi", mrd, Style::Line).colored(1));
    if c.f_range.0.is_finite() {
        let (a, b) = (c.alpha_3d.value, c.alpha_mrd.value);
        fig = fig.with(
            Series::new(
                format!("fit window and alpha_3D = {a:.3} (alpha_MRD = {b:.3})"),
                vec![(c.f_range.0, a), (c.f_range.1, a)],
                Style::Crosses,
            )
            .colored(2),
        );
    }
    fig.log_x = true;
    fig
}
