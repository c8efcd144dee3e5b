//! A body of revolution pressed on the 3D grid: the held normal pressure that the 3D
//! tangential outputs (elastic and viscoelastic partial slip) load tangentially, and the
//! settings (checks and defaults) that an adhesive sphere's 3D cycles share.

use crate::checks::{bad, check_memory, check_tolerance, require_positive};
use crate::error::Result;
use bem3d::{
    ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace, Solution, SolverOptions,
};
use mrd::reference::for_profile;
use mrd::Profile;

pub use bem3d::tangential::equivalent_body;

/// The side of a free grid in the loop of a time integration, in Hertz contact radii: a
/// sphere's tangential runs in time (`ring_down`, `friction_forced`) hold their contact
/// well inside it.
pub const SIDE_IN_RADII: f64 = 2.5;

/// The grid of an axisymmetric 3D contact: `cells` per side over `side` (a length), on
/// the periodic half-space (the side its period) or the free one.
#[derive(Debug, Clone, Copy)]
pub struct AxisymGrid {
    pub cells: usize,
    pub side: f64,
    pub periodic: bool,
}

impl AxisymGrid {
    /// Cell centre `k` (row-major), from the grid's centre.
    fn at(&self, k: usize) -> (f64, f64) {
        let (n, l) = (self.cells, self.side);
        let h = l / n as f64;
        let x = ((k % n) as f64 + 0.5) * h - 0.5 * l;
        let y = ((k / n) as f64 + 0.5) * h - 0.5 * l;
        (x, y)
    }

    /// The profile's heights on the grid, centred: a sphere in its own arithmetic, other
    /// bodies from the profile with cells beyond its reach (a punch's rim, a table's
    /// end) masked out.
    pub fn heights(&self, profile: &Profile) -> (Vec<f64>, Option<Vec<bool>>) {
        let n = self.cells;
        match for_profile::sphere_radius(profile) {
            Some(radius) => (
                (0..n * n)
                    .map(|k| {
                        let (x, y) = self.at(k);
                        -(x * x + y * y) / (2.0 * radius)
                    })
                    .collect(),
                None,
            ),
            None => {
                let reach = profile.max_contact_radius();
                let r = |k: usize| self.at(k).0.hypot(self.at(k).1);
                let mask: Vec<bool> = (0..n * n).map(|k| r(k) < reach).collect();
                let z = (0..n * n)
                    .map(|k| if mask[k] { -profile.z(r(k)) } else { 0.0 })
                    .collect();
                (z, Some(mask))
            }
        }
    }

    /// The profile pressed to `force` on a half-space of modulus `e_star`.
    pub fn press(
        &self,
        profile: &Profile,
        e_star: f64,
        force: f64,
        opts: &SolverOptions,
    ) -> bem3d::Result<Solution> {
        let (z, mask) = self.heights(profile);
        let (n, l) = (self.cells, self.side);
        if self.periodic {
            let op = PeriodicHalfSpace::new(n, n, l, l, e_star);
            ContactSolver::new(op, &z, mask)?.solve(Load::Force(force), opts, None)
        } else {
            let op = NonPeriodicHalfSpace::try_new(n, n, l, l, e_star)?;
            ContactSolver::new(op, &z, mask)?.solve(Load::Force(force), opts, None)
        }
    }
}

/// The grid's side over the contact diameter of an adhesive sphere's 3D cycle, unless
/// the scene gives `extent`.
pub fn default_adhesive_extent() -> f64 {
    1.25
}

/// Approach steps of an adhesive sphere's loading, unless the scene gives `steps`.
pub fn default_adhesive_steps() -> usize {
    100
}

/// Checks the settings an adhesive sphere's 3D cycles share (the JKR-limit and the
/// cohesive outputs): the work of adhesion, the deepest approach, the refinement ladder
/// (and the memory of its finest grid), the grid's extent, the steps and the tolerance.
pub fn check_adhesive_cycle(
    gamma: f64,
    depth_max: f64,
    cells: &[usize],
    extent: f64,
    steps: usize,
    tolerance: f64,
) -> Result<()> {
    require_positive("gamma (work of adhesion)", gamma)?;
    require_positive("depth_max", depth_max)?;
    if cells.is_empty() || cells.iter().any(|n| !(16..=2048).contains(n)) {
        return bad(format!(
            "cells = {cells:?}: give grid sizes in 16..=2048, coarse to fine"
        ));
    }
    if cells.windows(2).any(|w| w[1] <= w[0]) {
        return bad(format!(
            "cells = {cells:?} must increase (a refinement ladder)"
        ));
    }
    let n = *cells.last().unwrap_or(&16);
    check_memory(
        (n * n) as f64 * crate::checks::cell_bytes::ADHESION,
        &format!("cells = {n}"),
    )?;
    if !(extent.is_finite() && (1.1..=100.0).contains(&extent)) {
        return bad(format!(
            "extent = {extent}: the grid's side over the contact's diameter at depth_max (the cohesive zone's, for a cohesive law) must lie in [1.1, 100]"
        ));
    }
    if !(2..=10_000).contains(&steps) {
        return bad(format!("steps = {steps} must lie in 2..=10000"));
    }
    check_tolerance(tolerance)
}
