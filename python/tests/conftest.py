"""Shared helpers: the CLI binary (for bit-identity checks) and small problems."""

import os
import pathlib
import shutil
import subprocess

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
