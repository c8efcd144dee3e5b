"""mrdw: the MRD validation workbench from Python.

The method of reduction of dimensionality (MRD) and a fast 3D FFT boundary-element
contact solver, on numpy arrays. Equation numbers refer to V. L. Popov, M. Hess, Method
of reduction of dimensionality in contact and friction mechanics, Friction 1 (2013)
41-62.

3D contact::

    c = mrdw.Contact(heights, size=(lx, ly), e_star=E, periodic=True)
    r = c.solve(mean_pressure=0.01 * E)      # or force=..., approach=...
    r.pressure, r.gap, r.contact_fraction, r.mean_gap, r.iterations, r.residual

Viscoelastic contact in time (E*(t) = relaxed + sum E_k exp(-t / tau_k))::

    v = mrdw.TransientContact(heights, relaxed=E, terms=[(2 * E, tau)], size=(lx, ly))
    s = v.step(0.1 * tau, force=F)           # or mean_pressure=..., approach=...
    s.time, s.approach, s.force, s.contact_area, s.pressure

Adhesive contact along a history (JKR limit; w the work of adhesion)::

    a = mrdw.AdhesiveContact(heights, work=w, size=(lx, ly), periodic=False)
    s = a.step(approach=d)                   # or force=..., mean_pressure=...; < 0 pulls
    s.force, s.contact_area, s.separated, s.pressure

Finite-range (Maugis-Dugdale) adhesion, sigma0 the cohesive stress::

    c = mrdw.CohesiveContact(heights, work=w, sigma0=s0, size=(lx, ly))
    s = c.step(d)                            # approach from first contact; < 0 pulls
    s.force, s.contact_cells, s.cohesive_cells, c.resolved

Roughness: spectrum, line_spectrum, calibrated_lambda (lambda(H) of Eq. 76; the
table with its provenance: calibrated_lambda_table), surface, line, psd, moments,
read_topography (a Topography: heights, physical size, undefined cells).
MRD: Profile (sphere, cone, power_law, flattened_sphere, flat_punch, tabulated),
normal, pressure, adhesion, pull_off, cattaneo_mindlin, damping, hess_inverse,
RoughLine, PlasticLine, fit_line. Scenes: scenes(), run_scene(name_or_path).

Units are whatever consistent set the inputs use (length and stress); docstrings give
the dimension of each quantity. Bad input raises ValueError (the CLI's message); an
iteration that stops short raises ConvergenceError with .iterations, .residual and,
for contact solves, .last (the last iterate).
"""

from ._mrdw import (
    __version__,
    ConvergenceError,
    Contact,
    ContactResult,
    TransientContact,
    TransientStep,
    AdhesiveContact,
    AdhesiveStep,
    CohesiveContact,
    CohesiveStep,
    PlasticContact,
    PlasticStep,
    ContactLaw,
    LawForces,
    PartialSlip,
    TangentialStep,
    ViscoelasticSlip,
    ViscoelasticStep,
    stick_stiffness,
    spectrum,
    line_spectrum,
    calibrated_lambda,
    calibrated_lambda_table,
    surface,
    line,
    psd,
    moments,
    fit_line,
    RoughLine,
    PlasticLine,
    Profile,
    hess_inverse,
    normal,
    pressure,
    adhesion,
    pull_off,
    cattaneo_mindlin,
    damping,
    scenes,
    run_scene,
)
from ._topography import Topography, read_topography
from ._calibrate import calibrate

__all__ = [
    "calibrate",
    "__version__",
    "ConvergenceError",
    "Contact",
    "ContactResult",
    "TransientContact",
    "TransientStep",
    "AdhesiveContact",
    "AdhesiveStep",
    "CohesiveContact",
    "CohesiveStep",
    "PlasticContact",
    "PlasticStep",
    "ContactLaw",
    "LawForces",
    "PartialSlip",
    "TangentialStep",
    "ViscoelasticSlip",
    "ViscoelasticStep",
    "stick_stiffness",
    "spectrum",
    "line_spectrum",
    "calibrated_lambda",
    "calibrated_lambda_table",
    "surface",
    "line",
    "psd",
    "moments",
    "read_topography",
    "Topography",
    "fit_line",
    "RoughLine",
    "PlasticLine",
    "Profile",
    "hess_inverse",
    "normal",
    "pressure",
    "adhesion",
    "pull_off",
    "cattaneo_mindlin",
    "damping",
    "scenes",
    "run_scene",
]
