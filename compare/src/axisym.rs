//! Executors for the axisymmetric (exact MRD) outputs: each turns one output request
//! into tables, figures and scalar results, running only its planned stages.

use crate::error::{MrdContext, Result};
use crate::plan::Stage;
use crate::report::{Figure, Report, Series, Style, Table};
use crate::scene::{ClosedForm, ControlSpec, Drive, OutputSpec, Scene};
use mrd::adhesion::{simulate_cycle, AdhesiveContact, Control};
use mrd::discrete::DiscreteAxisymmetric;
use mrd::normal::AxisymmetricContact;
use mrd::oscillation::{dissipation_semi_analytic, OscillatingContact};
use mrd::pressure::{abel_pressure, integrate_force};
use mrd::reference as rf;
use mrd::tangential::TangentialContact;

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Runs output `index` of `scene` into `report`.
pub fn run_output(scene: &Scene, index: usize, report: &mut Report) -> Result<()> {
    let out = &scene.file.outputs[index];
    let ctx = format!("outputs[{index}] ({})", out.kind());
    let cf = scene.file.profile.as_ref().and_then(|p| p.closed_form());
    let profile = scene.profile()?.clone();
    let e = scene.material.e_star;
    let u = &scene.file.units;
    let (len, stress, force, stiff) =
        (u.length.clone(), u.stress.clone(), u.force(), u.stiffness());
    let contact = AxisymmetricContact::new(profile.clone(), e).ctx(&ctx)?;
    report.ran(Stage::HessTransform);
    match out {
        OutputSpec::Profile1d { r_max, points } => {
            let mut t = Table::new(
                "profile_1d",
                &[
                    format!("r_or_x [{len}]"),
                    format!("z_3d [{len}]"),
                    format!("z1d_closed_form [{len}]"),
                    format!("z1d_quadrature [{len}]"),
                ],
            );
            t.notes.push("z1d by the rule of Hess (Eq. 11): per-shape closed form and independent tanh-sinh quadrature".into());
            let limit = r_max.min(profile.max_contact_radius());
            let mut max_dev: f64 = 0.0;
            for k in 0..*points {
                let x = limit * k as f64 / (*points - 1) as f64;
                let zc = profile.z1d(x);
                let zq = profile.z1d_numeric(x).ctx(&ctx)?;
                if zc > 0.0 {
                    max_dev = max_dev.max(rel(zq, zc));
                }
                t.push(vec![x, profile.z(x), zc, zq]);
            }
            report.scalar("profile_1d.max_rel_dev_quadrature_vs_closed_form", max_dev);
            let fig = Figure::new(
                "profile_1d",
                "3D profile and its MRD image (rule of Hess, Eq. 11)",
                &format!("r, x [{len}]"),
                &format!("height [{len}]"),
            )
            .with(Series::new(
                "3D profile z(r)",
                t.rows.iter().map(|r| (r[0], r[1])).collect(),
                Style::Line,
            ))
            .with(Series::new(
                "1D image z1d(x), closed form",
                t.rows.iter().map(|r| (r[0], r[2])).collect(),
                Style::Line,
            ))
            .with(Series::new(
                "1D image z1d(x), quadrature of Eq. 11",
                subsample(&t, 0, 3, 25),
                Style::Markers,
            ));
            report.tables.push(t);
            report.figures.push(fig);
        }
        OutputSpec::ForceDepth {
            max,
            drive,
            points,
            springs,
            half_length,
            resistivity_sum,
        } => {
            report.ran(Stage::NormalSemiAnalytic);
            let states: Vec<_> = (1..=*points)
                .map(|k| {
                    let v = max * k as f64 / *points as f64;
                    match drive {
                        Drive::Depth => contact.state_at_depth(v),
                        Drive::Force => contact.state_at_force(v),
                    }
                })
                .collect::<std::result::Result<_, _>>()
                .ctx(&ctx)?;
            let mut cols = vec![
                format!("depth [{len}]"),
                format!("force [{force}]"),
                format!("contact_radius [{len}]"),
                format!("stiffness [{stiff}]"),
            ];
            let disc = match springs {
                Some(n) => {
                    report.ran(Stage::NormalDiscrete);
                    let a_top = states.last().map_or(1.0, |s| s.radius);
                    let l = half_length.unwrap_or(1.5 * a_top);
                    cols.extend([
                        format!("force_discrete [{force}]"),
                        format!("contact_radius_discrete [{len}]"),
                    ]);
                    Some(DiscreteAxisymmetric::new(&profile, e, *n, l).ctx(&ctx)?)
                }
                None => None,
            };
            let closed = cf.and_then(|c| closed_force(c, e));
            if closed.is_some() {
                report.ran(Stage::ClosedForm);
                cols.push(format!("force_closed_form [{force}]"));
            }
            if resistivity_sum.is_some() {
                cols.push("electrical_conductance [1/(resistivity unit * length unit)]".into());
            }
            let mut t = Table::new("force_depth", &cols);
            t.notes.push(format!(
                "drive: {drive:?}; MRD semi-analytic (Eqs. 20, 24, 25), relative tolerance 1e-9"
            ));
            let (mut dev_cf, mut dev_disc): (f64, f64) = (0.0, 0.0);
            let has_rim = profile.rim().is_some();
            for s in &states {
                let mut row = vec![s.depth, s.force, s.radius, s.stiffness];
                if let Some(d) = &disc {
                    let ds = d.state_at_depth(s.depth, has_rim).ctx(&ctx)?;
                    dev_disc = dev_disc.max(rel(ds.force, s.force));
                    row.extend([ds.force, ds.radius]);
                }
                if let Some(f) = &closed {
                    let fc = f(s.depth);
                    dev_cf = dev_cf.max(rel(s.force, fc));
                    row.push(fc);
                }
                if let Some(rho) = resistivity_sum {
                    row.push(s.electrical_conductance(e, *rho));
                }
                t.push(row);
            }
            if closed.is_some() {
                report.scalar("force_depth.max_rel_error_vs_closed_form", dev_cf);
            }
            if let Some(d) = &disc {
                report.scalar(
                    "force_depth.max_rel_dev_discrete_vs_semi_analytic",
                    dev_disc,
                );
                report.scalar("force_depth.springs", springs.unwrap_or(0) as f64);
                report.scalar("force_depth.spring_spacing", d.dx());
                t.notes.push(format!(
                    "discrete foundation: {} springs, dx = {:e}",
                    springs.unwrap_or(0),
                    d.dx()
                ));
            }
            let last = states.last().unwrap();
            report.scalar("force_depth.final_depth", last.depth);
            report.scalar("force_depth.final_force", last.force);
            report.scalar("force_depth.final_contact_radius", last.radius);
            let mut fig = Figure::new(
                "force_depth",
                "Normal force against indentation depth",
                &format!("depth d [{len}]"),
                &format!("normal force F [{force}]"),
            )
            .with(Series::new(
                "MRD, semi-analytic",
                t.rows.iter().map(|r| (r[0], r[1])).collect(),
                Style::Line,
            ));
            if disc.is_some() {
                fig = fig.with(Series::new(
                    format!("MRD, {} discrete springs", springs.unwrap()),
                    subsample(&t, 0, 4, 20),
                    Style::Markers,
                ));
            }
            if closed.is_some() {
                let j = t
                    .columns
                    .iter()
                    .position(|c| c.starts_with("force_closed_form"))
                    .unwrap();
                fig = fig.with(Series::new(
                    closed_label(cf.unwrap()),
                    t.rows.iter().map(|r| (r[0], r[j])).collect(),
                    Style::Dashed,
                ));
            }
            report.tables.push(t);
            report.figures.push(fig);
        }
        OutputSpec::Pressure { depth, points } => {
            report.ran(Stage::NormalSemiAnalytic);
            let s = contact.state_at_depth(*depth).ctx(&ctx)?;
            report.ran(Stage::AbelPressure);
            let closed = cf.and_then(|c| closed_pressure(c, e, *depth, s.force));
            let mut cols = vec![format!("r [{len}]"), format!("pressure [{stress}]")];
            if closed.is_some() {
                report.ran(Stage::ClosedForm);
                cols.push(format!("pressure_closed_form [{stress}]"));
            }
            let mut t = Table::new("pressure", &cols);
            t.notes.push(format!("Abel transform (Eq. 26) at depth {depth:e}, contact radius {:e}; samples at cell centres r = a (k + 1/2)/N", s.radius));
            let mut dev: f64 = 0.0;
            for k in 0..*points {
                let r = s.radius * (k as f64 + 0.5) / *points as f64;
                let p = abel_pressure(&profile, e, *depth, s.radius, 0.0, r).ctx(&ctx)?;
                if !p.is_finite() {
                    continue; // exactly on a slope jump (log singularity): not sampled
                }
                let mut row = vec![r, p];
                if let Some(f) = &closed {
                    let pc = f(r);
                    dev = dev.max(rel(p, pc));
                    row.push(pc);
                }
                t.push(row);
            }
            if profile
                .shapes()
                .iter()
                .any(|s| matches!(s, mrd::Shape::Table(_)))
            {
                report.warnings.push(
                    "pressure: a piecewise-linear table has slope jumps at its nodes, under which the exact \
                     pressure is log-singular (peaks at node radii); use a finer table or analytic shapes \
                     for a smooth pressure"
                        .into(),
                );
            }
            let total = integrate_force(
                |r| abel_pressure(&profile, e, *depth, s.radius, 0.0, r),
                s.radius,
                &profile.breaks(),
            )
            .ctx(&ctx)?;
            report.scalar("pressure.contact_radius", s.radius);
            report.scalar("pressure.force_1d", s.force);
            report.scalar("pressure.force_from_pressure_integral", total);
            report.scalar("pressure.equilibrium_rel_error", rel(total, s.force));
            if closed.is_some() {
                report.scalar("pressure.max_rel_error_vs_closed_form", dev);
            }
            let mut fig = Figure::new(
                "pressure",
                "Contact pressure from the 1D line load (Abel transform, Eq. 26)",
                &format!("radius r [{len}]"),
                &format!("pressure p [{stress}]"),
            )
            .with(Series::new(
                "MRD + Abel transform",
                t.rows.iter().map(|r| (r[0], r[1])).collect(),
                Style::Line,
            ));
            if closed.is_some() {
                fig = fig.with(Series::new(
                    closed_label(cf.unwrap()),
                    t.rows.iter().map(|r| (r[0], r[2])).collect(),
                    Style::Dashed,
                ));
            }
            report.tables.push(t);
            report.figures.push(fig);
        }
        OutputSpec::Adhesion {
            gamma,
            depth_max,
            control,
            springs,
            half_length,
            points,
        } => run_adhesion(
            report,
            &ctx,
            &contact,
            cf,
            *gamma,
            *depth_max,
            *control,
            *springs,
            *half_length,
            *points,
            u,
        )?,
        OutputSpec::Tangential {
            mu,
            normal_force,
            points,
            traction_at,
        } => {
            report.ran(Stage::NormalSemiAnalytic);
            let g = scene.material.g_star().ctx(&ctx)?;
            if let Some(w) = scene.material.similarity_warning() {
                report.warnings.push(w);
            }
            let tc = TangentialContact::new(contact.clone(), g, *mu, *normal_force).ctx(&ctx)?;
            report.ran(Stage::Tangential);
            let sphere = matches!(cf, Some(ClosedForm::Sphere { .. }));
            let mut cols = vec![
                format!("tangential_force [{force}]"),
                format!("displacement [{len}]"),
                format!("stick_radius [{len}]"),
            ];
            if sphere {
                report.ran(Stage::ClosedForm);
                cols.extend([
                    format!("displacement_closed_form [{len}]"),
                    format!("stick_radius_closed_form [{len}]"),
                ]);
            }
            let mut t = Table::new("tangential", &cols);
            t.notes.push(format!("normal force {normal_force:e}, mu = {mu}, E* = {e:e}, G* = {g:e}; Jager/Cattaneo-Mindlin (Eqs. 41-50)"));
            let n = &tc.normal;
            let fmax = mu * n.force;
            let mut dev: f64 = 0.0;
            for k in 0..*points {
                let fx = fmax * k as f64 / *points as f64;
                let st = tc.at_force(fx).ctx(&ctx)?;
                let mut row = vec![fx, st.displacement, st.stick_radius];
                if sphere {
                    let uc = rf::cattaneo_mindlin::displacement(*mu, e, g, n.depth, fx, n.force);
                    let cc = n.radius * rf::cattaneo_mindlin::stick_ratio(fx, *mu, n.force);
                    if fx > 0.0 {
                        dev = dev
                            .max(rel(st.displacement, uc))
                            .max(rel(st.stick_radius, cc));
                    }
                    row.extend([uc, cc]);
                }
                t.push(row);
            }
            t.push(
                vec![fmax, tc.max_displacement(), 0.0]
                    .into_iter()
                    .chain(if sphere {
                        vec![
                            rf::cattaneo_mindlin::max_displacement(*mu, e, g, n.depth),
                            0.0,
                        ]
                    } else {
                        vec![]
                    })
                    .collect(),
            );
            report.scalar("tangential.max_displacement", tc.max_displacement());
            report.scalar("tangential.sliding_force", fmax);
            report.scalar("tangential.contact_radius", n.radius);
            if sphere {
                report.scalar("tangential.max_rel_error_vs_cattaneo_mindlin", dev);
            }
            let mut fig = Figure::new(
                "tangential",
                "Tangential force against displacement (Cattaneo-Mindlin / Jager)",
                &format!("tangential displacement u_x [{len}]"),
                &format!("tangential force F_x [{force}]"),
            )
            .with(Series::new(
                "MRD",
                t.rows.iter().map(|r| (r[1], r[0])).collect(),
                Style::Line,
            ));
            if sphere {
                fig = fig.with(Series::new(
                    "Cattaneo-Mindlin (Mindlin 1949)",
                    t.rows.iter().map(|r| (r[3], r[0])).collect(),
                    Style::Dashed,
                ));
            }
            report.tables.push(t);
            report.figures.push(fig);
            if !traction_at.is_empty() {
                report.ran(Stage::AbelTraction);
                let mut cols = vec![format!("r [{len}]")];
                for f in traction_at {
                    cols.push(format!("traction_at_{f}_muFN [{stress}]"));
                    if sphere {
                        cols.push(format!("traction_closed_form_at_{f}_muFN [{stress}]"));
                    }
                }
                let mut t = Table::new("traction", &cols);
                t.notes.push("tangential traction by the Abel transform (Eq. 26) of the line load of Eq. (51)".into());
                let states: Vec<_> = traction_at
                    .iter()
                    .map(|f| tc.at_force(f * fmax))
                    .collect::<std::result::Result<_, _>>()
                    .ctx(&ctx)?;
                let p0 = rf::hertz::pressure(
                    e,
                    match cf {
                        Some(ClosedForm::Sphere { radius }) => radius,
                        _ => 1.0,
                    },
                    n.depth,
                    0.0,
                );
                let mut dev: f64 = 0.0;
                for k in 0..*points {
                    let r = n.radius * (k as f64 + 0.5) / *points as f64;
                    let mut row = vec![r];
                    for st in &states {
                        let tau = tc.traction(st, r).ctx(&ctx)?;
                        row.push(tau);
                        if sphere {
                            let tcf = rf::cattaneo_mindlin::traction(
                                *mu,
                                p0,
                                n.radius,
                                st.stick_radius,
                                r,
                            );
                            dev = dev.max((tau - tcf).abs() / (mu * p0));
                            row.push(tcf);
                        }
                    }
                    t.push(row);
                }
                if sphere {
                    report.scalar("traction.max_error_over_mu_p0", dev);
                }
                let mut fig = Figure::new(
                    "traction",
                    "Tangential traction (Abel transform of Eq. 51)",
                    &format!("radius r [{len}]"),
                    &format!("traction tau [{stress}]"),
                );
                let stride = if sphere { 2 } else { 1 };
                for (i, f) in traction_at.iter().enumerate() {
                    let j = 1 + stride * i;
                    fig = fig.with(Series::new(
                        format!("MRD, F_x = {f} mu F_N"),
                        t.rows.iter().map(|r| (r[0], r[j])).collect(),
                        Style::Line,
                    ));
                }
                if sphere {
                    for (i, f) in traction_at.iter().enumerate() {
                        let j = 2 + stride * i;
                        fig = fig.with(Series::new(
                            format!("Cattaneo-Mindlin, {f} mu F_N"),
                            t.rows.iter().map(|r| (r[0], r[j])).collect(),
                            Style::Dashed,
                        ));
                    }
                }
                report.tables.push(t);
                report.figures.push(fig);
            }
        }
        OutputSpec::Damping {
            mu,
            depth,
            max_amplitude_ratio,
            points,
            springs,
            half_length,
            steps_per_cycle,
        } => {
            report.ran(Stage::NormalSemiAnalytic);
            let g = scene.material.g_star().ctx(&ctx)?;
            if let Some(w) = scene.material.similarity_warning() {
                report.warnings.push(w);
            }
            let s = contact.state_at_depth(*depth).ctx(&ctx)?;
            let beta = e / g;
            let ac0 = mu * beta * depth;
            report.ran(Stage::OscillationDiscrete);
            let l = half_length.unwrap_or(1.05 * s.radius);
            let osc =
                OscillatingContact::new(&profile, e, g, *mu, *depth, *springs, l).ctx(&ctx)?;
            let sphere = match cf {
                Some(ClosedForm::Sphere { radius }) => Some(radius),
                _ => None,
            };
            let energy = u.energy();
            let mut cols = vec![
                format!("amplitude [{len}]"),
                format!("dissipation_time_stepped [{energy}]"),
                format!("dissipation_semi_analytic [{energy}]"),
                format!("force_amplitude [{force}]"),
            ];
            if sphere.is_some() {
                report.ran(Stage::ClosedForm);
                cols.extend([
                    format!("dissipation_eq58_exact [{energy}]"),
                    format!("dissipation_eq61_small_amplitude [{energy}]"),
                    format!("dissipation_mindlin_force [{energy}]"),
                ]);
            }
            let mut t = Table::new("damping", &cols);
            t.notes.push(format!(
                "depth {depth:e}, mu = {mu}, E*/G* = {beta}, A_c0 = mu E*/G* d = {ac0:e}; {springs} springs on [-{l:e}, {l:e}], {steps_per_cycle} steps per cycle, 2 cycles (the second is reported)"
            ));
            let mut dev: f64 = 0.0;
            // Log-spaced amplitudes over two decades below the maximum.
            for k in 0..*points {
                let amp = max_amplitude_ratio
                    * ac0
                    * 10f64.powf(-2.0 * (1.0 - k as f64 / (*points - 1) as f64));
                let sim = osc.simulate(amp, 2, *steps_per_cycle).ctx(&ctx)?;
                let semi = dissipation_semi_analytic(&profile, e, g, *mu, *depth, amp).ctx(&ctx)?;
                let mut row = vec![amp, sim.dissipation, semi, sim.force_amplitude];
                if let Some(r) = sphere {
                    let ex = rf::mindlin_damping::dissipation_exact(e, beta, r, *mu, *depth, amp);
                    dev = dev.max(rel(sim.dissipation, ex));
                    row.extend([
                        ex,
                        rf::mindlin_damping::dissipation_small_amplitude(
                            e, beta, r, *mu, *depth, amp,
                        ),
                        rf::mindlin_damping::dissipation_force_amplitude(
                            g,
                            s.radius,
                            *mu,
                            s.force,
                            sim.force_amplitude,
                        ),
                    ]);
                }
                t.push(row);
            }
            report.scalar("damping.critical_amplitude_ac0", ac0);
            if sphere.is_some() {
                report.scalar("damping.max_rel_error_time_stepped_vs_eq58", dev);
            }
            let mut fig = Figure::new(
                "damping",
                "Dissipated energy per cycle of an oscillating tangential contact",
                &format!("displacement amplitude A [{len}]"),
                &format!("dissipated energy per cycle W [{energy}]"),
            )
            .with(Series::new(
                format!("MRD, time-stepped ({springs} springs)"),
                subsample(&t, 0, 1, 25),
                Style::Markers,
            ))
            .with(Series::new(
                "MRD, semi-analytic",
                t.rows.iter().map(|r| (r[0], r[2])).collect(),
                Style::Line,
            ));
            if sphere.is_some() {
                fig = fig
                    .with(Series::new(
                        "Eq. 58 (Mindlin et al. 1952)",
                        t.rows.iter().map(|r| (r[0], r[4])).collect(),
                        Style::Dashed,
                    ))
                    .with(Series::new(
                        "Eq. 61, small-amplitude limit",
                        t.rows.iter().map(|r| (r[0], r[5])).collect(),
                        Style::Dashed,
                    ));
            }
            fig.log_x = true;
            fig.log_y = true;
            report.tables.push(t);
            report.figures.push(fig);
        }
        OutputSpec::Viscoelastic {
            e_inf,
            prony,
            depth_max,
            ramp_time,
            end_time,
            springs,
            half_length,
            steps,
        } => {
            use mrd::viscoelastic::{radok_force, simulate, Prony};
            let g = Prony::new(*e_inf, prony.iter().map(|t| (t[0], t[1])).collect()).ctx(&ctx)?;
            let rate = depth_max / ramp_time;
            let depth = move |t: f64| rate * t.min(*ramp_time);
            let depth_rate = move |t: f64| if t < *ramp_time { rate } else { 0.0 };
            let times: Vec<f64> = (0..=*steps)
                .map(|k| end_time * k as f64 / *steps as f64)
                .collect();
            let a_max = contact.state_at_depth(*depth_max).ctx(&ctx)?.radius;
            report.ran(Stage::Viscoelastic);
            let f = simulate(
                &profile,
                &g,
                &depth,
                &times,
                *springs,
                half_length.unwrap_or(1.2 * a_max),
            )
            .ctx(&ctx)?;
            report.ran(Stage::ClosedForm);
            let mut t = Table::new(
                "viscoelastic",
                &[
                    "time [s]".to_string(),
                    format!("depth [{len}]"),
                    format!("force [{force}]"),
                    format!("force_radok [{force}]"),
                ],
            );
            t.notes.push(format!("Eq. (63) with E*(t) = {e_inf} + sum E_i exp(-t/tau_i), Prony {prony:?}; ramp to {depth_max} in {ramp_time}, hold to {end_time}; {springs} springs; Radok (1957) by quadrature (valid while the contact grows; during the hold the contact radius is fixed, so it remains exact)"));
            let mut dev: f64 = 0.0;
            for (k, &tk) in times.iter().enumerate() {
                // Radok's integrand jumps at the end of the ramp: split there.
                let exact = if tk == 0.0 {
                    0.0
                } else {
                    radok_force(&profile, &g, &depth, &depth_rate, &[*ramp_time], tk).ctx(&ctx)?
                };
                if exact > 0.0 && k > steps / 20 {
                    dev = dev.max(rel(f[k], exact));
                }
                t.push(vec![tk, depth(tk), f[k], exact]);
            }
            report.scalar("viscoelastic.max_rel_dev_springs_vs_radok", dev);
            report.scalar(
                "viscoelastic.peak_force",
                f.iter().fold(0.0f64, |m, &v| m.max(v)),
            );
            let fig = Figure::new(
                "viscoelastic",
                "Viscoelastic indentation: ramp and hold (Eq. 63)",
                "time t [s]",
                &format!("normal force F [{force}]"),
            )
            .with(Series::new(
                format!("MRD, {springs} Prony springs"),
                subsample(&t, 0, 2, 40),
                Style::Markers,
            ))
            .with(Series::new(
                "Radok (1957)",
                t.rows.iter().map(|r| (r[0], r[3])).collect(),
                Style::Line,
            ));
            report.tables.push(t);
            report.figures.push(fig);
        }
        OutputSpec::StaticFriction { .. }
        | OutputSpec::RoughStiffness { .. }
        | OutputSpec::HurstSweep(_)
        | OutputSpec::BemContact { .. } => {
            unreachable!("rough outputs run in crate::rough")
        }
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn run_adhesion(
    report: &mut Report,
    ctx: &str,
    contact: &AxisymmetricContact,
    cf: Option<ClosedForm>,
    gamma: f64,
    depth_max: f64,
    control: ControlSpec,
    springs: Option<usize>,
    half_length: Option<f64>,
    points: usize,
    u: &crate::scene::Units,
) -> Result<()> {
    let (len, force) = (u.length.clone(), u.force());
    let control = match control {
        ControlSpec::Force => Control::Force,
        ControlSpec::Displacement => Control::Displacement,
    };
    report.ran(Stage::AdhesionSemiAnalytic);
    let ad = AdhesiveContact::new(contact.clone(), gamma).ctx(ctx)?;
    let top = contact.state_at_depth(depth_max).ctx(ctx)?;
    let a_max = top.radius;
    let po = ad.pull_off(a_max, control).ctx(ctx)?;
    let mut t = Table::new(
        "adhesion",
        &[
            format!("depth [{len}]"),
            format!("force [{force}]"),
            format!("contact_radius [{len}]"),
            "unloading [0/1]".into(),
        ],
    );
    t.notes.push(format!(
        "work of adhesion {gamma:e} [{}]; loading without adhesion (springs attach on touching), unloading by the rule of Hess (Eq. 33), {control:?} control",
        u.surface_energy()
    ));
    // Loading (non-adhesive) branch.
    for k in 0..=points {
        let a = a_max * k as f64 / points as f64;
        let s = contact.state_at_radius(a).ctx(ctx)?;
        t.push(vec![s.depth, s.force, a, 0.0]);
    }
    // Unloading: pinned at a_max until the rim spring reaches dl_max, then the branch.
    t.push(vec![top.depth, top.force, a_max, 1.0]);
    for k in 0..=points {
        let a = a_max - (a_max - po.radius) * k as f64 / points as f64;
        t.push(vec![
            ad.depth_at_radius(a).ctx(ctx)?,
            ad.force_at_radius(a).ctx(ctx)?,
            a,
            1.0,
        ]);
    }
    report.scalar("adhesion.pull_off_force", po.force);
    report.scalar("adhesion.pull_off_depth", po.depth);
    report.scalar("adhesion.pull_off_radius", po.radius);
    let mut fig = Figure::new(
        "adhesion",
        &format!("Adhesive loading and unloading ({control:?} control)"),
        &format!("depth d [{len}]"),
        &format!("normal force F [{force}]"),
    )
    .with(Series::new(
        "MRD loading (springs attach on touch)",
        t.rows
            .iter()
            .filter(|r| r[3] == 0.0)
            .map(|r| (r[0], r[1]))
            .collect(),
        Style::Line,
    ))
    .with(Series::new(
        "MRD unloading (rule of Hess, Eq. 33)",
        t.rows
            .iter()
            .filter(|r| r[3] == 1.0)
            .map(|r| (r[0], r[1]))
            .collect(),
        Style::Line,
    ));
    if let Some(n) = springs {
        report.ran(Stage::AdhesionDiscrete);
        let l = half_length.unwrap_or(1.5 * a_max);
        let cyc = simulate_cycle(&ad, n, l, depth_max, control).ctx(ctx)?;
        let mut td = Table::new(
            "adhesion_discrete",
            &[
                format!("depth [{len}]"),
                format!("force [{force}]"),
                format!("contact_radius [{len}]"),
                "unloading [0/1]".into(),
            ],
        );
        td.notes.push(format!(
            "event-driven spring row: {n} springs on the half-line [0, {l:e}] (mirrored)"
        ));
        for p in &cyc.curve {
            td.push(vec![p.depth, p.force, p.radius, p.unloading as u8 as f64]);
        }
        report.scalar("adhesion.pull_off_force_discrete", cyc.pull_off.force);
        report.scalar(
            "adhesion.pull_off_rel_dev_discrete_vs_semi_analytic",
            rel(cyc.pull_off.force, po.force),
        );
        let stride = (cyc.curve.len() / 60).max(1);
        fig = fig.with(Series::new(
            format!("MRD, {n} discrete springs"),
            cyc.curve
                .iter()
                .step_by(stride)
                .map(|p| (p.depth, p.force))
                .collect(),
            Style::Markers,
        ));
        report.tables.push(td);
    }
    let exact = match cf {
        Some(ClosedForm::Sphere { radius }) => Some((
            match control {
                Control::Force => rf::jkr::pull_off_force_control(radius, gamma),
                Control::Displacement => rf::jkr::pull_off_displacement_control(radius, gamma),
            },
            "JKR",
        )),
        Some(ClosedForm::Cone { slope }) if control == Control::Force => Some((
            rf::adhesive_cone_pull_off(contact.e_star, slope, gamma),
            "Eq. 37",
        )),
        Some(ClosedForm::FlatPunch { radius }) => Some((
            rf::adhesive_flat_punch_pull_off(contact.e_star, radius, gamma),
            "Eq. 34",
        )),
        _ => None,
    };
    if let Some((f_a, source)) = exact {
        report.ran(Stage::ClosedForm);
        report.scalar("adhesion.pull_off_force_closed_form", -f_a);
        report.scalar(
            "adhesion.pull_off_rel_error_vs_closed_form",
            rel(po.force, -f_a),
        );
        if let Some(ClosedForm::Sphere { radius }) = cf {
            let pts: Vec<(f64, f64)> = (0..=points)
                .map(|k| {
                    let a = po.radius + (a_max - po.radius) * k as f64 / points as f64;
                    (
                        rf::jkr::depth(contact.e_star, radius, gamma, a),
                        rf::jkr::force(contact.e_star, radius, gamma, a),
                    )
                })
                .collect();
            fig = fig.with(Series::new("JKR (Johnson et al. 1971)", pts, Style::Dashed));
        }
        fig = fig.with(Series::new(
            format!("pull-off, {source}: F = {:.4e}", -f_a),
            vec![(po.depth, -f_a)],
            Style::Crosses,
        ));
    }
    report.tables.insert(
        report
            .tables
            .len()
            .saturating_sub(springs.is_some() as usize),
        t,
    );
    report.figures.push(fig);
    Ok(())
}

/// Every `n`-th row's (x, y) columns, for marker overlays.
fn subsample(t: &Table, x: usize, y: usize, n: usize) -> Vec<(f64, f64)> {
    let stride = (t.rows.len() / n).max(1);
    t.rows
        .iter()
        .step_by(stride)
        .map(|r| (r[x], r[y]))
        .collect()
}

fn closed_label(cf: ClosedForm) -> String {
    match cf {
        ClosedForm::FlatPunch { .. } => "flat punch, F = 2aE*d (Eq. 1)".into(),
        ClosedForm::Sphere { .. } => "Hertz".into(),
        ClosedForm::Cone { .. } => "cone (Love 1939)".into(),
        ClosedForm::PowerLaw { n, .. } => format!("power law n = {n} (Sneddon 1965)"),
        ClosedForm::FlattenedSphere { .. } => "Ejike 1981 (Eqs. 24-25)".into(),
    }
}

type Curve = Box<dyn Fn(f64) -> f64>;

/// Closed-form F(d), where one exists.
fn closed_force(cf: ClosedForm, e: f64) -> Option<Curve> {
    Some(match cf {
        ClosedForm::FlatPunch { radius } => Box::new(move |d| rf::flat_punch::force(e, radius, d)),
        ClosedForm::Sphere { radius } => Box::new(move |d| rf::hertz::force(e, radius, d)),
        ClosedForm::Cone { slope } => Box::new(move |d| rf::cone::force(e, slope, d)),
        ClosedForm::PowerLaw { c, n } => Box::new(move |d| {
            let a = (d / (mrd::profile::kappa(n) * c)).powf(1.0 / n);
            rf::power_law::force(e, c, n, a)
        }),
        ClosedForm::FlattenedSphere {
            radius,
            flat_radius,
        } => Box::new(move |d| {
            // Invert Eq. (24) for a: a^2 = (a0^2 + sqrt(a0^4 + 4 R^2 d^2))/2.
            let a0 = flat_radius;
            let a = (0.5 * (a0 * a0 + (a0.powi(4) + 4.0 * radius * radius * d * d).sqrt())).sqrt();
            rf::ejike::force(e, radius, a0, a)
        }),
    })
}

/// Closed-form p(r) at depth d (force f), where one exists.
fn closed_pressure(cf: ClosedForm, e: f64, d: f64, f: f64) -> Option<Curve> {
    Some(match cf {
        ClosedForm::FlatPunch { radius } => {
            Box::new(move |r| rf::flat_punch::pressure(f, radius, r))
        }
        ClosedForm::Sphere { radius } => Box::new(move |r| rf::hertz::pressure(e, radius, d, r)),
        ClosedForm::Cone { slope } => Box::new(move |r| rf::cone::pressure(e, slope, d, r)),
        _ => return None,
    })
}
