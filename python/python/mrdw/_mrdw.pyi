"""Type stubs of the compiled module mrdw._mrdw (see the docstrings at run time)."""

from os import PathLike
from typing import Any, Dict, Literal, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
F64 = npt.NDArray[np.float64]

__version__: str

class ConvergenceError(RuntimeError):
    """An iteration stopped before its tolerance."""

    what: str
    iterations: int
    residual: float
    last: Optional["ContactResult"]

class ContactResult:
    """A solved 3D contact state."""

    @property
    def pressure(self) -> F64:
        """Cell pressures, shape (ny, nx) [stress]."""
    @property
    def gap(self) -> F64:
        """Gap at cell centres, shape (ny, nx) [length]; zero in contact."""
    @property
    def approach(self) -> float:
        """Rigid-body approach from first contact [length]."""
    @property
    def force(self) -> float:
        """Total normal force [stress x length^2]."""
    @property
    def mean_pressure(self) -> float:
        """Force over lx * ly [stress]."""
    @property
    def contact_area(self) -> float:
        """Contact cells times cell area [length^2]."""
    @property
    def contact_fraction(self) -> float:
        """Contact cells over the cells that may touch."""
    @property
    def contact_cells(self) -> int: ...
    @property
    def mean_gap(self) -> float:
        """Mean gap over the cells that may touch [length]."""
    @property
    def iterations(self) -> int: ...
    @property
    def residual(self) -> float:
        """Convergence criterion reached."""
    @property
    def certificate(self) -> float:
        """Bound of the energy's duality gap over force x rms height;
        (p - p*).K(p - p*) <= 2 certificate F h_rms. At most the tolerance when
        converged, except in complete contact, where a solve may stop at the floor
        rounding leaves (then above the tolerance)."""
    @property
    def stiffness(self) -> Optional[float]:
        """Tangent stiffness dF/dd [stress x length] if requested (+inf at complete
        contact of a periodic map)."""
    @property
    def complete_contact(self) -> bool: ...
    @property
    def warm_started(self) -> bool: ...
    @property
    def restricted(self) -> bool:
        """Solved restricted to part of the grid: a window around a compact contact
        on the non-periodic half-space (`iterations` then count iterations on the
        window), or a small candidate set at low contact fractions (`iterations` then
        count applications of a dense K between its cells)."""
    @property
    def path(self) -> str:
        """The path the solve took: "full grid", "window" or "candidate set"."""
    @property
    def nested_start(self) -> bool:
        """Started from the solution on the grid coarsened 2 x 2."""
    @property
    def single_precision_iterations(self) -> int:
        """Of `iterations`, those with K p carried in single precision."""
    @property
    def stencil_iterations(self) -> int:
        """Of `iterations`, those with the preconditioner applied by its stencil."""
    @property
    def scaled_directions(self) -> bool:
        """The direction vectors were stored as 16-bit integers scaled per row chunk
        (grids above 2048^2 cells, unless forbidden)."""

class Contact:
    """Frictionless normal contact of a rigid rough surface on an elastic half-space
    (3D FFT boundary elements)."""

    def __init__(
        self,
        heights: Union[ArrayLike, Any],
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        periodic: Optional[bool] = None,
        mask: Optional[ArrayLike] = None,
    ) -> None:
        """heights: (ny, nx) array, or a topography object with heights() (indexed
        (x, y)) and physical_sizes (e.g. SurfaceTopography's), whose size and
        is_periodic are the defaults of size and periodic (else (1, 1) and True; a
        topography whose physical_sizes is None needs size). A numpy masked array's
        masked cells (undefined points) are left out of the contact, as mask= does,
        with a UserWarning that counts them. A float64 array in C order (or a
        topography's in F order) is read in place, not copied: do not write to it
        while a solve runs; a solve after it changed raises ValueError."""
    def solve(
        self,
        mean_pressure: Optional[float] = None,
        force: Optional[float] = None,
        approach: Optional[float] = None,
        *,
        tolerance: float = 1e-10,
        max_iterations: int = 10000,
        stiffness: bool = False,
        warm: Optional[ContactResult] = None,
        paths: Optional[Dict[str, str]] = None,
    ) -> ContactResult:
        """Solve for exactly one of mean_pressure [stress], force [stress x length^2]
        or approach [length]. Releases the GIL. paths: {strategy: "forbid" | "allow" |
        "force"} for window, candidate_set, stencil, nested_start, single_precision,
        scaled_directions."""
    def solve_many(
        self,
        mean_pressures: Optional[ArrayLike] = None,
        forces: Optional[ArrayLike] = None,
        approaches: Optional[ArrayLike] = None,
        *,
        tolerance: float = 1e-10,
        max_iterations: int = 10000,
        stiffness: bool = False,
        paths: Optional[Dict[str, str]] = None,
    ) -> list[ContactResult]:
        """A load list, solved in order with warm starts where they pay."""
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> Tuple[float, float]: ...
    @property
    def e_star(self) -> float: ...
    @property
    def periodic(self) -> bool: ...
    @property
    def undefined_cells(self) -> int:
        """Cells a masked array left undefined: outside the contact."""

class TransientStep:
    """The state after a step of TransientContact.step."""

    @property
    def time(self) -> float:
        """Time at the step's end [time]."""
    @property
    def approach(self) -> float:
        """Rigid-body position from the first contact of the undeformed surface [length]."""
    @property
    def force(self) -> float:
        """Total normal force [stress x length^2]."""
    @property
    def contact_area(self) -> float:
        """Contact cells times cell area [length^2]."""
    @property
    def contact_cells(self) -> int: ...
    @property
    def pressure(self) -> F64:
        """Cell pressures, shape (ny, nx) [stress]."""
    @property
    def effective_modulus(self) -> float:
        """The step's effective modulus E_eff [stress]."""
    @property
    def iterations(self) -> int:
        """Iterations of the step's elastic solve (0 without a solve)."""
    @property
    def residual(self) -> float: ...
    @property
    def certificate(self) -> float: ...

class TransientContact:
    """A rigid rough surface on a linear viscoelastic half-space, stepped in time
    (E*(t) = relaxed + sum_k E_k exp(-t / tau_k))."""

    def __init__(
        self,
        heights: Union[ArrayLike, Any],
        relaxed: float,
        terms: Sequence[Tuple[float, float]],
        size: Optional[Tuple[float, float]] = None,
        periodic: Optional[bool] = None,
        mask: Optional[ArrayLike] = None,
    ) -> None:
        """terms: (E_k [stress], tau_k [time]) pairs; heights, size, periodic, mask as
        for Contact. Starts undeformed at t = 0."""
    def step(
        self,
        dt: float,
        mean_pressure: Optional[float] = None,
        force: Optional[float] = None,
        approach: Optional[float] = None,
        *,
        tolerance: float = 1e-10,
        max_iterations: int = 10000,
    ) -> TransientStep:
        """Advance by dt [time] to exactly one load at the step's end (linear over the
        step). Releases the GIL."""
    @property
    def time(self) -> float: ...
    @property
    def displacement(self) -> F64:
        """Surface displacement into the half-space, shape (ny, nx) [length]."""
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> Tuple[float, float]: ...
    @property
    def periodic(self) -> bool: ...

class AdhesiveStep:
    """The state after a step of AdhesiveContact.step."""

    @property
    def approach(self) -> float:
        """Approach from first contact [length] (negative: retracted past it)."""
    @property
    def force(self) -> float:
        """Total normal force [stress x length^2], negative in tension."""
    @property
    def contact_area(self) -> float:
        """Contact cells times cell area [length^2]."""
    @property
    def contact_cells(self) -> int: ...
    @property
    def joined(self) -> int:
        """Cells that joined (touched) during the step."""
    @property
    def detached(self) -> int:
        """Cells that detached during the step."""
    @property
    def tension(self) -> float:
        """The largest tension of a contact cell over the critical stress (<= 1)."""
    @property
    def rounds(self) -> int:
        """Set-update rounds of the step."""
    @property
    def iterations(self) -> int:
        """Conjugate-gradient iterations summed over the rounds."""
    @property
    def residual(self) -> float:
        """The last round's criterion value."""
    @property
    def separated(self) -> bool:
        """No cell is in contact at the end of the step."""
    @property
    def pressure(self) -> F64:
        """Cell pressures, shape (ny, nx) [stress], negative in tension."""

class AdhesiveContact:
    """A rigid surface in adhesive contact with an elastic half-space, loaded along a
    history: zero-range adhesion in the JKR limit (a cell joins on touching and detaches
    when its tension exceeds sqrt(2 w E* / c), Pohrt & Popov's mesh-dependent criterion;
    converges to JKR as the cells shrink)."""

    def __init__(
        self,
        heights: Union[ArrayLike, Any],
        work: float,
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        periodic: Optional[bool] = None,
        mask: Optional[ArrayLike] = None,
    ) -> None:
        """work: the work of adhesion w [stress x length], > 0; heights, size, e_star,
        periodic, mask as for Contact. Starts out of contact."""
    def step(
        self,
        mean_pressure: Optional[float] = None,
        force: Optional[float] = None,
        approach: Optional[float] = None,
        *,
        tolerance: float = 1e-8,
    ) -> AdhesiveStep:
        """Load from the last state to exactly one of mean_pressure [stress], force
        [stress x length^2] (negative: tension) or approach [length] from first contact
        (negative: retracted; free half-space only). Releases the GIL."""
    @property
    def critical_stress(self) -> float:
        """The critical tension of a cell [stress]."""
    @property
    def gap(self) -> F64:
        """Gap of the last step, shape (ny, nx) [length]."""
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> Tuple[float, float]: ...
    @property
    def periodic(self) -> bool: ...

class CohesiveStep:
    """The state after a step of CohesiveContact.step."""

    @property
    def approach(self) -> float:
        """Approach from first contact [length] (negative: retracted past it)."""
    @property
    def force(self) -> float:
        """Total normal force [stress x length^2], negative in tension."""
    @property
    def contact_area(self) -> float:
        """Contact cells (gap 0) times cell area [length^2]."""
    @property
    def contact_cells(self) -> int: ...
    @property
    def cohesive_cells(self) -> int:
        """Cells in the cohesive zone (0 < gap < w / sigma0)."""
    @property
    def rounds(self) -> int: ...
    @property
    def iterations(self) -> int: ...
    @property
    def residual(self) -> float: ...
    @property
    def pressure(self) -> F64:
        """Cell pressures, shape (ny, nx) [stress], negative in tension (>= -sigma0)."""

class LawForces:
    """The forces of one state of a ContactLaw."""

    @property
    def normal(self) -> float:
        """Normal force [stress x length^2], >= 0."""
    @property
    def tangential(self) -> float:
        """Tangential force [stress x length^2], resisting the displacement."""
    @property
    def contact_area(self) -> float: ...
    @property
    def stiffness(self) -> Optional[float]:
        """Normal tangent stiffness dF/dd; None where the law does not compute it (3D)."""
    @property
    def dissipated(self) -> float:
        """Energy dissipated by slip in the step [stress x length^3]."""
    @property
    def iterations(self) -> int: ...

class ContactLaw:
    """A contact law with history for a time integrator (Section 12): trial a step's
    motion, then commit or rollback. MRD's springs (body, rough_line) or the 3D solve
    (bem3d) behind one interface."""

    @staticmethod
    def body(
        profile: Profile,
        e_star: float = 1.0,
        springs: int = 2000,
        half_length: Optional[float] = None,
        g_star: Optional[float] = None,
        mu: Optional[float] = None,
    ) -> "ContactLaw":
        """MRD's springs for a body of revolution (rule of Hess), with Coulomb friction
        when g_star and mu are given."""
    @staticmethod
    def rough_line(
        heights: ArrayLike,
        length: float,
        e_star: float = 1.0,
        nominal_area: Optional[float] = None,
        g_star: Optional[float] = None,
        mu: Optional[float] = None,
    ) -> "ContactLaw":
        """MRD's rough line (springs E* dx under 1D heights over `length`)."""
    @staticmethod
    def bem3d(
        heights: Union[ArrayLike, Any],
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        mask: Optional[ArrayLike] = None,
        periodic: bool = False,
        tolerance: Optional[float] = None,
    ) -> "ContactLaw":
        """The 3D normal contact of a height map, warm-started from the last step."""
    @staticmethod
    def viscoelastic_body(
        profile: Profile,
        relaxed: float,
        terms: Sequence[Tuple[float, float]],
        springs: int = 2000,
        half_length: Optional[float] = None,
    ) -> "ContactLaw":
        """MRD's viscoelastic springs for a body of revolution: E*(t) = relaxed +
        sum_k E_k exp(-t / tau_k), terms (E_k [stress], tau_k [time]); Eq. 63 per spring,
        separating at zero force. Frictionless; the force depends on each trial's dt."""
    @staticmethod
    def viscoelastic_bem3d(
        heights: Union[ArrayLike, Any],
        relaxed: float,
        terms: Sequence[Tuple[float, float]],
        size: Optional[Tuple[float, float]] = None,
        mask: Optional[ArrayLike] = None,
        periodic: bool = False,
        tolerance: Optional[float] = None,
    ) -> "ContactLaw":
        """The 3D transient viscoelastic contact of the height map as a contact law: each
        trial one time step of dt; a rollback restores the state before it."""
    @staticmethod
    def adhesive_body(
        profile: Profile,
        e_star: float,
        work: float,
        springs: int = 2000,
        half_length: Optional[float] = None,
    ) -> "ContactLaw":
        """MRD's adhesive springs for a body of revolution (JKR limit, work w): attached
        once touched, detached by Eq. 33; tensile forces negative. Frictionless."""
    @staticmethod
    def adhesive_bem3d(
        heights: Union[ArrayLike, Any],
        e_star: float,
        work: float,
        size: Optional[Tuple[float, float]] = None,
        mask: Optional[ArrayLike] = None,
        periodic: bool = False,
        tolerance: Optional[float] = None,
    ) -> "ContactLaw":
        """The 3D adhesive contact of the height map as a contact law: each trial one step
        to the approach; a rollback restores the state before it."""
    @staticmethod
    def slip_bem3d(
        heights: Union[ArrayLike, Any],
        normal_force: float,
        g_star: float,
        mu: float,
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        tolerance: Optional[float] = None,
    ) -> "ContactLaw":
        """The 3D partial slip of the height map on the free half-space at a held normal
        force as a tangential contact law; a rollback restores the slip before a trial."""
    @staticmethod
    def oblique_bem3d(
        heights: Union[ArrayLike, Any],
        g_star: float,
        mu: float,
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        tolerance: Optional[float] = None,
    ) -> "ContactLaw":
        """The 3D contact of the height map on the free half-space with both motions free
        (the normal solve, then the partial slip under its pressure, the slip carried);
        it starts apart, and a contact forming again after separating is a first contact
        again (its origin the tangential displacement of that moment)."""
    def trial(self, normal: float, tangential: float = 0.0, dt: float = 1.0) -> LawForces:
        """The forces at the step's end motion from the last accepted state."""
    def commit(self) -> None:
        """Accept the last trial."""
    def rollback(self) -> None:
        """Discard the last trial."""
    @property
    def committed(self) -> LawForces: ...
    def approach_at(self, force: float) -> float:
        """The approach carrying `force` with the history as accepted."""

class PlasticStep:
    """The state after a step of PlasticContact.step."""

    @property
    def approach(self) -> float:
        """Approach from the first contact of the undeformed surface [length]."""
    @property
    def force(self) -> float:
        """Total normal force [stress x length^2]."""
    @property
    def contact_cells(self) -> int: ...
    @property
    def plastic_cells(self) -> int:
        """Cells at the hardness (within 1e-6 of it)."""
    @property
    def contact_area(self) -> float: ...
    @property
    def plastic_area(self) -> float: ...
    @property
    def plastic_depth(self) -> float:
        """The largest plastic displacement so far [length]."""
    @property
    def flowed(self) -> int:
        """Cells whose plastic displacement grew in this step."""
    @property
    def iterations(self) -> int: ...
    @property
    def solves(self) -> int:
        """Solves of the step: 1, more where the solve holding a force stalled."""
    @property
    def residual(self) -> float: ...
    @property
    def pressure(self) -> F64:
        """Cell pressures (ny, nx) [stress], in [0, hardness]."""
    @property
    def plastic_displacement(self) -> F64:
        """The plastic displacement so far (ny, nx) [length]: after unloading, the imprint."""

class PlasticContact:
    """A rigid surface pressed on an elastic-perfectly plastic half-space (the pressure
    cap: pressures saturate at the hardness, the surface flows where they would exceed
    it and stays lowered), free or periodic, loaded along a history."""

    def __init__(
        self,
        heights: Union[ArrayLike, Any],
        hardness: float,
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        mask: Optional[ArrayLike] = None,
        periodic: bool = False,
    ) -> None:
        """hardness: H [stress] > 0 (inf: the elastic contact); heights, size, e_star,
        mask as for Contact. Starts out of contact, the surface undeformed."""
    def step(
        self,
        *,
        mean_pressure: Optional[float] = None,
        force: Optional[float] = None,
        approach: Optional[float] = None,
        tolerance: Optional[float] = None,
    ) -> PlasticStep:
        """Load from the last state to exactly one of a mean pressure, a force (>= 0,
        below force_limit; 0: just touching) or an approach from the undeformed first
        contact (any finite value). tolerance: relative, in (0, 0.01] (None: 1e-8).
        Releases the GIL."""
    @property
    def hardness(self) -> float: ...
    @property
    def force_limit(self) -> float:
        """H times the domain's area: the largest force a step carries."""
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> Tuple[float, float]: ...
    @property
    def periodic(self) -> bool: ...

class CohesiveContact:
    """A rigid surface in finite-range adhesive contact with an elastic half-space, free
    or periodic, loaded along an approach history. law="dugdale": a tension sigma0
    wherever the gap lies below the range rho = w / sigma0; law="exponential": the
    tension sigma0 exp(-gap / rho) (Bradley's to JKR's limit with the Tabor parameter)."""

    def __init__(
        self,
        heights: Union[ArrayLike, Any],
        work: float,
        sigma0: float,
        size: Optional[Tuple[float, float]] = None,
        e_star: float = 1.0,
        mask: Optional[ArrayLike] = None,
        periodic: bool = False,
        law: str = "dugdale",
    ) -> None:
        """work: the work of adhesion w [stress x length], > 0; sigma0: the peak
        cohesive stress [stress], > 0; heights, size, e_star, mask as for Contact.
        periodic=False: the free half-space, approach from first contact; periodic=True:
        the approach d fixes the mean gap at mean(max(h) - h) - d (approaches reaching
        complete contact raise ValueError). law: "dugdale" or "exponential" (the
        adhesive energy -w exp(-gap / rho), rho = w / sigma0). Starts out of contact."""
    def step(self, approach: float, *, tolerance: float = 1e-8) -> CohesiveStep:
        """Load from the last state to the approach [length] from first contact
        (negative: retracted). Releases the GIL."""
    @property
    def dugdale_length(self) -> float:
        """E* w / sigma0^2 [length]: the cohesive zone's width scale."""
    @property
    def resolved(self) -> bool:
        """Whether the Dugdale length spans at least 10 cells."""
    @property
    def law(self) -> str:
        """The traction-gap law: "dugdale" or "exponential"."""
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> Tuple[float, float]: ...
    @property
    def periodic(self) -> bool: ...

class TangentialStep:
    """The state after a step of PartialSlip.load."""

    @property
    def force(self) -> float:
        """The tangential force reached [stress x length^2]."""
    @property
    def shift(self) -> Optional[float]:
        """Rigid shift along x [length]: from the mean surface displacement (periodic),
        absolute (free); None when sliding (a quasi-static step does not set how far)."""
    @property
    def stick_cells(self) -> int: ...
    @property
    def slip_cells(self) -> int: ...
    @property
    def dissipated(self) -> Optional[float]:
        """Energy dissipated by slip in this step [stress x length^3]; None when sliding."""
    @property
    def iterations(self) -> int: ...
    @property
    def residual(self) -> float: ...
    @property
    def sliding(self) -> bool:
        """The force reached mu P: the body slides as a whole."""

class PartialSlip:
    """Partial slip of a held normal contact under a tangential force along x (3D,
    Coulomb's law with Cerruti's operator, periodic or free (`periodic=False`: the
    shift is then absolute); Sections 6-7 in 3D)."""

    def __init__(
        self,
        pressure: ArrayLike,
        mu: float,
        size: Tuple[float, float] = (1.0, 1.0),
        e_star: float = 1.0,
        poisson: float = 0.5,
        *,
        periodic: bool = True,
    ) -> None: ...
    def load(self, force: float, *, tolerance: float = 1e-8) -> TangentialStep:
        """Loads to the tangential force [stress x length^2] from the last state."""
    def cycle(
        self, amplitude: float, steps: int = 10, cycles: int = 2, *, tolerance: float = 1e-8
    ) -> Tuple[float, float]:
        """The last cycle's dissipated energy and loop area [stress x length^3]; at most
        1e6 loads, steps x (2 cycles + 1)."""
    @property
    def friction_limit(self) -> float:
        """mu P [stress x length^2]."""
    @property
    def traction(self) -> F64:
        """The traction of the last step, shape (ny, nx) [stress]."""
    @property
    def slip(self) -> F64:
        """The accumulated slip of each cell, shape (ny, nx) [length]."""

class ViscoelasticStep:
    """The state after ViscoelasticSlip.step."""

    @property
    def time(self) -> float:
        """Time at the end of the step [time]."""
    @property
    def shift(self) -> float:
        """The prescribed shift [length]."""
    @property
    def force(self) -> float:
        """The tangential force it takes [stress x length^2]."""
    @property
    def stick_cells(self) -> int: ...
    @property
    def slip_cells(self) -> int: ...
    @property
    def dissipated(self) -> float:
        """Energy dissipated by slip in this step [stress x length^3]."""
    @property
    def solves(self) -> int:
        """Solves the step took: 1 on the free half-space (the shift held), the trials of
        the force on the periodic one, 0 where the body slides."""
    @property
    def iterations(self) -> int:
        """Conjugate-gradient iterations of those solves."""
    @property
    def sliding(self) -> bool: ...

class ViscoelasticSlip:
    """Partial slip of a held normal contact on a viscoelastic half-space (shear modulus
    G(t) = relaxed + sum G_k exp(-t / tau_k) [stress], Poisson's ratio held) under a
    prescribed tangential shift history along x (3D; Eqs. 64-65 in 3D). Free
    half-space by default."""

    def __init__(
        self,
        pressure: ArrayLike,
        mu: float,
        relaxed: float,
        terms: Sequence[Tuple[float, float]] = (),
        size: Tuple[float, float] = (1.0, 1.0),
        poisson: float = 0.5,
        *,
        periodic: bool = False,
    ) -> None: ...
    def step(self, dt: float, shift: float, *, tolerance: float = 1e-8) -> ViscoelasticStep:
        """Moves the body to `shift` [length] over `dt` [time], linearly in time."""
    @property
    def friction_limit(self) -> float:
        """mu P [stress x length^2]."""

def stick_stiffness(
    contact: ArrayLike,
    size: Tuple[float, float] = (1.0, 1.0),
    e_star: float = 1.0,
    poisson: float = 0.5,
    *,
    tolerance: float = 1e-10,
) -> Tuple[float, float, float]:
    """(k_x, k_y, k_x with q_y = 0) [stress x length] of cells held in full stick."""

def spectrum(
    q: ArrayLike,
    hurst: float,
    q0: float,
    qr: float,
    q1: float,
    *,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
) -> F64:
    """Self-affine C2D(q) (Eq. 70) [length^4]."""

def line_spectrum(
    q: ArrayLike,
    hurst: float,
    q0: float,
    qr: float,
    q1: float,
    *,
    lam: float = ...,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
) -> F64:
    """C1D = lam |q| C2D (Eq. 76) [length^3]."""

def calibrated_lambda(hurst: float) -> float:
    """lambda(H) of Eq. (76) from the shipped calibration (fig6-converged, bandwidth 128),
    as Eq. (76) states it: lines built with C1D = lambda q C2D of the same C2D
    (line(lam=...), line_spectrum(lam=...)), not rescaled."""

def calibrated_lambda_table() -> str:
    """The shipped calibration as CSV text with its provenance."""

def surface(
    shape: Tuple[int, int],
    size: Tuple[float, float],
    hurst: float,
    q0: float,
    qr: float,
    q1: float,
    *,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    seed: int = 0,
    realisation: int = 0,
    gaussian: bool = False,
) -> F64:
    """Periodic random-phase surface (Eq. 71), shape (ny, nx)."""

def line(
    n: int,
    length: float,
    hurst: float,
    q0: float,
    qr: float,
    q1: float,
    *,
    lam: float = ...,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    seed: int = 0,
    realisation: int = 0,
    gaussian: bool = False,
) -> F64:
    """Periodic rough line (Eq. 72) with C1D = lam q C2D (Eq. 76)."""

def psd(h: ArrayLike, size: Union[float, Tuple[float, float]], bins: int = 32) -> Tuple[F64, F64]:
    """(q, C1D) of a line or (q, C2D) radially averaged of a surface."""

class Moments(TypedDict):
    rms_height: float
    rms_slope: float
    rms_curvature: float

def moments(h: ArrayLike, size: Union[float, Tuple[float, float]]) -> Moments: ...
def _read_topography_file(path: Union[str, PathLike[str]]) -> Tuple[F64, Optional[Tuple[float, float]]]:
    """A height map (rows of y) from a file and its cell size (dx, dy) where the
    file states it; used by mrdw.read_topography."""

def _topography_parts(
    source: Any,
) -> Tuple[F64, Optional[npt.NDArray[np.bool_]], Optional[Tuple[float, float]], Optional[bool]]:
    """An array, masked array or topography object taken apart as Contact takes it:
    heights (rows of y, NaN where undefined), undefined cells, size, periodicity."""

class LineFit(TypedDict):
    a: float
    b: float
    se_a: float
    se_b: float

def fit_line(x: ArrayLike, y: ArrayLike) -> LineFit: ...

class RoughState(TypedDict):
    depth: float
    force: float
    contacts: int
    contact_length: float
    stiffness: float
    contact_slope: float

class RoughLine:
    """A rough line on the MRD foundation (springs E* dx)."""

    def __init__(self, heights: ArrayLike, length: float, e_star: float) -> None: ...
    def at_force(self, force: float) -> RoughState: ...
    def at_depth(self, depth: float) -> RoughState: ...
    @property
    def full_contact_depth(self) -> float: ...
    @property
    def rms_height(self) -> float: ...
    def reduced_force(self, force: float) -> float: ...
    def reduced_stiffness(self, stiffness: float) -> float: ...
    def __len__(self) -> int: ...

class LineStep(TypedDict):
    approach: float
    force: float
    contacts: int
    capped: int
    patches: int
    stiffness: float
    largest_set: float

class PlasticLine:
    """A rough line on an elastic-perfectly plastic MRD foundation (patch-capped springs)."""

    def __init__(
        self, heights: ArrayLike, length: float, e_star: float, hardness: float
    ) -> None: ...
    def step(self, approach: float) -> LineStep: ...
    def step_to_force(self, force: float, tolerance: Optional[float] = None) -> LineStep: ...
    @property
    def set(self) -> F64: ...
    @property
    def load(self) -> F64: ...
    @property
    def force_limit(self) -> float: ...
    def __len__(self) -> int: ...

class Profile:
    """An axisymmetric rigid indenter z(r)."""

    @staticmethod
    def sphere(radius: float, rim: Optional[float] = None) -> "Profile": ...
    @staticmethod
    def cone(tan_theta: float, rim: Optional[float] = None) -> "Profile": ...
    @staticmethod
    def power_law(c: float, n: float, rim: Optional[float] = None) -> "Profile": ...
    @staticmethod
    def flattened_sphere(
        radius: float, flat_radius: float, rim: Optional[float] = None
    ) -> "Profile": ...
    @staticmethod
    def flat_punch(radius: float) -> "Profile": ...
    @staticmethod
    def tabulated(r: ArrayLike, z: ArrayLike, rim: Optional[float] = None) -> "Profile": ...
    def __add__(self, other: "Profile") -> "Profile": ...
    def z(self, r: ArrayLike) -> F64: ...
    def z1d(self, x: ArrayLike) -> F64:
        """Rule of Hess (Eq. 11), closed forms."""
    def z1d_numeric(self, x: ArrayLike) -> F64:
        """Rule of Hess by quadrature."""
    @property
    def max_contact_radius(self) -> float: ...

def hess_inverse(x: ArrayLike, g: ArrayLike, r: ArrayLike) -> F64: ...

class NormalState(TypedDict):
    depth: float
    radius: float
    force: float
    stiffness: float

def normal(
    profile: Profile,
    e_star: float,
    *,
    depth: Optional[float] = None,
    force: Optional[float] = None,
    radius: Optional[float] = None,
) -> NormalState: ...
def pressure(
    profile: Profile,
    e_star: float,
    r: ArrayLike,
    *,
    depth: Optional[float] = None,
    force: Optional[float] = None,
) -> F64: ...

class AdhesiveState(TypedDict):
    radius: float
    depth: float
    force: float

def adhesion(profile: Profile, e_star: float, gamma: float, radius: float) -> AdhesiveState: ...
def pull_off(
    profile: Profile,
    e_star: float,
    gamma: float,
    *,
    control: Literal["force", "displacement"] = "force",
    max_radius: Optional[float] = None,
) -> AdhesiveState: ...

class TangentialState(TypedDict):
    force: float
    stick_radius: float
    displacement: float
    contact_radius: float
    max_displacement: float

def cattaneo_mindlin(
    profile: Profile,
    e_star: float,
    g_star: float,
    mu: float,
    normal_force: float,
    tangential_force: float,
) -> TangentialState: ...
def damping(
    profile: Profile,
    e_star: float,
    g_star: float,
    mu: float,
    depth: float,
    amplitude: float,
) -> float: ...
def scenes() -> list[Tuple[str, str]]: ...
def run_scene(scene: str) -> dict[str, Any]: ...
def _run_to_folder(
    scene: str, out: str, work: str | None = None, progress: bool = False
) -> dict[str, Any]:
    """Runs a scene file into the report folder `out` (checkpoints kept in `work`)."""
    ...
