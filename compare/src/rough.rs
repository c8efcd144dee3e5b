//! Executors for rough-line outputs (MRD only): the static-friction experiment of
//! Section 10.2 (Fig. 9) and the ensemble stiffness-force law (Eq. 77) with the
//! reduction of Table 1 to a power-law profile with n = H.

use crate::error::{CompareError, MrdContext, Result};
use crate::plan::Stage;
use crate::report::{Figure, Report, Series, Style, Table};
use crate::scene::{LambdaSpec, OutputSpec, Scene};
use mrd::friction::{log_space, static_friction, FrictionSetup};
use mrd::rough_contact::{ensemble, fit_line, RoughLine, Stat};
use mrd::roughness::synthesis::Amplitudes;
use mrd::roughness::{Lambda, LambdaTable, SelfAffine};
use std::f64::consts::PI;

/// The project's own lambda(H), calibrated by the `fig6` scene (provenance in the file).
pub const DEFAULT_LAMBDA_CSV: &str = include_str!("../data/lambda_fig6.csv");

pub fn lambda_of(spec: &LambdaSpec, base: Option<&std::path::Path>) -> Result<Lambda> {
    Ok(match spec {
        LambdaSpec::Named(s) if s == "pi" => Lambda::Pi,
        LambdaSpec::Named(s) if s == "cut" => Lambda::Cut,
        LambdaSpec::Named(s) if s == "calibrated" => {
            Lambda::Table(LambdaTable::from_csv(DEFAULT_LAMBDA_CSV).ctx("embedded lambda table")?)
        }
        LambdaSpec::Named(s) => {
            let path = match base {
                Some(b) => b.join(s),
                None => std::path::PathBuf::from(s),
            };
            let text = std::fs::read_to_string(&path).map_err(crate::error::io_err(format!(
                "reading lambda table {}",
                path.display()
            )))?;
            Lambda::Table(
                LambdaTable::from_csv(&text).ctx(format!("lambda table {}", path.display()))?,
            )
        }
        LambdaSpec::Value(v) => Lambda::Value(*v),
    })
}

pub fn run_output(scene: &Scene, index: usize, report: &mut Report) -> Result<()> {
    let out = &scene.file.outputs[index];
    let ctx = format!("outputs[{index}] ({})", out.kind());
    let e = scene.material.e_star;
    match out {
        OutputSpec::StaticFriction {
            hurst,
            points,
            length,
            rms_height,
            contacts_at_max_force,
            realisations,
            seed,
            force_min,
            force_max,
            force_points,
            paper_a,
            paper_b,
        } => {
            report.ran(Stage::RoughSynthesis);
            report.ran(Stage::RoughContact);
            let mut setup = FrictionSetup {
                hurst: *hurst,
                points: *points,
                length: *length,
                e_star: e,
                rms_height: rms_height.unwrap_or(1.0),
                realisations: *realisations,
                seed: *seed,
                forces: log_space(*force_min, *force_max, *force_points),
            };
            if let Some(target) = contacts_at_max_force {
                // Calibrate h on min(realisations, 40) lines so that the mean number of
                // touching points at F = force_max is the target.
                setup.rms_height =
                    mrd::friction::calibrate_rms_height(&setup, *target, (*realisations).min(40))
                        .ctx(&ctx)?;
                report.scalar("static_friction.calibrated_rms_height", setup.rms_height);
            }
            let r = static_friction(&setup).ctx(&ctx)?;
            let fitted = r
                .fit
                .ok_or_else(|| CompareError::Scene(format!("{ctx}: need force_points >= 3")))?;
            let mut t = Table::new(
                "static_friction",
                &[
                    "force [force unit]".into(),
                    "f = F/(E* h L) [1]".into(),
                    "xi_mean [1]".into(),
                    "xi_std [1]".into(),
                    "xi_ci95 [1]".into(),
                    "contacts_mean [1]".into(),
                ],
            );
            t.notes.push(format!(
                "Section 10.2: N = {points}, L = {length}, H = {hurst}, h = {:e}, E* = {e}, {realisations} realisations (seed {seed}), band pi/L < q < 0.1 pi/dx (Eq. 85); xi = a + b ln f (Eq. 91)",
                setup.rms_height
            ));
            for p in &r.points {
                t.push(vec![
                    p.force,
                    p.reduced_force,
                    p.xi.mean,
                    p.xi.std,
                    p.xi.ci95,
                    p.contacts.mean,
                ]);
            }
            report.scalar("static_friction.a", fitted.a);
            report.scalar("static_friction.b", fitted.b);
            report.scalar("static_friction.a_ci95", 1.96 * fitted.se_a);
            report.scalar("static_friction.b_ci95", 1.96 * fitted.se_b);
            report.scalar(
                "static_friction.contacts_at_max_force",
                r.points.last().unwrap().contacts.mean,
            );
            let fit: Vec<(f64, f64)> = r
                .points
                .iter()
                .map(|p| (p.reduced_force, fitted.a + fitted.b * p.reduced_force.ln()))
                .collect();
            let mut fig = Figure::new(
                "static_friction",
                &format!("Mean slope in contact, H = {hurst} (Fig. 9)"),
                "reduced force f = F/(E* h L) [1]",
                "xi = grad z_cont / grad z [1]",
            )
            .with(Series::new(
                format!("MRD, mean of {realisations} lines"),
                r.points
                    .iter()
                    .map(|p| (p.reduced_force, p.xi.mean))
                    .collect(),
                Style::Markers,
            ))
            .with(Series::new(
                format!("fit xi = {:.4} + {:.4} ln f", fitted.a, fitted.b),
                fit,
                Style::Line,
            ))
            .with(Series::new(
                "mean +/- 95% CI",
                r.points
                    .iter()
                    .map(|p| (p.reduced_force, p.xi.mean + p.xi.ci95))
                    .collect(),
                Style::Dashed,
            ))
            .with(
                Series::new(
                    "",
                    r.points
                        .iter()
                        .map(|p| (p.reduced_force, p.xi.mean - p.xi.ci95))
                        .collect(),
                    Style::Dashed,
                )
                .colored(2),
            );
            if let (Some(pa), Some(pb)) = (paper_a, paper_b) {
                report.scalar("static_friction.paper_a", *pa);
                report.scalar("static_friction.paper_b", *pb);
                let line: Vec<(f64, f64)> = r
                    .points
                    .iter()
                    .map(|p| (p.reduced_force, pa + pb * p.reduced_force.ln()))
                    .collect();
                fig = fig.with(
                    Series::new(format!("paper: xi = {pa} + {pb} ln f"), line, Style::Dashed)
                        .colored(5),
                );
            }
            fig.log_x = true;
            report.tables.push(t);
            report.figures.push(fig);
        }
        OutputSpec::RoughStiffness {
            hurst,
            measured,
            points,
            length,
            upper_cutoff_ratio,
            lambda,
            realisations,
            seed,
            f_min,
            f_max,
            f_points,
        } => {
            report.ran(Stage::RoughSynthesis);
            report.ran(Stage::RoughContact);
            let lam = lambda_of(lambda, scene.base_dir.as_deref())?
                .at(*hurst)
                .ctx(&ctx)?;
            let q0 = 2.0 * PI / length;
            let q1 = PI * *points as f64 / length * upper_cutoff_ratio;
            let surf = SelfAffine::new(*hurst, q0, q0, q1).ctx(&ctx)?;
            let spec = surf.to_line(lam).with_rms_height(1.0).ctx(&ctx)?;
            // A measured surface: its radially averaged PSD, C1D = lambda q C2D (Eq. 76).
            let tab = match measured {
                Some(m) => {
                    let path = scene.base_dir.as_deref().map_or_else(
                        || std::path::PathBuf::from(&m.heights),
                        |b| b.join(&m.heights),
                    );
                    let map = mrd::topography::HeightMap::read(&path).ctx(&ctx)?;
                    let psd = mrd::roughness::stats::surface_psd(
                        &map.data, map.cols, map.rows, m.size[0], m.size[1], 40,
                    );
                    let t = mrd::roughness::TabulatedSpectrum::new(&psd)
                        .ctx(format!("{ctx}: PSD of {}", path.display()))?
                        .with_lowest_wavenumber(2.0 * PI / m.size[0].max(m.size[1]));
                    report.scalar("rough_stiffness.measured_fitted_hurst", t.fitted_hurst());
                    report.ran(Stage::Psd);
                    Some(t)
                }
                None => None,
            };
            let c1d = |q: f64| match &tab {
                Some(t) => lam * q * t.c2d(q),
                None => spec.c1d(q),
            };
            let fs = log_space(*f_min, *f_max, *f_points);
            let per: Vec<Vec<f64>> = ensemble(*realisations, |r| {
                let h = mrd::roughness::synthesis::line_from(
                    &c1d,
                    *points,
                    *length,
                    *seed,
                    r,
                    Amplitudes::Deterministic,
                )?;
                let rl = RoughLine::new(&h, *length, e)?;
                fs.iter()
                    .map(|&f| {
                        Ok(rl.reduced_stiffness(
                            rl.at_force(f * e * rl.rms_height * length)?.stiffness,
                        ))
                    })
                    .collect()
            })
            .ctx(&ctx)?;
            let stats: Vec<Stat> = (0..fs.len())
                .map(|k| Stat::of(&per.iter().map(|v| v[k]).collect::<Vec<_>>()))
                .collect();
            // Power-law regime: k/(E*L) between 2 contact points and 10 % of full stiffness.
            let k_lo = 2.0 / *points as f64;
            let sel: Vec<usize> = (0..fs.len())
                .filter(|&k| stats[k].mean > k_lo && stats[k].mean < 0.1)
                .collect();
            if sel.len() < 3 {
                return Err(CompareError::Scene(format!(
                    "{ctx}: fewer than 3 loads in the power-law regime; widen f_min..f_max"
                )));
            }
            let fit = fit_line(
                &sel.iter().map(|&k| fs[k].ln()).collect::<Vec<_>>(),
                &sel.iter().map(|&k| stats[k].mean.ln()).collect::<Vec<_>>(),
            )
            .ctx(&ctx)?;
            let alpha_theory = 1.0 / (1.0 + hurst); // Eq. (80)
            let mut t = Table::new(
                "rough_stiffness",
                &[
                    "f = F/(E* h L) [1]".into(),
                    "k/(E* L) mean [1]".into(),
                    "k/(E* L) std [1]".into(),
                    "k/(E* L) ci95 [1]".into(),
                    "in_fit_range [0/1]".into(),
                ],
            );
            t.notes.push(match measured {
                Some(m) => format!("Eq. (77) on {realisations} MRD rough lines: N = {points}, L = {length}, C1D = lambda q C2D with lambda = {lam} (at H = {hurst}) and C2D the radially averaged PSD of {} ({} x {})", m.heights, m.size[0], m.size[1]),
                None => format!("Eq. (77) on {realisations} MRD rough lines: N = {points}, L = {length}, H = {hurst}, C1D = lambda q C2D with lambda = {lam}, q from 2 pi/L to {upper_cutoff_ratio} x Nyquist"),
            });
            for (k, s) in stats.iter().enumerate() {
                t.push(vec![
                    fs[k],
                    s.mean,
                    s.std,
                    s.ci95,
                    sel.contains(&k) as u8 as f64,
                ]);
            }
            report.scalar("rough_stiffness.alpha", fit.b);
            report.scalar("rough_stiffness.alpha_ci95", 1.96 * fit.se_b);
            report.scalar("rough_stiffness.zeta", fit.a.exp());
            report.scalar("rough_stiffness.alpha_scaling_eq80", alpha_theory);
            report.scalar("rough_stiffness.lambda", lam);
            // Table 1, dashed arrows: a power-law profile z = c r^n with n = H has
            // k ~ F^(1/(1+n)) exactly (Eqs. 20-21); its curve is drawn through the fit's
            // centre for comparison of slopes.
            let mut fig = Figure::new(
                "rough_stiffness",
                &format!("Stiffness-force law (Eq. 77), H = {hurst}"),
                "reduced force F/(E* h L) [1]",
                "reduced stiffness k/(E* L) [1]",
            )
            .with(Series::new(
                format!("MRD rough lines ({realisations})"),
                stats
                    .iter()
                    .enumerate()
                    .map(|(k, s)| (fs[k], s.mean))
                    .collect(),
                Style::Markers,
            ))
            .with(Series::new(
                format!("fit: alpha = {:.3} +/- {:.3}", fit.b, 1.96 * fit.se_b),
                sel.iter()
                    .map(|&k| (fs[k], (fit.a + fit.b * fs[k].ln()).exp()))
                    .collect(),
                Style::Line,
            ));
            if *hurst > 0.0 {
                let mid = sel[sel.len() / 2];
                let c = stats[mid].mean / fs[mid].powf(alpha_theory);
                report.scalar(
                    "rough_stiffness.alpha_power_law_profile_n_eq_H",
                    alpha_theory,
                );
                fig = fig.with(Series::new(
                    format!("power-law profile n = H: alpha = 1/(1+H) = {alpha_theory:.3}"),
                    sel.iter()
                        .map(|&k| (fs[k], c * fs[k].powf(alpha_theory)))
                        .collect(),
                    Style::Dashed,
                ));
            }
            fig.log_x = true;
            fig.log_y = true;
            report.tables.push(t);
            report.figures.push(fig);
        }
        _ => unreachable!("not a rough output"),
    }
    Ok(())
}
