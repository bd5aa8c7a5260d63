"""Closed-form element integrals (src/grid/influence.c) against independent numerical quadrature.

Love's coefficient is the Boussinesq integral over one uniformly loaded hx x hy element,

    u(x, y) = 1/(pi E*) * integral_element 1/r dA',

and chi is the element's self-energy factor, U = sigma^2 chi / E* with U = 1/2 int p u dA, so

    chi = 1/(2 pi) * integral_element integral_element 1/|x - x'| dA dA'.

The references here use only NumPy: Gauss-Legendre in the angle of polar coordinates centred
on the (weakly singular) field point, tensor Gauss-Legendre where the integrand is smooth.
Serial only: nothing here is collective.
"""
import math

import numpy as np
import pytest

import adhbem

GL_X, GL_W = np.polynomial.legendre.leggauss(64)


def gauss(a, b, n=None):
    """Gauss-Legendre nodes and weights on [a, b] (64 points unless n is given)."""
    x, w = (GL_X, GL_W) if n is None else np.polynomial.legendre.leggauss(n)
    return 0.5 * (b - a) * x + 0.5 * (a + b), 0.5 * (b - a) * w


def corner_rectangle(A, B):
    """integral over [0, A] x [0, B] of 1/r, the field point at the corner (0, 0).

    Split along the diagonal into two triangles; in polar coordinates about the corner the
    radial integral of (1/r) r dr is analytic (the radius at which the ray leaves the triangle),
    and the angular integrand A/cos(theta) is smooth on [0, atan(B/A)] < pi/2: Gauss-Legendre.
    """
    if A <= 0.0 or B <= 0.0:
        return 0.0
    total = 0.0
    for P, Q in ((A, B), (B, A)):
        t, w = angle_rule(math.atan2(Q, P))
        total += np.sum(w * P / np.cos(t))
    return total


def angle_rule(theta, n=20):
    """Composite Gauss-Legendre on [0, theta] for integrands with a pole at pi/2: cells halve
    towards theta until they are no longer than the gap to the pole (elongated rectangles)."""
    gap = 0.5 * math.pi - theta
    edges, length = [theta], theta
    while length > gap and length > 2.0**-16 * theta:
        length *= 0.5
        edges.append(theta - length)
    edges = sorted(edges + [0.0])
    nodes = [gauss(a, b, n) for a, b in zip(edges[:-1], edges[1:])]
    return np.concatenate([x for x, _ in nodes]), np.concatenate([w for _, w in nodes])


def boussinesq_polar(x, y, hx, hy):
    """integral_element 1/r dA' for any field point (x, y) relative to the element centre.

    The element [x1, x2] x [y1, y2] is the signed sum of the four rectangles spanned by the field
    point and each corner (exact for inside, edge, corner and outside points alike).
    """
    total = 0.0
    for sx, X in ((1, x + 0.5 * hx), (-1, x - 0.5 * hx)):  # corners relative to the field point
        for sy, Y in ((1, y + 0.5 * hy), (-1, y - 0.5 * hy)):
            total += sx * sy * np.sign(X) * np.sign(Y) * corner_rectangle(abs(X), abs(Y))
    return total


def boussinesq_tensor(x, y, hx, hy, n=24, cells=1):
    """integral_element 1/r dA' by tensor Gauss-Legendre (the field point well outside)."""
    edges_x = np.linspace(-0.5 * hx, 0.5 * hx, cells + 1)
    edges_y = np.linspace(-0.5 * hy, 0.5 * hy, cells + 1)
    total = 0.0
    for a, b in zip(edges_x[:-1], edges_x[1:]):
        xs, wx = gauss(a, b, n)
        for c, d in zip(edges_y[:-1], edges_y[1:]):
            ys, wy = gauss(c, d, n)
            r = np.hypot(x - xs[:, None], y - ys[None, :])
            total += np.sum(wx[:, None] * wy[None, :] / r)
    return total


ELEMENTS = [(1.0, 1.0), (0.37, 0.37), (1.0, 0.4), (0.25, 0.9), (2.0, 0.2)]
E_STAR = 2.7


def near_points(hx, hy):
    return {
        "centre": (0.0, 0.0),
        "edge x": (0.5 * hx, 0.0),
        "edge y": (0.0, -0.5 * hy),
        "corner": (0.5 * hx, 0.5 * hy),
        "corner-": (-0.5 * hx, 0.5 * hy),
        "inside": (0.31 * hx, -0.17 * hy),
        "neighbour": (hx, 0.0),
        "diagonal": (hx, -hy),
        "near": (1.3 * hx, 0.6 * hy),
    }


@pytest.mark.parametrize("hx,hy", ELEMENTS)
def test_love_near_against_polar_quadrature(hx, hy):
    for name, (x, y) in near_points(hx, hy).items():
        ref = boussinesq_polar(x, y, hx, hy) / (math.pi * E_STAR)
        got = adhbem.love_coefficient(x, y, hx, hy, E_STAR)
        assert got == pytest.approx(ref, rel=1e-12), name


@pytest.mark.parametrize("hx,hy", ELEMENTS)
def test_love_far_against_tensor_gauss(hx, hy):
    for x, y in [(7 * hx, 0.0), (0.0, 7 * hy), (7 * hx, -7 * hy), (-3 * hx, 5 * hy), (20 * hx, 11 * hy)]:
        ref = boussinesq_tensor(x, y, hx, hy) / (math.pi * E_STAR)
        got = adhbem.love_coefficient(x, y, hx, hy, E_STAR)
        assert got == pytest.approx(ref, rel=1e-12), (x, y)
        # far away the element acts as a point load hx hy / (pi E* r)
        if math.hypot(x, y) > 6 * max(hx, hy):
            assert got == pytest.approx(hx * hy / (math.pi * E_STAR * math.hypot(x, y)), rel=0.01)


def test_love_neighbour_two_ways():
    """Tensor Gauss on sub-cells and the polar rule agree next to the element (cross-check of the references)."""
    hx, hy = 1.0, 0.4
    for x, y in [(hx, 0.0), (1.5 * hx, 0.7 * hy), (0.0, 2 * hy)]:
        a = boussinesq_polar(x, y, hx, hy)
        b = boussinesq_tensor(x, y, hx, hy, n=24, cells=8)
        assert a == pytest.approx(b, rel=1e-9)


def test_love_centre_value():
    for h in (1.0, 0.013, 250.0):
        for E in (1.0, 3.5e9):
            got = adhbem.love_coefficient(0.0, 0.0, h, h, E)
            assert got == pytest.approx(4 * math.log(1 + math.sqrt(2)) / math.pi * h / E, rel=1e-14)
            assert got * E / h == pytest.approx(1.1222, abs=5e-5)


def test_love_symmetry_and_scaling():
    hx, hy = 0.8, 0.3
    for x, y in [(0.2, 0.1), (1.7, -0.4), (5.0, 3.0)]:
        v = adhbem.love_coefficient(x, y, hx, hy, 1.0)
        for sx in (1, -1):
            for sy in (1, -1):
                assert adhbem.love_coefficient(sx * x, sy * y, hx, hy, 1.0) == pytest.approx(v, rel=1e-14)
        # swapping the axes of point and element; scaling everything by s scales u by s, 1/E* by E*
        assert adhbem.love_coefficient(y, x, hy, hx, 1.0) == pytest.approx(v, rel=1e-14)
        assert adhbem.love_coefficient(3 * x, 3 * y, 3 * hx, 3 * hy, 2.0) == pytest.approx(1.5 * v, rel=1e-14)


# ---- chi: the element self-energy -------------------------------------------------------------

def self_energy_autocorrelation(hx, hy):
    """integral_elem integral_elem 1/r by the exact reduction to the difference vector:
    4 integral_[0,hx]x[0,hy] (hx-u)(hy-v)/sqrt(u^2+v^2) du dv, then polar about the corner with the
    radial polynomial integrated exactly and Gauss-Legendre in angle."""
    total = 0.0
    # triangle under the diagonal: theta in [0, atan(hy/hx)], r up to hx/cos(theta); and its mirror
    for P, Q in ((hx, hy), (hy, hx)):
        t, w = angle_rule(math.atan2(Q, P))
        c, s = np.cos(t), np.sin(t)
        R = P / c
        # integral_0^R (P - r c)(Q - r s) dr
        radial = P * Q * R - (P * s + Q * c) * R**2 / 2 + c * s * R**3 / 3
        total += np.sum(w * radial)
    return 4.0 * total


def graded_gauss(L, levels=14, n=8, ratio=0.35):
    """Composite Gauss-Legendre on [0, L], cells graded geometrically towards both ends (where
    the displacement of a loaded element has its log-type derivative singularities)."""
    half = [0.0] + [0.5 * L * ratio**k for k in range(levels, 0, -1)] + [0.5 * L]
    edges = np.unique(np.concatenate([half, L - np.array(half)]))
    xs, ws = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        x, w = gauss(a, b, n)
        xs.append(x)
        ws.append(w)
    return np.concatenate(xs), np.concatenate(ws)


def self_energy_direct(hx, hy):
    """integral over the element of the inner integral (polar rule, independent of influence.c),
    outer integral by graded composite Gauss on sub-cells."""
    xs, wx = graded_gauss(hx)
    ys, wy = graded_gauss(hy)
    # angle rule on [0, 1], graded towards 1 (the pole at pi/2 of elongated corner rectangles);
    # scaled to each point's angle range theta: nodes theta * t, weights theta * w
    t, w = angle_rule(0.5 * math.pi, n=12)
    t, w = t / (0.5 * math.pi), w / (0.5 * math.pi)
    Y = ys - 0.5 * hy
    total = 0.0
    for x, weight in zip(xs - 0.5 * hx, wx):  # one outer row at a time: vectorised over y
        inner = np.zeros_like(Y)
        for sx, cx in ((1, x + 0.5 * hx), (-1, x - 0.5 * hx)):
            for sy, cy in ((1, Y + 0.5 * hy), (-1, Y - 0.5 * hy)):
                A, B = np.abs(cx) * np.ones_like(cy), np.abs(cy)
                rect = np.zeros_like(Y)
                for P, Q in ((A, B), (B, A)):
                    th = np.arctan2(Q, P)[:, None]
                    rect += np.sum(w * th * P[:, None] / np.cos(th * t), axis=-1)
                inner += sx * sy * np.sign(cx) * np.sign(cy) * rect
        total += weight * np.sum(wy * inner)
    return total


def test_chi_square_constant():
    for h in (1.0, 0.02, 7.0):
        assert adhbem.chi(h, h) == pytest.approx(adhbem.chi_square(h), rel=1e-14)
        assert adhbem.chi_square(h) / h**3 == pytest.approx(0.473201, abs=5e-7)
        assert self_energy_autocorrelation(h, h) / (2 * math.pi) == pytest.approx(adhbem.chi_square(h), rel=1e-12)


@pytest.mark.parametrize("hx,hy", [(1.0, 0.5), (0.3, 1.0), (1.0, 0.1), (2.0, 1.7)])
def test_chi_rectangular_against_quadrature(hx, hy):
    got = adhbem.chi(hx, hy)
    assert got == pytest.approx(self_energy_autocorrelation(hx, hy) / (2 * math.pi), rel=1e-12)
    assert got == pytest.approx(self_energy_direct(hx, hy) / (2 * math.pi), rel=1e-9)
    assert adhbem.chi(hy, hx) == pytest.approx(got, rel=1e-14)


def test_chi_from_love_coefficients():
    """chi = E*/2 * integral_elem love_coefficient dA (the energy definition U = 1/2 int p u)."""
    hx, hy, E = 1.0, 0.45, 3.0
    xs, wx = graded_gauss(hx)
    ys, wy = graded_gauss(hy)
    u = np.array([[adhbem.love_coefficient(x - 0.5 * hx, y - 0.5 * hy, hx, hy, E) for y in ys] for x in xs])
    assert adhbem.chi(hx, hy) == pytest.approx(0.5 * E * np.sum(wx[:, None] * wy[None, :] * u), rel=1e-9)


# ---- Sigma --------------------------------------------------------------------------------------

def test_critical_stress_formula():
    for hx, hy, E, g in [(1.0, 1.0, 1.0, 1.0), (0.01, 0.03, 2e9, 0.05), (3.0, 0.5, 7.0, 0.0)]:
        expected = math.sqrt(hx * hy * E * g / adhbem.chi(hx, hy))
        assert adhbem.critical_stress(hx, hy, E, g) == pytest.approx(expected, rel=1e-14, abs=0.0)
    h, E, g = 0.02, 5.0, 0.3
    assert adhbem.critical_stress(h, h, E, g) == pytest.approx(math.sqrt(E * g / (0.473201 * h)), rel=2e-6)
    assert adhbem.critical_stress(h, h, E, 0.0) == 0.0


@pytest.mark.parametrize("aspect", [1.0, 0.4, 2.5])
def test_critical_stress_scales_as_h_to_minus_half(aspect):
    E, g = 1.3, 0.07
    hs = np.array([1.0, 0.5, 0.25, 0.125, 1e-3])
    sig = np.array([adhbem.critical_stress(h, aspect * h, E, g) for h in hs])
    np.testing.assert_allclose(sig * np.sqrt(hs), sig[0] * np.sqrt(hs[0]), rtol=1e-13)
    slope = np.polyfit(np.log(hs), np.log(sig), 1)[0]
    assert slope == pytest.approx(-0.5, abs=1e-12)
