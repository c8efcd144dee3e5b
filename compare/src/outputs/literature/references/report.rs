//! `references`' report: one row per computation, its deviation and verdict.

use super::{Computed, Published, References};
use crate::report::{Section, Table};

impl References {
    /// The table (one row per computation), its Markdown twin with the citations, the
    /// scalars, and a failure per computation that does not hold.
    pub(super) fn report(&self, out: &mut Section, rows: &[(usize, &Published, Computed)]) {
        let mut t = Table::new(
            "references",
            &[
                "reference [1]",
                "method [0 MRD, 1 3D, 2 3D cohesive]",
                "published [1]",
                "uncertainty [1]",
                "workbench [1]",
                "deviation_rel [1]",
                "allowed_rel [1]",
                "holds [0/1]",
            ],
        );
        t.notes.push(
            "reference: the row of compare/data/references.toml (from 1); holds when |workbench - published| <= k u + tolerance |published| (k = 1 for a bound, 2 for a standard uncertainty); a computation that does not hold fails the run unless its cause is diagnosed (references.md gives it)".into(),
        );
        let mut md = String::from(
            "| reference | quantity | published | method | workbench | deviation | allowed | verdict | resolution | source |\n|---|---|---|---|---|---|---|---|---|---|\n",
        );
        for (k, r, c) in rows {
            let allowed = r.coverage() * r.uncertainty + c.tolerance * r.value.abs();
            let dev = c.value - r.value;
            let holds = dev.abs() <= allowed;
            t.push(vec![
                (*k + 1) as f64,
                match c.method {
                    "MRD" => 0.0,
                    "3D" => 1.0,
                    _ => 2.0,
                },
                r.value,
                r.uncertainty,
                c.value,
                dev / r.value,
                allowed / r.value.abs(),
                holds as u8 as f64,
            ]);
            let key = format!(
                "{}_{}",
                r.id.replace('-', "_"),
                c.method.to_lowercase().replace(' ', "_")
            );
            out.scalar(key.clone(), c.value);
            out.scalar(format!("{key}_holds"), holds as u8 as f64);
            let published = if r.uncertainty > 0.0 {
                format!("{} +/- {} ({})", r.value, r.uncertainty, r.uncertainty_kind)
            } else {
                format!("{} (exact)", r.value)
            };
            let doi = if r.doi.is_empty() {
                String::new()
            } else {
                format!(", doi:{}", r.doi)
            };
            md.push_str(&format!(
                "| {} | {} | {published} | {} | {:.6} | {:+.2e} | {:.1e} | {} | {} | {}{doi}, {} |\n",
                r.id,
                r.quantity,
                c.method,
                c.value,
                dev / r.value,
                allowed / r.value.abs(),
                match (holds, c.diagnosis) {
                    (true, _) => "holds".to_string(),
                    (false, None) => "does not hold".to_string(),
                    (false, Some(why)) => format!("does not hold (diagnosed: {why})"),
                },
                c.why,
                r.citation,
                r.location,
            ));
            if !holds && c.diagnosis.is_none() {
                out.failures.push(format!(
                    "{} by {}: {} against the published {published}, outside the allowed {allowed:.2e} ({})",
                    r.id, c.method, c.value, c.why
                ));
            }
        }
        out.files.push(("references.md".into(), md.into_bytes()));
        out.tables.push(t);
    }
}
