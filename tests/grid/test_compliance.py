"""The half-space compliance K (u = K p) as a MatShell on distributed FFTW (src/grid/compliance.c).

References are independent of the C code's FFT path: a dense direct sum of Love coefficients
(free), a NumPy FFT with the 2/(E*|q|) multiplier (periodic), Hertz's analytic displacement.

Tests marked `mpi` (and `ranks3`) are collective and run on any number of ranks: inputs are
built from a fixed seed on every rank, results are gathered (allgather) or reduced, so every
rank asserts on the same values and a failure never leaves one rank waiting in a collective.
"""
import json
import math
import os

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from common import ROOT, apply, assembled



def mpi(comm):
    return comm.tompi4py()


def dense_free(Nx, Ny, hx, hy, E):
    """Direct sum: K[(j,i),(l,k)] = love((i-k) hx, (j-l) hy), in the row-major order j*Nx + i."""
    di = np.arange(-(Nx - 1), Nx)
    dj = np.arange(-(Ny - 1), Ny)
    table = np.array([[adhbem.love_coefficient(a * hx, b * hy, hx, hy, E) for a in di] for b in dj])
    j, i = np.divmod(np.arange(Nx * Ny), Nx)
    return table[(j[:, None] - j[None, :]) + Ny - 1, (i[:, None] - i[None, :]) + Nx - 1]


def periodic_multiplier(Nx, Ny, Lx, Ly, E):
    """2/(E*|q|) on NumPy's full FFT grid, shape (Ny, Nx), q = 2 pi (kx/Lx, ky/Ly), q = 0 zero."""
    qx = 2 * np.pi * np.fft.fftfreq(Nx, d=1.0 / Nx) / Lx
    qy = 2 * np.pi * np.fft.fftfreq(Ny, d=1.0 / Ny) / Ly
    q = np.hypot(qx[None, :], qy[:, None])
    m = np.zeros_like(q)
    m[q > 0] = 2.0 / (E * q[q > 0])
    return m


def periodic_reference(p, Lx, Ly, E):
    Ny, Nx = p.shape
    return np.real(np.fft.ifft2(np.fft.fft2(p) * periodic_multiplier(Nx, Ny, Lx, Ly, E)))


def rel_max(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


# ---- free: dense direct sum ----------------------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.ranks3
def test_free_against_dense_direct_sum(comm):
    Nx, Ny, Lx, Ly, E = 12, 17, 1.2, 2.9, 2.5  # hx = 0.1, hy = 0.17...
    K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "free", comm=comm)
    assert adhbem.grid_shape(K) == (Nx, Ny)
    D = dense_free(Nx, Ny, Lx / Nx, Ly / Ny, E)
    M = assembled(K)
    assert rel_max(M, D) < 1e-12
    rng = np.random.default_rng(1)
    for _ in range(3):
        p = rng.standard_normal((Ny, Nx))
        assert rel_max(apply(K, p), (D @ p.ravel()).reshape(Ny, Nx)) < 1e-12


# ---- periodic: NumPy FFT reference ---------------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("Nx,Ny,Lx,Ly", [(18, 25, 1.0, 1.7), (21, 14, 3.0, 1.1), (30, 45, 2.0, 2.0)])
def test_periodic_against_numpy_fft(comm, Nx, Ny, Lx, Ly):
    E = 0.7
    K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "periodic", comm=comm)
    rng = np.random.default_rng(2)
    for _ in range(3):
        p = rng.standard_normal((Ny, Nx))
        assert rel_max(apply(K, p), periodic_reference(p, Lx, Ly, E)) < 1e-12
    # a single Fourier mode is an eigenvector: u = 2/(E*|q|) p
    x = (np.arange(Nx) + 0.5) * Lx / Nx
    y = (np.arange(Ny) + 0.5) * Ly / Ny
    kx, ky = 2, 3
    p = np.cos(2 * np.pi * (kx * x[None, :] / Lx + ky * y[:, None] / Ly))
    q = 2 * np.pi * math.hypot(kx / Lx, ky / Ly)
    assert rel_max(apply(K, p), 2.0 / (E * q) * p) < 1e-12
    # the mean (q = 0) carries no displacement
    assert np.max(np.abs(apply(K, np.ones((Ny, Nx))))) < 1e-13


@pytest.mark.mpi
def test_single_precision_on_a_set(comm):
    """MatAdhComplianceMultOnSet (a periodic compliance on a random half of the points): in double
    as R K R^T from NumPy's FFT to 1e-12; in single precision (-adh_cascade_single's loose solves)
    within 1e-6 of it, and not equal to it (the float transforms ran)."""
    from adhbem import _adhbem
    Nx, Ny, Lx, Ly, E = 40, 24, 2.0, 1.5, 0.7
    K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "periodic", comm=comm)
    rng = np.random.default_rng(5)
    p = rng.standard_normal((Ny, Nx)) * (rng.random((Ny, Nx)) < 0.5)
    x = K.createVecRight()
    adhbem.set_local_rows(x, K, p)
    reference = periodic_reference(p, Lx, Ly, E) * (p != 0)
    double = adhbem.gather(_adhbem.compliance_mult_on_set(K, x, False), K)
    single = adhbem.gather(_adhbem.compliance_mult_on_set(K, x, True), K)
    assert rel_max(double, reference) < 1e-12
    assert 1e-10 < rel_max(single, double) < 1e-6
    assert adhbem.compliance_info(K)["single_mult_count"] == 1


@pytest.mark.mpi
def test_single_precision_where_the_grid_is_not_the_transform(comm):
    """A free compliance on several ranks: its grid's rows are not its zero-padded transform's, so
    the set cannot go straight into it; single precision is refused with an error, nothing runs.
    (On one rank they are, and it runs, within 1e-6 of double.)"""
    from adhbem import _adhbem
    K = adhbem.compliance((8, 6), (1.0, 1.0), 1.0, "free", comm=comm)
    x = K.createVecRight()
    adhbem.set_local_rows(x, K, np.random.default_rng(3).standard_normal((6, 8)))
    if comm.getSize() > 1:
        with pytest.raises(ValueError):
            _adhbem.compliance_mult_on_set(K, x, True)
        assert adhbem.compliance_info(K)["single_mult_count"] == 0
    else:
        double = adhbem.gather(_adhbem.compliance_mult_on_set(K, x, False), K)
        single = adhbem.gather(_adhbem.compliance_mult_on_set(K, x, True), K)
        assert 1e-10 < rel_max(single, double) < 1e-6


@pytest.mark.mpi
@pytest.mark.ranks3
def test_tiny_grids(comm):
    """Grids so small that some ranks get no FFTW rows or no spectral columns (Nx = 1, 2;
    Ny = number of ranks): both boundaries still match their references exactly."""
    P = comm.getSize()
    Lx, Ly, E = 0.7, 1.3, 1.0
    for Nx, Ny in [(1, P), (2, P), (3, P + 2), (5, P + 1)]:
        K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "free", comm=comm)
        assert rel_max(assembled(K), dense_free(Nx, Ny, Lx / Nx, Ly / Ny, E)) < 1e-12, (Nx, Ny)
        K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "periodic", comm=comm)
        ref = np.column_stack([periodic_reference(e.reshape(Ny, Nx), Lx, Ly, E).ravel() for e in np.eye(Nx * Ny)])
        # (on a 1 x 1 grid only the mean mode exists and K = 0)
        assert np.max(np.abs(assembled(K) - ref)) <= 1e-12 * max(np.max(np.abs(ref)), 1e-3), (Nx, Ny)


@pytest.mark.mpi
@pytest.mark.parametrize("layout", ["serial", "transposed"])
def test_one_rank_plan_layouts(comm, layout):
    """On one rank the transforms are FFTW's serial plans (spectrum in natural order) or
    FFTW-MPI's transposed ones; by default the second only above 2^22 points, so both are forced
    here (-adh_fftw_layout) on odd and even sizes, free and periodic, against the references.
    Several ranks always use FFTW-MPI's: serial is refused there, naming the option, and
    transposed gives the references."""
    opts = PETSc.Options()
    opts["adh_fftw_layout"] = layout
    try:
        if comm.getSize() > 1 and layout == "serial":
            with pytest.raises(ValueError) as err:
                adhbem.compliance((6, 8), comm=comm)
            assert "-adh_fftw_layout" in str(err.value)
            return
        Lx, Ly, E = 1.3, 0.9, 1.7
        rng = np.random.default_rng(5)
        for Nx, Ny in [(7, 5), (8, 11), (12, 12)]:
            p = rng.standard_normal((Ny, Nx))
            K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "free", comm=comm)
            D = dense_free(Nx, Ny, Lx / Nx, Ly / Ny, E)
            assert rel_max(apply(K, p), (D @ p.ravel()).reshape(Ny, Nx)) < 1e-12, (layout, Nx, Ny)
            K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "periodic", comm=comm)
            assert rel_max(apply(K, p), periodic_reference(p, Lx, Ly, E)) < 1e-12, (layout, Nx, Ny)
    finally:
        opts.delValue("adh_fftw_layout")


# ---- symmetry and positivity ---------------------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.parametrize("boundary", ["free", "periodic"])
def test_symmetry(comm, boundary):
    Nx, Ny = 23, 19
    K = adhbem.compliance((Nx, Ny), (1.3, 0.8), 1.9, boundary, comm=comm)
    rng = np.random.default_rng(3)
    x, y, Kx, Ky = K.createVecRight(), K.createVecRight(), K.createVecLeft(), K.createVecLeft()
    for _ in range(3):
        adhbem.set_local_rows(x, K, rng.standard_normal((Ny, Nx)))
        adhbem.set_local_rows(y, K, rng.standard_normal((Ny, Nx)))
        K.mult(x, Kx)
        K.mult(y, Ky)
        a, b = x.dot(Ky), y.dot(Kx)  # collective: the same numbers on every rank
        assert abs(a - b) <= 1e-13 * x.norm() * Ky.norm()
    # the transpose product is the same operator
    K.multTranspose(x, Ky)
    K.mult(x, Kx)
    Ky.axpy(-1.0, Kx)
    assert Ky.norm() <= 1e-14 * Kx.norm()


@pytest.mark.mpi
def test_positivity_random(comm):
    Nx, Ny = 40, 27
    rng = np.random.default_rng(4)
    for boundary in ("free", "periodic"):
        K = adhbem.compliance((Nx, Ny), (2.0, 1.0), 3.0, boundary, comm=comm)
        x, Kx = K.createVecRight(), K.createVecLeft()
        for kind in ("noise", "smooth", "checkerboard"):
            if kind == "noise":
                f = rng.standard_normal((Ny, Nx))
            elif kind == "smooth":
                f = np.outer(np.sin(np.linspace(0, 3, Ny)), np.cos(np.linspace(0, 2, Nx)))
            else:
                f = (-1.0) ** np.add.outer(np.arange(Ny), np.arange(Nx))
            if boundary == "periodic":
                f = f - f.mean()
            adhbem.set_local_rows(x, K, f)
            K.mult(x, Kx)
            assert x.dot(Kx) > 0, (boundary, kind)


@pytest.mark.mpi
def test_spectrum_small_grid(comm):
    """The whole spectrum of the assembled operator on a small grid: free is SPD, and the
    lambda_min bound the solver relies on (Cauchy interlacing) holds; periodic is positive
    semi-definite with exactly the constants as null space."""
    Nx, Ny = 9, 7
    K = adhbem.compliance((Nx, Ny), (1.0, 1.4), 1.0, "free", comm=comm)
    M = assembled(K)
    assert np.max(np.abs(M - M.T)) < 1e-14 * np.max(np.abs(M))
    lam = np.linalg.eigvalsh(0.5 * (M + M.T))
    bound = adhbem.compliance_info(K)["lambda_min"]
    assert lam[0] > 0
    assert 0 < bound <= lam[0] * (1 + 1e-12)

    K = adhbem.compliance((Nx, Ny), (1.0, 1.4), 1.0, "periodic", comm=comm)
    M = assembled(K)
    lam, vec = np.linalg.eigh(0.5 * (M + M.T))
    assert abs(lam[0]) < 1e-13 * lam[-1]
    assert np.allclose(np.abs(vec[:, 0]), 1 / math.sqrt(Nx * Ny), rtol=1e-10)
    assert lam[1] > 1e-3 * lam[-1]



@pytest.mark.mpi
def test_row_norm_bound_small_grid(comm):
    """The row-norm bound the certified attach test relies on: no row of the assembled operator is
    longer; on a periodic cell every row has exactly that length, on a free grid the longest
    (the centre's) is within a few percent of it (the padded circulant's row holds a few more
    offsets)."""
    for Nx, Ny, size in ((9, 7, (1.0, 1.4)), (16, 16, (1.0, 1.0))):
        for boundary in ("free", "periodic"):
            K = adhbem.compliance((Nx, Ny), size, 2.0, boundary, comm=comm)
            M = assembled(K)
            rows = np.sqrt((M ** 2).sum(axis=1))
            rho = adhbem.compliance_info(K)["row_norm_bound"]
            assert rows.max() <= rho * (1 + 1e-12), (boundary, Nx, rows.max(), rho)
            if boundary == "periodic":
                assert np.allclose(rows, rho, rtol=1e-12), (Nx, rows.min(), rows.max(), rho)
            else:
                assert rows.max() > 0.9 * rho, (Nx, rows.max(), rho)

# ---- Hertz: convergence to the analytic displacement ----------------------------------------------

HERTZ = {}


@pytest.mark.mpi
def test_hertz_pressure_convergence(comm, record_property):
    """p = p0 sqrt(1 - r^2/a^2) sampled at element centres, a = L/4: the displacement inside
    r < a must approach pi p0 (2 a^2 - r^2) / (4 a E*). The error reported is the maximum over
    *all* element centres with r < a (none excluded) of |u - u_Hertz| / u_Hertz."""
    L, E, p0 = 1.0, 2.0, 1.0
    a = L / 4
    errors, centre, rms = {}, {}, {}
    for N in (64, 128, 256):
        K = adhbem.compliance(N, L, E, "free", comm=comm)
        h = L / N
        x = (np.arange(N) - N // 2) * h  # DESIGN.md section 8: apex on element (N/2, N/2)
        r2 = x[None, :] ** 2 + x[:, None] ** 2
        inside = r2 < a * a
        p = np.where(inside, p0 * np.sqrt(np.clip(1 - r2 / a**2, 0, None)), 0.0)
        u = apply(K, p)
        exact = np.pi * p0 * (2 * a * a - r2) / (4 * a * E)
        rel = np.abs(u - exact)[inside] / exact[inside]
        errors[N] = float(rel.max())
        rms[N] = float(np.sqrt(np.mean(rel**2)))
        centre[N] = float(abs(u[N // 2, N // 2] / exact[N // 2, N // 2] - 1))
    HERTZ.update(max_rel=errors, rms_rel=rms, centre_rel=centre, ranks=comm.getSize())
    orders = [math.log2(errors[n] / errors[2 * n]) for n in (64, 128)]
    print("\nHertz, a = L/4, max |u - u_H|/u_H over all centres with r < a:")
    for N in errors:
        print(f"  N = {N:4d}: max {errors[N]:.3e}   rms {rms[N]:.3e}   centre {centre[N]:.3e}")
    print(f"  observed orders (max): {orders[0]:.2f}, {orders[1]:.2f}")
    for N in errors:
        record_property(f"hertz_max_rel_{N}", errors[N])
    if comm.getRank() == 0:
        try:
            os.makedirs(os.path.join(ROOT, "results"), exist_ok=True)
            with open(os.path.join(ROOT, "results", "hertz_convergence.json"), "w") as f:
                json.dump(HERTZ, f, indent=1)
        except OSError:
            pass
    assert errors[256] < 2e-3
    assert errors[128] < 0.6 * errors[64] and errors[256] < 0.6 * errors[128]  # first order or better
    assert centre[256] < centre[128] < centre[64]


# ---- the same K p on one rank and on all ----------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("boundary", ["free", "periodic"])
def test_world_equals_self(comm, boundary):
    """K on COMM_WORLD (distributed FFTW) and on COMM_SELF (every rank the whole grid) give the
    same K p. With one rank this compares two serial operators (trivial but harmless)."""
    Nx, Ny, L, E = 37, 50, (1.1, 1.6), 1.3
    rng = np.random.default_rng(5)
    p = rng.standard_normal((Ny, Nx))
    u_world = apply(adhbem.compliance((Nx, Ny), L, E, boundary, comm=comm), p)
    u_self = apply(adhbem.compliance((Nx, Ny), L, E, boundary, comm=PETSc.COMM_SELF), p)
    diff = mpi(comm).allreduce(rel_max(u_world, u_self), op=max_op())
    assert diff < 1e-13


def max_op():
    from mpi4py import MPI
    return MPI.MAX


# ---- diagonal and a user's own KSP ---------------------------------------------------------------

@pytest.mark.mpi
def test_diagonal(comm):
    Nx, Ny, Lx, Ly, E = 20, 13, 1.0, 0.6, 4.0
    hx, hy = Lx / Nx, Ly / Ny
    K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "free", comm=comm)
    d = adhbem.gather(K.getDiagonal(), K)
    assert rel_max(d, np.full((Ny, Nx), adhbem.love_coefficient(0, 0, hx, hy, E))) < 1e-13
    K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "periodic", comm=comm)
    d = adhbem.gather(K.getDiagonal(), K)
    assert rel_max(d, np.full((Ny, Nx), periodic_multiplier(Nx, Ny, Lx, Ly, E).mean())) < 1e-13


@pytest.mark.mpi
def test_ksp_cg_jacobi(comm):
    Nx, Ny = 48, 35
    K = adhbem.compliance((Nx, Ny), (1.0, 0.75), 1.0, "free", comm=comm)
    u, p = K.createVecs()
    x = (np.arange(Nx) + 0.5) / Nx
    y = (np.arange(Ny) + 0.5) / Ny
    adhbem.set_local_rows(u, K, 1.0 + 0.3 * np.outer(np.cos(5 * y), np.sin(3 * x)))
    ksp = PETSc.KSP().create(comm=comm)
    ksp.setOperators(K)
    ksp.setType("cg")
    ksp.getPC().setType("jacobi")
    ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
    ksp.setTolerances(rtol=1e-10, atol=0.0, max_it=2000)
    ksp.solve(u, p)
    assert ksp.getConvergedReason() > 0
    r = u.duplicate()
    K.mult(p, r)
    r.aypx(-1.0, u)
    assert r.norm() <= 1.01e-10 * u.norm()
    assert adhbem.compliance_info(K)["mult_count"] >= ksp.getIterationNumber()
    ksp.destroy()


# ---- bad input ------------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs,option", [
    (dict(n=(-3, 4)), "-adh_n"),
    (dict(n=(5, 0)), "-adh_n"),
    (dict(n=4, size=-1.0), "-adh_size"),
    (dict(n=4, size=(1.0, 0.0)), "-adh_size"),
    (dict(n=4, size=float("nan")), "-adh_size"),
    (dict(n=4, E_star=0.0), "-adh_E_star"),
    (dict(n=4, E_star=-2.0), "-adh_E_star"),
    (dict(n=4, E_star=float("inf")), "-adh_E_star"),
])
def test_bad_input_names_option(kwargs, option):
    with pytest.raises(ValueError) as err:
        adhbem.compliance(comm=PETSc.COMM_SELF, **kwargs)
    assert option in str(err.value)


def test_bad_boundary():
    with pytest.raises(ValueError) as err:
        adhbem.compliance(4, boundary="clamped", comm=PETSc.COMM_SELF)
    assert "boundary" in str(err.value)


@pytest.mark.mpi
@pytest.mark.ranks3
def test_more_ranks_than_rows(comm):
    size = comm.getSize()
    if size < 2:
        pytest.skip("needs 2 or more ranks")
    message = ""
    try:
        adhbem.compliance((4, size - 1), comm=comm)
    except ValueError as e:
        message = str(e)
    raised = mpi(comm).allgather(("-adh_n" in message, bool(message)))
    assert all(r[1] for r in raised)  # every rank raised
    assert all(r[0] for r in raised)  # and the message names the option
    # and the library still works afterwards
    K = adhbem.compliance((4, size), (1.0, 0.5), 1.0, comm=comm)
    D = dense_free(4, size, 0.25, 0.5 / size, 1.0)
    assert rel_max(apply(K, np.ones((size, 4))), (D @ np.ones(4 * size)).reshape(size, 4)) < 1e-12


@pytest.mark.mpi
@pytest.mark.ranks3
def test_solver_whole_grid_equals_windows(comm):
    """A JKR unloading curve with K_CC applied on the whole grid (-adh_box 0: straight into the
    transform on one rank, through grid vectors and a scatter on several) equals the one on
    bounding-box windows: the same contact sets, forces to rounding."""
    import math
    from common import gamma_for
    n = 48
    ac = 10.0 / n
    opts = dict(n=n, size=1.0, gamma=gamma_for(ac), radius=1.0, path=[(1.3 * ac) ** 2, -0.02], steps=12)
    c_box = adhbem.Solver(comm=comm, **opts).solve_path()
    c_grid = adhbem.Solver(comm=comm, box=False, **opts).solve_path()
    assert np.array_equal(c_box["contact_points"], c_grid["contact_points"])
    assert np.max(np.abs(c_box["force"] - c_grid["force"])) <= 1e-9 * np.max(np.abs(c_box["force"]))
    assert c_box["contact_points"][0] > 0 and math.isfinite(c_box["force"].min())


def test_queries_refuse_another_matrix():
    """The operator's queries check what they are given: a Mat that is not adhbem's compliance is
    refused with one line naming the call (it was read as a compliance's context)."""
    A = PETSc.Mat().createAIJ([4, 4], nnz=1, comm=PETSc.COMM_SELF)
    A.setUp()
    A.assemble()
    with pytest.raises(ValueError, match="MatAdhComplianceGetLambdaMin needs a compliance or stiffness Mat of adhbem"):
        adhbem.compliance_info(A)
    A.destroy()
