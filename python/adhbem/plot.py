"""Figures of results files for papers: python3 -m adhbem.plot FILE.h5 [--out FILE.pdf]
[--width column|double] [--states deepest,tension,K] [--compare OTHER.h5 ...] [--normalised]
[--resolution]

One function a panel, each drawing on matplotlib axes of your own:

- ``curve(ax, results)``: force against indentation (mean pressure on a periodic cell), the
  approach solid and the retraction dashed, the analytic curve over the data's range where the
  indenter has one (Hertz or JKR for the sphere, Kendall's punch, the JKR-type cone), the pull-off
  force (the largest tension) and the state where the contact was lost marked;
- ``area(ax, results)``: contact area against force (area fraction against mean pressure on a
  periodic cell);
- ``contact_map(ax, results, state)``: the pressure on the contact (or the contact set) of a state,
  named by what it is (``"deepest"`` indentation, largest ``"tension"``) or by its curve row, with
  its colour bar;
- ``resolution(ax, results)``: the share of the tension carried by patches too small to be
  resolved, per state.

``figure(results)`` puts them together at the width of a journal column (3.5 in) or of a page
(``width="double"``, 7.2 in); ``plot(FILE)`` writes it, as PNG, PDF or SVG by the extension of
``out``. ``results`` is a file name or an ``adhbem.load(...)`` object; ``compare`` adds other runs
(the same surface without adhesion, another criterion, ...), each labelled by its file name and
what differs between the runs. ``normalised=True`` draws a JKR sphere in F/F_adh, a/a_c, d/abs(d_c).

adhbem has no units of its own: lengths, E* and dgamma are those of the input (any consistent
set), so axes carry symbols, not units.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
from typing import TYPE_CHECKING, Optional, Sequence, Union

import numpy as np

from . import theory
from .results import Results, load

if TYPE_CHECKING:  # matplotlib is imported when a figure is drawn
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

ResultsLike = Union[str, os.PathLike, Results]  # a results file's name, or one adhbem.load opened

COLUMN = 3.5  # inches: one column of a two-column journal page
DOUBLE = 7.2  # inches: the width of the page
STYLE = {"font.size": 7, "axes.labelsize": 7, "axes.titlesize": 7, "legend.fontsize": 6, "xtick.labelsize": 6,
         "ytick.labelsize": 6, "lines.linewidth": 0.9, "lines.markersize": 2.5, "axes.linewidth": 0.6,
         "savefig.dpi": 300}
STATE_NAMES = {"deepest": "deepest indentation", "tension": "largest tension"}


class UsageError(ValueError):
    """An option that does not fit the file (--states out of range, --normalised without scales)."""


class Run:
    """One results file as the panels read it: its curve, parameters, label and field access."""

    def __init__(self, results, label=None):
        self._own = not isinstance(results, Results)
        self.results = load(results) if self._own else results
        self.path, self.curve, self.params = self.results.path, self.results.curve, self.results.params
        if not len(self.curve.get("d", ())):
            raise ValueError(f"{self.path} holds no state (the run stopped before its first)")
        self.label = label

    def close(self):
        if self._own:
            self.results.close()


def _runs(results, compare=(), labels=None):
    runs = [Run(r) for r in (results, *compare)]
    given = list(labels) if labels else run_labels([r.path for r in runs], [r.params for r in runs])
    if len(given) != len(runs):
        raise UsageError(f"labels: one a run ({len(runs)}), got {len(given)}")
    for run, label in zip(runs, given):
        run.label = label
    return runs


def _close(runs):
    for run in runs:
        run.close()


def analytic(params, d, area):
    """(label, d, F, A) of the analytic curve of this run, or None (periodic cells, topographies,
    dgamma fields, a body other than the half-space)."""
    if (params.get("boundary") != "free" or params.get("gamma_field") or params.get("critical_stress_fixed")
            or params.get("elastic", "halfspace") != "halfspace"):
        return None
    E, gamma, kind = params["E_star"], params.get("gamma", 0.0), params.get("indenter")
    amax = 1.2 * math.sqrt(max(area.max(), 1e-300) / math.pi)
    a = np.linspace(amax / 400, amax, 400)
    if kind == "sphere":
        dd, F = theory.jkr_sphere(a, params["radius"], gamma, E)
        return ("JKR" if gamma > 0 else "Hertz"), dd, F, math.pi * a ** 2
    if kind == "cone":
        dd, F = theory.jkr_cone(a, params["cone_slope"], gamma, E)
        return ("JKR-type cone" if gamma > 0 else "cone"), dd, F, math.pi * a ** 2
    if kind == "punch":
        ap = params["punch_radius"]
        stiffness, dcrit = theory.kendall_punch(ap, gamma, E)
        dd = np.linspace(max(dcrit, d.min()), d.max(), 200)
        return "Kendall", dd, stiffness * dd, np.full_like(dd, math.pi * ap ** 2)
    return None


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
        return [adhesion_label(params[0])]
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


def visible(curve):
    """The rows worth drawing: states in contact and their neighbours (the last state before first
    touch, the first after the contact was lost); a run of states with nothing in contact is one
    point on the axis, not a line along it."""
    points = np.asarray(curve.get("contact_points", np.ones(len(curve["d"]))))
    touching = points > 0
    near = touching.copy()
    near[1:] |= touching[:-1]
    near[:-1] |= touching[1:]
    return near


def scales(params):
    """The scales --normalised divides by: ("jkr", F_adh, a_c, abs(d_c)) for a sphere with a uniform
    dgamma > 0 on a free boundary, else None."""
    g = params.get("gamma", 0.0)
    if (params.get("indenter") == "sphere" and params.get("boundary") == "free" and g > 0
            and not params.get("gamma_field") and not params.get("critical_stress_fixed")
            and params.get("elastic", "halfspace") == "halfspace"):
        R, E = params["radius"], params["E_star"]
        return ("jkr", 1.5 * math.pi * g * R, (9 * math.pi * g * R ** 2 / (8 * E)) ** (1 / 3),
                (3 * math.pi ** 2 * g ** 2 * R / (64 * E ** 2)) ** (1 / 3))
    return None


def _scale(run, normalised):
    if not normalised:
        return None
    sc = scales(run.params)
    if sc is None:
        raise UsageError(f"--normalised: {run.path} has no scales to divide by: they are JKR's, for a sphere with "
                         "a uniform dgamma > 0 on a free boundary (a periodic cell is drawn as mean pressure and "
                         "contact area fraction already)")
    return sc


def quantities(d, F, A, params, scale=None):
    """(x, y, area) as drawn, and their axis labels: the input's quantities, a periodic cell's mean
    pressure and area fraction, or JKR's normalised ones."""
    if scale is not None:
        _, Fadh, ac, dc = scale
        return (d / dc, F / Fadh, np.sqrt(A / math.pi) / ac), \
            ("indentation $d/|d_c|$", "force $F/F_\\mathrm{adh}$", "contact radius $a/a_c$")
    if params.get("boundary") == "periodic":
        cell = params["Lx"] * params["Ly"]
        return (d, F / cell, A / cell), ("indentation $d$", "mean pressure $\\bar p$", "contact area fraction")
    return (d, F, A), ("indentation $d$", "force $F$", "contact area $A$")


def _draw_theory(ax, run, scale, drawn, pair):
    """The run's analytic curve, if it has one, as quantities pair of (d, F, A) as drawn, over the
    range of the drawn data's first quantity only."""
    ref = analytic(run.params, run.curve["d"], run.curve["area"])
    if not ref:
        return
    name, rd, rF, rA = ref
    q, _ = quantities(rd, rF, rA, run.params, scale)
    x, y = q[pair[0]], q[pair[1]]
    drawn = np.concatenate(drawn)
    lo, hi = (drawn.min(), drawn.max()) if len(drawn) else (x.min(), x.max())
    keep = (x >= lo) & (x <= hi)
    ax.plot(x[keep], y[keep], "k:", lw=1.0, label=f"{name} theory")


def _colors():
    import matplotlib
    return matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]


def _draw_legs(ax, x, y, run, color, many):
    """A run's curve: approach solid, retraction dashed, the states with nothing in contact left out
    but one at each end."""
    show = visible(run.curve)
    done = set()
    for direction, rows in legs(run.curve, run.params):
        rows = rows[show[rows]]
        if len(rows) < 1:
            continue
        kind = "approach" if direction > 0 else "retraction"
        # alone: a legend entry a leg; among others: one a run (its colour), the legs by _leg_styles
        label = (run.label if not done else "_nolegend_") if many else (kind if kind not in done else "_nolegend_")
        done.add(kind)
        style = dict(ls="-", marker="o", mfc=color) if direction > 0 else dict(ls="--", marker="v", mfc="white")
        # a gap in the rows (states left out) breaks the line
        for piece in np.split(rows, np.nonzero(np.diff(rows) > 1)[0] + 1):
            ax.plot(x[piece], y[piece], color=color, mec=color, label=label, **style)
            label = "_nolegend_"


def _leg_styles(ax):
    """Legend entries for the line styles of the legs, in grey: when several runs share the axes
    their colours name the runs."""
    from matplotlib.lines import Line2D
    return [Line2D([], [], color="0.4", ls="-", marker="o", label="approach"),
            Line2D([], [], color="0.4", ls="--", marker="v", mfc="white", label="retraction")]


def _scale_axis(axis, set_label, label):
    """Tick labels of a small or large quantity as plain numbers, the power of ten in the axis
    label ("force $F$ ($\\times 10^{-3}$)"): matplotlib's offset text would sit on the label."""
    from matplotlib.ticker import FuncFormatter
    lo, hi = axis.get_view_interval()
    top = max(abs(lo), abs(hi))
    if not top > 0 or not np.isfinite(top):
        return
    e = int(math.floor(math.log10(top)))
    minus = "\N{MINUS SIGN}"  # as matplotlib's own labels have it
    if -3 < e < 4:
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}".replace("-", minus)))
        return
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v / 10.0 ** e:g}".replace("-", minus)))
    set_label(f"{label} ($\\times 10^{{{e}}}$)")


def _finish(ax, legend, many=False):
    from matplotlib.ticker import MaxNLocator
    ax.xaxis.set_major_locator(MaxNLocator(3))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    ax.axhline(0, color="0.75", lw=0.4, zorder=0)
    _scale_axis(ax.xaxis, ax.set_xlabel, ax.get_xlabel())
    _scale_axis(ax.yaxis, ax.set_ylabel, ax.get_ylabel())
    if many:
        ax._adhbem_styles = _leg_styles(ax)  # figure() puts them in its legend
    if legend:
        handles, _ = ax.get_legend_handles_labels()
        ax.legend(handles=handles + (ax._adhbem_styles if many else []), frameon=False)


def curve(ax: "Axes", results: ResultsLike, compare: Sequence[ResultsLike] = (), normalised: bool = False,
          theory: bool = True, legend: bool = True, labels: Optional[Sequence[str]] = None) -> None:
    """Force against indentation: approach solid, retraction dashed, the analytic curve over the
    data's range, the pull-off force (the largest tension) as a star, where the contact was lost as
    a cross. A periodic cell is drawn as mean pressure.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    results : str, os.PathLike or adhbem.Results
        A results file's name, or one ``adhbem.load`` opened.
    compare : sequence of the same, optional
        Other runs drawn beside, one colour a run.
    normalised : bool, default False
        A JKR sphere in F/F_adh, a/a_c, d/abs(d_c).
    theory : bool, default True
        Draw the analytic curve where the indenter has one.
    legend : bool, default True
        Put a legend on the axes.
    labels : sequence of str, optional
        A name a run (default: the file names and what differs between the runs).
    """
    runs = _runs(results, compare, labels)
    try:
        colors, many = _colors(), len(runs) > 1
        first_scale = _scale(runs[0], normalised)
        names = quantities(runs[0].curve["d"], runs[0].curve["force"], runs[0].curve["area"], runs[0].params, first_scale)[1]
        lost_drawn = False
        xs = []
        for i, run in enumerate(runs):
            c, color = run.curve, colors[i % len(colors)]
            sc = _scale(run, normalised)
            (x, y, _), _ = quantities(c["d"], c["force"], c["area"], run.params, sc)
            xs.append(x[visible(c)])
            _draw_legs(ax, x, y, run, color, many)
            if c["force"].min() < 0:
                k = int(np.argmin(c["force"]))
                if sc:
                    value = f"{-y[k]:.3g} $F_\\mathrm{{adh}}$"
                elif run.params.get("boundary") == "periodic":
                    value = f"(mean tension {-y[k]:.3g})"
                else:
                    value = f"{-y[k]:.3g}"
                # a pull-off force only where the surfaces came apart
                what = "pull-off force" if run.results.came_apart else "largest tension (did not come apart)"
                ax.plot(x[k], y[k], "*", ms=7, color="red" if i == 0 else color, mec="red", zorder=5,
                        label=f"{what} {value}")
            lost = list(np.nonzero(c.get("pulled_off", np.zeros(0)))[0])
            if lost:
                ax.plot(x[lost], y[lost], "x", ms=5, mew=1.0, color=color, zorder=5,
                        label="_nolegend_" if lost_drawn else "contact lost")
                lost_drawn = True
        if theory:
            _draw_theory(ax, runs[0], first_scale, xs, (0, 1))
        ax.set_xlabel(names[0] + (", force control" if runs[0].params.get("control") == "force" else ""))
        ax.set_ylabel(names[1])
        _finish(ax, legend, many)
    finally:
        _close(runs)


def area(ax: "Axes", results: ResultsLike, compare: Sequence[ResultsLike] = (), normalised: bool = False,
         theory: bool = True, legend: bool = True, labels: Optional[Sequence[str]] = None) -> None:
    """Contact area against force, approach solid, retraction dashed (area fraction against mean
    pressure on a periodic cell).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    results : str, os.PathLike or adhbem.Results
        A results file's name, or one ``adhbem.load`` opened.
    compare : sequence of the same, optional
        Other runs drawn beside, one colour a run.
    normalised : bool, default False
        A JKR sphere in F/F_adh, a/a_c, d/abs(d_c).
    theory : bool, default True
        Draw the analytic curve where the indenter has one.
    legend : bool, default True
        Put a legend on the axes.
    labels : sequence of str, optional
        A name a run (default: the file names and what differs between the runs).
    """
    runs = _runs(results, compare, labels)
    try:
        colors, many = _colors(), len(runs) > 1
        first_scale = _scale(runs[0], normalised)
        names = quantities(runs[0].curve["d"], runs[0].curve["force"], runs[0].curve["area"], runs[0].params, first_scale)[1]
        ys = []
        for i, run in enumerate(runs):
            c = run.curve
            (_, y, A), _ = quantities(c["d"], c["force"], c["area"], run.params, _scale(run, normalised))
            ys.append(y[visible(c)])
            _draw_legs(ax, y, A, run, colors[i % len(colors)], many)
        if theory:
            _draw_theory(ax, runs[0], first_scale, ys, (1, 2))
        ax.set_xlabel(names[1])
        ax.set_ylabel(names[2])
        ax.axvline(0, color="0.75", lw=0.4, zorder=0)
        _finish(ax, legend, many)
    finally:
        _close(runs)


def state_row(curve: dict, state: Union[int, str, tuple]) -> int:
    """The curve row of ``state``: an int (negative from the end), ``"deepest"`` (the deepest
    indentation) or ``"tension"`` (the largest tension), or a tuple of those naming one row."""
    n = len(curve["d"])
    if isinstance(state, tuple):
        return state_row(curve, state[0])
    if state == "deepest":
        return int(np.argmax(curve["d"]))
    if state == "tension":
        if curve["force"].min() >= 0:
            raise UsageError("--states: 'tension': no state carries tension")
        return int(np.argmin(curve["force"]))
    k = int(state)
    if not -n <= k < n:
        raise UsageError(f"--states: {k} is not a state: the curve has rows 0 to {n - 1} (or -{n} to -1, from the end)")
    return k % n


def _edges(N, L):
    """The outer edges of the elements along an axis: element i is centred at (i - N//2) h."""
    h = L / N
    return (-(N // 2) - 0.5) * h, (N - 1 - N // 2 + 0.5) * h


def _window(mask, Lx, Ly):
    """(x0, x1, y0, y1): a square around the points of mask with a fifth of its size to spare."""
    if not mask.any():
        return None
    Ny, Nx = mask.shape
    hx, hy = Lx / Nx, Ly / Ny
    jj, ii = np.nonzero(mask)
    x = (np.array([ii.min(), ii.max()]) - Nx // 2) * hx + np.array([-hx, hx]) / 2
    y = (np.array([jj.min(), jj.max()]) - Ny // 2) * hy + np.array([-hy, hy]) / 2
    cx, cy = x.mean(), y.mean()
    half = 0.6 * max(x[1] - x[0], y[1] - y[0])
    (x0, x1), (y0, y1) = _edges(Nx, Lx), _edges(Ny, Ly)
    return (max(cx - half, x0), min(cx + half, x1), max(cy - half, y0), min(cy + half, y1))


def _state_title(curve, state, row, periodic, params, scale=None, wanted=None):
    names = state if isinstance(state, tuple) else (state,)
    name = ", ".join(STATE_NAMES.get(s, f"state {row}") for s in names)
    if wanted is not None and wanted != row:  # fields of every K-th state only: the nearest written
        name = f"state {row}, the written one nearest the {name}" if name != f"state {row}" else f"state {row}"
    F = curve["force"][row]
    if scale is not None:
        _, Fadh, _, dc = scale
        return f"{name}\n$d/|d_c|$ = {curve['d'][row] / dc:.3g}, $F/F_\\mathrm{{adh}}$ = {F / Fadh:.3g}"
    if periodic:
        return f"{name}\n$d$ = {curve['d'][row]:.3g}, $\\bar p$ = {F / (params['Lx'] * params['Ly']):.3g}"
    return f"{name}\n$d$ = {curve['d'][row]:.3g}, $F$ = {F:.3g}"


def _written(results, row):
    """The curve row nearest to row whose fields the file holds (-adh_fields_stride)."""
    return int(results.states[np.argmin(np.abs(results.states - row))])


def contact_map(ax: "Axes", results: ResultsLike, state: Union[int, str] = "deepest", field: str = "auto",
                colorbar: bool = True, normalised: bool = False) -> int:
    """The contact of one state: the pressure on the contact set (tension blue, compression red)
    when the file has the pressure field, else the contact set, with its colour bar; titled by
    what the state is.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    results : str, os.PathLike or adhbem.Results
        A results file's name, or one ``adhbem.load`` opened.
    state : int or {'deepest', 'tension'}, default 'deepest'
        A curve row (negative from the end), the deepest indentation or the largest tension; the
        file's written state nearest to it is drawn (``-adh_fields_stride``).
    field : {'auto', 'pressure', 'contact'}, default 'auto'
        What to draw: the pressure when the file has it, or the contact set.
    colorbar : bool, default True
        Add the colour bar.
    normalised : bool, default False
        A JKR sphere in F/F_adh, a/a_c, d/abs(d_c).

    Returns
    -------
    int
        The curve row drawn.
    """
    import matplotlib
    run = Run(results)
    try:
        r, c, p = run.results, run.curve, run.params
        if "contact" not in r.field_names:
            raise UsageError(f"--states: {run.path} has no fields to map (write them with -adh_fields contact or pressure)")
        wanted = state_row(c, state)
        row = _written(r, wanted)
        mask = r.field("contact", row) > 0
        use_pressure = "pressure" in r.field_names if field == "auto" else field == "pressure"
        Lx, Ly = p.get("Lx", 1.0), p.get("Ly", 1.0)
        Ny, Nx = mask.shape
        extent = (*_edges(Nx, Lx), *_edges(Ny, Ly))
        window = None
        if p.get("boundary") == "free":
            # an isolated contact: the window around the largest contact (the deepest state's),
            # the same for every state of the run
            deepest = _written(r, state_row(c, "deepest"))
            window = _window(mask | (r.field("contact", deepest) > 0), Lx, Ly)
        if use_pressure:
            pressure = r.field("pressure", row)
            # the tension at an adhesive edge is singular: the colours span the bulk (98% of the
            # points), the bar's arrows say that some lie beyond
            vmax = float(np.percentile(np.abs(pressure[mask]), 98)) if mask.any() else 1.0
            vmax = vmax if vmax > 0 else 1.0
            im = ax.imshow(np.where(mask, pressure, np.nan), origin="lower", extent=extent, cmap="RdBu_r",
                           vmin=-vmax, vmax=vmax, interpolation="nearest")
            if colorbar:
                bar = ax.figure.colorbar(im, ax=ax, fraction=0.046, pad=0.03, extend="both")
                bar.set_label("pressure $p$", labelpad=1)
                bar.ax.ticklabel_format(style="sci", scilimits=(-4, 5), useMathText=True)
        else:
            cmap = matplotlib.colors.ListedColormap(["white", "#1f77b4"])
            im = ax.imshow(mask.astype(float), origin="lower", extent=extent, cmap=cmap, vmin=0, vmax=1,
                           interpolation="nearest")
            if colorbar:
                bar = ax.figure.colorbar(im, ax=ax, fraction=0.046, pad=0.03, ticks=[0.25, 0.75])
                bar.ax.set_yticklabels(["free", "contact"])
        if window:
            ax.set_xlim(window[0], window[1])
            ax.set_ylim(window[2], window[3])
        ax.set_xlabel("$x$")
        ax.set_ylabel("$y$", labelpad=1)
        ax.set_title(_state_title(c, state, row, p.get("boundary") == "periodic", p, _scale(run, normalised), wanted))
        return row
    finally:
        run.close()


def resolution(ax: "Axes", results: ResultsLike, compare: Sequence[ResultsLike] = (), legend: bool = True,
               labels: Optional[Sequence[str]] = None) -> None:
    """The resolution of the adhesion: the share of the tension carried by contact patches under
    314 elements, per state carrying tension (above 0.1 at the pull-off force a JKR-limit
    criterion's grid does not resolve the adhesion; a finite-range criterion's zone width decides,
    and its line is not drawn), the pull-off state marked, the run's verdict as the title.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    results : str, os.PathLike or adhbem.Results
        A results file's name, or one ``adhbem.load`` opened.
    compare : sequence of the same, optional
        Other runs drawn beside, one colour a run.
    legend : bool, default True
        Put a legend on the axes.
    labels : sequence of str, optional
        A name a run (default: the file names and what differs between the runs).
    """
    runs = _runs(results, compare, labels)
    try:
        colors = _colors()
        for i, run in enumerate(runs):
            c, prm = run.curve, run.params
            if "small_patch_tension" not in c or not (c["force"] < 0).any():
                continue  # nothing to resolve
            rows = np.arange(len(c["d"]))
            tension = c["force"] < 0
            color = colors[i % len(colors)]
            ax.plot(rows[tension], c["small_patch_tension"][tension], ".-", color=color,
                    label=run.label.split(":")[0] if len(runs) > 1 else "states carrying tension")
            k = int(np.argmin(c["force"]))
            ac = prm.get("asperity_contact_radius")
            verdict = "resolved" if prm.get("adhesion_resolved") else "not resolved"
            ax.plot(k, c["small_patch_tension"][k], "*", ms=7, color="red" if i == 0 else color, mec="red",
                    label=f"{'pull-off force' if run.results.came_apart else 'largest tension'}: {verdict}"
                    + (f" ($a_c/h$ {ac:.3g})" if ac else ""))
        if any(str(r.params.get("criterion", "pohrt-popov")) in ("crack-closure", "pohrt-popov") for r in runs):
            ax.axhline(0.1, color="0.5", ls="--", lw=0.6, label="resolved below (JKR-limit criteria)")
        ax.set_ylim(-0.03, 1.03)
        ax.set_xlabel("state (curve row)")
        ax.set_ylabel("tension share in patches < 314 el.")
        first = runs[0].params
        verdict = "resolved" if first.get("adhesion_resolved") else "not resolved"
        ac = first.get("asperity_contact_radius")
        ax.set_title(f"adhesion {verdict}" + (f"\n($a_c/h$ = {ac:.3g})" if ac else ""))
        if legend:
            ax.legend(frameon=False)
    finally:
        _close(runs)


def has_tension_statistics(results):
    run = Run(results)
    try:
        return "small_patch_tension" in run.curve and run.curve["force"].min() < 0
    finally:
        run.close()


def default_states(curve):
    """The deepest indentation and, when a state carries tension, the largest tension."""
    return ["deepest"] + (["tension"] if curve["force"].min() < 0 else [])


def figure(results: ResultsLike, states: Optional[Sequence[Union[int, str]]] = None, compare: Sequence[ResultsLike] = (),
           normalised: bool = False, width: str = "column", resolution_panel: bool = False,
           labels: Optional[Sequence[str]] = None) -> "Figure":
    """A figure for a paper: the force-indentation curve, area against force, contact maps and,
    on request, the resolution of the adhesion, with one legend above the panels.

    Parameters
    ----------
    results : str, os.PathLike or adhbem.Results
        A results file's name, or one ``adhbem.load`` opened.
    states : sequence of int or {'deepest', 'tension'}, optional
        The contact maps (default: the deepest indentation and the largest tension, when the file
        has fields; one map where they are the same state).
    compare : sequence of the same, optional
        Other runs drawn beside, one colour a run.
    normalised : bool, default False
        A JKR sphere in F/F_adh, a/a_c, d/abs(d_c).
    width : {'column', 'double'}, default 'column'
        A journal column (3.5 in, two panels a row) or the page (7.2 in, one row).
    resolution_panel : bool, default False
        Add the resolution panel.
    labels : sequence of str, optional
        A name a run (default: the file names and what differs between the runs).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if width not in ("column", "double"):
        raise UsageError(f"--width: 'column' or 'double', got {width!r}")
    run = Run(results)
    try:
        if states is None:
            states = default_states(run.curve) if "contact" in run.results.field_names else []
        elif states and "contact" not in run.results.field_names:
            raise UsageError(f"--states: {run.path} has no fields to map (write them with -adh_fields)")
        rows = {}
        for s in states:  # a bad state fails before drawing; one map a state drawn
            row = state_row(run.curve, s)
            rows.setdefault(_written(run.results, row) if len(run.results.states) else row, []).append(s)
        states = [names[0] if len(names) == 1 else tuple(names) for names in rows.values()]
    finally:
        run.close()
    panels = ["curve", "area"] + [("map", s) for s in states] + (["resolution"] if resolution_panel else [])
    # each file read once: the panels take the opened results
    opened = [r if isinstance(r, Results) else load(r) for r in (results, *compare)]
    try:
        return _figure(panels, opened[0], opened[1:], normalised, width, labels)
    finally:
        for r, given in zip(opened, (results, *compare)):
            if r is not given:
                r.close()


def _figure(panels, results, compare, normalised, width, labels):
    import matplotlib
    from matplotlib.figure import Figure

    with matplotlib.rc_context(STYLE):
        if width == "column":
            ncols, nrows = 2, (len(panels) + 1) // 2
            size = (COLUMN, 0.45 + 1.75 * nrows)
        else:
            ncols, nrows = len(panels), 1
            size = (DOUBLE, 0.45 + 2.0)
        fig = Figure(figsize=size)
        axes = fig.subplots(nrows, ncols, squeeze=False).ravel()
        for ax in axes[len(panels):]:
            ax.set_visible(False)
        for ax, panel in zip(axes, panels):
            if panel == "curve":
                curve(ax, results, compare, normalised, legend=False, labels=labels)
            elif panel == "area":
                area(ax, results, compare, normalised, legend=False, labels=labels)
            elif panel == "resolution":
                resolution(ax, results, compare, legend=False, labels=labels)
            else:
                contact_map(ax, results, panel[1], normalised=normalised)
        handles, labels = axes[0].get_legend_handles_labels()
        h2, l2 = axes[1].get_legend_handles_labels()
        for h, l in zip(h2 + getattr(axes[0], "_adhbem_styles", []), l2 + [h.get_label() for h in getattr(axes[0], "_adhbem_styles", [])]):
            if l not in labels:
                handles.append(h)
                labels.append(l)
        ncol = max(1, min(len(labels), 2 if width == "column" else 4))
        top = 1 - (0.06 + 0.13 * math.ceil(len(labels) / ncol)) / size[1]
        if labels:  # a run that never touched has nothing to name
            fig.legend(handles, labels, loc="upper center", ncol=ncol, frameon=False, bbox_to_anchor=(0.5, 1.0),
                       handlelength=2.2, columnspacing=1.0)
        fig.tight_layout(pad=0.3, h_pad=0.6, w_pad=0.6, rect=(0, 0, 1, top))
    return fig


def plot(path: ResultsLike, out: Optional[Union[str, os.PathLike]] = None, states: Optional[Sequence[Union[int, str]]] = None,
         compare: Sequence[ResultsLike] = (), normalised: bool = False, width: str = "column",
         resolution_panel: bool = False, labels: Optional[Sequence[str]] = None) -> str:
    """Draws ``figure(path, ...)`` into a file.

    Parameters
    ----------
    path : str, os.PathLike or adhbem.Results
        The results file.
    out : str or os.PathLike, optional
        The figure file: PNG (300 dpi), PDF or SVG by its extension (default: FILE.png beside
        FILE.h5).
    states, compare, normalised, width, resolution_panel, labels
        As for ``figure``.

    Returns
    -------
    str
        The file written.
    """
    name = path.path if isinstance(path, Results) else os.fspath(path)
    out = os.fspath(out) if out else (name[:-3] if name.endswith(".h5") else name) + ".png"
    figure(path, states, compare, normalised, width, resolution_panel, labels).savefig(out, dpi=STYLE["savefig.dpi"])
    return out


def _state(text):
    return text if text in STATE_NAMES else int(text)


def main(argv=None):
    # the name it was called by: the adhbem-plot command, or python3 -m adhbem.plot
    prog = "adhbem-plot" if os.path.basename(sys.argv[0]) == "adhbem-plot" else "python3 -m adhbem.plot"
    ap = argparse.ArgumentParser(prog=prog, description=__doc__.split("\n\n")[0])
    ap.add_argument("file", help="results file written with -adh_output")
    ap.add_argument("--out", help="figure file, PNG, PDF or SVG by its extension (default: FILE.png)")
    ap.add_argument("--width", default="column", choices=("column", "double"),
                    help="a journal column (3.5 in, the default) or the page (7.2 in)")
    ap.add_argument("--states", help="contact maps: comma-separated curve rows (negative from the end), 'deepest' "
                    "or 'tension' (default: deepest,tension)")
    ap.add_argument("--compare", nargs="*", default=(), help="other results files whose curves go beside")
    ap.add_argument("--normalised", action="store_true", help="a JKR sphere on a free boundary in F/F_adh, a/a_c, d/abs(d_c)")
    ap.add_argument("--resolution", action="store_true", help="add the panel of the resolution of the adhesion")
    a = ap.parse_args(argv)
    try:
        states = [_state(s) for s in a.states.split(",")] if a.states else None
    except ValueError:
        ap.error(f"--states: curve rows, 'deepest' or 'tension', comma-separated; got {a.states!r}")
    try:
        out = plot(a.file, a.out, states, a.compare, a.normalised, a.width, a.resolution)
    except UsageError as e:
        ap.error(str(e))
    except (OSError, KeyError, ValueError) as e:
        print(f"adhbem.plot: {a.file}: {e}", file=sys.stderr)
        return 1
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
