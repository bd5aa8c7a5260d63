"""Tests run serially (`pytest tests`) and, for those marked `mpi`, under `mpirun -n 2`
(`ranks3`: also on 3 ranks). Collective tests assert on values every rank has, so a failure
fails on all ranks instead of leaving one waiting in a collective."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))

import pytest  # noqa: E402


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def comm():
    from adhbem import PETSc
    return PETSc.COMM_WORLD
