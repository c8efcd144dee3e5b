//! The calibration's source made into a spectrum in units of the punch diameter, and its
//! checkpointed solves: one task per 3D punch, one for the MRD ensemble, and for a
//! measured map its own 3D solve and the MRD ensemble of its whole spectrum.

use super::Calibrate;
use crate::context::Context;
use crate::error::{CompareError, Context as _, Result};
use crate::experiment::measured::Measured;
use crate::experiment::rough_punch::{line_stiffness, punch_curve, BemCurve};
use crate::experiment::tasks;
use crate::output::RunControl;
use crate::plan::Stage;
use crate::report::clock;
use mrd::rough_contact::RoughLine;
use mrd::roughness::nested;
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{SelfAffine, TabulatedSpectrum};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};
use std::path::Path;

/// The spectrum in units of L (wavenumbers q L, C2D / L^4).
#[derive(Debug, Clone)]
pub enum Spectrum {
    SelfAffine(SelfAffine),
    Table { table: TabulatedSpectrum, side: f64 },
}

impl Spectrum {
    pub fn c2d(&self, q: f64) -> f64 {
        match self {
            Spectrum::SelfAffine(s) => s.c2d(q),
            Spectrum::Table { table, side } => table.c2d(q / side) / side.powi(4),
        }
    }
}

/// What the source gives the calibration.
#[derive(Debug, Clone)]
pub struct Case {
    pub spectrum: Spectrum,
    /// Bandwidth of the calibration punches and lines.
    pub band: usize,
    /// 3D cells a side of a calibration punch.
    pub grid: usize,
    /// The source's own bandwidth (a map's Nyquist wavenumber, a table's last q, in
    /// units of 2 pi / L).
    pub source_band: usize,
    /// Physical side L [length] (1 for a self-affine source).
    pub side: f64,
    /// The measured map, when the source is one.
    pub map: Option<Measured>,
    /// Warnings the report carries.
    pub warnings: Vec<String>,
    /// A fingerprint of the source's data: checkpoints of another source are refused.
    pub fingerprint: String,
}

impl Case {
    /// Reads and checks the source.
    pub fn new(spec: &Calibrate, ctx: &Context) -> Result<Self> {
        let bad = |m: String| Err(CompareError::Scene(m));
        let given = [
            spec.topography.is_some(),
            spec.psd.is_some(),
            spec.self_affine.is_some(),
        ];
        if given.iter().filter(|&&g| g).count() != 1 {
            return bad("give exactly one of topography, psd and self_affine".into());
        }
        if spec.solve_map.is_some() && spec.topography.is_none() {
            return bad("solve_map applies to a topography (a measured map) only".into());
        }
        if spec.size.is_some() && spec.self_affine.is_some() {
            return bad(
                "size: a self_affine spectrum is in units of the punch diameter L; give no size"
                    .into(),
            );
        }
        let mut warnings = Vec::new();
        let (spectrum, source_band, side, map, fingerprint) = if let Some(t) = &spec.topography {
            let path = ctx.resolve(t);
            let (m, cell) = mrd::topography::HeightMap::read_with_cell(&path)
                .ctx(format!("topography {}", path.display()))?;
            let size = match (spec.size, cell) {
                (Some(s), _) => (s[0], s[1]),
                (None, Some((dx, dy))) => (dx * m.cols as f64, dy * m.rows as f64),
                (None, None) => {
                    return bad(format!(
                        "topography {}: the file states no cell size; give size = [lx, ly] in the scene's length unit",
                        path.display()
                    ))
                }
            };
            let measured = Measured::new(&m.data, m.rows, m.cols, size)?;
            warnings.extend(measured.warnings());
            let table = measured.spectrum()?;
            let fp = crate::output::checkpoint_key(&format!("{:?}", measured.heights));
            let side = measured.side;
            (
                Spectrum::Table { table, side },
                measured.n / 2,
                side,
                Some(measured),
                fp,
            )
        } else if let Some(p) = &spec.psd {
            let path = ctx.resolve(p);
            let (q, c) = mrd::topography::read_two_columns(&path, ["q", "C2D"]).ctx(format!(
                "psd table {} (columns q [1/length], C2D [length^4])",
                path.display()
            ))?;
            check_psd(&q, &c)
                .map_err(|m| CompareError::Scene(format!("psd table {}: {m}", path.display())))?;
            let side = match spec.size {
                Some([a, b]) if a == b && a > 0.0 && a.is_finite() => a,
                _ => {
                    return bad(
                        "psd: give size = [L, L], the punch diameter in the scene's length unit (the PSD's lowest wavenumber is 2 pi / L)".into(),
                    )
                }
            };
            let pts: Vec<(f64, f64)> = q.iter().copied().zip(c.iter().copied()).collect();
            let table =
                TabulatedSpectrum::new(&pts).ctx(format!("psd table {}", path.display()))?;
            if q[0] > TAU / side * 1.01 {
                warnings.push(format!(
                    "psd: the table starts at q = {:.4e}, above 2 pi / L = {:.4e}: C2D is held at its first value down to 2 pi / L (a roll-off assumed there)",
                    q[0],
                    TAU / side
                ));
            }
            let table = table.with_lowest_wavenumber(TAU / side);
            let band = (q.last().copied().unwrap_or(0.0) * side / TAU).floor() as usize;
            let fp = crate::output::checkpoint_key(&format!("{pts:?}"));
            (Spectrum::Table { table, side }, band, side, None, fp)
        } else {
            let s = spec.self_affine.expect("one source given");
            if !(-1.0..=3.0).contains(&s.hurst) {
                return bad(format!(
                    "self_affine.hurst = {} must lie in [-1, 3]",
                    s.hurst
                ));
            }
            if !(s.rolloff >= 1.0 && s.rolloff < spec.bandwidth as f64) {
                return bad(format!(
                    "self_affine.rolloff = {} must lie in [1, bandwidth = {})",
                    s.rolloff, spec.bandwidth
                ));
            }
            let edge = 1.0 + 1e-9;
            let sa = SelfAffine::new(
                s.hurst,
                TAU / edge,
                TAU * s.rolloff / edge,
                TAU * spec.bandwidth as f64 * edge,
            )
            .ctx("self_affine")?;
            (
                Spectrum::SelfAffine(sa),
                spec.bandwidth,
                1.0,
                None,
                String::new(),
            )
        };
        if source_band < 8 {
            return bad(format!(
                "the source's spectrum reaches {source_band} x 2 pi / L; a calibration needs at least 8"
            ));
        }
        let band = spec.bandwidth.min(source_band);
        if band < spec.bandwidth {
            warnings.push(format!(
                "bandwidth = {} is above the source's {source_band}: calibrated at {band}",
                spec.bandwidth
            ));
        }
        Ok(Self {
            spectrum,
            band,
            grid: spec.cells * band,
            source_band,
            side,
            map,
            warnings,
            fingerprint,
        })
    }

    /// pi h1^2 / h3^2 per unit lambda at bandwidth `band` (the punch face).
    pub fn rms_factor(&self, band: usize) -> f64 {
        self.spectrum.rms_factor(band)
    }
}

impl Spectrum {
    /// pi h1^2 / h3^2 per unit lambda at bandwidth `band` (the punch face).
    pub fn rms_factor(&self, band: usize) -> f64 {
        use crate::experiment::lambda_meaning::{rms_matched, Face};
        rms_matched(1.0, &|q| self.c2d(q), band as f64, 1.0, Face::Disc)
    }
}

/// Refuses a PSD table a calibration cannot trust: rows out of order, a wavenumber or a
/// C2D that is not a positive finite number (corrupt or clipped data; a band limit is
/// the table's last row, not zeros after it), or values whose spectral moments overflow
/// or vanish in double precision (rescale the unit of length).
fn check_psd(q: &[f64], c: &[f64]) -> std::result::Result<(), String> {
    if q.len() < 2 {
        return Err("needs at least 2 rows".into());
    }
    for (k, (&q, &c)) in q.iter().zip(c).enumerate() {
        if !(q.is_finite() && q > 0.0) {
            return Err(format!("row {}: q = {q} must be finite and > 0", k + 1));
        }
        if !(c.is_finite() && c > 0.0) {
            return Err(format!(
                "row {}: C2D = {c} must be finite and > 0 (end the table at the band limit instead of padding it)",
                k + 1
            ));
        }
    }
    if let Some(k) = q.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!(
            "row {}: q = {} does not increase from {}",
            k + 2,
            q[k + 1],
            q[k]
        ));
    }
    // The mean square height and slope, by the trapezoid rule on q dq: both must be
    // normal positive numbers.
    let moment = |power: i32| -> f64 {
        q.windows(2)
            .zip(c.windows(2))
            .map(|(q, c)| 0.5 * (q[1] - q[0]) * (q[0].powi(power) * c[0] + q[1].powi(power) * c[1]))
            .sum::<f64>()
    };
    for (name, m) in [("rms height", moment(1)), ("rms slope", moment(3))] {
        if !(m.is_normal() && m > 0.0) {
            return Err(format!(
                "its {name} squared is {m:e}, outside double precision's normal range: give q and C2D in another unit of length"
            ));
        }
    }
    Ok(())
}

/// The surrogates' seed stream, apart from the punches' phases.
const SURROGATE_STREAM: u64 = 0x7370_6563_7472_756d;

/// One surrogate spectrum's checkpoint.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Resample {
    /// The surrogate map's estimated PSD (q [1/length], C2D [length^4]).
    pub psd: Vec<(f64, f64)>,
    /// pi h1^2 / h3^2 per unit lambda of this spectrum at the calibration's bandwidth.
    pub rms_factor: f64,
    /// The MRD ensemble's mean k/(E* L) (lambda = pi) on the reduced force grid.
    pub k1: Vec<f64>,
    /// The punches with this spectrum, the main sample's phases.
    pub punches: Vec<BemCurve>,
}

/// Computes surrogate `s` of a measured map: its spectrum, its MRD ensemble and its
/// punches (the spectrum's part of the interval: `super::spectrum`).
pub fn run_surrogate(spec: &Calibrate, case: &Case, s: u64) -> Result<Resample> {
    let m = case.map.as_ref().expect("a spectrum task has a map");
    let psd = m.surrogate_psd(spec.seed ^ SURROGATE_STREAM, s)?;
    let spectrum = surrogate_spectrum(&psd, case)?;
    let lines = run_lines(
        spec,
        &spectrum,
        case.band,
        spec.points_1d_per_cell * case.grid,
    )?;
    let punches = (0..spec.spectrum_punches())
        .into_par_iter()
        .map(|r| run_bem(spec, case, &spectrum, r))
        .collect::<Result<Vec<_>>>()?;
    Ok(Resample {
        rms_factor: spectrum.rms_factor(case.band),
        k1: lines.mean().into_iter().flatten().collect(),
        psd,
        punches,
    })
}

/// A surrogate's PSD as the calibration reads a map's: held flat down to 2 pi / L.
pub fn surrogate_spectrum(psd: &[(f64, f64)], case: &Case) -> Result<Spectrum> {
    let table = TabulatedSpectrum::new(psd)
        .map_err(|e| CompareError::Scene(format!("surrogate PSD: {e}")))?
        .with_lowest_wavenumber(TAU / case.side);
    Ok(Spectrum::Table {
        table,
        side: case.side,
    })
}

/// One unit of checkpointed work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Task {
    /// The MRD ensemble at the calibration's bandwidth.
    Mrd,
    /// The MRD ensemble of the measured map's whole spectrum.
    MapMrd,
    /// The measured map in 3D.
    MapBem,
    /// 3D punch `r`.
    Bem(u64),
    /// Surrogate spectrum `s` of a measured map, its MRD ensemble and its first
    /// `punches` punches.
    Spectrum { s: u64, punches: u64 },
}

impl Task {
    pub fn file_name(&self) -> String {
        match self {
            Task::Mrd => "mrd.json".into(),
            Task::MapMrd => "map_mrd.json".into(),
            Task::MapBem => "map_bem.json".into(),
            Task::Bem(r) => format!("bem_r{r}.json"),
            Task::Spectrum { s, punches } => format!("spectrum_s{s}_p{punches}.json"),
        }
    }
}

/// Every task in its global order: the ensembles, the map and the surrogate spectra
/// first, then the punches up to `realisations.max`.
pub fn all(spec: &Calibrate) -> Vec<Task> {
    let mut t = vec![Task::Mrd];
    if spec.solves_map() {
        t.extend([Task::MapMrd, Task::MapBem]);
    }
    if let Some(u) = spec.spectrum_resamples() {
        let punches = spec.spectrum_punches();
        t.extend((0..u.resamples).map(|s| Task::Spectrum { s, punches }));
    }
    t.extend((0..spec.realisations.max).map(Task::Bem));
    t
}

/// The MRD ensemble: k/(E* L) of each line (lambda = pi) on the reduced force grid.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Lines {
    pub band: usize,
    pub points: usize,
    pub stiffness: Vec<Vec<f64>>,
}

impl Lines {
    /// The ensemble's mean k on the grid.
    pub fn mean(&self) -> Vec<Option<f64>> {
        let n = self.stiffness.len() as f64;
        (0..self.stiffness.first().map_or(0, Vec::len))
            .map(|j| Some(self.stiffness.iter().map(|v| v[j]).sum::<f64>() / n))
            .collect()
    }
}

/// The reduced force grid f = F/(E* h L) of every curve.
pub fn f_grid() -> Vec<f64> {
    mrd::friction::log_space(1e-7, 1e2, 181)
}

/// Punch `r` of the spectrum `spectrum` at the case's bandwidth and grid.
pub fn run_bem(spec: &Calibrate, case: &Case, spectrum: &Spectrum, r: u64) -> Result<BemCurve> {
    let g = case.grid;
    let c2d = |q: f64| spectrum.c2d(q);
    let h = clock::time(Stage::RoughSynthesis, || {
        nested::surface_with(
            &c2d,
            case.band,
            &Grid::square(g, 1.0),
            spec.seed,
            r,
            spec.amplitudes.synthesis(),
        )
    })
    .ctx("3D punch face")?;
    punch_curve(&h, g, spec.loads, spec.tolerance)
}

fn run_map_bem(spec: &Calibrate, case: &Case) -> Result<BemCurve> {
    let m = case.map.as_ref().expect("a map task has a map");
    let h: Vec<f64> = m.heights.iter().map(|v| v / case.side).collect();
    punch_curve(&h, m.n, spec.loads, spec.tolerance)
}

/// `lines` MRD lines of the spectrum `spectrum`, bandwidth `band`, on `points` points,
/// each line's k on the grid.
pub fn run_lines(
    spec: &Calibrate,
    spectrum: &Spectrum,
    band: usize,
    points: usize,
) -> Result<Lines> {
    let fs = f_grid();
    let c1d = |q: f64| PI * q * spectrum.c2d(q);
    let stiffness = (0..spec.lines)
        .into_par_iter()
        .map(|r| -> Result<Vec<f64>> {
            let z = clock::time(Stage::RoughSynthesis, || {
                nested::line(&c1d, band, points, 1.0, spec.seed, r)
            })
            .ctx("MRD line")?;
            line_stiffness(&RoughLine::new(&z, 1.0, 1.0).ctx("MRD line")?, &fs)
        })
        .collect::<Result<_>>()?;
    Ok(Lines {
        band,
        points,
        stiffness,
    })
}

fn run(spec: &Calibrate, case: &Case, t: Task) -> Result<String> {
    use tasks::json;
    let map_n = case.map.as_ref().map_or(0, |m| m.n);
    match t {
        Task::Mrd => json(&run_lines(
            spec,
            &case.spectrum,
            case.band,
            spec.points_1d_per_cell * case.grid,
        )?),
        Task::MapMrd => json(&run_lines(
            spec,
            &case.spectrum,
            case.source_band,
            spec.points_1d_per_cell * map_n,
        )?),
        Task::MapBem => json(&run_map_bem(spec, case)?),
        Task::Bem(r) => json(&run_bem(spec, case, &case.spectrum, r)?),
        Task::Spectrum { s, .. } => json(&run_surrogate(spec, case, s)?),
    }
}

/// Computes the missing tasks among the first `upto` of [`all`] into `work`, after
/// checking that its checkpoints were computed for this source; `first`: the run's
/// first call (it says what it resumes from).
pub fn compute(
    spec: &Calibrate,
    case: &Case,
    work: &Path,
    upto: usize,
    first: bool,
    control: &RunControl,
) -> Result<()> {
    check_source(case, work)?;
    let list = all(spec);
    let names: Vec<String> = list.iter().map(Task::file_name).collect();
    tasks::compute(work, "calibrate", &names, upto, first, control, &|i| {
        run(spec, case, list[i])
    })
}

/// Records the source's fingerprint in `work`, or refuses checkpoints of another.
fn check_source(case: &Case, work: &Path) -> Result<()> {
    std::fs::create_dir_all(work)
        .map_err(crate::error::io_err(format!("creating {}", work.display())))?;
    let p = work.join("source.txt");
    match std::fs::read_to_string(&p) {
        Ok(s) if s.trim() == case.fingerprint => Ok(()),
        Ok(_) => Err(CompareError::Scene(format!(
            "the checkpoints in {} were computed for another surface (the file changed?): remove that folder or give another --work",
            work.display()
        ))),
        Err(_) => crate::files::write_atomic(&p, &case.fingerprint),
    }
}

/// Reads task `t`'s checkpoint.
pub fn load<T: for<'de> Deserialize<'de>>(work: &Path, t: Task) -> Result<T> {
    tasks::load(work, &t.file_name())
}
