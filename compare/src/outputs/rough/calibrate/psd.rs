//! `calibrate`'s spectra: the map's or table's C2D and the lines' C1D = lambda q C2D,
//! as a table and two figures.

use super::tasks::{Case, Spectrum};
use crate::report::{Figure, Style, Table};
use std::f64::consts::TAU;

pub(super) fn psd_table(case: &Case, lambda: f64, unit: &str) -> Table {
    let (unit, scale) = match case.spectrum {
        Spectrum::SelfAffine(_) => ("L", 1.0),
        Spectrum::Table { side, .. } => (unit, side),
    };
    // A dimensionless map (length unit "1") has dimensionless spectra: "[1]", not "[1^4]".
    let (unit_q, unit_c, unit_1) = if unit == "1" {
        ("[1]".to_string(), "[1]".to_string(), "[1]".to_string())
    } else {
        (
            format!("[1/{unit}]"),
            format!("[{unit}^4]"),
            format!("[{unit}^3]"),
        )
    };
    let mut t = Table::new(
        "psd",
        &[
            format!("q {unit_q}"),
            format!("C2D {unit_c}"),
            format!("C1D = lambda q C2D {unit_1}"),
        ],
    );
    t.notes.push(format!(
        "the spectrum the punches carry (the source's, to {} x 2 pi / L) and the MRD line's at the calibrated lambda = {lambda:.4}; L = {:.6e}",
        case.band, case.side
    ));
    for k in 1..=case.band {
        // Reduced q' = 2 pi k (units of 1/L); physical q = q' / L, C2D = C2D' L^4.
        let qr = TAU * k as f64;
        let c = case.spectrum.c2d(qr) * scale.powi(4);
        let q = qr / scale;
        t.push(vec![q, c, lambda * q * c]);
    }
    t
}

/// The 2D spectrum (the punches' and, for a map, the map's own) and, on an axis of its
/// own units, the MRD line's C1D = lambda q C2D.
pub(super) fn psd_figures(t: &Table, case: &Case, lambda: f64) -> [Figure; 2] {
    let q = &t.columns[0];
    let punches = t.xy(&t.columns[0], &t.columns[1]);
    let mut c2d = Figure::new(
        "psd",
        if case.map.is_some() {
            "The 2D spectrum of the punches and of the map"
        } else {
            "The 2D spectrum of the punches"
        },
        &format!("wavenumber {q}"),
        &format!("C2D {}", unit(&t.columns[1])),
    )
    .plot(
        format!("C2D of the 3D punch faces (to B = {})", case.band),
        punches.clone(),
        Style::Line,
    );
    if let Some(m) = &case.map {
        // The map's periodogram to twice the punches' band, and above a floor 1e-12 below
        // the punches' smallest C2D: beyond, it is the heights' rounding, not the surface.
        let q_max = punches.iter().map(|p| p.0).fold(0.0, f64::max);
        let c_min = punches.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let shown: Vec<(f64, f64)> = m
            .psd
            .iter()
            .copied()
            .filter(|&(q, c)| q <= 2.0 * q_max && c >= 1e-12 * c_min)
            .collect();
        c2d = c2d.plot(
            format!(
                "the map's PSD ({0} x {0}, mean plane removed, Hann window, radial average; to 2 B)",
                m.n
            ),
            shown,
            Style::Markers,
        );
    }
    let c1d = Figure::new(
        "psd_line",
        "The MRD line's spectrum, C1D = lambda q C2D (Eq. 76)",
        &format!("wavenumber {q}"),
        &format!("C1D {}", unit(&t.columns[2])),
    )
    .plot(
        format!("C1D of the MRD lines, lambda = {lambda:.3}"),
        t.xy(&t.columns[0], &t.columns[2]),
        Style::Line,
    );
    [c2d.log_log(), c1d.log_log()]
}

/// The "[unit]" at the end of a column header.
fn unit(header: &str) -> &str {
    header.rfind(" [").map_or("", |i| &header[i + 1..])
}
