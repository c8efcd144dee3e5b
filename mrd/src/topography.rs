//! Height maps on disk: NumPy `.npy` (float32/float64, little or big endian, C or
//! Fortran order, format versions 1-3) and plain-text matrices (whitespace, comma or
//! semicolon separated; `#` comments), plus two-column profile tables (r, z).
//! Arrays are returned row-major `rows x cols`. Physical sizes come from the caller.

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

    /// Reads `.npy` or text depending on the extension (`.npy` vs anything else).
    pub fn read(path: &Path) -> Result<Self> {
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
        {
            Self::read_npy(path)
        } else {
            Self::read_text(path)
        }
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
        Self { rows, cols, data }.checked(path)
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

/// Reads a two-column profile table (r, z): `#` comments and one header line allowed.
pub fn read_profile_csv(path: &Path) -> Result<(Vec<f64>, Vec<f64>)> {
    let text = std::fs::read_to_string(path).map_err(|e| bad(path, e))?;
    let (mut r, mut z) = (Vec::new(), Vec::new());
    let mut header_seen = false;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
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
                        "line {}: expected two numeric columns `r, z`, found `{line}`",
                        i + 1
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
