"""-adh_cascade_rtol: the solves between set updates of a step stop at a loose relative residual,
and the set is updated on their pressures; a set that stands on one is solved to the full
tolerance and tested again. The sets along the way may differ from the exact cascade's; what
counts is the error against theory and the cost (docs/developers/notebook/performance.md, the work-precision table)."""
import math

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from common import _max, _min, gamma_for, jkr_scales, radius, say

R = E = 1.0
# an adhesive rough cell, approach and retraction
# (each route below is measured against the exact cascade, -adh_cascade_local 0, and alone: the
# default route with crack-closure is local solves on the whole grid)
ROUGH = dict(n=48, size=48.0, gamma=0.004, indenter="rough", boundary="periodic", start="adhesive",
             hurst=0.8, rms_slope=0.1, seed=3, path=[0.0, 0.5, -0.3], steps=8, cascade_local=0)


def jkr_unloading(N, ratio, **options):
    """The JKR sphere unloaded from a Hertz start at 1.3 a_c to d~ = -4 (60 steps): the largest
    tension over F_adh, the RMS of F~ - JKR over the stable branch after detachment started, and
    the KSP iterations. The exact cascade unless a route is given."""
    from test_validation import D_JUMP, jkr_force
    options.setdefault("cascade_local", 0)
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    c = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz",
                      path=[(1.3 * ac) ** 2 / R, -4 * dc], steps=60, **options).solve_path()
    dn, Fn, n = c["d"] / dc, c["force"] / Fadh, c["contact_points"]
    m = (n > 0) & (n < n[0]) & (dn >= D_JUMP)
    return -Fn.min(), math.sqrt(np.mean((Fn[m] - jkr_force(dn[m])) ** 2)), int(c["ksp_iterations"].sum())


def test_loose_cascade_on_the_jkr_sphere():
    """a_c/h = 25: the largest tension and the curve as close to JKR as the exact cascade's (within
    1.25 times its error and 0.2% of F_adh), with fewer KSP iterations."""
    exact = jkr_unloading(80, 25.0)
    loose = jkr_unloading(80, 25.0, cascade_rtol=1e-3)
    say(f"\nJKR sphere a_c/h 25, exact cascade: largest tension {exact[0]:.4f} F_adh, RMS {exact[1]:.4f}, KSP {exact[2]};"
        f" -adh_cascade_rtol 1e-3: {loose[0]:.4f}, RMS {loose[1]:.4f}, KSP {loose[2]}")
    assert abs(loose[0] - 1) <= 1.25 * abs(exact[0] - 1) + 0.002
    assert loose[1] <= 1.25 * exact[1] + 0.002
    assert loose[2] < exact[2]


def assert_same_on_any_ranks(opts):
    """COMM_WORLD against COMM_SELF: the same contact counts and KSP iterations, forces to 1e-10;
    every state holds (detach_ratio <= 1)."""
    world = adhbem.Solver(**opts).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, **opts).solve_path()
    mpi = PETSc.COMM_WORLD.tompi4py()
    same = mpi.allreduce(int(np.array_equal(world["contact_points"], alone["contact_points"])
                             and np.array_equal(world["ksp_iterations"], alone["ksp_iterations"])), op=_min())
    rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / np.max(np.abs(alone["force"]))), op=_max())
    assert same == 1 and rel < 1e-10
    assert np.all(world["detach_ratio"] <= 1 + 1e-9) and world["contact_points"].max() > 0


def test_loose_cascade_under_force_control():
    """The JKR sphere's pull-off force under force control (bisected to 1e-3): as the exact
    cascade's within 0.5%."""
    ac = 25.0 / 80
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    forces = []
    for rtol in (0.0, 1e-3):
        s = adhbem.Solver(n=80, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz", control="force",
                          path=[0.5 * Fadh, -2 * Fadh], steps=20, cascade_rtol=rtol)
        s.solve_path()
        forces.append(s.pull_off_force / Fadh)
    say(f"\nforce control, pull-off / F_adh: exact cascade {forces[0]:.4f}, loose {forces[1]:.4f}")
    assert abs(forces[1] / forces[0] - 1) < 0.005


@pytest.mark.mpi
def test_loose_cascade_on_any_number_of_ranks():
    """An adhesive rough cell, approach and retraction: COMM_WORLD against COMM_SELF, the same
    contact counts and KSP iterations, forces to 1e-10; every state holds (detach_ratio <= 1)."""
    assert_same_on_any_ranks(dict(ROUGH, cascade_rtol=1e-3))


@pytest.mark.parametrize("route", [dict(cascade_rtol=1e-3), dict(cascade_local=math.inf)], ids=["loose", "local"])
def test_single_precision_loose_solves(route):
    """-adh_cascade_single: the loose solves in float transforms (and only they): those of
    -adh_cascade_rtol, and the local solves of crack-closure's default route. On the rough cell
    the same contact sets and KSP iterations as in double, the forces far within the loose
    tolerance of the double-precision route's."""
    runs = {}
    for single in (False, True):
        s = adhbem.Solver(comm=PETSc.COMM_SELF, **dict(ROUGH, **route), cascade_single=single)
        runs[single] = s.solve_path()
        info = adhbem.compliance_info(s.compliance)
        # the float transforms ran in the loose solves only (the openings' multiplies stay double)
        assert (0 < info["single_mult_count"] < info["mult_count"]) if single else info["single_mult_count"] == 0
    double, single = runs[False], runs[True]
    rel = float(np.max(np.abs(single["force"] - double["force"])) / np.max(np.abs(double["force"])))
    say(f"\nrough cell, {route} -adh_cascade_single: forces {rel:.2e} apart from double precision's")
    assert np.array_equal(single["contact_points"], double["contact_points"])
    assert np.array_equal(single["ksp_iterations"], double["ksp_iterations"])
    assert rel < 1e-6


def test_single_precision_loose_solves_on_the_jkr_sphere():
    """a_c/h = 25: with -adh_cascade_single the largest tension and the curve within 1e-4 F_adh of
    the double-precision loose cascade's."""
    loose = jkr_unloading(80, 25.0, cascade_rtol=1e-3)
    single = jkr_unloading(80, 25.0, cascade_rtol=1e-3, cascade_single=True)
    say(f"\nJKR sphere a_c/h 25, -adh_cascade_rtol 1e-3: largest tension {loose[0]:.5f} F_adh, RMS {loose[1]:.5f};"
        f" with -adh_cascade_single: {single[0]:.5f}, RMS {single[1]:.5f}")
    assert abs(single[0] - loose[0]) < 1e-4 and abs(single[1] - loose[1]) < 1e-4


@pytest.mark.mpi
@pytest.mark.parametrize("route", [dict(cascade_rtol=1e-3), dict(cascade_local=math.inf)], ids=["loose", "local"])
def test_single_precision_loose_solves_on_any_number_of_ranks(route):
    """As test_loose_cascade_on_any_number_of_ranks, in single precision: the float transforms of
    one and two ranks round differently, and the full solve that ends each step takes that out."""
    assert_same_on_any_ranks(dict(ROUGH, cascade_single=True, **route))


@pytest.mark.parametrize("value", ["-0.1", "1"])
def test_bad_cascade_rtol_is_refused(tmp_path, value):
    import subprocess
    from adhbem_build import EXE
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial")
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gamma", "1e-3", "-adh_path", "0.01,0", "-adh_cascade_rtol", value,
                        "-adh_output", str(tmp_path / "x.h5")], capture_output=True, text=True)
    assert r.returncode != 0 and "-adh_cascade_rtol must lie in [0, 1)" in r.stderr + r.stdout
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


# -adh_cascade_apart D: points may join in a set update that lets others go, D grid spacings away
# from them (docs/developers/notebook/performance.md: the work-precision table and the cost as the cell grows).


def test_apart_cascade_on_the_jkr_sphere():
    """a_c/h = 25: the largest tension and the curve as close to JKR as the exact cascade's (within
    1.25 times its error and 0.2% of F_adh)."""
    exact = jkr_unloading(80, 25.0)
    apart = jkr_unloading(80, 25.0, cascade_apart=8)
    say(f"\nJKR sphere a_c/h 25, exact cascade: largest tension {exact[0]:.4f} F_adh, RMS {exact[1]:.4f}, KSP {exact[2]};"
        f" -adh_cascade_apart 8: {apart[0]:.4f}, RMS {apart[1]:.4f}, KSP {apart[2]}")
    assert abs(apart[0] - 1) <= 1.25 * abs(exact[0] - 1) + 0.002
    assert apart[1] <= 1.25 * exact[1] + 0.002


def test_apart_cascade_on_a_rough_cell():
    """Joins beside the updates that let points go take fewer set updates than the exact cascade;
    with D beyond the cell (every point near any point let go) it is the exact cascade, state for
    state: the marks reach across the periodic cell's edges."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial")
    exact = adhbem.Solver(comm=PETSc.COMM_SELF, **ROUGH).solve_path()
    apart = adhbem.Solver(comm=PETSc.COMM_SELF, cascade_apart=4, **ROUGH).solve_path()
    wide = adhbem.Solver(comm=PETSc.COMM_SELF, cascade_apart=24, **ROUGH).solve_path()
    say(f"\nrough 48^2: set updates exact {int(exact['outer_iterations'].sum())}, apart 4 {int(apart['outer_iterations'].sum())},"
        f" apart 24 {int(wide['outer_iterations'].sum())}")
    assert apart["outer_iterations"].sum() < exact["outer_iterations"].sum()
    for key in ("contact_points", "outer_iterations", "ksp_iterations"):
        np.testing.assert_array_equal(wide[key], exact[key], err_msg=key)
    np.testing.assert_allclose(wide["force"], exact["force"], rtol=0, atol=1e-12 * np.abs(exact["force"]).max())


@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("D", [4, 20])
def test_apart_cascade_on_any_number_of_ranks(D):
    """COMM_WORLD against COMM_SELF, the same contact counts and KSP iterations, forces to 1e-10;
    D = 20 reaches past the neighbouring rank's rows on 3 ranks (16 rows each) and wraps."""
    assert_same_on_any_ranks(dict(ROUGH, cascade_apart=D))


@pytest.mark.parametrize("args, message", [
    (["-adh_cascade_apart", "-1"], "-adh_cascade_apart must lie in [0, 64]"),
    (["-adh_cascade_apart", "65"], "-adh_cascade_apart must lie in [0, 64]"),
    (["-adh_cascade_apart", "8", "-adh_control", "force"], "-adh_cascade_apart: displacement control only"),
    (["-adh_cascade_local", "-1"], "-adh_cascade_local must be >= 0"),
    (["-adh_cascade_local", "nan"], "-adh_cascade_local: expected a real number, got 'nan' (NaN, not a value)"),
    (["-adh_cascade_local", "8", "-adh_cascade_local_rtol", "0"], "-adh_cascade_local_rtol must lie in (0, 1)"),
    (["-adh_cascade_local", "8", "-adh_control", "force"], "-adh_cascade_local: displacement control only"),
    (["-adh_cascade_local", "3", "-adh_local_ksp_rtl", "1e-3"], "did you mean -adh_local_ksp_rtol?"),
    (["-adh_cascade_local", "3", "-adh_local_ksp_guess_type", "fischer"], "-adh_local_ksp_guess_type: PETSc's initial guesses"),
])
def test_bad_cascade_options_are_refused(tmp_path, args, message):
    import subprocess
    from adhbem_build import EXE
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial")
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gamma", "1e-3", "-adh_path", "0.01,0", *args,
                        "-adh_output", str(tmp_path / "x.h5")], capture_output=True, text=True)
    assert r.returncode != 0 and message in r.stderr + r.stdout
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


def test_apart_cascade_loading_branch_is_jkr():
    """The JKR sphere loaded from first touch (the jump-in, then 12 steps), where joins and
    detachments meet, at a_c/h 25: within the default's bounds (tests/solver/test_validation.py;
    measured a/a_JKR 1.2% low on average, at most 1.9%, against the exact cascade's 1.5% and 2.8%;
    at a_c/h 50, not run here for its time, 0.6% and 1.3% against 0.6% and 1.1%)."""
    from test_validation import loading_branch
    coarse = loading_branch(25.0, 100, cascade_apart=16, cascade_local=0)
    assert np.all(np.abs(coarse) < 0.03) and abs(coarse.mean()) < 0.02


# -adh_cascade_local F: after a set update lets points go, local solves within F times the
# smallest asperities' JKR radius of them (W grid spacings), until one lets nothing go; then the
# whole set again (docs/developers/notebook/performance.md). ROUGH's estimated a_c is 1.428 spacings; the F below lie
# well inside the intervals that give the widths named.


def test_local_cascade_with_a_window_over_the_whole_set_is_exact():
    """With a window beyond the cell (F = inf: the whole grid; and F = 100, capped at the cell's 48
    spacings, the same) and local solves to 1e-10
    every local solve is a solve of the whole set, so the states are the exact cascade's, state for
    state (the marks reach across the periodic cell's edges), in fewer solves of the whole set;
    W = 4 (F = 2.5) takes fewer FFT pairs."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial")
    exact = adhbem.Solver(comm=PETSc.COMM_SELF, **ROUGH).solve_path()
    whole = adhbem.Solver(comm=PETSc.COMM_SELF, **dict(ROUGH, cascade_local=float("inf"), cascade_local_rtol=1e-10)).solve_path()
    capped = adhbem.Solver(comm=PETSc.COMM_SELF, **dict(ROUGH, cascade_local=100.0, cascade_local_rtol=1e-10)).solve_path()
    local = adhbem.Solver(comm=PETSc.COMM_SELF, **dict(ROUGH, cascade_local=2.5)).solve_path()
    say(f"\nrough 48^2: set updates exact {int(exact['outer_iterations'].sum())}, whole window {int(whole['outer_iterations'].sum())},"
        f" W = 4 {int(local['outer_iterations'].sum())}; FFT pairs {int(exact['fft_pairs'].sum())},"
        f" {int(whole['fft_pairs'].sum())}, {int(local['fft_pairs'].sum())}")
    np.testing.assert_array_equal(whole["contact_points"], exact["contact_points"])
    np.testing.assert_array_equal(capped["force"], whole["force"])
    np.testing.assert_allclose(whole["force"], exact["force"], rtol=0, atol=1e-9 * np.abs(exact["force"]).max())
    assert whole["outer_iterations"].sum() < exact["outer_iterations"].sum()
    assert local["outer_iterations"].sum() < exact["outer_iterations"].sum()
    assert local["fft_pairs"].sum() < exact["fft_pairs"].sum()


@pytest.mark.parametrize("apart", [0, 3])
def test_local_cascade_states_are_equilibria(apart):
    """Every state recorded with W = 2 (F = 1.4 of a_c = 1.34 spacings), alone and after the
    joins of -adh_cascade_apart 3, is one the exact cascade's rules accept: the pressure on the
    set solves the dense K_CC p = d - h_C, nothing on the set is beyond the critical tension, and
    no point off the set penetrates (pohrt-popov, penetration: the rules without averages)."""
    from common import assembled
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial")
    opts = dict(ROUGH, n=24, size=24.0, path=[0.0, 0.3, -0.3], criterion="pohrt-popov", attach="penetration", cascade_local=1.4,
                cascade_apart=apart)
    s = adhbem.Solver(comm=PETSc.COMM_SELF, **opts)
    K = None
    detached = 0
    for state in s.iterate_path():
        if K is None:
            K = assembled(s.compliance)
            Sigma = s.critical_stress
        p = s.pressure.getArray().copy()
        h = s.profile.getArray().copy()
        C = np.zeros(p.size, bool)
        C[s.contact_set.getIndices()] = True
        if not C.any():
            continue
        pC = np.linalg.solve(K[np.ix_(C, C)], state["d"] - h[C])
        assert np.max(np.abs(p[C] - pC)) <= 1e-7 * np.max(np.abs(pC))
        assert np.all(p[~C] == 0)
        assert np.all(p[C] >= -Sigma * (1 + 1e-9))
        assert np.all((h - state["d"] + K @ p)[~C] >= -1e-9 * np.abs(h).max())
        detached += int(np.any(p[C] < -0.5 * Sigma))
    assert detached > 0  # the path does carry tension near the limit
    exact = adhbem.Solver(comm=PETSc.COMM_SELF, **dict(opts, cascade_local=0)).solve_path()
    assert s.curve()["outer_iterations"].sum() < exact["outer_iterations"].sum()  # local solves did take updates


def test_local_cascade_on_the_jkr_sphere():
    """a_c/h = 25, with F = inf (the whole grid, crack-closure's default), 3 and 1 (W = 75 and 25):
    the largest tension and the curve as close to JKR as the exact cascade's (within 1.25 times its
    error and 0.2% of F_adh), in fewer KSP iterations (the local solves did run)."""
    exact = jkr_unloading(80, 25.0)
    for F in (math.inf, 3.0, 1.0):
        local = jkr_unloading(80, 25.0, cascade_local=F)
        say(f"\nJKR sphere a_c/h 25, exact cascade: largest tension {exact[0]:.4f} F_adh, RMS {exact[1]:.4f}, KSP {exact[2]};"
            f" -adh_cascade_local {F}: {local[0]:.4f}, RMS {local[1]:.4f}, KSP {local[2]}")
        assert abs(local[0] - 1) <= 1.25 * abs(exact[0] - 1) + 0.002
        assert local[1] <= 1.25 * exact[1] + 0.002
        assert local[2] < exact[2]


@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("F, D", [(math.inf, 0), (2.5, 0), (13.7, 0), (2.5, 8), (13.7, 4)])
def test_local_cascade_on_any_number_of_ranks(F, D):
    """COMM_WORLD against COMM_SELF, the same contact counts and KSP iterations, forces to 1e-10
    (F = inf: crack-closure's default route);
    W = 20 (F = 13.7) reaches past the neighbouring rank's rows on 3 ranks (16 rows each) and wraps;
    with -adh_cascade_apart D the first window widens D's marks (by none where D = 8 > W = 4)."""
    assert_same_on_any_ranks(dict(ROUGH, cascade_local=F, cascade_apart=D))


@pytest.mark.mpi
@pytest.mark.ranks3
def test_local_cascade_on_any_number_of_ranks_free_boundary():
    """The JKR sphere on the free boundary (its bounding-box window: the local solves scatter onto
    it) with a window of half a JKR radius: COMM_WORLD against COMM_SELF as above."""
    ac = 12.0 / 48
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    assert_same_on_any_ranks(dict(n=48, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz",
                                  path=[(1.3 * ac) ** 2 / R, -4 * dc], steps=20, cascade_local=0.5))
