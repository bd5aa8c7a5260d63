"""Where the adhbem build is: its directory, the executable and the Python extension.

ADHBEM_BUILD names the build directory (relative to the repository's root, or absolute);
without it, build/. The package (adhbem/__init__.py), the tests, tools and benchmarks all ask
here. Importing this module starts neither PETSc nor MPI, so a process can ask before it
launches mpirun.
"""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, os.environ.get("ADHBEM_BUILD") or "build")
EXE = os.path.join(BUILD, "adhbem")
EXTENSION_DIR = os.path.join(BUILD, "python", "adhbem")
