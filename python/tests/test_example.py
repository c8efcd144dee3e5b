"""The README's worked example runs and prints what it promises."""

import pathlib
import subprocess
import sys

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "periodic_contact.py"


def test_example_runs():
    out = subprocess.run([sys.executable, str(EXAMPLE), "--n", "64"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "relative contact area" in out.stdout and "mean gap / rms height" in out.stdout
    area = float(out.stdout.split("relative contact area")[1].split()[0])
    assert 0.0 < area < 0.5
