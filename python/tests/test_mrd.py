"""MRD for axisymmetric contacts from Python, against closed forms of the literature:
Hertz, Sneddon's cone, the flat punch, JKR, Cattaneo-Mindlin and Mindlin's damping."""

import math

import numpy as np
import pytest

import mrdw

E, R = 2.0, 1.5


def test_rule_of_hess_closed_form_quadrature_and_inverse():
    s = mrdw.Profile.sphere(R)
    x = np.linspace(0.0, 0.8, 9)
    np.testing.assert_allclose(s.z1d(x), x**2 / R, rtol=1e-15)  # Eq. (13)
    np.testing.assert_allclose(s.z1d_numeric(x), x**2 / R, rtol=1e-9)
    cone = mrdw.Profile.cone(0.3)
    np.testing.assert_allclose(cone.z1d(x), np.pi / 2 * 0.3 * np.abs(x), rtol=1e-15)  # Eq. (14)
    pl = mrdw.Profile.power_law(0.7, 2.5)
    # Eq. (15): kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2)
    kappa = np.sqrt(np.pi) * math.gamma(2.5 / 2 + 1) / math.gamma(2.5 / 2 + 0.5)
    np.testing.assert_allclose(pl.z1d(x), kappa * 0.7 * np.abs(x) ** 2.5, rtol=1e-13)
    # inverse rule: a fine piecewise-linear g = x^2 / R back to z = r^2 / (2R)
    xs = np.linspace(0.0, 1.0, 4001)
    r = np.array([0.1, 0.4, 0.9])
    bound = (xs[1] - xs[0]) ** 2 / 8 * (2 / R)  # linear interpolation error of g
    np.testing.assert_allclose(mrdw.hess_inverse(xs, xs**2 / R, r), r**2 / (2 * R), rtol=0, atol=bound)
    with pytest.raises(ValueError, match="exceeds"):
        mrdw.hess_inverse(xs, xs**2 / R, [1.5])


def test_hertz_normal_contact_and_pressure():
    s = mrdw.Profile.sphere(R)
    d = 0.01
    st = mrdw.normal(s, E, depth=d)
    a = np.sqrt(R * d)
    assert st["radius"] == pytest.approx(a, rel=1e-12)
    assert st["force"] == pytest.approx(4 / 3 * E * np.sqrt(R) * d**1.5, rel=1e-12)
    assert st["stiffness"] == pytest.approx(2 * a * E, rel=1e-12)  # Eq. (20)
    back = mrdw.normal(s, E, force=st["force"])
    assert back["depth"] == pytest.approx(d, rel=1e-10)
    assert mrdw.normal(s, E, radius=a)["force"] == pytest.approx(st["force"], rel=1e-12)
    r = np.array([0.0, 0.3 * a, 0.9 * a, 1.1 * a])
    p = mrdw.pressure(s, E, r, depth=d)
    p_hertz = 2 * E / (np.pi * R) * np.sqrt(np.maximum(a * a - r * r, 0.0))
    np.testing.assert_allclose(p, p_hertz, rtol=1e-9, atol=1e-12 * p_hertz.max())


def test_cone_and_flat_punch():
    t, d = 0.2, 0.05
    st = mrdw.normal(mrdw.Profile.cone(t), E, depth=d)
    a = 2 * d / (np.pi * t)
    assert st["radius"] == pytest.approx(a, rel=1e-12)
    assert st["force"] == pytest.approx(np.pi / 2 * E * t * a * a, rel=1e-12)  # Sneddon / Love
    fp = mrdw.normal(mrdw.Profile.flat_punch(0.4), E, depth=d)
    assert fp["force"] == pytest.approx(2 * 0.4 * E * d, rel=1e-15)  # Eq. (1)
    both = mrdw.Profile.sphere(R) + mrdw.Profile.cone(t)
    assert both.z([0.3])[0] == pytest.approx(0.09 / (2 * R) + 0.3 * t, rel=1e-15)


def test_jkr_branch_and_pull_off():
    s, gamma = mrdw.Profile.sphere(R), 0.01
    a = 0.2
    st = mrdw.adhesion(s, E, gamma, a)
    assert st["depth"] == pytest.approx(a * a / R - np.sqrt(2 * np.pi * a * gamma / E), rel=1e-12)
    assert st["force"] == pytest.approx(4 * E * a**3 / (3 * R) - np.sqrt(8 * np.pi * gamma * E * a**3), rel=1e-12)
    f = mrdw.pull_off(s, E, gamma, control="force", max_radius=1.0)
    assert f["force"] == pytest.approx(-1.5 * np.pi * R * gamma, rel=1e-9)  # Eq. (34)
    g = mrdw.pull_off(s, E, gamma, control="displacement", max_radius=1.0)
    assert g["force"] == pytest.approx(-5 / 6 * np.pi * R * gamma, rel=1e-9)  # Eq. (37)
    with pytest.raises(ValueError, match="max_radius"):
        mrdw.pull_off(s, E, gamma)
    with pytest.raises(ValueError, match="control"):
        mrdw.pull_off(s, E, gamma, control="both", max_radius=1.0)


def test_cattaneo_mindlin():
    s, g_star, mu, fn = mrdw.Profile.sphere(R), 1.2, 0.4, 0.01
    n = mrdw.normal(s, E, force=fn)
    for fx in [0.0, 0.3 * mu * fn, 0.9 * mu * fn]:
        t = mrdw.cattaneo_mindlin(s, E, g_star, mu, fn, fx)
        ratio = 1 - fx / (mu * fn)
        assert t["contact_radius"] == pytest.approx(n["radius"], rel=1e-12)
        assert t["stick_radius"] == pytest.approx(n["radius"] * ratio ** (1 / 3), rel=1e-9)  # Eq. (49)
        u = mu * E / g_star * n["depth"] * (1 - ratio ** (2 / 3))
        assert t["displacement"] == pytest.approx(u, rel=1e-9, abs=1e-15)
    assert t["max_displacement"] == pytest.approx(mu * E / g_star * n["depth"], rel=1e-12)  # Eq. (50)


def test_damping_matches_mindlin_integral():
    """W = 4 mu E* sqrt(R) Int_0^ds delta (A - mu beta delta) (d - delta)^(-1/2) d delta,
    ds = min(d, A / (mu beta)); by the substitution s^2 = d - delta, numerically."""
    s, g_star, mu, d = mrdw.Profile.sphere(R), 1.5, 0.5, 0.02
    beta = E / g_star
    for amp in [0.1 * mu * beta * d, 0.7 * mu * beta * d]:
        ds = min(d, amp / (mu * beta))
        t = np.linspace(np.sqrt(d - ds), np.sqrt(d), 200001)
        delta = d - t * t
        f = 2 * delta * (amp - mu * beta * delta)
        w = 4 * mu * E * np.sqrt(R) * np.sum((f[1:] + f[:-1]) / 2 * np.diff(t))
        assert mrdw.damping(s, E, g_star, mu, d, amp) == pytest.approx(w, rel=1e-8)


def test_mrd_bad_input():
    with pytest.raises(ValueError, match="radius"):
        mrdw.Profile.sphere(-1.0)
    with pytest.raises(ValueError, match="exactly one of"):
        mrdw.normal(mrdw.Profile.sphere(1.0), 1.0, depth=0.1, force=0.1)
    with pytest.raises(ValueError, match="e_star"):
        mrdw.normal(mrdw.Profile.sphere(1.0), 0.0, depth=0.1)
    with pytest.raises(ValueError, match="exceeds"):
        mrdw.normal(mrdw.Profile.flat_punch(0.1), 1.0, radius=0.2)
