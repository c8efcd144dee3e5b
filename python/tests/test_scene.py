"""Scenes from Python: the same tables as the CLI's CSVs, and the CLI's error lines."""

import csv

import numpy as np
import pytest

import mrdw
from conftest import run_cli


def read_csv(path):
    with open(path) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header, body = rows[0], rows[1:]
    return {h: np.array([float(r[j]) if r[j] else np.nan for r in body]) for j, h in enumerate(header)}


def test_tour_tables_equal_the_cli_csvs(mrdw_bin, tmp_path):
    out = run_cli(mrdw_bin, "run", "tour", "--out", str(tmp_path / "tour"))
    assert out.returncode == 0, out.stderr
    res = mrdw.run_scene("tour")
    assert res["name"] == "tour"
    assert set(res["tables"]) == {p.stem for p in (tmp_path / "tour").glob("*.csv")}
    for name, cols in res["tables"].items():
        cli = read_csv(tmp_path / "tour" / f"{name}.csv")
        assert list(cols) == list(cli), name
        for h, v in cols.items():
            assert np.array_equal(v, cli[h], equal_nan=True), (name, h)
    assert res["failures"] == []
    assert all(isinstance(k, str) for k in res["results"])
    assert any("hess" in s or "normal" in s for stages in res["plan"].values() for s in stages)


def test_scene_file_and_listing(tmp_path):
    names = [n for n, _ in mrdw.scenes()]
    assert "tour" in names and "fig6" in names
    scene = tmp_path / "s.toml"
    scene.write_text(small_scene())
    res = mrdw.run_scene(str(scene))
    assert res["tables"]


def small_scene():
    # A small scene written by hand (the format of cases/README.md).
    return """
name = "py-sphere"
[units]
length = "mm"
stress = "MPa"
[material]
e_star = 1.0
[profile]
shapes = [{ kind = "sphere", radius = 10.0 }]
[[outputs]]
kind = "force_depth"
max = 0.1
points = 5
"""


def test_bad_scenes_raise_value_error_with_the_cli_message(mrdw_bin, tmp_path):
    out = run_cli(mrdw_bin, "run", "no-such-scene", "--out", str(tmp_path / "x"))
    assert out.returncode == 2
    with pytest.raises(ValueError) as e:
        mrdw.run_scene("no-such-scene")
    assert str(e.value) in out.stderr
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "bad"\n[material]\ne_star = -1.0\n')
    out = run_cli(mrdw_bin, "run", str(bad), "--out", str(tmp_path / "y"))
    assert out.returncode == 2
    with pytest.raises(ValueError) as e:
        mrdw.run_scene(str(bad))
    assert str(e.value) in out.stderr
