"""adhbem: adhesive normal contact with the boundary element method, on PETSc.

Reading and plotting results needs only h5py, NumPy and matplotlib: ``adhbem.load`` (results.py)
and ``python3 -m adhbem.plot`` (plot.py) work on a machine without PETSc. The solver side
(``Solver``, ``compliance``, ``PETSc``, ...; solver.py) needs petsc4py and the C extension, and is
imported the first time one of its names is used: ``from adhbem import PETSc`` or ``adhbem.Solver``.
"""
import os
import re


def _version_of_source_tree() -> str:
    """The version in the source tree's CMakeLists.txt (``project(adhbem VERSION ...)``), where
    adhbem is used from its clone (``PYTHONPATH=python``) and no installed metadata says it."""
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "CMakeLists.txt")
    try:
        with open(path) as f:
            return re.search(r"project\(adhbem VERSION ([0-9.]+)", f.read()).group(1)
    except (OSError, AttributeError):
        return "unknown"


try:
    from ._version import __version__  # written into the installed package by pip (pyproject.toml)
except ImportError:
    __version__ = _version_of_source_tree()

from .results import Results, load  # noqa: F401,E402

# Open MPI's own MPI-IO (ompio), which HDF5 writes through, opens a shared-file-pointer component
# with every file: "sm" locks it with a semaphore named after the file's base name (one left locked
# by a killed job hangs every later run writing a file of that name), the others leave lock and
# data files beside it when the job is killed. adhbem never uses shared file pointers: ROMIO, which
# creates nothing beside the file, is asked for, as the executable does (this only helps if MPI is
# not started yet; a choice of the user's stays).
os.environ.setdefault("OMPI_MCA_io", "^ompio")
os.environ.setdefault("OMPI_MCA_sharedfp", "^sm")

# The names of the solver side, given on first use, and the module of each.
_SOLVER_NAMES = {"PETSc": "_extension", "_adhbem": "_extension", "chi": "_extension", "chi_square": "_extension",
                 "critical_stress": "_extension", "love_coefficient": "_extension",
                 "compliance": "grid", "compliance_info": "grid", "grid_shape": "grid", "row_range": "grid",
                 "local_rows": "grid", "set_local_rows": "grid", "gather": "grid",
                 "rough_surface": "surface", "Solver": "solver"}

__all__ = ["__version__", "load", "Results", *(n for n in _SOLVER_NAMES if n != "_adhbem")]


def __getattr__(name):
    if name not in _SOLVER_NAMES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib
    try:
        module = importlib.import_module(f".{_SOLVER_NAMES[name]}", __name__)
    except ModuleNotFoundError as e:
        if e.name not in ("petsc4py", "mpi4py"):
            raise
        raise ImportError(f"adhbem.{name} needs petsc4py ({e}); reading results (adhbem.load) and plotting "
                          "(python3 -m adhbem.plot) need only h5py, NumPy and matplotlib", name=e.name) from e
    return getattr(module, name)


def __dir__():
    return sorted(set(globals()) | set(_SOLVER_NAMES))
