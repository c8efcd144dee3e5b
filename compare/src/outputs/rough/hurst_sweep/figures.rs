//! The sweep's tables, figures and summary results, from the typed [`Results`]:
//! alpha(H) in the style of Fig. 6, lambda(H), zeta(H), k(F) per H with bands and the
//! fit window, the finite-size study, and the lambda table in the form `mrd` loads.

use super::aggregate::{PerHurst, Results};
use super::HurstSweep;
use crate::experiment::fit::Estimate;
use crate::experiment::rough_punch::SolveTally;
use crate::report::{number_label, Figure, Section, Series, Style, Table};
use mrd::roughness::lambda_cut;
use std::f64::consts::PI;

/// Fills the sweep's section.
pub fn report(spec: &HurstSweep, r: &Results, out: &mut Section) {
    let label = out.label.clone();
    scalars(r, out);
    let alpha = alpha_table(spec, r, &label);
    let lambda = lambda_table(spec, r, &label);
    let curves = curves_table(r, &label);
    let bandwidth = spec.upper_cutoff_ratio * spec.grid as f64 / 2.0;
    out.figures.extend(summary_figures(r, &label, bandwidth));
    out.figures
        .extend(r.per_hurst.iter().map(|h| kf_figure(spec, r, h, &label)));
    out.tables
        .extend([alpha, lambda, curves, solves_table(spec, r, &label)]);
    failures(spec, r, out);
    if !r.convergence.is_empty() {
        let (t, fig) = convergence(spec, r, &label);
        out.figures.push(fig);
        out.tables.push(t);
    }
}

fn scalars(r: &Results, out: &mut Section) {
    // The tasks' own times summed over threads (on 2 threads up to twice the wall time).
    out.scalar("cpu_time_3d_s", r.seconds_3d);
    out.scalar("cpu_time_mrd_s", r.seconds_mrd);
    out.scalar("realisations_3d_total", r.realisations_3d as f64);
    out.scalar("realisations_mrd_total", r.realisations_mrd as f64);
    if !r.speedups.is_empty() {
        let mut s = r.speedups.clone();
        s.sort_by(f64::total_cmp);
        out.scalar("mrd_speedup_at_equal_error_median", s[s.len() / 2]);
    }
    let mut per_h = serde_json::Map::new();
    for h in &r.per_hurst {
        let mut o = serde_json::Map::new();
        for (name, e) in [
            ("alpha_3d", h.alpha_3d),
            ("alpha_mrd", h.alpha_mrd),
            ("zeta_3d", h.zeta_3d),
            ("zeta_mrd", h.zeta_mrd),
            ("lambda", h.lambda),
        ] {
            for (suffix, v) in [("", e.value), ("_lo95", e.lo), ("_hi95", e.hi)] {
                if v.is_finite() {
                    o.insert(format!("{name}{suffix}"), serde_json::json!(v));
                }
            }
        }
        o.insert(
            "unconverged_3d_solves".into(),
            serde_json::json!(h.unconverged_3d),
        );
        per_h.insert(format!("{}", h.hurst), serde_json::Value::Object(o));
    }
    out.value("per_hurst", serde_json::Value::Object(per_h));
}

fn alpha_table(spec: &HurstSweep, r: &Results, label: &str) -> Table {
    let mut t = Table::new(
        &format!("{label}_alpha"),
        &[
            "hurst [1]",
            "alpha_3d [1]",
            "alpha_3d_lo95 [1]",
            "alpha_3d_hi95 [1]",
            "alpha_mrd [1]",
            "alpha_mrd_lo95 [1]",
            "alpha_mrd_hi95 [1]",
            "alpha_eq80 [1]",
            "zeta_3d [1]",
            "zeta_3d_lo95 [1]",
            "zeta_3d_hi95 [1]",
            "zeta_mrd [1]",
            "zeta_mrd_lo95 [1]",
            "zeta_mrd_hi95 [1]",
            "lambda [1]",
            "lambda_lo95 [1]",
            "lambda_hi95 [1]",
            "lambda_cut [1]",
        ],
    );
    let (lo, hi) = spec.window(spec.grid);
    t.notes.push(format!(
        "Eq. (77) fits over k/(E* L) in [{lo:e}, {hi}] (lambda: over [0.02, 0.5], the shipped calibration's range); 95 % intervals: bootstrap over realisations (200 resamples); 3D grid {}^2 ({} realisations), 1D N = {} ({} realisations); empty cells: undefined (1/(1+H) at H = -1, lambda_cut for H <= -1/2, failed fits)",
        spec.grid, spec.realisations_3d, spec.points_1d_factor * spec.grid, spec.realisations_1d
    ));
    t.missing_ok = true;
    for h in &r.per_hurst {
        let eq80 = if h.hurst > -1.0 {
            1.0 / (1.0 + h.hurst)
        } else {
            f64::NAN
        };
        let mut row = vec![h.hurst];
        row.extend(h.alpha_3d.columns());
        row.extend(h.alpha_mrd.columns());
        row.push(eq80);
        row.extend(h.zeta_3d.columns());
        row.extend(h.zeta_mrd.columns());
        row.extend(h.lambda.columns());
        row.push(h.lambda_cut);
        t.push(row);
    }
    t
}

/// lambda(H) in the two-column form `mrd` loads (LambdaTable::from_csv; scene key
/// `lambda = "<file>"`), rows with a calibrated value only.
fn lambda_table(spec: &HurstSweep, r: &Results, label: &str) -> Table {
    let mut t = Table::new(
        &format!("{label}_lambda_table"),
        &["hurst [1]", "lambda [1]"],
    );
    t.notes.push(format!(
        "calibrated lambda(H) of Eq. (76) (C1D = lambda q C2D of the same C2D, the line not rescaled) on 3D {0}^2 circular rough punches ({1} realisations per H) against {2} MRD lines per H, fitted over k/(E* L) in [{3}, {4}] as the shipped calibration is; load with lambda = \"<this file>\"",
        spec.grid, spec.realisations_3d, spec.realisations_1d, super::aggregate::LAMBDA_WINDOW.0, super::aggregate::LAMBDA_WINDOW.1
    ));
    for h in r.per_hurst.iter().filter(|h| h.lambda.value.is_finite()) {
        t.push(vec![h.hurst, h.lambda.value]);
    }
    t
}

fn curves_table(r: &Results, label: &str) -> Table {
    let mut t = Table::new(
        &format!("{label}_curves"),
        &[
            "hurst [1]",
            "f = F/(E* h L) [1]",
            "k3d/(E* L) mean [1]",
            "k3d ci95 [1]",
            "kmrd/(E* L) mean [1]",
            "kmrd ci95 [1]",
            "in_fit_window [0/1]",
        ],
    );
    t.missing_ok = true;
    for h in &r.per_hurst {
        let (lo, hi) = h.window;
        for (j, &f) in r.f.iter().enumerate() {
            if let (Some(a), Some(b)) = (h.mean_3d[j], h.mean_mrd[j]) {
                t.push(vec![
                    h.hurst,
                    f,
                    a,
                    h.ci_3d[j],
                    b,
                    h.ci_mrd[j],
                    (a >= lo && a <= hi) as u8 as f64,
                ]);
            }
        }
    }
    t
}

/// Every 3D solve with its status: the record behind the curves.
fn solves_table(spec: &HurstSweep, r: &Results, label: &str) -> Table {
    let mut t = Table::new(
        &format!("{label}_solves"),
        &[
            "hurst [1]",
            "grid [cells]",
            "realisation [count]",
            "load [count]",
            "approach [L]",
            "force [E* L^2]",
            "iterations [count]",
            "residual [1]",
            "converged [0/1]",
            "stiffness_converged [0/1]",
        ],
    );
    t.notes.push(format!(
        "every 3D solve of the sweep: tolerance {:e} (criterion: bem3d::solver docs); unconverged solves (converged = 0, the residual reached) and failed stiffness solves are left out of the curves; iterations of restricted solves count iterations on a window around a compact contact (non-periodic) or applications of a dense K between a small candidate set (few contact cells; bem3d::solver docs)",
        spec.tolerance
    ));
    for (h, g, real, k, s) in &r.solves {
        t.push(vec![
            *h,
            *g as f64,
            *real as f64,
            *k as f64,
            s.approach,
            s.force,
            s.iterations as f64,
            s.residual,
            s.converged as u8 as f64,
            s.stiffness_converged as u8 as f64,
        ]);
    }
    t
}

/// Unconverged 3D solves make the run fail visibly (the report is still written).
fn failures(spec: &HurstSweep, r: &Results, out: &mut Section) {
    let mut tally = SolveTally::default();
    r.solves.iter().for_each(|s| tally.add(&s.4));
    tally.report(spec.tolerance, out);
}

/// One H of a lambda table: (hurst, lambda, lo95, hi95).
type LambdaRow = (f64, f64, f64, f64);

/// The shipped calibration from its CSV text.
fn shipped_lambda(csv: &str) -> Vec<LambdaRow> {
    csv.lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').map_while(|x| x.parse().ok()).collect();
            (v.len() >= 4).then(|| (v[0], v[1], v[2], v[3]))
        })
        .collect()
}

/// The lambda study's (hurst, lambda, lo95, hi95) at the bandwidth it has nearest to
/// `bandwidth` (in ratio), with that bandwidth.
fn study_at_bandwidth(bandwidth: f64) -> Option<(f64, Vec<LambdaRow>)> {
    let rows: Vec<[f64; 5]> = crate::experiment::lambda::LAMBDA_BY_BANDWIDTH_CSV
        .lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').map_while(|x| x.parse().ok()).collect();
            (v.len() >= 5).then(|| [v[0], v[1], v[2], v[3], v[4]])
        })
        .collect();
    let b = rows.iter().map(|r| r[1]).min_by(|x, y| {
        (x / bandwidth)
            .ln()
            .abs()
            .total_cmp(&(y / bandwidth).ln().abs())
    })?;
    let at: Vec<_> = rows
        .iter()
        .filter(|r| r[1] == b)
        .map(|r| (r[0], r[2], r[3], r[4]))
        .collect();
    Some((b, at))
}

/// alpha(H) (Fig. 6), lambda(H) and zeta(H).
fn summary_figures(r: &Results, label: &str, bandwidth: f64) -> [Figure; 3] {
    let shipped = shipped_lambda(crate::experiment::lambda::DEFAULT_LAMBDA_CSV);
    let surfaces = r.per_hurst.first().map_or(0, |h| h.realisations_3d);
    let pts = |f: fn(&PerHurst) -> Estimate| -> Vec<(f64, f64)> {
        r.per_hurst
            .iter()
            .filter(|h| f(h).value.is_finite())
            .map(|h| (h.hurst, f(h).value))
            .collect()
    };
    let bars = |f: fn(&PerHurst) -> Estimate| -> Vec<(f64, f64, f64)> {
        r.per_hurst
            .iter()
            .filter(|h| f(h).value.is_finite())
            .map(|h| (h.hurst, f(h).lo, f(h).hi))
            .collect()
    };
    // Eq. (80) is drawn from H = 1/4 (alpha 0.8, the top of the data), so that it does
    // not set the range and the data with their intervals fill the plot.
    let theory: Vec<(f64, f64)> = (0..=64)
        .map(|i| 0.25 + 2.75 * i as f64 / 64.0)
        .map(|h| (h, 1.0 / (1.0 + h)))
        .collect();
    // One quantity's 3D and MRD estimates against H, with their intervals.
    let sides = |fig: Figure, d3: fn(&PerHurst) -> Estimate, mrd: fn(&PerHurst) -> Estimate| {
        let three_d = Series::new("3D boundary elements (95% CI)", pts(d3), Style::Crosses);
        let line = Series::new("MRD (1D), lambda = pi (95% CI)", pts(mrd), Style::Line);
        fig.with(three_d.with_bars(bars(d3)))
            .with(line.with_bars(bars(mrd)))
    };
    let fig6 = sides(
        Figure::new(
            &format!("{label}_fig6"),
            "Exponent alpha of Eq. (77) against the Hurst exponent (cf. Fig. 6)",
            "Hurst exponent H [1]",
            "alpha [1]",
        ),
        |h| h.alpha_3d,
        |h| h.alpha_mrd,
    )
    .plot("1/(1+H), Eq. (80)", theory, Style::Dashed);
    let lam_cut_pts: Vec<(f64, f64)> = (0..=70)
        .map(|i| -0.45 + 3.45 * i as f64 / 70.0)
        .map(|h| (h, lambda_cut(h).unwrap_or(f64::NAN)))
        .collect();
    let mut figl = Figure::new(
        &format!("{label}_lambda"),
        "Calibrated lambda(H) of Eq. (76)",
        "Hurst exponent H [1]",
        "lambda [1]",
    )
    .with(
        Series::new(
            format!("this scene: bandwidth {bandwidth}, {surfaces} 3D surfaces (95% CI)"),
            pts(|h| h.lambda),
            Style::Crosses,
        )
        .with_bars(bars(|h| h.lambda)),
    )
    .with(
        Series::new(
            "shipped calibration: fig6-converged, bandwidth 128 (95% CI)",
            shipped.iter().map(|s| (s.0, s.1)).collect(),
            Style::Markers,
        )
        .with_bars(shipped.iter().map(|s| (s.0, s.2, s.3)).collect()),
    );
    // The study's value at this sweep's bandwidth (or the nearest it has): what the
    // sweep's intervals should hold, lambda depending on the bandwidth for H <= 0.
    if let Some((b, rows)) = study_at_bandwidth(bandwidth).filter(|(b, _)| *b != 128.0) {
        let which = if b == bandwidth {
            "the same"
        } else {
            "the nearest studied"
        };
        figl = figl.with(
            Series::new(
                format!("fig6-converged at bandwidth {b} ({which}; 95% CI; drawn at H + 0.08)"),
                rows.iter().map(|s| (s.0 + 0.08, s.1)).collect(),
                Style::Markers,
            )
            .with_bars(rows.iter().map(|s| (s.0 + 0.08, s.2, s.3)).collect()),
        );
    }
    figl = figl
        .plot("pi (Eq. 73)", vec![(-1.0, PI), (3.0, PI)], Style::Dashed)
        .plot(
            "straight cut sqrt(pi) G(H+1/2)/G(H+1)",
            lam_cut_pts,
            Style::Line,
        );
    figl.log_y = true;
    let figz = sides(
        Figure::new(
            &format!("{label}_zeta"),
            "Prefactor zeta of Eq. (77)",
            "Hurst exponent H [1]",
            "zeta [1]",
        ),
        |h| h.zeta_3d,
        |h| h.zeta_mrd,
    );
    [fig6, figl, figz]
}

/// k(F) at one H: the 3D mean with its 95 % interval as bars, MRD over the same force
/// range, the 3D fit over its window (drawn at half height, so that it does not hide
/// under the points it fits), MRD with the calibrated lambda, and the stiffness of one
/// contacting cell: the grid's floor, below which no 3D k can fall.
fn kf_figure(spec: &HurstSweep, r: &Results, h: &PerHurst, label: &str) -> Figure {
    let fs = &r.f;
    let pts = |m: &[Option<f64>]| -> Vec<(f64, f64)> {
        fs.iter()
            .zip(m)
            .filter_map(|(&f, v)| v.map(|v| (f, v)))
            .collect()
    };
    let three_d = pts(&h.mean_3d);
    // MRD over the 3D force range and half a decade either side: below it the line
    // carries loads no 3D punch of this grid resolves.
    let (f_lo, f_hi) = three_d.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    let in_range = |p: &(f64, f64)| p.0 >= f_lo / 3.0 && p.0 <= f_hi * 3.0;
    let bars: Vec<(f64, f64, f64)> = fs
        .iter()
        .zip(&h.mean_3d)
        .zip(&h.ci_3d)
        .filter_map(|((&f, m), c)| m.map(|m| (f, m - c, m + c)))
        .collect();
    let mut fig = Figure::new(
        &format!("{label}_kf_h{}", number_label(h.hurst)),
        &format!("k(F), H = {} (Eq. 77)", number_label(h.hurst)),
        "F/(E* h L) [1]",
        "k/(E* L) [1]",
    )
    .with(
        Series::new(
            format!(
                "3D BEM, {}^2, mean of {} realisations (95% CI)",
                spec.grid, h.realisations_3d
            ),
            three_d.clone(),
            Style::Markers,
        )
        .with_bars(bars),
    )
    .plot(
        format!("MRD, {} lines, lambda = pi", h.realisations_mrd),
        pts(&h.mean_mrd).into_iter().filter(in_range).collect(),
        Style::Line,
    );
    if let Some((a, z)) = h.fit_3d {
        let (lo, hi) = h.window;
        let w: Vec<(f64, f64)> = three_d
            .iter()
            .filter(|p| p.1 >= lo && p.1 <= hi)
            .map(|&(f, _)| (f, 0.5 * z * f.powf(a)))
            .collect();
        fig = fig.plot(
            format!("3D fit over its window, alpha = {a:.3} (drawn at half height)"),
            w,
            Style::Dashed,
        );
    }
    if h.lambda.value.is_finite() {
        let l = h.lambda.value;
        let s = (PI / h.lambda_shift).sqrt();
        let (f1, v1): (Vec<f64>, Vec<f64>) = pts(&h.mean_mrd).into_iter().unzip();
        let shifted: Vec<(f64, f64)> = fs
            .iter()
            .filter_map(|&f| crate::experiment::fit::interp_loglog(&f1, &v1, f * s).map(|v| (f, v)))
            .filter(in_range)
            .collect();
        fig = fig.plot(
            format!("MRD with calibrated lambda = {l:.3}"),
            shifted,
            Style::Dashed,
        );
    }
    // One contacting square cell of side dx under a rigid flat: k = pi E* dx / (4
    // ln(1 + sqrt 2)) (Love's deflection at the centre of a uniformly loaded square),
    // with dx = L / grid (the punch fills the grid).
    let floor = PI / (4.0 * (1.0 + 2f64.sqrt()).ln()) / spec.grid as f64;
    if f_lo.is_finite() {
        fig = fig.plot(
            format!("one cell in contact: k/(E* L) = {floor:.2e}, the grid's floor"),
            vec![(f_lo / 3.0, floor), (f_hi * 3.0, floor)],
            Style::Dashed,
        );
    }
    fig.log_log()
}

/// The finite-size study: 3D alpha against the grid (system size at 8 cells per
/// shortest wavelength).
fn convergence(spec: &HurstSweep, r: &Results, label: &str) -> (Table, Figure) {
    let mut t = Table::new(
        &format!("{label}_convergence"),
        &[
            "hurst [1]",
            "grid [cells]",
            "L / shortest wavelength [1]",
            "alpha_3d [1]",
            "alpha_3d_lo95 [1]",
            "alpha_3d_hi95 [1]",
        ],
    );
    t.missing_ok = true;
    for c in &r.convergence {
        t.push(vec![
            c.hurst,
            c.grid as f64,
            spec.upper_cutoff_ratio * c.grid as f64 / 2.0,
            c.alpha_3d.value,
            c.alpha_3d.lo,
            c.alpha_3d.hi,
        ]);
    }
    let mut fig = Figure::new(
        &format!("{label}_convergence"),
        "Finite-size study: 3D alpha against system size (8 cells per shortest wavelength)",
        "grid cells across the punch, = 8 L / shortest wavelength [1]",
        "alpha_3d [1] (95% CI)",
    );
    let mut grids: Vec<f64> = r.convergence.iter().map(|c| c.grid as f64).collect();
    grids.push(spec.grid as f64);
    grids.sort_by(f64::total_cmp);
    grids.dedup();
    fig.log_x = true;
    fig.x_keys = Some(grids);
    // Each H: markers with their intervals, joined by a thin line of the same colour;
    // the H are offset by a few per cent along x so that their bars stay apart.
    let n = spec.hurst.len().max(1) as f64;
    for (j, &hurst) in spec.hurst.iter().enumerate() {
        let shift = 1.0 + 0.06 * (j as f64 - (n - 1.0) / 2.0) / n;
        let mut est: Vec<(f64, Estimate)> = r
            .convergence
            .iter()
            .filter(|c| c.hurst == hurst && c.alpha_3d.value.is_finite())
            .map(|c| (c.grid as f64, c.alpha_3d))
            .collect();
        if let Some(h) = r.per_hurst.iter().find(|h| h.hurst == hurst) {
            est.push((spec.grid as f64, h.alpha_3d));
        }
        est.sort_by(|a, b| a.0.total_cmp(&b.0));
        let pts: Vec<(f64, f64)> = est.iter().map(|(g, e)| (g * shift, e.value)).collect();
        let bars = est.iter().map(|(g, e)| (g * shift, e.lo, e.hi)).collect();
        fig = fig
            .with(
                Series::new(format!("H = {hurst}"), pts.clone(), Style::Markers)
                    .with_bars(bars)
                    .colored(j),
            )
            .with(Series::new("", pts, Style::Line).colored(j).thin());
    }
    (t, fig)
}
