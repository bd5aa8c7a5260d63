"""The Lennard-Jones 9-3 cohesive law (-adh_criterion lj93), cut at its minimum by the hard wall:
every state an equilibrium of the law (the attraction (9 dgamma/(2 z0)) ((z0/z)^4 - (z0/z)^10),
z = z0 + g, off the contact; no tension on it) and a minimum; the sphere's pull-off between
DMT's and JKR's as Tabor's parameter grows; 1 rank equal to 2 and 3; its attributes, a restart
that changes z0 refused; bad input refused."""
import math
import subprocess

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import _max, _min, say
from test_exponential import stiffness_matrix

GAMMA = 2e-3


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process or compares with one")


def law(g, z0, dgamma=GAMMA):
    """The potential's first and second derivatives in the gap: the attraction and its slope."""
    x = z0 / (z0 + g)
    return 4.5 * dgamma / z0 * (x ** 4 - x ** 10), 4.5 * dgamma / z0 ** 2 * (-4 * x ** 5 + 10 * x ** 11)


def path(n=32, z0=0.01, d=(0.0, 0.01, -0.03), steps=10, comm=None, **extra):
    opts = dict(n=n, boundary="periodic", gamma=GAMMA, criterion="lj93", lj93_distance=z0, start="adhesive",
                progress=False, path=list(d), steps=steps, stop_at_pulloff=False)
    opts.update(extra)
    with adhbem.Solver(**opts, **({"comm": comm} if comm else {})) as s:
        return s.solve_path()


def test_every_state_is_an_equilibrium_and_a_minimum():
    """On a 16^2 cell along a loading and unloading path: off the contact the pressure is the
    law's attraction; on it the gap is 0 and the pressure compressive (the law holds nothing at
    contact); the pressure is the stiffness of the displacement; the energy's Hessian on the free
    gaps (mean-free) is positive definite."""
    serial_only()
    n, z0 = 16, 0.02
    S = stiffness_matrix(n)
    peak = 1.466 * GAMMA / z0
    opts = dict(n=n, boundary="periodic", gamma=GAMMA, criterion="lj93", lj93_distance=z0, start="adhesive",
                progress=False, path=[0.0, 0.01, -0.02], steps=6, stop_at_pulloff=False, minimize_rtol=1e-11)
    with adhbem.Solver(**opts) as s:
        states = touching = 0
        for state in s.iterate_path():
            p, g, h = s.pressure_array().ravel(), s.gap_array().ravel(), s.profile_array().ravel()
            free = g > 0
            attraction, slope = law(g, z0)
            assert np.max(np.abs(p[free] + attraction[free])) < 1e-8 * peak
            assert np.all(g >= 0) and np.all(p[~free] >= -1e-8 * peak)
            u = g - h + state["d"]
            assert np.max(np.abs(S @ (u - u.mean()) - (p - p.mean()))) < 1e-8 * peak
            if free.sum() > 1:
                H = S[np.ix_(free, free)] + np.diag(slope[free])
                P = np.eye(free.sum()) - 1.0 / free.sum()
                eig = np.linalg.eigvalsh(P @ H @ P)
                assert np.sum(eig < -1e-10 * np.abs(eig).max()) == 0
            states += 1
            touching += bool((~free).any())
    assert states > 10 and touching > 3


def test_pulloff_goes_from_dmt_to_jkr():
    """The sphere (R = E* = 1, z0 = 1.3 grid spacings): the pull-off falls from near DMT's
    2 pi dgamma R (mu = 0.05) through mu = 0.1 and 0.3 to near JKR's 1.5 (mu = 2), and the cohesive
    zone is recorded. At mu = 2 the law's stiffness near the wall is far above an element's: the
    preconditioner scaled by it keeps a state under 1 000 FFT pairs (about 660; 1 900 with the
    compliance alone)."""
    serial_only()
    ratio = {}
    for mu, n, z0, d, steps in ((0.05, 64, 0.02, (0.0, 0.02, -0.04), 30), (0.1, 64, 0.02, (0.0, 0.02, -0.04), 30),
                                (0.3, 64, 0.02, (0.0, 0.02, -0.04), 30), (2.0, 128, 0.01, (0.0, 0.005, -0.02), 12)):
        gamma = (mu * z0) ** 1.5  # mu = (R dgamma^2 / (E*^2 z0^3))^(1/3)
        c = path(n, z0, d=d, steps=steps, gamma=gamma, stop_at_pulloff=True)
        ratio[mu] = -float(np.min(c["force"])) / (math.pi * gamma)
        assert np.max(c["cohesive_area"]) > 0 and c["pulled_off"][-1] == 1
        if mu == 2.0:
            assert np.mean(c["fft_pairs"][1:]) < 1000, np.mean(c["fft_pairs"][1:])
    say(f"\nlj93: pull-off / (pi dgamma R) {ratio}")
    assert 1.88 < ratio[0.05] < 2.0 and 1.5 < ratio[2.0] < 1.65
    assert ratio[0.05] > ratio[0.1] > ratio[0.3] > ratio[2.0]


@pytest.mark.mpi
@pytest.mark.ranks3
def test_same_curve_on_any_number_of_ranks():
    """COMM_WORLD against COMM_SELF under both controls and on the free boundary (force control
    there is test_exponential's: the same code, and costly with this law), each solved to
    a relative projected gradient of 1e-10: the same contact counts, forces to 1e-8 (the law's
    stiffness near the wall carries the solves' rounding into the force at 1e-8 at the default
    1e-8)."""
    mpi = PETSc.COMM_WORLD.tompi4py()
    for boundary, control, d in (("periodic", "displacement", (0.0, 0.01, -0.03)), ("periodic", "force", (0.005, -0.02)),
                                 ("free", "displacement", (0.0, 0.01, -0.03))):
        world = path(30, d=d, steps=8, control=control, boundary=boundary, minimize_rtol=1e-10)
        alone = path(30, d=d, steps=8, control=control, boundary=boundary, minimize_rtol=1e-10, comm=PETSc.COMM_SELF)
        same = mpi.allreduce(int(len(world["d"]) == len(alone["d"]) and np.array_equal(world["contact_points"], alone["contact_points"])), op=_min())
        rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / np.max(np.abs(alone["force"]))), op=_max())
        say(f"\nlj93, {boundary}, {control}, {PETSc.COMM_WORLD.getSize()} ranks vs 1: max |dF|/max|F| {rel:.1e}")
        assert same == 1 and rel < 1e-8 and np.min(alone["force"]) < 0


def test_results_attributes_and_restart_refusal(tmp_path):
    """The results file records z0 and the sphere's Tabor parameter; a restart with another z0 is
    refused naming -adh_lj93_distance, one with the same goes on."""
    serial_only()
    import h5py
    base = [EXE, "-adh_n", "32", "-adh_boundary", "periodic", "-adh_gamma", str(GAMMA), "-adh_criterion", "lj93",
            "-adh_path", "0,0.01,-0.03", "-adh_steps", "6", "-adh_start", "adhesive"]
    ck = tmp_path / "ck.h5"
    r = subprocess.run(base + ["-adh_lj93_distance", "0.01", "-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(tmp_path / "a.h5", "r") as f:
        assert f.attrs["criterion"] == "lj93"
        assert float(f.attrs["lj93_distance"]) == pytest.approx(0.01, rel=1e-14)
        mu = (GAMMA ** 2 / 0.01 ** 3) ** (1 / 3)
        assert float(f.attrs["tabor_mu"]) == pytest.approx(mu, rel=1e-12)
        assert float(f.attrs["asperity_tabor"]) == pytest.approx(mu, rel=1e-12)
    r = subprocess.run(base + ["-adh_lj93_distance", "0.02", "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and "-adh_lj93_distance" in r.stderr, r.stderr[-2000:]
    r = subprocess.run(base + ["-adh_lj93_distance", "0.01", "-adh_restart", str(ck), "-adh_output", str(tmp_path / "c.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]


def test_the_laws_numbers():
    """The peak tension and its gap that -adh_view prints, and the range dgamma/peak that the
    stickiness report takes, against the law's maximum found on a fine grid of gaps."""
    serial_only()
    import re
    z0 = 0.01
    g = np.linspace(0, 0.05, 500001)
    attraction, _ = law(g, z0)
    peak, at = attraction.max(), g[attraction.argmax()]
    out = subprocess.run([EXE, "-adh_n", "16", "-adh_boundary", "periodic", "-adh_gamma", str(GAMMA), "-adh_criterion", "lj93",
                          "-adh_lj93_distance", str(z0), "-adh_steps", "1", "-adh_view"], capture_output=True, text=True,
                         timeout=60).stdout
    m = re.search(r"largest tension (\S+) at gap (\S+)", out)
    assert m, out
    assert float(m.group(1)) == pytest.approx(peak, rel=1e-5) and float(m.group(2)) == pytest.approx(at, rel=1e-3)
    x = (np.arange(32) + 0.5) / 32
    wave = 0.01 * (1 - np.cos(2 * math.pi * np.tile(x, (4, 1))))
    s = adhbem.Solver(n=(32, 4), size=(1.0, 4 / 32), boundary="periodic", topography=wave, topography_kind="gap",
                      gamma=GAMMA, criterion="lj93", lj93_distance=z0)
    assert s.stickiness["range"] == pytest.approx(GAMMA / peak, rel=1e-8)


@pytest.mark.parametrize("args, culprit", [
    ([], "-adh_lj93_distance"),
    (["-adh_lj93_distance", "-1"], "-adh_lj93_distance"),
    (["-adh_lj93_distance", "inf"], "-adh_lj93_distance"),
    (["-adh_lj93_distance", "0.01", "-adh_attach", "reach"], "-adh_attach"),
])
def test_bad_input_refused(args, culprit):
    """One line naming the option, a non-zero exit."""
    serial_only()
    base = [EXE, "-adh_n", "16", "-adh_gamma", str(GAMMA), "-adh_criterion", "lj93", "-adh_steps", "2"]
    if "-adh_boundary" not in args:
        base += ["-adh_boundary", "periodic"]
    r = subprocess.run(base + args, capture_output=True, text=True, timeout=60)
    assert r.returncode != 0 and culprit in r.stderr, r.stderr[-2000:]
