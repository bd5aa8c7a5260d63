"""
A measured topography
=====================

A height map from an instrument (an AFM scan, a profilometer, an interferometer) is not periodic,
is tilted, and comes in the instrument's units. This tutorial takes such a map from a file, levels
it, puts it in consistent units, and runs it on the free boundary (an isolated body, the scan
and nothing around it), saying at each step what was chosen and why.

The scan here is made up, so that the tutorial runs anywhere: a window cut out of a larger rough
surface (so its edges do not match: not periodic), tilted, offset and written in micrometres as an
instrument would export it. With a file of your own, start at "Reading the file".

Run it yourself from a clone (after ``./run build``)::

    PYTHONPATH=python /usr/bin/python3 tutorials/tutorial_5_measured_topography.py
"""
# %%
# An instrument's export
# ----------------------
# 128 x 128 pixels of 0.1 um (a 12.8 um scan), heights in um with a tilt of 2% along x and an
# offset, as a NumPy file (adhbem also reads HDF5 datasets; SurfaceTopography reads the
# instruments' own formats and hands its topography objects to ``adhbem.Solver`` directly).
import os
import tempfile

import matplotlib.pyplot as plt
import numpy as np

import adhbem

QUICK = os.environ.get("ADHBEM_TUTORIAL_QUICK") == "1"   # the test suite runs it small
n = 64 if QUICK else 128
pixel = 0.1                                                   # um
z_big, _ = adhbem.rough_surface(2 * n, size=2 * n * pixel, hurst=0.7, rms_slope=0.15, cutoff_wavelength=8 * pixel, seed=5)
scan = adhbem.gather(z_big, z_big)[:n, :n]                    # a window: its edges do not match
y, x = np.mgrid[0:n, 0:n] * pixel
scan = scan + 0.02 * x + 3.0                                  # the instrument's tilt and offset
folder = tempfile.mkdtemp()
np.save(os.path.join(folder, "scan.npy"), scan)

# %%
# Reading the file
# ----------------
# Rows are y, columns x, as instruments and adhbem store them ((Ny, Nx); SurfaceTopography's
# ``heights()`` is (nx, ny): pass its topography object instead, which adhbem transposes).
# Levelling: a least-squares plane is taken off, as an instrument's software would, since the
# tilt is the sample's mounting, not its roughness.
z = np.load(os.path.join(folder, "scan.npy"))
A = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
coef, *_ = np.linalg.lstsq(A, z.ravel(), rcond=None)
z = z - (A @ coef).reshape(z.shape)
print(f"levelled: removed a tilt of {coef[1]:.3g} (x) and {coef[2]:.3g} (y); rms height {z.std():.3g} um")

# %%
# Units and the choices
# ---------------------
# adhbem has no units: any consistent set works. Here lengths in um and stresses in MPa, so
# forces come out in uN (MPa um^2) and the work of adhesion is in MPa um = 1 N/m = 1000 mJ/m^2:
# a soft polymer's reduced modulus of 50 MPa and dgamma = 50 mJ/m^2 = 0.05 MPa um.
#
# - **Boundary**: the scan is not periodic (its edges do not match), so the free boundary:
#   an isolated body of the scan's size, pressed by its highest peaks (``boundary="free"``; a
#   periodic cell would join the scan's opposite edges with a step).
# - **Profile**: ``topography_kind="height"`` (the default) takes z as heights: the gap is
#   ``h = max(z) - z``, the highest peak touches at d = 0.
# - **Resolution**: the run says whether its grid resolves the adhesion, from the contact
#   patches that carry the tension at pull-off (for a measured map there is no spectrum to
#   estimate the asperities' JKR radius from before the run).
E_star, dgamma = 50.0, 0.05
s = adhbem.Solver(n=z.shape[::-1], size=(n * pixel, n * pixel), E_star=E_star, gamma=dgamma,
                  boundary="free", topography=z, start="adhesive",
                  path=[0.0, 0.3, -0.3], steps=10 if QUICK else 25)
curve = s.solve_path(progress=False)
r = s.resolution
print(f"pull-off force {s.pull_off_force:.3g} uN; at it, {100 * r['small_patch_tension']:.0f}% of the tension in "
      f"contact patches under 314 pixels (the smallest with a net tension: {r['smallest_tensile_patch']} pixels); "
      f"resolved: {r['resolved']}")

# %%
# The result
# ----------
# The levelled scan, and the force against the approach. Here the report says the pull-off force
# depends on the grid: at the largest tension most of it is carried by asperity contacts of a few
# pixels. Refining the grid by interpolation adds no roughness below the pixel, so the remedy is a
# scan with finer pixels (or a question that does not hinge on the smallest contacts: the loading
# curve and the contact area converge sooner than the pull-off).
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8.5, 3.5), layout="constrained")
im = ax1.imshow(z, origin="lower", extent=(0, n * pixel, 0, n * pixel), cmap="gray")
fig.colorbar(im, ax=ax1, label="height (um)")
ax1.set_xlabel("x (um)")
ax1.set_ylabel("y (um)")
k = np.argmax(curve["d"])
ax2.plot(curve["d"][:k + 1], curve["force"][:k + 1], "o-", ms=3, label="approach")
ax2.plot(curve["d"][k:], curve["force"][k:], "s--", ms=3, label="retraction")
ax2.axhline(0, color="k", lw=0.5)
ax2.set_xlabel("approach d (um)")
ax2.set_ylabel("force F (uN)")
ax2.legend(fontsize=8)

# %%
# From the command line
# ---------------------
# The same run from the file, once levelled and saved (``np.save("scan_levelled.npy", z)``)::
#
#     mpirun -n 4 build/adhbem -adh_topography scan_levelled.npy -adh_n 128 -adh_size 12.8 \
#         -adh_E_star 50 -adh_gamma 0.05 -adh_boundary free -adh_start adhesive \
#         -adh_path 0,0.3,-0.3 -adh_steps 25 -adh_output scan.h5
#
# A topography on the free boundary gets a warning line unless ``-adh_boundary free`` is given,
# since a periodic cell is more often meant for generated surfaces.
