"""A Python script on several ranks whose exception every rank raises prints its traceback once
(rank 0) and exits 1 on every rank without MPI_Abort; an exception on one rank only is printed by
that rank with its rank and aborts the job instead of leaving the others waiting."""
import os
import subprocess
import sys

import pytest

from adhbem import PETSc

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON = os.path.join(os.path.dirname(os.path.dirname(HERE)), "python")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", ADHBEM_ERROR_WAIT="3",
           PYTHONPATH=PYTHON + os.pathsep + os.environ.get("PYTHONPATH", ""))
EVERY_RANK = """
import numpy as np, adhbem
adhbem.Solver(n=32, topography=np.zeros((3, 3)), boundary="periodic")
"""
ONE_RANK = """
import adhbem
from adhbem import PETSc
s = adhbem.Solver(n=16, path=[0.01, 0], steps=1)
if PETSc.COMM_WORLD.getRank() == 1:
    raise RuntimeError("only rank 1")
s.solve_path(progress=False)
"""


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")


def mpirun(tmp_path, ranks, script):
    (tmp_path / "job.py").write_text(script)
    return subprocess.run(["mpirun", "-q", "-n", str(ranks), sys.executable, "job.py"], cwd=tmp_path, env=ENV,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("ranks", [2, 3])
def test_an_error_of_every_rank_prints_once(tmp_path, ranks):
    p = mpirun(tmp_path, ranks, EVERY_RANK)
    assert p.returncode == 1, p.stderr
    err = p.stderr
    assert err.count("Traceback (most recent call last)") == 1, err
    assert err.count("ValueError: topography: expected shape (Ny, Nx) = (32, 32), got (3, 3)") == 1, err
    assert "MPI_ABORT" not in err and "ORTE_ERROR_LOG" not in err, err


def test_an_error_of_one_rank_aborts_naming_it(tmp_path):
    p = mpirun(tmp_path, 2, ONE_RANK)
    assert p.returncode != 0
    assert "[rank 1 of 2, alone] Traceback" in p.stderr and "RuntimeError: only rank 1" in p.stderr, p.stderr
