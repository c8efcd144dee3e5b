//! The 3D partial-slip contact as a tangential contact law ([`SlipBem3d`]): a body
//! pressed by a held normal force onto the free half-space, moved along x by the
//! integrator, with Coulomb's law cell by cell (Sections 6-7 in 3D, the reference MRD's
//! tangential springs are held against inside a time integration).
//!
//! **Model.** The normal contact is solved once, in 3D, at the held force; its pressure
//! is held (the uncoupled approximation of `bem3d::tangential`, exact for nu = 0.5 or
//! elastically similar bodies). Each trial prescribes the body's tangential displacement:
//! `bem3d::tangential::ViscoelasticSlip` with a constant shear modulus is the elastic
//! partial slip under a prescribed shift (on the free half-space one box-constrained
//! solve holding the shift; verified against the force-controlled solver, `bem3d`'s
//! tests), so the law takes the displacement an integrator gives. The free half-space
//! measures the shift absolutely, as the body's rigid displacement.
//!
//! **Trial and commit.** A trial starts from the accepted state (the slip of every
//! cell, the traction); a rejected trial is taken back by the solver's snapshot, bit for
//! bit (`crate::held`, as the other 3D laws). The normal motion must stay at the held
//! approach: the law refuses another (`crate::oblique::ObliqueBem3d` lets both motions
//! vary).

use crate::held::Held;
use crate::law::{check_motion, ContactLaw, Forces, Motion};
use crate::{bad, Result};
use bem3d::tangential::{equivalent_body, CerrutiFree, ViscoelasticSlip};
use bem3d::viscoelastic::Relaxation;
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};

/// Poisson's ratio and shear modulus of the elastic body with contact moduli `e_star`
/// and `g_star` (`bem3d::tangential::equivalent_body`), refused where no body has them.
pub(crate) fn shear_body(e_star: f64, g_star: f64) -> Result<(f64, f64)> {
    // G* / E* = 2 (1 - nu) / (2 - nu) lies in [2/3, 1] for nu in [0, 0.5].
    let ratio = g_star / e_star;
    if !(e_star.is_finite() && e_star > 0.0 && (2.0 / 3.0..=1.0).contains(&ratio)) {
        return bad(format!(
            "e_star = {e_star}, g_star = {g_star}: give E* > 0 and G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5])"
        ));
    }
    Ok(equivalent_body(e_star, g_star))
}

/// The normal contact of `heights` (`ny x nx` over `lx x ly`) on the free half-space of
/// modulus `e_star`, and its solves' options (`tolerance`, an iteration cap growing with
/// the grid): the normal side of the 3D tangential laws.
pub(crate) fn free_normal(
    heights: &[f64],
    (nx, ny): (usize, usize),
    (lx, ly): (f64, f64),
    e_star: f64,
    tolerance: f64,
) -> Result<(ContactSolver<NonPeriodicHalfSpace>, SolverOptions)> {
    let options = SolverOptions::new(tolerance, 20 * nx.max(ny) + 2000);
    options.validate()?;
    let op = NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?;
    Ok((ContactSolver::new(op, heights, None)?, options))
}

/// The 3D partial-slip law at a held normal force (module docs).
pub struct SlipBem3d {
    slip: Held<ViscoelasticSlip<CerrutiFree>>,
    /// The approach that carries the held normal force [length].
    approach: f64,
    normal: f64,
    contact_area: f64,
    tolerance: f64,
    label: String,
}

impl SlipBem3d {
    /// A body of `heights` (`ny x nx` cells, peaks up) over `lx x ly` on the free
    /// half-space, pressed by `normal_force`, with contact moduli `e_star` and `g_star`
    /// (one elastic body under a rigid one: its shear modulus and Poisson's ratio,
    /// `bem3d::tangential::equivalent_body`, take the tangential problem) and Coulomb's
    /// `mu`; every solve to `tolerance`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        heights: &[f64],
        (nx, ny): (usize, usize),
        (lx, ly): (f64, f64),
        (e_star, g_star): (f64, f64),
        mu: f64,
        normal_force: f64,
        tolerance: f64,
    ) -> Result<Self> {
        if !(normal_force.is_finite() && normal_force > 0.0) {
            return bad(format!(
                "normal_force = {normal_force} must be finite and > 0 (the law holds a pressed contact)"
            ));
        }
        let (nu, g) = shear_body(e_star, g_star)?;
        let (mut normal, options) = free_normal(heights, (nx, ny), (lx, ly), e_star, tolerance)?;
        let sol = normal.solve(Load::Force(normal_force), &options, None)?;
        let cell = lx * ly / (nx * ny) as f64;
        let shear = CerrutiFree::new(nx, ny, lx, ly, 1.0, nu)?;
        let slip = ViscoelasticSlip::new(shear, &sol.pressure, mu, Relaxation::new(g, vec![])?)?;
        let contact_area = sol.contact_cells as f64 * cell;
        let accepted = Forces {
            normal: sol.force,
            contact_area,
            ..Forces::default()
        };
        Ok(Self {
            slip: Held::new(slip, accepted),
            approach: sol.approach,
            normal: sol.force,
            contact_area,
            tolerance,
            label: format!("3D partial slip, {nx} x {ny} cells, Coulomb mu = {mu}"),
        })
    }

    /// The approach of the held normal force (from first contact of the highest cell).
    pub fn approach(&self) -> f64 {
        self.approach
    }
}

impl ContactLaw for SlipBem3d {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        check_motion(motion)?;
        if (motion.normal - self.approach).abs() > 1e-9 * self.approach.abs() {
            return bad(format!(
                "normal = {}: the 3D partial-slip law holds the approach {} of its normal force (module docs)",
                motion.normal, self.approach
            ));
        }
        let (normal, area, tolerance) = (self.normal, self.contact_area, self.tolerance);
        self.slip.trial(|c| {
            let step = c.step(motion.dt, motion.tangential, tolerance)?;
            Ok(Forces {
                normal,
                tangential: step.force,
                contact_area: area,
                stiffness: f64::NAN,
                dissipated: step.dissipated,
                iterations: step.solves,
            })
        })
    }

    fn commit(&mut self) -> Result<()> {
        self.slip.commit()
    }

    fn rollback(&mut self) {
        self.slip.rollback()
    }

    fn committed(&self) -> Forces {
        self.slip.committed()
    }

    /// The held approach, for the held normal force only.
    fn approach_at(&mut self, force: f64) -> Result<f64> {
        if (force - self.normal).abs() > 1e-9 * self.normal {
            return bad(format!(
                "approach_at(force = {force}): the 3D partial-slip law holds the normal force {}",
                self.normal
            ));
        }
        Ok(self.approach)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::Springs;
    use mrd::profile::{Profile, Shape};

    /// A sphere (E* = R = 1, nu = 0.3, mu = 0.3) pressed by 1e-3 on `n^2` cells over
    /// 2.5 Hertz contact radii, and MRD's exact springs on the same body.
    fn pair(n: usize) -> (SlipBem3d, Springs, f64) {
        let (e, r, nu, mu, f): (f64, f64, f64, f64, f64) = (1.0, 1.0, 0.3, 0.3, 1e-3);
        let g = e * (1.0 - nu) / 2.0;
        let g_star = 4.0 * g / (2.0 - nu);
        let a = (3.0 * f * r / (4.0 * e)).cbrt();
        let side = 2.5 * a;
        let h = side / n as f64;
        let heights: Vec<f64> = (0..n * n)
            .map(|k| {
                let (x, y) = (
                    ((k % n) as f64 + 0.5) * h - side / 2.0,
                    ((k / n) as f64 + 0.5) * h - side / 2.0,
                );
                -(x * x + y * y) / (2.0 * r)
            })
            .collect();
        let three =
            SlipBem3d::new(&heights, (n, n), (side, side), (e, g_star), mu, f, 1e-10).unwrap();
        let profile = Profile::single(Shape::paraboloid(r).unwrap());
        let springs = Springs::body(&profile, e, 4000, 1.5 * a)
            .unwrap()
            .with_friction(g_star, mu)
            .unwrap();
        (three, springs, mu * f)
    }

    /// Along a displacement history (a virgin loading to 0.6 mu P's shift, back to its
    /// negative, forward again), the 3D law's force follows MRD's springs (Cattaneo-
    /// Mindlin and Mindlin-Deresiewicz, exact for the sphere) within 1e-3 of mu P at
    /// 25.6 cells per contact radius (measured 8.5e-5), the slip energy of the loop (its
    /// last 80 steps) within 1e-3 (measured 7.7e-7); each at its own approach of the
    /// normal force.
    #[test]
    fn the_3d_law_follows_mrd_springs_through_a_loop() {
        let (mut three, mut springs, limit) = pair(64);
        let d3 = three.approach_at(1e-3).unwrap();
        let dm = springs.approach_at(1e-3).unwrap();
        // The shift of 0.6 mu P (Cattaneo-Mindlin: 3 mu P / (4 G* a) (1 - (1 - x)^(2/3))).
        let (g_star, a) = (4.0 * 0.35 / 1.7, (0.75e-3f64).cbrt());
        let top = 3.0 * limit / (4.0 * g_star * a) * (1.0 - 0.4f64.powf(2.0 / 3.0));
        // The springs touch at no shift (a spring anchors where it first touches).
        springs
            .trial(Motion {
                normal: dm,
                tangential: 0.0,
                dt: 1.0,
            })
            .unwrap();
        springs.commit().unwrap();
        let path: Vec<f64> = (1..=20)
            .map(|k| top * k as f64 / 20.0)
            .chain((1..=40).map(|k| top * (1.0 - k as f64 / 20.0)))
            .chain((1..=40).map(|k| top * (-1.0 + k as f64 / 20.0)))
            .collect();
        let (mut worst, mut w3, mut wm) = (0.0f64, 0.0, 0.0);
        for (k, u) in path.iter().enumerate() {
            let f3 = three
                .trial(Motion {
                    normal: d3,
                    tangential: *u,
                    dt: 1.0,
                })
                .unwrap();
            three.commit().unwrap();
            let fm = springs
                .trial(Motion {
                    normal: dm,
                    tangential: *u,
                    dt: 1.0,
                })
                .unwrap();
            springs.commit().unwrap();
            worst = worst.max((f3.tangential - fm.tangential).abs() / limit);
            if (20..100).contains(&k) {
                w3 += f3.dissipated;
                wm += fm.dissipated;
            }
        }
        assert!(worst < 1e-3, "force off by {worst} of mu P");
        assert!(
            (w3 / wm - 1.0).abs() < 1e-3,
            "loop energy {w3} against {wm}"
        );
    }

    /// A rejected trial leaves no trace (the next trial is the one that would have
    /// followed the commit, bit for bit); another normal motion or force is refused.
    #[test]
    fn a_rollback_replays_and_the_normal_is_held() {
        let (mut three, _, _) = pair(24);
        let d = three.approach();
        let at = |u: f64| Motion {
            normal: d,
            tangential: u,
            dt: 1.0,
        };
        three.trial(at(1e-5)).unwrap();
        three.commit().unwrap();
        let first = three.trial(at(2e-5)).unwrap();
        three.rollback();
        three.trial(at(-3e-5)).unwrap();
        let again = three.trial(at(2e-5)).unwrap();
        assert_eq!(again.tangential.to_bits(), first.tangential.to_bits());
        assert_eq!(again.dissipated.to_bits(), first.dissipated.to_bits());
        assert_eq!(again.iterations, first.iterations);
        let e = three
            .trial(Motion {
                normal: 1.1 * d,
                tangential: 0.0,
                dt: 1.0,
            })
            .unwrap_err()
            .to_string();
        assert!(e.contains("normal = "), "{e}");
        assert!(three.approach_at(2e-3).is_err());
    }
}
