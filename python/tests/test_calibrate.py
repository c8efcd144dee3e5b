"""mrdw.calibrate: lambda of Eq. (76) for one surface, from a spectrum, a PSD table or a
measured map, and its refusals of bad input."""

import os

import numpy as np
import pytest

import mrdw

SMALL = dict(bandwidth=16, cells=4, realisations=(8, 16, 8), lines=100, loads=10, progress=False)


def test_a_self_affine_spectrum_calibrates_like_the_cli(tmp_path):
    """The embedded scene `calibrate-ci` and the same parameters from Python give the
    same lambda, interval and exponents, bit for bit; lambda at H = 0.5, bandwidth 16
    lies where the lambda study puts it at low bandwidth, inside its interval; the report
    folder holds the tables, the figures and the scene."""
    ci = dict(bandwidth=16, cells=4, realisations=(8, 64, 8), target=0.3, lines=200, loads=12)
    r = mrdw.calibrate({"hurst": 0.5}, out=tmp_path / "a", seed=3, progress=False, **ci)
    cli = mrdw.run_scene("calibrate-ci")["results"]
    for k in ("lambda", "lambda_lo", "lambda_hi", "alpha_3d", "alpha_mrd", "misfit_max"):
        assert r["results"][k] == cli[f"calibrate.{k}"], k
    lo, hi = r["interval"]
    assert lo < r["lambda"] < hi and 2.5 < r["lambda"] < 4.5
    assert abs(r["alpha_3d"] - r["alpha_mrd"]) < 0.05
    names = {os.path.basename(f) for f in r["files"]}
    assert {"calibration.csv", "curves.csv", "curves.png", "psd.csv", "summary.json"} <= names
    again = mrdw.calibrate({"hurst": 0.5}, out=tmp_path / "b", seed=3, progress=False, **ci)
    a = (tmp_path / "a" / "curves.csv").read_text().split("\n# scene file")[1]
    b = (tmp_path / "b" / "curves.csv").read_text().split("\n# scene file")[1]
    assert again["lambda"] == r["lambda"] and a == b


def test_a_map_and_its_psd_table_end_to_end(tmp_path):
    """A synthetic map (as a measurement would be: tilted, non-periodic crop) solved
    with the map itself, and its PSD passed as a table: both calibrate, the map's own
    solve is reported, and a PSD table needs the punch diameter."""
    h = mrdw.surface((96, 96), (2.0, 2.0), 0.8, np.pi, np.pi, 48 * np.pi, rms_height=1e-3, seed=5)
    h = h[:64, :64] + 1e-4 * np.arange(64)[None, :]
    with pytest.warns(UserWarning, match="units"):
        r = mrdw.calibrate(h, size=(4 / 3, 4 / 3), out=tmp_path / "map", **SMALL)
    assert 1.0 < r["lambda"] < 8.0
    assert r["results"]["map_pixels"] == 64 and np.isfinite(r["results"]["map_misfit_max"])
    # the map's spectrum's own part of the interval, and both parts together
    lo, hi = r["interval_spectrum"]
    assert lo <= r["lambda"] <= hi
    assert r["interval_total"][0] <= min(lo, r["interval"][0])
    assert r["interval_total"][1] >= max(hi, r["interval"][1])
    # the bootstrap's bias correction: lambda over (1 + bias), inside a wider interval
    value, (blo, bhi) = r["lambda_bias_corrected"]
    bias = r["results"]["spectrum_bias"]
    assert value * (1 + bias) == pytest.approx(r["lambda"], rel=1e-12)
    assert blo < value < bhi
    assert bhi / blo >= r["interval_total"][1] / r["interval_total"][0]
    q, c = mrdw.psd(h, (4 / 3, 4 / 3), bins=24)
    with pytest.raises(ValueError, match="size"):
        mrdw.calibrate((q, c), out=tmp_path / "psd0", **SMALL)
    t = mrdw.calibrate((q, c), size=4 / 3, out=tmp_path / "psd", **SMALL)
    assert 1.0 < t["lambda"] < 8.0
    assert t["interval_spectrum"] is None and t["interval_total"] is None
    assert t["lambda_bias_corrected"] is None


@pytest.mark.filterwarnings("ignore:units")
@pytest.mark.parametrize(
    "source, kwargs, needle",
    [
        (np.zeros((16, 64)), {"size": (1.0, 0.25)}, "16 x 64 pixels"),
        (np.zeros((64, 64)), {}, "size"),
        (np.zeros((64, 64)), {"size": (1.0, 2.0)}, "square pixels"),
        (np.where(np.eye(64) > 0, np.nan, 0.0), {"size": (1.0, 1.0)}, "undefined"),
        ({"hurst": 5.0}, {}, "hurst"),
        ({"hurst": 0.5, "rolloff": 0.5}, {}, "rolloff"),
        ({"hurst": 0.5}, {"window": (0.5, 0.1)}, "window"),
        ({"hurst": 0.5}, {"realisations": (8, 4, 2)}, "realisations.max"),
        ({"hurst": 0.5}, {"size": 1.0}, "size"),
        ({"hurst": 0.5}, {"solve_map": False}, "solve_map"),
        ({"hurst": 0.5}, {"spectrum_uncertainty": (8, 8)}, "spectrum_uncertainty applies"),
        (np.random.default_rng(1).normal(size=(64, 64)), {"size": (1.0, 1.0),
         "spectrum_uncertainty": (2, 8)}, "spectrum_uncertainty.resamples = 2"),
        (np.random.default_rng(1).normal(size=(64, 64)), {"size": (1.0, 1.0),
         "spectrum_uncertainty": (8,)}, "resamples, punches"),
        (np.random.default_rng(1).normal(size=(64, 64)), {"size": (1.0, 1.0),
         "spectrum_uncertainty": (8, 4.5)}, "spectrum_uncertainty.punches"),
        # a masked array's masked cells are undefined, as for Topography
        (np.ma.masked_array(np.random.default_rng(1).normal(size=(64, 64)),
                            mask=np.eye(64, dtype=bool)), {"size": (1.0, 1.0)}, "undefined"),
        # a plane has no roughness; a constant map neither
        (np.add.outer(0.01 * np.arange(64), 0.02 * np.arange(64)), {"size": (1.0, 1.0)}, "flat"),
        (np.full((64, 64), 3.0), {"size": (1.0, 1.0)}, "flat"),
        # whole numbers are not rounded, pairs not truncated
        ({"hurst": 0.5}, {"bandwidth": 8.9}, "bandwidth = 8.9 must be a whole number"),
        ({"hurst": 0.5}, {"cells": 4.7}, "cells"),
        ({"hurst": 0.5}, {"seed": 1.5}, "seed"),
        ({"hurst": 0.5}, {"bandwidth": "a"}, "bandwidth"),
        ({"hurst": 0.5}, {"window": (0.02, 0.3, 0.5)}, "window"),
        ({"hurst": 0.5}, {"realisations": (8, 16)}, "realisations"),
        ({"hurst": 0.5}, {"cells": 2}, "cells = 2 must lie in"),
        ((np.array([1.0, 2.0, 3.0]), np.array([1.0, 0.5, 0.2])), {"size": (1.0, 2.0)}, "one diameter"),
        ((np.array([7.0, 20.0, 60.0]), np.array([1.0, -0.5, 0.2])), {"size": 1.0}, "C2D = -0.5"),
        ((np.array([7.0, 20.0, 60.0]), np.array([1.0, np.nan, 0.2])), {"size": 1.0}, "C2D = NaN"),
    ],
)
def test_bad_input_names_the_parameter(tmp_path, source, kwargs, needle):
    with pytest.raises(ValueError, match=needle) as e:
        mrdw.calibrate(source, out=tmp_path / "x", **{**SMALL, **kwargs})
    assert not (tmp_path / "x").exists() and not (tmp_path / "x.work").exists()
    # the message speaks of what the caller gave, not of a temporary scene file
    assert "mrdw-calibrate-" not in str(e.value)


def test_amplitudes_is_checked_before_computing(tmp_path):
    with pytest.raises(ValueError, match="amplitudes"):
        mrdw.calibrate({"hurst": 0.5}, out=tmp_path / "o", amplitudes="normal")
