//! A family's rigid surface: the caller's heights and mask checked and put in the gap's
//! terms.

use crate::error::{BemError, Result};
use crate::operator::Preconditioner;

/// The rigid surface of a family from the caller's heights and mask, checked (the normal
/// solver's conventions).
pub(crate) struct RigidSurface {
    /// `max(h) - h`, the max over the cells that may touch [length].
    pub z: Vec<f64>,
    /// The cells that may touch.
    pub domain: Vec<bool>,
    /// The rms of z over the domain [length].
    pub rms: f64,
    /// The largest z over the domain: the approach of complete contact on a rigid
    /// foundation [length].
    pub relief: f64,
}

/// Reads `heights` (`ny x nx`, finite) and the optional `mask` onto `op`'s grid.
pub(crate) fn rigid_surface<C: Preconditioner>(
    op: &C,
    heights: &[f64],
    mask: Option<&[bool]>,
) -> Result<RigidSurface> {
    let n = op.cells();
    if heights.len() != n {
        return Err(BemError::InvalidInput(format!(
            "heights have {} values for a grid of {} x {} cells",
            heights.len(),
            op.nx(),
            op.ny()
        )));
    }
    if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
        return Err(BemError::InvalidInput(format!(
            "heights[{i}] = {} must be finite",
            heights[i]
        )));
    }
    let domain: Vec<bool> = match mask {
        Some(m) if m.len() != n => {
            return Err(BemError::InvalidInput(format!(
                "mask has {} values for a grid of {n} cells",
                m.len()
            )))
        }
        Some(m) => m.to_vec(),
        None => vec![true; n],
    };
    let cells = domain.iter().filter(|d| **d).count();
    if cells == 0 {
        return Err(BemError::InvalidInput(
            "the mask leaves no cell that may touch".into(),
        ));
    }
    let top = (0..n)
        .filter(|&i| domain[i])
        .map(|i| heights[i])
        .fold(f64::NEG_INFINITY, f64::max);
    let z: Vec<f64> = heights.iter().map(|h| top - h).collect();
    let mean = (0..n).filter(|&i| domain[i]).map(|i| z[i]).sum::<f64>() / cells as f64;
    let rms = ((0..n)
        .filter(|&i| domain[i])
        .map(|i| (z[i] - mean).powi(2))
        .sum::<f64>()
        / cells as f64)
        .sqrt();
    let relief = (0..n)
        .filter(|&i| domain[i])
        .map(|i| z[i])
        .fold(0.0, f64::max);
    Ok(RigidSurface {
        z,
        domain,
        rms,
        relief,
    })
}
