"""./run bench newton_spectrum: how well preconditioners condition the minimisation's Newton
system on Maugis' sphere, measured densely on small grids.

The minimisation's cost at a fixed zone width grows with lambda because the conjugate gradient
of each Newton step needs more iterations (docs/theory/minimisation.md). This benchmark isolates
that system so that a preconditioner can be judged before it is written in C. For each lambda
of --lambdas it runs the Maugis sphere of `./run bench maugis` (smoothed Dugdale law, the grid
sized so that the zone at pull-off spans --width elements) under displacement control and keeps
the state of largest tension. There it builds, densely, the compliance K of the free boundary
(one multiply by a unit vector a column; N^2 up to 12 000 points), the stiffness S = K^-1 and
the Hessian of the energy on the free points (gap > 0), H = S_ff + phi''(g), phi'' the law's
drop. It then runs the preconditioned conjugate gradient on H x = b from two right-hand sides
(random over the free points, and H applied to a random field in the zone and its
surroundings, g < 3 ranges) and counts the iterations to each of --tols, relative in the
preconditioned norm as the solver's KSPNASH measures it.

The preconditioners (rows of the table):

- fourier: K_ff, the compliance on the free points, as adhbem applies it (one FFT pair);
- clamped: S_ff^-1, the exact inverse of the stiffness on the free points (the compliance with
  the contact held, a Schur complement: an inner solve in practice);
- fourier + zone, clamped + zone: the same with a coarse space of the zone's points (unit vectors
  at the free points with g < (1 + smoothing) range, its matrix H there exact) in the balancing
  form (Mandel; Tang et al. 2009's A-BNN), symmetric positive definite, whose apply costs two
  more multiplies by H;
- fourier + zone x2: the coarse space out to twice the zone's outer gap.

The table: lambda, N, Maugis' a/zone, free points, the preconditioner, the coarse space's size,
and for each right-hand side the iterations to each tolerance. Serial, in this process.

--modes K: also the K slowest eigenvectors of the fourier-preconditioned system (K_ff H, by a
dense symmetric eigendecomposition: minutes at 8 000 free points), each with its eigenvalue over
the largest and the share of its squared amplitude in the zone (g < (1 + smoothing) range),
within 3 ranges of gap and within 10: where the soft modes a coarse space must hold live.

    ./run bench newton_spectrum [--lambdas 1,2] [--width 3] [--steps 40] [--tols 1e-2,1e-4,1e-6] [--modes 4]
"""
import argparse
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
from maugis import GAMMA, case  # noqa: E402  (the same sphere and grids as ./run bench maugis)

LARGEST = 12000  # points of the dense compliance (12 000^2 doubles: 1.2 GB, and its inverse)


def largest_tension_state(lam, width, steps, smoothing):
    """The free boundary's gap field at the state of largest tension on Maugis' sphere, the grid
    size N, s0 and Maugis' a/zone; the compliance as a dense matrix."""
    import adhbem
    s0, N, L, F, a, zone, d_pull = case(lam, width)
    if N * N > LARGEST:
        sys.exit(f"bench newton_spectrum: lambda {lam} at --width {width} needs {N}^2 points, over the {LARGEST} a dense compliance holds here")
    d0 = 0.5 * a * a
    best = None
    with adhbem.Solver(n=N, size=L, gamma=GAMMA, criterion="dugdale", dugdale_stress=s0, dugdale_smoothing=smoothing,
                       path=[d0, 2 * d_pull - 0.2 * d0], steps=steps) as s:
        for state in s.iterate_path():
            if best is None or state["force"] < best[0]:
                best = (state["force"], s.gap_array().copy())
        K = s.compliance
        x, y = K.createVecs()
        Kd = np.empty((N * N, N * N))
        for j in range(N * N):
            x.set(0.0)
            x.setValue(j, 1.0)
            x.assemble()
            K.mult(x, y)
            Kd[:, j] = y.getArray()
    return best[1].reshape(-1), N, s0, a / zone, 0.5 * (Kd + Kd.T)


def pcg(H, prec, b, tols):
    """Iterations of the preconditioned conjugate gradient from 0 to each relative tolerance of
    the preconditioned residual norm sqrt(r.z)."""
    x, r = np.zeros_like(b), b.copy()
    z = prec(r)
    p, rz = z.copy(), r @ z
    r0, out, k = math.sqrt(rz), [], 0
    while len(out) < len(tols) and k < 5000:
        q = H @ p
        alpha = rz / (p @ q)
        x += alpha * p
        r -= alpha * q
        z = prec(r)
        rzn = r @ z
        k += 1
        while len(out) < len(tols) and math.sqrt(abs(rzn)) <= tols[len(out)] * r0:
            out.append(k)
        p = z + (rzn / rz) * p
        rz = rzn
    return out + [None] * (len(tols) - len(out))


def balancing(H, M, idx):
    """The balancing preconditioner of M with the coarse space of unit vectors at idx: with
    Q = W (W^T H W)^-1 W^T, z = (I - Q H) M (I - H Q) r + Q r."""
    E = H[np.ix_(idx, idx)]
    if np.linalg.eigvalsh(E)[0] <= 0:
        return None  # the zone's own Hessian indefinite: no coarse solve
    Ei = np.linalg.inv(E)

    def Q(r):
        out = np.zeros_like(r)
        out[idx] = Ei @ r[idx]
        return out

    def apply(r):
        c = Q(r)
        z = M(r - H @ c)
        return z - Q(H @ z) + c
    return apply


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lambdas", default="1,2")
    ap.add_argument("--width", type=float, default=3.0, help="the zone's width at pull-off in elements")
    ap.add_argument("--steps", type=int, default=40)
    ap.add_argument("--smoothing", type=float, default=0.2, help="-adh_dugdale_smoothing")
    ap.add_argument("--tols", default="1e-2,1e-4,1e-6")
    ap.add_argument("--modes", type=int, default=0, help="also the slowest eigenvectors' shares in and near the zone")
    args = ap.parse_args()
    tols = [float(t) for t in args.tols.split(",")]
    e = args.smoothing
    head = f"{'lambda':>6} {'N':>4} {'a/zone':>6} {'free':>6} {'preconditioner':>18} {'coarse':>6}  iterations to {', '.join(args.tols.split(','))}: random; zone"
    print(f"# the minimisation's Newton system at the largest tension of Maugis' sphere (zone {args.width:g} elements), dense")
    print(head, flush=True)
    for lam in (float(v) for v in args.lambdas.split(",")):
        rng_ = np.random.default_rng(0)  # each lambda's right-hand sides whatever the others run
        g, N, s0, a_zone, K = largest_tension_state(lam, args.width, args.steps, e)
        rng = GAMMA / s0
        lo, hi = rng * (1 - e), rng * (1 + e)
        f = np.flatnonzero(g > 0)
        gf = g[f]
        S = np.linalg.inv(K)
        Sff = 0.5 * (S + S.T)[np.ix_(f, f)]
        del S
        H = Sff + np.diag(np.where((gf > lo) & (gf < hi), -s0 / (hi - lo), 0.0))
        Kf = K[np.ix_(f, f)]
        Sfi = np.linalg.inv(Sff)
        del Sff
        rhs = [rng_.standard_normal(len(f)), H @ np.where(gf < 3 * rng, rng_.standard_normal(len(f)), 0.0)]
        fourier, clamped = (lambda r: Kf @ r), (lambda r: Sfi @ r)
        zone, zone2 = np.flatnonzero(gf < hi), np.flatnonzero(gf < 2 * hi)
        rows = [("fourier", fourier, 0), ("clamped", clamped, 0),
                ("fourier + zone", balancing(H, fourier, zone), len(zone)), ("clamped + zone", balancing(H, clamped, zone), len(zone)),
                ("fourier + zone x2", balancing(H, fourier, zone2), len(zone2))]
        for name, prec, k in rows:
            its = "; ".join(", ".join("-" if i is None else str(i) for i in pcg(H, prec, b, tols)) for b in rhs) if prec else "the zone's Hessian is indefinite"
            print(f"{lam:>6g} {N:>4} {a_zone:>6.2f} {len(f):>6} {name:>18} {k:>6}  {its}", flush=True)
        if args.modes > 0:  # x = L y, y the eigenvectors of L^T H L (K_ff = L L^T): those of K_ff H
            L = np.linalg.cholesky(Kf)
            w, V = np.linalg.eigh(L.T @ H @ L)
            for j in range(min(args.modes, len(w))):
                x = (L @ V[:, j]) ** 2
                x /= x.sum()
                print(f"#   lambda {lam:g}, slow mode {j}: eigenvalue {w[j] / w[-1]:.4f} of the largest; squared amplitude "
                      f"{x[gf < hi].sum():.2f} in the zone, {x[gf < 3 * rng].sum():.2f} within 3 ranges, {x[gf < 10 * rng].sum():.2f} within 10", flush=True)


if __name__ == "__main__":
    main()
