"""./run rough: adhesive contact of a self-affine rough surface, approach then retraction.

A periodic cell of N x N grid points (spacing 1, E* = 1) with a random self-affine surface
(Hurst 0.8, rms slope 0.1, roll-off at the cell, cut-off at 32 grid spacings) is pressed in from
first touch (d = 0) to the indentation at which a quarter of the gap profile lies below it, then
pulled back to d = 0 and on until it comes off, once with adhesion (dgamma = 0.209 E* h) and once
without, with the default detachment criterion (crack-closure) and attach rule (griffith). Writes
results/rough.h5 and .csv (with adhesion), results/rough_nonadhesive.h5 and .csv,
results/rough.png, and prints a short table and how well the grid resolves the adhesion.

The parameters are those at which the adhesion is resolved: the smallest asperities' JKR contact
radius at pull-off spans about 20 grid spacings, and on the same kind of surface refined from 10
to 20 spacings (./run bench convergence --config resolved) the pull-off force and the loop's
energy change by a few percent (docs/verification/rough-convergence.md). A shorter cut-off or a weaker adhesion makes
the asperity contacts a few elements wide: then the numbers depend on the grid, and the run says so.

Run as `./run rough [--n N] [--np P] [--gamma G] [--cutoff C] [--steps K]`. The solve runs under mpirun on P
ranks through the Python layer (the same solver as build/adhbem); the adhesive run writes its
pressure fields and contact masks (-adh_fields pressure,contact: 9 bytes a point a state, about
40 MB at 256^2), and the plot is adhbem.plot's: the pressure maps at the deepest indentation and
at the largest tension, with a colour bar, as in the README's figure.
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def surface_options(a):
    return dict(n=a.n, size=float(a.n), E_star=1.0, indenter="rough", hurst=0.8, rms_slope=0.1,
                rolloff_wavelength=a.rolloff * a.n, cutoff_wavelength=a.cutoff, seed=1, boundary="periodic")


def worker(a):
    """Runs under mpirun: both solves, through the solver's HDF5 output."""
    sys.path.insert(0, os.path.join(ROOT, "python"))
    import adhbem
    from adhbem import PETSc
    rank = PETSc.COMM_WORLD.getRank()
    opts = surface_options(a)
    z, stats = adhbem.rough_surface(a.n, size=float(a.n), hurst=0.8, rms_slope=0.1,
                                    rolloff_wavelength=opts["rolloff_wavelength"],
                                    cutoff_wavelength=opts["cutoff_wavelength"], seed=1)
    Z = adhbem.gather(z, z)
    d1 = float(np.quantile(Z.max() - Z, a.depth))
    for name, gamma in (("rough", a.gamma), ("rough_nonadhesive", 0.0)):
        # the same indentations on approach and retraction down to d = 0, then on to pull-off
        s = adhbem.Solver(**opts, gamma=gamma, start="adhesive",
                          path=[0.0, d1, 0.0, -d1], steps=a.steps,
                          fields="pressure,contact" if gamma else "none",
                          output=os.path.join(a.results, name + ".h5"))
        if rank == 0:
            print(f"\n{name}: dgamma = {gamma}, N = {a.n}, path 0 -> {d1:.4g} -> 0 -> {-d1:.4g}, {a.steps} steps a leg", flush=True)
        s.solve_path()
        del s


def loop_energy(d, F):
    """Energy dissipated over the approach-retraction loop, the loop integral of F dd (no force
    before first touch at d = 0)."""
    return np.trapz(F, d) if len(d) > 1 else 0.0


def report(a):
    sys.path.insert(0, os.path.join(ROOT, "python"))
    import adhbem
    curves, params = {}, {}
    for name in ("rough", "rough_nonadhesive"):
        with adhbem.load(os.path.join(a.results, name + ".h5")) as r:
            curves[name], params[name] = r.curve, r.params
    attrs = params["rough"]  # the adhesive run's: its resolution
    c, c0 = curves["rough"], curves["rough_nonadhesive"]
    k, k0 = int(np.argmax(c["d"])), int(np.argmax(c0["d"]))
    seconds = c["seconds"].sum() + c0["seconds"].sum()
    print(f"\nrough surface {a.n} x {a.n} (Hurst {attrs['hurst']:.2g}, rms slope {attrs['realised_rms_slope']:.4g},"
          f" rms height {attrs['realised_rms_height']:.4g}), dgamma = {a.gamma}, {a.np} ranks:"
          f" {seconds:.0f} s of solving, {int(c['ksp_iterations'].sum() + c0['ksp_iterations'].sum())} KSP iterations,"
          f" {int(c['compliance_applications'].sum() + c0['compliance_applications'].sum())} compliance applications,"
          f" {int(c['fft_pairs'].sum() + c0['fft_pairs'].sum())} FFT pairs")
    print(f"{'quantity':<52}{'with adhesion':>16}{'without':>16}")
    rows = [("pull-off force (the largest tension)", max(0.0, -c["force"].min()), max(0.0, -c0["force"].min())),
            ("mean pressure at the deepest indentation", c["mean_pressure"][k], c0["mean_pressure"][k0]),
            ("contact area fraction at the deepest indentation", c["area_fraction"][k], c0["area_fraction"][k0]),
            ("contact patches at the deepest indentation", c["patches"][k], c0["patches"][k0]),
            ("energy dissipated over the loop", loop_energy(c["d"], c["force"]), loop_energy(c0["d"], c0["force"]))]
    for name, x, y in rows:
        print(f"{name:<52}{x:>16.6g}{y:>16.6g}")
    ac = attrs.get("asperity_contact_radius", 0.0)
    share = attrs.get("pull_off_small_patch_tension", 0.0)
    print(f"resolution: the smallest asperities' JKR contact radius spans about {ac:.3g} grid spacings;"
          f" at the largest tension {100 * share:.0f}% of the tension is in contact patches under 314 elements:"
          + (" the grid resolves the adhesion" if attrs.get("adhesion_resolved") else
             " the pull-off force depends on the grid (refine it, or raise --cutoff or --gamma)"))
    plot(a, c, c0)


def plot(a, c, c0):
    """adhbem.plot: the loop and the area fraction against mean pressure beside the non-adhesive
    run, and the pressure maps at the deepest indentation and the largest tension."""
    from adhbem.plot import plot as draw
    out = draw(os.path.join(a.results, "rough.h5"), compare=[os.path.join(a.results, "rough_nonadhesive.h5")],
               labels=[f"with adhesion ($\\Delta\\gamma$ = {a.gamma:g})", "without adhesion"])
    print(f"wrote {out}, {os.path.join(a.results, 'rough.h5')} (.csv, .xmf), {os.path.join(a.results, 'rough_nonadhesive.h5')} (.csv)")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, default=256, help="grid points per side")
    p.add_argument("--np", type=int, default=2, help="MPI ranks")
    p.add_argument("--gamma", type=float, default=0.209, help="work of adhesion (E* = 1, grid spacing 1)")
    p.add_argument("--rolloff", type=float, default=1.0, help="roll-off wavelength over the cell size")
    p.add_argument("--cutoff", type=float, default=32.0, help="cut-off wavelength in grid spacings")
    p.add_argument("--steps", type=int, default=25, help="steps per leg")
    p.add_argument("--depth", type=float, default=0.25,
                   help="the deepest indentation: the fraction of the gap profile that lies below it")
    p.add_argument("--results", default=os.path.join(ROOT, "results"))
    p.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.worker:
        worker(a)
        return
    os.makedirs(a.results, exist_ok=True)
    cmd = ["mpirun", "--oversubscribe", "-n", str(a.np), sys.executable, os.path.abspath(__file__), "--worker",
           "--n", str(a.n), "--np", str(a.np), "--gamma", repr(a.gamma), "--cutoff", repr(a.cutoff), "--steps", str(a.steps),
           "--rolloff", repr(a.rolloff), "--depth", repr(a.depth), "--results", a.results]
    subprocess.run(cmd, check=True)
    report(a)


if __name__ == "__main__":
    main()
