"""
Johnson's wavy surface
======================

A periodic wave ``h = D (1 - cos(2 pi x / lambda))`` pressed by a mean pressure ``p`` against a flat
elastic half-space with adhesion carries a contact strip of half-width ``a`` with (Johnson 1995)

    ``p / p* = sin^2(pi a / lambda) - alpha sqrt(tan(pi a / lambda))``,

``p* = pi E* D / lambda`` and ``alpha = sqrt(2 lambda dgamma / (pi^2 E* D^2))``. The curve falls to a
minimum (the largest tension, where a force-controlled contact comes off) and rises to a maximum
beyond which the strip jumps into full contact. This tutorial loads and unloads the wave under
force control on a periodic cell and sets the contact strip's width against the curve: a contact
whose edge is not a circle, in a periodic cell.

Run it yourself from a clone (after ``./run build``)::

    PYTHONPATH=python /usr/bin/python3 tutorials/tutorial_3_wavy_surface.py
"""
# %%
# The wave on a periodic cell
# ---------------------------
# The solution does not depend on y, so a strip of 4 rows is enough: an N x 4 periodic cell of
# width lambda = 1. The profile is handed over as the gap ``h`` itself
# (``topography_kind="gap"``); alpha = 0.3 sets the work of adhesion.
import os

import matplotlib.pyplot as plt
import numpy as np

import adhbem
from adhbem import theory

QUICK = os.environ.get("ADHBEM_TUTORIAL_QUICK") == "1"   # the test suite runs it small
N = 64 if QUICK else 256
lam, D, E_star, alpha = 1.0, 0.01, 1.0, 0.3
dgamma = alpha ** 2 * np.pi ** 2 * E_star * D ** 2 / (2 * lam)
pstar = np.pi * E_star * D / lam
h_grid = lam / N
x = (np.arange(N) + 0.5) * h_grid
h = np.tile(D * (1 - np.cos(2 * np.pi * x / lam)), (4, 1))   # (Ny, Nx) = (4, N)
cell = lam * 4 * h_grid                                          # the cell's area

a_theory = np.linspace(1e-4, 0.4999, 2000) * lam
p_theory = theory.johnson_wave(a_theory, lam, D, dgamma, E_star)
p_min = p_theory[a_theory < 0.25 * lam].min()                   # the force-controlled pull-off
p_max = p_theory[a_theory > 0.25 * lam].max()                   # the jump into full contact
print(f"dgamma = {dgamma:.4g}; Johnson: pull-off at p = {p_min / pstar:.4f} p*, jump-in at {p_max / pstar:.4f} p*")

# %%
# Loading and unloading under force control
# -----------------------------------------
# The path holds forces (mean pressure times the cell's area). Loading with adhesion from first
# touch (``start="adhesive"``) to 0.9 p_max, then unloading beyond Johnson's pull-off: under force
# control, when no state carries the asked-for tension, the step bisects the force to the largest
# tension carried (the pull-off force) and the leg ends there.
s = adhbem.Solver(n=(N, 4), size=(lam, 4 * h_grid), E_star=E_star, gamma=dgamma, boundary="periodic",
                  topography=h, topography_kind="gap", start="adhesive", control="force",
                  path=[0.0, 0.9 * p_max * cell, 1.5 * p_min * cell], steps=10 if QUICK else 25)
curve = s.solve_path(progress=False)
p = curve["force"] / cell
a = curve["area"] / cell * lam / 2                               # the strip's half-width
print(f"adhbem: pull-off at p = {p.min() / pstar:.4f} p* ({p.min() / p_min - 1:+.2%} from Johnson)")

# %%
# Against Johnson's curve
# -----------------------
loading = np.arange(len(p)) <= np.argmax(p)
fig, ax = plt.subplots(figsize=(5.5, 3.6), layout="constrained")
ax.plot(a_theory / lam, p_theory / pstar, color="0.6", lw=3, label="Johnson (1995)")
ax.plot(a[loading] / lam, p[loading] / pstar, "o-", ms=3, label="adhbem, loading")
ax.plot(a[~loading] / lam, p[~loading] / pstar, "s--", ms=3, label="adhbem, unloading")
ax.axhline(0, color="k", lw=0.5)
ax.set_xlim(0, 0.5)
ax.set_ylim(1.3 * p_min / pstar, 1.2 * p_max / pstar)
ax.set_xlabel(r"contact half-width $a/\lambda$")
ax.set_ylabel(r"mean pressure $p/p^*$")
ax.legend(fontsize=8)

# %%
# What the figure says
# --------------------
# Loading starts with the jump into a strip of finite width at zero load and follows the rising
# branch; unloading follows it back down and past zero load to the minimum, where the strip comes
# off. Both branches lie on Johnson's curve to within about a grid spacing in ``a``: the default
# attach rule (griffith) and criterion (crack-closure) act with the work of adhesion on a straight
# edge. With the paper's criterion (``criterion="pohrt-popov"``, attach rule ``reach``) the
# same run acts as if dgamma were up to 1.85 times larger on unloading and 0.77 times on loading
# along a grid axis; the verification pages measure both in every direction.
