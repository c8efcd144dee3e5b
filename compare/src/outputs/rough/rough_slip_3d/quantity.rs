//! One compared quantity of `rough_slip_3d` (its 3D value per realisation, MRD's law, its
//! scale and unit), what the tables and the figures share.

use super::runs::Run3d;
use crate::experiment::tangential_map::Mapping;

/// A 3D value of one realisation at (Poisson index, x index).
pub(super) type Value3d = fn(&Run3d, usize, usize) -> f64;

/// Rows of a table per case (hurst, roughness).
pub(super) type CaseRows<'t> = Vec<((f64, f64), Vec<&'t Vec<f64>>)>;

/// One compared quantity at the `xs` (fractions or amplitudes of mu F_N): its 3D value
/// per realisation (Poisson index k, x index j), MRD's law on a normal curve
/// (E*/G* = ratio), and the scale the table divides both by.
pub(super) struct Quantity<'a> {
    pub(super) table: &'static str,
    pub(super) stem: &'static str,
    pub(super) x_name: &'static str,
    pub(super) x_label: &'static str,
    pub(super) xs: &'a [f64],
    pub(super) three: Value3d,
    pub(super) law: fn(&Mapping, f64, usize) -> f64,
    pub(super) scale: f64,
    pub(super) unit: &'static str,
    /// A further 3D column (name, value per realisation), e.g. the stick fraction.
    pub(super) extra: Option<(&'static str, Value3d)>,
}

/// Below this (in the table's scaled units: mu d_0, mu^2 F_N d_0) a value is zero
/// within the solvers' tolerance: the energy per cycle of a contact whose normal curve
/// is linear over the cycle (a smooth punch; MRD's punch whose springs all touch) is a
/// difference of equal terms, left at 1e-17 by MRD's exact springs and at up to 1e-7 by
/// the 3D normal solves; the smallest energies the studies resolve are 1e-4.
pub(super) const ZERO: f64 = 1e-6;
