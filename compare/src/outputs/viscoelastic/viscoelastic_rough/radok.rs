//! Radok's force: while the contact does not recede the displacement field is the
//! elastic one at the current approach, so the force is the hereditary integral of the
//! elastic force at the same approach, F(t) = Int E*(t - t') / E_inf dF_el(t') (Eq. 63
//! for one spring). Evaluated on each side's mean history with the solvers' own time
//! integration (exact for F_el piecewise linear in time), so that during indentation
//! F / F_Radok = 1 to the solver tolerance; on unloading the material lags behind the
//! punch (Ting's problem) and the ratio leaves 1.

use super::report::range;
use super::runs::{Run, Runs};
use super::{ViscoelasticRough, PHASES};
use crate::report::{Figure, Section, Series, Style, Table};

/// Radok's force of an elastic force history `fel` (at modulus E_inf, one value at the
/// end of each step of length dt, zero before the first): F_n = fel_n + sum_k (E_k /
/// E_inf) h_k, with h_k <- a_k h_k + b_k (fel_n - fel_n-1), a_k = exp(-dt / tau_k),
/// b_k = (tau_k / dt)(1 - a_k).
pub fn hereditary(fel: &[f64], dt: f64, relaxed: f64, terms: &[[f64; 2]]) -> Vec<f64> {
    let mut h = vec![0.0; terms.len()];
    let mut prev = 0.0;
    fel.iter()
        .map(|&f| {
            let mut v = f;
            for (hk, &[e, tau]) in h.iter_mut().zip(terms) {
                let x = -dt / tau;
                *hk = x.exp() * *hk - x.exp_m1() * tau / dt * (f - prev);
                v += e / relaxed * *hk;
            }
            prev = f;
            v
        })
        .collect()
}

/// Mean and 95 % half-width (1.96 s / sqrt(n)) of `v`.
fn mean_ci(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    if v.len() < 2 {
        return (m, 0.0);
    }
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, 1.96 * (var / n).sqrt())
}

/// One side's mean history: f with its half-width, the elastic f, Radok's f.
struct Side {
    force: Vec<(f64, f64)>,
    elastic: Vec<f64>,
    radok: Vec<f64>,
}

fn side(spec: &ViscoelasticRough, runs: &[Run]) -> Side {
    let steps = runs.first().map_or(0, |r| r.points.len());
    let at = |j: usize, pick: fn(&super::runs::Point) -> f64| -> Vec<f64> {
        runs.iter().map(|r| pick(&r.points[j])).collect()
    };
    let force: Vec<(f64, f64)> = (0..steps).map(|j| mean_ci(&at(j, |p| p.force))).collect();
    let elastic: Vec<f64> = (0..steps)
        .map(|j| mean_ci(&at(j, |p| p.force_elastic)).0)
        .collect();
    let m = &spec.modulus;
    let radok = hereditary(&elastic, spec.dt(), m.relaxed, &m.terms);
    Side {
        force,
        elastic,
        radok,
    }
}

/// The force table, F / F_Radok per side (figure `_radok_force`), under approach
/// control the forces in time (figure `_force`), and per phase the ranges of
/// F / F_Radok and of MRD's over 3D's force.
pub fn report(spec: &ViscoelasticRough, runs: &Runs, out: &mut Section) {
    let (lambdas, runs_3d, runs_1d) = (&runs.lambdas[..], &runs.d3[..], &runs.d1[..]);
    let label = out.label.clone();
    let phases = spec.phases();
    let s3 = side(spec, runs_3d);
    let s1: Vec<Side> = runs_1d.iter().map(|r| side(spec, r)).collect();
    let mut cols: Vec<String> = [
        "time [time]",
        "phase [0 ramp/1 hold/2 unload/3 reload]",
        "f_3d [1]",
        "f_3d_ci95 [1]",
        "f_radok_3d [1]",
        "f_elastic_3d [1]",
    ]
    .map(String::from)
    .to_vec();
    for l in lambdas {
        cols.push(format!("f_mrd lambda={l:.4} [1]"));
        cols.push(format!("f_radok_mrd lambda={l:.4} [1]"));
        cols.push(format!("f_elastic_mrd lambda={l:.4} [1]"));
    }
    let mut t = Table::new(&format!("{label}_force"), &cols);
    t.notes.push("f = F/(E_relaxed h L) of the viscoelastic contact (mean over realisations; ci95 = 1.96 s / sqrt(n) over 3D realisations); f_elastic = the elastic contact's at the same approach (modulus E_relaxed); f_radok = Int E*(t - t')/E_relaxed df_elastic(t'), Radok's force, equal to f while the contact does not recede".into());
    let ratio = |s: &Side, j: usize| (s.radok[j] > 0.0).then(|| s.force[j].0 / s.radok[j]);
    let mut dev: Vec<Vec<Vec<f64>>> = vec![vec![Vec::new(); PHASES.len()]; 1 + lambdas.len()];
    let mut over: Vec<Vec<Vec<f64>>> = vec![vec![Vec::new(); PHASES.len()]; lambdas.len()];
    let mut curves: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 1 + lambdas.len()];
    for (j, &ph) in phases.iter().enumerate() {
        let time = spec.dt() * (j + 1) as f64;
        let mut row = vec![
            time,
            ph as f64,
            s3.force[j].0,
            s3.force[j].1,
            s3.radok[j],
            s3.elastic[j],
        ];
        for (k, s) in std::iter::once(&s3).chain(&s1).enumerate() {
            if k > 0 {
                row.extend([s.force[j].0, s.radok[j], s.elastic[j]]);
                if s3.force[j].0 > 0.0 {
                    over[k - 1][ph].push(s.force[j].0 / s3.force[j].0);
                }
            }
            // NaN where Radok's force is zero or tensile: the curve breaks there.
            let r = ratio(s, j);
            if let Some(r) = r {
                dev[k][ph].push(r);
            }
            curves[k].push((time, r.unwrap_or(f64::NAN)));
        }
        t.push(row);
    }
    out.tables.push(t);
    figures(spec, lambdas, (&s3, runs_3d.len()), &s1, curves, out);
    let mut verdict = serde_json::Map::new();
    for (ph, name) in PHASES.iter().enumerate() {
        let mut v = serde_json::Map::new();
        v.insert("force_over_radok_3d".into(), range(&dev[0][ph]));
        for (li, l) in lambdas.iter().enumerate() {
            v.insert(
                format!("force_over_radok_mrd_lambda_{l:.4}"),
                range(&dev[li + 1][ph]),
            );
            if spec.by_approach() {
                v.insert(
                    format!("force_mrd_over_3d_lambda_{l:.4}"),
                    range(&over[li][ph]),
                );
            }
        }
        verdict.insert((*name).into(), serde_json::Value::Object(v));
    }
    out.value("radok_force", serde_json::Value::Object(verdict));
}

/// F / F_Radok against time; under approach control also f against time.
fn figures(
    spec: &ViscoelasticRough,
    lambdas: &[f64],
    (s3, n3): (&Side, usize),
    s1: &[Side],
    curves: Vec<Vec<(f64, f64)>>,
    out: &mut Section,
) {
    let label = out.label.clone();
    let phases = super::report::phases_title(spec);
    let t_end = spec.dt() * spec.phases().len() as f64;
    let mut fig = Figure::new(
        &format!("{label}_radok_force"),
        &format!("Force / Radok's force (none where it is <= 0); {phases}"),
        "time [time]",
        "F / Int E*(t - t') dF_elastic(t') [1]",
    );
    let mut curves = curves.into_iter();
    let c3 = curves.next().unwrap_or_default();
    fig.series
        .push(Series::new(format!("3D (mean of {n3})"), c3, Style::Crosses).colored(0));
    // The MRD ratios hardly depend on lambda: the later ones dashed over the first.
    for (li, (l, c)) in lambdas.iter().zip(curves).enumerate() {
        let style = if li == 0 { Style::Line } else { Style::Dashed };
        fig.series
            .push(Series::new(format!("MRD, lambda = {l:.3}"), c, style).colored(li + 1));
    }
    fig.series.push(
        Series::new("Radok", vec![(0.0, 1.0), (t_end, 1.0)], Style::Dashed)
            .colored(lambdas.len() + 1),
    );
    out.figures.push(fig);
    if !spec.by_approach() {
        return;
    }
    let mut force = Figure::new(
        &format!("{label}_force"),
        &format!("Prescribed approach: force; {phases}"),
        "time [time]",
        "F / (E_relaxed h L) [1]",
    );
    let time = |j: usize| spec.dt() * (j + 1) as f64;
    let pts = |s: &Side| -> Vec<(f64, f64)> {
        s.force
            .iter()
            .enumerate()
            .map(|(j, f)| (time(j), f.0))
            .collect()
    };
    let bars = s3
        .force
        .iter()
        .enumerate()
        .map(|(j, f)| (time(j), f.0 - f.1, f.0 + f.1))
        .collect();
    force.series.push(
        Series::new(format!("3D (n = {n3}, 95% CI)"), pts(s3), Style::Crosses)
            .with_bars(bars)
            .colored(0),
    );
    for (li, (l, s)) in lambdas.iter().zip(s1).enumerate() {
        force.series.push(
            Series::new(format!("MRD, lambda = {l:.3}"), pts(s), Style::Line).colored(li + 1),
        );
    }
    out.figures.push(force);
}

#[cfg(test)]
mod tests {
    use super::hereditary;

    #[test]
    fn hereditary_integral_of_a_ramp_and_hold_is_the_closed_form() {
        // fel = t / T on [0, T], then held: F(t) = (1/T) Int_0^min(t,T) E(t - s) ds with
        // E = 1 + 4 exp(-t / tau) (units of E_inf), exact for the piecewise-linear ramp.
        let (dt, tau, ramp) = (0.05, 0.7, 1.0);
        let steps = 60;
        let fel: Vec<f64> = (1..=steps)
            .map(|k| (k as f64 * dt / ramp).min(1.0))
            .collect();
        let f = hereditary(&fel, dt, 1.0, &[[4.0, tau]]);
        for (k, v) in f.iter().enumerate() {
            let t = (k + 1) as f64 * dt;
            let a = t.min(ramp);
            // Int_0^a (1 + 4 exp(-(t - s)/tau)) ds / T
            let exact = (a + 4.0 * tau * ((-(t - a) / tau).exp() - (-t / tau).exp())) / ramp;
            assert!(
                (v - exact).abs() <= 1e-13 * exact.abs().max(1.0),
                "{t}: {v} {exact}"
            );
        }
        // Constant modulus: F = fel.
        assert_eq!(hereditary(&fel, dt, 2.0, &[]), fel);
    }
}
