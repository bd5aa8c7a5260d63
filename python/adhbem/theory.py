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
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    g = (math.sqrt(5.0) - 1.0) / 2.0  # golden section on the bracket
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    for _ in range(100):
        if P(x1) < P(x2):
            hi, x2 = x2, x1
            x1 = hi - g * (hi - lo)
        else:
            lo, x1 = x1, x2
            x2 = lo + g * (hi - lo)
    a = 0.5 * (lo + hi)
    Pa, Da, _ = maugis_sphere(lam, [a])
    return float(Pa[0]), a, float(Da[0])
