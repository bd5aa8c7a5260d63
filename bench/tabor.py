"""./run bench tabor: the JKR limit on a rough surface, measured with finite-range adhesion.

On a rough cell there is no closed form for the JKR limit (zero range), and the two JKR-limit
criteria converge with the grid to answers that differ. Maugis' finite-range model
(-adh_criterion dugdale) has no singularity at the contact's edge: at a given range it converges
with the grid to a well-defined continuum answer once its cohesive zones span several elements,
and as the range shrinks it tends to the JKR limit. This bench measures that limit and sets the
JKR-limit criteria against it.

The surface and path are ./run bench convergence's configuration (--config, default resolved:
the same band-limited surface on every grid, displacement control 0 -> d1 -> 0 -> -d1). The range
is given as the Tabor-Maugis parameter of the smallest asperities, lambda = 2 s0 (R/(pi dgamma
K^2))^(1/3), K = 4E*/3, R their mean tip radius (the estimate adhbem reports): s0 follows from
lambda, the range is dgamma/s0. For each lambda of --lambdas the dugdale run is made on each grid
of --n and extrapolated in the grid (Richardson's estimate with the order three grids show; first
order for the sharp law's fixed point, which the sphere shows: tests/solver/test_dugdale.py), with
an error bar (at least the last refinement's change); then the extrapolated values are
extrapolated in the range (f = f_JKR + c/lambda^k, k between 1 and 2, from the two largest lambdas
whose grid limits are within 1%: Maugis' sphere approaches its JKR pull-off so; the middle of the
two forms, half their distance in the error bar). crack-closure and pohrt-popov run on the same
grids, extrapolated in the grid as bench convergence does (their observed order).

Per quantity (the largest tension, the energy dissipated over the loop, the force and the contact
area fraction at the deepest state) the table gives every run's value, the extrapolations, and at
the end each JKR-limit criterion's difference from the finite-range limit. Counts and CPU time
per run are printed as the runs finish (stderr) and kept in --json.

    ./run bench tabor [--config resolved|moderate|unresolved] [--hurst H] [--seed S] [--n N1,N2] [--lambdas L1,L2,...]
        [--route minimize|fixed-point] [--criteria crack-closure,pohrt-popov|none] [--np P] [--steps K] [--quick]
        [--json FILE] [-- OPTIONS]
    ./run bench tabor --from-json A.json[,B.json...]    (the table of saved runs of one surface)

--criteria: the JKR-limit criteria beside, each with its default attach rule (griffith with
crack-closure, reach with pohrt-popov) or the one after a slash (crack-closure/reach).

--route: how the dugdale runs find their zones (-adh_dugdale_route): the energy minimisation of the
law smoothed over -adh_dugdale_smoothing of its range (adhbem's default) or the fixed point of set
updates (Maugis' sharp law). --criteria none runs the finite-range model alone.

--quick: grids 48,96 and lambdas 0.5,1 (a smoke test of a few minutes; not the study). The zones at
pull-off are about 0.4 a_c wide at lambda 1, 1.2 a_c at 0.5 and 0.13 a_c at 2 (a_c the asperities'
JKR contact radius, 5, 10, 20 spacings of grids 64, 128, 256 in the resolved configuration): a
lambda is only worth its runs on grids where that spans several elements.
"""
import argparse
import importlib.util
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
spec = importlib.util.spec_from_file_location("bench_convergence", os.path.join(ROOT, "bench", "convergence.py"))
convergence = importlib.util.module_from_spec(spec)
spec.loader.exec_module(convergence)

# A lambda's grid limit counts as resolved, and enters the zero-range limit, when its error bar
# is within this share of its value.
RESOLVED = 0.01

KEYS = (("largest_tension", "largest tension (-min F)"),
        ("loop_energy", "energy dissipated over the loop"),
        ("force_deepest", "force at the deepest state"),
        ("area_deepest", "contact area fraction at the deepest state"))


sys.path.insert(0, os.path.join(ROOT, "python"))
from adhbem.theory import maugis_pulloff, maugis_sphere, tabor_lambda  # noqa: E402  (numpy only)


def s0_for(lam, surface, gamma, E=convergence.E_STAR):
    """The cohesive stress at which the smallest asperities' Tabor-Maugis parameter is lam
    (lambda is linear in s0)."""
    return lam / tabor_lambda(1.0, gamma, surface.tip_radius(), E)


def first_order(values):
    """Two grids, the spacing halved: f_inf = 2 f_2N - f_N (first order)."""
    if len(values) < 2 or any(not math.isfinite(v) for v in values[-2:]):
        return float("nan")
    return 2.0 * values[-1] - values[-2]


def grid_limit(values):
    """The grid limit of a JKR-limit criterion: bench convergence's Richardson estimate with the
    observed order from three grids, first order from two."""
    if len(values) >= 3:
        r = convergence.richardson(values)
        if r["f_inf"] is not None:
            return r["f_inf"]
    return first_order(values)


def limit_and_error(name, run, sizes, key):
    """A run's grid limit and its error bar (the distance of the finest grid from it). The fixed
    point of set updates converges at first order (the zone's edge snaps to an element); the other
    runs by Richardson's estimate with the order three grids show (first order from two)."""
    vals = [float("nan") if run["grids"][n]["quantities"][key] is None else run["grids"][n]["quantities"][key] for n in sizes]
    fixed = name.startswith("dugdale") and run.get("route", "fixed-point") == "fixed-point"
    lim = first_order(vals) if fixed else grid_limit(vals)
    if not math.isfinite(lim):
        return vals, lim, float("nan")
    # at least the last refinement's change: an order observed from an unresolved coarse grid can
    # be spurious (lambda 2's 649, 610.90, 610.87 gives p = 10)
    return vals, lim, max(abs(lim - vals[-1]), abs(vals[-1] - vals[-2]))


def zero_range(limits, lambdas, key):
    """The zero-range limit through the two largest lambdas whose grid limits are resolved (an
    error bar within RESOLVED of the value), a and b: f = f_JKR + c / lambda^k, with k between 1 and
    2 (Maugis' sphere approaches its JKR pull-off so: k goes from 1.1 between lambda 0.5 and 1 to
    1.5 between 1 and 2 and to 2 as lambda grows; adhbem.theory.maugis_pulloff). The value is the
    middle of the two forms' limits, its error bar half their distance plus the grid errors carried
    through (the larger form's factors). Returns the limit, its error bar, the lambdas used and
    those left out (no finite grid limit, or one not resolved)."""
    finite = [v for v in sorted(lambdas) if math.isfinite(limits[f"dugdale lambda {v:g}"][key][0])]
    ok = [v for v in finite if limits[f"dugdale lambda {v:g}"][key][1] <= RESOLVED * abs(limits[f"dugdale lambda {v:g}"][key][0])]
    out = [v for v in sorted(lambdas) if v not in ok]
    if len(ok) < 2:
        return float("nan"), float("nan"), ok, out
    a, b = ok[-2:]
    (fa, ea), (fb, eb) = (limits[f"dugdale lambda {v:g}"][key] for v in (a, b))
    forms, carried = [], 0.0
    for k in (1.0, 2.0):
        wa, wb = a ** k, b ** k
        forms.append((wb * fb - wa * fa) / (wb - wa))
        carried = max(carried, (wb * eb + wa * ea) / (wb - wa))
    return 0.5 * (forms[0] + forms[1]), 0.5 * abs(forms[0] - forms[1]) + carried, [a, b], out


def report(runs, sizes):
    """The table: every run's values, its grid limit with its error bar, the zero-range limit, and
    each JKR-limit criterion against it."""
    width = 12
    lambdas = sorted(r["lam"] for r in runs.values() if "lam" in r)
    criteria = [name for name, r in runs.items() if "lam" not in r]
    print(f"\n{'run':<26}" + "".join(f"{'N = ' + str(n):>{width}}" for n in sizes) + f"{'grid limit':>{width + 10}}")
    limits = {}
    for key, label in KEYS:
        print(f"\n{label}")
        for name, r in runs.items():
            vals, lim, err = limit_and_error(name, r, sizes, key)
            limits.setdefault(name, {})[key] = (lim, err)
            print(f"  {name:<24}" + "".join(f"{v:>{width}.5g}" for v in vals) + f"{lim:>{width}.5g} +- {err:<7.2g}")
        if len(lambdas) >= 2:
            jkr, err, used, out = zero_range(limits, lambdas, key)
            limits.setdefault("dugdale, zero range", {})[key] = (jkr, err)
            print(f"  {'dugdale, zero range':<24}" + " " * (width * len(sizes)) + f"{jkr:>{width}.5g} +- {err:<7.2g}"
                  + f" (from lambda {' and '.join(f'{v:g}' for v in used) or 'none'}"
                  + (f"; lambda {', '.join(f'{v:g}' for v in out)} left out: no grid limit within {RESOLVED:.0%})" if out else ")"))
    held = [f"{name} N = {n}" for name, r in runs.items() for n in sizes if not r["grids"][n]["run"]["pulled_off"]]
    if held:  # their largest tension is the tension at the path's end, not a pull-off
        print("\nStill in contact at the path's end (their largest tension is not a pull-off): " + ", ".join(held))
    if criteria and len(lambdas) >= 2:
        print("\nThe JKR-limit criteria against the finite-range limit (grid limits; (criterion - zero range) / |zero range|,"
              " +- the two error bars added):")
    for crit in criteria if len(lambdas) >= 2 else ():
        parts = []
        for key, label in KEYS:
            (ref, eref), (c, ec) = limits["dugdale, zero range"][key], limits[crit][key]
            parts.append(f"{key} {(c - ref) / abs(ref):+.1%} +- {(ec + eref) / abs(ref):.1%}" if math.isfinite(ref) and ref else f"{key} n/a")
        print(f"  {crit:<26} " + ", ".join(parts))
    return limits


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", default="resolved", choices=("resolved", "moderate", "unresolved"))
    ap.add_argument("--hurst", type=float, default=0.8, help="the surface's Hurst exponent (default 0.8)")
    ap.add_argument("--seed", type=int, default=1, help="the surface's random seed (default 1)")
    ap.add_argument("--n", help="grids N1,N2[,N3] (each twice the last; default 64,128,256)")
    ap.add_argument("--lambdas", help="Tabor-Maugis parameters of the smallest asperities (default 0.5,1,2), or none (the criteria alone)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--steps", type=int, default=25, help="steps per leg")
    ap.add_argument("--quick", action="store_true", help="grids 48,96 and lambdas 0.5,1: a smoke test")
    ap.add_argument("--route", default="minimize", choices=("minimize", "fixed-point"),
                    help="the dugdale runs' -adh_dugdale_route (default minimize, adhbem's)")
    ap.add_argument("--criteria", default="crack-closure,pohrt-popov",
                    help="the JKR-limit criteria run beside, comma-separated, or none (the finite-range runs alone)")
    ap.add_argument("--json", help="write all numbers to this JSON file")
    ap.add_argument("--from-json", help="run nothing: the table of the runs in these --json files (comma-separated, one surface and grid set)")
    ap.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = ap.parse_args()
    if a.from_json:
        return from_json(ap, a.from_json.split(","))
    sizes = [int(v) for v in a.n.split(",")] if a.n else [48, 96] if a.quick else [64, 128, 256]
    lambdas = [] if a.lambdas == "none" else [float(v) for v in a.lambdas.split(",")] if a.lambdas else [0.5, 1.0] if a.quick else [0.5, 1.0, 2.0]
    if len(sizes) < 2 or any(m != 2 * n for n, m in zip(sizes, sizes[1:])):
        ap.error("--n: two grids or more, each twice the last")
    if len(lambdas) == 1 or any(not v > 0 for v in lambdas):
        ap.error("--lambdas: two or more positive values, or none")
    criteria = [] if a.criteria == "none" else [c.strip() for c in a.criteria.split(",") if c.strip()]
    if not lambdas and not criteria:
        ap.error("--lambdas none --criteria none: nothing to run")
    for crit in criteria:  # criterion[/attach rule]: the criterion's default attach rule without
        rule, _, attach = crit.partition("/")
        if rule not in ("crack-closure", "pohrt-popov") or attach not in ("", "griffith", "reach", "penetration"):
            ap.error(f"--criteria: unknown JKR-limit criterion '{crit}' (crack-closure or pohrt-popov, each with an optional "
                     "/griffith, /reach or /penetration attach rule, or none)")
    s, gamma, what = convergence.configuration(a.config, sizes[0], hurst=a.hurst, seed=a.seed)
    Z = {n: s.heights(n) for n in sizes}
    zmax = float(Z[sizes[-1]].max())
    d1 = float(convergence.np.quantile(zmax - Z[sizes[-1]], 0.25))
    ac = s.jkr_radius(gamma)
    print(f"# The JKR limit on a rough cell, measured with finite-range adhesion ({a.config}: {what}; Hurst {a.hurst:g}, seed {a.seed})")
    print("# path " + " -> ".join(f"{v:.5g}" for v in convergence.path(d1, 3)) + f", {a.steps} steps a leg (a run ends early if it comes apart)")
    print(f"# dgamma {gamma:.6g}, asperity tip radius {s.tip_radius():.4g}, a_c {ac:.4g} = "
          + ", ".join(f"{ac * n / s.L:.3g}" for n in sizes) + f" spacings on grids {', '.join(map(str, sizes))}; d1 {d1:.5g}")
    K = 4.0 * convergence.E_STAR / 3.0
    for lam in lambdas:  # Maugis' sphere of the asperities' tip radius: the zone's width at its pull-off
        _, A, _ = maugis_pulloff(lam)
        m = maugis_sphere(lam, [A])[2][0]
        width = (m - 1) * A * (math.pi * gamma * s.tip_radius() ** 2 / K) ** (1 / 3)
        print(f"# lambda {lam:g}: s0 {s0_for(lam, s, gamma):.5g}, range {gamma / s0_for(lam, s, gamma):.4g}; an asperity's zone at its pull-off "
              f"about " + ", ".join(f"{width * n / s.L:.3g}" for n in sizes) + " spacings wide (resolved from about 10)")
    runs = {}

    def measure(criterion, extra, tag):
        out = {}
        for n in sizes:
            c, attrs, cpu, wall = convergence.run(s, n, zmax - Z[n], d1, gamma, criterion, a.steps, a.np, 3, list(extra) + a.extra, None, tag)
            q, k = convergence.quantities(c, d1, s.L)
            zone = float(max(c["cohesive_area"])) if "cohesive_area" in c else 0.0
            k["largest_tension_d"] = float(c["d"][int(convergence.np.argmin(c["force"]))])
            out[n] = dict(quantities=q, run=k, cpu=cpu, wall=wall, largest_zone_area=zone)
            print(f"[{tag} N = {n}: {k['states']} states, {k['set_updates']} set updates, {k['ksp']} KSP iterations, "
                  f"{k['fft_pairs']} FFT pairs, CPU {cpu:.1f} s, largest tension at d = {k['largest_tension_d']:.5g}, "
                  + (f"pulled off at d = {k['pull_off_d']:.5g}]" if k["pulled_off"] else "still in contact at the path's end]"), file=sys.stderr, flush=True)
        return out

    for lam in lambdas:
        s0 = s0_for(lam, s, gamma)
        runs[f"dugdale lambda {lam:g}"] = dict(s0=s0, range=gamma / s0, lam=lam, route=a.route,
                                              grids=measure("dugdale", ["-adh_dugdale_stress", repr(s0), "-adh_dugdale_route", a.route],
                                                            f"dugdale-{lam:g}"))
    for crit in criteria:
        runs[crit] = dict(grids=measure(crit, [], crit))
    limits = report(runs, sizes)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(convergence.finite(dict(config=a.config, hurst=a.hurst, seed=a.seed, steps=a.steps, grids=sizes, lambdas=lambdas, gamma=gamma, d1=d1,
                                              a_c=ac, tip_radius=s.tip_radius(), runs={k: dict(v, grids={str(n): g for n, g in v["grids"].items()})
                                                                                       for k, v in runs.items()},
                                              limits=limits)), f, indent=1)
        print(f"\nwrote {a.json}")


def from_json(ap, files):
    """The table of runs saved by --json, merged from several files of one surface (the dugdale
    runs in one job, the criteria in another): a study run across batch jobs."""
    runs, first = {}, None
    for path in files:
        try:
            with open(path) as f:
                d = json.load(f)
        except (OSError, ValueError) as e:
            ap.error(f"--from-json: cannot read {path}: {e}")
        same = ("config", "hurst", "seed", "grids", "gamma", "d1", "steps")
        if first is None:
            first = d
        else:  # a key an older file lacks is not a difference
            differ = [k for k in same if k in d and k in first and d[k] != first[k]]
            if differ:
                ap.error(f"--from-json: {path} is another surface, grid set or path than {files[0]} ("
                         + ", ".join(f"{k} {d[k]} against {first[k]}" for k in differ) + ")")
        for name, r in d["runs"].items():
            if name in runs:
                ap.error(f"--from-json: the run '{name}' is in {path} and in an earlier file: merge files of different runs")
            runs[name] = dict(r, grids={int(n): g for n, g in r["grids"].items()})
    print(f"# The JKR limit on a rough cell ({first['config']}, Hurst {first['hurst']:g}, seed {first['seed']}), from "
          + ", ".join(files) + f"; d1 {first['d1']:.5g}")
    return report(runs, first["grids"])


if __name__ == "__main__":
    main()
