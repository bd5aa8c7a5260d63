"""Finite-range adhesion (-adh_criterion dugdale, Maugis' cohesive zone) against Maugis' closed
form for the sphere (adhbem.theory, Johnson & Greenwood's notation), by both routes (the energy
minimisation of the smoothed law, the default, and the fixed point of set updates on the sharp
law): the pull-off force near DMT and between, converging with the grid as the cohesive zone
spans more elements, the same under force and under displacement control, the contact radius
along the path, 1 rank equal to 2 and 3; the results file's attributes, a restart that changes s0
or the route refused, bad input refused."""
import math
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem.theory import maugis_pulloff, maugis_scales, maugis_sphere, tabor_lambda
from adhbem_build import EXE
from common import _max, _min, say

GAMMA = 0.004655  # E* = R = 1: the pull-off contact radius about 0.2 at lambda = 1
FSCALE, ASCALE, DSCALE = maugis_scales(GAMMA)  # F = P FSCALE, a = A ASCALE, d = D DSCALE


def s0_for(lam):
    return lam / tabor_lambda(1.0, GAMMA)


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process or compares with one")


ROUTES = ("minimize", "fixed-point")  # the default first


def run(n, lam, control="displacement", path=(0.04, -0.06), steps=100, comm=None, route=None, **extra):
    """Maugis' sphere on the free boundary; route None: the default."""
    s = adhbem.Solver(n=n, gamma=GAMMA, criterion="dugdale", dugdale_stress=s0_for(lam), control=control,
                      path=list(path), steps=steps, **({"comm": comm} if comm else {}),
                      **({"dugdale_route": route} if route else {}), **extra)
    with s:
        return s.solve_path()


def largest_tension(curve):
    return -float(np.min(curve["force"]))


def test_fixed_point_pulloff_converges_to_maugis_at_lambda_1():
    """lambda = 1 (pull-off 1.601 pi dgamma R), the sharp law's fixed point: the error halves with
    the spacing (the zone spans about 6 and 12 elements at pull-off), and the two grids
    extrapolated (first order) land within 1%."""
    serial_only()
    P, _, _ = maugis_pulloff(1.0)
    exact = -P * FSCALE
    F = {n: largest_tension(run(n, 1.0, route="fixed-point")) for n in (64, 128)}
    err = {n: F[n] / exact - 1 for n in F}
    extrapolated = 2 * F[128] - F[64]
    say(f"\ndugdale lambda 1: pull-off {F[64]:.6g} (64), {F[128]:.6g} (128), extrapolated {extrapolated:.6g}, "
        f"Maugis {exact:.6g}; errors {err[64]:+.2%}, {err[128]:+.2%}")
    assert 0 < err[128] < 0.6 * err[64] and err[128] < 0.04
    assert abs(extrapolated / exact - 1) < 0.01


@pytest.mark.parametrize("route", ROUTES)
def test_resolution_reports_the_zone_width(route):
    """The resolution report gives the zone's width at the largest tension (an annulus around the
    contact's disk) against Maugis' (c - a) at pull-off, within a grid spacing, and its verdict:
    under 10 spacings the pull-off force depends on the grid."""
    serial_only()
    lam = 1.0
    _, A, _ = maugis_pulloff(lam)
    _, _, m = maugis_sphere(lam, [A])
    for n in (64, 128):
        with adhbem.Solver(n=n, gamma=GAMMA, criterion="dugdale", dugdale_stress=s0_for(lam), path=[0.04, -0.06],
                           steps=100, progress=False, dugdale_route=route) as s:
            s.solve_path()
            r = s.resolution
        exact = (m[0] - 1) * A * ASCALE * n
        say(f"\ndugdale lambda 1 ({route}), {n}^2: zone {r['cohesive_width']:.2f} grid spacings wide ({r['cohesive_elements']:.0f} "
            f"elements), Maugis {exact:.2f}; resolved {r['resolved']}")
        assert abs(r["cohesive_width"] - exact) < 1.0 and r["cohesive_elements"] > 0
        assert r["resolved"] == (exact >= 10)



@pytest.mark.parametrize("route", ROUTES)
def test_zone_width_of_any_profile_from_the_perimeter(route):
    """The sphere given as an array (a profile like a measured map's): its zone's width is the
    zone's area over the mean of its inner and outer edges (the contact's perimeter and the
    zone's), which matches Maugis' (c - a) as the annulus does, within a grid spacing."""
    serial_only()
    lam, n = 1.0, 64
    _, A, _ = maugis_pulloff(lam)
    _, _, m = maugis_sphere(lam, [A])
    exact = (m[0] - 1) * A * ASCALE * n
    h = adhbem.Solver(n=n).profile_array()
    with adhbem.Solver(n=n, boundary="free", topography=h, topography_kind="gap", gamma=GAMMA, criterion="dugdale",
                       dugdale_stress=s0_for(lam), path=[0.04, -0.06], steps=100, progress=False, dugdale_route=route) as s:
        c = s.solve_path()
        r = s.resolution
    st = r["state"]
    say(f"\ndugdale lambda 1 ({route}), {n}^2, the sphere as an array: zone {r['cohesive_width']:.2f} grid spacings wide "
        f"(area {c['cohesive_area'][st]:.4g} over edges {c['contact_perimeter'][st]:.4g}, {c['cohesive_perimeter'][st]:.4g}), "
        f"Maugis {exact:.2f}")
    edges = (c["contact_perimeter"][st] + c["cohesive_perimeter"][st]) / 2
    assert r["cohesive_width"] == pytest.approx(c["cohesive_area"][st] / edges * n, rel=1e-12)
    assert abs(r["cohesive_width"] - exact) < 1.0
    assert r["resolved"] is False and "zone" in r["unresolved"]


@pytest.mark.parametrize("route, tolerance", [("minimize", 0.002), ("fixed-point", 0.015)])
def test_pulloff_near_dmt(route, tolerance):
    """lambda = 0.3, towards DMT (pull-off 1.816 pi dgamma R, 2 as lambda -> 0): the wide zone is
    resolved already at 64^2 (the zone 22 elements wide; the minimisation within 0.2%, the fixed
    point within 1.5%)."""
    serial_only()
    P, _, _ = maugis_pulloff(0.3)
    F = largest_tension(run(64, 0.3, path=(0.04, -0.08), steps=120, route=route))
    say(f"\ndugdale lambda 0.3 ({route}): pull-off {F:.6g}, Maugis {-P * FSCALE:.6g} ({F / (-P * FSCALE) - 1:+.2%})")
    assert abs(F / (-P * FSCALE) - 1) < tolerance


def test_a_wide_zone_around_a_small_contact_is_resolved():
    """Near DMT (lambda 0.3, 64^2) the contact at pull-off is a small disk whose zone is 22 elements
    wide: the contact patch carries the contact's tension (100% measured), which would make a zero-range
    criterion's pull-off depend on the grid, but here the zone carries the tension and its edge is
    not singular, so the report says the grid resolves it (the pull-off is within 0.2%:
    test_pulloff_near_dmt)."""
    serial_only()
    with adhbem.Solver(n=64, gamma=GAMMA, criterion="dugdale", dugdale_stress=s0_for(0.3), path=[0.04, -0.08],
                       steps=120, progress=False) as s:
        s.solve_path()
        r = s.resolution
    say(f"\ndugdale lambda 0.3, 64^2: zone {r['cohesive_width']:.1f} spacings, {r['small_patch_tension']:.0%} of the contact's "
        f"tension on small patches; resolved {r['resolved']}")
    assert r["small_patch_tension"] > 0.9 and r["cohesive_width"] > 10
    assert r["resolved"] is True and not r["unresolved"]


def test_a_zone_narrower_than_an_element_is_not_resolved():
    """lambda 10 on 32^2 by the minimisation: the zone at pull-off is about a tenth of an element,
    so no point lies off the contact within the range and the curve counts no zone; the report
    must not take that for a resolved zone (the contact's own patch rule does not apply to a
    finite-range criterion)."""
    serial_only()
    route = "minimize"
    with adhbem.Solver(n=32, gamma=GAMMA, criterion="dugdale", dugdale_stress=s0_for(10.0), dugdale_route=route,
                       path=[0.04, -0.06], steps=40, progress=False) as s:
        c = s.solve_path()
        r = s.resolution
    k = r["state"]
    say(f"\ndugdale lambda 10 ({route}), 32^2: zone area {c['cohesive_area'][k]:.3g} at the largest tension; unresolved {r['unresolved']}")
    assert c["cohesive_area"][k] == 0 and c["force"][k] < 0
    assert r["resolved"] is False and "zone" in r["unresolved"]


@pytest.mark.parametrize("route", ROUTES)
def test_force_control_pulls_off_at_the_same_tension(route):
    """Under force control the contact comes off at the largest tension (bisected to
    -adh_pulloff_rtol), the same as the largest one displacement control passes through."""
    serial_only()
    disp = largest_tension(run(64, 1.0, route=route))
    force = run(64, 1.0, control="force", path=(0.02, -0.03), steps=50, route=route)
    F = largest_tension(force)
    say(f"\ndugdale lambda 1 ({route}), force control: pull-off {F:.6g} against {disp:.6g} under displacement control")
    assert force["pulled_off"][-1] == 1
    assert abs(F / disp - 1) < 0.005


@pytest.mark.parametrize("lam, through", [(0.5, (-0.019, -0.0235)), (1.0, (-0.0235, -0.0265))])
def test_force_control_finds_the_branch_largest_tension(lam, through):
    """The minimisation under force control on the free boundary pulls off at the largest tension
    of the branch, to -adh_pulloff_rtol: against a displacement path through the top of the branch
    in steps of 7.5e-5 and 5e-5 (a fortieth of the law's range), on coarse grids (a zone of 3
    elements, 22^2 and 38^2) whose branch is kinked by the zone's edge crossing elements, where the
    walk's trials alone (moves of 0.02 of the range) miss its top by 0.13% (lambda 0.5), and where
    the states the walk's short moves reach near the top carry less than the displacement path's
    (lambda 1: 3.7e-4 low while a walk's first move was not aimed by the last walk's slope)."""
    serial_only()
    rtol = 1e-4
    P, A, _ = maugis_pulloff(lam)
    m = float(maugis_sphere(lam, [A])[2][0])
    F, a, zone = -P * FSCALE, A * ASCALE, (m - 1) * A * ASCALE  # F: the pull-off, > 0
    n = 2 * math.ceil(4.0 * m * a / (zone / 3) / 2)
    size = n * zone / 3
    opts = dict(n=n, size=size, gamma=GAMMA, criterion="dugdale", dugdale_stress=s0_for(lam))
    with adhbem.Solver(path=[0.5 * a * a, *through], steps=60, **opts) as s:
        top = largest_tension(s.solve_path())
    with adhbem.Solver(control="force", path=[0.5 * F, -1.5 * F], steps=40, pulloff_rtol=rtol, **opts) as s:
        force = s.solve_path()
    pulloff = largest_tension(force)
    say(f"\ndugdale lambda {lam} on {n}^2, force control: pull-off {pulloff:.7g}, the branch's top {top:.7g} "
        f"({pulloff / top - 1:+.2e})")
    assert force["pulled_off"][-1] == 1
    assert abs(pulloff / top - 1) < 2 * rtol


def path_errors(n, route):
    """The worst contact radius error (grid spacings) and the worst and mean force errors (over the
    pull-off force) against Maugis' a(d) and F(d), from a Hertz preload at lambda = 1, over the
    states whose contact is larger than the zone before Maugis' turning point."""
    c = run(n, 1.0, steps=50, route=route)
    A = np.linspace(0.3, 2.2, 400)
    P, D, _ = maugis_sphere(1.0, A)
    stable = A >= A[np.argmin(D)]  # the branch displacement control follows
    pulloff = -maugis_pulloff(1.0)[0] * FSCALE
    ea, eF = [], []
    for d, area, F in list(zip(c["d"], c["area"], c["force"]))[1:]:  # the first state is the adhesion-free start
        a = math.sqrt(area / math.pi)
        if a < 0.1 or d < D.min() * DSCALE:
            continue
        ea.append(abs(a - float(np.interp(d / DSCALE, D[stable], A[stable])) * ASCALE) * n)
        eF.append(abs(F - float(np.interp(d / DSCALE, D[stable], P[stable])) * FSCALE) / pulloff)
    return len(ea), max(ea), max(eF), float(np.mean(eF))


@pytest.mark.parametrize("route, radius, ratio, worst, mean", [("minimize", 0.3, 0.5, 0.002, 0.0006),
                                                            ("fixed-point", 1.5, 0.6, math.inf, 0.03)])
def test_contact_radius_and_force_along_the_path(route, radius, ratio, worst, mean):
    """The contact radius sqrt(area/pi) and the force against Maugis' a(d) and F(d) while the sphere
    is pulled from a Hertz preload (lambda = 1), on 64^2 and 128^2. The minimisation (the default):
    the radius within 0.3 grid spacings, the force's error falling at least as the spacing, to 0.2%
    of the pull-off force at 128^2 at worst and 0.06% on average. The sharp law's fixed point: the
    radius within 1.5 grid spacings, the force's error falling at about first order (the zone's edge
    is where an element's centre is within the range), to 3% of the pull-off force on average."""
    serial_only()
    errors = {n: path_errors(n, route) for n in (64, 128)}
    for n, (count, ea, w, m) in errors.items():
        say(f"\ndugdale lambda 1 ({route}), {n}^2, {count} states: contact radius within {ea:.2f} grid spacings of Maugis' a(d); "
            f"force error at most {w:.2%}, on average {m:.2%} of the pull-off force")
    (n64, a64, w64, m64), (n128, a128, w128, m128) = errors[64], errors[128]
    assert n64 > 30 and n128 > 30
    assert a64 < radius and a128 < radius
    assert w128 < ratio * w64 and m128 < ratio * m64 and w128 < worst and m128 < mean


@pytest.mark.parametrize("route", ROUTES)
def test_gamma_field(route):
    """A work-of-adhesion field: a constant one is the scalar to rounding; with dgamma halved on the
    half x > 0 the range halves there (s0 the same) and the pull-off force lies between the two
    uniform ones'."""
    serial_only()
    n, lam = 48, 1.0
    x = (np.arange(n) - n / 2 + 0.5) / n
    X, _ = np.meshgrid(x, x)
    scalar = run(n, lam, steps=40, route=route)
    same = run(n, lam, steps=40, gamma_field=np.full((n, n), GAMMA), route=route)
    assert np.allclose(same["force"], scalar["force"], rtol=0, atol=1e-12 * np.abs(scalar["force"]).max())
    assert np.array_equal(same["contact_points"], scalar["contact_points"])
    half = largest_tension(run(n, lam, steps=40, gamma_field=np.where(X > 0, GAMMA / 2, GAMMA), route=route))
    with adhbem.Solver(n=n, gamma=GAMMA / 2, criterion="dugdale", dugdale_stress=s0_for(lam), path=[0.04, -0.06],
                       steps=40, dugdale_route=route) as s:
        weaker = largest_tension(s.solve_path())
    say(f"\ndugdale ({route}) with a dgamma field: pull-off {half:.6g} between {weaker:.6g} (dgamma/2) and {largest_tension(scalar):.6g}")
    assert weaker < half < largest_tension(scalar)


@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("route", ROUTES)
def test_same_curve_on_any_number_of_ranks(route):
    """COMM_WORLD against COMM_SELF under both controls: the fixed point the same contact counts and
    edges (the contact's and its zone's) and forces to 1e-10; the minimisation, whose iterates carry
    the ranks' rounding to its tolerance (1e-8, as exponential's and lj93's), the same contact
    counts and forces to 1e-8."""
    mpi = PETSc.COMM_WORLD.tompi4py()
    keys, tol = (("contact_points", "contact_perimeter", "cohesive_perimeter"), 1e-10) if route == "fixed-point" else (("contact_points",), 1e-8)
    for control, path in (("displacement", (0.03, -0.05)), ("force", (0.01, -0.03))):
        world = run(32, 0.5, control=control, path=path, steps=12, route=route)
        alone = run(32, 0.5, control=control, path=path, steps=12, comm=PETSc.COMM_SELF, route=route)
        same = mpi.allreduce(int(len(world["d"]) == len(alone["d"]) and all(np.array_equal(world[k], alone[k]) for k in keys)), op=_min())
        rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / np.max(np.abs(alone["force"]))), op=_max())
        say(f"\ndugdale ({route}), {control}, {PETSc.COMM_WORLD.getSize()} ranks vs 1: max |dF|/max|F| {rel:.1e}")
        assert same == 1 and rel < tol
        assert np.min(alone["force"]) < 0


@pytest.mark.parametrize("route", (None,) + ROUTES[1:], ids=["default", "fixed-point"])
def test_results_attributes_and_restart_refusal(tmp_path, route):
    """The results file records s0, the range, the route and the sphere's lambda (and on the
    minimisation its Newton direction and trust region), and its contact
    field the cohesive zone (2) beside the contact (1), whose tension is s0 (the minimisation's
    smoothed law: s0 down to s0/2 at the range); a restart with another s0 is refused, naming
    -adh_dugdale_stress, and one with the same goes on."""
    serial_only()
    base = [EXE, "-adh_n", "32", "-adh_gamma", str(GAMMA), "-adh_criterion", "dugdale", "-adh_path", "0.03,-0.05",
            "-adh_steps", "6"] + (["-adh_dugdale_route", route] if route else [])
    s0 = s0_for(1.0)
    ck = tmp_path / "ck.h5"
    r = subprocess.run(base + ["-adh_dugdale_stress", str(s0), "-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5"),
                               "-adh_fields", "contact,pressure,gap"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(tmp_path / "a.h5", "r") as f:
        # the contact field: 1 in contact, 2 in the cohesive zone, whose tension is s0 in the pressure field
        contact, pressure = f["fields/contact"][()], f["fields/pressure"][()]
        cells = 32 * 32 / float(f.attrs["Lx"] * f.attrs["Ly"])
        for frame, row in enumerate(f["fields/state"][()].astype(int)):
            assert (contact[frame] == 1).sum() == f["curve/contact_points"][row]
            assert (contact[frame] == 2).sum() == round(f["curve/cohesive_area"][row] * cells)
            zone = pressure[frame][contact[frame] == 2]
            if route == "fixed-point":
                assert np.allclose(zone, -s0, rtol=1e-12)
            else:
                # the law's traction, s0 down to s0/2 at the range, to the residual gradient: a
                # point's is below the projected gradient's norm, -adh_minimize_rtol (1e-8) of the field's
                residual = 1e-8 * np.linalg.norm(pressure[frame])
                assert np.all(zone >= -s0 - residual) and np.all(zone <= -s0 / 2 + residual)
            free = pressure[frame][contact[frame] == 0]
            if route == "fixed-point":
                assert np.all(free == 0)
            else:  # the smoothed law's tail beyond the range (below s0/2), and none beyond its support
                assert np.all(free >= -s0 / 2 - residual) and np.all(free <= residual)
                beyond = f["fields/gap"][()][frame] >= 1.2 * GAMMA / s0 * (1 + 1e-9)
                assert beyond.any() and np.all(pressure[frame][beyond] == 0)
        # the first state, the Hertz start, has no adhesion: no zone, no traction off the contact
        assert f["curve/cohesive_area"][0] == 0 and f["curve/cohesive_force"][0] == 0
        assert (contact == 2).any()
        assert f.attrs["criterion"] == "dugdale" and f.attrs["attach"] == "penetration"
        assert float(f.attrs["dugdale_stress"]) == pytest.approx(s0, rel=1e-12)
        assert float(f.attrs["dugdale_range"]) == pytest.approx(GAMMA / s0, rel=1e-12)
        route_attr = f.attrs["dugdale_route"]
        assert (route_attr.decode() if isinstance(route_attr, bytes) else route_attr) == (route or "minimize")
        assert float(f.attrs["tabor_lambda"]) == pytest.approx(1.0, rel=1e-9)
        assert float(f.attrs["asperity_tabor"]) == pytest.approx(1.0, rel=1e-9)  # the resolution report's, of the sphere
        if route is None:  # the minimisation's Newton steps and their trust region (the default, 2)
            direction = f.attrs["minimize_direction"]
            assert (direction.decode() if isinstance(direction, bytes) else direction) == "newton"
            assert float(f.attrs["minimize_trust_region"]) == 2.0
        else:
            assert "minimize_trust_region" not in f.attrs
    r = subprocess.run(base + ["-adh_dugdale_stress", str(2 * s0), "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and "-adh_dugdale_stress" in r.stderr, r.stderr[-2000:]
    r = subprocess.run(base + ["-adh_dugdale_stress", str(s0), "-adh_restart", str(ck), "-adh_output", str(tmp_path / "c.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]


def test_an_unresolved_zone_ends_its_updates(tmp_path):
    """The fixed point: where the zone is narrower than an element (s0 above Sigma: lambda 2 on bench convergence's
    resolved surface at 64^2) its points can switch in and out of the zone for ever; a point that
    has left it three times in a step stays out, so each step ends (it ran into -adh_max_outer
    before), and -info says how many points were kept out."""
    serial_only()
    import importlib.util
    from common import ROOT
    spec = importlib.util.spec_from_file_location("bench_convergence", f"{ROOT}/bench/convergence.py")
    convergence = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(convergence)
    surface, gamma, _ = convergence.configuration("resolved", 64)
    z = surface.heights(64)
    h = np.ascontiguousarray(z.max() - z)
    np.save(tmp_path / "h.npy", h)
    s0 = 2.0 / tabor_lambda(1.0, gamma, surface.tip_radius())  # lambda 2 at the asperities' tips
    r = subprocess.run([EXE, "-adh_n", "64", "-adh_size", "64", "-adh_boundary", "periodic", "-adh_indenter", "file",
                        "-adh_topography", str(tmp_path / "h.npy"), "-adh_topography_kind", "gap", "-adh_gamma", repr(gamma),
                        "-adh_criterion", "dugdale", "-adh_dugdale_stress", repr(s0), "-adh_dugdale_route", "fixed-point", "-adh_start", "adhesive",
                        "-adh_path", f"0,{float(np.quantile(h, 0.25))!r}", "-adh_steps", "8", "-adh_max_outer", "1000",
                        "-info", ":adhsolver"], capture_output=True, text=True, timeout=120)
    kept = r.stdout.count("kept out of the zone")
    say(f"\ndugdale, unresolved zone on a rough cell: {kept} set updates ended with points kept out")
    assert r.returncode == 0, r.stderr[-2000:]
    assert kept > 0


@pytest.mark.parametrize("args, says", [
    ([], "-adh_criterion dugdale needs the cohesive stress: give -adh_dugdale_stress"),
    (["-adh_dugdale_stress", "-1"], "-adh_dugdale_stress must be > 0"),
    (["-adh_dugdale_stress", "0.1", "-adh_attach", "reach"], "-adh_attach reach does not apply to -adh_criterion dugdale"),
    (["-adh_dugdale_stress", "0.1", "-adh_critical_stress", "0.5"], "-adh_critical_stress does not apply"),
    (["-adh_dugdale_stress", "0.1", "-adh_cascade_apart", "4"], "-adh_cascade_apart does not apply"),
    (["-adh_dugdale_stress", "0.1", "-adh_cascade_local", "3"], "-adh_cascade_local does not apply"),
])
def test_bad_input_is_one_line(args, says):
    serial_only()
    r = subprocess.run([EXE, "-adh_n", "16", "-adh_gamma", "0.001", "-adh_criterion", "dugdale", "-adh_path", "0.01,0",
                        "-adh_steps", "1", *args], capture_output=True, text=True, timeout=60)
    assert r.returncode != 0 and says in r.stderr, r.stderr[-2000:]
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr


def test_default_route_is_closer_to_maugis():
    """The default route, -adh_dugdale_route minimize (the law's drop smoothed over 0.2 of the range,
    each state a minimum of the energy), lands within 0.5% of Maugis' pull-off at lambda 1 on 64^2
    (the zone 6 elements wide), where the fixed point of set updates is several times further off."""
    serial_only()
    P, _, _ = maugis_pulloff(1.0)
    exact = -P * FSCALE
    smooth = largest_tension(run(64, 1.0)) / exact - 1
    sharp = largest_tension(run(64, 1.0, route="fixed-point")) / exact - 1
    say(f"\ndugdale lambda 1, 64^2: minimize {smooth:+.2%}, fixed point {sharp:+.2%} from Maugis")
    assert abs(smooth) < 0.005 and abs(sharp) > 5 * abs(smooth)


def test_newton_directions_cost_fewer_fft_pairs():
    """Maugis' sphere at lambda 2 on 64^2 (a zone of about 2 elements, a contact of 13 in radius):
    the Newton direction reaches Polak-Ribiere's states (the largest tension to 1e-6) for at most
    0.8 times its FFT pairs (0.62 measured), and its curve counts its conjugate gradients as the
    Krylov iterations, a few a Newton step."""
    serial_only()
    c = {direction: run(64, 2.0, steps=40, minimize_direction=direction) for direction in ("newton", "polak-ribiere")}
    new, old = c["newton"], c["polak-ribiere"]
    ffts = {k: int(v["fft_pairs"].sum()) for k, v in c.items()}
    say(f"\ndugdale lambda 2, 64^2: FFT pairs newton {ffts['newton']}, polak-ribiere {ffts['polak-ribiere']}; "
        f"Newton steps {int(new['outer_iterations'].sum())}, their CG iterations {int(new['ksp_iterations'].sum())}")
    assert abs(largest_tension(new) / largest_tension(old) - 1) < 1e-6
    assert ffts["newton"] < 0.8 * ffts["polak-ribiere"]
    assert new["ksp_iterations"].sum() > new["outer_iterations"].sum() > len(new["d"])


def test_trust_region_reaches_the_same_states_for_fewer_fft_pairs():
    """Maugis' sphere at lambda 2 on 64^2: the Newton steps' conjugate gradient within a trust
    region (-adh_minimize_trust_region 2, the default: along negative curvature to the region's
    edge) reaches the states it reaches without one (0: stopping at negative curvature, Nash's
    truncation), the largest tension to 1e-6 and every force to 1e-5 of it, for at most 0.9 times
    the FFT pairs (0.86 measured; 0.79 at lambda 3 on 188^2, ./run bench maugis)."""
    serial_only()
    c = {t: run(64, 2.0, steps=40, minimize_trust_region=t) for t in (2.0, 0.0)}
    ffts = {t: int(v["fft_pairs"].sum()) for t, v in c.items()}
    say(f"\ndugdale lambda 2, 64^2: FFT pairs with the trust region {ffts[2.0]}, without {ffts[0.0]}; "
        f"Newton steps {int(c[2.0]['outer_iterations'].sum())} and {int(c[0.0]['outer_iterations'].sum())}")
    assert abs(largest_tension(c[2.0]) / largest_tension(c[0.0]) - 1) < 1e-6
    assert len(c[2.0]["d"]) == len(c[0.0]["d"])
    assert np.max(np.abs(c[2.0]["force"] - c[0.0]["force"])) < 1e-5 * largest_tension(c[0.0])
    assert ffts[2.0] < 0.9 * ffts[0.0]


def test_route_change_refused_on_restart(tmp_path):
    """A restart that changes the route (from the default to the fixed point) is refused, naming the option."""
    serial_only()
    base = [EXE, "-adh_n", "32", "-adh_gamma", str(GAMMA), "-adh_criterion", "dugdale", "-adh_dugdale_stress", str(s0_for(1.0)),
            "-adh_path", "0.03,-0.05", "-adh_steps", "4"]
    ck = tmp_path / "ck.h5"
    r = subprocess.run(base + ["-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-2000:]
    r = subprocess.run(base + ["-adh_dugdale_route", "fixed-point", "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode != 0 and "-adh_dugdale_route" in r.stderr, r.stderr[-2000:]
