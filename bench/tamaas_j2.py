#!/usr/bin/env python3
"""How far the pressure cap lies from J2 plasticity: a sphere pressed into an
elastic-perfectly plastic half-space and unloaded, mrdw.PlasticContact (the pressure cap at
the hardness H = 2.8 sigma_y, periodic) against Tamaas 2.9's volume-integral
elasto-plastic solver (EPICSolver: von Mises plasticity in the volume below the surface,
no hardening) on the same periodic cell and the same surface grid.

Usage (from the repository root, with the mrdw Python module built):
    pip install tamaas==2.9.0
    OMP_NUM_THREADS=1 python3 bench/tamaas_j2.py --layers 16 --csv j2.csv

(about 8 minutes at 16 layers, most of it Tamaas' plastic solves; 32 layers about twice;
the rough surface at `--depth 0.25 --layers 16` about 9 minutes.)

The problem: a rigid sphere z = -r^2 / (2 R), R = 1, on a periodic cell L = 1 of 64^2
cells, E = 1, nu = 0.3 (E* = E / (1 - nu^2) for the cap), sigma_y = 0.04 E. Loads are
mean pressures, in units of the force F_c at which Hertz's largest pressure reaches
1.6 sigma_y (the onset of J2 yield below the surface for nu = 0.3; Johnson, Contact
Mechanics, Sec. 6.2): loading to 1, 3, 10, 30 F_c, then unloading to 3 and 0.01 F_c.
The pressure cap yields where the pressure reaches H, which its users set from the
hardness of a fully plastic indent, H = 2.8 sigma_y (Tabor's constraint factor);
J2 yields at 1.6 sigma_y = 0.57 H. Tamaas' volume is `--depth` deep (default 0.5 L)
in `--layers` layers. For each load: the contact cells, the largest and the mean contact
pressure over sigma_y, by each model (and by the elastic contact). Not run by CI.

`--surface rough`: the same cell, materials and models on a periodic random-phase
self-affine surface instead of the sphere (`mrdw.surface`: H = 0.8, wavelengths from L
down to L / 8, i.e. 8 cells per shortest wavelength, rms slope `--rms-slope` (0.1),
seed 1: the mixed regime, where at the first load J2 would yield under a third of the
contact cells (elastic pressure above 1.6 sigma_y) and the cap saturates a tenth), loaded
to mean pressures of 0.05, 0.15 and 0.4 sigma_y and unloaded to 0.15 and 0.01 sigma_y.
Use `--depth 0.25 --layers 16` (the layers' depth equal to the cells' width; plastic zones
under summits of L / 8 stay within L / 16 of the surface).
"""
import argparse, csv, time
import numpy as np
import tamaas as tm
from tamaas.nonlinear_solvers import DFSANECXXSolver
import mrdw

E, NU, SIGMA_Y, N, L, R = 1.0, 0.3, 0.04, 64, 1.0, 1.0
LOADS = [1, 3, 10, 30, 3, 0.01]  # over F_c: loading, then unloading
ROUGH_LOADS = [0.05, 0.15, 0.4, 0.15, 0.01]  # mean pressure over sigma_y


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--layers", type=int, default=16, help="Tamaas' layers below the surface")
    ap.add_argument("--depth", type=float, default=0.5, help="Tamaas' volume depth over L")
    ap.add_argument("--surface", choices=("sphere", "rough"), default="sphere",
                    help="the rigid body: the sphere, or a self-affine rough surface")
    ap.add_argument("--rms-slope", type=float, default=0.1, help="the rough surface's rms slope")
    ap.add_argument("--csv", help="write the rows to this file")
    args = ap.parse_args()
    tm.set_log_level(tm.LogLevel.error)
    e_star = E / (1 - NU**2)
    hardness = 2.8 * SIGMA_Y
    x = (np.arange(N) - N // 2) * (L / N)
    if args.surface == "sphere":
        h = np.ascontiguousarray(-(x[None, :] ** 2 + x[:, None] ** 2) / (2 * R))
    else:
        q0 = 2 * np.pi / L
        h = np.ascontiguousarray(mrdw.surface((N, N), (L, L), 0.8, q0, q0, 8 * q0,
                                              rms_slope=args.rms_slope, seed=1))
    model = tm.ModelFactory.createModel(
        tm.model_type.volume_2d, [args.depth * L, L, L], [args.layers, N, N])
    model.E, model.nu = E, NU
    material = tm.materials.IsotropicHardening(model, sigma_y=SIGMA_Y, hardening=0.0)
    plastic = DFSANECXXSolver(tm.Residual(model, material))
    model.setIntegrationMethod(tm.integration_method.linear, 1e-12)
    epic = tm.EPICSolver(tm.PolonskyKeerRey(model, h, 1e-12), plastic, 1e-7, relaxation=0.3)
    cap = mrdw.PlasticContact(h, hardness, size=(L, L), e_star=e_star, periodic=True)
    elastic = mrdw.PlasticContact(h, float("inf"), size=(L, L), e_star=e_star, periodic=True)
    p_onset = 1.6 * SIGMA_Y
    f_c = np.pi**3 * R**2 * p_onset**3 / (6 * e_star**2)  # Hertz: p0 = (6 F E*^2 / (pi^3 R^2))^(1/3)
    a_c = np.pi * p_onset * R / (2 * e_star)
    print(f"cells per contact radius at F_c: {a_c / (L / N):.2f}; layer depth over cell: "
          f"{args.depth * N / args.layers:.2f}")
    if args.surface == "sphere":
        loads, unit, first = LOADS, f_c / (L * L), "load_over_fc"
    else:
        loads, unit, first = ROUGH_LOADS, SIGMA_Y, "mean_pressure_over_sy"
    head = (first, "phase", "contact_cells_j2", "contact_cells_cap", "contact_cells_elastic",
            "p_max_over_sy_j2", "p_max_over_sy_cap", "p_mean_over_sy_j2", "p_mean_over_sy_cap",
            "t_j2_s")
    rows, peak = [], 0.0
    print(" | ".join(head))
    for f in loads:
        p = f * unit
        t0 = time.perf_counter()
        epic.solve(p)
        t = time.perf_counter() - t0
        pj = np.array(model.traction[..., 2])
        pc = cap.step(mean_pressure=p, tolerance=1e-10).pressure
        pe = elastic.step(mean_pressure=p, tolerance=1e-10).pressure
        phase = "load" if f >= peak else "unload"
        peak = max(peak, f)
        cells = lambda q: int((q > 0).sum())
        row = (f, phase, cells(pj), cells(pc), cells(pe), pj.max() / SIGMA_Y, pc.max() / SIGMA_Y,
               pj.sum() / max(cells(pj), 1) / SIGMA_Y, pc.sum() / max(cells(pc), 1) / SIGMA_Y,
               round(t, 1))
        rows.append(row)
        print(" | ".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in row), flush=True)
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(head)
            w.writerows(rows)


if __name__ == "__main__":
    main()
