//! An axisymmetric contact on a discretised foundation of N springs.
//!
//! Springs sit at the midpoints x_i = -L + (i + 1/2) dx of [-L, L] (dx = 2L/N) with gaps
//! z1d(|x_i|). The contact radius is read as a = m dx / 2 for m springs in contact, so
//! the discrete stiffness E* dx m is exactly 2 a E* (Eq. 20). Forces converge to the
//! semi-analytic ones at second order in dx for profiles whose z1d is smooth away from
//! the axis (measured in the tests: order 2.0 +/- 0.2); flat punches under a rim are
//! exact.

use crate::error::{positive, MrdError, Result};
use crate::foundation::{Foundation, FoundationState};
use crate::normal::ContactState;
use crate::profile::Profile;

#[derive(Debug, Clone)]
pub struct DiscreteAxisymmetric {
    foundation: Foundation,
    half_length: f64,
    e_star: f64,
}

impl DiscreteAxisymmetric {
    /// `n` springs over [-L, L]; L is the rim if the profile has one, else `half_length`.
    pub fn new(profile: &Profile, e_star: f64, n: usize, half_length: f64) -> Result<Self> {
        positive("e_star", e_star)?;
        crate::error::springs(n)?;
        let l = crate::foundation::line_extent(profile, half_length)?;
        let dx = 2.0 * l / n as f64;
        let gaps: Vec<f64> = (0..n)
            .map(|i| profile.z1d(-l + (i as f64 + 0.5) * dx))
            .collect();
        Ok(Self {
            foundation: Foundation::new(&gaps, dx, e_star)?,
            half_length: l,
            e_star,
        })
    }

    pub fn dx(&self) -> f64 {
        self.foundation.dx()
    }

    fn to_contact(&self, s: FoundationState, rim: bool) -> Result<ContactState> {
        if s.contacts == self.foundation.len() && !rim && s.force > 0.0 {
            return Err(MrdError::OutOfRange {
                needed: f64::INFINITY,
                limit: self.half_length,
            });
        }
        Ok(ContactState {
            depth: s.depth,
            radius: 0.5 * s.contacts as f64 * self.dx(),
            force: s.force,
            stiffness: s.stiffness,
        })
    }

    /// State at depth `d` (exact for the discrete system).
    pub fn state_at_depth(&self, d: f64, has_rim: bool) -> Result<ContactState> {
        crate::error::non_negative("depth", d)?;
        self.to_contact(self.foundation.at_depth(d)?, has_rim)
    }

    /// State under force `f` (exact inversion of the piecewise-linear F(d)).
    pub fn state_at_force(&self, f: f64, has_rim: bool) -> Result<ContactState> {
        self.to_contact(self.foundation.at_force(f)?, has_rim)
    }

    pub fn e_star(&self) -> f64 {
        self.e_star
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::AxisymmetricContact;
    use crate::profile::Shape;

    /// Largest relative force error over several depths (the error oscillates with the
    /// position of the contact edge between springs, so take the envelope).
    fn envelope_error(p: &Profile, n: usize) -> f64 {
        let exact = AxisymmetricContact::new(p.clone(), 1.0).unwrap();
        let disc = DiscreteAxisymmetric::new(p, 1.0, n, 1.0).unwrap();
        // Radii spread quasi-randomly (golden-ratio sequence) so that edge positions
        // relative to the springs are not aligned with the grid.
        (1..=23)
            .map(|k| {
                let frac = (k as f64 * 0.618_033_988_749_895).fract();
                let d = exact.depth_at_radius(0.3 + 0.5 * frac).unwrap();
                let f0 = exact.state_at_depth(d).unwrap().force;
                let f1 = disc.state_at_depth(d, false).unwrap().force;
                ((f1 - f0) / f0).abs()
            })
            .fold(0.0, f64::max)
    }

    fn observed_order(p: &Profile) -> (f64, f64) {
        let ns = [250usize, 500, 1000, 2000, 4000, 8000];
        let pts: Vec<(f64, f64)> = ns
            .iter()
            .map(|&n| ((2.0 / n as f64).ln(), envelope_error(p, n).ln()))
            .collect();
        let mx = pts.iter().map(|p| p.0).sum::<f64>() / pts.len() as f64;
        let my = pts.iter().map(|p| p.1).sum::<f64>() / pts.len() as f64;
        let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
        (sxy / sxx, envelope_error(p, 8000))
    }

    #[test]
    fn converges_at_second_order() {
        for shape in [
            Shape::paraboloid(1.0).unwrap(),
            Shape::cone(0.2).unwrap(),
            Shape::power_law(1.0, 3.0).unwrap(),
        ] {
            let p = Profile::single(shape.clone());
            let (order, err) = observed_order(&p);
            assert!((order - 2.0).abs() < 0.2, "{shape:?}: order {order}");
            // Stated tolerance at N = 8000 springs over [-1, 1]: 2e-5 relative.
            assert!(err < 2e-5, "{shape:?}: error {err}");
        }
    }

    #[test]
    fn hertz_force_control_and_radius() {
        let p = Profile::single(Shape::paraboloid(1.0).unwrap());
        let disc = DiscreteAxisymmetric::new(&p, 1.0, 20_000, 1.0).unwrap();
        let f = crate::reference::hertz::force(1.0, 1.0, 0.25);
        let s = disc.state_at_force(f, false).unwrap();
        assert!((s.depth / 0.25 - 1.0).abs() < 1e-6);
        assert!((s.radius - 0.5).abs() <= disc.dx());
    }

    #[test]
    fn flat_punch_is_exact_and_domain_overflow_is_an_error() {
        let p = Profile::flat_punch(0.5).unwrap();
        let disc = DiscreteAxisymmetric::new(&p, 2.0, 10, 0.0).unwrap();
        let s = disc.state_at_depth(0.1, true).unwrap();
        assert!((s.force - crate::reference::flat_punch::force(2.0, 0.5, 0.1)).abs() < 1e-14);
        let sphere = Profile::single(Shape::paraboloid(1.0).unwrap());
        let disc = DiscreteAxisymmetric::new(&sphere, 1.0, 100, 0.1).unwrap();
        assert!(disc.state_at_depth(1.0, false).is_err());
    }
}
