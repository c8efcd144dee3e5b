"""Height maps with their physical size: what `read_topography` returns."""

import os

import numpy as np

from . import _mrdw


class Topography:
    """A height map with its physical size and its undefined cells.

    Attributes:
        data: ndarray (ny, nx), rows along y, peaks up [length]; NaN where undefined.
        undefined: bool ndarray (ny, nx) of the undefined cells, or None (all defined).
        size: (lx, ly) [length] where the source states it (an ESRI grid's or an x-y-z
            list's cell size times the cells, a topography object's physical_sizes),
            else None.
        periodic: the source's periodicity, or None where it does not say.

    It follows SurfaceTopography's protocol, so ``Contact(t)`` and
    ``TransientContact(t)`` take its size and leave its undefined cells out of the
    contact: ``heights()`` (indexed (x, y), a masked array where cells are undefined),
    ``physical_sizes``, ``is_periodic``, ``nb_grid_pts``, ``has_undefined_data``.
    ``np.asarray(t)`` is ``t.data``.
    """

    def __init__(self, data, undefined=None, size=None, periodic=None, source=None):
        """Checks each argument and names the one that does not fit. A float64 C- or
        Fortran-ordered `data` is kept without a copy; NaN cells count as undefined
        (added to `undefined`), as do the masked cells of a masked array."""
        if np.ma.isMaskedArray(data):
            mask = np.ma.getmaskarray(data)
            data = np.ma.filled(data.astype(np.float64), np.nan)
            if undefined is None and mask.any():
                undefined = mask
        data = np.asarray(data, dtype=np.float64)
        if data.ndim != 2:
            raise ValueError(f"Topography: data must be a 2D array (ny, nx), got {data.ndim}D")
        nan = np.isnan(data)
        if undefined is not None:
            undefined = np.asarray(undefined)
            if undefined.dtype != np.bool_ or undefined.shape != data.shape:
                raise ValueError(
                    f"Topography: undefined must be a bool array of data's shape {data.shape}, "
                    f"got {undefined.dtype} {undefined.shape}"
                )
            if nan.any():
                undefined = undefined | nan
        elif nan.any():
            undefined = nan
        if size is not None:
            try:
                lx, ly = (float(v) for v in size)
            except (TypeError, ValueError):
                raise ValueError(
                    f"Topography: size must be (lx, ly) or None, got {size!r}"
                ) from None
            if not (np.isfinite(lx) and np.isfinite(ly) and lx > 0 and ly > 0):
                raise ValueError(f"Topography: size = ({lx}, {ly}) must be finite and > 0")
            size = (lx, ly)
        if periodic is not None and not isinstance(periodic, (bool, np.bool_)):
            raise ValueError(f"Topography: periodic must be True, False or None, got {periodic!r}")
        self.data = data
        self.undefined = undefined
        self.size = size
        self.periodic = None if periodic is None else bool(periodic)
        self.source = source

    @property
    def shape(self):
        """(ny, nx)"""
        return self.data.shape

    def heights(self):
        """Heights indexed (x, y) [length]; a masked array where cells are undefined."""
        if self.undefined is None:
            return self.data.T
        return np.ma.masked_array(self.data.T, mask=self.undefined.T)

    @property
    def physical_sizes(self):
        """(lx, ly) [length], or None where the source does not say."""
        return self.size

    @property
    def is_periodic(self):
        return self.periodic

    @property
    def nb_grid_pts(self):
        """(nx, ny)"""
        return (self.data.shape[1], self.data.shape[0])

    @property
    def has_undefined_data(self):
        return self.undefined is not None and bool(self.undefined.any())

    def __array__(self, dtype=None, copy=None):
        if dtype is None or np.dtype(dtype) == self.data.dtype:
            return self.data.copy() if copy else self.data
        return self.data.astype(dtype)

    def __repr__(self):
        ny, nx = self.data.shape
        undefined = 0 if self.undefined is None else int(self.undefined.sum())
        return (
            f"Topography(shape=({ny}, {nx}), size={self.size}, periodic={self.periodic}, "
            f"undefined_cells={undefined}, source={self.source!r})"
        )


def read_topography(source):
    """read_topography(source) -> Topography

    A height map from a file or from a topography object, with its physical size and
    its undefined cells.

    source: a path (str, bytes or os.PathLike) to a `.npy` (float32/float64, C or
    Fortran order), `.xyz` point list, ESRI ASCII grid or text matrix (rows of y),
    read by the same code as the CLI's bem_contact output (the file is read without
    holding the GIL); or an object with `heights()` (indexed (x, y)) and
    `physical_sizes` (a SurfaceTopography Topography, for one), whose masked cells
    stay undefined. The size is the file's cell size times its cells where the format
    states it (ESRI grid, x-y-z list), the object's `physical_sizes`, else None (then
    give `size=` to Contact). ``np.asarray`` of the result is the (rows, cols) array.
    """
    if isinstance(source, bytes):
        source = os.fsdecode(source)
    if isinstance(source, (str, os.PathLike)):
        data, cell = _mrdw._read_topography_file(os.fspath(source))
        ny, nx = data.shape
        size = None if cell is None else (cell[0] * nx, cell[1] * ny)
        return Topography(data, size=size, source=os.fspath(source))
    if hasattr(source, "heights") or hasattr(source, "physical_sizes"):
        data, undefined, size, periodic = _mrdw._topography_parts(source)
        return Topography(data, undefined, size, periodic, source=type(source).__name__)
    raise TypeError(
        "read_topography: source must be a path (str, bytes or os.PathLike) or a "
        "topography object with heights() and physical_sizes, got "
        f"{type(source).__name__}"
    )
