//! Tests of the library that reach its whole output registry or its 3D solvers. They
//! live here, linked against the built library, rather than beside the code: a unit test
//! that reaches them makes the unit-test binary compile every output and solver a
//! second time.

use compare::context::Context;
use compare::output::{Env, Output};
use compare::outputs::friction::static_friction_3d::runs::{press_line, solve_3d};
use compare::outputs::friction::static_friction_3d::{Geometry, StaticFriction3d};
use compare::plan::Stage;
use compare::report::Section;
use compare::scene::{Entry, Scene};
use compare::{run, CompareError, Result};
use std::f64::consts::PI;

/// Declares the 3D solver but runs only the rule of Hess.
#[derive(Debug)]
struct Liar;

impl Output for Liar {
    fn validate(&self, _: &Context) -> Result<()> {
        Ok(())
    }
    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![Stage::Bem3d]
    }
    fn run(&self, _: &Env, out: &mut Section) -> Result<()> {
        out.stage(Stage::HessTransform, || ());
        Ok(())
    }
}

#[test]
fn a_plan_that_is_not_what_ran_is_an_error() {
    let mut scene = Scene::parse(
        "name = \"x\"\n[material]\ne_star = 1.0\n[profile]\nshapes = [{ kind = \"sphere\", radius = 1.0 }]\n[[outputs]]\nkind = \"profile_1d\"\nr_max = 0.1\n",
        "test",
        None,
    )
    .unwrap();
    assert!(run(&scene).is_ok());
    scene.outputs.push(Entry {
        kind: "liar",
        label: "liar".into(),
        output: Box::new(Liar),
    });
    match run(&scene) {
        Err(CompareError::Internal(m)) => assert!(m.contains("declared"), "{m}"),
        other => panic!("expected an internal error, got {other:?}"),
    }
}

/// The static-friction study's spec with 20 cells per shortest wavelength.
fn spec() -> StaticFriction3d {
    toml::from_str(
        "hurst = [0.7]\nbandwidth = 4\ncells = 20\nrealisations_3d = 2\nrealisations_1d = 2\nf_min = 1e-3\nf_max = 1.0\n",
    )
    .unwrap()
}

#[test]
fn xi_is_one_at_complete_contact_in_3d() {
    let s = spec();
    for g in [Geometry::Periodic, Geometry::Disc] {
        let run = solve_3d(&s, g, 0.7, 0, 20, &[1e-3, 1e4]).unwrap();
        let full = run.points[1].unwrap();
        assert_eq!(full.area, 1.0, "{g:?}");
        assert!((full.xi - 1.0).abs() < 1e-12, "{g:?}: {}", full.xi);
        let sparse = run.points[0].unwrap();
        assert!(
            sparse.xi > 0.0 && sparse.xi < 1.0 && sparse.area < 0.05,
            "{sparse:?}"
        );
    }
}

#[test]
fn lambda_only_rescales_the_line() {
    // C1D = lambda q C2D scales a line by sqrt(lambda / pi): pressed with forces
    // scaled the same way it has the same contact set, so xi(f) of lambda at 3D
    // height h equals xi(f) of pi at h sqrt(pi / lambda) (Section 10.2's scaling).
    let s = spec();
    let fs = mrd::friction::log_space(1e-3, 1.0, 7);
    let lam = 5.0;
    for g in [Geometry::Periodic, Geometry::Disc] {
        let a = press_line(&s, g, 0.7, lam, 1.0, 3, &fs).unwrap();
        let b = press_line(&s, g, 0.7, PI, (PI / lam).sqrt(), 3, &fs).unwrap();
        for (p, q) in a.iter().zip(&b) {
            assert_eq!(p.contacts, q.contacts);
            assert!((p.xi - q.xi).abs() < 1e-12, "{p:?} {q:?}");
        }
        assert!(a[0].contacts < a[6].contacts);
    }
}
