//! The 3D contact with both motions free ([`ObliqueBem3d`]): a body that touches the
//! free half-space, is pressed and moved along x by the integrator, and separates;
//! the normal force and the tangential force both follow the motion (an oblique
//! impact; an oscillating normal force with a tangential one, Section 7's case).
//!
//! **Model.** Each trial solves the normal contact at the step's approach (warm-started
//! from the accepted solution), then presses the partial-slip solver with that pressure
//! (`bem3d::tangential::ViscoelasticSlip::press`: the slip carried over, a cell that
//! enters contact sticking where it is) and prescribes the body's tangential
//! displacement since first contact, with Coulomb's law cell by cell. This is the
//! uncoupled model of `bem3d::tangential` step by step: exact for nu = 0.5 or
//! elastically similar bodies; MRD's springs (`crate::law::Springs::with_friction`) are
//! its 1D counterpart, exact for bodies of revolution.
//!
//! **Contacts.** The law starts apart; the first trial with a cell in contact starts
//! the slip solver (the tangential displacement of that moment is its origin). When no
//! cell is in contact any more the forces are zero, and the half-space carries no
//! traction and no displacement (a quasi-static elastic body keeps no memory of the
//! contact); the half-space is flat, so a contact that forms again anywhere along x is
//! a first contact again: a new slip solver, its origin the tangential displacement of
//! that moment. MRD's springs do the same spring by spring (a spring that touches again
//! sticks where it is).
//!
//! **Trial and commit.** The slip solver's trial is taken back bit for bit by its
//! snapshot (`crate::held`); the normal solution of a trial replaces the accepted one
//! on commit only.

use crate::held::Held;
use crate::law::{approach_of, check_motion, ContactLaw, Forces, Motion};
use crate::slip::{free_normal, shear_body};
use crate::{bad, Result};
use bem3d::tangential::{CerrutiFree, ViscoelasticSlip};
use bem3d::viscoelastic::Relaxation;
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, Solution, SolverOptions};

/// Where the contact of an [`ObliqueBem3d`] is.
enum Phase {
    /// Apart: not yet touched, or separated after a contact.
    Apart,
    /// In contact: the accepted normal solution, the slip solver, and the tangential
    /// displacement at first contact.
    Touching {
        normal: Solution,
        slip: Box<Held<ViscoelasticSlip<CerrutiFree>>>,
        origin: f64,
    },
}

/// A trial's outcome, applied on commit.
enum Pending {
    /// The slip solver's trial (held inside it) with this normal solution.
    Touching(Solution),
    /// First contact: a new slip solver, its trial held, and its origin.
    First {
        normal: Solution,
        slip: Box<Held<ViscoelasticSlip<CerrutiFree>>>,
        origin: f64,
    },
    /// No cell in contact.
    Apart,
}

/// The 3D contact with free normal and tangential motion (module docs).
pub struct ObliqueBem3d {
    normal: ContactSolver<NonPeriodicHalfSpace>,
    options: SolverOptions,
    /// The grid, size and elastic body of the tangential operator.
    grid: (usize, usize, f64, f64),
    nu: f64,
    g: f64,
    mu: f64,
    tolerance: f64,
    phase: Phase,
    pending: Option<(Pending, Forces)>,
    committed: Forces,
    label: String,
}

impl ObliqueBem3d {
    /// A body of `heights` (`ny x nx` cells, peaks up) over `lx x ly` on the free
    /// half-space, apart (the approach measured from first contact of its highest
    /// cell), with contact moduli `e_star`, `g_star` (one elastic body under a rigid
    /// one, `bem3d::tangential::equivalent_body`) and Coulomb's `mu`; every solve to
    /// `tolerance`.
    pub fn new(
        heights: &[f64],
        (nx, ny): (usize, usize),
        (lx, ly): (f64, f64),
        (e_star, g_star): (f64, f64),
        mu: f64,
        tolerance: f64,
    ) -> Result<Self> {
        let (nu, g) = shear_body(e_star, g_star)?;
        if !(mu.is_finite() && mu > 0.0 && mu <= 1e6) {
            return bad(format!(
                "friction coefficient mu = {mu} must lie in (0, 1e6]"
            ));
        }
        let (normal, options) = free_normal(heights, (nx, ny), (lx, ly), e_star, tolerance)?;
        // The tangential operator's checks now, not at first contact.
        CerrutiFree::new(nx, ny, lx, ly, 1.0, nu)?;
        Ok(Self {
            normal,
            options,
            grid: (nx, ny, lx, ly),
            nu,
            g,
            mu,
            tolerance,
            phase: Phase::Apart,
            pending: None,
            committed: Forces::default(),
            label: format!("3D oblique contact, {nx} x {ny} cells, Coulomb mu = {mu}"),
        })
    }

    fn cell_area(&self) -> f64 {
        let (nx, ny, lx, ly) = self.grid;
        lx * ly / (nx * ny) as f64
    }

    /// The normal solution at `approach` (none below first contact or with no cell in
    /// contact), warm-started from the accepted one.
    fn press(&mut self, approach: f64) -> Result<Option<Solution>> {
        if approach <= 0.0 {
            return Ok(None);
        }
        let start = match &self.phase {
            Phase::Touching { normal, .. } => Some(normal),
            _ => None,
        };
        let sol = self
            .normal
            .solve(Load::Approach(approach), &self.options, start)?;
        Ok((sol.contact_cells > 0).then_some(sol))
    }

    /// The forces of a partial-slip step at this normal solution.
    fn forces(sol: &Solution, area: f64, step: bem3d::tangential::ViscoelasticStep) -> Forces {
        Forces {
            normal: sol.force,
            tangential: step.force,
            contact_area: sol.contact_cells as f64 * area,
            stiffness: f64::NAN,
            dissipated: step.dissipated,
            iterations: sol.iterations + step.solves,
        }
    }
}

impl ContactLaw for ObliqueBem3d {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        check_motion(motion)?;
        self.rollback();
        let sol = self.press(motion.normal)?;
        let (area, tolerance) = (self.cell_area(), self.tolerance);
        let (pending, forces) = match (sol, &mut self.phase) {
            (None, _) => (Pending::Apart, Forces::default()),
            (Some(sol), Phase::Touching { slip, origin, .. }) => {
                let shift = motion.tangential - *origin;
                let forces = slip.trial(|c| {
                    c.press(&sol.pressure)?;
                    let step = c.step(motion.dt, shift, tolerance)?;
                    Ok(Self::forces(&sol, area, step))
                })?;
                (Pending::Touching(sol), forces)
            }
            (Some(sol), Phase::Apart) => {
                let (nx, ny, lx, ly) = self.grid;
                let shear = CerrutiFree::new(nx, ny, lx, ly, 1.0, self.nu)?;
                let c = ViscoelasticSlip::new(
                    shear,
                    &sol.pressure,
                    self.mu,
                    Relaxation::new(self.g, vec![])?,
                )?;
                let mut slip = Box::new(Held::new(c, Forces::default()));
                // The first contact's step: no shift yet, so no tangential force.
                let forces = slip.trial(|c| {
                    let step = c.step(motion.dt, 0.0, tolerance)?;
                    Ok(Self::forces(&sol, area, step))
                })?;
                let first = Pending::First {
                    normal: sol,
                    slip,
                    origin: motion.tangential,
                };
                (first, forces)
            }
        };
        self.pending = Some((pending, forces));
        Ok(forces)
    }

    fn commit(&mut self) -> Result<()> {
        let Some((pending, forces)) = self.pending.take() else {
            return bad("commit: no trial step to accept (call trial first)");
        };
        match pending {
            Pending::Apart => self.phase = Phase::Apart,
            Pending::Touching(sol) => {
                if let Phase::Touching { normal, slip, .. } = &mut self.phase {
                    slip.commit()?;
                    *normal = sol;
                }
            }
            Pending::First {
                normal,
                mut slip,
                origin,
            } => {
                slip.commit()?;
                self.phase = Phase::Touching {
                    normal,
                    slip,
                    origin,
                };
            }
        }
        self.committed = forces;
        Ok(())
    }

    fn rollback(&mut self) {
        if let Some((Pending::Touching(_), _)) = &self.pending {
            if let Phase::Touching { slip, .. } = &mut self.phase {
                slip.rollback();
            }
        }
        self.pending = None;
    }

    fn committed(&self) -> Forces {
        self.committed
    }

    /// The approach of a normal force (a frictionless query: the normal solve alone).
    fn approach_at(&mut self, force: f64) -> Result<f64> {
        approach_of(&mut self.normal, &self.options, None, force)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}

#[cfg(test)]
mod tests {

    use super::*;
    use crate::integrate::{Planar, PlanarSample};
    use crate::law::Springs;
    use mrd::profile::{Profile, Shape};
    use mrd::reference::hertz_impact;

    /// A rigid sphere (R = E* = 1, m = 1e-3, normal speed 0.05) striking the half-space
    /// with tangential speed `ratio x mu x` the normal one, translating only: the exit
    /// velocities (normal, tangential) and the slip energy, by `law`.
    fn impact(law: &mut dyn ContactLaw, ratio: f64, mu: f64, steps: f64) -> ([f64; 2], f64) {
        let (e, r, m, v) = (1.0, 1.0, 1e-3, 0.05);
        let tc = hertz_impact::duration(e, r, m, v);
        let dmax = hertz_impact::max_approach(e, r, m, v);
        let planar = Planar {
            mass: [m, m],
            dt: tc / steps,
            dt_min: tc / (1e3 * steps),
            max_jump: 0.05,
            force_scale: hertz_impact::max_force(e, r, m, v),
        };
        let x0 = -1e-3 * dmax;
        let apart = |s: &PlanarSample| s.x[0] < x0 && s.v[0] < 0.0;
        let (samples, _) = planar
            .run(law, ([x0, 0.0], [v, ratio * mu * v]), &apart, 2.0 * tc)
            .unwrap();
        let last = samples.last().unwrap();
        let w = samples.iter().map(|s| s.forces.dissipated).sum();
        ([-last.v[0] / v, last.v[1] / (ratio * mu * v)], w)
    }

    fn springs(g_star: f64, mu: f64) -> Springs {
        let dmax = hertz_impact::max_approach(1.0, 1.0, 1e-3, 0.05);
        let profile = Profile::single(Shape::paraboloid(1.0).unwrap());
        Springs::body(&profile, 1.0, 4000, 1.5 * dmax.sqrt())
            .unwrap()
            .with_friction(g_star, mu)
            .unwrap()
    }

    fn three(n: usize, g_star: f64, mu: f64) -> ObliqueBem3d {
        let a = hertz_impact::max_approach(1.0, 1.0, 1e-3, 0.05).sqrt();
        let side = 2.5 * a;
        let h = side / n as f64;
        let heights: Vec<f64> = (0..n * n)
            .map(|k| {
                let (x, y) = (
                    ((k % n) as f64 + 0.5) * h - side / 2.0,
                    ((k / n) as f64 + 0.5) * h - side / 2.0,
                );
                -(x * x + y * y) / 2.0
            })
            .collect();
        ObliqueBem3d::new(&heights, (n, n), (side, side), (1.0, g_star), mu, 1e-9).unwrap()
    }

    /// Closed forms of the translating sphere (no rotation), by MRD (4000 springs,
    /// t_c / 2000) and in 3D (32^2 cells over 2.5 contact radii, t_c / 400):
    /// - nu = 0 (G* = E*: the tangential springs as stiff as the normal ones) and a
    ///   tangential speed below mu times the normal one: the tangential motion is the
    ///   normal one scaled, `Q = (v_t / v_n) F` never reaches `mu F`, nothing slips and
    ///   the tangential speed reverses, `v_t' = -v_t`;
    /// - sliding throughout (tangential speed 4 and 10 mu the normal one):
    ///   `v_t' = v_t - 2 mu v_n` (the impulse `mu` times the normal one, `2 m v_n`);
    /// - the normal restitution 1.
    ///
    /// Each within 1e-5 (measured at most 8.2e-7 by MRD, 1.7e-6 in 3D; the normal 1.8e-7).
    #[test]
    fn a_translating_sphere_meets_the_closed_forms() {
        let mu = 0.3;
        for (ratio, g_star, want) in [(0.5, 1.0, -1.0), (4.0, 1.4 / 1.7, 0.5), (10.0, 1.0, 0.8)] {
            let (m, _) = impact(&mut springs(g_star, mu), ratio, mu, 2000.0);
            let (t, _) = impact(&mut three(32, g_star, mu), ratio, mu, 400.0);
            for (who, got) in [("MRD", m), ("3D", t)] {
                assert!((got[0] - 1.0).abs() < 1e-5, "{who} normal {got:?}");
                assert!((got[1] - want).abs() < 1e-5, "{who} ratio {ratio}: {got:?}");
            }
        }
    }

    /// Where stick and slip share the impact (nu = 0.3, tangential speed 0.5 and 1 mu
    /// the normal one: the tangential springs softer than the normal ones, the
    /// tangential force overtakes `mu F` as the contact shrinks), the 3D contact's
    /// tangential rebound follows MRD's springs within 3e-3 of the incoming speed
    /// (measured 1.2e-3 and 7.2e-4) and its slip energy within 10 % (measured 5.1 % and
    /// 1.1 %).
    #[test]
    fn the_3d_rebound_follows_mrd_where_stick_and_slip_share_the_impact() {
        let (mu, g_star) = (0.3, 1.4 / 1.7);
        for ratio in [0.5, 1.0] {
            let (m, wm) = impact(&mut springs(g_star, mu), ratio, mu, 2000.0);
            let (t, wt) = impact(&mut three(32, g_star, mu), ratio, mu, 400.0);
            assert!(
                (t[1] - m[1]).abs() < 3e-3,
                "ratio {ratio}: 3D {t:?} MRD {m:?}"
            );
            assert!(
                (wt / wm - 1.0).abs() < 0.1,
                "ratio {ratio}: slip energy {wt} {wm}"
            );
        }
    }

    /// Section 7 with the normal force oscillating too: a sphere pressed to `d0` (from
    /// apart, in 20 steps), then moved along `d0 (1 + 0.2 sin)` and `u1 sin` in phase
    /// (u1 twice and half the shift at which a stuck contact would carry `mu P`), 40
    /// steps a cycle, three cycles, 48^2 cells over 2.5 contact radii: the 3D slip
    /// energy of the last cycle within 5 % of MRD's (measured 4.0e-4 and 3.3 %: the
    /// smaller loop dissipates 1/160 of the larger's), the tangential force within 5e-3
    /// of `mu P` at every step (measured 3.1e-3 and 1.5e-3). At a quarter of that shift
    /// the contact shakes down: MRD's springs slip no more in the last cycle, the 3D
    /// contact's slip energy falls to 1.1e-3 of the half amplitude's loop (the cells at
    /// the edge of a moving contact).
    #[test]
    fn oscillating_normal_and_tangential_motion_follow_mrd() {
        let (mu, g_star) = (0.3, 1.4 / 1.7);
        let d0 = 0.5 * hertz_impact::max_approach(1.0, 1.0, 1e-3, 0.05);
        // Full stick from a pressed contact: Q = 2 G* a u, so mu P is reached at
        // u = mu (4/3) a^3 / (2 G* a) = (2/3) mu d0 E* / G*.
        let u_slip = 2.0 / 3.0 * mu * d0 / g_star;
        let mut loops = vec![];
        for amplitude in [2.0 * u_slip, 0.5 * u_slip, 0.25 * u_slip] {
            let mut path = vec![];
            for k in 1..=20 {
                path.push((d0 * k as f64 / 20.0, 0.0));
            }
            for k in 1..=120 {
                let phase = (2.0 * std::f64::consts::PI * k as f64 / 40.0).sin();
                path.push((d0 * (1.0 + 0.2 * phase), amplitude * phase));
            }
            let (mut springs, mut three) = (springs(g_star, mu), three(48, g_star, mu));
            let (mut wm, mut w3, mut worst) = (0.0, 0.0, 0.0f64);
            for (k, (d, u)) in path.iter().enumerate() {
                let m = Motion {
                    normal: *d,
                    tangential: *u,
                    dt: 1.0,
                };
                let fm = springs.trial(m).unwrap();
                springs.commit().unwrap();
                let f3 = three.trial(m).unwrap();
                three.commit().unwrap();
                worst = worst.max((f3.tangential - fm.tangential).abs() / (mu * fm.normal));
                if k >= 100 {
                    wm += fm.dissipated;
                    w3 += f3.dissipated;
                }
            }
            assert!(worst < 5e-3, "{amplitude}: force off by {worst} of mu P");
            loops.push((wm, w3));
        }
        for (wm, w3) in &loops[..2] {
            assert!(
                (w3 / wm - 1.0).abs() < 0.05,
                "slip energy {w3} against {wm}"
            );
        }
        // Shakedown at the smallest amplitude: no slip left in MRD's last cycle, and the
        // 3D one's under 1 % of the next amplitude's loop.
        let ((wm, w3), (_, w_half)) = (loops[2], loops[1]);
        assert_eq!(wm, 0.0);
        assert!(w3 < 1e-2 * w_half, "3D slip energy {w3} against {w_half}");
    }

    /// A rejected trial leaves no trace (the trial after it is bit for bit the one
    /// without it); a contact that forms again after separating is a first contact
    /// again: the same motion from the new origin gives the same bits.
    #[test]
    fn a_rollback_replays_and_a_contact_forms_again() {
        let mut law = three(16, 1.0, 0.3);
        let d = 1e-3;
        // A tangential step that is exact in binary from either origin below.
        let du = 2f64.powi(-13);
        let at = |normal: f64, tangential: f64| Motion {
            normal,
            tangential,
            dt: 1.0,
        };
        let touch = law.trial(at(d, 0.0)).unwrap();
        law.commit().unwrap();
        let pressed = law.trial(at(1.5 * d, du)).unwrap();
        law.commit().unwrap();
        let first = law.trial(at(1.2 * d, 2.0 * du)).unwrap();
        law.rollback();
        law.trial(at(2.0 * d, -3.0 * du)).unwrap();
        let again = law.trial(at(1.2 * d, 2.0 * du)).unwrap();
        assert_eq!(again.tangential.to_bits(), first.tangential.to_bits());
        assert_eq!(again.normal.to_bits(), first.normal.to_bits());
        law.commit().unwrap();
        let apart = law.trial(at(-d, 2.0 * du)).unwrap();
        assert_eq!((apart.normal, apart.tangential), (0.0, 0.0));
        law.commit().unwrap();
        // In contact again at x = 0.25: the first two steps once more.
        let bits = |f: Forces| [f.normal, f.tangential, f.contact_area].map(f64::to_bits);
        let retouch = law.trial(at(d, 0.25)).unwrap();
        law.commit().unwrap();
        let repressed = law.trial(at(1.5 * d, 0.25 + du)).unwrap();
        law.commit().unwrap();
        assert_eq!(bits(retouch), bits(touch));
        assert_eq!(bits(repressed), bits(pressed));
        assert!(pressed.tangential > 0.0);
    }

    /// One contact's tangential forces step by step and its slip energy, by MRD and in 3D.
    type Contact = [(Vec<f64>, f64); 2];

    /// A sphere in and out of contact while it drifts along x (Section 7's fretting
    /// with separation), `nc` steps a cycle: the normal approach
    /// `d0 sin(2 pi (k - 1/2) / nc)` (apart on the negative half), the tangential
    /// displacement `6 u_s k / nc` (u_s the shift at which a stuck contact carries
    /// `mu P` at d0), each contact sticking first and sliding at its end; 32^2 cells
    /// over 2.5 contact radii at d0. Returns the largest difference of the tangential
    /// forces (3D less MRD) over `mu P(d0)`, and per contact, by MRD and in 3D, the
    /// tangential forces of its steps and its slip energy.
    fn fretting(nc: usize, contacts: usize) -> (f64, Vec<Contact>) {
        let (mu, g_star) = (0.3, 1.4 / 1.7);
        let d0 = 0.5 * hertz_impact::max_approach(1.0, 1.0, 1e-3, 0.05);
        let u_slip = 2.0 / 3.0 * mu * d0 / g_star;
        let mu_p0 = mu * 4.0 / 3.0 * d0.powf(1.5);
        let (mut springs, mut three) = (springs(g_star, mu), three(32, g_star, mu));
        let mut out: Vec<Contact> = vec![];
        let mut worst = 0.0f64;
        for k in 1..=contacts * nc {
            let phase = ((k % nc) as f64 - 0.5) / nc as f64;
            let m = Motion {
                normal: d0 * (2.0 * std::f64::consts::PI * phase).sin(),
                tangential: 6.0 * u_slip * k as f64 / nc as f64,
                dt: 1.0,
            };
            let fm = springs.trial(m).unwrap();
            springs.commit().unwrap();
            let f3 = three.trial(m).unwrap();
            three.commit().unwrap();
            if k % nc == 1 {
                out.push(Default::default());
            }
            if (1..=nc / 2).contains(&(k % nc)) {
                let c = out.last_mut().unwrap();
                for (side, f) in c.iter_mut().zip([fm, f3]) {
                    side.0.push(f.tangential);
                    side.1 += f.dissipated;
                }
                worst = worst.max((f3.tangential - fm.tangential).abs() / mu_p0);
            } else {
                assert_eq!(
                    (fm.normal, f3.normal, f3.tangential),
                    (0.0, 0.0, 0.0),
                    "{k}"
                );
            }
        }
        for c in &out {
            let again = c.iter().zip(&out[0]);
            for ((q, _), (q0, _)) in again {
                let off = q.iter().zip(q0).map(|(a, b)| (a - b).abs());
                let off = off.fold(0.0, f64::max);
                assert!(off < 1e-9 * mu_p0, "a contact again: {off}");
            }
        }
        (worst, out)
    }

    /// Contacts that form again after separating ([`fretting`]):
    /// - each is the first one again: the second's and third's tangential forces equal
    ///   the first's within 1e-9 of `mu P(d0)`, in 3D and by MRD (the same motion from a
    ///   new origin; they differ by the rounding of the shift);
    /// - the 3D tangential force follows MRD's within 8 % of `mu P(d0)` at 40 steps a
    ///   cycle (measured 6.3 %) and the difference falls with the step, below 0.75 of it
    ///   at 80 (measured 3.9 %, then 2.1 % at 160): first order, a cell entering contact
    ///   anchored at the step's start in 3D, a spring at its end by MRD; each contact's
    ///   slip energy within 8 % and 5 % (measured 5.2 % and 3.3 %).
    #[test]
    fn contacts_that_form_again_follow_mrd() {
        let (coarse, contacts) = fretting(40, 3);
        let (fine, once) = fretting(80, 1);
        assert!(coarse < 0.08, "3D force off MRD's by {coarse} of mu P");
        assert!(fine < 0.75 * coarse, "{fine} against {coarse}");
        for (c, tolerance) in contacts.iter().map(|c| (c, 0.08)).chain([(&once[0], 0.05)]) {
            let [(_, wm), (_, w3)] = c;
            assert!(*wm > 0.0);
            assert!(
                (w3 / wm - 1.0).abs() < tolerance,
                "slip energy {w3} against {wm}"
            );
        }
    }

    /// A mass ringing down on the sphere's tangential springs while the normal approach
    /// oscillates (`d0 (1 + b sin(omega t))`, `omega` over the tangential stiffness'
    /// natural frequency `ratio`; `Axis::Tangential` where `wave` is false), by `law`:
    /// pressed at t = 0, loaded quasi-statically to `u0` (50 steps), released at rest,
    /// `periods` periods of the initial tangential stiffness at `steps` each.
    fn ring_wave(
        law: &mut dyn ContactLaw,
        (wave, b, ratio): (bool, f64, f64),
        u0: f64,
        (periods, steps): (usize, usize),
    ) -> Vec<crate::integrate::Sample> {
        use crate::integrate::{Axis, Oscillator, Stop};
        let (mu, g_star, m) = (0.3, 1.4 / 1.7, 1e-3);
        let d0 = 0.5 * hertz_impact::max_approach(1.0, 1.0, 1e-3, 0.05);
        let omega_t = (2.0 * g_star * d0.sqrt() / m).sqrt();
        let period = 2.0 * std::f64::consts::PI / omega_t;
        for k in 0..=50 {
            law.trial(Motion {
                normal: d0,
                tangential: u0 * k as f64 / 50.0,
                dt: 1.0,
            })
            .unwrap();
            law.commit().unwrap();
        }
        let drive = |_t: f64| 0.0;
        let axis = if wave {
            Axis::TangentialWave {
                approach: d0,
                amplitude: b,
                omega: ratio * omega_t,
                phase: 0.0,
            }
        } else {
            Axis::Tangential { approach: d0 }
        };
        let osc = Oscillator {
            mass: m,
            damping: 0.0,
            drive: &drive,
            axis,
            dt: period / steps as f64,
            dt_min: period / (100.0 * steps as f64),
            max_jump: 0.05,
            force_scale: mu * 4.0 / 3.0 * d0.powf(1.5),
        };
        let end = Stop::At(periods as f64 * period);
        osc.run(law, (u0, 0.0), end, 1).unwrap().0
    }

    /// Frictional damping in time with the normal force oscillating too (Section 7's
    /// case, integrated): a mass released at half the stick range `u_s` rings down for
    /// four periods (100 steps each) while the approach moves along
    /// `d0 (1 + 0.2 sin(omega t))`; 32^2 cells over 2.5 contact radii.
    /// - A wave of amplitude 0 is the held approach, bit for bit (MRD).
    /// - The 3D run follows MRD's: the tangential force within 2e-2 of `mu P(d0)` at
    ///   every step (measured 7.8e-3 to 1.4e-2; 9.4e-3 at the held approach), the slip
    ///   energy within 8 % (measured 0.1 % to 6.1 %, the largest where the loss is
    ///   smallest) and the last period's amplitude within 2 % (measured 0.8 % at most).
    /// - How the normal motion's frequency sets the damping, by both methods: at twice
    ///   the ring-down's frequency (the approach at its mean at each turning point,
    ///   highest an eighth of a period after it) the loss falls below 0.6 of the held
    ///   approach's (measured 0.50 MRD, 0.47 3D); at the same frequency (the approach
    ///   highest as the mass passes the middle one way, lowest as it passes back) it
    ///   rises above 1.15 of it (measured 1.27).
    ///
    /// Refined (measured, not run here): at 400 and 1600 steps a period the ratios move
    /// to 0.54 / 0.56 and 1.30 / 1.31 (MRD; 3D alike), first order in the step; the 3D
    /// run stays within 1.3 % of mu P in force, 3.9 % in slip energy and 0.7 % in
    /// amplitude of MRD's at every step; on 64^2 cells at 100 steps the 3D energies come
    /// within 3.8 % (from 6.1 %) and the forces within 1.2 % (from 1.4 %).
    #[test]
    fn ring_down_under_a_normal_wave_follows_mrd() {
        let (mu, g_star) = (0.3, 1.4 / 1.7);
        let d0 = 0.5 * hertz_impact::max_approach(1.0, 1.0, 1e-3, 0.05);
        let u0 = 0.5 * 2.0 / 3.0 * mu * d0 / g_star;
        let mu_p0 = mu * 4.0 / 3.0 * d0.powf(1.5);
        let run = |wave, b, ratio, three_d: bool| {
            if three_d {
                ring_wave(&mut three(32, g_star, mu), (wave, b, ratio), u0, (4, 100))
            } else {
                ring_wave(&mut springs(g_star, mu), (wave, b, ratio), u0, (4, 100))
            }
        };
        let loss = |s: &[crate::integrate::Sample]| s.iter().map(|s| s.dissipated).sum::<f64>();
        let held = run(false, 0.0, 1.0, false);
        let flat = run(true, 0.0, 1.0, false);
        let bits = |s: &[crate::integrate::Sample]| -> Vec<[u64; 2]> {
            s.iter()
                .map(|s| [s.x.to_bits(), s.force.to_bits()])
                .collect()
        };
        assert_eq!(bits(&held), bits(&flat));
        let mut losses = vec![];
        for ratio in [1.0, 2.0, 0.5] {
            let (sm, s3) = (run(true, 0.2, ratio, false), run(true, 0.2, ratio, true));
            let worst = sm.iter().zip(&s3).map(|(a, c)| (a.force - c.force).abs());
            let worst = worst.fold(0.0, f64::max) / mu_p0;
            assert!(worst < 2e-2, "ratio {ratio}: force off by {worst} of mu P");
            let (wm, w3) = (loss(&sm), loss(&s3));
            assert!(
                (w3 / wm - 1.0).abs() < 0.08,
                "ratio {ratio}: loss {w3} against {wm}"
            );
            // The largest excursion over the last of the four periods (by time: a run
            // that halves steps has more samples).
            let last = |s: &[crate::integrate::Sample]| {
                let end = s.last().map_or(0.0, |p| p.t);
                let tail = s.iter().filter(|p| p.t >= 0.75 * end);
                tail.map(|p| p.x.abs()).fold(0.0, f64::max)
            };
            let (am, a3) = (last(&sm), last(&s3));
            assert!(
                (a3 / am - 1.0).abs() < 0.02,
                "ratio {ratio}: amplitude {a3} against {am}"
            );
            losses.push((wm, w3));
        }
        let w_held = loss(&held);
        let (wm, w3) = losses[1];
        assert!(
            wm < 0.6 * w_held && w3 < 0.6 * w_held,
            "{wm} {w3} against {w_held}"
        );
        let (wm, w3) = losses[0];
        assert!(
            wm > 1.15 * w_held && w3 > 1.15 * w_held,
            "{wm} {w3} against {w_held}"
        );
    }
}
