"""Where the adhbem build is: its directory, the executable and the Python extension.

./run sets ADHBEM_BUILD to the build of the PETSc it chose: build/ (Debian's PETSc, 32-bit
indices) or build64/ (ADHBEM_INDICES=64, Debian's PETSc64); without it, build/. A relative
ADHBEM_BUILD is taken from the repository's root. The package (adhbem/__init__.py), the tests,
tools and benchmarks all ask here. Importing this module starts neither PETSc nor MPI, so a
process can ask before it launches mpirun.
"""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, os.environ.get("ADHBEM_BUILD") or "build")
EXE = os.path.join(BUILD, "adhbem")
EXTENSION_DIR = os.path.join(BUILD, "python", "adhbem")
