"""The main jobs of ./run: the paper's JKR pull-off and the Kendall flat punch.

Runs the adhbem executable (build/adhbem; build64/adhbem with ADHBEM_INDICES=64) under mpirun,
writes results/NAME.h5, .csv and .png, and prints the numbers next to the analytic ones
(JKR and Kendall). Run through ./run jkr or ./run punch.

Both reproduce the paper (Pohrt & Popov 2015): its detachment criterion (-adh_criterion
pohrt-popov) and its loop, which only lets points go on unloading (-adh_attach penetration).
`--criterion crack-closure` runs the same case with adhbem's default criterion.
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# adhbem (petsc4py) is imported only after mpirun has run: an MPI process that has started
# MPI cannot launch mpirun.
sys.path.insert(0, os.path.join(ROOT, "python"))
from adhbem_build import EXE  # noqa: E402  (no PETSc, no MPI)


def jkr_theory(gamma, R, E):
    F_adh = 1.5 * math.pi * gamma * R
    a_c = (9 * math.pi * gamma * R**2 / (8 * E)) ** (1 / 3)
    d_c = (3 * math.pi**2 * gamma**2 * R / (64 * E**2)) ** (1 / 3)   # |d_c|
    return F_adh, a_c, d_c


# the paper's criterion and loop (adhbem's defaults are crack-closure and griffith)
PAPER = {"criterion": "pohrt-popov", "attach": "penetration"}


def jkr_options(n, ratio, R=1.0, E=1.0, L=1.0, steps=45, start_ratio=1.3, end=-2.3):
    """Sphere with a_c = ratio*h; Hertz start with radius start_ratio*a_c; unload to end*|d_c|."""
    h = L / n
    a_c = ratio * h
    gamma = a_c**3 * 8 * E / (9 * math.pi * R**2)
    _, _, d_c = jkr_theory(gamma, R, E)
    d0 = (start_ratio * a_c) ** 2 / R
    return {"n": n, "size": L, "E_star": E, "radius": R, "gamma": gamma, "indenter": "sphere",
            "path": [d0, end * d_c], "steps": steps, "start": "hertz", **PAPER}


def punch_options(n, ratio, E=1.0, L=1.0, gamma=1e-3, steps=80):
    """Flat punch of radius a = ratio*h, unloaded from d = +|d_crit|/2 to 1.25 d_crit."""
    a = ratio * L / n
    d_crit = math.sqrt(2 * math.pi * a * gamma / E)
    return {"n": n, "size": L, "E_star": E, "punch_radius": a, "gamma": gamma, "indenter": "punch",
            "path": [0.5 * d_crit, -1.25 * d_crit], "steps": steps, "start": "hertz", **PAPER}


def run_adhbem(options, output, np_ranks, extra=()):
    args = []
    for k, v in options.items():
        args += [f"-adh_{k}", ",".join(repr(x) for x in v) if isinstance(v, list) else str(v)]
    cmd = ["mpirun", "--oversubscribe", "-n", str(np_ranks), EXE,
           *args, "-adh_output", output, "-adh_fields", "pressure,contact", *extra]
    subprocess.run(cmd, check=True)
    import adhbem
    with adhbem.load(output) as r:
        return r.curve, r.params


def draw(output):
    """The curves against the analytic solution, and the pressure maps (adhbem.plot)."""
    from adhbem.plot import plot
    png = plot(output)
    print(f"wrote {png}")


def table(rows):
    print(f"{'quantity':<34}{'adhbem':>14}{'analytic':>14}{'error':>10}")
    for name, num, ref in rows:
        print(f"{name:<34}{num:>14.6g}{ref:>14.6g}{100 * (num - ref) / abs(ref):>9.2f}%")


def criterion_line(opts):
    if opts["criterion"] == PAPER["criterion"]:
        return ("detachment criterion pohrt-popov: the paper's, reproduced here (adhbem's default is crack-closure: "
                "--criterion crack-closure)")
    return f"detachment criterion {opts['criterion']} (the paper's is pohrt-popov, this job's default)"


def jkr(args):
    opts = dict(jkr_options(args.n, args.ratio, steps=args.steps), criterion=args.criterion)
    out = os.path.join(args.results, "jkr.h5")
    curve, attrs = run_adhbem(opts, out, args.np, args.extra)
    F_adh, a_c, d_c = jkr_theory(opts["gamma"], opts["radius"], opts["E_star"])
    d, F, A = curve["d"], curve["force"], curve["area"]
    a = np.sqrt(A / math.pi)
    k = int(np.argmin(F))
    last = int(np.nonzero(curve["contact_points"])[0].max())
    print(f"\nJKR pull-off: sphere R = {opts['radius']}, {args.n} x {args.n}, a_c/h = {args.ratio}, "
          f"{len(d) - 1} unloading steps on {args.np} ranks, {curve['seconds'].sum():.2f} s, "
          f"{int(curve['compliance_applications'].sum())} compliance applications, "
          f"{int(curve['ksp_iterations'].sum())} KSP iterations, {int(curve['outer_iterations'].sum())} set updates")
    print(criterion_line(opts))
    table([("pull-off force (the largest tension)", -F[k], F_adh),
           ("indentation at largest tension", d[k], -d_c),
           ("contact radius at largest tension", a[k], a_c),
           ("jump-off indentation (last contact)", d[last], -2.080 * d_c),
           ("contact radius at jump-off", a[last], 3 ** (-2 / 3) * a_c)])
    draw(out)


def punch(args):
    opts = dict(punch_options(args.n, args.ratio, steps=args.steps), criterion=args.criterion)
    out = os.path.join(args.results, "punch.h5")
    curve, attrs = run_adhbem(opts, out, args.np, args.extra)
    a, E, g = opts["punch_radius"], opts["E_star"], opts["gamma"]
    F_adh = math.sqrt(8 * math.pi * a**3 * E * g)
    d_crit = -math.sqrt(2 * math.pi * a * g / E)
    d, F, pts = curve["d"], curve["force"], curve["contact_points"]
    last = int(np.nonzero(pts)[0].max())
    k = int(np.argmin(F))
    pos = d > 0
    stiff = np.median(F[pos] / d[pos]) if pos.any() else float("nan")
    print(f"\nKendall punch: a = {a:.4g} ({args.ratio} h), {args.n} x {args.n}, {len(d) - 1} steps on "
          f"{args.np} ranks, {curve['seconds'].sum():.2f} s; points in contact before pull-off "
          f"{int(pts[last])}, after {int(pts[last + 1]) if last + 1 < len(pts) else 'n/a'}")
    print(criterion_line(opts))
    table([("stiffness F/d before detachment", stiff, 2 * a * E),
           ("pull-off force", -F[k], F_adh),
           ("pull-off indentation", d[last], d_crit)])
    draw(out)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("job", choices=["jkr", "punch"])
    p.add_argument("--np", type=int, default=2, help="MPI ranks")
    p.add_argument("--n", type=int, default=256, help="grid points per side")
    p.add_argument("--ratio", type=float, default=None, help="a_c/h (jkr) or a/h (punch)")
    p.add_argument("--steps", type=int, default=None, help="unloading steps")
    p.add_argument("--criterion", default=PAPER["criterion"], choices=["pohrt-popov", "crack-closure"],
                   help="detachment criterion (default: the paper's)")
    p.add_argument("--results", default=os.path.join(ROOT, "results"))
    p.add_argument("extra", nargs="*", help="further adhbem options, after --")
    args = p.parse_args()
    os.makedirs(args.results, exist_ok=True)
    if args.job == "jkr":
        args.ratio = args.ratio or 50.0
        args.steps = args.steps or 45
        jkr(args)
    else:
        args.ratio = args.ratio or 32.0
        args.steps = args.steps or 80
        punch(args)


if __name__ == "__main__":
    sys.exit(main())
