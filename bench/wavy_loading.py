"""Loading Johnson's adhesive wavy surface under force control: the contact strip's half-width
along the loading branch and the mean pressure at which the cell jumps into full contact.

    ./run bench wavy_loading [--n 128,256,512] [--alpha 0.3,0.2] [--attach reach,griffith,penetration]
                             [--dp 0.005] [--fine 0.001] [--angle45]

Johnson (1995): a periodic wave h = D (1 - cos(2 pi x / lam)) pressed by a mean pressure p carries
a contact strip of half-width a with

    p/p* = sin^2(pi a/lam) - alpha sqrt(tan(pi a/lam)),   p* = pi E* D / lam,
    alpha = sqrt(2 lam dgamma / (pi^2 E* D^2)).

p(a) rises from its minimum (the force-controlled pull-off) to a maximum p_max at a_max < lam/2
(alpha 0.3: a_max = 0.379 lam, p_max = 0.3877 p*; alpha 0.2: 0.399 lam, 0.5537 p*) and falls
beyond it: under force control a reversible (energy-balanced) contact follows the rising part of
the branch on loading and jumps into full contact at p_max.

Each case loads from first touch with adhesion (start "adhesive" at F = 0: the jump-in to the
branch's zero, a = 0.1546 lam at alpha 0.3), then in steps of dp p* (default 0.005 p*; from
0.9 p_max on, of --fine p* if given) until the whole cell is in contact or p reaches 2.8 p_max
(beyond p*, where even the adhesion-free wave is in full contact). The table gives:

- a/a_th, worst: over the states with 0 <= p < 0.9 p_max, the mean and the worst of
  a / a_theory(p), a from the area (a = A / A_cell * lam / 2). Nearer p_max a(p) is
  ill-conditioned (da/dp grows without bound): the jump measures that part.
- a0/a_th: the first state's (the jump-in at F = 0);
- p_last, p_jump: the last partial state's and the first full-contact state's p / p_max (the
  jump lies between them);
- a_last: the last partial state's a / a_max;
- dg_eff: the median over the same states of the work of adhesion for which Johnson's curve
  passes through the state's (a, p), over dgamma (1: the attach rule acts with dgamma);
- outer, KSP, K apps: set updates, KSP iterations and compliance applications over the path.

The criterion is the default, crack-closure. Waves along a grid axis run on an N x 4 strip (the
solution does not depend on y); --angle45 adds the wave with wavevector (1, 1) on an N x N cell
(N = n sqrt 2 rounded, so lam/h = n) for the first two n.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import adhbem  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from criterion import johnson_wave  # noqa: E402  (the wave of ./run bench criterion)

E = 1.0


def johnson(t, alpha):
    """p/p* at t = pi a / lam."""
    return np.sin(t) ** 2 - alpha * np.sqrt(np.tan(t))


def branch(alpha):
    """(t_min, t_max, p_min, p_max) of Johnson's curve: the rising (stable under force control)
    part runs from its minimum at t_min to its maximum at t_max (t = pi a / lam, p in units of p*)."""
    t = np.linspace(1e-7, math.pi / 2 - 1e-7, 400001)
    p = johnson(t, alpha)
    i = int(np.argmax(p))
    j = int(np.argmin(p[:i]))
    # polish both extrema by bisection on dp/dt = sin 2t - alpha sec^2 t / (2 sqrt(tan t))
    def slope(x):
        return math.sin(2 * x) - alpha / (2 * math.cos(x) ** 2 * math.sqrt(math.tan(x)))
    ext = []
    for k in (j, i):
        lo, hi = t[max(k - 1, 0)], t[min(k + 1, len(t) - 1)]
        s_lo = slope(lo)
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            if (slope(mid) > 0) == (s_lo > 0):
                lo = mid
            else:
                hi = mid
        ext.append(0.5 * (lo + hi))
    tmin, tmax = ext
    return tmin, tmax, float(johnson(tmin, alpha)), float(johnson(tmax, alpha))


def a_theory(p, alpha, tmin, tmax):
    """Half-width / lam on the rising part of the branch at mean pressure p (units of p*)."""
    lo, hi = tmin, tmax
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if johnson(mid, alpha) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi) / math.pi


def load(N, alpha=0.3, attach="reach", dp=0.005, diagonal=False, criterion="crack-closure", top=2.8, ny=4,
         fine=None):
    """Loads the wave on an N x ny strip (diagonal: wavevector (1, 1) on an N x N cell) from first
    touch at F = 0 in steps of dp p* (from 0.9 p_max on, of fine p* if given) until full contact or
    p = top p_max (the default 2.8 is beyond Westergaard's full contact at p*). Returns a dict: the
    states' p/p* and a/lam, a/a_theory on the branch, the jump, and the counts."""
    L = 1.0
    if diagonal:
        m, n, ny = 1, 1, N
    else:
        m, n = 1, 0
    hgrid = L / N
    lam, D, dgamma, pstar, h = johnson_wave(N, ny, m, n, alpha, L)
    cell = L * ny * hgrid
    s = adhbem.Solver(n=(N, ny), size=(L, ny * hgrid), gamma=dgamma, E_star=E, boundary="periodic",
                      topography=h, topography_kind="gap", start="adhesive", criterion=criterion,
                      attach=attach, control="force", steps=1, **OPTIONS)
    tmin, tmax, pmin, pmax = branch(alpha)
    total = N * ny
    states = []
    counts = dict(outer=0, ksp=0, mults=0)

    def record(st):
        for key, col in (("outer", "outer_iterations"), ("ksp", "ksp_iterations"), ("mults", "compliance_applications")):
            counts[key] += int(st[col])
        states.append((st["force"] / cell / pstar, st["area"] / (L * ny * hgrid) * lam / 2 / lam,
                       st["contact_points"] == total))

    record(s.start(0.0))
    target = 0.0
    while not states[-1][2] and states[-1][0] < top * pmax:
        target += fine if fine and target >= 0.9 * pmax else dp
        record(s.step(target * pstar * cell))
    p = np.array([q[0] for q in states])
    a = np.array([q[1] for q in states])
    full = np.array([q[2] for q in states])
    on = (~full) & (p < 0.9 * pmax) & (p >= -1e-12)  # where a(p) is well conditioned: da/dp grows without bound at p_max
    theory = np.array([a_theory(q, alpha, tmin, tmax) for q in p[on]])
    # the work of adhesion the states act with: Johnson's curve through (a, p) solved for alpha^2
    t = math.pi * a[on]
    geff = ((np.sin(t) ** 2 - p[on]) / np.sqrt(np.tan(t)) / alpha) ** 2
    partial = np.nonzero(~full)[0]
    jumped = bool(full.any())
    return dict(N=N, ny=ny, lam_h=lam / hgrid, alpha=alpha, attach=attach, dp=dp, diagonal=diagonal,
                p=p, a=a, full=full, ratio=a[on] / theory, p_on=p[on],
                gamma_eff=float(np.median(geff)) if len(geff) else float("nan"),
                first=a[0] / a_theory(max(p[0], 0.0), alpha, tmin, tmax),
                p_jump=p[np.argmax(full)] / pmax if jumped else float("nan"),
                p_last=p[partial[-1]] / pmax, a_last=a[partial[-1]] / (tmax / math.pi),
                pmax=pmax, amax=tmax / math.pi, **counts)


def row(r):
    q = r["ratio"]
    worst = q[np.argmax(np.abs(q - 1))] if len(q) else float("nan")
    grid = f"{r['N']}x{r['ny']}"
    case = "45 deg" if r["diagonal"] else "axis"
    return (f"{case:7s} {grid:>9s} {r['lam_h']:6.0f} {r['alpha']:5.2f} {r['attach']:>11s} {len(q):5d}"
            f" {q.mean():7.4f} {worst:7.4f} {r['first']:7.4f} {r['p_last']:7.4f} {r['p_jump']:7.4f}"
            f" {r['a_last']:7.4f} {r['gamma_eff']:7.3f} {r['outer']:6d} {r['ksp']:7d} {r['mults']:7d}")


HEADER = (f"{'wave':7s} {'grid':>9s} {'lam/h':>6s} {'alpha':>5s} {'attach':>11s} {'n':>5s}"
          f" {'a/a_th':>7s} {'worst':>7s} {'a0/a_th':>7s} {'p_last':>7s} {'p_jump':>7s}"
          f" {'a_last':>7s} {'dg_eff':>7s} {'outer':>6s} {'KSP':>7s} {'K apps':>7s}")


OPTIONS = {}  # further solver options (--cascade-rtol)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", default="128,256,512", help="grid points per wavelength along the axis")
    ap.add_argument("--alpha", default="0.3,0.2")
    ap.add_argument("--attach", default="reach,griffith,penetration")
    ap.add_argument("--dp", type=float, default=0.005, help="load step in units of p*")
    ap.add_argument("--fine", type=float, help="load step from 0.9 p_max on, in units of p* (default: dp)")
    ap.add_argument("--angle45", action="store_true", help="also the wave at 45 degrees for the first two n: N x N cells, N = n sqrt 2 (lam/h = n)")
    ap.add_argument("--cascade-rtol", type=float, help="the solves between set updates to this relative residual (-adh_cascade_rtol)")
    ap.add_argument("--cascade-apart", type=int, help="joins in set updates that let points go, this many spacings from them (-adh_cascade_apart)")
    args = ap.parse_args()
    if args.cascade_rtol is not None:
        OPTIONS["cascade_rtol"] = args.cascade_rtol
    if args.cascade_apart is not None:
        OPTIONS["cascade_apart"] = args.cascade_apart
    print(HEADER)
    print("(a/a_th: mean over the states with 0 <= p < 0.9 p_max; p_last, p_jump: the last partial and the first full-contact"
          " state's p / p_max; a_last: the last partial state's a / a_max; dg_eff: the median over those states of the"
          " work of adhesion Johnson's curve through (a, p) gives, over dgamma)")
    for alpha in (float(v) for v in args.alpha.split(",")):
        for attach in args.attach.split(","):
            for N in (int(v) for v in args.n.split(",")):
                print(row(load(N, alpha, attach, args.dp, fine=args.fine)), flush=True)
            if args.angle45:
                for N in (int(round(int(v) * math.sqrt(2))) for v in args.n.split(",")[:2]):
                    print(row(load(N, alpha, attach, args.dp, diagonal=True, fine=args.fine)), flush=True)


if __name__ == "__main__":
    main()
