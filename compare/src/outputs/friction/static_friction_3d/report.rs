//! Ensemble curves, the fits of Eq. (91) with bootstrap intervals, the tables, the
//! refinement check and the figures.

use super::runs::{Point, Run3d};
use super::{Geometry, Refinement, StaticFriction3d, RESAMPLES};
use crate::experiment::lambda::LambdaSpec;
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::rough_contact::{fit_line, Stat};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Map, Value};

/// Both sides of one (geometry, H).
pub struct Case {
    pub geometry: Geometry,
    pub hurst: f64,
    pub runs_3d: Vec<Run3d>,
    /// Per lambda entry: its value at H and the lines.
    pub runs_1d: Vec<(f64, Vec<Vec<Point>>)>,
}

/// xi per realisation on the f grid (None: no converged solve there).
type Curves = Vec<Vec<Option<f64>>>;

/// The ensemble at one f: mean and 95 % half-width of xi, mean area and contacts.
#[derive(Debug, Clone, Copy)]
struct Level {
    xi: f64,
    ci: f64,
    area: f64,
    contacts: f64,
}

/// Ensemble levels on the f grid; None where fewer than 2 realisations have data.
fn levels(points: &[Vec<Option<Point>>], nf: usize) -> Vec<Option<Level>> {
    (0..nf)
        .map(|k| {
            let at: Vec<Point> = points.iter().filter_map(|p| p[k]).collect();
            if at.len() < 2 {
                return None;
            }
            let xi = Stat::of(&at.iter().map(|p| p.xi).collect::<Vec<_>>());
            let n = at.len() as f64;
            Some(Level {
                xi: xi.mean,
                ci: xi.ci95,
                area: at.iter().map(|p| p.area).sum::<f64>() / n,
                contacts: at.iter().map(|p| p.contacts).sum::<f64>() / n,
            })
        })
        .collect()
}

/// The ensemble levels of both sides of a case (MRD: one row per lambda entry).
struct Levels {
    l3: Vec<Option<Level>>,
    l1: Vec<Vec<Option<Level>>>,
}

impl Levels {
    fn of(case: &Case, nf: usize) -> Self {
        let p3: Vec<Vec<Option<Point>>> = case.runs_3d.iter().map(|r| r.points.clone()).collect();
        let l1 = case
            .runs_1d
            .iter()
            .map(|(_, lines)| {
                let p: Vec<Vec<Option<Point>>> = lines
                    .iter()
                    .map(|l| l.iter().map(|&p| Some(p)).collect())
                    .collect();
                levels(&p, nf)
            })
            .collect();
        Self {
            l3: levels(&p3, nf),
            l1,
        }
    }
}

/// xi = a + b ln f (Eq. 91) with 95 % percentile intervals over realisations.
#[derive(Debug, Clone, Copy)]
struct Fit {
    a: f64,
    b: f64,
    a95: (f64, f64),
    b95: (f64, f64),
}

fn fit_on(curves: &Curves, pick: &[usize], fit_at: &[usize], lnf: &[f64]) -> Option<(f64, f64)> {
    let x: Vec<f64> = fit_at.iter().map(|&k| lnf[k]).collect();
    let y: Vec<f64> = fit_at
        .iter()
        .map(|&k| pick.iter().filter_map(|&r| curves[r][k]).sum::<f64>() / pick.len() as f64)
        .collect();
    fit_line(&x, &y).ok().map(|f| (f.a, f.b))
}

fn percentile95(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((q * (v.len() - 1) as f64).round() as usize).min(v.len() - 1)];
    (at(0.025), at(0.975))
}

fn fit(curves: &Curves, fit_at: &[usize], lnf: &[f64], seed: u64) -> Option<Fit> {
    let n = curves.len();
    let all: Vec<usize> = (0..n).collect();
    let (a, b) = fit_on(curves, &all, fit_at, lnf)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut av, mut bv) = (Vec::new(), Vec::new());
    for _ in 0..RESAMPLES {
        let pick: Vec<usize> = (0..n).map(|_| rng.random_range(0..n)).collect();
        if let Some((ra, rb)) = fit_on(curves, &pick, fit_at, lnf) {
            av.push(ra);
            bv.push(rb);
        }
    }
    Some(Fit {
        a,
        b,
        a95: percentile95(av),
        b95: percentile95(bv),
    })
}

/// A lambda entry's name in column names and legends.
fn lambda_name(l: &LambdaSpec) -> String {
    match l {
        LambdaSpec::Value(v) => format!("{v}"),
        LambdaSpec::Named(s) => std::path::Path::new(s)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| s.clone()),
    }
}

fn columns(spec: &StaticFriction3d) -> Vec<String> {
    let mut c: Vec<String> = [
        "geometry [0 periodic; 1 disc]",
        "hurst [1]",
        "f = sqrt(pi) F/(2 E* h sqrt(A)) [1]",
        "xi_3d [1]",
        "xi_3d_ci95 [1]",
        "area_3d [A_real/A]",
        "contact_cells_3d [1]",
        "realisations_3d [count]",
    ]
    .map(String::from)
    .to_vec();
    for l in &spec.lambda {
        let n = lambda_name(l);
        c.push(format!("lambda_{n} [1]"));
        c.push(format!("xi_mrd_{n} [1]"));
        c.push(format!("xi_mrd_{n}_ci95 [1]"));
        c.push(format!("area_mrd_{n} [length fraction]"));
    }
    c
}

/// Everything the output reports.
pub fn report(
    spec: &StaticFriction3d,
    fs: &[f64],
    cases: &[Case],
    refined: Option<&(Refinement, usize, Vec<Run3d>)>,
    out: &mut Section,
) {
    let mut t = main_table(spec);
    let mut fits = fits_table(spec);
    let mut findings = Map::new();
    let mut figures: Vec<Figure> = Vec::new();
    for (ci, case) in cases.iter().enumerate() {
        let nf = fs.len();
        let lv = Levels::of(case, nf);
        let (l3, l1) = (&lv.l3, &lv.l1);
        let unconverged: usize = case.runs_3d.iter().map(|r| r.unconverged).sum();
        if unconverged > 0 {
            out.failures.push(format!(
                "{}, H = {}: {unconverged} 3D solves did not converge (left out)",
                case.geometry.name(),
                case.hurst
            ));
        }
        for k in 0..nf {
            let Some(a) = l3[k] else { continue };
            let mut row = vec![
                case.geometry.code(),
                case.hurst,
                fs[k],
                a.xi,
                a.ci,
                a.area,
                a.contacts,
                case.runs_3d
                    .iter()
                    .filter(|r| r.points[k].is_some())
                    .count() as f64,
            ];
            for (j, (lam, _)) in case.runs_1d.iter().enumerate() {
                let m = l1[j][k].expect("every line has every f");
                row.extend([*lam, m.xi, m.ci, m.area]);
            }
            t.push(row);
        }
        let mut found = fit_case(spec, (case, ci), fs, &lv, &mut fits, out);
        if let Some(first) = l3.iter().flatten().next() {
            found.insert("contact_cells_3d_at_f_min".into(), json!(first.contacts));
        }
        findings.insert(
            format!("{}_h{}", case.geometry.code(), case.hurst),
            Value::Object(found),
        );
        add_to_figure(spec, &mut figures, case, fs, &lv);
    }
    out.value("per_case", Value::Object(findings));
    if let Some((rf, k, fine)) = refined {
        refinement(spec, cases, rf, *k, fine, out);
    }
    out.tables.push(t);
    out.tables.push(fits);
    for mut f in figures {
        f.log_x = true;
        out.figures.push(f);
    }
}

fn main_table(spec: &StaticFriction3d) -> Table {
    let mut t = Table::new("static_friction_3d", &columns(spec));
    t.notes.push(format!(
        "Eq. (93) in 3D: self-affine surfaces, bandwidth L/lambda_min = {b}, {c} cells per shortest wavelength ({n}^2 cells, Eq. 85's cut-off at 1/10 of Nyquist for c = 20), {r3} realisations per (geometry, H), E* = 1, L = 1; xi = rms forward-difference |grad z| over the cells in contact / over A (Eqs. 86-89), h = rms height over A of each realisation; MRD: {r1} lines of length 2 sqrt(A/pi) with C1D = lambda q C2D (Eq. 76), same shortest wavelength and sampling, pressed with the force of the 3D system at f (3D ensemble's mean h); ci95 = 1.96 s/sqrt(n); solver tolerance {tol:e}",
        b = spec.bandwidth,
        c = spec.cells,
        n = spec.grid(spec.cells),
        r3 = spec.realisations_3d,
        r1 = spec.realisations_1d,
        tol = spec.tolerance,
    ));
    t
}

fn fits_table(spec: &StaticFriction3d) -> Table {
    let mut fits = Table::new(
        "static_friction_3d_fit",
        &[
            "geometry [0 periodic; 1 disc]",
            "hurst [1]",
            "lambda [1; 0 = 3D]",
            "a [1]",
            "a_lo95 [1]",
            "a_hi95 [1]",
            "b [1]",
            "b_lo95 [1]",
            "b_hi95 [1]",
            "max_rel_diff_vs_3d [1]",
            "fit_f_min [1]",
            "fit_f_max [1]",
        ],
    );
    fits.notes.push(format!(
        "xi = a + b ln f (Eq. 91), least squares on the ensemble means over the f points where every 3D realisation converged and the 3D contact fraction is below {}; 95 % percentile intervals from {RESAMPLES} bootstrap resamples of the realisations; max_rel_diff_vs_3d = max |xi_MRD / xi_3D - 1| over that range",
        spec.fit_max_area
    ));
    fits
}

/// The fits of Eq. (91) of one case, added to `fits`; its findings.
fn fit_case(
    spec: &StaticFriction3d,
    (case, ci): (&Case, usize),
    fs: &[f64],
    lv: &Levels,
    fits: &mut Table,
    out: &mut Section,
) -> Map<String, Value> {
    let (l3, l1) = (&lv.l3, &lv.l1);
    let (nf, lnf) = (fs.len(), fs.iter().map(|f| f.ln()).collect::<Vec<_>>());
    // The fit range: every realisation converged, sparse contact.
    let fit_at: Vec<usize> = (0..nf)
        .filter(|&k| {
            case.runs_3d.iter().all(|r| r.points[k].is_some())
                && l3[k].is_some_and(|l| l.area < spec.fit_max_area)
        })
        .collect();
    let curves3: Curves = case
        .runs_3d
        .iter()
        .map(|r| r.points.iter().map(|p| p.map(|p| p.xi)).collect())
        .collect();
    let seed = spec.seed ^ 0x93 ^ ((ci as u64) << 32);
    let mut found = Map::new();
    found.insert("geometry".into(), case.geometry.name().into());
    found.insert("hurst".into(), json!(case.hurst));
    if let Some(f3) = (fit_at.len() >= 3)
        .then(|| fit(&curves3, &fit_at, &lnf, seed))
        .flatten()
    {
        push_fit(fits, case, 0.0, &f3, 0.0, fs, &fit_at);
        found.insert("a_3d".into(), json!(f3.a));
        found.insert("b_3d".into(), json!(f3.b));
        found.insert("a_3d_95".into(), json!([f3.a95.0, f3.a95.1]));
        found.insert("b_3d_95".into(), json!([f3.b95.0, f3.b95.1]));
        for (j, (lam, lines)) in case.runs_1d.iter().enumerate() {
            let c1: Curves = lines
                .iter()
                .map(|l| l.iter().map(|p| Some(p.xi)).collect())
                .collect();
            let Some(f1) = fit(&c1, &fit_at, &lnf, seed ^ (j as u64 + 1)) else {
                continue;
            };
            let diff = fit_at
                .iter()
                .filter_map(|&k| Some((l1[j][k]?.xi / l3[k]?.xi - 1.0).abs()))
                .fold(0.0f64, f64::max);
            push_fit(fits, case, *lam, &f1, diff, fs, &fit_at);
            found.insert(
                format!("mrd_{}", lambda_name(&spec.lambda[j])),
                json!({"lambda": lam, "a": f1.a, "b": f1.b, "a_95": [f1.a95.0, f1.a95.1],
                       "b_95": [f1.b95.0, f1.b95.1], "max_rel_diff_vs_3d": diff}),
            );
        }
    } else {
        out.warn(format!(
            "{}, H = {}: fewer than 3 f points with sparse contact and every 3D solve converged: no fit",
            case.geometry.name(),
            case.hurst
        ));
    }
    found
}

fn push_fit(t: &mut Table, case: &Case, lam: f64, f: &Fit, diff: f64, fs: &[f64], at: &[usize]) {
    t.push(vec![
        case.geometry.code(),
        case.hurst,
        lam,
        f.a,
        f.a95.0,
        f.a95.1,
        f.b,
        f.b95.0,
        f.b95.1,
        diff,
        fs[at[0]],
        fs[*at.last().expect("a fit has points")],
    ]);
}

/// The grid refinement: the same surfaces with twice the cells per shortest wavelength
/// at one f; the change is paired (realisation by realisation).
fn refinement(
    spec: &StaticFriction3d,
    cases: &[Case],
    rf: &Refinement,
    k: usize,
    fine: &[Run3d],
    out: &mut Section,
) {
    let Some(case) = cases
        .iter()
        .find(|c| c.geometry == rf.geometry && c.hurst == rf.hurst)
    else {
        return;
    };
    let pairs: Vec<(f64, f64)> = case
        .runs_3d
        .iter()
        .zip(fine)
        .filter_map(|(c, f)| Some((c.points[k]?.xi, f.points[0]?.xi)))
        .collect();
    if pairs.len() < 2 {
        out.failures
            .push("refinement: fewer than 2 realisations converged on both grids".into());
        return;
    }
    let coarse = Stat::of(&pairs.iter().map(|p| p.0).collect::<Vec<_>>());
    let finer = Stat::of(&pairs.iter().map(|p| p.1).collect::<Vec<_>>());
    let change = Stat::of(&pairs.iter().map(|p| p.1 - p.0).collect::<Vec<_>>());
    out.scalar("refine_f", spec.f_grid()[k]);
    out.scalar("refine_cells", spec.cells as f64);
    out.scalar("refine_xi", coarse.mean);
    out.scalar("refine_xi_ci95", coarse.ci95);
    out.scalar("refine_xi_fine", finer.mean);
    out.scalar("refine_change", change.mean);
    out.scalar("refine_change_ci95", change.ci95);
    if change.mean.abs() > coarse.ci95 {
        out.warn(format!(
            "refinement: xi moves by {:.4} (+/- {:.4}) from {} to {} cells per shortest wavelength, more than its interval +/- {:.4}",
            change.mean,
            change.ci95,
            spec.cells,
            2 * spec.cells,
            coarse.ci95
        ));
    }
}

/// Adds a case's curves to its geometry's figure (one figure per geometry).
fn add_to_figure(
    spec: &StaticFriction3d,
    figures: &mut Vec<Figure>,
    case: &Case,
    fs: &[f64],
    lv: &Levels,
) {
    let (l3, l1) = (&lv.l3, &lv.l1);
    let name = match case.geometry {
        Geometry::Periodic => "static_friction_3d_periodic",
        Geometry::Disc => "static_friction_3d_disc",
    };
    if !figures.iter().any(|f| f.name == name) {
        figures.push(Figure::new(
            name,
            &format!(
                "Eq. (93), {} on {}^2 cells: 3D (95% CI) and MRD",
                case.geometry.name(),
                spec.grid(spec.cells)
            ),
            "f = sqrt(pi) F / (2 E* h sqrt(A)) [1]",
            "xi = grad z_cont / grad z [1]",
        ));
    }
    let fig = figures.iter_mut().find(|f| f.name == name).expect("added");
    let color = spec
        .hurst
        .iter()
        .position(|&h| h == case.hurst)
        .unwrap_or(0);
    let pts: Vec<(f64, f64, f64)> = (0..fs.len())
        .filter_map(|k| l3[k].map(|l| (fs[k], l.xi, l.ci)))
        .collect();
    fig.series.push(
        Series::new(
            format!("3D, H = {}", case.hurst),
            pts.iter().map(|p| (p.0, p.1)).collect(),
            Style::Crosses,
        )
        .with_bars(pts.iter().map(|p| (p.0, p.1 - p.2, p.1 + p.2)).collect())
        .colored(color),
    );
    for (j, (lam, _)) in case.runs_1d.iter().enumerate() {
        let line: Vec<(f64, f64)> = (0..fs.len())
            .filter_map(|k| l1[j][k].map(|l| (fs[k], l.xi)))
            .collect();
        let style = if j == 0 { Style::Line } else { Style::Dashed };
        fig.series.push(
            Series::new(
                format!(
                    "MRD, lambda = {} ({lam:.2}), H = {}",
                    lambda_name(&spec.lambda[j]),
                    case.hurst
                ),
                line,
                style,
            )
            .colored(color),
        );
    }
    if let Some([a, b, h]) = spec.paper {
        if h == case.hurst {
            // xi <= 1 far from the bound holds on both sides; the paper's law is drawn
            // where it stays below XI_DRAWN, and said under the axis where it does not.
            let law: Vec<(f64, f64)> = fs
                .iter()
                .map(|&f| (f, a + b * f.ln()))
                .filter(|p| p.1 <= XI_DRAWN)
                .collect();
            if law.is_empty() {
                let lowest = a + b * fs[0].ln();
                fig.x_label.push_str(&format!(
                    "; the paper's Eq. (92) at H = {h}: xi > {lowest:.2}, off the plot"
                ));
            } else {
                fig.series.push(
                    Series::new(
                        format!("paper, Eq. (92)-(93): xi = {a} + {b} ln f (H = {h})"),
                        law,
                        Style::Dashed,
                    )
                    .colored(spec.hurst.len() + 1),
                );
            }
        }
    }
}

/// Largest xi a figure draws the paper's law at (xi -> 1 at complete contact).
const XI_DRAWN: f64 = 1.25;
