//! Ensemble curves of both sides, the comparison at equal approach (force) and equal
//! force (stiffness, radius), Hertz for the smooth sphere, tables and figures.

use super::runs::{Run, State};
use super::{RoughSphere, AGREEMENT};
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::reference::hertz;
use mrd::rough_contact::Stat;
use serde_json::{json, Map, Value};

/// Mean and 95 % half-width of each quantity at one force.
#[derive(Debug, Clone, Copy)]
struct Level {
    approach: Stat,
    stiffness: Stat,
    radius: Stat,
    outermost: f64,
    count: usize,
}

fn levels(runs: &[Run], nf: usize) -> Vec<Option<Level>> {
    (0..nf)
        .map(|k| {
            let s: Vec<State> = runs.iter().filter_map(|r| r.states[k]).collect();
            if s.is_empty() {
                return None;
            }
            let of = |g: fn(&State) -> f64| Stat::of(&s.iter().map(g).collect::<Vec<_>>());
            Some(Level {
                approach: of(|s| s.approach),
                stiffness: of(|s| s.stiffness),
                radius: of(|s| s.radius),
                outermost: of(|s| s.outermost).mean,
                count: s.len(),
            })
        })
        .collect()
}

/// F of the curve (d_k, F_k) at approach `d`, linear in d and ln F, extrapolated by
/// at most one segment's width beyond either end; None farther out.
fn force_at(curve: &[(f64, f64)], d: f64) -> Option<f64> {
    let n = curve.len();
    if n < 2 {
        return None;
    }
    let k = curve
        .iter()
        .position(|p| p.0 >= d)
        .unwrap_or(n)
        .clamp(1, n - 1);
    let ((d0, f0), (d1, f1)) = (curve[k - 1], curve[k]);
    let t = (d - d0) / (d1 - d0);
    ((-1.0..=2.0).contains(&t)).then(|| (f0.ln() + t * (f1.ln() - f0.ln())).exp())
}

fn columns(lambdas: &[f64]) -> Vec<String> {
    let mut c: Vec<String> = [
        "alpha [1]",
        "rms_height [length]",
        "force [force]",
        "d_hertz [length]",
        "k_hertz [force/length]",
        "a_hertz [length]",
        "d_3d [length]",
        "d_3d_ci95 [length]",
        "k_3d [force/length]",
        "k_3d_ci95 [force/length]",
        "a_3d [length]",
        "a_3d_ci95 [length]",
        "outermost_3d [length]",
        "realisations_3d [count]",
    ]
    .map(String::from)
    .to_vec();
    for (j, _) in lambdas.iter().enumerate() {
        for (name, unit) in [
            ("lambda", "1"),
            ("d_mrd", "length"),
            ("k_mrd", "force/length"),
            ("a_mrd", "length"),
            ("outermost_mrd", "length"),
            ("d_diff_over_d_hertz", "1"),
            ("force_rel_diff_at_d", "1"),
            ("k_rel_diff", "1"),
            ("a_rel_diff", "1"),
        ] {
            c.push(format!("{name}_{j} [{unit}]"));
        }
    }
    c
}

/// The comparison of one lambda's MRD levels with 3D at force index k: relative
/// differences of F at the 3D approach (NaN where MRD's curve does not reach that
/// approach), of k and of a at equal force.
fn diffs(l3: &Level, mrd: &[Option<Level>], fs: &[f64], k: usize) -> [f64; 3] {
    let Some(m) = mrd[k] else {
        return [f64::NAN; 3];
    };
    let curve: Vec<(f64, f64)> = (0..fs.len())
        .filter_map(|j| mrd[j].map(|l| (l.approach.mean, fs[j])))
        .collect();
    [
        force_at(&curve, l3.approach.mean).map_or(f64::NAN, |f| f / fs[k] - 1.0),
        m.stiffness.mean / l3.stiffness.mean - 1.0,
        m.radius.mean / l3.radius.mean - 1.0,
    ]
}

pub fn report(
    spec: &RoughSphere,
    lambdas: &[f64],
    all_3d: &[Vec<Run>],
    all_1d: &[Vec<Vec<Run>>],
    out: &mut Section,
) {
    let fs = spec.forces();
    let (nf, e) = (fs.len(), 1.0);
    let mut t = Table::new("rough_sphere", &columns(lambdas));
    t.missing_ok = true; // F at the 3D approach where MRD's F(d) does not reach it
    t.notes.push(format!(
        "rough sphere on the free half-space: R = {r}, E* = 1, a_H = {ah:e} (Hertz radius at the largest force), map and MRD row {side} a_H wide, {n}^2 cells, {b} roughness modes across, H = {hu}; {r3} surfaces and {r1} MRD lines per alpha (1 for alpha = 0), MRD springs {p} per cell, lambda_j = {lambdas:?}; d = approach of the mean sphere from the smooth apex; a = sqrt(5/2 <r^2>_p) (3D), sqrt(5 <x^2>_q) (MRD); rel diffs: F_MRD at the 3D mean approach over F, and k, a at equal F; ci95 = 1.96 s/sqrt(n)",
        r = spec.radius,
        ah = spec.a_hertz(),
        side = spec.side,
        n = spec.grid,
        b = spec.bandwidth,
        hu = spec.hurst,
        r3 = spec.realisations_3d,
        r1 = spec.realisations_1d,
        p = spec.points_1d_factor,
    ));
    let mut verdict = Map::new();
    let mut figs = figures(spec);
    for (ai, (&alpha, (r3, r1))) in spec.alpha.iter().zip(all_3d.iter().zip(all_1d)).enumerate() {
        let failed: usize = r3.iter().map(|r| r.unconverged).sum();
        if failed > 0 {
            out.failures.push(format!(
                "alpha = {alpha}: {failed} 3D solves or stiffnesses did not converge (left out)"
            ));
        }
        let edges = r3
            .iter()
            .chain(r1.iter().flatten())
            .flat_map(|r| r.states.iter().flatten())
            .filter(|s| s.edge)
            .count();
        if edges > 0 {
            out.warn(format!(
                "alpha = {alpha}: at {edges} states a contact lies beyond 0.9 of the half-side: the map bounds the contact; widen `side`"
            ));
        }
        let l3 = levels(r3, nf);
        let l1: Vec<Vec<Option<Level>>> = r1.iter().map(|runs| levels(runs, nf)).collect();
        let mut worst = vec![[0.0f64; 3]; lambdas.len()];
        // Forces where MRD's F(d) does not reach the 3D approach (not comparable).
        let mut uncompared = vec![0usize; lambdas.len()];
        let mut hertz_dev = [0.0f64; 6];
        for (k, &force) in fs.iter().enumerate() {
            let Some(a) = l3[k] else { continue };
            let d_h = hertz::depth(e, spec.radius, force);
            let (a_h, k_h) = (
                hertz::radius(spec.radius, d_h),
                2.0 * e * hertz::radius(spec.radius, d_h),
            );
            let mut row = vec![
                alpha,
                spec.rms_height(alpha),
                force,
                d_h,
                k_h,
                a_h,
                a.approach.mean,
                a.approach.ci95,
                a.stiffness.mean,
                a.stiffness.ci95,
                a.radius.mean,
                a.radius.ci95,
                a.outermost,
                a.count as f64,
            ];
            for (j, &lam) in lambdas.iter().enumerate() {
                let m = l1[j][k].expect("springs always solve");
                let d = diffs(&a, &l1[j], &fs, k);
                uncompared[j] += d[0].is_nan() as usize;
                for (w, v) in worst[j].iter_mut().zip(d) {
                    *w = if v.is_nan() { *w } else { w.max(v.abs()) };
                }
                let dd = (m.approach.mean - a.approach.mean) / spec.hertz_depth;
                row.extend([
                    lam,
                    m.approach.mean,
                    m.stiffness.mean,
                    m.radius.mean,
                    m.outermost,
                    dd,
                ]);
                row.extend(d); // NaN (an empty cell) where F(d) is not comparable
                if alpha == 0.0 && j == 0 {
                    let rel = |x: f64, y: f64| (x / y - 1.0).abs();
                    let devs = [
                        rel(a.approach.mean, d_h),
                        rel(a.stiffness.mean, k_h),
                        rel(a.radius.mean, a_h),
                        rel(m.approach.mean, d_h),
                        rel(m.stiffness.mean, k_h),
                        rel(m.radius.mean, a_h),
                    ];
                    for (h, v) in hertz_dev.iter_mut().zip(devs) {
                        *h = h.max(v);
                    }
                }
            }
            t.push(row);
        }
        let mut v = Map::new();
        v.insert("rms_height".into(), json!(spec.rms_height(alpha)));
        for (j, w) in worst.iter().enumerate() {
            v.insert(
                format!("lambda_{j}"),
                json!({"lambda": lambdas[j], "force_at_d_max_rel_diff": w[0],
                       "forces_where_f_of_d_is_not_comparable": uncompared[j],
                       "stiffness_max_rel_diff": w[1], "radius_max_rel_diff": w[2],
                       "within_5_percent": uncompared[j] == 0 && w.iter().all(|x| *x <= AGREEMENT)}),
            );
        }
        if alpha == 0.0 {
            for (name, dev) in ["3d_d", "3d_k", "3d_a", "mrd_d", "mrd_k", "mrd_a"]
                .iter()
                .zip(hertz_dev)
            {
                out.scalar(format!("smooth_{name}_max_rel_dev_vs_hertz"), dev);
            }
        }
        verdict.insert(format!("{alpha}"), Value::Object(v));
        add_curves(spec, &mut figs, (ai, alpha), &fs, (&l3, &l1), lambdas);
    }
    out.value("per_alpha", Value::Object(verdict));
    out.tables.push(t);
    out.figures.extend(figs);
}

fn figures(spec: &RoughSphere) -> [Figure; 3] {
    let h = format!("H = {}, {}^2 cells", spec.hurst, spec.grid);
    let mut fd = Figure::new(
        "rough_sphere_force",
        &format!("Rough sphere: force against approach ({h}), 3D (95% CI) and MRD"),
        "approach of the mean sphere d / d_H [1]",
        "force F / F_H [1]",
    );
    fd.log_y = true;
    let mut k = Figure::new(
        "rough_sphere_stiffness",
        &format!("Rough sphere: stiffness over Hertz's at equal force ({h})"),
        "force F / F_H [1]",
        "k / k_Hertz(F) [1]",
    );
    k.log_x = true;
    let mut a = Figure::new(
        "rough_sphere_radius",
        &format!("Rough sphere: apparent contact radius over Hertz's ({h})"),
        "force F / F_H [1]",
        "a / a_Hertz(F) [1]",
    );
    a = a.log_log();
    [fd, k, a]
}

/// What figure `which` plots of a level at force f: (x, y, half-width of y).
fn point(spec: &RoughSphere, which: usize, v: &Level, f: f64, f_h: f64) -> (f64, f64, f64) {
    let d = hertz::depth(1.0, spec.radius, f);
    let a_h = hertz::radius(spec.radius, d);
    let k_h = 2.0 * a_h; // k = 2 E* a, E* = 1
    match which {
        0 => (v.approach.mean / spec.hertz_depth, f / f_h, 0.0),
        1 => (f / f_h, v.stiffness.mean / k_h, v.stiffness.ci95 / k_h),
        _ => (f / f_h, v.radius.mean / a_h, v.radius.ci95 / a_h),
    }
}

/// Adds one alpha's curves (3D with bars, MRD per lambda) to the three figures.
fn add_curves(
    spec: &RoughSphere,
    figs: &mut [Figure; 3],
    (color, alpha): (usize, f64),
    fs: &[f64],
    (l3, l1): (&[Option<Level>], &[Vec<Option<Level>>]),
    lambdas: &[f64],
) {
    let f_h = fs[fs.len() - 1];
    let pick = |l: &[Option<Level>], which: usize| {
        (0..fs.len())
            .filter_map(|k| l[k].map(|v| point(spec, which, &v, fs[k], f_h)))
            .collect::<Vec<_>>()
    };
    for (which, fig) in figs.iter_mut().enumerate() {
        let p3 = pick(l3, which);
        fig.series.push(
            Series::new(
                format!("3D, alpha = {alpha}"),
                p3.iter().map(|p| (p.0, p.1)).collect(),
                Style::Crosses,
            )
            .with_bars(p3.iter().map(|p| (p.0, p.1 - p.2, p.1 + p.2)).collect())
            .colored(color),
        );
        for (j, lam) in lambdas.iter().enumerate() {
            let p1 = pick(&l1[j], which);
            fig.series.push(
                Series::new(
                    format!("MRD lambda = {lam:.2}, alpha = {alpha}"),
                    p1.iter().map(|p| (p.0, p.1)).collect(),
                    if j == 0 { Style::Line } else { Style::Dashed },
                )
                .colored(color),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::force_at;

    #[test]
    fn force_at_interpolates_in_ln_f_and_extrapolates_one_segment() {
        // F = exp(d) is linear in ln F: exact inside and one segment beyond each end.
        let c: Vec<(f64, f64)> = (0..4).map(|k| (k as f64, (k as f64).exp())).collect();
        for d in [-1.0, 0.0, 0.3, 1.5, 3.0, 4.0] {
            let f = force_at(&c, d).unwrap();
            assert!((f.ln() - d).abs() < 1e-12, "{d}: {f}");
        }
        assert_eq!(force_at(&c, -1.01), None);
        assert_eq!(force_at(&c, 4.01), None);
        assert_eq!(force_at(&c[..1], 0.0), None);
    }
}
