#!/usr/bin/env python3
"""Tamaas 2.9's MaxwellViscoelastic against the closed form of a relaxing sinusoid.

The test case of bem3d's `sinusoid_in_full_contact_relaxes_as_the_closed_form`: a rigid
periodic surface h = h0 cos(2 pi x / L) pressed at a mean pressure far above the
complete-contact pressure, so that the displacement's varying part is h - mean(h) from
the first step on. Its pressure amplitude over pi h0 / L (the elastic one at unit
modulus) is then the contact modulus seen by the history: for a parallel generalised
Maxwell medium E*(t) = E_inf + sum_k E_k exp(-t / tau_k), with the first step a ramp
over dt, (1/dt) Int_0^dt E*(t - s) ds, which tends to E_inf.

Tamaas' conventions found here: its elastic model (E, nu = 0.5) gives E_inf = E / (1 -
nu^2); a branch of shear modulus G_k adds 4 G_k to the glassy contact modulus (the first
step matches backward Euler: E_inf + 4 G_k tau_k / (tau_k + dt)).

    pip install tamaas==2.9.0 numpy
    OMP_NUM_THREADS=1 python3 bench/tamaas_viscoelastic.py
"""
import numpy as np
import tamaas as tm

N, H0, P_MEAN = 32, 1e-3, 0.2


def tamaas_amplitudes(e, shear, times, dt, t_end):
    x = np.arange(N) / N
    surface = np.tile(H0 * np.cos(2 * np.pi * x), (N, 1)).T.copy()
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [N, N])
    model.E, model.nu = e, 0.5
    solver = tm.MaxwellViscoelastic(model, surface, 1e-12, dt, shear, times)
    out = []
    for k in range(1, int(round(t_end / dt)) + 1):
        solver.solve(P_MEAN)
        p = np.array(model.traction).reshape(N, N)
        out.append((k * dt, 2 * np.mean(p * np.cos(2 * np.pi * x)[:, None]) / (np.pi * H0)))
    return out


def closed_form(e_inf, branches, dt, t):
    return e_inf + sum(
        e * tau / dt * (1 - np.exp(-dt / tau)) * np.exp(-(t - dt) / tau) for e, tau in branches
    )


def main():
    tm.set_log_level(tm.LogLevel.error)
    dt, t_end = 0.01, 4.0
    print("E, G_k, tau_k | t | Tamaas | generalised Maxwell (closed form) | E_inf")
    for e, shear, times in [(1.0, [1.0], [0.5]), (2.0, [1.0], [0.5]), (1.0, [2.0], [0.5]), (1.0, [1.0], [5.0])]:
        e_inf = e / (1 - 0.25)
        branches = [(4 * g, tau) for g, tau in zip(shear, times)]
        for t, a in tamaas_amplitudes(e, shear, times, dt, t_end)[::100]:
            print(f"{e}, {shear}, {times} | {t:.2f} | {a:.4f} | {closed_form(e_inf, branches, dt, t):.4f} | {e_inf:.4f}")


if __name__ == "__main__":
    main()
