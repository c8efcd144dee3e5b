//! Ensemble statistics of both sides, the comparison tables, the scalars and figures.

use super::figures::*;
use super::quantity::{Quantity, ZERO};
use super::runs::{Case, Run1d};
use super::RoughSlip3d;
use crate::experiment::tangential_map::{e_over_g, NODES};
use crate::output::Env;
use crate::report::{Section, Table};
use mrd::rough_contact::Stat;

/// a / b, undefined (NaN) where b is zero within [`ZERO`].
fn over(a: f64, b: f64) -> f64 {
    if b.abs() < ZERO {
        f64::NAN
    } else {
        a / b
    }
}

/// mean 3D / mean MRD and its 95 % half-width (independent ensembles, first order);
/// undefined where MRD's mean is zero.
fn ratio_of_means(a: &Stat, b: &Stat) -> (f64, f64) {
    let r = over(a.mean, b.mean);
    if r.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    let rel = ((a.ci95 / a.mean).powi(2) + (b.ci95 / b.mean).powi(2)).sqrt();
    (r, (r * rel).abs())
}

fn stat(v: impl Iterator<Item = f64>) -> Stat {
    Stat::of(&v.collect::<Vec<_>>())
}

/// The largest |x - 1| of the finite values seen.
#[derive(Default, Clone, Copy)]
struct Dev(f64);

impl Dev {
    fn see(&mut self, x: f64) {
        if x.is_finite() {
            self.0 = self.0.max((x - 1.0).abs());
        }
    }
}

fn columns(q: &Quantity, lambdas: &[Vec<f64>]) -> Vec<String> {
    let (s, u) = (q.stem, q.unit);
    let mut c: Vec<String> = vec![
        "hurst [1]".into(),
        "roughness_over_d0 [1]".into(),
        "poisson [1]".into(),
        "grid [cells]".into(),
        format!("{} [1]", q.x_name),
        format!("{s}_3d_mean [{u}]"),
        format!("{s}_3d_ci95 [{u}]"),
        format!("{s}_law_on_3d_curve_mean [{u}]"),
        format!("{s}_3d_over_law_mean [1]"),
        format!("{s}_3d_over_law_ci95 [1]"),
    ];
    if let Some((name, _)) = q.extra {
        c.push(format!("{name} [1]"));
    }
    for j in 0..lambdas.len() {
        c.push(format!("lambda_{j} [1]"));
        c.push(format!("{s}_mrd_{j}_mean [{u}]"));
        c.push(format!("{s}_mrd_{j}_ci95 [{u}]"));
        c.push(format!("{s}_3d_over_mrd_{j} [1]"));
        c.push(format!("{s}_3d_over_mrd_{j}_ci95 [1]"));
    }
    c
}

/// The table of one quantity; records in `devs[k]` (Poisson index k) the deviations on
/// the finest grid (index 0: the smooth body against MRD; 1: rough against the law on the 3D curve;
/// 2 + j: rough against MRD with lambda j) and the largest change of a 3D mean from
/// the grid before.
fn quantity_table(
    spec: &RoughSlip3d,
    q: &Quantity,
    lambdas: &[Vec<f64>],
    cases: &[Case],
    devs: &mut [Vec<Dev>],
    change: &mut Dev,
) -> Table {
    let mut t = Table::new(q.table, &columns(q, lambdas));
    // Empty cells: lambda of the smooth body (no line), ratios to a value that is 0.
    t.missing_ok = true;
    let finest = spec.cells.len() - 1;
    for case in cases {
        let hi = spec.hurst.iter().position(|&x| x == case.hurst);
        for (k, &nu) in spec.poisson.iter().enumerate() {
            let ratio = e_over_g(nu);
            for (g, runs) in case.runs_3d.iter().enumerate() {
                for j in 0..q.xs.len() {
                    let s3 = stat(runs.iter().map(|r| (q.three)(r, k, j) / q.scale));
                    let law = stat(runs.iter().map(|r| (q.law)(&r.mapping, ratio, j) / q.scale));
                    let paired = stat(runs.iter().map(|r| {
                        over(
                            (q.three)(r, k, j) / q.scale,
                            (q.law)(&r.mapping, ratio, j) / q.scale,
                        )
                    }));
                    let mut row = vec![
                        case.hurst,
                        case.roughness,
                        nu,
                        spec.cells[g] as f64,
                        q.xs[j],
                        s3.mean,
                        s3.ci95,
                        law.mean,
                        paired.mean,
                        paired.ci95,
                    ];
                    if let Some((_, f)) = q.extra {
                        row.push(stat(runs.iter().map(|r| f(r, k, j))).mean);
                    }
                    let rough = case.roughness > 0.0;
                    if g == finest {
                        if rough {
                            devs[k][1].see(paired.mean);
                        }
                        if g > 0 {
                            let before = stat(
                                case.runs_3d[g - 1]
                                    .iter()
                                    .map(|r| (q.three)(r, k, j) / q.scale),
                            );
                            change.see(s3.mean / before.mean);
                        }
                    }
                    for (l, lam) in lambdas.iter().enumerate() {
                        let runs_1d: &[Run1d] = &case.runs_1d[l];
                        let sm = stat(
                            runs_1d
                                .iter()
                                .map(|r| (q.law)(&r.mapping, ratio, j) / q.scale),
                        );
                        let (rm, rc) = ratio_of_means(&s3, &sm);
                        if g == finest {
                            devs[k][if rough { 2 + l } else { 0 }].see(rm);
                        }
                        let lambda = if rough {
                            hi.map_or(f64::NAN, |i| lam[i])
                        } else {
                            f64::NAN
                        };
                        row.extend([lambda, sm.mean, sm.ci95, rm, rc]);
                    }
                    t.push(row);
                }
            }
        }
    }
    t
}

/// k_n and k_t / k_n per case, Poisson's ratio and grid; the largest deviation of the
/// 3D k_t / k_n from MRD's G*/E* on the finest grid.
fn stiffness_table(
    spec: &RoughSlip3d,
    lambdas: &[Vec<f64>],
    cases: &[Case],
    kn_scale: f64,
    dev: &mut [Dev],
) -> Table {
    let mut c: Vec<String> = [
        "hurst [1]",
        "roughness_over_d0 [1]",
        "poisson [1]",
        "grid [cells]",
        "kn_3d_mean [1]",
        "kn_3d_ci95 [1]",
        "kt_over_kn_3d_mean [1]",
        "kt_over_kn_3d_ci95 [1]",
        "kt_over_kn_mrd [1]",
    ]
    .map(String::from)
    .to_vec();
    for j in 0..lambdas.len() {
        c.push(format!("kn_mrd_{j}_mean [1]"));
        c.push(format!("kn_mrd_{j}_ci95 [1]"));
    }
    let mut t = Table::new("stiffness", &c);
    let finest = spec.cells.len() - 1;
    for case in cases {
        for (k, &nu) in spec.poisson.iter().enumerate() {
            for (g, runs) in case.runs_3d.iter().enumerate() {
                let kn = stat(runs.iter().map(|r| r.kn / kn_scale));
                let kt = stat(runs.iter().map(|r| r.slips[k].kt / r.kn));
                let mrd = 1.0 / e_over_g(nu);
                if g == finest {
                    dev[k].see(kt.mean / mrd);
                }
                let mut row = vec![
                    case.hurst,
                    case.roughness,
                    nu,
                    spec.cells[g] as f64,
                    kn.mean,
                    kn.ci95,
                    kt.mean,
                    kt.ci95,
                    mrd,
                ];
                for runs_1d in &case.runs_1d {
                    let s = stat(runs_1d.iter().map(|r| r.kn / kn_scale));
                    row.extend([s.mean, s.ci95]);
                }
                t.push(row);
            }
        }
    }
    t
}

pub fn report(
    spec: &RoughSlip3d,
    env: &Env,
    lambdas: &[Vec<f64>],
    cases: &[Case],
    out: &mut Section,
) {
    let e_star = env.ctx.material.e_star;
    let d0 = spec.smooth_approach(e_star);
    let lambda_names: Vec<String> = spec
        .lambda
        .iter()
        .enumerate()
        .map(|(j, l)| format!("lambda_{j}: {}", lambda_name(l)))
        .collect();
    let note = format!(
        "{} held at F_N = {} (smooth approach d_0 = {d0:.6e}), mu = {}, self-affine roughness of rms height roughness x d_0 (modes |k| <= {} of 2 pi / side, side {}), grids {:?} cells across (the same surfaces on each), {} surfaces in 3D and {} MRD lines per case; 3D: free half-space, partial slip under the held pressure (Coulomb, Cerruti's operator, q_y = 0), the absolute shift; law on 3D curve: u = mu (E*/G*) [d(F_N) - d(F_N - Q/mu)] on each surface's 3D normal curve, Masing's rule for the cycles ({NODES}-point Gauss-Legendre); MRD: the same on the rough line's springs, C1D = lambda q C2D ({}); 3D over law: paired per surface; 3D over MRD: ratio of the means, its interval first order; intervals: 95 %, 1.96 standard errors",
        spec.body_name(),
        spec.force,
        spec.mu,
        spec.bandwidth,
        spec.side,
        spec.cells,
        spec.realisations_3d,
        spec.realisations_1d,
        lambda_names.join(", "),
    );
    let nl = lambdas.len();
    let (mut change, mut change_w) = (Dev::default(), Dev::default());
    let np = spec.poisson.len();
    let mut dev_shift = vec![vec![Dev::default(); 2 + nl]; np];
    let curve = Quantity {
        table: "curve",
        stem: "shift",
        x_name: "force_over_mu_fn",
        x_label: "tangential force Q over mu F_N [1]",
        xs: &spec.fractions,
        three: |r, k, j| r.slips[k].shifts[j],
        law: |m, ratio, j| m.shifts(ratio)[j],
        scale: spec.mu * d0,
        unit: "mu d_0",
        extra: Some(("stick_fraction_3d_mean", |r, k, j| r.slips[k].stick[j])),
    };
    let mut t_curve = quantity_table(spec, &curve, lambdas, cases, &mut dev_shift, &mut change);
    t_curve.notes.push(note.clone());
    t_curve
        .notes
        .push("empty cells: lambda of the smooth body (it has no rough line); ratios to a value that is zero up to rounding (below 1e-6 in the table's units: the energy per cycle of a normal curve that is linear over the cycle, a smooth punch or MRD's fully touching one)".into());
    let mut dev_w = vec![vec![Dev::default(); 2 + nl]; np];
    let cycles = Quantity {
        table: "dissipation",
        stem: "dissipation",
        x_name: "amplitude_over_mu_fn",
        x_label: "force amplitude over mu F_N [1]",
        xs: &spec.amplitudes,
        three: |r, k, j| r.slips[k].energies[j],
        law: |m, ratio, j| m.energies(ratio)[j],
        scale: spec.mu * spec.mu * spec.force * d0,
        unit: "mu^2 F_N d_0",
        extra: None,
    };
    let mut t_w = quantity_table(spec, &cycles, lambdas, cases, &mut dev_w, &mut change_w);
    t_w.notes.push(t_curve.notes[1].clone());
    t_w.notes.push(format!(
        "{note}; 3D: the energy dissipated by slip in one full cycle after the ramp to the amplitude ({} steps per half cycle)",
        spec.steps
    ));
    let mut dev_k = vec![Dev::default(); np];
    let mut t_k = stiffness_table(spec, lambdas, cases, spec.force / d0, &mut dev_k);
    t_k.notes.push(format!(
        "{note}; kn = dF/dd over F_N / d_0; kt: the stick stiffness (the friction bound lifted), k_t / k_n paired per surface; MRD: k_t / k_n = G*/E* = 2 (1 - nu) / (2 - nu)"
    ));
    let rough = cases.iter().any(|c| c.roughness > 0.0);
    for (k, &nu) in spec.poisson.iter().enumerate() {
        // Keys name the Poisson's ratio without a dot: nu_0p5 for 0.5.
        let nu = format!("nu_{}", format!("{nu}").replace('.', "p"));
        let (ds, dw) = (&dev_shift[k], &dev_w[k]);
        out.scalar(format!("shift_smooth_max_rel_dev_3d_vs_mrd_{nu}"), ds[0].0);
        if dw[0].0 > 0.0 {
            out.scalar(
                format!("dissipation_smooth_max_rel_dev_3d_vs_mrd_{nu}"),
                dw[0].0,
            );
        }
        if rough {
            out.scalar(format!("shift_rough_max_rel_dev_3d_vs_law_{nu}"), ds[1].0);
            out.scalar(
                format!("dissipation_rough_max_rel_dev_3d_vs_law_{nu}"),
                dw[1].0,
            );
            for j in 0..nl {
                out.scalar(
                    format!("shift_rough_max_rel_dev_3d_vs_mrd_{j}_{nu}"),
                    ds[2 + j].0,
                );
                out.scalar(
                    format!("dissipation_rough_max_rel_dev_3d_vs_mrd_{j}_{nu}"),
                    dw[2 + j].0,
                );
            }
        }
        out.scalar(format!("kt_over_kn_max_rel_dev_3d_vs_mrd_{nu}"), dev_k[k].0);
    }
    if spec.cells.len() > 1 {
        out.scalar("shift_max_rel_change_3d_last_refinement", change.0);
        out.scalar("dissipation_max_rel_change_3d_last_refinement", change_w.0);
    }
    let grid = *spec.cells.last().unwrap_or(&0) as f64;
    out.figures
        .push(curve_figure(spec, &t_curve, &curve, grid, false));
    out.figures
        .push(curve_figure(spec, &t_w, &cycles, grid, true));
    out.figures.push(ratio_figure(spec, &t_curve, &curve, grid));
    out.figures.push(ratio_figure(spec, &t_w, &cycles, grid));
    out.figures.extend(stick_maps(spec, cases));
    out.tables.extend([t_curve, t_w, t_k]);
}
