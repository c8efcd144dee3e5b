#!/usr/bin/env python3
"""Side-by-side: finite-range adhesive contact, mrdw.CohesiveContact(periodic=True) against
Tamaas 2.9's PolonskyKeerRey in gap formulation with MaugisAdhesionFunctional (Dugdale) or
ExponentialAdhesionFunctional (exponential law).

Usage (from the repository root, with the mrdw Python module built):
    pip install tamaas==2.9.0
    OMP_NUM_THREADS=1 python3 bench/tamaas_adhesion.py --csv steps.csv   # about 8 minutes
    OMP_NUM_THREADS=1 python3 bench/tamaas_adhesion.py --law exponential --csv exp.csv

Both codes solve the same periodic cell (E* = 1, L = 1) along the same history of mean
gaps: Tamaas' solve(mean_gap) from its last state, ours step(d) with d = mean(z) - mean
gap (z = max(h) - h; the periodic half-space carries no mean displacement). Tamaas'
functional has the tension w / rho wherever the gap lies below rho, as ours has sigma0
below w / sigma0; its exponential functional has the energy -w exp(-g / rho), the
tension sigma0 exp(-g / rho) of ours with law="exponential" (rho = w / sigma0). Two cases:
  sphere: z = r^2 / 2 (R = 1) on 64^2 and 128^2 cells, w = 0.002, Tabor parameter 0.3;
  rough:  a self-affine surface (H = 0.8, 128^2, rms slope 0.1, q1 = 32 q0, seed 1),
          w = 1e-4, sigma0 = 0.03 (rho = 3.3e-3 against rms height 6.0e-3; the Dugdale
          length spans 14 cells).
For every step it prints and writes the two forces, their difference over the mean
|pressure|, the contact (gap <= 1e-9 rho) and cohesive-zone cells, and, for each code's
state, the largest departure from the law over sigma0 (gaps from Tamaas' operator, so
both states are judged by one evaluation). Not run by CI.
"""
import argparse, csv, sys, time
import numpy as np
import tamaas as tm
import mrdw


def law_departure(p, gap, sigma0, rho, law):
    """Largest departure from the law over sigma0, and the cell counts (contact, and the
    cells out of contact within rho)."""
    contact = gap <= 1e-9 * rho
    zone = ~contact & (gap < rho)
    beyond = gap >= rho
    if law == "dugdale":
        outside = max(np.abs(p[zone] + sigma0).max(initial=0.0), np.abs(p[beyond]).max(initial=0.0))
    else:
        free = ~contact
        outside = np.abs(p[free] + sigma0 * np.exp(-gap[free] / rho)).max(initial=0.0)
    worst = max(
        outside,
        np.maximum(-sigma0 - p[contact], 0.0).max(initial=0.0),
        np.maximum(-gap, 0.0).max(initial=0.0) / rho * sigma0,
    )
    return worst / sigma0, int(contact.sum()), int(zone.sum())


def gap_of(model, p, h, mean_gap):
    """The gap under pressure p by Tamaas' operator, with the prescribed mean."""
    model.traction[:] = p
    model.solveNeumann()
    g = model.displacement - h
    return g - g.mean() + mean_gap


def run(case, h, w, sigma0, approaches, writer, law):
    n = h.shape[0]
    rho = w / sigma0
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, h, 1e-10, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    solver.max_iter = 100000
    if law == "dugdale":
        functional = tm.MaugisAdhesionFunctional(h)
    else:
        functional = tm.ExponentialAdhesionFunctional(h)
    functional.parameters = {"rho": rho, "surface_energy": w}
    solver.addFunctionalTerm(functional)
    ours = mrdw.CohesiveContact(h, w, sigma0, size=(1.0, 1.0), periodic=True, law=law)
    z_mean = (h.max() - h).mean()
    times = [0.0, 0.0]
    print(f"{case} {n}^2, {law} law: w {w:g}, sigma0 {sigma0:.4g}, rho {rho:.4g}, rms height {h.std():.3g}")
    print(f"{'d':>10} {'F tamaas':>12} {'F ours':>12} {'dF/<|p|>':>9} {'contact t/o':>11} {'zone t/o':>11} {'law t':>8} {'law o':>8}")
    for d in approaches:
        mean_gap = z_mean - d
        t0 = time.perf_counter()
        solver.solve(mean_gap)
        times[0] += time.perf_counter() - t0
        p_t = model.traction.copy()
        t0 = time.perf_counter()
        step = ours.step(d, tolerance=1e-10)
        times[1] += time.perf_counter() - t0
        p_o = step.pressure
        law_t, contact_t, zone_t = law_departure(p_t, gap_of(model, p_t, h, mean_gap), sigma0, rho, law)
        law_o, contact_o, zone_o = law_departure(p_o, gap_of(model, p_o, h, mean_gap), sigma0, rho, law)
        scale = max(np.abs(p_t).mean(), 1e-300)
        row = dict(law=law, case=case, cells=n, approach=d, mean_gap=mean_gap, force_tamaas=p_t.mean(),
                   force_ours=p_o.mean(), rel_diff=abs(p_t.mean() - p_o.mean()) / scale,
                   contact_tamaas=contact_t, contact_ours=contact_o, zone_tamaas=zone_t,
                   zone_ours=zone_o, law_tamaas=law_t, law_ours=law_o)
        writer.writerow(row)
        print(f"{d:>+10.3e} {p_t.mean():>+12.5e} {p_o.mean():>+12.5e} {row['rel_diff']:>9.1e} "
              f"{contact_t:>5}/{contact_o:<5} {zone_t:>5}/{zone_o:<5} {law_t:>8.1e} {law_o:>8.1e}")
    print(f"  time: tamaas {times[0]:.1f} s, ours {times[1]:.2f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csv", default="tamaas_adhesion_steps.csv", help="per-step table")
    ap.add_argument("--law", choices=["dugdale", "exponential"], default="dugdale",
                    help="the traction-gap law of both codes")
    ap.add_argument("--cases", nargs="+", choices=["sphere64", "sphere128", "rough"],
                    default=["sphere64", "sphere128", "rough"], help="which histories to run")
    args = ap.parse_args()
    tm.set_log_level(tm.LogLevel.error)
    fields = ["law", "case", "cells", "approach", "mean_gap", "force_tamaas", "force_ours", "rel_diff",
              "contact_tamaas", "contact_ours", "zone_tamaas", "zone_ours", "law_tamaas", "law_ours"]
    with open(args.csv, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        w = 0.002
        sigma0 = 0.3 / (9.0 / (2.0 * np.pi * w)) ** (1.0 / 3.0)
        for n in (n for n in (64, 128) if f"sphere{n}" in args.cases):
            x = (np.arange(n) + 0.5) / n - 0.5
            X, Y = np.meshgrid(x, x, indexing="ij")
            h = -(X ** 2 + Y ** 2) / 2.0
            # Approach into contact and back out past the pull-off (the first contact at 0).
            ds = list(np.linspace(0.01, 0.08, 8)) + list(np.linspace(0.07, -0.01, 9))
            run("sphere", h, w, sigma0, ds, writer, args.law)
        if "rough" not in args.cases:
            return
        n = 128
        h = mrdw.surface((n, n), (1.0, 1.0), 0.8, 2 * np.pi, 2 * np.pi, 2 * np.pi * n / 4,
                         rms_slope=0.1, seed=1)
        s = h.std()
        ds = list(np.linspace(0.0, 2.0 * s, 6)) + list(np.linspace(1.6 * s, -0.6 * s, 12))
        run("rough", h, 1e-4, 0.03, ds, writer, args.law)


if __name__ == "__main__":
    sys.exit(main())
