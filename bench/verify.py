"""./run bench verify: the analytic verification cases, one figure and one table each.

    ./run bench verify [--case CASE[,CASE...]|all] [--quick] [--out DIR] [--json FILE]

Each case runs adhbem (the Python API, one process, one core) against a closed form, draws
DIR/CASE.png (default DIR: docs/_static/verification/, with --quick build/verification-quick/;
the closed forms as grey lines, adhbem's states as markers) and prints the figure's numbers as
tables, with the counts of every run summed over its states (set updates, KSP iterations and FFT
pairs: the curve's columns outer_iterations, ksp_iterations, fft_pairs) and its CPU seconds.
E* = 1 throughout.

- hertz: the non-adhesive sphere (R = 1) on the free boundary, loaded from a = 0.1 to 0.3 on grids
  of side 1 (64, 128, 256, 512; a/h 6 to 154): the force against the indentation beside Hertz's
  F = 4/3 E* sqrt(R) d^1.5 (its relative error at each state), and the pressure along the line
  through the centre at the deepest state against Hertz's p0 sqrt(1 - r^2/a^2).
- westergaard: Westergaard's wavy surface h = D (1 - cos(2 pi x/lam)) on a periodic N x 4 strip
  (non-adhesive, D = 0.01 lam), at mean pressures 0.3 and 0.6 p* (p* = pi E* D/lam): under force
  control the indentation d against the exact solution's (its zero-mean displacement from the
  exact pressure, sampled on 2^20 points), under displacement control at that d the mean pressure;
  their errors against N (64 to 4096) on log axes, and the pressure profile on the coarsest grid.
- jkr: the JKR sphere. Left: one force-indentation curve under displacement control, loading from
  first touch (start adhesive) and unloading beyond the jump-off (a_c/h 25), against
  adhbem.theory.jkr_sphere. Right: the pull-off force under force control (a Hertz start at
  0.5 F_adh, 30 steps to -2 F_adh; the leg ends at the largest tension, bisected), over
  F_adh = 1.5 pi dgamma R, against a_c/h 12.5, 25, 50 for the default criterion crack-closure and
  the paper's pohrt-popov.
- punch: Kendall's flat punch (dgamma 1e-3) under force control, from compression to beyond the
  pull-off, a/h 17.5, 35.5, 71 (N = 4 a/h), both criteria: the pull-off force over Kendall's
  sqrt(8 pi dgamma E* a^3) with a the radius of the face's area (the digitised disk; the nominal
  radius's ratio is printed too), and one force-indentation curve against F = 2 E* a d.
- wave: Johnson's (1995) adhesive wave along a grid axis on a periodic N x 4 strip (alpha 0.3,
  D = 0.01 lam), under force control: loaded from first touch (start adhesive) to 0.9 p_max and
  unloaded to pull-off, lam/h 128 to 2048, both criteria (each with its default attach rule): the
  mean pressure against the contact half-width (from the area) beside adhbem.theory.johnson_wave
  (lam/h 256), and the pull-off (the largest tension) over Johnson's minimum of p.
- maugis: the Maugis-Dugdale sphere (criterion dugdale by the sharp law's fixed point, whose
  first-order convergence the extrapolation assumes; lambda 1, dgamma 0.004655): the pull-off
  force under force control over Maugis' (adhbem.theory.maugis_pulloff) on grids 64, 128, 256 of
  side 1 (the cohesive zone about 6, 12, 24 spacings wide), with the first-order extrapolation of
  successive grids, and one force-indentation curve under displacement control (128^2, unloading
  from a preload) against adhbem.theory.maugis_sphere, in Johnson & Greenwood's units.

- layer: JKR spheres on thin layers (an array: one rigid sphere R = 1 a periodic cell 1 x 1) of an
  incompressible layer (E1 = 1, nu1 = 0.5) bonded to a rigid base, of thicknesses T = 0.2 to
  0.0125 (a_c/T 1 to 7), dgamma 2.8e-3 (on the half-space a_c = 0.195), under force control from a
  Hertz start at 0.5 F_adh to -2 F_adh, bisected, crack-closure on grids 128 to 512 (a_c/h 11 to
  100), pohrt-popov on 128, 256, 512, and the half-space on the free boundary as the control: the
  pull-off and the contact radius along the unloading against adhbem.theory.layer_sphere and
  layer_pulloff (an isolated sphere, solved by Lebedev and Ufliand's integral equation), beside
  Shull's (2002) fitted corrections. Left: force against contact radius at three thicknesses
  (N = 256); right: the pull-off over the half-space's against a_c/T. About 20 minutes.

--quick runs the coarse grids only (a smoke test of about 40 s in all; its figures are not the
study's). --json FILE writes the tables' numbers as JSON (tests/test_verify_bench.py reads it).
Full size takes 5 s (westergaard) to about a minute (jkr) a case on one core, and about 20 minutes
(layer); about 23 minutes in all.
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np

# one core: one FFTW/BLAS thread (./run sets the same)
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import adhbem  # noqa: E402
from adhbem import theory  # noqa: E402

E = 1.0
GREY = dict(color="0.6", lw=2.5, zorder=1)
MARKERS = "osD^vp"
COUNTS_HEADER = ["updates", "KSP", "FFT pairs", "CPU s"]


# ---- running and printing ------------------------------------------------------------------------

def run(keep=None, **options):
    """Runs the solver's path with `options`; returns a dict: the curve, the pull-off force, the
    counts summed over the states, the CPU seconds, and whatever keep(solver) returns (read
    after the path: the last state's fields)."""
    t0 = time.process_time()
    with adhbem.Solver(**options) as s:
        c = s.solve_path(progress=False)
        r = dict(curve=c, pull_off=s.pull_off_force, resolution=s.resolution)
        if keep is not None:
            r.update(keep(s))
    r["counts"] = counts(c, time.process_time() - t0)
    return r


def counts(c, cpu):
    return dict(updates=int(c["outer_iterations"].sum()), ksp=int(c["ksp_iterations"].sum()),
                fft=int(c["fft_pairs"].sum()), cpu=float(cpu))


def add_counts(*many):
    return dict(updates=sum(k["updates"] for k in many), ksp=sum(k["ksp"] for k in many),
                fft=sum(k["fft"] for k in many), cpu=sum(k["cpu"] for k in many))


def count_cells(k):
    return [f"{k['updates']}", f"{k['ksp']}", f"{k['fft']}", f"{k['cpu']:.1f}"]


def table(title, header, rows):
    """Prints a Markdown table under a title line."""
    print(f"\n{title}\n")
    print("| " + " | ".join(header) + " |")
    print("|" + " --- |" * len(header))
    for row in rows:
        print("| " + " | ".join(row) + " |")
    sys.stdout.flush()


def figure():
    return plt.subplots(1, 2, figsize=(8, 3.4), dpi=110, layout="constrained")


def save(fig, out, name):
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, f"{name}.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"\nfigure: {path}")
    return path


# ---- hertz -----------------------------------------------------------------------------------------

def case_hertz(quick, out):
    R, L = 1.0, 1.0
    grids = (64, 128) if quick else (64, 128, 256, 512)
    d0, d1 = 0.1 ** 2 / R, 0.3 ** 2 / R        # a = sqrt(R d) from 0.1 to 0.3
    runs = {}
    for N in grids:
        runs[N] = run(keep=lambda s: dict(p=s.pressure_array()), n=N, size=L, E_star=E, gamma=0.0, radius=R,
                      start="hertz", path=[d0, d1], steps=8)
    d = runs[grids[0]]["curve"]["d"]
    a_h = np.sqrt(R * d)
    F_h = 4.0 / 3.0 * E * math.sqrt(R) * d ** 1.5
    err = {N: runs[N]["curve"]["force"] / F_h - 1 for N in grids}
    table("hertz: F / F_Hertz - 1 at each state (E* = R = 1, grids of side 1)",
          ["d", "a_Hertz"] + [f"N = {N} (a/h)" for N in grids],
          [[f"{d[k]:.4f}", f"{a_h[k]:.4f}"] + [f"{err[N][k]:+.2e} ({a_h[k] * N / L:.1f})" for N in grids]
           for k in range(len(d))])
    a, p0 = a_h[-1], 2 * E * a_h[-1] / (math.pi * R)
    rows, summary = [], {}
    for N in grids:
        h = L / N
        x = (np.arange(N) - N // 2) * h
        line = runs[N]["p"][N // 2, :]          # the row y = 0
        p_h = p0 * np.sqrt(np.clip(1 - x ** 2 / a ** 2, 0, None))
        summary[N] = dict(force_error=float(np.max(np.abs(err[N]))), centre=float(line[N // 2] / p0 - 1),
                          line=float(np.max(np.abs(line - p_h)) / p0), x=x, p=line)
        rows.append([f"{N}", f"{a / h:.1f}", f"{summary[N]['force_error']:.2e}", f"{summary[N]['centre']:+.2e}",
                     f"{summary[N]['line']:.2e}"] + count_cells(runs[N]["counts"]))
    table("hertz: per grid (the pressure along y = 0 at the deepest state, d = 0.09, a = 0.3)",
          ["N", "a/h deepest", "max abs(F/F_H - 1)", "p(0)/p0 - 1", "max abs(p - p_H) / p0 on the line"] + COUNTS_HEADER, rows)

    fig, (ax1, ax2) = figure()
    dd = np.linspace(0, d1 * 1.02, 200)
    ax1.plot(dd, 4.0 / 3.0 * E * math.sqrt(R) * dd ** 1.5, **GREY, label="Hertz")
    inset = ax1.inset_axes([0.16, 0.45, 0.4, 0.45])
    for m, N in zip(MARKERS, grids):
        c = runs[N]["curve"]
        ax1.plot(c["d"], c["force"], m, ms=4, mfc="none", label=f"N = {N}")
        inset.semilogy(c["d"], np.abs(err[N]), m + "-", ms=3, lw=0.8, mfc="none")
    ax1.set_xlabel("indentation $d$ ($R$ = $E^*$ = 1)")
    ax1.set_ylabel("force $F$")
    ax1.set_xlim(0, d1 * 1.05)
    ax1.set_ylim(0, F_h[-1] * 1.08)
    ax1.legend(fontsize=8, loc="lower right")
    inset.set_ylabel(r"$|F/F_\mathrm{Hertz} - 1|$", fontsize=8, labelpad=1)
    inset.tick_params(labelsize=7)
    inset.set_xlabel("$d$", fontsize=7, labelpad=1)
    r = np.linspace(-a, a, 400)
    ax2.plot(r / a, np.sqrt(1 - r ** 2 / a ** 2), **GREY, label="Hertz")
    for m, N in zip(MARKERS, grids):
        stride = max(1, N // 64)
        x, p = summary[N]["x"], summary[N]["p"]
        sel = (np.abs(x) <= 1.3 * a) & (np.arange(N) % stride == 0)
        ax2.plot(x[sel] / a, p[sel] / p0, m, ms=4, mfc="none", label=f"N = {N}" + (f" (1 point in {stride})" if stride > 1 else ""))
    ax2.set_xlim(-1.3, 1.3)
    ax2.set_ylim(-0.05, 1.15)
    ax2.set_xlabel("$x/a$ (through the centre, deepest state)")
    ax2.set_ylabel(r"pressure $p/p_0$, $p_0 = 2E^*a/(\pi R)$")
    ax2.legend(fontsize=7, loc="lower center")
    save(fig, out, "hertz")
    return dict(max_force_error=max(v["force_error"] for v in summary.values()),
                grids={str(N): dict(force_error=v["force_error"], centre=v["centre"], line=v["line"],
                                    **runs[N]["counts"]) for N, v in summary.items()})


# ---- westergaard -----------------------------------------------------------------------------------

LAM, D_WAVE = 1.0, 0.01
P_STAR = math.pi * E * D_WAVE / LAM


def westergaard_pressure(x, pbar):
    return theory.westergaard_pressure(x, pbar, LAM, D_WAVE, E)


def case_westergaard(quick, out):
    grids = (64, 128, 256) if quick else (64, 128, 256, 512, 1024, 2048, 4096)
    loads = (0.3, 0.6)
    exact = {f: theory.westergaard_wave(f * P_STAR, LAM, D_WAVE, E)[:2] for f in loads}
    res, rows = {}, []
    for N in grids:
        x = (np.arange(N) - N // 2) * LAM / N
        h = np.tile(D_WAVE * (1 - np.cos(2 * np.pi * x / LAM)), (4, 1))
        cell = LAM * 4 * LAM / N
        base = dict(n=(N, 4), size=(LAM, 4 * LAM / N), E_star=E, gamma=0.0, boundary="periodic", start="hertz",
                    topography=h, topography_kind="gap", steps=1)
        res[N] = {}
        ks = []
        for f in loads:
            a, d_exact = exact[f]
            fr = run(keep=lambda s: dict(p=s.pressure_array()[0]), control="force", path=[f * P_STAR * cell] * 2, **base)
            dr = run(path=[d_exact] * 2, **base)
            half = fr["curve"]["contact_points"][-1] / 4 / 2 * LAM / N
            res[N][f] = dict(d=abs(fr["curve"]["d"][-1] - d_exact) / D_WAVE,
                             p=abs(dr["curve"]["force"][-1] / cell - f * P_STAR) / P_STAR,
                             half=(half - a) * N / LAM, x=x, pressure=fr["p"])
            ks += [fr["counts"], dr["counts"]]
        k = add_counts(*ks)
        res[N]["counts"] = k
        rows.append([f"{N}"] + [f"{res[N][f]['d']:.2e}" for f in loads] + [f"{res[N][f]['p']:.2e}" for f in loads]
                    + [f"{res[N][f]['half']:+.2f}" for f in loads] + count_cells(k))
    table("westergaard: errors against the exact solution (N x 4 periodic strip, D = 0.01 lam; "
          "counts: the four runs of a grid)",
          ["N = lam/h"] + [f"abs(d - d_exact)/D at {f} p*" for f in loads] + [f"abs(p - pbar)/p* at {f} p*" for f in loads]
          + [f"half-width - a (elements) at {f} p*" for f in loads] + COUNTS_HEADER, rows)

    fig, (ax1, ax2) = figure()
    N0 = grids[0]
    for (m, f) in zip("os", loads):
        a = exact[f][0]
        xx = np.linspace(-a, a, 400)
        ax1.plot(xx / LAM, westergaard_pressure(xx, f * P_STAR) / P_STAR, **GREY,
                 label="Westergaard" if f == loads[0] else None)
        sel = np.abs(res[N0][f]["x"]) <= 0.3 * LAM
        ax1.plot(res[N0][f]["x"][sel] / LAM, res[N0][f]["pressure"][sel] / P_STAR, m, ms=4, mfc="none",
                 label=rf"N = {N0}, $\bar p$ = {f} $p^*$")
    ax1.set_xlim(-0.3, 0.3)
    ax1.set_ylim(-0.05, 2.3)
    ax1.set_xlabel(r"$x/\lambda$")
    ax1.set_ylabel(r"pressure $p/p^*$, $p^* = \pi E^* D/\lambda$")
    ax1.legend(fontsize=8, loc="upper center")
    Ns = np.array(grids, dtype=float)
    for (m, f) in zip("os", loads):
        ax2.loglog(Ns, [res[N][f]["d"] for N in grids], m + "-", ms=5, lw=1, label=rf"$|d - d_\mathrm{{exact}}|/D$, {f} $p^*$")
        ax2.loglog(Ns, [res[N][f]["p"] for N in grids], m + "--", ms=5, lw=1, mfc="none",
                   label=rf"$|\bar p - \bar p_\mathrm{{exact}}|/p^*$, {f} $p^*$")
    first = np.exp(np.mean([np.log(res[grids[0]][f][e]) for f in loads for e in ("d", "p")]))
    ax2.loglog(Ns, 3 * first * (Ns / Ns[0]) ** -2, ":", color="0.5", lw=1, label="$\\propto N^{-2}$")
    ax2.set_xlabel(r"grid $N = \lambda/h$")
    ax2.set_ylabel("relative error")
    ax2.set_xticks(Ns, [f"{int(n)}" for n in Ns])
    ax2.minorticks_off()
    ax2.legend(fontsize=7, loc="lower left")
    save(fig, out, "westergaard")
    return dict(grids={str(N): {**{f"d_error_{f}": res[N][f]["d"] for f in loads},
                                **{f"p_error_{f}": res[N][f]["p"] for f in loads}, **res[N]["counts"]} for N in grids})


# ---- jkr -------------------------------------------------------------------------------------------

CRITERIA = ("crack-closure", "pohrt-popov")


def log2_axis(ax, x, right=1.3):
    """A log2 x axis ticked at the grids x, with a margin either side."""
    ax.set_xscale("log", base=2)
    ax.set_xticks(x, [f"{q:g}" for q in x])
    ax.minorticks_off()
    ax.set_xlim(x[0] / 1.3, x[-1] * right)


def convergence_panel(ax, x, ratios, reference, margin, colours=None):
    """The pull-off over its closed form against the resolution x (log2 axis), one line a
    criterion: ratios[crit] lists the ratios at x; reference labels the closed form's line at 1."""
    x = np.asarray(x, dtype=float)
    ax.axhline(1.0, **GREY, label=reference)
    for m, crit in zip("os", CRITERIA):
        ax.plot(x, ratios[crit], m + "-", ms=6, lw=1, color=(colours or {}).get(crit),
                label=crit + (" (default)" if crit == "crack-closure" else ""))
    log2_axis(ax, x)
    vals = [v for crit in CRITERIA for v in ratios[crit]]
    ax.set_ylim(min(min(vals), 1.0) - margin, max(max(vals), 1.0) + margin)


def case_jkr(quick, out):
    R, ac = 1.0, 0.3125
    ratios = (12.5, 25.0) if quick else (12.5, 25.0, 50.0)
    g = theory.jkr_dgamma(ac, R, E)
    F_adh, _ = theory.jkr_pulloff(R, g, E)
    dc = -float(theory.jkr_sphere(ac, R, g, E)[0])          # a_c^2/(3R): d at the force-controlled pull-off
    # the pull-off under force control, L = 1, N = a_c/h / a_c
    pull, rows = {}, []
    for crit in CRITERIA:
        pull[crit] = {}
        for ratio in ratios:
            N = int(round(ratio / ac))
            r = run(n=N, size=1.0, E_star=E, gamma=g, radius=R, start="hertz", control="force", criterion=crit,
                    path=[0.5 * F_adh, -2.0 * F_adh], steps=30, pulloff_rtol=1e-4)
            c = r["curve"]
            k = int(np.argmin(c["force"]))
            pull[crit][ratio] = dict(ratio=r["pull_off"] / F_adh, a=math.sqrt(c["area"][k] / math.pi) / ac,
                                     pulled_off=bool(c["pulled_off"].any()), **r["counts"])
            q = pull[crit][ratio]
            rows.append([crit, f"{ratio:g}", f"{N}", f"{q['ratio']:.4f}", f"{q['a']:.3f}",
                         "yes" if q["pulled_off"] else "NO"] + count_cells(r["counts"]))
    table("jkr: pull-off under force control (Hertz start at 0.5 F_adh, 30 steps to -2 F_adh, bisected to 1e-4)",
          ["criterion", "a_c/h", "N", "pull-off / F_adh", "a/a_c there", "pulled off"] + COUNTS_HEADER, rows)

    # one curve under displacement control: first touch, loading, unloading beyond the jump-off
    ratio_c = 12.5 if quick else 25.0
    L = 1.5
    N = int(round(L * ratio_c / ac))
    r = run(n=N, size=L, E_star=E, gamma=g, radius=R, start="adhesive", path=[0.0, 4 * dc, 0.0, -2.6 * dc], steps=20)
    c = r["curve"]
    dn, Fn, an = c["d"] / dc, c["force"] / F_adh, np.sqrt(c["area"] / math.pi) / ac
    loading = np.arange(len(dn)) <= np.argmax(dn)
    on = c["contact_points"] > 0
    # JKR's stable branch under displacement control (a >= 3^(-2/3) a_c), F against d
    a_branch = np.linspace(3 ** (-2 / 3), 3.0, 20001) * ac
    d_b, F_b = theory.jkr_sphere(a_branch, R, g, E)
    dev = Fn - np.interp(c["d"], d_b, F_b) / F_adh
    crows = []
    for name, sel in (("loading", loading & on), ("unloading", ~loading & on)):
        crows.append([name, f"{np.count_nonzero(sel)}", f"{np.mean(np.abs(dev[sel])):.4f}", f"{np.max(np.abs(dev[sel])):.4f}"])
    table(f"jkr: the curve under displacement control (a_c/h {ratio_c:g}, N = {N}, L = {L}; start adhesive at d = 0, "
          f"to 4 |d_c|, back to -2.6 |d_c|, 20 steps a leg): F/F_adh against JKR's stable branch at the same d",
          ["leg", "states in contact", "mean abs(dF)/F_adh", "max abs(dF)/F_adh"], crows)
    table("jkr: the curve's run", ["a_c/h", "N", "states", "largest tension (sampled) / F_adh", "a/a_c at first touch (JKR 1.211)"]
          + COUNTS_HEADER,
          [[f"{ratio_c:g}", f"{N}", f"{len(dn)}", f"{r['pull_off'] / F_adh:.4f}", f"{an[0]:.3f}"] + count_cells(r["counts"])])

    fig, (ax1, ax2) = figure()
    a = np.linspace(1e-4, 1.05 * an.max(), 2000) * ac
    d_j, F_j = theory.jkr_sphere(a, R, g, E)
    ax1.plot(d_j / dc, F_j / F_adh, **GREY, label="JKR")
    ax1.plot(dn[loading], Fn[loading], "o", ms=4, label="adhbem, loading")
    ax1.plot(dn[~loading], Fn[~loading], "s", ms=4, mfc="none", label="adhbem, unloading")
    ax1.axhline(-1, color="k", lw=0.5)
    ax1.axhline(0, color="k", lw=0.5, ls=":")
    ax1.set_xlim(-3.2, 4.3)
    ax1.set_ylim(-1.25, 1.05 * max(Fn.max(), 1.0))
    ax1.set_xlabel(r"indentation $d/|d_c|$, $|d_c| = a_c^2/(3R)$")
    ax1.set_ylabel(r"force $F/F_\mathrm{adh}$")
    ax1.set_title(f"crack-closure, $a_c/h$ = {ratio_c:g}, displacement control", fontsize=9)
    ax1.legend(fontsize=8, loc="upper left")
    convergence_panel(ax2, ratios, {crit: [pull[crit][q]["ratio"] for q in ratios] for crit in CRITERIA},
                      r"JKR: $F_\mathrm{adh} = 1.5\pi\Delta\gamma R$", 0.02)
    ax2.set_xlabel(r"$a_c/h$")
    ax2.set_ylabel(r"pull-off force / $F_\mathrm{adh}$")
    ax2.set_title("force control", fontsize=9)
    ax2.legend(fontsize=8, loc="upper right")
    save(fig, out, "jkr")
    return dict(pull_off={crit: {f"{q:g}": pull[crit][q] for q in ratios} for crit in CRITERIA},
                curve=dict(ratio=ratio_c, N=N, mean_deviation=float(np.mean(np.abs(dev[on]))), **r["counts"]))


# ---- punch -----------------------------------------------------------------------------------------

def case_punch(quick, out):
    g = 1e-3
    sizes = (17.5, 35.5) if quick else (17.5, 35.5, 71.0)
    show = sizes[1]
    res, rows = {}, []
    for crit in CRITERIA:
        res[crit] = {}
        for aoh in sizes:
            N = int(round(4 * aoh))
            a = aoh / N
            stiffness, d_c = theory.kendall_punch(a, g, E)
            F_k = -stiffness * d_c
            r = run(n=N, size=1.0, E_star=E, gamma=g, indenter="punch", punch_radius=a, start="hertz", control="force",
                    criterion=crit, path=[0.5 * F_k, -1.5 * F_k], steps=30, pulloff_rtol=1e-4)
            c = r["curve"]
            face = int(c["contact_points"][0])
            a_eff = math.sqrt(c["area"][0] / math.pi)       # the digitised face's radius (its area)
            k_eff, dc_eff = theory.kendall_punch(a_eff, g, E)
            F_eff = -k_eff * dc_eff
            full = (c["contact_points"] == face) & (np.abs(c["force"]) > 0.05 * F_eff)
            stiff = np.max(np.abs(c["force"][full] / (k_eff * c["d"][full]) - 1))
            res[crit][aoh] = dict(N=N, face=face, ratio=r["pull_off"] / F_eff, nominal=r["pull_off"] / F_k,
                                  stiffness=float(stiff), d=c["d"] / abs(dc_eff), F=c["force"] / F_eff,
                                  pulled_off=bool(c["pulled_off"].any()), counts=r["counts"])
            q = res[crit][aoh]
            rows.append([crit, f"{aoh:g}", f"{N}", f"{face}", f"{a_eff / a:.4f}", f"{q['ratio']:.4f}", f"{q['nominal']:.4f}",
                         f"{q['stiffness']:.2e}", "yes" if q["pulled_off"] else "NO"] + count_cells(r["counts"]))
    table("punch: Kendall's flat punch under force control (0.5 F_K to -1.5 F_K, 30 steps, bisected to 1e-4), dgamma 1e-3",
          ["criterion", "a/h", "N", "face points", "a_face/a", "pull-off / Kendall (a_face)", "pull-off / Kendall (a)",
           "max abs(F/(2 E* a_face d) - 1), full face", "pulled off"] + COUNTS_HEADER, rows)

    fig, (ax1, ax2) = figure()
    dd = np.linspace(-1, 0.55, 50)
    ax1.plot(dd, dd, **GREY, label=r"Kendall: $F = 2E^*a\,d$")
    ax1.plot([-1, -1], [-1, 0], color="0.6", lw=1, ls="--", zorder=1)
    for m, crit in zip("os", CRITERIA):
        q = res[crit][show]
        ax1.plot(q["d"], q["F"], m, ms=5 if m == "o" else 7, mfc="none" if m == "s" else None, label=crit)
    ax1.axhline(0, color="k", lw=0.5, ls=":")
    ax1.set_xlim(-1.25, 0.6)
    ax1.set_ylim(-1.25, 0.6)
    ax1.set_xlabel(r"indentation $d/|d_c|$, $d_c = -\sqrt{2\pi\Delta\gamma a/E^*}$")
    ax1.set_ylabel(r"force $F/F_K$, $F_K = \sqrt{8\pi\Delta\gamma E^* a^3}$")
    ax1.set_title(f"$a/h$ = {show:g}, force control ($a$: the face's area radius)", fontsize=8)
    ax1.legend(fontsize=8, loc="upper left")
    convergence_panel(ax2, sizes, {crit: [res[crit][q]["ratio"] for q in sizes] for crit in CRITERIA}, "Kendall", 0.01)
    ax2.set_xlabel("$a/h$")
    ax2.set_ylabel("pull-off force / Kendall's")
    ax2.legend(fontsize=8, loc="upper right")
    save(fig, out, "punch")
    return dict(pull_off={crit: {f"{q:g}": dict(ratio=res[crit][q]["ratio"], nominal=res[crit][q]["nominal"],
                                                 stiffness=res[crit][q]["stiffness"], **res[crit][q]["counts"])
                              for q in sizes} for crit in CRITERIA})


# ---- wave ------------------------------------------------------------------------------------------

def case_wave(quick, out):
    lam, D, alpha = 1.0, 0.01, 0.3
    dgamma = alpha ** 2 * math.pi ** 2 * E * D ** 2 / (2 * lam)
    pstar = math.pi * E * D / lam
    grids = (128, 256) if quick else (128, 256, 512, 1024, 2048)
    show = 256
    a_th = np.linspace(1e-6, 0.4999, 400001) * lam
    p_th = theory.johnson_wave(a_th, lam, D, dgamma, E)
    i_min = int(np.argmin(np.where(a_th < 0.25 * lam, p_th, np.inf)))
    p_min, a_min = p_th[i_min], a_th[i_min]               # the force-controlled pull-off
    p_max = p_th[a_th > 0.25 * lam].max()                  # the jump into full contact
    res, rows = {}, []
    for crit in CRITERIA:
        res[crit] = {}
        for N in grids:
            hg = lam / N
            x = (np.arange(N) + 0.5) * hg
            h = np.tile(D * (1 - np.cos(2 * np.pi * x / lam)), (4, 1))
            cell = lam * 4 * hg
            r = run(n=(N, 4), size=(lam, 4 * hg), E_star=E, gamma=dgamma, boundary="periodic", topography=h,
                    topography_kind="gap", start="adhesive", control="force", criterion=crit,
                    path=[0.0, 0.9 * p_max * cell, 2.5 * p_min * cell], steps=40, pulloff_rtol=1e-5)
            c = r["curve"]
            p = c["force"] / cell
            a = c["area"] / cell * lam / 2
            loading = np.arange(len(p)) <= np.argmax(p)
            dev = (p - theory.johnson_wave(a, lam, D, dgamma, E)) / pstar
            k = int(np.argmin(p))
            res[crit][N] = dict(p=p / pstar, a=a / lam, loading=loading, ratio=p[k] / p_min, a_off=a[k] / a_min,
                                load_dev=float(np.mean(np.abs(dev[loading]))), unload_dev=float(np.mean(np.abs(dev[~loading]))),
                                pulled_off=bool(c["pulled_off"].any()), counts=r["counts"])
            q = res[crit][N]
            rows.append([crit, f"{N}", f"{q['ratio']:.5f}", f"{q['a_off']:.3f}", f"{q['load_dev']:.4f}", f"{q['unload_dev']:.4f}",
                         "yes" if q["pulled_off"] else "NO"] + count_cells(r["counts"]))
    table(f"wave: Johnson's wave along the x axis (N x 4 strip, alpha {alpha}, D = 0.01 lam), force control: first touch "
          f"to 0.9 p_max, unloading to pull-off (40 steps a leg, bisected to 1e-5); Johnson: p_min = {p_min / pstar:.5f} p* "
          f"at a = {a_min / lam:.4f} lam, p_max = {p_max / pstar:.4f} p*",
          ["criterion", "N = lam/h", "pull-off / Johnson's", "a/a_Johnson there", "mean abs(p - p_J(a))/p*, loading",
           "unloading", "pulled off"] + COUNTS_HEADER, rows)

    fig, (ax1, ax2) = figure()
    ax1.plot(a_th / lam, p_th / pstar, **GREY, label="Johnson (1995)")
    colours = {"crack-closure": "C0", "pohrt-popov": "C1"}
    for m, crit in zip("os", CRITERIA):
        q = res[crit][show]
        ax1.plot(q["a"][q["loading"]], q["p"][q["loading"]], m, ms=4, color=colours[crit], label=f"{crit}, loading")
        ax1.plot(q["a"][~q["loading"]], q["p"][~q["loading"]], m, ms=4, mfc="none", color=colours[crit],
                 label=f"{crit}, unloading")
    ax1.axhline(0, color="k", lw=0.5, ls=":")
    lowest = min(res[crit][show]["p"].min() for crit in CRITERIA)
    ax1.set_xlim(0, 0.42)
    ax1.set_ylim(1.25 * lowest, 1.3 * p_max / pstar)
    ax1.set_xlabel(r"contact half-width $a/\lambda$")
    ax1.set_ylabel(r"mean pressure $\bar p/p^*$")
    ax1.set_title(rf"$\lambda/h$ = {show}, $\alpha$ = {alpha}, force control", fontsize=9)
    ax1.legend(fontsize=7, loc="upper left")
    convergence_panel(ax2, grids, {crit: [res[crit][N]["ratio"] for N in grids] for crit in CRITERIA}, "Johnson", 0.05,
                      colours)
    ax2.set_xlabel(r"$\lambda/h$")
    ax2.set_ylabel("pull-off (largest tension) / Johnson's")
    ax2.legend(fontsize=8, loc="center right")
    save(fig, out, "wave")
    return dict(pull_off={crit: {str(N): dict(ratio=res[crit][N]["ratio"], **res[crit][N]["counts"]) for N in grids}
                          for crit in CRITERIA})


# ---- maugis ----------------------------------------------------------------------------------------

def case_maugis(quick, out):
    G, lam, R = 0.004655, 1.0, 1.0
    FSCALE, ASCALE, DSCALE = theory.maugis_scales(G, R, E)
    s0 = lam / theory.tabor_lambda(1.0, G, R, E)
    P, A_off, D_off = theory.maugis_pulloff(lam)
    F_m = -P * FSCALE
    m_off = float(theory.maugis_sphere(lam, [A_off])[2][0])
    grids = (32, 64) if quick else (64, 128, 256)
    res, rows = {}, []
    for k, N in enumerate(grids):
        r = run(n=N, size=1.0, E_star=E, gamma=G, radius=R, criterion="dugdale", dugdale_stress=s0, dugdale_route="fixed-point", control="force",
                path=[0.02, -0.03], steps=30, pulloff_rtol=1e-4)
        zone = (m_off - 1) * A_off * ASCALE * N
        res[N] = dict(ratio=r["pull_off"] / F_m, width=float(r["resolution"]["cohesive_width"]), zone=zone,
                      pulled_off=bool(r["curve"]["pulled_off"].any()), counts=r["counts"])
        extra = ""
        if k:
            res[N]["extrapolated"] = 2 * res[N]["ratio"] - res[grids[k - 1]]["ratio"]   # first order, h halved
            extra = f"{res[N]['extrapolated']:.4f}"
        q = res[N]
        rows.append([f"{N}", f"{q['width']:.1f}", f"{q['zone']:.1f}", f"{q['ratio']:.4f}", extra,
                     "yes" if q["pulled_off"] else "NO"] + count_cells(r["counts"]))
    table(f"maugis: dugdale (the sharp law's fixed point, -adh_dugdale_route fixed-point) on the sphere, lambda {lam:g} (dgamma {G}, s0 {s0:.4g}, E* = R = 1, side 1), pull-off under force "
          f"control (F 0.02 to -0.03, 30 steps, bisected to 1e-4); Maugis: {-P:.4f} pi dgamma R",
          ["N", "zone width at pull-off (spacings)", "Maugis' (c - a)/h", "pull-off / Maugis", "extrapolated (first order)",
           "pulled off"] + COUNTS_HEADER, rows)

    # one curve under displacement control, unloading from a preload (the first state is adhesion-free)
    Nc = 64 if quick else 128
    r = run(n=Nc, size=1.0, E_star=E, gamma=G, radius=R, criterion="dugdale", dugdale_stress=s0, dugdale_route="fixed-point", path=[0.04, -0.06], steps=100)
    c = r["curve"]
    A = np.linspace(0.05, 2.5, 2000)
    P_m, D_m, _ = theory.maugis_sphere(lam, A)
    stable = A >= A[np.argmin(D_m)]
    Dn, Pn, An = c["d"] / DSCALE, c["force"] / FSCALE, np.sqrt(c["area"] / math.pi) / ASCALE
    sel = (np.arange(len(Dn)) > 0) & (c["contact_points"] > 0) & (Dn >= D_m.min())
    eF = np.abs(Pn[sel] - np.interp(Dn[sel], D_m[stable], P_m[stable])) * FSCALE / F_m
    ea = np.abs(An[sel] - np.interp(Dn[sel], D_m[stable], A[stable])) * ASCALE * Nc
    table(f"maugis: the curve under displacement control ({Nc}^2, d 0.04 to -0.06 in 100 steps, from an adhesion-free preload): "
          "the states in contact after the first, within the d range of Maugis' stable branch, against its F(d) and a(d)",
          ["N", "states compared", "mean abs(dF) / pull-off", "max abs(dF) / pull-off", "max abs(da) (spacings)",
           "largest tension (sampled) / Maugis"] + COUNTS_HEADER,
          [[f"{Nc}", f"{len(eF)}", f"{eF.mean():.4f}", f"{eF.max():.4f}", f"{ea.max():.2f}", f"{r['pull_off'] / F_m:.4f}"]
           + count_cells(r["counts"])])

    fig, (ax1, ax2) = figure()
    shown = D_m <= Dn.max() * 1.05
    ax1.plot(D_m[shown], P_m[shown], **GREY, label=rf"Maugis, $\lambda$ = {lam:g}")
    ax1.plot(Dn[1:], Pn[1:], "o", ms=3.5, mfc="none", label=f"adhbem, {Nc}$^2$, unloading")
    ax1.axhline(P, color="k", lw=0.5)
    ax1.axhline(0, color="k", lw=0.5, ls=":")
    ax1.set_xlabel(r"indentation $D = d\,(K^2/(\pi^2\Delta\gamma^2R))^{1/3}$")
    ax1.set_ylabel(r"force $P = F/(\pi\Delta\gamma R)$")
    ax1.set_xlim(min(D_m.min(), Dn.min()) - 0.1, Dn.max() * 1.05)
    ax1.set_ylim(P * 1.15, max(Pn.max(), 0.5) * 1.1)
    ax1.legend(fontsize=8, loc="upper left")
    ax1.set_title("dugdale (fixed point), displacement control", fontsize=9)
    x = np.array(grids, dtype=float)
    ax2.axhline(1.0, **GREY, label="Maugis")
    ax2.plot(x, [res[N]["ratio"] for N in grids], "o-", ms=6, lw=1, label="adhbem")
    ax2.plot(x[1:], [res[N]["extrapolated"] for N in grids[1:]], "D", ms=6, mfc="none",
             label="first-order extrapolation\nof the grid and the one before")
    for N in grids:
        ax2.annotate(f"zone {res[N]['width']:.0f} h", (N, res[N]["ratio"]), textcoords="offset points", xytext=(7, -3), fontsize=7)
    log2_axis(ax2, x, right=1.7)
    vals = [res[N]["ratio"] for N in grids] + [res[N]["extrapolated"] for N in grids[1:]]
    ax2.set_ylim(min(min(vals), 1.0) - 0.01, max(max(vals), 1.0) + 0.015)
    ax2.set_xlabel("grid $N$ (side 1)")
    ax2.set_ylabel("pull-off force / Maugis'")
    ax2.set_title("force control", fontsize=9)
    ax2.legend(fontsize=8, loc="upper right")
    save(fig, out, "maugis")
    return dict(pull_off={str(N): dict(ratio=res[N]["ratio"], width=res[N]["width"],
                                       **({"extrapolated": res[N]["extrapolated"]} if "extrapolated" in res[N] else {}),
                                       **res[N]["counts"]) for N in grids},
                curve=dict(N=Nc, mean_force_error=float(eF.mean()), max_force_error=float(eF.max()), **r["counts"]))


# ---- layer -----------------------------------------------------------------------------------------

def shull_load(x):
    """Shull's (2002) fitted correction to Hertz's load on a thin incompressible bonded layer
    (full friction at the indenter), at a/T = x: 1 + 0.33 x^3."""
    return 1 + 0.33 * np.asarray(x, dtype=float) ** 3


def shull_compliance(x):
    """Shull's fitted correction to the flat punch's compliance, the same layer: 1 / (1 + 1.33 x + 1.33 x^3)."""
    x = np.asarray(x, dtype=float)
    return 1 / (1 + 1.33 * x + 1.33 * x ** 3)


def shull_sphere(a, T: float, R: float, dgamma: float, E_star: float) -> np.ndarray:
    """The force of Shull's JKR sphere at contact radii a: his corrections in JKR's energy balance,
    F = F_H(a) - sqrt(2 dgamma / |dC/dA|), A = pi a^2 (fitted to finite-element results for an
    indenter bonded to the layer; adhbem's contact is frictionless)."""
    a = np.asarray(a, dtype=float)
    x = a / T
    F_H = 4 * E_star * a ** 3 / (3 * R) * shull_load(x)
    C0, fC = 1 / (2 * E_star * a), shull_compliance(x)
    dCda = -C0 / a * fC - C0 * (1.33 + 3 * 1.33 * x ** 2) / T * fC ** 2
    return F_H - np.sqrt(2 * dgamma * 2 * math.pi * a / np.abs(dCda))


def shull_pulloff(T: float, R: float, dgamma: float, E_star: float, a_c: float) -> tuple[float, float]:
    """Shull's pull-off force (> 0) and its contact radius, the minimum over 0.3 to 3 a_c (a_c: a
    guess, the exact one) sampled at 0.05% of a_c."""
    radii = np.linspace(0.3 * a_c, 3.0 * a_c, 5401)
    F = shull_sphere(radii, T, R, dgamma, E_star)
    k = int(np.argmin(F))
    return -float(F[k]), float(radii[k])


def shull_table(E1, nu1, R, g, F_half, a_half):
    """Shull's corrections against the exact ones (theory.layer_punch, layer_sphere) and a thick
    layer's pull-off, the numbers the verification page quotes."""
    Es = E1 / (1 - nu1 ** 2)
    a, rows = 0.1, []
    for x in (0.25, 0.5, 1.0, 2.0, 3.0, 5.0):
        T = a / x
        fC = float(theory.layer_punch(a, T, E1, nu1)[0]) * 2 * Es * a
        d, F = theory.layer_sphere([a], T, R, 0.0, E1, nu1)
        fP = float(F[0]) / (4 * Es * a ** 3 / (3 * R))
        rows.append([f"{x:g}", f"{fC:.4f}", f"{float(shull_compliance(x)):.4f}", f"{fP:.4f}", f"{float(shull_load(x)):.4f}"])
    table("layer: the corrections at a/T, exact (frictionless) against Shull's fits (full friction): the flat punch's "
          "compliance and the sphere's Hertz load over the half-space's", ["a/T", "compliance, exact", "Shull",
                                                                            "Hertz load, exact", "Shull"], rows)
    F_adh, a_c, _ = theory.layer_pulloff(0.4, R, g, E1, nu1)
    F_s, a_s = shull_pulloff(0.4, R, g, Es, a_c)
    print(f"\nlayer: T = 0.4 (a_c/T {a_c / 0.4:.2f}): the exact pull-off {F_adh / F_half:.4f} of the half-space's, "
          f"Shull's {F_s / F_adh:.4f} of the exact, his contact radius {a_s / a_c:.4f}")


def case_layer(quick, out):
    R, E1, nu1, g = 1.0, 1.0, 0.5, 2.8e-3
    Es = E1 / (1 - nu1 ** 2)
    thicknesses = (math.inf, 0.05) if quick else (math.inf, 0.2, 0.1, 0.05, 0.025, 0.0125)
    grids = {"crack-closure": (128, 192) if quick else (128, 192, 256, 384, 512),
             "pohrt-popov": (128,) if quick else (128, 256, 512)}
    show_N = 192 if quick else 256
    F_half, a_half = theory.jkr_pulloff(R, g, Es)
    res, rows, srows = {}, [], []
    for T in thicknesses:
        F_adh, a_c, _ = theory.layer_pulloff(T, R, g, E1, nu1)
        radii = np.linspace(0.3 * a_c, 3.0 * a_c, 40 if quick else 100)
        d_th, F_th = theory.layer_sphere(radii, T, R, g, E1, nu1)
        stable = radii >= a_c
        res[T] = dict(exact=F_adh, a_c=a_c, grids={})
        if not math.isinf(T):
            F_s, a_s = shull_pulloff(T, R, g, Es, a_c)
            res[T].update(shull=F_s / F_adh, shull_a=a_s / a_c)
        # the half-space's control on the free boundary; each layer on the periodic cell (its neighbours screened)
        body = dict(boundary="free", E_star=Es) if math.isinf(T) else \
            dict(boundary="periodic", elastic="layer", layer_thickness=T, E1=E1, nu1=nu1)
        for crit, Ns in grids.items():
            res[T]["grids"][crit] = {}
            for N in Ns:
                r = run(n=N, **body, gamma=g, radius=R, criterion=crit, start="hertz", control="force",
                        path=[0.5 * F_adh, -2.0 * F_adh], steps=30, pulloff_rtol=1e-4)
                c = r["curve"]
                a_run = np.sqrt(c["area"] / math.pi)
                k = int(np.argmin(c["force"]))
                # the contact radius along the unloading on JKR's stable branch (a > 1.1 a_c), against the exact one
                on = (a_run > 1.1 * a_c) & (c["contact_points"] > 0)
                on[0] = False                            # the Hertz start, not an adhesive state
                a_th = np.interp(c["force"][on], F_th[stable], radii[stable])
                res[T]["grids"][crit][N] = dict(ratio=r["pull_off"] / F_adh, a=float(a_run[k]) / a_c,
                                                a_path=float(np.max(np.abs(a_run[on] / a_th - 1))) if on.any() else None,
                                                pulled_off=bool(c["pulled_off"].any()), counts=r["counts"],
                                                F=c["force"] / F_half, r=a_run / a_half)
                q = res[T]["grids"][crit][N]
                rows.append([f"{T:g}", f"{a_c / T:.2f}", crit, f"{N}", f"{a_c * N:.1f}", f"{q['ratio']:.4f}",
                             f"{q['a']:.3f}", f"{q['a_path']:.4f}" if q["a_path"] is not None else "",
                             "yes" if q["pulled_off"] else "NO"] + count_cells(q["counts"]))
        cc = [q["ratio"] for q in res[T]["grids"]["crack-closure"].values()]
        pp = res[T]["grids"]["pohrt-popov"]
        res[T]["crack-closure range"] = (min(cc), max(cc))
        srows.append([f"{T:g}", f"{a_c / T:.2f}", f"{F_adh / F_half:.4f}", f"{a_c / a_half:.4f}",
                      f"{min(cc):.4f} to {max(cc):.4f}", f"{max(abs(v - 1) for v in cc):.4f}",
                      " ".join(f"{pp[N]['ratio']:.4f}" for N in grids["pohrt-popov"]),
                      f"{res[T]['shull']:.4f}" if "shull" in res[T] else "", f"{res[T]['shull_a']:.3f}" if "shull" in res[T] else ""])
    table(f"layer: JKR spheres on an incompressible bonded layer (R = 1, cell 1 x 1, dgamma {g:g}; T = inf: the half-space "
          "on the free boundary 1 x 1; force control from 0.5 F_adh to -2 F_adh, 30 steps, bisected to 1e-4): the pull-off "
          "over the exact F_adh, the contact radius there over a_c, the largest error of the contact radius along the "
          "unloading (a > 1.1 a_c)",
          ["T", "a_c/T", "criterion", "N", "a_c/h", "pull-off / F_adh", "a/a_c there", "max abs(a/a_exact - 1)",
           "pulled off"] + COUNTS_HEADER, rows)
    table("layer: the exact pull-off (theory.layer_pulloff) over the half-space's 1.5 pi dgamma R and its contact radius; "
          f"crack-closure's pull-off over the exact on the grids {', '.join(map(str, grids['crack-closure']))} (the range "
          f"and the largest deviation), pohrt-popov's on {', '.join(map(str, grids['pohrt-popov']))}; Shull's fitted "
          "corrections' pull-off and contact radius over the exact",
          ["T", "a_c/T", "F_adh / half-space's", "a_c / half-space's", "crack-closure / F_adh", "largest abs(r - 1)",
           "pohrt-popov / F_adh", "Shull / exact", "Shull's a_c / exact"], srows)

    shull_table(E1, nu1, R, g, F_half, a_half)

    layers = [T for T in thicknesses if not math.isinf(T)]
    fig, (ax1, ax2) = figure()
    shown = [t for t in layers if t in (0.2, 0.05, 0.0125)] or layers
    for colour, T in zip(("C0", "C1", "C2"), shown):
        a_c = res[T]["a_c"]
        radii = np.linspace(0.5 * a_c, 2.6 * a_c, 40 if quick else 100)
        _, F_th = theory.layer_sphere(radii, T, R, g, E1, nu1)
        ax1.plot(radii / a_half, F_th / F_half, color=colour, lw=2.5, alpha=0.45, zorder=1)
        ax1.plot(radii / a_half, shull_sphere(radii, T, R, g, Es) / F_half, color=colour, lw=1, ls="--", zorder=1)
        q = res[T]["grids"]["crack-closure"][show_N]
        on = q["r"] > 0
        on[0] = False                                    # the Hertz start, not an adhesive state
        ax1.plot(q["r"][on], q["F"][on], "o", ms=3.5, color=colour, label=f"$T$ = {T:g} ($a_c/T$ = {a_c / T:.1f})")
    ax1.plot([], [], color="0.4", lw=2.5, alpha=0.45, label="exact")
    ax1.plot([], [], color="0.4", lw=1, ls="--", label="Shull's fits")
    ax1.axhline(0, color="k", lw=0.5, ls=":")
    ax1.set_ylim(-1.8, 1.0)
    ax1.set_xlim(0.2, 1.7)
    ax1.set_xlabel("contact radius / half-space's $a_c$")
    ax1.set_ylabel(r"force / $1.5\pi\Delta\gamma R$")
    ax1.set_title(f"crack-closure, N = {show_N}, force control", fontsize=9)
    ax1.legend(fontsize=7, loc="lower right")
    aT = np.array([res[T]["a_c"] / T for T in layers])
    Tfine = np.geomspace(min(layers) / 1.2, 2.0, 6 if quick else 30)
    ex = [theory.layer_pulloff(T, R, g, E1, nu1) for T in Tfine]
    ax2.plot([e[1] / T for e, T in zip(ex, Tfine)], [e[0] / F_half for e in ex], **GREY, label="exact")
    ax2.plot(aT, [res[T]["shull"] * res[T]["exact"] / F_half for T in layers], "k--", lw=1, label="Shull's fits")
    for m, crit in zip("os", CRITERIA):
        vals = np.array([[q["ratio"] * res[T]["exact"] / F_half for q in res[T]["grids"][crit].values()] for T in layers])
        mid = np.median(vals, axis=1)
        ax2.errorbar(aT, mid, yerr=[mid - vals.min(axis=1), vals.max(axis=1) - mid], fmt=m, ms=5, mfc="none", capsize=2,
                     label=f"{crit}, N {grids[crit][0]}-{grids[crit][-1]}")
    ax2.set_xscale("log")
    ax2.set_xlabel("$a_c / T$ (the layer's $a_c$)")
    ax2.set_ylabel(r"pull-off / $1.5\pi\Delta\gamma R$")
    ax2.set_title("force control", fontsize=9)
    ax2.legend(fontsize=7, loc="upper left")
    save(fig, out, "layer")
    return dict(thickness={f"{T:g}": dict(exact=res[T]["exact"], a_c=res[T]["a_c"], shull=res[T].get("shull"),
                                          grids={crit: {str(N): dict(ratio=q["ratio"], a=q["a"], a_path=q["a_path"],
                                                                     pulled_off=q["pulled_off"], **q["counts"])
                                                        for N, q in res[T]["grids"][crit].items()} for crit in CRITERIA})
                           for T in thicknesses})


CASES = dict(hertz=case_hertz, westergaard=case_westergaard, jkr=case_jkr, punch=case_punch, wave=case_wave,
             maugis=case_maugis, layer=case_layer)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog="cases: " + ", ".join(CASES) + ". See the module docstring (the top of bench/verify.py).")
    ap.add_argument("--case", default="all", help="comma-separated cases, or all (default)")
    ap.add_argument("--quick", action="store_true", help="coarse grids only (a smoke test, about 40 s in all)")
    ap.add_argument("--out", help="the folder of the figures CASE.png (default: docs/_static/verification/; with --quick "
                    "BUILD/verification-quick/, so that a smoke test does not replace the documentation's figures)")
    ap.add_argument("--json", help="also write the tables' numbers to this JSON file")
    args = ap.parse_args()
    if args.out is None:
        from adhbem_build import BUILD
        args.out = os.path.join(BUILD, "verification-quick") if args.quick else os.path.join(ROOT, "docs", "_static", "verification")
    names = list(CASES) if args.case == "all" else [c.strip() for c in args.case.split(",") if c.strip()]
    unknown = [c for c in names if c not in CASES]
    if unknown:
        ap.error(f"unknown case(s) {', '.join(unknown)} (have: {', '.join(CASES)}, all)")
    results = {}
    for name in names:
        print(f"\n## {name}{' (quick)' if args.quick else ''}", flush=True)
        w0, c0 = time.perf_counter(), time.process_time()
        results[name] = CASES[name](args.quick, args.out)
        results[name]["wall"] = time.perf_counter() - w0
        results[name]["cpu"] = time.process_time() - c0
        print(f"\n{name}: {results[name]['wall']:.1f} s wall, {results[name]['cpu']:.1f} s CPU", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(dict(quick=args.quick, cases=results), f, indent=1)


if __name__ == "__main__":
    main()
