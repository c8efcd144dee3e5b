//! The getters that every class solving on a grid shares: `shape`, `size` and
//! `periodic`, read from the class's fields of those names.

/// A bool as Python writes it, for `__repr__`.
pub fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

/// `grid_getters!(Class)`: a second `#[pymethods]` block of `Class` (pyo3's
/// `multiple-pymethods`) with the three getters.
macro_rules! grid_getters {
    ($name:ident) => {
        #[pymethods]
        impl $name {
            /// (ny, nx)
            #[getter]
            fn shape(&self) -> (usize, usize) {
                self.shape
            }
            /// (lx, ly) [length]
            #[getter]
            fn size(&self) -> (f64, f64) {
                self.size
            }
            /// Whether the half-space repeats with the cell (else the free half-space).
            #[getter]
            fn periodic(&self) -> bool {
                self.periodic
            }
        }
    };
}
