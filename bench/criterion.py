"""Accuracy of the detachment criterion: the effective work of adhesion against edge direction
and grid.

    ./run bench criterion [--criterion pohrt-popov,crack-closure] [--radius R] [--radius-max R] [--cascade-rtol R]
        [--cascade-apart D] [--cascade-local F]
        [--cascade-local-rtol R] [--quick] [--fine]

A contact that holds tension lets go where the criterion says so. At that state the analytic
solution of the case gives back the work of adhesion the criterion acted with: dgamma_eff. A
criterion without bias gives dgamma_eff / dgamma = 1 whatever the edge's direction on the grid.

How a state at the detachment is found. Each state of an unloading path (displacement control)
has a contact set C. For a fixed C the pressure and the gaps are affine in d, so the criterion's
load over its limit (the curve column detach_ratio, a stress ratio; its square is an energy
ratio) is, squared, a quadratic in d: three probe steps with the same C give it exactly, and its
root is the d at which C lets go. The force there, with the contact size of C, goes into the
analytic solution:

- straight edges: Johnson's (1995) adhesive wavy surface on a periodic cell, the wave along a
  grid axis, at atan(1/2) = 26.6 degrees and at 45 degrees (wavevector (1,0), (2,1), (1,1)), and
  at 14.0, 18.4 and 21.8 degrees ((4,1), (3,1), (5,2)):
  p/p* = sin^2(pi a/lam) - alpha sqrt(tan(pi a/lam)), a the half-width of the contact strip
  (from the area), alpha^2 proportional to dgamma; alpha = 0.3, D = 0.01 lam.
- the JKR sphere: F = 4 E* a^3 / (3 R) - sqrt(8 pi a^3 E* dgamma), a = sqrt(A / pi).
- the cone: F = (pi/2) E* a^2 tan(theta) - sqrt(8 pi a^3 E* dgamma).
- the flat punch (Kendall): the face lets go at once at F = -sqrt(8 pi a^3 E* dgamma).

The table gives the median and range of dgamma_eff / dgamma over the states at the detachment
(waves: contact half-widths 0.05-0.25 lam; sphere and cone: radii 0.5-1.2 a_c and 0.3-1 of the
start), the largest tension found relative to the analytic pull-off force, and the counts.
"""
import argparse
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import adhbem  # noqa: E402
from adhbem import theory  # noqa: E402

E = 1.0
# solver options every case gets (--radius): the sets only let go (a point that joins on unloading
# would change the set whose threshold is measured)
OPTIONS = {"attach": "penetration"}


def threshold(s, A, delta):
    """From state A (set C): the state at which C lets go, ((d*, F*), last state) or (None, last
    state) when a probe already changed the set. A small probe gives the slope of detach_ratio,
    probes at 50% and 90% of the way to its linear prediction make the quadratic of its square."""
    B = s.step(A["d"] - delta)
    if B["contact_points"] != A["contact_points"]:
        return None, B
    rA, rB = A["detach_ratio"], B["detach_ratio"]
    if rB <= rA:
        return None, B
    dlin = A["d"] - delta * (1 - rA) / (rB - rA)
    probes = [A]
    for f in (0.5, 0.9):
        X = s.step(A["d"] + f * (dlin - A["d"]))
        if X["contact_points"] != A["contact_points"]:
            return None, X
        probes.append(X)
    x = (np.array([q["d"] for q in probes]) - A["d"]) / (dlin - A["d"])
    c = np.polyfit(x, np.array([q["detach_ratio"] for q in probes]) ** 2 - 1, 2)
    roots = np.roots(c)
    roots = roots[np.isreal(roots)].real
    roots = roots[roots > 0.9 - 1e-9]
    if not len(roots):
        return None, probes[-1]
    dstar = A["d"] + roots.min() * (dlin - A["d"])
    last = probes[-1]
    Fstar = A["force"] + (dstar - A["d"]) * (last["force"] - A["force"]) / (last["d"] - A["d"])
    return (dstar, Fstar), last


def unload(s, d0, scale, on_threshold):
    """Unload from the start at d0 through every detachment; on_threshold(A, d*, F*) per set."""
    st = s.start(d0)
    while st["detach_ratio"] <= 0 and st["contact_points"] > 0:
        st = s.step(st["d"] - 0.01 * scale)
    counts = dict(ksp=0, mults=0)
    step = s.step

    def counted(d):
        r = step(d)
        counts["ksp"] += r["ksp_iterations"]
        counts["mults"] += r["compliance_applications"]
        return r
    s.step = counted
    while st["contact_points"] > 0:
        A = st
        res, st = threshold(s, A, 1e-6 * scale)
        if res is None:
            continue
        dstar, Fstar = res
        on_threshold(A, dstar, Fstar)
        # just past it: C lets go, and the cascade runs
        st = s.step(dstar - 1e-3 * abs(dstar - A["d"]) - 1e-12 * scale)
    return counts


def johnson_wave(N, ny, m, n, alpha, L=1.0):
    """Johnson's wavy surface with wavevector (m, n) on a periodic N x ny cell of width L, grid
    spacing L/N, amplitude D = 0.01 lam: (lam, D, dgamma for alpha, p*, the gap profile h)."""
    hgrid = L / N
    lam = L / math.hypot(m, n)
    D = 0.01 * lam
    dgamma = alpha ** 2 * math.pi ** 2 * E * D ** 2 / (2 * lam)
    pstar = math.pi * E * D / lam
    X, Y = np.meshgrid((np.arange(N) + 0.5) * hgrid, (np.arange(ny) + 0.5) * hgrid)
    return lam, D, dgamma, pstar, D * (1 - np.cos(2 * math.pi * (m * X + n * Y) / L))


def wave(N, m, n, criterion, alpha=0.3):
    """Johnson's wavy surface with wavevector (m, n) on an N x N periodic cell (N x 4 along an axis:
    the solution does not depend on y)."""
    ny = 4 if n == 0 else N
    L, hgrid = 1.0, 1.0 / N
    lam, D, dgamma, pstar, h = johnson_wave(N, ny, m, n, alpha, L)
    s = adhbem.Solver(n=(N, ny), size=(L, ny * hgrid), gamma=dgamma, E_star=E, boundary="periodic",
                      topography=h, topography_kind="gap", start="hertz", criterion=criterion, **OPTIONS)
    ratios, tension = [], [0.0]

    def record(A, dstar, Fstar):
        a = A["contact_points"] / (N * ny) * lam / 2
        pbar = Fstar / (L * ny * hgrid)
        t = math.pi * a / lam
        tension[0] = max(tension[0], -pbar)
        if 0.05 <= a / lam <= 0.25:
            ratios.append(((math.sin(t) ** 2 - pbar / pstar) / math.sqrt(math.tan(t)) / alpha) ** 2)

    counts = unload(s, 0.5 * D, D, record)
    # Johnson's largest tension (force-controlled pull-off), the minimum of his curve
    t = np.linspace(1e-5, 0.25, 200001) * math.pi
    johnson = -np.min(np.sin(t) ** 2 - alpha * np.sqrt(np.tan(t))) * pstar
    angle = math.degrees(math.atan2(n, m))
    return dict(case=f"wave {angle:4.1f} deg", grid=f"{N}x{ny}", size=f"lam/h {lam / hgrid:.0f}",
                ratios=ratios, tension=tension[0] / johnson, **counts)


def sphere(ac_over_h, criterion, R=1.0):
    ac = 0.3125
    N = int(round(160 * ac_over_h / 50))
    hgrid = 1.0 / N
    dgamma = theory.jkr_dgamma(ac, R, E)
    Fadh = 1.5 * math.pi * dgamma * R
    dc = (3 * math.pi ** 2 * dgamma ** 2 * R / (64 * E ** 2)) ** (1 / 3)
    s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=dgamma, radius=R, start="hertz", criterion=criterion,
                      **OPTIONS)
    ratios, tension = [], [0.0]

    def record(A, dstar, Fstar):
        a = math.sqrt(A["area"] / math.pi)
        tension[0] = max(tension[0], -Fstar)
        if 0.5 <= a / ac <= 1.2:
            ratios.append((4 * E * a ** 3 / (3 * R) - Fstar) ** 2 / (8 * math.pi * a ** 3 * E) / dgamma)

    counts = unload(s, (1.3 * ac) ** 2 / R, dc, record)
    return dict(case="JKR sphere", grid=f"{N}x{N}", size=f"a_c/h {ac / hgrid:.0f}", ratios=ratios,
                tension=tension[0] / Fadh, **counts)


def cone(a_over_h, criterion, slope=0.1):
    """Unload from the adhesion-free state at a0 = a_over_h h."""
    N = 4 * a_over_h
    hgrid = 1.0 / N
    a0 = a_over_h * hgrid
    dgamma = math.pi / 128 * E * slope ** 2 * a0  # the adhesive term is half the adhesion-free force at a0
    s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=dgamma, indenter="cone", cone_slope=slope,
                      start="hertz", criterion=criterion, **OPTIONS)
    ratios, tension = [], [0.0]

    def record(A, dstar, Fstar):
        a = math.sqrt(A["area"] / math.pi)
        tension[0] = max(tension[0], -Fstar)
        if 0.3 <= a / a0 <= 1.0:
            ratios.append((math.pi / 2 * E * a ** 2 * slope - Fstar) ** 2 / (8 * math.pi * a ** 3 * E) / dgamma)

    counts = unload(s, math.pi / 2 * a0 * slope, a0 * slope, record)
    # the JKR-type cone's largest tension: min over a of F(a)
    a = np.linspace(1e-3, 1.0, 100001) * a0
    F = math.pi / 2 * E * a ** 2 * slope - np.sqrt(8 * math.pi * a ** 3 * E * dgamma)
    return dict(case="cone", grid=f"{N}x{N}", size=f"a0/h {a_over_h}", ratios=ratios,
                tension=tension[0] / -F.min(), **counts)


def punch(a_over_h, criterion):
    N = int(round(4 * a_over_h))
    hgrid = 1.0 / N
    a = a_over_h * hgrid
    dgamma = 1e-3
    dk = math.sqrt(2 * math.pi * a * dgamma / E)
    s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=dgamma, indenter="punch", punch_radius=a,
                      start="hertz", criterion=criterion, **OPTIONS)
    face, tensions = [], []

    def record(A, dstar, Fstar):
        if not face:
            face.append(A["area"])
        tensions.append(-Fstar)

    counts = unload(s, 0.5 * dk, dk, record)
    # Kendall's force is the largest tension the face carries, against the face's own radius. On
    # finer grids parts of the rim let go before the rest (first the four single points at the tips
    # of the digitised circle's axes), and the largest tension may come at any of these thresholds.
    aface = math.sqrt(face[0] / math.pi) if face else float("nan")
    ratios = [max(tensions) ** 2 / (8 * math.pi * aface ** 3 * E) / dgamma] if tensions else []
    return dict(case="flat punch", grid=f"{N}x{N}", size=f"a/h {a_over_h}", ratios=ratios,
                tension=math.sqrt(ratios[0]) if ratios else float("nan"), **counts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--criterion", default="pohrt-popov,crack-closure")
    ap.add_argument("--radius", type=float, help="crack-closure's averaging radius (-adh_criterion_radius)")
    ap.add_argument("--radius-max", type=float, help="crack-closure's largest averaging radius (-adh_criterion_radius_max;"
                    " equal to the radius: a fixed window)")
    ap.add_argument("--cascade-rtol", type=float, help="the solves between set updates to this relative residual (-adh_cascade_rtol)")
    ap.add_argument("--cascade-apart", type=int, help="joins in set updates that let points go, this many spacings from them (-adh_cascade_apart)")
    ap.add_argument("--cascade-local", type=float, help="local solves within F times the estimated JKR radius a_c of the points a set update lets go (-adh_cascade_local)")
    ap.add_argument("--cascade-local-rtol", type=float, help="the relative residual of those local solves (-adh_cascade_local_rtol)")
    ap.add_argument("--quick", action="store_true", help="the coarse grids only")
    ap.add_argument("--fine", action="store_true", help="also a third, finer grid for the sphere and the punch")
    args = ap.parse_args()
    if args.radius is not None:
        OPTIONS["criterion_radius"] = args.radius
    if args.radius_max is not None:
        OPTIONS["criterion_radius_max"] = args.radius_max
    if args.cascade_rtol is not None:
        OPTIONS["cascade_rtol"] = args.cascade_rtol
    if args.cascade_apart is not None:
        OPTIONS["cascade_apart"] = args.cascade_apart
    if args.cascade_local is not None:
        OPTIONS["cascade_local"] = args.cascade_local
    if args.cascade_local_rtol is not None:
        OPTIONS["cascade_local_rtol"] = args.cascade_local_rtol
    cases = [(wave, (256, 1, 0)), (wave, (512, 1, 0)), (wave, (2048, 1, 0)), (wave, (256, 2, 1)), (wave, (256, 1, 1)),
             (wave, (512, 4, 1)), (wave, (512, 3, 1)), (wave, (512, 5, 2)),
             (sphere, (25,)), (cone, (40,)), (punch, (17.5,))]
    if not args.quick:
        cases += [(wave, (512, 2, 1)), (wave, (512, 1, 1)), (sphere, (50,)), (cone, (80,)), (punch, (35.5,))]
    if args.fine:
        cases += [(wave, (1024, 3, 1)), (sphere, (100,)), (punch, (71.0,))]
    print(f"{'case':16s} {'grid':>9s} {'resolution':>12s} {'criterion':>14s} {'states':>6s}"
          f" {'dgamma_eff/dgamma':>18s} {'range':>15s} {'tension/analytic':>16s} {'KSP':>7s} {'K apps':>7s} {'s':>6s}")
    for crit in args.criterion.split(","):
        for fn, a in cases:
            t0 = time.process_time()
            r = fn(*a, crit)
            sec = time.process_time() - t0
            q = np.array(r["ratios"]) if r["ratios"] else np.array([np.nan])
            print(f"{r['case']:16s} {r['grid']:>9s} {r['size']:>12s} {crit:>14s} {len(r['ratios']):6d}"
                  f" {np.median(q):18.4f} {q.min():7.4f}-{q.max():7.4f} {r['tension']:16.4f}"
                  f" {r['ksp']:7d} {r['mults']:7d} {sec:6.1f}", flush=True)


if __name__ == "__main__":
    main()
