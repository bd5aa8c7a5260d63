"""
The JKR sphere
==============

A rigid sphere pressed into an elastic half-space with adhesion and pulled off again, under
displacement control: force and contact radius against the indentation beside the theory of
Johnson, Kendall & Roberts (1971), the jump into contact at first touch, and the pull-off force
(the largest tension the contact carries).

Run it yourself from a clone (after ``./run build``)::

    PYTHONPATH=python /usr/bin/python3 tutorials/tutorial_1_jkr_sphere.py
"""
# %%
# The problem
# -----------
# Lengths in units of the sphere's radius, stresses in units of the reduced modulus ``E*``. The
# work of adhesion is chosen so that the contact radius at pull-off, ``a_c``, spans 12 grid
# spacings on a 128 x 128 grid of side 1 (the resolution report says whether the grid resolves
# the adhesion: under 10 spacings it says the pull-off force depends on the grid; aim for 20
# where a few percent matter). The sphere touches at ``d = 0``, is pressed in
# to ``d1`` and pulled back out beyond the point where it comes off.
import os

import matplotlib.pyplot as plt
import numpy as np

import adhbem
from adhbem import theory

QUICK = os.environ.get("ADHBEM_TUTORIAL_QUICK") == "1"   # the test suite runs it small
N = 64 if QUICK else 128
R, E_star, size = 1.0, 1.0, 1.0
h = size / N
a_c = 12 * h                                     # the wanted contact radius at pull-off
dgamma = theory.jkr_dgamma(a_c, R, E_star)        # the work of adhesion that gives it
F_adh, a_c = theory.jkr_pulloff(R, dgamma, E_star)
print(f"dgamma = {dgamma:.4g}, F_adh = 1.5 pi dgamma R = {F_adh:.4g}, a_c = {a_c / h:.1f} spacings")

# %%
# The run
# -------
# ``start="adhesive"`` loads with adhesion from first touch (the default ``hertz`` start begins
# from the adhesion-free state). The default criterion is ``crack-closure`` with the
# ``griffith`` attach rule, which gives the JKR jump-in on loading.
d1 = 2 * a_c ** 2 / R
# The largest tension lies at d = -a_c^2/(3R) on JKR's branch and the contact is lost at
# -0.69 a_c^2/R: the last leg, from -0.3 to -0.8 a_c^2/R, takes small steps there (a recorded
# state only catches the peak as closely as the steps pass it; force control finds it by bisection).
path = [0.0, d1, -0.3 * a_c ** 2 / R, -0.8 * a_c ** 2 / R]
s = adhbem.Solver(n=N, size=size, radius=R, E_star=E_star, gamma=dgamma, start="adhesive",
                  path=path, steps=12 if QUICK else 30)
curve = s.solve_path(progress=False)
print(f"largest tension {s.largest_tension:.4g} = {s.largest_tension / F_adh:.3f} F_adh")
print(f"resolution: JKR contact radius {s.resolution['asperity_contact_radius']:.1f} spacings, "
      f"resolved: {s.resolution['resolved']}")

# %%
# Against JKR
# -----------
# The force and the contact radius (from the contact area, ``a = sqrt(A / pi)``) along the path,
# loading solid and unloading dashed, with JKR's curve. Under displacement control the path
# follows JKR's unloading branch past the largest tension, ``F_adh``, down to where ``dF/dd`` turns
# infinite and the contact is lost.
a = np.linspace(1e-4, 1.4 * np.sqrt(curve["area"].max() / np.pi), 400)
d_jkr, F_jkr = theory.jkr_sphere(a, R, dgamma, E_star)
loading = np.arange(len(curve["d"])) <= np.argmax(curve["d"])
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.4), layout="constrained")
for ax, y, y_jkr, label in ((ax1, curve["force"] / F_adh, F_jkr / F_adh, "force $F/F_\\mathrm{adh}$"),
                            (ax2, np.sqrt(curve["area"] / np.pi) / a_c, a / a_c, "contact radius $a/a_c$")):
    ax.plot(d_jkr, y_jkr, color="0.6", lw=3, label="JKR")
    ax.plot(curve["d"][loading], y[loading], "o-", ms=3, label="adhbem, loading")
    ax.plot(curve["d"][~loading], y[~loading], "s--", ms=3, label="adhbem, unloading")
    ax.set_xlabel("indentation $d$")
    ax.set_ylabel(label)
ax1.axhline(-1, color="k", lw=0.5)
ax1.legend(fontsize=8)
for ax, y, low in ((ax1, curve["force"] / F_adh, -1.2), (ax2, np.sqrt(curve["area"] / np.pi) / a_c, 0.0)):
    ax.set_xlim(-0.5 * d1, 1.05 * d1)
    ax.set_ylim(low, 1.1 * y.max())

# %%
# What the figure says
# --------------------
# On loading, the contact jumps to a finite radius at first touch, as JKR predicts (the
# ``griffith`` attach rule: a point beside the contact joins when the edge's energy release rate
# one element further out is below dgamma). On unloading, the contact radius follows JKR's branch
# and the largest tension is within a few percent of ``F_adh`` at this resolution; it converges as
# the grid is refined (the verification pages give the figures). The same run from the command
# line::
#
#     mpirun -n 2 build/adhbem -adh_n 128 -adh_gamma 2.331e-4 -adh_start adhesive \
#         -adh_path 0,0.01758,-0.002637,-0.007031 -adh_steps 30 -adh_output jkr.h5
#
# and ``adhbem-plot jkr.h5 --normalised`` draws the same comparison from the results file.
