"""Tests, one folder per layer of the library (sys/, grid/, geometry/, solver/, results/) and
scripting/ for the Python layer, run serially (`pytest tests`) and, for those marked `mpi`, under `mpirun -n 2`
(`ranks3`: also on 3 ranks). Collective tests assert on values every rank has, so a failure
fails on all ranks instead of leaving one waiting in a collective."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
# the test files sit in one folder per layer (grid/, solver/, ...) and share common.py
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import pytest  # noqa: E402


@pytest.fixture(scope="session")
def comm():
    from adhbem import PETSc
    return PETSc.COMM_WORLD


def pytest_configure(config):
    # Under mpirun every rank is a pytest process; one temporary base directory per rank keeps
    # their clean-ups of old directories from racing each other.
    rank = os.environ.get("OMPI_COMM_WORLD_RANK")
    if rank is not None and not config.option.basetemp:
        size = os.environ.get("OMPI_COMM_WORLD_SIZE", "1")
        config.option.basetemp = os.path.join("/tmp", f"adhbem-pytest-{os.getuid()}-{size}ranks-rank{rank}")
