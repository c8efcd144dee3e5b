//! The tangential operator a partial-slip solver iterates with.

/// The tangential compliance (x traction to x displacement) that [`super::PartialSlip`] iterates
/// with: [`super::CerrutiPeriodic`] (a periodic surface; displacements about their mean) or
/// [`super::CerrutiFree`] (the free half-space; absolute displacements, so the shift is the
/// body's rigid displacement).
pub trait TangentialCompliance: Send {
    /// The grid: `(nx, ny, lx, ly)`, cells along x and y and the sizes they span.
    fn grid(&self) -> (usize, usize, f64, f64);
    /// Cells of the grid.
    fn cells(&self) -> usize {
        let (nx, ny, _, _) = self.grid();
        nx * ny
    }
    /// Area of one cell.
    fn cell_area(&self) -> f64 {
        let (nx, ny, lx, ly) = self.grid();
        lx * ly / (nx * ny) as f64
    }
    /// Whether the surface is periodic (the shift is then measured from the mean surface
    /// displacement).
    fn is_periodic(&self) -> bool;
    /// `u = K_t q`.
    fn apply(&mut self, q: &[f64], u: &mut [f64]);
    /// `z = M r` with `M` a symmetric positive approximation of the operator's inverse
    /// (up to a positive factor), for the partial-slip iteration's directions; returns
    /// whether the operator has one (without, `z` is left as it is and the iteration
    /// runs unpreconditioned).
    fn precondition(&mut self, _r: &[f64], _z: &mut [f64]) -> bool {
        false
    }
}

/// A boxed operator, for callers that choose the half-space at run time.
impl<T: TangentialCompliance + ?Sized> TangentialCompliance for Box<T> {
    fn grid(&self) -> (usize, usize, f64, f64) {
        (**self).grid()
    }
    fn is_periodic(&self) -> bool {
        (**self).is_periodic()
    }
    fn apply(&mut self, q: &[f64], u: &mut [f64]) {
        (**self).apply(q, u)
    }
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        (**self).precondition(r, z)
    }
}
