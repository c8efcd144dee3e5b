#!/usr/bin/env python3
"""Side-by-side: the pressure-cap (saturated) elasto-plastic contact, mrdw.PlasticContact
(periodic=True) against Tamaas 2.9's KatoSaturated, on the same periodic cells.

Usage (from the repository root, with the mrdw Python module built):
    pip install tamaas==2.9.0
    OMP_NUM_THREADS=1 RAYON_NUM_THREADS=1 python3 bench/tamaas_plastic.py --csv plastic.csv

(about a minute; one thread each: the timings are comparable.)

Both codes solve one problem: a rigid surface pressed by a mean pressure onto an elastic
half-space (E* = 1, periodic cell L = 1) whose contact pressure may not exceed the
hardness H. Tamaas' KatoSaturated bounds the pressure by its `pmax` = H in one solve; ours
takes the load as one step from the undeformed state (under a monotonic load the
pressure-cap solution does not depend on the path; the history matters only on
unloading, which Tamaas' solver does not model). Two surfaces:
  sphere: z = -r^2 / (2 R), R = 1, on 96^2 cells, H = 0.05, mean pressures 0.001 to
          0.04: from a small plastic core (Hertz's largest pressure 1.2 H at 0.001) to a
          plateau at H over most of the contact;
  rough:  a self-affine surface (Tamaas' SurfaceGeneratorFilter, H_surf = 0.8, 128^2,
          q0 = 4, q1 = 4, q2 = 32, rms slope 0.1, seed 1), H = 0.1.
For each load it prints and writes: the relative L2 difference of the two pressure
fields, the contact and saturated cell counts of each, and each code's wall time. The
codes stop by different criteria (Tamaas: its error measure below 1e-8; ours: the
complementarity of every cell within 1e-10 of the surface's length scale), so the
pressures agree to the coarser of the two. Not run by CI.
"""
import argparse, csv, multiprocessing as mp, os, sys, tempfile, time
import numpy as np
import tamaas as tm
import mrdw

# Tamaas' stopping tolerance (its relative error measure); 1e-10 stalls on these cells.
TAMAAS_TOLERANCE = 1e-8


def quiet(f):
    """Runs f with Tamaas' C++ output (file descriptors 1 and 2) discarded."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    with tempfile.TemporaryFile() as sink:
        os.dup2(sink.fileno(), 1)
        os.dup2(sink.fileno(), 2)
        try:
            return f()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)


def tamaas_solve(h, hardness, mean_pressure, out):
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(h.shape))
    model.E, model.nu = 1.0, 0.0  # E* = 1
    solver = tm.KatoSaturated(model, h, TAMAAS_TOLERANCE, hardness)
    solver.max_iter = 20000
    t0 = time.perf_counter()
    quiet(lambda: solver.solve(mean_pressure))
    out.put((model.traction.copy(), time.perf_counter() - t0))


def tamaas_saturated(h, hardness, mean_pressure, timeout=120.0):
    """Tamaas' solve in a child process: KatoSaturated 2.9 does not return for some
    grids and loads (e.g. the sphere on 128^2 cells at a mean pressure of 0.005 E*, even
    with a hardness that never binds), so a solve that takes longer than `timeout` is
    reported as such (None)."""
    out = mp.Queue()
    child = mp.Process(target=tamaas_solve, args=(h, hardness, mean_pressure, out))
    child.start()
    try:
        return out.get(timeout=timeout)
    except Exception:
        return None
    finally:
        child.kill()
        child.join()


def ours(h, hardness, mean_pressure):
    t0 = time.perf_counter()
    c = mrdw.PlasticContact(h, hardness, size=(1.0, 1.0), periodic=True)
    s = c.step(mean_pressure=mean_pressure, tolerance=1e-10)
    return s.pressure, time.perf_counter() - t0


def surfaces():
    n = 96
    x = (np.arange(n) - n // 2) / n
    r2 = x[None, :] ** 2 + x[:, None] ** 2
    yield "sphere", np.ascontiguousarray(-r2 / 2.0), 0.05, [0.001, 0.002, 0.01, 0.02, 0.04]
    n = 128
    gen = tm.SurfaceGeneratorFilter2D([n, n])
    gen.spectrum = tm.Isopowerlaw2D()
    gen.spectrum.q0, gen.spectrum.q1, gen.spectrum.q2, gen.spectrum.hurst = 4, 4, 32, 0.8
    gen.random_seed = 1
    h = gen.buildSurface()
    h *= 0.1 / tm.Statistics2D.computeSpectralRMSSlope(h)
    yield "rough", np.ascontiguousarray(h), 0.1, [0.005, 0.01, 0.02, 0.04]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csv", help="write the rows to this file")
    args = ap.parse_args()
    rows = []
    head = ("surface", "hardness", "mean_pressure", "dp_rel", "contact_tamaas",
            "contact_mrdw", "saturated_tamaas", "saturated_mrdw", "t_tamaas_s", "t_mrdw_s")
    print(" | ".join(head))
    for name, h, hardness, loads in surfaces():
        for p in loads:
            pm, tm_ = ours(h, hardness, p)
            got = tamaas_saturated(h, hardness, p)
            if got is None:
                row = (name, hardness, p, "no return", "", int((pm > 0).sum()), "", "", "> 120", f"{tm_:.3f}")
                rows.append(row)
                print(" | ".join(str(v) for v in row))
                continue
            pt, tt = got
            dp = np.linalg.norm(pm - pt) / np.linalg.norm(pt)
            sat = lambda q: int((q >= hardness * (1 - 1e-8)).sum())
            row = (name, hardness, p, f"{dp:.2e}", int((pt > 0).sum()), int((pm > 0).sum()),
                   sat(pt), sat(pm), f"{tt:.3f}", f"{tm_:.3f}")
            rows.append(row)
            print(" | ".join(str(v) for v in row))
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(head)
            w.writerows(rows)


if __name__ == "__main__":
    main()
