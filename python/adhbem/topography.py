"""Topographies as users have them: a SurfaceTopography topography object (the contact.engineering
package, optional: https://github.com/ContactEngineering/SurfaceTopography), which brings the file
formats it reads (x3p, di, opd, sur, ...).

Axis order. adhbem's arrays are (Ny, Nx): rows along y, as the grid is distributed by rows and as
h5py and matplotlib show them. SurfaceTopography's ``heights()`` is (nx, ny), x first; it is
transposed here, so a square map keeps its orientation (x stays x)."""
from __future__ import annotations

import numpy as np


def is_surface_topography(obj) -> bool:
    """Whether ``obj`` looks like a SurfaceTopography 2-D topography (duck typing: the package is
    not a dependency).

    Parameters
    ----------
    obj : object
        Anything.
    """
    return callable(getattr(obj, "heights", None)) and hasattr(obj, "physical_sizes") and hasattr(obj, "nb_grid_pts")


def from_surface_topography(t) -> tuple[np.ndarray, tuple[int, int], tuple[float, float], bool]:
    """What adhbem needs of a SurfaceTopography topography.

    Parameters
    ----------
    t : SurfaceTopography.Topography
        A 2-D topography without undefined (NaN) heights.

    Returns
    -------
    z : numpy.ndarray
        The heights, (Ny, Nx) (SurfaceTopography's ``heights()`` transposed).
    n : (int, int)
        (Nx, Ny).
    size : (float, float)
        (Lx, Ly), its physical sizes.
    periodic : bool
        Whether it is periodic.
    """
    if getattr(t, "dim", 2) != 2:
        raise ValueError(f"topography: a SurfaceTopography object of dimension {t.dim}; adhbem needs a 2-D map")
    h = np.asarray(t.heights(), dtype=np.float64)
    if h.ndim != 2:
        raise ValueError(f"topography: heights() of shape {h.shape}; adhbem needs a 2-D map")
    if np.isnan(h).any():
        raise ValueError("topography: the SurfaceTopography map has undefined (NaN) heights; fill them first "
                         "(e.g. its interpolate_undefined_data())")
    nx, ny = h.shape
    sx, sy = (float(v) for v in t.physical_sizes)
    return np.ascontiguousarray(h.T), (nx, ny), (sx, sy), bool(getattr(t, "is_periodic", False))
