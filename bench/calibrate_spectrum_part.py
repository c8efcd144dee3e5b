"""The spectrum's part of a calibration's interval against the punches per surrogate:
one synthetic map (a Gaussian random field, H = 0.8, roll-off at 4 x 2 pi / L, 256^2
pixels, side 1) calibrated with `spectrum_uncertainty = (12, p)` for p = 4, 8, 16, 64
(one work folder: the main punches are computed once). Prints one JSON line per p: the
surrogates' variance of ln lambda, the part the punches explain, the resulting interval
and whether it is resolved.

    python3 bench/calibrate_spectrum_part.py --out reports/spectrum-part [--punches 4 8 16 64]
"""

import argparse
import json
import math
import os
import time

import mrdw


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", required=True, help="folder for the report folders and the work folder")
    p.add_argument("--punches", nargs="+", type=int, default=[4, 8, 16, 64])
    a = p.parse_args()
    n, side = 256, 1.0
    q0 = 2 * math.pi / side
    heights = mrdw.surface((n, n), (side, side), 0.8, q0, 4 * q0, math.pi * n / side,
                           seed=5, gaussian=True)
    work = os.path.join(a.out, "work")
    for punches in a.punches:
        t0 = time.time()
        r = mrdw.calibrate(
            heights,
            size=(side, side),
            out=os.path.join(a.out, f"p{punches}"),
            work=work,
            realisations=(max(16, punches), 400, 16),
            spectrum_uncertainty=(12, punches),
            progress=False,
            name="synthetic",
        )
        res = r["results"]
        print(json.dumps({
            "punches_per_surrogate": punches,
            "lambda": round(r["lambda"], 3),
            "interval_punches": [round(v, 3) for v in r["interval"]],
            "interval_spectrum": [round(v, 3) for v in r["interval_spectrum"]],
            "interval_total": [round(v, 3) for v in r["interval_total"]],
            "var_ln_ratio": round(res["spectrum_var_ln_ratio"], 5),
            "var_from_punches": round(res["spectrum_var_punches"], 5),
            "resolved": bool(res["spectrum_resolved"]),
            "upper": round(res["spectrum_upper"], 3),
            "bias": round(res["spectrum_bias"], 3),
            "realisations": r["realisations"],
            "seconds": round(time.time() - t0, 1),
        }), flush=True)


if __name__ == "__main__":
    main()
