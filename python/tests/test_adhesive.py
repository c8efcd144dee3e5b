"""mrdw.AdhesiveContact: 3D adhesive contact from Python, checked against JKR, against
the command line's scene (bit for bit) and on bad input."""

import math

import numpy as np
import pytest

import mrdw

SCENE = """
name = "adhesion-3d-py"
[units]
length = "1"
stress = "1"
[material]
e_star = 1.0
[profile]
shapes = [{ kind = "sphere", radius = 1.0 }]
[[outputs]]
kind = "adhesion_3d"
gamma = 0.002
depth_max = 0.155
cells = [64]
extent = 1.25
steps = 100
"""


def sphere(n, l):
    x = (np.arange(n) + 0.5) * (l / n) - 0.5 * l
    r = np.hypot(x[None, :], x[:, None])
    return -(r * r) / 2.0


def cycle(n, l, w=0.002, d_max=0.155, steps=100):
    """The scene's cycle: loading in steps, unloading by the same steps to separation."""
    h = sphere(n, l)
    c = mrdw.AdhesiveContact(h, work=w, size=(l, l), periodic=False)
    apex = h.max()
    dd = d_max / steps
    out = []
    for k in range(1, steps + 1):
        s = c.step(approach=dd * k + apex)
        out.append((dd * k, s.force, 0))
    k = 0
    while True:
        d = d_max - dd * k
        s = c.step(approach=d + apex)
        if s.separated:
            return out
        out.append((d, s.force, 1))
        k += 1


def test_the_pull_off_is_jkrs_and_the_clis(tmp_path):
    path = tmp_path / "a.toml"
    path.write_text(SCENE)
    res = mrdw.run_scene(str(path))
    table = res["tables"]["cycle"]
    cells = table["cells [cells]"]
    # The scene's grid: 1.25 loaded contact diameters, MRD's radius at depth_max.
    a_top = table["contact_radius [1]"][cells == 0].max()
    assert a_top == pytest.approx(math.sqrt(0.155), rel=1e-9)
    curve = cycle(64, 1.25 * 2 * a_top)
    pull_off = min(f for _, f, _ in curve)
    jkr = 1.5 * math.pi * 0.002
    # 12.5 cells per pull-off radius: 9.3 % above JKR (the grid's lattice trapping).
    assert 0.0 < -pull_off / jkr - 1 < 0.12
    forces = table["force [1]"][cells == 64]
    assert np.array_equal(forces, np.array([f for _, f, _ in curve]))
    assert res["results"]["adhesion_3d.pull_off_rel_error_3d"] == pytest.approx(
        -pull_off / jkr - 1, rel=1e-12)


def test_a_periodic_surface_takes_a_force_and_separates_below_its_pull_off():
    n = 32
    h = 0.02 * np.cos(2 * np.pi * np.arange(n) / n)[None, :] * np.ones((n, 1))
    c = mrdw.AdhesiveContact(h, work=1e-4, size=(1.0, 1.0), periodic=True)
    s = c.step(mean_pressure=1e-3)
    assert s.contact_cells > 0 and s.force == pytest.approx(1e-3, rel=1e-12)
    assert c.critical_stress > 0
    with pytest.raises(ValueError, match="prescribe the force"):
        c.step(approach=0.01)
    s = c.step(mean_pressure=-1.0)
    assert s.separated and s.force == 0.0


@pytest.mark.parametrize("work", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_work_of_adhesion_names_it(work):
    with pytest.raises(ValueError, match="work"):
        mrdw.AdhesiveContact(np.zeros((8, 8)), work=work)


def test_bad_steps_name_the_parameter():
    c = mrdw.AdhesiveContact(sphere(16, 1.0), work=0.01, size=(1.0, 1.0), periodic=False)
    with pytest.raises(ValueError, match="exactly one"):
        c.step()
    with pytest.raises(ValueError, match="approach = NaN must be finite"):
        c.step(approach=float("nan"))
    with pytest.raises(ValueError, match="tolerance"):
        c.step(approach=0.01, tolerance=0.5)
    # Beyond the normal solve's bound, pushing or pulling: bad input, not a breakdown.
    with pytest.raises(ValueError, match="a mean pressure of -1e300, more than 1e10 E"):
        c.step(force=-1e300)
    with pytest.raises(ValueError, match="approach = 1e300 is more than 1e10 times"):
        c.step(approach=1e300)
    s = c.step(approach=-1.0)  # retraction past separation is a state
    assert s.separated and s.force == 0.0
