"""lambda of Eq. (76) calibrated end to end from measured topography files, read by
SurfaceTopography (pip install SurfaceTopography): an AFM map (Digital Instruments
`.di`, 512^2) and others from its file-format examples. Prints one line per file and
bandwidth and leaves each report folder, with its checkpoints (a rerun resumes from
them), under --out; --spectrum R P sets the surrogate spectra of the interval's
spectrum part (default: the kind's).

    python3 bench/calibrate_measured.py --examples <SurfaceTopography>/test/file_format_examples \
        --out reports/calibrate-measured [--files di-1.di nid-1.nid] [--bandwidths 32 64] \
        [--spectrum 12 64]
"""

import argparse
import json
import os
import time
import warnings

import mrdw
import SurfaceTopography as st


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--examples", required=True, help="SurfaceTopography's test/file_format_examples")
    p.add_argument("--out", required=True, help="folder for the report folders")
    p.add_argument("--files", nargs="+", default=["di-1.di", "nid-1.nid"])
    p.add_argument("--bandwidths", nargs="+", type=int, default=[32])
    p.add_argument("--cells", type=int, default=8)
    p.add_argument("--spectrum", nargs=2, type=int, default=None, metavar=("RESAMPLES", "PUNCHES"))
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    for name in a.files:
        t = st.open_topography(os.path.join(a.examples, name)).topography()
        for b in a.bandwidths:
            t0 = time.time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = mrdw.calibrate(
                    t,
                    out=os.path.join(a.out, f"{name}-B{b}"),
                    work=os.path.join(a.out, f"{name}-B{b}.work"),
                    bandwidth=b,
                    cells=a.cells,
                    spectrum_uncertainty=a.spectrum,
                    # the surrogates' punches are the main sample's first ones
                    realisations=None if a.spectrum is None else (max(16, a.spectrum[1]), 400, 16),
                    progress=False,
                    name=name,
                )
            res = r["results"]
            print(
                json.dumps(
                    {
                        "file": name,
                        "pixels": list(t.nb_grid_pts),
                        "size": [float(v) for v in t.physical_sizes],
                        "unit": t.unit,
                        "bandwidth": r["bandwidth"],
                        "cells": a.cells,
                        "lambda": round(r["lambda"], 3),
                        "interval": [round(v, 3) for v in r["interval"]],
                        "interval_spectrum": [round(v, 3) for v in r["interval_spectrum"]],
                        "interval_total": [round(v, 3) for v in r["interval_total"]],
                        "spectrum_resolved": bool(res["spectrum_resolved"]),
                        "spectrum_upper": round(res["spectrum_upper"], 3),
                        "spectrum_bias": round(res["spectrum_bias"], 3),
                        "realisations": r["realisations"],
                        "misfit": [round(v, 3) for v in r["misfit"]],
                        "alpha_3d": round(r["alpha_3d"], 3),
                        "alpha_mrd": round(r["alpha_mrd"], 3),
                        "map_misfit": [round(res["map_misfit_max"], 3), round(res["map_misfit_rms"], 3)],
                        "map_lambda_alone": round(res["map_lambda_alone"], 3),
                        "anisotropy": round(res["map_anisotropy"], 2),
                        "warnings": [w.split(":")[1].strip()[:40] for w in r["warnings"]],
                        "seconds": round(time.time() - t0, 1),
                    }
                ),
                flush=True,
            )


if __name__ == "__main__":
    main()
