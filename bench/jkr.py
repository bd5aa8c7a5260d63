"""./run bench jkr [--sizes 128,256,512,1024] [--ranks 1,2] [--steps 45] [--budget SECONDS]

The paper's JKR pull-off (sphere, Hertz start, 45 unloading steps) with the same physical
problem on finer grids (a_c = 0.195 L, a_c/h = 50 at N = 256), on 1 and 2 ranks. Prints total
time, compliance applications (FFT convolutions of any window size), KSP iterations, shrink
(set update) iterations and time per application. Counts do not depend on the machine; times do.
A size is skipped once the previous size took more than the budget.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import job  # noqa: E402


def run(n, ranks, steps, extra):
    opts = job.jkr_options(n, 50.0 * n / 256, steps=steps)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "jkr.h5")
        args = []
        for k, v in opts.items():
            args += [f"-adh_{k}", ",".join(repr(x) for x in v) if isinstance(v, list) else str(v)]
        t0 = time.perf_counter()
        subprocess.run(["mpirun", "--oversubscribe", "-n", str(ranks), job.EXE,
                        *args, "-adh_output", out, *extra], check=True, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        with h5py.File(out, "r") as f:
            c = {k: f["curve"][k][()] for k in f["curve"]}
    F_adh, _, _ = job.jkr_theory(opts["gamma"], opts["radius"], opts["E_star"])
    return {"wall": wall, "solve": float(c["seconds"].sum()), "mults": int(c["compliance_applications"].sum()),
            "ksp": int(c["ksp_iterations"].sum()), "outer": int(c["outer_iterations"].sum()),
            "err": 100 * (-c["force"].min() - F_adh) / F_adh}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", default="128,256,512,1024")
    p.add_argument("--ranks", default="1,2")
    p.add_argument("--steps", type=int, default=45)
    p.add_argument("--budget", type=float, default=120.0, help="skip larger sizes once one took longer")
    p.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = p.parse_args()
    sizes = [int(s) for s in a.sizes.split(",")]
    ranks = [int(r) for r in a.ranks.split(",")]
    print(f"{'N':>5} {'ranks':>5} {'wall s':>8} {'solve s':>8} {'K-apps':>8} {'KSP its':>8} {'shrink':>7}"
          f" {'ms/app':>7} {'Fmax err':>9}")
    rows = {}
    for r in ranks:
        for n in sizes:
            if n // 2 in rows.get(r, {}) and rows[r][n // 2]["wall"] > a.budget:
                print(f"{n:>5} {r:>5}  skipped (N = {n // 2} took {rows[r][n // 2]['wall']:.0f} s > budget)")
                continue
            m = run(n, r, a.steps, a.extra)
            rows.setdefault(r, {})[n] = m
            print(f"{n:>5} {r:>5} {m['wall']:>8.2f} {m['solve']:>8.2f} {m['mults']:>8} {m['ksp']:>8} {m['outer']:>7}"
                  f" {1e3 * m['solve'] / m['mults']:>7.2f} {m['err']:>8.2f}%", flush=True)
    for r, byn in rows.items():
        ns = sorted(byn)
        if len(ns) >= 2:
            e_t = np.polyfit(np.log(ns), np.log([byn[n]["solve"] for n in ns]), 1)[0]
            e_m = np.polyfit(np.log(ns), np.log([byn[n]["mults"] for n in ns]), 1)[0]
            e_o = np.polyfit(np.log(ns), np.log([byn[n]["outer"] for n in ns]), 1)[0]
            print(f"{r} rank(s): solve time ~ N^{e_t:.2f}, compliance applications ~ N^{e_m:.2f}, "
                  f"shrink iterations ~ N^{e_o:.2f} (paper: time ~ N^2.5)")


if __name__ == "__main__":
    main()
