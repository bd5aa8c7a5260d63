"""Closed forms the solver is validated against: the JKR sphere (Johnson, Kendall & Roberts 1971),
the JKR-type cone, Kendall's flat punch (1971), Westergaard's wavy surface (1939), Johnson's adhesive wavy
surface (1995), and Maugis' finite-range (Dugdale) adhesion of a
sphere, in the notation of Johnson & Greenwood (1997).

The JKR limit (zero range), for a contact radius ``a``, work of adhesion ``dgamma`` and reduced
modulus ``E*``: a sphere of radius ``R`` carries ``F = 4 E* a^3 / (3 R) - sqrt(8 pi dgamma E* a^3)``
at the indentation ``d = a^2 / R - sqrt(2 pi dgamma a / E*)``; its pull-off force (the largest
tension) is ``1.5 pi dgamma R``, at the contact radius ``a_c = (9 pi dgamma R^2 / (8 E*))^(1/3)``.

Maugis:
With ``K = 4 E*/3``, a sphere of radius ``R``, work of adhesion ``dgamma`` and cohesive stress
``s0`` (range ``dgamma/s0``), the Tabor-Maugis parameter is
``lambda = 2 s0 (R / (pi dgamma K^2))^(1/3)``; the contact radius ``a``, force ``F`` and indentation
``d`` scale as ``A = a (K / (pi dgamma R^2))^(1/3)``, ``P = F / (pi dgamma R)`` and
``D = d (K^2 / (pi^2 dgamma^2 R))^(1/3)``. With ``m = c/a`` (``c`` the cohesive zone's outer radius)
and ``k = sqrt(m^2 - 1)``::

    (lambda A^2 / 2) [k + (m^2 - 2) atan k] + (4 lambda^2 A / 3) [k atan k - m + 1] = 1
    P = A^3 - lambda A^2 [k + m^2 atan k]
    D = A^2 - (4/3) lambda A k

The pull-off force ``-min P`` goes from 2 (DMT, ``lambda -> 0``) to 1.5 (JKR, large ``lambda``).

An elastic layer on a rigid base (``layer_multiplier``, ``layer_punch``, ``layer_sphere``,
``layer_pulloff``): a rigid flat punch or sphere pressed without friction on a layer of thickness
``T``, bonded to its base or slipping on it, an isolated contact. Its surface moves by
``C(q) = 2 f(qT) / (E* q)`` under a pressure wave of wave number ``q`` (``E* = E1 / (1 - nu1^2)``).
Written as ``p(r) = phi(a) / sqrt(a^2 - r^2) - int_r^a phi'(t) / sqrt(t^2 - r^2) dt``, the
contact problem is the Fredholm equation of the second kind (Lebedev and Ufliand, 1958)::

    phi(t) - int_0^a K(t, s) phi(s) ds = (E*/2) (2/pi) d/dt int_0^t r w(r) / sqrt(t^2 - r^2) dr
    K(t, s) = (2 / (pi T)) int_0^inf (1 - f(x)) cos(x t / T) cos(x s / T) dx

(``w(r)`` the displacement the contact imposes), solved here by Gauss-Legendre quadrature in
``x`` and Nystrom's method in ``t``. The force is ``2 pi int_0^a phi``, and the edge's energy
release rate ``pi phi(a)^2 / (2 E* a)``: JKR on the layer is ``phi(a) = -sqrt(2 E* a dgamma / pi)``.
``K = 0`` gives the half-space's closed forms above.
"""
from __future__ import annotations

import math

import numpy as np


def jkr_sphere(a, R: float = 1.0, dgamma: float = 0.0, E_star: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """The JKR sphere (Hertz without adhesion): indentation and force at contact radii ``a``.

    Parameters
    ----------
    a : array_like
        Contact radii.
    R : float, optional
        The sphere's radius.
    dgamma : float, optional
        The work of adhesion (0: Hertz).
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    d, F : numpy.ndarray
        ``d = a^2/R - sqrt(2 pi dgamma a / E*)`` and ``F = 4 E* a^3 / (3 R) - sqrt(8 pi dgamma E* a^3)``.

    Examples
    --------
    >>> d, F = jkr_sphere([0.1], R=1.0, dgamma=0.0)
    >>> round(float(d[0]), 6), round(float(F[0]), 6)
    (0.01, 0.001333)
    """
    a = np.asarray(a, dtype=float)
    return (a ** 2 / R - np.sqrt(2 * math.pi * dgamma * a / E_star),
            4 * E_star * a ** 3 / (3 * R) - np.sqrt(8 * math.pi * dgamma * E_star * a ** 3))


def jkr_pulloff(R: float, dgamma: float, E_star: float = 1.0) -> tuple[float, float]:
    """The JKR sphere's pull-off: the largest tension ``1.5 pi dgamma R`` and its contact radius.

    Parameters
    ----------
    R : float
        The sphere's radius.
    dgamma : float
        The work of adhesion.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    F_adh, a_c : float
        ``1.5 pi dgamma R`` and ``(9 pi dgamma R^2 / (8 E*))^(1/3)``.
    """
    return 1.5 * math.pi * dgamma * R, (9 * math.pi * dgamma * R ** 2 / (8 * E_star)) ** (1.0 / 3.0)


def jkr_dgamma(a_c: float, R: float = 1.0, E_star: float = 1.0) -> float:
    """The work of adhesion that gives the JKR sphere the pull-off contact radius ``a_c``.

    Parameters
    ----------
    a_c : float
        The contact radius at pull-off (choose it in grid spacings to set the resolution).
    R : float, optional
        The sphere's radius.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    float
        ``8 E* a_c^3 / (9 pi R^2)``, the inverse of ``jkr_pulloff``'s radius.

    Examples
    --------
    >>> round(jkr_pulloff(1.0, jkr_dgamma(0.1))[1], 12)
    0.1
    """
    return 8 * E_star * a_c ** 3 / (9 * math.pi * R ** 2)


def jkr_cone(a, slope: float, dgamma: float = 0.0, E_star: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """The JKR-type cone of surface slope ``slope`` (Maugis & Barquins): indentation and force at
    contact radii ``a``: ``d = pi a slope / 2 - sqrt(2 pi dgamma a / E*)``,
    ``F = pi E* a^2 slope / 2 - sqrt(8 pi dgamma E* a^3)``.

    Parameters
    ----------
    a : array_like
        Contact radii.
    slope : float
        The cone's surface slope (``h = slope r``).
    dgamma : float, optional
        The work of adhesion (0: Sneddon's cone).
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    d, F : numpy.ndarray
        The indentation and the force at each radius.
    """
    a = np.asarray(a, dtype=float)
    return (math.pi / 2 * a * slope - np.sqrt(2 * math.pi * dgamma * a / E_star),
            math.pi / 2 * E_star * a ** 2 * slope - np.sqrt(8 * math.pi * dgamma * E_star * a ** 3))


def kendall_punch(radius: float, dgamma: float, E_star: float = 1.0) -> tuple[float, float]:
    """Kendall's flat punch of radius ``radius``: its stiffness ``2 E* radius`` (``F = 2 E* radius d``
    while in contact) and the indentation at which it comes off, ``-sqrt(2 pi dgamma radius / E*)``;
    the pull-off force is the stiffness times that, ``sqrt(8 pi dgamma E* radius^3)``.

    Parameters
    ----------
    radius : float
        The punch's radius.
    dgamma : float
        The work of adhesion.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    stiffness, d_c : float
        ``2 E* radius`` and ``-sqrt(2 pi dgamma radius / E*)``.
    """
    return 2 * E_star * radius, -math.sqrt(2 * math.pi * dgamma * radius / E_star)


def johnson_wave(a, wavelength: float, amplitude: float, dgamma: float = 0.0, E_star: float = 1.0) -> np.ndarray:
    """Johnson's (1995) adhesive wavy surface: the mean pressure at contact-strip half-widths ``a``.

    The gap profile ``h = D (1 - cos(2 pi x / wavelength))`` (``D`` the amplitude) pressed by a mean
    pressure ``p`` carries a contact strip of half-width ``a`` with
    ``p / p* = sin^2(pi a / wavelength) - alpha sqrt(tan(pi a / wavelength))``, ``p* = pi E* D / wavelength``
    (the mean pressure of full contact without adhesion) and
    ``alpha = sqrt(2 wavelength dgamma / (pi^2 E* D^2))``.

    Parameters
    ----------
    a : array_like
        Half-widths of the contact strip, between 0 and ``wavelength / 2``.
    wavelength, amplitude : float
        The wave's wavelength and amplitude ``D``.
    dgamma : float, optional
        The work of adhesion.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    numpy.ndarray
        The mean pressure ``p`` (compression > 0).

    Examples
    --------
    >>> round(float(johnson_wave(0.25, 1.0, 0.01, 0.0)[()]), 6)   # sin^2(pi/4) p*
    0.015708
    """
    t = np.pi * np.asarray(a, dtype=float) / wavelength
    pstar = math.pi * E_star * amplitude / wavelength
    alpha = math.sqrt(2 * wavelength * dgamma / (math.pi ** 2 * E_star * amplitude ** 2))
    return pstar * (np.sin(t) ** 2 - alpha * np.sqrt(np.tan(t)))


def westergaard_wave(pbar: float, wavelength: float, amplitude: float, E_star: float = 1.0,
                     samples: int = 2 ** 20) -> tuple[float, float, float]:
    """Westergaard's wavy surface without adhesion at the mean pressure ``pbar``: the contact's
    half-width and the indentation.

    The gap profile ``h = D (1 - cos(2 pi x / wavelength))`` pressed to ``pbar`` (below
    ``p* = pi E* D / wavelength``, full contact) is in contact where ``|x| < a``,
    ``sin^2(pi a / wavelength) = pbar / p*``, under the pressure ``westergaard_pressure``. The
    indentation ``d`` is adhbem's: the approach relative to the mean plane of the deformed surface,
    ``d = h + u`` on the contact with ``u`` of zero mean, computed from the exact pressure sampled on
    ``samples`` points (its periodic displacement by FFT, the multiplier ``2/(E* q)``).

    Parameters
    ----------
    pbar : float
        The mean pressure, ``0 < pbar < p*``.
    wavelength, amplitude : float
        The wave's wavelength and amplitude ``D``.
    E_star : float, optional
        The reduced modulus.
    samples : int, optional
        Points of the sampled pressure (the indentation's error falls like its square).

    Returns
    -------
    a, d, spread : float
        The half-width, the indentation, and ``max - min`` of ``h + u`` over the contact (0 for the
        exact solution: the sampling's error).

    Examples
    --------
    >>> a, d, spread = westergaard_wave(0.5 * math.pi * 0.01, 1.0, 0.01)
    >>> round(a, 6), spread < 1e-8
    (0.25, True)
    """
    x = (np.arange(samples) - samples // 2) * wavelength / samples
    a = wavelength / math.pi * math.asin(math.sqrt(pbar / (math.pi * E_star * amplitude / wavelength)))
    p = westergaard_pressure(x, pbar, wavelength, amplitude, E_star)
    ph = np.fft.rfft(p)
    q = 2 * math.pi * np.arange(len(ph)) / wavelength
    multiplier = np.zeros_like(q)
    multiplier[1:] = 2 / (E_star * q[1:])
    u = np.fft.irfft(ph * multiplier, samples)
    hu = (amplitude * (1 - np.cos(2 * math.pi * x / wavelength)) + u)[np.abs(x) < a]
    return a, float(hu.mean()), float(hu.max() - hu.min())


def westergaard_pressure(x, pbar: float, wavelength: float, amplitude: float, E_star: float = 1.0) -> np.ndarray:
    """The pressure of Westergaard's wavy surface at ``x`` (``|x| <= wavelength/2``) under the mean
    pressure ``pbar``: ``2 pbar cos(pi x/wavelength) sqrt(s^2 - sin^2(pi x/wavelength)) / s^2``,
    ``s^2 = pbar / p*``, in the contact and 0 outside it (``westergaard_wave`` has the notation).

    Parameters
    ----------
    x : array_like
        Positions along the wave, its crest (the first contact) at 0.
    pbar : float
        The mean pressure, below ``p* = pi E* D / wavelength``.
    wavelength, amplitude : float
        The wave's wavelength and amplitude ``D``.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    numpy.ndarray
        The pressure at ``x``.

    Examples
    --------
    >>> round(float(westergaard_pressure(0.0, 0.5 * math.pi * 0.01, 1.0, 0.01)), 6)   # 2 pbar / s
    0.044429
    """
    s2 = pbar / (math.pi * E_star * amplitude / wavelength)
    t = math.pi * np.asarray(x, dtype=float) / wavelength
    return 2 * pbar * np.cos(t) / s2 * np.sqrt(np.maximum(s2 - np.sin(t) ** 2, 0.0))


def tabor_lambda(s0: float, dgamma: float, R: float = 1.0, E_star: float = 1.0) -> float:
    """The Tabor-Maugis parameter of a sphere.

    Parameters
    ----------
    s0 : float
        The cohesive stress (``-adh_dugdale_stress``).
    dgamma : float
        The work of adhesion.
    R : float, optional
        The sphere's radius.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    float
        ``lambda = 2 s0 (R / (pi dgamma K^2))^(1/3)``, ``K = 4 E*/3``.

    Examples
    --------
    >>> round(tabor_lambda(0.148, 0.004655), 3)
    0.999
    """
    K = 4.0 * E_star / 3.0
    return 2.0 * s0 * (R / (math.pi * dgamma * K * K)) ** (1.0 / 3.0)


def maugis_scales(dgamma: float, R: float = 1.0, E_star: float = 1.0) -> tuple[float, float, float]:
    """Johnson & Greenwood's units of Maugis' sphere, to turn ``maugis_sphere`` into forces and lengths.

    Parameters
    ----------
    dgamma : float
        The work of adhesion.
    R : float, optional
        The sphere's radius.
    E_star : float, optional
        The reduced modulus.

    Returns
    -------
    force, radius, indentation : float
        ``pi dgamma R``, ``(pi dgamma R^2 / K)^(1/3)`` and ``(pi^2 dgamma^2 R / K^2)^(1/3)``,
        ``K = 4 E*/3``: ``F = P force``, ``a = A radius``, ``d = D indentation``.

    Examples
    --------
    >>> F, a, d = maugis_scales(0.004655)
    >>> round(-maugis_pulloff(1.0)[0] * F, 5)     # the pull-off force at lambda 1
    0.02341
    """
    K = 4.0 * E_star / 3.0
    return (math.pi * dgamma * R, (math.pi * dgamma * R ** 2 / K) ** (1.0 / 3.0),
            (math.pi ** 2 * dgamma ** 2 * R / K ** 2) ** (1.0 / 3.0))


def _zone_ratio(lam: float, A: float) -> float:
    """m = c/a of Maugis' first equation, by bisection (its left side rises with m)."""
    def f(m):
        k = math.sqrt(m * m - 1.0)
        return (lam * A * A / 2.0) * (k + (m * m - 2.0) * math.atan(k)) \
            + (4.0 * lam * lam * A / 3.0) * (k * math.atan(k) - m + 1.0) - 1.0
    lo, hi = 1.0, 2.0
    while f(hi) < 0.0:
        lo, hi = hi, 2.0 * hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0.0 else (lo, mid)
        if hi - lo <= 1e-15 * hi:
            break
    return 0.5 * (lo + hi)


def maugis_sphere(lam: float, A) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maugis' sphere in Johnson & Greenwood's units, at given contact radii.

    Parameters
    ----------
    lam : float
        The Tabor-Maugis parameter (``tabor_lambda``), > 0.
    A : float or array_like
        Contact radii ``a (K / (pi dgamma R^2))^(1/3)``, > 0.

    Returns
    -------
    P, D, m : numpy.ndarray
        The force ``F / (pi dgamma R)``, the indentation ``d (K^2 / (pi^2 dgamma^2 R))^(1/3)`` and the
        zone's ratio ``c/a`` at each radius.

    Examples
    --------
    >>> P, D, m = maugis_sphere(1.0, [0.9])
    >>> round(float(P[0]), 3)
    -1.601
    """
    A = np.atleast_1d(np.asarray(A, dtype=float))
    m = np.array([_zone_ratio(lam, a) for a in A])
    k = np.sqrt(m * m - 1.0)
    P = A ** 3 - lam * A * A * (k + m * m * np.arctan(k))
    D = A * A - (4.0 / 3.0) * lam * A * k
    return P, D, m


def _golden_min(f, lo: float, hi: float, iterations: int = 100) -> float:
    """The minimiser of a unimodal f on [lo, hi] by golden section."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = f(x1), f(x2)
    for _ in range(iterations):
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = f(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = f(x2)
        if hi - lo <= 1e-10 * hi:
            break
    return 0.5 * (lo + hi)


def maugis_pulloff(lam: float) -> tuple[float, float, float]:
    """The pull-off of Maugis' sphere: the largest tension, where it is carried.

    Parameters
    ----------
    lam : float
        The Tabor-Maugis parameter, > 0.

    Returns
    -------
    P, A, D : float
        ``-P`` is the pull-off force over ``pi dgamma R`` (2 for DMT, 1.5 for JKR); ``A`` and ``D`` the
        contact radius and indentation there, in Johnson & Greenwood's units.

    Examples
    --------
    >>> round(-maugis_pulloff(1.0)[0], 3)
    1.601
    """
    def P(a):
        return float(maugis_sphere(lam, [a])[0][0])
    grid = np.geomspace(1e-3, 4.0, 400)
    i = int(np.argmin([P(a) for a in grid]))
    a = _golden_min(P, grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)])
    Pa, Da, _ = maugis_sphere(lam, [a])
    return float(Pa[0]), a, float(Da[0])


# ---- an elastic layer on a rigid base -----------------------------------------------------------

def layer_multiplier(t, nu1: float, base: str = "bonded") -> np.ndarray:
    """The layer's compliance over the half-space's, ``f(qT)`` in ``C(q) = 2 f(qT) / (E* q)``.

    Parameters
    ----------
    t : array_like
        ``q T``, the wave number times the layer's thickness, >= 0.
    nu1 : float
        The layer's Poisson ratio, from 0 to 0.5.
    base : {"bonded", "slip"}, optional
        The layer bonded to its rigid base or slipping on it without friction.

    Returns
    -------
    numpy.ndarray
        bonded: ``(k sinh 2t - 2t) / (k cosh 2t + 2t^2 + (1 + k^2)/2)``, ``k = 3 - 4 nu1``;
        slip: ``(cosh 2t - 1) / (sinh 2t + 2t)``; both tend to 1 for a thick layer.

    Examples
    --------
    >>> round(float(layer_multiplier(30.0, 0.5)[()]), 12)
    1.0
    """
    if base not in ("bonded", "slip"):
        raise ValueError(f"base: 'bonded' or 'slip', not {base!r}")
    t = np.asarray(t, dtype=float)
    out = np.ones_like(t)
    x = t[t < 20.0]                       # beyond, f = 1 to 1e-15
    if base == "bonded":
        k = 3.0 - 4.0 * nu1
        out[t < 20.0] = (k * np.sinh(2 * x) - 2 * x) / (k * np.cosh(2 * x) + 2 * x * x + (1 + k * k) / 2)
    else:
        out[t < 20.0] = (np.cosh(2 * x) - 1) / (np.sinh(2 * x) + 2 * x)
    return out


def _check_layer(T: float, nu1: float, base: str) -> None:
    if not T > 0:
        raise ValueError(f"T: the layer's thickness must be > 0, not {T!r}")
    if not 0.0 <= nu1 <= 0.5:
        raise ValueError(f"nu1: the layer's Poisson ratio must be from 0 to 0.5, not {nu1!r}")
    if base not in ("bonded", "slip"):
        raise ValueError(f"base: 'bonded' or 'slip', not {base!r}")


def _layer_moments(a: float, T: float, nu1: float, base: str) -> tuple[np.ndarray, np.ndarray]:
    """Lebedev and Ufliand's equation for the right-hand sides 1 and t^2 on [0, a]: their
    integrals and their values at t = a (both scaled by pi / E*)."""
    if a / T > 200:
        raise ValueError(f"a/T = {a / T:g}: beyond this reference's range (200; the lubrication limit applies)")
    n = 32 + int(12 * a / T)              # the kernel's width is T: resolve it on [0, a]
    s, ws = np.polynomial.legendre.leggauss(n)
    s, ws = 0.5 * a * (s + 1), 0.5 * a * ws
    rhs = np.stack([np.ones(n), s * s], axis=1)
    if math.isinf(T):
        return ws @ rhs, np.array([1.0, a * a])
    xmax = 20.0                           # 1 - f(x) ~ x^2 exp(-2x): below 1e-15 beyond (layer_multiplier's 1)
    m = 64 + int(4.0 * xmax * a / T)      # about 6 nodes a period of the kernel's fastest cos(2 x a / T)
    x, wx = np.polynomial.legendre.leggauss(m)
    x, wx = 0.5 * xmax * (x + 1), 0.5 * xmax * wx
    g = (1.0 - layer_multiplier(x, nu1, base)) * wx * 2.0 / (math.pi * T)
    cs = np.cos(np.multiply.outer(s, x) / T)             # n x m
    K = (cs * g) @ cs.T                                   # K(s_i, s_j), separable in t and s
    phi = np.linalg.solve(np.eye(n) - K * ws, rhs)
    Ka = (np.cos(x * a / T) * g) @ cs.T                   # K(a, s_j)
    return ws @ phi, np.array([1.0, a * a]) + (Ka * ws) @ phi


def layer_punch(a, T: float, E1: float = 1.0, nu1: float = 0.5, base: str = "bonded") -> np.ndarray:
    """The compliance ``d / F`` of a rigid flat punch of radius ``a`` on a layer of thickness ``T``.

    Parameters
    ----------
    a : array_like
        The punch's radii, > 0.
    T : float
        The layer's thickness, > 0 (``math.inf``: the half-space).
    E1, nu1 : float, optional
        The layer's Young's modulus and Poisson ratio.
    base : {"bonded", "slip"}, optional
        The layer bonded to its rigid base or slipping on it.

    Returns
    -------
    numpy.ndarray
        The compliance; ``1 / (2 E* a)`` on the half-space.

    Examples
    --------
    >>> round(float(layer_punch(0.1, math.inf, 0.75, 0.5)[0]), 12)   # E* = 1
    5.0
    """
    _check_layer(T, nu1, base)
    Es = E1 / (1.0 - nu1 * nu1)
    a = np.atleast_1d(np.asarray(a, dtype=float))
    return np.array([1.0 / (2.0 * Es * _layer_moments(float(r), T, nu1, base)[0][0]) for r in a])


def layer_sphere(a, T: float, R: float = 1.0, dgamma: float = 0.0, E1: float = 1.0, nu1: float = 0.5,
                 base: str = "bonded") -> tuple[np.ndarray, np.ndarray]:
    """The JKR sphere on a layer: indentation and force at contact radii ``a``.

    Parameters
    ----------
    a : array_like
        Contact radii, > 0.
    T : float
        The layer's thickness, > 0 (``math.inf``: ``jkr_sphere``).
    R : float, optional
        The rigid sphere's radius (a paraboloid ``r^2 / (2R)``).
    dgamma : float, optional
        The work of adhesion (0: the layer's Hertz problem).
    E1, nu1 : float, optional
        The layer's Young's modulus and Poisson ratio.
    base : {"bonded", "slip"}, optional
        The layer bonded to its rigid base or slipping on it.

    Returns
    -------
    d, F : numpy.ndarray
        The indentation (the approach of the sphere to the layer's undeformed surface far away) and
        the force (compression > 0).

    Examples
    --------
    >>> d, F = layer_sphere([0.1], math.inf, 1.0, 0.0, 0.75, 0.5)   # Hertz, E* = 1
    >>> round(float(d[0]), 9), round(float(F[0]), 9)
    (0.01, 0.001333333)
    """
    _check_layer(T, nu1, base)
    Es = E1 / (1.0 - nu1 * nu1)

    def one(r):
        I, at_a = _layer_moments(r, T, nu1, base)
        # phi = (E*/pi) (d phi_1 - phi_2 / R), its edge value -sqrt(2 E* a dgamma / pi)
        d = (at_a[1] / R - math.pi / Es * math.sqrt(2.0 * Es * r * dgamma / math.pi)) / at_a[0]
        return d, 2.0 * Es * (d * I[0] - I[1] / R)

    a = np.atleast_1d(np.asarray(a, dtype=float))
    dF = np.array([one(float(r)) for r in a])
    return dF[:, 0], dF[:, 1]


def layer_pulloff(T: float, R: float = 1.0, dgamma: float = 1.0, E1: float = 1.0, nu1: float = 0.5,
                  base: str = "bonded") -> tuple[float, float, float]:
    """The JKR sphere's pull-off on a layer: the largest tension, with the contact radius and the
    indentation there (the pull-off under force control).

    Parameters
    ----------
    T : float
        The layer's thickness, > 0 (``math.inf``: ``jkr_pulloff``).
    R, dgamma : float, optional
        The sphere's radius and the work of adhesion.
    E1, nu1 : float, optional
        The layer's Young's modulus and Poisson ratio.
    base : {"bonded", "slip"}, optional
        The layer bonded to its rigid base or slipping on it.

    Returns
    -------
    F_adh, a_c, d_c : float
        The pull-off force (> 0), the contact radius and the indentation at it.

    Examples
    --------
    >>> F, a, d = layer_pulloff(math.inf, 1.0, 1e-3, 0.75, 0.5)
    >>> round(F / (1.5 * math.pi * 1e-3), 9), round(a / jkr_pulloff(1.0, 1e-3)[1], 6)
    (1.0, 1.0)
    """
    _, a_jkr = jkr_pulloff(R, dgamma, E1 / (1.0 - nu1 * nu1))

    def force(r):
        return float(layer_sphere([r], T, R, dgamma, E1, nu1, base)[1][0])
    _check_layer(T, nu1, base)
    grid = np.geomspace(0.05 * a_jkr, 2.0 * a_jkr, 24)   # a layer shrinks the radius at pull-off
    i = int(np.argmin([force(r) for r in grid]))
    if i in (0, len(grid) - 1):
        raise ValueError(f"layer_pulloff: no largest tension between the contact radii {grid[0]:g} and "
                         f"{grid[-1]:g}, the range searched (T/a_JKR = {T / a_jkr:g})")
    a = _golden_min(force, grid[i - 1], grid[i + 1])
    d, F = layer_sphere([a], T, R, dgamma, E1, nu1, base)
    return -float(F[0]), a, float(d[0])
