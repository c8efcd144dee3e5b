"""mrdw.ContactLaw: a contact law in the user's own integrator (Section 12), MRD's springs
and the 3D solve behind one class, checked against Hertz's impact solution."""

import math

import numpy as np
import pytest

import mrdw

E, R, M, V = 1.0, 1.0, 1e-3, 0.05


def hertz_impact():
    d = (15 * M * V * V / (16 * E * math.sqrt(R))) ** 0.4
    c = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
    return c * d / V, 4 / 3 * E * math.sqrt(R) * d**1.5, d


def impact(law, steps):
    """A plain velocity-Verlet loop: the contact time and largest force."""
    tc, _, d = hertz_impact()
    dt = tc / steps
    x, v = -1e-3 * d, V
    a = -law.trial(x).normal / M
    law.commit()
    t, t_in, peak = 0.0, None, 0.0
    while t < 1.3 * tc:
        half = v + 0.5 * dt * a
        x_new = x + dt * half
        f = law.trial(x_new, dt=dt)
        law.commit()
        a = -f.normal / M
        v = half + 0.5 * dt * a
        if x <= 0 < x_new:
            t_in = t + dt * (-x / (x_new - x))
        if x > 0 >= x_new:
            return t + dt * (x / (x - x_new)) - t_in, peak
        peak = max(peak, f.normal)
        x, t = x_new, t + dt
    raise AssertionError("no separation")


def test_hertz_impact_in_a_users_loop_with_mrd_and_3d():
    tc, fmax, d = hertz_impact()
    a = math.sqrt(R * d)
    law = mrdw.ContactLaw.body(mrdw.Profile.sphere(R), e_star=E, springs=4000, half_length=2 * a)
    t, peak = impact(law, 2000)
    assert abs(t / tc - 1) < 1e-4 and abs(peak / fmax - 1) < 1e-3
    n, side = 48, 3 * a
    x = (np.arange(n) + 0.5) * side / n - side / 2
    h = -(x[None, :] ** 2 + x[:, None] ** 2) / (2 * R)
    t3, peak3 = impact(mrdw.ContactLaw.bem3d(h, size=(side, side), e_star=E), 200)
    assert abs(t3 / tc - 1) < 5e-3 and abs(peak3 / fmax - 1) < 5e-3


def test_trial_commit_rollback():
    law = mrdw.ContactLaw.body(mrdw.Profile.sphere(1.0), springs=500, half_length=0.3,
                               g_star=0.8, mu=0.3)
    d = law.approach_at(1e-3)
    law.trial(d, 0.0)
    law.commit()
    first = law.trial(d, 1e-4)
    law.rollback()
    law.trial(d, 5e-4)  # another trial replaces it ...
    law.rollback()
    again = law.trial(d, 1e-4)  # ... and the state is the accepted one
    assert again.tangential == first.tangential and again.tangential > 0
    law.commit()
    assert law.committed.tangential == again.tangential
    with pytest.raises(ValueError, match="no trial"):
        law.commit()


def test_bad_input_names_the_parameter():
    sphere = mrdw.Profile.sphere(1.0)
    with pytest.raises(ValueError, match="half_length"):
        mrdw.ContactLaw.body(sphere)
    with pytest.raises(ValueError, match="g_star and mu"):
        mrdw.ContactLaw.body(sphere, half_length=0.3, mu=0.3)
    law = mrdw.ContactLaw.body(sphere, half_length=0.3)
    with pytest.raises(ValueError, match="dt"):
        law.trial(0.01, dt=0.0)
    with pytest.raises(ValueError, match="finite"):
        law.trial(float("nan"))
    h = np.zeros((16, 16))
    with pytest.raises(ValueError, match="frictionless"):
        mrdw.ContactLaw.bem3d(h, size=(1.0, 1.0)).trial(0.01, tangential=1e-3)


def rebound(law, v_in, tc, d, steps):
    """Velocity Verlet through one impact on a law with memory: the speed ratio out / in."""
    dt = tc / steps
    x, v = -1e-3 * d, v_in
    a = -law.trial(x, dt=dt).normal / M
    law.commit()
    for _ in range(3 * steps):
        half = v + 0.5 * dt * a
        x_new = x + dt * half
        f = law.trial(x_new, dt=dt)
        law.commit()
        a = -f.normal / M
        v_new = half + 0.5 * dt * a
        if x > 0 >= x_new:
            w = x / (x - x_new)
            return -(v + w * (v_new - v)) / v_in
        x, v = x_new, v_new
    raise AssertionError("no separation")


def test_viscoelastic_impact_in_a_users_loop_with_mrd_and_3d():
    # The `viscoelastic-impact` scene's sphere at v = 1e-3 on E*(t) = 1 + 3 exp(-t / 0.5):
    # the CLI gives restitution 0.77784 by MRD (0.77786 in 3D on 64^2 cells).
    v, terms = 1e-3, [(3.0, 0.5)]
    d = (15 * M * v * v / (16 * 1.0 * math.sqrt(R))) ** 0.4
    tc = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9) * d / v
    a = math.sqrt(R * d)
    law = mrdw.ContactLaw.viscoelastic_body(mrdw.Profile.sphere(R), 1.0, terms, springs=2000,
                                            half_length=1.5 * a)
    e_mrd = rebound(law, v, tc, d, 2000)
    assert abs(e_mrd - 0.77784) < 1e-4
    n, side = 32, 2.6 * a
    x = (np.arange(n) + 0.5) * side / n - side / 2
    h = -(x[None, :] ** 2 + x[:, None] ** 2) / (2 * R)
    law3 = mrdw.ContactLaw.viscoelastic_bem3d(h, 1.0, terms, size=(side, side))
    e_3d = rebound(law3, v, tc, d, 200)
    assert abs(e_3d - e_mrd) < 1e-3
    with pytest.raises(ValueError, match="relaxation time"):
        mrdw.ContactLaw.viscoelastic_body(mrdw.Profile.sphere(R), 1.0, [(3.0, -1.0)],
                                          half_length=0.1)


def test_adhesive_impact_in_a_users_loop_with_mrd_and_3d():
    # The `adhesive-impact` scene's sphere (m = 1e-3, R = E* = 1, w = 1e-4) at v = 0.105,
    # 1.5 times the capture speed: the closed form (Hertz in, JKR out) gives restitution
    # 0.62943, the CLI 0.62935 by MRD and 0.5655 in 3D on 32^2 cells.
    v, w = 0.105, 1e-4
    d = (15 * M * v * v / (16 * 1.0 * math.sqrt(R))) ** 0.4
    tc = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9) * d / v
    a = max(math.sqrt(R * d), (math.pi * w * R * R / 8.0) ** (1.0 / 3.0))
    law = mrdw.ContactLaw.adhesive_body(mrdw.Profile.sphere(R), 1.0, w, springs=2000,
                                        half_length=1.5 * a)

    def released(law, steps):
        """Velocity Verlet until the sphere has left the contact: its speed out over in."""
        dt = tc / steps
        x, u = -1e-3 * d, v
        acc = -law.trial(x, dt=dt).normal / M
        law.commit()
        touched = False
        for _ in range(5 * steps):
            half = u + 0.5 * dt * acc
            x += dt * half
            f = law.trial(x, dt=dt)
            law.commit()
            acc = -f.normal / M
            u = half + 0.5 * dt * acc
            touched = touched or f.contact_area > 0
            if touched and f.contact_area == 0 and u < 0:
                return -u / v
        raise AssertionError("captured")

    assert abs(released(law, 2000) - 0.62943) < 2e-3
    n, side = 32, 2.6 * a
    x = (np.arange(n) + 0.5) * side / n - side / 2
    h = -(x[None, :] ** 2 + x[:, None] ** 2) / (2 * R)
    law3 = mrdw.ContactLaw.adhesive_bem3d(h, 1.0, w, size=(side, side))
    assert abs(released(law3, 200) - 0.62943) < 0.1
    with pytest.raises(ValueError, match="history"):
        law.approach_at(1e-4)
    with pytest.raises(ValueError, match="work"):
        mrdw.ContactLaw.adhesive_body(mrdw.Profile.sphere(R), 1.0, 0.0, half_length=0.1)


def test_slip_bem3d_follows_mrd_springs_and_names_bad_input():
    """The 3D partial slip at a held normal force (a sphere, 48^2 cells over 2.5 contact
    radii, nu = 0.3) against MRD's springs with Coulomb slip along a displacement
    history: forces within 1e-3 of mu P (the Rust test measures 8.5e-5 at 64^2); a
    rollback replays; another normal motion, a periodic map or G* / E* out of range are
    refused by name."""
    nu, mu, f = 0.3, 0.3, 1e-3
    g_star = 2 * (1 - nu) / (2 - nu)  # E* = 1
    a = (3 * f * R / (4 * E)) ** (1 / 3)
    n, side = 48, 2.5 * a
    x = (np.arange(n) + 0.5) * side / n - side / 2
    h = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)
    three = mrdw.ContactLaw.slip_bem3d(h, f, g_star, mu, size=(side, side))
    springs = mrdw.ContactLaw.body(mrdw.Profile.sphere(R), springs=4000, half_length=1.5 * a,
                                   g_star=g_star, mu=mu)
    d3, dm = three.approach_at(f), springs.approach_at(f)
    springs.trial(dm, 0.0)
    springs.commit()
    top = 3 * mu * f / (4 * g_star * a) * (1 - 0.4 ** (2 / 3))
    path = [top * k / 10 for k in range(1, 11)] + [top * (1 - k / 10) for k in range(1, 21)]
    worst = 0.0
    for u in path:
        f3 = three.trial(d3, u)
        three.commit()
        fm = springs.trial(dm, u)
        springs.commit()
        worst = max(worst, abs(f3.tangential - fm.tangential) / (mu * f))
    assert worst < 1e-3, worst
    first = three.trial(d3, 0.5 * top)
    three.rollback()
    three.trial(d3, -0.5 * top)
    assert three.trial(d3, 0.5 * top).tangential == first.tangential
    with pytest.raises(ValueError, match="normal = "):
        three.trial(1.1 * d3, 0.0)
    with pytest.raises(ValueError, match="g_star"):
        mrdw.ContactLaw.slip_bem3d(h, f, 0.3, mu, size=(side, side))
    with pytest.raises(ValueError, match="normal_force"):
        mrdw.ContactLaw.slip_bem3d(h, 0.0, g_star, mu, size=(side, side))


def test_oblique_bem3d_meets_the_sliding_impulse_and_names_bad_input():
    """A sphere (24^2 cells over 2.5 contact radii of its largest approach, nu = 0.3)
    pressed and released while moved tangentially, sliding throughout (the tangential
    displacement far beyond the stick range): the tangential force is mu times the
    normal one at every step within 1e-6; the law starts apart, a contact that forms
    again is a first contact again (the same forces at the same motion from the new
    origin), and it names bad input."""
    nu, mu, dmax = 0.3, 0.3, 1e-2
    g_star = 2 * (1 - nu) / (2 - nu)  # E* = 1
    n, side = 24, 2.5 * (R * dmax) ** 0.5
    x = (np.arange(n) + 0.5) * side / n - side / 2
    h = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)
    law = mrdw.ContactLaw.oblique_bem3d(h, g_star, mu, size=(side, side))
    assert law.trial(-1e-4, 0.0).normal == 0.0
    law.commit()
    touch = law.trial(dmax / 10, 0.0)
    law.rollback()
    steps = [dmax * k / 10 for k in range(1, 11)] + [dmax * (1 - k / 10) for k in range(1, 10)]
    for k, d in enumerate(steps):
        f = law.trial(d, 10.0 * dmax * (k + 1))
        law.commit()
        if k > 0:
            assert abs(f.tangential - mu * f.normal) <= 1e-6 * mu * f.normal, (k, f)
    assert law.trial(-1e-4, 0.0).normal == 0.0
    law.commit()
    again = law.trial(dmax / 10, 0.25)
    assert (again.normal, again.tangential) == (touch.normal, touch.tangential)
    assert again.normal > 0.0
    with pytest.raises(ValueError, match="g_star"):
        mrdw.ContactLaw.oblique_bem3d(h, 0.3, mu, size=(side, side))
    with pytest.raises(ValueError, match="mu"):
        mrdw.ContactLaw.oblique_bem3d(h, g_star, 0.0, size=(side, side))
