"""Fields from files and arrays: topographies (-adh_topography, -adh_topography_kind,
Solver(topography=...)) and the work-of-adhesion field (-adh_gamma_field,
Solver(gamma_field=...)), read by src/geometry/fieldfile.c.

The reference is the built-in sphere, h = r^2/2R at the element centres ((i - Nx/2) hx,
(j - Ny/2) hy). The height map z = -r^2/2R has its maximum 0 on the centre element, so
max(z) - z is the sphere's profile to the last bit, and the curves must agree to rounding.
Files live in a temporary directory; tests marked `mpi` assert only on all-reduced values.
"""
import math
import os
import subprocess

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import FakeSurfaceTopography

N, L, R, E = 32, 1.0, 1.0, 1.0
H = L / N
# Loading past first touch and back, non-adhesive: 13 to 18 elements of contact radius.
PATH = [(6 * H) ** 2 / R, (9 * H) ** 2 / R, (6 * H) ** 2 / R]
OPTS = dict(n=N, size=L, E_star=E, gamma=0.0, start="hertz", path=PATH, steps=3)
# An adhesive unloading to pull-off, for the gamma field: JKR a_c = 6 h.
AC = 6 * H
GAMMA = AC ** 3 * 8 * E / (9 * math.pi * R ** 2)
DC = (3 * math.pi ** 2 * GAMMA ** 2 * R / (64 * E ** 2)) ** (1 / 3)
ADH_OPTS = dict(n=N, size=L, E_star=E, gamma=GAMMA, radius=R, start="hertz",
                path=[(1.3 * AC) ** 2 / R, -2.5 * DC], steps=12)


def mpi():
    return PETSc.COMM_WORLD.tompi4py()


def rank0():
    return PETSc.COMM_WORLD.getRank() == 0


def height_map(n=N):
    """z = -r^2/2R on the element centres, computed as the C code computes the sphere."""
    i = np.arange(n)
    x = (i - n // 2) * (L / n)
    X, Y = np.meshgrid(x, x)          # [j, i]: rows are y
    r = np.sqrt(X * X + Y * Y)
    return -(r * r / (2.0 * R))


def write_field(path, array, dataset="h"):
    """A .npy or HDF5 file, written by rank 0 only (the others wait)."""
    if rank0():
        if str(path).endswith(".npy"):
            np.save(path, array)
        else:
            import h5py
            with h5py.File(path, "w") as f:
                f[dataset] = array
    mpi().Barrier()
    return str(path)


@pytest.fixture
def tmp(tmp_path):
    """A temporary directory shared by the ranks (rank 0's name)."""
    return mpi().bcast(str(tmp_path), root=0)


def curve(**kw):
    opts = dict(OPTS)
    opts.update(kw)
    if "topography" in kw:
        opts.pop("radius", None)
    return adhbem.Solver(**opts).solve_path()


def same_curve(a, b):
    """Largest relative force difference; inf if the states or contact counts differ."""
    if len(a["d"]) != len(b["d"]) or not np.array_equal(a["contact_points"], b["contact_points"]):
        return math.inf
    return float(np.max(np.abs(a["force"] - b["force"])) / np.max(np.abs(b["force"])))


@pytest.fixture(scope="module")
def sphere():
    c = curve(radius=R)
    assert c["contact_points"].max() > 100          # the path makes real contact
    return c


# ---- topographies ------------------------------------------------------------------------------

@pytest.mark.parametrize("ext", ["npy", "h5"])
def test_height_map_file_is_the_sphere(tmp, sphere, ext):
    z = height_map()
    path = write_field(os.path.join(tmp, f"z.{ext}"), z)
    s = adhbem.Solver(topography=path, **OPTS)       # -adh_topography alone implies indenter file
    h = adhbem.gather(s.profile, s.compliance)
    c = s.solve_path()
    err = same_curve(c, sphere)
    print(f"\nheight map .{ext} vs sphere: max |dF|/max|F| = {err:.1e}")
    np.testing.assert_array_equal(h, z.max() - z)
    assert err < 1e-12


def test_gap_file_needs_kind_gap(tmp, sphere):
    z = height_map()
    path = write_field(os.path.join(tmp, "h.npy"), z.max() - z)
    as_gap = curve(topography=path, topography_kind="gap")
    as_height = curve(topography=path)                 # the default reads it as heights: upside down
    err = same_curve(as_gap, sphere)
    print(f"\ngap file, kind gap vs sphere: {err:.1e}; as a height map: contact points {as_height['contact_points']}")
    assert err < 1e-12
    assert same_curve(as_height, sphere) > 1e-3


def test_height_map_hdf5_dataset_and_float32(tmp, sphere):
    z = height_map()
    path = write_field(os.path.join(tmp, "z.h5"), z, dataset="topo")
    c = curve(topography=path, topography_dataset="topo")
    assert same_curve(c, sphere) < 1e-12
    # float32 is read too (and widened exactly).
    z32 = z.astype(np.float32)
    path32 = write_field(os.path.join(tmp, "z32.npy"), z32)
    s = adhbem.Solver(topography=path32, **OPTS)
    h = adhbem.gather(s.profile, s.compliance)
    np.testing.assert_array_equal(h, z32.max().astype(np.float64) - z32.astype(np.float64))


def test_height_map_array_and_vec(sphere):
    z = height_map()
    from_array = curve(topography=z)
    from_gap = curve(topography=z.max() - z, topography_kind="gap")
    s = adhbem.Solver(**OPTS)
    v = s.make_field(z)
    from_vec = curve(topography=v)
    print(f"\narray vs sphere {same_curve(from_array, sphere):.1e}, gap array {same_curve(from_gap, sphere):.1e},"
          f" Vec {same_curve(from_vec, sphere):.1e}")
    assert same_curve(from_array, sphere) < 1e-12
    assert same_curve(from_gap, sphere) < 1e-12
    assert same_curve(from_vec, sphere) < 1e-12


def test_set_topography_after_set_up(sphere):
    """A solver set up as a punch becomes the bump: the profile and the curve follow."""
    s = adhbem.Solver(indenter="punch", **OPTS)
    s.set_topography(height_map())
    c = s.solve_path()
    assert same_curve(c, sphere) < 1e-12


def test_output_attributes(tmp):
    z = height_map()
    path = write_field(os.path.join(tmp, "z.npy"), z)
    gpath = write_field(os.path.join(tmp, "g.npy"), np.full((N, N), 1e-3))
    out_file = os.path.join(tmp, "file.h5")
    out_array = os.path.join(tmp, "array.h5")
    s = adhbem.Solver(topography=path, gamma_field=gpath, **OPTS)
    s.write(out_file)
    s = adhbem.Solver(topography=z, topography_kind="gap", **OPTS)
    s.write(out_array)
    import h5py
    with h5py.File(out_file, "r") as f:
        a = dict(f.attrs)
    with h5py.File(out_array, "r") as f:
        b = dict(f.attrs)
    text = lambda v: v.decode() if isinstance(v, bytes) else str(v)  # noqa: E731
    assert text(a["indenter"]) == "file" and text(a["topography"]) == path
    assert text(a["topography_kind"]) == "height"
    assert bool(a["gamma_field"]) and text(a["gamma_field_file"]) == gpath
    assert text(b["indenter"]) == "array" and text(b["topography_kind"]) == "gap"
    assert not bool(b["gamma_field"]) and "gamma_field_file" not in b


@pytest.mark.mpi
@pytest.mark.parametrize("kind", ["height", "gap"])
def test_array_topography_is_in_the_results_file(tmp, kind):
    """A topography handed over as an array (or Vec) is saved as /topography, as given, by
    solve_path's output and by write(); read back with its kind it gives the same curve."""
    z = height_map() + 1e-4 * np.cos(7 * np.arange(N))[None, :]   # not symmetric in x
    given = z if kind == "height" else z.max() - z
    out, written = os.path.join(tmp, f"{kind}.h5"), os.path.join(tmp, f"{kind}_write.h5")
    s = adhbem.Solver(topography=given, topography_kind=kind, output=out, **OPTS)
    c = s.solve_path()
    s.write(written)
    mpi().Barrier()
    import h5py
    for name in (out, written):
        with h5py.File(name, "r") as f:
            same = np.array_equal(f["topography"][()], given) and f.attrs["topography_kind"] == kind
        assert mpi().allreduce(int(same), op=_min()) == 1, name
    again = curve(topography=out, topography_dataset="topography", topography_kind=kind)
    assert same_curve(again, c) < 1e-12


# ---- the work-of-adhesion field ------------------------------------------------------------------

@pytest.fixture(scope="module")
def jkr():
    c = adhbem.Solver(**ADH_OPTS).solve_path()
    assert c["force"].min() < 0                       # adhesive: a tensile force before pull-off
    return c


@pytest.mark.parametrize("source", ["npy", "h5", "array"])
def test_constant_gamma_field_is_the_scalar(tmp, jkr, source):
    g = np.full((N, N), GAMMA)
    field = g if source == "array" else write_field(os.path.join(tmp, f"g.{source}"), g, dataset="gamma")
    c = adhbem.Solver(gamma_field=field, **ADH_OPTS).solve_path()
    err = same_curve(c, jkr)
    print(f"\nconstant gamma field ({source}) vs scalar: {err:.1e}")
    assert err < 1e-12


def test_constant_gamma_field_is_the_scalar_with_the_papers_criterion():
    """The same with pohrt-popov, whose certified early stop reads the allowed tension point by
    point where a field gives it (and one value where dgamma is uniform)."""
    opts = dict(ADH_OPTS, criterion="pohrt-popov")
    scalar = adhbem.Solver(**opts).solve_path()
    c = adhbem.Solver(gamma_field=np.full((N, N), GAMMA), **opts).solve_path()
    assert scalar["force"].min() < 0
    err = same_curve(c, scalar)
    print(f"\npohrt-popov, constant gamma field vs scalar: {err:.1e}")
    assert err < 1e-12


def test_gamma_field_changes_the_curve(tmp, jkr):
    g = np.full((N, N), GAMMA)
    g[: N // 2] *= 3.0                                # stickier on the lower half (y < 0)
    path = write_field(os.path.join(tmp, "g.npy"), g)
    c = adhbem.Solver(gamma_field=path, **ADH_OPTS).solve_path()
    print(f"\nlargest tension: scalar {-jkr['force'].min():.4e}, half 3x {-c['force'].min():.4e}")
    assert -c["force"].min() > 1.05 * -jkr["force"].min()


def _bad_fields():
    ok = np.full((N, N), GAMMA)
    neg, nan, inf = ok.copy(), ok.copy(), ok.copy()
    neg[3, 4] = -1e-6
    nan[N - 2, 5] = np.nan                            # on the last rank's rows
    inf[0, 0] = np.inf
    return {"shape": (np.full((N, N + 1), GAMMA), "shape"), "negative": (neg, "negative"),
            "nan": (nan, "NaN or Inf"), "inf": (inf, "NaN or Inf"),
            "three_d": (ok[None], "dimension"), "int": (ok.astype(np.int64), "dtype")}


BAD = _bad_fields()
FILE_CASES = sorted(BAD) + ["missing", "dataset", "not_a_field_file"]


def bad_file(tmp, case):
    """(option value, extra options) of a broken gamma field file."""
    if case == "missing":
        return os.path.join(tmp, "nowhere.npy"), {}
    if case == "dataset":
        return write_field(os.path.join(tmp, "g.h5"), np.full((N, N), GAMMA), dataset="gamma"), {"gamma_field_dataset": "dgamma"}
    if case == "not_a_field_file":
        path = os.path.join(tmp, "g.txt")
        if rank0():
            with open(path, "w") as f:
                f.write("0.1 0.2\n")
        mpi().Barrier()
        return path, {}
    return write_field(os.path.join(tmp, f"{case}.npy"), BAD[case][0]), {}


@pytest.mark.parametrize("case", FILE_CASES)
def test_bad_gamma_file_raises(tmp, case):
    path, extra = bad_file(tmp, case)
    with pytest.raises(FileNotFoundError if case == "missing" else ValueError, match="-adh_gamma_field"):
        adhbem.Solver(gamma_field=path, **extra, **ADH_OPTS)


@pytest.mark.parametrize("case", ["shape", "negative", "nan", "inf", "three_d"])
def test_bad_gamma_array_raises(case):
    with pytest.raises(ValueError, match="gamma_field"):
        adhbem.Solver(gamma_field=BAD[case][0], **ADH_OPTS)


@pytest.mark.parametrize("case", ["shape", "nan", "inf"])
def test_bad_topography_raises(tmp, case):
    z = height_map()
    if case == "shape":
        z = z[:, :-1]
    else:
        z[N // 2, 3] = np.nan if case == "nan" else np.inf
    with pytest.raises(ValueError, match="topography"):
        adhbem.Solver(topography=z, **OPTS)
    path = write_field(os.path.join(tmp, f"z_{case}.npy"), z)
    with pytest.raises(ValueError, match="-adh_topography"):
        adhbem.Solver(topography=path, **OPTS)


def test_bad_topography_vec_raises():
    s = adhbem.Solver(**OPTS)
    v = s.make_field(height_map())
    v.getArray()[0] = np.nan
    with pytest.raises(ValueError, match="NaN or Inf"):
        s.set_topography(v)
    # The failed call left the solver as it was: still the sphere.
    assert s.solve_path()["contact_points"].max() > 100


# ---- the executable --------------------------------------------------------------------------

def run_exe(args, cwd):
    """The executable on 2 ranks, in a clean MPI environment (this process may be a singleton)."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_"))}
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
    return subprocess.run(["mpirun", "--oversubscribe", "-n", "2", EXE] + args, cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=120)


def exe_args(extra):
    return ["-adh_n", str(N), "-adh_gamma", repr(GAMMA), "-adh_path", "0.05,-0.01", "-adh_steps", "2",
            "-adh_output", "x.h5"] + extra


@pytest.mark.parametrize("case", ["negative", "shape", "nan", "missing", "dataset"])
def test_executable_refuses_bad_gamma_field(tmp, case):
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")
    path, extra = bad_file(tmp, case)
    args = ["-adh_gamma_field", path] + [a for k, v in extra.items() for a in (f"-adh_{k}", v)]
    r = run_exe(exe_args(args), tmp)
    left = sorted(f for f in os.listdir(tmp) if f.startswith("x."))
    print(f"\n{case}: exit {r.returncode}; " + " | ".join(l for l in r.stderr.splitlines() if "-adh_gamma_field:" in l)[:300])
    assert r.returncode != 0
    assert f"-adh_gamma_field: " in r.stderr and os.path.basename(path) in r.stderr
    assert left == []


def test_executable_refuses_bad_topography(tmp):
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")
    path = write_field(os.path.join(tmp, "z.npy"), height_map()[:-1])
    r = run_exe(exe_args(["-adh_topography", path]), tmp)
    assert r.returncode != 0
    assert "-adh_topography: " in r.stderr and "z.npy" in r.stderr and "shape" in r.stderr
    assert sorted(f for f in os.listdir(tmp) if f.startswith("x.")) == []


def test_executable_with_good_files(tmp):
    """The same files that fail above, when right, give a complete result."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")
    z = write_field(os.path.join(tmp, "z.h5"), height_map(), dataset="z")
    g = write_field(os.path.join(tmp, "g.npy"), np.full((N, N), GAMMA))
    r = run_exe(exe_args(["-adh_topography", z, "-adh_topography_dataset", "z", "-adh_gamma_field", g]), tmp)
    assert r.returncode == 0, r.stderr
    assert sorted(f for f in os.listdir(tmp) if f.startswith("x.")) == ["x.csv", "x.h5"]


# ---- ranks --------------------------------------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.ranks3
def test_topography_file_on_ranks_is_the_same_curve(tmp):
    """A height map and a gamma field read on all ranks give the curve of one rank."""
    z = height_map() + 1e-4 * np.cos(7 * np.arange(N))[None, :]   # not symmetric in x
    g = np.full((N, N), GAMMA)
    g[:, : N // 3] *= 2.0
    zpath = write_field(os.path.join(tmp, "z.npy"), z)
    gpath = write_field(os.path.join(tmp, "g.h5"), g, dataset="gamma")
    opts = dict(ADH_OPTS)
    opts.pop("radius")
    world = adhbem.Solver(topography=zpath, gamma_field=gpath, **opts).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, topography=zpath, gamma_field=gpath, **opts).solve_path()
    m = mpi()
    same_len = m.allreduce(int(len(world["d"]) == len(alone["d"])), op=_min())
    assert same_len == 1
    counts = m.allreduce(int(np.array_equal(world["contact_points"], alone["contact_points"])), op=_min())
    rel = m.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / np.max(np.abs(alone["force"]))), op=_max())
    touched = m.allreduce(int(alone["contact_points"].max() > 20 and alone["force"].min() < 0), op=_min())
    if rank0():
        print(f"\n{PETSc.COMM_WORLD.getSize()} ranks vs 1 with files: max |dF|/max|F| = {rel:.1e}, counts equal {bool(counts)}")
    assert touched == 1 and counts == 1
    assert rel < 1e-10


def _max():
    from mpi4py import MPI
    return MPI.MAX


def _min():
    from mpi4py import MPI
    return MPI.MIN


def test_a_path_that_never_touches_says_so(tmp_path):
    """A path that stays above the surface runs (every state empty) and says so."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_path", "-0.02,-0.01", "-adh_steps", "2",
                        "-adh_output", str(tmp_path / "x.h5")], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0
    assert "never touches the surface" in r.stdout and "first touch at d = 0" in r.stdout
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_path", "-0.02,0.01", "-adh_steps", "2"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "never touches" not in r.stdout


def surface_topography_cases():
    """The duck-typed stand-in, and the real package's Topography when it is installed."""
    yield "stand-in", FakeSurfaceTopography
    try:
        from SurfaceTopography import Topography
    except ImportError:
        return
    yield "SurfaceTopography", lambda h, sizes, periodic: Topography(h, sizes, periodic=periodic)


def test_surface_topography_object_keeps_its_axes():
    """A SurfaceTopography map (heights (nx, ny)) gives the profile of the same map as an (Ny, Nx)
    array: not transposed, with its grid, sizes and periodicity; a conflicting n is refused."""
    nx, ny, sx, sy = 24, 16, 3.0, 2.0
    x = (np.arange(nx) + 0.5) * sx / nx
    y = (np.arange(ny) + 0.5) * sy / ny
    zxy = 0.05 * np.exp(-((x[:, None] - 1.0) ** 2 + (y[None, :] - 1.2) ** 2) / 0.2)  # (nx, ny), off-centre
    ref = adhbem.Solver(n=(nx, ny), size=(sx, sy), boundary="periodic", topography=np.ascontiguousarray(zxy.T))
    want = adhbem.gather(ref.profile, ref.compliance)
    for name, make in surface_topography_cases():
        s = adhbem.Solver(topography=make(zxy, (sx, sy), True))
        got = adhbem.gather(s.profile, s.compliance)
        assert got.shape == (ny, nx) and np.array_equal(got, want), name
        assert s.compliance.getSize()[0] == nx * ny
        with pytest.raises(ValueError, match="n="):
            adhbem.Solver(n=(ny, nx), topography=make(zxy, (sx, sy), True))
