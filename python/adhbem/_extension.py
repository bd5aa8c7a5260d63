"""Loading adhbem's C extension: petsc4py initialised with the command line, and the extension
checked against petsc4py (PETSc objects pass between the two, so both must come from the same
PETSc) and against the package's version.

Installed (``pip install``), the extension lies beside the package's Python files. In the source
tree (``PYTHONPATH=python``) it stays in the build folder that ``adhbem_build`` names (build/, or
build64/ for the 64-bit-index PETSc), so builds against different PETSc do not overwrite each other.
"""
import importlib.util
import os
import sys

import petsc4py

# Let PETSc see the command line (options such as -adh_fftw_planner) unless the user already
# initialised petsc4py.
# Under `python -c CODE ARGS` sys.argv[0] is "-c", which petsc4py passes on as an option (taking the
# first argument for its value, which PETSc 3.2x then reports as unused at exit): the program's
# name stands in for it.
if "petsc4py.PETSc" not in sys.modules:
    petsc4py.init([sys.executable, *sys.argv[1:]] if sys.argv[:1] == ["-c"] else sys.argv)
from petsc4py import PETSc  # noqa: E402

try:  # an uncaught exception on several ranks: one traceback, no abort banner (_mpierrors.py)
    from ._mpierrors import install as _install_mpi_errors
    _install_mpi_errors(PETSc.COMM_WORLD.tompi4py())
except ImportError:  # petsc4py without mpi4py: Python's own hook
    pass

from . import __version__  # noqa: E402

_package_path = sys.modules[__package__].__path__  # where the extension is looked for


def _where() -> str:
    """Find the extension: beside the package (installed) or in the source tree's build folder.
    Returns where it was looked for, for the messages."""
    if importlib.util.find_spec(__package__ + "._adhbem") is not None:
        return os.path.dirname(__file__)
    try:
        import adhbem_build  # the source tree's python/ folder
    except ImportError:
        raise ImportError(f"adhbem: the C extension is not in {os.path.dirname(__file__)}: reinstall the package "
                          "(pip install --no-build-isolation .)") from None
    if adhbem_build.EXTENSION_DIR not in _package_path:
        _package_path.insert(0, adhbem_build.EXTENSION_DIR)
    if importlib.util.find_spec(__package__ + "._adhbem") is None:
        raise ImportError(f"adhbem: the C extension is not built in {adhbem_build.BUILD}: run ./run build "
                          "(ADHBEM_INDICES=64 ./run build for the 64-bit-index PETSc, into build64/)")
    return adhbem_build.BUILD


def _import_extension():
    """The C extension, checked against petsc4py's PETSc (the same major.minor and PetscInt) and
    against this package's version."""
    where = _where()
    from . import _adhbem
    built = "%d.%d" % _adhbem.petsc_version[:2]
    runs = "%d.%d" % PETSc.Sys.getVersion()[:2]
    if built != runs:
        raise ImportError(f"adhbem: the C extension in {where} is built against PETSc {built}, but petsc4py "
                          f"({os.path.dirname(petsc4py.__file__)}) runs PETSc {runs}: rebuild adhbem against "
                          f"petsc4py's PETSc, or use the petsc4py of PETSc {built}")
    ours, theirs = 8 * _adhbem.petsc_int_size, 8 * PETSc.IntType().itemsize
    if ours != theirs:
        raise ImportError(f"adhbem: the C extension in {where} is built against a PETSc with {ours}-bit "
                          f"indices, but petsc4py ({os.path.dirname(petsc4py.__file__)}) is the one of a PETSc with "
                          f"{theirs}-bit indices. ./run chooses both (ADHBEM_INDICES=32 or 64); by hand, set "
                          f"ADHBEM_BUILD to the build of petsc4py's PETSc (build/ for 32-bit, build64/ for 64-bit "
                          f"indices) or PYTHONPATH so that it gives the {ours}-bit petsc4py")
    if _adhbem.version != __version__:
        raise ImportError(f"adhbem: the C extension in {where} is adhbem {_adhbem.version}, the Python package "
                          f"{__version__}: rebuild it (./run build, or pip install the package again)")
    return _adhbem


_adhbem = _import_extension()
from ._adhbem import chi, chi_square, critical_stress, love_coefficient  # noqa: E402,F401
