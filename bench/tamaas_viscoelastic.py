#!/usr/bin/env python3
"""bem3d's transient viscoelastic contact against Tamaas 2.9's MaxwellViscoelastic.

Three parts (docs/verification.md quotes their output):

1. `scaling`: the relaxing sinusoid of bem3d's test
   `sinusoid_in_full_contact_relaxes_as_the_closed_form` (a rigid h0 cos(2 pi x / L)
   pressed far beyond complete contact, so the displacement's varying part is fixed from
   the first step on and the pressure amplitude over pi h0 / L is the contact modulus
   seen by the history). A generalised Maxwell medium relaxes it at the rate 1/tau_k
   towards E*_inf, whatever the moduli. Tamaas does so only when its elastic model's
   shear modulus E / (2 (1 + nu)) is 1; otherwise its rate and relaxed level depend on
   the moduli' scale, which no linear viscoelastic medium's do.
2. `sinusoid`: with that shear modulus at 1, Tamaas against the closed form of backward
   Euler (its first step and its decay per step, tau / (tau + dt)).
3. `rough`: the same set-up on a periodic rough surface (partial contact, contact set
   moving through ramp, hold, unload and reload under a prescribed mean pressure),
   Tamaas and `mrdw.TransientContact` step by step at three time steps. Tamaas' backward
   Euler is first order in dt, ours exact for piecewise-linear displacement, so their
   difference halves with dt; Richardson's combination 2 T(dt/2) - T(dt) of Tamaas
   removes its first-order error and must approach ours faster.

Conventions: Tamaas' contact moduli are E*_inf = E / (1 - nu^2) and 2 G_k / (1 - nu) per
branch of shear modulus G_k (4 G_k at nu = 0.5); lengths in L; its `solve(p)` sets the
mean pressure at the step's end, as `step(dt, mean_pressure=p)` does here.

    pip install tamaas==2.9.0 numpy     (and the mrdw package: python/README.md)
    OMP_NUM_THREADS=1 python3 bench/tamaas_viscoelastic.py [--csv steps.csv]
"""
import argparse

import numpy as np
import tamaas as tm

SIN_N, SIN_H0, SIN_P = 32, 1e-3, 0.2


def sinusoid_amplitudes(e, nu, shear, times, dt, steps):
    """Tamaas' pressure amplitude / (pi h0 / L) after each step of the relaxing sinusoid."""
    x = np.arange(SIN_N) / SIN_N
    surface = np.tile(SIN_H0 * np.cos(2 * np.pi * x), (SIN_N, 1)).T.copy()
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [SIN_N, SIN_N])
    model.E, model.nu = e, nu
    solver = tm.MaxwellViscoelastic(model, surface, 1e-12, dt, shear, times)
    out = []
    for _ in range(steps):
        solver.solve(SIN_P)
        p = np.array(model.traction).reshape(SIN_N, SIN_N)
        out.append(2 * np.mean(p * np.cos(2 * np.pi * x)[:, None]) / (np.pi * SIN_H0))
    return np.array(out)


def scaling():
    print("1. relaxing sinusoid, one branch G_1 = 1, tau = 0.5: rate from the ratio of "
          "successive decrements (dt = 1e-3), level after 30 tau (dt = 0.01)")
    print("E, nu | G_inf = E/(2(1+nu)) | rate x tau (Maxwell: 1) | relaxed level | E*_inf")
    for e, nu in [(1.0, 0.5), (2.0, 0.5), (3.0, 0.5), (1.0, 0.0), (2.0, 0.0), (2.6, 0.3), (3.0, 0.3)]:
        a = sinusoid_amplitudes(e, nu, [1.0], [0.5], 1e-3, 12)
        d = np.diff(a)
        rate = -np.log(d[6] / d[5]) / 1e-3 * 0.5
        level = sinusoid_amplitudes(e, nu, [1.0], [0.5], 0.01, 1500)[-1]
        print(f"{e}, {nu} | {e / (2 * (1 + nu)):.4f} | {rate:.4f} | {level:.5f} | {e / (1 - nu * nu):.5f}")


def sinusoid():
    e, nu, dt = 3.0, 0.5, 0.01  # G_inf = 1
    shear, times = [2.0, 1.0], [0.3, 2.0]
    a = sinusoid_amplitudes(e, nu, shear, times, dt, 400)
    n = np.arange(1, 401)
    be = 4.0 + sum(4 * g * (tau / (tau + dt)) ** n for g, tau in zip(shear, times))
    print(f"2. relaxing sinusoid at G_inf = 1 (E = 3, nu = 0.5, G_k = {shear}, tau_k = {times}, "
          f"dt = {dt}, 400 steps): max |Tamaas - backward Euler| / E*_inf = "
          f"{np.max(np.abs(a - be)) / 4.0:.1e}")


# The rough case: H = 0.8, 64^2, 4 cells per shortest wavelength, rms slope 0.1; E*_inf = 4,
# two branches; mean pressure [E*_inf units x 4]: ramp, hold, unload to a quarter, reload.
ROUGH_N, E, NU, SHEAR, TIMES = 64, 3.0, 0.5, [2.0, 1.0], [0.3, 2.0]
T_END = 5.0
STEPS = [0.04, 0.02, 0.01]


def rough_surface():
    import mrdw

    n = ROUGH_N
    return mrdw.surface((n, n), (1, 1), 0.8, 2 * np.pi, 2 * np.pi, 2 * np.pi * n / 4,
                        rms_slope=0.1, seed=7)


def mean_pressure(t):
    return np.interp(t, [0, 1, 3, 4, 5], [0, 0.02, 0.02, 0.005, 0.02])


def phase(t):
    return "ramp" if t <= 1 else "hold" if t <= 3 else "unload" if t <= 4 else "reload"


def rough_tamaas(h, dt):
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(h.shape))
    model.E, model.nu = E, NU
    solver = tm.MaxwellViscoelastic(model, h.copy(), 1e-12, dt, SHEAR, TIMES)
    out = []
    for k in range(1, int(round(T_END / dt)) + 1):
        solver.solve(mean_pressure(k * dt))
        out.append(np.array(model.traction).reshape(h.shape).copy())
    return out


def rough_mrdw(h, dt):
    import mrdw

    terms = [(2 * g / (1 - NU), tau) for g, tau in zip(SHEAR, TIMES)]
    c = mrdw.TransientContact(h, E / (1 - NU * NU), terms, size=(1, 1), periodic=True)
    return [np.array(c.step(dt, mean_pressure=mean_pressure(k * dt), tolerance=1e-11).pressure)
            for k in range(1, int(round(T_END / dt)) + 1)]


def rel(a, b):
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def rough(csv):
    h = rough_surface()
    tam = {dt: rough_tamaas(h, dt) for dt in STEPS}
    ours = {dt: rough_mrdw(h, dt) for dt in STEPS + [STEPS[-1] / 2]}
    rows = []
    for dt in STEPS:
        for k, (pt, pm) in enumerate(zip(tam[dt], ours[dt])):
            t = (k + 1) * dt
            fine = ours[dt / 2][2 * k + 1]
            rich = ""
            if dt * 2 in tam:  # Tamaas' Richardson combination at this step's time
                rich = rel(2 * pt - tam[dt * 2][(k + 1) // 2 - 1], pm) if (k + 1) % 2 == 0 else ""
            rows.append((dt, t, phase(t), rel(pt, pm), rich, rel(pm, fine),
                         int((pt > 0).sum()), int((pm > 0).sum())))
    if csv:
        with open(csv, "w") as f:
            f.write("# bench/tamaas_viscoelastic.py: periodic rough 64^2 (H = 0.8, rms slope 0.1), "
                    "E*_inf = 4, branches 4 G_k = 8, 4, tau_k = 0.3, 2; mean pressure ramp 0-1, "
                    "hold 1-3, unload to a quarter 3-4, reload 4-5\n")
            f.write("dt,time,phase,rel_l2_tamaas_vs_mrdw,rel_l2_tamaas_richardson_vs_mrdw,"
                    "rel_l2_mrdw_dt_vs_dt_half,contact_cells_tamaas,contact_cells_mrdw\n")
            for r in rows:
                f.write(",".join(f"{v:.3e}" if isinstance(v, float) else str(v) for v in r) + "\n")
    print("3. rough 64^2, ramp / hold / unload / reload: relative L2 difference of the "
          "pressure fields, max over each phase's steps")
    print("dt | phase | Tamaas vs mrdw | Tamaas Richardson vs mrdw | mrdw dt vs dt/2 | "
          "contact cells differing (max)")
    for dt in STEPS:
        for ph in ["ramp", "hold", "unload", "reload"]:
            sel = [r for r in rows if r[0] == dt and r[2] == ph]
            rich = [r[4] for r in sel if r[4] != ""]
            rich = f"{max(rich):.2e}" if rich else "-"
            print(f"{dt} | {ph} | {max(r[3] for r in sel):.2e} | {rich} | "
                  f"{max(r[5] for r in sel):.2e} | {max(abs(r[6] - r[7]) for r in sel)}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csv", help="write the rough case's per-step differences here")
    a = ap.parse_args()
    tm.set_log_level(tm.LogLevel.error)
    scaling()
    sinusoid()
    rough(a.csv)


if __name__ == "__main__":
    main()
