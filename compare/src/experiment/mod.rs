//! The shared experiment layer that the studies stand on instead of on each other:
//! the rule of Hess's stage of the axisymmetric outputs ([`hess`]), lambda as scenes give it and its calibrated table ([`lambda`]), its one meaning
//! ([`lambda_meaning`]), the fits and intervals of ensemble curves ([`fit`]), the
//! periodic self-affine patches of the 3D rough studies ([`periodic`]), the rough
//! punch's k(F) ladder and MRD ensemble ([`rough_punch`]), the rough sphere with its MRD
//! line ([`rough_sphere`]), a rough sphere or punch as the studies
//! name it ([`rough_body`]), a body of revolution pressed on the 3D
//! grid for the tangential outputs ([`axisym_3d`]), MRD's tangential law on any normal
//! curve ([`tangential_map`]), the elastomer of the sliding-friction outputs with the fit
//! of Eq. (82) ([`elastomer`]) and their MRD ensemble of sliding lines
//! ([`sliding_line`]), a measured topography's detrended square and isotropic PSD
//! ([`measured`]), checkpointed task sets ([`tasks`]), the progress bar of long stages
//! ([`progress`]), a rigid body's impact on a contact law in time ([`impact`]), a mass on a rough punch in the loop ([`punch_loop`]), a mass released on a frictional contact and its cycles' losses ([`ring`]) and the options of a study's 3D normal solves ([`solve_options`]).

pub mod axisym_3d;
pub mod elastomer;
pub mod fit;
pub mod hess;
pub mod impact;
pub mod lambda;
pub mod lambda_meaning;
pub mod measured;
pub mod periodic;
pub mod progress;
pub mod punch_loop;
pub mod ring;
pub mod rough_body;
pub mod rough_punch;
pub mod rough_sphere;
pub mod sliding_line;
pub mod tangential_map;
pub mod tasks;

/// The options of a study's 3D normal solves on `n x n` cells: the scene's `tolerance`
/// and at most 20 n + 2000 iterations (the conjugate gradient's count grows about
/// linearly with the grid's side; the constant covers the small grids).
pub fn solve_options(tolerance: f64, n: usize) -> bem3d::SolverOptions {
    bem3d::SolverOptions::new(tolerance, 20 * n + 2000)
}
