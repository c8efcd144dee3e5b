#!/usr/bin/env python3
"""Cattaneo-Mindlin on the free half-space: mrdw's partial-slip solver against ASPHER's
FrictionSolver (PyPI `aspher`, Coulomb friction), cell for cell, with the closed forms,
and their times on one thread each. Not run by CI.

Set-up: as in bench/aspher_compare.py (ASPHER from source, then `pip install ./python`
in the same environment). Run:

    OMP_NUM_THREADS=1 RAYON_NUM_THREADS=1 python bench/aspher_tangential.py \
        [--cells 40 80 160 320] [--poisson 0.0] [--rounds 3] [--csv out.csv]

The case (ASPHER's theory notes' anchor): a rigid sphere of radius 1 pressed into the
free half-space (E* = 1, side 1) to the Hertz contact radius a = 0.4, then a tangential
force Q = mu P / 2 along x (mu = 0.3) in one step from rest. `--cells 160` puts 128
cells across the contact, ASPHER's resolution for its published c/a = 0.7972 against
the closed form (1 - Q/(mu P))^(1/3) = 0.7937.

Each solver takes its own normal solution (ASPHER's FrictionSolver solves the normal
step itself; mrdw's `Contact(..., periodic=False)` at tolerance 1e-10) and then the
tangential step (ASPHER `step(q_bar=...)` with tol_tangential 1e-9; mrdw
`PartialSlip(..., periodic=False).load(...)` at 1e-9; `--aspher-tolerance` sets
ASPHER's, whose default is 1e-5). Reported per grid: the stick
radius from the count of stick cells (over the Hertz a and over the 3D contact
radius), the shift against Mindlin's
delta = 3 mu P (2 - nu) / (16 G a) [1 - (1 - Q/(mu P))^(2/3)] (G = E* (1 - nu) / 2),
the relative L2 distance between the two pressure and the two traction fields, and the
tangential step's time (median over rounds, the solvers interleaved). At nu = 0 the
two solvers solve the same discrete problem (Cerruti's xy coupling vanishes, so
ASPHER's traction along y is zero as ours is by model); for nu > 0 ASPHER also
solves for q_y, mrdw holds it at zero (Mindlin's model), and the difference measures
that model.

`--roughness R --hurst H` adds self-affine roughness to the sphere (C2D ~ q^(-2H-2),
wavelengths from the side down to side / 16, random phases of `--seed`, rms height R
times the Hertz approach a^2 / radius; the same heights go to both codes): the rough
sphere of `mrdw run rough-slip-3d` on the peer's grid.
"""

import argparse
import csv
import os
import platform
import statistics
import time

import numpy as np

import aspher
import mrdw


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def roughness(n, hurst, rms, seed, band=16):
    """Self-affine heights on the unit square, modes 1 <= |k| <= band (units of 2 pi),
    C2D ~ |k|^(-2H-2), random phases; rms height `rms`. The same modes on every grid."""
    rng = np.random.default_rng(seed)
    spec = np.zeros((n, n), complex)
    for i in range(-band, band + 1):
        for j in range(-band, band + 1):
            k2 = i * i + j * j
            phase = rng.uniform(0, 2 * np.pi)
            if 0 < k2 <= band * band:
                spec[i % n, j % n] = k2 ** (-(hurst + 1) / 2) * np.exp(1j * phase)
    z = np.fft.ifft2(spec).real
    z -= z.mean()
    return z * rms / np.sqrt((z**2).mean())


def case(n, nu, mu=0.3, a=0.4, radius=1.0, rough=None):
    h = 1.0 / n
    x = (np.arange(n) + 0.5) * h - 0.5
    xx, yy = np.meshgrid(x, x)
    gap = (xx**2 + yy**2) / (2 * radius)
    if rough is not None:
        r, hurst, seed = rough
        z = roughness(n, hurst, r * a * a / radius, seed)
        gap = gap - z
        gap -= gap.min()
    force = 4 * a**3 / (3 * radius)
    return gap, force, h


def run_aspher(gap, force, h, n, nu, mu, tol, max_iter):
    fs = aspher.FrictionSolver(
        grid_size=n, domain_size=1.0, E_star=1.0, nu=nu, model=aspher.CoulombFriction(mu)
    )
    fs.set_gap(gap.ravel())
    r0 = fs.step(p_bar=force, q_bar=(0.0, 0.0), tol_normal=1e-10, tol_tangential=1e-9)
    assert r0.converged, r0.status_reason
    p = np.asarray(fs.pressure).reshape(n, n)
    big_p = p.sum() * h * h
    t = time.perf_counter()
    r1 = fs.step(q_bar=(0.5 * mu * big_p, 0.0), tol_normal=1e-10, tol_tangential=tol,
                 max_iter=max_iter)
    elapsed = time.perf_counter() - t
    assert r1.converged, r1.status_reason
    if r1.status_reason:
        print(f"# ASPHER at {n}^2: {r1.status_reason} (projection residual {r1.proj_residual:.2e})")
    q = np.asarray(r1.qx).reshape(n, n)
    qy = np.asarray(r1.qy).reshape(n, n)
    return dict(
        pressure=p, traction=q, traction_y=qy, stick=r1.n_stick, shift=r1.delta_t[0],
        force=big_p, seconds=elapsed, iterations=r1.tangential_iters,
    )


def run_mrdw(gap, force, h, n, nu, mu):
    c = mrdw.Contact(-gap, size=(1.0, 1.0), e_star=1.0, periodic=False)
    sol = c.solve(force=force, tolerance=1e-10)
    p = np.asarray(sol.pressure)
    big_p = p.sum() * h * h
    t = time.perf_counter()
    ps = mrdw.PartialSlip(p, mu, size=(1.0, 1.0), e_star=1.0, poisson=nu, periodic=False)
    step = ps.load(0.5 * ps.friction_limit, tolerance=1e-9)
    elapsed = time.perf_counter() - t
    return dict(
        pressure=p, traction=np.asarray(ps.traction), stick=step.stick_cells, shift=step.shift,
        force=big_p, seconds=elapsed, iterations=step.iterations,
    )


def l2(a, b):
    return float(np.sqrt(((a - b) ** 2).sum() / (b**2).sum()))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cells", type=int, nargs="+", default=[40, 80, 160, 320])
    ap.add_argument("--poisson", type=float, default=0.0)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--csv", default=None)
    ap.add_argument("--aspher-tolerance", type=float, default=1e-9,
                    help="ASPHER's tol_tangential (its default is 1e-5)")
    ap.add_argument("--aspher-max-iterations", type=int, default=20000,
                    help="ASPHER's max_iter (its default is 20000)")
    ap.add_argument("--roughness", type=float, default=0.0,
                    help="rms height of added roughness over the Hertz approach (0: smooth)")
    ap.add_argument("--hurst", type=float, default=0.8)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    mu, a, nu = 0.3, 0.4, args.poisson
    rough = (args.roughness, args.hurst, args.seed) if args.roughness > 0 else None
    print(f"# CPU: {cpu_model()}; OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS')}, "
          f"RAYON_NUM_THREADS={os.environ.get('RAYON_NUM_THREADS')}; nu = {nu}; "
          f"ASPHER tol_tangential {args.aspher_tolerance:g}; roughness {args.roughness} "
          f"(H = {args.hurst}, seed {args.seed})")
    rows = []
    for n in args.cells:
        gap, force, h = case(n, nu, rough=rough)
        times = {"aspher": [], "mrdw": []}
        for _ in range(args.rounds):
            ra = run_aspher(gap, force, h, n, nu, mu, args.aspher_tolerance,
                            args.aspher_max_iterations)
            rm = run_mrdw(gap, force, h, n, nu, mu)
            times["aspher"].append(ra["seconds"])
            times["mrdw"].append(rm["seconds"])
        g = (1.0 - nu) / 2.0
        row = dict(cells=n, cells_per_radius=a * n)
        for name, r in (("aspher", ra), ("mrdw", rm)):
            x = 0.5
            c = np.sqrt(r["stick"] * h * h / np.pi)
            area = (r["pressure"] > 0).sum() * h * h
            mindlin = 3 * mu * r["force"] * (2 - nu) / (16 * g * a) * (1 - (1 - x) ** (2 / 3))
            row[f"c_over_a_{name}"] = c / a
            row[f"c_over_a3d_{name}"] = c / np.sqrt(area / np.pi)
            row[f"shift_over_mindlin_{name}"] = r["shift"] / mindlin
            row[f"seconds_{name}"] = statistics.median(times[name])
            row[f"iterations_{name}"] = r["iterations"]
        row["pressure_l2_mrdw_vs_aspher"] = l2(rm["pressure"], ra["pressure"])
        row["traction_l2_mrdw_vs_aspher"] = l2(rm["traction"], ra["traction"])
        row["traction_y_aspher_over_x"] = float(
            np.abs(ra["traction_y"]).max() / np.abs(ra["traction"]).max()
        )
        row["aspher_over_mrdw_time"] = row["seconds_aspher"] / row["seconds_mrdw"]
        rows.append(row)
        print(", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
                        for k, v in row.items()), flush=True)
    if rough is None:
        print("# closed form c/a = 0.793701")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
