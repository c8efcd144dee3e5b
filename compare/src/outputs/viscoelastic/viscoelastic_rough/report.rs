//! The table, two figures and the per-phase verdict of `viscoelastic_rough`.

use super::runs::{Point, Run, Runs};
use super::{ViscoelasticRough, PHASES};
use crate::report::{Figure, Section, Series, Style, Table};

/// Ensemble means at each step: (approach, its 95 % half-width, area, elastic area).
fn means(runs: &[Run], j: usize) -> (f64, f64, f64, f64) {
    let n = runs.len() as f64;
    let pick = |f: fn(&Point) -> f64| runs.iter().map(|r| f(&r.points[j])).collect::<Vec<_>>();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / n;
    let d = pick(|p| p.approach);
    let m = mean(&d);
    let half = if runs.len() > 1 {
        let var = d.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0);
        1.96 * (var / n).sqrt()
    } else {
        0.0
    };
    (
        m,
        half,
        mean(&pick(|p| p.area)),
        mean(&pick(|p| p.area_elastic)),
    )
}

/// [min, max] of `v`, or an empty list.
pub(super) fn range(v: &[f64]) -> serde_json::Value {
    if v.is_empty() {
        return serde_json::json!([]);
    }
    let lo = v.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    serde_json::json!([lo, hi])
}

/// The phases' time spans, for figure titles.
pub(super) fn phases_title(spec: &ViscoelasticRough) -> String {
    let (r, h) = (spec.ramp, spec.hold_steps() as f64 * spec.dt());
    format!(
        "ramp 0-{r}, hold -{}, unload -{}, reload -{}",
        r + h,
        2.0 * r + h,
        3.0 * r + h
    )
}

/// The history table's columns and notes (rows added by [`report`]).
fn history_table(
    spec: &ViscoelasticRough,
    lambdas: &[f64],
    n3: usize,
    runs_1d: &[Vec<Run>],
    label: &str,
) -> Table {
    let mut cols: Vec<String> = [
        "time [time]",
        "phase [0 ramp/1 hold/2 unload/3 reload]",
        "f = F/(E_relaxed h L) [1]",
        "approach_3d/h [1]",
        "approach_3d_ci95/h [1]",
        "area_3d [1]",
        "area_elastic_3d [1]",
    ]
    .map(String::from)
    .to_vec();
    if spec.by_approach() {
        cols[2] = "prescribed approach d/h [1]".into();
    }
    for l in lambdas {
        cols.push(format!("approach_mrd/h lambda={l:.4} [1]"));
        cols.push(format!("area_mrd lambda={l:.4} [1]"));
        cols.push(format!("area_elastic_mrd lambda={l:.4} [1]"));
    }
    let mut t = Table::new(&format!("{label}_history"), &cols);
    t.notes.push(format!(
        "Section 8: rough punch (H = {}, bandwidth {}, {}^2 cells, {} realisations) on a generalised-Maxwell half-space against MRD lines on viscoelastic springs (Eq. 63; {} lines per lambda); {} history ramp/hold/unload to {}/reload; approach from the first contact of the undeformed face over the surface's rms height h; area = contact fraction of the face (3D cells; MRD springs); area_elastic = the elastic contact fraction at the same approach (Radok: equal while the contact does not recede); ci95 = 1.96 s / sqrt(n) over 3D realisations",
        spec.hurst,
        spec.bandwidth,
        spec.grid(),
        n3,
        runs_1d.first().map_or(0, Vec::len),
        if spec.by_approach() { "approach" } else { "force" },
        spec.unload
    ));
    t
}

pub fn report(spec: &ViscoelasticRough, runs: &Runs, out: &mut Section) {
    let (lambdas, runs_3d, runs_1d) = (&runs.lambdas[..], &runs.d3[..], &runs.d1[..]);
    let label = out.label.clone();
    let history = spec.history();
    let phases = spec.phases();
    let mut t = history_table(spec, lambdas, runs_3d.len(), runs_1d, &label);
    let mut time = 0.0f64;
    let phases_title = phases_title(spec);
    let mut approach = Figure::new(
        &format!("{label}_approach"),
        &format!(
            "Viscoelastic rough punch, approach{}; {phases_title}",
            if spec.by_approach() {
                " (prescribed)"
            } else {
                ""
            }
        ),
        "time [time]",
        "approach / rms height [1]",
    );
    let mut radok = Figure::new(
        &format!("{label}_radok"),
        &format!("Area / elastic area at equal approach; {phases_title}"),
        "time [time]",
        "area / elastic area at the same approach [1]",
    );
    let (mut a3, mut r3) = (Vec::new(), Vec::new());
    let mut bars = Vec::new();
    let mut a1: Vec<Vec<(f64, f64)>> = vec![Vec::new(); lambdas.len()];
    let mut r1: Vec<Vec<(f64, f64)>> = vec![Vec::new(); lambdas.len()];
    // Per phase: 3D area ratios; per lambda MRD area ratios and approach ratios.
    let mut dev3: Vec<Vec<f64>> = vec![Vec::new(); PHASES.len()];
    let mut dev1: Vec<Vec<Vec<f64>>> = vec![vec![Vec::new(); PHASES.len()]; lambdas.len()];
    let mut ratio: Vec<Vec<Vec<f64>>> = vec![vec![Vec::new(); PHASES.len()]; lambdas.len()];
    for (j, &(dt, f)) in history.iter().enumerate() {
        // Equal steps: the time of step j without accumulated rounding.
        time = dt * (j + 1) as f64;
        let ph = phases[j];
        let (d3, ci3, ar3, el3) = means(runs_3d, j);
        let mut row = vec![time, ph as f64, f, d3, ci3, ar3, el3];
        // At most about 60 3D markers, so that the MRD lines stay visible.
        let shown = j % history.len().div_ceil(60) == 0;
        if shown {
            a3.push((time, d3));
            bars.push((time, d3 - ci3, d3 + ci3));
        }
        if el3 > 0.0 {
            if shown {
                r3.push((time, ar3 / el3));
            }
            dev3[ph].push(ar3 / el3);
        }
        for (li, runs) in runs_1d.iter().enumerate() {
            let (d1, _, ar1, el1) = means(runs, j);
            row.extend([d1, ar1, el1]);
            a1[li].push((time, d1));
            if el1 > 0.0 {
                r1[li].push((time, ar1 / el1));
                dev1[li][ph].push(ar1 / el1);
            }
            if d3 > 0.0 {
                ratio[li][ph].push(d1 / d3);
            }
        }
        t.push(row);
    }
    approach.series.push(
        Series::new(
            match history.len().div_ceil(60) {
                1 => format!("3D (n = {}, 95% CI)", runs_3d.len()),
                k => format!("3D (n = {}, 95% CI; one step in {k})", runs_3d.len()),
            },
            a3,
            Style::Crosses,
        )
        .with_bars(bars)
        .colored(0),
    );
    radok
        .series
        .push(Series::new("3D", r3, Style::Crosses).colored(0));
    for (li, &l) in lambdas.iter().enumerate() {
        let name = format!("MRD, lambda = {l:.3}");
        // Later lambdas dashed, so that a curve lying on the first stays visible.
        let style = if li == 0 { Style::Line } else { Style::Dashed };
        approach
            .series
            .push(Series::new(name.clone(), a1[li].clone(), style).colored(li + 1));
        radok
            .series
            .push(Series::new(name, r1[li].clone(), style).colored(li + 1));
    }
    let t_end = time;
    radok.series.push(
        Series::new("Radok", vec![(0.0, 1.0), (t_end, 1.0)], Style::Dashed)
            .colored(lambdas.len() + 1),
    );
    let mut verdict = serde_json::Map::new();
    for (ph, name) in PHASES.iter().enumerate() {
        let mut v = serde_json::Map::new();
        v.insert("area_over_elastic_3d".into(), range(&dev3[ph]));
        for (li, l) in lambdas.iter().enumerate() {
            v.insert(
                format!("area_over_elastic_mrd_lambda_{l:.4}"),
                range(&dev1[li][ph]),
            );
            v.insert(
                format!("approach_mrd_over_3d_lambda_{l:.4}"),
                range(&ratio[li][ph]),
            );
        }
        verdict.insert((*name).into(), serde_json::Value::Object(v));
    }
    out.value("phases", serde_json::Value::Object(verdict));
    out.value(
        "iterations_3d",
        serde_json::json!(runs_3d.iter().map(|r| r.iterations).sum::<usize>()),
    );
    out.tables.push(t);
    out.figures.push(approach);
    out.figures.push(radok);
}
