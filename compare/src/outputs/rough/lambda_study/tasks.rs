//! The study's cases and checkpointed work: one task per 3D realisation of a case
//! (H, bandwidth, cells, tolerance) and one per (H, bandwidth) for the whole MRD
//! ensemble; the plan of the tasks still needed, realisations added batch by batch
//! while a case misses its target.

use super::LambdaStudy;
use crate::error::{io_err, CompareError, Context as _, Result};
use crate::experiment::rough_punch::{line_stiffness, punch_curve, BemCurve, MrdEnsemble};
use crate::report::number_label;
use mrd::rough_contact::RoughLine;
use mrd::roughness::nested;
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{LineSpectrum, SelfAffine};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};
use std::path::Path;
use std::time::Instant;

/// What a case is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The main ladder at or below `calibrate_at`: realisations added to the target.
    Ladder,
    /// A bandwidth above `calibrate_at` (main ladder or extra), paired with
    /// `calibrate_at`: realisations until the paired ratio settles (see `above`).
    Above,
    /// Other cells per wavelength at the resolution check's bandwidth.
    Resolution,
    /// The second tolerance.
    Tolerance,
}

/// One set of paired 3D realisations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    pub hurst: f64,
    pub band: usize,
    pub cells: usize,
    pub tolerance: f64,
    pub role: Role,
}

impl Case {
    pub fn grid(&self) -> usize {
        self.band * self.cells
    }

    fn file(&self, r: u64) -> String {
        format!(
            "bem_H{}_B{}_c{}_t{:e}_r{r}.json",
            number_label(self.hurst),
            self.band,
            self.cells,
            self.tolerance
        )
    }
}

/// The MRD ensemble of one H and bandwidth.
pub fn mrd_file(hurst: f64, band: usize) -> String {
    format!("mrd_H{}_B{band}.json", number_label(hurst))
}

/// The MRD forces at fixed approach of one H and bandwidth (the scatter's).
pub fn approach_file(hurst: f64, band: usize) -> String {
    format!("mrdu_H{}_B{band}.json", number_label(hurst))
}

/// The study's MRD lines at fixed approach: F/(E* h L) of each line at each reduced
/// approach u of [`LambdaStudy::approach_grid`] (rigid indentation past the line's mean
/// height, in units of its rms height h; 0 before the first contact).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ApproachEnsemble {
    pub approach: Vec<f64>,
    pub force: Vec<Vec<f64>>,
    pub seconds: f64,
}

/// Every case of the study, main ladder first (in the order of `hurst` and
/// `bandwidths`), then extras, resolution and tolerance checks; no case twice.
pub fn cases(s: &LambdaStudy) -> Vec<Case> {
    let mut v: Vec<Case> = Vec::new();
    let mut push = |c: Case| {
        let same = |o: &Case| {
            o.hurst == c.hurst
                && o.band == c.band
                && o.cells == c.cells
                && o.tolerance == c.tolerance
        };
        if !v.iter().any(same) {
            v.push(c);
        }
    };
    let main = |hurst: f64, band: usize| Case {
        hurst,
        band,
        cells: s.cells,
        tolerance: s.tolerance,
        role: if band <= s.calibrate_at {
            Role::Ladder
        } else {
            Role::Above
        },
    };
    for &h in &s.hurst {
        for &b in &s.bandwidths {
            push(main(h, b));
        }
    }
    for e in &s.extra {
        for &h in &e.hurst {
            push(main(h, e.bandwidth));
        }
    }
    if let Some(r) = &s.resolution {
        for &h in &s.hurst {
            // The reference at the main cells (also on the ladder if it lists this band).
            push(main(h, r.bandwidth));
            for &c in &r.cells {
                push(Case {
                    cells: c,
                    role: Role::Resolution,
                    ..main(h, r.bandwidth)
                });
            }
        }
    }
    if let Some(t) = &s.tolerance_check {
        push(Case {
            tolerance: t.tolerance,
            role: Role::Tolerance,
            ..main(t.hurst, s.calibrate_at)
        });
    }
    if let Some(t) = &s.top_check {
        push(Case {
            cells: 2 * s.cells,
            role: Role::Resolution,
            ..main(t.hurst, t.bandwidth)
        });
        push(Case {
            tolerance: t.tolerance,
            role: Role::Tolerance,
            ..main(t.hurst, t.bandwidth)
        });
    }
    v
}

/// Whether `case` is one of the two checks of `top_check`.
pub(super) fn top_checked(s: &LambdaStudy, case: &Case) -> bool {
    s.top_check.is_some_and(|t| {
        t.hurst == case.hurst
            && t.bandwidth == case.band
            && matches!(case.role, Role::Resolution | Role::Tolerance)
    })
}

/// The control ensemble of a case's grid: face statistics of many surfaces (no solve),
/// whose means are the expectations the control variates need.
pub fn control_file(case: &Case, m: u64) -> String {
    format!(
        "ctl_H{}_B{}_c{}_m{m}.json",
        number_label(case.hurst),
        case.band,
        case.cells
    )
}

/// Realisations of control ensembles start here (apart from the solved ones).
const CONTROL_OFFSET: u64 = 1 << 40;

/// A case's control ensemble, as [`CONTROL_BATCHES`] batch means of its faces' summit
/// and Winkler curve (a bootstrap over batch means gives the expectations' sampling
/// error; the faces themselves are not kept).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ControlEnsemble {
    pub faces: u64,
    pub batches: Vec<FaceMean>,
    pub seconds: f64,
}

/// Mean summit and Winkler curve of a batch of faces (None where a face lacks it).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct FaceMean {
    pub summit: f64,
    pub winkler: Vec<Option<f64>>,
}

/// Batches of a control ensemble.
pub const CONTROL_BATCHES: u64 = 20;

/// One unit of checkpointed work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Task {
    Bem { case: Case, r: u64 },
    Mrd { hurst: f64, band: usize },
    MrdApproach { hurst: f64, band: usize },
    Control { case: Case, m: u64 },
}

impl Task {
    pub fn file_name(&self) -> String {
        match self {
            Task::Bem { case, r } => case.file(*r),
            Task::Mrd { hurst, band } => mrd_file(*hurst, *band),
            Task::MrdApproach { hurst, band } => approach_file(*hurst, *band),
            Task::Control { case, m } => control_file(case, *m),
        }
    }

    /// Which round a task belongs to: MRD ensembles first, then the cases the shipped
    /// table and the checks need (adaptive) with their control ensembles, then
    /// bandwidths above `calibrate_at` (their checks included) one grid size at a time,
    /// smallest first, so that a grid's adaptive batches settle before a larger grid
    /// takes the machine.
    pub(super) fn priority(&self, s: &LambdaStudy) -> u8 {
        match self {
            Task::Mrd { .. } | Task::MrdApproach { .. } => 0,
            Task::Bem { case, .. } | Task::Control { case, .. } if case.band > s.calibrate_at => {
                let doublings = (case.grid() / (s.calibrate_at * s.cells).max(1))
                    .checked_ilog2()
                    .unwrap_or(0);
                2u8.saturating_add(doublings.min(200) as u8)
            }
            Task::Bem { .. } | Task::Control { .. } => 1,
        }
    }

    /// Relative cost, for ordering a round: cells of the 3D grid.
    pub(super) fn cost(&self) -> usize {
        match self {
            Task::Bem { case, .. } | Task::Control { case, .. } => case.grid() * case.grid(),
            Task::Mrd { .. } | Task::MrdApproach { .. } => 0,
        }
    }
}

/// Realisations 0..n of `case` all present in `work`: the largest such n.
pub fn done(work: &Path, case: &Case) -> u64 {
    (0..)
        .take_while(|&r| work.join(case.file(r)).exists())
        .count() as u64
}

/// pi h1^2 / h3^2 per unit lambda for the study's lines and punch faces of (H, band):
/// the fit's shift of the reduced curves, lambda_rms, is lambda (Eq. 76) times this
/// ([`crate::experiment::lambda_meaning`]).
pub fn rms_factor(hurst: f64, band: usize) -> Result<f64> {
    use crate::experiment::lambda_meaning::{rms_matched, Face};
    let c2d = spectrum(hurst, band).ctx("study spectrum")?;
    Ok(rms_matched(
        1.0,
        &|q| c2d.c2d(q),
        band as f64,
        1.0,
        Face::Disc,
    ))
}

fn spectrum(hurst: f64, band: usize) -> mrd::Result<SelfAffine> {
    // The band's edges are cut by the nested synthesis (|k| in 1..=B): the spectrum
    // reaches a little beyond them so that no mode sits on its boundary.
    let q0 = TAU * (1.0 - 1e-9);
    SelfAffine::new(hurst, q0, q0, TAU * (band as f64 + 0.5))
}

/// One 3D realisation: the punch's curve, and cheap statistics of the same punch face
/// that may serve as control variates of its k(f).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct StudyCurve {
    pub bem: BemCurve,
    pub face: FaceStats,
}

/// Statistics of a punch face (the disc's heights), computed in milliseconds.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct FaceStats {
    /// k/(E* L) of a Winkler foundation (independent springs E* per unit area under
    /// each cell) on the face, at each f of the study's grid (None beyond its range).
    pub winkler: Vec<Option<f64>>,
    /// Skewness and kurtosis of the face's heights; (max - mean) / rms height.
    pub skewness: f64,
    pub kurtosis: f64,
    pub summit: f64,
}

/// Realisation `r` of `case`'s surface on its grid.
fn heights(case: &Case, seed: u64, r: u64) -> Result<Vec<f64>> {
    let sa = spectrum(case.hurst, case.band).ctx("study spectrum")?;
    nested::surface(
        &|q| sa.c2d(q),
        case.band,
        &Grid::square(case.grid(), 1.0),
        seed,
        r,
    )
    .ctx("3D surface")
}

/// [`FaceStats`] of the disc inscribed in the `g x g` map `h` (side 1).
pub fn face_stats(h: &[f64], g: usize, fs: &[f64]) -> Result<FaceStats> {
    let mask = bem3d::mask::disc(g, g, 1.0, 1.0, 0.5);
    let face: Vec<f64> = h
        .iter()
        .zip(&mask)
        .filter(|(_, &m)| m)
        .map(|(&v, _)| v)
        .collect();
    let n = face.len() as f64;
    let mean = face.iter().sum::<f64>() / n;
    let m = |p: i32| face.iter().map(|v| (v - mean).powi(p)).sum::<f64>() / n;
    let rms = m(2).sqrt();
    // Springs of stiffness E* x cell area: a line of the face's cells with dx = cell area.
    let cell = 1.0 / (g * g) as f64;
    let springs = RoughLine::new(&face, n * cell, 1.0).ctx("Winkler face")?;
    let full = springs
        .at_depth(springs.full_contact_depth())
        .ctx("Winkler face")?
        .force;
    let winkler = fs
        .iter()
        .map(|&f| {
            let force = f * rms;
            if force >= full {
                return Ok(None);
            }
            Ok(Some(springs.at_force(force).ctx("Winkler face")?.stiffness))
        })
        .collect::<Result<_>>()?;
    Ok(FaceStats {
        winkler,
        skewness: m(3) / rms.powi(3),
        kurtosis: m(4) / rms.powi(4),
        summit: (face.iter().copied().fold(f64::NEG_INFINITY, f64::max) - mean) / rms,
    })
}

pub(super) fn run_bem(s: &LambdaStudy, case: &Case, r: u64) -> Result<StudyCurve> {
    let t0 = Instant::now();
    let g = case.grid();
    let h = heights(case, s.seed, r)?;
    let face = face_stats(&h, g, &s.f_grid())?;
    let mut bem = punch_curve(&h, g, s.loads, case.tolerance)?;
    bem.seconds = t0.elapsed().as_secs_f64();
    Ok(StudyCurve { bem, face })
}

pub(super) fn run_control(s: &LambdaStudy, case: &Case, m: u64) -> Result<ControlEnsemble> {
    let t0 = Instant::now();
    let fs = s.f_grid();
    let faces: Vec<FaceStats> = (0..m)
        .into_par_iter()
        .map(|i| {
            face_stats(
                &heights(case, s.seed, CONTROL_OFFSET + i)?,
                case.grid(),
                &fs,
            )
        })
        .collect::<Result<_>>()?;
    let per = (m / CONTROL_BATCHES).max(1) as usize;
    let batches = faces
        .chunks(per)
        .map(|b| {
            let n = b.len() as f64;
            FaceMean {
                summit: b.iter().map(|f| f.summit).sum::<f64>() / n,
                winkler: (0..fs.len())
                    .map(|j| {
                        b.iter()
                            .map(|f| f.winkler[j])
                            .sum::<Option<f64>>()
                            .map(|v| v / n)
                    })
                    .collect(),
            }
        })
        .collect();
    Ok(ControlEnsemble {
        faces: m,
        batches,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// MRD line `r` of H and bandwidth `band` (C1D = pi q C2D) as springs of length 1, E* = 1.
fn mrd_line(s: &LambdaStudy, line: &LineSpectrum, band: usize, r: u64) -> Result<RoughLine> {
    let n1 = s.points_1d_per_cell * s.cells * band;
    let z = nested::line(&|q| line.c1d(q), band, n1, 1.0, s.seed, r).ctx("1D line")?;
    RoughLine::new(&z, 1.0, 1.0).ctx("1D line")
}

pub(super) fn run_mrd(s: &LambdaStudy, hurst: f64, band: usize) -> Result<MrdEnsemble> {
    let t0 = Instant::now();
    let line = spectrum(hurst, band).ctx("study spectrum")?.to_line(PI);
    let fs = s.f_grid();
    let stiffness: Vec<Vec<f64>> = (0..s.realisations_1d)
        .into_par_iter()
        .map(|r| -> Result<Vec<f64>> { line_stiffness(&mrd_line(s, &line, band, r)?, &fs) })
        .collect::<Result<_>>()?;
    Ok(MrdEnsemble {
        stiffness,
        seconds: t0.elapsed().as_secs_f64(),
        points: s.points_1d_per_cell * s.cells * band,
    })
}

/// The same lines as [`run_mrd`], their force at each reduced approach u past the mean
/// height: depth from the highest point d = u h + (max - mean).
pub(super) fn run_mrd_approach(
    s: &LambdaStudy,
    hurst: f64,
    band: usize,
) -> Result<ApproachEnsemble> {
    let t0 = Instant::now();
    let line = spectrum(hurst, band).ctx("study spectrum")?.to_line(PI);
    let us = s.approach_grid();
    let force: Vec<Vec<f64>> = (0..s.realisations_1d)
        .into_par_iter()
        .map(|r| -> Result<Vec<f64>> {
            let rl = mrd_line(s, &line, band, r)?;
            let h = rl.rms_height;
            let above_mean = rl.mean_plane_depth();
            us.iter()
                .map(|&u| {
                    let d = u * h + above_mean;
                    Ok(if d <= 0.0 {
                        0.0
                    } else {
                        rl.at_depth(d).ctx("1D")?.force / h
                    })
                })
                .collect()
        })
        .collect::<Result<_>>()?;
    Ok(ApproachEnsemble {
        approach: us,
        force,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Reads one checkpoint, if present.
pub fn load<T: for<'de> Deserialize<'de>>(work: &Path, file: &str) -> Result<Option<T>> {
    let p = work.join(file);
    match std::fs::read_to_string(&p) {
        Ok(text) => serde_json::from_str(&text)
            .map(Some)
            .map_err(|e| CompareError::Internal(format!("{}: {e}", p.display()))),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(io_err(format!("reading {}", p.display()))(e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mrd_force_at_fixed_approach_is_exact_in_complete_contact() {
        let s: LambdaStudy = toml::from_str(
            "hurst = [0.5]\nbandwidths = [8]\ncalibrate_at = 8\nrealisations_1d = 16\n\
             realisations = { min = 4, max = 4, batch = 4 }\ncells = 4\nseed = 3",
        )
        .unwrap();
        let e = run_mrd_approach(&s, 0.5, 8).unwrap();
        assert_eq!(e.approach, s.approach_grid());
        let line = spectrum(0.5, 8).unwrap().to_line(PI);
        let mut complete = 0;
        for (r, f) in e.force.iter().enumerate() {
            let rl = mrd_line(&s, &line, 8, r as u64).unwrap();
            let h = rl.rms_height;
            // Complete contact from u = (mean - min) / h on: F/(E* h L) = u exactly
            // (every spring compressed by u h + z - mean; the heights average to the mean).
            let u_full = (rl.full_contact_depth() - rl.mean_plane_depth()) / h;
            // Before the first contact, u < -(max - mean) / h: no force.
            let u_first = -rl.mean_plane_depth() / h;
            for (j, &u) in e.approach.iter().enumerate() {
                if u >= u_full {
                    assert!(
                        (f[j] - u).abs() < 1e-12 * u.abs().max(1.0),
                        "{r} {u}: {}",
                        f[j]
                    );
                    complete += 1;
                }
                if u <= u_first {
                    assert_eq!(f[j], 0.0);
                }
                if j > 0 {
                    assert!(f[j] >= f[j - 1]);
                }
            }
        }
        assert!(complete > 16, "{complete}");
    }
}
