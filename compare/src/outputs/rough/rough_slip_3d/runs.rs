//! One realisation of each side: the rough body held at F_N and loaded tangentially,
//! in 3D on the free half-space or on MRD's springs.

use super::RoughSlip3d;
use crate::error::{Context as _, Result};
use crate::experiment::tangential_map::Mapping;
use bem3d::tangential::{CerrutiFree, PartialSlip};
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace};
use mrd::foundation::Foundation;

/// The friction bound of the stick solve, over mu: far above any traction the held
/// force needs, so that no cell slips.
const STICK: f64 = 1e6;

/// 3D partial slip on one substrate (one Poisson's ratio).
#[derive(Debug, Clone)]
pub struct Slip {
    /// Absolute shifts at the fractions [length].
    pub shifts: Vec<f64>,
    /// Stick cells over cells in contact at the fractions.
    pub stick: Vec<f64>,
    /// Energies per cycle at the amplitudes [force x length].
    pub energies: Vec<f64>,
    /// Stick stiffness k_t [force / length].
    pub kt: f64,
    /// Where the contact sticks and slips at the fraction [`StickMap::AT`] (when asked).
    pub map: Option<StickMap>,
}

/// The cells in contact at one tangential force, split into stick and slip (cell
/// centres over the smooth body's contact radius).
#[derive(Debug, Clone, Default)]
pub struct StickMap {
    /// The tangential force over mu F_N.
    pub fraction: f64,
    pub stick: Vec<(f64, f64)>,
    pub slip: Vec<(f64, f64)>,
}

impl StickMap {
    /// The map is drawn at the fraction of mu F_N closest to this.
    pub const AT: f64 = 0.5;

    /// The index of the fraction the map is drawn at.
    pub fn index(fractions: &[f64]) -> usize {
        (0..fractions.len())
            .min_by(|&i, &j| {
                (fractions[i] - Self::AT)
                    .abs()
                    .total_cmp(&(fractions[j] - Self::AT).abs())
            })
            .unwrap_or(0)
    }

    /// Stick (|q| < mu p, the step's own test) and slip among the cells with p > 0.
    fn of(
        fraction: f64,
        pressure: &[f64],
        q: &[f64],
        mu: f64,
        at: impl Fn(usize) -> (f64, f64),
    ) -> Self {
        let mut map = StickMap {
            fraction,
            ..Default::default()
        };
        for (c, (&p, &qc)) in pressure.iter().zip(q).enumerate() {
            if p > 0.0 {
                if qc.abs() < mu * p {
                    map.stick.push(at(c));
                } else {
                    map.slip.push(at(c));
                }
            }
        }
        map
    }
}

/// A 3D realisation: the normal stiffness, MRD's law on its normal curve, and the
/// partial slip per Poisson's ratio.
#[derive(Debug, Clone)]
pub struct Run3d {
    pub kn: f64,
    pub mapping: Mapping,
    pub slips: Vec<Slip>,
}

/// An MRD realisation: the normal stiffness and the law on the line's normal curve.
#[derive(Debug, Clone)]
pub struct Run1d {
    pub kn: f64,
    pub mapping: Mapping,
}

/// A case (hurst, roughness) with its 3D runs per grid and MRD runs per lambda, one
/// per realisation each.
pub struct Case {
    pub hurst: f64,
    pub roughness: f64,
    pub runs_3d: Vec<Vec<Run3d>>,
    pub runs_1d: Vec<Vec<Run1d>>,
}

/// The factor that gives the surfaces of a case unit rms height (the finest grid's; the
/// MRD lines take the same factor, so both sides carry the same C2D).
pub fn unit_rms_scale(spec: &RoughSlip3d, hurst: f64, roughness: f64) -> Result<f64> {
    let finest = *spec.cells.last().unwrap_or(&16);
    spec.geometry(hurst, finest).unit_rms_scale(roughness)
}

/// Realisation `r` of the case (hurst, roughness, scale) on an `n`^2 grid in 3D; with
/// `keep_map`, the stick map of each Poisson's ratio.
pub fn run_3d(
    spec: &RoughSlip3d,
    (hurst, roughness, scale): (f64, f64, f64),
    (n, keep_map): (usize, bool),
    r: u64,
    e_star: f64,
) -> Result<Run3d> {
    let geometry = spec.geometry(hurst, n);
    let h = roughness * spec.smooth_approach(e_star);
    let z = geometry.heights(h, scale, r)?;
    let reach2 = spec.body().reach().powi(2);
    let mask: Vec<bool> = (0..n * n).map(|c| geometry.r2(c) < reach2).collect();
    let op = NonPeriodicHalfSpace::new(n, n, spec.side, spec.side, e_star);
    let mut solver = ContactSolver::new(op, &z, Some(mask)).ctx("3D solver set-up")?;
    let opts = crate::experiment::solve_options(spec.tolerance, n);
    let sol = solver
        .solve(Load::Force(spec.force), &opts, None)
        .ctx("3D normal solve")?;
    let kn = solver
        .tangent_stiffness(&sol, &opts)
        .ctx("3D normal stiffness")?;
    let mu_fn = spec.mu * spec.force;
    let mapping = Mapping::new(mu_fn, &spec.fractions, &spec.amplitudes, |q| {
        let s = solver
            .solve(Load::Force(spec.force - q / spec.mu), &opts, Some(&sol))
            .ctx("3D normal solve at a reduced force")?;
        Ok(spec.mu * (sol.approach - s.approach))
    })?;
    let mut slips = Vec::with_capacity(spec.poisson.len());
    for &nu in &spec.poisson {
        let g = e_star * (1.0 - nu) / 2.0;
        let fresh = |mu: f64| -> bem3d::Result<PartialSlip<CerrutiFree>> {
            let op = CerrutiFree::new(n, n, spec.side, spec.side, g, nu)?;
            PartialSlip::new(op, &sol.pressure, mu)
        };
        let stick = fresh(STICK * spec.mu)
            .and_then(|mut ps| ps.load(mu_fn, spec.tolerance))
            .ctx("3D stick solve")?;
        let mut ps = fresh(spec.mu).ctx("3D partial slip")?;
        let (mut shifts, mut sticking, mut map) = (Vec::new(), Vec::new(), None);
        let a = spec.contact_radius(e_star);
        let at = |c: usize| {
            let x = crate::experiment::rough_sphere::centre(c % n, n, spec.side);
            let y = crate::experiment::rough_sphere::centre(c / n, n, spec.side);
            (x / a, y / a)
        };
        for (j, x) in spec.fractions.iter().enumerate() {
            let s = ps.load(x * mu_fn, spec.tolerance).ctx("3D partial slip")?;
            shifts.push(s.shift);
            sticking.push(s.stick_cells as f64 / (s.stick_cells + s.slip_cells) as f64);
            if keep_map && j == StickMap::index(&spec.fractions) {
                map = Some(StickMap::of(*x, &sol.pressure, ps.traction(), spec.mu, at));
            }
        }
        let energies = spec
            .amplitudes
            .iter()
            .map(|a| {
                fresh(spec.mu)
                    .and_then(|mut ps| ps.cycle(a * mu_fn, spec.steps, 1, spec.tolerance))
                    .map(|c| c.dissipated)
                    .ctx("3D cycle")
            })
            .collect::<Result<_>>()?;
        slips.push(Slip {
            shifts,
            stick: sticking,
            energies,
            kt: mu_fn / stick.shift,
            map,
        });
    }
    Ok(Run3d { kn, mapping, slips })
}

/// MRD line `r` of the case with factor `lambda`.
pub fn run_1d(
    spec: &RoughSlip3d,
    (hurst, roughness, scale): (f64, f64, f64),
    lambda: f64,
    r: u64,
    e_star: f64,
) -> Result<Run1d> {
    let geometry = spec.geometry(hurst, *spec.cells.last().unwrap_or(&16));
    let h = roughness * spec.smooth_approach(e_star);
    let n1 = spec.springs();
    let (x, w) = geometry.line(h, scale, lambda, n1, r)?;
    // The springs under the body (all of them for the sphere).
    let w: Vec<f64> = x
        .iter()
        .zip(w)
        .filter(|(x, _)| x.abs() < spec.body().reach())
        .map(|(_, w)| w)
        .collect();
    let top = w.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let gaps: Vec<f64> = w.iter().map(|v| top - v).collect();
    let row = Foundation::new(&gaps, spec.side / n1 as f64, e_star).ctx("MRD springs")?;
    let held = row.at_force(spec.force).ctx("MRD")?;
    let mapping = Mapping::new(
        spec.mu * spec.force,
        &spec.fractions,
        &spec.amplitudes,
        |q| {
            let s = row.at_force(spec.force - q / spec.mu).ctx("MRD")?;
            Ok(spec.mu * (held.depth - s.depth))
        },
    )?;
    Ok(Run1d {
        kn: held.stiffness,
        mapping,
    })
}
