"""Load control (-adh_control force): the path holds forces F = sum(p) hx hy, each step finds the
d at which the Pohrt-Popov equilibrium set carries F, and a leg ends at pull-off on the state
carrying the largest tension (bisection to -adh_pulloff_rtol), marked pulled_off = 1.

Hertz under force control (d, contact radius, and the same states as displacement control), the
JKR pull-off force and contact radius under force control, pull-off followed by reloading from
first touch, bad input (Python and the executable), and 1 rank vs several.

Every test prints its key numbers (`pytest -s` shows them). Tests marked `mpi` are collective and
assert only on all-reduced values, so a failure never leaves a rank waiting in a collective.
"""
import math
import subprocess
import time

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import _max, _min, gamma_for, jkr_scales, radius, rank0, say  # noqa: E402

R = 1.0   # sphere radius
E = 1.0   # reduced modulus E*


def hertz_force(a):
    """Hertz force at contact radius a."""
    return 4.0 / 3.0 * E * a ** 3 / R


# ---- Hertz under force control ---------------------------------------------------------------------

def test_hertz_force_control():
    """gamma = 0, forces from the Hertz force at a/h = 17 to 20 (13 states): d against Hertz
    d = (3F/(4 E* sqrt(R)))^(2/3), the contact radius, and the same states under displacement
    control at the d the force run found (same sets, same forces)."""
    N = 64
    h = 1.0 / N
    t0 = time.perf_counter()
    s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=0.0, radius=R, start="hertz", control="force",
                      path=[hertz_force(17 * h), hertz_force(20 * h)], steps=12)
    c = s.solve_path()
    t1 = time.perf_counter()
    F, d = c["force"], c["d"]
    targets = np.linspace(hertz_force(17 * h), hertz_force(20 * h), 13)
    d_hertz = (3 * F / (4 * E * math.sqrt(R))) ** (2 / 3)
    d_err = d / d_hertz - 1
    a_err = radius(c["area"]) / np.sqrt(R * d_hertz) - 1
    # The same states under displacement control (one step per breakpoint).
    disp = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=0.0, radius=R, start="hertz",
                         path=list(d), steps=1).solve_path()
    t2 = time.perf_counter()
    F_rel = np.abs(disp["force"] / F - 1)
    say(f"\nHertz under force control N={N}: {len(d)} states, a/h {math.sqrt(R * d_hertz[0]) / h:.2f}"
        f" .. {math.sqrt(R * d_hertz[-1]) / h:.2f}; d error {d_err.min():+.2e} .. {d_err.max():+.2e};"
        f" radius error mean {a_err.mean():+.3%} ({a_err.min():+.3%} .. {a_err.max():+.3%});"
        f" displacement control at the same d: max |F_d/F_f - 1| = {F_rel.max():.1e},"
        f" contact counts identical: {np.array_equal(disp['contact_points'], c['contact_points'])}"
        f" ({c['contact_points'][0]} .. {c['contact_points'][-1]} points); {t1 - t0:.2f} s + {t2 - t1:.2f} s")
    assert len(d) == 13 and len(disp["d"]) == 13
    np.testing.assert_allclose(F, targets, rtol=1e-10)
    assert np.all(c["pulled_off"] == 0)
    assert np.max(np.abs(d_err)) < 1e-3
    assert abs(a_err.mean()) < 1e-2
    np.testing.assert_array_equal(disp["d"], d)
    assert np.array_equal(disp["contact_points"], c["contact_points"])
    assert F_rel.max() < 1e-8


# ---- JKR pull-off under force control --------------------------------------------------------------

_jkr = {}


def jkr_force_run(N, ratio, steps=20, criterion="pohrt-popov"):
    """Force-controlled JKR unloading on the N x N grid (L = 1) with a_c = ratio h: Hertz start at
    the Hertz force of a = 1.3 a_c, then to -1.2 F_adh (the leg ends at pull-off); the paper's loop,
    in which points only let go (-adh_attach penetration). Cached."""
    key = (N, ratio, steps, criterion)
    if key not in _jkr:
        ac = ratio / N
        gamma = gamma_for(ac)
        ac, dc, Fadh = jkr_scales(gamma)
        t0 = time.perf_counter()
        s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz", control="force",
                          path=[hertz_force(1.3 * ac), -1.2 * Fadh], steps=steps, criterion=criterion,
                          attach="penetration")
        c = s.solve_path()
        seconds = time.perf_counter() - t0
        k = int(np.argmin(c["force"]))
        run = dict(c=c, ac=ac, dc=dc, Fadh=Fadh, gamma=gamma, seconds=seconds, k=k,
                   tension=-c["force"][k] / Fadh, an=radius(c["area"][k]) / ac)
        run["error"] = run["tension"] - 1
        say(f"  [force-controlled JKR N={N} a_c/h={ratio} ({criterion}): {len(c['d'])} states, largest tension"
            f" {run['tension']:.4f} F_adh at a/a_c = {run['an']:.4f} ({c['contact_points'][k]} points),"
            f" {int(c['ksp_iterations'].sum())} KSP its, {seconds:.2f} s]")
        _jkr[key] = run
    return _jkr[key]


def test_jkr_pull_off_force_control():
    """The sphere comes off at F_adh = 3/2 pi dgamma R with a contact radius near a_c. The error is
    the criterion's own mesh error and decreases with a_c/h: within 3% at a_c/h = 62.5 (N = 200;
    1.0308 F_adh at a_c/h = 50, 1.0666 at 25). The pull-off state ends the leg: it is the last
    state, the minimum of the curve, and still in contact. At a_c/h = 25 the pull-off force agrees
    with the largest tension of the displacement-controlled unloading on the same grid."""
    say("")
    coarse = jkr_force_run(80, 25.0)
    fine = jkr_force_run(200, 62.5)
    for run in (coarse, fine):
        c = run["c"]
        last = len(c["d"]) - 1
        assert c["pulled_off"][last] == 1 and np.all(c["pulled_off"][:last] == 0)
        assert run["k"] == last and c["force"][last] == c["force"].min()
        assert c["contact_points"][last] > 0
        # Every state before the pull-off carries its target force exactly.
        targets = np.linspace(hertz_force(1.3 * run["ac"]), -1.2 * run["Fadh"], 21)[:last]
        np.testing.assert_allclose(c["force"][:last], targets, rtol=1e-10, atol=1e-14 * run["Fadh"])
        # The pull-off force lies between the last target carried and the first one not.
        assert targets[-1] > c["force"][last] > -1.2 * run["Fadh"]
    # Displacement control on the coarse grid: unloading from the same Hertz state in steps of
    # 0.082 |d_c| (as in test_validation.py), its largest tension.
    t0 = time.perf_counter()
    disp = adhbem.Solver(n=80, size=1.0, E_star=E, gamma=coarse["gamma"], radius=R, start="hertz",
                         criterion="pohrt-popov", attach="penetration",
                         path=[(1.3 * coarse["ac"]) ** 2 / R, -4.0 * coarse["dc"]], steps=110).solve_path()
    t_disp = time.perf_counter() - t0
    disp_tension = -disp["force"].min() / coarse["Fadh"]
    agree = coarse["tension"] / disp_tension - 1
    say(f"JKR under force control: largest tension / F_adh = {coarse['tension']:.4f} at a_c/h = 25"
        f" (a/a_c = {coarse['an']:.4f}), {fine['tension']:.4f} at a_c/h = 62.5 (a/a_c = {fine['an']:.4f},"
        f" error {fine['error']:+.3%}, {fine['seconds']:.1f} s); displacement control at a_c/h = 25:"
        f" {disp_tension:.4f} F_adh (force/displacement - 1 = {agree:+.3%}, {t_disp:.2f} s)")
    assert abs(fine["error"]) < abs(coarse["error"])
    assert abs(fine["error"]) < 0.03
    assert abs(fine["an"] - 1) < 0.05
    assert abs(agree) < 0.03


def test_jkr_pull_off_force_control_crack_closure():
    """With the crack-closure criterion the sphere comes off within 3% of F_adh already at
    a_c/h = 50 (0.996 F_adh; the paper's criterion: 1.031) and at a/a_c within 5%."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial measurement")
    say("")
    run = jkr_force_run(160, 50.0, criterion="crack-closure")
    c = run["c"]
    last = len(c["d"]) - 1
    assert c["pulled_off"][last] == 1 and run["k"] == last and c["contact_points"][last] > 0
    assert abs(run["error"]) < 0.03
    assert abs(run["an"] - 1) < 0.05


# ---- Pull-off, then reloading from first touch -------------------------------------------------------

def test_reloading_after_pull_off():
    """Path [F0, -1.5 F_adh, F0] (N = 48, a_c/h = 15): the unloading leg ends at pull-off; on the
    loading leg the targets F <= 0 find the bodies apart (no contact, no force), then the first
    positive target starts again from first touch, and d and the contact grow to the final force
    F0 (the reloaded contact's radius against the adhesion-free start's and JKR's is printed).
    The legs after a pull-off run only when told (stop_at_pulloff=False)."""
    N, ratio, steps = 48, 15.0, 12
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    F0 = hertz_force(1.3 * ac)
    t0 = time.perf_counter()
    c = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz", control="force",
                      path=[F0, -1.5 * Fadh, F0], steps=steps, stop_at_pulloff=False).solve_path()
    seconds = time.perf_counter() - t0
    F, d, n, off = c["force"], c["d"], c["contact_points"], c["pulled_off"]
    po = np.nonzero(off)[0]
    assert len(po) == 1
    k = int(po[0])
    assert 0 < k < steps + 1 and n[k] > 0 and F[k] == F.min()
    # The rest of the unloading leg is skipped: the next state is the loading leg's first target.
    targets = np.linspace(-1.5 * Fadh, F0, steps + 1)[1:]
    assert len(F) == k + 1 + len(targets)
    load = slice(k + 1, None)
    Fl, dl, nl = F[load], d[load], n[load]
    apart = targets <= 0
    touching = ~apart
    assert apart.any() and touching.any()
    assert np.all(nl[apart] == 0) and np.all(Fl[apart] == 0.0)
    assert np.all(nl[touching] > 0)
    np.testing.assert_allclose(Fl[touching], targets[touching], rtol=1e-10)
    assert np.all(np.diff(dl[touching]) > 0) and np.all(np.diff(nl[touching]) >= 0)
    assert abs(F[-1] / F0 - 1) < 1e-10
    # JKR a~ at the force F0: F~ = a~^3 - 2 a~^(3/2) on the branch a~ >= 1.
    a_grid = np.linspace(1.0, 4.0, 300001)
    a_jkr = np.interp(F0 / Fadh, a_grid ** 3 - 2 * a_grid ** 1.5, a_grid)
    say(f"\nreloading after pull-off (N={N}, a_c/h={ratio}): pull-off at state {k} with {n[k]} points,"
        f" {-F[k] / Fadh:.4f} F_adh; {int(apart.sum())} targets apart, first touch at F~ ="
        f" {targets[touching][0] / Fadh:+.4f} with {nl[touching][0]} points; at F0: start {n[0]} points"
        f" (a/a_c {radius(c['area'][0]) / ac:.3f}, d {d[0]:.6f}), reloaded {n[-1]} points"
        f" (a/a_c {radius(c['area'][-1]) / ac:.3f}, d {d[-1]:.6f}; JKR a/a_c {a_jkr:.3f});"
        f" |F_end/F0 - 1| = {abs(F[-1] / F0 - 1):.1e}; {seconds:.2f} s")
    assert n[-1] >= n[0]


# ---- Bad input -----------------------------------------------------------------------------------------

def test_force_control_bad_input(tmp_path):
    """A negative first force with the Hertz start, pulloff_rtol = 0, and the same from the
    executable (non-zero exit, the option named, no results file), an unknown control type."""
    with pytest.raises(ValueError) as e:
        adhbem.Solver(n=16, gamma=1e-3, start="hertz", control="force", path=[-0.01, 0.01], steps=2).solve_path()
    say(f"\nnegative first force: {type(e.value).__name__} {e.value}")
    with pytest.raises(ValueError) as e:
        adhbem.Solver(n=16, gamma=1e-3, control="force", pulloff_rtol=0.0, path=[0.01, -0.01], steps=2)
    say(f"pulloff_rtol = 0: {e.value}")
    with pytest.raises(ValueError):
        adhbem.Solver(n=16, control="forse", path=[0.01], steps=1)

    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, "-adh_n", "16", "-adh_control", "force", "-adh_start", "hertz",
                        "-adh_path", "-0.1,0.1", "-adh_output", str(out)],
                       capture_output=True, text=True, timeout=60)
    msg = r.stdout + r.stderr
    lines = [ln for ln in msg.splitlines() if "-adh_path" in ln and "first force" in ln]
    say(f"executable, negative first force: exit {r.returncode}: {lines[0].strip() if lines else '(no message)'}")
    assert r.returncode != 0
    assert lines, msg[-2000:]
    assert not out.exists() and not (tmp_path / "x.csv").exists()

    r = subprocess.run([EXE, "-adh_n", "16", "-adh_control", "forse", "-adh_path", "0.1",
                        "-adh_output", str(out)], capture_output=True, text=True, timeout=60)
    msg = r.stdout + r.stderr
    lines = [ln for ln in msg.splitlines() if "-adh_control" in ln and "forse" in ln]
    say(f"executable, -adh_control forse: exit {r.returncode}: {lines[0].strip() if lines else '(no message)'}")
    assert r.returncode != 0
    assert lines, msg[-2000:]
    assert not out.exists()


# ---- 1 rank vs several ------------------------------------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.ranks3
def test_force_control_ranks_give_the_same_curve():
    """A force-controlled JKR path with pull-off and reloading (N = 48) on COMM_WORLD and on
    COMM_SELF: forces and d to 1e-10 relative, identical contact counts and pulled_off."""
    N, ratio = 48, 15.0
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    F0 = hertz_force(1.3 * ac)
    opts = dict(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz", control="force",
                path=[F0, -1.2 * Fadh, 0.5 * F0], steps=12)
    world = adhbem.Solver(**opts).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, **opts).solve_path()
    mpi = PETSc.COMM_WORLD.tompi4py()
    same_len = mpi.allreduce(int(len(world["d"]) == len(alone["d"])), op=_min())
    assert same_len == 1
    Fscale, dscale = np.max(np.abs(alone["force"])), np.max(np.abs(alone["d"]))
    relF = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / Fscale), op=_max())
    reld = mpi.allreduce(float(np.max(np.abs(world["d"] - alone["d"])) / dscale), op=_max())
    counts = mpi.allreduce(int(np.array_equal(world["contact_points"], alone["contact_points"])), op=_min())
    patches = mpi.allreduce(int(np.array_equal(world["patches"], alone["patches"])), op=_min())
    pulled = mpi.allreduce(int(np.array_equal(world["pulled_off"], alone["pulled_off"])), op=_min())
    had_pulloff = mpi.allreduce(int(alone["pulled_off"].sum() == 1), op=_min())
    say(f"\nforce control, {PETSc.COMM_WORLD.getSize()} ranks vs 1: {len(world['d'])} states,"
        f" max |F_P - F_1| / max|F| = {relF:.2e}, max |d_P - d_1| / max|d| = {reld:.2e},"
        f" contact counts identical: {bool(counts)}, patches identical: {bool(patches)},"
        f" pulled_off identical: {bool(pulled)}")
    assert counts == 1 and patches == 1 and pulled == 1 and had_pulloff == 1
    assert relF < 1e-10 and reld < 1e-10


def test_force_control_without_adhesion_comes_off_at_zero():
    """Without adhesion no equilibrium carries tension: a force path into tension comes off at a
    force of zero (within -adh_pulloff_rtol of the step's forces) and ends; the bisection must end
    although the pull-off force is 0 (run with a time limit, so that a hang fails)."""
    r = subprocess.run([EXE, "-adh_n", "16", "-adh_control", "force",
                        "-adh_path", "0.01,-0.01", "-adh_steps", "3", "-adh_monitor"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "contact lost at d = " in r.stdout and "adhbem: 3 states; no tension carried; contact lost at d = " in r.stdout, r.stdout
    s = adhbem.Solver(n=16, control="force", path=[0.01, -0.01, -0.005], steps=3, stop_at_pulloff=False)
    c = s.solve_path()
    k = int(np.nonzero(c["pulled_off"])[0][0])
    say(f"\nforce control, gamma = 0: pull-off state {k} at F = {c['force'][k]:.3e}, {c['contact_points'][k]} points;"
        f" states after it: points {c['contact_points'][k + 1:].tolist()}")
    assert 0 <= c["force"][k] <= 1e-3 * 0.01 and c["contact_points"][k] > 0
    # after pull-off (a new leg at F < 0): nothing in contact, the undeformed gap
    h = adhbem.gather(s.profile, s.compliance)
    assert k + 1 < len(c["d"]) and np.all(c["contact_points"][k + 1:] == 0) and np.all(c["force"][k + 1:] == 0)
    np.testing.assert_allclose(c["mean_gap"][-1], h.mean() - c["d"][-1], rtol=1e-12)


def test_force_loading_with_adhesion_does_not_overshoot():
    """Loading with adhesion under force control in 1 step reaches the state of 40 steps, and of
    displacement control in 40 steps at that force: a step adds points in the order in which they
    touch, not every point that penetrates at the depth the old, softer set needs (adhesion would
    keep those: 512 points instead of 19 before). With the penetration attach: under reach this
    smooth cell jumps into nearly full contact, and force control at a force of the jump's unstable
    part finds another equilibrium than displacement control (a matter of the physics, not of the
    stepping)."""
    base = dict(n=32, size=1.0, indenter="rough", rms_height=0.01, gamma=1e-3, start="adhesive", attach="penetration")
    disp = adhbem.Solver(**base, path=[0.0, 0.004, 0.008], steps=40).solve_path()
    F = [disp["force"][40], disp["force"][80]]
    runs = {k: adhbem.Solver(**base, control="force", path=[0.0] + F, steps=k).solve_path() for k in (1, 40)}
    pts = {k: c["contact_points"][[k, 2 * k]].tolist() for k, c in runs.items()}
    say(f"\nforce-controlled adhesive loading to F = {F}: points after 1 step a leg {pts[1]}, 40 steps {pts[40]},"
        f" displacement control {disp['contact_points'][[40, 80]].tolist()}")
    for k, c in runs.items():
        assert pts[k] == disp["contact_points"][[40, 80]].tolist()
        np.testing.assert_allclose(c["d"][[k, 2 * k]], [0.004, 0.008], rtol=1e-8)
