"""mrdw.PlasticContact: the 3D pressure-cap solver from Python, checked against the
elastic solver (no hardness), the fully plastic bound and the CLI's MRD comparison."""

import numpy as np
import pytest

import mrdw


def sphere(n=48, side=0.8):
    x = (np.arange(n) + 0.5) * side / n - side / 2
    return -(x[None, :] ** 2 + x[:, None] ** 2) / 2.0, (side, side)


def test_no_hardness_is_the_elastic_contact():
    h, size = sphere()
    p = mrdw.PlasticContact(h, float("inf"), size=size).step(force=0.004, tolerance=1e-10)
    e = mrdw.Contact(h, size=size, periodic=False).solve(force=0.004, tolerance=1e-12)
    assert p.plastic_cells == 0 and p.flowed == 0
    assert abs(p.approach / e.approach - 1) < 1e-7
    assert np.abs(p.pressure - e.pressure).max() < 1e-6 * e.pressure.max()


def test_a_load_cycle_leaves_an_imprint_and_reloads_elastically():
    h, size = sphere()
    c = mrdw.PlasticContact(h, 0.05, size=size)
    top = c.step(force=0.008)
    assert top.plastic_cells > 0 and top.pressure.max() <= 0.05
    # the fully plastic bound: plastic area <= F / H <= contact area
    assert top.plastic_area <= 0.008 / 0.05 <= top.contact_area
    off = c.step(force=0.0)
    assert off.force == 0.0 and off.plastic_displacement.max() == pytest.approx(top.plastic_depth)
    again = c.step(force=0.008)
    assert again.flowed < top.plastic_cells // 10
    assert again.approach == pytest.approx(top.approach, rel=1e-6)
    assert c.step(approach=-1.0).force == 0.0  # lifted off


def test_bad_input_names_the_parameter():
    h, size = sphere(16)
    for hardness in (0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="hardness"):
            mrdw.PlasticContact(h, hardness, size=size)
    c = mrdw.PlasticContact(h, 0.05, size=size)
    with pytest.raises(ValueError, match="force"):
        c.step(force=2 * c.force_limit)
    with pytest.raises(ValueError, match="force = -1"):
        c.step(force=-1.0)
    with pytest.raises(ValueError, match="exactly one"):
        c.step(force=0.001, approach=0.01)
    with pytest.raises(ValueError, match="tolerance"):
        c.step(force=0.001, tolerance=0.5)
