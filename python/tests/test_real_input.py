"""Real-world input: masked topographies (undefined points), files with their cell size,
ordinary exports, and helpers that refuse what is not a number. Each class has a
property test beside the cases that were once answered wrongly."""

import os
import threading
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mrdw


def rough(n=32, seed=3):
    two_pi = 2 * np.pi
    return mrdw.surface((n, n), (1.0, 1.0), 0.8, two_pi, two_pi, two_pi * (n // 4), rms_height=0.01, seed=seed)


class FakeTopography:
    """What SurfaceTopography gives for a map with undefined points: heights() indexed
    (x, y) as a masked array, physical_sizes, is_periodic."""

    def __init__(self, masked_rows_of_y, size=(1.0, 1.0), periodic=True):
        self._h = masked_rows_of_y
        self.physical_sizes = size
        self.is_periodic = periodic

    def heights(self):
        return self._h.T


def test_a_masked_spike_carries_no_load():
    """A spike in one masked cell: the undefined cell is left out (as mask= would), not
    pressed as the highest point of the map."""
    h = rough()
    spiked = h.copy()
    spiked[5, 7] = 1.0
    undefined = np.zeros_like(h, dtype=bool)
    undefined[5, 7] = True
    masked = np.ma.masked_array(spiked, mask=undefined)
    expected = mrdw.Contact(h, mask=~undefined).solve(mean_pressure=1e-3)
    for given_heights in [masked, FakeTopography(masked)]:
        with pytest.warns(UserWarning, match="1 of 1024 cells are undefined"):
            c = mrdw.Contact(given_heights)
        assert c.undefined_cells == 1
        r = c.solve(mean_pressure=1e-3)
        assert r.pressure[5, 7] == 0.0
        np.testing.assert_array_equal(r.pressure, expected.pressure)
        assert r.contact_fraction > 0.02, r.contact_fraction


def test_a_mask_and_undefined_cells_combine():
    h = rough()
    undefined = np.zeros_like(h, dtype=bool)
    undefined[:, :3] = True
    mask = np.ones_like(h, dtype=bool)
    mask[:2, :] = False
    with pytest.warns(UserWarning, match="96 of 1024"):
        c = mrdw.Contact(np.ma.masked_array(h, mask=undefined), mask=mask)
    r = c.solve(mean_pressure=1e-3)
    both = mrdw.Contact(h, mask=mask & ~undefined).solve(mean_pressure=1e-3)
    np.testing.assert_array_equal(r.pressure, both.pressure)


def test_transient_contact_honours_undefined_cells():
    h = rough()
    spiked = h.copy()
    spiked[9, 9] = 1.0
    undefined = np.zeros_like(h, dtype=bool)
    undefined[9, 9] = True
    with pytest.warns(UserWarning, match="undefined"):
        v = mrdw.TransientContact(
            np.ma.masked_array(spiked, mask=undefined), relaxed=1.0, terms=[(2.0, 1.0)]
        )
    s = v.step(0.1, mean_pressure=1e-3)
    assert s.pressure[9, 9] == 0.0 and s.contact_area > 0.0
    expected = mrdw.TransientContact(h, relaxed=1.0, terms=[(2.0, 1.0)], mask=~undefined)
    np.testing.assert_array_equal(s.pressure, expected.step(0.1, mean_pressure=1e-3).pressure)


def test_every_cell_undefined_is_refused():
    h = np.ma.masked_all((8, 8))
    with pytest.raises(ValueError, match="every height is masked"):
        mrdw.Contact(h)


@settings(max_examples=25, deadline=None)
@given(
    cells=st.lists(st.tuples(st.integers(0, 15), st.integers(0, 15)), min_size=1, max_size=40),
    spike=st.floats(-1e3, 1e3),
)
def test_masked_cells_never_change_the_answer(cells, spike):
    """Whatever the masked cells hold (spikes, NaN), the answer is that of mask=."""
    h = rough(16, seed=5)
    undefined = np.zeros_like(h, dtype=bool)
    for i, j in cells:
        undefined[i, j] = True
    data = h.copy()
    data[undefined] = spike
    data[0, 0] = np.nan if undefined[0, 0] else data[0, 0]
    if undefined.all():
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        r = mrdw.Contact(np.ma.masked_array(data, mask=undefined)).solve(mean_pressure=1e-3)
    expected = mrdw.Contact(h, mask=~undefined).solve(mean_pressure=1e-3)
    np.testing.assert_array_equal(r.pressure, expected.pressure)


def test_read_topography_keeps_the_mask_and_the_size():
    h = rough()
    undefined = np.zeros_like(h, dtype=bool)
    undefined[3, 4] = True
    t = mrdw.read_topography(FakeTopography(np.ma.masked_array(h, mask=undefined), size=(2.0, 3.0)))
    assert isinstance(t, mrdw.Topography)
    assert t.size == (2.0, 3.0) and t.has_undefined_data
    assert np.isnan(np.asarray(t)[3, 4])
    np.testing.assert_array_equal(t.undefined, undefined)
    with pytest.warns(UserWarning, match="1 of 1024"):
        c = mrdw.Contact(t)
    assert c.size == (2.0, 3.0) and c.undefined_cells == 1


def test_read_topography_gives_the_files_size(tmp_path):
    """An ESRI grid's cell size reaches Contact: 32 x 16 cells of 0.5 um is 16 x 8 um."""
    h = rough(16)[:, :]
    rows = [" ".join(f"{v:.9e}" for v in row) for row in h[::-1]]
    (tmp_path / "g.asc").write_text(
        "ncols 16\nnrows 16\nxllcorner 0\nyllcorner 0\ncellsize 0.5\n" + "\n".join(rows) + "\n"
    )
    t = mrdw.read_topography(tmp_path / "g.asc")
    assert t.size == (8.0, 8.0)
    np.testing.assert_allclose(np.asarray(t), h, rtol=1e-9)
    assert mrdw.Contact(t).size == (8.0, 8.0)
    # A .npy file states no size: Contact asks for it.
    np.save(tmp_path / "h.npy", h)
    t = mrdw.read_topography(os.fsencode(tmp_path / "h.npy"))
    assert t.size is None
    with pytest.raises(ValueError, match="give size"):
        mrdw.Contact(t)
    assert mrdw.Contact(t, size=(1.0, 1.0)).size == (1.0, 1.0)


def test_read_topography_does_not_hold_the_gil(tmp_path):
    """A pipe fed by another thread of this process is read without a deadlock."""
    fifo = tmp_path / "heights.txt"
    os.mkfifo(fifo)
    text = "\n".join(" ".join(str(i * j) for j in range(4)) for i in range(3)) + "\n"

    def feed():
        with open(fifo, "w") as f:
            f.write(text)

    writer = threading.Thread(target=feed)
    writer.start()
    t = mrdw.read_topography(fifo)
    writer.join(timeout=10)
    assert np.asarray(t).shape == (3, 4)


@pytest.mark.parametrize(
    "source, message",
    [
        (5, "must be a path"),
        (object(), "must be a path"),
    ],
)
def test_read_topography_names_what_it_takes(source, message):
    with pytest.raises(TypeError, match=message):
        mrdw.read_topography(source)


def test_topography_objects_that_are_not_quite(tmp_path):
    class Attr:
        heights = np.zeros((4, 4))
        physical_sizes = (1.0, 1.0)

    class NoSize:
        def heights(self):
            return np.zeros((4, 4))

    class ListSize:
        physical_sizes = [2.0, 2.0]

        def heights(self):
            return np.arange(16.0).reshape(4, 4)

    with pytest.raises(ValueError, match=r"method heights\(\).*not an attribute"):
        mrdw.Contact(Attr())
    with pytest.raises(ValueError, match="no physical_sizes"):
        mrdw.Contact(NoSize())
    assert mrdw.Contact(ListSize()).size == (2.0, 2.0)
    with pytest.raises(TypeError, match="2D float array"):
        mrdw.Contact("not an array")
    for missing in [(tmp_path, "is a folder"), (tmp_path / "none.npy", "no such file")]:
        with pytest.raises(ValueError, match=missing[1]):
            mrdw.read_topography(missing[0])
    with pytest.raises(ValueError, match="device"):
        mrdw.read_topography("/dev/null")


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"data": np.zeros(4)}, "data must be a 2D array"),
        ({"data": np.zeros((4, 4)), "undefined": np.zeros((2, 2), bool)}, "undefined must be"),
        ({"data": np.zeros((4, 4)), "undefined": np.zeros((4, 4))}, "undefined must be"),
        ({"data": np.zeros((4, 4)), "size": (-1.0, 2.0)}, r"size = \(-1.0, 2.0\)"),
        ({"data": np.zeros((4, 4)), "size": 3.0}, "size must be"),
        ({"data": np.zeros((4, 4)), "size": (1.0, float("nan"))}, r"size = \(1.0, nan\) must be finite"),
        ({"data": np.zeros((4, 4)), "periodic": "yes"}, "periodic must be"),
    ],
)
def test_a_topography_names_the_argument_that_does_not_fit(kwargs, message):
    with pytest.raises(ValueError, match=f"Topography: {message}"):
        mrdw.Topography(**kwargs)


def test_a_topography_counts_nan_and_masked_cells_as_undefined():
    h = np.add.outer(np.arange(8.0), np.arange(8.0)) / 100
    assert mrdw.Topography(h).data is h  # kept, not copied
    hole = h.copy()
    hole[2, 3] = np.nan
    masked = np.ma.masked_array(h, mask=np.isnan(hole))
    given = np.zeros((8, 8), bool)
    given[5, 5] = True
    for t, cells in [
        (mrdw.Topography(hole), [(2, 3)]),
        (mrdw.Topography(masked), [(2, 3)]),
        (mrdw.Topography(hole, given), [(2, 3), (5, 5)]),
    ]:
        assert t.has_undefined_data
        assert sorted(zip(*np.nonzero(t.undefined))) == cells
    # The contact leaves them out as it leaves out a mask's cells.
    with pytest.warns(UserWarning, match="1 of 64 cells are undefined"):
        a = mrdw.Contact(mrdw.Topography(masked), size=(1.0, 1.0)).solve(force=1e-3)
    b = mrdw.Contact(h, size=(1.0, 1.0), mask=~masked.mask).solve(force=1e-3)
    assert np.array_equal(a.pressure, b.pressure)


@settings(max_examples=30, deadline=None)
@given(
    n=st.integers(2, 40),
    noise=st.sampled_from(["%g", "1e-15", "exact"]),
    origin=st.floats(-10.0, 10.0),
    step=st.floats(1e-4, 10.0),
)
def test_xyz_exports_read_back(tmp_path_factory, n, noise, origin, step):
    """A point list written with six significant digits (%g) or with rounding noise in
    its coordinates is read as its grid, with its cell size."""
    tmp = tmp_path_factory.mktemp("xyz")
    rng = np.random.default_rng(n)
    z = rng.normal(size=(n, n + 1)).tolist()
    lines = ["\ufeffx y z"]
    for j in range(n):
        for i in range(n + 1):
            x, y = origin + i * step, origin + j * step
            if noise == "%g":
                lines.append(f"{x:g} {y:g} {z[j][i]!r}")
            elif noise == "1e-15":
                lines.append(f"{x + 1e-15 * (i % 3 - 1)!r} {y - 1e-15 * (j % 2)!r} {z[j][i]!r}")
            else:
                lines.append(f"{x!r} {y!r} {z[j][i]!r}")
    if noise == "%g" and step / max(abs(origin), abs(origin + n * step), 1e-300) < 1e-3:
        return  # %g cannot resolve such a grid: refusing it is right
    (tmp / "s.xyz").write_text("\n".join(lines) + "\n")
    t = mrdw.read_topography(tmp / "s.xyz")
    np.testing.assert_array_equal(np.asarray(t), np.array(z))
    np.testing.assert_allclose(t.size, ((n + 1) * step, n * step), rtol=1e-3)


def test_an_irregular_xyz_list_says_what_differs(tmp_path):
    lines = [f"{x} {y} 0" for y in range(3) for x in [0, 1, 2, 3.4]]
    (tmp_path / "s.xyz").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"x = 3.4 is .* cells off the regular grid"):
        mrdw.read_topography(tmp_path / "s.xyz")


def test_helpers_refuse_what_is_not_a_number():
    q = np.array([10.0, 20.0])
    with pytest.raises(ValueError, match="lam"):
        mrdw.line_spectrum(q, 0.8, 4.0, 4.0, 32.0, lam=-1.0)
    with pytest.raises(ValueError, match=r"r\[0\] = NaN is not a number"):
        mrdw.pressure(mrdw.Profile.sphere(1.0), 1.0, [np.nan], depth=0.1)
    with pytest.raises(ValueError, match="no load has it"):
        mrdw.normal(mrdw.Profile.flat_punch(1.0), 1.0, radius=0.5)
    assert mrdw.normal(mrdw.Profile.flat_punch(1.0), 1.0, radius=1.0)["stiffness"] == 2.0
    for bad in [np.nan, np.inf]:
        with pytest.raises(ValueError, match="finite points"):
            mrdw.fit_line([0.0, 1.0, bad, 3.0], [1.0, 2.0, 3.0, 4.0])


def test_nan_arguments_are_named():
    nan = float("nan")
    with pytest.raises(ValueError, match=r"x\[0\] = NaN is not a number"):
        mrdw.Profile.sphere(1.0).z1d([nan])
    with pytest.raises(ValueError, match=r"q\[1\] = NaN is not a number"):
        mrdw.spectrum([1.0, nan], 0.8, 1.0, 1.0, 10.0)
    with pytest.raises(ValueError, match="glassy modulus relaxed"):
        mrdw.TransientContact(rough(16), relaxed=1e100, terms=[(1e100, 1.0)])


def test_loads_are_named_as_given():
    v = mrdw.TransientContact(rough(16), relaxed=1.0, terms=[(2.0, 1.0)])
    with pytest.raises(ValueError, match=r"^force = -0.01 must be finite and >= 0"):
        v.step(0.1, force=-0.01)
    with pytest.raises(ValueError, match="mean_pressure = NaN"):
        mrdw.Contact(rough(16)).solve(mean_pressure=np.nan)
