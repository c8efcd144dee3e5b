//! The Hurst sweep (Section 9, Fig. 6): the same rough contact in 3D (bem3d, circular
//! rough punch) and in 1D (MRD rough lines), for Hurst exponents from -1 to 3.
//!
//! Set-up, with E* = 1 and punch diameter L = 1: a self-affine surface without
//! long-wavelength cut-off (C2D ~ q^(-2H-2) from q0 = 2 pi/L to q1 = ratio x pi/dx3,
//! ratio 0.25 by default so the shortest wavelength spans 8 cells, Eq. 70) is synthesised on a `grid x grid` square of side L; the inscribed disc is the
//! punch face (mask). It is pressed, displacement-controlled and warm-started, from 1e-3
//! of the full-contact approach to full contact, and the tangent stiffness k = dF/dd is
//! computed at each approach with the contact set fixed. The 1D line of length L, with
//! `C1D = pi q C2D` (Eq. 73) over the same band, is loaded on a fixed grid of reduced
//! forces. Both give k/(E* L) against f = F/(E* h L) (Eq. 77), h the rms height of the
//! punch face or of the line.
//!
//! Fit window (documented, plotted): ensemble-mean k/(E* L) in [3/grid, 0.3], i.e. from
//! a few cells in contact to well below saturation (k -> E* L); alpha and zeta by least
//! squares in log space, 95 % intervals by a bootstrap over realisations (200 resamples).
//!
//! lambda(H): under Eq. (77) lambda only rescales the 1D heights, h1 = sqrt(lambda/pi) h3,
//! so the 1D law in terms of the 3D surface's h is K1(f sqrt(pi/lambda)); lambda is the
//! least-squares fit in log space of that curve to the 3D one over the 3D fit window.
//!
//! Every task (one 3D realisation, or the whole 1D ensemble of one H) is checkpointed
//! atomically to `<out>.work/<hash>/`; a killed run resumes from there, shards
//! (`--shard K/N`) compute disjoint task subsets, and results do not depend on thread
//! count, shard split or interruption.

use crate::error::{io_err, CompareError, MrdContext, Result};
use crate::plan::Stage;
use crate::report::{Figure, Report, Series, Style, Table};
use bem3d::{BemError, ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use mrd::rough_contact::{fit_line, RoughLine};
use mrd::roughness::synthesis::{line, surface, Amplitudes, Grid};
use mrd::roughness::{lambda_cut, SelfAffine};
use rand::{RngExt, SeedableRng};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Parameters of one sweep (an `[[outputs]]` entry of kind `hurst_sweep`).
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Hurst exponents, each in [-1, 3].
    pub hurst: Vec<f64>,
    /// 3D grid side (cells across the punch diameter).
    pub grid: usize,
    /// Extra, coarser grids for the convergence study of alpha (optional).
    #[serde(default)]
    pub convergence_grids: Vec<usize>,
    /// Upper cut-off q1 as a fraction of the 3D grid's Nyquist wavenumber pi/dx. The
    /// default 0.25 resolves the shortest wavelength with 8 cells; at 0.5 (4 cells) the
    /// 3D alpha for H < 0 is biased low (64^2, H = -0.5: 0.55 against MRD's 0.74; at 0.25
    /// both give 0.62).
    #[serde(default = "quarter")]
    pub upper_cutoff_ratio: f64,
    pub realisations_3d: u64,
    pub realisations_1d: u64,
    /// 1D points per 3D cell across (N1 = factor x grid).
    #[serde(default = "sixteen")]
    pub points_1d_factor: usize,
    /// Number of approaches per 3D realisation.
    #[serde(default = "twenty")]
    pub loads: usize,
    #[serde(default)]
    pub seed: u64,
    /// 3D solver tolerance (see bem3d::solver).
    #[serde(default = "tol")]
    pub tolerance: f64,
}

fn quarter() -> f64 {
    0.25
}
fn sixteen() -> usize {
    16
}
fn twenty() -> usize {
    20
}
fn tol() -> f64 {
    1e-8
}

impl SweepSpec {
    pub fn validate(&self) -> std::result::Result<(), String> {
        if self.hurst.is_empty() {
            return Err("hurst list is empty".into());
        }
        if let Some(h) = self.hurst.iter().find(|h| !(-1.0..=3.0).contains(*h)) {
            return Err(format!("hurst = {h} must lie in [-1, 3]"));
        }
        for &g in std::iter::once(&self.grid).chain(&self.convergence_grids) {
            if !(16..=4096).contains(&g) {
                return Err(format!("grid {g} must lie in 16..=4096"));
            }
        }
        if !(self.upper_cutoff_ratio > 0.0 && self.upper_cutoff_ratio <= 1.0) {
            return Err("upper_cutoff_ratio must lie in (0, 1]".into());
        }
        if self.realisations_3d < 2 || self.realisations_1d < 2 {
            return Err("need at least 2 realisations in 3D and in 1D (for intervals)".into());
        }
        if self.loads < 6 || self.points_1d_factor < 2 {
            return Err("need loads >= 6 and points_1d_factor >= 2".into());
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1e-2) {
            return Err("tolerance must lie in (0, 1e-2)".into());
        }
        Ok(())
    }

    fn grids(&self) -> Vec<usize> {
        let mut g = vec![self.grid];
        g.extend(
            self.convergence_grids
                .iter()
                .copied()
                .filter(|&x| x != self.grid),
        );
        g
    }

    /// Reduced forces at which the 1D lines are loaded and all curves are compared.
    fn f_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(1e-7, 1e2, 91)
    }

    fn key(&self) -> String {
        // FNV-1a of the parameters' debug form (f64 prints round-trip exactly).
        let text = format!("{self:?}");
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in text.bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
        format!("{h:016x}")
    }
}

/// One unit of checkpointed work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Task {
    /// 3D realisation `r` at Hurst index `h` on grid `g`.
    Bem { h: usize, g: usize, r: u64 },
    /// The whole 1D ensemble at Hurst index `h` (1D is cheap).
    Mrd { h: usize },
}

impl Task {
    /// Checkpoint file name of the task.
    pub fn file_name(&self) -> String {
        self.file()
    }

    fn file(&self) -> String {
        match self {
            Task::Bem { h, g, r } => format!("bem_h{h}_g{g}_r{r}.json"),
            Task::Mrd { h } => format!("mrd_h{h}.json"),
        }
    }
}

/// Result of one 3D realisation: F and k at each approach (E* = 1, L = 1).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct BemCurve {
    pub rms_height: f64,
    pub force: Vec<f64>,
    pub stiffness: Vec<f64>,
    pub iterations: usize,
    /// Largest residual reached; above the tolerance when a solve did not converge.
    pub max_residual: f64,
    pub unconverged: usize,
    pub seconds: f64,
}

/// Result of the 1D ensemble at one H: k/(E* L) per realisation on the f grid.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct MrdEnsemble {
    pub stiffness: Vec<Vec<f64>>,
    pub seconds: f64,
    pub points: usize,
}

fn stream(seed: u64, task_kind: u64, h: usize, g: usize, r: u64) -> (u64, u64) {
    (
        seed,
        (task_kind << 60) ^ ((h as u64) << 40) ^ ((g as u64) << 24) ^ r,
    )
}

fn spectrum(spec: &SweepSpec, hurst: f64, grid: usize) -> mrd::Result<SelfAffine> {
    let q0 = 2.0 * PI;
    let q1 = spec.upper_cutoff_ratio * PI * grid as f64;
    SelfAffine::new(hurst, q0, q0, q1)
}

fn run_bem(spec: &SweepSpec, h: usize, g: usize, r: u64) -> Result<BemCurve> {
    let t0 = Instant::now();
    let hurst = spec.hurst[h];
    let sa = spectrum(spec, hurst, g).ctx("sweep spectrum")?;
    let (seed, id) = stream(spec.seed, 1, h, g, r);
    let heights = surface(
        &sa,
        &Grid::square(g, 1.0),
        seed,
        id,
        Amplitudes::Deterministic,
    )
    .ctx("3D surface")?;
    let dx = 1.0 / g as f64;
    let mask: Vec<bool> = (0..g * g)
        .map(|k| {
            let (x, y) = (
                ((k % g) as f64 + 0.5) * dx - 0.5,
                ((k / g) as f64 + 0.5) * dx - 0.5,
            );
            x * x + y * y <= 0.25
        })
        .collect();
    let on: Vec<f64> = heights
        .iter()
        .zip(&mask)
        .filter(|(_, &m)| m)
        .map(|(v, _)| *v)
        .collect();
    let mean = on.iter().sum::<f64>() / on.len() as f64;
    let rms = (on.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / on.len() as f64).sqrt();
    let top = on.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let bottom = on.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    let full = top - bottom;
    let mut solver = ContactSolver::new(
        NonPeriodicHalfSpace::new(g, g, 1.0, 1.0, 1.0),
        &heights,
        Some(mask),
    )
    .map_err(|e| CompareError::Scene(format!("3D solver set-up: {e}")))?;
    let opts = SolverOptions {
        tolerance: spec.tolerance,
        max_iterations: 20 * g + 2000,
    };
    let mut out = BemCurve {
        rms_height: rms,
        force: vec![],
        stiffness: vec![],
        iterations: 0,
        max_residual: 0.0,
        unconverged: 0,
        seconds: 0.0,
    };
    let mut warm: Option<bem3d::Solution> = None;
    for k in 0..spec.loads {
        let d = full * 10f64.powf(-3.0 * (1.0 - k as f64 / (spec.loads - 1) as f64));
        let sol = match solver.solve(Load::Approach(d), &opts, warm.as_ref()) {
            Ok(s) => s,
            Err(BemError::NoConvergence { last, .. }) => {
                out.unconverged += 1;
                *last
            }
            Err(e) => return Err(CompareError::Scene(format!("3D solve: {e}"))),
        };
        out.iterations += sol.iterations;
        out.max_residual = out.max_residual.max(sol.residual);
        let stiffness_opts = SolverOptions {
            tolerance: 1e-9,
            ..opts
        };
        let kk = match solver.tangent_stiffness(&sol, &stiffness_opts) {
            Ok(v) => v,
            Err(BemError::NoConvergence { .. } | BemError::Breakdown { .. }) => f64::NAN,
            Err(e) => return Err(CompareError::Scene(format!("3D stiffness: {e}"))),
        };
        if sol.force > 0.0 && kk.is_finite() && kk > 0.0 {
            out.force.push(sol.force);
            out.stiffness.push(kk);
        }
        warm = Some(sol);
    }
    out.seconds = t0.elapsed().as_secs_f64();
    Ok(out)
}

fn run_mrd(spec: &SweepSpec, h: usize) -> Result<MrdEnsemble> {
    let t0 = Instant::now();
    let hurst = spec.hurst[h];
    let n1 = spec.points_1d_factor * spec.grid;
    let line_spec = spectrum(spec, hurst, spec.grid)
        .ctx("sweep spectrum")?
        .to_line(PI);
    let fs = spec.f_grid();
    let stiffness: Vec<Vec<f64>> = (0..spec.realisations_1d)
        .into_par_iter()
        .map(|r| -> Result<Vec<f64>> {
            let (seed, id) = stream(spec.seed, 2, h, spec.grid, r);
            let z =
                line(&line_spec, n1, 1.0, seed, id, Amplitudes::Deterministic).ctx("1D line")?;
            let rl = RoughLine::new(&z, 1.0, 1.0).ctx("1D line")?;
            let full_force = rl.at_depth(rl.full_contact_depth()).ctx("1D")?.force;
            fs.iter()
                .map(|&f| {
                    let force = f * rl.rms_height;
                    if full_force <= force {
                        return Ok(1.0); // complete contact: k = E* L
                    }
                    Ok(rl.at_force(force).ctx("1D")?.stiffness)
                })
                .collect()
        })
        .collect::<Result<_>>()?;
    Ok(MrdEnsemble {
        stiffness,
        seconds: t0.elapsed().as_secs_f64(),
        points: n1,
    })
}

/// The work folder of a sweep output next to the report folder.
pub fn work_dir(out_dir: &Path, spec: &SweepSpec) -> PathBuf {
    let name = out_dir
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("report");
    out_dir
        .with_file_name(format!("{name}.work"))
        .join(spec.key())
}

fn write_atomic(path: &Path, text: &str) -> Result<()> {
    let dir = path.parent().unwrap();
    let mut tmp = tempfile::NamedTempFile::new_in(dir)
        .map_err(io_err(format!("temporary file in {}", dir.display())))?;
    std::io::Write::write_all(&mut tmp, text.as_bytes()).map_err(io_err("writing checkpoint"))?;
    tmp.persist(path).map_err(|e| CompareError::Io {
        context: format!("saving {}", path.display()),
        source: e.error,
    })?;
    Ok(())
}

/// All tasks of a sweep in a fixed global order (shards take every N-th).
pub fn tasks(spec: &SweepSpec) -> Vec<Task> {
    let mut t = Vec::new();
    for h in 0..spec.hurst.len() {
        for g in spec.grids() {
            for r in 0..spec.realisations_3d {
                t.push(Task::Bem { h, g, r });
            }
        }
        t.push(Task::Mrd { h });
    }
    t
}

/// How a run divides and limits its work.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunControl {
    /// (K, N): compute only tasks with index % N == K.
    pub shard: Option<(usize, usize)>,
    /// Test hook: stop (exit code 3) after computing this many new tasks.
    pub stop_after: Option<usize>,
    pub progress: bool,
}

/// Computes the missing tasks of `spec` (of this shard) into `work`.
pub fn compute(spec: &SweepSpec, work: &Path, control: &RunControl) -> Result<()> {
    std::fs::create_dir_all(work).map_err(io_err(format!("creating {}", work.display())))?;
    let todo: Vec<Task> = tasks(spec)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| control.shard.is_none_or(|(k, n)| i % n == k))
        .map(|(_, t)| t)
        .filter(|t| !work.join(t.file()).exists())
        .collect();
    let bar = if control.progress && !todo.is_empty() {
        let b = indicatif::ProgressBar::new(todo.len() as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "{msg} [{bar:30}] {pos}/{len} tasks, {elapsed} elapsed, ETA {eta}",
            )
            .unwrap()
            .progress_chars("=> "),
        );
        b.set_message("hurst sweep");
        Some(b)
    } else {
        None
    };
    let done = std::sync::atomic::AtomicUsize::new(0);
    todo.par_iter()
        .with_max_len(1)
        .try_for_each(|t| -> Result<()> {
            let text = match *t {
                Task::Bem { h, g, r } => serde_json::to_string(&run_bem(spec, h, g, r)?),
                Task::Mrd { h } => serde_json::to_string(&run_mrd(spec, h)?),
            }
            .map_err(|e| CompareError::Scene(e.to_string()))?;
            write_atomic(&work.join(t.file()), &text)?;
            if let Some(b) = &bar {
                b.inc(1);
            }
            let n = done.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
            if control.stop_after.is_some_and(|s| n >= s) {
                eprintln!("stopping after {n} tasks (MRDW_STOP_AFTER_TASKS)");
                std::process::exit(3);
            }
            Ok(())
        })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(())
}

fn load<T: for<'de> Deserialize<'de>>(work: &Path, t: &Task) -> Result<T> {
    let p = work.join(t.file());
    let text = std::fs::read_to_string(&p).map_err(io_err(format!(
        "reading {} (missing task: run all shards, or rerun to resume)",
        p.display()
    )))?;
    serde_json::from_str(&text).map_err(|e| CompareError::Scene(format!("{}: {e}", p.display())))
}

/// Log-log interpolation of a monotone curve (x ascending) at `x`; None outside.
fn interp_loglog(xs: &[f64], ys: &[f64], x: f64) -> Option<f64> {
    if xs.len() < 2 || x < xs[0] || x > *xs.last().unwrap() {
        return None;
    }
    let k = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
    let (x0, x1, y0, y1) = (xs[k - 1].ln(), xs[k].ln(), ys[k - 1].ln(), ys[k].ln());
    let t = if x1 > x0 {
        (x.ln() - x0) / (x1 - x0)
    } else {
        0.0
    };
    Some((y0 + t * (y1 - y0)).exp())
}

/// Ensemble mean of curves given on `fs` (None = outside that realisation's range);
/// a point is kept only where every realisation has a value.
fn mean_curve(curves: &[Vec<Option<f64>>], idx: &[usize], nf: usize) -> Vec<Option<f64>> {
    (0..nf)
        .map(|j| {
            let vals: Option<Vec<f64>> = idx.iter().map(|&i| curves[i][j]).collect();
            vals.map(|v| v.iter().sum::<f64>() / v.len() as f64)
        })
        .collect()
}

/// alpha, zeta by least squares over the window; None if fewer than 3 points.
fn fit_window(fs: &[f64], k: &[Option<f64>], lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (x, y): (Vec<f64>, Vec<f64>) = fs
        .iter()
        .zip(k)
        .filter_map(|(&f, &v)| v.filter(|&v| v >= lo && v <= hi).map(|v| (f.ln(), v.ln())))
        .unzip();
    fit_line(&x, &y).ok().map(|l| (l.b, l.a.exp()))
}

/// lambda minimising the log-space misfit of K1(f sqrt(pi/lambda)) to K3(f).
fn calibrate_lambda(
    fs: &[f64],
    k3: &[Option<f64>],
    k1: &[Option<f64>],
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let (f1, v1): (Vec<f64>, Vec<f64>) = fs
        .iter()
        .zip(k1)
        .filter_map(|(&f, &v)| v.map(|v| (f, v)))
        .unzip();
    let pts: Vec<(f64, f64)> = fs
        .iter()
        .zip(k3)
        .filter_map(|(&f, &v)| v.filter(|&v| v >= lo && v <= hi).map(|v| (f, v)))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let cost = |ln_lam: f64| -> f64 {
        let s = (PI / ln_lam.exp()).sqrt();
        pts.iter()
            .map(|&(f, v)| match interp_loglog(&f1, &v1, f * s) {
                Some(w) => (v.ln() - w.ln()).powi(2),
                None => 1e3,
            })
            .sum()
    };
    // Golden-section search on ln lambda over [ln 1e-3, ln 1e4] after a coarse scan.
    let (mut a, mut b) = ((1e-3f64).ln(), (1e4f64).ln());
    let scan: Vec<f64> = (0..=200).map(|i| a + (b - a) * i as f64 / 200.0).collect();
    let best = scan.iter().copied().fold((f64::INFINITY, 0.0), |m, x| {
        let c = cost(x);
        if c < m.0 {
            (c, x)
        } else {
            m
        }
    });
    let step = (b - a) / 200.0;
    a = best.1 - step;
    b = best.1 + step;
    let gr = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (c, d) = (b - gr * (b - a), a + gr * (b - a));
        if cost(c) < cost(d) {
            b = d;
        } else {
            a = c;
        }
    }
    Some((0.5 * (a + b)).exp())
}

/// Percentile interval of finite values.
fn interval(mut v: Vec<f64>) -> (f64, f64) {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    v.sort_by(f64::total_cmp);
    let q = |p: f64| v[((p * (v.len() - 1) as f64).round() as usize).min(v.len() - 1)];
    (q(0.025), q(0.975))
}

/// Aggregates the checkpoints of a complete sweep into tables, figures and results.
pub fn aggregate(spec: &SweepSpec, work: &Path, report: &mut Report, label: &str) -> Result<()> {
    report.ran(Stage::RoughSynthesis);
    report.ran(Stage::Bem3d);
    report.ran(Stage::RoughContact);
    report.ran(Stage::SweepFit);
    let fs = spec.f_grid();
    let nf = fs.len();
    let (lo, hi) = (3.0 / spec.grid as f64, 0.3);
    let mut alpha_t = Table::new(
        &format!("{label}_alpha"),
        &[
            "hurst [1]",
            "alpha_3d [1]",
            "alpha_3d_lo95 [1]",
            "alpha_3d_hi95 [1]",
            "alpha_mrd [1]",
            "alpha_mrd_lo95 [1]",
            "alpha_mrd_hi95 [1]",
            "alpha_eq80 [1]",
            "zeta_3d [1]",
            "zeta_3d_lo95 [1]",
            "zeta_3d_hi95 [1]",
            "zeta_mrd [1]",
            "zeta_mrd_lo95 [1]",
            "zeta_mrd_hi95 [1]",
            "lambda [1]",
            "lambda_lo95 [1]",
            "lambda_hi95 [1]",
            "lambda_cut [1]",
        ]
        .map(String::from),
    );
    alpha_t.notes.push(format!(
        "Eq. (77) fits over k/(E* L) in [{lo:e}, {hi}]; 95 % intervals: bootstrap over realisations (200 resamples); 3D grid {}^2 ({} realisations), 1D N = {} ({} realisations); empty cells: undefined (1/(1+H) at H = -1, lambda_cut for H <= -1/2, failed fits)",
        spec.grid, spec.realisations_3d, spec.points_1d_factor * spec.grid, spec.realisations_1d
    ));
    alpha_t.missing_ok = true;
    let mut curves_t = Table::new(
        &format!("{label}_curves"),
        &[
            "hurst [1]",
            "f = F/(E* h L) [1]",
            "k3d/(E* L) mean [1]",
            "k3d ci95 [1]",
            "kmrd/(E* L) mean [1]",
            "kmrd ci95 [1]",
            "in_fit_window [0/1]",
        ]
        .map(String::from),
    );
    curves_t.missing_ok = true;
    let mut conv_t = Table::new(
        &format!("{label}_convergence"),
        &[
            "hurst [1]",
            "grid [cells]",
            "L / shortest wavelength [1]",
            "alpha_3d [1]",
            "alpha_3d_lo95 [1]",
            "alpha_3d_hi95 [1]",
        ]
        .map(String::from),
    );
    conv_t.missing_ok = true;
    let (mut t3, mut t1, mut n3, mut n1) = (0.0, 0.0, 0usize, 0usize);
    let mut speedups = Vec::new();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(spec.seed ^ 0xB007);
    let mut per_h = serde_json::Map::new();
    let mut kf_figs = Vec::new();
    for (hi_idx, &hurst) in spec.hurst.iter().enumerate() {
        let ens: MrdEnsemble = load(work, &Task::Mrd { h: hi_idx })?;
        t1 += ens.seconds;
        n1 += ens.stiffness.len();
        let k1: Vec<Vec<Option<f64>>> = ens
            .stiffness
            .iter()
            .map(|v| v.iter().map(|&x| Some(x)).collect())
            .collect();
        let all1: Vec<usize> = (0..k1.len()).collect();
        let m1 = mean_curve(&k1, &all1, nf);
        let fit1 = fit_window(&fs, &m1, lo, hi);
        for g in spec.grids() {
            let bem: Vec<BemCurve> = (0..spec.realisations_3d)
                .map(|r| load(work, &Task::Bem { h: hi_idx, g, r }))
                .collect::<Result<_>>()?;
            let k3: Vec<Vec<Option<f64>>> = bem
                .iter()
                .map(|c| {
                    let f: Vec<f64> = c.force.iter().map(|&x| x / c.rms_height).collect();
                    fs.iter()
                        .map(|&x| interp_loglog(&f, &c.stiffness, x))
                        .collect()
                })
                .collect();
            let all3: Vec<usize> = (0..k3.len()).collect();
            let m3 = mean_curve(&k3, &all3, nf);
            let (glo, ghi) = (3.0 / g as f64, hi);
            let fit3 = fit_window(&fs, &m3, glo, ghi);
            let boot3: Vec<Option<(f64, f64)>> = (0..200)
                .map(|_| {
                    let idx: Vec<usize> = (0..k3.len())
                        .map(|_| rng.random_range(0..k3.len()))
                        .collect();
                    fit_window(&fs, &mean_curve(&k3, &idx, nf), glo, ghi)
                })
                .collect();
            let ci_a3 = interval(boot3.iter().flatten().map(|x| x.0).collect());
            if g != spec.grid {
                conv_t.push(vec![
                    hurst,
                    g as f64,
                    spec.upper_cutoff_ratio * g as f64 / 2.0,
                    fit3.map_or(f64::NAN, |x| x.0),
                    ci_a3.0,
                    ci_a3.1,
                ]);
                continue;
            }
            t3 += bem.iter().map(|c| c.seconds).sum::<f64>();
            n3 += bem.len();
            let boot1: Vec<Option<(f64, f64)>> = (0..200)
                .map(|_| {
                    let idx: Vec<usize> = (0..k1.len())
                        .map(|_| rng.random_range(0..k1.len()))
                        .collect();
                    fit_window(&fs, &mean_curve(&k1, &idx, nf), glo, ghi)
                })
                .collect();
            let boot_lam: Vec<f64> = (0..200)
                .filter_map(|_| {
                    let i3: Vec<usize> = (0..k3.len())
                        .map(|_| rng.random_range(0..k3.len()))
                        .collect();
                    let i1: Vec<usize> = (0..k1.len())
                        .map(|_| rng.random_range(0..k1.len()))
                        .collect();
                    calibrate_lambda(
                        &fs,
                        &mean_curve(&k3, &i3, nf),
                        &mean_curve(&k1, &i1, nf),
                        glo,
                        ghi,
                    )
                })
                .collect();
            let lam = calibrate_lambda(&fs, &m3, &m1, glo, ghi);
            let ci_z3 = interval(boot3.iter().flatten().map(|x| x.1).collect());
            let ci_a1 = interval(boot1.iter().flatten().map(|x| x.0).collect());
            let ci_z1 = interval(boot1.iter().flatten().map(|x| x.1).collect());
            let ci_l = interval(boot_lam);
            let lcut = lambda_cut(hurst).unwrap_or(f64::NAN);
            let (a3, z3) = fit3.unwrap_or((f64::NAN, f64::NAN));
            let (a1, z1) = fit1.unwrap_or((f64::NAN, f64::NAN));
            alpha_t.push(vec![
                hurst,
                a3,
                ci_a3.0,
                ci_a3.1,
                a1,
                ci_a1.0,
                ci_a1.1,
                if hurst > -1.0 {
                    1.0 / (1.0 + hurst)
                } else {
                    f64::NAN
                },
                z3,
                ci_z3.0,
                ci_z3.1,
                z1,
                ci_z1.0,
                ci_z1.1,
                lam.unwrap_or(f64::NAN),
                ci_l.0,
                ci_l.1,
                lcut,
            ]);
            // Speed-up at equal statistical error: per-realisation alpha scatter (sigma)
            // and cost per realisation; n needed ~ sigma^2 for a given interval width.
            let per3: Vec<f64> = k3
                .iter()
                .filter_map(|c| fit_window(&fs, c, glo, ghi).map(|x| x.0))
                .collect();
            let per1: Vec<f64> = k1
                .iter()
                .filter_map(|c| fit_window(&fs, c, glo, ghi).map(|x| x.0))
                .collect();
            let s3 = mrd::rough_contact::Stat::of(&per3).std;
            let s1 = mrd::rough_contact::Stat::of(&per1).std;
            let c3 = bem.iter().map(|c| c.seconds).sum::<f64>() / bem.len() as f64;
            let c1 = ens.seconds / ens.stiffness.len() as f64;
            if s3 > 0.0 && s1 > 0.0 && c1 > 0.0 {
                speedups.push(c3 * s3 * s3 / (c1 * s1 * s1));
            }
            for j in 0..nf {
                if let (Some(a), Some(b)) = (m3[j], m1[j]) {
                    let sd = |v: &Vec<Vec<Option<f64>>>| {
                        mrd::rough_contact::Stat::of(
                            &v.iter().filter_map(|c| c[j]).collect::<Vec<_>>(),
                        )
                        .ci95
                    };
                    curves_t.push(vec![
                        hurst,
                        fs[j],
                        a,
                        sd(&k3),
                        b,
                        sd(&k1),
                        (a >= glo && a <= ghi) as u8 as f64,
                    ]);
                }
            }
            let mut o = serde_json::Map::new();
            for (k, v) in [
                ("alpha_3d", a3),
                ("alpha_3d_lo95", ci_a3.0),
                ("alpha_3d_hi95", ci_a3.1),
                ("alpha_mrd", a1),
                ("alpha_mrd_lo95", ci_a1.0),
                ("alpha_mrd_hi95", ci_a1.1),
                ("zeta_3d", z3),
                ("zeta_3d_lo95", ci_z3.0),
                ("zeta_3d_hi95", ci_z3.1),
                ("zeta_mrd", z1),
                ("zeta_mrd_lo95", ci_z1.0),
                ("zeta_mrd_hi95", ci_z1.1),
                ("lambda", lam.unwrap_or(f64::NAN)),
                ("lambda_lo95", ci_l.0),
                ("lambda_hi95", ci_l.1),
            ] {
                if v.is_finite() {
                    o.insert(k.into(), serde_json::json!(v));
                }
            }
            o.insert(
                "unconverged_3d_solves".into(),
                serde_json::json!(bem.iter().map(|c| c.unconverged).sum::<usize>()),
            );
            per_h.insert(format!("{hurst}"), serde_json::Value::Object(o));
            // Per-H k(F) figure.
            let pts = |m: &[Option<f64>]| -> Vec<(f64, f64)> {
                fs.iter()
                    .zip(m)
                    .filter_map(|(&f, v)| v.map(|v| (f, v)))
                    .collect()
            };
            let mut fig = Figure::new(
                &format!("{label}_kf_h{hurst}"),
                &format!("k(F), H = {hurst} (Eq. 77)"),
                "F/(E* h L) [1]",
                "k/(E* L) [1]",
            )
            .with(Series::new(
                format!("3D BEM, {}^2, {} realisations", g, bem.len()),
                pts(&m3),
                Style::Crosses,
            ))
            .with(Series::new(
                format!("MRD, {} lines, lambda = pi", k1.len()),
                pts(&m1),
                Style::Line,
            ));
            // 95 % confidence bands of the 3D ensemble mean (mean +/- 1.96 s/sqrt(n)).
            let band = |sign: f64| -> Vec<(f64, f64)> {
                (0..nf)
                    .filter_map(|j| {
                        let v: Vec<f64> = k3.iter().filter_map(|c| c[j]).collect();
                        m3[j].map(|m| (fs[j], m + sign * mrd::rough_contact::Stat::of(&v).ci95))
                    })
                    .filter(|p| p.1 > 0.0)
                    .collect()
            };
            fig = fig
                .with(Series::new("3D mean +/- 95% CI", band(1.0), Style::Dashed).colored(0))
                .with(Series::new("", band(-1.0), Style::Dashed).colored(0));
            if let Some((a, z)) = fit3 {
                let w: Vec<(f64, f64)> = pts(&m3)
                    .into_iter()
                    .filter(|p| p.1 >= glo && p.1 <= ghi)
                    .map(|(f, _)| (f, z * f.powf(a)))
                    .collect();
                fig = fig.with(Series::new(
                    format!("3D fit window: alpha = {a:.3}"),
                    w,
                    Style::Dashed,
                ));
            }
            if let Some(l) = lam {
                let s = (PI / l).sqrt();
                let (f1, v1): (Vec<f64>, Vec<f64>) = fs
                    .iter()
                    .zip(&m1)
                    .filter_map(|(&f, &v)| v.map(|v| (f, v)))
                    .unzip();
                let shifted: Vec<(f64, f64)> = fs
                    .iter()
                    .filter_map(|&f| interp_loglog(&f1, &v1, f * s).map(|v| (f, v)))
                    .collect();
                fig = fig.with(Series::new(
                    format!("MRD with calibrated lambda = {l:.3}"),
                    shifted,
                    Style::Dashed,
                ));
            }
            fig.log_x = true;
            fig.log_y = true;
            kf_figs.push(fig);
        }
    }
    report.scalar(format!("{label}.wall_time_3d_s"), t3);
    report.scalar(format!("{label}.wall_time_mrd_s"), t1);
    report.scalar(format!("{label}.realisations_3d_total"), n3 as f64);
    report.scalar(format!("{label}.realisations_mrd_total"), n1 as f64);
    if !speedups.is_empty() {
        speedups.sort_by(f64::total_cmp);
        report.scalar(
            format!("{label}.mrd_speedup_at_equal_error_median"),
            speedups[speedups.len() / 2],
        );
    }
    report.scalars.insert(
        format!("{label}.per_hurst"),
        serde_json::Value::Object(per_h),
    );
    // Figures: alpha(H) in the style of Fig. 6, lambda(H), zeta(H).
    let col = |j: usize| -> Vec<(f64, f64)> {
        alpha_t
            .rows
            .iter()
            .filter(|r| r[j].is_finite())
            .map(|r| (r[0], r[j]))
            .collect()
    };
    let bars = |j: usize, lo: usize, hi: usize| -> Vec<(f64, f64, f64)> {
        alpha_t
            .rows
            .iter()
            .filter(|r| r[j].is_finite())
            .map(|r| (r[0], r[lo], r[hi]))
            .collect()
    };
    // Eq. (80) is drawn where it stays in the plotted range (H >= -0.2).
    let theory: Vec<(f64, f64)> = (0..=64)
        .map(|i| -0.2 + 3.2 * i as f64 / 64.0)
        .map(|h| (h, 1.0 / (1.0 + h)))
        .collect();
    let fig6 = Figure::new(
        &format!("{label}_fig6"),
        "Exponent alpha of Eq. (77) against the Hurst exponent (cf. Fig. 6)",
        "Hurst exponent H [1]",
        "alpha [1]",
    )
    .with(
        Series::new("3D boundary elements (95% CI)", col(1), Style::Crosses)
            .with_bars(bars(1, 2, 3)),
    )
    .with(Series::new("MRD (1D), lambda = pi", col(4), Style::Line))
    .with(Series::new("1/(1+H), Eq. (80)", theory, Style::Dashed));
    let lam_cut_pts: Vec<(f64, f64)> = (0..=70)
        .map(|i| -0.45 + 3.45 * i as f64 / 70.0)
        .map(|h| (h, lambda_cut(h).unwrap()))
        .collect();
    let mut figl = Figure::new(
        &format!("{label}_lambda"),
        "Calibrated lambda(H) of Eq. (76)",
        "Hurst exponent H [1]",
        "lambda [1]",
    )
    .with(
        Series::new("calibrated on 3D (95% CI)", col(14), Style::Crosses)
            .with_bars(bars(14, 15, 16)),
    )
    .with(Series::new(
        "pi (Eq. 73)",
        vec![(-1.0, PI), (3.0, PI)],
        Style::Dashed,
    ))
    .with(Series::new(
        "straight cut sqrt(pi) G(H+1/2)/G(H+1)",
        lam_cut_pts,
        Style::Line,
    ));
    figl.log_y = true;
    let figz = Figure::new(
        &format!("{label}_zeta"),
        "Prefactor zeta of Eq. (77)",
        "Hurst exponent H [1]",
        "zeta [1]",
    )
    .with(
        Series::new("3D boundary elements (95% CI)", col(8), Style::Crosses)
            .with_bars(bars(8, 9, 10)),
    )
    .with(Series::new("MRD (1D), lambda = pi", col(11), Style::Line));
    report.figures.extend([fig6, figl, figz]);
    report.figures.extend(kf_figs);
    // lambda(H) in the two-column form `mrd` loads (LambdaTable::from_csv; scene key
    // `lambda = "<file>"`), rows with a calibrated value only.
    let mut lam_t = Table::new(
        &format!("{label}_lambda_table"),
        &["hurst [1]".into(), "lambda [1]".into()],
    );
    lam_t.notes.push(format!(
        "calibrated lambda(H) of Eq. (76) on 3D {0}^2 circular rough punches ({1} realisations per H) against {2} MRD lines per H; load with lambda = \"<this file>\"",
        spec.grid, spec.realisations_3d, spec.realisations_1d
    ));
    for r in alpha_t.rows.iter().filter(|r| r[14].is_finite()) {
        lam_t.push(vec![r[0], r[14]]);
    }
    report.tables.push(alpha_t);
    report.tables.push(lam_t);
    report.tables.push(curves_t);
    if !conv_t.rows.is_empty() {
        let mut figc = Figure::new(
            &format!("{label}_convergence"),
            "Finite-size study: 3D alpha against system size (8 cells per shortest wavelength)",
            "grid cells across the punch, = 8 L / shortest wavelength [1]",
            "alpha_3d [1]",
        );
        for &hurst in &spec.hurst {
            let mut pts: Vec<(f64, f64)> = conv_t
                .rows
                .iter()
                .filter(|r| r[0] == hurst && r[3].is_finite())
                .map(|r| (r[1], r[3]))
                .collect();
            if let Some(main) = report_alpha(&report.tables, label, hurst) {
                pts.push((spec.grid as f64, main));
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            figc = figc.with(Series::new(format!("H = {hurst}"), pts, Style::Line));
        }
        report.figures.push(figc);
        report.tables.push(conv_t);
    }
    Ok(())
}

fn report_alpha(tables: &[Table], label: &str, hurst: f64) -> Option<f64> {
    tables
        .iter()
        .find(|t| t.name == format!("{label}_alpha"))?
        .rows
        .iter()
        .find(|r| r[0] == hurst)
        .map(|r| r[1])
}
