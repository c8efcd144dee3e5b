"""3D contact from numpy: against a dense numpy solve, closed forms, the warm-start
ladder, errors, and the GIL."""

import sys
import threading
import time

import numpy as np
import pytest

import mrdw


def rough(n, seed=3):
    h = mrdw.surface((n, n), (1.0, 1.0), 0.8, 2 * np.pi, 4 * np.pi, 2 * np.pi * (n // 4), seed=seed)
    return h * (0.1 / mrdw.moments(h, (1.0, 1.0))["rms_slope"])


def periodic_matrix(nx, ny, lx, ly, e_star):
    """Dense periodic influence matrix: u = ifft2(2 / (E* |q|) fft2(p)), mean mode 0."""
    kx = 2 * np.pi * np.fft.fftfreq(nx, d=lx / nx)
    ky = 2 * np.pi * np.fft.fftfreq(ny, d=ly / ny)
    q = np.hypot(*np.meshgrid(kx, ky))
    c = np.zeros_like(q)
    c[q > 0] = 2.0 / (e_star * q[q > 0])
    k = np.empty((nx * ny, nx * ny))
    for j in range(nx * ny):
        e = np.zeros(nx * ny)
        e[j] = 1.0
        k[:, j] = np.real(np.fft.ifft2(np.fft.fft2(e.reshape(ny, nx)) * c)).ravel()
    return k


def active_set(k, z, force, cell_area):
    """Force-controlled contact by an active-set method with numpy.linalg.solve:
    K_CC p_C - d = -z_C, sum p_C cell_area = F, p >= 0, gap >= 0."""
    n = len(z)
    contact = z <= z.min() + 1e-12
    for _ in range(200):
        idx = np.flatnonzero(contact)
        m = len(idx)
        a = np.zeros((m + 1, m + 1))
        a[:m, :m] = k[np.ix_(idx, idx)]
        a[:m, m] = -1.0
        a[m, :m] = cell_area
        rhs = np.concatenate([-z[idx], [force]])
        x = np.linalg.solve(a, rhs)
        p = np.zeros(n)
        p[idx] = x[:m]
        d = x[m]
        gap = k @ p + z - d
        if p.min() < -1e-14 * p.max():
            contact[idx[x[:m] < 0]] = False
            continue
        outside = (~contact) & (gap < -1e-14 * z.std())
        if not outside.any():
            return p, d
        contact |= outside
    raise RuntimeError("active set did not settle")


def test_periodic_matches_dense_numpy_solve_16():
    n, e_star = 16, 2.0
    h = rough(n)
    z = (h.max() - h).ravel()
    force = 0.02 * e_star
    p_ref, d_ref = active_set(periodic_matrix(n, n, 1.0, 1.0, e_star), z, force, 1.0 / n**2)
    r = mrdw.Contact(h, e_star=e_star).solve(force=force, tolerance=1e-13)
    assert 0 < r.contact_fraction < 1
    peak = p_ref.max()
    assert np.max(np.abs(r.pressure.ravel() - p_ref)) < 1e-9 * peak
    assert abs(r.approach - d_ref) < 1e-9 * abs(d_ref)
    assert r.force == pytest.approx(force, rel=1e-12)
    assert r.mean_pressure == pytest.approx(force, rel=1e-12)  # area 1
    # the gap vanishes on contact (to rounding) and is non-negative elsewhere
    assert np.abs(r.gap[r.pressure > 0]).max() < 1e-12 * h.std()
    assert r.gap.min() >= -1e-9 * h.std()


def test_hertz_nonperiodic():
    """Sphere R = 1 on a 128^2 non-periodic grid, a = L/4: approach and peak within
    2e-4 of Hertz (the CLI's test asserts 2e-5 at 256^2)."""
    n, lx, radius, e_star = 128, 1.0, 1.0, 1.0
    x = (np.arange(n) + 0.5) * lx / n - lx / 2
    xx, yy = np.meshgrid(x, x)
    h = -(xx**2 + yy**2) / (2 * radius)
    a = lx / 4
    force = 4 * e_star * a**3 / (3 * radius)
    r = mrdw.Contact(h, size=(lx, lx), e_star=e_star, periodic=False).solve(force=force)
    d_hertz = a * a / radius
    p0 = 2 * e_star * a / (np.pi * radius)
    # first contact is at the highest cell centre, which sits h[0] below the apex
    d = r.approach + (h.max() - 0.0)
    assert d == pytest.approx(d_hertz, rel=2e-3)
    assert r.pressure.max() == pytest.approx(p0, rel=2e-2)
    assert r.contact_area == pytest.approx(np.pi * a * a, rel=5e-2)


def test_control_modes_agree_and_stiffness():
    h = rough(32)
    c = mrdw.Contact(h, size=(1.0, 1.0), e_star=1.0)
    by_p = c.solve(mean_pressure=0.01, tolerance=1e-12)
    by_d = c.solve(approach=by_p.approach, tolerance=1e-12)
    assert by_d.force == pytest.approx(by_p.force, rel=1e-8)
    np.testing.assert_allclose(by_d.pressure, by_p.pressure, atol=1e-8 * by_p.pressure.max())
    s = c.solve(mean_pressure=0.01, tolerance=1e-12, stiffness=True).stiffness
    # central difference of F(d)
    eps = 1e-4 * by_p.approach
    f1 = c.solve(approach=by_p.approach + eps, tolerance=1e-12).force
    f0 = c.solve(approach=by_p.approach - eps, tolerance=1e-12).force
    assert s == pytest.approx((f1 - f0) / (2 * eps), rel=1e-3)
    assert by_p.stiffness is None


def test_complete_contact_and_mask():
    h = rough(16)
    c = mrdw.Contact(h, e_star=1.0)
    r = c.solve(mean_pressure=3.0, stiffness=True)
    assert r.complete_contact and r.contact_fraction == 1.0
    assert r.stiffness == float("inf")
    mask = np.zeros((16, 16), bool)
    mask[4:12, 4:12] = True
    r = mrdw.Contact(h, mask=mask).solve(mean_pressure=0.005)
    assert np.all(r.pressure[~mask] == 0.0)
    assert r.contact_cells <= 64


def test_load_ladder_warm_starts_and_matches_cold():
    h = rough(64)
    c = mrdw.Contact(h)
    loads = [0.01, 0.0104, 0.0108, 0.0112]  # 4 % steps: inside the warm-start window
    warm = c.solve_many(mean_pressures=loads, tolerance=1e-11)
    assert any(r.warm_started for r in warm[1:])
    for p, r in zip(loads, warm):
        cold = c.solve(mean_pressure=p, tolerance=1e-11)
        assert r.iterations <= cold.iterations
        np.testing.assert_allclose(r.pressure, cold.pressure, atol=1e-7 * cold.pressure.max())
    again = c.solve(mean_pressure=0.0103, warm=warm[0], tolerance=1e-11)
    assert again.warm_started


def test_bad_input_raises_value_error():
    h = rough(16)
    with pytest.raises(ValueError, match="exactly one of"):
        mrdw.Contact(h).solve(force=1.0, approach=0.1)
    with pytest.raises(ValueError, match="e_star"):
        mrdw.Contact(h, e_star=-1.0)
    with pytest.raises(ValueError, match="size"):
        mrdw.Contact(h, size=(0.0, 1.0))
    bad = h.copy()
    bad[3, 5] = np.nan
    with pytest.raises(ValueError, match="non-finite height at row 3, column 5"):
        mrdw.Contact(bad)
    with pytest.raises(ValueError, match="mask"):
        mrdw.Contact(h, mask=np.ones((4, 4), bool))
    with pytest.raises(ValueError, match="no solution"):
        mrdw.Contact(h).solve(approach=10.0)  # beyond complete contact of a periodic map
    with pytest.raises(ValueError, match="2 x 2"):
        mrdw.Contact(np.zeros((1, 8)))
    # a grid that cannot fit in memory is refused before anything is allocated (a
    # broadcast view: no memory behind it)
    with pytest.raises(MemoryError, match="needs about .* GB of memory"):
        mrdw.Contact(np.broadcast_to(0.0, (100_000, 100_000)))


def test_iteration_cap_raises_convergence_error_with_last_iterate():
    h = rough(64)
    with pytest.raises(mrdw.ConvergenceError) as info:
        mrdw.Contact(h).solve(mean_pressure=0.01, max_iterations=3)
    e = info.value
    assert e.iterations == 3 and e.residual > 1e-10 and e.what == "contact solve"
    assert isinstance(e.last, mrdw.ContactResult)
    assert e.last.pressure.shape == (64, 64)
    assert e.last.force == pytest.approx(0.01, rel=1e-12)
    assert "did not converge" in str(e)


def test_solve_releases_the_gil():
    """Another Python thread runs while a solve is under way. With a switch interval of
    1000 s, a thread that held the GIL through the solve would keep it: the counter
    could not move between the solver thread's two reads."""
    h = rough(256)
    c = mrdw.Contact(h)
    counter = [0]
    seen = {}
    started = threading.Event()
    done = threading.Event()

    def work():
        started.set()
        before = counter[0]
        c.solve(mean_pressure=0.01)
        seen["moved"] = counter[0] - before
        done.set()

    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        t = threading.Thread(target=work)
        t.start()
        started.wait()
        while not done.is_set():
            counter[0] += 1
            time.sleep(1e-6)  # blocks briefly, releasing the GIL so the solver can return
        t.join()
    finally:
        sys.setswitchinterval(old)
    assert seen["moved"] > 0


def test_low_contact_runs_restricted_and_says_so():
    h = rough(64)
    c = mrdw.Contact(h)
    low = c.solve(mean_pressure=1e-4)
    assert low.restricted and 0 < low.contact_cells < 3 * 64
    assert low.path == "candidate set"
    assert low.residual <= 1e-10
    high = c.solve(mean_pressure=0.05)
    assert not high.restricted and high.path == "full grid"
    # The strategies of the full-grid iteration are counted in its iterations.
    assert 0 <= high.single_precision_iterations <= high.iterations
    assert 0 <= high.stencil_iterations <= high.iterations
    assert high.single_precision_iterations > 0
    assert high.nested_start is False  # 64^2: below the nested start's 512 cells a side


def test_paths_can_be_forced_or_forbidden():
    h = rough(64)
    c = mrdw.Contact(h)
    base = c.solve(mean_pressure=0.05)
    forced = c.solve(mean_pressure=0.05, paths={"stencil": "force", "nested_start": "force"})
    assert forced.stencil_iterations == forced.iterations and forced.nested_start
    plain = c.solve(mean_pressure=0.05, paths={"single_precision": "forbid"})
    assert plain.single_precision_iterations == 0
    assert not base.scaled_directions  # 64^2: below the 2048^2 cells where it is allowed
    scaled = c.solve(mean_pressure=0.05, paths={"scaled_directions": "force"})
    assert scaled.scaled_directions
    for r in (forced, plain, scaled):
        assert np.abs(r.pressure - base.pressure).max() <= 1e-8 * base.pressure.max()
    # A forced path that cannot run, and bad names or values, are ValueErrors.
    with pytest.raises(ValueError, match="forced window"):
        c.solve(mean_pressure=0.05, paths={"window": "force"})
    with pytest.raises(ValueError, match="no strategy"):
        c.solve(mean_pressure=0.05, paths={"windw": "force"})
    with pytest.raises(ValueError, match="forbid"):
        c.solve_many(mean_pressures=[0.05], paths={"window": "always"})


def test_certificate_is_reported_and_within_the_tolerance():
    # The certificate's value and bound are tested in Rust (bem3d/tests/certificate.rs);
    # here: it reaches Python, within the tolerance, and larger at a looser tolerance.
    h = rough(64)
    tight = mrdw.Contact(h).solve(mean_pressure=0.05, tolerance=1e-10)
    loose = mrdw.Contact(h).solve(mean_pressure=0.05, tolerance=1e-4)
    assert 0 < tight.certificate <= 1e-10
    assert tight.certificate < loose.certificate <= 1e-4
    assert "certificate=" in repr(loose)


class TopographyLike:
    """Stands in for a SurfaceTopography Topography: heights() indexed (x, y),
    physical_sizes (lx, ly), and is_periodic where given."""

    def __init__(self, heights_xy, sizes, periodic=None):
        self._h = heights_xy
        self.physical_sizes = sizes
        if periodic is not None:
            self.is_periodic = periodic

    def heights(self):
        return self._h


def test_a_topography_object_is_taken_as_its_array():
    h = rough(64)[:48]  # 48 rows (y) x 64 columns (x): a mix-up of axes would show
    lx, ly = 2.0, 1.5
    ref = mrdw.Contact(h, size=(lx, ly), periodic=False).solve(mean_pressure=0.02)
    topo = TopographyLike(h.T, (lx, ly), periodic=False)
    c = mrdw.Contact(topo)
    assert c.shape == (48, 64) and c.size == (lx, ly)
    r = c.solve(mean_pressure=0.02)
    assert np.array_equal(r.pressure, ref.pressure)
    assert np.array_equal(mrdw.read_topography(topo), h)
    # Arguments override the object's attributes; without is_periodic: periodic.
    assert np.array_equal(
        mrdw.Contact(topo, periodic=True).solve(mean_pressure=0.02).pressure,
        mrdw.Contact(h, size=(lx, ly)).solve(mean_pressure=0.02).pressure,
    )
    assert mrdw.Contact(TopographyLike(h.T, (lx, ly))).periodic
    with pytest.raises(ValueError, match="physical_sizes"):
        mrdw.Contact(TopographyLike(h.T, "wide"))
    # A topography of unknown size needs size=.
    with pytest.raises(ValueError, match="give size="):
        mrdw.Contact(TopographyLike(h.T, None))
    sized = mrdw.Contact(TopographyLike(h.T, None, periodic=False), size=(lx, ly))
    assert np.array_equal(sized.solve(mean_pressure=0.02).pressure, ref.pressure)


def test_a_surfacetopography_topography_when_installed():
    st = pytest.importorskip("SurfaceTopography")
    h = rough(64)[:48]
    topo = st.Topography(np.ascontiguousarray(h.T), (2.0, 1.5), periodic=True)
    r = mrdw.Contact(topo).solve(mean_pressure=0.02)
    ref = mrdw.Contact(h, size=(2.0, 1.5), periodic=True).solve(mean_pressure=0.02)
    assert np.array_equal(r.pressure, ref.pressure)


def test_heights_are_read_in_place_bit_for_bit_and_a_change_is_refused():
    """Contact reads a C-ordered float64 array in place (no copy beside the caller's):
    the solve equals that of a copied (F-ordered) array bit for bit, periodic and free,
    and a solve after the array changed raises ValueError naming the heights."""
    n = 48
    x = (np.arange(n) + 0.5) / n - 0.5
    h = -(x[:, None] ** 2 + x[None, :] ** 2) + 1e-3 * np.sin(23 * x)[:, None] * np.cos(17 * x)[None, :]
    for periodic in (True, False):
        a = mrdw.Contact(h, periodic=periodic).solve(mean_pressure=1e-3)
        b = mrdw.Contact(np.asfortranarray(h), periodic=periodic).solve(mean_pressure=1e-3)
        assert np.array_equal(a.pressure, b.pressure) and a.iterations == b.iterations
    c = mrdw.Contact(h)
    c.solve(mean_pressure=1e-3)
    h[5, 7] = np.nextafter(h[5, 7], 1.0)
    with pytest.raises(ValueError, match="heights: the array changed"):
        c.solve(mean_pressure=1e-3)


@pytest.mark.parametrize("periodic", [True, False])
def test_every_grid_class_reports_its_shape_size_and_periodicity(periodic):
    """Contact, TransientContact, AdhesiveContact and CohesiveContact share the getters
    shape (ny, nx), size (lx, ly) and periodic, as given to the constructor."""
    h = np.zeros((6, 8))
    h[3, 4] = 1e-3
    size = (2.0, 1.5)
    grids = [
        mrdw.Contact(h, size=size, periodic=periodic),
        mrdw.TransientContact(h, 1.0, [(1.0, 1.0)], size=size, periodic=periodic),
        mrdw.AdhesiveContact(h, work=1e-3, size=size, periodic=periodic),
        mrdw.CohesiveContact(h, work=1e-3, sigma0=0.1, size=size, periodic=periodic),
    ]
    for g in grids:
        assert (g.shape, g.size, g.periodic) == ((6, 8), size, periodic), repr(g)
        assert f"periodic={periodic}" in repr(g)
