"""Plots of a results file: python3 -m adhbem.plot FILE.h5 [--out FILE.png] [--states K,L,...]
[--compare OTHER.h5 ...] [--normalised]

Draws the force against the indentation, with the approach and the retraction told apart (and
the analytic curve where the indenter has one on a free boundary: Hertz or JKR for the sphere,
Kendall for the flat punch, the JKR-type cone), the contact area against the force, and, when the
file has fields (-adh_fields), contact maps of the chosen states (default: the deepest
indentation and the largest tension). Curves of other results files (--compare, e.g. the same
surface without adhesion) are drawn beside, each labelled by its file name and what differs
between the runs. --normalised draws the JKR sphere on a free boundary in F/F_adh, a/a_c and
d/|d_c|, and a periodic cell as mean pressure and contact area fraction. Writes FILE.png by
default.

adhbem has no units of its own: lengths, E* and dgamma are those of the input, any consistent
set (forces are then in E* x length^2, pressures in E*).
"""
import argparse
import math
import os
import sys

import numpy as np

from .results import load

UNITS_NOTE = "units: those of the input (any consistent set); force in E* x length^2, pressure in E*"
LENGTH = "input length unit"


class UsageError(ValueError):
    """An option that does not fit the file (--states out of range, --normalised without scales)."""


def analytic(params, d, area):
    """(label, d, F, A) of the analytic curve of this run, or None (periodic cells, topographies,
    dgamma fields)."""
    if params.get("boundary") != "free" or params.get("gamma_field") or params.get("critical_stress_fixed"):
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


def adhesion_label(params):
    """What sticks: a dgamma field (-adh_gamma_field), a fixed critical stress, the scalar dgamma,
    or nothing."""
    if params.get("gamma_field"):
        source = params.get("gamma_field_file")
        return "dgamma field" + (f" {os.path.basename(source)}" if source else "")
    if params.get("critical_stress_fixed"):
        return f"critical stress {params.get('Sigma', 0.0):g}"
    g = params.get("gamma", 0.0)
    return f"dgamma = {g:g}" if g else "no adhesion"


def describe(params):
    """The features of a run that a comparison may differ in, in the order the labels give them."""
    criterion = params.get("criterion", "pohrt-popov")
    if criterion == "crack-closure":
        low = params.get("criterion_radius", 16)
        high = max(low, params.get("criterion_radius_max", low))  # files before 2026-11-25: a fixed window
        criterion += f" (radius {low:g})" if high == low else f" (radius {low:g}-{high:g})"
    Nx, Ny = params.get("Nx"), params.get("Ny")
    return {"adhesion": adhesion_label(params), "criterion": criterion,
            "attach": f"attach {params['attach']}" if "attach" in params else None,
            "grid": f"N = {Nx}" if Nx == Ny else f"{Nx} x {Ny}",
            "control": f"{params.get('control', 'displacement')} control", "start": f"{params.get('start')} start",
            "indenter": params.get("indenter"), "boundary": f"{params.get('boundary')} boundary"}


def run_labels(paths, params):
    """One legend label per run: alone, what sticks; among others, the file's stem and what differs
    between the runs (adhesion, criterion, attach rule, grid, ...)."""
    if len(paths) == 1:
        return [f"adhbem, {adhesion_label(params[0])}"]
    described = [describe(p) for p in params]
    differs = [k for k in described[0] if len({d.get(k) for d in described}) > 1]
    names = [os.path.splitext(os.path.basename(p))[0] for p in paths]
    if len(set(names)) < len(names):  # the same name in other directories
        names = [os.path.join(os.path.basename(os.path.dirname(os.path.abspath(p))), n) for p, n in zip(paths, names)]
    labels = []
    for name, d in zip(names, described):
        what = [d[k] for k in differs if d.get(k)]
        labels.append(name + (": " + ", ".join(what) if what else ""))
    return labels


def legs(curve, params):
    """The curve as runs of rows in one direction: (+1 approach or -1 retraction, rows), each run
    beginning at the row where the one before ends. The direction is that of the controlled
    quantity (d, or the force under force control) from one row to the next."""
    x = curve["force"] if params.get("control") == "force" else curve["d"]
    if len(x) < 2:
        return [(1, np.arange(len(x)))]
    step = np.sign(np.diff(x))  # step k goes from row k to row k + 1
    for k in range(len(step)):
        if step[k] == 0:  # a step that does not move goes on as the one before
            step[k] = step[k - 1] if k else 1
    out, first = [], 0
    for k in range(1, len(step) + 1):
        if k == len(step) or step[k] != step[first]:
            out.append((int(step[first]), np.arange(first, k + 1)))
            first = k
    return out


def scales(params):
    """The scales --normalised divides by: ("jkr", F_adh, a_c, |d_c|) for a sphere with a uniform
    dgamma > 0 on a free boundary, ("periodic", cell area) for a periodic cell, else None."""
    if params.get("boundary") == "periodic":
        return ("periodic", params["Nx"] * params["hx"] * params["Ny"] * params["hy"])
    g = params.get("gamma", 0.0)
    if (params.get("indenter") == "sphere" and params.get("boundary") == "free" and g > 0
            and not params.get("gamma_field") and not params.get("critical_stress_fixed")):
        R, E = params["radius"], params["E_star"]
        return ("jkr", 1.5 * math.pi * g * R, (9 * math.pi * g * R ** 2 / (8 * E)) ** (1 / 3),
                (3 * math.pi ** 2 * g ** 2 * R / (64 * E ** 2)) ** (1 / 3))
    return None


def quantities(d, F, A, scale):
    """(x, F, area) as drawn, and their axis labels, in the input's units or normalised."""
    if scale is None:
        return (d, F, A), (f"indentation d ({LENGTH})", "force F (input units: E* x length^2)",
                           f"contact area A ({LENGTH}^2)")
    if scale[0] == "jkr":
        _, Fadh, ac, dc = scale
        return (d / dc, F / Fadh, np.sqrt(A / math.pi) / ac), \
            ("indentation d / |d_c|", "force F / F_adh", "contact radius a / a_c  (a = sqrt(A / pi))")
    cell = scale[1]
    return (d, F / cell, A / cell), (f"indentation d ({LENGTH})", "mean pressure F / (Lx Ly) (units of E*)",
                                     "contact area fraction A / (Lx Ly)")


def check_states(path, states, n, field_states):
    if not len(field_states):
        raise UsageError(f"--states: {path} has no fields to map (write them with -adh_fields)")
    for k in states:
        if not -n <= k < n:
            raise UsageError(f"--states: {k} is not a state of {path}: its curve has rows 0 to {n - 1} "
                             f"(or -{n} to -1, counted from the end)")


def draw_curve(ax, x, y, rows_by_leg, color, label, legend_done):
    """One run's curve on ax: the approach solid, the retraction dashed, one legend entry each."""
    for direction, rows in rows_by_leg:
        kind = "approach" if direction > 0 else "retraction"
        style = dict(ls="-", marker="o", mfc=color) if direction > 0 else dict(ls="--", marker="v", mfc="white")
        first = (label, kind) not in legend_done
        legend_done.add((label, kind))
        ax.plot(x[rows], y[rows], color=color, ms=3.5, lw=1.0, mec=color, **style,
                label=f"{label}, {kind}" if first else "_nolegend_")


def figure(path, states=None, compare=(), normalised=False):
    """The matplotlib Figure of results file `path` (see the module's description); raises
    UsageError when states or normalised do not fit the files."""
    import matplotlib
    from matplotlib.figure import Figure

    paths = [path, *compare]
    runs = []
    for p in paths:
        with load(p) as r:
            runs.append((r.curve, r.params))
    for p, (curve, _) in zip(paths, runs):
        if not len(curve["d"]):
            raise ValueError(f"{p} holds no state (the run stopped before its first)")
    params = [p for _, p in runs]
    labels = run_labels(paths, params)
    run_scales = [scales(p) for p in params] if normalised else [None] * len(runs)
    if normalised:
        for p, sc in zip(paths, run_scales):
            if sc is None:
                raise UsageError(f"--normalised: {p} has no scales to divide by: they are JKR's for a sphere with a "
                                 "uniform dgamma > 0 on a free boundary, and the cell's area on a periodic cell")
        if len({sc[0] for sc in run_scales}) > 1:
            raise UsageError("--normalised: the runs have different scales (a JKR sphere and a periodic cell)")

    c, p = runs[0]
    with load(path) as r:
        n = len(c["d"])
        if states is None:
            states = default_states(c) if "contact" in r.field_names else []
        else:
            check_states(path, states, n, r.states if "contact" in r.field_names else [])
        maps = []
        for k in states:
            # the written state nearest to the one asked for (-adh_fields_stride)
            row = int(r.states[np.argmin(np.abs(r.states - (k % n)))])
            maps.append((row, r.field("contact", row), r.field("pressure", row) if "pressure" in r.field_names else None))

    # how well the grid resolves the adhesion, per state (files of adhesive runs that have it)
    resolution = "small_patch_tension" in c and c["force"].min() < 0
    ncols = 2 + len(maps) + resolution
    fig = Figure(figsize=(5.2 * ncols, 4.8))
    ax = fig.subplots(1, ncols, squeeze=False)[0]
    colors = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
    legend_done = (set(), set())  # (run, leg) entries each axes has in its legend
    marked_contact_lost = False
    names = quantities(c["d"], c["force"], c["area"], run_scales[0])[1]
    for i, ((curve, prm), label, sc) in enumerate(zip(runs, labels, run_scales)):
        color = colors[i % len(colors)]
        (x, F, A), _ = quantities(curve["d"], curve["force"], curve["area"], sc)
        by_leg = legs(curve, prm)
        draw_curve(ax[0], x, F, by_leg, color, label, legend_done[0])
        draw_curve(ax[1], F, A, by_leg, color, label, legend_done[1])
        if curve["force"].min() < 0:
            k = int(np.argmin(curve["force"]))
            own = "" if len(runs) == 1 else f" ({label.split(':')[0]})"
            ax[0].plot(x[k], F[k], "*", ms=13, color="red" if i == 0 else color, mec="red", zorder=5,
                       label=f"pull-off force{own} F = {-curve['force'][k]:.4g} (largest tension)")
        lost = np.nonzero(curve.get("pulled_off", np.zeros(0)))[0]
        lost = [k for k in lost if curve["force"][k] >= 0]  # force control ends at the largest tension itself
        if len(lost):
            ax[0].plot(x[lost], F[lost], "x", ms=8, mew=1.5, color=color, zorder=5,
                       label="_nolegend_" if marked_contact_lost else "contact lost: the leg ends")
            marked_contact_lost = True
    ref = analytic(p, c["d"], c["area"])
    if ref:
        name, rd, rF, rA = ref
        (rx, rF, rA), _ = quantities(rd, rF, rA, run_scales[0])
        ax[0].plot(rx, rF, "k:", lw=1.3, label=f"{name} (theory)")
        ax[1].plot(rF, rA, "k:", lw=1.3, label=f"{name} (theory)")
    xlabel, flabel, alabel = names
    if p.get("control") == "force":
        xlabel += ", force control"
    ax[0].set_xlabel(xlabel)
    ax[0].set_ylabel(flabel)
    ax[1].set_xlabel(flabel)
    ax[1].set_ylabel(alabel)
    for a in ax[:2]:
        a.axhline(0, color="0.7", lw=0.5)
        a.ticklabel_format(style="sci", scilimits=(-3, 4))  # mean pressures of 1e-3 E* stay legible
        a.legend(fontsize=8)
    if run_scales[0] and run_scales[0][0] == "jkr":
        _, Fadh, ac, dc = run_scales[0]
        ax[0].set_title(f"JKR scales: F_adh = 1.5 pi dgamma R = {Fadh:.4g}, a_c = {ac:.4g}, |d_c| = {dc:.4g}", fontsize=8)

    Lx, Ly = p.get("Lx", 1.0), p.get("Ly", 1.0)
    d, F = c["d"], c["force"]
    for a, (row, mask, pressure) in zip(ax[2:], maps):
        extent = (-Lx / 2, Lx / 2, -Ly / 2, Ly / 2)
        if pressure is not None:
            vmax = np.max(np.abs(pressure)) or 1.0
            im = a.imshow(np.where(mask > 0, pressure, np.nan), origin="lower", extent=extent, cmap="RdBu_r",
                          vmin=-vmax, vmax=vmax, interpolation="nearest")
            fig.colorbar(im, ax=a, shrink=0.8, label="pressure p on the contact (units of E*)")
        else:
            a.imshow(mask, origin="lower", extent=extent, cmap="Greys", interpolation="nearest")
        a.set_xlabel(f"x ({LENGTH})")
        a.set_ylabel(f"y ({LENGTH})")
        a.set_title(f"state {row}: d = {d[row]:.4g}, F = {F[row]:.4g}", fontsize=10)
    if resolution:
        draw_resolution(ax[-1], runs, labels, colors)
    attach = f", attach {p['attach']}" if "attach" in p else ""
    fig.suptitle(f"{path}: {p.get('indenter')} indenter, {p.get('boundary')} boundary, {p.get('Nx')} x {p.get('Ny')},"
                 f" {adhesion_label(p)}, {p.get('criterion', 'pohrt-popov')}{attach}"
                 + ("" if p.get("complete", 1) else " (incomplete run)"), fontsize=10)
    fig.text(0.005, 0.005, UNITS_NOTE, fontsize=7, color="0.4", ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    return fig


def draw_resolution(a, runs, labels, colors):
    """The share of the tension carried by contact patches under 314 elements, per state: above 0.1
    at the pull-off force the grid does not resolve the adhesion."""
    for i, ((curve, prm), label) in enumerate(zip(runs, labels)):
        if "small_patch_tension" not in curve:
            continue
        rows = np.arange(len(curve["d"]))
        tension = curve["force"] < 0
        if not tension.any():
            continue  # a run without tension (no adhesion) has nothing to resolve
        a.plot(rows[tension], curve["small_patch_tension"][tension], ".-", ms=4, color=colors[i % len(colors)],
               label=label.split(":")[0] if len(runs) > 1 else "states carrying tension")
        k = int(np.argmin(curve["force"]))
        ac = prm.get("asperity_contact_radius")
        verdict = "resolved" if prm.get("adhesion_resolved") else "not resolved"
        a.plot(k, curve["small_patch_tension"][k], "*", ms=13, color="red" if i == 0 else colors[i % len(colors)],
               mec="red", label=f"pull-off force: {verdict}" + (f" (asperity a_c/h {ac:.3g})" if ac else ""))
    a.axhline(0.1, color="0.5", ls="--", lw=0.8, label="resolved at most")
    a.set_ylim(-0.03, 1.03)
    a.set_xlabel("state (curve row)")
    a.set_ylabel("share of the tension in patches < 314 elements")
    a.set_title("resolution of the adhesion", fontsize=10)
    a.legend(fontsize=8)


def plot(path, out=None, states=None, compare=(), normalised=False):
    """Draws figure(path, ...) into out (default: FILE.png beside FILE.h5) and returns out."""
    out = out or (path[:-3] if path.endswith(".h5") else path) + ".png"
    figure(path, states, compare, normalised).savefig(out, dpi=110)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m adhbem.plot", description=__doc__.split("\n\n")[0])
    ap.add_argument("file", help="results file written with -adh_output")
    ap.add_argument("--out", help="image file (default: FILE.png)")
    ap.add_argument("--states", help="curve rows of the contact maps, comma-separated, negative from the end "
                    "(default: largest load and largest tension)")
    ap.add_argument("--compare", nargs="*", default=(), help="other results files whose curves go beside")
    ap.add_argument("--normalised", action="store_true",
                    help="JKR sphere on a free boundary: F/F_adh, a/a_c, d/|d_c|; periodic cell: mean pressure and "
                    "contact area fraction")
    a = ap.parse_args(argv)
    try:
        states = [int(s) for s in a.states.split(",")] if a.states else None
    except ValueError:
        ap.error(f"--states: comma-separated integers, got {a.states!r}")
    try:
        out = plot(a.file, a.out, states, a.compare, a.normalised)
    except UsageError as e:
        ap.error(str(e))
    except (OSError, KeyError, ValueError) as e:
        print(f"adhbem.plot: {a.file}: {e}", file=sys.stderr)
        return 1
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
