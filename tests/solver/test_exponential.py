"""The exponential cohesive law (-adh_criterion exponential), whose steps minimise the total
energy: every state an equilibrium of the law (the attraction (dgamma/rho) exp(-g/rho) off the
contact, at most dgamma/rho of tension on it) and a minimum (the Hessian on the free gaps positive
definite, assembled densely on a small cell); without adhesion the contact solver's states; the
DMT limit of a long range; force control pulling off where displacement control passes the largest
tension; 1 rank equal to 2 and 3; a restart that changes the range refused; bad input refused."""
import math
import re
import subprocess

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import _max, _min, say

GAMMA = 2e-3


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process or compares with one")


def solver(n=32, rho=0.01, comm=None, **extra):
    opts = dict(n=n, boundary="periodic", gamma=GAMMA, criterion="exponential", exponential_range=rho,
                start="adhesive", progress=False)
    opts.update(extra)
    return adhbem.Solver(**opts, **({"comm": comm} if comm else {}))


def path(n=32, rho=0.01, d=(0.0, 0.01, -0.03), steps=10, **extra):
    with solver(n, rho, path=list(d), steps=steps, stop_at_pulloff=False, **extra) as s:
        return s.solve_path()


def stiffness_matrix(n, L=1.0, E=1.0):
    """The periodic stiffness E*|q|/2 as a dense matrix on the mean-free vectors (mean mode 0)."""
    q = 2 * math.pi * np.fft.fftfreq(n, d=L / n)
    Q = np.sqrt(q[None, :] ** 2 + q[:, None] ** 2)
    S = np.empty((n * n, n * n))
    for k in range(n * n):
        e = np.zeros(n * n)
        e[k] = 1
        S[:, k] = np.real(np.fft.ifft2(E * Q / 2 * np.fft.fft2(e.reshape(n, n)))).ravel()
    return S


def test_every_state_is_an_equilibrium_and_a_minimum():
    """On a 16^2 cell along a loading and unloading path: off the contact the pressure is the
    law's attraction; on it the gap is 0 and the tension at most dgamma/rho; the pressure is the
    stiffness of the displacement (to the mean); and the energy's Hessian on the free gaps
    (mean-free, as the mean gap is held) is positive definite: a minimum, not a saddle. The mean
    gap is mean(h) - d in every state (each starts with the last contact held at the wall, the
    rest shifted to keep it)."""
    serial_only()
    n, rho = 16, 0.02
    S = stiffness_matrix(n)
    peak = GAMMA / rho
    with solver(n, rho, path=[0.0, 0.01, -0.02], steps=6, stop_at_pulloff=False, minimize_rtol=1e-11) as s:
        states = 0
        for state in s.iterate_path():
            p, g, h = s.pressure_array().ravel(), s.gap_array().ravel(), s.profile_array().ravel()
            free = g > 0
            attraction = peak * np.exp(-g / rho)
            assert np.max(np.abs(p[free] + attraction[free])) < 1e-8 * peak
            assert np.all(g >= 0) and np.all(p[~free] >= -peak * (1 + 1e-8))
            u = g - h + state["d"]
            assert np.max(np.abs(S @ (u - u.mean()) - (p - p.mean()))) < 1e-8 * peak
            assert abs(g.mean() - (h.mean() - state["d"])) < 1e-12 * np.abs(h).max()  # the mean gap d holds, from the held start on
            if free.sum() > 1:
                H = S[np.ix_(free, free)] - np.diag(GAMMA / rho ** 2 * np.exp(-g[free] / rho))
                P = np.eye(free.sum()) - 1.0 / free.sum()  # the mean gap is held
                eig = np.linalg.eigvalsh(P @ H @ P)
                assert np.sum(eig < -1e-10 * np.abs(eig).max()) == 0
            states += 1
    assert states > 10


def test_free_boundary_states_are_the_compliances_equilibria():
    """On the free boundary the minimisation runs on the zero-padded grid, the padding's
    displacements free: every state's gap is h - d + K p with the free compliance K (the padding
    carries no pressure), off the contact the pressure is the law's attraction, on it the gap is 0."""
    serial_only()
    n, rho = 24, 0.02
    peak = GAMMA / rho
    with solver(n, rho, boundary="free", path=[0.0, 0.01, -0.03], steps=6, stop_at_pulloff=False, minimize_rtol=1e-11) as s:
        states = 0
        for state in s.iterate_path():
            K, x = s.compliance, s.pressure.duplicate()
            K.mult(s.pressure, x)
            p, g, h = s.pressure_array(), s.gap_array(), s.profile_array()
            u = x.getArray().reshape(n, n)
            assert np.max(np.abs(g - (h - state["d"] + u))) < 1e-9 * np.max(np.abs(u))
            free = g > 0
            assert np.max(np.abs(p[free] + peak * np.exp(-g[free] / rho))) < 1e-8 * peak
            assert np.all(g >= 0) and np.all(p[~free] >= -peak * (1 + 1e-8))
            states += 1
    assert states > 10


def test_without_adhesion_the_contact_solvers_states():
    """With dgamma = 0 the minimisation is plain contact: the same states as the set solver of the
    zero-range criteria (forces to 1e-8, the same contact points)."""
    serial_only()
    for boundary in ("periodic", "free"):
        kw = dict(n=48, boundary=boundary, gamma=0.0, path=[0.002, 0.02, 0.001], steps=9, progress=False)
        with adhbem.Solver(criterion="exponential", exponential_range=0.01, **kw) as s:
            a = s.solve_path()
        with adhbem.Solver(criterion="pohrt-popov", **kw) as s:
            b = s.solve_path()
        assert np.array_equal(a["contact_points"], b["contact_points"])
        assert np.max(np.abs(a["force"] - b["force"])) < 1e-8 * np.max(np.abs(b["force"]))


def test_long_range_reaches_dmt():
    """As Tabor's mu shrinks (a long range against the deformation: 0.1 and 0.046, the work of
    adhesion lowered at a range of 0.01, which the grid resolves), the pull-off force rises to
    DMT's 2 pi dgamma R, its shortfall about proportional to mu, the same on a grid twice as fine."""
    serial_only()
    ratio = {}
    for gamma, n in ((3.2e-5, 64), (3.2e-5, 128), (1e-5, 64)):
        with solver(n, 0.01, gamma=gamma, path=[0.0, 0.002, -0.06], steps=40) as s:
            c = s.solve_path()
        ratio[gamma, n] = -float(np.min(c["force"])) / (2 * math.pi * gamma)
    say(f"\nexponential, pull-off over DMT's: {ratio}")
    assert abs(ratio[3.2e-5, 128] - ratio[3.2e-5, 64]) < 0.005
    assert 0.9 < ratio[3.2e-5, 64] < ratio[1e-5, 64] < 1.0
    assert 1 - ratio[1e-5, 64] < 0.55 * (1 - ratio[3.2e-5, 64])


def test_force_control_pulls_off_at_the_largest_tension():
    """Under force control the contact comes off at the largest tension (bisected to
    -adh_pulloff_rtol) that displacement control passes through, and the last state is marked
    pulled off."""
    serial_only()
    disp = -float(np.min(path(48, d=(0.0, 0.01, -0.03), steps=40)["force"]))
    force = path(48, d=(0.005, -0.02), steps=20, control="force")
    F = -float(np.min(force["force"]))
    say(f"\nexponential, force control: pull-off {F:.6g} against {disp:.6g} under displacement control")
    assert force["pulled_off"][-1] == 1
    assert abs(F / disp - 1) < 2e-3


def test_force_control_on_the_free_boundary():
    """On the free boundary (no mean mode to carry a force) each force-controlled state is the
    displacement-controlled branch's at its d (the force of a fine displacement path interpolated
    there, to 1e-3 of the largest tension), and the contact comes off at the branch's largest
    tension (to 2e-3, the control's pull-off tolerance)."""
    serial_only()
    disp = path(48, d=(0.0, 0.045, -0.03), steps=150, boundary="free")  # beyond the force path's deepest d
    force = path(48, d=(0.005, -0.02), steps=20, control="force", boundary="free")
    largest = -float(np.min(disp["force"]))
    F = -float(np.min(force["force"]))
    say(f"\nexponential, free boundary, force control: pull-off {F:.6g} against {largest:.6g} under displacement control")
    assert force["pulled_off"][-1] == 1 and abs(F / largest - 1) < 2e-3
    carried = force["pulled_off"] == 0  # every other state carries its step's force
    targets = np.linspace(0.005, -0.02, 21)[: len(force["d"])]
    assert np.max(np.abs(force["force"][carried] - targets[carried])) < 1e-6 * largest
    back = slice(int(np.argmax(disp["d"])), None)  # the unloading leg, d falling
    dd, fd = disp["d"][back][::-1], disp["force"][back][::-1]
    unload = np.arange(len(force["d"])) > int(np.argmax(force["force"]))
    for d, f in zip(force["d"][unload][:-1], force["force"][unload][:-1]):
        assert abs(np.interp(d, dd, fd) - f) < 1e-3 * largest, (d, f)


def test_force_control_through_a_jump_into_full_contact_on_the_free_boundary():
    """A sticky rough map under force control on the free boundary jumps into full contact between
    its first two states; every state carries its force (a search that skipped the minimisation
    of the step's first state, a first touch at p = 0, took the jump's edge for the state: -24
    where 5 was asked)."""
    serial_only()
    targets = np.linspace(10.0, -10.0, 5)
    with adhbem.Solver(n=64, size=64.0, boundary="free", indenter="rough", rms_slope=0.1, rolloff_wavelength=32.0,
                       cutoff_wavelength=8.0, gamma=0.3, criterion="exponential", exponential_range=0.3, control="force",
                       path=[10.0, -10.0], steps=4, progress=False) as s:
        c = s.solve_path()
    say(f"\nexponential, sticky map, force control: forces {np.round(c['force'], 6).tolist()}, points {c['contact_points'].tolist()}")
    assert len(c["force"]) == 5 and not c["pulled_off"].any()
    assert np.max(np.abs(c["force"] - targets)) < 1e-6 * 10.0
    assert c["contact_points"][-1] == 64 * 64 > c["contact_points"][0]


def test_fft_pairs_a_state_stay_few():
    """The preconditioned minimisation takes a few tens of FFT pairs a state under displacement
    control (the unpreconditioned one several times more), on 64^2 as on 32^2."""
    serial_only()
    counts = {}
    for n in (32, 64):
        for pc in ("fourier", "none"):
            c = path(n, d=(0.0, 0.01, -0.03), steps=10, minimize_pc=pc)
            counts[n, pc] = float(np.mean(c["fft_pairs"][1:]))
    say(f"\nexponential: FFT pairs a state {counts}")
    assert counts[64, "fourier"] < 100 and counts[64, "fourier"] < 1.5 * counts[32, "fourier"]
    assert counts[64, "none"] > 2 * counts[64, "fourier"]


@pytest.mark.parametrize("boundary, control, d", [("periodic", "displacement", (0.0, 0.01, -0.03)),
                                                  ("periodic", "force", (0.005, -0.02)),
                                                  ("free", "displacement", (0.0, 0.01, -0.03)),
                                                  ("free", "force", (0.005, -0.02))])
def test_both_directions_reach_the_same_states(boundary, control, d):
    """The Newton direction (the default) and Polak-Ribiere's minimise to the same states, through
    the jump into contact and the pull-off: the same contact counts, forces and d to 1e-7 of the
    largest force (both stop at a relative projected gradient of 1e-10), the pull-off marked alike.
    The curve counts Newton's steps as its outer iterations, one a state for Polak-Ribiere."""
    serial_only()
    c = {direction: path(30, d=d, steps=8, control=control, boundary=boundary, minimize_direction=direction,
                         minimize_rtol=1e-10)
         for direction in ("newton", "polak-ribiere")}
    new, old = c["newton"], c["polak-ribiere"]
    scale = float(np.max(np.abs(old["force"])))
    say(f"\nexponential, {boundary}, {control}: newton against polak-ribiere, max |dF| {np.max(np.abs(new['force'] - old['force'])) / scale:.1e} "
        f"of the largest; FFT pairs {int(new['fft_pairs'].sum())} against {int(old['fft_pairs'].sum())}")
    assert len(new["d"]) == len(old["d"]) and np.array_equal(new["contact_points"], old["contact_points"])
    assert np.max(np.abs(new["force"] - old["force"])) < 1e-7 * scale
    assert np.max(np.abs(new["d"] - old["d"])) < 1e-7 * np.max(np.abs(old["d"]))
    assert np.array_equal(new["pulled_off"], old["pulled_off"])
    assert np.all(new["outer_iterations"] >= 1) and new["outer_iterations"].sum() > len(new["d"])
    if control == "displacement":  # one minimisation a state (force control on the free boundary marches through trials)
        assert np.all(old["outer_iterations"] == 1)


@pytest.mark.mpi
@pytest.mark.ranks3
def test_same_curve_on_any_number_of_ranks():
    """COMM_WORLD against COMM_SELF under both controls (and Polak-Ribiere's direction on one): the
    same contact counts, forces to 1e-8."""
    mpi = PETSc.COMM_WORLD.tompi4py()
    for boundary, control, d, direction in (("periodic", "displacement", (0.0, 0.01, -0.03), "newton"),
                                            ("periodic", "force", (0.005, -0.02), "newton"),
                                            ("free", "displacement", (0.0, 0.01, -0.03), "newton"),
                                            ("free", "force", (0.005, -0.02), "newton"),
                                            ("periodic", "displacement", (0.0, 0.01, -0.03), "polak-ribiere")):
        world = path(30, d=d, steps=8, control=control, boundary=boundary, minimize_direction=direction)
        alone = path(30, d=d, steps=8, control=control, boundary=boundary, minimize_direction=direction, comm=PETSc.COMM_SELF)
        same = mpi.allreduce(int(len(world["d"]) == len(alone["d"]) and np.array_equal(world["contact_points"], alone["contact_points"])), op=_min())
        rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / np.max(np.abs(alone["force"]))), op=_max())
        say(f"\nexponential, {boundary}, {control}, {direction}, {PETSc.COMM_WORLD.getSize()} ranks vs 1: max |dF|/max|F| {rel:.1e}")
        assert same == 1 and rel < 1e-8


def test_results_attributes_and_restart_refusal(tmp_path):
    """The results file records the range and the sphere's Tabor parameter; a restart with another
    range is refused, naming -adh_exponential_range, and one with the same range goes on."""
    serial_only()
    import h5py
    base = [EXE, "-adh_n", "32", "-adh_boundary", "periodic", "-adh_gamma", str(GAMMA), "-adh_criterion", "exponential",
            "-adh_path", "0,0.01,-0.03", "-adh_steps", "6", "-adh_start", "adhesive"]
    ck = tmp_path / "ck.h5"
    r = subprocess.run(base + ["-adh_exponential_range", "0.01", "-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(tmp_path / "a.h5", "r") as f:
        assert f.attrs["criterion"] == "exponential"
        assert float(f.attrs["exponential_range"]) == pytest.approx(0.01, rel=1e-12)
        direction = f.attrs["minimize_direction"]
        assert (direction.decode() if isinstance(direction, bytes) else direction) == "newton"
        mu = (GAMMA ** 2 / 0.01 ** 3) ** (1 / 3)
        assert float(f.attrs["tabor_mu"]) == pytest.approx(mu, rel=1e-9)
        assert float(f.attrs["asperity_tabor"]) == pytest.approx(mu, rel=1e-9)  # the resolution report's, of the sphere
        assert np.all(f["curve/cohesive_area"][1:] > 0)
    r = subprocess.run(base + ["-adh_exponential_range", "0.02", "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and "-adh_exponential_range" in r.stderr, r.stderr[-2000:]
    r = subprocess.run(base + ["-adh_exponential_range", "0.01", "-adh_restart", str(ck), "-adh_output", str(tmp_path / "c.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]


@pytest.mark.parametrize("direction, outer, inner", [
    ("newton", "Newton steps", "conjugate gradient iterations"),
    ("polak-ribiere", "minimisations", "Polak-Ribiere iterations"),
])
def test_summary_names_the_minimisations_counts(tmp_path, direction, outer, inner):
    """The executable's summary line says what a cohesive law's counts are (not set updates and
    KSP iterations), and its numbers are the curve's sums."""
    serial_only()
    import h5py
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_boundary", "periodic", "-adh_gamma", str(GAMMA), "-adh_criterion", "exponential",
                        "-adh_exponential_range", "0.01", "-adh_path", "0,0.01,-0.03", "-adh_steps", "6", "-adh_start", "adhesive",
                        "-adh_minimize_direction", direction, "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    m = re.search(rf"^adhbem: \d+ states; .*; (\d+) {outer}, (\d+) {inner}, \d+ compliance applications", r.stdout, re.M)
    assert m, r.stdout
    assert "set updates" not in m.group(0)
    with h5py.File(tmp_path / "a.h5", "r") as f:
        assert int(m.group(1)) == int(f["curve/outer_iterations"][()].sum()) > 0
        assert int(m.group(2)) == int(f["curve/ksp_iterations"][()].sum()) > 0


@pytest.mark.parametrize("args, culprit", [
    ([], "-adh_exponential_range"),
    (["-adh_exponential_range", "-1"], "-adh_exponential_range"),
    (["-adh_exponential_range", "nan"], "-adh_exponential_range"),
    (["-adh_exponential_range", "0.01", "-adh_attach", "reach"], "-adh_attach"),
    (["-adh_exponential_range", "0.01", "-adh_minimize_rtol", "2"], "-adh_minimize_rtol"),
    (["-adh_exponential_range", "0.01", "-adh_minimize_pc", "jacobi"], "-adh_minimize_pc"),
    (["-adh_exponential_range", "0.01", "-adh_minimize_direction", "bfgs"], "-adh_minimize_direction"),
])
def test_bad_input_refused(args, culprit):
    """One line naming the option, a non-zero exit."""
    serial_only()
    base = [EXE, "-adh_n", "16", "-adh_gamma", str(GAMMA), "-adh_criterion", "exponential", "-adh_steps", "2"]
    if "-adh_boundary" not in args:
        base += ["-adh_boundary", "periodic"]
    r = subprocess.run(base + args, capture_output=True, text=True, timeout=60)
    assert r.returncode != 0 and culprit in r.stderr, r.stderr[-2000:]


def test_gamma_field():
    """A work-of-adhesion field under the law: a constant one is the scalar to rounding, on both
    boundaries; with dgamma halved on half the cell the largest tension lies between the two
    uniform ones'."""
    serial_only()
    n = 32
    x = (np.arange(n) - n / 2 + 0.5) / n
    X, _ = np.meshgrid(x, x)
    for boundary in ("periodic", "free"):
        scalar = path(n, boundary=boundary)
        same = path(n, boundary=boundary, gamma_field=np.full((n, n), GAMMA))
        assert np.array_equal(same["contact_points"], scalar["contact_points"])
        assert np.max(np.abs(same["force"] - scalar["force"])) < 1e-10 * np.max(np.abs(scalar["force"]))
    half = -np.min(path(n, gamma_field=np.where(X > 0, GAMMA / 2, GAMMA))["force"])
    weaker = -np.min(path(n, gamma=GAMMA / 2)["force"])
    stronger = -np.min(path(n)["force"])
    say(f"\nexponential with a dgamma field: largest tension {half:.6g} between {weaker:.6g} and {stronger:.6g}")
    assert weaker < half < stronger


def test_free_boundary_restart_continues_the_curve(tmp_path):
    """On the free boundary a run stopped by SIGTERM after a few states and restarted from its
    checkpoint gives the uninterrupted curve (forces to 1e-8: the restart starts from the
    checkpoint's pressure, the minimisation to its tolerance)."""
    serial_only()
    import signal
    import time
    import h5py
    base = [EXE, "-adh_n", "128", "-adh_gamma", str(GAMMA), "-adh_criterion", "exponential", "-adh_exponential_range", "0.01",
            "-adh_path", "0,0.01,-0.03", "-adh_steps", "20", "-adh_start", "adhesive", "-adh_stop_at_pulloff", "false",
            "-adh_fftw_planner", "estimate"]
    r = subprocess.run(base + ["-adh_output", str(tmp_path / "whole.h5")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    run = base + ["-adh_output", str(tmp_path / "run.h5"), "-adh_checkpoint", str(tmp_path / "run.ck.h5")]
    p = subprocess.Popen(run, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    journal = tmp_path / "run.csv.part"
    while p.poll() is None and (not journal.exists() or len(journal.read_text().splitlines()) < 6):
        time.sleep(0.01)
    p.send_signal(signal.SIGTERM)
    p.communicate(timeout=120)
    with h5py.File(tmp_path / "run.h5", "r") as f:
        stopped = len(f["curve/force"][()])
    r = subprocess.run(run + ["-adh_restart", str(tmp_path / "run.ck.h5")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(tmp_path / "whole.h5", "r") as f, h5py.File(tmp_path / "run.h5", "r") as g:
        whole, restarted = f["curve/force"][()], g["curve/force"][()]
    say(f"\nexponential, free boundary: stopped after {stopped} of {len(whole)} states, restarted")
    assert 0 < stopped < len(whole) and len(restarted) == len(whole)
    assert np.max(np.abs(restarted - whole)) < 1e-8 * np.max(np.abs(whole))
