#!/usr/bin/env python3
"""Hertz-limit estimate of lambda(H) for large H (docs/results.md, "Why lambda >> pi").

For large H the roughness is dominated by the few longest wavelengths, so a rough punch
first touches like one smooth bump: 3D Hertz, k = (6 E*^2 R F)^(1/3) with R the
geometric mean of the principal radii at the face's highest point; MRD springs on a
line whose peak has second derivative kappa give the same law with R1 = 2 / kappa (the
rule of Hess maps r^2/(2R) to x^2/R). With every realisation in units of its own rms
height h, Eq. (77)'s calibration K3(f) = K1(f sqrt(pi/lambda)) then gives

    lambda_Hertz = pi * (<R1^(1/3)> / <R3^(1/3)>)^6,

R in units of L^2/h. This script estimates it from independent Gaussian syntheses
(numpy FFT, not the workbench's generator): surfaces with |k| in 1..B (units 2 pi/L) on
n^2 cells, the face the inscribed disc; lines with C1D ~ q C2D on 16 points per cell.
Curvatures by central differences at the highest point (faces whose highest point is
not a maximum of the surface, e.g. on the rim with a non-negative-definite Hessian,
are skipped; "interior" also skips highest points within 3 cells of the rim).

    python3 scripts/lambda_hertz_limit.py            # needs numpy; about a minute
"""
import numpy as np

N, B, REALISATIONS, SEED = 256, 32, 400, 2


def main():
    rng = np.random.default_rng(SEED)
    n, n1 = N, 16 * N
    k = np.fft.fftfreq(n, 1 / n)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    q = np.hypot(kx, ky)
    x = (np.arange(n) + 0.5) / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    r = np.hypot(xx - 0.5, yy - 0.5)
    face, interior = r <= 0.5, r < 0.5 - 3.0 / n
    k1 = np.fft.rfftfreq(n1, 1 / n1)
    dx, dx1 = 1 / n, 1 / n1
    print("H, lambda_Hertz (all faces), lambda_Hertz (interior maxima), faces used")
    for hurst in [1.5, 2.0, 2.5, 3.0]:
        band = (q >= 1) & (q <= B)
        amp = np.zeros_like(q)
        amp[band] = q[band] ** (-hurst - 1.0)  # sqrt(C2D)
        band1 = (k1 >= 1) & (k1 <= B)
        amp1 = np.zeros_like(k1)
        amp1[band1] = k1[band1] ** (-hurst - 0.5)  # sqrt(q C2D)
        r3, r3_in, r1 = [], [], []
        for _ in range(REALISATIONS):
            noise = rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n))
            z = np.real(np.fft.ifft2(amp * noise))
            z = (z - z[face].mean()) / z[face].std()
            i, j = np.unravel_index(np.argmax(np.where(face, z, -np.inf)), z.shape)
            ip, jp = (i + 1) % n, (j + 1) % n
            zxx = (z[ip, j] - 2 * z[i, j] + z[i - 1, j]) / dx**2
            zyy = (z[i, jp] - 2 * z[i, j] + z[i, j - 1]) / dx**2
            zxy = (z[ip, jp] - z[ip, j - 1] - z[i - 1, jp] + z[i - 1, j - 1]) / (4 * dx * dx)
            det = zxx * zyy - zxy**2
            if det > 0 and zxx < 0:
                r3.append(det ** (-1 / 6))  # (1/sqrt(det))^(1/3)
                if interior[i, j]:
                    r3_in.append(det ** (-1 / 6))
            noise1 = rng.normal(size=k1.size) + 1j * rng.normal(size=k1.size)
            line = np.fft.irfft(amp1 * noise1, n1)
            line = (line - line.mean()) / line.std()
            m = np.argmax(line)
            kappa = -(line[(m + 1) % n1] - 2 * line[m] + line[m - 1]) / dx1**2
            r1.append((2 / kappa) ** (1 / 3))
        lam = np.pi * (np.mean(r1) / np.mean(r3)) ** 6
        lam_in = np.pi * (np.mean(r1) / np.mean(r3_in)) ** 6
        print(f"{hurst}, {lam:.2f}, {lam_in:.2f}, {len(r3)} of {REALISATIONS}")


if __name__ == "__main__":
    main()
