"""
A rough periodic surface
========================

The study most users come for: a random self-affine surface on a periodic cell, pressed in and
pulled off with adhesion and without. It shows the hysteresis loop of mean pressure against
indentation, the contact area against the load beside the non-adhesive curve, the contact maps,
the resolution report, and the check that matters most: the same surface on a grid twice as fine.

Run it yourself from a clone (after ``./run build``)::

    PYTHONPATH=python /usr/bin/python3 tutorials/tutorial_4_rough_surface.py

For cells that need many ranks, the same script runs under ``mpirun -n P``.
"""
# %%
# The surface
# -----------
# A cell of side L = 96 (lengths in any unit; here grid spacings of the coarse grid), Hurst
# exponent 0.8, rms slope 0.1, power spectrum rolled off at the cell and cut off at L/4: the
# smallest asperities are 24 spacings wide on the coarse grid and 48 on the fine one. The heights
# are drawn once on the fine grid; the coarse grid samples every other point of it, so both
# grids see the same surface (a band-limited surface is resolved by both).
import os
import tempfile

import matplotlib.pyplot as plt
import numpy as np

import adhbem
import adhbem.plot

QUICK = os.environ.get("ADHBEM_TUTORIAL_QUICK") == "1"   # the test suite runs it small
N = 32 if QUICK else 96               # the coarse grid; the fine one has 2N
L, E_star, dgamma = float(N), 1.0, 0.05
z_vec, stats = adhbem.rough_surface(2 * N, size=L, hurst=0.8, rms_slope=0.1, cutoff_wavelength=L / 4, seed=3)
Z_fine = adhbem.gather(z_vec, z_vec)  # (2N, 2N) heights, on every rank
Z = {2 * N: Z_fine, N: Z_fine[::2, ::2]}
h = Z[N].max() - Z[N]                 # the gap profile: the highest peak touches at d = 0
d1 = float(np.quantile(h, 0.4))       # pressed in until 40% of the profile lies below
print(f"rms height {stats['realised_rms_height']:.3g}, rms slope {stats['realised_rms_slope']:.3g}, d1 = {d1:.3g}")

# %%
# With adhesion and without
# -------------------------
# Displacement control from first touch to d1, back to 0 and on until the surfaces come off,
# with adhesion (the default criterion, crack-closure, and attach rule, griffith) and without.
# Each run writes a results file with the pressure and contact map of every state; the runs print the
# resolution report at the end (and ``Solver.resolution`` returns it).
out = tempfile.mkdtemp()
steps = 8 if QUICK else 20


def run(n, gamma, name):
    s = adhbem.Solver(n=n, size=L, E_star=E_star, gamma=gamma, boundary="periodic", topography=Z[n],
                      start="adhesive", path=[0.0, d1, 0.0, -d1], steps=steps, fields="pressure,contact",
                      output=os.path.join(out, name + ".h5"))
    s.solve_path(progress=False)
    return s


sticky = run(N, dgamma, "adhesive")
plain = run(N, 0.0, "nonadhesive")
r = sticky.resolution
print(f"smallest asperities' JKR contact radius about {r['asperity_contact_radius']:.0f} spacings; "
      f"{100 * r['small_patch_tension']:.0f}% of the tension at pull-off in patches under 314 elements; "
      f"resolved: {r['resolved']}")

# %%
# The loop, the area and the contact maps
# ---------------------------------------
# ``adhbem.plot`` draws each panel on axes of your own (``adhbem.plot.figure`` and the
# ``adhbem-plot`` command put them together for a paper): the loop as mean pressure against
# indentation, the contact area fraction against the mean pressure beside the non-adhesive run,
# and the contact maps at the deepest indentation and at the largest tension.
files = [os.path.join(out, "adhesive.h5"), os.path.join(out, "nonadhesive.h5")]
labels = ["with adhesion", "without"]
fig, axes = plt.subplots(2, 2, figsize=(8, 7), layout="constrained")
adhbem.plot.curve(axes[0, 0], files[0], compare=files[1:], labels=labels, legend=False)
adhbem.plot.area(axes[0, 1], files[0], compare=files[1:], labels=labels)
adhbem.plot.contact_map(axes[1, 0], files[0], "deepest")
adhbem.plot.contact_map(axes[1, 1], files[0], "tension")

# %%
# Is the grid fine enough?
# ------------------------
# The resolution report judges from the patches that carry the tension; the proof is the same
# surface on a grid twice as fine. The pull-off force (the largest tension) and the energy the
# loop dissipates should change little.
fine = run(2 * N, dgamma, "adhesive_fine")


def loop_energy(c):
    return float(np.trapz(c["force"], c["d"]))


for name, s in (("coarse", sticky), ("fine", fine)):
    c = s.curve()
    print(f"{name:>6} grid: pull-off force {s.pull_off_force:.4g}, "
          f"loop energy {loop_energy(c):.4g}, area fraction at d1 {c['area'][np.argmax(c['d'])] / L ** 2:.3f}")

# %%
# What the numbers say
# --------------------
# Adhesion makes the contact larger at every load and lets it carry tension on the way out; the
# loop between loading and unloading is the energy lost to the jumps of asperity contacts in and
# out. When the two grids agree to a few percent the answer belongs to the surface and not to the
# grid; when they do not, refine further (or make the adhesion weaker relative to the asperities'
# size: the resolution report's JKR radius is the guide; under 10 spacings the run says the
# pull-off force depends on the grid, and 20 is the aim).
