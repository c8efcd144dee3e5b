"""lambda of Eq. (76) for the user's own surface: `calibrate`."""

import os
import tempfile
import warnings

import numpy as np

from . import _mrdw
from ._topography import read_topography


def _stage_source(source, size, folder, name):
    """The scene's source keys and length unit for `source`, files written to `folder`."""
    if isinstance(source, dict):
        if size is not None:
            raise ValueError("size: a self-affine spectrum is in units of the punch diameter L; give no size")
        if "hurst" not in source:
            raise ValueError("source: a self-affine spectrum is a dict with 'hurst' (and 'rolloff')")
        keys = {k: float(v) for k, v in source.items()}
        unknown = set(keys) - {"hurst", "rolloff"}
        if unknown:
            raise ValueError(f"source: unknown self-affine keys {sorted(unknown)}")
        inner = ", ".join(f"{k} = {v!r}" for k, v in keys.items())
        return [f"self_affine = {{ {inner} }}"], "1"
    if isinstance(source, tuple) and len(source) == 2:
        q, c = (np.asarray(v, dtype=float).ravel() for v in source)
        if q.shape != c.shape or q.size < 2:
            raise ValueError("source: an isotropic PSD is (q, C2D), two arrays of one length >= 2")
        if size is None:
            raise ValueError(
                "size: a PSD needs the punch diameter L (its lowest wavenumber is 2 pi / L): pass size=L"
            )
        path = os.path.join(folder, "psd.csv")
        np.savetxt(path, np.column_stack([q, c]), delimiter=",", header="q, C2D", fmt="%.17g")
        length = float(size[0] if np.ndim(size) else size)
        return ["psd = \"psd.csv\"", f"size = [{length!r}, {length!r}]"], "1"
    if isinstance(source, np.ndarray):
        from ._topography import Topography

        data = np.asarray(source, dtype=float)
        if data.ndim != 2:
            raise ValueError(f"source: a height map is 2D, got shape {data.shape}")
        nan = ~np.isfinite(data)
        source = Topography(data, nan if nan.any() else None)
    topo = read_topography(source)
    if topo.undefined is not None and topo.undefined.any():
        raise ValueError(
            f"source: {int(topo.undefined.sum())} of {topo.undefined.size} heights are undefined; "
            "fill or crop the missing points first (the calibration needs a complete map)"
        )
    lx_ly = size if size is not None else topo.size
    if lx_ly is None:
        raise ValueError(
            "size: the topography states no physical size; pass size=(lx, ly) in the unit of its heights"
        )
    lx, ly = (float(lx_ly[0]), float(lx_ly[1])) if np.ndim(lx_ly) else (float(lx_ly),) * 2
    unit = getattr(source, "unit", None)
    if unit is None:
        warnings.warn(
            "units: the topography states no length unit; sizes and heights are taken in one "
            "unspecified unit (lambda is dimensionless; the PSD table's unit reads '1')",
            stacklevel=3,
        )
    if name is None and isinstance(source, (str, bytes, os.PathLike)):
        name = os.path.basename(os.fsdecode(source))
    stem = "".join(c if c.isalnum() or c in "-_." else "_" for c in (name or "map"))
    np.save(os.path.join(folder, stem + ".npy"), np.ascontiguousarray(topo.data, dtype=float))
    return [f"topography = \"{stem}.npy\"", f"size = [{lx!r}, {ly!r}]"], str(unit or "1")


def calibrate(
    source,
    *,
    out,
    size=None,
    work=None,
    bandwidth=32,
    cells=8,
    realisations=(16, 400, 16),
    target=0.10,
    window=(0.02, 0.5),
    loads=16,
    lines=1000,
    solve_map=True,
    seed=0,
    progress=True,
    name=None,
):
    """calibrate(source, *, out, size=None, work=None, ...) -> dict

    lambda of Eq. (76) (C1D = lambda q C2D of the same C2D) for this surface: rigid
    circular 3D punches of diameter L whose faces carry the source's spectrum, against MRD
    lines of the same spectrum; lambda makes MRD's k(F) match the 3D ensemble mean over
    k/(E* L) in `window`. The same computation as the CLI's `calibrate` output kind (the
    scene is written into `out` as scene.toml).

    source: a measured topography (a path read as `read_topography` reads it, a
        `Topography`, a SurfaceTopography topography or an ndarray with `size=`), an
        isotropic PSD `(q [1/length], C2D [length^4])` with `size=L` (the punch
        diameter), or a self-affine spectrum `{"hurst": H, "rolloff": q_r / q0}`.
    out: the report folder (CSV + PNG + summary.json), written as `mrdw run --out` does.
    size: (lx, ly) [length] of a map whose source states none, or L for a PSD.
    work: a checkpoint folder kept after the run: a rerun with the same arguments resumes
        from it (without it the checkpoints are removed once the report is written).
    bandwidth, cells: L / lambda_min of the punches (the spectrum cut there, or at the
        map's Nyquist wavenumber) and cells per shortest wavelength.
    realisations: (min, max, batch) punches: batches are added while lambda's 95 %
        interval is wider than +/- `target`.
    window: the calibration range in k/(E* L); loads: approaches per punch; lines: MRD
        lines; solve_map: also solve the measured map itself in 3D; seed: the random
        phases; name: the map's name in titles (default: the file's name, else "map").

    Returns {"lambda", "interval" (95 %), "misfit" (max, rms |Delta ln k| over the
    range), "alpha_3d", "alpha_3d_interval", "alpha_mrd", "realisations", "bandwidth",
    "results" (every scalar of summary.json), "warnings", "files"}. Raises ValueError
    for bad input (the parameter named), MemoryError for grids that do not fit.
    """
    r = tuple(int(v) for v in realisations)
    if len(r) != 3:
        raise ValueError("realisations: give (min, max, batch)")
    out = os.fspath(out)
    with tempfile.TemporaryDirectory(prefix="mrdw-calibrate-") as folder:
        keys, unit = _stage_source(source, size, folder, name)
        if keys[0].startswith("topography"):
            keys.append(f"solve_map = {'true' if solve_map else 'false'}")
        elif not solve_map:
            raise ValueError("solve_map: applies to a measured map only")
        lines_toml = [
            'name = "calibrate"',
            'title = "lambda of Eq. (76) calibrated for one surface"',
            "[units]",
            f"length = {unit!r}".replace("'", '"'),
            'stress = "1"',
            "[material]",
            "e_star = 1.0",
            "[[outputs]]",
            'kind = "calibrate"',
            *keys,
            f"bandwidth = {int(bandwidth)}",
            f"cells = {int(cells)}",
            f"realisations = {{ min = {r[0]}, max = {r[1]}, batch = {r[2]} }}",
            f"target = {float(target)!r}",
            f"window = [{float(window[0])!r}, {float(window[1])!r}]",
            f"loads = {int(loads)}",
            f"lines = {int(lines)}",
            f"seed = {int(seed)}",
        ]
        scene = os.path.join(folder, "scene.toml")
        with open(scene, "w") as f:
            f.write("\n".join(lines_toml) + "\n")
        done = _mrdw._run_to_folder(
            scene, out, None if work is None else os.fspath(work), bool(progress)
        )
    res = {k.split(".", 1)[1]: v for k, v in done["results"].items()}
    return {
        "lambda": res["lambda"],
        "interval": (res["lambda_lo"], res["lambda_hi"]),
        "misfit": (res["misfit_max"], res["misfit_rms"]),
        "alpha_3d": res["alpha_3d"],
        "alpha_3d_interval": (res["alpha_3d_lo"], res["alpha_3d_hi"]),
        "alpha_mrd": res["alpha_mrd"],
        "realisations": int(res["realisations"]),
        "bandwidth": int(res["bandwidth"]),
        "results": res,
        "warnings": done["warnings"],
        "files": done["files"],
    }
