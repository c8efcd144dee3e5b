#!/usr/bin/env python3
"""Side-by-side: Tamaas (PolonskyKeerRey) on the periodic surfaces written by mrdw.

Usage (from the repository root):
    cargo run --release -- bench bem --max-n 1024 --write-surfaces /tmp/bem
    pip install tamaas==2.9.0
    python3 bench/tamaas_compare.py /tmp/bem

For each surface_N.npy it times a fresh Tamaas solve (mean pressure 0.01 E*, its
tolerance 1e-10), reads the iteration count from Tamaas' log, and evaluates ONE accuracy
measure on both solutions with Tamaas' own elastic operator: the Tamaas error
|sum(p g)| / (sum(p) std(h, ddof=1)), g the gap shifted to min 0, plus the relative
difference of the two pressure fields. Not run by CI.
"""
import os, re, sys, tempfile, time
import numpy as np
import tamaas as tm

def tamaas_error(model, h, p):
    model.traction[:] = p
    model.solveNeumann()
    g = model.displacement - h
    g -= g.min()
    return abs((p * g).sum()) / (p.sum() * h.std(ddof=1))

def main(folder):
    tm.set_log_level(tm.LogLevel.info)
    files = sorted((int(m.group(1)), f) for f in os.listdir(folder)
                   if (m := re.match(r"surface_(\d+)\.npy$", f)))
    print(f"{'grid':>7} | {'tamaas [s]':>10} | {'iters':>5} | {'tamaas err':>10} | {'mrdw err':>10} | {'|dp|/|p|':>9}")
    for n, f in files:
        h = np.load(os.path.join(folder, f))
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(h.shape))
        model.E, model.nu = 1.0, 0.0   # E* = 1
        solver = tm.PolonskyKeerRey(model, h, 1e-10)
        solver.max_iter = 100000
        # Tamaas logs from C++ to file descriptors 1/2: capture them there.
        with tempfile.TemporaryFile(mode="w+") as log:
            sys.stdout.flush()
            sys.stderr.flush()
            saved = [os.dup(1), os.dup(2)]
            os.dup2(log.fileno(), 1)
            os.dup2(log.fileno(), 2)
            try:
                t0 = time.perf_counter()
                solver.solve(0.01)
                t = time.perf_counter() - t0
            finally:
                sys.stdout.flush()
                sys.stderr.flush()
                os.dup2(saved[0], 1)
                os.dup2(saved[1], 2)
                for fd in saved:
                    os.close(fd)
            log.seek(0)
            its = [int(m.group(1)) for m in re.finditer(r"^\s*(\d+)\s+\S+\s+\S+\s*$", log.read(), re.M)]
        p_t = model.traction.copy()
        err_t = tamaas_error(model, h, p_t)
        p_m = np.load(os.path.join(folder, f"mrdw_pressure_{n}.npy"))
        err_m = tamaas_error(model, h, p_m)
        dp = np.linalg.norm(p_m - p_t) / np.linalg.norm(p_t)
        print(f"{n:>5}^2 | {t:>10.2f} | {max(its) if its else -1:>5} | {err_t:>10.2e} | {err_m:>10.2e} | {dp:>9.2e}")

if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "/tmp/bem")
