"""JKR spheres and flat punches on a thin layer against the axisymmetric solution of an isolated
contact (adhbem.theory.layer_sphere, layer_punch, layer_pulloff: Lebedev and Ufliand's integral
equation): the reference itself against the half-space's closed forms, the first-order effect of a
thick layer, the thin (lubrication) limit and JKR's energy balance; then the solver's flat-punch
compliance and JKR pull-off on an incompressible bonded layer against it. The full study (six
thicknesses, grids to 512^2, both criteria, Shull's fits) is ./run bench verify --case layer."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import adhbem
from adhbem import theory
from common import apply

E1, NU1 = 1.0, 0.5
ES = E1 / (1 - NU1 ** 2)


def test_multiplier_is_the_solvers():
    """theory.layer_multiplier is the C library's symbol: f = C(q) E* q / 2 of the solver's
    compliance applied to cos(q x), for both bases and two Poisson ratios."""
    n, L, T = (64, 4), 1.0, 0.05
    x = np.arange(n[0]) * L / n[0]
    for base in ("bonded", "slip"):
        for nu in (0.3, 0.5):
            with adhbem.Solver(n=n, size=(L, L / 16), boundary="periodic", elastic="layer", layer_thickness=T,
                               layer_base=base, E1=E1, nu1=nu, gamma=0.0, progress=False) as s:
                for m in (1, 3, 10, 25):
                    q = 2 * math.pi * m / L
                    wave = np.tile(np.cos(q * x), (n[1], 1))
                    C = float(np.sum(apply(s.compliance, wave) * wave) / np.sum(wave * wave))
                    f = C * E1 / (1 - nu ** 2) * q / 2
                    assert f == pytest.approx(float(theory.layer_multiplier(q * T, nu, base)), rel=1e-12), (base, nu, m)


def test_reference_is_jkr_on_the_halfspace():
    a = np.array([0.05, 0.1, 0.2])
    for T in (math.inf, 1e4):
        d, F = theory.layer_sphere(a, T, 1.0, 2e-3, E1, NU1)
        d0, F0 = theory.jkr_sphere(a, 1.0, 2e-3, ES)
        tol = 1e-12 if math.isinf(T) else 1e-5        # a layer 1e5 times the contact: its effect ~ a/T
        assert np.allclose(F, F0, rtol=tol, atol=0), T
        # the approach also counts the layer's settlement far away, of order F / (E* T)
        assert np.allclose(d, d0, rtol=tol, atol=0 if math.isinf(T) else np.max(np.abs(F)) / (ES * T)), T
        C = theory.layer_punch(a, T, E1, NU1)
        assert np.allclose(C, 1 / (2 * ES * a), rtol=tol, atol=0 if math.isinf(T) else 1 / (ES * T))
    F_adh, a_c, _ = theory.layer_pulloff(math.inf, 1.0, 2e-3, E1, NU1)
    F_jkr, a_jkr = theory.jkr_pulloff(1.0, 2e-3, ES)
    assert F_adh == pytest.approx(F_jkr, rel=1e-12) and a_c == pytest.approx(a_jkr, rel=1e-6)


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_thick_layer_first_order(nu):
    """A punch small against the layer feels it to first order in a/T:
    C/C_half = 1 - (2/pi) (a/T) int_0^inf (1 - f(t)) dt, the integral by adaptive quadrature."""
    integral = quad(lambda t: 1 - float(theory.layer_multiplier(t, nu)), 0, 60, limit=200)[0]
    slope = 2 / math.pi * integral
    for x in (0.002, 0.004):
        C = float(theory.layer_punch(0.01, 0.01 / x, E1, nu)[()])
        ratio = C * 2 * (E1 / (1 - nu ** 2)) * 0.01
        assert (1 - ratio) / x == pytest.approx(slope, rel=3 * x * slope), x   # the next order ~ (a/T)^2


def test_thin_limit_is_lubrication():
    """A thin incompressible bonded layer squeezed without friction under the contact: the punch's
    compliance tends to 8 T^3 / (pi E1 a^4) and the sphere's Hertz load to pi E1 a^6 / (96 R T^3)
    at d = a^2 / (4R), each deficit shrinking about as T/a."""
    a, R = 0.1, 1.0
    dev = []
    for x in (20, 40):
        T = a / x
        C = float(theory.layer_punch(a, T, E1, NU1)[()])
        d, F = theory.layer_sphere([a], T, R, 0.0, E1, NU1)
        dev.append([1 - C / (8 * T ** 3 / (math.pi * E1 * a ** 4)),
                    F[0] / (math.pi * E1 * a ** 6 / (96 * R * T ** 3)) - 1,
                    d[0] / (a * a / (4 * R)) - 1])
    dev = np.array(dev)
    assert np.all(dev > 0)
    assert np.all(dev[1] / dev[0] > 0.4) and np.all(dev[1] / dev[0] < 0.65), dev   # first order in T/a
    assert np.all(dev[1] < [0.15, 0.3, 0.1]), dev


@pytest.mark.parametrize("T", [0.2, 0.05])
def test_reference_keeps_jkr_energy_balance(T):
    """The edge's stress intensity (layer_sphere with dgamma) against JKR's energy construction
    with the layer's own Hertz load and punch compliance: F = F_H - sqrt(2 dgamma / |dC/dA|)."""
    g = 2.8e-3
    for a in (0.05, 0.1, 0.15):
        e = 1e-4 * a
        Cp, Cm = theory.layer_punch([a + e, a - e], T, E1, NU1)
        dCdA = (Cp - Cm) / (2 * e) / (2 * math.pi * a)
        F_H = theory.layer_sphere([a], T, 1.0, 0.0, E1, NU1)[1][0]
        F = theory.layer_sphere([a], T, 1.0, g, E1, NU1)[1][0]
        assert F_H - math.sqrt(2 * g / abs(dCdA)) == pytest.approx(F, rel=1e-6), a


def layer_run(N, T, **extra):
    return adhbem.Solver(n=N, boundary="periodic", elastic="layer", layer_thickness=T, E1=E1, nu1=NU1, progress=False,
                         **extra)


def test_punch_compliance_converges_to_the_reference():
    """A rigid flat punch on a thin layer (T = 0.05, a/T = 3): the solver's compliance against
    layer_punch at the digitised face's radius, first order in the grid (the edge's singularity)."""
    T, r = 0.05, 0.15
    err = []
    for N in (64, 128):
        with layer_run(N, T, gamma=0.0, indenter="punch", punch_radius=r, start="hertz", path=[0.001, 0.002],
                       steps=1) as s:
            c = s.solve_path()
        C = (c["d"][-1] - c["d"][-2]) / (c["force"][-1] - c["force"][-2])
        err.append(C / float(theory.layer_punch(math.sqrt(c["area"][-1] / math.pi), T, E1, NU1)[()]) - 1)
    assert 0 < err[1] < 0.6 * err[0] and err[1] < 0.025, err


def test_pull_off_on_a_thin_layer():
    """JKR's sphere on an incompressible bonded layer (T = 0.05: the pull-off 1.46 times the
    half-space's, its contact radius 0.73 times) under force control, crack-closure on 128^2
    (a_c/h 18): the pull-off within 1% of the exact one (the half-space's lattice scatter at this
    resolution), the contact radius along the unloading's stable branch within 3%."""
    T, g = 0.05, 2.8e-3
    F_adh, a_c, _ = theory.layer_pulloff(T, 1.0, g, E1, NU1)
    F_half, a_half = theory.jkr_pulloff(1.0, g, ES)
    assert F_adh / F_half == pytest.approx(1.46, abs=0.01) and a_c / a_half == pytest.approx(0.73, abs=0.01)
    with layer_run(128, T, gamma=g, start="hertz", control="force", path=[0.5 * F_adh, -2 * F_adh], steps=30,
                   pulloff_rtol=1e-4) as s:
        c = s.solve_path()
        F = s.pull_off_force
    assert F == pytest.approx(F_adh, rel=0.01)
    a = np.sqrt(c["area"] / math.pi)
    on = a > 1.1 * a_c
    assert on.sum() >= 10
    radii = np.linspace(a_c, 3 * a_c, 60)
    a_exact = np.interp(c["force"][on], theory.layer_sphere(radii, T, 1.0, g, E1, NU1)[1], radii)
    assert np.max(np.abs(a[on] / a_exact - 1)) < 0.03
