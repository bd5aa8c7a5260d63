"""./run bench work_precision: a faster route against the exact cascade, judged by its error over an
ensemble of perturbed runs, with its cost.

    ./run bench convergence --config resolved --n 64,128,256 --criteria crack-closure \\
        --perturb 4 --perturb-size 1e-4 --json exact.json -- -adh_cascade_local 0
    ./run bench convergence ... (the same) --json default.json
    ./run bench convergence ... (the same) --json loose.json -- -adh_cascade_local 0 -adh_cascade_rtol 1e-3
    ./run bench work_precision exact.json default=default.json loose=loose.json [NAME=FILE ...]

(The first file is the reference route: the exact cascade, -adh_cascade_local 0; crack-closure's
default is local solves on the whole grid.)

A FILE may be A.json+B.json: one ensemble from several runs of bench convergence, the later ones
with --perturb-first past the earlier ones' perturbations.

A cascade's avalanches can tip either way on a perturbation of the heights far below any physical
scale (bench convergence --perturb), so one run's distance from the converged answer is partly
luck. The reference is the Richardson estimate (bench convergence's) from the exact cascade's
ensemble means on the grids of the file; each route's error on a grid is the RMS over its
ensemble (the run and its perturbed reruns) of (f - f_ref) / |f_ref|, next to the exact cascade's
own, and their ratio (the rule for a new default: at most 1.25 on every quantity and grid, on
top of the analytic cases). The counts are the unperturbed run's: FFT pairs and CPU seconds.
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from convergence import QUANTITIES, richardson  # noqa: E402


def load_one(path):
    with open(path) as f:
        out = json.load(f)
    if len(out["configurations"]) != 1 or len(out["criteria"]) != 1:
        sys.exit(f"bench work_precision: {path} must hold one configuration and one criterion (--config, --criteria)")
    return out


def load(paths):
    """One route's ensemble from A.json[+B.json...]: the runs of bench convergence on the same
    surface and options, the later ones with --perturb-first past the earlier ones' samples. The
    unperturbed run is the same in each (the runs are deterministic) and counts once."""
    files = [load_one(path) for path in paths.split("+")]
    first = files[0]
    config, crit = first["configurations"][0], first["criteria"][0]
    taken = []
    for path, out in zip(paths.split("+"), files):
        c = out["configurations"][0]
        if out["criteria"][0] != crit or out["grids"] != first["grids"] or c["configuration"] != config["configuration"] \
                or None not in (out.get("perturb_size"), first.get("perturb_size")) and out["perturb_size"] != first["perturb_size"]:
            sys.exit(f"bench work_precision: {path} is another configuration, criterion, set of grids or perturbation size than {paths.split('+')[0]}")
        k = max(len(c["results"][crit][str(n)].get("perturbed", [])) for n in out["grids"])
        lo = out.get("perturb_first", 0)
        if any(lo < b and a < lo + k for a, b in taken):
            sys.exit(f"bench work_precision: {path} repeats perturbations of an earlier file (bench convergence --perturb-first)")
        taken.append((lo, lo + k))
        if out is not first:
            for n in out["grids"]:
                config["results"][crit][str(n)].setdefault("perturbed", []).extend(c["results"][crit][str(n)].get("perturbed", []))
    return config, crit


def samples(config, crit, n, key):
    r = config["results"][crit][str(n)]
    if "perturbed" not in r:
        sys.exit("bench work_precision: the runs need their ensembles (bench convergence --perturb K)")
    values = [r["quantities"][key]] + [s[key] for s in r["perturbed"]]
    return np.array([v if v is not None else np.nan for v in values], dtype=float)


def main(argv):
    if len(argv) < 2 or any("=" not in a for a in argv[1:]):
        sys.exit(__doc__)
    exact, crit = load(argv[0])
    routes = {}
    for arg in argv[1:]:
        name, path = arg.split("=", 1)
        routes[name] = load(path)
        if routes[name][1] != crit or routes[name][0]["grids"] != exact["grids"] or routes[name][0]["configuration"] != exact["configuration"]:
            sys.exit(f"bench work_precision: {path} is another configuration, criterion or set of grids than {argv[0]}")
    grids = exact["grids"]
    print(f"# Work and precision: {exact['configuration']} configuration, {crit}, grids {', '.join(map(str, grids))}\n")
    print("| quantity | reference | N | exact cascade: RMS error | " + " | ".join(f"{name}: RMS error (ratio)" for name in routes) + " |")
    print("|" + " --- |" * (4 + len(routes)))
    for key, label in QUANTITIES:
        ref = richardson([float(np.nanmean(samples(exact, crit, n, key))) for n in grids])
        f = ref["f_inf"]
        for n in grids:
            e = float(np.sqrt(np.nanmean((samples(exact, crit, n, key) - f) ** 2)) / abs(f))
            cells = []
            for name, (config, _) in routes.items():
                r = float(np.sqrt(np.nanmean((samples(config, crit, n, key) - f) ** 2)) / abs(f))
                cells.append(f"{100 * r:.2f}% ({r / e:.2f})" if e > 0 else f"{100 * r:.2f}%")
            print(f"| {label} | {f:.5g} +- {ref['error']:.2g} | {n} | {100 * e:.2f}% | " + " | ".join(cells) + " |")
    print("\n| route | " + " | ".join(f"N = {n}: FFT pairs, CPU s" for n in grids) + " |")
    print("|" + " --- |" * (1 + len(grids)))
    for name, (config, _) in [("exact cascade", (exact, crit))] + list(routes.items()):
        cells = [f"{config['results'][crit][str(n)]['run']['fft_pairs']}, {config['results'][crit][str(n)]['cpu']:.1f}" for n in grids]
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
