//! Effective elastic moduli of a contact pair.
//!
//! Normal springs have stiffness E* dx (Eq. 3), tangential springs G* dx (Eq. 6).

use crate::error::{positive, MrdError, Result};

/// One elastic body: Young's modulus (may be `f64::INFINITY` for a rigid body) and
/// Poisson ratio in (-1, 0.5].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticBody {
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
}

impl ElasticBody {
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self> {
        if youngs_modulus.is_nan() || youngs_modulus <= 0.0 {
            return Err(MrdError::InvalidParameter {
                name: "youngs_modulus",
                value: youngs_modulus,
                reason: "must be > 0 (use inf for a rigid body)",
            });
        }
        if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
            return Err(MrdError::InvalidParameter {
                name: "poisson_ratio",
                value: poisson_ratio,
                reason: "must lie in (-1, 0.5]",
            });
        }
        Ok(Self {
            youngs_modulus,
            poisson_ratio,
        })
    }

    pub fn rigid() -> Self {
        Self {
            youngs_modulus: f64::INFINITY,
            poisson_ratio: 0.0,
        }
    }

    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    fn is_rigid(&self) -> bool {
        self.youngs_modulus.is_infinite()
    }
}

/// Effective moduli of a pair: E* (Eq. 2) for normal and G* (Eq. 5) for tangential
/// springs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Effective normal modulus E* (Eq. 2).
    pub e_star: f64,
    /// Effective tangential modulus G* (Eq. 5); `None` when only E* was given.
    pub g_star: Option<f64>,
    /// Relative violation of elastic similarity (Eq. 7); 0 when satisfied or unknown.
    pub similarity_mismatch: f64,
}

impl Material {
    /// E* given directly (normal problems only).
    pub fn from_e_star(e_star: f64) -> Result<Self> {
        Ok(Self {
            e_star: positive("e_star", e_star)?,
            g_star: None,
            similarity_mismatch: 0.0,
        })
    }

    /// E* and G* given directly.
    pub fn from_moduli(e_star: f64, g_star: f64) -> Result<Self> {
        Ok(Self {
            e_star: positive("e_star", e_star)?,
            g_star: Some(positive("g_star", g_star)?),
            similarity_mismatch: 0.0,
        })
    }

    /// Effective moduli of two bodies (Eqs. 2 and 5) and the elastic-similarity check
    /// (Eq. 7). At least one body must be deformable.
    pub fn from_bodies(b1: ElasticBody, b2: ElasticBody) -> Result<Self> {
        if b1.is_rigid() && b2.is_rigid() {
            return Err(MrdError::InvalidParameter {
                name: "youngs_modulus",
                value: f64::INFINITY,
                reason: "at least one body must be deformable",
            });
        }
        let compliance = |b: &ElasticBody| {
            if b.is_rigid() {
                0.0
            } else {
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus
            }
        };
        let e_star = 1.0 / (compliance(&b1) + compliance(&b2)); // Eq. (2)
        let shear = |b: &ElasticBody| {
            if b.is_rigid() {
                0.0
            } else {
                (2.0 - b.poisson_ratio) / (4.0 * b.shear_modulus())
            }
        };
        let g_star = 1.0 / (shear(&b1) + shear(&b2)); // Eq. (5)
        let side = |b: &ElasticBody| {
            if b.is_rigid() {
                0.0
            } else {
                (1.0 - 2.0 * b.poisson_ratio) / b.shear_modulus()
            }
        };
        let (s1, s2) = (side(&b1), side(&b2)); // Eq. (7)
        let scale = s1.abs().max(s2.abs());
        let similarity_mismatch = if scale > 0.0 {
            (s1 - s2).abs() / scale
        } else {
            0.0
        };
        Ok(Self {
            e_star,
            g_star: Some(g_star),
            similarity_mismatch,
        })
    }

    /// G*, or an error naming the missing input for tangential problems.
    pub fn g_star(&self) -> Result<f64> {
        self.g_star.ok_or(MrdError::Missing {
            name: "g_star",
            hint: "tangential problems need G*: give material.g_star, or [material.indenter] \
                   and [material.substrate] with E and nu",
        })
    }

    /// Warning text when elastic similarity (Eq. 7) is violated by more than 1e-9
    /// (relative): normal and tangential problems are then coupled and MRD's decoupled
    /// tangential solution is an approximation.
    pub fn similarity_warning(&self) -> Option<String> {
        (self.similarity_mismatch > 1e-9).then(|| {
            format!(
                "elastic similarity (Eq. 7) violated: (1-2nu1)/G1 and (1-2nu2)/G2 differ by {:.3}% \
                 (relative); the tangential solution neglects the normal-tangential coupling",
                100.0 * self.similarity_mismatch
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_on_elastic_moduli() {
        let m = Material::from_bodies(
            ElasticBody::rigid(),
            ElasticBody::new(2.0, 1.0 / 3.0).unwrap(),
        )
        .unwrap();
        assert!((m.e_star - 2.0 / (1.0 - 1.0 / 9.0)).abs() < 1e-14);
        // E*/G* = (2-nu)/(2(1-nu)) for a rigid indenter (the ratio in Eq. 54).
        let ratio = m.e_star / m.g_star.unwrap();
        assert!((ratio - 1.25).abs() < 1e-14);
        assert_eq!(m.similarity_mismatch, 1.0);
        assert!(m.similarity_warning().is_some());
    }

    #[test]
    fn identical_bodies_are_similar() {
        let b = ElasticBody::new(210e9, 0.3).unwrap();
        let m = Material::from_bodies(b, b).unwrap();
        assert!((m.e_star - 210e9 / (2.0 * 0.91)).abs() / m.e_star < 1e-14);
        assert!(m.similarity_warning().is_none());
        // Rigid vs incompressible also satisfies Eq. (7): both sides vanish.
        let m = Material::from_bodies(ElasticBody::rigid(), ElasticBody::new(1.0, 0.5).unwrap())
            .unwrap();
        assert!(m.similarity_warning().is_none());
    }

    #[test]
    fn bad_moduli_rejected() {
        assert!(ElasticBody::new(-1.0, 0.3).is_err());
        assert!(ElasticBody::new(1.0, 0.7).is_err());
        assert!(Material::from_e_star(f64::NAN).is_err());
        assert!(Material::from_bodies(ElasticBody::rigid(), ElasticBody::rigid()).is_err());
    }
}
