//! PNG rendering of figures (plotters, bitmap backend, embedded DejaVu Sans).

use super::figure::{Figure, Series, Style};
use crate::error::{CompareError, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

const FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");

fn ensure_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(90, 90, 90),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
];

fn bounds(fig: &Figure) -> ((f64, f64), (f64, f64)) {
    // Points and the ends of error bars.
    let bar_ends: Vec<(f64, f64)> = fig
        .series
        .iter()
        .flat_map(|s| s.bars.iter().flat_map(|&(x, lo, hi)| [(x, lo), (x, hi)]))
        .collect();
    let pts = fig
        .series
        .iter()
        .flat_map(|s| s.points.iter())
        .chain(bar_ends.iter())
        .filter(|(x, y)| {
            x.is_finite() && y.is_finite() && (!fig.log_x || *x > 0.0) && (!fig.log_y || *y > 0.0)
        });
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = |lo: f64, hi: f64, log: bool| -> (f64, f64) {
        if log {
            let (l, h) = (lo.ln(), hi.ln());
            let p = 0.05 * (h - l).max(1e-3);
            ((l - p).exp(), (h + p).exp())
        } else {
            let p = 0.05 * (hi - lo).abs().max(1e-12 * hi.abs().max(1e-300));
            (lo - p, hi + p)
        }
    };
    (pad(x0, x1, fig.log_x), pad(y0, y1, fig.log_y))
}

/// The corner for the legend that covers the fewest data: points, lines and error bars
/// (sampled along each segment) are counted inside an estimate of the legend box, in
/// axis coordinates scaled to [0, 1]; ties keep the upper left.
type Bounds = ((f64, f64), (f64, f64));

/// The least fraction of the plot's height the data keep when headroom is made for the
/// legend; a taller legend goes beside the plot.
const MIN_DATA_HEIGHT: f64 = 0.6;

/// Axis ranges and the legend's place: the corner that covers the fewest data; when
/// every corner covers some, headroom added above the data for the legend, or, if
/// that would leave the data less than [`MIN_DATA_HEIGHT`] of the plot, no legend in
/// the plot (None: it is drawn beside it).
fn layout(fig: &Figure) -> (Bounds, Option<SeriesLabelPosition>) {
    let b = bounds(fig);
    let (covered, corner, h) = legend_corner(fig, b);
    if covered == 0 {
        return (b, Some(corner));
    }
    let ((x0, x1), (y0, y1)) = b;
    let frac = 1.0 - h - 0.02;
    if frac < MIN_DATA_HEIGHT {
        return (b, None);
    }
    let y1 = if fig.log_y {
        (y0.ln() + (y1.ln() - y0.ln()) / frac).exp()
    } else {
        y0 + (y1 - y0) / frac
    };
    let b = ((x0, x1), (y0, y1));
    let (_, corner, _) = legend_corner(fig, b);
    (b, Some(corner))
}

/// The labelled series: (palette colour, style, label).
fn legend_entries(fig: &Figure) -> Vec<(RGBColor, Style, u32, &str)> {
    fig.series
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.label.is_empty())
        .map(|(i, s)| (series_color(i, s), s.style, s.width, s.label.as_str()))
        .collect()
}

fn series_color(index: usize, s: &Series) -> RGBColor {
    PALETTE[s.color.unwrap_or(index) % PALETTE.len()]
}

/// Width in pixels of a legend drawn beside the plot.
fn side_legend_width(fig: &Figure) -> u32 {
    let chars = legend_entries(fig)
        .iter()
        .map(|e| e.3.chars().count())
        .max()
        .unwrap_or(0);
    (chars as f64 * 8.5 + 60.0) as u32
}

/// The legend beside the plot: one row per labelled series, from the plot area's top,
/// each with the glyph of its style.
fn draw_side_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    fig: &Figure,
    path: &Path,
) -> Result<()> {
    let err = |e| plot_err(path, e);
    for (k, (color, style, width, label)) in legend_entries(fig).into_iter().enumerate() {
        let y = 66 + 21 * k as i32;
        let pen = color.stroke_width(width);
        match style {
            Style::Line => area.draw(&PathElement::new(vec![(4, y), (26, y)], pen)),
            Style::Dashed => area.draw(&PathElement::new(vec![(4, y), (12, y)], pen)),
            Style::Markers => area.draw(&Circle::new((14, y), 4, pen)),
            Style::Crosses => area.draw(&Cross::new((14, y), 6, pen)),
        }
        .map_err(err)?;
        let font = ("sans-serif", 15).into_font().color(&BLACK);
        let text = Text::new(
            label.to_string(),
            (34, y),
            font.pos(Pos::new(HPos::Left, VPos::Center)),
        );
        area.draw(&text).map_err(err)?;
    }
    Ok(())
}

/// The legend corner covering the fewest points (and that count, and the legend's
/// height as a fraction of the plot) for axis ranges `b`.
fn legend_corner(fig: &Figure, b: Bounds) -> (usize, SeriesLabelPosition, f64) {
    let labels: Vec<&str> = fig
        .series
        .iter()
        .map(|s| s.label.as_str())
        .filter(|l| !l.is_empty())
        .collect();
    if labels.is_empty() {
        return (0, SeriesLabelPosition::UpperLeft, 0.0);
    }
    let ((x0, x1), (y0, y1)) = b;
    let scale = |v: f64, lo: f64, hi: f64, log: bool| {
        if log {
            (v.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else {
            (v - lo) / (hi - lo)
        }
    };
    // Plot area about 880 x 550 px; legend rows 21 px, text about 8.5 px a character.
    let chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let w = (chars as f64 * 8.5 + 45.0) / 880.0;
    let h = (labels.len() as f64 * 21.0 + 12.0) / 550.0;
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for s in &fig.series {
        let p: Vec<(f64, f64)> = s
            .points
            .iter()
            .filter(|(x, y)| {
                x.is_finite()
                    && y.is_finite()
                    && (!fig.log_x || *x > 0.0)
                    && (!fig.log_y || *y > 0.0)
            })
            .map(|&(x, y)| (scale(x, x0, x1, fig.log_x), scale(y, y0, y1, fig.log_y)))
            .collect();
        let joined = matches!(s.style, Style::Line | Style::Dashed);
        for (k, &a) in p.iter().enumerate() {
            pts.push(a);
            if let (true, Some(&b)) = (joined, p.get(k + 1)) {
                for t in 1..16 {
                    let t = t as f64 / 16.0;
                    pts.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                }
            }
        }
        // Error bars are data too: each sampled along its length.
        for &(x, lo, hi) in &s.bars {
            if !(x.is_finite() && lo.is_finite() && hi.is_finite())
                || (fig.log_x && x <= 0.0)
                || (fig.log_y && lo <= 0.0)
            {
                continue;
            }
            let u = scale(x, x0, x1, fig.log_x);
            let (v0, v1) = (scale(lo, y0, y1, fig.log_y), scale(hi, y0, y1, fig.log_y));
            for t in 0..=16 {
                pts.push((u, v0 + t as f64 / 16.0 * (v1 - v0)));
            }
        }
    }
    let corners = [
        (SeriesLabelPosition::UpperLeft, 0.0, 1.0 - h),
        (SeriesLabelPosition::UpperRight, 1.0 - w, 1.0 - h),
        (SeriesLabelPosition::LowerRight, 1.0 - w, 0.0),
        (SeriesLabelPosition::LowerLeft, 0.0, 0.0),
    ];
    let covered = |u0: f64, v0: f64| {
        pts.iter()
            .filter(|p| p.0 >= u0 && p.0 <= u0 + w && p.1 >= v0 && p.1 <= v0 + h)
            .count()
    };
    corners
        .into_iter()
        .map(|(c, u0, v0)| (covered(u0, v0), c, h))
        .min_by_key(|c| c.0)
        .expect("four corners")
}

fn plot_err(file: &Path, e: impl std::fmt::Display) -> CompareError {
    CompareError::Plot {
        file: file.display().to_string(),
        message: e.to_string(),
    }
}

macro_rules! draw_with {
    ($root:expr, $fig:expr, $path:expr, $xs:expr, $ys:expr, $corner:expr, $zero:expr) => {{
        let (x_zero, y_zero): (f64, f64) = $zero;
        let mut chart = ChartBuilder::on(&$root)
            .caption(&$fig.title, ("sans-serif", 24))
            .margin(18)
            .x_label_area_size(56)
            .y_label_area_size(86)
            .build_cartesian_2d($xs, $ys)
            .map_err(|e| plot_err($path, e))?;
        chart
            .configure_mesh()
            .x_desc($fig.x_label.as_str())
            .y_desc($fig.y_label.as_str())
            .x_labels(8)
            .y_labels(8)
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 18))
            .x_label_formatter(&|v| fmt_tick(*v, x_zero))
            .y_label_formatter(&|v| fmt_tick(*v, y_zero))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| plot_err($path, e))?;
        for (i, s) in $fig.series.iter().enumerate() {
            let color = series_color(i, s);
            let width = s.width;
            let drawable = |&(x, y): &(f64, f64)| {
                x.is_finite()
                    && y.is_finite()
                    && (!$fig.log_x || x > 0.0)
                    && (!$fig.log_y || y > 0.0)
            };
            let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(drawable).collect();
            // A point that cannot be drawn (e.g. NaN where a quantity is undefined)
            // breaks a line instead of being bridged.
            let runs: Vec<Vec<(f64, f64)>> = s
                .points
                .split(|p| !drawable(p))
                .filter(|r| !r.is_empty())
                .map(<[(f64, f64)]>::to_vec)
                .collect();
            let label = s.label.as_str();
            let show = !label.is_empty();
            // Error bars: a stroke as wide as the series' with caps of 8 pixels, so that
            // an interval reads at a glance and stays visible beside a marker.
            for &(x, lo, hi) in &s.bars {
                if x.is_finite() && lo.is_finite() && hi.is_finite() && (!$fig.log_y || lo > 0.0) {
                    let stroke = color.stroke_width(width.min(2));
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(x, lo), (x, hi)],
                            stroke,
                        )))
                        .map_err(|e| plot_err($path, e))?;
                    chart
                        .draw_series([lo, hi].into_iter().map(|y| {
                            EmptyElement::at((x, y))
                                + PathElement::new(vec![(-4, 0), (4, 0)], stroke)
                        }))
                        .map_err(|e| plot_err($path, e))?;
                }
            }
            let err = |e| plot_err($path, e);
            match s.style {
                Style::Line => {
                    for (k, run) in runs.into_iter().enumerate() {
                        let anno = chart
                            .draw_series(LineSeries::new(run, color.stroke_width(width)))
                            .map_err(err)?;
                        if show && k == 0 {
                            anno.label(label).legend(move |(x, y)| {
                                PathElement::new(
                                    vec![(x, y), (x + 22, y)],
                                    color.stroke_width(width),
                                )
                            });
                        }
                    }
                }
                Style::Dashed => {
                    for (k, run) in runs.into_iter().enumerate() {
                        let anno = chart
                            .draw_series(DashedLineSeries::new(
                                run,
                                8,
                                6,
                                color.stroke_width(width),
                            ))
                            .map_err(err)?;
                        if show && k == 0 {
                            anno.label(label).legend(move |(x, y)| {
                                PathElement::new(
                                    vec![(x, y), (x + 8, y)],
                                    color.stroke_width(width),
                                )
                            });
                        }
                    }
                }
                Style::Markers => {
                    let anno = chart
                        .draw_series(
                            pts.into_iter()
                                .map(|p| Circle::new(p, 4, color.stroke_width(width))),
                        )
                        .map_err(err)?;
                    if show {
                        anno.label(label).legend(move |(x, y)| {
                            Circle::new((x + 10, y), 4, color.stroke_width(width))
                        });
                    }
                }
                Style::Crosses => {
                    let anno = chart
                        .draw_series(
                            pts.into_iter()
                                .map(|p| Cross::new(p, 6, color.stroke_width(width))),
                        )
                        .map_err(err)?;
                    if show {
                        anno.label(label).legend(move |(x, y)| {
                            Cross::new((x + 10, y), 6, color.stroke_width(width))
                        });
                    }
                }
            }
        }
        if let Some(corner) = $corner {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .label_font(("sans-serif", 15))
                .position(corner)
                .draw()
                .map_err(|e| plot_err($path, e))?;
        }
    }};
}

/// A tick label; `zero` is the magnitude below which a value is the axis' zero (a
/// linear axis' key points are sums of steps: a key meant to be 0 may come out as
/// 1e-17 of the range).
fn fmt_tick(v: f64, zero: f64) -> String {
    if v.abs() <= zero {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-3 {
        // "1e-4" beside "0.001", not "1.0e-4"; "2.5e-4" keeps its digit.
        format!("{v:.1e}").replace(".0e", "e")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Labelled points of a log axis on [lo, hi] (plotters alone labels too few on short
/// ranges): 1 to 9 times the powers of ten within one decade, 1, 2 and 5 times them
/// within three, the powers of ten beyond.
fn log_keys(lo: f64, hi: f64) -> Vec<f64> {
    // A range a log axis cannot show (or wider than the doubles): no labels, no loop
    // over billions of decades.
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return Vec::new();
    }
    let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let steps: &[f64] = if hi / lo < 10.0 {
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]
    } else if hi / lo < 1e3 {
        &[1.0, 2.0, 5.0]
    } else {
        &[1.0]
    };
    (a..=b)
        .flat_map(|k| steps.iter().map(move |m| m * 10f64.powi(k)))
        .filter(|v| (lo..=hi).contains(v))
        .collect()
}

/// Renders one figure to a PNG file.
/// Width over height of the plotting area of a 1000 x 680 image (its margins and label
/// areas taken off).
const PLOT_ASPECT: f64 = 1.6;

/// The ranges widened about their centres so that a unit of x and of y have one length
/// on the page.
fn equal_ranges((x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let (dx, dy) = (x1 - x0, y1 - y0);
    if !(dx > 0.0 && dy > 0.0) {
        return ((x0, x1), (y0, y1));
    }
    let widen = |lo: f64, hi: f64, span: f64| {
        let c = 0.5 * (lo + hi);
        (c - 0.5 * span, c + 0.5 * span)
    };
    if dx < PLOT_ASPECT * dy {
        (widen(x0, x1, PLOT_ASPECT * dy), (y0, y1))
    } else {
        ((x0, x1), widen(y0, y1, dx / PLOT_ASPECT))
    }
}

pub fn render(fig: &Figure, path: &Path) -> Result<()> {
    ensure_font();
    let (((x0, x1), (y0, y1)), corner) = layout(fig);
    let ((x0, x1), (y0, y1)) = if fig.equal_axes && !fig.log_x && !fig.log_y {
        equal_ranges((x0, x1), (y0, y1))
    } else {
        ((x0, x1), (y0, y1))
    };
    // A legend beside the plot widens the image (the plot keeps its size) and, if need
    // be, heightens it.
    let (side, rows) = match corner {
        Some(_) => (0, 0),
        None => (side_legend_width(fig), legend_entries(fig).len() as u32),
    };
    let height = 680.max(66 + 21 * rows + 20);
    let canvas = BitMapBackend::new(path, (1000 + side, height)).into_drawing_area();
    canvas.fill(&WHITE).map_err(|e| plot_err(path, e))?;
    let (root, beside) = canvas.split_horizontally(1000);
    if side > 0 {
        draw_side_legend(&beside, fig, path)?;
    }
    let x_keys = match &fig.x_keys {
        Some(keys) => keys
            .iter()
            .copied()
            .filter(|v| (x0..=x1).contains(v))
            .collect(),
        None => log_keys(x0, x1),
    };
    // Below 1e-9 of a linear axis' range a tick is its zero; log axes have none.
    let zero = |lo: f64, hi: f64, log: bool| if log { 0.0 } else { 1e-9 * (hi - lo).abs() };
    let zeros = (zero(x0, x1, fig.log_x), zero(y0, y1, fig.log_y));
    match (fig.log_x, fig.log_y) {
        (false, false) => draw_with!(root, fig, path, x0..x1, y0..y1, corner, zeros),
        (true, false) => draw_with!(
            root,
            fig,
            path,
            (x0..x1).log_scale().with_key_points(x_keys),
            y0..y1,
            corner,
            zeros
        ),
        (false, true) => draw_with!(
            root,
            fig,
            path,
            x0..x1,
            (y0..y1).log_scale().with_key_points(log_keys(y0, y1)),
            corner,
            zeros
        ),
        (true, true) => draw_with!(
            root,
            fig,
            path,
            (x0..x1).log_scale().with_key_points(x_keys),
            (y0..y1).log_scale().with_key_points(log_keys(y0, y1)),
            corner,
            zeros
        ),
    }
    canvas.present().map_err(|e| plot_err(path, e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{fmt_tick, layout, log_keys, render};

    /// A linear axis' key meant as 0 but off by rounding is labelled 0; small values on
    /// a log axis (no zero) and real values keep their labels.
    #[test]
    fn tick_labels_show_the_axis_zero_not_its_rounding() {
        assert_eq!(fmt_tick(6.9e-18, 1e-9 * 0.5), "0");
        assert_eq!(fmt_tick(-2.0e-17, 1e-9 * 3.0), "0");
        assert_eq!(fmt_tick(6.9e-18, 0.0), "6.9e-18");
        assert_eq!(fmt_tick(0.25, 1e-9), "0.25");
        assert_eq!(fmt_tick(2.0e-4, 1e-9 * 1e-3), "2e-4");
        assert_eq!(fmt_tick(2.5e-4, 0.0), "2.5e-4");
        assert_eq!(fmt_tick(-1.0e5, 0.0), "-1e5");
    }
    use crate::report::figure::{Figure, Style};

    /// Eighteen lines across the whole plot: every corner covers data and headroom for
    /// an 18-row legend would squeeze them into 3/10 of the height, so the legend goes
    /// beside the plot (a wider image) and the y range stays the data's. Two lines keep
    /// a legend inside.
    #[test]
    fn a_tall_legend_goes_beside_the_plot() {
        let lines = |n: usize| {
            (0..n).fold(Figure::new("f", "t", "x", "y"), |f, k| {
                let y = k as f64;
                let pts = (0..=10).map(|i| (i as f64, y + 0.1 * i as f64)).collect();
                f.plot(format!("line {k}"), pts, Style::Line)
            })
        };
        let (((_, _), (_, y1)), corner) = layout(&lines(18));
        assert!(corner.is_none() && y1 < 19.0, "{y1}");
        assert!(layout(&lines(2)).1.is_some());
        let dir = crate::files::ScratchDir::new().unwrap();
        let file = dir.path().join("f.png");
        render(&lines(18), &file).unwrap();
        let png = std::fs::read(&file).unwrap();
        let width = u32::from_be_bytes([png[16], png[17], png[18], png[19]]);
        assert!(width > 1000, "{width}");
    }

    /// Error bars count as data for the legend's place: markers along the bottom with
    /// one bar up into the upper left corner keep the legend out of that corner.
    #[test]
    fn the_legend_does_not_cover_error_bars() {
        use super::{legend_corner, SeriesLabelPosition};
        let markers: Vec<(f64, f64)> = (0..=10).map(|i| (i as f64, 0.0)).collect();
        let plain = Figure::new("f", "t", "x", "y").plot("m", markers.clone(), Style::Markers);
        let b = ((0.0, 10.0), (0.0, 10.0));
        assert!(matches!(
            legend_corner(&plain, b).1,
            SeriesLabelPosition::UpperLeft
        ));
        let barred = Figure::new("f", "t", "x", "y").with(
            crate::report::figure::Series::new("m", markers, Style::Markers)
                .with_bars(vec![(0.2, 0.0, 9.9)]),
        );
        let (covered, corner, _) = legend_corner(&barred, b);
        assert_eq!(covered, 0);
        assert!(!matches!(corner, SeriesLabelPosition::UpperLeft));
    }

    #[test]
    fn log_keys_by_span_and_on_degenerate_ranges() {
        assert_eq!(log_keys(28.0, 75.0), vec![30.0, 40.0, 50.0, 60.0, 70.0]);
        assert_eq!(
            log_keys(1.5, 120.0),
            vec![2.0, 5.0, 10.0, 20.0, 50.0, 100.0]
        );
        assert_eq!(log_keys(1e-7, 1e2).len(), 10);
        for (lo, hi) in [
            (0.0, 1.0),
            (1.0, f64::INFINITY),
            (f64::NAN, 1.0),
            (2.0, 1.0),
        ] {
            assert!(log_keys(lo, hi).is_empty(), "{lo} {hi}");
        }
        assert!(log_keys(1e-300, 1e300).len() <= 601);
    }
}
