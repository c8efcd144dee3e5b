//! What the solver families share, below them and above the operators: the rigid
//! surface read from the caller's heights ([`surface`]), passes over the cells in
//! chunks whose sums do not depend on the threads ([`chunks`]), and the projected
//! conjugate gradient on per-cell boxes ([`box_cg`]) under which a family is a choice
//! of boxes, of the set of cells and of its outer loop (cohesive zones, the
//! elastic-perfectly plastic contact), and the acceleration of outer fixed-point loops
//! ([`anderson`]). No family imports another; each imports this.
//!
//! The normal solver (`solver`) keeps its own, tuned iteration (single-precision
//! transforms, windows, candidate sets: `docs/solver.md`); the kit's iteration is its
//! double-precision, whole-grid form with boxes on both sides.

pub(crate) mod anderson;
pub(crate) mod box_cg;
pub(crate) mod chunks;
pub(crate) mod surface;
