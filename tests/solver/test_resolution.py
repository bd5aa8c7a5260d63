"""How well the grid resolves the adhesion: per state, the smallest contact patch carrying a net
tension and the share of the tension carried by patches of fewer than 314 points (a disk of
radius 10 elements), checked against the fields; at set-up, the estimate of the smallest
asperities' JKR contact radius over h; and the line at the end of a run that tells a resolved
pull-off from a mesh artefact."""
import math
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import say, _max, _min, gamma_for, label_patches

SMALL = 314  # points: a patch below this does not resolve its edge


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")


def perimeter(contact, periodic, h=1.0):
    """pi/4 times the contact's element edges facing a point off it (wrapping on a periodic cell)."""
    c = contact.astype(bool)
    if periodic:
        edges = np.count_nonzero(c != np.roll(c, 1, axis=0)) + np.count_nonzero(c != np.roll(c, 1, axis=1))
    else:
        edges = np.count_nonzero(c[1:] != c[:-1]) + np.count_nonzero(c[:, 1:] != c[:, :-1])
    return math.pi / 4 * edges * h


def expected(p, contact, periodic):
    """(patches, smallest patch with net tension, share of tension in patches < SMALL points)."""
    label, n = label_patches(contact.astype(bool), periodic)
    sizes = np.bincount(label[label >= 0], minlength=n)
    force = np.bincount(label[label >= 0], weights=p[label >= 0], minlength=n)
    tension = np.bincount(label[label >= 0], weights=np.minimum(p[label >= 0], 0), minlength=n)
    tensile = sizes[force < 0]
    share = tension[sizes < SMALL].sum() / tension.sum() if tension.sum() < 0 else 0.0
    return n, (tensile.min() if len(tensile) else 0), share


def bumps(N):
    """A free-boundary gap profile of paraboloidal bumps of several radii: patches of many sizes."""
    x = np.arange(N) - N // 2
    X, Y = np.meshgrid(x, x)
    h = np.full((N, N), np.inf)
    for cx, cy, R in ((-0.42, -0.42, 600.0), (0.36, -0.31, 150.0), (-0.31, 0.4, 60.0), (0.31, 0.31, 25.0), (0, 0, 8.0)):
        h = np.minimum(h, ((X - cx * N) ** 2 + (Y - cy * N) ** 2) / (2 * R))
    return np.minimum(h, 2.0)


@pytest.mark.parametrize("boundary", ["free", "periodic"])
def test_statistics_against_the_fields(tmp_path, boundary):
    """Every state's patches, smallest tensile patch, small-patch share and perimeter equal a flood
    fill and an edge count of the written contact and pressure fields (periodic: patches wrap
    across the seam)."""
    serial_only()
    N = 96
    h = bumps(N)
    if boundary == "periodic":
        h = np.roll(h, (N // 2 - 3, N // 2 - 5), axis=(0, 1))  # bumps across the seam
    np.save(tmp_path / "h.npy", h)
    out = tmp_path / "r.h5"
    r = subprocess.run([EXE, "-adh_n", str(N), "-adh_size", str(N), "-adh_boundary", boundary,
                        "-adh_topography", str(tmp_path / "h.npy"), "-adh_topography_kind", "gap",
                        "-adh_gamma", "0.02", "-adh_start", "adhesive", "-adh_path", "0,0.8,-0.5", "-adh_steps", "6",
                        "-adh_fields", "pressure,contact", "-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    checked = 0
    with h5py.File(out, "r") as f:
        c = f["curve"]
        for frame, row in enumerate(f["fields/state"][()].astype(int)):
            p, m = f["fields/pressure"][frame], f["fields/contact"][frame]
            n, smallest, share = expected(p, m, boundary == "periodic")
            assert c["patches"][row] == n
            assert c["smallest_tensile_patch"][row] == smallest
            assert abs(c["small_patch_tension"][row] - share) < 1e-12
            assert c["contact_perimeter"][row] == pytest.approx(perimeter(m, boundary == "periodic"), rel=1e-14)
            assert c["cohesive_perimeter"][row] == c["contact_perimeter"][row]  # no zone
            checked += smallest > 0 and 0 < share < 1
        say(f"\n{boundary}: patches {c['patches'][()].astype(int).tolist()}, smallest tensile "
            f"{c['smallest_tensile_patch'][()].astype(int).tolist()}, small-patch share {np.round(c['small_patch_tension'][()], 3).tolist()}")
    assert checked >= 2  # states with small and large tensile patches at once


def run(tmp_path, args):
    out = tmp_path / "r.h5"
    r = subprocess.run([EXE, *args, "-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    lines = [l for l in r.stdout.splitlines() if l.startswith("adhbem: resolution:")]
    with h5py.File(out, "r") as f:
        attrs = dict(f.attrs)
    return lines, attrs


@pytest.mark.parametrize("boundary", ["free", "periodic"])
def test_resolved_sphere(tmp_path, boundary):
    """The JKR sphere at a_c/h = 25: the estimate is a_c/h itself (on a periodic cell too, where the
    profile's kink at the cell's edge must not count as an asperity), no tension in small patches,
    and the run says the grid resolves the adhesion."""
    serial_only()
    N, ratio = 128, 25.0
    gamma = gamma_for(ratio / N)
    lines, attrs = run(tmp_path, ["-adh_n", str(N), "-adh_size", "1", "-adh_gamma", repr(gamma), "-adh_boundary", boundary,
                                  "-adh_path", f"{(1.3 * ratio / N) ** 2!r},-0.03", "-adh_steps", "20"])
    say("\n" + "\n".join(lines))
    assert abs(attrs["asperity_contact_radius"] - ratio) < 1e-9 * ratio
    assert attrs["pull_off_small_patch_tension"] == 0.0 and attrs["pull_off_smallest_tensile_patch"] > SMALL
    assert attrs["adhesion_resolved"] == 1
    assert len(lines) == 2 and "about 25 grid spacings" in lines[0] and lines[1].endswith("the grid resolves the adhesion")


def test_unresolved_rough_cell(tmp_path):
    """A rough cell cut off at 4 spacings with dgamma = 0.004 E* h: asperity contacts of about one
    element at pull-off; the run says the pull-off depends on the grid (whatever the patches' size:
    they are clusters of unresolved asperity contacts)."""
    serial_only()
    lines, attrs = run(tmp_path, ["-adh_n", "64", "-adh_size", "64", "-adh_boundary", "periodic", "-adh_indenter", "rough",
                                  "-adh_rolloff_wavelength", "32", "-adh_gamma", "0.004", "-adh_start", "adhesive",
                                  "-adh_path", "0,0.5,-0.5", "-adh_steps", "6"])
    say("\n" + "\n".join(lines))
    assert attrs["asperity_contact_radius"] < 3 and attrs["pull_off_small_patch_tension"] > 0
    assert attrs["adhesion_resolved"] == 0
    assert len(lines) == 2 and "under 10: the pull-off force depends on the grid" in lines[0]
    assert "the pull-off force depends on the grid" in lines[1]


def test_asperity_radius_estimate_of_a_wave(tmp_path):
    """h = A cos(kx) cos(ky): the rms of its Laplacian is k^2 A, so the estimate's summit radius is
    1 / (sqrt(8 / (3 pi)) k^2 A) and a_c/h follows from JKR."""
    serial_only()
    N, A, gamma = 64, 0.5, 0.01
    k = 2 * math.pi * 4 / N
    x = np.arange(N)
    X, Y = np.meshgrid(x, x)
    np.save(tmp_path / "w.npy", A * np.cos(k * X) * np.cos(k * Y))
    _, attrs = run(tmp_path, ["-adh_n", str(N), "-adh_size", str(N), "-adh_boundary", "periodic",
                              "-adh_topography", str(tmp_path / "w.npy"), "-adh_gamma", repr(gamma),
                              "-adh_path", "0,0.1", "-adh_steps", "2"])
    R = 1 / (math.sqrt(8 / (3 * math.pi)) * k ** 2 * A)
    assert abs(attrs["asperity_contact_radius"] / (9 * math.pi * gamma * R ** 2 / 8) ** (1 / 3) - 1) < 1e-10


def test_asperity_estimate_with_a_gamma_field(tmp_path):
    """A dgamma field given from Python after set-up: the estimate takes its weakest adhesion (the
    smallest a_c), as a scalar dgamma of that value gives."""
    serial_only()
    opts = dict(n=64, size=64.0, boundary="periodic", indenter="rough", rolloff_wavelength=32.0, seed=3,
                start="adhesive", path=[0.0, 0.4, -0.4], steps=3)
    field = np.where(np.arange(64)[None, :] < 32, 0.004, 0.002) * np.ones((64, 1))
    radii = []
    for k, extra in enumerate((dict(gamma_field=field), dict(gamma=0.002))):
        out = tmp_path / f"r{k}.h5"
        adhbem.Solver(**opts, **extra, output=str(out)).solve_path()
        with h5py.File(out, "r") as f:
            radii.append(float(f.attrs["asperity_contact_radius"]))
    assert radii[0] == radii[1] and 0 < radii[0] < 3


def test_band_around_a_strip_is_resolved():
    """A line contact on a strip 4 rows wide (a wave along x) has few points per patch but a long
    edge: it counts as resolved, as on a cell 34 rows wide."""
    serial_only()
    N, D, gamma = 128, 0.01, 4.44e-5
    x = (np.arange(N) + 0.5) / N
    shares = []
    for ny in (4, 34):
        h = D * (1 - np.cos(2 * math.pi * np.tile(x, (ny, 1))))
        c = adhbem.Solver(n=(N, ny), size=(1.0, ny / N), gamma=gamma, boundary="periodic", topography=h,
                          topography_kind="gap", start="hertz", path=[0.5 * D, -0.5 * D], steps=20).solve_path()
        assert c["force"].min() < 0
        shares.append(c["small_patch_tension"])
    say(f"\nwave on 128 x 4 and 128 x 34: small-patch shares {shares[0].max():.3f}, {shares[1].max():.3f}")
    assert np.all(shares[0] == 0) and np.all(shares[1] == 0)


@pytest.mark.mpi
@pytest.mark.ranks3
def test_statistics_on_any_number_of_ranks():
    """Patches that cross rank boundaries and the periodic seam: the statistics of every state on
    all ranks equal those on one."""
    N = 48
    h = bumps(N)
    h = np.roll(h, (N // 2 - 1, 3), axis=(0, 1))
    opts = dict(n=N, size=float(N), boundary="periodic", topography=h, topography_kind="gap", gamma=0.02,
                start="adhesive", path=[0.0, 0.4, -0.5], steps=6)
    world = adhbem.Solver(**opts).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, **opts).solve_path()
    mpi = PETSc.COMM_WORLD.tompi4py()
    same = all(np.array_equal(world[k], alone[k]) for k in ("patches", "smallest_tensile_patch", "contact_perimeter",
                                                           "cohesive_perimeter"))
    diff = float(np.max(np.abs(world["small_patch_tension"] - alone["small_patch_tension"])))
    assert mpi.allreduce(int(same), op=_min()) == 1
    assert mpi.allreduce(diff, op=_max()) < 1e-12
    assert alone["smallest_tensile_patch"].max() > 0 and alone["contact_perimeter"].max() > 0


def test_perimeter_of_a_disk():
    """The JKR sphere's contact disk: the perimeter is 2 pi a to within a spacing in the radius,
    where a spans 20 to 40 elements (pi/4 times the staircase is right on average over the edge's
    directions; a digital disk's staircase is 4 times the rows and columns it spans)."""
    N = 128
    s = adhbem.Solver(n=N, size=1.0, gamma=gamma_for(25.0 / N), path=[0.05, 0.0], steps=4)
    c = s.solve_path()
    for area, length in zip(c["area"][1:], c["contact_perimeter"][1:]):
        a = math.sqrt(area / math.pi)
        say(f"\ndisk a = {a * N:.1f} spacings: perimeter / (2 pi a) = {length / (2 * math.pi * a):.4f}")
        assert a * N > 20 and length == pytest.approx(2 * math.pi * a, abs=2 * math.pi / N)
