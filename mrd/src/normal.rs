//! Frictionless normal contact of an axisymmetric indenter, semi-analytically.
//!
//! With the MRD image z1d of the profile (Eq. 11), for contact radius a:
//! depth `d = z1d(a)` (Eq. 24), force `F = 2E* Int_0^a (d - z1d(x)) dx` (Eq. 25) and
//! incremental stiffness `k = dF/dd = 2 a E*` (Eq. 20). Depth- and force-controlled
//! states are found by inverting these monotone relations (Brent's method on a).
//! Inside a rim (cylindrical punch) the contact radius stops at the rim and the force
//! grows with the flat-punch stiffness 2 a E*.

use crate::error::{non_negative, MrdError, Result};
use crate::numerics::roots::{bracket_up, brent};
use crate::profile::Profile;

/// Contact state at one load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Indentation depth d (rigid-body approach).
    pub depth: f64,
    /// Contact radius a.
    pub radius: f64,
    /// Normal force F.
    pub force: f64,
    /// Incremental stiffness dF/dd = 2 a E* (Eq. 20).
    pub stiffness: f64,
}

impl ContactState {
    /// Electrical contact conductance from the stiffness (end of Section 8):
    /// `k = E* (rho1 + rho2) Lambda / 2`, so `Lambda = 2 k / (E* (rho1 + rho2))`.
    pub fn electrical_conductance(&self, e_star: f64, rho_sum: f64) -> f64 {
        2.0 * self.stiffness / (e_star * rho_sum)
    }
    /// Thermal contact conductance, by the same analogy with conductivities:
    /// `Lambda_th = 2 k / (E* (1/lambda1 + 1/lambda2))`.
    pub fn thermal_conductance(&self, e_star: f64, inverse_conductivity_sum: f64) -> f64 {
        2.0 * self.stiffness / (e_star * inverse_conductivity_sum)
    }
}

/// An axisymmetric rigid indenter on an elastic half-space with modulus E*.
#[derive(Debug, Clone)]
pub struct AxisymmetricContact {
    pub profile: Profile,
    pub e_star: f64,
}

impl AxisymmetricContact {
    pub fn new(profile: Profile, e_star: f64) -> Result<Self> {
        crate::error::positive("e_star", e_star)?;
        Ok(Self { profile, e_star })
    }

    fn limit(&self) -> f64 {
        self.profile.max_contact_radius()
    }

    fn check_radius(&self, a: f64) -> Result<()> {
        crate::error::non_negative("contact radius", a)?;
        if a > self.limit() * (1.0 + 1e-12) {
            return Err(MrdError::OutOfRange {
                needed: a,
                limit: self.limit(),
            });
        }
        Ok(())
    }

    /// Depth at which the contact radius is `a` (Eq. 24 generalised: d = z1d(a)).
    pub fn depth_at_radius(&self, a: f64) -> Result<f64> {
        self.check_radius(a)?;
        Ok(self.profile.z1d(a))
    }

    /// Force at contact radius `a` without rim loading (Eq. 25 generalised):
    /// F = 2E* (a z1d(a) - Int_0^a z1d).
    pub fn force_at_radius(&self, a: f64) -> Result<f64> {
        self.check_radius(a)?;
        Ok(2.0 * self.e_star * (a * self.profile.z1d(a) - self.profile.int_z1d(a)))
    }

    /// The state at a contact radius `a` that a load reaches: as
    /// [`Self::state_at_radius`], but a radius inside a flat central face (a flat
    /// punch's, a flattened sphere's) is refused, since contact jumps from 0 to the
    /// face's edge at depth 0 and no load has that radius. The query for a radius a user
    /// gives.
    pub fn state_at_reached_radius(&self, a: f64) -> Result<ContactState> {
        self.check_radius(a)?;
        let beyond = (a * (1.0 + 1e-9)).min(self.limit());
        if a > 0.0 && beyond > a && self.profile.z1d(beyond) <= 0.0 {
            return Err(MrdError::InvalidParameter {
                name: "contact radius",
                value: a,
                reason: "no load has it: the profile is flat out to a larger radius, where contact starts at once (a flat punch touches with its whole face)",
            });
        }
        self.state_at_radius(a)
    }

    /// State at contact radius `a` (a below the rim), the formulas of the module docs
    /// at any radius (inside a flat face: zero depth and force).
    pub fn state_at_radius(&self, a: f64) -> Result<ContactState> {
        Ok(ContactState {
            depth: self.depth_at_radius(a)?,
            radius: a,
            force: self.force_at_radius(a)?,
            stiffness: 2.0 * a * self.e_star,
        })
    }

    /// Characteristic length used to start bracket searches.
    fn scale(&self) -> f64 {
        let l = self.limit();
        if l.is_finite() {
            l
        } else {
            1.0
        }
    }

    /// Displacement-controlled solve: the state at depth `d >= 0`.
    pub fn state_at_depth(&self, d: f64) -> Result<ContactState> {
        non_negative("depth", d)?;
        if d == 0.0 {
            return Ok(ContactState {
                depth: 0.0,
                radius: 0.0,
                force: 0.0,
                stiffness: 0.0,
            });
        }
        if let Some(rim) = self.profile.rim() {
            let d_rim = self.profile.z1d(rim);
            if d >= d_rim {
                let base = self.force_at_radius(rim)?;
                return Ok(ContactState {
                    depth: d,
                    radius: rim,
                    force: base + 2.0 * rim * self.e_star * (d - d_rim),
                    stiffness: 2.0 * rim * self.e_star,
                });
            }
        }
        let z1d = |a: f64| self.profile.z1d(a);
        let hi =
            bracket_up(|a| Ok(z1d(a)), d, 1e-3 * self.scale(), self.limit()).map_err(|_| {
                MrdError::Unreachable {
                    depth: d,
                    limit: self.limit(),
                }
            })?;
        let a = brent(|a| z1d(a) - d, 0.0, hi, 1e-16 * hi)?;
        let mut s = self.state_at_radius(a)?;
        s.depth = d;
        Ok(s)
    }

    /// Force-controlled solve: the state under normal force `f >= 0`.
    pub fn state_at_force(&self, f: f64) -> Result<ContactState> {
        non_negative("force", f)?;
        if f == 0.0 {
            return self.state_at_depth(0.0);
        }
        if let Some(rim) = self.profile.rim() {
            let f_rim = self.force_at_radius(rim)?;
            if f >= f_rim {
                let d_rim = self.profile.z1d(rim);
                let d = d_rim + (f - f_rim) / (2.0 * rim * self.e_star);
                return Ok(ContactState {
                    depth: d,
                    radius: rim,
                    force: f,
                    stiffness: 2.0 * rim * self.e_star,
                });
            }
        }
        let force = |a: f64| self.force_at_radius(a);
        let hi = bracket_up(force, f, 1e-3 * self.scale(), self.limit())?;
        let a = brent(
            |a| self.force_at_radius(a).unwrap_or(f64::NAN) - f,
            0.0,
            hi,
            1e-16 * hi,
        )?;
        let mut s = self.state_at_radius(a)?;
        s.force = f;
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::rel;
    use crate::profile::Shape;
    use crate::reference::{cone, ejike, flat_punch, hertz, power_law};

    #[test]
    fn hertz_depth_and_force_control() {
        let c = AxisymmetricContact::new(Profile::single(Shape::paraboloid(2.0).unwrap()), 1.5)
            .unwrap();
        for &d in &[1e-6, 1e-3, 0.1, 2.0] {
            let s = c.state_at_depth(d).unwrap();
            assert!(rel(s.radius, hertz::radius(2.0, d)) < 1e-9);
            assert!(rel(s.force, hertz::force(1.5, 2.0, d)) < 1e-9);
            let t = c.state_at_force(s.force).unwrap();
            assert!(rel(t.depth, d) < 1e-9);
            // Eq. (20): stiffness equals a central difference of F(d).
            let h = 1e-5 * d;
            let k = (c.state_at_depth(d + h).unwrap().force
                - c.state_at_depth(d - h).unwrap().force)
                / (2.0 * h);
            assert!(rel(s.stiffness, k) < 1e-6);
        }
    }

    #[test]
    fn cone_and_power_laws() {
        let c = AxisymmetricContact::new(Profile::single(Shape::cone(0.1).unwrap()), 1.0).unwrap();
        let s = c.state_at_depth(0.05).unwrap();
        assert!(rel(s.force, cone::force(1.0, 0.1, 0.05)) < 1e-9);
        assert!(rel(s.radius, cone::radius(0.1, 0.05)) < 1e-9);
        for &n in &[0.5, 1.0, 2.0, 3.0, 4.5, 250.0, 1000.0] {
            let c =
                AxisymmetricContact::new(Profile::single(Shape::power_law(0.8, n).unwrap()), 2.0)
                    .unwrap();
            let s = c.state_at_force(0.37).unwrap();
            assert!(
                rel(power_law::force(2.0, 0.8, n, s.radius), 0.37) < 1e-9,
                "n={n}"
            );
            assert!(
                rel(power_law::depth(0.8, n, s.radius), s.depth) < 1e-9,
                "n={n}"
            );
        }
    }

    #[test]
    fn ejike_flattened_paraboloid() {
        let c = AxisymmetricContact::new(
            Profile::single(Shape::flattened_paraboloid(1.0, 0.2).unwrap()),
            1.0,
        )
        .unwrap();
        for &a in &[0.21, 0.3, 0.8] {
            let d = ejike::depth(1.0, 0.2, a);
            let s = c.state_at_depth(d).unwrap();
            assert!(rel(s.radius, a) < 1e-9);
            assert!(rel(s.force, ejike::force(1.0, 1.0, 0.2, a)) < 1e-9);
        }
        // Any depth > 0 contacts the whole flat of radius a0.
        let r = c.state_at_depth(1e-12).unwrap().radius;
        assert!(r >= 0.2 * (1.0 - 1e-15), "{r}");
    }

    #[test]
    fn flat_punch_and_rim() {
        let c = AxisymmetricContact::new(Profile::flat_punch(0.5).unwrap(), 3.0).unwrap();
        let s = c.state_at_depth(0.01).unwrap();
        assert!(rel(s.force, flat_punch::force(3.0, 0.5, 0.01)) < 1e-14);
        assert!(rel(s.stiffness, 3.0) < 1e-14); // k = D E* (Eq. 1)
        assert!(rel(c.state_at_force(s.force).unwrap().depth, 0.01) < 1e-14);
        // A sphere inside a rim: Hertz until a reaches the rim, flat punch after.
        let p = Profile::new(vec![Shape::paraboloid(1.0).unwrap()], Some(0.1)).unwrap();
        let c = AxisymmetricContact::new(p, 1.0).unwrap();
        let d_rim = 0.01;
        let s = c.state_at_depth(2.0 * d_rim).unwrap();
        assert_eq!(s.radius, 0.1);
        let expect = hertz::force(1.0, 1.0, d_rim) + 2.0 * 0.1 * d_rim;
        assert!(rel(s.force, expect) < 1e-12);
    }

    #[test]
    fn bad_loads_are_errors() {
        let c = AxisymmetricContact::new(Profile::single(Shape::paraboloid(1.0).unwrap()), 1.0)
            .unwrap();
        assert!(c.state_at_depth(-1.0).is_err());
        assert!(c.state_at_force(f64::NAN).is_err());
        assert!(AxisymmetricContact::new(c.profile.clone(), -2.0).is_err());
        let t = crate::profile::TabulatedProfile::new(vec![0.0, 1.0], vec![0.0, 0.5]).unwrap();
        let c = AxisymmetricContact::new(Profile::single(Shape::Table(t)), 1.0).unwrap();
        assert!(matches!(
            c.state_at_depth(10.0),
            Err(MrdError::Unreachable { .. })
        ));
    }
}
