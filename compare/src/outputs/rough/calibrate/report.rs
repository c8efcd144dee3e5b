//! The calibration's results, tables and figures.

use super::analysis::{self, Calibration};
use super::psd::{psd_figures, psd_table};
use super::spectrum::SpectrumPart;
use super::tasks::{f_grid, Case, Lines};
use super::Calibrate;
use crate::error::Result;
use crate::experiment::fit::{calibrate_lambda_at, fit_points, window_points};
use crate::experiment::rough_punch::{BemCurve, SolveRecord, SolveTally};
use crate::report::{Figure, Section, Series, Style, Table};

/// The measured map's own 3D curve and the MRD ensemble of its whole spectrum.
pub struct MapCurves {
    pub bem: BemCurve,
    pub lines: Lines,
    pub rms_factor: f64,
}

/// The map against MRD at the calibrated lambda.
struct MapCheck {
    k3: Vec<Option<f64>>,
    mrd: Vec<Option<f64>>,
    misfit: (f64, f64),
    /// lambda fitted on the map alone (one realisation), NaN where the map's curve has
    /// fewer than 3 points in the window.
    lambda_alone: f64,
    alpha: f64,
}

fn map_check(spec: &Calibrate, cal: &Calibration, m: &MapCurves) -> MapCheck {
    let fs = f_grid();
    let k3 = analysis::reduce(&m.bem, &fs);
    let k1 = m.lines.mean();
    let mrd = analysis::mrd_at(&fs, &k1, cal.lambda.value * m.rms_factor);
    let points = window_points(&k3, spec.window[0], spec.window[1]);
    MapCheck {
        misfit: analysis::misfit(&k3, &mrd, &points),
        lambda_alone: calibrate_lambda_at(&fs, &k3, &k1, &points)
            .map_or(f64::NAN, |l| l / m.rms_factor),
        alpha: fit_points(&fs, &k3, &points).map_or(f64::NAN, |a| a.0),
        k3,
        mrd,
    }
}

pub fn report(
    spec: &Calibrate,
    case: &Case,
    cal: &Calibration,
    part: Option<&SpectrumPart>,
    map: Option<&MapCurves>,
    unit: &str,
    out: &mut Section,
) -> Result<()> {
    let l = &cal.lambda;
    let width = l.relative_half_width();
    if width > spec.target {
        out.warn(format!(
            "lambda's 95 % interval is +/- {:.1} % after {} punches (realisations.max), wider than target = {}: raise realisations.max",
            100.0 * width,
            cal.realisations,
            spec.target
        ));
    }
    for (k, v) in [
        ("lambda", l.value),
        ("lambda_lo", l.lo),
        ("lambda_hi", l.hi),
        ("realisations", cal.realisations as f64),
        ("bandwidth", case.band as f64),
        ("grid", case.grid as f64),
        ("misfit_max", cal.misfit.0),
        ("misfit_rms", cal.misfit.1),
        ("alpha_3d", cal.alpha_3d.value),
        ("alpha_3d_lo", cal.alpha_3d.lo),
        ("alpha_3d_hi", cal.alpha_3d.hi),
        ("alpha_mrd", cal.alpha_mrd),
        ("rms_factor", case.rms_factor(case.band)),
        ("lambda_lower_half", cal.halves.0),
        ("lambda_upper_half", cal.halves.1),
    ] {
        out.scalar(k, v);
    }
    out.value(
        "amplitudes",
        serde_json::json!(match spec.amplitudes {
            super::AmplitudeStatistics::Fixed => "fixed",
            super::AmplitudeStatistics::Gaussian => "gaussian",
        }),
    );
    if let Some(p) = part {
        spectrum_part(p, cal, out);
    }
    let check = map.map(|m| map_check(spec, cal, m));
    if let Some(c) = check.as_ref().filter(|c| !c.misfit.0.is_finite()) {
        let inside = c.k3.iter().flatten().count();
        out.warn(format!(
            "the measured map's own 3D curve reaches {inside} reduced forces, none of them with k/(E* L) in window = {:?}: the map is not checked against MRD (its columns stay empty)",
            spec.window
        ));
    }
    if let Some(c) = check
        .as_ref()
        .filter(|c| c.misfit.0 > 2.0 * cal.misfit.0 + 0.05)
    {
        out.warn(format!(
            "the measured map's own 3D curve departs from MRD at the calibrated lambda by up to {:.2} in ln k (the ensemble of its spectrum by {:.2}): lambda = {:.3} makes MRD reproduce surfaces of this spectrum (random phases, isotropic), not this one map, whose anisotropy, single realisation or phase order the spectrum does not carry; MRD lines of its spectrum reproduce the map's own curve best at lambda = {:.3} (map_lambda_alone, one realisation, no interval)",
            c.misfit.0,
            cal.misfit.0,
            cal.lambda.value,
            c.lambda_alone
        ));
    }
    if let (Some(c), Some(m)) = (&check, &case.map) {
        out.scalar("map_misfit_max", c.misfit.0);
        out.scalar("map_misfit_rms", c.misfit.1);
        out.scalar("map_lambda_alone", c.lambda_alone);
        out.scalar("map_alpha_3d", c.alpha);
        out.scalar("map_pixels", m.n as f64);
        out.scalar("map_anisotropy", m.anisotropy);
    }
    out.tables.push(summary_table(spec, case, cal, part));
    let curves = curves_table(spec, case.grid, cal, check.as_ref());
    out.figures
        .push(curves_figure(spec, case, cal, &curves, check.is_some()));
    out.tables.push(curves);
    let psd = psd_table(case, l.value, unit);
    out.figures.extend(psd_figures(&psd, case, l.value));
    out.tables.push(psd);
    Ok(())
}

/// The spectrum's part of the interval: its scalars, the combined interval, a note on
/// which part to reduce, and the surrogates' table.
fn spectrum_part(p: &SpectrumPart, cal: &Calibration, out: &mut Section) {
    let width = |e: &crate::experiment::fit::Estimate| e.relative_half_width();
    let calibrated = p
        .rows
        .iter()
        .filter(|r| (r.lambda / r.reference).is_finite())
        .count();
    if !(p.total.lo.is_finite() && p.total.hi.is_finite()) {
        out.warn(format!(
            "the spectrum's part of lambda's interval is undefined: {calibrated} of {} surrogate spectra could be calibrated in window (fewer than 3 points of their mean curve, or a failed fit); lambda_spectrum and lambda_total are left empty (spectrum_resamples.csv)",
            p.rows.len()
        ));
    }
    for (k, v) in [
        ("lambda_spectrum_lo", p.lambda.lo),
        ("lambda_spectrum_hi", p.lambda.hi),
        ("lambda_total_lo", p.total.lo),
        ("lambda_total_hi", p.total.hi),
        ("spectrum_resamples", p.rows.len() as f64),
        ("spectrum_punches", p.punches as f64),
        ("spectrum_bias", p.bias),
        ("spectrum_var_ln_ratio", p.variance.0),
        ("spectrum_var_punches", p.variance.1),
    ] {
        out.scalar(k, v);
    }
    let bias_corrected = p.bias_corrected();
    out.scalar("lambda_bias_corrected", bias_corrected.value);
    out.scalar("lambda_bias_corrected_lo", bias_corrected.lo);
    out.scalar("lambda_bias_corrected_hi", bias_corrected.hi);
    out.scalar("spectrum_resolved", p.resolved as u8 as f64);
    out.scalar("spectrum_upper", p.upper.exp() - 1.0);
    out.scalar("spectrum_estimate", p.estimate.exp() - 1.0);
    let (punches, spectrum) = (width(&cal.lambda), width(&p.lambda));
    if p.bias.ln_1p().abs() > 2.0 * p.bias_error {
        out.warn(format!(
            "the surrogate spectra give a lambda {:.0} % {} the map's on average (standard error {:.0} %): the PSD estimator (mean plane, Hann window, radial bins) shifts this spectrum's lowest annuli, and the map's own estimate may be shifted as much the other way; the bootstrap's bias-corrected lambda is {:.3} [{:.3}, {:.3}] (lambda_bias_corrected: lambda / (1 + spectrum_bias), the total interval widened by the correction's standard error; spectrum_resamples.csv)",
            100.0 * p.bias.abs(),
            if p.bias < 0.0 { "below" } else { "above" },
            100.0 * p.bias_error,
            bias_corrected.value,
            bias_corrected.lo,
            bias_corrected.hi
        ));
    }
    if !p.resolved && p.total.lo.is_finite() {
        out.warn(format!(
            "the spectrum's part of lambda's interval is not resolved from the punches' noise with {} surrogate spectra of {} punches each (variance of ln lambda {:.2e} over the surrogates, of which the punches explain {:.2e}; estimate +/- {:.1} %): taken at its upper bound, +/- {:.1} %, in lambda_spectrum and lambda_total; raise spectrum_uncertainty.punches to narrow it (the punches' noise falls as 1 / punches)",
            p.rows.len(),
            p.punches,
            p.variance.0,
            p.variance.1,
            100.0 * (p.estimate.exp() - 1.0),
            100.0 * (p.upper.exp() - 1.0)
        ));
    } else if spectrum > punches {
        out.warn(format!(
            "lambda's 95 % interval from the map's spectrum (+/- {:.1} %) is wider than the punches' (+/- {:.1} %): more realisations will not narrow the total [{:.3}, {:.3}]; a larger map, or several maps of the surface, would",
            100.0 * spectrum,
            100.0 * punches,
            p.total.lo,
            p.total.hi
        ));
    }
    let mut t = Table::new(
        "spectrum_resamples",
        &[
            "resample [index]",
            "lambda with the surrogate spectrum [1]",
            "lambda with the map's spectrum, same punches [1]",
            "ratio [1]",
            "split-half var ln ratio [1]",
            "mean square height, surrogate / map [1]",
            "unconverged 3D solves [count]",
        ],
    );
    t.missing_ok = true;
    t.notes.push(format!(
        "the spectrum's own uncertainty by a parametric bootstrap: each surrogate is a Gaussian random field (Rayleigh amplitudes, random phases) with the map's estimated C2D, cut to the map's size from a periodic square 1.5 times larger and read by the same estimator (plane, Hann window, radial bins); lambda is calibrated with its spectrum (punch faces and MRD lines) on the main sample's first {} punches (same phases), against lambda of those punches with the map's spectrum; var(ln ratio) over the surrogates = {:.3e}, of which the punches' sampling explains {:.3e} (the mean of each row's (ln ratio on the first half of its punches - on the second half)^2 / 4); the spectrum's 95 % interval is lambda x exp(+/- 1.96 sqrt(the difference)) where the difference exceeds its standard error, else lambda x exp(+/- 1.96 sqrt(var ln ratio)) (its upper bound); combined with the punches' in quadrature in ln lambda; mean ratio - 1: {:.3}",
        p.punches,
        p.variance.0,
        p.variance.1,
        p.bias
    ));
    for (s, r) in p.rows.iter().enumerate() {
        t.push(vec![
            s as f64,
            r.lambda,
            r.reference,
            r.lambda / r.reference,
            r.noise,
            r.mean_square,
            r.unconverged as f64,
        ]);
    }
    out.tables.push(t);
}

/// One punch's solves (`None`: the measured map's own).
pub type Solves = (Option<u64>, Vec<SolveRecord>);

/// Every 3D solve of the calibration as a table; unconverged ones fail the run visibly
/// (they are left out of the curves, so lambda rests on fewer points than asked).
/// The surrogate spectra's punches (`surrogates`) join the tally, not the table: their
/// own table (`spectrum_resamples`) counts their unconverged solves.
pub fn solves<'a>(
    spec: &Calibrate,
    solves: &[Solves],
    surrogates: impl Iterator<Item = &'a BemCurve>,
    out: &mut Section,
) {
    let mut t = Table::new(
        "solves",
        &[
            "punch [index, -1: the map]",
            "load [index]",
            "approach [L]",
            "force [E* L^2]",
            "iterations [count]",
            "residual [1]",
            "converged [0/1]",
            "stiffness_converged [0/1]",
        ],
    );
    t.notes.push(format!(
        "every 3D solve of the calibration (units of the punch diameter L, E* = 1): tolerance {:e} (criterion: bem3d::solver docs); unconverged solves (converged = 0, the residual reached) and failed stiffness solves are left out of the curves and listed in summary.json's failures",
        spec.tolerance
    ));
    let mut tally = SolveTally::default();
    for (punch, records) in solves {
        for (k, s) in records.iter().enumerate() {
            tally.add(s);
            t.push(vec![
                punch.map_or(-1.0, |r| r as f64),
                k as f64,
                s.approach,
                s.force,
                s.iterations as f64,
                s.residual,
                s.converged as u8 as f64,
                s.stiffness_converged as u8 as f64,
            ]);
        }
    }
    surrogates.for_each(|c| tally.add_curve(c));
    tally.report(spec.tolerance, out);
    out.tables.push(t);
}

fn summary_table(
    spec: &Calibrate,
    case: &Case,
    cal: &Calibration,
    part: Option<&SpectrumPart>,
) -> Table {
    let cols = [
        "bandwidth L/lambda_min [1]",
        "grid [cells]",
        "realisations [count]",
        "lambda [1]",
        "lambda_lo95 [1]",
        "lambda_hi95 [1]",
        "misfit_max |dln k| [1]",
        "misfit_rms |dln k| [1]",
        "alpha_3d [1]",
        "alpha_3d_lo95 [1]",
        "alpha_3d_hi95 [1]",
        "alpha_mrd [1]",
        "lambda_lower_half [1]",
        "lambda_upper_half [1]",
        "lambda_spectrum_lo95 [1]",
        "lambda_spectrum_hi95 [1]",
        "lambda_total_lo95 [1]",
        "lambda_total_hi95 [1]",
    ];
    let mut t = Table::new("calibration", &cols);
    // Empty without a spectrum part, or where too few surrogates calibrated.
    t.missing_ok = true;
    t.notes.push(format!(
        "lambda of Eq. (76) (C1D = lambda q C2D of the same C2D, the line not rescaled) for this surface: {} rigid circular punches of diameter L (the source's side) with faces of its spectrum up to {} x 2 pi / L, {} cells a side, against {} MRD lines; fitted over k/(E* L) in [{}, {}] of the 3D mean (f = F/(E* h L), each curve over its own rms height); amplitude statistics of the faces: {} (the lines: fixed, Eq. 72); 95 % bootstrap intervals over the punches ({} resamples); misfit: |ln k3D - ln kMRD| at the calibrated lambda over that range; alpha: slope of ln k against ln f there (Eq. 77); halves: lambda fitted on the lower / upper half of the range's forces",
        cal.realisations,
        case.band,
        case.grid,
        spec.lines,
        spec.window[0],
        spec.window[1],
        spec.amplitudes.name(),
        analysis::RESAMPLES
    ));
    t.push(vec![
        case.band as f64,
        case.grid as f64,
        cal.realisations as f64,
        cal.lambda.value,
        cal.lambda.lo,
        cal.lambda.hi,
        cal.misfit.0,
        cal.misfit.1,
        cal.alpha_3d.value,
        cal.alpha_3d.lo,
        cal.alpha_3d.hi,
        cal.alpha_mrd,
        cal.halves.0,
        cal.halves.1,
        part.map_or(f64::NAN, |p| p.lambda.lo),
        part.map_or(f64::NAN, |p| p.lambda.hi),
        part.map_or(f64::NAN, |p| p.total.lo),
        part.map_or(f64::NAN, |p| p.total.hi),
    ]);
    t.notes.push(match part {
        Some(p) => format!(
            "lambda_spectrum: the 95 % interval from the map's spectrum alone ({} surrogate spectra, each on the first {} punches: spectrum_resamples.csv); lambda_total: both intervals combined in quadrature in ln lambda",
            p.rows.len(),
            p.punches
        ),
        None => "lambda_spectrum, lambda_total: empty; the spectrum is taken as exact (a self-affine or tabulated source, or spectrum_uncertainty.resamples = 0)".into(),
    });
    t
}

fn curves_table(spec: &Calibrate, grid: usize, cal: &Calibration, map: Option<&MapCheck>) -> Table {
    let mut cols: Vec<String> = [
        "f = F/(E* h L) [1]",
        "k3D/(E* L) mean [1]",
        "k3D lo95 [1]",
        "k3D hi95 [1]",
        "kMRD/(E* L) at lambda [1]",
        "in_range [0/1]",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    if map.is_some() {
        cols.push("k3D/(E* L) of the map [1]".into());
        cols.push("kMRD/(E* L) of the map's spectrum at lambda [1]".into());
    }
    let mut t = Table::new("curves", &cols);
    // The map's own curve covers the forces its solves reached: empty cells elsewhere.
    t.missing_ok = map.is_some();
    t.notes.push(format!(
        "k(f) where the 3D mean is defined and above 3 contact cells' worth (k/(E* L) >= 3 / grid = {:.4}; below, a handful of cells set k and the curve is the grid's, not the surface's): the punches' mean with its pointwise 95 % bootstrap interval, MRD at the calibrated lambda; in_range marks the calibration range k/(E* L) in [{}, {}]; the map's columns (empty outside its range): the measured map itself as a punch, and MRD lines of its whole spectrum (to its Nyquist wavenumber) at the same lambda",
        3.0 / grid as f64,
        spec.window[0],
        spec.window[1]
    ));
    let nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    for (j, f) in f_grid().into_iter().enumerate() {
        let (Some(m), Some((lo, hi))) = (cal.mean3[j], cal.band3[j]) else {
            continue;
        };
        if m < 3.0 / grid as f64 {
            continue;
        }
        let mut row = vec![f, m, lo, hi, nan(cal.mrd[j]), cal.points[j] as u8 as f64];
        if let Some(c) = map {
            row.extend([nan(c.k3[j]), nan(c.mrd[j])]);
        }
        t.push(row);
    }
    t
}

fn curves_figure(
    spec: &Calibrate,
    case: &Case,
    cal: &Calibration,
    t: &Table,
    with_map: bool,
) -> Figure {
    let l = &cal.lambda;
    let f = t.column("f = F/(E* h L)");
    let pick = |name: &str, keep: &dyn Fn(usize) -> bool| -> Vec<(f64, f64)> {
        t.column(name)
            .into_iter()
            .enumerate()
            .filter(|&(j, v)| keep(j) && v.is_finite())
            .map(|(j, v)| (f[j], v))
            .collect()
    };
    let inr = t.column("in_range");
    let all = |_: usize| true;
    let mut fig = Figure::new(
        "curves",
        &format!(
            "k(F) of {}, 3D against MRD: lambda = {:.3} [{:.3}, {:.3}], B = {}",
            source(spec, case),
            l.value,
            l.lo,
            l.hi,
            case.band
        ),
        "reduced force F/(E* h L) [1]",
        "reduced stiffness k/(E* L) [1]",
    )
    .plot(
        format!("3D mean of {} punches", cal.realisations),
        pick("k3D/(E* L) mean", &all),
        Style::Line,
    )
    .with(Series::new("3D 95 % interval", pick("k3D lo95", &all), Style::Dashed).colored(0))
    .with(Series::new("", pick("k3D hi95", &all), Style::Dashed).colored(0))
    .plot(
        format!("MRD, {} lines, calibrated lambda", spec.lines),
        pick("kMRD/(E* L) at lambda", &all),
        Style::Line,
    )
    .plot(
        format!(
            "calibration range k/(E* L) in [{}, {}]",
            spec.window[0], spec.window[1]
        ),
        pick("k3D/(E* L) mean", &|j| inr[j] > 0.5),
        Style::Markers,
    );
    if with_map {
        fig = fig
            .plot(
                "the measured map in 3D",
                pick("k3D/(E* L) of the map", &all),
                Style::Crosses,
            )
            .plot(
                "MRD of the map's whole spectrum, same lambda",
                pick("kMRD/(E* L) of the map's spectrum at lambda", &all),
                Style::Dashed,
            );
    }
    fig.log_log()
}

/// The source in a few words, for titles.
fn source(spec: &Calibrate, case: &Case) -> String {
    let file = |p: &str| {
        std::path::Path::new(p)
            .file_stem()
            .map_or(p.to_string(), |f| f.to_string_lossy().into_owned())
    };
    match (&spec.topography, &spec.psd, &spec.self_affine, &case.map) {
        (Some(t), _, _, Some(m)) => format!("{} ({}^2)", file(t), m.n),
        (_, Some(p), _, _) => file(p),
        (_, _, Some(s), _) if s.rolloff > 1.0 => {
            format!("H = {}, q_r / q0 = {}", s.hurst, s.rolloff)
        }
        (_, _, Some(s), _) => format!("H = {}", s.hurst),
        _ => "the source".into(),
    }
}
