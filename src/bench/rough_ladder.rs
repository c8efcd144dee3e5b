//! Rough contacts in the benchmark report: no closed form exists, so the error of the
//! fitted exponent alpha of k ~ F^alpha (Eq. 80) is measured against a high-resolution,
//! many-realisation reference of the same method, as a function of total time.
//!
//! The experiment is the rough punch of the Hurst sweep (Fig. 6) at H = 0.7, run as a
//! `hurst_sweep` scene per rung: 3D on n^2 cells with R surfaces, MRD on 16 n points with
//! R lines (equal numbers of realisations). Rungs raise n and R together; the error of a
//! rung mixes discretisation and sampling, which is what a user buys with time. The
//! MRD speed-up at equal error interpolates MRD's time-error ladder at the 3D rungs'
//! errors (log-log); the interval given is the range over the rungs where both ladders
//! overlap.

use super::common::{log_slope, Options};
use compare::error::{CompareError, Result};
use compare::report::figure::{Figure, Series, Style};
use compare::report::table::Table;
use compare::report::Section;
use compare::scene::Scene;

const HURST: f64 = 0.7;

/// MRD points per line for each cell along the 3D grid's side.
const POINTS_1D: usize = 16;

/// One hurst_sweep run: alpha (with its 95 % interval) and the time of each side.
#[derive(Debug, Clone, Copy)]
struct Sweep {
    alpha_3d: [f64; 3],
    alpha_mrd: [f64; 3],
    seconds_3d: f64,
    seconds_mrd: f64,
}

fn sweep(grid: usize, r3: usize, r1: usize, loads: usize) -> Result<Sweep> {
    let text = format!(
        "name = \"bench-rough\"\n[units]\nlength = \"1\"\nstress = \"1\"\n[material]\ne_star = 1.0\n\
         [[outputs]]\nkind = \"hurst_sweep\"\nhurst = [{HURST}]\ngrid = {grid}\n\
         realisations_3d = {r3}\nrealisations_1d = {r1}\npoints_1d_factor = {POINTS_1D}\n\
         loads = {loads}\nseed = 2026\n"
    );
    let scene = Scene::parse(&text, "<bench report>", None)?;
    let report = compare::run::run(&scene)?;
    let table = report
        .tables()
        .find(|t| t.name == "hurst_sweep_alpha")
        .ok_or_else(|| CompareError::Internal("hurst_sweep wrote no alpha table".into()))?;
    let col = |name: &str| table.column(name)[0];
    let results = report.results();
    let num = |key: &str| {
        results
            .get(&format!("hurst_sweep.{key}"))
            .and_then(|v| v.as_f64())
            .ok_or_else(|| CompareError::Internal(format!("hurst_sweep has no {key}")))
    };
    Ok(Sweep {
        alpha_3d: [col("alpha_3d"), col("alpha_3d_lo95"), col("alpha_3d_hi95")],
        alpha_mrd: [
            col("alpha_mrd"),
            col("alpha_mrd_lo95"),
            col("alpha_mrd_hi95"),
        ],
        seconds_3d: num("cpu_time_3d_s")?,
        seconds_mrd: num("cpu_time_mrd_s")?,
    })
}

/// One rung: resolution n, realisations R, alpha and its error for each method.
#[derive(Debug, Clone, Copy)]
struct Rung {
    grid: usize,
    realisations: usize,
    sweep: Sweep,
}

/// The rough ladders and their references.
pub struct RoughLadder {
    rungs: Vec<Rung>,
    /// ([alpha, lo95, hi95], seconds, grid or points, realisations) of each reference.
    ref_3d: ([f64; 3], f64, usize, usize),
    ref_mrd: ([f64; 3], f64, usize, usize),
}

/// Rungs (grid, realisations) and the reference (grid, 3D surfaces, MRD lines): the
/// reference shares the largest band (the band's upper cut-off follows the grid).
fn plan(o: Options) -> (Vec<(usize, usize)>, (usize, usize, usize)) {
    if o.quick {
        (vec![(32, 2), (48, 3), (64, 4)], (128, 8, 400))
    } else {
        (vec![(32, 2), (64, 4), (128, 8), (256, 8)], (512, 16, 2000))
    }
}

pub fn run(o: Options) -> Result<RoughLadder> {
    let loads = if o.quick { 10 } else { 20 };
    let (rungs_plan, (g, r3, r1)) = plan(o);
    let mut rungs = Vec::new();
    for (grid, r) in rungs_plan {
        rungs.push(Rung {
            grid,
            realisations: r,
            sweep: sweep(grid, r, r, loads)?,
        });
    }
    let reference = sweep(g, r3, r1, loads)?;
    Ok(RoughLadder {
        rungs,
        ref_3d: (reference.alpha_3d, reference.seconds_3d, g, r3),
        ref_mrd: (
            reference.alpha_mrd,
            reference.seconds_mrd,
            g * POINTS_1D,
            r1,
        ),
    })
}

impl RoughLadder {
    /// Error bars of each rung for one method: its error -/+ the half-width of its own
    /// 95 % interval of alpha (the lower end held at 1e-3 on the log axis).
    fn bars(&self, mrd: bool) -> Vec<(f64, f64, f64)> {
        self.errors(mrd)
            .into_iter()
            .zip(&self.rungs)
            .map(|((t, e), r)| {
                let a = if mrd {
                    r.sweep.alpha_mrd
                } else {
                    r.sweep.alpha_3d
                };
                let hw = (a[2] - a[1]) / 2.0;
                (t, (e - hw).max(1e-3), e + hw)
            })
            .collect()
    }

    /// (time, error) of each rung for one method.
    fn errors(&self, mrd: bool) -> Vec<(f64, f64)> {
        self.rungs
            .iter()
            .map(|r| {
                if mrd {
                    (
                        r.sweep.seconds_mrd,
                        (r.sweep.alpha_mrd[0] - self.ref_mrd.0[0]).abs(),
                    )
                } else {
                    (
                        r.sweep.seconds_3d,
                        (r.sweep.alpha_3d[0] - self.ref_3d.0[0]).abs(),
                    )
                }
            })
            .collect()
    }

    /// MRD's time at each 3D rung's error, interpolated log-log along MRD's ladder
    /// (sorted by error); the ratio 3D time / MRD time where the error lies inside
    /// MRD's range.
    pub fn speedups(&self) -> Vec<f64> {
        let mut m = self.errors(true);
        m.retain(|p| p.1 > 0.0);
        m.sort_by(|a, b| b.1.total_cmp(&a.1));
        let mut out = Vec::new();
        for (t3, e3) in self.errors(false) {
            for w in m.windows(2) {
                let ((ta, ea), (tb, eb)) = (w[0], w[1]);
                if e3 <= ea && e3 >= eb && ea > eb {
                    let s = (e3.ln() - ea.ln()) / (eb.ln() - ea.ln());
                    let t = (ta.ln() + s * (tb.ln() - ta.ln())).exp();
                    out.push(t3 / t);
                    break;
                }
            }
        }
        out
    }

    pub fn report(&self, sec: &mut Section, notes: &[String]) {
        let cols = [
            "method_id [-]",
            "grid [-]",
            "points_1d [-]",
            "realisations [-]",
            "time [s]",
            "alpha [1]",
            "alpha_lo95 [1]",
            "alpha_hi95 [1]",
            "alpha_error [1]",
            "reference [-]",
        ];
        let mut t = Table::new("bench_rough", &cols);
        t.notes = notes.to_vec();
        t.notes.push(format!(
            "rough punch of the Hurst sweep at H = {HURST} (hurst_sweep scenes, seed 2026): method_id 0 = 3D (grid^2 cells), 1 = MRD ({POINTS_1D} grid points per line); alpha_error = |alpha - alpha of the reference row| (reference = 1); time: that method's task time in the sweep (synthesis, solves and stiffness of every realisation, summed over threads: CPU seconds)"
        ));
        for r in &self.rungs {
            let s = &r.sweep;
            let e3 = (s.alpha_3d[0] - self.ref_3d.0[0]).abs();
            let e1 = (s.alpha_mrd[0] - self.ref_mrd.0[0]).abs();
            t.push(vec![
                0.0,
                r.grid as f64,
                0.0,
                r.realisations as f64,
                s.seconds_3d,
                s.alpha_3d[0],
                s.alpha_3d[1],
                s.alpha_3d[2],
                e3,
                0.0,
            ]);
            t.push(vec![
                1.0,
                r.grid as f64,
                (POINTS_1D * r.grid) as f64,
                r.realisations as f64,
                s.seconds_mrd,
                s.alpha_mrd[0],
                s.alpha_mrd[1],
                s.alpha_mrd[2],
                e1,
                0.0,
            ]);
        }
        let (a3, t3, g3, r3) = self.ref_3d;
        let (a1, t1, n1, r1) = self.ref_mrd;
        t.push(vec![
            0.0, g3 as f64, 0.0, r3 as f64, t3, a3[0], a3[1], a3[2], 0.0, 1.0,
        ]);
        t.push(vec![
            1.0,
            (n1 / POINTS_1D) as f64,
            n1 as f64,
            r1 as f64,
            t1,
            a1[0],
            a1[1],
            a1[2],
            0.0,
            1.0,
        ]);
        sec.tables.push(t);

        let mut fig = Figure::new(
            "bench_rough",
            &format!("Rough punch, H = {HURST}: error of alpha vs time (bars: each rung's 95 % interval)"),
            "task time, summed over threads [s]",
            "|alpha - alpha_reference| [1]",
        )
        .log_log();
        for (i, (mrd, name)) in [
            (false, "3D (n^2 cells, R surfaces)"),
            (true, "MRD (16 n points, R lines)"),
        ]
        .into_iter()
        .enumerate()
        {
            let pts: Vec<(f64, f64)> = self.errors(mrd).into_iter().filter(|p| p.1 > 0.0).collect();
            let (half, ci) = if mrd { (a1, "MRD") } else { (a3, "3D") };
            let label = format!(
                "{name}; reference 95 % half-width {:.3} ({ci})",
                (half[2] - half[1]) / 2.0
            );
            fig = fig
                .with(
                    Series::new(label, pts.clone(), Style::Line)
                        .colored(i)
                        .with_bars(self.bars(mrd)),
                )
                .with(Series::new("", pts, Style::Markers).colored(i));
        }
        sec.figures.push(fig);

        let sp = self.speedups();
        sec.scalar("rough_alpha_reference_3d", a3[0]);
        sec.scalar("rough_alpha_reference_mrd", a1[0]);
        if let (Some(lo), Some(hi)) = (
            sp.iter().copied().reduce(f64::min),
            sp.iter().copied().reduce(f64::max),
        ) {
            sec.scalar("rough_mrd_speedup_min", lo);
            sec.scalar("rough_mrd_speedup_max", hi);
        }
        let slope = |mrd: bool| log_slope(&self.errors(mrd));
        if let Some(s) = slope(false) {
            sec.scalar("rough_error_time_slope_3d", s);
        }
        if let Some(s) = slope(true) {
            sec.scalar("rough_error_time_slope_mrd", s);
        }
        // The same against the work (cells or points times realisations): free of
        // timing noise, which sub-millisecond MRD rungs are not.
        let work_slope = |mrd: bool| {
            let pts: Vec<(f64, f64)> = self
                .errors(mrd)
                .into_iter()
                .zip(&self.rungs)
                .map(|((_, e), r)| {
                    let size = if mrd {
                        (POINTS_1D * r.grid) as f64
                    } else {
                        (r.grid * r.grid) as f64
                    };
                    (size * r.realisations as f64, e)
                })
                .collect();
            log_slope(&pts)
        };
        if let Some(s) = work_slope(false) {
            sec.scalar("rough_error_work_slope_3d", s);
        }
        if let Some(s) = work_slope(true) {
            sec.scalar("rough_error_work_slope_mrd", s);
        }
    }
}
