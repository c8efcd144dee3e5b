"""Cost of calling the 3D solver from Python against the CLI (issue 12's performance
requirement: at most 2 % at 512^2). Not run by CI.

Both time the same work on the same surface (the benchmark's reference surface, H = 0.8,
rms slope 0.1, mean pressure 0.01 E*, tolerance 1e-10): building the solver (operator,
buffers, heights) and one solve. The CLI figure is `mrdw bench bem`'s periodic row; the
Python figure is mrdw.Contact(h) + solve(), including the conversion of the numpy input
and of the result arrays. Runs are interleaved; medians are reported.

    pip install ./python && python bench/python_overhead.py [--n 512] [--rounds 7]
"""

import argparse
import math
import pathlib
import platform
import statistics
import subprocess
import time

import numpy as np

import mrdw

ROOT = pathlib.Path(__file__).resolve().parents[1]


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def cli_time(exe, n):
    out = subprocess.run([exe, "bench", "bem", "--max-n", str(n)], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        cells = [c.strip() for c in line.split("|")]
        if len(cells) > 3 and cells[0] == "periodic" and cells[1] == f"{n}^2":
            return float(cells[2]), int(cells[3])
    raise RuntimeError(f"no periodic {n}^2 row in:\n{out}")


def python_time(h):
    t0 = time.perf_counter()
    r = mrdw.Contact(h, size=(1.0, 1.0), e_star=1.0).solve(mean_pressure=0.01, tolerance=1e-10)
    t = time.perf_counter() - t0
    _ = r.pressure  # the result array, converted as a user reads it
    return time.perf_counter() - t0, t, r.iterations


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=512)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--mrdw", default=str(ROOT / "target" / "release" / "mrdw"))
    args = ap.parse_args()
    n = args.n
    unit = 2 * math.pi
    h = mrdw.surface((n, n), (1.0, 1.0), 0.8, unit, 2 * unit, unit * (n // 4), seed=2026)
    h = h * (0.1 / mrdw.moments(h, (1.0, 1.0))["rms_slope"])
    cli, py, py_solve = [], [], []
    for _ in range(args.rounds):
        t, it_cli = cli_time(args.mrdw, n)
        cli.append(t)
        total, solve, it_py = python_time(h)
        py.append(total)
        py_solve.append(solve)
    assert it_cli == it_py, (it_cli, it_py)
    c, p = statistics.median(cli), statistics.median(py)
    print(f"CPU: {cpu_model()}; grid {n}^2, {it_py} iterations, {args.rounds} interleaved rounds")
    print(f"CLI (mrdw bench bem)          median {c:.4f} s  [{min(cli):.4f}, {max(cli):.4f}]")
    print(f"Python Contact + solve        median {statistics.median(py_solve):.4f} s")
    print(f"Python incl. result array     median {p:.4f} s  [{min(py):.4f}, {max(py):.4f}]")
    print(f"Python / CLI                  {p / c:.3f}")


if __name__ == "__main__":
    main()
