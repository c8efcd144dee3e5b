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


def rough_line(n=1024, scale=1e-2):
    x = np.arange(n) / n * 2 * np.pi
    return scale * (np.sin(3 * x) + 0.5 * np.cos(7 * x + 1) + 0.2 * np.sin(23 * x + 2))


def test_plastic_line_without_hardness_is_the_rough_line():
    h = rough_line()
    elastic = mrdw.RoughLine(h, 1.0, 1.0)
    line = mrdw.PlasticLine(h, 1.0, 1.0, float("inf"))
    for f in [1e-5, 1e-4, 1e-3, 3e-4]:
        s = line.step_to_force(f)
        e = elastic.at_force(f)
        assert abs(s["approach"] - e["depth"]) <= 1e-9 * e["depth"]
        assert s["contacts"] == e["contacts"] and s["largest_set"] == 0.0


def test_plastic_line_unloads_elastically_and_saturates_at_the_punch_limit():
    line = mrdw.PlasticLine(rough_line(), 1.0, 1.0, 2e-3)
    peak = line.step_to_force(5e-4)
    assert peak["capped"] > 0 and peak["largest_set"] > 0
    set_at_peak = line.set.copy()
    line.step_to_force(1e-4)
    again = line.step_to_force(5e-4)
    assert abs(again["approach"] - peak["approach"]) <= 1e-9 * peak["approach"]
    assert np.abs(line.set - set_at_peak).max() <= 1e-10 * peak["largest_set"]
    # A flat line pressed far is one fully plastic patch: H pi L^2 / 4 as springs refine.
    flat = mrdw.PlasticLine(np.zeros(1600), 2.0, 1.0, 0.3)
    assert abs(flat.step(10.0)["force"] / (0.3 * np.pi) - 1) < 2e-3
    assert flat.force_limit == pytest.approx(flat.step(20.0)["force"], rel=1e-12)


@pytest.mark.parametrize(
    "args, needle",
    [
        ((np.zeros(8), 1.0, 1.0, 0.0), "hardness"),
        ((np.zeros(8), -1.0, 1.0, 1.0), "length"),
        ((np.array([0.0, np.nan]), 1.0, 1.0, 1.0), "index 1"),
    ],
)
def test_plastic_line_bad_input_names_the_parameter(args, needle):
    with pytest.raises(ValueError, match=needle):
        mrdw.PlasticLine(*args)
    line = mrdw.PlasticLine(np.zeros(8), 1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="force"):
        line.step_to_force(-1.0)
    with pytest.raises(ValueError, match="must stay below"):
        line.step_to_force(10.0)
