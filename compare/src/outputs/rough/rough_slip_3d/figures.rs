//! `rough_slip_3d`'s figures: the curves against the force, MRD over 3D, the stick maps.

use super::quantity::{CaseRows, Quantity, ZERO};
use super::runs::Case;
use super::Body;
use super::RoughSlip3d;
use crate::experiment::lambda::LambdaSpec;
use crate::report::{Figure, Series, Style, Table};

/// lambda as the scene names it: "lambda = pi", "lambda = calibrated", "lambda = 3".
pub(super) fn lambda_name(l: &LambdaSpec) -> String {
    match l {
        LambdaSpec::Value(v) => format!("lambda = {v}"),
        LambdaSpec::Named(n) => format!("lambda = {n}"),
    }
}

fn case_label(hurst: f64, roughness: f64) -> String {
    if roughness == 0.0 {
        "smooth".into()
    } else {
        format!("H = {hurst}, h = {roughness} d_0")
    }
}

/// The Poisson's ratio the figures show: the largest (0.5: the paper's elastomers).
fn figure_poisson(spec: &RoughSlip3d) -> f64 {
    spec.poisson.iter().copied().fold(0.0, f64::max)
}

/// The cases' rows of `t` on `grid` at the figures' Poisson's ratio, in case order.
fn case_rows<'t>(spec: &RoughSlip3d, t: &'t Table, grid: f64) -> CaseRows<'t> {
    let nu = figure_poisson(spec);
    spec.cases()
        .into_iter()
        .map(|(h, r)| {
            let rows = t
                .rows
                .iter()
                .filter(|row| row[0] == h && row[1] == r && row[2] == nu && row[3] == grid)
                .collect();
            ((h, r), rows)
        })
        .collect()
}

/// The quantity against the force (or amplitude): 3D means with intervals, MRD per
/// lambda as lines; per case one colour; at the figures' Poisson's ratio.
pub(super) fn curve_figure(
    spec: &RoughSlip3d,
    t: &Table,
    q: &Quantity,
    grid: f64,
    log: bool,
) -> Figure {
    let (title, name, y) = if q.stem == "shift" {
        (
            "Tangential force-shift curves of rough bodies up to gross slip: 3D and MRD",
            "force_shift",
            "shift over mu d_0 [1]",
        )
    } else {
        (
            "Energy per cycle of an oscillating tangential force on rough bodies: 3D and MRD",
            "dissipation",
            "energy per cycle over mu^2 F_N d_0 [1]",
        )
    };
    let mut fig = Figure::new(
        name,
        &format!("{title} (nu = {})", figure_poisson(spec)),
        q.x_label,
        y,
    );
    if log {
        fig = fig.log_log();
    }
    let s = q.stem;
    let [m3, c3] = [format!("{s}_3d_mean"), format!("{s}_3d_ci95")].map(|c| t.index(&c));
    for (i, ((h, r), rows)) in case_rows(spec, t, grid).into_iter().enumerate() {
        let keep: Vec<&&Vec<f64>> = rows.iter().filter(|row| !log || row[m3] > ZERO).collect();
        fig = fig.with(
            Series::new(
                format!(
                    "3D, {}: mean of {} on {grid}^2 cells, 95 % interval",
                    case_label(h, r),
                    spec.realisations(r, spec.realisations_3d)
                ),
                keep.iter().map(|row| (row[4], row[m3])).collect(),
                Style::Markers,
            )
            .with_bars(
                keep.iter()
                    .map(|row| (row[4], row[m3] - row[c3], row[m3] + row[c3]))
                    .collect(),
            )
            .colored(i + 1),
        );
        let lines = if r == 0.0 { 1 } else { spec.lambda.len() };
        for j in 0..lines {
            let mm = t.index(&format!("{s}_mrd_{j}_mean"));
            let lam = if r == 0.0 {
                "the rule of Hess".to_string()
            } else {
                lambda_name(&spec.lambda[j])
            };
            fig = fig.with(
                Series::new(
                    format!("MRD, {}: {lam}", case_label(h, r)),
                    rows.iter()
                        .filter(|row| !log || row[mm] > ZERO)
                        .map(|row| (row[4], row[mm]))
                        .collect(),
                    if j == 0 { Style::Line } else { Style::Dashed },
                )
                .colored(i + 1),
            );
        }
    }
    fig
}

/// 3D over MRD per case and lambda, and 3D over the law on the 3D curve.
pub(super) fn ratio_figure(spec: &RoughSlip3d, t: &Table, q: &Quantity, grid: f64) -> Figure {
    let s = q.stem;
    let what = if s == "shift" {
        "shift"
    } else {
        "energy per cycle"
    };
    let bodies = match spec.body() {
        Body::Sphere(_) => "Rough spheres",
        Body::Punch(_) => "Rough flat punches",
    };
    // Series at one abscissa side by side: each moved right by a small step, so that
    // no interval hides another.
    let step = 0.006;
    let mut fig = Figure::new(
        &format!("{s}_ratio"),
        &format!(
            "{bodies}: the 3D {what} over MRD's (nu = {})",
            figure_poisson(spec)
        ),
        &format!("{} (series side by side, {step} apart)", q.x_label),
        "3D over MRD [1]",
    )
    .plot("MRD exact", vec![(0.0, 1.0), (1.0, 1.0)], Style::Dashed);
    let [lm, lc] = [
        format!("{s}_3d_over_law_mean"),
        format!("{s}_3d_over_law_ci95"),
    ]
    .map(|c| t.index(&c));
    // The largest ratio shown: beyond 5 the axis is logarithmic (a ratio to a nearly
    // vanishing MRD energy), and the lower bars are cut at a tenth of the mean.
    let mut spread = 0.0f64;
    let mut shown = 0usize;
    for (i, ((h, r), rows)) in case_rows(spec, t, grid).into_iter().enumerate() {
        let label = case_label(h, r);
        for j in 0..if r == 0.0 { 1 } else { spec.lambda.len() } {
            let [m, c] = [
                format!("{s}_3d_over_mrd_{j}"),
                format!("{s}_3d_over_mrd_{j}_ci95"),
            ]
            .map(|n| t.index(&n));
            let lam = if r == 0.0 {
                String::new()
            } else {
                format!(", {}", lambda_name(&spec.lambda[j]))
            };
            // Ratios to a zero are undefined (empty cells): left out.
            let defined: Vec<&&Vec<f64>> = rows.iter().filter(|row| row[m].is_finite()).collect();
            if defined.is_empty() {
                continue;
            }
            let dx = step * shown as f64;
            shown += 1;
            fig = fig.with(
                Series::new(
                    format!("3D over MRD, {label}{lam}"),
                    defined.iter().map(|row| (row[4] + dx, row[m])).collect(),
                    if j == 0 {
                        Style::Markers
                    } else {
                        Style::Crosses
                    },
                )
                .with_bars(
                    defined
                        .iter()
                        .map(|row| {
                            let lo = (row[m] - row[c]).max(0.1 * row[m]);
                            (row[4] + dx, lo, row[m] + row[c])
                        })
                        .collect(),
                )
                .colored(i + 1),
            );
            spread = spread.max(defined.iter().map(|row| row[m]).fold(0.0, f64::max));
        }
        if r > 0.0 {
            let dx = step * shown as f64;
            shown += 1;
            let law = || rows.iter().filter(|row| row[lm].is_finite());
            fig = fig.with(
                Series::new(
                    format!("3D over the law on its own normal curve, {label}"),
                    law().map(|row| (row[4] + dx, row[lm])).collect(),
                    Style::Line,
                )
                .with_bars(
                    law()
                        .map(|row| (row[4] + dx, row[lm] - row[lc], row[lm] + row[lc]))
                        .collect(),
                )
                .colored(i + 1),
            );
        }
    }
    fig.log_y = spread > 5.0;
    fig
}

/// The stick maps of the first surface on the finest grid at the figures' Poisson's
/// ratio: the smooth body and each roughness at the last Hurst exponent, with the smooth
/// body's contact circle and, for the sphere, Cattaneo-Mindlin's stick circle.
pub(super) fn stick_maps(spec: &RoughSlip3d, cases: &[Case]) -> Vec<Figure> {
    let nu = figure_poisson(spec);
    let k = spec.poisson.iter().position(|&v| v == nu).unwrap_or(0);
    let last_h = spec.hurst.last().copied().unwrap_or(0.0);
    let circle = |radius: f64| -> Vec<(f64, f64)> {
        (0..=120)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 120.0;
                (radius * t.cos(), radius * t.sin())
            })
            .collect()
    };
    let mut figs = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        if case.roughness > 0.0 && case.hurst != last_h {
            continue;
        }
        let Some(map) = case
            .runs_3d
            .last()
            .and_then(|runs| runs.first())
            .and_then(|run| run.slips[k].map.as_ref())
        else {
            continue;
        };
        let x = map.fraction;
        let mut fig = Figure::new(
            &format!("stick_map_{i}"),
            &format!(
                "Stick and slip at Q = {x} mu F_N: {}, {}, nu = {nu}",
                spec.body_name(),
                case_label(case.hurst, case.roughness)
            ),
            "x / a (a: the smooth body's contact radius) [1]",
            "y / a [1]",
        );
        fig.equal_axes = true;
        // The cells first, the reference circles over them.
        let cells = spec.cells.last().copied().unwrap_or(0);
        fig = fig
            .with(
                Series::new(
                    format!("stick cells (first surface, {cells}^2 cells)"),
                    map.stick.clone(),
                    Style::Markers,
                )
                .colored(1),
            )
            .with(Series::new("slip cells", map.slip.clone(), Style::Crosses).colored(2))
            .with(
                Series::new(
                    "smooth body's contact circle r = a",
                    circle(1.0),
                    Style::Dashed,
                )
                .colored(0),
            );
        if let Body::Sphere(_) = spec.body() {
            fig = fig.with(
                Series::new(
                    "smooth sphere's stick circle, Cattaneo-Mindlin c = a (1 - Q/(mu F_N))^(1/3)",
                    circle((1.0 - x).cbrt()),
                    Style::Line,
                )
                .colored(0),
            );
        }
        figs.push(fig);
    }
    figs
}
