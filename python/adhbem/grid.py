"""The grid as petsc4py objects: the half-space compliance (a ``PETSc.Mat``, a MatShell applied
with distributed FFTW) and fields as ``PETSc.Vec`` on its row layout. Grids are distributed by
whole rows: each rank holds rows ``j`` in ``row_range(K)`` and all ``Nx`` points of each, so a
local array has shape ``(rows, Nx)`` and index ``[j - j0, i]``."""
from __future__ import annotations

from typing import Sequence, Union

import numpy as np

from ._extension import PETSc, _adhbem
from .options import _is_sequence


Pair = Union[float, Sequence[float]]  # one value for both axes, or (x, y)


def _ndim(value):
    try:
        return np.ndim(value)
    except Exception:  # a ragged list: the check of the array says what is wrong
        return -1


def _shape(value):
    return np.shape(value)


def _pair(value, name):
    if _is_sequence(value):
        value = list(value)
        if len(value) != 2:
            raise ValueError(f"{name}: give one value or two (x, y), got {value!r}")
        return value[0], value[1]
    return value, value


def _comm(comm):
    comm = PETSc.COMM_WORLD if comm is None else comm
    return comm if isinstance(comm, PETSc.Comm) else PETSc.Comm(comm)


def compliance(n: Pair, size: Pair = 1.0, E_star: float = 1.0, boundary: str = "free", comm=None) -> PETSc.Mat:
    """The half-space compliance K (u = K p) on a grid, as a PETSc matrix.

    Parameters
    ----------
    n : int or (int, int)
        Grid points per side, N or (Nx, Ny).
    size : float or (float, float), default 1.0
        The domain's side lengths, L or (Lx, Ly).
    E_star : float, default 1.0
        The reduced modulus E*.
    boundary : {'free', 'periodic'}, default 'free'
        An isolated contact (exact linear convolution, zero-padded) or a periodic cell.
    comm : mpi4py.MPI.Comm or petsc4py.PETSc.Comm, optional
        The ranks (default ``PETSc.COMM_WORLD``).

    Returns
    -------
    petsc4py.PETSc.Mat
        A MatShell applied with distributed FFTW; ``K.createVecs()`` gives Vecs on its grid rows.

    Examples
    --------
    >>> K = adhbem.compliance(64, 1.0)
    >>> p, u = K.createVecs()
    >>> K.mult(p, u)
    """
    Nx, Ny = _pair(n, "n")
    Lx, Ly = _pair(size, "size")
    return _adhbem.compliance(_comm(comm), int(Nx), int(Ny), float(Lx), float(Ly), float(E_star), str(boundary))


def compliance_info(K: PETSc.Mat) -> dict:
    """What a compliance matrix knows of itself.

    Parameters
    ----------
    K : petsc4py.PETSc.Mat
        A compliance made by ``compliance`` or a solver.

    Returns
    -------
    dict
        ``lambda_min`` (a lower bound on the eigenvalues of every restriction K_CC),
        ``row_norm_bound`` (an upper bound on the 2-norm of every row), ``mult_count`` (the
        multiplies so far), ``single_mult_count`` (how many ran in single precision,
        ``cascade_single``), ``Nx``, ``Ny``.
    """
    return _adhbem.compliance_info(K)


def grid_shape(obj: Union[PETSc.Mat, PETSc.Vec]) -> tuple[int, int]:
    """(Nx, Ny) of the grid behind a compliance or a grid Vec.

    Parameters
    ----------
    obj : petsc4py.PETSc.Mat or petsc4py.PETSc.Vec
        A compliance, or a Vec whose block is a grid row (``K.createVecs()``, the solver's fields,
        ``rough_surface``).

    Returns
    -------
    (int, int)
        Nx and Ny.

    Raises
    ------
    TypeError
        For another object; ``ValueError`` for a Vec without grid rows (block size 1).
    """
    if isinstance(obj, PETSc.Mat):
        info = _adhbem.compliance_info(obj)
        return info["Nx"], info["Ny"]
    if isinstance(obj, PETSc.Vec):
        Nx, N = obj.getBlockSize(), obj.getSize()
    else:
        raise TypeError(f"grid_shape: a compliance Mat or a grid Vec, not {type(obj).__name__}")
    if Nx <= 1 and N > 1:
        raise ValueError("this object carries no grid rows (block size 1): pass the compliance Mat, "
                         "or make the Vec with K.createVecs() or rough_surface")
    return Nx, N // Nx


def row_range(obj: Union[PETSc.Mat, PETSc.Vec]) -> tuple[int, int]:
    """(j0, j1): the grid rows this rank owns (grids are distributed by whole rows).

    Parameters
    ----------
    obj : petsc4py.PETSc.Mat or petsc4py.PETSc.Vec
        A compliance or a grid Vec.
    """
    Nx, _ = grid_shape(obj)
    r0, r1 = obj.getOwnershipRange()
    return r0 // Nx, r1 // Nx


def local_rows(vec: PETSc.Vec, obj: Union[PETSc.Mat, PETSc.Vec]) -> np.ndarray:
    """This rank's rows of a grid Vec as a (j1 - j0, Nx) NumPy view: writes go into the Vec.

    Parameters
    ----------
    vec : petsc4py.PETSc.Vec
        A Vec on the grid.
    obj : petsc4py.PETSc.Mat or petsc4py.PETSc.Vec
        What gives the grid (the compliance, or ``vec`` itself).
    """
    Nx, _ = grid_shape(obj)
    j0, j1 = row_range(obj)
    return vec.getArray().reshape(j1 - j0, Nx)


def set_local_rows(vec: PETSc.Vec, obj: Union[PETSc.Mat, PETSc.Vec], array) -> None:
    """Sets this rank's rows of a grid Vec.

    Parameters
    ----------
    vec : petsc4py.PETSc.Vec
        A Vec on the grid.
    obj : petsc4py.PETSc.Mat or petsc4py.PETSc.Vec
        What gives the grid.
    array : array_like
        This rank's rows, shape (j1 - j0, Nx), or the whole field, shape (Ny, Nx) (every rank takes
        its rows of it).

    Raises
    ------
    ValueError
        For another shape.
    """
    Nx, Ny = grid_shape(obj)
    j0, j1 = row_range(obj)
    array = np.asarray(array, dtype=PETSc.ScalarType)
    if array.shape == (Ny, Nx):
        array = array[j0:j1]
    if array.shape != (j1 - j0, Nx):
        raise ValueError(f"expected shape {(j1 - j0, Nx)} (local rows) or {(Ny, Nx)}, got {array.shape}")
    vec.getArray()[:] = array.ravel()


def gather(vec: PETSc.Vec, obj: Union[PETSc.Mat, PETSc.Vec]) -> np.ndarray:
    """The whole field of a grid Vec as an (Ny, Nx) NumPy array on every rank (a copy).

    Collective. Each rank holds the whole grid afterwards: for grids that fit one rank's memory.

    Parameters
    ----------
    vec : petsc4py.PETSc.Vec
        A Vec on the grid.
    obj : petsc4py.PETSc.Mat or petsc4py.PETSc.Vec
        What gives the grid.
    """
    Nx, Ny = grid_shape(obj)
    comm = vec.getComm().tompi4py()
    parts = comm.allgather(vec.getArray().copy())
    return np.concatenate(parts).reshape(Ny, Nx)
