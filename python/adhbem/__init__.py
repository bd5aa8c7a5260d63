"""adhbem: adhesive normal contact with the boundary element method, on PETSc.

The objects this package hands out are real petsc4py objects: the half-space compliance is a
``PETSc.Mat`` (a MatShell applied with distributed FFTW), fields are ``PETSc.Vec`` on its row
layout. Grids are distributed by whole rows: each rank holds rows ``j`` in ``row_range(K)`` and
all ``Nx`` points of each, so a local array has shape ``(rows, Nx)`` and index ``[j - j0, i]``.
"""
import sys

import petsc4py

# Let PETSc see the command line (options such as -adh_fftw_planner) unless the user already
# initialised petsc4py.
if "petsc4py.PETSc" not in sys.modules:
    petsc4py.init(sys.argv)
from petsc4py import PETSc  # noqa: E402

from . import _adhbem  # noqa: E402
from ._adhbem import chi, chi_square, critical_stress, love_coefficient  # noqa: E402,F401

__all__ = ["PETSc", "compliance", "grid_shape", "row_range", "local_rows", "set_local_rows",
           "gather", "compliance_info", "chi", "chi_square", "critical_stress", "love_coefficient"]


def _pair(value, name):
    if isinstance(value, (tuple, list)):
        if len(value) != 2:
            raise ValueError(f"{name}: give one value or two (x, y), got {value!r}")
        return value[0], value[1]
    return value, value


def compliance(n, size=1.0, E_star=1.0, boundary="free", comm=None):
    """The compliance K (u = K p) on an n = N or (Nx, Ny) grid over size = L or (Lx, Ly).

    boundary is "free" (isolated contact, exact linear convolution) or "periodic".
    """
    Nx, Ny = _pair(n, "n")
    Lx, Ly = _pair(size, "size")
    comm = PETSc.COMM_WORLD if comm is None else comm
    if not isinstance(comm, PETSc.Comm):
        comm = PETSc.Comm(comm)
    return _adhbem.compliance(comm, int(Nx), int(Ny), float(Lx), float(Ly), float(E_star), str(boundary))


def compliance_info(K):
    """dict(lambda_min=..., mult_count=...) of a compliance Mat."""
    return _adhbem.compliance_info(K)


def grid_shape(obj):
    """(Nx, Ny) of the grid behind a compliance Mat (or its DM)."""
    dm = obj.getDM() if isinstance(obj, PETSc.Mat) else obj
    Nx, Ny = dm.getSizes()
    return Nx, Ny


def row_range(obj):
    """(j0, j1): the rows of the grid this rank owns."""
    dm = obj.getDM() if isinstance(obj, PETSc.Mat) else obj
    (_, _), (j0, j1) = dm.getRanges()
    return j0, j1


def local_rows(vec, obj):
    """The local part of a grid Vec as a (rows, Nx) NumPy view (writes go into the Vec)."""
    Nx, _ = grid_shape(obj)
    j0, j1 = row_range(obj)
    return vec.getArray().reshape(j1 - j0, Nx)


def set_local_rows(vec, obj, array):
    """Set the local rows of a grid Vec from a (rows, Nx) array, or from the full (Ny, Nx) field."""
    import numpy as np
    Nx, Ny = grid_shape(obj)
    j0, j1 = row_range(obj)
    array = np.asarray(array, dtype=PETSc.ScalarType)
    if array.shape == (Ny, Nx):
        array = array[j0:j1]
    if array.shape != (j1 - j0, Nx):
        raise ValueError(f"expected shape {(j1 - j0, Nx)} (local rows) or {(Ny, Nx)}, got {array.shape}")
    vec.getArray()[:] = array.ravel()


def gather(vec, obj):
    """The whole field as an (Ny, Nx) NumPy array on every rank (for small grids and tests)."""
    import numpy as np
    Nx, Ny = grid_shape(obj)
    comm = vec.getComm().tompi4py()
    parts = comm.allgather(vec.getArray().copy())
    return np.concatenate(parts).reshape(Ny, Nx)
