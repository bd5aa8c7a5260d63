"""./run rough: adhesive contact of a self-affine rough surface, approach then retraction.

A periodic cell of N x N grid points (spacing 1, E* = 1) with a random self-affine surface
(Hurst 0.8, rms slope 0.1, roll-off at a quarter of the cell, cut-off at 4 grid spacings) is pressed in
from first touch (d = 0) to the indentation at which 15% of the gap profile lies below it,
then pulled back to d = 0 and on until it comes off, once with adhesion and once without. Writes
results/rough.h5 and .csv (with adhesion), results/rough_nonadhesive.h5 and .csv,
results/rough.png, and prints a short table.

Run as `./run rough [--n N] [--np P] [--gamma G] [--steps K]`. The solve runs under mpirun on P
ranks through the Python layer (the same solver as build/adhbem), whose monitor keeps the
contact maps at the largest load and the largest tension.
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
                rolloff_wavelength=a.rolloff * a.n, seed=1, boundary="periodic")


def worker(a):
    """Runs under mpirun: both solves, curves through the solver's HDF5 output, maps to .npz."""
    sys.path.insert(0, os.path.join(ROOT, "python"))
    import adhbem
    from adhbem import PETSc
    rank = PETSc.COMM_WORLD.getRank()
    opts = surface_options(a)
    z, stats = adhbem.rough_surface(a.n, size=float(a.n), hurst=0.8, rms_slope=0.1,
                                    rolloff_wavelength=opts["rolloff_wavelength"], seed=1)
    Z = adhbem.gather(z, z)
    d1 = float(np.quantile(Z.max() - Z, a.depth))
    maps = {}
    for name, gamma in (("rough", a.gamma), ("rough_nonadhesive", 0.0)):
        # the same indentations on approach and retraction down to d = 0, then on to pull-off
        s = adhbem.Solver(**opts, gamma=gamma, start="adhesive", attach="reach",
                          path=[0.0, d1, 0.0, -d1], steps=a.steps, monitor=True,
                          output=os.path.join(a.results, name + ".h5"))
        best = {"load": (-np.inf, None), "tension": (np.inf, None)}

        def keep(step, state, s=s, best=best, deepest=[-np.inf]):
            # the contact maps of the largest load (the deepest indentation) and of the largest
            # tension so far
            F = state["force"]
            for key, better in (("load", state["d"] > deepest[0]), ("tension", F < best["tension"][0] and F < 0)):
                if better:
                    best[key] = (F, adhbem.gather(s.contact_mask(), s.compliance) > 0)
            deepest[0] = max(deepest[0], state["d"])
        s.monitor(keep)
        if rank == 0:
            print(f"\n{name}: dgamma = {gamma}, N = {a.n}, path 0 -> {d1:.4g} -> 0 -> {-d1:.4g}, {a.steps} steps a leg", flush=True)
        s.solve_path()
        if name == "rough":
            maps = {f"{k}_map": v[1] for k, v in best.items() if v[1] is not None}
            maps.update({f"{k}_force": v[0] for k, v in best.items() if v[1] is not None})
        del s
    if rank == 0:
        np.savez_compressed(os.path.join(a.results, "rough_maps.npz"), **maps)


def loop_energy(d, F):
    """Energy dissipated over the approach-retraction loop, the loop integral of F dd (no force
    before first touch at d = 0)."""
    return np.trapz(F, d) if len(d) > 1 else 0.0


def report(a):
    import h5py
    curves = {}
    for name in ("rough", "rough_nonadhesive"):
        with h5py.File(os.path.join(a.results, name + ".h5"), "r") as f:
            curves[name] = {k: f["curve"][k][()] for k in f["curve"]}
            attrs = dict(f.attrs)
    c, c0 = curves["rough"], curves["rough_nonadhesive"]
    k, k0 = int(np.argmax(c["d"])), int(np.argmax(c0["d"]))
    N2 = a.n * a.n
    seconds = c["seconds"].sum() + c0["seconds"].sum()
    print(f"\nrough surface {a.n} x {a.n} (Hurst {attrs['hurst']:.2g}, rms slope {attrs['realised_rms_slope']:.4g},"
          f" rms height {attrs['realised_rms_height']:.4g}), dgamma = {a.gamma}, {a.np} ranks:"
          f" {seconds:.0f} s of solving, {int(c['ksp_iterations'].sum() + c0['ksp_iterations'].sum())} KSP iterations,"
          f" {int(c['compliance_applications'].sum() + c0['compliance_applications'].sum())} compliance applications,"
          f" {int(c['fft_pairs'].sum() + c0['fft_pairs'].sum())} FFT pairs")
    print(f"{'quantity':<46}{'with adhesion':>16}{'without':>16}")
    rows = [("largest pull-off force (largest tension)", max(0.0, -c["force"].min()), max(0.0, -c0["force"].min())),
            ("force at the largest load", c["force"][k], c0["force"][k0]),
            ("contact area fraction at the largest load", c["area"][k] / N2, c0["area"][k0] / N2),
            ("contact patches at the largest load", c["patches"][k], c0["patches"][k0]),
            ("energy dissipated over the loop", loop_energy(c["d"], c["force"]), loop_energy(c0["d"], c0["force"]))]
    for name, x, y in rows:
        print(f"{name:<46}{x:>16.6g}{y:>16.6g}")
    plot(a, c, c0)


def in_contact(c):
    """The states up to the first one without contact after the deepest: a retraction that has
    come off has nothing more to show."""
    k = int(np.argmax(c["d"]))
    off = np.nonzero(c["contact_points"][k:] == 0)[0]
    end = k + int(off[0]) + 1 if len(off) else len(c["d"])
    return {key: v[:end] for key, v in c.items()}


def plot(a, c, c0):
    c, c0 = in_contact(c), in_contact(c0)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    maps = np.load(os.path.join(a.results, "rough_maps.npz"))
    N2 = a.n * a.n
    fig, ax = plt.subplots(2, 2, figsize=(11, 9.5))
    ax[0, 0].plot(c["d"], c["force"], ".-", label=f"dgamma = {a.gamma}")
    ax[0, 0].plot(c0["d"], c0["force"], ".-", label="no adhesion")
    ax[0, 0].axhline(0, color="gray", lw=0.5)
    ax[0, 0].set(xlabel="indentation d", ylabel="force F (mean pressure x cell area)",
                 title="approach and retraction: the hysteresis loop")
    ax[0, 0].legend()
    ax[0, 1].plot(c["force"], c["area"] / N2, ".-", label=f"dgamma = {a.gamma}")
    ax[0, 1].plot(c0["force"], c0["area"] / N2, ".-", label="no adhesion")
    ax[0, 1].set(xlabel="force F", ylabel="contact area fraction A / A0", title="contact area against force")
    ax[0, 1].legend()
    for j, key, title in ((0, "load", "largest load"), (1, "tension", "largest tension")):
        axm = ax[1, j]
        if f"{key}_map" in maps:
            m = maps[f"{key}_map"]
            # a small contact is shown in its own window (the cell is periodic: no wrap here)
            j, i = np.nonzero(m)
            pad = 16
            j0, j1, i0, i1 = 0, m.shape[0], 0, m.shape[1]
            if len(j):
                j0, j1 = max(j.min() - pad, 0), min(j.max() + pad + 1, m.shape[0])
                i0, i1 = max(i.min() - pad, 0), min(i.max() + pad + 1, m.shape[1])
            axm.imshow(m[j0:j1, i0:i1], origin="lower", cmap="Greys", interpolation="nearest",
                       extent=(i0 - 0.5, i1 - 0.5, j0 - 0.5, j1 - 0.5))
            axm.set_title(f"contact map at the {title}, F = {float(maps[key + '_force']):.4g}")
        else:
            axm.set_title(f"no state carries a tension")
        axm.set(xlabel="i", ylabel="j")
    fig.tight_layout()
    out = os.path.join(a.results, "rough.png")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}, {os.path.join(a.results, 'rough.h5')} (.csv), {os.path.join(a.results, 'rough_nonadhesive.h5')} (.csv)")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, default=1024, help="grid points per side")
    p.add_argument("--np", type=int, default=2, help="MPI ranks")
    p.add_argument("--gamma", type=float, default=0.004, help="work of adhesion (E* = 1, grid spacing 1)")
    p.add_argument("--rolloff", type=float, default=0.25, help="roll-off wavelength over the cell size")
    p.add_argument("--steps", type=int, default=10, help="steps per leg")
    p.add_argument("--depth", type=float, default=0.15,
                   help="the deepest indentation: the fraction of the gap profile that lies below it")
    p.add_argument("--results", default=os.path.join(ROOT, "results"))
    p.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.worker:
        worker(a)
        return
    os.makedirs(a.results, exist_ok=True)
    cmd = ["mpirun", "--oversubscribe", "-n", str(a.np), sys.executable, os.path.abspath(__file__), "--worker",
           "--n", str(a.n), "--np", str(a.np), "--gamma", repr(a.gamma), "--steps", str(a.steps),
           "--rolloff", repr(a.rolloff), "--depth", repr(a.depth), "--results", a.results]
    subprocess.run(cmd, check=True)
    report(a)


if __name__ == "__main__":
    main()
