//! CSV text of a table: provenance comment block, one header line with units, values.

use super::table::Table;
use super::Provenance;
use crate::error::{CompareError, Result};
use std::fmt::Write as _;

/// The CSV text of `table`: `#` comment lines (tool, scene, seed, the table's notes,
/// the scene text as given), then the header and one line per row. Non-finite values
/// are an error unless the table allows missing cells (NaN, written empty).
pub(crate) fn csv_text(table: &Table, prov: &Provenance) -> Result<String> {
    let mut s = String::new();
    let _ = writeln!(s, "# {} -- table `{}`", prov.tool, table.name);
    let _ = writeln!(
        s,
        "# scene `{}` from {}",
        prov.scene_name, prov.scene_origin
    );
    let _ = writeln!(
        s,
        "# seed: {}",
        prov.seed
            .map_or("none (deterministic)".to_string(), |v| v.to_string())
    );
    for n in &table.notes {
        let _ = writeln!(s, "# {n}");
    }
    let _ = writeln!(s, "# scene file as given:");
    for line in prov.scene_text.lines() {
        let _ = writeln!(s, "#   {line}");
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&table.columns)
        .map_err(|e| csv_err(&table.name, e))?;
    for row in &table.rows {
        if let Some((j, v)) = row.iter().enumerate().find(|(_, v)| {
            !(v.is_finite()
                || (table.missing_ok && v.is_nan())
                || (table.infinite_ok && **v == f64::INFINITY))
        }) {
            return Err(CompareError::Internal(format!(
                "non-finite value {v} in table `{}` column `{}`",
                table.name, table.columns[j]
            )));
        }
        w.write_record(row.iter().map(|v| {
            if v.is_nan() {
                String::new()
            } else {
                format!("{v:e}")
            }
        }))
        .map_err(|e| csv_err(&table.name, e))?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| CompareError::Internal(e.to_string()))?;
    s.push_str(&String::from_utf8_lossy(&bytes));
    Ok(s)
}

fn csv_err(name: &str, e: csv::Error) -> CompareError {
    CompareError::Internal(format!("writing table {name}: {e}"))
}
