"""mrdw.TransientContact: the 3D transient viscoelastic solver from Python, checked
against the elastic solver at its two limits (constant modulus, long-time relaxation)."""

import numpy as np
import pytest

import mrdw


def rough(n=64):
    return mrdw.surface((n, n), (1.0, 1.0), 0.8, 2 * np.pi, 4 * np.pi, 2 * np.pi * 16,
                        rms_slope=0.1, seed=7)


def test_a_constant_modulus_is_the_elastic_contact_bit_for_bit():
    h = rough()
    v = mrdw.TransientContact(h, relaxed=2.0, terms=[])
    s = v.step(0.5, mean_pressure=0.01)
    e = mrdw.Contact(h, e_star=2.0).solve(mean_pressure=0.01)
    assert np.array_equal(s.pressure, e.pressure)
    assert s.approach == e.approach and s.time == 0.5 and s.effective_modulus == 2.0
    assert s.iterations == e.iterations > 0 and s.certificate <= 1e-10


def test_a_held_load_creeps_to_the_relaxed_elastic_contact():
    # E*(t) = 1 + 3 exp(-t): glassy 4, relaxed 1; under a held force the creep's
    # retardation time is tau E*(0) / E*(inf) = 4. After 160 (steps of 4: the scheme's
    # fixed point is exact whatever the step) the contact is the elastic one at E* = 1
    # (the creep left is about e^-40 of its amplitude).
    h = rough()
    v = mrdw.TransientContact(h, relaxed=1.0, terms=[(3.0, 1.0)])
    first = v.step(0.01, mean_pressure=0.01)
    steps = [v.step(4.0, mean_pressure=0.01) for _ in range(40)]
    approaches = [first.approach] + [s.approach for s in steps]
    assert all(b >= a - 1e-12 for a, b in zip(approaches, approaches[1:])), "creep"
    relaxed = mrdw.Contact(h, e_star=1.0).solve(mean_pressure=0.01)
    assert abs(steps[-1].approach / relaxed.approach - 1) < 1e-9  # measured 1.5e-12
    peak = relaxed.pressure.max()
    assert np.abs(steps[-1].pressure - relaxed.pressure).max() < 1e-8 * peak  # 1.5e-10
    assert abs(v.time - 160.01) < 1e-12
    # the first step is stiffer than the relaxed medium: a smaller approach
    assert first.approach < 0.9 * relaxed.approach
    assert v.displacement.shape == h.shape


def test_a_negative_approach_lifts_the_body_off():
    # Lift-off: no contact, no force, and the medium relaxes from where it was.
    h = rough(32)
    v = mrdw.TransientContact(h, relaxed=1.0, terms=[(3.0, 1.0)])
    pressed = v.step(0.1, approach=0.01)
    assert pressed.force > 0
    off = v.step(0.1, approach=-1.0)
    assert off.force == 0.0 and off.contact_cells == 0 and off.approach == -1.0
    with pytest.raises(ValueError, match="force = -1"):
        v.step(0.1, force=-1.0)


def test_bad_input_is_refused():
    h = rough(16)
    with pytest.raises(ValueError, match="Prony term"):
        mrdw.TransientContact(h, relaxed=1.0, terms=[(1.0, -2.0)])
    with pytest.raises(ValueError, match="modulus vanishes"):
        mrdw.TransientContact(h, relaxed=0.0, terms=[])
    v = mrdw.TransientContact(h, relaxed=1.0, terms=[(1.0, 1.0)])
    for dt in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="time step"):
            v.step(dt, force=0.01)
    with pytest.raises(ValueError, match="exactly one"):
        v.step(0.1, force=0.01, approach=0.1)
    with pytest.raises(ValueError, match="mask"):
        mrdw.TransientContact(h, relaxed=1.0, terms=[], mask=np.ones((4, 4), bool))
    assert v.time == 0.0


def test_a_rough_contact_in_time_matches_tamaas_to_its_first_order_error():
    # Tamaas 2.9's MaxwellViscoelastic (backward Euler, first order in dt) is a
    # generalised Maxwell medium when its elastic shear modulus E / (2 (1 + nu)) is 1
    # (bench/tamaas_viscoelastic.py; docs/verification.md): E = 3, nu = 0.5 gives
    # E*_inf = 4 and branches 4 G_k. A rough 32^2 contact through a ramp and a hold of
    # the mean pressure: the two solvers' pressures differ by Tamaas' time-stepping error,
    # which halves with dt, and Richardson's 2 T(dt/2) - T(dt) comes closer.
    tm = pytest.importorskip("tamaas")
    tm.set_log_level(tm.LogLevel.error)
    h = rough(32)
    shear, times = [2.0, 1.0], [0.3, 2.0]

    def load(t):  # from a quarter (a first contact of one cell stops Tamaas)
        return 0.005 + 0.015 * min(t, 1.0)

    def tamaas(dt):
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [32, 32])
        model.E, model.nu = 3.0, 0.5
        solver = tm.MaxwellViscoelastic(model, h.copy(), 1e-12, dt, shear, times)
        for k in range(1, int(round(2.0 / dt)) + 1):
            solver.solve(load(k * dt))
        return np.array(model.traction).reshape(h.shape)

    v = mrdw.TransientContact(h, relaxed=4.0, terms=[(4 * g, t) for g, t in zip(shear, times)])
    for k in range(1, 401):
        s = v.step(0.005, mean_pressure=load(k * 0.005), tolerance=1e-11)
    ours = s.pressure

    def diff(p):
        return np.linalg.norm(p - ours) / np.linalg.norm(ours)

    coarse, fine = tamaas(0.04), tamaas(0.02)
    assert 1e-4 < diff(fine) < 3e-3  # measured 6.0e-4
    assert 1.7 < diff(coarse) / diff(fine) < 2.6  # first order; measured 2.23
    assert diff(2 * fine - coarse) < 0.5 * diff(fine)  # measured 0.27
