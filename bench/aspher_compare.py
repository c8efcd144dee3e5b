#!/usr/bin/env python3
"""Side-by-side: mrdw against ASPHER (PyPI `aspher`) and optionally Tamaas 2.9 on the
periodic benchmark surfaces, at equal accuracy, one thread against one thread and two
against two. Not run by CI.

Set-up (ASPHER builds from source: cmake, a C++ compiler and Eigen):

    apt-get install cmake libeigen3-dev
    python3 -m venv /tmp/asp && . /tmp/asp/bin/activate
    pip install numpy scikit-build-core pybind11 rfgen ninja
    pip install --no-build-isolation aspher
    pip install ./python                       # mrdw's Python package
    cargo run --release -- bench bem --max-n 1024 --write-surfaces /tmp/bem
    python bench/aspher_compare.py /tmp/bem [--rounds 3] [--max-n 1024]

Each timed solve runs in a fresh worker process with its thread count fixed
(RAYON_NUM_THREADS for mrdw, OMP_NUM_THREADS for ASPHER); rounds interleave the solvers.
Times are each solver's call as a user makes it: mrdw `Contact(h).solve(...)` (operator
set-up included), ASPHER `solve_nested(...)` (nested-grid continuation, its fastest
path). Equal accuracy is judged by ONE routine on both final pressure fields: Tamaas'
error |sum(p g)| / (sum(p) std(h, ddof=1)), g the gap of p under the periodic operator
2 / (E* |q|) (numpy FFT), shifted to min 0. mrdw runs at tolerance 1e-10, ASPHER at
1e-11 (needed to meet the same measure, see shared notes on peer solvers).
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time

import numpy as np


def tamaas_error(h, p):
    n0, n1 = h.shape
    qx = 2 * np.pi * np.fft.fftfreq(n1, d=1.0 / n1)
    qy = 2 * np.pi * np.fft.fftfreq(n0, d=1.0 / n0)
    q = np.hypot(*np.meshgrid(qx, qy))
    c = np.zeros_like(q)
    c[q > 0] = 2.0 / q[q > 0]
    u = np.real(np.fft.ifft2(np.fft.fft2(p) * c))
    g = u - h
    g -= g.min()
    return abs((p * g).sum()) / (p.sum() * h.std(ddof=1))


def worker(solver, path):
    h = np.load(path)
    n = h.shape[0]
    if solver == "mrdw":
        import mrdw

        t0 = time.perf_counter()
        r = mrdw.Contact(h, size=(1.0, 1.0), e_star=1.0).solve(mean_pressure=0.01, tolerance=1e-10)
        t = time.perf_counter() - t0
        p, its = r.pressure, r.iterations
    elif solver == "tamaas":
        import tamaas as tm

        tm.set_log_level(tm.LogLevel.error)
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(h.shape))
        model.E, model.nu = 1.0, 0.0  # E* = 1
        t0 = time.perf_counter()
        pk = tm.PolonskyKeerRey(model, h, 1e-10)
        pk.max_iter = 100000
        pk.solve(0.01)
        t = time.perf_counter() - t0
        p, its = model.traction.copy(), -1  # Tamaas reports iterations only in its log
    else:
        import aspher

        t0 = time.perf_counter()
        r = aspher.solve_nested(grid_size=n, gap=-h.ravel(), p_nominal=0.01, tol=1e-11, backend="periodic")
        t = time.perf_counter() - t0
        p, its = np.asarray(r.pressure).reshape(h.shape), int(r.iterations)
    print(json.dumps({"time": t, "iterations": its, "error": tamaas_error(h, p)}))


def run(solver, path, threads):
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads), OMP_NUM_THREADS=str(threads))
    out = subprocess.run([sys.executable, __file__, "--worker", solver, path], env=env,
                         capture_output=True, text=True, timeout=3600)
    if out.returncode != 0:
        raise RuntimeError(f"{solver} on {path}: {out.stderr[-2000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def cpu_model():
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", nargs="?")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--max-n", type=int, default=1024)
    ap.add_argument("--aspher-threads", type=int, nargs="+", default=[1],
                    help="ASPHER thread counts to time (its OpenMP threads stall on some VMs)")
    ap.add_argument("--tamaas", action="store_true",
                    help="also time Tamaas 2.9 (PolonskyKeerRey, tolerance 1e-10, 1 thread)")
    ap.add_argument("--worker", nargs=2, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.worker:
        return worker(*a.worker)
    files = sorted((int(m.group(1)), os.path.join(a.folder, f)) for f in os.listdir(a.folder)
                   if (m := re.match(r"surface_(\d+)\.npy$", f)))
    cases = [("mrdw", 1), ("mrdw", 2)] + [("aspher", t) for t in a.aspher_threads]
    if a.tamaas:
        cases.append(("tamaas", 1))
    print(f"CPU: {cpu_model()}; {a.rounds} interleaved rounds; medians [min-max]")
    print(f"{'grid':>6} | {'solver':>10} | {'time [s]':>22} | {'iters':>5} | {'Tamaas error':>12}")
    for n, path in files:
        if n > a.max_n:
            continue
        res = {c: [] for c in cases}
        for _ in range(a.rounds):
            for c in cases:
                res[c].append(run(c[0], path, c[1]))
        med = {}
        for (s, t), rs in res.items():
            ts = [r["time"] for r in rs]
            med[(s, t)] = statistics.median(ts)
            print(f"{n:>5}^2 | {s + ' ' + str(t) + 't':>10} | {med[(s, t)]:8.3f} [{min(ts):.3f}-{max(ts):.3f}] |"
                  f" {rs[-1]['iterations']:>5} | {max(r['error'] for r in rs):12.2e}")
        if ("tamaas", 1) in med:
            print(f"{'':>6}   Tamaas / mrdw 1t = {med[('tamaas', 1)] / med[('mrdw', 1)]:.1f}")
        best_aspher = min(v for (s, _), v in med.items() if s == "aspher")
        one = (f"ASPHER 1t / mrdw 1t = {med[('aspher', 1)] / med[('mrdw', 1)]:.2f}; "
               if ("aspher", 1) in med else "")
        print(f"{'':>6}   {one}best ASPHER / mrdw 2t = {best_aspher / med[('mrdw', 2)]:.2f}; "
              f"mrdw 1t / 2t = {med[('mrdw', 1)] / med[('mrdw', 2)]:.2f}")


if __name__ == "__main__":
    main()
