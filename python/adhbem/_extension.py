"""Loading adhbem's C extension: petsc4py initialised with the command line, and the extension
of the build ``adhbem_build`` names, checked against petsc4py (PETSc objects pass between the two,
so both must come from the same PETSc)."""
import importlib.util
import os
import sys

import adhbem_build
import petsc4py

# Let PETSc see the command line (options such as -adh_fftw_planner) unless the user already
# initialised petsc4py.
if "petsc4py.PETSc" not in sys.modules:
    petsc4py.init(sys.argv)
from petsc4py import PETSc  # noqa: E402

_package_path = sys.modules[__package__].__path__  # where the extension is looked for


def _import_extension():
    """The C extension of the build adhbem_build names, checked against petsc4py: PETSc objects
    pass between the two, so both must come from the same PETSc (the same PetscInt)."""
    if adhbem_build.EXTENSION_DIR not in _package_path:
        _package_path.insert(0, adhbem_build.EXTENSION_DIR)
    if importlib.util.find_spec(__package__ + "._adhbem") is None:
        raise ImportError(f"adhbem: the C extension is not built in {adhbem_build.BUILD}: run ./run build "
                          "(ADHBEM_INDICES=64 ./run build for the 64-bit-index PETSc, into build64/)")
    from . import _adhbem
    ours, theirs = 8 * _adhbem.petsc_int_size, 8 * PETSc.IntType().itemsize
    if ours != theirs:
        raise ImportError(f"adhbem: the C extension in {adhbem_build.BUILD} is built against a PETSc with {ours}-bit "
                          f"indices, but petsc4py ({os.path.dirname(petsc4py.__file__)}) is the one of a PETSc with "
                          f"{theirs}-bit indices. ./run chooses both (ADHBEM_INDICES=32 or 64); by hand, set "
                          f"ADHBEM_BUILD to the build of petsc4py's PETSc (build/ for 32-bit, build64/ for 64-bit "
                          f"indices) or PYTHONPATH so that it gives the {ours}-bit petsc4py")
    return _adhbem


_adhbem = _import_extension()
from ._adhbem import chi, chi_square, critical_stress, love_coefficient  # noqa: E402,F401
