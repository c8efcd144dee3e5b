//! The context every output runs in: units, material, indenter profile, and the one
//! resolver of file paths relative to the scene. Built from the scene's top-level
//! tables (`[units]`, `[material]`, `[profile]`).

use crate::error::{CompareError, Context as _, Result};
use mrd::{ElasticBody, Material, Profile, Shape, TabulatedProfile};
use serde::Deserialize;
use std::any::Any;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// What outputs see of the scene.
#[derive(Debug, Clone)]
pub struct Context {
    /// Where the scene came from (a path, or `<embedded:name>`), for messages.
    pub origin: String,
    pub units: Units,
    pub material: Material,
    pub profile: Option<Profile>,
    /// Folder of the scene file (None for embedded scenes).
    pub base_dir: Option<PathBuf>,
    /// What outputs computed from the scene's files once ([`Context::memo`]).
    pub memo: Memo,
}

/// Values an output derives from the scene's files (a measured map read and
/// transformed) once, for its validation and its run: keyed by the output, shared by
/// the clones of a context, dropped with the scene.
#[derive(Clone, Default)]
pub struct Memo(Arc<Mutex<HashMap<String, Arc<dyn Any + Send + Sync>>>>);

impl std::fmt::Debug for Memo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let held = self.0.lock().map_or(0, |m| m.len());
        write!(f, "Memo({held} values)")
    }
}

impl Context {
    /// The indenter profile; outputs that need one call this.
    pub fn profile(&self) -> Result<&Profile> {
        self.profile.as_ref().ok_or_else(|| {
            CompareError::Scene(format!("{}: this output needs a [profile]", self.origin))
        })
    }

    /// The value stored under `key`, made by `make` the first time (a failure is not
    /// stored: the next call tries again).
    pub fn memo<T: Any + Send + Sync>(
        &self,
        key: &str,
        make: impl FnOnce() -> Result<T>,
    ) -> Result<Arc<T>> {
        let held = |m: &Memo| {
            m.0.lock()
                .unwrap_or_else(|e| e.into_inner())
                .get(key)
                .cloned()
        };
        if let Some(v) = held(&self.memo).and_then(|v| v.downcast::<T>().ok()) {
            return Ok(v);
        }
        let v = Arc::new(make()?);
        let mut m = self.memo.0.lock().unwrap_or_else(|e| e.into_inner());
        m.insert(key.to_string(), v.clone());
        Ok(v)
    }

    /// A file named in the scene: relative paths are relative to the scene's folder
    /// (embedded scenes: to the current folder).
    pub fn resolve(&self, file: &str) -> PathBuf {
        resolve(self.base_dir.as_deref(), file)
    }
}

fn resolve(base: Option<&Path>, file: &str) -> PathBuf {
    let p = Path::new(file);
    match base {
        Some(b) if p.is_relative() => b.join(p),
        _ => p.to_path_buf(),
    }
}

/// Unit labels (the computation is unit-agnostic; labels go into headers and axes).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    #[serde(default = "default_length")]
    pub length: String,
    #[serde(default = "default_stress")]
    pub stress: String,
}

fn default_length() -> String {
    "m".into()
}
fn default_stress() -> String {
    "Pa".into()
}

impl Default for Units {
    fn default() -> Self {
        Self {
            length: default_length(),
            stress: default_stress(),
        }
    }
}

impl Units {
    /// Force unit = stress x length^2, named where the pair is a standard one.
    pub fn force(&self) -> String {
        match (self.stress.as_str(), self.length.as_str()) {
            ("Pa", "m") | ("MPa", "mm") => "N".into(),
            ("GPa", "mm") => "kN".into(),
            ("MPa", "um") => "uN".into(),
            ("GPa", "um") => "mN".into(),
            ("1", "1") => "1".into(),
            (s, l) => format!("{s}*{l}^2"),
        }
    }
    /// Energy unit = force x length.
    pub fn energy(&self) -> String {
        match (self.force().as_str(), self.length.as_str()) {
            ("N", "m") => "J".into(),
            ("N", "mm") => "mJ".into(),
            ("1", "1") => "1".into(),
            (f, l) => format!("{f}*{l}"),
        }
    }
    /// Work of adhesion unit = energy / area = stress x length.
    pub fn surface_energy(&self) -> String {
        match (self.stress.as_str(), self.length.as_str()) {
            ("Pa", "m") => "J/m^2".into(),
            ("1", "1") => "1".into(),
            (s, l) => format!("{s}*{l}"),
        }
    }
    /// Stiffness unit = force / length = stress x length.
    pub fn stiffness(&self) -> String {
        match (self.stress.as_str(), self.length.as_str()) {
            ("Pa", "m") => "N/m".into(),
            ("MPa", "mm") => "N/mm".into(),
            ("1", "1") => "1".into(),
            (s, l) => format!("{s}*{l}"),
        }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Young's modulus; `inf` for a rigid body.
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
}

/// Either effective moduli directly (`e_star`, optional `g_star`) or the two bodies.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub e_star: Option<f64>,
    pub g_star: Option<f64>,
    pub indenter: Option<BodySpec>,
    pub substrate: Option<BodySpec>,
}

impl MaterialSpec {
    pub fn build(&self) -> Result<Material> {
        match (self.e_star, &self.indenter, &self.substrate) {
            (Some(e), None, None) => match self.g_star {
                Some(g) => Material::from_moduli(e, g),
                None => Material::from_e_star(e),
            }
            .ctx("material"),
            (None, Some(a), Some(b)) => {
                if self.g_star.is_some() {
                    return Err(CompareError::Scene(
                        "material: give either e_star/g_star or indenter+substrate, not both"
                            .into(),
                    ));
                }
                let a =
                    ElasticBody::new(a.youngs_modulus, a.poisson_ratio).ctx("material.indenter")?;
                let b = ElasticBody::new(b.youngs_modulus, b.poisson_ratio)
                    .ctx("material.substrate")?;
                Material::from_bodies(a, b).ctx("material")
            }
            _ => Err(CompareError::Scene(
                "material: give either e_star (and optionally g_star) or both [material.indenter] \
                 and [material.substrate]"
                    .into(),
            )),
        }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// z = c r^n (Eq. 12), any real n > 0.
    PowerLaw { c: f64, n: f64 },
    /// Sphere of radius R (paraboloid z = r^2/(2R)).
    Sphere { radius: f64 },
    /// Cone z = r tan(theta); `slope` = tan(theta).
    Cone { slope: f64 },
    /// Flattened sphere (Eq. 22): flat of radius `flat_radius`, then a paraboloid.
    FlattenedSphere { radius: f64, flat_radius: f64 },
    /// Piecewise-linear table: two-column CSV `file` (r, z; relative to the scene) or
    /// inline arrays `r` and `z`.
    Table {
        file: Option<String>,
        r: Option<Vec<f64>>,
        z: Option<Vec<f64>>,
    },
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileSpec {
    /// Shapes summed into one profile (may be empty for a flat punch).
    #[serde(default)]
    pub shapes: Vec<ShapeSpec>,
    /// Radius of the cylindrical punch carrying the profile (flat punch: no shapes).
    pub rim: Option<f64>,
}

impl ProfileSpec {
    pub fn build(&self, base_dir: Option<&Path>) -> Result<Profile> {
        let mut shapes = Vec::new();
        for (i, s) in self.shapes.iter().enumerate() {
            let ctx = format!("profile.shapes[{i}]");
            shapes.push(match s {
                ShapeSpec::PowerLaw { c, n } => Shape::power_law(*c, *n).ctx(ctx)?,
                ShapeSpec::Sphere { radius } => Shape::paraboloid(*radius).ctx(ctx)?,
                ShapeSpec::Cone { slope } => Shape::cone(*slope).ctx(ctx)?,
                ShapeSpec::FlattenedSphere {
                    radius,
                    flat_radius,
                } => Shape::flattened_paraboloid(*radius, *flat_radius).ctx(ctx)?,
                ShapeSpec::Table { file, r, z } => {
                    let (r, z) = match (file, r, z) {
                        (Some(f), None, None) => {
                            mrd::topography::read_profile_csv(&resolve(base_dir, f)).ctx(&ctx)?
                        }
                        (None, Some(r), Some(z)) => (r.clone(), z.clone()),
                        _ => {
                            return Err(CompareError::Scene(format!(
                                "{ctx}: a table needs either `file` or both `r` and `z`"
                            )))
                        }
                    };
                    Shape::Table(TabulatedProfile::new(r, z).ctx(ctx)?)
                }
            });
        }
        Profile::new(shapes, self.rim).ctx("profile")
    }
}

/// How a force-depth curve is driven.
#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Drive {
    #[default]
    Depth,
    Force,
}

#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ControlSpec {
    #[default]
    Force,
    Displacement,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A memo makes its value once per key and type, keeps no failure, and is shared by
    /// the clones of a context.
    #[test]
    fn a_memo_makes_each_value_once() {
        let ctx = Context {
            origin: "test".into(),
            units: Units::default(),
            material: Material::from_e_star(1.0).unwrap(),
            profile: None,
            base_dir: None,
            memo: Memo::default(),
        };
        let made = std::cell::Cell::new(0);
        let make = || {
            made.set(made.get() + 1);
            Ok(vec![1.0, 2.0])
        };
        let a = ctx.memo("map", make).unwrap();
        let b = ctx.clone().memo("map", make).unwrap();
        assert!(Arc::ptr_eq(&a, &b) && made.get() == 1);
        let failed: Result<Arc<f64>> = ctx.memo("bad", || Err(CompareError::Scene("no".into())));
        assert!(failed.is_err());
        assert_eq!(*ctx.memo("bad", || Ok(2.0)).unwrap(), 2.0);
    }
}
