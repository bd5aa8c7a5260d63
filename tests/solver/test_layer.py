"""The elastic layer on a rigid base (-adh_elastic layer): its compliance symbol against an
independent plane-strain solution of Navier's equations for one Fourier mode, its limits (a thick
layer is the half-space, the thin bonded, incompressible and slipping asymptotes), the
full-contact pressure of a cosine, a run on a thick layer equal to the half-space's, 1 rank equal
to 2 and 3, the results file's attributes, a restart that changes the body refused, bad input
refused."""
import math
import subprocess

import numpy as np
import pytest
from scipy.linalg import expm

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import _max, _min, apply, say


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process or compares with one")


def navier_compliance(q, T, E, nu, base):
    """W(0)/p of a layer 0 <= z <= T (z into the layer) under the pressure p cos(qx) on z = 0
    without shear, solved numerically: the displacements u_x = U(z) sin(qx), u_z = W(z) cos(qx) of
    Navier's equations in plane strain, a first-order system Y' = M Y in (U, U', W, W') carried
    across the layer by the matrix exponential, the base's two conditions solved for U(0), W(0)."""
    mu = E / (2 * (1 + nu))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    # mu (U'' - q^2 U) - (lam + mu) q (q U + W') = 0 with u_x = U sin: U'' = ((lam + 2 mu) q^2 U + (lam + mu) q W') / mu
    # mu (W'' - q^2 W) + (lam + mu) (q U' + W'') = 0:                W'' = (mu q^2 W - (lam + mu) q U') / (lam + 2 mu)
    M = np.array([[0, 1, 0, 0],
                  [(lam + 2 * mu) * q * q / mu, 0, 0, (lam + mu) * q / mu],
                  [0, 0, 0, 1],
                  [0, -(lam + mu) * q / (lam + 2 * mu), mu * q * q / (lam + 2 * mu), 0]])
    P = expm(M * T)
    # at z = 0: no shear, mu (U' - q W) = 0; sigma_zz = lam (q U + W') + 2 mu W' = -p (p = 1)
    # Y(0) = U0 a + W0 b + c with U0, W0 free
    a = np.array([1.0, 0.0, 0.0, -lam * q / (lam + 2 * mu)])
    b = np.array([0.0, q, 1.0, 0.0])
    c = np.array([0.0, 0.0, 0.0, -1.0 / (lam + 2 * mu)])
    Ya, Yb, Yc = P @ a, P @ b, P @ c
    if base == "bonded":  # U(T) = W(T) = 0
        rows = [0, 2]
        A = np.array([[Ya[0], Yb[0]], [Ya[2], Yb[2]]])
        r = -np.array([Yc[0], Yc[2]])
    else:  # W(T) = 0 and no shear, U'(T) - q W(T) = 0
        A = np.array([[Ya[2], Yb[2]], [Ya[1] - q * Ya[2], Yb[1] - q * Yb[2]]])
        r = -np.array([Yc[2], Yc[1] - q * Yc[2]])
    U0, W0 = np.linalg.solve(A, r)
    return W0


def layer_solver(n=(64, 4), size=(1.0, 1.0 / 16), T=0.1, E1=1.0, nu1=0.3, base="bonded", comm=None, **extra):
    opts = dict(n=n, size=size, boundary="periodic", elastic="layer", layer_thickness=T, layer_base=base,
                E1=E1, nu1=nu1, gamma=0.0, progress=False)
    opts.update(extra)
    return adhbem.Solver(**opts, **({"comm": comm} if comm else {}))


def measured_symbol(s, m, L=1.0, n=(64, 4)):
    """C(q) of the solver's compliance at q = 2 pi m / L: K applied to cos(q x)."""
    x = np.arange(n[0]) * L / n[0]
    wave = np.tile(np.cos(2 * math.pi * m * x / L), (n[1], 1))
    u = apply(s.compliance, wave)
    return float(np.sum(u * wave) / np.sum(wave * wave))


@pytest.mark.parametrize("base", ["bonded", "slip"])
def test_symbol_against_navier(base):
    """On the grid's modes m = 1, 3, 8 and thicknesses with qT from 0.03 to 5, for nu = 0, 0.3,
    0.49 and an elastic indenter once: the compliance's response to a cosine is the numerical
    plane-strain solution to 1e-9 (the indenter's half-space added in series)."""
    worst = 0.0
    for nu in (0.0, 0.3, 0.49):
        for qT in (0.03, 0.4, 1.5, 5.0):
            for m in (1, 3, 8):
                q = 2 * math.pi * m
                T = qT / q
                with layer_solver(T=T, E1=2.0, nu1=nu, base=base, E2=5.0, nu2=0.25) as s:
                    got = measured_symbol(s, m)
                want = navier_compliance(q, T, 2.0, nu, base) + 2 * (1 - 0.25 ** 2) / (5.0 * q)
                worst = max(worst, abs(got / want - 1))
    say(f"\n{base} layer: max |C/C_Navier - 1| over nu, qT, q = {worst:.1e}")
    assert worst < 1e-9


def test_limits():
    """A thick layer is the half-space of E* = E1/(1 - nu1^2) (1e-12 on the symbol: the difference
    is exp(-2qT)); a thin bonded layer tends to the oedometer's T (1+nu)(1-2nu)/(E(1-nu)), to
    q^2 T^3 / E when incompressible, a thin slipping one to T (1 - nu^2)/E (at qT = 1e-3, to the
    next order's (qT)^2, 1e-5)."""
    E1, m = 3.0, 2
    q = 2 * math.pi * m
    for base in ("bonded", "slip"):
        for nu in (0.0, 0.3, 0.5):
            with layer_solver(T=20.0, E1=E1, nu1=nu, base=base) as s:
                thick = measured_symbol(s, m)
            assert abs(thick / (2 * (1 - nu ** 2) / (E1 * q)) - 1) < 1e-12, (base, nu, thick)
    T = 1e-3 / q
    cases = {("bonded", 0.3): T * 1.3 * 0.4 / (E1 * 0.7), ("bonded", 0.0): T / E1,
             ("bonded", 0.5): q * q * T ** 3 / E1, ("slip", 0.3): T * (1 - 0.09) / E1, ("slip", 0.5): T * 0.75 / E1}
    for (base, nu), want in cases.items():
        with layer_solver(T=T, E1=E1, nu1=nu, base=base) as s:
            got = measured_symbol(s, m)
        say(f"thin {base} layer, nu = {nu}: C / asymptote - 1 = {got / want - 1:.1e}")
        assert abs(got / want - 1) < 1e-5, (base, nu, got, want)


def test_full_contact_pressure_of_a_cosine():
    """Force control beyond full contact of the gap h = D (1 - cos(2 pi x / lam)) on a bonded
    incompressible layer (T = lam / 8): every point touches and the pressure is
    pbar + (D / C(q)) cos(q x), with C(q) the closed form, to 1e-8 of pbar."""
    N, lam, D, T, E1, nu = 64, 1.0, 0.01, 0.125, 1.0, 0.5
    q, t, k = 2 * math.pi / lam, 2 * math.pi / lam * T, 3 - 4 * nu
    C = 2 * (1 - nu ** 2) / (E1 * q) * (k * math.sinh(2 * t) - 2 * t) / (k * math.cosh(2 * t) + 2 * t * t + (1 + k * k) / 2)
    pstar = D / C
    x = (np.arange(N) - N // 2) * lam / N
    h = np.tile(D * (1 - np.cos(q * x)), (4, 1))
    cell = lam * 4 * lam / N
    pbar = 1.5 * pstar
    with layer_solver(n=(N, 4), size=(lam, 4 * lam / N), T=T, E1=E1, nu1=nu, control="force", start="hertz",
                      path=[0.5 * pstar * cell, pbar * cell], steps=1, topography=h, topography_kind="gap") as s:
        c = s.solve_path()
        p = adhbem.gather(s.pressure, s.compliance)
    p_exact = np.tile(pbar + pstar * np.cos(q * x), (4, 1))
    rel = np.max(np.abs(p - p_exact)) / pbar
    say(f"\nfull contact on a layer: {c['contact_points'][-1]} of {4 * N} points, max |p - p_exact| / pbar = {rel:.1e}")
    assert c["contact_points"][-1] == 4 * N
    assert rel < 1e-8


def sphere_path(elastic, comm=None, n=48, **extra):
    """An adhesive sphere on a periodic cell, loaded and pulled: crack-closure's curve."""
    opts = dict(n=n, boundary="periodic", gamma=5e-4, path=[0.0, 0.01, -0.01], steps=10, start="adhesive",
                progress=False, stop_at_pulloff=False)
    if elastic == "halfspace":
        opts.update(E1=1.0, nu1=0.3)
    else:
        opts.update(elastic="layer", E1=1.0, nu1=0.3, **elastic)
    opts.update(extra)
    with adhbem.Solver(**opts, **({"comm": comm} if comm else {})) as s:
        return s.solve_path()


def test_thick_layer_runs_as_the_halfspace():
    """A bonded layer twice as thick as the cell (its symbol within 4e-9 of the half-space's at the
    longest wave, (4 t^2 / k) exp(-2t) at t = qT = 4 pi) gives the half-space's curve: the same
    contact counts, forces within 1e-7 of the largest."""
    serial_only()
    half = sphere_path("halfspace")
    thick = sphere_path({"layer_thickness": 2.0})
    rel = np.max(np.abs(thick["force"] - half["force"])) / np.max(np.abs(half["force"]))
    say(f"\nthick layer against the half-space: max |dF| / max |F| = {rel:.1e}")
    assert np.array_equal(thick["contact_points"], half["contact_points"])
    assert rel < 1e-7


@pytest.mark.parametrize("criterion, options", [
    ("crack-closure", {}), ("crack-closure", {"attach": "reach"}), ("pohrt-popov", {}),
    ("pohrt-popov", {"attach": "penetration"}), ("dugdale", {"dugdale_stress": 0.1, "dugdale_route": "fixed-point"}),
    ("dugdale", {"dugdale_stress": 0.1}),
    ("exponential", {"exponential_range": 0.005}), ("lj93", {"lj93_distance": 0.005})],
    ids=["crack-closure", "crack-closure-reach", "pohrt-popov", "pohrt-popov-penetration", "dugdale-fixed-point",
         "dugdale", "exponential", "lj93"])
def test_thin_layer_stiffens_the_contact(criterion, options):
    """A thin bonded layer (T = 0.05 R, 2.4 elements) under the same sphere and path carries more
    than 1.5 times the half-space's force at the deepest state (its compliance is below the
    half-space's at every wave number), and holds a tension on the way out, with every criterion,
    attach rule and cohesive law (the element's constants taken from the body)."""
    serial_only()
    extra = {"criterion": criterion, **options}
    half = sphere_path("halfspace", **extra)
    thin = sphere_path({"layer_thickness": 0.05}, **extra)
    deep = int(np.argmax(half["d"]))
    say(f"\n{criterion}: deepest force half-space {half['force'][deep]:.4g}, thin layer {thin['force'][deep]:.4g};"
        f" largest tension {-np.min(half['force']):.4g} / {-np.min(thin['force']):.4g}")
    assert thin["force"][deep] > 1.5 * max(half["force"][deep], 0.0) and thin["force"][deep] > 0
    assert np.min(thin["force"]) < 0


@pytest.mark.mpi
@pytest.mark.ranks3
def test_same_curve_on_any_number_of_ranks():
    """A layer's curve on COMM_WORLD equals COMM_SELF's, bonded and slipping with crack-closure and
    bonded with the exponential law (solved to 1e-10): the same contact counts, forces to 1e-10
    (1e-8 with the law, its solves' tolerance)."""
    mpi = PETSc.COMM_WORLD.tompi4py()
    for base, extra, tol in (("bonded", {}, 1e-10), ("slip", {}, 1e-10),
                             ("bonded", {"criterion": "exponential", "exponential_range": 0.005, "minimize_rtol": 1e-10}, 1e-8)):
        world = sphere_path({"layer_thickness": 0.1, "layer_base": base}, **extra)
        alone = sphere_path({"layer_thickness": 0.1, "layer_base": base}, comm=PETSc.COMM_SELF, **extra)
        same = mpi.allreduce(int(np.array_equal(world["contact_points"], alone["contact_points"])), op=_min())
        rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / np.max(np.abs(alone["force"]))), op=_max())
        say(f"\n{base} layer {extra.get('criterion', '')}, {PETSc.COMM_WORLD.getSize()} ranks vs 1: max |dF|/max|F| {rel:.1e}")
        assert same == 1 and rel < tol


def test_attributes_and_restart_refusal(tmp_path):
    """The results file records the body; a restart that changes the thickness, the base or the
    body is refused naming the option, one with the same body goes on."""
    serial_only()
    import h5py
    base = [EXE, "-adh_n", "32", "-adh_boundary", "periodic", "-adh_gamma", "5e-4", "-adh_path", "0,0.01,-0.01",
            "-adh_steps", "6", "-adh_start", "adhesive", "-adh_E1", "1", "-adh_nu1", "0.3"]
    layer = ["-adh_elastic", "layer", "-adh_layer_thickness", "0.1"]
    ck = tmp_path / "ck.h5"
    r = subprocess.run(base + layer + ["-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(tmp_path / "a.h5", "r") as f:
        text = lambda v: v.decode() if isinstance(v, bytes) else str(v)
        assert text(f.attrs["elastic"]) == "layer" and text(f.attrs["layer_base"]) == "bonded"
        assert float(f.attrs["layer_thickness"]) == 0.1 and float(f.attrs["nu1"]) == 0.3
        assert np.isinf(float(f.attrs["E2"]))
    for changed, option in ((["-adh_elastic", "layer", "-adh_layer_thickness", "0.2"], "-adh_layer_thickness"),
                            (layer + ["-adh_layer_base", "slip"], "-adh_layer_base"),
                            ([], "-adh_elastic")):
        r = subprocess.run(base + changed + ["-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                           capture_output=True, text=True, timeout=120)
        assert r.returncode != 0 and option in r.stdout + r.stderr, (changed, (r.stdout + r.stderr)[-1500:])
    r = subprocess.run(base + layer + ["-adh_restart", str(ck), "-adh_output", str(tmp_path / "c.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]


def test_checkpoint_of_the_version_before_goes_on_as_a_half_space(tmp_path):
    """A checkpoint of version 8 (before the elastic body: no -adh_elastic in it) is taken as a
    half-space's: a restart from it gives the uninterrupted run's curve; on a layer it is refused."""
    serial_only()
    import h5py
    base = [EXE, "-adh_n", "32", "-adh_boundary", "periodic", "-adh_gamma", "5e-4", "-adh_path", "0,0.01,-0.01",
            "-adh_steps", "6", "-adh_start", "adhesive", "-adh_fftw_planner", "estimate"]
    whole = tmp_path / "whole.h5"
    assert subprocess.run(base + ["-adh_output", str(whole)], capture_output=True, timeout=120).returncode == 0
    ck = tmp_path / "ck.h5"
    r = subprocess.run(base + ["-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(ck, "r+") as f:  # as adhbem of version 8 wrote it
        assert int(f.attrs["version"]) == 9
        f.attrs["version"] = np.array(8, dtype=f.attrs["version"].dtype)
        del f.attrs["-adh_elastic"]
    r = subprocess.run(base + ["-adh_elastic", "layer", "-adh_layer_thickness", "0.1", "-adh_E1", "1", "-adh_nu1", "0.3",
                               "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")], capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and "-adh_elastic" in r.stdout + r.stderr
    r = subprocess.run(base + ["-adh_restart", str(ck), "-adh_output", str(tmp_path / "c.h5")], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(whole, "r") as a, h5py.File(tmp_path / "c.h5", "r") as b:
        assert np.array_equal(a["curve/force"][()], b["curve/force"][()])


@pytest.mark.parametrize("options, words", [
    (dict(boundary="free"), "-adh_boundary periodic"),
    (dict(layer_thickness=0.0), "-adh_layer_thickness"),
    (dict(layer_thickness=-0.1), "-adh_layer_thickness"),
    (dict(nu1=-0.1), "-adh_nu1"),
    (dict(nu1=None), "needs the layer's Poisson ratio: give -adh_nu1"),
    (dict(nu1=0.6), "-adh_nu1"),
    (dict(E1=None, E_star=1.0), "-adh_E1"),
    (dict(layer_base="glued"), "-adh_layer_base"),
])
def test_bad_input(options, words):
    """Each refused with one line naming the option (ValueError from Python)."""
    opts = dict(n=16, boundary="periodic", elastic="layer", layer_thickness=0.1, E1=1.0, nu1=0.3, gamma=1e-4,
                progress=False, path=[0.0, 0.005], steps=2)
    opts.update(options)
    opts = {k: v for k, v in opts.items() if v is not None}
    with pytest.raises(ValueError) as e:
        with adhbem.Solver(**opts) as s:
            s.solve_path()
    assert words in str(e.value), str(e.value)


def view_ratio(T, n=32):
    """The layer's element self-compliance over the half-space's, as -adh_view prints it."""
    import re
    r = subprocess.run([EXE, "-adh_n", str(n), "-adh_boundary", "periodic", "-adh_elastic", "layer", "-adh_layer_thickness", repr(T),
                        "-adh_E1", "1", "-adh_nu1", "0.3", "-adh_gamma", "1e-4", "-adh_path", "0,0.001", "-adh_steps", "1",
                        "-adh_view"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-1500:]
    m = re.search(r"the element's self-compliance ([0-9.eE+-]+) times the half-space's", r.stdout)
    assert m, r.stdout[-2000:]
    return float(m.group(1)), "approximate" in r.stdout


def test_element_constants_are_continuous_in_the_thickness():
    """The element's self-compliance on a 32^2 cell across a grid spacing, where its formula changes
    (h (1 - 1e-6) against h (1 + 1e-6): within 1e-5), and it falls with the thickness towards the
    thin limit, positive (h/8, h/64)."""
    serial_only()
    h = 1.0 / 32
    below, approx_below = view_ratio(h * (1 - 1e-6))
    above, approx_above = view_ratio(h * (1 + 1e-6))
    say(f"\nself-compliance over the half-space's at h (1 -+ 1e-6): {below:.6f} / {above:.6f}")
    assert approx_below and not approx_above
    assert abs(below / above - 1) < 1e-5
    thin = [view_ratio(h * f)[0] for f in (0.5, 0.125, 1 / 64)]
    assert above > thin[0] > thin[1] > thin[2] > 0


def test_resolution_estimate_on_a_thin_incompressible_layer():
    """The JKR radius the resolution report estimates on a thin incompressible layer is the root of
    a = (9 pi dgamma R^2 / (8 E(1/a)))^(1/3), E(q) = 2 / (q C(q)), found here by bisection (the
    fixed point of that map cycles there)."""
    serial_only()
    import re
    n, T, dgamma = 64, 0.01, 5e-4
    r = subprocess.run([EXE, "-adh_n", str(n), "-adh_boundary", "periodic", "-adh_elastic", "layer", "-adh_layer_thickness", repr(T),
                        "-adh_E1", "1", "-adh_nu1", "0.5", "-adh_gamma", repr(dgamma), "-adh_path", "0,0.001", "-adh_steps", "1",
                        "-adh_view"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-1500:]
    got = float(re.search(r"JKR contact radius of the smallest asperities \(estimate\) over the grid spacing: ([0-9.eE+-]+)", r.stdout).group(1))

    def excess(E):
        a = (9 * math.pi * dgamma / (8 * E)) ** (1 / 3)
        q, t = 1 / a, T / a
        C = 2 * 0.75 / q * (math.sinh(2 * t) - 2 * t) / (math.cosh(2 * t) + 2 * t * t + 1)
        return E - 2 / (q * C)
    lo, hi = 4 / 3, 4 / 3
    while excess(hi) < 0:
        hi *= 2
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if excess(mid) < 0 else (lo, mid)
    want = (9 * math.pi * dgamma / (8 * lo)) ** (1 / 3) * n
    say(f"\nthin incompressible layer: JKR radius {got:.5g} spacings, the root {want:.5g}")
    assert abs(got / want - 1) < 1e-5
