//! Elastic-perfectly plastic normal contact in the pressure-cap model: a rigid surface on
//! an elastic half-space whose surface pressure cannot exceed the hardness `H`. Each
//! cell's pressure lies in `[0, H]`; a cell at `H` whose gap would be negative flows: the
//! half-space's surface there is lowered for good by the penetration (the plastic
//! displacement `u_p >= 0`), so after unloading the surface carries a residual
//! topography and a reloading is elastic up to the largest earlier load. This is the
//! model of Tamaas' saturated solver and of the rough-contact literature's "hardness"
//! (Almqvist et al., Wear 262 (2007) 983; Pei et al., J. Mech. Phys. Solids 53 (2005)
//! 2385 compare it with J2 plasticity): the pressure saturates, the stresses below the
//! surface are not resolved.
//!
//! **Conventions** are the normal solver's ([`crate::solver`]): `heights` the rigid
//! surface's topography (peaks up), `z = max(h) - h`, gap `g = u + z + u_p - d` at
//! approach `d` (first contact of the undeformed surface at `d = 0`), `u = K p`.
//!
//! **One step.** For an approach, the pressures minimise the convex energy
//! `p.K p / 2 + p.(z + u_p - d)` over the boxes `0 <= p <= H`: the kit's projected
//! conjugate gradient (`kit::box_cg`) with the box `[0, H]` on every cell of the
//! domain. Its optimality conditions are the model's: a cell out of contact has
//! `p = 0, g >= 0`, an elastic contact cell `0 < p < H, g = 0`, a plastic one `p = H,
//! g <= 0`. Then each plastic cell's penetration becomes plastic displacement,
//! `u_p += max(0, -g)`, which leaves its gap at 0 and every pressure unchanged, so the
//! state is the model's solution on the new surface. Under a prescribed force, the same
//! solve holds `A sum p = F` (A the cell area) instead of the approach: the approach is
//! the constraint's multiplier (`kit::box_cg`'s `Hold::Sum`), one warm-started solve per
//! step, the force met to rounding and the gaps to the tolerance. Where that solve
//! stalls (`box_cg::STALLED`: near saturation on rough faces), the approach is searched
//! from the state it reached: the root of the non-decreasing `F(d) = A sum p(d)`, by
//! bracketing and the Illinois form of regula falsi on warm-started solves holding the
//! approach, until `|F - F_target| <= tolerance F_target` (each solve to a tenth of
//! that), about ten solves (bench/HISTORY.md). The plastic displacement grows only once
//! the step's state is found: the trial solves leave the surface as it was.
//!
//! **Limits.** Without a cell at `H` the step is the elastic contact (the normal
//! solver's, to its tolerance: the two iterations differ, the optimum does not); at a
//! load that saturates every cell of the domain the force is `H` times the domain's
//! area, the largest a step can carry: a larger force is refused.

use crate::error::{BemError, Result};
use crate::kit::box_cg::{self, Bound, BoxProblem, Hold, Scratch};
use crate::kit::surface::{rigid_surface, RigidSurface};
use crate::operator::Preconditioner;
use crate::solver::{check_load_magnitude, Interrupt, Load};

/// A cell within this fraction of the hardness counts as plastic (a reloading brings the
/// core back to H, which an iterate reaches only to its tolerance).
pub const AT_CAP: f64 = 1.0 - 1e-6;
/// The tolerance of a step where a caller names none (the Python class's default).
pub const STEP_TOLERANCE: f64 = 1e-8;
/// Conjugate-gradient iterations of one solve.
const MAX_ITERATIONS: usize = 20_000;
/// Solves of the force search of one step.
const MAX_SEARCH: usize = 200;

/// What a force search spent.
#[derive(Debug, Default)]
struct Count {
    iterations: usize,
    solves: usize,
    residual: f64,
}

impl Count {
    /// (iterations, solves, the last solve's criterion).
    fn of(&self) -> (usize, usize, f64) {
        (self.iterations, self.solves, self.residual)
    }
}

/// The state reached by one load step.
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticStep {
    /// Approach `d` from the first contact of the undeformed surface [length].
    pub approach: f64,
    /// Total normal force `A sum p` [force].
    pub force: f64,
    /// Cells carrying pressure, and those of them at the hardness (within [`AT_CAP`]).
    pub contact_cells: usize,
    pub plastic_cells: usize,
    /// Contact cells and plastic cells times the cell area [length^2].
    pub contact_area: f64,
    pub plastic_area: f64,
    /// The largest plastic displacement of the surface so far [length].
    pub plastic_depth: f64,
    /// Cells whose plastic displacement grew in this step.
    pub flowed: usize,
    /// Conjugate-gradient iterations summed over the step's solves, and the solves (one,
    /// but where a solve holding the force stalled and the approach was searched).
    pub iterations: usize,
    pub solves: usize,
    /// The last solve's criterion at its stop (`kit::box_cg`).
    pub residual: f64,
}

/// A rigid surface pressed on an elastic-perfectly plastic half-space along a history
/// (module docs). Shares the normal solver's operators.
pub struct PlasticContact<C: Preconditioner> {
    op: C,
    z: Vec<f64>,
    domain: Vec<bool>,
    hardness: f64,
    /// Length scale of the criterion: the rms of z (at least the smallest normal number).
    scale: f64,
    plastic: Vec<f64>,
    /// `z + u_p`, the surface the solves see.
    surface: Vec<f64>,
    p: Vec<f64>,
    u: Vec<f64>,
    approach: f64,
    interrupt: Option<Interrupt>,
    scratch: Scratch,
}

impl<C: Preconditioner> PlasticContact<C> {
    /// [`Self::new`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn new_generic(
        op: C,
        heights: &[f64],
        mask: Option<&[bool]>,
        hardness: f64,
    ) -> Result<Self> {
        if hardness.is_nan() || hardness <= 0.0 {
            return Err(BemError::InvalidInput(format!(
                "hardness H = {hardness} must be > 0 (infinite: no plasticity)"
            )));
        }
        let RigidSurface { z, domain, rms, .. } = rigid_surface(&op, heights, mask)?;
        let n = z.len();
        let scale = rms.max(f64::MIN_POSITIVE);
        Ok(Self {
            op,
            surface: z.clone(),
            z,
            domain,
            hardness,
            scale,
            plastic: vec![0.0; n],
            p: vec![0.0; n],
            u: vec![0.0; n],
            approach: 0.0,
            interrupt: None,
            scratch: Scratch::default(),
        })
    }

    /// Stops the iteration of a step with [`BemError::Interrupted`] once `flag` is set
    /// (from another thread), polled once per iteration.
    pub fn interrupt_on(&mut self, flag: Interrupt) {
        self.interrupt = Some(flag);
    }

    /// The hardness H [stress].
    pub fn hardness(&self) -> f64 {
        self.hardness
    }

    /// Cell pressures of the last step (`ny x nx`) [stress].
    pub fn pressure(&self) -> &[f64] {
        &self.p
    }

    /// The plastic displacement of each cell so far (`ny x nx`, >= 0): how far the
    /// half-space's surface was lowered for good [length]. After unloading it is the
    /// residual topography (an imprint).
    pub fn plastic_displacement(&self) -> &[f64] {
        &self.plastic
    }

    /// Gap `u + z + u_p - d` of the last step at every cell (`ny x nx`) [length].
    pub fn gap(&self) -> Vec<f64> {
        (0..self.z.len())
            .map(|i| self.u[i] + self.surface[i] - self.approach)
            .collect()
    }

    /// The largest force a step can carry: `H` times the domain's area [force].
    pub fn force_limit(&self) -> f64 {
        let cells = self.domain.iter().filter(|d| **d).count();
        self.hardness * cells as f64 * self.op.cell_area()
    }

    /// [`Self::step`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn step_generic(&mut self, load: Load, tolerance: f64) -> Result<PlasticStep> {
        if !(tolerance > 0.0 && tolerance <= 0.01) {
            return Err(BemError::InvalidInput(format!(
                "tolerance {tolerance} must lie in (0, 0.01]"
            )));
        }
        let op = &self.op;
        check_load_magnitude(load, op.e_star(), (op.lx(), op.ly()))?;
        let force = match load {
            Load::Approach(d) if d.is_finite() => None,
            Load::Force(f) => Some(f),
            Load::MeanPressure(p) => Some(p * op.lx() * op.ly()),
            Load::Approach(d) => {
                return Err(BemError::InvalidInput(format!(
                    "approach {d} must be finite"
                )))
            }
        };
        if let Some(f) = force {
            let limit = self.force_limit();
            if !(f.is_finite() && f >= 0.0 && f < limit) {
                return Err(BemError::InvalidInput(format!(
                    "force {f} must lie in [0, H x domain area = {limit:e}): at the limit every cell is at the hardness"
                )));
            }
        }
        crate::pool::on_pool(|| {
            let (iterations, solves, residual) = match (load, force) {
                (Load::Approach(d), _) => {
                    let r = self.solve_holding(Hold::Approach(d), tolerance)?;
                    (r.iterations, 1, r.residual)
                }
                (_, Some(f)) => self.solve_force(f, tolerance)?,
                _ => unreachable!("a force or an approach"),
            };
            let flowed = self.flow(tolerance * self.scale.max(self.approach.abs()));
            Ok(self.report(flowed, iterations, solves, residual))
        })
    }

    /// One solve holding `hold` from the last pressures; the approach is the one held or
    /// the multiplier of the force.
    fn solve_holding(&mut self, hold: Hold, tolerance: f64) -> Result<box_cg::Reached> {
        let d = match hold {
            Hold::Approach(d) => d,
            Hold::Sum { start, .. } => start,
        };
        let problem = BoxProblem {
            set: &self.domain,
            lo: Bound::Uniform(0.0),
            hi: Bound::Uniform(self.hardness),
            z: &self.surface,
            hold,
            scale: self.scale.max(d.abs()),
            tolerance,
            max_iterations: MAX_ITERATIONS,
            what: "elastic-plastic contact",
            interrupt: self.interrupt.as_ref(),
        };
        let reached = box_cg::solve(
            &mut self.op,
            &problem,
            &mut self.p,
            &mut self.u,
            &mut self.scratch,
        )?;
        self.approach = reached.approach;
        Ok(reached)
    }

    fn force(&self) -> f64 {
        self.p.iter().sum::<f64>() * self.op.cell_area()
    }

    /// The step under a prescribed force (module docs): one solve holding the sum of the
    /// pressures, the approach its multiplier; where that solve stalls, a search of the
    /// approach from the state it reached. Returns the iterations, solves and last
    /// criterion.
    fn solve_force(&mut self, target: f64, tolerance: f64) -> Result<(usize, usize, f64)> {
        if target == 0.0 {
            // Apart: the body just touching the surface as it stands.
            self.p.iter_mut().for_each(|p| *p = 0.0);
            self.u.iter_mut().for_each(|u| *u = 0.0);
            self.approach = self.lowest_surface();
            return Ok((0, 0, 0.0));
        }
        let hold = Hold::Sum {
            sum: target / self.op.cell_area(),
            start: self.approach,
        };
        match self.solve_holding(hold, tolerance) {
            Ok(r) => Ok((r.iterations, 1, r.residual)),
            Err(BemError::Breakdown {
                reason, iterations, ..
            }) if reason == box_cg::STALLED => {
                let (more, solves, residual) = self.search(target, tolerance)?;
                Ok((iterations + more, 1 + solves, residual))
            }
            Err(e) => Err(e),
        }
    }

    /// The approach that carries `target` where the solve holding the force stalled
    /// (module docs): a bracket grown from the last approach, then regula falsi
    /// (Illinois) on solves holding the approach. Returns the iterations, solves and
    /// last criterion.
    fn search(&mut self, target: f64, tolerance: f64) -> Result<(usize, usize, f64)> {
        let mut count = Count::default();
        let done = |miss: f64| miss.abs() <= tolerance * target;
        // A bracket [a, b] with F(a) < target <= F(b), grown from the last approach by
        // steps that double.
        let mut a = self.approach;
        let mut fa = self.miss(a, target, tolerance, &mut count)?;
        if done(fa) {
            return Ok(count.of());
        }
        let mut width = 0.1 * self.scale.max(a.abs());
        let (mut b, mut fb);
        loop {
            b = if fa < 0.0 { a + width } else { a - width };
            fb = self.miss(b, target, tolerance, &mut count)?;
            if done(fb) {
                return Ok(count.of());
            }
            if (fa < 0.0) != (fb < 0.0) {
                break;
            }
            (a, fa) = (b, fb);
            width *= 2.0;
            if count.solves > MAX_SEARCH {
                return Err(self.lost(count.iterations, target));
            }
        }
        if fa > 0.0 {
            std::mem::swap(&mut a, &mut b);
            std::mem::swap(&mut fa, &mut fb);
        }
        // Illinois: halve the weight of an end that stays twice.
        let mut side = 0i8;
        while count.solves <= MAX_SEARCH {
            let d = b - fb * (b - a) / (fb - fa);
            let f = self.miss(d, target, tolerance, &mut count)?;
            if done(f) || (b - a).abs() <= f64::EPSILON * d.abs().max(self.scale) {
                return Ok(count.of());
            }
            if f < 0.0 {
                (a, fa) = (d, f);
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            } else {
                (b, fb) = (d, f);
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            }
        }
        Err(self.lost(count.iterations, target))
    }

    /// `F(d) - target` from a solve at `d` within a tenth of the force tolerance.
    fn miss(&mut self, d: f64, target: f64, tolerance: f64, count: &mut Count) -> Result<f64> {
        let r = self.solve_holding(Hold::Approach(d), 0.1 * tolerance)?;
        count.iterations += r.iterations;
        count.solves += 1;
        count.residual = r.residual;
        Ok(self.force() - target)
    }

    fn lost(&self, iterations: usize, target: f64) -> BemError {
        BemError::Breakdown {
            what: "elastic-plastic contact",
            iterations,
            residual: (self.force() - target).abs() / target,
            reason: "the approach carrying the force was not found within the search's solves",
        }
    }

    /// The lowest point of the surface as it stands (`z + u_p` over the domain): the
    /// approach at which the body just touches it.
    fn lowest_surface(&self) -> f64 {
        (0..self.z.len())
            .filter(|&i| self.domain[i])
            .map(|i| self.surface[i])
            .fold(f64::INFINITY, f64::min)
    }

    /// Turns the penetration of the cells at the hardness into plastic displacement,
    /// where it exceeds `resolution` (the solve's own: below it a penetration is the
    /// stopping error, and an elastic reloading would otherwise creep); returns how many
    /// cells flowed.
    fn flow(&mut self, resolution: f64) -> usize {
        let mut flowed = 0;
        for i in 0..self.z.len() {
            if self.domain[i] && self.p[i] >= self.hardness {
                let g = self.u[i] + self.surface[i] - self.approach;
                if g < -resolution {
                    self.plastic[i] -= g;
                    self.surface[i] = self.z[i] + self.plastic[i];
                    flowed += 1;
                }
            }
        }
        flowed
    }

    fn report(
        &self,
        flowed: usize,
        iterations: usize,
        solves: usize,
        residual: f64,
    ) -> PlasticStep {
        let cell = self.op.cell_area();
        let contact = self.p.iter().filter(|&&p| p > 0.0).count();
        let plastic = self
            .p
            .iter()
            .filter(|&&p| p >= AT_CAP * self.hardness)
            .count();
        PlasticStep {
            approach: self.approach,
            force: self.force(),
            contact_cells: contact,
            plastic_cells: plastic,
            contact_area: contact as f64 * cell,
            plastic_area: plastic as f64 * cell,
            plastic_depth: self.plastic.iter().cloned().fold(0.0, f64::max),
            flowed,
            iterations,
            solves,
            residual,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operator::NonPeriodicHalfSpace;
    use crate::{ContactSolver, SolverOptions};
    use std::f64::consts::PI;

    /// A sphere of radius 1 (E* = 1) on `n`^2 cells of side `l`, apex between cells.
    fn sphere(n: usize, l: f64) -> Vec<f64> {
        crate::mask::centred(n, l, |x, y| -(x * x + y * y) / 2.0)
    }

    fn free(n: usize, l: f64) -> NonPeriodicHalfSpace {
        NonPeriodicHalfSpace::new(n, n, l, l, 1.0)
    }

    /// With no hardness the model is the elastic contact: the normal solver's pressures
    /// (within 1e-6 of the peak: both solves stop at 1e-10 of their own criteria) and
    /// contact cells, under a prescribed approach and a prescribed force.
    #[test]
    fn infinite_hardness_is_the_elastic_contact() {
        let (n, l) = (48, 1.0);
        let h = sphere(n, l);
        let mut c = PlasticContact::new(free(n, l), &h, None, f64::INFINITY).unwrap();
        let s = c.step(Load::Approach(0.02), 1e-10).unwrap();
        assert_eq!((s.plastic_cells, s.flowed), (0, 0));
        crate::adhesion::is_the_normal_solve(
            free(n, l),
            &h,
            0.02,
            c.pressure(),
            s.force,
            s.contact_cells,
        );
        let f = 0.4 * s.force;
        let s = c.step(Load::Force(f), 1e-9).unwrap();
        assert!((s.force / f - 1.0).abs() <= 1e-9, "{s:?}");
        let normal = ContactSolver::new(free(n, l), &h, None)
            .unwrap()
            .solve(Load::Force(f), &SolverOptions::new(1e-12, 10_000), None)
            .unwrap();
        assert!(
            (s.approach - normal.approach).abs() < 1e-7 * normal.approach,
            "{} against {}",
            s.approach,
            normal.approach
        );
    }

    /// Plastic flow starts exactly when the elastic peak pressure reaches H: with H set
    /// to the normal solver's largest cell pressure at a force F0, a step to 0.999 F0 has
    /// no cell at H, one to 1.001 F0 has.
    #[test]
    fn flow_starts_where_the_elastic_peak_reaches_the_hardness() {
        let (n, l) = (48, 1.0);
        let h = sphere(n, l);
        let f0 = 0.01;
        let normal = ContactSolver::new(free(n, l), &h, None)
            .unwrap()
            .solve(Load::Force(f0), &SolverOptions::new(1e-12, 10_000), None)
            .unwrap();
        let peak = normal.pressure.iter().cloned().fold(0.0, f64::max);
        // Hertz's peak at f0 for orientation: the cells resolve it to 2 %.
        let a = (3.0 * f0 / 4.0f64).cbrt();
        let hertz = 3.0 * f0 / (2.0 * PI * a * a);
        assert!((peak / hertz - 1.0).abs() < 0.02, "{peak} {hertz}");
        for (scale, plastic) in [(0.999, false), (1.001, true)] {
            let mut c = PlasticContact::new(free(n, l), &h, None, peak).unwrap();
            let s = c.step(Load::Force(scale * f0), 1e-10).unwrap();
            assert_eq!(s.plastic_cells > 0, plastic, "{scale}: {s:?}");
            assert_eq!(s.flowed > 0, plastic, "{scale}: {s:?}");
        }
    }

    /// Far into plasticity the contact carries the hardness over almost all of its area:
    /// the plastic area stays below F/H, the contact area above it, and the elastic rim
    /// between them shrinks as the load grows (the fully plastic limit A = F / H).
    #[test]
    fn the_fully_plastic_limit_is_area_equals_force_over_hardness() {
        let (n, l) = (64, 1.0);
        let h = sphere(n, l);
        let hardness = 0.05;
        let mut c = PlasticContact::new(free(n, l), &h, None, hardness).unwrap();
        let mut last = f64::INFINITY;
        for f in [0.002, 0.004, 0.008] {
            let s = c.step(Load::Force(f), 1e-9).unwrap();
            let ideal = f / hardness;
            assert!(
                s.plastic_area <= ideal && ideal <= s.contact_area,
                "F = {f}: plastic {} <= F/H {ideal} <= contact {}",
                s.plastic_area,
                s.contact_area
            );
            // The elastic rim's share of the area (measured 0.29, 0.10, 0.06).
            let rim = (s.contact_area - s.plastic_area) / ideal;
            assert!(rim < last, "F = {f}: {rim} after {last}");
            last = rim;
            assert!(c.pressure().iter().all(|&p| (0.0..=hardness).contains(&p)));
        }
        assert!(last < 0.08, "{last}");
    }

    /// The two ways of a step under a force reach one state: the solve holding the force
    /// (one solve) and the search of the approach it falls back on where that solve
    /// stalls (several solves holding the approach), from the same start, on a plastic
    /// sphere: approaches within 1e-7 of each other, pressures within 1e-5 of H, forces
    /// within the search's tolerance.
    #[test]
    fn holding_the_force_and_searching_the_approach_agree() {
        let (n, l) = (48, 1.0);
        let h = sphere(n, l);
        let mut held = PlasticContact::new(free(n, l), &h, None, 0.05).unwrap();
        let mut searched = PlasticContact::new(free(n, l), &h, None, 0.05).unwrap();
        for f in [0.001, 0.003] {
            let s = held.step(Load::Force(f), 1e-9).unwrap();
            assert_eq!(s.solves, 1);
            let (_, solves, _) = crate::pool::on_pool(|| searched.search(f, 1e-9)).unwrap();
            assert!(solves > 1);
            searched.flow(1e-9 * searched.scale.max(searched.approach.abs()));
            assert!(
                (held.approach - searched.approach).abs() < 1e-7,
                "{} {}",
                held.approach,
                searched.approach
            );
            assert!((searched.force() / f - 1.0).abs() < 1e-9);
            let worst = held
                .pressure()
                .iter()
                .zip(searched.pressure())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-5 * 0.05, "{worst}");
            assert!(s.plastic_cells > 0);
        }
    }

    /// Unloading leaves an imprint; a reloading is elastic up to the largest earlier
    /// force (no cell flows, the same approach at that force) and flows again beyond.
    #[test]
    fn unloading_leaves_an_imprint_and_reloading_is_elastic() {
        let (n, l) = (48, 1.0);
        let h = sphere(n, l);
        let mut c = PlasticContact::new(free(n, l), &h, None, 0.05).unwrap();
        let top = c.step(Load::Force(0.004), 1e-9).unwrap();
        assert!(top.plastic_cells > 10 && top.flowed > 0, "{top:?}");
        let off = c.step(Load::Force(0.0), 1e-9).unwrap();
        assert!(off.force == 0.0 && off.plastic_depth > 0.0);
        assert!((off.plastic_depth - top.plastic_depth).abs() < 1e-15);
        // The imprint: the approach of first contact is now deeper than the apex.
        assert!(off.approach > 0.0, "{off:?}");
        let half = c.step(Load::Force(0.002), 1e-9).unwrap();
        assert_eq!(half.flowed, 0, "{half:?}");
        let again = c.step(Load::Force(0.004), 1e-9).unwrap();
        assert!(again.flowed < top.plastic_cells / 10, "{again:?}");
        assert!(
            (again.approach - top.approach).abs() < 1e-6 * top.approach,
            "{} against {}",
            again.approach,
            top.approach
        );
        let beyond = c.step(Load::Force(0.006), 1e-9).unwrap();
        assert!(beyond.flowed > 0 && beyond.plastic_depth > top.plastic_depth);
    }

    /// A periodic rough surface: pressures within [0, H], the force held, H = infinity
    /// the elastic contact at the same mean gap.
    #[test]
    fn a_periodic_rough_surface_saturates_below_the_hardness() {
        let n = 32;
        let h = crate::testing::on_unit_cell(n, |x, y| {
            0.01 * (2.0 * PI * x).cos() * (2.0 * PI * y).cos()
                + 0.003 * (6.0 * PI * x + 1.0).sin() * (4.0 * PI * y).cos()
        });
        let op = || crate::PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        let mut c = PlasticContact::new(op(), &h, None, 0.02).unwrap();
        let s = c.step(Load::MeanPressure(0.005), 1e-9).unwrap();
        assert!((s.force - 0.005).abs() <= 1e-9 * 0.005, "{s:?}");
        assert!(s.plastic_cells > 0 && s.plastic_cells < s.contact_cells);
        assert!(c.pressure().iter().all(|&p| (0.0..=0.02).contains(&p)));
        let mut e = PlasticContact::new(op(), &h, None, f64::INFINITY).unwrap();
        let s = e.step(Load::Approach(0.01), 1e-10).unwrap();
        crate::adhesion::is_the_normal_solve(
            op(),
            &h,
            0.01,
            e.pressure(),
            s.force,
            s.contact_cells,
        );
    }

    #[test]
    fn bad_input_names_the_parameter() {
        let h = sphere(16, 1.0);
        for hardness in [0.0, -1.0, f64::NAN] {
            let e = PlasticContact::new(free(16, 1.0), &h, None, hardness)
                .err()
                .unwrap()
                .to_string();
            assert!(e.contains("hardness"), "{e}");
        }
        let mut c = PlasticContact::new(free(16, 1.0), &h, None, 0.1).unwrap();
        let limit = c.force_limit();
        for (load, needle) in [
            (Load::Force(limit), "H x domain area"),
            (Load::Force(-1.0), "force -1"),
            (Load::Approach(f64::NAN), "approach"),
        ] {
            let e = c.step(load, 1e-8).unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        }
        let e = c.step(Load::Force(0.001), 0.5).unwrap_err().to_string();
        assert!(e.contains("tolerance"), "{e}");
    }
}
