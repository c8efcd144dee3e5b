//! The Cerruti compliance of the periodic half-space (the tangential operator).

use super::compliance::TangentialCompliance;
use crate::error::{BemError, Result};
use crate::fft::Fft2;
use crate::operator::spectral_grid;

/// The Cerruti compliance (x traction to x displacement) of a periodic half-space of
/// shear modulus `G` and Poisson's ratio `nu` on an `ny x nx` grid of size `lx x ly`.
pub struct CerrutiPeriodic {
    pub(super) nx: usize,
    pub(super) ny: usize,
    pub(super) lx: f64,
    pub(super) ly: f64,
    pub(super) shear_modulus: f64,
    pub(super) poisson: f64,
    pub(super) fft: Fft2,
    /// The xx entry of the tensor (module docs of [`super`]).
    symbol: Vec<f64>,
    /// Its inverse `G |k| / (1 - nu kx^2 / |k|^2)` (0 at k = 0): the partial-slip
    /// iteration's preconditioner, exact on the whole grid.
    inverse: Vec<f64>,
}

impl CerrutiPeriodic {
    pub fn new(
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        shear_modulus: f64,
        poisson: f64,
    ) -> Result<Self> {
        check_grid((nx, ny, lx, ly), shear_modulus, poisson)?;
        let g = shear_modulus;
        let symbol = spectral_grid(nx, ny, lx, ly, |kx, ky| {
            let k2 = kx * kx + ky * ky;
            if k2 == 0.0 {
                0.0
            } else {
                (1.0 - poisson * kx * kx / k2) / (g * k2.sqrt())
            }
        });
        Ok(Self {
            nx,
            ny,
            lx,
            ly,
            shear_modulus,
            poisson,
            fft: Fft2::new(nx, ny),
            symbol,
            inverse: inverse_symbol((nx, ny, lx, ly), shear_modulus, poisson),
        })
    }
}

impl TangentialCompliance for CerrutiPeriodic {
    fn grid(&self) -> (usize, usize, f64, f64) {
        (self.nx, self.ny, self.lx, self.ly)
    }

    fn is_periodic(&self) -> bool {
        true
    }

    /// `u = K_t q` (zero mean).
    fn apply(&mut self, q: &[f64], u: &mut [f64]) {
        self.fft.convolve(q, (self.nx, self.ny), &self.symbol, u);
    }

    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        self.fft.convolve(r, (self.nx, self.ny), &self.inverse, z);
        true
    }
}

/// The inverse of the periodic Cerruti operator's symbol (its xx entry) on the grid
/// `(nx, ny, lx, ly)` (as [`TangentialCompliance::grid`] gives it):
/// `G |k| / (1 - nu kx^2 / |k|^2)`, 0 at `k = 0`.
pub(super) fn inverse_symbol(
    (nx, ny, lx, ly): (usize, usize, f64, f64),
    shear_modulus: f64,
    poisson: f64,
) -> Vec<f64> {
    spectral_grid(nx, ny, lx, ly, |kx, ky| {
        let k2 = kx * kx + ky * ky;
        if k2 == 0.0 {
            0.0
        } else {
            shear_modulus * k2.sqrt() / (1.0 - poisson * kx * kx / k2)
        }
    })
}

/// The grid `(nx, ny, lx, ly)`, shear modulus and Poisson's ratio of a tangential
/// operator, checked.
pub(super) fn check_grid(
    (nx, ny, lx, ly): (usize, usize, f64, f64),
    shear_modulus: f64,
    poisson: f64,
) -> Result<()> {
    if nx < 2 || ny < 2 {
        return Err(BemError::InvalidInput(format!(
            "tangential grid {nx} x {ny}: at least 2 x 2 cells"
        )));
    }
    // The normal operators' range: cell areas and moduli of products stay finite.
    let (lo, hi) = crate::operator::SCALE_RANGE;
    if !((lo..=hi).contains(&lx) && (lo..=hi).contains(&ly)) {
        return Err(BemError::InvalidInput(format!(
            "tangential grid size {lx:e} x {ly:e} must lie in [{lo:e}, {hi:e}]"
        )));
    }
    if !(lo..=hi).contains(&shear_modulus) {
        return Err(BemError::InvalidInput(format!(
            "shear modulus G = {shear_modulus:e} must lie in [{lo:e}, {hi:e}]"
        )));
    }
    if !(0.0..=0.5).contains(&poisson) {
        return Err(BemError::InvalidInput(format!(
            "Poisson's ratio nu = {poisson} must lie in [0, 0.5]"
        )));
    }
    Ok(())
}
