//! Scene (case) files: what is modelled and which outputs are wanted.
//!
//! A scene is TOML; unknown keys are errors. It declares units, the material, the
//! indenter profile (together: the [`Context`]) and a list of `[[outputs]]`, each parsed
//! by its kind from the registry ([`crate::registry::KINDS`]) and validated before
//! anything runs. The format is documented with examples in `cases/README.md`.

use crate::context::{Context, MaterialSpec, ProfileSpec, Units};
use crate::error::{CompareError, Result};
use crate::output::Output;
use crate::registry;
use serde::Deserialize;
use std::path::Path;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: String,
    title: Option<String>,
    description: Option<String>,
    #[serde(default)]
    units: Units,
    material: MaterialSpec,
    profile: Option<ProfileSpec>,
    outputs: Vec<toml::Spanned<toml::Table>>,
}

/// One requested output: its kind, its label (`kind`, or `kind_k` for the k-th output
/// of that kind) and its parameters.
#[derive(Debug)]
pub struct Entry {
    pub kind: &'static str,
    pub label: String,
    pub output: Box<dyn Output>,
}

/// A parsed and validated scene, with its source text for provenance.
#[derive(Debug)]
pub struct Scene {
    /// Short name; the default output folder is `reports/<name>/`.
    pub name: String,
    pub title: Option<String>,
    pub description: Option<String>,
    pub source: String,
    pub context: Context,
    pub outputs: Vec<Entry>,
}

impl Scene {
    /// Parses TOML text; `base_dir` resolves files named by the scene (None for
    /// embedded scenes: the current folder).
    pub fn parse(source: &str, origin: &str, base_dir: Option<&Path>) -> Result<Self> {
        let file: SceneFile = toml::from_str(source).map_err(|e| {
            let (line, col) = e
                .span()
                .map(|s| line_col(source, s.start))
                .unwrap_or((0, 0));
            CompareError::Scene(format!(
                "{origin}:{line}:{col}: {}",
                e.message().lines().next().unwrap_or("invalid TOML").trim()
            ))
        })?;
        if file.name.trim().is_empty()
            || !file
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(CompareError::Scene(format!(
                "{origin}: name `{}` must be non-empty and use only letters, digits, '-' and '_'",
                file.name
            )));
        }
        if file.outputs.is_empty() {
            return Err(CompareError::Scene(format!(
                "{origin}: no [[outputs]] requested: nothing to compute"
            )));
        }
        let context = Context {
            origin: origin.to_string(),
            units: file.units.clone(),
            material: file.material.build()?,
            profile: file
                .profile
                .as_ref()
                .map(|p| p.build(base_dir))
                .transpose()?,
            base_dir: base_dir.map(Path::to_path_buf),
            memo: Default::default(),
        };
        let mut entries: Vec<Entry> = Vec::new();
        for (i, spanned) in file.outputs.iter().enumerate() {
            let (line, col) = line_col(source, spanned.span().start);
            let at = format!("{origin}:{line}:{col}: outputs[{i}]");
            let mut table = spanned.get_ref().clone();
            let kind_name = match table.remove("kind") {
                Some(toml::Value::String(k)) => k,
                Some(_) => {
                    return Err(CompareError::Scene(format!(
                        "{at}: `kind` must be a string"
                    )))
                }
                None => {
                    return Err(CompareError::Scene(format!(
                        "{at}: missing `kind` (one of: {})",
                        kind_names()
                    )))
                }
            };
            let kind = registry::kind(&kind_name).ok_or_else(|| {
                CompareError::Scene(format!(
                    "{at}: unknown output kind `{kind_name}` (one of: {})",
                    kind_names()
                ))
            })?;
            let output = kind
                .parse(toml::Value::Table(table))
                .map_err(|m| CompareError::Scene(format!("{at} ({}): {m}", kind.name)))?;
            output.validate(&context).map_err(|e| {
                CompareError::Scene(format!("{origin}: outputs[{i}] ({}): {e}", kind.name))
            })?;
            let k = 1 + entries.iter().filter(|e| e.kind == kind.name).count();
            let label = if k == 1 {
                kind.name.to_string()
            } else {
                format!("{}_{k}", kind.name)
            };
            entries.push(Entry {
                kind: kind.name,
                label,
                output,
            });
        }
        Ok(Self {
            name: file.name,
            title: file.title,
            description: file.description,
            source: source.to_string(),
            context,
            outputs: entries,
        })
    }

    /// Loads a scene from a path.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(crate::error::io_err(format!(
            "reading scene {}",
            path.display()
        )))?;
        Self::parse(&text, &path.display().to_string(), path.parent())
    }

    /// A scene by name, as the command line takes it: an existing file, else an embedded
    /// scene (see [`crate::scenes`]).
    pub fn open(name: &str) -> Result<Self> {
        let path = Path::new(name);
        // A folder is never a scene: a report folder named like the scene it holds
        // (`mrdw run hertz --out hertz`) must not hide the embedded scene.
        if path.exists() && !path.is_dir() {
            return Self::load(path);
        }
        if let Some(text) = crate::scenes::get(name) {
            return Self::parse(text, &format!("<embedded:{name}>"), None);
        }
        let hint = if path.is_dir() {
            "a folder, not a scene file, and not an embedded scene (see `mrdw scenes`)"
        } else if name.ends_with(".toml") {
            "no such file"
        } else {
            "neither a file nor an embedded scene (see `mrdw scenes`)"
        };
        Err(CompareError::Scene(format!("scene `{name}`: {hint}")))
    }

    /// Where the scene came from (a path, or `<embedded:name>`).
    pub fn origin(&self) -> &str {
        &self.context.origin
    }

    /// Seed recorded in the provenance: the first output that has one.
    pub fn seed(&self) -> Option<u64> {
        self.outputs.iter().find_map(|e| e.output.seed())
    }
}

fn kind_names() -> String {
    registry::KINDS
        .iter()
        .map(|k| k.name)
        .collect::<Vec<_>>()
        .join(", ")
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map_or(0, |p| p + 1) + 1;
    (line, col)
}
