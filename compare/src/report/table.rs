//! Tables: named columns with units, rows of numbers, read back by column name.

/// A named table; column headers carry units, e.g. `depth [m]`. A column is addressed
/// by its name, the header without the unit (`depth`).
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub name: String,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<f64>>,
    /// Extra comment lines (method, tolerances) written under the provenance block.
    pub notes: Vec<String>,
    /// Undefined values (NaN) are written as empty cells; otherwise they are an error.
    pub missing_ok: bool,
    /// +inf is a legitimate value here (written `inf`), e.g. the stiffness at complete
    /// contact of a periodic surface; otherwise it is an error.
    pub infinite_ok: bool,
}

impl Table {
    pub fn new(name: &str, columns: &[impl AsRef<str>]) -> Self {
        Self {
            name: name.into(),
            columns: columns.iter().map(|c| c.as_ref().to_string()).collect(),
            ..Default::default()
        }
    }

    /// Appends a row (values in column order).
    pub fn push(&mut self, row: Vec<f64>) {
        debug_assert_eq!(row.len(), self.columns.len(), "table {}", self.name);
        self.rows.push(row);
    }

    /// Position of the column called `name` (header `name` or `name [unit]`).
    ///
    /// # Panics
    /// If there is no such column: column names are fixed by the code that builds the
    /// table, so a miss is a bug (every output runs in the test suite).
    pub fn index(&self, name: &str) -> usize {
        self.columns
            .iter()
            .position(|c| {
                c == name
                    || c.strip_prefix(name)
                        .is_some_and(|rest| rest.starts_with(" ["))
            })
            .unwrap_or_else(|| panic!("table `{}` has no column `{name}`", self.name))
    }

    /// Whether a column called `name` exists.
    pub fn has(&self, name: &str) -> bool {
        self.columns.iter().any(|c| {
            c == name
                || c.strip_prefix(name)
                    .is_some_and(|rest| rest.starts_with(" ["))
        })
    }

    /// The values of column `name`.
    pub fn column(&self, name: &str) -> Vec<f64> {
        let j = self.index(name);
        self.rows.iter().map(|r| r[j]).collect()
    }

    /// (x, y) pairs of two columns, rows with non-finite values left out.
    pub fn xy(&self, x: &str, y: &str) -> Vec<(f64, f64)> {
        let (i, j) = (self.index(x), self.index(y));
        self.rows
            .iter()
            .map(|r| (r[i], r[j]))
            .filter(|(a, b)| a.is_finite() && b.is_finite())
            .collect()
    }

    /// Every `stride`-th (x, y) pair for about `n` markers over the table.
    pub fn xy_sampled(&self, x: &str, y: &str, n: usize) -> Vec<(f64, f64)> {
        let stride = (self.rows.len() / n).max(1);
        let (i, j) = (self.index(x), self.index(y));
        self.rows
            .iter()
            .step_by(stride)
            .map(|r| (r[i], r[j]))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_by_name() {
        let mut t = Table::new("t", &["depth [m]", "depth_2 [m]", "flag"]);
        t.push(vec![1.0, 2.0, 0.0]);
        t.push(vec![3.0, f64::NAN, 1.0]);
        assert_eq!(t.index("depth"), 0);
        assert_eq!(t.index("depth_2"), 1);
        assert_eq!(t.index("flag"), 2);
        assert!(t.has("depth") && !t.has("dep"));
        assert_eq!(t.column("depth"), vec![1.0, 3.0]);
        assert_eq!(t.xy("depth", "depth_2"), vec![(1.0, 2.0)]);
        assert_eq!(t.xy_sampled("depth", "flag", 1), vec![(1.0, 0.0)]);
    }

    #[test]
    #[should_panic(expected = "no column `dep`")]
    fn a_missing_column_is_a_bug() {
        Table::new("t", &["depth [m]"]).index("dep");
    }
}
