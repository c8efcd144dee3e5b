//! CSV text of a table: provenance comment block, one header line with units, values.

use super::table::Table;
use super::Provenance;
use crate::error::{CompareError, Result};
use std::fmt::Write as _;

/// The CSV text of `table`: `#` comment lines (tool, scene, seed, the table's notes,
/// the scene text as given), then the header and one line per row. Non-finite values
/// are an error unless the table allows missing cells (NaN, written empty). Counts and
/// flags are written as integers.
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
    let integer: Vec<bool> = table.columns.iter().map(|c| is_integer(c)).collect();
    for row in &table.rows {
        if let Some((j, v)) = row.iter().enumerate().find(|&(j, v)| {
            !(v.is_finite()
                || (table.missing_ok && v.is_nan())
                || (table.infinite_ok && *v == f64::INFINITY))
                || (integer[j] && v.is_finite() && (v.fract() != 0.0 || v.abs() > 9e15))
        }) {
            return Err(CompareError::Internal(format!(
                "value {v} in table `{}` column `{}` is not {}",
                table.name,
                table.columns[j],
                if integer[j] { "an integer" } else { "finite" }
            )));
        }
        w.write_record(row.iter().zip(&integer).map(|(v, &int)| {
            if v.is_nan() {
                String::new()
            } else if int && v.is_finite() {
                format!("{}", *v as i64)
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

/// Columns of counts, flags, indices and codes hold integers and are written as such:
/// units `[count]`, `[cells]`, `[cells a side]`, `[0/1]`, `[index]`, and codes listed in
/// their unit (`[0 MRD, 1 3D]`, `[0 periodic; 1 disc]`).
fn is_integer(header: &str) -> bool {
    ["[count]", "[cells]", "[cells a side]", "[0/1]", "[index]"]
        .iter()
        .any(|u| header.ends_with(u))
        || header
            .rsplit_once('[')
            .is_some_and(|(_, unit)| unit.starts_with("0 ") && unit.ends_with(']'))
}

fn csv_err(name: &str, e: csv::Error) -> CompareError {
    CompareError::Internal(format!("writing table {name}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn prov() -> Provenance {
        Provenance {
            tool: "mrdw test".into(),
            scene_name: "s".into(),
            scene_origin: "o".into(),
            scene_text: "name = \"s\"".into(),
            seed: None,
        }
    }

    #[test]
    fn counts_and_flags_are_integers_and_missing_cells_empty() {
        let mut t = Table::new("t", &["x [m]", "iterations [count]", "converged [0/1]"]);
        t.missing_ok = true;
        t.push(vec![0.5, 34.0, 1.0]);
        t.push(vec![f64::NAN, 7.0, 0.0]);
        let text = csv_text(&t, &prov()).unwrap();
        let data: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
        assert_eq!(
            data,
            [
                "x [m],iterations [count],converged [0/1]",
                "5e-1,34,1",
                ",7,0"
            ]
        );
        // A fraction in a count column is a bug, reported, not rounded.
        t.push(vec![1.0, 3.5, 1.0]);
        assert!(matches!(
            csv_text(&t, &prov()),
            Err(CompareError::Internal(_))
        ));
    }

    #[test]
    fn infinity_only_where_allowed() {
        let mut t = Table::new("t", &["k [N/m]"]);
        t.push(vec![f64::INFINITY]);
        assert!(csv_text(&t, &prov()).is_err());
        t.infinite_ok = true;
        assert!(csv_text(&t, &prov()).unwrap().ends_with("inf\n"));
    }
}
