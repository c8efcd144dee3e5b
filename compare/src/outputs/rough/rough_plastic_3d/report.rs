//! `rough_plastic_3d`'s report: the loading stiffness against the force, the readings
//! by plasticity index with the refit of lambda, the load history's figures.

use super::*;
use crate::report::{Figure, Section, Series, Style, Table};
use std::f64::consts::PI;

impl RoughPlastic3d {
    pub(super) fn report(&self, out: &mut Section, d: &Data) {
        let setting = self.setting(d);
        self.stiffness_report(out, d, &setting);
        let (s, refits, retrace) = self.by_plasticity(d, setting);
        let fine = self.scalars(out, &s, &refits, retrace);
        Self::plasticity_figures(out, &fine, &refits, d.lambda);
        out.tables.push(s);
        self.history_report(out, d);
    }

    /// The setting every table states.
    fn setting(&self, d: &Data) -> String {
        let (h, slope, lambda) = (d.h, d.slope, d.lambda);
        format!(
            "rough punch of diameter L = 1 on E* = 1: self-affine face H = {}, wave vectors 1..{} (units 2 pi / L), fixed amplitudes, spectral rms height h = {h:.4e} and slope h' = {slope:.4e} over the square; hardness H = h' / psi; 3D on free grids of {:?} cells per shortest wavelength, {} faces per case; MRD lines of {} springs, C1D = lambda q C2D with lambda = {lambda:.4} (the refit scans 0.5-2 times it), {} lines per case, each spring's line load capped patch by patch at 2 H sqrt(a^2 - (x - c)^2) (mrd::plastic_line); f = F / (E* h L); intervals: 95 % of the mean over faces (3D) and lines (MRD)",
            self.hurst, self.bandwidth, self.cells, self.realisations_3d, self.springs, self.lines
        )
    }

    /// The loading stiffness against the force, per case and grid: table and figure
    /// (finest grid).
    fn stiffness_report(&self, out: &mut Section, d: &Data, setting: &str) {
        let (cases, forces) = (&d.cases[..], &d.forces[..]);
        let finest = self.cells.len() - 1;
        // The loading stiffness against the force, per case, finest grid.
        let mut t = Table::new(
            "loading_stiffness",
            &[
                "psi [1]",
                "cells per wavelength [count]",
                "f [1]",
                "k_3D / (E* L) [1]",
                "k_3D low [1]",
                "k_3D high [1]",
                "k_MRD / (E* L) [1]",
                "k_MRD low [1]",
                "k_MRD high [1]",
            ],
        );
        t.notes.push(setting.to_string());
        t.notes.push(
            "k: the secant dF/dd between successive steps of the first loading, at their geometric mean force; geometric means over the runs with their 95 % intervals; MRD at the scene's lambda".into(),
        );
        let fs = &forces[..self.loads];
        let at = |runs: &[Reading], i: usize| {
            let v: Vec<f64> = runs.iter().map(|r| r.ln_k[i]).collect();
            mean_ci(&v)
        };
        for (c, &psi) in cases.iter().enumerate() {
            for g in 0..self.cells.len() {
                for i in 0..self.loads - 1 {
                    let (m3, e3) = at(d.three(c, g), i);
                    let (m1, e1) = at(d.mrd(c, UNIT), i);
                    t.push(vec![
                        psi,
                        self.cells[g] as f64,
                        (fs[i] * fs[i + 1]).sqrt(),
                        m3.exp(),
                        (m3 - e3).exp(),
                        (m3 + e3).exp(),
                        m1.exp(),
                        (m1 - e1).exp(),
                        (m1 + e1).exp(),
                    ]);
                }
            }
        }
        let mut fig = Figure::new(
            "loading_stiffness",
            "Rough punch, first loading: stiffness against force, 3D (markers) and MRD (lines)",
            "reduced force f = F / (E* h L) [1]",
            "loading stiffness k / (E* L) [1]",
        )
        .log_log();
        for (c, &psi) in cases.iter().enumerate() {
            let rows: Vec<&Vec<f64>> = t
                .rows
                .iter()
                .filter(|r| r[0] == psi && r[1] == self.cells[finest] as f64)
                .collect();
            fig = fig
                .with(
                    Series::new(
                        format!("3D {}", psi_label(psi)),
                        rows.iter().map(|r| (r[2], r[3])).collect(),
                        Style::Markers,
                    )
                    .with_bars(rows.iter().map(|r| (r[2], r[4], r[5])).collect())
                    .colored(c),
                )
                .with(
                    Series::new(
                        format!("MRD {}", psi_label(psi)),
                        rows.iter().map(|r| (r[2], r[6])).collect(),
                        Style::Line,
                    )
                    .colored(c),
                );
        }
        out.tables.push(t);
        out.figures.push(fig);
    }

    /// Per case and grid: the ratios, the fractions, the refit (the table, the refits of
    /// the finest grid, the largest reload retrace).
    fn by_plasticity(&self, d: &Data, setting: String) -> (Table, Vec<Refit>, f64) {
        let (cases, slope, lambda) = (&d.cases[..], d.slope, d.lambda);
        let finest = self.cells.len() - 1;
        // Per case and grid: the ratios, the fractions, the refit.
        let mut s = Table::new(
            "by_plasticity",
            &[
                "psi [1]",
                "hardness H / E* [1]",
                "cells per wavelength [count]",
                "loading k_MRD / k_3D [1]",
                "low [1]",
                "high [1]",
                "unloading k_MRD / k_3D [1]",
                "low [1]",
                "high [1]",
                "recovered approach MRD / 3D [1]",
                "low [1]",
                "high [1]",
                "approach at the peak MRD / 3D [1]",
                "low [1]",
                "high [1]",
                "3D contact fraction at the peak [1]",
                "3D plastic share of the contact at the peak [1]",
                "MRD capped share of the contact at the peak [1]",
                "3D H A / F at the peak [1]",
                "lambda refitted [1]",
                "low [1]",
                "high [1]",
            ],
        );
        s.missing_ok = true;
        s.notes.push(setting);
        s.notes.push(
            "ratios: exp of the difference of the mean logs (loading: each run's mean over the loading intervals), intervals from both sides' 95 % intervals added in quadrature; recovered approach: from the peak to 0.02 of it; approach at the peak: from each run's first contact; empty hardness and H A / F: the elastic case; lambda refitted: where the lines' mean log loading stiffness meets the 3D's, interpolated in ln lambda over the scanned factors (empty: outside 0.5-2 times lambda), its interval from the 3D interval's ends".into(),
        );
        let peak = self.loads - 1;
        let mut retrace: f64 = 0.0;
        let mut refits: Vec<Refit> = vec![];
        for (c, &psi) in cases.iter().enumerate() {
            let hard = if psi == 0.0 {
                f64::INFINITY
            } else {
                slope / psi
            };
            let mrd1 = d.mrd(c, UNIT);
            for g in 0..self.cells.len() {
                let bem = d.three(c, g);
                for r in bem.iter().chain(mrd1) {
                    retrace = retrace.max(r.retrace);
                }
                let ratio = |a: (f64, f64), b: (f64, f64)| {
                    let e = a.1.hypot(b.1);
                    let d = a.0 - b.0;
                    [d.exp(), (d - e).exp(), (d + e).exp()]
                };
                let pick = |runs: &[Reading], q: &dyn Fn(&Reading) -> f64| {
                    mean_ci(&runs.iter().map(q).collect::<Vec<_>>())
                };
                let load = ratio(Self::loading(mrd1), Self::loading(bem));
                let unl = ratio(
                    pick(mrd1, &|r| r.ln_k_unload),
                    pick(bem, &|r| r.ln_k_unload),
                );
                let rec = ratio(
                    pick(mrd1, &|r| r.ln_recovery),
                    pick(bem, &|r| r.ln_recovery),
                );
                let top = ratio(pick(mrd1, &|r| r.ln_peak), pick(bem, &|r| r.ln_peak));
                let mean_at = |runs: &[Reading], q: &dyn Fn(&Point) -> f64| {
                    runs.iter().map(|r| q(&r.points[peak])).sum::<f64>() / runs.len() as f64
                };
                let contact = mean_at(bem, &|p| p.contact);
                let plastic = mean_at(bem, &|p| p.plastic);
                let capped = mean_at(mrd1, &|p| p.plastic);
                let area_ratio = if hard.is_finite() {
                    mean_at(bem, &|p| hard * p.contact * PI / 4.0 / p.force)
                } else {
                    f64::NAN
                };
                // The refit: the lines' mean log loading stiffness against ln(factor).
                let target = Self::loading(bem);
                let curve: Vec<(f64, f64)> = (0..REFIT.len())
                    .map(|k| (REFIT[k].ln(), Self::loading(d.mrd(c, k)).0))
                    .collect();
                let fit = |y: f64| crossing(&curve, y).map(|x| lambda * x.exp());
                let (best, lo, hi) = (
                    fit(target.0),
                    fit(target.0 + target.1),
                    fit(target.0 - target.1),
                );
                if g == finest {
                    refits.push((psi, best, lo, hi));
                }
                s.push(vec![
                    psi,
                    if hard.is_finite() { hard } else { f64::NAN },
                    self.cells[g] as f64,
                    load[0],
                    load[1],
                    load[2],
                    unl[0],
                    unl[1],
                    unl[2],
                    rec[0],
                    rec[1],
                    rec[2],
                    top[0],
                    top[1],
                    top[2],
                    contact,
                    plastic,
                    capped,
                    area_ratio,
                    best.unwrap_or(f64::NAN),
                    lo.unwrap_or(f64::NAN),
                    hi.unwrap_or(f64::NAN),
                ]);
            }
        }
        (s, refits, retrace)
    }

    /// The finest grid's scalars; returns its rows.
    fn scalars(
        &self,
        out: &mut Section,
        s: &Table,
        refits: &[Refit],
        retrace: f64,
    ) -> Vec<Vec<f64>> {
        let finest = self.cells.len() - 1;
        // Scalars: the finest grid's.
        let rows_at = |g: usize| -> Vec<Vec<f64>> {
            s.rows
                .iter()
                .filter(|r| r[2] == self.cells[g] as f64)
                .cloned()
                .collect()
        };
        let fine = rows_at(finest);
        let (first, last) = (&fine[0], &fine[fine.len() - 1]);
        out.scalar("loading_ratio_elastic", first[3]);
        out.scalar("loading_ratio_most_plastic", last[3]);
        out.scalar("unloading_ratio_elastic", first[6]);
        out.scalar("unloading_ratio_most_plastic", last[6]);
        out.scalar("recovery_ratio_most_plastic", last[9]);
        out.scalar("peak_approach_ratio_elastic", first[12]);
        out.scalar("peak_approach_ratio_most_plastic", last[12]);
        out.scalar("plastic_share_3d_most_plastic", last[16]);
        out.scalar("capped_share_mrd_most_plastic", last[17]);
        out.scalar("area_hardness_over_force_most_plastic", last[18]);
        out.scalar("reload_retrace_max", retrace);
        if let (Some((_, Some(e), ..)), Some((_, Some(p), ..))) = (refits.first(), refits.last()) {
            out.scalar("lambda_refit_elastic", *e);
            out.scalar("lambda_refit_most_plastic", *p);
        }
        // The grid's effect: the largest change of ln(loading ratio) from the coarser grid.
        if self.cells.len() > 1 {
            let coarse = rows_at(finest - 1);
            let change = fine
                .iter()
                .zip(&coarse)
                .map(|(a, b)| (a[3] / b[3]).ln().abs())
                .fold(0.0, f64::max);
            out.scalar("loading_ratio_grid_change_max", change);
        }
        fine
    }

    /// The ratios and the refit against psi.
    fn plasticity_figures(out: &mut Section, fine: &[Vec<f64>], refits: &[Refit], lambda: f64) {
        let first = &fine[0];
        // Ratios against psi, each quantity a few per cent apart in psi so that the bars
        // stay apart, with the elastic case's value dashed in its colour.
        let plastic_rows: Vec<&Vec<f64>> = fine.iter().filter(|r| r[0] > 0.0).collect();
        let (x0, x1) = (
            plastic_rows.first().map_or(1.0, |r| r[0]),
            plastic_rows.last().map_or(1.0, |r| r[0]),
        );
        let quantities = [
            (3, "loading stiffness", Style::Markers),
            (6, "unloading stiffness at the peak", Style::Crosses),
            (9, "recovered approach", Style::Markers),
            (12, "approach at the peak", Style::Crosses),
        ];
        let mut ratio_fig = Figure::new(
            "ratio_against_plasticity",
            "MRD over 3D against the plasticity index (dashed: the elastic case's)",
            "plasticity index psi = E* h'_rms / H [1]",
            "MRD / 3D [1]",
        );
        for (k, &(col, label, style)) in quantities.iter().enumerate() {
            let shift = 1.0 + 0.04 * (k as f64 - 1.5);
            ratio_fig = ratio_fig.with(
                Series::new(
                    label,
                    plastic_rows
                        .iter()
                        .map(|r| (r[0] * shift, r[col]))
                        .collect(),
                    style,
                )
                .with_bars(
                    plastic_rows
                        .iter()
                        .map(|r| (r[0] * shift, r[col + 1], r[col + 2]))
                        .collect(),
                )
                .colored(k),
            );
        }
        for (k, &(col, label, _)) in quantities.iter().enumerate() {
            ratio_fig = ratio_fig.with(
                Series::new(
                    format!("{label}, elastic"),
                    vec![(x0, first[col]), (x1, first[col])],
                    Style::Dashed,
                )
                .colored(k),
            );
        }
        ratio_fig.log_x = true;
        out.figures.push(ratio_fig);
        let fitted: Vec<&Refit> = refits
            .iter()
            .filter(|r| r.0 > 0.0 && r.1.is_some())
            .collect();
        let mut lambda_fig = Figure::new(
            "lambda_refit",
            "lambda refitted to the 3D loading stiffness against the plasticity index",
            "plasticity index psi = E* h'_rms / H [1]",
            "lambda of Eq. (76) [1]",
        )
        .with(
            Series::new(
                "refitted at psi",
                fitted
                    .iter()
                    .map(|r| (r.0, r.1.unwrap_or(f64::NAN)))
                    .collect(),
                Style::Markers,
            )
            .with_bars(
                fitted
                    .iter()
                    .filter_map(|r| Some((r.0, r.2?, r.3?)))
                    .collect(),
            ),
        )
        .plot(
            "the scene's lambda",
            vec![(x0, lambda), (x1, lambda)],
            Style::Dashed,
        );
        if let Some((_, Some(e), ..)) = refits.first() {
            lambda_fig =
                lambda_fig.plot("refitted, elastic", vec![(x0, *e), (x1, *e)], Style::Line);
        }
        lambda_fig.log_x = true;
        out.figures.push(lambda_fig);
    }

    /// The mean history of the elastic and the most plastic case, both methods, finest
    /// grid: table and loop figure.
    fn history_report(&self, out: &mut Section, d: &Data) {
        let (cases, forces) = (&d.cases[..], &d.forces[..]);
        let finest = self.cells.len() - 1;
        // The mean history of the most plastic case, both methods, finest grid.
        let c = cases.len() - 1;
        let mut hist = Table::new(
            "history",
            &[
                "psi [1]",
                "step [index]",
                "f [1]",
                "3D approach [length]",
                "3D approach low [length]",
                "3D approach high [length]",
                "MRD approach [length]",
                "3D contact fraction [1]",
                "MRD contact fraction [1]",
                "3D plastic share [1]",
                "MRD capped share [1]",
            ],
        );
        hist.notes.push(format!(
            "means over the runs at each step of the history (first loading, unloading to {UNLOAD:?} and reloading to {RELOAD:?} of the peak); 3D on the finest grid; approaches from each run's first contact; 3D contact fraction: contact area over the face's disc; MRD contact fraction: the share of springs in contact (a length fraction of the line, not an area)"
        ));
        for c in [0, c] {
            let (bem, lines) = (d.three(c, finest), d.mrd(c, UNIT));
            for (k, &f) in forces.iter().enumerate() {
                let m = |runs: &[Reading], q: &dyn Fn(&Point) -> f64| {
                    mean_ci(&runs.iter().map(|r| q(&r.points[k])).collect::<Vec<_>>())
                };
                let (d3, e3) = m(bem, &|p| p.approach);
                hist.push(vec![
                    cases[c],
                    k as f64,
                    f,
                    d3,
                    d3 - e3,
                    d3 + e3,
                    m(lines, &|p| p.approach).0,
                    m(bem, &|p| p.contact).0,
                    m(lines, &|p| p.contact).0,
                    m(bem, &|p| p.plastic).0,
                    m(lines, &|p| p.plastic).0,
                ]);
            }
        }
        let mut loop_fig = Figure::new(
            "loop",
            "Force against approach, mean over the runs (dashed: unloading, reloading)",
            "approach from first contact d / L [1]",
            "reduced force f = F / (E* h L) [1]",
        );
        // The first loading, then the unloading from the peak and the reloading.
        let branches = [(0, self.loads), (self.loads - 1, forces.len())];
        for (i, &c) in [0, c].iter().enumerate() {
            let rows: Vec<&Vec<f64>> = hist.rows.iter().filter(|r| r[0] == cases[c]).collect();
            for (method, col, style) in [("3D", 3, Style::Markers), ("MRD", 6, Style::Line)] {
                for (b, &(from, to)) in branches.iter().enumerate() {
                    let style = match (style, b) {
                        (Style::Line, 1) => Style::Dashed,
                        (Style::Markers, 1) => Style::Crosses,
                        (s, _) => s,
                    };
                    let label = match b {
                        0 => format!("{method} {}, loading", psi_label(cases[c])),
                        _ => format!("{method} {}, unloading and reloading", psi_label(cases[c])),
                    };
                    loop_fig = loop_fig.with(
                        Series::new(
                            label,
                            rows[from..to].iter().map(|r| (r[col], r[2])).collect(),
                            style,
                        )
                        .colored(i),
                    );
                }
            }
        }
        out.figures.push(loop_fig);
        out.tables.push(hist);
    }
}

/// The psi of a case as a label.
fn psi_label(psi: f64) -> String {
    if psi == 0.0 {
        "elastic".to_string()
    } else {
        format!("psi = {psi}")
    }
}

/// The scene's lambda in the refit's scan (factor 1).
const UNIT: usize = 2;

/// The x where the piecewise-linear `curve` (x increasing, y monotone) takes `y`.
fn crossing(curve: &[(f64, f64)], y: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        let t = (y - y0) / (y1 - y0);
        (t.is_finite() && (0.0..=1.0).contains(&t)).then_some(x0 + t * (x1 - x0))
    })
}
