//! A rough line on an elastic-perfectly plastic MRD foundation, loaded along a history
//! (the review's Section 11 question for rough surfaces): the springs `E* dx` of a rough
//! line (Sections 9 and 10.2) whose line loads are capped patch by patch.
//!
//! **The patch cap.** At approach `d` spring `i` is pressed by `delta_i = d - z_i - s_i`
//! (`z_i` its gap to the highest point of the undeformed line, `s_i` its permanent set so
//! far). The springs in contact form patches, runs of neighbours; a patch of half-length
//! `a` centred at `c` is read as the MRD image of one microcontact of radius `a`, whose
//! fully plastic state (a uniform pressure `H` over the disc, force `pi a^2 H`) has the
//! line load `q_Y(x) = 2 H sqrt(a^2 - (x - c)^2)` (Eq. 25 for a uniform pressure). Each
//! spring carries `min(E* delta_i, q_Y(x_i))`; a spring pressed beyond its cap takes
//! the excess as permanent set, so unloading leaves a residual line. A spring keeps the
//! largest cap it has had: a patch shrinks as it unloads, and without that memory its
//! edge springs would flow again on the way down, where the 3D pressure-cap contact
//! unloads elastically; with it, unloading is elastic and reloading retraces it up to
//! the largest earlier load. On one patch this is `plasticity`'s
//! `PlasticRule::SpringCap` (the structure of Zunker & Kamrin's MDR model, J. Mech.
//! Phys. Solids 183 (2024) 105492); on a rough line it applies it to every microcontact.
//! When the whole line touches, it is one patch of half-length `L / 2`: the rigid flat
//! punch of diameter `L` the rough line stands for (Pohrt & Popov), whose fully plastic
//! force is `H pi L^2 / 4`, the 3D limit.
//!
//! The line is open (its ends are the punch's edge; patches do not wrap). Patches grow
//! or merge as the approach grows, and the cap of a merged patch covers those of its
//! parts, so the force is non-decreasing in the approach and a force-controlled step is
//! a bracketed root (Brent). The set grows only at a committed step, never during the
//! search. Units are the caller's.

use crate::error::{positive, MrdError, Result};

/// A spring within this fraction of its cap counts as saturated.
pub const AT_CAP: f64 = 1.0 - 1e-6;
/// The relative force tolerance of a step where a caller names none (the Python class's
/// default).
pub const STEP_TOLERANCE: f64 = 1e-10;
/// Force evaluations of one force-controlled step's search.
const MAX_SEARCH: usize = 400;

/// The state after one step of a [`PlasticLine`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineStep {
    /// Approach from the first contact of the undeformed line [length].
    pub approach: f64,
    /// Force `dx sum q_i` [force].
    pub force: f64,
    /// Springs in contact, and those of them at their cap.
    pub contacts: usize,
    pub capped: usize,
    /// Patches (runs of springs in contact).
    pub patches: usize,
    /// The unloading stiffness `E* dx contacts` [force/length].
    pub stiffness: f64,
    /// The largest permanent set so far [length].
    pub largest_set: f64,
}

/// A rough line of length `L` on `N` springs with patch-capped line loads (module docs).
#[derive(Debug, Clone)]
pub struct PlasticLine {
    e_star: f64,
    hardness: f64,
    dx: f64,
    /// Gap of each spring to the undeformed line's highest point (>= 0) [length].
    gap: Vec<f64>,
    /// Permanent set per spring (>= 0) [length].
    set: Vec<f64>,
    /// Line loads of the last step [force/length].
    load: Vec<f64>,
    /// The largest cap each spring has had at a committed step [force/length].
    reached: Vec<f64>,
    approach: f64,
}

impl PlasticLine {
    /// `heights` (finite, at least 2) at the centres of `N` springs over `length`, the
    /// modulus `e_star` > 0 and the hardness `hardness` > 0 (infinite: the elastic rough
    /// line of [`crate::rough_contact::RoughLine`]) [stress]. Starts apart.
    pub fn new(heights: &[f64], length: f64, e_star: f64, hardness: f64) -> Result<Self> {
        positive("length", length)?;
        positive("e_star", e_star)?;
        if hardness.is_nan() || hardness <= 0.0 {
            return Err(MrdError::InvalidParameter {
                name: "hardness H",
                value: hardness,
                reason: "must be > 0 (infinite: no plasticity)",
            });
        }
        let n = heights.len();
        if n < 2 {
            return Err(MrdError::InvalidData(
                "a rough line needs at least 2 points".into(),
            ));
        }
        if let Some((i, what)) = crate::error::bad_height(heights) {
            return Err(MrdError::InvalidData(format!(
                "rough line: {what} at index {i}"
            )));
        }
        let top = heights.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
        Ok(Self {
            e_star,
            hardness,
            dx: length / n as f64,
            gap: heights.iter().map(|h| top - h).collect(),
            set: vec![0.0; n],
            load: vec![0.0; n],
            reached: vec![0.0; n],
            approach: 0.0,
        })
    }

    /// The permanent set of each spring so far [length]: the residual line after
    /// unloading lies this far below the undeformed one.
    pub fn set(&self) -> &[f64] {
        &self.set
    }

    /// Line loads of the last step [force/length].
    pub fn load(&self) -> &[f64] {
        &self.load
    }

    /// The largest force a step can carry: the whole line one fully plastic patch,
    /// `dx sum 2 H sqrt(a^2 - x^2)` with `a = L / 2` (about `H pi L^2 / 4`) [force].
    pub fn force_limit(&self) -> f64 {
        let n = self.gap.len();
        let mut caps = vec![0.0; n];
        self.caps(0, n, &mut caps);
        self.dx * caps.iter().sum::<f64>()
    }

    /// Loads to approach `d` (finite) from the last state and commits it.
    pub fn step(&mut self, d: f64) -> Result<LineStep> {
        if !d.is_finite() {
            return Err(MrdError::InvalidParameter {
                name: "approach",
                value: d,
                reason: "must be finite",
            });
        }
        let mut load = std::mem::take(&mut self.load);
        self.load_at(d, &mut load);
        Ok(self.commit(d, load))
    }

    /// Makes `load` at approach `d` the state: springs pressed beyond what they carry
    /// take the excess as permanent set (a spring at its cap keeps its load, its
    /// compression becomes exactly load / E*).
    fn commit(&mut self, d: f64, load: Vec<f64>) -> LineStep {
        let mut caps = vec![0.0; self.gap.len()];
        self.patch_caps(d, &mut caps);
        for (r, c) in self.reached.iter_mut().zip(&caps) {
            *r = r.max(*c);
        }
        self.load = load;
        self.approach = d;
        for i in 0..self.gap.len() {
            let excess = d - self.gap[i] - self.set[i] - self.load[i] / self.e_star;
            if self.load[i] > 0.0 && excess > 0.0 {
                self.set[i] += excess;
            }
        }
        self.state()
    }

    /// Loads to the force `f` (finite, in `[0, force_limit)`) from the last state, to
    /// `tolerance` (relative, in (0, 0.01]) of the force: the approach by regula falsi
    /// (Illinois) on the non-decreasing force, bisecting when it stalls. The force
    /// jumps up where a spring joins a patch (its half-length grows by a spring) or two
    /// patches merge (the merged cap covers both): a force inside a jump is carried at
    /// the jump's approach by the blend of the loads on its two sides that gives `f`
    /// (a merge in progress), so every force is reached exactly.
    pub fn step_to_force(&mut self, f: f64, tolerance: f64) -> Result<LineStep> {
        if !(f.is_finite() && f >= 0.0) {
            return Err(MrdError::InvalidParameter {
                name: "force",
                value: f,
                reason: "must be finite and >= 0",
            });
        }
        if !(tolerance > 0.0 && tolerance <= 1e-2) {
            return Err(MrdError::InvalidParameter {
                name: "tolerance",
                value: tolerance,
                reason: "must lie in (0, 0.01]",
            });
        }
        let limit = self.force_limit();
        if f >= limit {
            return Err(MrdError::ImpossibleLoad(format!(
                "force {f} must stay below the fully plastic line's {limit:e} (every spring at its cap)"
            )));
        }
        let n = self.gap.len();
        let lo = (0..n)
            .map(|i| self.gap[i] + self.set[i])
            .fold(f64::INFINITY, f64::min);
        if f == 0.0 {
            return self.step(lo);
        }
        let mut load = vec![0.0; n];
        let excess = |d: f64, load: &mut Vec<f64>| {
            self.load_at(d, load);
            self.dx * load.iter().sum::<f64>() - f
        };
        // The stiffest state (every spring elastic) moves F by E* L per unit approach.
        let reach = f / (self.e_star * self.dx * n as f64);
        let (mut a, mut fa) = (lo, -f);
        let mut b = lo + (self.approach - lo).max(reach);
        let mut fb = excess(b, &mut load);
        while fb < 0.0 {
            (a, fa) = (b, fb);
            b = lo + 2.0 * (b - lo);
            if !b.is_finite() {
                return Err(MrdError::ImpossibleLoad(format!(
                    "force {f}: no approach carries it"
                )));
            }
            fb = excess(b, &mut load);
        }
        let xtol = 1e-3 * tolerance * reach;
        let mut side = 0i8;
        for _ in 0..MAX_SEARCH {
            if fb <= tolerance * f || b - a <= xtol {
                break;
            }
            let mut x = b - fb * (b - a) / (fb - fa);
            if !(x > a && x < b) {
                x = 0.5 * (a + b);
            }
            let fx = excess(x, &mut load);
            if fx >= 0.0 {
                (b, fb) = (x, fx);
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            } else {
                (a, fa) = (x, fx);
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            }
        }
        // The Illinois halvings scale fa and fb: the loads on each side are recomputed.
        let mut upper = vec![0.0; n];
        let f_upper = excess(b, &mut upper) + f;
        if f_upper - f > tolerance * f {
            let mut lower = vec![0.0; n];
            let f_lower = excess(a, &mut lower) + f;
            let w = (f - f_lower) / (f_upper - f_lower);
            for (u, l) in upper.iter_mut().zip(&lower) {
                *u = w * *u + (1.0 - w) * l;
            }
        }
        Ok(self.commit(b, upper))
    }

    /// The caps `2 H sqrt(a^2 - (x - c)^2)` of the patch of springs `from..to` into
    /// `caps[from..to]`.
    fn caps(&self, from: usize, to: usize, caps: &mut [f64]) {
        let a = 0.5 * (to - from) as f64 * self.dx;
        let c = 0.5 * (from + to) as f64 * self.dx;
        for (i, cap) in caps.iter_mut().enumerate().take(to).skip(from) {
            let x = (i as f64 + 0.5) * self.dx - c;
            *cap = 2.0 * self.hardness * (a * a - x * x).max(0.0).sqrt();
        }
    }

    /// The caps of the patches at approach `d` on the line as it stands into `caps`
    /// (0 out of contact; infinite without a hardness).
    fn patch_caps(&self, d: f64, caps: &mut [f64]) {
        let n = self.gap.len();
        let touches = |i: usize| d - self.gap[i] - self.set[i] > 0.0;
        let mut i = 0;
        while i < n {
            if !touches(i) {
                caps[i] = 0.0;
                i += 1;
                continue;
            }
            let from = i;
            while i < n && touches(i) {
                i += 1;
            }
            if self.hardness.is_finite() {
                self.caps(from, i, caps);
            } else {
                caps[from..i].fill(f64::INFINITY);
            }
        }
    }

    /// The line loads at approach `d` on the line as it stands, into `load`: each
    /// spring's elastic load up to the larger of its patch's cap and the largest cap it
    /// has had (so unloading, which shrinks the patches, stays elastic, as the
    /// pressure-cap model's does).
    fn load_at(&self, d: f64, load: &mut [f64]) {
        self.patch_caps(d, load);
        for (i, q) in load.iter_mut().enumerate() {
            let press = d - self.gap[i] - self.set[i];
            *q = if press > 0.0 {
                (self.e_star * press).min(q.max(self.reached[i]))
            } else {
                0.0
            };
        }
    }

    fn state(&self) -> LineStep {
        let n = self.gap.len();
        let (mut contacts, mut capped, mut patches) = (0, 0, 0);
        let mut caps = vec![0.0; n];
        let mut i = 0;
        while i < n {
            if self.load[i] <= 0.0 {
                i += 1;
                continue;
            }
            let from = i;
            while i < n && self.load[i] > 0.0 {
                i += 1;
            }
            patches += 1;
            contacts += i - from;
            if self.hardness.is_finite() {
                self.caps(from, i, &mut caps);
                capped += (from..i)
                    .filter(|&k| self.load[k] >= AT_CAP * caps[k].max(self.reached[k]))
                    .count();
            }
        }
        LineStep {
            approach: self.approach,
            force: self.dx * self.load.iter().sum::<f64>(),
            contacts,
            capped,
            patches,
            stiffness: self.e_star * self.dx * contacts as f64,
            largest_set: self.set.iter().cloned().fold(0.0, f64::max),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plasticity::{AxisymPlastic, PlasticRule};
    use crate::profile::{Profile, Shape};
    use crate::rough_contact::RoughLine;

    fn rough(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let x = i as f64 / n as f64 * std::f64::consts::TAU;
                (3.0 * x).sin() + 0.5 * (7.0 * x + 1.0).cos() + 0.2 * (23.0 * x + 2.0).sin()
            })
            .collect()
    }

    /// Without a cap the line is the elastic rough line: every force gives
    /// `RoughLine`'s approach.
    #[test]
    fn an_infinite_hardness_is_the_elastic_rough_line() {
        let h = rough(512);
        let elastic = RoughLine::new(&h, 1.0, 2.0).unwrap();
        let mut line = PlasticLine::new(&h, 1.0, 2.0, f64::INFINITY).unwrap();
        for f in [1e-3, 1e-2, 0.1, 1.0, 0.3, 0.0, 2.0] {
            let s = line.step_to_force(f, 1e-10).unwrap();
            let e = elastic.at_force(f).unwrap();
            assert!(
                (s.approach - e.depth).abs() <= 1e-9 * e.depth.max(1e-3),
                "{f}"
            );
            assert!(
                (s.force - f).abs() <= 1e-9 * f.max(1e-12),
                "{f}: {}",
                s.force
            );
            assert_eq!(s.contacts, e.contacts, "{f}");
            assert_eq!(s.largest_set, 0.0);
        }
    }

    /// One patch is `plasticity`'s spring cap: the rule of Hess image of a sphere
    /// (z1d = x^2 / R) on the two halves of a symmetric line gives, along a loading,
    /// the axisymmetric rule's forces to rounding (that rule has no memory of its
    /// caps: on unloading the two part, see the module docs).
    #[test]
    fn one_patch_is_the_axisymmetric_spring_cap() {
        let (n, r_max, radius, e, hard) = (200usize, 0.2, 1.0, 1.0, 0.05);
        let h = r_max / n as f64;
        let heights: Vec<f64> = (0..2 * n)
            .map(|i| {
                let x = (i as f64 + 0.5) * h - r_max;
                -x * x / radius
            })
            .collect();
        let mut line = PlasticLine::new(&heights, 2.0 * r_max, e, hard).unwrap();
        let profile = Profile::single(Shape::paraboloid(radius).unwrap());
        let mut axi =
            AxisymPlastic::new(&profile, e, hard, PlasticRule::SpringCap, n, r_max).unwrap();
        // Approaches from the apex: the line's highest springs sit h^2 / 4 below it.
        let offset = 0.25 * h * h / radius;
        for d in [1e-3, 2e-3, 5e-3, 8e-3, 1e-2, 1.2e-2] {
            let s = line.step(d - offset).unwrap();
            let a = axi.step(d, 1e-10).unwrap();
            assert!(
                (s.force - a.force).abs() <= 1e-12 * a.force.max(1e-12),
                "{d}: {} against {}",
                s.force,
                a.force
            );
        }
        assert!(line.set().iter().any(|&s| s > 0.0));
    }

    /// A flat line touches everywhere at once: one patch of half-length L/2, whose
    /// fully plastic force tends to `H pi L^2 / 4` as the springs refine (the sum of the
    /// ellipse's samples, an error of order dx^1.5).
    #[test]
    fn a_flat_line_saturates_at_the_punch_limit() {
        let (l, hard) = (2.0, 0.3);
        let exact = hard * std::f64::consts::PI * l * l / 4.0;
        let mut errors = vec![];
        for n in [100, 400, 1600] {
            let mut line = PlasticLine::new(&vec![0.0; n], l, 1.0, hard).unwrap();
            let s = line.step(10.0).unwrap();
            assert_eq!(s.patches, 1);
            assert_eq!(s.contacts, n);
            assert!((s.force - line.force_limit()).abs() <= 1e-12 * exact);
            errors.push((s.force / exact - 1.0).abs());
            assert!(line.step_to_force(1.01 * exact, 1e-8).is_err());
        }
        let order = (errors[0] / errors[1]).log(4.0);
        assert!((1.3..1.7).contains(&order), "{errors:?} order {order}");
    }

    /// Unloading is elastic and reloading retraces it up to the earlier peak: the set
    /// stays, the force at a reloaded approach is the unloaded one's.
    #[test]
    fn unloading_keeps_the_set_and_reloading_retraces_it() {
        let h: Vec<f64> = rough(1024).iter().map(|v| 1e-2 * v).collect();
        let mut line = PlasticLine::new(&h, 1.0, 1.0, 2e-3).unwrap();
        let peak = line.step_to_force(5e-4, 1e-10).unwrap();
        assert!(peak.capped > 0 && peak.largest_set > 0.0, "{peak:?}");
        let set = line.set().to_vec();
        let down = line.step_to_force(2e-4, 1e-10).unwrap();
        let up = line.step_to_force(5e-4, 1e-10).unwrap();
        assert!(down.approach < peak.approach);
        assert!(
            (up.approach - peak.approach).abs() <= 1e-9 * peak.approach,
            "{peak:?} {up:?}"
        );
        let moved = line
            .set()
            .iter()
            .zip(&set)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(moved <= 1e-10 * peak.largest_set, "{moved}");
        // The unloading stiffness is the contacts' springs.
        assert_eq!(peak.stiffness, 1.0 / 1024.0 * peak.contacts as f64);
    }

    #[test]
    fn bad_input_names_the_parameter() {
        let h = rough(16);
        for (r, name) in [
            (PlasticLine::new(&h, 1.0, 1.0, 0.0).err(), "hardness"),
            (PlasticLine::new(&h, 1.0, 1.0, f64::NAN).err(), "hardness"),
            (PlasticLine::new(&h, -1.0, 1.0, 1.0).err(), "length"),
            (PlasticLine::new(&[1.0], 1.0, 1.0, 1.0).err(), "2 points"),
            (
                PlasticLine::new(&[1.0, f64::NAN], 1.0, 1.0, 1.0).err(),
                "index 1",
            ),
        ] {
            let m = r.expect(name).to_string();
            assert!(m.contains(name), "{m}");
        }
        let mut line = PlasticLine::new(&h, 1.0, 1.0, 1.0).unwrap();
        assert!(line
            .step(f64::NAN)
            .unwrap_err()
            .to_string()
            .contains("approach"));
        assert!(line
            .step_to_force(-1.0, 1e-6)
            .unwrap_err()
            .to_string()
            .contains("force"));
        assert!(line
            .step_to_force(0.1, 0.0)
            .unwrap_err()
            .to_string()
            .contains("tolerance"));
    }
}
