"""Tangential contact in 3D from numpy: partial slip and the stick stiffness."""

import math

import numpy as np
import pytest

import mrdw


def waves(n):
    """A periodic surface with several contact spots."""
    x = np.arange(n) / n
    X, Y = np.meshgrid(x, x)
    t = 2 * math.pi
    return 0.01 * (np.cos(3 * t * X) + np.cos(2 * t * Y)) + 0.004 * np.cos(t * (5 * X + 3 * Y))


def test_at_nu_zero_partial_slip_is_the_normal_curve_shifted():
    # Ciavarella-Jaeger, exact on the grid when Cerruti's operator is the normal one:
    # the shift at Q is mu (d - d'), with F_N(d') = F_N(d) - Q / mu.
    c = mrdw.Contact(waves(64), size=(1.0, 1.0), e_star=1.0, periodic=True)
    f, mu = 0.002, 0.4
    r = c.solve(force=f, tolerance=1e-12)
    ps = mrdw.PartialSlip(r.pressure, mu, poisson=0.0)
    assert ps.friction_limit == pytest.approx(mu * f, rel=1e-9)
    for x in (0.2, 0.5, 0.8):
        s = ps.load(x * mu * f, tolerance=1e-10)
        reduced = c.solve(force=(1 - x) * f, tolerance=1e-12)
        assert s.shift == pytest.approx(mu * (r.approach - reduced.approach), rel=1e-6)
        assert s.stick_cells == int((reduced.pressure > 0).sum())
    for q in (ps.friction_limit, -1.5 * ps.friction_limit):
        s = ps.load(q)
        # How far the body slides at mu P is not set by a quasi-static step: no number
        # is made up for it (no NaN either).
        assert s.sliding and s.shift is None and s.dissipated is None
        assert "shift=None" in repr(s)


def test_on_the_free_half_space_the_shift_is_mindlins():
    # Cattaneo-Mindlin on the free half-space (no periodic images, absolute shift):
    # delta = 3 mu P (2 - nu) / (16 G a) [1 - (1 - Q/(mu P))^(2/3)], G = E* (1 - nu) / 2,
    # at 25.6 cells per contact radius (measured 1.3e-4 in bem3d's unit test).
    n, a, mu, nu = 64, 0.4, 0.3, 0.5
    x = (np.arange(n) + 0.5) / n - 0.5
    X, Y = np.meshgrid(x, x)
    c = mrdw.Contact(-(X**2 + Y**2) / 2, periodic=False)
    r = c.solve(force=4 * a**3 / 3, tolerance=1e-10)
    ps = mrdw.PartialSlip(r.pressure, mu, poisson=nu, periodic=False)
    s = ps.load(0.5 * ps.friction_limit, tolerance=1e-9)
    big_p = ps.friction_limit / mu
    g = (1 - nu) / 2
    mindlin = 3 * mu * big_p * (2 - nu) / (16 * g * a) * (1 - 0.5 ** (2 / 3))
    assert s.shift == pytest.approx(mindlin, rel=1e-3)
    # The periodic operator on the same map measures the shift from the mean surface
    # displacement instead: a different number.
    periodic = mrdw.PartialSlip(r.pressure, mu, poisson=nu).load(0.5 * ps.friction_limit)
    assert abs(periodic.shift / mindlin - 1) > 0.1


def test_a_circle_held_in_stick_has_mindlins_ratio():
    n = 128
    x = (np.arange(n) + 0.5) / n
    X, Y = np.meshgrid(x, x)
    disc = (X - 0.5) ** 2 + (Y - 0.5) ** 2 < (1 / 16) ** 2
    kx, ky, along = mrdw.stick_stiffness(disc, poisson=0.5)
    kn, _, _ = mrdw.stick_stiffness(disc, poisson=0.0, e_star=1.0)  # nu = 0: the normal one
    assert kx / kn == pytest.approx(2 / 3, rel=2e-3)
    assert ky == pytest.approx(kx, rel=1e-12)
    assert along < kx


def test_views_of_any_strides_are_read_in_their_logical_order():
    # A slice or a transposed view solves as its contiguous copy does, bit for bit.
    c = mrdw.Contact(waves(128), periodic=True)
    p = c.solve(force=0.002).pressure
    for view in (p[::2, ::2], p[::2, ::2].T, p[:, 5:69]):
        copy = np.ascontiguousarray(view)
        a = mrdw.PartialSlip(view, 0.5).load(0.2 * 0.5 * view.sum() / view.size)
        b = mrdw.PartialSlip(copy, 0.5).load(0.2 * 0.5 * copy.sum() / copy.size)
        assert (a.shift, a.stick_cells) == (b.shift, b.stick_cells)
        v = mrdw.ViscoelasticSlip(view, 0.5, 1.0, terms=[(1.0, 1.0)], periodic=True)
        w = mrdw.ViscoelasticSlip(copy, 0.5, 1.0, terms=[(1.0, 1.0)], periodic=True)
        assert v.step(0.1, 1e-4).force == w.step(0.1, 1e-4).force
    disc = np.zeros((32, 64), dtype=bool)
    disc[10:20, 20:40] = True
    assert mrdw.stick_stiffness(disc[:, ::2]) == mrdw.stick_stiffness(
        np.ascontiguousarray(disc[:, ::2])
    )


def test_a_cycle_dissipates_its_loop():
    c = mrdw.Contact(waves(64), periodic=True)
    r = c.solve(force=0.002)
    ps = mrdw.PartialSlip(r.pressure, 0.5)
    w, area = ps.cycle(0.5 * ps.friction_limit, steps=8)
    assert w > 0 and area == pytest.approx(w, rel=0.05)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"mu": 0.0},
        {"mu": float("nan")},
        {"mu": 1e12},
        {"mu": 0.5, "poisson": 0.7},
        {"mu": 0.5, "e_star": -1.0},
    ],
)
def test_bad_input_is_a_value_error(kwargs):
    p = np.zeros((16, 16))
    p[4:8, 4:8] = 1.0
    with pytest.raises(ValueError):
        mrdw.PartialSlip(p, **kwargs)


def test_no_contact_and_bad_cycles_are_value_errors():
    with pytest.raises(ValueError, match="no cell is in contact"):
        mrdw.PartialSlip(np.zeros((16, 16)), 0.5)
    p = np.zeros((16, 16))
    p[4:8, 4:8] = 1.0
    ps = mrdw.PartialSlip(p, 0.5)
    with pytest.raises(ValueError, match="slides"):
        ps.cycle(ps.friction_limit)
    with pytest.raises(ValueError):
        ps.load(float("nan"))


def test_viscoelastic_slip_in_full_stick_is_the_hereditary_integral():
    # Q(t) = k0 Int G(t - t') d delta(t'): a ramp and a hold, one Maxwell term.
    n, a = 32, 0.4
    x = (np.arange(n) + 0.5) / n - 0.5
    X, Y = np.meshgrid(x, x)
    p = np.sqrt(np.maximum(1 - (X**2 + Y**2) / a**2, 0))
    mu = 1e6
    k0 = 1e-3 / mrdw.PartialSlip(p, mu, e_star=4.0, periodic=False).load(1e-3, tolerance=1e-12).shift
    g_inf, g1, tau, rate, dt = 0.5, 1.5, 0.3, 1e-3, 0.05
    ve = mrdw.ViscoelasticSlip(p, mu, g_inf, [(g1, tau)])
    for k in range(1, 41):
        t = k * dt
        s = ve.step(dt, rate * min(t, 1.0), tolerance=1e-12)
        memory = rate * tau * (1 - math.exp(-min(t, 1.0) / tau)) * math.exp(-max(t - 1.0, 0) / tau)
        assert s.force == pytest.approx(k0 * (g_inf * rate * min(t, 1.0) + g1 * memory), rel=1e-7)
        assert s.slip_cells == 0 and not s.sliding


def test_viscoelastic_slip_matches_the_cli_scene(mrdw_bin, tmp_path):
    from conftest import run_coarse

    n = 32
    data, results = run_coarse(
        mrdw_bin, "tangential-viscoelastic-3d", tmp_path, "tangential_viscoelastic_3d.csv", cells_3d=n
    )
    # The scene on a coarser grid: a sphere R = 5 pressed with 0.1 on E* = 1, n^2 cells
    # over 2.5 contact radii (the side from the summary) on the free half-space;
    # G*(t) = 2/3 + 2 exp(-t / 0.5), mu = 0.3: the same forces bit for bit.
    side = results["tangential_viscoelastic.grid_side_3d"]
    r, f = 5.0, 0.1
    h = side / n
    x = (np.arange(n) + 0.5) * h - 0.5 * side
    X, Y = np.meshgrid(x, x)
    sol = mrdw.Contact(-(X**2 + Y**2) / (2 * r), size=(side, side), periodic=False).solve(
        force=f, tolerance=1e-8
    )
    g_star_inf = 0.6666666666666666
    rho = g_star_inf / 1.0
    nu = (2 - 2 * rho) / (2 - rho)
    c = (2 - nu) / 4
    ve = mrdw.ViscoelasticSlip(sol.pressure, 0.3, c * g_star_inf, [(c * 2.0, 0.5)], size=(side, side), poisson=nu)
    dt = data[0, 0]
    forces = np.array([ve.step(dt, ux).force for ux in data[:, 1]])
    assert np.array_equal(forces, data[:, 3])


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"mu": 0.0, "relaxed": 1.0}, "mu"),
        ({"mu": 0.3, "relaxed": float("nan")}, "relaxed"),
        ({"mu": 0.3, "relaxed": 1.0, "terms": [(1.0, -0.5)]}, "Prony"),
        ({"mu": 0.3, "relaxed": 0.0}, "vanishes"),
        ({"mu": 0.3, "relaxed": 1.0, "poisson": 0.7}, "poisson"),
    ],
)
def test_viscoelastic_slip_bad_input_is_a_value_error(kwargs, match):
    p = np.zeros((16, 16))
    p[4:8, 4:8] = 1.0
    with pytest.raises(ValueError, match=match):
        mrdw.ViscoelasticSlip(p, **kwargs)
    ve = mrdw.ViscoelasticSlip(p, 0.3, 1.0, [(1.0, 0.5)])
    for dt, shift, key in [(0.0, 0.1, "dt"), (0.1, float("inf"), "shift")]:
        with pytest.raises(ValueError, match=key):
            ve.step(dt, shift)
    with pytest.raises(ValueError, match="no cell is in contact"):
        mrdw.ViscoelasticSlip(np.zeros((16, 16)), 0.3, 1.0)


def test_partial_slip_loops_match_the_cli_scene(mrdw_bin, tmp_path):
    from conftest import run_coarse

    n = 48
    data, results = run_coarse(mrdw_bin, "tangential-3d-free", tmp_path, "loops.csv", cells=n)
    # The scene on a coarser grid: a sphere R = 10 pressed with 1 on E* = 4 (E = 3,
    # nu = 0.5 under a rigid body), n^2 cells on the free half-space, mu = 0.5, tolerance
    # 1e-8; the first loop (amplitude 0.2 mu P) after loading in 20 steps and one cycle:
    # the same shifts bit for bit.
    side, nu = results["tangential_3d.grid_side_3d"], results["tangential_3d.poisson_3d"]
    h = side / n
    x = (np.arange(n) + 0.5) * h - 0.5 * side
    X, Y = np.meshgrid(x, x)
    sol = mrdw.Contact(-(X * X + Y * Y) / (2 * 10.0), size=(side, side), e_star=4.0, periodic=False).solve(
        force=1.0, tolerance=1e-8
    )
    slip = mrdw.PartialSlip(sol.pressure, 0.5, size=(side, side), e_star=4.0, poisson=nu, periodic=False)
    amp, steps = 0.2 * slip.friction_limit, 20
    for k in range(1, steps + 1):
        slip.load(amp * k / steps)
    for _ in range(2):
        shifts = [slip.load(amp).shift]
        for k in range(1, 2 * steps + 1):
            f = amp * (1.0 - 2.0 * k / steps) if k <= steps else amp * (-1.0 + 2.0 * (k - steps) / steps)
            shifts.append(slip.load(f).shift)
    first = data[data[:, 0] == 0.2]
    assert len(first) == 2 * steps + 1
    assert np.array_equal(np.array(shifts), first[:, -1])
