"""Shared helpers: the CLI binary (for bit-identity checks) and small problems."""

import json
import os
import pathlib
import re
import shutil
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def mrdw_bin():
    """The `mrdw` binary of this checkout (built by `cargo build --release`), or skip."""
    exe = os.environ.get("MRDW_BIN") or str(ROOT / "target" / "release" / "mrdw")
    if not os.path.exists(exe):
        exe = shutil.which("mrdw")
    if not exe:
        pytest.skip("the mrdw binary is not built (cargo build --release)")
    return exe


def run_cli(exe, *args, cwd=None):
    return subprocess.run([exe, *args], capture_output=True, text=True, cwd=cwd)


def coarse_scene(name, folder, **keys):
    """A copy of the embedded scene `cases/<name>.toml` in `folder` with the given
    `key = value` lines replaced (e.g. a coarser grid), so that a bit-identity check
    against the CLI runs in seconds; each key must appear exactly once."""
    text = (ROOT / "cases" / f"{name}.toml").read_text()
    for key, value in keys.items():
        pattern = re.compile(rf"^{re.escape(key)} = .*$", re.MULTILINE)
        text, count = pattern.subn(f"{key} = {value}", text)
        assert count == 1, f"{name}.toml has {count} lines setting {key}"
    path = pathlib.Path(folder) / f"{name}.toml"
    path.write_text(text)
    return path


def run_coarse(exe, name, folder, csv, **keys):
    """Runs `coarse_scene(name, folder, **keys)` with the CLI `exe` into `folder/t`;
    returns the numbers of its table `csv` (comment lines and the header left out) and
    the summary's results."""
    scene = coarse_scene(name, folder, **keys)
    report = pathlib.Path(folder) / "t"
    out = run_cli(exe, "run", str(scene), "--out", str(report))
    assert out.returncode == 0, out.stderr
    rows = [r for r in open(report / csv) if not r.startswith("#")]
    results = json.load(open(report / "summary.json"))["results"]
    return np.loadtxt(rows[1:], delimiter=","), results
