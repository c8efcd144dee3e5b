//! Elastic-perfectly plastic contact of bodies of revolution by MRD in incremental form
//! (the open question of the review's Section 11), in the pressure-cap model: the
//! contact pressure cannot exceed the hardness `H`; where it would, the half-space's
//! surface flows and stays lowered (the plastic displacement), so unloading leaves an
//! imprint and reloading is elastic up to the largest earlier load.
//!
//! Two rules, one state (the plastic displacement so far), one loading history:
//!
//! - [`PlasticRule::IncrementalHess`]: at each load increment the body's profile as
//!   plastically deformed so far is taken through the rule of Hess (Eq. 11) to the line
//!   load `q(x) = 2 int_|x|^inf r p(r) / sqrt(r^2 - x^2) dr` (Eq. 25, inverted) and back
//!   to the surface displacement `u(r) = (2 / pi) int_0^r q(x) / (E* sqrt(r^2 - x^2)) dx`
//!   (the inverse rule of Hess; the same expression holds outside the contact, where
//!   `q = 0`). That chain is the exact axisymmetric Boussinesq operator, so each
//!   increment is an exact elastic contact with pressures held in `[0, H]` on the rings
//!   of a radial grid; the plastic displacement grows where a ring sits at `H` with a
//!   negative gap. Exact for bodies of revolution up to the rings' discretisation: the
//!   3D pressure-cap solver's answer.
//! - [`PlasticRule::SpringCap`]: the 1D springs alone, local and independent as MRD's
//!   springs are: each spring's line load is capped at the fully plastic contact's line
//!   load `q_Y(x) = 2 H sqrt(a^2 - x^2)` (the MRD image, Eq. 25, of a uniform pressure
//!   `H` over the contact radius `a` of the moment), and a spring pressed beyond it takes
//!   a permanent set. It has the fully plastic limit `F = pi a^2 H` by construction but
//!   yields later than the 3D contact (a sphere's central spring reaches its cap when
//!   Hertz's peak pressure is `4 H / pi`, not `H`). The structure, an elliptical 1D
//!   image of a saturated core, is that of Zunker & Kamrin's MDR model of
//!   elastic-perfectly plastic particles (J. Mech. Phys. Solids 183 (2024) 105492);
//!   this rule is the simplest local form of it, not their calibrated model.
//!
//! Units are the caller's: lengths, E* and H in one system. The radial grid has `n`
//! rings (or springs) of width `h = r_max / n`, centres `(i + 1/2) h`.

// Numerical kernels index several parallel arrays with one index.
#![allow(clippy::needless_range_loop)]

use crate::error::{positive, MrdError, Result};
use crate::profile::Profile;
use std::f64::consts::PI;

/// How MRD treats plasticity (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlasticRule {
    IncrementalHess,
    SpringCap,
}

impl PlasticRule {
    /// The rule's name in scenes and tables.
    pub fn name(&self) -> &'static str {
        match self {
            PlasticRule::IncrementalHess => "incremental_hess",
            PlasticRule::SpringCap => "spring_cap",
        }
    }

    /// The rule of a name, or an error listing the names.
    pub fn parse(name: &str) -> Result<Self> {
        match name {
            "incremental_hess" => Ok(PlasticRule::IncrementalHess),
            "spring_cap" => Ok(PlasticRule::SpringCap),
            other => Err(MrdError::InvalidData(format!(
                "MRD plasticity rule `{other}`: the rules are incremental_hess and spring_cap"
            ))),
        }
    }
}

/// The state after one load step.
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticState {
    /// Approach from the first contact of the undeformed body [length].
    pub approach: f64,
    /// Normal force [force].
    pub force: f64,
    /// Contact radius and the radius of the saturated core [length] (0: no core).
    pub contact_radius: f64,
    pub plastic_radius: f64,
    /// The largest plastic displacement so far [length].
    pub plastic_depth: f64,
}

/// A body of revolution pressed on an elastic-perfectly plastic half-space by MRD
/// (module docs), loaded along a history.
pub struct AxisymPlastic {
    rule: PlasticRule,
    e_star: f64,
    hardness: f64,
    h: f64,
    /// The undeformed profile at the ring centres (IncrementalHess) or its rule-of-Hess
    /// image at the spring positions (SpringCap) [length].
    shape: Vec<f64>,
    /// Plastic displacement per ring (IncrementalHess) or permanent set per spring
    /// (SpringCap) [length].
    plastic: Vec<f64>,
    /// `u_i = sum_j k[i n + j] p_j` (IncrementalHess only).
    k: Vec<f64>,
    /// Ring pressures (IncrementalHess) or line loads (SpringCap).
    load: Vec<f64>,
    approach: f64,
}

/// Most rings or springs of one contact (the dense operator has n^2 entries).
pub const MAX_RINGS: usize = 2000;

impl AxisymPlastic {
    /// `profile` on `n` rings (springs) over `[0, r_max]`; `hardness` > 0 [stress]
    /// (infinite: the elastic contact).
    pub fn new(
        profile: &Profile,
        e_star: f64,
        hardness: f64,
        rule: PlasticRule,
        n: usize,
        r_max: f64,
    ) -> Result<Self> {
        positive("e_star", e_star)?;
        positive("r_max", r_max)?;
        if hardness.is_nan() || hardness <= 0.0 {
            return Err(MrdError::InvalidParameter {
                name: "hardness H",
                value: hardness,
                reason: "must be > 0 (infinite: no plasticity)",
            });
        }
        if !(8..=MAX_RINGS).contains(&n) {
            return Err(MrdError::InvalidParameter {
                name: "rings",
                value: n as f64,
                reason: "must lie in 8..=2000",
            });
        }
        if profile.rim().is_some_and(|rim| rim < r_max) {
            return Err(MrdError::InvalidParameter {
                name: "r_max",
                value: r_max,
                reason: "lies beyond the profile's rim: a flat punch's edge carries a pressure singularity no cap follows",
            });
        }
        let h = r_max / n as f64;
        let centre = |i: usize| (i as f64 + 0.5) * h;
        let (shape, k): (Vec<f64>, Vec<f64>) = match rule {
            PlasticRule::IncrementalHess => (
                (0..n).map(|i| profile.z(centre(i))).collect(),
                operator(n, h, e_star),
            ),
            PlasticRule::SpringCap => ((0..n).map(|i| profile.z1d(centre(i))).collect(), vec![]),
        };
        if let Some(i) = shape.iter().position(|v| !v.is_finite()) {
            return Err(MrdError::InvalidData(format!(
                "the profile is not finite at r = {} (within r_max = {r_max})",
                centre(i)
            )));
        }
        Ok(Self {
            rule,
            e_star,
            hardness,
            h,
            shape,
            plastic: vec![0.0; n],
            k,
            load: vec![0.0; n],
            approach: 0.0,
        })
    }

    pub fn rule(&self) -> PlasticRule {
        self.rule
    }

    /// Ring (spring) centres [length].
    pub fn radii(&self) -> Vec<f64> {
        (0..self.shape.len())
            .map(|i| (i as f64 + 0.5) * self.h)
            .collect()
    }

    /// The plastic displacement per ring (IncrementalHess: the residual 3D profile's
    /// depth below the undeformed surface) or the permanent set per spring (SpringCap:
    /// a 1D quantity) [length].
    pub fn plastic(&self) -> &[f64] {
        &self.plastic
    }

    /// The imprint: how far the 3D surface lies below the undeformed one at the centres
    /// [length]: the plastic displacement (IncrementalHess), or the 3D image of the
    /// springs' permanent set by the inverse rule of Hess (SpringCap).
    pub fn imprint(&self) -> Vec<f64> {
        match self.rule {
            PlasticRule::IncrementalHess => self.plastic.clone(),
            PlasticRule::SpringCap => {
                let n = self.plastic.len();
                let w = inverse_hess(n, self.h);
                (0..n)
                    .map(|i| (0..n).map(|k| w[i * n + k] * self.plastic[k]).sum())
                    .collect()
            }
        }
    }

    /// Ring pressures [stress] (IncrementalHess), or the 3D pressure of the springs'
    /// line load by the inverse Abel transform (Eq. 26, SpringCap), at the centres.
    pub fn pressure(&self) -> Vec<f64> {
        match self.rule {
            PlasticRule::IncrementalHess => self.load.clone(),
            PlasticRule::SpringCap => abel_pressure(&self.load, self.h),
        }
    }

    /// Loads to approach `d` (finite) from the last state.
    pub fn step(&mut self, d: f64, tolerance: f64) -> Result<PlasticState> {
        if !d.is_finite() {
            return Err(MrdError::InvalidParameter {
                name: "approach",
                value: d,
                reason: "must be finite",
            });
        }
        if !(tolerance > 0.0 && tolerance <= 1e-2) {
            return Err(MrdError::InvalidParameter {
                name: "tolerance",
                value: tolerance,
                reason: "must lie in (0, 0.01]",
            });
        }
        self.approach = d;
        let mut load = std::mem::take(&mut self.load);
        let solved = self.load_at(d, tolerance, &mut load);
        self.load = load;
        solved?;
        self.flow(d, tolerance);
        self.state()
    }

    /// Loads to the force `f` (>= 0) from the last state: the approach by Brent's method
    /// on the non-decreasing force, within `tolerance f`.
    pub fn step_to_force(&mut self, f: f64, tolerance: f64) -> Result<PlasticState> {
        if !(f.is_finite() && f >= 0.0) {
            return Err(MrdError::InvalidParameter {
                name: "force",
                value: f,
                reason: "must be finite and >= 0",
            });
        }
        let limit = self.force_limit();
        if f >= limit {
            return Err(MrdError::ImpossibleLoad(format!(
                "force {f} must stay below H times the grid's area, {limit:e} (every ring at the hardness)"
            )));
        }
        // The trial loads leave the plastic state as it is: they load a copy of the
        // loads, from the last ones.
        let trial = |s: &Self, d: f64| -> Result<f64> {
            let mut load = s.load.clone();
            s.load_at(d, 0.1 * tolerance, &mut load)?;
            Ok(s.force_of(&load) - f)
        };
        let lo = self.lowest_surface();
        if f == 0.0 {
            // Apart: the body just touching the surface as it stands.
            self.load.iter_mut().for_each(|q| *q = 0.0);
            self.approach = lo;
            return self.state();
        }
        let mut hi = lo + self.h.max(self.approach - lo);
        while trial(self, hi)? < 0.0 {
            hi = lo + 2.0 * (hi - lo);
            if !hi.is_finite() {
                return Err(MrdError::ImpossibleLoad(format!(
                    "force {f}: no approach carries it"
                )));
            }
        }
        let xtol = tolerance * (hi - lo).abs().max(self.h) * 1e-3;
        let d =
            crate::numerics::roots::brent(|d| trial(self, d).unwrap_or(f64::NAN), lo, hi, xtol)?;
        self.step(d, tolerance)
    }

    /// The largest force: H over the grid's whole disc [force].
    pub fn force_limit(&self) -> f64 {
        let r = self.h * self.shape.len() as f64;
        self.hardness * PI * r * r
    }

    /// The approach of first contact of the surface as it stands.
    fn lowest_surface(&self) -> f64 {
        (0..self.shape.len())
            .map(|i| self.shape[i] + self.plastic[i])
            .fold(f64::INFINITY, f64::min)
    }

    fn force(&self) -> f64 {
        self.force_of(&self.load)
    }

    /// The force of ring pressures or line loads `load`.
    fn force_of(&self, load: &[f64]) -> f64 {
        match self.rule {
            PlasticRule::IncrementalHess => (0..load.len())
                .map(|i| load[i] * ring_area(i, self.h))
                .sum(),
            // Both halves of the line.
            PlasticRule::SpringCap => 2.0 * self.h * load.iter().sum::<f64>(),
        }
    }

    /// The loads at approach `d` on the surface as it stands, into `load` (from its
    /// values).
    fn load_at(&self, d: f64, tolerance: f64, load: &mut [f64]) -> Result<()> {
        match self.rule {
            PlasticRule::IncrementalHess => self.solve_rings(d, tolerance, load),
            PlasticRule::SpringCap => {
                self.load_springs(d, load);
                Ok(())
            }
        }
    }

    fn state(&self) -> Result<PlasticState> {
        let n = self.load.len();
        let last = |cond: &dyn Fn(usize) -> bool| {
            (0..n)
                .rev()
                .find(|&i| cond(i))
                .map_or(0.0, |i| (i + 1) as f64 * self.h)
        };
        let (contact, plastic) = match self.rule {
            PlasticRule::IncrementalHess => (
                last(&|i| self.load[i] > 0.0),
                last(&|i| self.load[i] >= AT_CAP * self.hardness),
            ),
            PlasticRule::SpringCap => {
                let a = last(&|i| self.load[i] > 0.0);
                let capped = |i: usize| {
                    let x = (i as f64 + 0.5) * self.h;
                    self.load[i] > 0.0 && self.load[i] >= AT_CAP * cap(self.hardness, a, x)
                };
                (a, last(&capped))
            }
        };
        if contact >= self.h * n as f64 {
            return Err(MrdError::OutOfRange {
                needed: contact,
                limit: self.h * n as f64,
            });
        }
        Ok(PlasticState {
            approach: self.approach,
            force: self.force(),
            contact_radius: contact,
            plastic_radius: plastic,
            plastic_depth: self.plastic.iter().cloned().fold(0.0, f64::max),
        })
    }

    /// SpringCap: line loads at approach `d` (module docs).
    fn load_springs(&self, d: f64, load: &mut [f64]) {
        let n = self.shape.len();
        let press = |i: usize| d - self.shape[i] - self.plastic[i];
        let a = (0..n)
            .rev()
            .find(|&i| press(i) > 0.0)
            .map_or(0.0, |i| (i + 1) as f64 * self.h);
        for i in 0..n {
            let x = (i as f64 + 0.5) * self.h;
            let elastic = self.e_star * press(i).max(0.0);
            load[i] = elastic.min(cap(self.hardness, a, x));
        }
    }

    /// IncrementalHess: ring pressures in [0, H] at approach `d` by projected
    /// Gauss-Seidel with over-relaxation on the dense operator, from the last pressures.
    fn solve_rings(&self, d: f64, tolerance: f64, load: &mut [f64]) -> Result<()> {
        let n = self.shape.len();
        let surface: Vec<f64> = (0..n).map(|i| self.shape[i] + self.plastic[i]).collect();
        let scale = surface
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(d.abs())
            .max(f64::MIN_POSITIVE);
        let mut u = vec![0.0; n];
        for j in 0..n {
            if load[j] != 0.0 {
                for i in 0..n {
                    u[i] += self.k[i * n + j] * load[j];
                }
            }
        }
        let omega = 1.5;
        for _sweep in 0..MAX_SWEEPS {
            let mut worst = 0.0f64;
            for i in 0..n {
                let g = u[i] + surface[i] - d;
                let p = load[i];
                let violation = if p > 0.0 && p < self.hardness {
                    g.abs()
                } else if p <= 0.0 {
                    (-g).max(0.0)
                } else {
                    g.max(0.0)
                };
                worst = worst.max(violation);
                let new = (p - omega * g / self.k[i * n + i]).clamp(0.0, self.hardness);
                let dp = new - p;
                if dp != 0.0 {
                    load[i] = new;
                    for (m, ui) in u.iter_mut().enumerate() {
                        *ui += self.k[m * n + i] * dp;
                    }
                }
            }
            if worst <= tolerance * scale {
                return Ok(());
            }
        }
        Err(MrdError::NoConvergence {
            what: "the rings' pressures (projected Gauss-Seidel sweeps)",
            iterations: MAX_SWEEPS,
            residual: f64::NAN,
        })
    }

    /// The plastic displacement grows where a ring (spring) sits at its cap with a
    /// negative gap (a spring pressed beyond its cap), beyond the solve's resolution.
    fn flow(&mut self, d: f64, tolerance: f64) {
        let n = self.shape.len();
        match self.rule {
            PlasticRule::IncrementalHess => {
                let mut u = vec![0.0; n];
                for j in 0..n {
                    for i in 0..n {
                        u[i] += self.k[i * n + j] * self.load[j];
                    }
                }
                let resolution = tolerance * d.abs().max(self.h);
                for i in 0..n {
                    let g = u[i] + self.shape[i] + self.plastic[i] - d;
                    if self.load[i] >= self.hardness && g < -resolution {
                        self.plastic[i] -= g;
                    }
                }
            }
            PlasticRule::SpringCap => {
                for i in 0..n {
                    let set = d - self.shape[i] - self.plastic[i] - self.load[i] / self.e_star;
                    if self.load[i] > 0.0 && set > 0.0 {
                        self.plastic[i] += set;
                    }
                }
            }
        }
    }
}

/// A ring or spring within this fraction of its cap counts as saturated (a reloading
/// brings the core back to the cap, which an iterate reaches only to its tolerance).
pub const AT_CAP: f64 = 1.0 - 1e-6;

/// Sweeps of the rings' projected Gauss-Seidel.
const MAX_SWEEPS: usize = 200_000;

/// The fully plastic line load at `x` for a contact of radius `a`: `2 H sqrt(a^2 - x^2)`.
fn cap(hardness: f64, a: f64, x: f64) -> f64 {
    2.0 * hardness * (a * a - x * x).max(0.0).sqrt()
}

/// The area of ring `i` (inner radius `i h`, outer `(i + 1) h`).
fn ring_area(i: usize, h: f64) -> f64 {
    PI * h * h * ((i + 1) * (i + 1) - i * i) as f64
}

/// The dense axisymmetric operator on `n` rings of width `h` (module docs): the surface
/// displacement at ring centre `i` per unit pressure on ring `j`, through the line load
/// (Abel's integral per ring, exact for a uniform ring pressure) and the inverse rule of
/// Hess (the line load held constant over each spring's cell, its `1/sqrt` kernel
/// integrated exactly).
fn operator(n: usize, h: f64, e_star: f64) -> Vec<f64> {
    let s = |r: f64, x: f64| (r * r - x * x).max(0.0).sqrt();
    // Abel: line load at spring k per unit pressure on ring j.
    let mut abel = vec![0.0; n * n];
    for k in 0..n {
        let x = (k as f64 + 0.5) * h;
        for j in 0..n {
            abel[k * n + j] = 2.0 * (s((j + 1) as f64 * h, x) - s(j as f64 * h, x));
        }
    }
    // Inverse Hess: displacement at ring i per unit line load on spring k.
    let hess = inverse_hess(n, h);
    let mut k_op = vec![0.0; n * n];
    for i in 0..n {
        for m in 0..n {
            let w = hess[i * n + m] / e_star;
            if w != 0.0 {
                for j in 0..n {
                    k_op[i * n + j] += w * abel[m * n + j];
                }
            }
        }
    }
    k_op
}

/// The inverse rule of Hess on `n` cells of width `h`: `f(r_i) = sum_k w[i n + k] g_k`
/// for a 1D function `g` held constant over each cell, `f(r) = (2 / pi) int_0^r g(x) /
/// sqrt(r^2 - x^2) dx` with the kernel integrated exactly over each cell.
fn inverse_hess(n: usize, h: f64) -> Vec<f64> {
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        let r = (i as f64 + 0.5) * h;
        for k in 0..n {
            let (lo, hi) = (k as f64 * h, (k + 1) as f64 * h);
            if lo >= r {
                break;
            }
            w[i * n + k] = 2.0 / PI * ((hi.min(r) / r).asin() - (lo / r).asin());
        }
    }
    w
}

/// The 3D pressure at the spring centres of a line load held constant over each spring's
/// cell, by the inverse Abel transform (Eq. 26) `p(r) = -(1/pi) int_r^inf q'(x) /
/// sqrt(x^2 - r^2) dx`: each cell boundary's jump integrated exactly.
fn abel_pressure(q: &[f64], h: f64) -> Vec<f64> {
    let n = q.len();
    (0..n)
        .map(|i| {
            let r = (i as f64 + 0.5) * h;
            // q drops by q[k] - q[k + 1] at x = (k + 1) h: p = sum of jumps / (pi sqrt).
            (i..n)
                .map(|k| {
                    let x = (k + 1) as f64 * h;
                    let next = if k + 1 < n { q[k + 1] } else { 0.0 };
                    (q[k] - next) / (PI * (x * x - r * r).sqrt())
                })
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Shape;

    fn sphere() -> Profile {
        Profile::single(Shape::paraboloid(1.0).unwrap())
    }

    /// With no hardness both rules are Hertz: F = 4/3 E* sqrt(R) d^(3/2), converging
    /// with the rings.
    #[test]
    fn without_hardness_both_rules_are_hertz() {
        let d: f64 = 0.01;
        let hertz = 4.0 / 3.0 * d.powf(1.5);
        for rule in [PlasticRule::IncrementalHess, PlasticRule::SpringCap] {
            let mut errs = vec![];
            for n in [50, 100, 200] {
                let mut c =
                    AxisymPlastic::new(&sphere(), 1.0, f64::INFINITY, rule, n, 0.2).unwrap();
                let s = c.step(d, 1e-10).unwrap();
                errs.push((s.force / hertz - 1.0).abs());
                assert_eq!(s.plastic_depth, 0.0);
            }
            assert!(errs[2] < 2e-3, "{rule:?}: {errs:?}");
            assert!(errs[2] < errs[0], "{rule:?}: {errs:?}");
        }
    }
}
