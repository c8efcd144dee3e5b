//! The tangential operator a partial-slip solver iterates with.

/// The tangential compliance (x traction to x displacement) that [`super::PartialSlip`] iterates
/// with: [`super::CerrutiPeriodic`] (a periodic surface; displacements about their mean) or
/// [`super::CerrutiFree`] (the free half-space; absolute displacements, so the shift is the
/// body's rigid displacement).
pub trait TangentialCompliance: Send {
    /// Cells of the grid.
    fn cells(&self) -> usize;
    /// Area of one cell.
    fn cell_area(&self) -> f64;
    /// Whether the surface is periodic (the shift is then measured from the mean surface
    /// displacement).
    fn is_periodic(&self) -> bool;
    /// `u = K_t q`.
    fn apply(&mut self, q: &[f64], u: &mut [f64]);
}

/// A boxed operator, for callers that choose the half-space at run time.
impl<T: TangentialCompliance + ?Sized> TangentialCompliance for Box<T> {
    fn cells(&self) -> usize {
        (**self).cells()
    }
    fn cell_area(&self) -> f64 {
        (**self).cell_area()
    }
    fn is_periodic(&self) -> bool {
        (**self).is_periodic()
    }
    fn apply(&mut self, q: &[f64], u: &mut [f64]) {
        (**self).apply(q, u)
    }
}
