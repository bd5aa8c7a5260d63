"""The random rough surface (src/geometry/surface.c, adhbem.rough_surface): the realised statistics are
the requested ones exactly, the power spectrum is the self-affine one with its roll-off and
cut-off, the surface depends on the seed alone (bit for bit on any number of ranks), and bad
parameters raise errors that name the option.

Every statistic is recomputed here from the gathered heights with NumPy, independently of the
library's own report. Tests marked `mpi` are collective and assert only on values every rank
has, so a failure never leaves a rank waiting in a collective.
"""
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from common import _min, rank0, say  # noqa: E402


def surface(n, comm=PETSc.COMM_SELF, **kw):
    """(heights as an (Ny, Nx) array, stats) of a rough surface."""
    z, stats = adhbem.rough_surface(n, comm=comm, **kw)
    a = adhbem.gather(z, z)
    z.destroy()
    return a, stats


def wavenumbers(shape, size):
    """|q| = 2 pi |(kx/Lx, ky/Ly)| for each entry of np.fft.fft2 of an (Ny, Nx) array."""
    Ny, Nx = shape
    Lx, Ly = size
    fx = np.fft.fftfreq(Nx, Lx / Nx)
    fy = np.fft.fftfreq(Ny, Ly / Ny)
    return 2 * np.pi * np.sqrt(fx[None, :] ** 2 + fy[:, None] ** 2)


def rms_height(a):
    return np.sqrt(np.mean(a ** 2))


def rms_slope(a, size):
    """sqrt(mean |grad z|^2) by Parseval: sqrt(sum q^2 |z_q|^2), z_q = fft2(z) / N."""
    Z = np.fft.fft2(a) / a.size
    return np.sqrt(np.sum(wavenumbers(a.shape, size) ** 2 * np.abs(Z) ** 2))


def rel(a, b):
    return abs(a - b) / abs(b)


# ---- realised statistics ---------------------------------------------------------------------

@pytest.mark.parametrize("n,size", [(64, 1.0), ((45, 32), (1.0, 0.6)), ((33, 27), (0.5, 0.7))])
def test_rms_height_is_exact(n, size):
    a, st = surface(n, size=size, rms_height=0.05, seed=3)
    L = size if isinstance(size, tuple) else (size, size)
    say(f"\nrms height: requested 0.05, numpy {rms_height(a):.17g}, reported {st['realised_rms_height']:.17g},"
        f" mean {np.mean(a):.2e}")
    assert st["requested"] == "rms_height" and st["requested_value"] == 0.05
    assert rel(rms_height(a), 0.05) < 1e-12
    assert rel(st["realised_rms_height"], 0.05) < 1e-12
    assert rel(st["realised_rms_slope"], rms_slope(a, L)) < 1e-12
    assert abs(np.mean(a)) < 1e-14 * 0.05
    assert abs(st["realised_mean"] - np.mean(a)) < 1e-15 * 0.05
    assert st["min_height"] == a.min() and st["max_height"] == a.max()


@pytest.mark.parametrize("n,size,slope", [(64, 1.0, None), ((45, 32), (1.0, 0.6), 0.3), ((33, 27), (0.5, 0.7), 0.02)])
def test_rms_slope_is_exact(n, size, slope):
    a, st = surface(n, size=size, rms_slope=slope, hurst=0.6, seed=11)
    L = size if isinstance(size, tuple) else (size, size)
    want = 0.1 if slope is None else slope  # the default
    got = rms_slope(a, L)
    say(f"\nrms slope: requested {want}, numpy {got:.17g}, reported {st['realised_rms_slope']:.17g}")
    assert st["requested"] == "rms_slope" and st["requested_value"] == want
    assert rel(got, want) < 1e-12
    assert rel(st["realised_rms_slope"], want) < 1e-12
    assert rel(st["realised_rms_height"], rms_height(a)) < 1e-12
    assert abs(np.mean(a)) < 1e-14 * rms_height(a)


def test_defaults_resolve_on_the_grid():
    _, st = surface((40, 20), size=(2.0, 0.5))
    hx, hy = 2.0 / 40, 0.5 / 20
    assert st["rolloff_wavelength"] == 2.0               # the cell size max(Lx, Ly)
    assert st["cutoff_wavelength"] == 4 * max(hx, hy)    # 4 grid spacings
    assert st["hurst"] == 0.8 and st["seed"] == 1
    # the range ends are allowed: cut-off at Nyquist, roll-off and cut-off at the cell size
    surface(32, cutoff_wavelength=2 / 32)
    surface(32, cutoff_wavelength=1.0, rolloff_wavelength=1.0)


# ---- the power spectrum ----------------------------------------------------------------------

@pytest.mark.parametrize("H", [0.8, 0.5])
def test_power_spectrum(H):
    """Radially averaged |z_q|^2 over four seeds on 256^2: log-log slope -2(1+H) between the
    roll-off (wavelength L/8) and the cut-off (4 spacings, wavelength L/64), flat below the
    roll-off, and zero above the cut-off to roundoff."""
    N, kr, ks = 256, 8, 64
    P = 0
    for seed in (1, 2, 3, 4):
        a, st = surface(N, hurst=H, rolloff_wavelength=1.0 / kr, seed=seed)
        P = P + np.abs(np.fft.fft2(a)) ** 2
    P = P / 4
    K = wavenumbers((N, N), (1.0, 1.0)) / (2 * np.pi)    # |k| in units of 1/L
    assert st["cutoff_wavelength"] == 1.0 / ks

    shells = np.arange(kr + 1, ks - 1)
    kmean = np.array([K[(K >= k) & (K < k + 1)].mean() for k in shells])
    pmean = np.array([P[(K >= k) & (K < k + 1)].mean() for k in shells])
    fit = np.polyfit(np.log(kmean), np.log(pmean), 1)[0]

    low = P[(K > 0) & (K < kr)]
    ref = (P * (K / kr) ** (2 * (1 + H)))[(K >= kr) & (K < 1.25 * kr)]
    flat_ratio = low.mean() / ref.mean()                 # 1 if C(q) = C(q_r) below q_r
    lshells = np.arange(1, kr)
    flat_fit = np.polyfit(np.log([K[(K >= k) & (K < k + 1)].mean() for k in lshells]),
                          np.log([P[(K >= k) & (K < k + 1)].mean() for k in lshells]), 1)[0]
    above = P[K > ks * (1 + 1e-9)].max() / P.max()
    say(f"\nH = {H}: fitted slope {fit:.4f} (expected {-2 * (1 + H):.2f}, {fit / (-2 * (1 + H)) - 1:+.2%}),"
        f" below roll-off: level ratio {flat_ratio:.3f}, slope {flat_fit:+.3f}; above cut-off max {above:.1e} of peak")
    assert abs(fit / (-2 * (1 + H)) - 1) < 0.03
    assert abs(flat_ratio - 1) < 0.25
    assert abs(flat_fit) < 0.5
    assert above < 1e-24
    assert P[0, 0] / P.max() < 1e-24                      # no mean


# ---- the seed and determinism ----------------------------------------------------------------

def test_same_seed_same_surface_other_seed_other_surface():
    a, _ = surface(48, seed=7)
    b, _ = surface(48, seed=7)
    c, _ = surface(48, seed=8)
    assert np.array_equal(a, b)
    assert not np.allclose(a, c)
    assert abs(np.corrcoef(a.ravel(), c.ravel())[0, 1]) < 0.3


def test_coefficients_depend_on_the_wavevector_only():
    """The same cell, cut-off and rms height on a grid twice as fine draws the same modes, so
    the coarse surface is the fine one at every other point (to the transform's rounding)."""
    kw = dict(size=1.0, cutoff_wavelength=1.0 / 8, rolloff_wavelength=0.5, rms_height=1.0, seed=5)
    coarse, _ = surface(32, **kw)
    fine, _ = surface(64, **kw)
    assert np.max(np.abs(fine[::2, ::2] - coarse)) < 1e-13


def test_fftw_wisdom_does_not_change_the_surface():
    """Measured plans of the same sizes (the periodic compliance) leave wisdom behind; the
    surface must not use it."""
    a, _ = surface((48, 36), seed=2)
    K = adhbem.compliance((48, 36), boundary="periodic", comm=PETSc.COMM_SELF)
    K2 = adhbem.compliance((48, 36), boundary="free", comm=PETSc.COMM_SELF)
    b, _ = surface((48, 36), seed=2)
    K.destroy()
    K2.destroy()
    assert np.array_equal(a, b)


@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("n,size", [(64, 1.0), ((45, 33), (1.0, 0.75)), ((30, 47), (0.6, 1.0)), ((17, 7), 1.0)])
def test_ranks_give_the_same_surface_bit_for_bit(n, size):
    """COMM_WORLD (all ranks of the run) vs COMM_SELF (one rank): identical bits, identical
    statistics; on square, non-square and odd grids."""
    mpi = PETSc.COMM_WORLD.tompi4py()
    world, sw = surface(n, comm=PETSc.COMM_WORLD, size=size, seed=9, hurst=0.7)
    alone, sa = surface(n, comm=PETSc.COMM_SELF, size=size, seed=9, hurst=0.7)
    same = mpi.allreduce(int(np.array_equal(world, alone)), op=_min())
    stats = mpi.allreduce(int(sw == sa), op=_min())
    # every rank gathered the same field
    everywhere = mpi.allreduce(int(np.array_equal(world, mpi.bcast(world, root=0))), op=_min())
    say(f"\n{PETSc.COMM_WORLD.getSize()} ranks vs 1 on {n}: bit-identical {bool(same)},"
        f" statistics identical {bool(stats)}, max |diff| {np.max(np.abs(world - alone)):.1e}")
    assert same == 1 and stats == 1 and everywhere == 1


# ---- bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs,option", [
    (dict(hurst=0.0), "-adh_hurst"),
    (dict(hurst=1.5), "-adh_hurst"),
    (dict(hurst=-0.2), "-adh_hurst"),
    (dict(rms_height=0.0), "-adh_rms_height"),
    (dict(rms_height=-1.0), "-adh_rms_height"),
    (dict(rms_slope=0.0), "-adh_rms_slope"),
    (dict(rms_slope=-2.0), "-adh_rms_slope"),           # PETSC_DEFAULT's value, given explicitly
    (dict(rms_height=0.1, rms_slope=0.1), "-adh_rms_slope"),
    (dict(cutoff_wavelength=1.9 / 32), "-adh_cutoff_wavelength"),
    (dict(cutoff_wavelength=1.5), "-adh_cutoff_wavelength"),
    (dict(rolloff_wavelength=1.5), "-adh_rolloff_wavelength"),
    (dict(rolloff_wavelength=0.05, cutoff_wavelength=0.1), "-adh_rolloff_wavelength"),
])
def test_bad_input_names_the_option(kwargs, option):
    with pytest.raises(ValueError) as err:
        surface(32, **kwargs)
    say(f"\n{kwargs}: {str(err.value).splitlines()[-1]}")
    assert option in str(err.value)
    # the range is in the message where there is one
    if "wavelength" in option:
        assert "[" in str(err.value) and "got" in str(err.value)


def test_both_rms_message():
    with pytest.raises(ValueError) as err:
        surface(16, rms_height=0.1, rms_slope=0.1)
    assert "-adh_rms_height" in str(err.value) and "-adh_rms_slope" in str(err.value)


def test_options_do_not_leak_between_calls():
    """The binding's options live under a prefix of their own and are removed afterwards: a
    bad call does not poison the next one."""
    with pytest.raises(ValueError):
        surface(16, hurst=2.0)
    a, st = surface(16)
    assert st["hurst"] == 0.8 and np.isfinite(a).all()


@pytest.mark.mpi
@pytest.mark.ranks3
def test_bad_input_fails_on_every_rank():
    mpi = PETSc.COMM_WORLD.tompi4py()
    message = ""
    try:
        surface(24, comm=PETSc.COMM_WORLD, cutoff_wavelength=0.01)
    except ValueError as e:
        message = str(e)
    raised = mpi.allgather(("-adh_cutoff_wavelength" in message, bool(message)))
    assert all(r[1] for r in raised)
    assert all(r[0] for r in raised)
    a, _ = surface(24, comm=PETSc.COMM_WORLD)        # and it works afterwards
    assert mpi.allreduce(int(np.isfinite(a).all()), op=_min()) == 1
