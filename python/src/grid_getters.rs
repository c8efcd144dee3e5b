//! The getters that every class solving on a grid shares: `shape`, `size` and
//! `periodic`, read from the class's field `frame` (a `contact::Frame`).

/// A bool as Python writes it, for `__repr__`.
pub fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

/// `grid_getters!(Class)`: a second `#[pymethods]` block of `Class` (pyo3's
/// `multiple-pymethods`) with the three getters, read from its field `frame`.
macro_rules! grid_getters {
    ($name:ident) => {
        #[pymethods]
        impl $name {
            /// (ny, nx)
            #[getter]
            fn shape(&self) -> (usize, usize) {
                self.frame.shape
            }
            /// (lx, ly) [length]
            #[getter]
            fn size(&self) -> (f64, f64) {
                self.frame.size
            }
            /// Whether the half-space repeats with the cell (else the free half-space).
            #[getter]
            fn periodic(&self) -> bool {
                self.frame.periodic
            }
        }
    };
}
