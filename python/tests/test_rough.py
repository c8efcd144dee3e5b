"""Roughness from numpy: synthesis bit-identical to the CLI, spectra and statistics
against their definitions, topography files, rough lines against brute-force sums."""

import numpy as np
import pytest

import mrdw
from conftest import run_cli

TWO_PI = 2 * np.pi


def test_surface_and_solve_are_bit_identical_to_the_cli(mrdw_bin, tmp_path):
    """`mrdw bench bem --write-surfaces` writes the benchmark's reference surface (H = 0.8,
    2 pi .. n/4 2 pi, seed 2026, scaled to rms slope 0.1) and its pressure at mean
    pressure 0.01 E* (tolerance 1e-10): the same, bit for bit, from Python."""
    out = run_cli(mrdw_bin, "bench", "bem", "--max-n", "128", "--write-surfaces", str(tmp_path))
    assert out.returncode == 0, out.stderr
    n = 128
    h = mrdw.surface((n, n), (1.0, 1.0), 0.8, TWO_PI, 2 * TWO_PI, TWO_PI * (n // 4), seed=2026)
    h = h * (0.1 / mrdw.moments(h, (1.0, 1.0))["rms_slope"])
    assert np.array_equal(h, np.load(tmp_path / f"surface_{n}.npy"))
    p = mrdw.Contact(h).solve(mean_pressure=0.01, tolerance=1e-10).pressure
    assert np.array_equal(p, np.load(tmp_path / f"mrdw_pressure_{n}.npy"))


def test_spectrum_shape_and_normalisation():
    q = np.array([0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0])
    c = mrdw.spectrum(q, 0.7, 1.0, 2.0, 16.0)
    assert c[0] == 0.0 and c[-1] == 0.0  # outside [q0, q1]
    assert c[1] == c[2] == 1.0  # plateau
    assert c[4] == pytest.approx((8.0 / 2.0) ** (-2 * 0.7 - 2), rel=1e-14)
    # rms height: 2 pi Int q C2D dq = h^2, by quadrature
    qs = np.geomspace(1.0, 16.0, 200001)
    cs = mrdw.spectrum(qs, 0.7, 1.0, 2.0, 16.0, rms_height=0.3)
    m0 = TWO_PI * np.trapezoid(qs * cs, qs) if hasattr(np, "trapezoid") else TWO_PI * np.trapz(qs * cs, qs)
    assert m0 == pytest.approx(0.09, rel=1e-5)
    c1 = mrdw.line_spectrum(q, 0.7, 1.0, 2.0, 16.0, lam=2.5)
    np.testing.assert_array_equal(c1, 2.5 * np.abs(q) * c)  # Eq. (76)


def test_surface_statistics_and_psd():
    n, l = 256, 1.0
    h = mrdw.surface((n, n), (l, l), 0.8, TWO_PI * 2, TWO_PI * 4, TWO_PI * 32, rms_height=1e-3, seed=5)
    m = mrdw.moments(h, (l, l))
    assert m["rms_height"] == pytest.approx(1e-3, rel=0.05)
    assert m["rms_height"] == pytest.approx(h.std(), rel=1e-10)
    q, c = mrdw.psd(h, (l, l), bins=24)
    inside = (q > TWO_PI * 6) & (q < TWO_PI * 24)
    expect = mrdw.spectrum(q[inside], 0.8, TWO_PI * 2, TWO_PI * 4, TWO_PI * 32, rms_height=1e-3)
    np.testing.assert_allclose(c[inside], expect, rtol=0.12)
    # the same seed gives the same surface; another realisation another one
    assert np.array_equal(h, mrdw.surface((n, n), (l, l), 0.8, TWO_PI * 2, TWO_PI * 4, TWO_PI * 32, rms_height=1e-3, seed=5))
    other = mrdw.surface((n, n), (l, l), 0.8, TWO_PI * 2, TWO_PI * 4, TWO_PI * 32, rms_height=1e-3, seed=5, realisation=1)
    assert not np.array_equal(h, other)


def test_line_spectrum_and_rms_height():
    """Eq. (72) with deterministic amplitudes: the line's mean square is exactly
    2 sum_k C1D(q_k) dq; its PSD estimate is C1D itself. Eq. (73): with lam = pi the line
    keeps the surface's rms height (to the discretisation of the band: 16 .. 512
    modes)."""
    n, l = 4096, 1.0
    band = (TWO_PI * 16, TWO_PI * 16, TWO_PI * 512)
    h = mrdw.line(n, l, 0.7, *band, rms_height=2e-3, seed=1)
    q = TWO_PI * np.arange(1, n // 2) / l
    c1 = mrdw.line_spectrum(q, 0.7, *band, rms_height=2e-3)
    assert mrdw.moments(h, l)["rms_height"] ** 2 == pytest.approx(2 * c1.sum() * TWO_PI / l, rel=1e-12)
    qe, ce = mrdw.psd(h, l)
    k = slice(20, 400)
    np.testing.assert_allclose(ce[k], c1[k], rtol=1e-10)
    assert mrdw.moments(h, l)["rms_height"] == pytest.approx(2e-3, rel=0.05)


def test_topography_files(tmp_path):
    h = np.arange(12.0).reshape(3, 4) * 1e-3
    np.save(tmp_path / "h.npy", h)
    np.save(tmp_path / "f.npy", np.asfortranarray(h.astype(np.float32)))
    np.savetxt(tmp_path / "h.txt", h)
    assert np.array_equal(mrdw.read_topography(tmp_path / "h.npy"), h)
    np.testing.assert_allclose(mrdw.read_topography(tmp_path / "f.npy"), h, rtol=1e-7)
    np.testing.assert_allclose(mrdw.read_topography(str(tmp_path / "h.txt")), h, rtol=1e-15)
    (tmp_path / "bad.txt").write_text("1 2\n3 nan\n")
    with pytest.raises(ValueError, match="non-finite"):
        mrdw.read_topography(tmp_path / "bad.txt")


def test_rough_line_against_brute_force():
    n, l, e_star = 2048, 1.0, 3.0
    h = mrdw.line(n, l, 0.7, TWO_PI, TWO_PI, TWO_PI * 256, rms_height=1e-3, seed=2)
    rl = mrdw.RoughLine(h, l, e_star)
    assert len(rl) == n
    dx = l / n
    for d in [1e-5, 3e-4, 1e-3]:
        s = rl.at_depth(d)
        overlap = np.maximum(0.0, h - (h.max() - d))
        assert s["force"] == pytest.approx(e_star * dx * overlap.sum(), rel=1e-10)
        assert s["contacts"] == np.count_nonzero(overlap > 0)
        assert s["stiffness"] == pytest.approx(e_star * dx * s["contacts"], rel=1e-12)
        back = rl.at_force(s["force"])
        assert back["depth"] == pytest.approx(d, rel=1e-10)
    assert rl.rms_height == pytest.approx(h.std(), rel=1e-12)


def test_fit_line_matches_least_squares():
    x = np.linspace(0, 1, 20)
    y = 1.5 + 0.25 * x + 0.01 * np.sin(40 * x)
    f = mrdw.fit_line(x, y)
    b, a = np.polyfit(x, y, 1)
    assert f["a"] == pytest.approx(a, rel=1e-12) and f["b"] == pytest.approx(b, rel=1e-12)
    assert f["se_b"] > 0
    with pytest.raises(ValueError, match="at least 3"):
        mrdw.fit_line([0, 1], [0, 1])


def test_roughness_bad_input():
    with pytest.raises(ValueError, match="hurst"):
        mrdw.spectrum([1.0], 3.5, 1.0, 2.0, 3.0)
    with pytest.raises(ValueError, match="at most one"):
        mrdw.surface((8, 8), (1, 1), 0.8, 1, 2, 3, rms_height=1, rms_slope=1)
    with pytest.raises(ValueError, match="at least 4"):
        mrdw.surface((2, 8), (1, 1), 0.8, 1, 2, 3)
    with pytest.raises(ValueError, match="1D or 2D"):
        mrdw.moments(np.zeros((2, 2, 2)), 1.0)


def test_calibrated_lambda_is_the_shipped_table():
    # The table's rows are returned exactly, linear in between; outside [-1, 3] is a
    # ValueError; the text carries its provenance and the documented columns.
    text = mrdw.calibrated_lambda_table()
    assert "fig6-converged" in text
    rows = [
        [float(v) for v in line.split(",")]
        for line in text.splitlines()
        if line and not line.startswith("#") and not line.startswith("hurst")
    ]
    assert [r[0] for r in rows] == [-1, -0.5, 0, 0.5, 1, 1.5, 2, 2.5, 3]
    for r in rows:
        assert mrdw.calibrated_lambda(r[0]) == r[1]
        assert r[2] <= r[1] <= r[3] and r[6] == 128
    mid = mrdw.calibrated_lambda(0.25)
    assert abs(mid - 0.5 * (rows[2][1] + rows[3][1])) < 1e-12
    for bad in (-1.5, 3.5, float("nan")):
        with pytest.raises(ValueError):
            mrdw.calibrated_lambda(bad)
