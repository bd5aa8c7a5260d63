"""Closed forms the solver is validated against: Maugis' finite-range (Dugdale) adhesion of a
sphere, in the notation of Johnson & Greenwood (1997).

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
