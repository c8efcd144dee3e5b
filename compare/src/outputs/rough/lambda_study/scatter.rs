//! Section 9: "comparisons of the statistical scattering of contact properties depending
//! on particular realization also coincide in both cases". Per H, on the main-ladder case
//! at the scene's `scatter.bandwidth` (which gets at least `scatter.realisations`), or
//! without it the one with the most 3D realisations: the coefficient of variation CV = s / mean of the
//! stiffness k across realisations at each reduced force f, in 3D (the rough punches)
//! and in MRD (the study's 2000 lines of that H and bandwidth), with 95 % bootstrap
//! intervals; and the two distributions of k / mean k side by side (quantiles) at the
//! middle of the calibration window.
//!
//! The same for the force at fixed approach: [`super::approach`].

use super::analysis::sample;
use super::approach::{self, ForceScatter};
use super::estimate::{cv_estimate, Agreement, CvPanels, CV_COLUMNS, RESAMPLES};
use super::tasks::{cases, done, load, mrd_file, Case, Role};
use super::LambdaStudy;
use crate::error::Result;
use crate::experiment::fit::Estimate;
use crate::experiment::rough_punch::MrdEnsemble;
use crate::report::{Figure, Section, Series, Style, Table};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// One H's scatter.
#[derive(Debug, Clone)]
pub struct Scatter {
    pub case: Case,
    pub realisations: usize,
    pub lines: usize,
    /// On the study's f grid; None where a realisation lacks k (outside its curve).
    pub cv_3d: Vec<Option<Estimate>>,
    pub cv_mrd: Vec<Option<Estimate>>,
    /// Whether the 3D mean k lies in the calibration window there.
    pub in_window: Vec<bool>,
    /// The f index of the quantile comparison and its (p, k/mean 3D, k/mean MRD).
    pub quantile_at: usize,
    pub quantiles: Vec<(f64, f64, f64)>,
    /// The scatter of F at fixed approach (where the MRD side is computed).
    pub force: Option<ForceScatter>,
}

/// `v / mean(v)` sorted.
fn normalised(v: &[f64]) -> Vec<f64> {
    let m = v.iter().sum::<f64>() / v.len() as f64;
    let mut out: Vec<f64> = v.iter().map(|x| x / m).collect();
    out.sort_by(f64::total_cmp);
    out
}

/// The empirical quantile of sorted `v` at probability p (linear between order stats).
fn quantile(v: &[f64], p: f64) -> f64 {
    let x = p * (v.len() - 1) as f64;
    let (i, t) = (x.floor() as usize, x - x.floor());
    if i + 1 >= v.len() {
        return v[v.len() - 1];
    }
    v[i] + t * (v[i + 1] - v[i])
}

/// The scatter of one case, if both sides have data.
fn of_case(s: &LambdaStudy, work: &Path, case: &Case) -> Result<Option<Scatter>> {
    let n = done(work, case);
    let Some(ens) = load::<MrdEnsemble>(work, &mrd_file(case.hurst, case.band))? else {
        return Ok(None);
    };
    let data = sample(s, work, case, n)?;
    if data.k3.len() < 3 {
        return Ok(None);
    }
    let nf = s.f_grid().len();
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed ^ 0x5CA7 ^ (case.hurst.to_bits() >> 8));
    let (mut cv_3d, mut cv_mrd, mut in_window) = (Vec::new(), Vec::new(), Vec::new());
    let [lo, hi] = s.window;
    for j in 0..nf {
        let k3: Option<Vec<f64>> = data.k3.iter().map(|c| c[j]).collect();
        let k1: Vec<f64> = ens.stiffness.iter().map(|c| c[j]).collect();
        match k3 {
            Some(k3) => {
                let mean = k3.iter().sum::<f64>() / k3.len() as f64;
                in_window.push((lo..=hi).contains(&mean));
                cv_3d.push(Some(cv_estimate(&k3, &mut rng)));
                cv_mrd.push(Some(cv_estimate(&k1, &mut rng)));
            }
            None => {
                in_window.push(false);
                cv_3d.push(None);
                cv_mrd.push(None);
            }
        }
    }
    let window: Vec<usize> = (0..nf).filter(|&j| in_window[j]).collect();
    let Some(&quantile_at) = window.get(window.len() / 2) else {
        return Ok(None);
    };
    let q3 = normalised(
        &data
            .k3
            .iter()
            .filter_map(|c| c[quantile_at])
            .collect::<Vec<_>>(),
    );
    let q1 = normalised(
        &ens.stiffness
            .iter()
            .map(|c| c[quantile_at])
            .collect::<Vec<_>>(),
    );
    let quantiles = (0..q3.len())
        .map(|i| {
            let p = (i as f64 + 0.5) / q3.len() as f64;
            (p, q3[i], quantile(&q1, p))
        })
        .collect();
    let fs = s.f_grid();
    let f_in = |j: &usize| fs[*j];
    let f_window = [
        window.first().map_or(f64::NAN, f_in),
        window.last().map_or(f64::NAN, f_in),
    ];
    Ok(Some(Scatter {
        force: approach::of_case(s, work, case, &data, f_window)?,
        case: *case,
        realisations: data.k3.len(),
        lines: ens.stiffness.len(),
        cv_3d,
        cv_mrd,
        in_window,
        quantile_at,
        quantiles,
    }))
}

/// Per H, the scatter of the main-ladder case at `scatter.bandwidth`, or without it the
/// one with the most realisations (the larger bandwidth on a tie).
pub fn scatter(s: &LambdaStudy, work: &Path) -> Result<Vec<Scatter>> {
    let mut out = Vec::new();
    for &h in &s.hurst {
        let best = cases(s)
            .into_iter()
            .filter(|c| c.hurst == h && c.role == Role::Ladder && c.cells == s.cells)
            .filter(|c| c.tolerance == s.tolerance)
            .filter(|c| s.scatter.is_none_or(|sc| sc.bandwidth == c.band))
            .max_by_key(|c| (done(work, c), c.band));
        if let Some(case) = best {
            if let Some(sc) = of_case(s, work, &case)? {
                out.push(sc);
            }
        }
    }
    Ok(out)
}

/// The scatter table, its two figures and the verdict per H: the largest |CV_MRD /
/// CV_3D - 1| in the calibration window and the share of its f points where the two
/// intervals overlap.
pub fn report(sc: &[Scatter], fs: &[f64], label: &str, out: &mut Section) {
    let mut t = Table::new(
        &format!("{label}_scatter"),
        &[
            &[
                "hurst [1]",
                "bandwidth [1]",
                "realisations_3d [count]",
                "lines_mrd [count]",
                "f = F/(E* h L) [1]",
                "in_window [0/1]",
            ],
            CV_COLUMNS,
        ]
        .concat(),
    );
    t.notes.push(format!(
        "Section 9: coefficient of variation s/mean of the stiffness k across realisations at each f, 3D rough punches against MRD lines (lambda = pi; k at fixed f = F/(E* h L) does not depend on lambda); per H the main-ladder case with the most 3D realisations; 95 % bootstrap intervals ({RESAMPLES} resamples); in_window = 1 where the 3D mean k/(E* L) lies in the calibration window"
    ));
    let mut cv_panels = CvPanels::new(
        &format!("{label}_scatter"),
        |what| format!("Scatter between realisations ({what}): CV of k, 3D (95% CI) and MRD"),
        "reduced force f = F/(E* h L) [1]",
        "CV of k across realisations [1]",
        false,
    );
    let mut q_fig = Figure::new(
        &format!("{label}_scatter_quantiles"),
        "Distribution of k / mean k: 3D quantiles against MRD quantiles (mid-window f)",
        "MRD quantile of k / mean k [1]",
        "3D quantile of k / mean k [1]",
    );
    let mut verdict = serde_json::Map::new();
    let (mut qlo, mut qhi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (i, x) in sc.iter().enumerate() {
        let mut agree = Agreement::default();
        let mut pts3 = Vec::new();
        let mut pts1 = Vec::new();
        for (j, &f) in fs.iter().enumerate() {
            let (Some(a), Some(b)) = (x.cv_3d[j], x.cv_mrd[j]) else {
                continue;
            };
            let case = [x.case.hurst, x.case.band as f64, x.realisations as f64];
            let at = [x.lines as f64, f, x.in_window[j] as u8 as f64];
            t.push([&case[..], &at, &a.columns(), &b.columns()].concat());
            pts3.push((f, a));
            pts1.push((f, b.value));
            if x.in_window[j] && a.value > 0.0 {
                agree.add(&a, &b);
            }
        }
        let width = x
            .in_window
            .iter()
            .zip(&x.cv_3d)
            .filter(|p| *p.0)
            .filter_map(|p| p.1.map(|e| e.relative_half_width()))
            .fold(0.0f64, f64::max);
        verdict.insert(
            format!("{}", x.case.hurst),
            serde_json::json!({
                "bandwidth": x.case.band, "realisations_3d": x.realisations,
                "max_rel_diff_in_window": agree.worst,
                "intervals_overlap": agree.overlaps(),
                "cv_3d_max_rel_half_width": width,
            }),
        );
        cv_panels.add(i, &x.case, x.realisations, &pts3, pts1);
        for q in &x.quantiles {
            qlo = qlo.min(q.1.min(q.2));
            qhi = qhi.max(q.1.max(q.2));
        }
        q_fig = q_fig.with(
            Series::new(
                format!("H = {} (f = {:.3})", x.case.hurst, fs[x.quantile_at]),
                x.quantiles.iter().map(|q| (q.2, q.1)).collect(),
                Style::Markers,
            )
            .colored(i),
        );
    }
    if qhi > qlo {
        q_fig = q_fig.with(
            Series::new(
                "equal distributions",
                vec![(qlo, qlo), (qhi, qhi)],
                Style::Dashed,
            )
            .colored(sc.len()),
        );
    }
    out.value("scatter", serde_json::Value::Object(verdict));
    out.tables.push(t);
    out.figures.extend(cv_panels.into_figures());
    out.figures.push(q_fig);
    let forces: Vec<ForceScatter> = sc.iter().filter_map(|x| x.force.clone()).collect();
    approach::report(&forces, label, out);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cv_and_quantiles_of_known_samples() {
        let v = [1.0, 2.0, 3.0, 4.0];
        let all = [0, 1, 2, 3];
        // mean 2.5, sample variance 5/3.
        assert!((super::super::estimate::cv(&v, &all) - (5.0f64 / 3.0).sqrt() / 2.5).abs() < 1e-15);
        // A constant sample has CV 0 and a zero-width interval.
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let e = cv_estimate(&[2.0; 10], &mut rng);
        assert_eq!((e.value, e.lo, e.hi), (0.0, 0.0, 0.0));
        let q = normalised(&v);
        assert_eq!(q, vec![0.4, 0.8, 1.2, 1.6]);
        assert!((quantile(&q, 0.5) - 1.0).abs() < 1e-15);
        assert_eq!(quantile(&q, 1.0), 1.6);
    }
}
