//! What the benchmark targets share: the reference surface, timing of repeated runs,
//! log-log slopes, the peak memory of this process, and the lines a child case prints.

use std::time::Instant;

/// A benchmark's failure: a write to its output, or a case a solver refused (named by
/// [`Case::case`]).
pub type Failed = Box<dyn std::error::Error + Send + Sync>;
/// The result of a benchmark target.
pub type Result<T> = std::result::Result<T, Failed>;

/// Names the benchmark case of a failure.
pub trait Case<T> {
    fn case(self, what: impl std::fmt::Display) -> Result<T>;
}

impl<T, E: std::fmt::Display> Case<T> for std::result::Result<T, E> {
    fn case(self, what: impl std::fmt::Display) -> Result<T> {
        self.map_err(|e| format!("{what}: {e}").into())
    }
}

/// The periodic reference problem shared with the Tamaas comparison: self-affine,
/// H = 0.8, spectrum from 2 pi/L (roll-off at 4 pi/L) to n/4 x 2 pi/L, rms slope 0.1,
/// L = 1, seed 2026, realisation 0.
pub fn reference_surface(n: usize) -> std::result::Result<Vec<f64>, mrd::MrdError> {
    use mrd::roughness::synthesis::{surface, Amplitudes, Grid};
    use mrd::roughness::SelfAffine;
    use std::f64::consts::PI;
    let spec = SelfAffine::new(0.8, 2.0 * PI, 4.0 * PI, 2.0 * PI * (n / 4) as f64)?;
    let grid = Grid::square(n, 1.0);
    let mut h = surface(&spec, &grid, 2026, 0, Amplitudes::Deterministic)?;
    let m = mrd::roughness::stats::surface_moments(&h, n, n, 1.0, 1.0);
    h.iter_mut().for_each(|v| *v *= 0.1 / m.rms_slope);
    Ok(h)
}

/// Peak resident memory of this process in MiB (Linux VmHWM), if readable.
pub fn peak_memory_mib() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// A benchmark child's own one-line error (its last `error: ` line, without its
/// progress lines), or its whole standard error.
pub fn child_error(stderr: &[u8]) -> String {
    let stderr = String::from_utf8_lossy(stderr);
    let line = stderr.lines().rev().find(|l| l.starts_with("error: "));
    line.map_or(stderr.trim(), |l| l.trim_start_matches("error: "))
        .to_string()
}

/// The number `k=value` of a child's RESULT line (NaN if absent).
pub fn field(l: &str, k: &str) -> f64 {
    l.split_whitespace()
        .find_map(|kv| {
            kv.strip_prefix(&format!("{k}="))
                .and_then(|v| v.parse().ok())
        })
        .unwrap_or(f64::NAN)
}

/// Sizes of the report.
#[derive(Debug, Clone, Copy)]
pub struct Options {
    /// Small ladders (the test suite's variant, well under a minute).
    pub quick: bool,
}

/// Median, min and max wall time of repeated runs [s].
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    pub median: f64,
    pub min: f64,
    pub max: f64,
    pub runs: usize,
}

/// Runs `f` at least 3 times and until about `budget` seconds are spent (at most 1000
/// runs); returns the timing and the last result.
pub fn timed<T>(budget: f64, mut f: impl FnMut() -> T) -> (Timing, T) {
    let mut ts = Vec::new();
    let start = Instant::now();
    let mut out;
    loop {
        let t0 = Instant::now();
        out = std::hint::black_box(f());
        ts.push(t0.elapsed().as_secs_f64());
        if (ts.len() >= 3 && start.elapsed().as_secs_f64() >= budget) || ts.len() >= 1000 {
            break;
        }
    }
    ts.sort_by(f64::total_cmp);
    let timing = Timing {
        median: ts[ts.len() / 2],
        min: ts[0],
        max: ts[ts.len() - 1],
        runs: ts.len(),
    };
    (timing, out)
}

/// Least-squares slope of ln y against ln x.
pub fn log_slope(xy: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = xy
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}
