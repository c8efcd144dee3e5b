//! Tables, figures and scalars of `rough_adhesion_3d`: the adhesion map (pull-off,
//! adhesion coefficient and loop energy against roughness, 3D and MRD, with intervals
//! over realisations) and the loops of one realisation per case.

use super::cycles::{Cases, Cycle};
use super::{band_moments, RoughAdhesion3d, Variant};
use crate::error::Result;
use crate::output::Env;
use crate::report::{Figure, Section, Series, Style, Table};
use mrd::rough_contact::Stat;

/// One row of the map: a case on one side (3D grid, or MRD with one lambda).
struct Row {
    hurst: f64,
    roughness: f64,
    grid: usize,
    lambda: f64,
    /// 0: 3D; MRD's rule code ([`super::Rule::code`]).
    rule: f64,
    pull_off: Stat,
    coefficient: Stat,
    hysteresis: Stat,
    force_max: f64,
}

fn row(
    (hurst, roughness): (f64, f64),
    (grid, lambda, rule): (usize, f64, f64),
    c: &[Cycle],
    smooth: f64,
) -> Row {
    let of = |f: &dyn Fn(&Cycle) -> f64| Stat::of(&c.iter().map(f).collect::<Vec<_>>());
    Row {
        hurst,
        roughness,
        grid,
        lambda,
        rule,
        pull_off: of(&|c| c.pull_off / smooth),
        coefficient: of(&|c| c.pull_off / c.force_max),
        hysteresis: of(&|c| c.hysteresis),
        force_max: of(&|c| c.force_max).mean,
    }
}

pub fn report(
    spec: &RoughAdhesion3d,
    env: &Env,
    variants: &[Variant],
    all_3d: &Cases,
    all_1d: &Cases,
    out: &mut Section,
) -> Result<()> {
    let smooth = spec.smooth_pull_off(env.ctx.material.e_star);
    let mut rows = Vec::new();
    for ((h, rough), per_grid) in all_3d {
        for (g, cycles) in per_grid.iter().enumerate() {
            rows.push(row((*h, *rough), (spec.cells[g], 0.0, 0.0), cycles, smooth));
        }
    }
    for ((h, rough), per_variant) in all_1d {
        let hi = spec.hurst.iter().position(|x| x == h).unwrap_or(0);
        for (v, cycles) in variants.iter().zip(per_variant) {
            let side = (0, v.lambda[hi], v.rule.code());
            rows.push(row((*h, *rough), side, cycles, smooth));
        }
    }
    let t = map_table(spec, env, &rows)?;
    scalars(spec, &rows, variants, out);
    let finest = *spec.cells.last().unwrap_or(&0);
    let by_roughness = match spec.body() {
        super::Body::Sphere(_) => "rms roughness / JKR length (pi^2 w^2 R / E*^2)^(1/3) [1]",
        super::Body::Punch(_) => "rms roughness / critical opening sqrt(2 pi a w / E*) [1]",
    };
    let (bodies, closed) = match spec.body() {
        super::Body::Sphere(_) => ("spheres", "(3/2 pi R w)"),
        super::Body::Punch(_) => ("flat punches", "sqrt(8 pi a^3 E* w)"),
    };
    let pull_off_axis = format!("pull-off force / {closed} [1]");
    let titles = [
        format!("Pull-off of rough adhesive {bodies}: 3D against MRD"),
        format!("Pull-off of rough adhesive {bodies} against the rms slope"),
    ];
    let energy = format!("loop area [{}]", env.ctx.units.energy());
    for (name, (x_col, x), stem, title, y) in [
        (
            "pull_off",
            ("roughness_over_adhesion_length", by_roughness),
            "pull_off_over_smooth",
            titles[0].as_str(),
            pull_off_axis.as_str(),
        ),
        (
            "pull_off_vs_slope",
            ("rms_slope", "rms slope of the roughness [1]"),
            "pull_off_over_smooth",
            titles[1].as_str(),
            pull_off_axis.as_str(),
        ),
        (
            "adhesion_coefficient",
            ("roughness_over_adhesion_length", by_roughness),
            "adhesion_coefficient",
            "Adhesion coefficient (pull-off over pressing force): 3D against MRD",
            "pull-off / force at depth_max [1]",
        ),
        (
            "loop_energy",
            ("roughness_over_adhesion_length", by_roughness),
            "loop_energy",
            "Energy lost in one adhesive loading-unloading cycle: 3D against MRD",
            energy.as_str(),
        ),
    ] {
        let axes = MapAxes { x_col, x, stem, y };
        out.figures
            .push(map_figure(spec, &t, finest, variants, name, title, axes));
    }
    let loops = loops_table(spec, env, all_3d, all_1d, variants);
    out.figures.push(loops_figure(spec, env, &loops, finest));
    out.tables.push(t);
    out.tables.push(loops);
    Ok(())
}

fn map_table(spec: &RoughAdhesion3d, env: &Env, rows: &[Row]) -> Result<Table> {
    let u = &env.ctx.units;
    let (len, force, energy) = (&u.length, u.force(), u.energy());
    let cols = vec![
        "hurst [1]".to_string(),
        "roughness_over_adhesion_length [1]".into(),
        format!("rms_height [{len}]"),
        "rms_slope [1]".into(),
        "flattening_energy_over_work [1]".into(),
        "grid [cells]".into(),
        "lambda [1]".into(),
        "mrd_rule [0 3D, 1 outer radius, 2 cluster]".into(),
        "realisations [count]".into(),
        "pull_off_over_smooth_mean [1]".into(),
        "pull_off_over_smooth_ci95_low [1]".into(),
        "pull_off_over_smooth_ci95_high [1]".into(),
        "adhesion_coefficient_mean [1]".into(),
        "adhesion_coefficient_ci95_low [1]".into(),
        "adhesion_coefficient_ci95_high [1]".into(),
        format!("loop_energy_mean [{energy}]"),
        format!("loop_energy_ci95_low [{energy}]"),
        format!("loop_energy_ci95_high [{energy}]"),
        format!("force_at_depth_max_mean [{force}]"),
    ];
    let mut t = Table::new("adhesion_map", &cols);
    let e_star = env.ctx.material.e_star;
    let delta = spec.adhesion_length(e_star);
    let (body, length, smooth, profile) = match spec.body() {
        super::Body::Sphere(r) => (
            format!("spheres R = {r}"),
            "(pi^2 w^2 R / E*^2)^(1/3)",
            "3/2 pi R w (JKR)",
            "x^2/R",
        ),
        super::Body::Punch(a) => (
            format!("flat punches of radius a = {a}"),
            "sqrt(2 pi a w / E*)",
            "sqrt(8 pi a^3 E* w) (Kendall, Eq. 34)",
            "the flat profile on |x| < a",
        ),
    };
    t.notes.push(format!(
        "rough {body} with self-affine roughness (modes |k| <= {} of 2 pi / {} side), work of adhesion w = {}, loaded to the mean body's approach {} in steps of {:e} and unloaded to separation; roughness = rms height / {length} = h / {:.6e}; grid 0: MRD ({profile} plus a line of C1D = lambda q C2D, springs detaching by the rule of Hess with, in Eq. 33, mrd_rule 1: the contact's outer radius, 2: the half-length of the spring's cluster), lambda 0 and mrd_rule 0: 3D (Pohrt-Popov criterion on the free half-space, grid^2 cells); pull-off: -(smallest force of the unloading) / {smooth}; adhesion coefficient: pull-off / force at depth_max; loop energy: loading work minus the work returned; flattening energy: E* h^2 <q> / 4 per area, Johnson's alpha for one sinusoid is 1 / sqrt(2 pi x this); intervals: mean +- 1.96 standard errors over realisations (the smooth body: one, no interval)",
        spec.bandwidth, spec.side, spec.work, spec.depth_max, spec.step(), delta
    ));
    for r in rows {
        let (slope, flat) = if r.roughness > 0.0 {
            let g = spec.geometry(r.hurst, *spec.cells.last().unwrap_or(&16));
            let (q1, q2) = band_moments(&g)?;
            let h = r.roughness * delta;
            (h * q2.sqrt(), e_star * h * h * q1 / (4.0 * spec.work))
        } else {
            (0.0, 0.0)
        };
        let ci = |s: &Stat| {
            if s.count > 1 {
                (s.mean - s.ci95, s.mean + s.ci95)
            } else {
                (s.mean, s.mean)
            }
        };
        let (p, c, w) = (ci(&r.pull_off), ci(&r.coefficient), ci(&r.hysteresis));
        t.push(vec![
            r.hurst,
            r.roughness,
            r.roughness * delta,
            slope,
            flat,
            r.grid as f64,
            r.lambda,
            r.rule,
            r.pull_off.count as f64,
            r.pull_off.mean,
            p.0,
            p.1,
            r.coefficient.mean,
            c.0,
            c.1,
            r.hysteresis.mean,
            w.0,
            w.1,
            r.force_max,
        ]);
    }
    Ok(t)
}

/// The verdict in numbers: the smooth sphere on both sides, MRD against the finest 3D
/// grid per lambda, and the 3D change under the last refinement.
fn scalars(spec: &RoughAdhesion3d, rows: &[Row], variants: &[Variant], out: &mut Section) {
    let finest = *spec.cells.last().unwrap_or(&0);
    let find = |h: f64, r: f64, grid: usize, v: Option<usize>| {
        let mut it = rows
            .iter()
            .filter(move |x| x.hurst == h && x.roughness == r && x.grid == grid);
        match v {
            Some(k) => it.nth(k),
            None => it.next(),
        }
    };
    if let Some(s) = find(0.0, 0.0, finest, None) {
        out.scalar("smooth_pull_off_over_closed_form_3d", s.pull_off.mean);
    }
    if let Some(s) = find(0.0, 0.0, 0, Some(0)) {
        out.scalar("smooth_pull_off_over_closed_form_mrd", s.pull_off.mean);
    }
    // Adhesion makes every cycle lose energy: the smallest loop (over the smooth 3D one)
    // must be positive.
    if let Some(s) = find(0.0, 0.0, finest, None) {
        let least = rows
            .iter()
            .map(|r| r.hysteresis.mean)
            .fold(f64::INFINITY, f64::min);
        out.scalar("loop_energy_min_over_smooth_3d", least / s.hysteresis.mean);
    }
    if spec.cells.len() > 1 {
        let coarse = spec.cells[spec.cells.len() - 2];
        let mut refine = 0.0f64;
        for r in rows.iter().filter(|r| r.grid == finest) {
            if let Some(c) = find(r.hurst, r.roughness, coarse, None) {
                refine = refine.max((r.pull_off.mean - c.pull_off.mean).abs());
            }
        }
        out.scalar(
            "pull_off_over_smooth_max_abs_change_last_refinement_3d",
            refine,
        );
    }
    for (k, v) in variants.iter().enumerate() {
        let mut worst = 0.0f64;
        for r in rows
            .iter()
            .filter(|r| r.grid == finest && r.roughness > 0.0)
        {
            if let Some(m) = find(r.hurst, r.roughness, 0, Some(k)) {
                worst = worst.max((m.pull_off.mean - r.pull_off.mean).abs());
            }
        }
        let rule = match v.rule {
            super::Rule::Outer => "outer",
            super::Rule::Cluster => "cluster",
        };
        out.scalar(
            format!("pull_off_over_smooth_max_abs_dev_mrd_{rule}_{k}_vs_3d"),
            worst,
        );
    }
}

/// A map figure's axes: the x column and label, the y columns' stem (`_mean`,
/// `_ci95_low`, `_ci95_high`) and label.
struct MapAxes<'a> {
    x_col: &'a str,
    x: &'a str,
    stem: &'a str,
    y: &'a str,
}

fn map_figure(
    spec: &RoughAdhesion3d,
    t: &Table,
    finest: usize,
    variants: &[Variant],
    name: &str,
    title: &str,
    axes: MapAxes,
) -> Figure {
    let MapAxes { x_col, x, stem, y } = axes;
    let c = |n: &str| t.index(n);
    let (ih, ir, ig, il, irule) = (
        c("hurst"),
        c("roughness_over_adhesion_length"),
        c("grid"),
        c("lambda"),
        c("mrd_rule"),
    );
    let x_col = c(x_col);
    let (col, lo, hi) = (
        c(&format!("{stem}_mean")),
        c(&format!("{stem}_ci95_low")),
        c(&format!("{stem}_ci95_high")),
    );
    let title = format!("{title} (means, 95 % intervals)");
    let mut fig = Figure::new(name, &title, x, y);
    // One colour per Hurst exponent; 3D markers, MRD lines (dashed for the outer radius,
    // solid for the cluster's half-length; thin for every lambda after the first); the
    // smooth sphere at 0 starts every series.
    let pick = |h: f64, grid: usize, how: Option<(f64, f64)>| -> Vec<&Vec<f64>> {
        let on_side =
            |r: &&Vec<f64>| r[ig] == grid as f64 && how.is_none_or(|(rule, _)| r[irule] == rule);
        let smooth = t.rows.iter().filter(on_side).find(|r| r[ir] == 0.0);
        smooth
            .into_iter()
            .chain(
                t.rows
                    .iter()
                    .filter(on_side)
                    .filter(|r| r[ih] == h && r[ir] > 0.0 && how.is_none_or(|(_, l)| r[il] == l)),
            )
            .collect()
    };
    for (k, &h) in spec.hurst.iter().enumerate() {
        let rows = pick(h, finest, None);
        fig = fig.with(
            Series::new(
                format!(
                    "3D, H = {h} ({} surfaces, {finest}^2 cells)",
                    spec.realisations_3d
                ),
                rows.iter().map(|r| (r[x_col], r[col])).collect(),
                Style::Markers,
            )
            .with_bars(rows.iter().map(|r| (r[x_col], r[lo], r[hi])).collect())
            .colored(k),
        );
        for (j, v) in variants.iter().enumerate() {
            let rows = pick(h, 0, Some((v.rule.code(), v.lambda[k])));
            let style = if v.rule == super::Rule::Outer {
                Style::Dashed
            } else {
                Style::Line
            };
            let series = Series::new(
                format!(
                    "MRD, H = {h}, {}, lambda {:.2} ({} lines)",
                    v.rule.name(),
                    v.lambda[k],
                    spec.realisations_1d
                ),
                rows.iter().map(|r| (r[x_col], r[col])).collect(),
                style,
            )
            .with_bars(rows.iter().map(|r| (r[x_col], r[lo], r[hi])).collect())
            .colored(k);
            // Variants run rule by rule, each through the lambdas in order.
            let first_lambda = j % spec.lambda.len().max(1) == 0;
            fig = fig.with(if first_lambda { series } else { series.thin() });
        }
    }
    fig
}

/// Realisation 0 of every case: the 3D loops on each grid and MRD's per lambda.
fn loops_table(
    spec: &RoughAdhesion3d,
    env: &Env,
    all_3d: &Cases,
    all_1d: &Cases,
    variants: &[Variant],
) -> Table {
    let u = &env.ctx.units;
    let mut t = Table::new(
        "loops",
        &[
            "hurst [1]".to_string(),
            "roughness_over_adhesion_length [1]".into(),
            "grid [cells]".into(),
            "lambda [1]".into(),
            "mrd_rule [0 3D, 1 outer radius, 2 cluster]".into(),
            format!("approach [{}]", u.length),
            format!("force [{}]", u.force()),
            "unloading [0/1]".into(),
        ],
    );
    t.notes.push(
        "realisation 0 of each case; approach of the mean body from its apex; grid 0: MRD (mrd_rule 1: outer radius, 2: cluster half-length), lambda 0 and mrd_rule 0: 3D"
            .into(),
    );
    let mut push = |h: f64, r: f64, (grid, lam, rule): (usize, f64, f64), c: &Cycle| {
        for &(d, f, unl) in &c.curve {
            t.push(vec![h, r, grid as f64, lam, rule, d, f, unl as u8 as f64]);
        }
    };
    for ((h, r), per_grid) in all_3d {
        for (g, cycles) in per_grid.iter().enumerate() {
            if let Some(c) = cycles.first() {
                push(*h, *r, (spec.cells[g], 0.0, 0.0), c);
            }
        }
    }
    for ((h, r), per_variant) in all_1d {
        let hi = spec.hurst.iter().position(|x| x == h).unwrap_or(0);
        for (v, cycles) in variants.iter().zip(per_variant) {
            if let Some(c) = cycles.first() {
                push(*h, *r, (0, v.lambda[hi], v.rule.code()), c);
            }
        }
    }
    t
}

/// The loops of the first Hurst exponent for the smooth sphere, the middle and the
/// largest roughness: 3D on the finest grid (markers) and MRD with the first lambda by
/// each rule (dashed: outer radius, solid: cluster), one colour per roughness.
fn loops_figure(spec: &RoughAdhesion3d, env: &Env, t: &Table, finest: usize) -> Figure {
    let u = &env.ctx.units;
    let h = spec.hurst.first().copied().unwrap_or(0.0);
    let mut fig = Figure::new(
        "loops",
        &format!("Adhesive loops (H = {h}, realisation 0): 3D against MRD"),
        &format!("approach of the mean body d [{}]", u.length),
        &format!("normal force F [{}]", u.force()),
    );
    let mut levels = vec![0.0];
    let n = spec.roughness.len();
    levels.extend([spec.roughness[n / 2], spec.roughness[n - 1]]);
    levels.dedup();
    let c = |n: &str| t.index(n);
    let (ih, ir, ig, il, irule, id, iforce) = (
        c("hurst"),
        c("roughness_over_adhesion_length"),
        c("grid"),
        c("lambda"),
        c("mrd_rule"),
        c("approach"),
        c("force"),
    );
    let lambda = t
        .rows
        .iter()
        .find(|r| r[ig] == 0.0 && r[ir] > 0.0)
        .map(|r| r[il]);
    for (k, &rough) in levels.iter().enumerate() {
        let hh = if rough == 0.0 { 0.0 } else { h };
        let of = |grid: usize, rule: f64| -> Vec<(f64, f64)> {
            t.rows
                .iter()
                .filter(|r| {
                    r[ih] == hh
                        && r[ir] == rough
                        && r[ig] == grid as f64
                        && r[irule] == rule
                        && (grid > 0 || lambda.is_none_or(|l| r[il] == l || rough == 0.0))
                })
                .map(|r| (r[id], r[iforce]))
                .collect()
        };
        // About 60 markers per loop, so the lines beneath stay visible.
        let all = of(finest, 0.0);
        let stride = (all.len() / 60).max(1);
        let pts: Vec<(f64, f64)> = all.into_iter().step_by(stride).collect();
        fig = fig.with(
            Series::new(
                format!("3D, h / adhesion length = {rough}, {finest}^2 cells"),
                pts,
                Style::Markers,
            )
            .colored(k),
        );
        for (i, rule) in spec.rules().iter().enumerate() {
            let mut m = of(0, rule.code());
            let label = if rough == 0.0 {
                // The smooth sphere's loop is the same for every lambda and both rules
                // (one contact): draw one.
                if i > 0 {
                    continue;
                }
                m.truncate(m.len() / spec.lambda.len().max(1));
                "MRD (either rule), h / adhesion length = 0".to_string()
            } else {
                format!("MRD ({}), h / adhesion length = {rough}", rule.name())
            };
            let style = if *rule == super::Rule::Outer {
                Style::Dashed
            } else {
                Style::Line
            };
            fig = fig.with(Series::new(label, m, style).colored(k));
        }
    }
    fig
}
