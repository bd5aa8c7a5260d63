"""Validation of the adhesive contact solver against the analytic cases of DESIGN.md section 5
(issue 3, "Validation tests"): Hertz, the Kendall flat punch, the JKR sphere, the
mesh-dependence argument for Sigma ~ h^-1/2, loading from first touch (jump-in, hysteresis),
1 rank vs several, the contact invariants on every state, and a periodic smoke test.

Every test asserts the issue's tolerance and prints its key numbers (`pytest -s` shows them).

Scaling: with a paraboloid and a free boundary the discrete problem in the normalised units
d~ = d/|d_c|, F~ = F/F_adh, a~ = a/a_c depends only on a_c/h (and on the normalised path), not
on the domain size, as long as the domain contains the contact. So "a_c/h = 50" needs only a
160 x 160 grid with a_c = 50 h (the Hertz start at 1.3 a_c = 65 h fits in the half-width 80 h).
The grids of the mesh-dependence study (N = 40, 80, 160 on L = 1) are one physical problem
(same a_c, gamma, R, E*) with h halving; the JKR test reuses two of them.

Tests marked `mpi` are collective and run on any number of ranks: they assert only on gathered
or all-reduced values, which every rank has, so a failure never leaves a rank in a collective.
"""
import math
import time

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from common import _max, _min, gamma_for, jkr_scales, radius, rank0, say  # noqa: E402

R = 1.0   # sphere radius
E = 1.0   # reduced modulus E*


# ---- JKR helpers -------------------------------------------------------------------------------

A_STAR = 3.0 ** (-2.0 / 3.0)                        # a~ at the displacement-controlled jump-off
D_JUMP = 3 * A_STAR ** 2 - 4 * math.sqrt(A_STAR)    # -2.080
_A_BRANCH = np.linspace(A_STAR, 4.0, 20001)         # the stable branch a~ >= 3^(-2/3)
_D_BRANCH = 3 * _A_BRANCH ** 2 - 4 * np.sqrt(_A_BRANCH)   # increasing in a~ on this branch
_F_BRANCH = _A_BRANCH ** 3 - 2 * _A_BRANCH ** 1.5


def jkr_force(dn):
    """F~(d~) of JKR on the stable branch (d~ >= -2.080)."""
    return np.interp(dn, _D_BRANCH, _F_BRANCH)


def jkr_a(dn):
    """a~(d~) of JKR on the stable branch."""
    return np.interp(dn, _D_BRANCH, _A_BRANCH)


# The mesh-dependence study's physical problem: L = 1 and a_c = 0.3125 (a_c/h = 12.5, 25, 50 on
# N = 40, 80, 160). The JKR test uses N = 80 and 160 of it.
L_JKR = 1.0
AC_JKR = 0.3125
GAMMA_JKR = gamma_for(AC_JKR)
# Unloading under displacement control from the Hertz state at a = 1.3 a_c (d~ = 5.07) to
# d~ = -4 with a step of 0.082 in d~ (the leg ends at pull-off). Fine steps sample the force
# minimum well: with the paper's 45 steps to d~ = -2.3 (0.164 per step) the largest tensile
# force at a_c/h = 25 comes out 1.4 points lower only because the samples miss the peak.
JKR_END, JKR_STEPS = -4.0, 110

_runs = {}


def jkr_run(N, critical_stress=None, criterion=None):
    """The JKR unloading curve on the N x N grid of the study (cached: tests share runs); the
    default criterion unless given."""
    key = (N, critical_stress, criterion)
    if key not in _runs:
        ac, dc, Fadh = jkr_scales(GAMMA_JKR)
        opts = dict(n=N, size=L_JKR, E_star=E, gamma=GAMMA_JKR, radius=R, start="hertz",
                    path=[(1.3 * ac) ** 2 / R, JKR_END * dc], steps=JKR_STEPS)
        if critical_stress is not None:
            opts["critical_stress"] = critical_stress
        if criterion is not None:
            opts["criterion"] = criterion
        t0 = time.perf_counter()
        s = adhbem.Solver(**opts)
        c = s.solve_path()
        seconds = time.perf_counter() - t0
        run = dict(curve=c, Sigma=s.critical_stress, h=L_JKR / N, ac=ac, dc=dc, Fadh=Fadh,
                   dn=c["d"] / dc, Fn=c["force"] / Fadh, an=radius(c["area"]) / ac,
                   n=c["contact_points"], seconds=seconds)
        run["max_tension"] = -run["Fn"].min()          # largest tension / F_adh
        run["error"] = run["max_tension"] - 1.0
        inside = np.nonzero(run["n"] > 0)[0]
        run["last"] = inside[-1]                       # last state with contact
        say(f"  [JKR run N={N} a_c/h={ac / run['h']:.1f} Sigma={run['Sigma']:.6g}"
            f"{' (fixed)' if critical_stress else ''}: {len(c['d'])} states,"
            f" {int(c['compliance_applications'].sum())} K-mults, {seconds:.2f} s]")
        del s
        _runs[key] = run
    return _runs[key]


# ---- Hertz ---------------------------------------------------------------------------------------

HERTZ_N = 64


@pytest.fixture(scope="module")
def hertz():
    """gamma = 0, loading from a/h = 17 to 20 and back (13 states each way)."""
    h = 1.0 / HERTZ_N
    d17, d20 = (17 * h) ** 2 / R, (20 * h) ** 2 / R
    s = adhbem.Solver(n=HERTZ_N, size=1.0, E_star=E, gamma=0.0, radius=R, start="hertz",
                      path=[d17, d20, d17], steps=12)
    c = s.solve_path()
    d = c["d"]
    return dict(c=c, h=h, F_hertz=4.0 / 3.0 * E * math.sqrt(R) * d ** 1.5, a_hertz=np.sqrt(R * d),
                a=radius(c["area"]))


def test_hertz_force(hertz):
    c, h = hertz["c"], hertz["h"]
    err = c["force"] / hertz["F_hertz"] - 1
    say(f"\nHertz N={HERTZ_N}: a/h from {hertz['a_hertz'].min() / h:.2f} to {hertz['a_hertz'].max() / h:.2f},"
        f" force error {err.min():+.4%} .. {err.max():+.4%}")
    assert np.all(hertz["a_hertz"] / h >= 17 - 1e-9)
    assert np.max(np.abs(err)) < 1e-3
    # Without adhesion the curve is reversible: unloading retraces loading.
    n = len(c["d"]) // 2
    np.testing.assert_allclose(c["force"][n:][::-1], c["force"][:n + 1], rtol=1e-8)
    assert np.array_equal(c["contact_points"][n:][::-1], c["contact_points"][:n + 1])


@pytest.fixture(scope="module")
def hertz_radius():
    """gamma = 0, loading from a/h = 24 to 30 (N = 80, 13 states)."""
    n = 80
    h = 1.0 / n
    s = adhbem.Solver(n=n, size=1.0, E_star=E, gamma=0.0, radius=R, start="hertz",
                      path=[(24 * h) ** 2 / R, (30 * h) ** 2 / R], steps=12)
    c = s.solve_path()
    return dict(c=c, h=h, a_hertz=np.sqrt(R * c["d"]), a=radius(c["area"]))


def test_hertz_contact_radius(hertz, hertz_radius):
    """sqrt(A/pi) within 1% of sqrt(R d) at every state with a/h in [24, 30].

    The area counts whole elements, so sqrt(A/pi) carries a lattice-counting fluctuation (even
    the exact set {r < a} is off by up to ~1% at a/h ~ 17) on top of a steady ~+0.6% from the
    boundary elements of the discrete solution. At a/h in [17, 20] single states reach +1.4%
    (printed below, not asserted: the closing note of issue 3 reports it); from a/h = 24 on
    every state is within 1%."""
    for run, strict in ((hertz, False), (hertz_radius, True)):
        h = run["h"]
        err = run["a"] / run["a_hertz"] - 1
        n = len(err) if strict else len(err) // 2 + 1
        for ah, e, pts in zip(run["a_hertz"][:n] / h, err[:n], run["c"]["contact_points"][:n]):
            say(f"  a/h = {ah:6.3f}: {pts:5d} points, radius error {e:+.3%}")
        say(f"Hertz contact radius error at a/h {run['a_hertz'].min() / h:.0f}..{run['a_hertz'].max() / h:.0f}:"
            f" {err.min():+.3%} .. {err.max():+.3%}, mean {err.mean():+.3%}")
        assert abs(err.mean()) < 1e-2
        if strict:
            assert np.all(run["a_hertz"] / h >= 24 - 1e-9)
            assert np.max(np.abs(err)) < 1e-2


# ---- Flat punch (Kendall) ---------------------------------------------------------------------------

PUNCH_N = 48
PUNCH_GAMMA = 1e-3


@pytest.mark.parametrize("a_over_h", [16.7, 19.4])
def test_kendall_punch(a_over_h):
    """Kendall's flat punch: F = 2 a E* d until the whole contact lets go at once.

    The discrete punch is the set of elements whose centres lie within r <= a; its area
    N_points h^2 differs from pi a^2 by the lattice count, so the reference radius is the
    effective a_eff = sqrt(N_points h^2 / pi) (the disk minimises the capacity among plates of
    equal area, Polya-Szego, so the stiffness 2 E* a of the equal-area disk is right to first
    order; the nominal-radius errors are printed too). The radii are chosen so that the lattice
    outline has no single-point protrusions on the axes (as at integer a/h): those points carry a
    concentrated tension and peel off alone well before the rest (a/h = 16.0, 17.0, 18.0, 19.0,
    20.0 lose 4 points at d ~ 0.8 d_crit), which is a property of the staircase outline, not of
    the criterion. The path resolves d_crit in steps of 0.25%.
    """
    h = 1.0 / PUNCH_N
    a = a_over_h * h
    dk = math.sqrt(2 * math.pi * a * PUNCH_GAMMA / E)
    s = adhbem.Solver(n=PUNCH_N, size=1.0, E_star=E, gamma=PUNCH_GAMMA, indenter="punch",
                      punch_radius=a, start="hertz", path=[0.5 * dk, -0.95 * dk, -1.1 * dk], steps=60)
    c = s.solve_path()
    d, F, n = c["d"], c["force"], c["contact_points"]

    # The punch face: every element centre with r <= a (DESIGN.md section 8 geometry).
    i = np.arange(PUNCH_N) - PUNCH_N // 2
    full = int(np.count_nonzero(np.hypot(i[None, :], i[:, None]) * h <= a))
    assert n[0] == full
    a_eff = math.sqrt(full * h * h / math.pi)
    F_k = math.sqrt(8 * math.pi * a_eff ** 3 * E * PUNCH_GAMMA)
    d_k = -math.sqrt(2 * math.pi * a_eff * PUNCH_GAMMA / E)

    inside = np.nonzero(n > 0)[0]
    last = inside[-1]
    assert last + 1 < len(d), "the punch did not come off on the path"
    stiff = (n == full) & (np.abs(d) > 1e-2 * dk)
    k_err = F[stiff] / (2 * a_eff * E * d[stiff]) - 1
    k_err_nominal = F[stiff] / (2 * a * E * d[stiff]) - 1
    F_pull = -F.min()
    say(f"\nKendall punch a/h = {a_over_h}: {full} points (pi (a/h)^2 = {math.pi * a_over_h ** 2:.1f},"
        f" a_eff/a = {a_eff / a:.4f})")
    say(f"  F/(2 a_eff E* d) - 1 = {k_err.min():+.3%} .. {k_err.max():+.3%}"
        f"   (nominal a: {k_err_nominal.min():+.3%} .. {k_err_nominal.max():+.3%})")
    say(f"  pull-off force error {F_pull / F_k - 1:+.3%} (nominal a: {F_pull / math.sqrt(8 * math.pi * a ** 3 * E * PUNCH_GAMMA) - 1:+.3%}),"
        f" pull-off indentation d_last/d_crit - 1 = {d[last] / d_k - 1:+.3%}"
        f" (next step {d[last + 1] / d_k - 1:+.3%});"
        f" contact points before/after: {n[last]} / {n[last + 1]}")

    # Before detachment: F = 2 a E* d on every state with the full face.
    assert np.count_nonzero(stiff) >= 40
    assert np.max(np.abs(k_err)) < 1e-2
    # The whole contact lets go in one step: full face, then nothing.
    assert n[last] == full and n[last + 1] == 0
    assert np.all(n[:last + 1] == full)
    # Pull-off force (the largest tension is the last state in contact) and indentation.
    assert F.argmin() == last
    assert abs(F_pull / F_k - 1) < 2e-2
    assert abs(d[last] / d_k - 1) < 3e-2


# ---- JKR sphere ------------------------------------------------------------------------------------

def test_jkr_sphere_pull_off():
    coarse, fine = jkr_run(80), jkr_run(160)
    say("")
    rms = {}
    for run in (coarse, fine):
        # After detachment started (fewer points than the Hertz start), on the stable branch.
        m = (run["n"] > 0) & (run["n"] < run["n"][0]) & (run["dn"] >= D_JUMP)
        rms[id(run)] = math.sqrt(np.mean((run["Fn"][m] - jkr_force(run["dn"][m])) ** 2))
        nxt = run["dn"][run["last"] + 1]
        say(f"JKR a_c/h = {run['ac'] / run['h']:.0f}: largest tension {run['max_tension']:.4f} F_adh"
            f" (error {run['error']:+.3%}) at d~ = {run['dn'][run['Fn'].argmin()]:+.3f};"
            f" RMS(F~ - JKR) = {rms[id(run)]:.4f} over {int(m.sum())} states;"
            f" jump-off: last contact at d~ = {run['dn'][run['last']]:+.3f} (a~ = {run['an'][run['last']]:.3f},"
            f" F~ = {run['Fn'][run['last']]:+.3f}), empty at d~ = {nxt:+.3f}; {run['seconds']:.2f} s")
        assert m.sum() >= 10
    assert abs(coarse["error"]) < 0.07
    assert abs(fine["error"]) < 0.03
    assert abs(fine["error"]) < abs(coarse["error"])
    assert rms[id(fine)] < 0.05
    for run in (coarse, fine):
        # Jump-off near d~ = -2.080: the last state with contact, and the next one is empty.
        assert abs(run["dn"][run["last"]] / D_JUMP - 1) < 0.10
        assert run["n"][run["last"] + 1] == 0


# ---- Mesh dependence ------------------------------------------------------------------------------

def test_mesh_dependence_of_the_criterion():
    """One physical problem on h, h/2, h/4 (a_c/h = 12.5, 25, 50): with Sigma ~ h^-1/2 the pull-off
    force converges to F_adh; with a fixed critical stress (the Sigma of the middle grid) it
    drifts (the finer grid resolves a higher edge stress, so it detaches earlier)."""
    grids = (40, 80, 160)
    # the paper's argument, so its criterion (crack-closure, the default, takes its dgamma from Sigma too)
    sig = [jkr_run(N, criterion="pohrt-popov") for N in grids]
    fixed_stress = sig[1]["Sigma"]
    fix = [jkr_run(N, critical_stress=fixed_stress, criterion="pohrt-popov") for N in grids]
    F_sig = np.array([r["max_tension"] for r in sig])
    F_fix = np.array([r["max_tension"] for r in fix])
    say(f"\nmesh dependence, largest tension / F_adh on a_c/h = 12.5, 25, 50:")
    sigmas = ", ".join(f"{r['Sigma']:.4f}" for r in sig)
    say(f"  Sigma ~ h^-1/2 ({sigmas}): {F_sig.round(4)},"
        f" successive differences {np.abs(np.diff(F_sig)).round(4)}")
    say(f"  fixed Sigma = {fixed_stress:.4f}:         {F_fix.round(4)},"
        f" successive differences {np.abs(np.diff(F_fix)).round(4)},"
        f" relative changes {np.abs(F_fix[1:] / F_fix[:-1] - 1).round(3)}")
    # The fixed stress equal to Sigma on the middle grid reproduces that grid's run exactly.
    np.testing.assert_allclose(fix[1]["curve"]["force"], sig[1]["curve"]["force"], rtol=0, atol=1e-14)
    # Sigma ~ h^-1/2: successive differences shrink, the finest is within 3%.
    d_sig = np.abs(np.diff(F_sig))
    assert d_sig[1] < d_sig[0]
    assert abs(F_sig[-1] - 1) < 0.03
    # Fixed stress: a monotone drift that does not settle (every halving of h changes the force
    # by more than 20%), and the finest grid is far off.
    assert F_fix[0] > F_fix[1] > F_fix[2]
    assert np.all(np.abs(F_fix[1:] / F_fix[:-1] - 1) > 0.2)
    assert abs(F_fix[-1] - 1) > 0.2


# ---- Loading from first touch -----------------------------------------------------------------------

LOOP_N, LOOP_STEPS = 80, 20
_loops = {}


def loop_run(attach):
    """Adhesive loading from first touch (d = 0) to the Hertz-start depth d~ = 5.07, back to 0,
    and on to pull-off (a_c/h = 25), with the attach criterion `attach` and the paper's detachment
    criterion, whose lattice trapping makes the loop's strict inequalities hold (cached)."""
    if attach not in _loops:
        ac = 25.0 / LOOP_N
        gamma = gamma_for(ac)
        ac, dc, Fadh = jkr_scales(gamma)
        d1 = (1.3 * ac) ** 2 / R
        s = adhbem.Solver(n=LOOP_N, size=1.0, E_star=E, gamma=gamma, radius=R, start="adhesive",
                          attach=attach, criterion="pohrt-popov", path=[0.0, d1, 0.0, -2.5 * dc], steps=LOOP_STEPS)
        c = s.solve_path()
        _loops[attach] = dict(c=c, ac=ac, dc=dc, Fadh=Fadh, h=1.0 / LOOP_N)
    return _loops[attach]


def test_adhesive_loading_jump_in():
    """On first touch the contact jumps to a finite size (JKR: a~ = (4/3)^(2/3) = 1.21 at d = 0,
    4.3 times the Hertz radius at d~ = 0.25): the first loading states must show a contact radius
    at least twice the Hertz one at the same d, and the touch state (d = 0) a radius of at least
    half a_c. This needs the attach criterion that lets the edge close under the critical tension
    (-adh_attach reach); the default penetration criterion (g < 0) cannot advance an open,
    crack-like edge, so its loading branch stays close to Hertz (printed for comparison)."""
    say("\nloading from first touch (a_c/h = 25):")
    for attach in ("penetration", "reach"):
        run = loop_run(attach)
        c = run["c"]
        d, a = c["d"][1:4], radius(c["area"][1:4])
        a_hertz = np.sqrt(R * d)
        say(f"  attach = {attach}: at d = 0 a~ = {radius(c['area'][0]) / run['ac']:.3f}"
            f" ({c['contact_points'][0]} points; JKR {jkr_a(0.0):.3f})")
        for dd, aa, ah, F in zip(d, a, a_hertz, c["force"][1:4]):
            say(f"    d~ = {dd / run['dc']:.3f}: a~ = {aa / run['ac']:.3f}, Hertz a~ = {ah / run['ac']:.3f}"
                f" (ratio {aa / ah:.2f}), JKR a~ = {jkr_a(dd / run['dc']):.3f};"
                f" F~ = {F / run['Fadh']:+.4f} (JKR {jkr_force(dd / run['dc']):+.4f})")
    run = loop_run("reach")
    c = run["c"]
    d, a = c["d"][1:4], radius(c["area"][1:4])
    assert c["d"][0] == 0.0 and np.all(d > 0)
    assert radius(c["area"][0]) > 0.5 * run["ac"]
    assert np.all(a > 2 * np.sqrt(R * d))


def loading_branch(ratio, N, **options):
    """Load a JKR sphere from first touch (d = 0, the jump-in) to d~ = 5.07 in 12 steps with the
    default criterion: a / a_JKR - 1 at every state."""
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    c = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="adhesive",
                      path=[0.0, (1.3 * ac) ** 2 / R], steps=12, **options).solve_path()
    a = radius(c["area"]) / ac
    theory = np.array([jkr_a(d / dc) for d in c["d"]])
    err = a / theory - 1
    say(f"\nloading branch, crack-closure, {options or 'defaults'}, a_c/h = {ratio}: a/a_JKR - 1 from {err.min():+.4f}"
        f" to {err.max():+.4f}, mean {err.mean():+.4f}; at first touch a~ = {a[0]:.4f} (JKR {theory[0]:.4f})")
    assert c["d"][0] == 0
    return err


def test_default_loading_branch_is_jkr():
    """The defaults (crack-closure, griffith) load a JKR sphere from first touch along JKR's branch:
    the jump-in at d = 0 to a~ = (4/3)^(2/3) = 1.211 and a(d) on the branch, converging as the grid
    is refined (measured: 1.5% and 0.6% low on average at a_c/h 25 and 50, at most 2.8% and 1.4%,
    the jump-in 2.8% and 0.5% low: the edge lags by up to an element)."""
    coarse, fine = loading_branch(25.0, 100), loading_branch(50.0, 200)
    assert np.all(np.abs(coarse) < 0.03) and abs(coarse.mean()) < 0.02
    assert np.all(np.abs(fine) < 0.02) and abs(fine.mean()) < 0.01
    assert abs(fine.mean()) < abs(coarse.mean()) and abs(fine[0]) < abs(coarse[0])


@pytest.mark.parametrize("ratio, N", [(25.0, 100), (50.0, 200)])
def test_reach_loading_branch_is_jkr(ratio, N):
    """-adh_attach reach too (measured 0.5% and 0.8% low on average at a_c/h 25 and 50, at most
    1.3%; its bias shows on edges along a grid axis: Johnson's wave, tests/solver/test_wavy_loading.py)."""
    err = loading_branch(ratio, N, attach="reach")
    assert np.all(np.abs(err) < 0.025) and abs(err.mean()) < 0.015


@pytest.mark.parametrize("attach", ["penetration", "reach"])
def test_adhesive_load_unload_hysteresis(attach):
    """Load from first touch, unload to pull-off: at the same d the unloading force is not above
    the loading one and the area not below it (strictly somewhere), and the loop (approach at
    F = 0 below first touch, retraction through the tensile branch) encloses a positive area."""
    run = loop_run(attach)
    c, K = run["c"], LOOP_STEPS
    load = slice(1, K)                   # d_1 .. d_{K-1} on loading
    unload = slice(2 * K - 1, K, -1)     # the same d on unloading
    np.testing.assert_allclose(c["d"][unload], c["d"][load], rtol=1e-12, atol=1e-15)
    F_l, F_u = c["force"][load], c["force"][unload]
    A_l, A_u = c["area"][load], c["area"][unload]
    # Loop work: the approach carries no force below d = 0, the retraction continues to pull-off.
    d_ret, F_ret = c["d"][K:], c["force"][K:]
    loop_work = np.trapz(c["force"][:K + 1], c["d"][:K + 1]) + np.trapz(F_ret, d_ret)  # d_ret decreasing
    Fscale = run["Fadh"]
    say(f"\nload-unload loop, attach = {attach} (a_c/h = 25): F~ at d~ = {c['d'][1] / run['dc']:.3f}"
        f" loading {F_l[0] / Fscale:+.4f}, unloading {F_u[0] / Fscale:+.4f};"
        f" max (F_u - F_l)/F_adh = {np.max(F_u - F_l) / Fscale:+.2e};"
        f" area ratio unload/load {np.min(A_u / A_l):.3f} .. {np.max(A_u / A_l):.3f};"
        f" loop area {loop_work / (Fscale * run['dc']):.4f} F_adh |d_c|;"
        f" largest tension {-c['force'].min() / Fscale:.4f} F_adh")
    assert np.all(F_u <= F_l + 1e-9 * Fscale) and np.any(F_u < F_l - 1e-3 * Fscale)
    assert np.all(A_u >= A_l) and np.any(A_u > A_l)
    assert loop_work > 0.5 * Fscale * run["dc"]
    # The loop ends in pull-off: the contact is gone at the end of the path.
    assert c["contact_points"][-1] == 0 and c["force"][-1] == 0.0
    assert c["force"].min() < -0.5 * Fscale


# ---- 1 rank vs several -------------------------------------------------------------------------------

@pytest.mark.mpi
def test_ranks_give_the_same_curve():
    """The same JKR curve on COMM_WORLD (all ranks) and on COMM_SELF (one rank)."""
    N, ratio = 64, 20.0
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    opts = dict(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz",
                path=[(1.3 * ac) ** 2 / R, -2.5 * dc], steps=30)
    world = adhbem.Solver(**opts).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, **opts).solve_path()
    mpi = PETSc.COMM_WORLD.tompi4py()
    same_len = mpi.allreduce(int(len(world["d"]) == len(alone["d"])), op=_min())
    assert same_len == 1
    scale = np.max(np.abs(alone["force"]))
    rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / scale), op=_max())
    counts = mpi.allreduce(int(np.array_equal(world["contact_points"], alone["contact_points"])), op=_min())
    dsame = mpi.allreduce(int(np.array_equal(world["d"], alone["d"])), op=_min())
    pulled = mpi.allreduce(int(world["contact_points"][-1] == 0), op=_min())
    say(f"\n{PETSc.COMM_WORLD.getSize()} ranks vs 1: {len(world['d'])} states,"
        f" max |F_P - F_1| / max|F| = {rel:.2e}, contact counts identical: {bool(counts)}")
    assert dsame == 1 and counts == 1 and pulled == 1
    assert rel < 1e-10


# ---- Invariants on every state ---------------------------------------------------------------------

@pytest.mark.mpi
@pytest.mark.parametrize("attach", ["penetration", "reach", "griffith"])
def test_invariants_on_every_state(attach):
    """After every step: p >= -Sigma on the set, p = 0 and g >= 0 off it, u = d - h on it.
    Adhesive loading from first touch (the set grows by attach), unloading (it shrinks by
    detach, with tensions up to Sigma) and pull-off, one start/step at a time."""
    N, ratio = 48, 15.0
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    d0 = (1.3 * ac) ** 2 / R
    s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="adhesive",
                      attach=attach, path=[0.0, d0], steps=8)
    K = s.compliance
    mpi = PETSc.COMM_WORLD.tompi4py()
    hx, hy = s.spacing
    path = list(np.linspace(0.0, d0, 9)[1:]) + list(np.linspace(d0, -3.0 * dc, 15)[1:])
    worst = dict(tension=-np.inf, gap=np.inf, p_off=0.0, u=0.0)
    npoints = []
    scale = d0                                              # the indentation scale
    for k in range(len(path) + 1):
        st = s.start(0.0) if k == 0 else s.step(path[k - 1])
        d = st["d"]
        p = adhbem.gather(s.pressure, K)
        g = adhbem.gather(s.gap, K)
        u = adhbem.gather(s.displacement, K)
        hprof = adhbem.gather(s.profile, K)
        Sigma = adhbem.gather(s.critical_stress_field, K)
        mask = np.zeros(p.size, dtype=bool)
        mask[np.concatenate(mpi.allgather(np.asarray(s.contact_set.getIndices())))] = True
        mask = mask.reshape(p.shape)
        on, off = mask, ~mask
        npoints.append(int(mask.sum()))
        assert mask.sum() == st["contact_points"]
        assert math.isclose(st["force"], p.sum() * hx * hy, rel_tol=1e-12, abs_tol=1e-15)
        if on.any():
            worst["tension"] = max(worst["tension"], float(np.max(-p[on] / Sigma[on])))
            worst["u"] = max(worst["u"], float(np.max(np.abs(u[on] - (d - hprof[on]))) / scale))
            assert np.all(p[on] >= -Sigma[on] * (1 + 1e-9))
            assert np.all(np.abs(u[on] - (d - hprof[on])) <= 1e-8 * scale)
        if off.any():
            worst["gap"] = min(worst["gap"], float(np.min(g[off])) / scale)
            worst["p_off"] = max(worst["p_off"], float(np.max(np.abs(p[off]))))
            assert np.all(p[off] == 0.0)
            assert np.all(g[off] >= -1e-12 * scale)
            np.testing.assert_allclose(g[off], hprof[off] - d + u[off], rtol=0, atol=1e-13 * scale)
    say(f"\ninvariants, attach = {attach}, over {len(npoints)} states (points {npoints}): largest tension/Sigma on the set"
        f" {worst['tension']:.6f}, smallest gap off the set {worst['gap']:.3e} d0,"
        f" largest |p| off the set {worst['p_off']:.1e}, largest |u - (d - h)| on the set {worst['u']:.1e} d0")
    # The path exercised attach, detach with tension near Sigma, and pull-off.
    assert npoints[8] > npoints[0] and all(b >= a for a, b in zip(npoints[:8], npoints[1:9]))
    assert worst["tension"] > 0.5
    assert npoints[-1] == 0


# ---- Periodic boundary (smoke) ----------------------------------------------------------------------

def test_periodic_sphere_smoke():
    N = 64
    h = 1.0 / N
    s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=0.0, radius=R, boundary="periodic",
                      start="hertz", path=[(8 * h) ** 2 / R, (14 * h) ** 2 / R], steps=6)
    c = s.solve_path()
    say(f"\nperiodic sphere: d = {c['d'].round(4)}, F = {c['force'].round(5)}")
    assert np.all(np.isfinite(c["force"]))
    assert np.all(c["force"] > 0)
    assert np.all(np.diff(c["force"]) > 0)
    assert np.all(np.diff(c["contact_points"]) >= 0)
