//! Axisymmetric indenter profiles z(r) and their MRD images z1d(x).
//!
//! The 1D profile follows the rule of Hess (Eq. 11):
//! `z1d(x) = x * Int_0^x z'(r) / sqrt(x^2 - r^2) dr`. It is linear in z, so a sum of
//! shapes maps to the sum of their images. Each shape carries its closed-form image;
//! [`crate::hess`] evaluates Eq. (11) by quadrature for any profile, and the tests check
//! both against each other.
//!
//! A profile may have a `rim`: the radius of a cylindrical punch whose face is the
//! profile (a flat punch is the empty profile with a rim). Beyond the rim there is no
//! indenter, so the contact radius never exceeds it.

use crate::error::{positive, MrdError, Result};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// Largest power-law exponent accepted (tested against Sneddon's closed form to 1e-12).
pub const MAX_POWER: f64 = 1000.0;

/// kappa_n of Eq. (15): the factor that maps c_n r^n to kappa_n c_n x^n.
pub fn kappa(n: f64) -> f64 {
    // Eq. (15); the Gamma ratio through log-Gamma where Gamma itself overflows.
    let ratio = if n < 300.0 {
        libm::tgamma(0.5 * n) / libm::tgamma(0.5 * n + 0.5)
    } else {
        (libm::lgamma(0.5 * n) - libm::lgamma(0.5 * n + 0.5)).exp()
    };
    0.5 * PI.sqrt() * n * ratio
}

/// A piecewise-linear profile z(r) read from a table, with r_0 = 0.
///
/// For piecewise-linear z, Eq. (11) is exact in closed form: with segment slopes s_k,
/// `z1d(x) = sum_j (s_{j-1} - s_j) A(x; r_j)`, `A(x; r) = x asin(min(r, x)/x)`.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedProfile {
    r: Vec<f64>,
    z: Vec<f64>,
    /// Slope change at node j: s_{j-1} - s_j (s_{-1} = 0; the last node closes the table).
    kinks: Vec<f64>,
}

impl TabulatedProfile {
    /// Builds a table from radii (strictly increasing, starting at 0) and heights.
    pub fn new(r: Vec<f64>, z: Vec<f64>) -> Result<Self> {
        if r.len() != z.len() {
            return Err(MrdError::InvalidTable(format!(
                "{} radii but {} heights",
                r.len(),
                z.len()
            )));
        }
        if r.len() < 2 {
            return Err(MrdError::InvalidTable("needs at least two rows".into()));
        }
        for (i, (&ri, &zi)) in r.iter().zip(&z).enumerate() {
            if !ri.is_finite() || !zi.is_finite() {
                return Err(MrdError::InvalidTable(format!(
                    "non-finite value in row {} (r = {ri}, z = {zi})",
                    i + 1
                )));
            }
        }
        if r[0] != 0.0 {
            return Err(MrdError::InvalidTable(format!(
                "first radius must be 0 (the axis), got {}",
                r[0]
            )));
        }
        if let Some(i) = r.windows(2).position(|w| w[1] <= w[0]) {
            return Err(MrdError::InvalidTable(format!(
                "radii must increase strictly (rows {} and {})",
                i + 1,
                i + 2
            )));
        }
        let slopes: Vec<f64> = (0..r.len() - 1)
            .map(|k| (z[k + 1] - z[k]) / (r[k + 1] - r[k]))
            .collect();
        let mut kinks = Vec::with_capacity(r.len());
        for j in 0..r.len() {
            let before = if j == 0 { 0.0 } else { slopes[j - 1] };
            let after = if j < slopes.len() { slopes[j] } else { 0.0 };
            kinks.push(before - after);
        }
        Ok(Self { r, z, kinks })
    }

    pub fn max_radius(&self) -> f64 {
        *self.r.last().unwrap()
    }

    fn segment(&self, r: f64) -> usize {
        match self.r.partition_point(|&ri| ri <= r) {
            0 => 0,
            k => (k - 1).min(self.r.len() - 2),
        }
    }

    fn z(&self, r: f64) -> f64 {
        let k = self.segment(r);
        let t = (r - self.r[k]) / (self.r[k + 1] - self.r[k]);
        self.z[k] + t * (self.z[k + 1] - self.z[k]) - self.z[0]
    }

    fn dz(&self, r: f64) -> f64 {
        let k = self.segment(r);
        (self.z[k + 1] - self.z[k]) / (self.r[k + 1] - self.r[k])
    }

    /// Segment k with r_k < x <= r_{k+1} (clamped to the table).
    fn segment_left(&self, x: f64) -> usize {
        self.r
            .partition_point(|&ri| ri < x)
            .saturating_sub(1)
            .min(self.r.len() - 2)
    }

    fn slope_left(&self, x: f64) -> f64 {
        let k = self.segment_left(x);
        (self.z[k + 1] - self.z[k]) / (self.r[k + 1] - self.r[k])
    }

    /// Interior nodes 0 < r_j < x with their slope changes.
    fn nodes_below(&self, x: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.r
            .iter()
            .zip(&self.kinks)
            .skip(1)
            .take_while(move |(&rj, _)| rj < x)
            .map(|(&rj, &kj)| (rj, kj))
    }

    fn z1d(&self, x: f64) -> f64 {
        // Nodes at r_j >= x contribute (s_{j-1} - s_j) x pi/2; these telescope to the
        // slope of the segment holding x.
        let mut sum = self.slope_left(x) * x * FRAC_PI_2;
        for (rj, kj) in self.nodes_below(x) {
            sum += kj * x * (rj / x).asin();
        }
        sum
    }

    fn dz1d(&self, x: f64) -> f64 {
        let mut sum = self.slope_left(x) * FRAC_PI_2;
        for (rj, kj) in self.nodes_below(x) {
            sum += kj * ((rj / x).asin() - rj / (x * x - rj * rj).sqrt());
        }
        sum
    }

    fn int_z1d(&self, a: f64) -> f64 {
        // Int_0^a A(x; r) dx = pi a^2/4 (a <= r), pi r^2/4 + G(a; r) (a > r) with
        // G(a; r) = a^2/2 asin(r/a) + r/2 sqrt(a^2 - r^2) - pi r^2/4.
        let big_a = |r: f64| -> f64 {
            if a <= r {
                FRAC_PI_4 * a * a
            } else {
                0.5 * a * a * (r / a).asin() + 0.5 * r * (a * a - r * r).sqrt()
            }
        };
        self.r
            .iter()
            .zip(&self.kinks)
            .filter(|(&rj, _)| rj > 0.0)
            .map(|(&rj, &kj)| kj * big_a(rj))
            .sum()
    }
}

/// One elementary axisymmetric shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// z = c r^n for any real n > 0 (Eq. 12).
    PowerLaw { c: f64, n: f64 },
    /// Sphere in the paraboloid approximation, z = r^2 / (2R).
    Paraboloid { radius: f64 },
    /// Cone, z = r tan(theta), with tan(theta) the slope.
    Cone { tan_theta: f64 },
    /// Flattened paraboloid (Eq. 22): 0 for r < a0, (r^2 - a0^2)/(2R) beyond.
    FlattenedParaboloid { radius: f64, flat_radius: f64 },
    /// Piecewise-linear table.
    Table(TabulatedProfile),
}

impl Shape {
    /// z = c r^n with 0 < n <= [`MAX_POWER`] (beyond, the profile is a flat punch to
    /// machine precision: give a rim instead).
    pub fn power_law(c: f64, n: f64) -> Result<Self> {
        let n = positive("n", n)?;
        if n > MAX_POWER {
            return Err(MrdError::InvalidParameter {
                name: "n",
                value: n,
                reason: "must lie in (0, 1000]; a steeper power law is a flat punch (give a rim and no shapes)",
            });
        }
        Ok(Shape::PowerLaw {
            c: positive("c_n", c)?,
            n,
        })
    }
    pub fn paraboloid(radius: f64) -> Result<Self> {
        Ok(Shape::Paraboloid {
            radius: positive("radius", radius)?,
        })
    }
    pub fn cone(tan_theta: f64) -> Result<Self> {
        Ok(Shape::Cone {
            tan_theta: positive("tan_theta", tan_theta)?,
        })
    }
    pub fn flattened_paraboloid(radius: f64, flat_radius: f64) -> Result<Self> {
        Ok(Shape::FlattenedParaboloid {
            radius: positive("radius", radius)?,
            flat_radius: positive("flat_radius", flat_radius)?,
        })
    }

    /// Height z(r) above the tip.
    pub fn z(&self, r: f64) -> f64 {
        match self {
            Shape::PowerLaw { c, n } => c * r.powf(*n),
            Shape::Paraboloid { radius } => r * r / (2.0 * radius),
            Shape::Cone { tan_theta } => r * tan_theta,
            Shape::FlattenedParaboloid {
                radius,
                flat_radius: a0,
            } => {
                if r > *a0 {
                    (r * r - a0 * a0) / (2.0 * radius)
                } else {
                    0.0
                }
            }
            Shape::Table(t) => t.z(r),
        }
    }

    /// Slope z'(r).
    pub fn dz(&self, r: f64) -> f64 {
        match self {
            Shape::PowerLaw { c, n } => c * n * r.powf(n - 1.0),
            Shape::Paraboloid { radius } => r / radius,
            Shape::Cone { tan_theta } => *tan_theta,
            Shape::FlattenedParaboloid {
                radius,
                flat_radius: a0,
            } => {
                if r > *a0 {
                    r / radius
                } else {
                    0.0
                }
            }
            Shape::Table(t) => t.dz(r),
        }
    }

    /// Closed-form MRD image z1d(x), x >= 0 (Eqs. 13-15, 23).
    pub fn z1d(&self, x: f64) -> f64 {
        match self {
            Shape::PowerLaw { c, n } => kappa(*n) * c * x.powf(*n), // Eq. (14)
            Shape::Paraboloid { radius } => x * x / radius,         // kappa_2 = 2, Eq. (10)
            Shape::Cone { tan_theta } => FRAC_PI_2 * tan_theta * x, // kappa_1 = pi/2
            Shape::FlattenedParaboloid {
                radius,
                flat_radius: a0,
            } => {
                if x > *a0 {
                    x * (x * x - a0 * a0).sqrt() / radius // Eq. (23)
                } else {
                    0.0
                }
            }
            Shape::Table(t) => t.z1d(x),
        }
    }

    /// Derivative of the image, d z1d / dx.
    pub fn dz1d(&self, x: f64) -> f64 {
        match self {
            Shape::PowerLaw { c, n } => kappa(*n) * c * n * x.powf(n - 1.0),
            Shape::Paraboloid { radius } => 2.0 * x / radius,
            Shape::Cone { tan_theta } => FRAC_PI_2 * tan_theta,
            Shape::FlattenedParaboloid {
                radius,
                flat_radius: a0,
            } => {
                if x > *a0 {
                    (2.0 * x * x - a0 * a0) / (radius * (x * x - a0 * a0).sqrt())
                } else {
                    0.0
                }
            }
            Shape::Table(t) => t.dz1d(x),
        }
    }

    /// Int_0^a z1d(x) dx in closed form.
    pub fn int_z1d(&self, a: f64) -> f64 {
        match self {
            Shape::PowerLaw { c, n } => kappa(*n) * c * a.powf(n + 1.0) / (n + 1.0),
            Shape::Paraboloid { radius } => a * a * a / (3.0 * radius),
            Shape::Cone { tan_theta } => FRAC_PI_4 * tan_theta * a * a,
            Shape::FlattenedParaboloid {
                radius,
                flat_radius: a0,
            } => {
                if a > *a0 {
                    (a * a - a0 * a0).powf(1.5) / (3.0 * radius)
                } else {
                    0.0
                }
            }
            Shape::Table(t) => t.int_z1d(a),
        }
    }

    /// Radii where z or z' is not smooth (quadrature break points).
    pub fn breaks(&self) -> Vec<f64> {
        match self {
            Shape::FlattenedParaboloid { flat_radius, .. } => vec![*flat_radius],
            Shape::Table(t) => t.r[1..].to_vec(),
            _ => Vec::new(),
        }
    }

    /// Largest radius where the shape is defined.
    pub fn max_radius(&self) -> f64 {
        match self {
            Shape::Table(t) => t.max_radius(),
            _ => f64::INFINITY,
        }
    }
}

/// An axisymmetric indenter: a sum of shapes, optionally cut by a cylindrical rim.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Profile {
    shapes: Vec<Shape>,
    rim: Option<f64>,
}

impl Profile {
    pub fn new(shapes: Vec<Shape>, rim: Option<f64>) -> Result<Self> {
        if let Some(r) = rim {
            positive("rim radius", r)?;
        }
        if shapes.is_empty() && rim.is_none() {
            return Err(MrdError::InvalidTable(
                "a profile needs at least one shape or a rim (flat punch)".into(),
            ));
        }
        let p = Self { shapes, rim };
        p.check_monotone()?;
        Ok(p)
    }

    pub fn single(shape: Shape) -> Self {
        Self {
            shapes: vec![shape],
            rim: None,
        }
    }

    /// Flat cylindrical punch of radius `a`.
    pub fn flat_punch(a: f64) -> Result<Self> {
        Self::new(Vec::new(), Some(a))
    }

    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    pub fn rim(&self) -> Option<f64> {
        self.rim
    }

    /// Radius beyond which the profile cannot be in contact: the rim, else the smallest
    /// table range (infinite for analytic shapes).
    pub fn max_contact_radius(&self) -> f64 {
        let table = self
            .shapes
            .iter()
            .map(Shape::max_radius)
            .fold(f64::INFINITY, f64::min);
        self.rim.map_or(table, |r| r.min(table))
    }

    pub fn z(&self, r: f64) -> f64 {
        self.shapes.iter().map(|s| s.z(r)).sum()
    }
    pub fn dz(&self, r: f64) -> f64 {
        self.shapes.iter().map(|s| s.dz(r)).sum()
    }
    /// MRD image z1d(|x|) (Eq. 11), closed form per shape.
    pub fn z1d(&self, x: f64) -> f64 {
        let x = x.abs();
        self.shapes.iter().map(|s| s.z1d(x)).sum()
    }
    pub fn dz1d(&self, x: f64) -> f64 {
        self.shapes.iter().map(|s| s.dz1d(x)).sum()
    }
    pub fn int_z1d(&self, a: f64) -> f64 {
        self.shapes.iter().map(|s| s.int_z1d(a)).sum()
    }
    pub fn breaks(&self) -> Vec<f64> {
        self.shapes.iter().flat_map(Shape::breaks).collect()
    }

    /// MRD requires a simply connected (disc) contact: z1d must not decrease. Checked on
    /// a grid over the defined range (finite) or [0, 1e3 * scale] for analytic sums.
    fn check_monotone(&self) -> Result<()> {
        let limit = self.max_contact_radius();
        if !limit.is_finite() {
            return Ok(()); // sums of analytic shapes with positive coefficients are monotone
        }
        let m = 4096;
        let mut prev = 0.0f64;
        for i in 1..=m {
            let x = limit * i as f64 / m as f64;
            let z = self.z1d(x);
            if z < prev - 1e-12 * prev.abs().max(1e-300) {
                return Err(MrdError::InvalidTable(format!(
                    "the MRD image z1d decreases near x = {x:.4e}: the contact would not be a \
                     single disc, which the axisymmetric mapping requires"
                )));
            }
            prev = z;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn kappa_through_log_gamma_for_steep_power_laws() {
        // Both Gamma paths agree where both work, and kappa approaches sqrt(pi n / 2)
        // (Stirling) as n grows; n = 1e6 is refused with a hint.
        let direct =
            |n: f64| 0.5 * PI.sqrt() * n * libm::tgamma(0.5 * n) / libm::tgamma(0.5 * n + 0.5);
        let logs = |n: f64| {
            0.5 * PI.sqrt() * n * (libm::lgamma(0.5 * n) - libm::lgamma(0.5 * n + 0.5)).exp()
        };
        for n in [50.0, 250.0, 299.0] {
            assert!((direct(n) / logs(n) - 1.0).abs() < 1e-12, "n = {n}");
        }
        for n in [300.0, 1000.0] {
            let stirling = (PI * n / 2.0).sqrt() * (1.0 + 1.0 / (4.0 * n));
            assert!(
                (kappa(n) / stirling - 1.0).abs() < 1e-5,
                "n = {n}: {}",
                kappa(n)
            );
        }
        assert!((kappa(299.999) / kappa(300.001) - 1.0).abs() < 1e-5);
        let e = Shape::power_law(1.0, 1e6).unwrap_err().to_string();
        assert!(e.contains("(0, 1000]") && e.contains("rim"), "{e}");
    }

    use super::*;

    #[test]
    fn kappa_special_values() {
        assert!((kappa(1.0) - FRAC_PI_2).abs() < 1e-15);
        assert!((kappa(2.0) - 2.0).abs() < 1e-15);
        // kappa_3 = 8/3 from sqrt(pi)/2 * 3 Gamma(3/2)/Gamma(2) = 3 pi/4
        assert!((kappa(3.0) - 3.0 * PI / 4.0).abs() < 1e-14);
    }

    #[test]
    fn table_of_a_cone_is_exact() {
        let r: Vec<f64> = (0..11).map(|i| i as f64 * 0.1).collect();
        let z: Vec<f64> = r.iter().map(|r| 0.3 * r).collect();
        let t = Shape::Table(TabulatedProfile::new(r, z).unwrap());
        let c = Shape::cone(0.3).unwrap();
        for &x in &[0.05, 0.1, 0.37, 0.99, 1.0] {
            assert!((t.z1d(x) - c.z1d(x)).abs() < 1e-14, "x={x}");
            assert!((t.dz1d(x) - c.dz1d(x)).abs() < 1e-13, "x={x}");
            assert!((t.int_z1d(x) - c.int_z1d(x)).abs() < 1e-14, "x={x}");
        }
    }

    #[test]
    fn table_errors() {
        assert!(TabulatedProfile::new(vec![0.0, 1.0], vec![0.0, f64::NAN]).is_err());
        assert!(TabulatedProfile::new(vec![0.0, 1.0, 0.5], vec![0.0, 1.0, 2.0]).is_err());
        assert!(TabulatedProfile::new(vec![0.1, 1.0], vec![0.0, 1.0]).is_err());
        assert!(TabulatedProfile::new(vec![0.0], vec![0.0]).is_err());
        // A profile with a raised centre maps to a decreasing z1d: rejected.
        let t = TabulatedProfile::new(vec![0.0, 0.5, 1.0], vec![0.0, -0.5, 1.0]).unwrap();
        assert!(Profile::new(vec![Shape::Table(t)], None).is_err());
    }

    #[test]
    fn bad_shapes_rejected() {
        assert!(Shape::power_law(1.0, 0.0).is_err());
        assert!(Shape::power_law(1.0, -2.0).is_err());
        assert!(Shape::paraboloid(-1.0).is_err());
        assert!(Profile::new(vec![], None).is_err());
    }
}
