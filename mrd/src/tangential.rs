//! Tangential contact with Coulomb friction (Section 6): Cattaneo-Mindlin for the
//! sphere and Jager's generalisation to any axisymmetric profile.
//!
//! Springs in the stick zone |x| < c carry G* u_x (Eq. 41); the slip zone carries
//! mu times the normal line load (Eq. 46). The stick radius follows from
//! `G* u_x = mu E* (d - z1d(c))` (Eq. 43 generalised), and the tangential force is
//! `F_x = mu (F_N(a) - F_N(c))` with F_N(c) the normal force of the same profile at
//! contact radius c (Eq. 48 generalised; Jager 1995).

use crate::error::{non_negative, positive, MrdError, Result};
use crate::normal::{AxisymmetricContact, ContactState};
use crate::pressure::abel_pressure;

/// A tangentially loaded contact at fixed normal state.
#[derive(Debug, Clone)]
pub struct TangentialContact {
    pub contact: AxisymmetricContact,
    pub g_star: f64,
    pub mu: f64,
    pub normal: ContactState,
}

/// State under a tangential force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialState {
    pub force: f64,
    /// Stick radius c.
    pub stick_radius: f64,
    /// Tangential displacement of the indenter u_x.
    pub displacement: f64,
}

impl TangentialContact {
    /// Contact first pressed to normal force `f_n`, then loaded tangentially.
    pub fn new(contact: AxisymmetricContact, g_star: f64, mu: f64, f_n: f64) -> Result<Self> {
        positive("g_star", g_star)?;
        positive("friction coefficient", mu)?;
        positive("normal force", f_n)?;
        let normal = contact.state_at_force(f_n)?;
        Ok(Self {
            contact,
            g_star,
            mu,
            normal,
        })
    }

    /// Full-sliding displacement u_x,max = mu E*/G* d (Eq. 50).
    pub fn max_displacement(&self) -> f64 {
        self.mu * self.contact.e_star / self.g_star * self.normal.depth // Eq. (50)
    }

    /// State at tangential displacement u_x (0 <= u_x <= u_x,max).
    pub fn at_displacement(&self, ux: f64) -> Result<TangentialState> {
        non_negative("tangential displacement", ux)?;
        if ux > self.max_displacement() * (1.0 + 1e-12) {
            return Err(MrdError::ImpossibleLoad(format!(
                "tangential displacement {ux:.4e} exceeds the full-sliding value {:.4e}",
                self.max_displacement()
            )));
        }
        // z1d(c) = d - G* u_x / (mu E*)  (Eq. 44 generalised)
        let zc = self.normal.depth - self.g_star * ux / (self.mu * self.contact.e_star);
        let inner = self.contact.state_at_depth(zc.max(0.0))?;
        let c = inner.radius.min(self.normal.radius);
        Ok(TangentialState {
            force: self.mu * (self.normal.force - self.contact.force_at_radius(c)?),
            stick_radius: c,
            displacement: ux,
        })
    }

    /// State under tangential force F_x (0 <= F_x < mu F_N).
    pub fn at_force(&self, fx: f64) -> Result<TangentialState> {
        non_negative("tangential force", fx)?;
        let limit = self.mu * self.normal.force;
        if fx >= limit {
            return Err(MrdError::ImpossibleLoad(format!(
                "tangential force {fx:.4e} reaches the sliding limit mu F_N = {limit:.4e}"
            )));
        }
        // F_N(c) = F_N - F_x/mu fixes c; then u_x from the stick condition.
        let inner = self
            .contact
            .state_at_force(self.normal.force - fx / self.mu)?;
        let c = inner.radius;
        let ux = self.mu * self.contact.e_star / self.g_star
            * (self.normal.depth - self.contact.profile.z1d(c));
        Ok(TangentialState {
            force: fx,
            stick_radius: c,
            displacement: ux,
        })
    }

    /// Tangential traction tau(r) by the Abel transform (Eq. 26) of the line load
    /// (Eq. 51): mu times the pressure of the flat-topped load with inner radius c.
    pub fn traction(&self, state: &TangentialState, r: f64) -> Result<f64> {
        let n = &self.normal;
        Ok(self.mu
            * abel_pressure(
                &self.contact.profile,
                self.contact.e_star,
                n.depth,
                n.radius,
                state.stick_radius,
                r,
            )?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{Profile, Shape};
    use crate::reference::{cattaneo_mindlin as cm, hertz};

    fn sphere() -> TangentialContact {
        let c = AxisymmetricContact::new(Profile::single(Shape::paraboloid(1.0).unwrap()), 1.0)
            .unwrap();
        TangentialContact::new(c, 0.8, 0.3, 0.01).unwrap()
    }

    #[test]
    fn stick_radius_eq49_and_displacement() {
        let t = sphere();
        let fmax = 0.3 * 0.01;
        for &q in &[0.01, 0.3, 0.7, 0.99] {
            let s = t.at_force(q * fmax).unwrap();
            let ratio = cm::stick_ratio(q * fmax, 0.3, 0.01);
            assert!(
                (s.stick_radius / t.normal.radius / ratio - 1.0).abs() < 1e-9,
                "q={q}"
            );
            let u = cm::displacement(0.3, 1.0, 0.8, t.normal.depth, q * fmax, 0.01);
            assert!((s.displacement / u - 1.0).abs() < 1e-9, "q={q}");
            let back = t.at_displacement(s.displacement).unwrap();
            assert!((back.force / s.force - 1.0).abs() < 1e-9);
        }
        let umax = cm::max_displacement(0.3, 1.0, 0.8, t.normal.depth); // Eq. (50)
        assert!((t.max_displacement() / umax - 1.0).abs() < 1e-14);
        assert!((t.at_displacement(umax).unwrap().force / fmax - 1.0).abs() < 1e-9);
    }

    #[test]
    fn traction_is_difference_of_hertz_distributions() {
        let t = sphere();
        let s = t.at_force(0.5 * 0.3 * 0.01).unwrap();
        let a = t.normal.radius;
        let p0 = hertz::pressure(1.0, 1.0, t.normal.depth, 0.0);
        for &f in &[0.0, 0.2, 0.5, 0.7, 0.95] {
            let r = f * a;
            let num = t.traction(&s, r).unwrap();
            let exact = cm::traction(0.3, p0, a, s.stick_radius, r);
            assert!((num - exact).abs() < 1e-9 * p0, "r/a={f}: {num} vs {exact}");
        }
    }

    #[test]
    fn jager_cone_matches_its_normal_problem() {
        // Jager: F_x = mu (F_N(a) - F_N(c)) for any profile; check the cone against
        // the closed-form cone forces.
        let c = AxisymmetricContact::new(Profile::single(Shape::cone(0.1).unwrap()), 1.0).unwrap();
        let t = TangentialContact::new(c, 1.0, 0.5, 0.02).unwrap();
        let s = t.at_force(0.004).unwrap();
        let d_c = crate::reference::cone::radius(0.1, 1.0).recip() * s.stick_radius; // d at radius c
        let f_c = crate::reference::cone::force(1.0, 0.1, d_c);
        assert!(((0.02 - f_c) * 0.5 / 0.004 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn impossible_tangential_loads() {
        let t = sphere();
        assert!(t.at_force(0.3 * 0.01).is_err());
        assert!(t.at_displacement(2.0 * t.max_displacement()).is_err());
        let c = t.contact.clone();
        assert!(TangentialContact::new(c.clone(), 1.0, 0.0, 0.01).is_err());
        assert!(TangentialContact::new(c, 1.0, -0.2, 0.01).is_err());
    }
}
