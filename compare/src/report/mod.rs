//! What a run produces and how it is written: per-output [`Section`]s of named tables,
//! figures, scalar results and extra files, collected into a [`Report`] and written as a
//! report folder ([`write`]): one CSV per table ([`csv`]), one PNG per figure
//! ([`plot`]) and `summary.json`.

pub mod csv;
pub mod figure;
pub mod plot;
pub mod table;
pub mod write;

pub use figure::{Figure, Series, Style};
pub use table::Table;

use crate::plan::{Plan, Stage};
use serde_json::{Map, Value};
use std::time::Instant;

/// Tool name and version written into every output.
pub fn tool_version() -> String {
    format!("mrdw {}", env!("CARGO_PKG_VERSION"))
}

/// `x` as a file name or a title shows a parameter: as `Display` writes it where that is
/// short (0.7, 1.25), in the shortest scientific form where it would run to dozens of
/// digits (1e-300, not 0.000...1), which a file name could not hold.
pub fn number_label(x: f64) -> String {
    let s = x.to_string();
    if s.len() > 12 {
        format!("{x:e}")
    } else {
        s
    }
}

/// Provenance written at the top of every CSV and into summary.json.
#[derive(Debug, Clone)]
pub struct Provenance {
    pub tool: String,
    pub scene_name: String,
    pub scene_origin: String,
    pub scene_text: String,
    pub seed: Option<u64>,
}

/// The results of one output: its tables, figures, scalars and files, and the stages
/// it ran (recorded by [`Section::stage`]).
#[derive(Debug)]
pub struct Section {
    pub kind: &'static str,
    /// `kind`, or `kind_k` for the k-th output of that kind in the scene: prefixes the
    /// output's results in summary.json.
    pub label: String,
    pub tables: Vec<Table>,
    pub figures: Vec<Figure>,
    /// (key, value), stored in summary.json as `label.key`.
    pub scalars: Vec<(String, Value)>,
    /// Extra files (name, bytes), e.g. requested fields as .npy.
    pub files: Vec<(String, Vec<u8>)>,
    pub warnings: Vec<String>,
    /// Requested results that could not be computed (e.g. unconverged solves), one line
    /// each: the report is still written, and the run fails visibly.
    pub failures: Vec<String>,
    /// Stages that ran, in order, with their wall time [s].
    pub ran: Vec<(Stage, f64)>,
}

impl Section {
    pub fn new(kind: &'static str, label: impl Into<String>) -> Self {
        Self {
            kind,
            label: label.into(),
            tables: Vec::new(),
            figures: Vec::new(),
            scalars: Vec::new(),
            files: Vec::new(),
            warnings: Vec::new(),
            failures: Vec::new(),
            ran: Vec::new(),
        }
    }

    /// Runs one stage of the computation: records it as run and adds its wall time.
    pub fn stage<T>(&mut self, stage: Stage, f: impl FnOnce() -> T) -> T {
        let t0 = Instant::now();
        let out = f();
        let dt = t0.elapsed().as_secs_f64();
        match self.ran.iter_mut().find(|(s, _)| *s == stage) {
            Some((_, t)) => *t += dt,
            None => self.ran.push((stage, dt)),
        }
        out
    }

    /// Runs stages that execute interleaved (e.g. each rough punch is synthesised,
    /// solved and its stiffness computed in one task, tasks on several threads): records
    /// them all and shares the wall time among them in proportion to the time each spent
    /// on all threads ([`clock::time`] inside the tasks), so that the stages' times add
    /// up to the wall time; where the tasks timed nothing (checkpoints read back), the
    /// first stage takes it.
    pub fn stages_together<T>(&mut self, stages: &[Stage], f: impl FnOnce() -> T) -> T {
        clock::take();
        let t0 = Instant::now();
        let out = f();
        let wall = t0.elapsed().as_secs_f64();
        let spent = clock::take();
        let timed: f64 = stages.iter().map(|s| spent[*s as usize]).sum();
        for (k, &s) in stages.iter().enumerate() {
            let share = if timed > 0.0 {
                spent[s as usize] / timed
            } else if k == 0 {
                1.0
            } else {
                0.0
            };
            self.stage(s, || ());
            if let Some((_, t)) = self.ran.iter_mut().find(|(r, _)| *r == s) {
                *t += share * wall;
            }
        }
        out
    }

    /// The stages that ran, in order.
    pub fn stages(&self) -> Vec<Stage> {
        self.ran.iter().map(|(s, _)| *s).collect()
    }

    /// A scalar result, stored as `label.key`.
    pub fn scalar(&mut self, key: impl Into<String>, value: f64) {
        self.value(key, serde_json::json!(value));
    }

    /// Any JSON result, stored as `label.key`.
    pub fn value(&mut self, key: impl Into<String>, value: Value) {
        let key = key.into();
        match self.scalars.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => *v = value,
            None => self.scalars.push((key, value)),
        }
    }

    pub fn warn(&mut self, w: impl Into<String>) {
        self.warnings.push(w.into());
    }
}

/// Everything a run produces: the plan it declared and one section per output.
#[derive(Debug, Default)]
pub struct Report {
    pub plan: Plan,
    pub sections: Vec<Section>,
}

impl Report {
    /// Every stage that ran, once, in first-use order.
    pub fn stages(&self) -> Vec<String> {
        let mut all: Vec<String> = Vec::new();
        for s in self.sections.iter().flat_map(|s| s.stages()) {
            if !all.iter().any(|n| n == s.name()) {
                all.push(s.name().into());
            }
        }
        all
    }

    /// All results keyed `label.key`.
    pub fn results(&self) -> Map<String, Value> {
        let mut m = Map::new();
        for sec in &self.sections {
            for (k, v) in &sec.scalars {
                m.insert(format!("{}.{k}", sec.label), v.clone());
            }
        }
        m
    }

    /// Warnings of all outputs, each once.
    pub fn warnings(&self) -> Vec<String> {
        let mut w: Vec<String> = Vec::new();
        for s in self.sections.iter().flat_map(|s| &s.warnings) {
            if !w.contains(s) {
                w.push(s.clone());
            }
        }
        w
    }

    /// Results that could not be computed, prefixed with their output's label.
    pub fn failures(&self) -> Vec<String> {
        self.sections
            .iter()
            .flat_map(|s| s.failures.iter().map(move |f| format!("{}: {f}", s.label)))
            .collect()
    }

    /// Makes every table, figure and file name unique across the report by suffixing
    /// the second and later uses of a name with _2, _3, ... (in output order).
    pub fn dedupe_names(&mut self) {
        // Files keep their extension: f.npy -> f_2.npy.
        fn fix<'a>(names: impl Iterator<Item = &'a mut String>, files: bool) {
            let mut seen: Vec<String> = Vec::new();
            for n in names {
                let base = n.clone();
                let mut k = 1;
                while seen.contains(n) {
                    k += 1;
                    *n = match base.rsplit_once('.') {
                        Some((stem, ext)) if files && !ext.is_empty() && !stem.is_empty() => {
                            format!("{stem}_{k}.{ext}")
                        }
                        _ => format!("{base}_{k}"),
                    };
                }
                seen.push(n.clone());
            }
        }
        fix(
            self.sections
                .iter_mut()
                .flat_map(|s| s.tables.iter_mut().map(|t| &mut t.name)),
            false,
        );
        fix(
            self.sections
                .iter_mut()
                .flat_map(|s| s.figures.iter_mut().map(|f| &mut f.name)),
            false,
        );
        fix(
            self.sections
                .iter_mut()
                .flat_map(|s| s.files.iter_mut().map(|f| &mut f.0)),
            true,
        );
    }

    pub fn tables(&self) -> impl Iterator<Item = &Table> {
        self.sections.iter().flat_map(|s| &s.tables)
    }
    pub fn figures(&self) -> impl Iterator<Item = &Figure> {
        self.sections.iter().flat_map(|s| &s.figures)
    }
    pub fn files(&self) -> impl Iterator<Item = &(String, Vec<u8>)> {
        self.sections.iter().flat_map(|s| &s.files)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_labels_stay_short() {
        assert_eq!(number_label(0.7), "0.7");
        assert_eq!(number_label(-0.25), "-0.25");
        assert_eq!(number_label(1e-300), "1e-300");
        assert_eq!(number_label(1e300), "1e300");
        assert_eq!(number_label(0.123456789012345), "1.23456789012345e-1");
    }

    #[test]
    fn names_are_unique_and_results_prefixed() {
        let mut a = Section::new("bem_contact", "bem_contact");
        a.tables.push(Table::new("t", &[] as &[&str]));
        a.files.push(("f.npy".into(), vec![]));
        a.scalar("x", 1.0);
        a.stage(Stage::Bem3d, || ());
        let mut b = Section::new("bem_contact", "bem_contact_2");
        b.tables.push(Table::new("t", &[] as &[&str]));
        b.files.push(("f.npy".into(), vec![]));
        b.scalar("x", 2.0);
        b.stage(Stage::Bem3d, || ());
        b.stage(Stage::Bem3dStiffness, || ());
        b.stage(Stage::Bem3d, || ());
        let mut r = Report {
            sections: vec![a, b],
            ..Default::default()
        };
        r.dedupe_names();
        let t: Vec<&str> = r.tables().map(|t| t.name.as_str()).collect();
        assert_eq!(t, ["t", "t_2"]);
        let f: Vec<&str> = r.files().map(|f| f.0.as_str()).collect();
        assert_eq!(f, ["f.npy", "f_2.npy"]);
        assert_eq!(r.results()["bem_contact_2.x"], 2.0);
        assert_eq!(r.stages(), ["bem3d", "bem3d_stiffness"]);
        assert_eq!(
            r.sections[1].stages(),
            [Stage::Bem3d, Stage::Bem3dStiffness]
        );
    }
}

/// The time spent in each stage by the tasks of interleaved stages, summed over threads
/// ([`Section::stages_together`] reads and resets it). One output runs at a time.
pub mod clock {
    use crate::plan::Stage;
    use std::sync::atomic::{AtomicU64, Ordering};
    use std::time::Instant;

    const SLOTS: usize = 64;
    static NANOS: [AtomicU64; SLOTS] = [const { AtomicU64::new(0) }; SLOTS];

    /// Runs `f`, adding its duration to `stage`.
    pub fn time<T>(stage: Stage, f: impl FnOnce() -> T) -> T {
        let t0 = Instant::now();
        let out = f();
        let nanos = t0.elapsed().as_nanos().min(u64::MAX as u128) as u64;
        NANOS[stage as usize % SLOTS].fetch_add(nanos, Ordering::Relaxed);
        out
    }

    /// Each stage's accumulated seconds (indexed by `Stage as usize`), reset to zero.
    pub(crate) fn take() -> [f64; SLOTS] {
        std::array::from_fn(|k| NANOS[k].swap(0, Ordering::Relaxed) as f64 * 1e-9)
    }
}
