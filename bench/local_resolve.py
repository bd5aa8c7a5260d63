"""Local re-solves after a ring lets go: a NumPy prototype of a route adhbem does not have yet.

The exact cascade solves the whole contact set again after every set update, one global solve
per ring of elements a receding edge crosses, so a step's solves grow with the grid. The route
measured here: after the points of a set update let go, correct the pressures only on the set's
points within W grid spacings of them (the rest of the set frozen), let go what that correction
shows, and repeat; solve the whole set again only when this local cascade stops, and go on from
there until a global solve lets nothing go. It still takes one solve per ring, but a local one;
every recorded state ends on a global solve and its attach test, as in the exact cascade. A point
let go on a local solve's pressures does not come back, so the states themselves may differ.

What the prototype has, for both routes: a periodic cell of side 1 on N x N elements (E* = 1,
the half-space's compliance with the element's shape, a finite k = 0 mode), a self-affine
surface (Hurst 0.8, roll-off at the cell, cut-off at mode --modes, rms slope 0.1) whose Fourier
coefficients are drawn per mode, so every N carries the same continuous surface; a pointwise
criterion (p < -Sigma lets go, Sigma = sqrt(E* dgamma / h): the paper's form without its
constant factor); the attach rule of adhbem's `penetration` (a point joins where its gap is
negative); displacement control, 12 steps to the depth at which about 40% of the cell touches,
24 back to the same height above. CG preconditioned with the inverse of the whole grid's
compliance, as adhbem's solves are: an iteration is two FFT pairs.

It prints, for the exact cascade and for each W: the global solves, their CG iterations and
all FFT pairs outside the local solves; the local solves, their iterations, and their FFT pairs
masked on the whole grid or (an estimate, with SciPy) on each cluster's own zero-padded box,
which neglects the coupling between clusters that the masked solve keeps; and the states against
the exact cascade's: the largest tension, the loop energy, the force along the path, the sets.

  ./run bench local_resolve --n 128 --w 8
  ./run bench local_resolve --n 256 --w 4,8,16 --save curves.npz
"""
import argparse
import time

import numpy as np

try:  # for the box estimate only; not among adhbem's own packages
    from scipy import ndimage
except ImportError:
    ndimage = None

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--n", type=int, default=128, help="elements per side")
ap.add_argument("--w", default="8", help="window half-widths in grid spacings, comma-separated")
ap.add_argument("--dgamma", type=float, default=4e-4, help="work of adhesion (E* = 1, cell side 1)")
ap.add_argument("--modes", type=float, default=4.0, help="cut-off of the surface, in modes of the cell")
ap.add_argument("--local-rtol", type=float, default=1e-2, help="relative residual of the local solves")
ap.add_argument("--truncate", type=int, default=0,
                help="the local solves' kernel truncated to this many spacings (0: the whole kernel)")
ap.add_argument("--save", help="write the curves and counts to this .npz file")
args = ap.parse_args()
N = args.n

# the compliance of a periodic half-space in Fourier space, the element's shape through sinc^2
MX, MY = np.meshgrid(np.fft.fftfreq(N, 1.0 / N), np.fft.rfftfreq(N, 1.0 / N), indexing="ij")
k = 2 * np.pi * np.sqrt(MX**2 + MY**2)
symbol = 2.0 / np.sqrt(k**2 + (2 * np.pi)**2) * np.sinc(MX / N)**2 * np.sinc(MY / N)**2
preconditioner = 1.0 / symbol  # the whole grid's stiffness


def apply(sym, p):
    return np.fft.irfft2(np.fft.rfft2(p) * sym, s=(N, N))


symbol_local = symbol
if args.truncate:
    kernel = np.fft.irfft2(symbol, s=(N, N))
    dist = np.minimum(np.arange(N), N - np.arange(N))
    kernel[(dist[:, None] > args.truncate) | (dist[None, :] > args.truncate)] = 0.0
    symbol_local = np.fft.rfft2(kernel)

# the surface: one coefficient per mode, seeded by the mode's indices
coef = np.zeros(MX.shape, complex)
for i, j in zip(*np.nonzero((MX**2 + MY**2 <= args.modes**2) & (MX**2 + MY**2 > 0))):
    r = np.random.default_rng([int(MX[i, j]) + 1000, int(MY[i, j]) + 1000])
    coef[i, j] = (r.normal() + 1j * r.normal()) * np.hypot(MX[i, j], MY[i, j])**(-1.8)
z = np.fft.irfft2(coef * N * N, s=(N, N))
slope_x = np.fft.irfft2(2j * np.pi * MX * np.fft.rfft2(z), s=(N, N))
slope_y = np.fft.irfft2(2j * np.pi * MY * np.fft.rfft2(z), s=(N, N))
z *= 0.1 / np.sqrt((slope_x**2 + slope_y**2).mean())
h = z.max() - z  # the gap at d = 0: the highest summit touches
Sigma = np.sqrt(args.dgamma * N)


class Counts:
    """Whole-grid FFT pairs (one a compliance or preconditioner application) by where they go."""
    def __init__(self):
        self.solves = self.its = self.pairs = 0  # global solves, their CG iterations, all pairs outside local solves
        self.local_solves = self.local_its = self.local_points = 0
        self.local_pairs_box = 0.0  # the local solves' iterations, as pairs on each cluster's box


def apply_counted(sym, p, c):
    c.pairs += 1
    return apply(sym, p)


def cg(mask, p0, rhs, rtol, c, sym=symbol):
    """Solve K_mm p = rhs_m on the mask from p0 (zero off the mask) by CG preconditioned with the
    inverse of the whole grid's compliance (as adhbem's solves are); returns p and the iterations.
    Each iteration is two FFT pairs, counted in c.pairs unless c is None (a local solve)."""
    app = apply if c is None else (lambda v, q: apply_counted(v, q, c))
    p = np.where(mask, p0, 0.0)
    r = np.where(mask, rhs - app(sym, p), 0.0)
    bnorm = np.linalg.norm(np.where(mask, rhs, 0.0)) or 1.0
    zr = np.where(mask, app(preconditioner, r), 0.0)
    q, rz, its = zr.copy(), (r * zr).sum(), 0
    while np.linalg.norm(r) > rtol * bnorm and its < 10000:
        Aq = np.where(mask, app(sym, q), 0.0)
        qAq = (q * Aq).sum()
        assert qAq > 0, "the local operator is not positive definite (--truncate too small)"
        a = rz / qAq
        p += a * q
        r -= a * Aq
        zr = np.where(mask, app(preconditioner, r), 0.0)
        rzn = (r * zr).sum()
        q = zr + rzn / rz * q
        rz, its = rzn, its + 1
    return p, its


def widen(mask, w):
    """The points within w spacings of the mask (a square), on the periodic grid."""
    out = mask.copy()
    for s in range(1, w + 1):
        out |= np.roll(mask, s, 0) | np.roll(mask, -s, 0)
    wide = out.copy()
    for s in range(1, w + 1):
        wide |= np.roll(out, s, 1) | np.roll(out, -s, 1)
    return wide


def box_cost(win):
    """A local iteration's cost in whole-grid FFT pairs, were each cluster of the window solved on
    its own zero-padded box (twice its bounding box each way; an FFT costs n log n). NaN without
    SciPy (apt-get install python3-scipy)."""
    if ndimage is None:
        return float("nan")
    lab, _ = ndimage.label(win, structure=np.ones((3, 3)))
    c = 0.0
    for sl in ndimage.find_objects(lab):
        a = 4.0 * (sl[0].stop - sl[0].start) * (sl[1].stop - sl[1].start)
        c += a * np.log2(max(a, 2.0))
    return min(c / (N * N * np.log2(N * N)), 1.0)  # never more than the whole grid, masked


def step(d, C, p, w, c):
    """One displacement step from the set C and pressures p; w = 0: the exact cascade. It returns
    only after a global solve that lets nothing go and lets nothing join."""
    rhs = d - h
    while True:
        p, its = cg(C, p, rhs, 1e-8, c)
        c.solves, c.its = c.solves + 1, c.its + its
        gone = C & (p < -Sigma)
        if gone.any():
            C = C & ~gone
            p = np.where(C, p, 0.0)
            while w and gone.any():  # the local cascade
                win = C & widen(gone, w)
                if not win.any():
                    break
                r = rhs - apply_counted(symbol, p, c)  # the residual the tension let go leaves
                dp, its = cg(win, np.zeros_like(p), np.where(win, r, 0.0), args.local_rtol, None, symbol_local)
                c.local_solves, c.local_its = c.local_solves + 1, c.local_its + its
                c.local_points += win.sum()
                c.local_pairs_box += 2 * its * box_cost(win)
                p = p + dp
                gone = win & (p < -Sigma)
                C = C & ~gone
                p = np.where(C, p, 0.0)
            continue
        joins = ~C & (h - d + apply_counted(symbol, p, c) < 0)
        if not joins.any():
            return C, p
        C = C | joins


dmax = np.quantile(h, 0.5) * 1.2
path = list(np.linspace(0, dmax, 13)) + list(np.linspace(dmax, -dmax, 25)[1:])


def run(w):
    C, p, c, states = np.zeros((N, N), bool), np.zeros((N, N)), Counts(), []
    for d in path:
        C, p = step(d, C, p, w, c)
        states.append((d, -p.sum() / N**2, C.copy(), p.copy()))  # the mean tension (tensile positive)
        if d < 0 and not C.any():
            break
    d = np.array([s[0] for s in states])
    F = np.array([s[1] for s in states])
    return states, F, -np.trapz(F, d), c


def padded(states, n):
    """The states to n, past pull-off with no force and nothing in contact."""
    empty = np.zeros((N, N), bool)
    return [s[:3] for s in states] + [(None, 0.0, empty)] * (n - len(states))


t = time.process_time()
ref, F0, E0, c0 = run(0)
print(f"N = {N}, dgamma {args.dgamma}, Sigma {Sigma:.4g}")
print(f"| route | global solves | their CG its | FFT pairs outside local solves | local solves | local CG its "
      f"| local pairs, masked / on boxes | mean window | largest tension | loop energy "
      f"| force along the path, RMS / max | sets differ by, at most | CPU s |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
print(f"| exact cascade | {c0.solves} | {c0.its} | {c0.pairs} | | | | | {F0.max():.6g} | {E0:.6g} | | | "
      f"{time.process_time() - t:.0f} |")
save = {"d": np.array([s[0] for s in ref]), "F_exact": F0, "counts_exact": [c0.solves, c0.its, c0.pairs]}
for w in [int(x) for x in args.w.split(",")]:
    t = time.process_time()
    states, F, E, c = run(w)
    n = max(len(states), len(ref))
    a, b = padded(states, n), padded(ref, n)
    Fa, Fb = np.array([s[1] for s in a]), np.array([s[1] for s in b])
    scale = np.abs(F0).max()
    rms = np.sqrt(((Fa - Fb)**2).mean()) / scale
    worst = np.abs(Fa - Fb).max() / scale
    differ = max(int((a[i][2] ^ b[i][2]).sum()) for i in range(n))
    print(f"| W = {w} | {c.solves} | {c.its} | {c.pairs} | {c.local_solves} | {c.local_its} "
          f"| {2 * c.local_its} / {c.local_pairs_box:.0f} | {c.local_points / max(c.local_solves, 1) / N**2:.2%} "
          f"| {F.max():.6g} ({F.max() / F0.max() - 1:+.3%}) | {E:.6g} ({E / E0 - 1:+.3%}) | {rms:.3%} / {worst:.3%} "
          f"| {differ} points | {time.process_time() - t:.0f} |")
    save[f"F_w{w}"] = F
    save[f"counts_w{w}"] = [c.solves, c.its, c.pairs, c.local_solves, c.local_its, c.local_points, c.local_pairs_box]
    save[f"sets_w{w}"] = np.array([s[2] for s in states])
    save[f"p_w{w}"] = np.array([s[3] for s in states])
save["sets_exact"] = np.array([s[2] for s in ref])
save["h"], save["Sigma"] = h, Sigma
save["kernel"] = np.fft.irfft2(symbol, s=(N, N))  # the displacement of a unit pressure at (0, 0)
if args.save:
    np.savez(args.save, **save)
