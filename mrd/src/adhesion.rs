//! Adhesive normal contact by the rule of Hess (Eq. 33).
//!
//! Pressed into the foundation, springs attach when they touch; pulled back, the
//! boundary springs detach once their elongation reaches the non-local critical value
//! `dl_max(a) = sqrt(2 pi a gamma / E*)` (Eq. 33), gamma being the work of adhesion.
//! On the adhesive (unloading) branch, at contact radius a:
//!
//! * depth `d(a) = z1d(a) - dl_max(a)` (Eq. 35 generalised),
//! * force `F(a) = F_0(a) - 2 a E* dl_max(a)` (Eq. 36 generalised), F_0 the
//!   non-adhesive force at the same radius.
//!
//! Under force control the contact is stable while dF/da > 0; pull-off occurs where
//! `a z1d'(a) = 3/2 dl_max(a)`. Under displacement control it is stable while
//! dd/da > 0; separation occurs where `a z1d'(a) = dl_max(a)/2`. A punch held at its
//! rim radius detaches at once everywhere (Eq. 34).
//!
//! The loading branch of the spring model is non-adhesive (springs attach only on
//! touching); the loop between the two branches is the adhesive hysteresis.

use crate::error::{positive, MrdError, Result};
use crate::normal::AxisymmetricContact;
use crate::numerics::roots::brent;
use std::f64::consts::PI;

/// Which quantity the machine controls while pulling off.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    Force,
    Displacement,
}

/// Point of instability (pull-off) on the adhesive branch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOff {
    pub radius: f64,
    pub depth: f64,
    /// Force at the instant of separation (negative: tensile).
    pub force: f64,
}

#[derive(Debug, Clone)]
pub struct AdhesiveContact {
    pub contact: AxisymmetricContact,
    /// Work of adhesion gamma_12 (energy per area).
    pub gamma: f64,
}

impl AdhesiveContact {
    pub fn new(contact: AxisymmetricContact, gamma: f64) -> Result<Self> {
        positive("work of adhesion", gamma)?;
        Ok(Self { contact, gamma })
    }

    /// Critical elongation of the boundary spring at contact radius a (Eq. 33).
    pub fn critical_elongation(&self, a: f64) -> f64 {
        (2.0 * PI * a * self.gamma / self.contact.e_star).sqrt() // Eq. (33)
    }

    /// Depth on the adhesive branch at radius a (Eq. 35 generalised).
    pub fn depth_at_radius(&self, a: f64) -> Result<f64> {
        Ok(self.contact.depth_at_radius(a)? - self.critical_elongation(a))
    }

    /// Force on the adhesive branch at radius a (Eq. 36 generalised).
    pub fn force_at_radius(&self, a: f64) -> Result<f64> {
        Ok(self.contact.force_at_radius(a)?
            - 2.0 * a * self.contact.e_star * self.critical_elongation(a))
    }

    /// Stability function: dF/da (force control) or dd/da (displacement control), up to
    /// positive factors; positive means stable.
    fn stability(&self, a: f64, control: Control) -> f64 {
        let slope = a * self.contact.profile.dz1d(a);
        let dl = self.critical_elongation(a);
        match control {
            Control::Force => slope - 1.5 * dl,
            Control::Displacement => slope - 0.5 * dl,
        }
    }

    /// Pull-off when unloading from contact radius `a_max` under `control`.
    pub fn pull_off(&self, a_max: f64, control: Control) -> Result<PullOff> {
        positive("maximal contact radius", a_max)?;
        let at = |a: f64| -> Result<PullOff> {
            Ok(PullOff {
                radius: a,
                depth: self.depth_at_radius(a)?,
                force: self.force_at_radius(a)?,
            })
        };
        let rim = self.contact.profile.rim();
        let a_top = rim.map_or(a_max, |r| a_max.min(r));
        // A punch held at its rim: the rim springs are stretched first (the radius cannot
        // grow), so the rim detaches when the adhesive branch at a = rim is reached and
        // then unstably if the branch is unstable there (flat punch, Eq. 34).
        if self.stability(a_top, control) <= 0.0 {
            return at(a_top);
        }
        // Scan down from a_top for the largest radius where stability is lost.
        let m = 4000;
        let mut hi = a_top;
        for i in (0..m).rev() {
            let lo = a_top * i as f64 / m as f64;
            let s = if lo == 0.0 {
                -1.0
            } else {
                self.stability(lo, control)
            };
            if s <= 0.0 {
                let a = brent(
                    |a| self.stability(a, control),
                    lo.max(1e-300),
                    hi,
                    1e-15 * a_top,
                )?;
                return at(a);
            }
            hi = lo;
        }
        Err(MrdError::NoConvergence {
            what: "pull-off search",
            iterations: m,
            residual: f64::NAN,
        })
    }
}

/// One recorded point of a simulated loading-unloading cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    pub depth: f64,
    pub force: f64,
    pub radius: f64,
    /// true while unloading.
    pub unloading: bool,
}

/// Result of a discrete adhesive simulation.
#[derive(Debug, Clone)]
pub struct AdhesiveCycle {
    pub curve: Vec<CurvePoint>,
    pub pull_off: PullOff,
}

/// Event-driven simulation of the spring row (half-line x > 0, mirrored): load to depth
/// `d_max` (springs attach on touching), then unload under `control` until the last
/// spring detaches. Detachment follows Eq. (33) with a = m dx for m attached springs;
/// each detachment event is computed exactly, so no load step is involved.
pub fn simulate_cycle(
    adhesive: &AdhesiveContact,
    n_half: usize,
    half_length: f64,
    d_max: f64,
    control: Control,
) -> Result<AdhesiveCycle> {
    positive("maximal depth", d_max)?;
    positive("half_length", half_length)?;
    crate::error::springs(n_half)?;
    let profile = &adhesive.contact.profile;
    let e = adhesive.contact.e_star;
    let (l, dx, gaps) = crate::foundation::half_line(profile, n_half, half_length)?;
    // Loading: springs with gap <= d attach (the profile is monotone in |x|).
    let m_max = gaps.partition_point(|&g| g <= d_max);
    if m_max == n_half && profile.rim().is_none() {
        return Err(MrdError::OutOfRange {
            needed: f64::INFINITY,
            limit: l,
        });
    }
    if m_max == 0 {
        return Err(MrdError::ImpossibleLoad(
            "maximal depth too small: no spring touches".into(),
        ));
    }
    let mut prefix = vec![0.0];
    for &g in &gaps {
        prefix.push(prefix.last().unwrap() + g);
    }
    let force = |d: f64, m: usize| 2.0 * e * dx * (m as f64 * d - prefix[m]);
    let mut curve = Vec::new();
    for m in 1..=m_max {
        // Each spring's touch-down is a vertex of the piecewise-linear loading curve.
        let d = gaps[m - 1];
        curve.push(CurvePoint {
            depth: d,
            force: force(d, m - 1),
            radius: (m - 1) as f64 * dx,
            unloading: false,
        });
    }
    curve.push(CurvePoint {
        depth: d_max,
        force: force(d_max, m_max),
        radius: m_max as f64 * dx,
        unloading: false,
    });
    // Unloading. Configuration with m attached springs loses its outer spring at
    // d_m = g_{m-1} - dl(m dx), where the force is F_m.
    let detach_depth = |m: usize| gaps[m - 1] - adhesive.critical_elongation(m as f64 * dx);
    let mut m = m_max;
    let mut level = match control {
        Control::Force => force(detach_depth(m), m),
        Control::Displacement => detach_depth(m),
    };
    loop {
        let d = detach_depth(m);
        curve.push(CurvePoint {
            depth: d,
            force: force(d, m),
            radius: m as f64 * dx,
            unloading: true,
        });
        let last = PullOff {
            radius: m as f64 * dx,
            depth: d,
            force: force(d, m),
        };
        // Detach the outer spring; the cascade continues while the next configuration is
        // already past its own detachment level at the current control level.
        m -= 1;
        if m == 0 {
            return Ok(AdhesiveCycle {
                curve,
                pull_off: last,
            });
        }
        let next = match control {
            Control::Force => force(detach_depth(m), m),
            Control::Displacement => detach_depth(m),
        };
        if next >= level {
            // Unstable: jumps straight through (the control level stays where it is).
            let mut k = m;
            while k > 0 {
                let lv = match control {
                    Control::Force => force(detach_depth(k), k),
                    Control::Displacement => detach_depth(k),
                };
                if lv < level {
                    break;
                }
                k -= 1;
            }
            if k == 0 {
                return Ok(AdhesiveCycle {
                    curve,
                    pull_off: last,
                });
            }
            m = k;
        }
        level = match control {
            Control::Force => force(detach_depth(m), m),
            Control::Displacement => detach_depth(m),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{Profile, Shape};
    use crate::reference::{adhesive_cone_pull_off, adhesive_flat_punch_pull_off, jkr};

    fn sphere(r: f64, e: f64, gamma: f64) -> AdhesiveContact {
        let c =
            AxisymmetricContact::new(Profile::single(Shape::paraboloid(r).unwrap()), e).unwrap();
        AdhesiveContact::new(c, gamma).unwrap()
    }

    #[test]
    fn jkr_branch_and_pull_off() {
        let ad = sphere(1.0, 1.0, 0.01);
        for &a in &[0.1, 0.3, 0.7] {
            assert!((ad.force_at_radius(a).unwrap() - jkr::force(1.0, 1.0, 0.01, a)).abs() < 1e-14);
            assert!((ad.depth_at_radius(a).unwrap() - jkr::depth(1.0, 1.0, 0.01, a)).abs() < 1e-14);
        }
        let f = ad.pull_off(1.0, Control::Force).unwrap();
        assert!((f.force / -jkr::pull_off_force_control(1.0, 0.01) - 1.0).abs() < 1e-9);
        let d = ad.pull_off(1.0, Control::Displacement).unwrap();
        assert!((d.force / -jkr::pull_off_displacement_control(1.0, 0.01) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn cone_and_flat_punch_pull_off() {
        let c = AxisymmetricContact::new(Profile::single(Shape::cone(0.2).unwrap()), 1.0).unwrap();
        let ad = AdhesiveContact::new(c, 1e-3).unwrap();
        let f = ad.pull_off(1.0, Control::Force).unwrap();
        assert!((f.force / -adhesive_cone_pull_off(1.0, 0.2, 1e-3) - 1.0).abs() < 1e-9); // Eq. (37)
        let c = AxisymmetricContact::new(Profile::flat_punch(0.5).unwrap(), 2.0).unwrap();
        let ad = AdhesiveContact::new(c, 0.1).unwrap();
        for control in [Control::Force, Control::Displacement] {
            let f = ad.pull_off(0.5, control).unwrap();
            assert!((f.force / -adhesive_flat_punch_pull_off(2.0, 0.5, 0.1) - 1.0).abs() < 1e-12);
            // Eq. (34)
        }
    }

    #[test]
    fn discrete_cycle_reproduces_jkr() {
        // Stated tolerance: 1e-3 relative with 20000 springs on the half-line [0, 1].
        let ad = sphere(1.0, 1.0, 0.01);
        for (control, exact) in [
            (Control::Force, jkr::pull_off_force_control(1.0, 0.01)),
            (
                Control::Displacement,
                jkr::pull_off_displacement_control(1.0, 0.01),
            ),
        ] {
            let cyc = simulate_cycle(&ad, 20_000, 1.0, 0.36, control).unwrap();
            let err = (cyc.pull_off.force / -exact - 1.0).abs();
            assert!(
                err < 1e-3,
                "{control:?}: {} vs {}",
                cyc.pull_off.force,
                -exact
            );
            // Loading is non-adhesive: the top of the loop is the Hertz force.
            let top = cyc.curve.iter().rev().find(|p| !p.unloading).unwrap();
            assert!(
                (top.force / crate::reference::hertz::force(1.0, 1.0, 0.36) - 1.0).abs() < 1e-3
            );
        }
    }

    #[test]
    fn discrete_error_falls_with_refinement() {
        let ad = sphere(1.0, 1.0, 0.01);
        let exact = jkr::pull_off_force_control(1.0, 0.01);
        let err = |n| {
            let c = simulate_cycle(&ad, n, 1.0, 0.36, Control::Force).unwrap();
            (c.pull_off.force / -exact - 1.0).abs()
        };
        let (e1, e2) = (err(2000), err(32_000));
        assert!(e2 < e1 / 4.0, "{e1} -> {e2}");
    }

    #[test]
    fn bad_inputs() {
        let c = AxisymmetricContact::new(Profile::single(Shape::paraboloid(1.0).unwrap()), 1.0)
            .unwrap();
        assert!(AdhesiveContact::new(c.clone(), -1.0).is_err());
        let ad = AdhesiveContact::new(c, 0.01).unwrap();
        assert!(simulate_cycle(&ad, 100, 0.1, 10.0, Control::Force).is_err());
        assert!(simulate_cycle(&ad, 100, 1.0, -1.0, Control::Force).is_err());
    }
}
