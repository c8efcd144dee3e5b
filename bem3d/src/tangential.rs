//! Partial slip under a held normal pressure: Coulomb friction on an elastic half-space,
//! periodic ([`CerrutiPeriodic`]) or free ([`CerrutiFree`]), loaded by a tangential force
//! along x (Sections 6 and 7 of the review in 3D; Cattaneo-Mindlin for a sphere); on a
//! viscoelastic half-space under a prescribed shift ([`ViscoelasticSlip`], Section 8,
//! Eqs. 64-65); and the stiffness of a contact held in full stick ([`StickStiffness`]).
//! The model and iteration below are the periodic operator's; the free one differs only
//! in its kernel (its module docs) and in measuring the shift absolutely.
//!
//! **Model.** The normal pressure `p` is given (from [`crate::ContactSolver`] or a closed
//! form) and held: the normal-tangential coupling vanishes for nu = 0.5 or elastically
//! similar bodies, the default case of the paper's elastomers; for other pairs it is
//! the usual uncoupled approximation. The traction `q` acts along x only (`q_y = 0`, as
//! in Mindlin's solution), and the surface displacement along x is the Cerruti
//! convolution `u = K_t q`, with symbol `(1 - nu kx^2/|k|^2) / (G |k|)` for `k != 0`
//! (the xx entry of the half-space's surface Green's tensor, from Cerruti's solution;
//! nu = 0 makes it isotropic; the normal symbol is `(1 - nu) / (G |k|) = 2 / (E* |k|)`).
//! The mean mode has no displacement on a periodic surface, so the rigid shift `delta`
//! of the body is measured from the mean surface displacement; the loop's area and the
//! dissipation do not depend on that reference. Periodic images act on the tangential
//! problem more than on the normal one (1/r decay): take the period >= 10 contact radii
//! (the tests measure 4 % on the dissipation per cycle at 5 radii, under 1 % at 10).
//!
//! **Coulomb's law, step by step.** Friction depends on the path: each load step starts
//! from the accumulated slip `s` of the cells (their displacement relative to the body
//! not recovered elastically). In a step to the force `Q`, a cell sticks (no new slip:
//! `u_i + s_i = delta`) while `|q_i| < mu p_i`, and slips where `|q_i| = mu p_i`, its
//! new slip `delta - u_i - s_i` of the sign of `q_i`. That is the minimum of the convex
//! energy `q.K_t q / 2 + s.q` over `-mu p <= q <= mu p` with `sum q = Q / cell area`,
//! `delta` its multiplier. The step's dissipated energy is `sum q_i * new slip_i` times
//! the cell area, with the traction at the end of the step (exact where a cell slips
//! through the whole step at its bound, as cells do under monotonic loading).
//!
//! **Iteration.** A preconditioned projected conjugate gradient on the stick set (as
//! Polonsky & Keer do for the normal problem, with two bounds instead of one): the
//! residual is the stick cells' `u + s` about their mean (`delta`); the direction is its
//! image under the inverse of the periodic operator's symbol,
//! `G |k| / (1 - nu kx^2/|k|^2)` (exact on the whole grid; the free operator uses it on
//! its own grid, a quarter of its padded transform), taken again about its mean on the
//! stick set so that the force stays; the step is projected on the bounds, the
//! force is restored on the stick cells, and a bound cell whose residual asks to leave
//! its bound rejoins the stick set (conjugacy restarts when the set changes). The
//! preconditioner takes the iterations per step from growing with the grid (about
//! n^0.4 without it) to about 9-16 from 128^2 to 512^2 (`mrdw bench tangential`,
//! bench/HISTORY.md). An
//! iteration whose step projects no cell and changes no force updates `u = K_t q` by
//! `-tau K_t t` instead of applying the operator again (every 50 such iterations and
//! before stopping, `u` is computed afresh), and the loops run over the contact cells
//! only, so the transforms (the operator's and the preconditioner's) dominate its
//! cost. It stops
//! when every cell satisfies the law within `tolerance` times the largest displacement
//! (floored at the rounding of the displacements the step starts from, so that a step
//! whose answer is no traction at all ends): stick cells
//! `|u + s - delta|`, slip cells the sign of their new slip. A step whose
//! force reaches the total friction `mu sum p` is gross sliding, reported as such.

/// Poisson's ratio and shear modulus of the one elastic body (under a rigid indenter)
/// with these contact moduli: `E* = 2 G / (1 - nu)`, `G* = 4 G / (2 - nu)`; the Cerruti
/// operators take `(G, nu)`, the scenes and MRD's springs `(E*, G*)`.
pub fn equivalent_body(e_star: f64, g_star: f64) -> (f64, f64) {
    let rho = g_star / e_star;
    let nu = (2.0 - 2.0 * rho) / (2.0 - rho);
    (nu, e_star * (1.0 - nu) / 2.0)
}

mod cerruti;
mod cerruti_free;
mod compliance;
mod partial_slip;
mod stick;
mod viscoelastic;

pub use cerruti::CerrutiPeriodic;
pub use cerruti_free::CerrutiFree;
pub use compliance::TangentialCompliance;
pub use partial_slip::{Cycle, PartialSlip, TangentialStep};
pub use stick::StickStiffness;
pub use viscoelastic::{SlipSnapshot, ViscoelasticSlip, ViscoelasticStep};
