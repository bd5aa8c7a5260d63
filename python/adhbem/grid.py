"""The grid as petsc4py objects: the half-space compliance (a ``PETSc.Mat``, a MatShell applied
with distributed FFTW) and fields as ``PETSc.Vec`` on its row layout. Grids are distributed by
whole rows: each rank holds rows ``j`` in ``row_range(K)`` and all ``Nx`` points of each, so a
local array has shape ``(rows, Nx)`` and index ``[j - j0, i]``."""
from ._extension import PETSc, _adhbem
from .options import _is_sequence


def _ndim(value):
    import numpy as np
    try:
        return np.ndim(value)
    except Exception:  # a ragged list: the check of the array says what is wrong
        return -1


def _shape(value):
    import numpy as np
    return np.shape(value)


def _pair(value, name):
    if _is_sequence(value):
        value = list(value)
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
    """dict(lambda_min=..., row_norm_bound=..., mult_count=..., single_mult_count=...) of a compliance
    Mat: a lower bound on the eigenvalues of every K_CC, an upper bound on the 2-norm of every row,
    the multiplies so far, and how many of them ran in single precision (-adh_cascade_single)."""
    return _adhbem.compliance_info(K)


def grid_shape(obj):
    """(Nx, Ny) of the grid behind a compliance Mat or a grid Vec: a row of the grid is a block
    (block size Nx) of the Vecs the Mat makes (``K.createVecs()``) and of the solver's fields."""
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


def row_range(obj):
    """(j0, j1): the rows of the grid this rank owns."""
    Nx, _ = grid_shape(obj)
    r0, r1 = obj.getOwnershipRange()
    return r0 // Nx, r1 // Nx


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
