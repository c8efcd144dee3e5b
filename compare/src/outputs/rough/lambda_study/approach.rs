//! The scatter of the force at fixed approach (Section 9, the second contact property of
//! the scatter): per H, on the scatter's case, F/(E* h L) of every realisation at each
//! reduced approach u = (rigid indentation past the face's mean height) / h, its
//! coefficient of variation across realisations in 3D and in MRD with 95 % bootstrap
//! intervals. Each realisation is normalised by its own rms height h, as f is.
//!
//! 3D: the solves give F at depths d from the first contact with the tangent stiffness
//! k = dF/dd, so F(d) is the cubic Hermite interpolant of (d, F, k) (fourth order in the
//! spacing; the solves are 1.44x apart in d), u = d/h - (max - mean)/h. A point below a
//! realisation's first contact has F = 0; one between the first contact and its first
//! solve, or past its last, has no value, and the u point is then left out, as is one
//! where either side's mean force is 0. MRD: the lines' exact F(d)
//! (`tasks::ApproachEnsemble`).

use super::analysis::Sample;
use super::estimate::{cv_estimate, Agreement, CvPanels, CV_COLUMNS};
use super::tasks::{approach_file, load, ApproachEnsemble, Case};
use super::LambdaStudy;
use crate::error::Result;
use crate::experiment::fit::interp_loglog;
use crate::experiment::fit::Estimate;
use crate::experiment::rough_punch::BemCurve;
use crate::report::{Section, Table};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// One H's scatter of F at fixed approach.
#[derive(Debug, Clone)]
pub struct ForceScatter {
    pub case: Case,
    pub realisations: usize,
    pub lines: usize,
    /// Reduced approaches u (where both sides have a value for every realisation).
    pub approach: Vec<f64>,
    pub mean_3d: Vec<f64>,
    pub mean_mrd: Vec<f64>,
    pub cv_3d: Vec<Estimate>,
    pub cv_mrd: Vec<Estimate>,
    /// Whether the 3D mean F/(E* h L) lies within the reduced forces of the stiffness
    /// scatter's calibration window there.
    pub in_window: Vec<bool>,
}

/// A 3D curve's converged solves as (d, F, dF/dd), d ascending.
type Points = Vec<(f64, f64, f64)>;

/// The converged solves of a 3D curve as (d, F, k), d ascending.
fn solve_points(b: &BemCurve) -> Points {
    let mut out = Vec::with_capacity(b.force.len());
    let mut j = 0;
    for s in &b.solves {
        if j < b.force.len() && s.force == b.force[j] {
            out.push((s.approach, s.force, b.stiffness[j]));
            j += 1;
        }
    }
    out
}

/// F at depth `d` from the cubic Hermite interpolant of `pts` (d, F, dF/dd): 0 for
/// d <= 0, None before the first point or past the last.
pub(super) fn hermite_force(pts: &[(f64, f64, f64)], d: f64) -> Option<f64> {
    if d <= 0.0 {
        return Some(0.0);
    }
    let i = pts.windows(2).position(|w| w[0].0 <= d && d <= w[1].0)?;
    let ((x0, f0, k0), (x1, f1, k1)) = (pts[i], pts[i + 1]);
    let w = x1 - x0;
    let t = (d - x0) / w;
    let (t2, t3) = (t * t, t * t * t);
    Some(
        (2.0 * t3 - 3.0 * t2 + 1.0) * f0
            + (t3 - 2.0 * t2 + t) * w * k0
            + (-2.0 * t3 + 3.0 * t2) * f1
            + (t3 - t2) * w * k1,
    )
}

/// The scatter of F at fixed approach of `case`, whose 3D realisations are `data` (the
/// stiffness scatter's sample), if the MRD forces at fixed approach are in `work`.
/// `f_window`: the reduced forces of the stiffness scatter's calibration window.
pub fn of_case(
    s: &LambdaStudy,
    work: &Path,
    case: &Case,
    data: &Sample,
    f_window: [f64; 2],
) -> Result<Option<ForceScatter>> {
    let Some(ens) = load::<ApproachEnsemble>(work, &approach_file(case.hurst, case.band))? else {
        return Ok(None);
    };
    if data.bem.len() < 3 || ens.approach != s.approach_grid() {
        return Ok(None);
    }
    // Per realisation: its solves, rms height and (max - mean) / h.
    let curves: Vec<(Points, f64, f64)> = data
        .bem
        .iter()
        .zip(&data.summit)
        .map(|(b, &summit)| (solve_points(b), b.rms_height, summit))
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed ^ 0xF0CE ^ (case.hurst.to_bits() >> 8));
    let mut out = ForceScatter {
        case: *case,
        realisations: curves.len(),
        lines: ens.force.len(),
        approach: Vec::new(),
        mean_3d: Vec::new(),
        mean_mrd: Vec::new(),
        cv_3d: Vec::new(),
        cv_mrd: Vec::new(),
        in_window: Vec::new(),
    };
    for (j, &u) in ens.approach.iter().enumerate() {
        let f3: Option<Vec<f64>> = curves
            .iter()
            .map(|(pts, h, summit)| hermite_force(pts, (u + summit) * h).map(|f| f / h))
            .collect();
        let Some(f3) = f3 else { continue };
        let f1: Vec<f64> = ens.force.iter().map(|c| c[j]).collect();
        let m3 = f3.iter().sum::<f64>() / f3.len() as f64;
        let m1 = f1.iter().sum::<f64>() / f1.len() as f64;
        // No CV where one side has no force at all (below every first contact), nor
        // where so few realisations touch that resamples without any contact (CV
        // undefined) leave its interval unknown.
        if m3 <= 0.0 || m1 <= 0.0 {
            continue;
        }
        let (cv3, cv1) = (cv_estimate(&f3, &mut rng), cv_estimate(&f1, &mut rng));
        if [cv3, cv1]
            .iter()
            .any(|e| !(e.lo.is_finite() && e.hi.is_finite()))
        {
            continue;
        }
        out.approach.push(u);
        out.mean_3d.push(m3);
        out.mean_mrd.push(m1);
        out.in_window
            .push((f_window[0]..=f_window[1]).contains(&m3));
        out.cv_3d.push(cv3);
        out.cv_mrd.push(cv1);
    }
    Ok((!out.approach.is_empty()).then_some(out))
}

/// The CV of MRD at the 3D mean force `m3` (log-log between MRD's u points), with its
/// interval; None outside MRD's forces.
fn mrd_at_force(x: &ForceScatter, m3: f64) -> Option<Estimate> {
    let at = |pick: fn(&Estimate) -> f64| {
        let cv: Vec<f64> = x.cv_mrd.iter().map(pick).collect();
        interp_loglog(&x.mean_mrd, &cv, m3).filter(|v| v.is_finite())
    };
    Some(Estimate {
        value: at(|e| e.value)?,
        lo: at(|e| e.lo)?,
        hi: at(|e| e.hi)?,
    })
}

/// The table, its two figures (H <= 0.5 and above: CV against each side's mean force,
/// so that the two are compared at equal load) and the verdict per H: at each 3D point
/// whose mean force lies in the calibration window, MRD's CV at the same mean force;
/// the largest |CV_MRD / CV_3D - 1| and the share of points where the intervals overlap.
pub fn report(sc: &[ForceScatter], label: &str, out: &mut Section) {
    if sc.is_empty() {
        return;
    }
    let mut t = Table::new(
        &format!("{label}_scatter_force"),
        &[
            &[
                "hurst [1]",
                "bandwidth [1]",
                "realisations_3d [count]",
                "lines_mrd [count]",
                "u = approach past mean height / h [1]",
                "in_window [0/1]",
                "mean_f_3d = F/(E* h L) [1]",
                "mean_f_mrd [1]",
            ],
            CV_COLUMNS,
        ]
        .concat(),
    );
    t.notes.push(
        "Section 9: coefficient of variation s/mean of the reduced force F/(E* h L) across realisations at each reduced approach u (rigid indentation past the face's or line's mean height over its own rms height h); 3D F(u) by cubic Hermite interpolation of the solves' (d, F, dF/dd); MRD lines exact (lambda = pi; F/h at fixed u/h does not depend on lambda); at equal u the mean forces differ (columns mean_f), so the verdict compares the CVs at equal mean force; 95 % bootstrap intervals; in_window = 1 where the 3D mean force lies within the forces of the stiffness calibration window".to_string(),
    );
    let mut panels = CvPanels::new(
        &format!("{label}_scatter_force"),
        |what| format!("Scatter of F at fixed approach ({what}): CV, 3D (95% CI) and MRD"),
        "mean reduced force at that approach F/(E* h L) [1]",
        "CV of F across realisations at fixed approach [1]",
        true,
    );
    let mut verdict = serde_json::Map::new();
    for (i, x) in sc.iter().enumerate() {
        let mut agree = Agreement::default();
        let mut ratio = [f64::INFINITY, f64::NEG_INFINITY];
        for j in 0..x.approach.len() {
            let (a, b) = (x.cv_3d[j], x.cv_mrd[j]);
            let case = [x.case.hurst, x.case.band as f64, x.realisations as f64];
            let at = [x.lines as f64, x.approach[j], x.in_window[j] as u8 as f64];
            let means = [x.mean_3d[j], x.mean_mrd[j]];
            t.push([&case[..], &at, &means, &a.columns(), &b.columns()].concat());
            let Some(b) = mrd_at_force(x, x.mean_3d[j]) else {
                continue;
            };
            if x.in_window[j] && a.value > 0.0 {
                agree.add(&a, &b);
                ratio = [
                    ratio[0].min(b.value / a.value),
                    ratio[1].max(b.value / a.value),
                ];
            }
        }
        verdict.insert(
            format!("{}", x.case.hurst),
            serde_json::json!({
                "max_rel_diff_in_window_at_equal_mean_force": agree.worst,
                "cv_mrd_over_cv_3d_in_window": if agree.count > 0 { vec![ratio[0], ratio[1]] } else { vec![] },
                "intervals_overlap": agree.overlaps(),
            }),
        );
        let three: Vec<(f64, Estimate)> = x
            .mean_3d
            .iter()
            .copied()
            .zip(x.cv_3d.iter().copied())
            .collect();
        let mrd = x
            .mean_mrd
            .iter()
            .zip(&x.cv_mrd)
            .filter(|p| p.1.value > 0.0)
            .map(|(&m, e)| (m, e.value))
            .collect();
        panels.add(i, &x.case, x.realisations, &three, mrd);
    }
    out.value("scatter_force", serde_json::Value::Object(verdict));
    out.tables.push(t);
    out.figures.extend(panels.into_figures());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_force_is_exact_for_cubics_and_fourth_order_for_powers() {
        // A cubic is reproduced exactly from its values and slopes.
        let c = |d: f64| 0.5 * d * d * d - d * d + 2.0 * d;
        let dc = |d: f64| 1.5 * d * d - 2.0 * d + 2.0;
        let pts: Vec<(f64, f64, f64)> = [0.5, 0.9, 1.7, 3.0]
            .iter()
            .map(|&d| (d, c(d), dc(d)))
            .collect();
        for d in [0.5, 0.6, 1.2, 2.9, 3.0] {
            assert!(
                (hermite_force(&pts, d).unwrap() - c(d)).abs() < 1e-12,
                "{d}"
            );
        }
        assert_eq!(hermite_force(&pts, -0.1), Some(0.0));
        assert_eq!(hermite_force(&pts, 0.4), None);
        assert_eq!(hermite_force(&pts, 3.01), None);
        // F = d^1.5 on nodes 1.44x apart (the solves' spacing): error below 1e-4
        // relative, and 16x smaller when the spacing halves (fourth order).
        let err = |ratio: f64| {
            let pts: Vec<(f64, f64, f64)> = (0..12)
                .map(|i| {
                    let d = ratio.powi(i);
                    (d, d.powf(1.5), 1.5 * d.sqrt())
                })
                .collect();
            (0..200)
                .map(|i| 1.0 + i as f64 * (pts[11].0 - 1.0) / 200.0)
                .map(|d| (hermite_force(&pts, d).unwrap() / d.powf(1.5) - 1.0).abs())
                .fold(0.0f64, f64::max)
        };
        let (coarse, fine) = (err(1.44), err(1.2));
        assert!(coarse < 1e-4, "{coarse}");
        assert!(coarse / fine > 10.0, "{coarse} {fine}");
    }
}
