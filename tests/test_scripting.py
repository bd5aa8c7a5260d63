"""The Python Solver as scripts use it: options from any sequence or NumPy array. Tests marked
`mpi` assert on values every rank has."""
import os

import numpy as np
import pytest

import adhbem
from adhbem import PETSc

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# JKR sphere, loaded from first touch and pulled off (a_c about 7 h)
OPTS = dict(n=32, size=1.0, E_star=1.0, gamma=1e-3, radius=1.0, steps=6)
PATH = [0.0, 0.02, -0.03]


def mpi():
    return PETSc.COMM_WORLD.tompi4py()


@pytest.fixture
def tmp(tmp_path):
    """A directory every rank sees: rank 0's."""
    return mpi().bcast(str(tmp_path), root=0)


def same_curve(a, b):
    """The columns of two curves equal to the last bit, but for the wall time."""
    return sorted(a) == sorted(b) and all(np.array_equal(a[k], b[k]) for k in a if k != "seconds")


@pytest.mark.mpi
def test_options_from_arrays_and_sequences():
    listed = adhbem.Solver(path=PATH, **OPTS).solve_path()
    for path in (np.array(PATH), tuple(PATH), [np.float64(v) for v in PATH], np.array([PATH]).T):
        c = adhbem.Solver(path=path, **OPTS).solve_path()
        assert same_curve(c, listed), path
    # a grid as an array too, and NumPy scalars
    c = adhbem.Solver(**dict(OPTS, n=np.array([32, 32]), steps=np.int64(6), gamma=np.float64(1e-3)), path=np.array(PATH)).solve_path()
    assert same_curve(c, listed)
