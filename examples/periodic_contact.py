"""A periodic rough contact from Python, set up as a Tamaas user would.

Tamaas' tutorial builds a self-affine surface with an isotropic power-law spectrum
(roll-off q_r = 4, cut-offs q_0 = 4, q_s = 32, in units of 2 pi / L; Hurst exponent
0.8), scales it to an rms slope and solves with PolonskyKeerRey at a mean pressure. The
same here with mrdw; the contact map is plotted when matplotlib is installed.

    python examples/periodic_contact.py [--n 256] [--plot reports/contact.png]
"""

import argparse
import os
import math

import numpy as np

import mrdw


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=256, help="cells per side (default 256)")
    ap.add_argument("--pressure", type=float, default=0.01, help="mean pressure / E* (default 0.01)")
    ap.add_argument("--plot", default=None, help="write the contact map to this PNG")
    args = ap.parse_args()

    n, length, e_star = args.n, 1.0, 1.0
    unit = 2 * math.pi / length  # wavenumbers in units of 2 pi / L, as in Tamaas
    h = mrdw.surface((n, n), (length, length), hurst=0.8, q0=4 * unit, qr=4 * unit,
                     q1=min(32, n // 4) * unit, rms_slope=0.1, seed=1)

    contact = mrdw.Contact(h, size=(length, length), e_star=e_star, periodic=True)
    r = contact.solve(mean_pressure=args.pressure * e_star, tolerance=1e-10)

    print(f"grid {n} x {n}, mean pressure {args.pressure} E*")
    print(f"relative contact area  {r.contact_fraction:.5f}")
    print(f"mean gap / rms height  {r.mean_gap / h.std():.5f}")
    print(f"iterations {r.iterations}, residual {r.residual:.1e}")

    if args.plot:
        try:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            raise SystemExit(
                f"--plot {args.plot}: matplotlib is not installed; install it with "
                "pip install './python[plot]' (or pip install matplotlib)"
            )
        fig, ax = plt.subplots(figsize=(5, 4.3))
        im = ax.imshow(r.pressure / e_star, origin="lower", extent=(0, length, 0, length),
                       cmap="magma")
        fig.colorbar(im, ax=ax, label="pressure / E*")
        ax.set_xlabel("x / L")
        ax.set_ylabel("y / L")
        ax.set_title(f"contact pressure, area {100 * r.contact_fraction:.2f} %")
        fig.tight_layout()
        os.makedirs(os.path.dirname(os.path.abspath(args.plot)), exist_ok=True)
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
