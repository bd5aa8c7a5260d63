"""Plots of a results file: python3 -m adhbem.plot FILE.h5 [--out FILE.png] [--states K,L,...]
[--compare OTHER.h5 ...]

Draws the force against the indentation (with the analytic curve where the indenter has one on a
free boundary: Hertz or JKR for the sphere, Kendall for the flat punch, the JKR-type cone), the
contact area against the force, and, when the file has fields (-adh_fields), contact maps of the
chosen states (default: the deepest indentation and the largest tension). Curves of other results
files (--compare, e.g. the same surface without adhesion) are drawn beside. Writes FILE.png by
default.
"""
import argparse
import math
import sys

import numpy as np

from .results import load


def analytic(params, d, area):
    """(label, d, F, A) of the analytic curve of this run, or None (periodic cells, topographies)."""
    if params.get("boundary") != "free":
        return None
    E, gamma, kind = params["E_star"], params.get("gamma", 0.0), params.get("indenter")
    amax = 1.2 * math.sqrt(max(area.max(), 1e-300) / math.pi)
    a = np.linspace(amax / 400, amax, 400)
    if kind == "sphere":
        R = params["radius"]
        F = 4 * E * a ** 3 / (3 * R) - np.sqrt(8 * math.pi * a ** 3 * E * gamma)
        dd = a ** 2 / R - np.sqrt(2 * math.pi * a * gamma / E)
        return ("JKR" if gamma > 0 else "Hertz"), dd, F, math.pi * a ** 2
    if kind == "cone":
        s = params["cone_slope"]
        F = math.pi / 2 * E * a ** 2 * s - np.sqrt(8 * math.pi * a ** 3 * E * gamma)
        dd = math.pi / 2 * a * s - np.sqrt(2 * math.pi * a * gamma / E)
        return ("JKR-type cone" if gamma > 0 else "cone"), dd, F, math.pi * a ** 2
    if kind == "punch":
        ap = params["punch_radius"]
        dcrit = -math.sqrt(2 * math.pi * ap * gamma / E)
        dd = np.linspace(max(dcrit, d.min()), d.max(), 200)
        return "Kendall", dd, 2 * ap * E * dd, np.full_like(dd, math.pi * ap ** 2)
    return None


def default_states(curve):
    """The largest load (the deepest indentation) and, when a state carries tension, the largest
    tension."""
    F = curve["force"]
    return sorted({int(np.argmax(curve["d"]))} | ({int(np.argmin(F))} if F.min() < 0 else set()))


def run_label(params):
    g = params.get("gamma", 0.0)
    return f"dgamma = {g:g}" if g else "no adhesion"


def plot(path, out=None, states=None, compare=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = out or (path[:-3] if path.endswith(".h5") else path) + ".png"
    with load(path) as r:
        c, p = r.curve, r.params
        d, F, A = c["d"], c["force"], c["area"]
        if states is None:
            states = default_states(c)
        maps = []
        if "contact" in r.field_names:
            for k in states:
                # the written state nearest to the one asked for
                row = int(r.states[np.argmin(np.abs(r.states - (k % len(d))))])
                maps.append((row, r.field("contact", row), r.field("pressure", row) if "pressure" in r.field_names else None))
        ncols = 2 + len(maps)
        fig, ax = plt.subplots(1, ncols, figsize=(5 * ncols, 4.4))
        ref = analytic(p, d, A)
        xlabel = "indentation d" if p.get("control") != "force" else "indentation d (force control)"
        ax[0].plot(d, F, ".-", ms=3, lw=0.8, label=f"adhbem, {run_label(p)}")
        ax[1].plot(F, A, ".-", ms=3, lw=0.8, label=f"adhbem, {run_label(p)}")
        for other in compare:
            with load(other) as o:
                ax[0].plot(o.curve["d"], o.curve["force"], ".-", ms=3, lw=0.8, label=f"adhbem, {run_label(o.params)}")
                ax[1].plot(o.curve["force"], o.curve["area"], ".-", ms=3, lw=0.8, label=f"adhbem, {run_label(o.params)}")
        if ref:
            label, rd, rF, rA = ref
            ax[0].plot(rd, rF, "k--", lw=1, label=label)
            ax[1].plot(rF, rA, "k--", lw=1, label=label)
        ax[0].set_xlabel(xlabel)
        ax[0].set_ylabel("force F")
        ax[1].set_xlabel("force F")
        ax[1].set_ylabel("contact area A")
        for a in ax[:2]:
            a.axhline(0, color="0.7", lw=0.5)
            a.legend()
        pulled = np.nonzero(c.get("pulled_off", np.zeros(0)))[0]
        if len(pulled):
            ax[0].plot(d[pulled], F[pulled], "rv", label="pull-off")
        Lx, Ly = p.get("Lx", 1.0), p.get("Ly", 1.0)
        for a, (row, mask, pressure) in zip(ax[2:], maps):
            extent = (-Lx / 2, Lx / 2, -Ly / 2, Ly / 2)
            if pressure is not None:
                vmax = np.max(np.abs(pressure)) or 1.0
                im = a.imshow(np.where(mask > 0, pressure, np.nan), origin="lower", extent=extent, cmap="RdBu_r",
                              vmin=-vmax, vmax=vmax, interpolation="nearest")
                fig.colorbar(im, ax=a, shrink=0.8, label="pressure (contact only)")
            else:
                a.imshow(mask, origin="lower", extent=extent, cmap="Greys", interpolation="nearest")
            a.set_title(f"state {row}: d = {d[row]:.4g}, F = {F[row]:.4g}", fontsize=10)
        fig.suptitle(f"{path}: {p.get('indenter')} indenter, {p.get('boundary')} boundary,"
                     f" {p.get('Nx')} x {p.get('Ny')}, dgamma = {p.get('gamma')}, {p.get('criterion', 'pohrt-popov')}"
                     + ("" if p.get("complete", 1) else " (incomplete run)"), fontsize=10)
        fig.tight_layout()
        fig.savefig(out, dpi=110)
        plt.close(fig)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m adhbem.plot", description=__doc__.split("\n\n")[0])
    ap.add_argument("file", help="results file written with -adh_output")
    ap.add_argument("--out", help="image file (default: FILE.png)")
    ap.add_argument("--states", help="curve rows of the contact maps, comma-separated (default: largest load and largest tension)")
    ap.add_argument("--compare", nargs="*", default=(), help="other results files whose curves go beside")
    a = ap.parse_args(argv)
    try:
        states = [int(s) for s in a.states.split(",")] if a.states else None
    except ValueError:
        ap.error(f"--states: comma-separated integers, got {a.states!r}")
    try:
        out = plot(a.file, a.out, states, a.compare)
    except (OSError, KeyError) as e:
        print(f"adhbem.plot: {a.file}: {e}", file=sys.stderr)
        return 1
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
