//! Tables, figures and the report folder.
//!
//! Every CSV starts with a `#` comment block (tool version, scene origin, the scene text
//! as given, seed) followed by one header line whose column names carry units. Figures
//! are PNGs with labelled axes and a legend. The whole folder is written into a
//! temporary sibling directory and renamed into place, so a failed run leaves no
//! partial output and an interrupted write never replaces a previous report.

use crate::error::{io_err, CompareError, Result};
use plotters::prelude::*;
use serde_json::{json, Map, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A named table; column names include units, e.g. `depth [m]`.
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub name: String,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<f64>>,
    /// Extra comment lines (method, tolerances) written under the provenance block.
    pub notes: Vec<String>,
    /// Undefined values (NaN) are written as empty cells; otherwise they are an error.
    pub missing_ok: bool,
}

impl Table {
    pub fn new(name: &str, columns: &[String]) -> Self {
        Self {
            name: name.into(),
            columns: columns.to_vec(),
            ..Default::default()
        }
    }
    pub fn push(&mut self, row: Vec<f64>) {
        debug_assert_eq!(row.len(), self.columns.len());
        self.rows.push(row);
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    Line,
    Dashed,
    Markers,
    Crosses,
}

#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    /// Palette index; None: the series' position.
    pub color: Option<usize>,
    /// Vertical error bars (x, low, high).
    pub bars: Vec<(f64, f64, f64)>,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        Self {
            label: label.into(),
            points,
            style,
            color: None,
            bars: Vec::new(),
        }
    }
    pub fn with_bars(mut self, bars: Vec<(f64, f64, f64)>) -> Self {
        self.bars = bars;
        self
    }
    /// Same colour as series `index` of the figure (e.g. both bounds of a band).
    pub fn colored(mut self, index: usize) -> Self {
        self.color = Some(index);
        self
    }
}

#[derive(Debug, Clone)]
pub struct Figure {
    pub name: String,
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub log_x: bool,
    pub log_y: bool,
}

impl Figure {
    pub fn new(name: &str, title: &str, x_label: &str, y_label: &str) -> Self {
        Self {
            name: name.into(),
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            log_x: false,
            log_y: false,
        }
    }
    pub fn with(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }
}

/// Everything a run produces.
#[derive(Debug, Default)]
pub struct Report {
    pub tables: Vec<Table>,
    pub figures: Vec<Figure>,
    pub scalars: Map<String, Value>,
    pub warnings: Vec<String>,
    pub stages: Vec<String>,
    /// (kind, label) of the output being run: scalars `kind.x` are stored as `label.x`,
    /// so that two outputs of one kind keep separate results.
    pub current: Option<(String, String)>,
    /// Extra files (name, bytes), e.g. requested fields as .npy.
    pub files: Vec<(String, Vec<u8>)>,
}

impl Report {
    pub fn scalar(&mut self, key: impl Into<String>, value: f64) {
        let mut key = key.into();
        if let Some((kind, label)) = &self.current {
            if let Some(rest) = key.strip_prefix(&format!("{kind}.")) {
                key = format!("{label}.{rest}");
            }
        }
        self.scalars.insert(key, json!(value));
    }
    /// Records a stage as run (once).
    pub fn ran(&mut self, stage: crate::plan::Stage) {
        let n = stage.name().to_string();
        if !self.stages.contains(&n) {
            self.stages.push(n);
        }
    }
    /// Makes table and figure names unique by suffixing _2, _3, ...
    pub fn dedupe_names(&mut self) {
        fn fix(names: Vec<&mut String>) {
            let mut seen: Vec<String> = Vec::new();
            for n in names {
                let base = n.clone();
                let mut k = 1;
                while seen.contains(n) {
                    k += 1;
                    *n = format!("{base}_{k}");
                }
                seen.push(n.clone());
            }
        }
        fix(self.tables.iter_mut().map(|t| &mut t.name).collect());
        fix(self.figures.iter_mut().map(|f| &mut f.name).collect());
    }
}

/// Provenance written at the top of every CSV and into summary.json.
#[derive(Debug, Clone)]
pub struct Provenance {
    pub tool: String,
    pub scene_name: String,
    pub scene_origin: String,
    pub scene_text: String,
    pub seed: Option<u64>,
}

fn csv_text(table: &Table, prov: &Provenance) -> Result<String> {
    let mut s = String::new();
    let _ = writeln!(s, "# {} -- table `{}`", prov.tool, table.name);
    let _ = writeln!(
        s,
        "# scene `{}` from {}",
        prov.scene_name, prov.scene_origin
    );
    let _ = writeln!(
        s,
        "# seed: {}",
        prov.seed
            .map_or("none (deterministic)".to_string(), |v| v.to_string())
    );
    for n in &table.notes {
        let _ = writeln!(s, "# {n}");
    }
    let _ = writeln!(s, "# scene file as given:");
    for line in prov.scene_text.lines() {
        let _ = writeln!(s, "#   {line}");
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&table.columns)
        .map_err(|e| csv_err(&table.name, e))?;
    for row in &table.rows {
        if let Some((j, v)) = row
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() || (table.missing_ok && v.is_nan())))
        {
            return Err(CompareError::Scene(format!(
                "internal: non-finite value {v} in table `{}` column `{}`",
                table.name, table.columns[j]
            )));
        }
        w.write_record(row.iter().map(|v| {
            if v.is_nan() {
                String::new()
            } else {
                format!("{v:e}")
            }
        }))
        .map_err(|e| csv_err(&table.name, e))?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| CompareError::Scene(e.to_string()))?;
    s.push_str(&String::from_utf8_lossy(&bytes));
    Ok(s)
}

fn csv_err(name: &str, e: csv::Error) -> CompareError {
    CompareError::Scene(format!("writing table {name}: {e}"))
}

const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

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
    let pts = fig
        .series
        .iter()
        .flat_map(|s| s.points.iter())
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

fn plot_err(file: &Path, e: impl std::fmt::Display) -> CompareError {
    CompareError::Plot {
        file: file.display().to_string(),
        message: e.to_string(),
    }
}

macro_rules! draw_with {
    ($root:expr, $fig:expr, $path:expr, $xs:expr, $ys:expr) => {{
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
            .x_label_formatter(&|v| fmt_tick(*v))
            .y_label_formatter(&|v| fmt_tick(*v))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| plot_err($path, e))?;
        for (i, s) in $fig.series.iter().enumerate() {
            let color = PALETTE[s.color.unwrap_or(i) % PALETTE.len()];
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|(x, y)| {
                    x.is_finite()
                        && y.is_finite()
                        && (!$fig.log_x || *x > 0.0)
                        && (!$fig.log_y || *y > 0.0)
                })
                .collect();
            let label = s.label.as_str();
            let show = !label.is_empty();
            for &(x, lo, hi) in &s.bars {
                if x.is_finite() && lo.is_finite() && hi.is_finite() && (!$fig.log_y || lo > 0.0) {
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(x, lo), (x, hi)],
                            color.stroke_width(1),
                        )))
                        .map_err(|e| plot_err($path, e))?;
                }
            }
            let err = |e| plot_err($path, e);
            match s.style {
                Style::Line => {
                    let anno = chart
                        .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                        .map_err(err)?;
                    if show {
                        anno.label(label).legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(2))
                        });
                    }
                }
                Style::Dashed => {
                    let anno = chart
                        .draw_series(DashedLineSeries::new(pts, 8, 6, color.stroke_width(2)))
                        .map_err(err)?;
                    if show {
                        anno.label(label).legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 8, y)], color.stroke_width(2))
                        });
                    }
                }
                Style::Markers => {
                    let anno = chart
                        .draw_series(
                            pts.into_iter()
                                .map(|p| Circle::new(p, 4, color.stroke_width(2))),
                        )
                        .map_err(err)?;
                    if show {
                        anno.label(label).legend(move |(x, y)| {
                            Circle::new((x + 10, y), 4, color.stroke_width(2))
                        });
                    }
                }
                Style::Crosses => {
                    let anno = chart
                        .draw_series(
                            pts.into_iter()
                                .map(|p| Cross::new(p, 6, color.stroke_width(2))),
                        )
                        .map_err(err)?;
                    if show {
                        anno.label(label).legend(move |(x, y)| {
                            Cross::new((x + 10, y), 6, color.stroke_width(2))
                        });
                    }
                }
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .label_font(("sans-serif", 15))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(|e| plot_err($path, e))?;
    }};
}

fn fmt_tick(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-3 {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Renders one figure to a PNG file.
pub fn render(fig: &Figure, path: &Path) -> Result<()> {
    ensure_font();
    let root = BitMapBackend::new(path, (1000, 680)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(path, e))?;
    let ((x0, x1), (y0, y1)) = bounds(fig);
    match (fig.log_x, fig.log_y) {
        (false, false) => draw_with!(root, fig, path, x0..x1, y0..y1),
        (true, false) => draw_with!(root, fig, path, (x0..x1).log_scale(), y0..y1),
        (false, true) => draw_with!(root, fig, path, x0..x1, (y0..y1).log_scale()),
        (true, true) => draw_with!(root, fig, path, (x0..x1).log_scale(), (y0..y1).log_scale()),
    }
    root.present().map_err(|e| plot_err(path, e))?;
    Ok(())
}

/// Writes the report atomically into `out_dir` (created or replaced).
pub fn write(
    report: &Report,
    prov: &Provenance,
    out_dir: &Path,
    wall_time_s: f64,
) -> Result<Vec<PathBuf>> {
    let parent = match out_dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent).map_err(io_err(format!("creating {}", parent.display())))?;
    let tmp = tempfile::Builder::new()
        .prefix(".mrdw-partial-")
        .tempdir_in(&parent)
        .map_err(io_err(format!(
            "creating a temporary folder in {}",
            parent.display()
        )))?;
    let mut files = Vec::new();
    for t in &report.tables {
        let name = format!("{}.csv", t.name);
        std::fs::write(tmp.path().join(&name), csv_text(t, prov)?)
            .map_err(io_err(format!("writing {name}")))?;
        files.push(name);
    }
    for f in &report.figures {
        let name = format!("{}.png", f.name);
        render(f, &tmp.path().join(&name))?;
        files.push(name);
    }
    for (name, bytes) in &report.files {
        std::fs::write(tmp.path().join(name), bytes).map_err(io_err(format!("writing {name}")))?;
        files.push(name.clone());
    }
    let summary = json!({
        "tool": prov.tool,
        "scene": prov.scene_name,
        "scene_origin": prov.scene_origin,
        "seed": prov.seed,
        "stages": report.stages,
        "results": report.scalars,
        "warnings": report.warnings,
        "files": files,
        "wall_time_s": wall_time_s,
    });
    let text =
        serde_json::to_string_pretty(&summary).map_err(|e| CompareError::Scene(e.to_string()))?;
    std::fs::write(tmp.path().join("summary.json"), text + "\n")
        .map_err(io_err("writing summary.json"))?;
    files.push("summary.json".into());
    // Swap into place: move an existing report aside first, then rename the new one in.
    let staged = tmp.keep();
    if out_dir.exists() {
        let old = parent.join(format!(
            ".mrdw-old-{}-{}",
            out_dir
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or("report"),
            std::process::id()
        ));
        std::fs::rename(out_dir, &old)
            .map_err(io_err(format!("moving aside {}", out_dir.display())))?;
        std::fs::rename(&staged, out_dir)
            .map_err(io_err(format!("renaming into {}", out_dir.display())))?;
        let _ = std::fs::remove_dir_all(&old);
    } else {
        std::fs::rename(&staged, out_dir)
            .map_err(io_err(format!("renaming into {}", out_dir.display())))?;
    }
    Ok(files.into_iter().map(|f| out_dir.join(f)).collect())
}
