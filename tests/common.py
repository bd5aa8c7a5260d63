"""Helpers shared by the test files: printing on rank 0, MPI reductions for collective
assertions, the environment of a child Python, a compliance applied and assembled densely, and the JKR scales of a sphere (R = 1, E* = 1
unless given)."""
import math
import os

import numpy as np
import adhbem
from adhbem import PETSc, theory

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # the project

R = 1.0   # sphere radius
E = 1.0   # reduced modulus E*


def rank0():
    return PETSc.COMM_WORLD.getRank() == 0


def say(*args):
    """Print on rank 0 only (pytest -s shows it)."""
    if rank0():
        print(*args, flush=True)


def _max():
    from mpi4py import MPI
    return MPI.MAX


def _min():
    from mpi4py import MPI
    return MPI.MIN


def python_env(**extra):
    """The environment of a child Python that imports adhbem: this one's, with python/ first on
    PYTHONPATH and the rest kept (./run puts the 64-bit petsc4py there), and `extra`."""
    python = os.path.join(ROOT, "python")
    path = os.environ.get("PYTHONPATH")
    return dict(os.environ, PYTHONPATH=python + (os.pathsep + path if path else ""), **extra)


def radius(area):
    """Contact radius from the area, a = sqrt(A / pi)."""
    return np.sqrt(np.asarray(area) / math.pi)


def jkr_scales(gamma, R=R, E=E):
    """(a_c, |d_c|, F_adh) of a sphere with work of adhesion gamma."""
    ac = (9 * math.pi * gamma * R ** 2 / (8 * E)) ** (1 / 3)
    dc = (3 * math.pi ** 2 * gamma ** 2 * R / (64 * E ** 2)) ** (1 / 3)
    return ac, dc, 1.5 * math.pi * gamma * R


def gamma_for(ac, R=R, E=E):
    """The work of adhesion that gives the JKR critical radius a_c (with the tests' R and E*)."""
    return theory.jkr_dgamma(ac, R, E)


def label_patches(mask, wrap):
    """The 4-connected clusters of a boolean (Ny, Nx) mask by flood fill, wrapping across the edges
    when wrap (a periodic cell): (labels, -1 off the mask and 0.. on it, and their number)."""
    ny, nx = mask.shape
    label = -np.ones(mask.shape, int)
    n = 0
    for j0, i0 in zip(*np.nonzero(mask)):
        if label[j0, i0] >= 0:
            continue
        label[j0, i0] = n
        todo = [(j0, i0)]
        while todo:
            j, i = todo.pop()
            for dj, di in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                b, a = j + dj, i + di
                if wrap:
                    b, a = b % ny, a % nx
                elif not (0 <= b < ny and 0 <= a < nx):
                    continue
                if mask[b, a] and label[b, a] < 0:
                    label[b, a] = n
                    todo.append((b, a))
        n += 1
    return label, n


def apply(K, field):
    """K applied to a full (Ny, Nx) field given on every rank; the full result on every rank."""
    p = K.createVecRight()
    adhbem.set_local_rows(p, K, field)
    u = K.createVecLeft()
    K.mult(p, u)
    return adhbem.gather(u, K)


def assembled(K):
    """The dense matrix of K, column by column from unit vectors (small grids only)."""
    Nx, Ny = adhbem.grid_shape(K)
    n = Nx * Ny
    M = np.empty((n, n))
    e = np.zeros(n)
    for k in range(n):
        e[:] = 0.0
        e[k] = 1.0
        M[:, k] = apply(K, e.reshape(Ny, Nx)).ravel()
    return M


class FakeSurfaceTopography:
    """What adhbem uses of a SurfaceTopography 2-D topography: heights() as (nx, ny), x first."""
    dim = 2

    def __init__(self, heights_xy, sizes, periodic):
        self._h, self.physical_sizes, self.is_periodic = heights_xy, sizes, periodic
        self.nb_grid_pts = heights_xy.shape

    def heights(self):
        return self._h


def wait_for(predicate, what, p, wait=600):
    """Polls predicate() until it holds; fails if the job p (a Popen) ends first or wait seconds pass."""
    import time
    import pytest
    t0 = time.monotonic()
    while not predicate():
        if p.poll() is not None:
            pytest.fail(f"the job ended before {what}")
        if time.monotonic() - t0 > wait:
            pytest.fail(f"no {what} after {wait} s")
        time.sleep(0.05)
