//! From the checkpoints to per-case results: ensemble curves on the common f grid,
//! lambda calibrated over the whole window with its bootstrap interval and residual
//! misfit, alpha of both sides, local exponents d ln k / d ln f with bands, and paired
//! ratios between cases (bandwidth, resolution, tolerance) over shared realisations.
//! Every bootstrap draws from a generator seeded by the study's seed and the case, so
//! results are reproducible bit for bit whatever order the checkpoints were written in.

use super::tasks::{
    cases, control_file, done, load, mrd_file, Case, ControlEnsemble, Role, StudyCurve,
};
use super::LambdaStudy;
use crate::error::Result;
use crate::experiment::fit::Estimate;
use crate::experiment::fit::{
    calibrate_lambda_at, fit_points, fit_window, interp_loglog, mean_curve, resample, window_points,
};
use crate::experiment::rough_punch::{BemCurve, MrdEnsemble};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// Bootstrap resamples per interval.
const RESAMPLES: usize = 200;

/// Results of one case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    pub case: Case,
    pub realisations: usize,
    pub lambda: Estimate,
    pub alpha_3d: Estimate,
    pub alpha_mrd: Estimate,
    /// max and rms |ln k3 - ln k1(lambda)| over the calibration range.
    pub misfit_max: f64,
    pub misfit_rms: f64,
    /// The calibration range in f (where the 3D mean lies in the window).
    pub f_range: (f64, f64),
    /// lambda calibrated on the lower and on the upper half of that range's points: how
    /// much the calibration depends on the forces it is fitted over.
    pub lambda_halves: (f64, f64),
    /// alpha_3D and alpha_MRD fitted on the same two halves (3D lower, 3D upper, MRD
    /// lower, MRD upper): the window-dependence of Eq. (77)'s exponent.
    pub alpha_halves: [f64; 4],
    pub mean_3d: Vec<Option<f64>>,
    pub mean_mrd: Vec<Option<f64>>,
    /// Local exponent of the 3D mean with its band, of the MRD mean.
    pub slope_3d: Vec<Option<Estimate>>,
    pub slope_mrd: Vec<Option<f64>>,
    pub target: f64,
    pub unconverged: usize,
    pub seconds_3d: f64,
}

/// A paired ratio lambda(case) / lambda(reference) over shared realisations.
#[derive(Debug, Clone)]
pub struct Pair {
    pub case: Case,
    pub reference: Case,
    pub ratio: Estimate,
    pub realisations: usize,
}

#[derive(Debug, Clone, Default)]
pub struct Results {
    pub f: Vec<f64>,
    pub cases: Vec<CaseResult>,
    pub pairs: Vec<Pair>,
    pub seconds_3d: f64,
    pub seconds_mrd: f64,
}

type Curves = Vec<Vec<Option<f64>>>;

/// The solved realisations of a case on the f grid, with their faces' control
/// statistics, and the expectations of those statistics (from the case's control
/// ensemble) when it has been computed.
pub(super) struct Sample {
    pub(super) k3: Curves,
    pub(super) bem: Vec<BemCurve>,
    pub(super) summit: Vec<f64>,
    winkler: Curves,
    controls: Option<Controls>,
}

/// The control ensemble's statistics (one entry per batch of surfaces).
struct Controls {
    pub(super) summit: Vec<f64>,
    winkler: Curves,
}

/// The first `n` realisations of `case` (F / h of each realisation on the f grid).
pub(super) fn sample(s: &LambdaStudy, work: &Path, case: &Case, n: u64) -> Result<Sample> {
    let fs = s.f_grid();
    let mut out = Sample {
        k3: Vec::new(),
        bem: Vec::new(),
        summit: Vec::new(),
        winkler: Vec::new(),
        controls: load::<ControlEnsemble>(work, &control_file(case, s.control_count(case.grid())))?
            .map(|c| Controls {
                summit: c.batches.iter().map(|f| f.summit).collect(),
                winkler: c.batches.into_iter().map(|f| f.winkler).collect(),
            }),
    };
    for r in 0..n {
        if let Some(c) = load::<StudyCurve>(work, &case_file(case, r))? {
            let f: Vec<f64> = c.bem.force.iter().map(|&x| x / c.bem.rms_height).collect();
            out.k3.push(
                fs.iter()
                    .map(|&x| interp_loglog(&f, &c.bem.stiffness, x))
                    .collect(),
            );
            out.summit.push(c.face.summit);
            out.winkler.push(c.face.winkler);
            out.bem.push(c.bem);
        }
    }
    Ok(out)
}

impl Sample {
    fn len(&self) -> usize {
        self.k3.len()
    }

    /// All control-batch indices (empty without the ensemble).
    fn all_controls(&self) -> Vec<usize> {
        (0..self.controls.as_ref().map_or(0, |c| c.summit.len())).collect()
    }

    /// The ensemble mean curve over realisations `idx` (a point where every one has a
    /// value), with control variates when the controls are known: at each f the
    /// regression estimate mean(k) - b . (mean(x) - E[x]), x = (face summit, Winkler
    /// k(f)), b by least squares over `idx`, E[x] the mean of the control ensemble's
    /// batch means `ctl` (resampled in bootstraps).
    fn mean(&self, idx: &[usize], ctl: &[usize]) -> Vec<Option<f64>> {
        let plain = mean_curve(&self.k3, idx, self.k3.first().map_or(0, Vec::len));
        let Some(c) = &self.controls else {
            return plain;
        };
        if idx.len() < 6 || ctl.is_empty() {
            return plain;
        }
        let mu_s = ctl.iter().map(|&i| c.summit[i]).sum::<f64>() / ctl.len() as f64;
        plain
            .iter()
            .enumerate()
            .map(|(j, m)| {
                let m = (*m)?;
                let mu_w: Option<f64> = ctl
                    .iter()
                    .map(|&i| c.winkler[i][j])
                    .sum::<Option<f64>>()
                    .map(|v| v / ctl.len() as f64);
                let xs: Vec<(f64, f64, Option<f64>)> = idx
                    .iter()
                    .map(|&i| {
                        (
                            self.k3[i][j].unwrap_or(m),
                            self.summit[i],
                            self.winkler[i][j],
                        )
                    })
                    .collect();
                let cv = regression_estimate(&xs, mu_s, mu_w);
                Some(cv.filter(|v| v.is_finite() && *v > 0.0).unwrap_or(m))
            })
            .collect()
    }
}

/// mean(y) - b . (mean(x) - mu) for y on x = (x1, x2) (x2 only where every point and
/// its expectation have it), b by least squares; None when the design is singular.
fn regression_estimate(pts: &[(f64, f64, Option<f64>)], mu1: f64, mu2: Option<f64>) -> Option<f64> {
    let n = pts.len() as f64;
    let my = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let m1 = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let x2: Option<Vec<f64>> = pts.iter().map(|p| p.2).collect();
    match (x2, mu2) {
        (Some(x2), Some(mu2)) => {
            let m2 = x2.iter().sum::<f64>() / n;
            let (mut s11, mut s12, mut s22, mut s1y, mut s2y) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for (p, &b) in pts.iter().zip(&x2) {
                let (dy, d1, d2) = (p.0 - my, p.1 - m1, b - m2);
                s11 += d1 * d1;
                s12 += d1 * d2;
                s22 += d2 * d2;
                s1y += d1 * dy;
                s2y += d2 * dy;
            }
            let det = s11 * s22 - s12 * s12;
            if det.partial_cmp(&(1e-12 * s11 * s22)) != Some(std::cmp::Ordering::Greater) {
                return None;
            }
            let b1 = (s22 * s1y - s12 * s2y) / det;
            let b2 = (s11 * s2y - s12 * s1y) / det;
            Some(my - b1 * (m1 - mu1) - b2 * (m2 - mu2))
        }
        _ => {
            let (mut s11, mut s1y) = (0.0, 0.0);
            for p in pts {
                s11 += (p.1 - m1).powi(2);
                s1y += (p.1 - m1) * (p.0 - my);
            }
            (s11 > 0.0).then(|| my - s1y / s11 * (m1 - mu1))
        }
    }
}

fn case_file(case: &Case, r: u64) -> String {
    super::tasks::Task::Bem { case: *case, r }.file_name()
}

/// The MRD ensemble's mean curve for the case's H and bandwidth, if computed.
fn mean_1d(s: &LambdaStudy, work: &Path, case: &Case) -> Result<Option<(Vec<Option<f64>>, f64)>> {
    let Some(ens) = load::<MrdEnsemble>(work, &mrd_file(case.hurst, case.band))? else {
        return Ok(None);
    };
    let k1: Curves = ens
        .stiffness
        .iter()
        .map(|v| v.iter().map(|&x| Some(x)).collect())
        .collect();
    let all: Vec<usize> = (0..k1.len()).collect();
    Ok(Some((mean_curve(&k1, &all, s.f_grid().len()), ens.seconds)))
}

/// A generator for the bootstraps of one case (or pair) at `n` realisations.
fn rng_for(s: &LambdaStudy, case: &Case, n: u64, salt: u64) -> ChaCha8Rng {
    let text = format!("{case:?} {n} {salt}");
    let mut h: u64 = s.seed ^ 0x1A3B_DA57;
    for b in text.bytes() {
        h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
    }
    ChaCha8Rng::seed_from_u64(h)
}

/// lambda of the first `n` realisations of `case` with its bootstrap interval (the
/// adaptive plan's test).
pub fn case_lambda(s: &LambdaStudy, work: &Path, case: &Case, n: u64) -> Result<Estimate> {
    let Some((m1, _)) = mean_1d(s, work, case)? else {
        return Ok(Estimate::NONE);
    };
    let data = sample(s, work, case, n)?;
    Ok(lambda_of(s, &data, &m1, &mut rng_for(s, case, n, 0)))
}

/// One bootstrap draw: resampled realisations and resampled controls.
fn draw(rng: &mut ChaCha8Rng, data: &Sample) -> (Vec<usize>, Vec<usize>) {
    let idx = resample(rng, data.len());
    let ctl = resample(rng, data.all_controls().len());
    (idx, ctl)
}

fn lambda_of(s: &LambdaStudy, data: &Sample, m1: &[Option<f64>], rng: &mut ChaCha8Rng) -> Estimate {
    let fs = s.f_grid();
    let [lo, hi] = s.window;
    if data.len() < 2 {
        return Estimate::NONE;
    }
    let all: Vec<usize> = (0..data.len()).collect();
    let full = data.mean(&all, &data.all_controls());
    let points = window_points(&full, lo, hi);
    let value = calibrate_lambda_at(&fs, &full, m1, &points);
    let boot = (0..RESAMPLES)
        .map(|_| {
            let (idx, ctl) = draw(rng, data);
            calibrate_lambda_at(&fs, &data.mean(&idx, &ctl), m1, &points).unwrap_or(f64::NAN)
        })
        .collect();
    Estimate::of(value, boot)
}

/// d ln k / d ln f by central differences (None where a neighbour is missing).
fn local_exponent(fs: &[f64], k: &[Option<f64>]) -> Vec<Option<f64>> {
    (0..fs.len())
        .map(|j| {
            if j == 0 || j + 1 == fs.len() {
                return None;
            }
            let (a, b) = (k[j - 1]?, k[j + 1]?);
            Some((b.ln() - a.ln()) / (fs[j + 1].ln() - fs[j - 1].ln()))
        })
        .collect()
}

/// The residual misfit of the calibrated MRD law: max and rms |ln k3 - ln k1(lambda)|
/// over the window, and the f range of those points.
fn misfit(
    s: &LambdaStudy,
    m3: &[Option<f64>],
    m1: &[Option<f64>],
    lambda: f64,
) -> (f64, f64, (f64, f64)) {
    let fs = s.f_grid();
    let [lo, hi] = s.window;
    let (f1, v1): (Vec<f64>, Vec<f64>) = fs
        .iter()
        .zip(m1)
        .filter_map(|(&f, &v)| v.map(|v| (f, v)))
        .unzip();
    let scale = (std::f64::consts::PI / lambda).sqrt();
    let d: Vec<(f64, f64)> = fs
        .iter()
        .zip(m3)
        .filter_map(|(&f, &v)| {
            let v = v.filter(|&v| v >= lo && v <= hi)?;
            let w = interp_loglog(&f1, &v1, f * scale)?;
            Some((f, (v.ln() - w.ln()).abs()))
        })
        .collect();
    if d.is_empty() || !lambda.is_finite() {
        return (f64::NAN, f64::NAN, (f64::NAN, f64::NAN));
    }
    let max = d.iter().map(|x| x.1).fold(0.0, f64::max);
    let rms = (d.iter().map(|x| x.1 * x.1).sum::<f64>() / d.len() as f64).sqrt();
    (max, rms, (d[0].0, d[d.len() - 1].0))
}

fn analyse_case(s: &LambdaStudy, work: &Path, case: &Case) -> Result<Option<(CaseResult, f64)>> {
    let n = done(work, case);
    let Some((m1, seconds_1d)) = mean_1d(s, work, case)? else {
        return Ok(None);
    };
    let data = sample(s, work, case, n)?;
    if data.len() < 2 {
        return Ok(None);
    }
    let (fs, nf) = (s.f_grid(), s.f_grid().len());
    let [lo, hi] = s.window;
    let mut rng = rng_for(s, case, n, 0);
    // Fitted as the shift of the reduced curves (lambda_rms), reported as lambda of
    // Eq. (76): divided by the case's rms factor (the plan's tests use the shift).
    let lambda_rms = lambda_of(s, &data, &m1, &mut rng);
    let to_eq76 = 1.0 / super::tasks::rms_factor(case.hurst, case.band)?;
    let all: Vec<usize> = (0..data.len()).collect();
    let m3 = data.mean(&all, &data.all_controls());
    let points = window_points(&m3, lo, hi);
    let mut boot_alpha = Vec::new();
    let mut boot_slope: Vec<Vec<f64>> = vec![Vec::new(); nf];
    for _ in 0..RESAMPLES {
        let (idx, ctl) = draw(&mut rng, &data);
        let m = data.mean(&idx, &ctl);
        boot_alpha.push(fit_points(&fs, &m, &points).map_or(f64::NAN, |x| x.0));
        for (j, v) in local_exponent(&fs, &m).into_iter().enumerate() {
            if let Some(v) = v {
                boot_slope[j].push(v);
            }
        }
    }
    let slope3 = local_exponent(&fs, &m3);
    let slope_3d = slope3
        .iter()
        .zip(boot_slope)
        .map(|(v, b)| v.map(|v| Estimate::of(Some(v), b)))
        .collect();
    let (misfit_max, misfit_rms, f_range) = misfit(s, &m3, &m1, lambda_rms.value);
    let (lower, upper) = halves(&points);
    let lambda_halves = (
        to_eq76 * calibrate_lambda_at(&fs, &m3, &m1, &lower).unwrap_or(f64::NAN),
        to_eq76 * calibrate_lambda_at(&fs, &m3, &m1, &upper).unwrap_or(f64::NAN),
    );
    let alpha = |k: &[Option<f64>], p: &[bool]| fit_points(&fs, k, p).map_or(f64::NAN, |x| x.0);
    let alpha_halves = [
        alpha(&m3, &lower),
        alpha(&m3, &upper),
        alpha(&m1, &lower),
        alpha(&m1, &upper),
    ];
    let alpha_mrd = Estimate {
        value: fit_window(&fs, &m1, lo, hi).map_or(f64::NAN, |x| x.0),
        lo: f64::NAN,
        hi: f64::NAN,
    };
    let result = CaseResult {
        case: *case,
        realisations: data.len(),
        lambda: lambda_rms.scaled(to_eq76),
        alpha_3d: Estimate::of(fit_points(&fs, &m3, &points).map(|x| x.0), boot_alpha),
        alpha_mrd,
        misfit_max,
        misfit_rms,
        f_range,
        lambda_halves,
        alpha_halves,
        slope_mrd: local_exponent(&fs, &m1),
        mean_mrd: m1,
        slope_3d,
        mean_3d: m3,
        target: s.target_at(case.hurst),
        unconverged: data.bem.iter().map(|c| c.unconverged).sum(),
        seconds_3d: data.bem.iter().map(|c| c.seconds).sum(),
    };
    Ok(Some((result, seconds_1d)))
}

/// The chosen points split in two: the lower half (by f) and the upper half.
fn halves(points: &[bool]) -> (Vec<bool>, Vec<bool>) {
    let n = points.iter().filter(|&&p| p).count();
    let mut seen = 0;
    let mut lower = vec![false; points.len()];
    let mut upper = vec![false; points.len()];
    for (j, &p) in points.iter().enumerate() {
        if p {
            if seen < n / 2 {
                lower[j] = true;
            } else {
                upper[j] = true;
            }
            seen += 1;
        }
    }
    (lower, upper)
}

/// The case a paired comparison of `case` refers to, if any.
fn reference(s: &LambdaStudy, case: &Case) -> Option<Case> {
    let main = Case {
        hurst: case.hurst,
        band: s.calibrate_at,
        cells: s.cells,
        tolerance: s.tolerance,
        role: Role::Ladder,
    };
    match case.role {
        Role::Ladder | Role::Above if case.band != s.calibrate_at => Some(main),
        // Other cells or tolerance: the main case of the same bandwidth.
        Role::Resolution | Role::Tolerance => Some(Case {
            band: case.band,
            role: if case.band <= s.calibrate_at {
                Role::Ladder
            } else {
                Role::Above
            },
            ..main
        }),
        _ => None,
    }
}

/// lambda(case) / lambda(reference) over their shared realisations, paired.
fn pair(s: &LambdaStudy, work: &Path, case: &Case, refc: &Case) -> Result<Option<Pair>> {
    pair_at(s, work, case, refc, done(work, case).min(done(work, refc)))
}

/// The paired ratio of a bandwidth above `calibrate_at` to it over the first `n`
/// realisations (the adaptive plan's test of such a case); None without the data.
pub fn above_ratio(s: &LambdaStudy, work: &Path, case: &Case, n: u64) -> Result<Option<Estimate>> {
    let Some(refc) = reference(s, case) else {
        return Ok(None);
    };
    if done(work, &refc) < n {
        return Ok(None);
    }
    Ok(pair_at(s, work, case, &refc, n)?.map(|p| p.ratio))
}

/// The paired ratio over realisations 0..n of both cases.
fn pair_at(s: &LambdaStudy, work: &Path, case: &Case, refc: &Case, n: u64) -> Result<Option<Pair>> {
    let (Some((m1a, _)), Some((m1b, _))) = (mean_1d(s, work, case)?, mean_1d(s, work, refc)?)
    else {
        return Ok(None);
    };
    let (a, b) = (sample(s, work, case, n)?, sample(s, work, refc, n)?);
    if a.len() < 2 || a.len() != b.len() {
        return Ok(None);
    }
    let fs = s.f_grid();
    let [lo, hi] = s.window;
    // Plain means over the shared realisations: the pairing already cancels the noise of
    // the shared modes, which is what the control variates remove from a single case;
    // their regressions and independent control ensembles would only add noise here.
    // Both sides fitted on the same points, those where both full-sample means lie in the
    // window (so the ratio compares one force range), in every resample too.
    let all: Vec<usize> = (0..a.len()).collect();
    let points: Vec<bool> = window_points(&a.mean(&all, &[]), lo, hi)
        .into_iter()
        .zip(window_points(&b.mean(&all, &[]), lo, hi))
        .map(|(x, y)| x && y)
        .collect();
    let ratio = |idx: &[usize]| -> Option<f64> {
        let la = calibrate_lambda_at(&fs, &a.mean(idx, &[]), &m1a, &points)?;
        let lb = calibrate_lambda_at(&fs, &b.mean(idx, &[]), &m1b, &points)?;
        Some(la / lb)
    };
    let mut rng = rng_for(s, case, n, 1);
    let boot = (0..RESAMPLES)
        .map(|_| ratio(&resample(&mut rng, a.len())).unwrap_or(f64::NAN))
        .collect();
    let value = ratio(&all);
    Ok(Some(Pair {
        case: *case,
        reference: *refc,
        ratio: Estimate::of(value, boot),
        realisations: a.len(),
    }))
}

/// Everything the checkpoints hold; cases without data are left out.
pub fn analyse(s: &LambdaStudy, work: &Path) -> Result<Results> {
    let mut res = Results {
        f: s.f_grid(),
        ..Default::default()
    };
    let mut seen_1d: Vec<(f64, usize)> = Vec::new();
    for case in cases(s) {
        if let Some((c, seconds_1d)) = analyse_case(s, work, &case)? {
            if !seen_1d.contains(&(case.hurst, case.band)) {
                seen_1d.push((case.hurst, case.band));
                res.seconds_mrd += seconds_1d;
            }
            res.seconds_3d += c.seconds_3d;
            res.cases.push(c);
        }
        if let Some(refc) = reference(s, &case) {
            if let Some(mut p) = pair(s, work, &case, &refc)? {
                // The ratio of the shifts, as a ratio of lambda (Eq. 76).
                let factor = super::tasks::rms_factor(refc.hurst, refc.band)?
                    / super::tasks::rms_factor(case.hurst, case.band)?;
                p.ratio = p.ratio.scaled(factor);
                res.pairs.push(p);
            }
        }
    }
    Ok(res)
}

#[cfg(test)]
mod tests {
    use super::halves;

    #[test]
    fn halves_split_the_chosen_points_by_f() {
        let p = [false, true, true, false, true, true, true, false];
        let (lo, hi) = halves(&p);
        assert_eq!(lo, [false, true, true, false, false, false, false, false]);
        assert_eq!(hi, [false, false, false, false, true, true, true, false]);
    }
}
