#!/usr/bin/env python3
"""How far the pressure cap lies from J2 plasticity: one sphere, two models, two codes.

Usage (from the repository root, with the mrdw Python module built):
    pip install tamaas==2.9.0
    OMP_NUM_THREADS=1 RAYON_NUM_THREADS=1 python3 bench/tamaas_j2.py --cells 64 --csv j2_64.csv

(about ten minutes at 64^2 cells, most of it in Tamaas' volume solver; 96^2 about four
times that.) Not run by CI.

The problem: a rigid sphere (R = 1) pressed onto a periodic cell (side L = 0.5, the sphere
at its centre) of an elastic-perfectly plastic half-space (E* = 1, nu = 0.3, von Mises
yield stress Y = 0.0125 E*, no hardening), loaded in five force steps to 2.3e-3 E* R^2
(the elastic contact radius 0.12 R, 0.24 L, about 15 cells), then unloaded to half and
to 2 % of the peak. Four answers on the same cells:

  J2      Tamaas 2.9's volume-integral elasto-plastic solver (EPICSolver: its
          Polonsky-Keer contact solve and a DFSANE solve of the plastic strain in a
          volume of `layers` layers down to 0.25 R, fixed point relaxed by 0.3, to 1e-8);
          plasticity in the volume, the yield surface von Mises;
  cap 2.8 mrdw.PlasticContact(periodic=True), the pressure capped at H = 2.8 Y (Tabor's
          hardness: the fully plastic mean pressure of a J2 solid);
  cap 1.6 the same with H = 1.6 Y (the peak Hertz pressure at which a J2 solid first
          yields for nu = 0.3, 0.577 x 2.8 Y: the onset matched instead of the limit);
  elastic Tamaas' elastic surface solver (PolonskyKeerRey) and mrdw.Contact: the check
          that both codes measure the same observables.

Observables, free of the periodic cell's zero mode: the contact area (cells in contact
times the cell's area) and the central indentation delta = u(centre) - u(corner) (surface
displacement into the half-space at the four cells around the sphere's axis, less that at
the cell farthest from it). For the pressure cap, u is the elastic displacement of its
pressure (the spectral Westergaard kernel 2 / (E* |q|), as Tamaas') plus its plastic
displacement. Each is written as the ratio to the elastic contact's at the same force.
"""
import argparse, csv, os, sys, tempfile, time
import numpy as np
import tamaas as tm
from tamaas.nonlinear_solvers import DFSANECXXSolver
import mrdw

R, L, LZ, NU, Y = 1.0, 0.5, 0.25, 0.3, 0.0125
E_STAR = 1.0
# Elastic contact radii of the loading steps, then the unloading fractions of the peak.
RADII = [0.04, 0.06, 0.08, 0.10, 0.12]
UNLOAD = [0.5, 0.02]


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


def history():
    peak = 4.0 * E_STAR * RADII[-1] ** 3 / (3.0 * R)
    loads = [4.0 * E_STAR * a**3 / (3.0 * R) for a in RADII]
    return loads + [f * peak for f in UNLOAD]


def sphere(n):
    x = (np.arange(n) + 0.5) * L / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    return -((xx - L / 2) ** 2 + (yy - L / 2) ** 2) / (2.0 * R)


def delta(u):
    """u at the four cells around the axis less u at the corner cell."""
    n = u.shape[0]
    c = u[n // 2 - 1 : n // 2 + 1, n // 2 - 1 : n // 2 + 1].mean()
    return c - u[0, 0]


def westergaard(p):
    """The periodic surface displacement of pressure p (zero mean), 2 / (E* |q|)."""
    n = p.shape[0]
    q = 2 * np.pi * np.fft.fftfreq(n, d=L / n)
    qq = np.hypot(*np.meshgrid(q, q, indexing="ij"))
    qq[0, 0] = np.inf
    return np.real(np.fft.ifft2(np.fft.fft2(p) * 2.0 / (E_STAR * qq)))


def tamaas_j2(n, layers):
    model = tm.ModelFactory.createModel(tm.model_type.volume_2d, [LZ, L, L], [layers, n, n])
    model.E, model.nu = E_STAR * (1 - NU**2), NU
    residual = tm.ModelFactory.createResidual(model, sigma_y=Y, hardening=0.0)
    surface = sphere(n)
    solver = tm.PolonskyKeerRey(model, surface, 1e-12)
    epic = tm.EPICSolver(solver, DFSANECXXSolver(residual), 1e-8, 0.3)
    rows = []
    for f in history():
        t = time.time()
        err = quiet(lambda: epic.solve(f / L**2))
        p = model["traction"][..., 2]
        u = model["displacement"][0, ..., 2]
        bottom = np.abs(model["plastic_strain"][-1]).max()
        rows.append(dict(force=f, area=(p > 0).sum() * (L / n) ** 2, delta=delta(u),
                         pmax=p.max(), seconds=time.time() - t, error=err, bottom=bottom))
        print(f"J2 {n}^2 x {layers}: F = {f:.3e}: {rows[-1]}", flush=True)
    return rows


def tamaas_elastic(n):
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [n, n])
    model.E, model.nu = E_STAR * (1 - NU**2), NU
    surface = sphere(n)
    solver = tm.PolonskyKeerRey(model, surface, 1e-12)
    rows = []
    for f in history():
        quiet(lambda: solver.solve(f / L**2))
        p = model["traction"]
        rows.append(dict(force=f, area=(p > 0).sum() * (L / n) ** 2,
                         delta=delta(model["displacement"]), pmax=p.max()))
    return rows


def ours(n, hardness):
    c = mrdw.PlasticContact(sphere(n), hardness, size=(L, L), e_star=E_STAR, periodic=True)
    rows = []
    for f in history():
        t = time.time()
        s = c.step(force=f, tolerance=1e-10)
        p = np.asarray(s.pressure)
        plastic = np.asarray(s.plastic_displacement)
        rows.append(dict(force=f, area=(p > 0).sum() * (L / n) ** 2,
                         delta=delta(westergaard(p) + plastic), pmax=p.max(),
                         seconds=time.time() - t))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cells", type=int, default=64)
    ap.add_argument("--layers", type=int, default=None, help="default: cells / 4")
    ap.add_argument("--csv", default=None)
    args = ap.parse_args()
    n = args.cells
    layers = args.layers or n // 4
    elastic = tamaas_elastic(n)
    el_ours = ours(n, float("inf"))
    cap28 = ours(n, 2.8 * Y)
    cap16 = ours(n, 1.6 * Y)
    j2 = tamaas_j2(n, layers)
    header = ["step", "force_over_e_r2", "elastic_area_over_r2", "elastic_delta_over_r",
              "elastic_ours_area_rel", "elastic_ours_delta_rel",
              "j2_area_rel", "j2_delta_rel", "j2_pmax_over_y", "j2_bottom_plastic_strain",
              "cap28_area_rel", "cap28_delta_rel", "cap16_area_rel", "cap16_delta_rel",
              "j2_seconds", "cap28_seconds"]
    table = []
    for k, f in enumerate(history()):
        e = elastic[k]
        rel = lambda r, key: r[k][key] / e[key]
        table.append([k + 1, f, e["area"], e["delta"],
                      rel(el_ours, "area"), rel(el_ours, "delta"),
                      rel(j2, "area"), rel(j2, "delta"), j2[k]["pmax"] / Y, j2[k]["bottom"],
                      rel(cap28, "area"), rel(cap28, "delta"),
                      rel(cap16, "area"), rel(cap16, "delta"),
                      j2[k]["seconds"], cap28[k]["seconds"]])
    print(f"# {n}^2 cells, {layers} layers; ratios to the elastic contact at the same force")
    print(" ".join(header))
    for row in table:
        print(" ".join(f"{v:.5g}" for v in row))
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows(table)


if __name__ == "__main__":
    main()
