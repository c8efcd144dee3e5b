//! `mrdw bench report`: run time against error, as a report folder (CSV + PNG).
//!
//! Which method and which resolution buys what accuracy:
//! - axisymmetric cases with closed forms (Hertz, cone, flat punch, JKR pull-off,
//!   Cattaneo-Mindlin, Mindlin damping): relative error against wall time for MRD
//!   semi-analytic, MRD on N springs and (Hertz, cone, flat punch) the non-periodic 3D
//!   solver on n^2 cells, each ladder with its fitted order of convergence;
//! - rough contacts (no closed form): the error of the fitted alpha (Eq. 80) against a
//!   high-resolution, many-realisation reference of the same method, against total
//!   time, 3D and MRD at equal numbers of realisations ([`super::rough_ladder`]);
//! - scaling: time against problem size for each solver, with the fitted exponent.
//!
//! Times are medians of repeated runs (at least 3, or as many as fill a small budget)
//! with their min and max; every table records the machine, the tool version and the
//! exact command.

use super::common::{log_slope, reference_surface, timed, Options, Timing};
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace, SolverOptions};
use compare::error::{Context as _, Result};
use compare::report::figure::{Figure, Series, Style};
use compare::report::table::Table;
use compare::report::{Report, Section};
use mrd::adhesion::{simulate_cycle, AdhesiveContact, Control};
use mrd::discrete::DiscreteAxisymmetric;
use mrd::normal::AxisymmetricContact;
use mrd::oscillation::{dissipation_semi_analytic, OscillatingContact};
use mrd::reference as rf;
use mrd::tangential::TangentialContact;
use mrd::{Profile, Shape};
use std::f64::consts::PI;
use std::time::Instant;

/// One point of a ladder: resolution, time, error.
#[derive(Debug, Clone, Copy)]
pub struct Point {
    pub resolution: f64,
    pub time: Timing,
    pub error: f64,
}

/// A method's ladder of resolutions on one case.
#[derive(Debug, Clone)]
pub struct Ladder {
    pub case: &'static str,
    pub method: &'static str,
    /// What the resolution counts (springs, cells per side, -).
    pub resolution: &'static str,
    pub points: Vec<Point>,
}

/// Errors below this are rounding, not discretisation: left out of order fits.
const ROUNDING: f64 = 1e-12;

impl Ladder {
    /// Observed order of convergence: -d ln(error) / d ln(resolution) over the points
    /// whose error is above rounding.
    pub fn order(&self) -> Option<f64> {
        let pts: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| p.error > ROUNDING)
            .map(|p| (p.resolution, p.error))
            .collect();
        log_slope(&pts).map(|s| -s)
    }

    fn label(&self) -> String {
        let var = match self.resolution {
            "springs" => "N",
            _ => "n",
        };
        let what = match self.resolution {
            "springs" => "N springs",
            _ => "n^2 cells",
        };
        match self.order() {
            Some(o) if self.points.len() > 1 => {
                format!("{}: {what}, error ~ {var}^-{o:.2}", self.method)
            }
            _ if self.points.len() > 1 => format!("{}: {what}, exact", self.method),
            _ => self.method.to_string(),
        }
    }

    /// The coarsest rung whose error is at most `target` (rungs are in increasing
    /// resolution).
    fn cheapest(&self, target: f64) -> Option<&Point> {
        self.points.iter().find(|p| p.error <= target)
    }
}

/// Short key of a method for summary.json.
fn slug(method: &str) -> &'static str {
    match method {
        "MRD semi-analytic" => "semi",
        "MRD springs" => "springs",
        _ => "3d",
    }
}

fn rel(x: f64, reference: f64) -> f64 {
    // The error of an exact result is shown at the rounding floor, not as zero (log axes).
    ((x - reference) / reference).abs().max(1e-16)
}

const E: f64 = 1.0;

/// Spring ladder: 10^2 .. 10^5 (quick 10^4).
fn springs(o: Options) -> Vec<usize> {
    let top = if o.quick { 4 } else { 5 };
    (2..=top).map(|k| 10usize.pow(k)).collect()
}

/// Cells per side of the non-periodic 3D ladder.
fn grids(o: Options) -> Vec<usize> {
    if o.quick {
        vec![32, 64, 128]
    } else {
        vec![64, 128, 256, 512, 1024]
    }
}

fn budget(o: Options) -> f64 {
    if o.quick {
        0.02
    } else {
        0.2
    }
}

/// The one point of a semi-analytic method.
fn semi_analytic(case: &'static str, time: Timing, error: f64) -> Ladder {
    Ladder {
        case,
        method: "MRD semi-analytic",
        resolution: "-",
        points: vec![Point {
            resolution: 1.0,
            time,
            error,
        }],
    }
}

/// The rungs of a ladder: `value(n)` timed at each resolution n, its relative error
/// against `reference`.
fn rungs(
    resolutions: Vec<usize>,
    budget: f64,
    reference: f64,
    value: impl Fn(usize) -> Result<f64>,
) -> Result<Vec<Point>> {
    resolutions
        .into_iter()
        .map(|n| {
            let (t, v) = timed(budget, || value(n));
            Ok(Point {
                resolution: n as f64,
                time: t,
                error: rel(v?, reference),
            })
        })
        .collect()
}

/// A non-periodic 3D solve of heights h(x, y) (apex at the centre cell), under a mask
/// or not, at force `f` on the unit square: the approach from first contact.
fn solve_3d(
    n: usize,
    h: impl Fn(f64, f64) -> f64,
    mask_radius: Option<f64>,
    f: f64,
) -> Result<f64> {
    let dx = 1.0 / n as f64;
    let c = |k: usize| (k as f64 - (n / 2) as f64) * dx;
    let heights: Vec<f64> = (0..n * n).map(|k| h(c(k % n), c(k / n))).collect();
    let mask = mask_radius.map(|r| {
        (0..n * n)
            .map(|k| c(k % n).powi(2) + c(k / n).powi(2) <= r * r)
            .collect()
    });
    let opts = SolverOptions {
        tolerance: 1e-10,
        max_iterations: 20_000,
        ..Default::default()
    };
    let what = format!("3D benchmark solve on {n}^2 cells");
    let mut s = ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, E), &heights, mask)
        .ctx(what.clone())?;
    Ok(s.solve(Load::Force(f), &opts, None).ctx(what)?.approach)
}

/// The depth-at-given-force ladders of an indenter: semi-analytic, springs, 3D.
struct Indenter {
    case: &'static str,
    profile: Profile,
    /// 3D heights (peaks up) and optional punch mask radius.
    h3d: fn(f64, f64) -> f64,
    mask: Option<f64>,
    force: f64,
    depth: f64,
    /// Springs cover [-half_length, half_length] (the rim for a punch).
    half_length: f64,
}

fn indenter_ladders(ind: &Indenter, o: Options) -> Result<Vec<Ladder>> {
    let has_rim = ind.profile.rim().is_some();
    let semi = AxisymmetricContact::new(ind.profile.clone(), E).ctx(ind.case)?;
    let (t, d) = timed(budget(o), || semi.state_at_force(ind.force));
    let d = d.ctx(ind.case)?.depth;
    let mut out = vec![semi_analytic(ind.case, t, rel(d, ind.depth))];
    let points = rungs(springs(o), budget(o), ind.depth, |n| {
        let springs = DiscreteAxisymmetric::new(&ind.profile, E, n, ind.half_length);
        let state = springs.and_then(|s| s.state_at_force(ind.force, has_rim));
        Ok(state.ctx(format!("{}, {n} springs", ind.case))?.depth)
    })?;
    out.push(Ladder {
        case: ind.case,
        method: "MRD springs",
        resolution: "springs",
        points,
    });
    let points = rungs(grids(o), budget(o), ind.depth, |n| {
        solve_3d(n, ind.h3d, ind.mask, ind.force)
    })?;
    out.push(Ladder {
        case: ind.case,
        method: "3D non-periodic",
        resolution: "cells per side",
        points,
    });
    Ok(out)
}

/// Hertz, cone and flat punch: contact radius a = L/4 on the 3D grid.
fn indenters() -> Result<Vec<Indenter>> {
    let a = 0.25;
    let tan = 0.2;
    Ok(vec![
        Indenter {
            case: "hertz",
            profile: Profile::single(Shape::paraboloid(1.0).ctx("hertz")?),
            h3d: |x, y| -(x * x + y * y) / 2.0,
            mask: None,
            force: rf::hertz::force(E, 1.0, a * a),
            depth: a * a,
            half_length: 1.5 * a,
        },
        Indenter {
            case: "cone",
            profile: Profile::single(Shape::cone(tan).ctx("cone")?),
            h3d: |x, y| -0.2 * (x * x + y * y).sqrt(),
            mask: None,
            force: PI / 2.0 * E * tan * a * a,
            depth: PI / 2.0 * a * tan,
            half_length: 1.5 * a,
        },
        Indenter {
            case: "flat_punch",
            profile: Profile::flat_punch(a).ctx("flat punch")?,
            h3d: |_, _| 0.0,
            mask: Some(a),
            force: 1e-3,
            depth: 1e-3 / (2.0 * a * E),
            half_length: a,
        },
    ])
}

/// JKR pull-off under force control: semi-analytic and event-driven springs.
fn jkr_ladders(o: Options) -> Result<Vec<Ladder>> {
    let (r, gamma, a_max) = (1.0, 1e-3, 0.5);
    let reference = -rf::jkr::pull_off_force_control(r, gamma);
    let sphere = Profile::single(Shape::paraboloid(r).ctx("jkr")?);
    let adh = AxisymmetricContact::new(sphere, E).and_then(|c| AdhesiveContact::new(c, gamma));
    let adh = adh.ctx("jkr")?;
    let (t, p) = timed(budget(o), || adh.pull_off(a_max, Control::Force));
    let semi = semi_analytic("jkr", t, rel(p.ctx("jkr pull-off")?.force, reference));
    let d_max = adh.depth_at_radius(a_max).ctx("jkr")?;
    let points = rungs(springs(o), budget(o), reference, |n| {
        let cycle = simulate_cycle(&adh, n / 2, 1.5 * a_max, d_max, Control::Force);
        Ok(cycle.ctx(format!("jkr, {n} springs"))?.pull_off.force)
    })?;
    Ok(vec![
        semi,
        Ladder {
            case: "jkr",
            method: "MRD springs",
            resolution: "springs",
            points,
        },
    ])
}

/// Cattaneo-Mindlin (displacement at F_x = mu F_N / 2) and Mindlin's damping
/// (dissipation per cycle at A = A_c0 / 2).
fn tangential_ladders(o: Options) -> Result<Vec<Ladder>> {
    let (r, g, mu, d) = (1.0, 0.8, 0.3, 0.01);
    let sphere = Profile::single(Shape::paraboloid(r).ctx("cattaneo_mindlin")?);
    let contact = AxisymmetricContact::new(sphere.clone(), E).ctx("cattaneo_mindlin")?;
    let fn_ = rf::hertz::force(E, r, d);
    let fx = 0.5 * mu * fn_;
    let u_ref = rf::cattaneo_mindlin::displacement(mu, E, g, d, fx, fn_);
    let (t, u) = timed(budget(o), || {
        TangentialContact::new(contact.clone(), g, mu, fn_).and_then(|c| c.at_force(fx))
    });
    let u = u.ctx("cattaneo_mindlin")?.displacement;
    let cm = semi_analytic("cattaneo_mindlin", t, rel(u, u_ref));
    let beta = E / g;
    let amp = 0.5 * mu * beta * d;
    let w_ref = rf::mindlin_damping::dissipation_exact(E, beta, r, mu, d, amp);
    let (t, w) = timed(budget(o), || {
        dissipation_semi_analytic(&sphere, E, g, mu, d, amp)
    });
    let semi = semi_analytic("damping", t, rel(w.ctx("damping")?, w_ref));
    let a = rf::hertz::radius(r, d);
    let points = rungs(springs(o), budget(o), w_ref, |n| {
        let springs = OscillatingContact::new(&sphere, E, g, mu, d, n / 2, 1.2 * a);
        let cycle = springs.and_then(|s| s.simulate(amp, 2, 8));
        Ok(cycle.ctx(format!("damping, {n} springs"))?.dissipation)
    })?;
    Ok(vec![
        cm,
        semi,
        Ladder {
            case: "damping",
            method: "MRD springs",
            resolution: "springs",
            points,
        },
    ])
}

/// Every axisymmetric ladder.
pub fn axisymmetric(o: Options) -> Result<Vec<Ladder>> {
    let mut all = Vec::new();
    for ind in indenters()? {
        all.extend(indenter_ladders(&ind, o)?);
    }
    all.extend(jkr_ladders(o)?);
    all.extend(tangential_ladders(o)?);
    Ok(all)
}

/// Time against problem size for one solver.
#[derive(Debug, Clone)]
pub struct Scaling {
    pub solver: &'static str,
    /// What the size counts.
    pub size: &'static str,
    pub points: Vec<(f64, Timing)>,
}

impl Scaling {
    pub fn exponent(&self) -> Option<f64> {
        let pts: Vec<(f64, f64)> = self.points.iter().map(|(n, t)| (*n, t.median)).collect();
        // The smallest sizes are dominated by fixed costs: fit the upper two thirds.
        let skip = pts.len() / 3;
        log_slope(&pts[skip..])
    }
}

/// Scaling ladders: MRD springs (set-up and one force-controlled solve), rough lines
/// (synthesis, set-up, 100 k(F) points), the periodic and non-periodic 3D solvers.
pub fn scaling(o: Options) -> Result<Vec<Scaling>> {
    use mrd::rough_contact::RoughLine;
    use mrd::roughness::synthesis::{line, Amplitudes};
    use mrd::roughness::SelfAffine;
    let b = budget(o);
    let top = if o.quick { 5 } else { 7 };
    let sphere = Profile::single(Shape::paraboloid(1.0).ctx("scaling")?);
    let f = rf::hertz::force(E, 1.0, 0.01);
    let springs_pts = (3..=top)
        .map(|k| {
            let n = 10usize.pow(k);
            let (t, state) = timed(b, || {
                DiscreteAxisymmetric::new(&sphere, E, n, 0.12)
                    .and_then(|s| s.state_at_force(f, false))
            });
            state.ctx(format!("scaling, {n} springs"))?;
            Ok((n as f64, t))
        })
        .collect::<Result<_>>()?;
    let rough_pts = (3..=top)
        .map(|k| {
            let n = 10usize.pow(k);
            let spec = SelfAffine::new(0.7, 2.0 * PI, 2.0 * PI, PI * n as f64 * 0.5)
                .and_then(|s| s.to_line(PI).with_rms_height(1.0))
                .ctx("scaling, rough line")?;
            let (t, k) = timed(b, || {
                let h = line(&spec, n, 1.0, 1, 0, Amplitudes::Deterministic)?;
                let rl = RoughLine::new(&h, 1.0, 1.0)?;
                mrd::friction::log_space(1e-6, 1e-1, 100)
                    .iter()
                    .map(|&f| rl.at_force(f).map(|s| s.stiffness))
                    .sum::<std::result::Result<f64, _>>()
            });
            k.ctx(format!("scaling, rough line of {n} points"))?;
            Ok((n as f64, t))
        })
        .collect::<Result<_>>()?;
    let grid_top = if o.quick { 128 } else { 1024 };
    let periodic_pts = std::iter::successors(Some(32usize), |n| Some(n * 2))
        .take_while(|&n| n <= grid_top)
        .map(|n| {
            let h = reference_surface(n).ctx("scaling, reference surface")?;
            let opts = SolverOptions {
                tolerance: 1e-10,
                max_iterations: 20_000,
                ..Default::default()
            };
            let (t, sol) = timed(b, || {
                ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, E), &h, None)
                    .and_then(|mut s| s.solve(Load::MeanPressure(0.01), &opts, None))
            });
            sol.ctx(format!("scaling, periodic {n}^2"))?;
            Ok(((n * n) as f64, t))
        })
        .collect::<Result<_>>()?;
    let hertz_pts = std::iter::successors(Some(32usize), |n| Some(n * 2))
        .take_while(|&n| n <= grid_top)
        .map(|n| {
            let force = rf::hertz::force(E, 1.0, 1.0 / 16.0);
            let (t, d) = timed(b, || {
                solve_3d(n, |x, y| -(x * x + y * y) / 2.0, None, force)
            });
            d?;
            Ok(((n * n) as f64, t))
        })
        .collect::<Result<_>>()?;
    Ok(vec![
        Scaling {
            solver: "MRD springs (set-up + solve)",
            size: "springs",
            points: springs_pts,
        },
        Scaling {
            solver: "MRD rough line (synthesis + 100 k(F))",
            size: "points",
            points: rough_pts,
        },
        Scaling {
            solver: "3D periodic rough (0.01 E*)",
            size: "cells",
            points: periodic_pts,
        },
        Scaling {
            solver: "3D non-periodic Hertz",
            size: "cells",
            points: hertz_pts,
        },
    ])
}

/// Header notes of every table: machine, tool, command.
fn provenance_notes(command: &str) -> Vec<String> {
    vec![
        format!(
            "machine: {} ({} threads in use, {} cores available)",
            sysmem::cpu_model(),
            rayon::current_num_threads(),
            std::thread::available_parallelism().map_or(0, |n| n.get())
        ),
        format!("command: {command}"),
        "time: median of repeated runs (at least 3), with min and max".into(),
    ]
}

fn ladder_table(ladders: &[Ladder], command: &str) -> Table {
    let cols = [
        "case_id [-]",
        "method_id [-]",
        "resolution [-]",
        "time_median [s]",
        "time_min [s]",
        "time_max [s]",
        "runs [-]",
        "relative_error [1]",
        "order [1]",
    ];
    let mut t = Table::new("bench_error_time", &cols);
    t.notes = provenance_notes(command);
    t.missing_ok = true;
    let (cases, methods) = ids(ladders);
    t.notes.push(format!(
        "case_id: {}",
        cases
            .iter()
            .enumerate()
            .map(|(i, c)| format!("{i} = {c}"))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    t.notes.push(format!(
        "method_id: {}; resolution: springs (MRD springs), cells per side (3D), 1 (semi-analytic)",
        methods
            .iter()
            .enumerate()
            .map(|(i, m)| format!("{i} = {m}"))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    t.notes.push("relative_error: Hertz, cone, flat punch: depth at a given force (a = L/4 in 3D); jkr: pull-off force (force control); cattaneo_mindlin: displacement at F_x = mu F_N / 2; damping: dissipation per cycle at A = A_c0 / 2 (springs: 2 cycles of 8 steps, the second reported); exact results are shown at 1e-16".into());
    for l in ladders {
        let ci = cases.iter().position(|c| *c == l.case).unwrap_or(0) as f64;
        let mi = methods.iter().position(|m| *m == l.method).unwrap_or(0) as f64;
        let order = l.order().filter(|_| l.points.len() > 1).unwrap_or(f64::NAN);
        for p in &l.points {
            t.push(vec![
                ci,
                mi,
                p.resolution,
                p.time.median,
                p.time.min,
                p.time.max,
                p.time.runs as f64,
                p.error,
                order,
            ]);
        }
    }
    t
}

fn ids(ladders: &[Ladder]) -> (Vec<&'static str>, Vec<&'static str>) {
    let mut cases: Vec<&'static str> = Vec::new();
    let mut methods: Vec<&'static str> = Vec::new();
    for l in ladders {
        if !cases.contains(&l.case) {
            cases.push(l.case);
        }
        if !methods.contains(&l.method) {
            methods.push(l.method);
        }
    }
    (cases, methods)
}

fn case_title(case: &str) -> &'static str {
    match case {
        "hertz" => "Hertz sphere: depth at given force, relative error vs time",
        "cone" => "Cone: depth at given force, relative error vs time",
        "flat_punch" => "Flat punch: depth at given force, relative error vs time",
        "jkr" => "JKR sphere: pull-off force, relative error vs time",
        "cattaneo_mindlin" => "Cattaneo-Mindlin: displacement, relative error vs time",
        _ => "Mindlin damping: dissipation per cycle, relative error vs time",
    }
}

fn error_figures(ladders: &[Ladder]) -> Vec<Figure> {
    let (cases, _) = ids(ladders);
    // Cattaneo-Mindlin has one method and one point: drawn with damping (same
    // loading, same sphere) rather than alone.
    let mut figs = Vec::new();
    for case in cases.iter().filter(|c| **c != "cattaneo_mindlin") {
        let mut fig = Figure::new(
            &format!("bench_{case}"),
            case_title(case),
            "wall time [s]",
            "relative error [1]",
        )
        .log_log();
        let members: Vec<&Ladder> = ladders
            .iter()
            .filter(|l| l.case == *case || (*case == "damping" && l.case == "cattaneo_mindlin"))
            .collect();
        for (i, l) in members.iter().enumerate() {
            let pts: Vec<(f64, f64)> = l.points.iter().map(|p| (p.time.median, p.error)).collect();
            let label = if l.case == "cattaneo_mindlin" {
                format!("Cattaneo-Mindlin displacement, {}", l.method)
            } else {
                l.label()
            };
            let style = if pts.len() > 1 {
                Style::Line
            } else {
                Style::Markers
            };
            let bars: Vec<(f64, f64, f64)> = Vec::new();
            fig = fig.with(
                Series::new(label, pts.clone(), style)
                    .colored(i)
                    .with_bars(bars),
            );
            if pts.len() > 1 {
                fig = fig.with(Series::new("", pts, Style::Markers).colored(i));
            }
        }
        figs.push(fig);
    }
    figs
}

fn scaling_table(sc: &[Scaling], command: &str) -> Table {
    let cols = [
        "solver_id [-]",
        "size [-]",
        "time_median [s]",
        "time_min [s]",
        "time_max [s]",
        "runs [-]",
        "exponent [1]",
    ];
    let mut t = Table::new("bench_scaling", &cols);
    t.notes = provenance_notes(command);
    t.missing_ok = true;
    t.notes.push(format!(
        "solver_id: {}; exponent: slope of ln(time) against ln(size) over the upper two thirds of the sizes",
        sc.iter()
            .enumerate()
            .map(|(i, s)| format!("{i} = {} (size: {})", s.solver, s.size))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    for (i, s) in sc.iter().enumerate() {
        let e = s.exponent().unwrap_or(f64::NAN);
        for (n, tm) in &s.points {
            t.push(vec![
                i as f64,
                *n,
                tm.median,
                tm.min,
                tm.max,
                tm.runs as f64,
                e,
            ]);
        }
    }
    t
}

fn scaling_figure(sc: &[Scaling]) -> Figure {
    let mut fig = Figure::new(
        "bench_scaling",
        "Time against problem size (fitted exponent of size)",
        "problem size (springs, points or cells) [-]",
        "wall time [s]",
    )
    .log_log();
    for (i, s) in sc.iter().enumerate() {
        let pts: Vec<(f64, f64)> = s.points.iter().map(|(n, t)| (*n, t.median)).collect();
        let bars = s.points.iter().map(|(n, t)| (*n, t.min, t.max)).collect();
        let label = match s.exponent() {
            Some(e) => format!("{} (exponent {e:.2})", s.solver),
            None => s.solver.to_string(),
        };
        fig = fig
            .with(
                Series::new(label, pts.clone(), Style::Line)
                    .colored(i)
                    .with_bars(bars),
            )
            .with(Series::new("", pts, Style::Markers).colored(i));
    }
    fig
}

fn seconds(t: f64) -> String {
    if t < 1e-6 {
        format!("{:.0} ns", t * 1e9)
    } else if t < 1e-3 {
        format!("{:.1} us", t * 1e6)
    } else if t < 1.0 {
        format!("{:.1} ms", t * 1e3)
    } else {
        format!("{t:.2} s")
    }
}

/// The README's table: per case and method, the coarsest tested resolution that meets
/// 1 % and 1e-4, with its time.
fn conclusions(ladders: &[Ladder], command: &str) -> String {
    let mut md = format!(
        "<!-- generated by `{command}` on {} -->\n\n| case | method | error <= 1e-2 | error <= 1e-4 |\n|---|---|---|---|\n",
        sysmem::cpu_model()
    );
    for l in ladders {
        let cell = |target: f64| match l.cheapest(target) {
            None => "not reached".to_string(),
            Some(p) if l.points.len() == 1 => seconds(p.time.median),
            Some(p) => match l.resolution {
                "springs" => format!("{} springs, {}", p.resolution, seconds(p.time.median)),
                _ => format!("{}^2 cells, {}", p.resolution, seconds(p.time.median)),
            },
        };
        md.push_str(&format!(
            "| {} | {} | {} | {} |\n",
            l.case,
            l.method,
            cell(1e-2),
            cell(1e-4)
        ));
    }
    md
}

/// Runs the benchmark report: one section, its tables and figures.
pub fn run(o: Options, command: &str, progress: &mut dyn FnMut(&str)) -> Result<Report> {
    let mut sec = Section::new("bench_report", "bench");
    progress("axisymmetric cases (MRD semi-analytic, springs, 3D)");
    let ladders = axisymmetric(o)?;
    progress("rough contacts (alpha, 3D and MRD)");
    let rough = super::rough_ladder::run(o)?;
    progress("scaling");
    let sc = scaling(o)?;
    sec.tables.push(ladder_table(&ladders, command));
    sec.files.push((
        "bench_summary.md".into(),
        conclusions(&ladders, command).into_bytes(),
    ));
    sec.figures.extend(error_figures(&ladders));
    for l in &ladders {
        if let (Some(order), true) = (l.order(), l.points.len() > 1) {
            sec.scalar(format!("order_{}_{}", l.case, slug(l.method)), order);
        }
    }
    rough.report(&mut sec, &provenance_notes(command));
    sec.tables.push(scaling_table(&sc, command));
    sec.figures.push(scaling_figure(&sc));
    for (s, key) in sc
        .iter()
        .zip(["springs", "rough_line", "3d_periodic", "3d_hertz"])
    {
        if let Some(e) = s.exponent() {
            sec.scalar(format!("exponent_{key}"), e);
        }
    }
    Ok(Report {
        plan: Default::default(),
        sections: vec![sec],
    })
}

/// Runs the report and writes it into `out` (a new folder, an empty one or a report
/// folder mrdw wrote: the rules of `mrdw run --out`); returns the files written.
pub fn write(
    o: Options,
    command: &str,
    out: &std::path::Path,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<std::path::PathBuf>> {
    let t0 = Instant::now();
    let dest = compare::report::write::Destination::claim(out)?;
    let report = run(o, command, progress)?;
    let prov = compare::report::Provenance {
        tool: compare::run::tool_version(),
        scene_name: if o.quick { "bench-quick" } else { "bench" }.into(),
        scene_origin: command.into(),
        scene_text: String::new(),
        seed: Some(2026),
    };
    dest.write_report(&report, &prov, t0.elapsed().as_secs_f64())
}
