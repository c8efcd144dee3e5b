"""Property tests over the numeric arguments of the Python entry points: whatever the
numbers, a call returns finite values or raises a Python exception; it never kills the
interpreter, hangs or returns NaN.

Sizes are drawn from small ones and absurd ones (over the address space or any machine's
memory), never from the valid-but-huge middle, so every example is fast. Examples are
derandomised and bounded (CI runs them all in seconds); MRDW_FUZZ_EXAMPLES=5000 runs a
longer search."""

import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mrdw

# An entry point may refuse its input with these, and only these.
REFUSALS = (ValueError, MemoryError, OverflowError, TypeError, mrdw.ConvergenceError)

FUZZ = settings(
    max_examples=int(os.environ.get("MRDW_FUZZ_EXAMPLES", "120")),
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)

reals = st.one_of(
    st.sampled_from(
        [0.0, -1.0, 1.0, 0.5, 1e-300, 1e300, 1e-100, 1e100, 5e-324, -0.0, 3.0, -3.5, 1e8]
    ),
    st.floats(allow_nan=True, allow_infinity=True),
)
positive = st.one_of(st.sampled_from([1e-300, 1e-100, 1e-8, 1.0, 7.5, 1e100, 1e300]), reals)
hurst = st.one_of(st.sampled_from([-1.0, 0.0, 0.8, 3.0, 3.1, -1.5]), reals)
small = st.sampled_from([0, 1, 2, 3, 4, 5, 16, 33])
absurd = st.sampled_from([10**9, 2**33, 2**40, 2**62, 2**63 - 1, 2**64])
count = st.one_of(small, absurd)


def finite(*values):
    for v in values:
        a = np.asarray(v, dtype=float)
        assert np.all(np.isfinite(a)), v


@FUZZ
@given(ny=count, nx=count, lx=positive, ly=positive, h=hurst, q0=positive, q1=positive,
       rms=st.one_of(st.none(), positive))
def test_surface(ny, nx, lx, ly, h, q0, q1, rms):
    try:
        s = mrdw.surface((ny, nx), (lx, ly), h, q0, q0, q1, rms_height=rms, seed=3)
    except REFUSALS:
        return
    assert s.shape == (ny, nx)
    finite(s)


@FUZZ
@given(n=count, length=positive, h=hurst, q0=positive, q1=positive, lam=positive)
def test_line(n, length, h, q0, q1, lam):
    try:
        z = mrdw.line(n, length, h, q0, q0, q1, lam=lam, seed=2)
    except REFUSALS:
        return
    assert z.shape == (n,)
    finite(z)


@FUZZ
@given(bins=count, lx=positive, scale=reals)
def test_psd_and_moments(bins, lx, scale):
    h = scale * np.sin(np.arange(64.0)).reshape(8, 8)
    for call in (lambda: mrdw.psd(h, (lx, lx), bins), lambda: mrdw.moments(h, (lx, lx))):
        try:
            out = call()
        except REFUSALS:
            continue
        finite(*(out.values() if isinstance(out, dict) else out))


@FUZZ
@given(n=st.sampled_from([1, 2, 3, 8]), lx=positive, ly=positive, e_star=positive,
       scale=reals, load=reals, kind=st.sampled_from(["mean_pressure", "force", "approach"]),
       tolerance=reals, max_iterations=st.sampled_from([0, 1, 5, 200]),
       periodic=st.booleans(), stiffness=st.booleans())
def test_contact(n, lx, ly, e_star, scale, load, kind, tolerance, max_iterations, periodic,
                 stiffness):
    h = scale * np.cos(np.arange(n * n, dtype=float)).reshape(n, n)
    try:
        c = mrdw.Contact(h, size=(lx, ly), e_star=e_star, periodic=periodic)
        r = c.solve(**{kind: load}, tolerance=tolerance, max_iterations=max_iterations,
                    stiffness=stiffness)
    except REFUSALS:
        return
    finite(r.pressure, r.gap, r.force, r.approach, r.mean_gap, r.residual, r.certificate)
    assert r.residual <= tolerance and r.certificate <= tolerance


@FUZZ
@given(n=st.sampled_from([0, 1, 2, 3, 8]), relaxed=reals, e1=reals, tau=positive, dt=reals,
       load=reals, kind=st.sampled_from(["mean_pressure", "force", "approach"]),
       periodic=st.booleans(), scale=reals)
def test_transient_contact(n, relaxed, e1, tau, dt, load, kind, periodic, scale):
    h = scale * np.cos(np.arange(n * n, dtype=float)).reshape(n, n)
    try:
        v = mrdw.TransientContact(h, relaxed=relaxed, terms=[(e1, tau)], periodic=periodic)
        steps = [v.step(dt, **{kind: load}), v.step(dt, **{kind: 0.5 * load})]
    except REFUSALS:
        return
    for s in steps:
        finite(s.pressure, s.force, s.approach, s.time, s.effective_modulus, s.residual)
    finite(v.displacement)


@FUZZ
@given(length=positive, e_star=positive, scale=reals, force=reals, depth=reals)
def test_rough_line(length, e_star, scale, force, depth):
    try:
        line = mrdw.RoughLine(scale * np.sin(np.arange(32.0)), length, e_star)
        states = [line.at_force(force), line.at_depth(depth)]
    except REFUSALS:
        return
    for s in states:
        finite(*s.values())


@FUZZ
@given(radius=positive, e_star=positive, g_star=positive, mu=reals, depth=reals,
       gamma=positive, amplitude=reals, tf=reals)
def test_axisymmetric(radius, e_star, g_star, mu, depth, gamma, amplitude, tf):
    calls = [
        lambda: mrdw.normal(mrdw.Profile.sphere(radius), e_star, depth=depth),
        lambda: mrdw.pressure(mrdw.Profile.sphere(radius), e_star, [0.0, 0.5 * radius], depth=depth),
        lambda: mrdw.adhesion(mrdw.Profile.sphere(radius), e_star, gamma, depth),
        lambda: mrdw.pull_off(mrdw.Profile.flat_punch(radius), e_star, gamma),
        lambda: mrdw.cattaneo_mindlin(mrdw.Profile.sphere(radius), e_star, g_star, mu, depth, tf),
        lambda: mrdw.damping(mrdw.Profile.sphere(radius), e_star, g_star, mu, depth, amplitude),
    ]
    for call in calls:
        try:
            out = call()
        except REFUSALS:
            continue
        finite(*(out.values() if isinstance(out, dict) else [out]))


def test_the_fuzz_reaches_valid_inputs():
    # The strategies above are not all refusals: a valid call of each kind succeeds.
    assert mrdw.surface((16, 16), (1.0, 1.0), 0.8, 4.0, 4.0, 40.0, rms_height=1.0).shape == (16, 16)
    assert mrdw.line(64, 1.0, 0.8, 4.0, 4.0, 40.0).shape == (64,)
    r = mrdw.Contact(np.cos(np.arange(64.0)).reshape(8, 8)).solve(mean_pressure=0.1)
    assert math.isfinite(r.force)
