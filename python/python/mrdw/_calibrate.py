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
        if np.ndim(size):
            sides = [_number("size", v) for v in np.ravel(size)]
            if len(sides) != 2 or sides[0] != sides[1]:
                raise ValueError(
                    f"size = {size!r}: a PSD's punch is a disc of one diameter L; give size=L"
                )
            length = sides[0]
        else:
            length = _number("size", size)
        return ["psd = \"psd.csv\"", f"size = [{length!r}, {length!r}]"], "1"
    if isinstance(source, np.ndarray):
        from ._topography import Topography

        if source.ndim != 2:
            raise ValueError(f"source: a height map is 2D, got shape {source.shape}")
        # Topography reads a masked array's mask and NaN cells as undefined.
        source = Topography(source)
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


def _count(name, value):
    """`value` as an int, refused (naming `name`) unless it is a whole number."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} = {value!r} must be a whole number")
    if isinstance(value, (int, np.integer)):
        return int(value)
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} must be a whole number") from None
    if not (np.isfinite(v) and v == int(v)):
        raise ValueError(f"{name} = {value!r} must be a whole number")
    return int(v)


def _number(name, value):
    """`value` as a float, refused (naming `name`) unless it is a real number."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} = {value!r} must be a number")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} must be a number") from None


def _pair(name, value):
    """`value` as two floats, refused (naming `name`) unless it has exactly two."""
    try:
        items = list(value)
    except TypeError:
        raise ValueError(f"{name} = {value!r} must be a pair (lo, hi)") from None
    if len(items) != 2:
        raise ValueError(f"{name} = {value!r} must be a pair (lo, hi), got {len(items)} values")
    return tuple(_number(f"{name}[{k}]", v) for k, v in enumerate(items))


def calibrate(
    source,
    *,
    out,
    size=None,
    work=None,
    bandwidth=None,
    cells=None,
    realisations=None,
    target=None,
    window=None,
    loads=None,
    lines=None,
    solve_map=True,
    seed=None,
    amplitudes=None,
    spectrum_uncertainty=None,
    progress=True,
    name=None,
):
    """calibrate(source, *, out, size=None, work=None, ...) -> dict

    lambda of Eq. (76) (C1D = lambda q C2D of the same C2D) for this surface: rigid
    circular 3D punches of diameter L whose faces carry the source's spectrum, against MRD
    lines of the same spectrum; lambda makes MRD's k(F) match the 3D ensemble mean over
    k/(E* L) in `window`. The same computation as the CLI's `calibrate` output kind; the
    scene it ran is recorded in `out`'s summary.json (key "scene").

    source: a measured topography (a path read as `read_topography` reads it, a
        `Topography`, a SurfaceTopography topography or an ndarray with `size=`; the
        masked cells of a numpy masked array and NaN heights count as undefined and are
        refused), an isotropic PSD `(q [1/length], C2D [length^4])` with `size=L` (the
        punch diameter), or a self-affine spectrum `{"hurst": H, "rolloff": q_r / q0}`.
    out: the report folder (CSV + PNG + summary.json), written as `mrdw run --out` does.
    size: (lx, ly) [length] of a map whose source states none, or L for a PSD.
    work: a checkpoint folder kept after the run: a rerun with the same arguments resumes
        from it (without it the checkpoints are removed once the report is written).
    bandwidth, cells: L / lambda_min of the punches (the spectrum cut there, or at the
        map's Nyquist wavenumber) and cells per shortest wavelength.
    realisations: (min, max, batch) punches: batches are added while lambda's 95 %
        interval is wider than +/- `target`.
    window: the calibration range (lo, hi) in k/(E* L); loads: approaches per punch;
        lines: MRD lines; solve_map: also solve the measured map itself in 3D; seed: the
        random phases; amplitudes: the 3D punches' faces, "fixed" (|H(q)| as Eq. 71 writes
        it, the shipped lambda table's) or "gaussian" (a Gaussian random field of the
        same mean spectrum); the MRD lines keep Eq. 72's fixed amplitudes;
        spectrum_uncertainty: (resamples, punches) for a measured map: surrogate spectra
        of the map's estimated PSD, each calibrated on the first `punches` punches, give
        the spectrum's own part of the interval ((0, 0) leaves it out); name: the map's
        name in titles (default: the file's name, else "map").

    Parameters left at None take the `calibrate` scene kind's defaults (the same as the
    CLI's; `mrdw show calibrate-ci` and cases/README.md list them). Whole-number
    parameters refuse fractions; every bad value raises ValueError naming it.

    Returns {"lambda", "interval" (95 %, from the punches), "interval_spectrum" (95 %,
    from a measured map's spectrum; None for other sources or without it),
    "interval_total" (both; None likewise), "lambda_bias_corrected" (the spectrum
    bootstrap's bias-corrected lambda, lambda / (1 + spectrum_bias), and its interval:
    an alternative reading; None likewise), "misfit" (max, rms |Delta ln k| over the
    range), "alpha_3d", "alpha_3d_interval", "alpha_mrd", "realisations", "bandwidth",
    "results" (every scalar of summary.json), "warnings", "files"}. Raises ValueError
    for bad input (the parameter named), MemoryError for grids that do not fit.
    """
    keys_given = []
    for key, value in (("bandwidth", bandwidth), ("cells", cells), ("loads", loads),
                       ("lines", lines), ("seed", seed)):
        if value is not None:
            keys_given.append(f"{key} = {_count(key, value)}")
    if realisations is not None:
        try:
            r = list(realisations)
        except TypeError:
            raise ValueError(f"realisations = {realisations!r}: give (min, max, batch)") from None
        if len(r) != 3:
            raise ValueError(f"realisations = {realisations!r}: give (min, max, batch)")
        lo, hi, batch = (_count(f"realisations.{k}", v) for k, v in zip(("min", "max", "batch"), r))
        keys_given.append(f"realisations = {{ min = {lo}, max = {hi}, batch = {batch} }}")
    if spectrum_uncertainty is not None:
        try:
            u = list(spectrum_uncertainty)
        except TypeError:
            raise ValueError(
                f"spectrum_uncertainty = {spectrum_uncertainty!r}: give (resamples, punches)"
            ) from None
        if len(u) != 2:
            raise ValueError(
                f"spectrum_uncertainty = {spectrum_uncertainty!r}: give (resamples, punches)"
            )
        resamples, punches = (_count(f"spectrum_uncertainty.{k}", v)
                              for k, v in zip(("resamples", "punches"), u))
        keys_given.append(
            f"spectrum_uncertainty = {{ resamples = {resamples}, punches = {punches} }}"
        )
    if target is not None:
        keys_given.append(f"target = {_number('target', target)!r}")
    if amplitudes is not None:
        if amplitudes not in ("fixed", "gaussian"):
            raise ValueError(f'amplitudes = {amplitudes!r}: give "fixed" or "gaussian"')
        keys_given.append(f'amplitudes = "{amplitudes}"')
    if window is not None:
        lo, hi = _pair("window", window)
        keys_given.append(f"window = [{lo!r}, {hi!r}]")
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
            *keys_given,
        ]
        scene = os.path.join(folder, "scene.toml")
        with open(scene, "w") as f:
            f.write("\n".join(lines_toml) + "\n")
        try:
            done = _mrdw._run_to_folder(
                scene, out, None if work is None else os.fspath(work), bool(progress)
            )
        except ValueError as e:
            # The scene file is this function's own: its path means nothing to the caller.
            message = (
                str(e)
                .removeprefix(f"{scene}: ")
                .replace(os.path.join(folder, "psd.csv"), "source (q, C2D)")
                .replace(folder + os.sep, "")
            )
            raise ValueError(message) from None
    res = {k.split(".", 1)[1]: v for k, v in done["results"].items()}
    return {
        "lambda": res["lambda"],
        "interval": (res["lambda_lo"], res["lambda_hi"]),
        "interval_spectrum": (
            (res["lambda_spectrum_lo"], res["lambda_spectrum_hi"])
            if "lambda_spectrum_lo" in res else None
        ),
        "interval_total": (
            (res["lambda_total_lo"], res["lambda_total_hi"]) if "lambda_total_lo" in res else None
        ),
        "lambda_bias_corrected": (
            (
                res["lambda_bias_corrected"],
                (res["lambda_bias_corrected_lo"], res["lambda_bias_corrected_hi"]),
            )
            if "lambda_bias_corrected" in res else None
        ),
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
