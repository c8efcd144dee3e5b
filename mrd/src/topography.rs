//! Height maps on disk: NumPy `.npy` (float32/float64, little or big endian, C or
//! Fortran order, format versions 1-3), plain-text matrices (whitespace, comma or
//! semicolon separated; `#` comments), the ESRI ASCII grid (a text matrix after an
//! `ncols` / `nrows` / `cellsize` header, as profilometer and GIS software export it)
//! and x-y-z point lists (`.xyz`: one `x y z` line per point of a regular grid, in any
//! order), plus two-column profile tables (r, z). Arrays are returned row-major
//! `rows x cols`, row index along y (the ESRI grid's first row, its top, becomes the
//! last). The grid and point-list formats carry their cell size
//! ([`HeightMap::read_with_cell`]); the others leave the size to the caller.

use crate::error::{MrdError, Result};
use std::path::Path;

/// A 2D array of heights, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    pub rows: usize,
    pub cols: usize,
    pub data: Vec<f64>,
}

fn bad(path: &Path, what: impl std::fmt::Display) -> MrdError {
    MrdError::InvalidData(format!("{}: {what}", path.display()))
}

/// Why `path` cannot be read as a height file, if it cannot: missing, a folder, or a
/// device or socket (a regular file or a named pipe is read).
pub fn unreadable(path: &Path) -> Option<String> {
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Some(format!("no such file {}", path.display()))
        }
        Err(e) => return Some(format!("{}: {e}", path.display())),
    };
    let kind = meta.file_type();
    #[cfg(unix)]
    let pipe = std::os::unix::fs::FileTypeExt::is_fifo(&kind);
    #[cfg(not(unix))]
    let pipe = false;
    if kind.is_dir() {
        Some(format!("{} is a folder, not a height file", path.display()))
    } else if !kind.is_file() && !pipe {
        Some(format!(
            "{} is a device or socket, not a height file",
            path.display()
        ))
    } else {
        None
    }
}

impl HeightMap {
    fn checked(self, path: &Path) -> Result<Self> {
        if self.rows == 0 || self.cols == 0 {
            return Err(bad(path, "empty array"));
        }
        if let Some(i) = self.data.iter().position(|v| !v.is_finite()) {
            return Err(bad(
                path,
                format!(
                    "non-finite height at row {}, column {}",
                    i / self.cols + 1,
                    i % self.cols + 1
                ),
            ));
        }
        Ok(self)
    }

    /// Reads `.npy`, `.xyz` or text depending on the extension (a text file with an
    /// ESRI header is read as that grid).
    pub fn read(path: &Path) -> Result<Self> {
        Ok(Self::read_with_cell(path)?.0)
    }

    /// [`Self::read`], and the cell size `(dx, dy)` where the file states it (ESRI grid,
    /// x-y-z list).
    pub fn read_with_cell(path: &Path) -> Result<(Self, Option<(f64, f64)>)> {
        if let Some(why) = unreadable(path) {
            return Err(MrdError::InvalidData(why));
        }
        let ext = |e: &str| path.extension().is_some_and(|x| x.eq_ignore_ascii_case(e));
        if ext("npy") {
            return Ok((Self::read_npy(path)?, None));
        }
        let text = std::fs::read_to_string(path).map_err(|e| bad(path, e))?;
        // A byte-order mark, as Windows programs write before UTF-8 text.
        let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
        let (map, cell) = if ext("xyz") {
            let (m, cell) = parse_xyz(text).map_err(|m| bad(path, m))?;
            (m, Some(cell))
        } else if let Some(grid) = parse_esri(text).map_err(|m| bad(path, m))? {
            (grid.0, Some(grid.1))
        } else {
            (Self::parse_text(path, text)?, None)
        };
        Ok((map.checked(path)?, cell))
    }

    pub fn read_npy(path: &Path) -> Result<Self> {
        let bytes = std::fs::read(path).map_err(|e| bad(path, e))?;
        Self::parse_npy(&bytes)
            .map_err(|m| bad(path, m))?
            .checked(path)
    }

    fn parse_npy(b: &[u8]) -> std::result::Result<Self, String> {
        if b.len() < 10 || &b[..6] != b"\x93NUMPY" {
            return Err("not a .npy file (bad magic)".into());
        }
        let (hlen, start) = match b[6] {
            1 => (u16::from_le_bytes([b[8], b[9]]) as usize, 10),
            2 | 3 => {
                if b.len() < 12 {
                    return Err("truncated header".into());
                }
                (u32::from_le_bytes([b[8], b[9], b[10], b[11]]) as usize, 12)
            }
            v => return Err(format!("unsupported .npy version {v}")),
        };
        let header = std::str::from_utf8(b.get(start..start + hlen).ok_or("truncated header")?)
            .map_err(|_| "header is not text")?;
        let field = |key: &str| -> std::result::Result<&str, String> {
            let k = header
                .find(&format!("'{key}'"))
                .ok_or(format!("header lacks '{key}'"))?;
            let rest = &header[k + key.len() + 2..];
            let colon = rest.find(':').ok_or("malformed header")?;
            Ok(rest[colon + 1..].trim_start())
        };
        let descr = field("descr")?;
        let descr = descr.trim_start_matches('\'');
        let descr = &descr[..descr.find('\'').ok_or("malformed descr")?];
        let fortran = field("fortran_order")?.starts_with("True");
        let shape_txt = field("shape")?;
        let close = shape_txt.find(')').ok_or("malformed shape")?;
        if !shape_txt.starts_with('(') || close == 0 {
            return Err("malformed shape".into());
        }
        let shape_txt = &shape_txt[1..close];
        let shape: Vec<usize> = shape_txt
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(|s| {
                s.parse::<usize>()
                    .map_err(|_| format!("bad shape entry `{s}`"))
            })
            .collect::<std::result::Result<_, _>>()?;
        let (rows, cols) = match shape.as_slice() {
            [r, c] => (*r, *c),
            [n] => (1, *n),
            s => return Err(format!("expected a 1D or 2D array, got shape {s:?}")),
        };
        let body = &b[start + hlen..];
        let n = rows.checked_mul(cols).ok_or("shape too large")?;
        let (size, big, float32) = match descr {
            "<f8" | "=f8" | "|f8" => (8, false, false),
            ">f8" => (8, true, false),
            "<f4" | "=f4" | "|f4" => (4, false, true),
            ">f4" => (4, true, true),
            d => return Err(format!("unsupported dtype `{d}` (need float32 or float64)")),
        };
        if n.checked_mul(size).is_none_or(|bytes| body.len() < bytes) {
            return Err(format!(
                "data truncated: {} bytes for {n} values of {size} bytes",
                body.len()
            ));
        }
        let mut vals: Vec<f64> = body[..n * size]
            .chunks_exact(size)
            .map(|c| match (float32, big) {
                (false, false) => f64::from_le_bytes(c.try_into().unwrap()),
                (false, true) => f64::from_be_bytes(c.try_into().unwrap()),
                (true, false) => f32::from_le_bytes(c.try_into().unwrap()) as f64,
                (true, true) => f32::from_be_bytes(c.try_into().unwrap()) as f64,
            })
            .collect();
        if fortran && rows > 1 {
            let mut c_order = vec![0.0; n];
            for j in 0..cols {
                for i in 0..rows {
                    c_order[i * cols + j] = vals[j * rows + i];
                }
            }
            vals = c_order;
        }
        Ok(Self {
            rows,
            cols,
            data: vals,
        })
    }

    /// Writes a float64 C-order `.npy` (version 1.0).
    pub fn write_npy(&self, path: &Path) -> Result<()> {
        std::fs::write(path, self.to_npy_bytes()).map_err(|e| bad(path, e))
    }

    /// The float64 C-order `.npy` (version 1.0) encoding of the map.
    pub fn to_npy_bytes(&self) -> Vec<u8> {
        let mut header = format!(
            "{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}",
            self.rows, self.cols
        );
        while (10 + header.len() + 1) % 64 != 0 {
            header.push(' ');
        }
        header.push('\n');
        let mut out = Vec::with_capacity(10 + header.len() + 8 * self.data.len());
        out.extend_from_slice(b"\x93NUMPY\x01\x00");
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        for v in &self.data {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out
    }

    pub fn read_text(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| bad(path, e))?;
        // A byte-order mark, as Windows programs write before UTF-8 text.
        let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
        Self::parse_text(path, text)?.checked(path)
    }

    fn parse_text(path: &Path, text: &str) -> Result<Self> {
        let mut data = Vec::new();
        let mut cols = 0;
        let mut rows = 0;
        for (ln, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let vals: Vec<f64> = line
                .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
                .filter(|s| !s.is_empty())
                .map(|s| {
                    s.parse::<f64>()
                        .map_err(|_| bad(path, format!("line {}: `{s}` is not a number", ln + 1)))
                })
                .collect::<Result<_>>()?;
            if rows == 0 {
                cols = vals.len();
            } else if vals.len() != cols {
                return Err(bad(
                    path,
                    format!(
                        "ragged rows: line {} has {} values, expected {cols}",
                        ln + 1,
                        vals.len()
                    ),
                ));
            }
            data.extend(vals);
            rows += 1;
        }
        Ok(Self { rows, cols, data })
    }

    pub fn write_text(&self, path: &Path) -> Result<()> {
        let mut s = String::new();
        for r in 0..self.rows {
            let line: Vec<String> = self.data[r * self.cols..(r + 1) * self.cols]
                .iter()
                .map(|v| format!("{v:e}"))
                .collect();
            s.push_str(&line.join(" "));
            s.push('\n');
        }
        std::fs::write(path, s).map_err(|e| bad(path, e))
    }
}

/// A map and its cell size (dx, dy).
type WithCell = (HeightMap, (f64, f64));

/// The numbers of a text line (whitespace, comma or semicolon separated).
fn numbers(line: &str) -> std::result::Result<Vec<f64>, String> {
    line.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))
        })
        .collect()
}

/// An ESRI ASCII grid: `ncols`, `nrows`, `xllcorner`/`xllcenter`,
/// `yllcorner`/`yllcenter`, `cellsize` (or `dx` and `dy`) and optionally
/// `nodata_value`, one per line, then `nrows` rows of `ncols` heights, the first row the
/// top (largest y). None if the text has no such header; cells holding the no-data value
/// are refused (a contact solve needs every height).
fn parse_esri(text: &str) -> std::result::Result<Option<WithCell>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .peekable();
    let mut keys = std::collections::HashMap::new();
    while let Some(&(ln, line)) = lines.peek() {
        let mut it = line.split_whitespace();
        let key = it.next().unwrap_or("").to_ascii_lowercase();
        const KEYS: [&str; 9] = [
            "ncols",
            "nrows",
            "xllcorner",
            "yllcorner",
            "xllcenter",
            "yllcenter",
            "cellsize",
            "dx",
            "dy",
        ];
        if !(KEYS.contains(&key.as_str()) || key == "nodata_value") {
            break;
        }
        let value = it
            .next()
            .and_then(|v| v.parse::<f64>().ok())
            .ok_or(format!("line {}: header `{key}` needs a number", ln + 1))?;
        keys.insert(key, value);
        lines.next();
    }
    if !keys.contains_key("ncols") {
        return Ok(None);
    }
    let count = |k: &str| match keys.get(k) {
        None => Err(format!("the header has `ncols` but no `{k}`")),
        Some(&v) if v > 1e9 => Err(format!(
            "header `{k}` = {v}: more than 1e9 cells along one side"
        )),
        Some(&v) if v >= 1.0 && v.fract() == 0.0 => Ok(v as usize),
        Some(&v) => Err(format!("header `{k}` = {v} must be a whole number >= 1")),
    };
    let (cols, rows) = (count("ncols")?, count("nrows")?);
    let cell = match (keys.get("cellsize"), keys.get("dx"), keys.get("dy")) {
        (Some(&c), _, _) => (c, c),
        (None, Some(&dx), Some(&dy)) => (dx, dy),
        _ => return Err("header needs `cellsize` (or `dx` and `dy`)".into()),
    };
    if !(cell.0 > 0.0 && cell.1 > 0.0 && cell.0.is_finite() && cell.1.is_finite()) {
        return Err(format!("cell size {cell:?} must be positive"));
    }
    // Grown from the file's numbers, not sized from the header (which may be anything).
    let mut top_first = Vec::new();
    for (ln, line) in lines {
        let vals = numbers(line).map_err(|m| format!("line {}: {m}", ln + 1))?;
        top_first.extend(vals);
    }
    if Some(top_first.len()) != rows.checked_mul(cols) {
        return Err(format!(
            "{} heights, but the header says {rows} x {cols}",
            top_first.len()
        ));
    }
    if let Some(&nodata) = keys.get("nodata_value") {
        let missing = top_first.iter().filter(|&&v| v == nodata).count();
        if missing > 0 {
            return Err(format!(
                "{missing} cells hold the no-data value {nodata}: fill or crop them first"
            ));
        }
    }
    // Row index along y: the file's last row first.
    let data = top_first.chunks(cols).rev().flatten().copied().collect();
    Ok(Some((HeightMap { rows, cols, data }, cell)))
}

/// How far a point list's coordinate may lie from its grid line, in cells: exports that
/// print six significant digits (C's `%g`) of a 512-cell scan are off by up to 3e-4 of a
/// cell, coordinates computed as `i * dx` by rounding noise.
pub const XYZ_GRID_TOLERANCE: f64 = 0.01;

/// The grid lines of one axis of a point list: the sorted coordinates grouped into
/// lines (a new line where consecutive values differ by more than a tenth of the
/// largest gap), each line's mean; the lines must be uniformly spaced and each line's
/// values within [`XYZ_GRID_TOLERANCE`] of a cell of it. Returns the lines and the step.
fn grid_axis(name: &str, mut v: Vec<f64>) -> std::result::Result<(Vec<f64>, f64), String> {
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        return Err(format!("non-finite {name} coordinate {x}"));
    }
    v.sort_by(f64::total_cmp);
    let largest_gap = v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    // (first, last, sum, count) of each grid line.
    let mut lines: Vec<(f64, f64, f64, usize)> = Vec::new();
    for &x in &v {
        match lines.last_mut() {
            Some(l) if x - l.1 <= 0.1 * largest_gap => {
                l.1 = x;
                l.2 += x;
                l.3 += 1;
            }
            _ => lines.push((x, x, x, 1)),
        }
    }
    let axis: Vec<f64> = lines.iter().map(|l| l.2 / l.3 as f64).collect();
    if axis.len() < 2 {
        return Ok((axis, 1.0));
    }
    // The span gives the step; the median spacing names a line off the grid.
    let mut gaps: Vec<f64> = axis.windows(2).map(|w| w[1] - w[0]).collect();
    gaps.sort_by(f64::total_cmp);
    let typical = gaps[gaps.len() / 2];
    let step = (axis[axis.len() - 1] - axis[0]) / (axis.len() - 1) as f64;
    let tol = XYZ_GRID_TOLERANCE;
    if let Some(l) = lines.iter().find(|l| l.1 - l.0 > tol * step) {
        return Err(format!(
            "{name} = {} and {name} = {} are {:.3} cells apart: neither one grid line \
             (within {tol} of a cell) nor two (the grid's step is {step}); the spacing is \
             not uniform",
            l.0,
            l.1,
            (l.1 - l.0) / step
        ));
    }
    let off = |k: usize| (axis[k] - axis[0]) / step - k as f64;
    if (0..axis.len()).any(|k| off(k).abs() > tol) {
        // Named by the first spacing that differs from the median one, else by the
        // first line off the grid that the end lines span.
        let gap_off = |k: usize| (axis[k] - axis[k - 1]) / typical - 1.0;
        let (k, by, from, step) = match (1..axis.len()).find(|&k| gap_off(k).abs() > tol) {
            Some(k) => (k, gap_off(k), axis[k - 1], typical),
            None => {
                let k = (0..axis.len()).find(|&k| off(k).abs() > tol).unwrap_or(0);
                (k, off(k), axis[0], step)
            }
        };
        return Err(format!(
            "{name} = {} is {by:.3} cells off the regular grid of step {step} from {name} = \
             {from} ({} grid lines; allowed: {tol} of a cell)",
            axis[k],
            axis.len()
        ));
    }
    Ok((axis, step))
}

/// An x-y-z point list on a regular grid: `#` comments and one header line allowed; the
/// points in any order, each grid point exactly once, each coordinate within
/// [`XYZ_GRID_TOLERANCE`] of a cell of its grid line.
fn parse_xyz(text: &str) -> std::result::Result<WithCell, String> {
    let mut points = Vec::new();
    let mut header = false;
    for (ln, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        match numbers(line) {
            Ok(v) if v.len() == 3 => points.push((v[0], v[1], v[2])),
            Ok(v) => {
                return Err(format!(
                    "line {}: {} values, expected x y z",
                    ln + 1,
                    v.len()
                ))
            }
            // One header line before the points.
            Err(_) if points.is_empty() && !header => header = true,
            Err(m) => return Err(format!("line {}: {m}", ln + 1)),
        }
    }
    let (xs, dx) = grid_axis("x", points.iter().map(|p| p.0).collect())?;
    let (ys, dy) = grid_axis("y", points.iter().map(|p| p.1).collect())?;
    let (cols, rows) = (xs.len(), ys.len());
    // Checked before the grid is allocated (scattered points would span a huge one).
    if Some(points.len()) != rows.checked_mul(cols) {
        return Err(format!(
            "{} points, but the coordinates span a {cols} x {rows} grid: every grid point once",
            points.len()
        ));
    }
    let index = |v: f64, axis: &[f64], step: f64| ((v - axis[0]) / step).round() as usize;
    let mut data = vec![0.0; rows * cols];
    let mut seen = vec![false; rows * cols];
    for &(x, y, z) in &points {
        let cell = index(y, &ys, dy) * cols + index(x, &xs, dx);
        if std::mem::replace(&mut seen[cell], true) {
            return Err(format!("the point ({x}, {y}) appears twice"));
        }
        data[cell] = z;
    }
    Ok((HeightMap { rows, cols, data }, (dx, dy)))
}

/// Reads a two-column profile table (r, z): `#` comments and one header line allowed.
pub fn read_profile_csv(path: &Path) -> Result<(Vec<f64>, Vec<f64>)> {
    read_two_columns(path, ["r", "z"])
}

/// Reads a table of two numeric columns named `names` (for the messages): columns
/// separated by commas, semicolons or tabs, or else by spaces; `#` comments and one
/// header line allowed.
pub fn read_two_columns(path: &Path, names: [&str; 2]) -> Result<(Vec<f64>, Vec<f64>)> {
    let text = std::fs::read_to_string(path).map_err(|e| bad(path, e))?;
    let (mut r, mut z) = (Vec::new(), Vec::new());
    let mut header_seen = false;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = if line.contains([',', ';', '\t']) {
            line.split([',', ';', '\t']).map(str::trim).collect()
        } else {
            line.split_whitespace().collect()
        };
        let parsed: Option<Vec<f64>> = cols.iter().map(|c| c.parse::<f64>().ok()).collect();
        match parsed {
            Some(v) if v.len() == 2 => {
                r.push(v[0]);
                z.push(v[1]);
            }
            None if !header_seen && r.is_empty() => header_seen = true,
            _ => {
                return Err(bad(
                    path,
                    format!(
                        "line {}: expected two numeric columns `{}, {}`, found `{line}`",
                        i + 1,
                        names[0],
                        names[1]
                    ),
                ))
            }
        }
    }
    if r.is_empty() {
        return Err(bad(path, "no data rows"));
    }
    Ok((r, z))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(descr: &str, fortran: bool, shape: &str, body: &[u8]) -> Vec<u8> {
        let mut h = format!(
            "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
            if fortran { "True" } else { "False" }
        );
        while (10 + h.len() + 1) % 16 != 0 {
            h.push(' ');
        }
        h.push('\n');
        let mut v = b"\x93NUMPY\x01\x00".to_vec();
        v.extend_from_slice(&(h.len() as u16).to_le_bytes());
        v.extend_from_slice(h.as_bytes());
        v.extend_from_slice(body);
        v
    }

    #[test]
    fn npy_round_trip_and_variants() {
        let dir = tempdir();
        let m = HeightMap {
            rows: 2,
            cols: 3,
            data: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.5],
        };
        let p = dir.join("a.npy");
        m.write_npy(&p).unwrap();
        assert_eq!(HeightMap::read(&p).unwrap(), m);
        // float32, Fortran order: column-major data.
        let body: Vec<u8> = [1.0f32, 4.0, 2.0, 5.0, 3.0, 6.5]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        std::fs::write(&p, npy("<f4", true, "(2, 3)", &body)).unwrap();
        assert_eq!(HeightMap::read(&p).unwrap(), m);
        // Errors: NaN, dtype, truncation, magic.
        let body: Vec<u8> = [1.0f64, f64::NAN]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        std::fs::write(&p, npy("<f8", false, "(1, 2)", &body)).unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("non-finite"));
        std::fs::write(&p, npy("<i8", false, "(1, 1)", &[0; 8])).unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("dtype"));
        std::fs::write(&p, npy("<f8", false, "(2, 2)", &[0; 8])).unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("truncated"));
        std::fs::write(&p, b"hello").unwrap();
        assert!(HeightMap::read(&p).is_err());
        // Malformed headers are errors, not panics.
        for shape in [
            "), ",
            "(",
            "(99999999999, 99999999999)",
            "(a, 2)",
            "(1, 2, 3)",
        ] {
            std::fs::write(&p, npy("<f8", false, shape, &[0; 16])).unwrap();
            assert!(HeightMap::read(&p).is_err(), "{shape}");
        }
    }

    #[test]
    fn text_matrices() {
        let dir = tempdir();
        let p = dir.join("a.txt");
        std::fs::write(&p, "# heights\n1 2 3\n4,5,6.5\n").unwrap();
        let m = HeightMap::read(&p).unwrap();
        assert_eq!((m.rows, m.cols), (2, 3));
        m.write_text(&p).unwrap();
        assert_eq!(HeightMap::read(&p).unwrap(), m);
        std::fs::write(&p, "1 2 3\n4 5\n").unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("ragged"));
        std::fs::write(&p, "").unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("empty"));
        std::fs::write(&p, "1 x\n").unwrap();
        assert!(HeightMap::read(&p).is_err());
        // Words that parse as numbers are heights, not an ESRI header.
        std::fs::write(&p, "inf 1\n2 3\n").unwrap();
        let e = HeightMap::read(&p).unwrap_err().to_string();
        assert!(e.contains("non-finite height at row 1, column 1"), "{e}");
    }

    /// Both plain grid formats round-trip a map (x-y-z shuffled), carry its cell size,
    /// and refuse what is not a full regular grid.
    #[test]
    fn esri_grids_and_xyz_lists() {
        let dir = tempdir();
        let m = HeightMap {
            rows: 3,
            cols: 4,
            data: (0..12).map(|k| (k as f64 * 0.37).sin()).collect(),
        };
        // ESRI: the top row (largest y) first.
        let p = dir.join("g.asc");
        let mut s = String::from(
            "ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 0.5\nNODATA_value -9999\n",
        );
        for r in (0..3).rev() {
            let row: Vec<String> = m.data[r * 4..r * 4 + 4]
                .iter()
                .map(|v| format!("{v:e}"))
                .collect();
            s += &(row.join(" ") + "\n");
        }
        std::fs::write(&p, &s).unwrap();
        assert_eq!(
            HeightMap::read_with_cell(&p).unwrap(),
            (m.clone(), Some((0.5, 0.5)))
        );
        std::fs::write(
            &p,
            s.replacen("1e0", "-9999", 1)
                .replace(&format!("{:e}", m.data[0]), "-9999"),
        )
        .unwrap();
        let e = HeightMap::read(&p).unwrap_err().to_string();
        assert!(e.contains("no-data"), "{e}");
        std::fs::write(&p, s.replace("nrows 3", "nrows 4")).unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("header says"));
        // A header promising a huge grid is refused by the count, not by an allocation.
        let huge = s
            .replace("nrows 3", "nrows 1000000000")
            .replace("ncols 4", "ncols 1000000000");
        std::fs::write(&p, huge).unwrap();
        assert!(HeightMap::read(&p)
            .unwrap_err()
            .to_string()
            .contains("header says"));

        // x-y-z, shuffled, with a header line; x spacing 0.25, y spacing 0.5.
        let p = dir.join("g.xyz");
        let mut lines: Vec<String> = (0..12)
            .map(|k| {
                format!(
                    "{} {} {:e}",
                    (k % 4) as f64 * 0.25 + 1.0,
                    (k / 4) as f64 * 0.5,
                    m.data[k]
                )
            })
            .collect();
        lines.reverse();
        lines.swap(2, 7);
        let body = lines.join("\n");
        std::fs::write(&p, format!("x y z\n{body}\n")).unwrap();
        assert_eq!(
            HeightMap::read_with_cell(&p).unwrap(),
            (m.clone(), Some((0.25, 0.5)))
        );
        for (broken, why) in [
            (lines[1..].join("\n"), "every grid point once"),
            (format!("{body}\n{}", lines[0]), "every grid point once"),
            (
                format!("{}\n{}", lines[1..].join("\n"), lines[1]),
                "appears twice",
            ),
            (body.replacen("1.25 ", "1.3 ", 1), "off the regular grid"),
        ] {
            std::fs::write(&p, broken).unwrap();
            let e = HeightMap::read(&p).unwrap_err().to_string();
            assert!(e.contains(why), "{why}: {e}");
        }
    }

    /// Exports as programs write them: a 512-pixel scan with coordinates printed to six
    /// significant digits (C's `%g`) and a byte-order mark; coordinates with rounding
    /// noise; headers that lack a key or promise too much name that key.
    #[test]
    fn ordinary_exports() {
        let dir = tempdir();
        let p = dir.join("scan.xyz");
        let n = 512;
        let dx = 1.0 / n as f64;
        let z = |i: usize, j: usize| ((i * 7 + j * 13) % 17) as f64 * 1e-3;
        let mut text = String::from("\u{feff}");
        for j in 0..4 {
            for i in 0..n {
                // Six significant digits, as printf's %g writes them.
                let g = |v: f64| format!("{:.*e}", 5, v).parse::<f64>().unwrap();
                text += &format!("{} {} {}\n", g(i as f64 * dx), g(j as f64 * dx), z(i, j));
            }
        }
        std::fs::write(&p, &text).unwrap();
        let (m, cell) = HeightMap::read_with_cell(&p).unwrap();
        assert_eq!((m.rows, m.cols), (4, n));
        assert_eq!(m.data[n + 3], z(3, 1));
        let (cx, cy) = cell.unwrap();
        assert!((cx / dx - 1.0).abs() < 1e-5 && (cy / dx - 1.0).abs() < 1e-5);
        // 1e-15 of noise on i * dx.
        let noisy: String = (0..3)
            .flat_map(|j| (0..5).map(move |i| (i, j)))
            .map(|(i, j)| {
                let e = 1e-15 * ((i + j) % 3) as f64 - 1e-15;
                format!(
                    "{} {} {}\n",
                    i as f64 * 0.1 + e,
                    j as f64 * 0.1 - e,
                    i + 10 * j
                )
            })
            .collect();
        std::fs::write(&p, noisy).unwrap();
        let m = HeightMap::read(&p).unwrap();
        assert_eq!((m.rows, m.cols, m.data[7]), (3, 5, 12.0));
        // A byte-order mark before a headerless text matrix keeps its first value.
        let t = dir.join("m.txt");
        std::fs::write(&t, "\u{feff}1 2\n3 4\n").unwrap();
        assert_eq!(HeightMap::read(&t).unwrap().data, vec![1.0, 2.0, 3.0, 4.0]);
        let g = dir.join("g.asc");
        std::fs::write(&g, "\u{feff}ncols 2\nnrows 2\ncellsize 1\n1 2\n3 4\n").unwrap();
        assert_eq!(HeightMap::read(&g).unwrap().data, vec![3.0, 4.0, 1.0, 2.0]);
        for (header, why) in [
            (
                "ncols 2\ncellsize 1\n",
                "the header has `ncols` but no `nrows`",
            ),
            (
                "ncols 10000000000\nnrows 2\ncellsize 1\n",
                "`ncols` = 10000000000: more than 1e9",
            ),
            (
                "ncols 2.5\nnrows 2\ncellsize 1\n",
                "`ncols` = 2.5 must be a whole number",
            ),
        ] {
            std::fs::write(&g, format!("{header}1 2\n3 4\n")).unwrap();
            let e = HeightMap::read(&g).unwrap_err().to_string();
            assert!(e.contains(why), "{why}: {e}");
        }
        // What is not a file says what it is.
        let e = HeightMap::read(&dir).unwrap_err().to_string();
        assert!(e.contains("is a folder"), "{e}");
        let e = HeightMap::read(&dir.join("none.txt"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no such file"), "{e}");
        #[cfg(unix)]
        {
            let e = HeightMap::read(Path::new("/dev/null"))
                .unwrap_err()
                .to_string();
            assert!(e.contains("device"), "{e}");
        }
    }

    fn tempdir() -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!(
            "mrd-topo-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        std::fs::create_dir_all(&d).unwrap();
        d
    }
}
