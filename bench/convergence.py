"""./run bench convergence: grid refinement of adhesive rough contact, with Richardson estimates.

One periodic, band-limited, self-affine surface is contacted on grids N, 2N, 4N of the same cell,
with both detachment criteria, and the results are compared from grid to grid. The surface is the
SAME continuous function on every grid: its Fourier coefficients are drawn once (fixed seed) for
the wavevectors of the cell, independent of N, and every grid samples that trigonometric sum at
its element centres x_i = (i - N/2) h, h = L/N (an inverse FFT with the coefficients placed into
the N x N spectrum: exact, as the spectrum is zero above the cut-off and N >= 2 L/lambda_c + 1).
The bench asserts that the samples of successive grids agree at their common points to rounding,
and checks a few points against the direct trigonometric sum.

The spectrum (isotropic; q = 2 pi k/L, k integer 2-vectors, k != 0):

    z(x) = sum_k z_k exp(i q.x),  z_-k = conj(z_k),
    z_k = c sqrt(C(|q|)) w_k,     C(q) = (max(q, q_r)/q_r)^(-2(1+H)) for |q| <= q_c, 0 above,

q_r = 2 pi/lambda_r (roll-off), q_c = 2 pi/lambda_c (cut-off), w_k = (g_k + conj(g_-k))/sqrt(2)
with g_k complex Gaussians (E|g|^2 = 1) drawn once from numpy's default_rng(seed) on the square
|kx|, |ky| <= floor(L/lambda_c); c makes the rms slope exact: m2 = sum_k |q|^2 |z_k|^2 = s^2
(Parseval: the mean of |grad z|^2 over the cell). No mode at k = 0.

Tip radius of the smallest asperities, from the same coefficients: m4 = sum_k |q|^4 |z_k|^2 is the
mean of (lap z)^2 over the cell, and the mean summit curvature of a Gaussian isotropic surface is
kappa_s = sqrt(8/(3 pi)) sqrt(m4) (Nayak 1971, wide band; a cap z = z0 - r^2/(2R) has mean
curvature 1/R), so R = 1/kappa_s, the estimate adhbem itself reports at set-up. (With H < 1, m4 is
dominated by the modes near the cut-off: q^4 C(q) q grows like q^(3-2H).) The smallest asperities'
JKR contact radius at pull-off is a_c = (9 pi dgamma R^2/(8 E*))^(1/3); a_c/h on each grid is
printed with the table (an order of magnitude, not a sharp number).

The problem: periodic cell L x L, E* = 1, -adh_start adhesive (each criterion's default attach rule: griffith with crack-closure, reach with pohrt-popov), displacement
control along 0 -> d1 -> 0 -> -d1, --steps steps a leg (the run ends at pull-off), with
-adh_criterion pohrt-popov and -adh_criterion crack-closure. The surface goes to build/adhbem as a
gap profile (-adh_indenter file -adh_topography_kind gap), h = zmax - z with zmax the largest
sample of the finest grid, the same for all grids, so that d means the same indentation on every
grid (the coarser grids' highest sample lies a little below zmax: they touch at a slightly
positive d). d1 is the indentation at which --depth (default a quarter) of the finest grid's gap
profile lies below it. The same d values are visited on every grid. The retraction returns
through the approach's d values (as ./run rough does): with --legs 2, 0 -> d1 -> -d1, its steps
are twice the approach's, and the trapezoidal loop integral then carries a bias of about
(dd_r^2 - dd_a^2)/12 F'(d1), which in the moderate configuration (--quick) was of the order of
the dissipated energy itself.

Configurations (--config, default all; lengths in units of the coarsest grid's spacing, L = N1):
- unresolved: like ./run rough used to be, cut-off at 4 spacings of the coarsest grid (8, 16 on
  the finer ones), roll-off at a quarter of the cell, dgamma = 0.004 E*. a_c is about one coarse
  spacing: the coarse grids do not resolve the smallest asperities' contacts.
- moderate: a cell of 8 cut-off wavelengths, roll-off at the cell, dgamma chosen from the
  spectrum so that a_c = 5/16 lambda_c (10 spacings of the middle grid at 128, 256, 512).
- resolved: the same surface with a_c = 5/8 lambda_c (stronger adhesion: the contact at the
  deepest state is pulled in, 75% of the cell); `--n 64,128,256` gives a_c/h 5, 10, 20, the
  resolution of ./run rough.
Every spacing halves with the grids given, --n 256,512,1024 at about eight times the cost of
128,256,512.
--quick runs them on grids 48, 96, 192 (the same physics at 3/8 of the resolution: a smoke test of
about a minute, not a convergence study).

Per (configuration, criterion, N), from the curve: the force and the contact area fraction at the
deepest state, the largest tension (-min F), the energy dissipated over the loop (the loop
integral of F dd, tools/rough.py's loop_energy) and the force on retraction at d1/2
(interpolated on the retraction leg); and the counts: KSP iterations and FFT pairs (curve sums),
the CPU seconds of mpirun and its ranks (getrusage(RUSAGE_CHILDREN) around the subprocess) and
the wall time. For each quantity the table gives the values on the grids, the relative change
between successive grids, (f_2N - f_N)/|f_2N|, the observed order p = log2(|f_N - f_N/2| /
|f_2N - f_N|) from the last three grids and the Richardson estimate f_inf = f_2N + (f_2N - f_N) /
(2^p - 1) with the error bar |f_inf - f_2N|. Where p is not defined (the two differences of
opposite sign, one of them zero, or p <= 0: no sign of convergence) the order 1 is assumed and
the table says so.

    ./run bench convergence [--config unresolved|moderate|resolved|all] [--quick] [--n N1,N2,N3] [--np P]
        [--steps K] [--legs 3|2] [--gamma G] [--criteria pohrt-popov,crack-closure] [--seed S] [--depth F]
        [--perturb K [--perturb-size EPS] [--perturb-first M]] [--json FILE] [--plot PNG] [--keep DIR] [-- OPTIONS]

--gamma overrides the configurations' dgamma (units of the coarsest spacing, E* = 1); --keep DIR
keeps each run's results file (CONFIG_CRITERION_N.h5 and .csv); further adhbem options go after --.
--perturb K runs every case K more times on heights perturbed by --perturb-size (default 1e-6) of
their rms, independent Gaussian noise per sample, and reports each quantity's mean and standard
deviation over the K + 1 runs: a cascade's avalanches can tip either way on a perturbation far
below any physical scale, and this spread is how much of the answer the data determine (the
yardstick for a faster route whose contact sets differ from the exact cascade's). --perturb-first M
numbers the perturbations from M, so a second ensemble draws other samples than the first.
"""
import argparse
import importlib.util
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from adhbem_build import EXE  # noqa: E402  (no PETSc, no MPI: this process starts mpirun)


def _tool(name):
    """A module of tools/ by its path (bench/ has modules of the same names)."""
    spec = importlib.util.spec_from_file_location(f"tools_{name}", os.path.join(ROOT, "tools", name + ".py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


loop_energy = _tool("rough").loop_energy  # tools/rough.py: numpy only at import

E_STAR = 1.0
CRITERIA = ("pohrt-popov", "crack-closure")
# a mode whose wavenumber lies on the cut-off to this relative rounding counts as inside (as src/geometry/surface.c)
EDGE_RTOL = 1e-9


class BandLimitedSurface:
    """A periodic self-affine surface on an L x L cell as one trigonometric sum, independent of
    any grid: z(x) = sum_k z_k exp(i 2 pi k.x/L) over integer k with 0 < |k| <= L/lambda_c.

    The coefficients are drawn once from numpy's default_rng(seed) on the square |kx|, |ky| <=
    floor(L/lambda_c) (so they depend on seed, L/lambda_c only), made Hermitian, shaped by the
    spectrum C(q) = (max(q, q_r)/q_r)^(-2(1+H)) (zero above q_c) and scaled to the rms slope
    sqrt(sum |q|^2 |z_k|^2) = rms_slope exactly. heights(N) samples it at the element centres of
    an N x N grid; tip_radius() and jkr_radius() estimate the smallest asperities' curvature
    radius and JKR contact radius from the same coefficients."""

    def __init__(self, L, rolloff, cutoff, hurst=0.8, rms_slope=0.1, seed=1):
        if not (0 < hurst <= 1):
            raise ValueError(f"Hurst exponent must lie in (0, 1], got {hurst}")
        if not (0 < cutoff <= rolloff <= L * (1 + 1e-12)):
            raise ValueError(f"need 0 < cut-off <= roll-off <= cell: {cutoff}, {rolloff}, {L}")
        self.L, self.rolloff, self.cutoff, self.hurst, self.rms_slope, self.seed = L, rolloff, cutoff, hurst, rms_slope, seed
        K = int(math.floor(L / cutoff * (1 + EDGE_RTOL)))
        self.K = K
        rng = np.random.default_rng(seed)
        g = rng.standard_normal((2 * K + 1, 2 * K + 1)) + 1j * rng.standard_normal((2 * K + 1, 2 * K + 1))
        g /= math.sqrt(2.0)                      # E|g|^2 = 1
        w = (g + np.conj(g[::-1, ::-1])) / math.sqrt(2.0)  # w_-k = conj(w_k) exactly; E|w|^2 = 1 off k = 0
        ky, kx = np.mgrid[-K:K + 1, -K:K + 1]
        k2 = kx * kx + ky * ky
        inside = (k2 > 0) & (k2 <= (L / cutoff) ** 2 * (1 + EDGE_RTOL))
        q = 2 * math.pi / L * np.sqrt(k2[inside].astype(float))
        qr = 2 * math.pi / rolloff
        amp = (np.maximum(q, qr) / qr) ** (-(1.0 + hurst))  # sqrt(C(q)/C(q_r))
        z = w[inside] * amp
        m2 = float(np.sum(q ** 2 * np.abs(z) ** 2))
        z *= rms_slope / math.sqrt(m2)
        self.kx, self.ky, self.q, self.z = kx[inside], ky[inside], q, z
        self.m0 = float(np.sum(np.abs(z) ** 2))          # rms height^2
        self.m2 = float(np.sum(q ** 2 * np.abs(z) ** 2))  # rms slope^2 (= rms_slope^2 to rounding)
        self.m4 = float(np.sum(q ** 4 * np.abs(z) ** 2))  # mean (lap z)^2

    @property
    def modes(self):
        return len(self.z)

    @property
    def rms_height(self):
        return math.sqrt(self.m0)

    def min_grid(self):
        """The smallest N on which the samples are the exact sum: no two modes alias."""
        return 2 * self.K + 1

    def heights(self, N):
        """z at the element centres x_i = (i - N/2) h, y_j = (j - N/2) h, h = L/N, as an (N, N)
        array [j, i]: the coefficients placed into an N x N spectrum (times exp(-i q.(N/2) h) =
        (-1)^(kx+ky), the shift to the centres) and one inverse FFT."""
        if N < self.min_grid():
            raise ValueError(f"N = {N} < 2 L/lambda_c + 1 = {self.min_grid()}: the modes would alias")
        spec = np.zeros((N, N), complex)
        sign = np.where((self.kx + self.ky) % 2, -1.0, 1.0)
        spec[self.ky % N, self.kx % N] = self.z * sign
        return np.fft.ifft2(spec).real * (N * N)

    def at(self, x, y):
        """The direct trigonometric sum at points (x, y) (for checks)."""
        x, y = np.atleast_1d(x), np.atleast_1d(y)
        ph = 2 * math.pi / self.L * (np.outer(x, self.kx) + np.outer(y, self.ky))
        return (np.exp(1j * ph) @ self.z).real

    def rounding(self):
        """A bound on the rounding of a sample: a few hundred ulps of sum |z_k|."""
        return 256 * np.finfo(float).eps * float(np.sum(np.abs(self.z)))

    def tip_radius(self):
        """R = 1/kappa_s with kappa_s = sqrt(8/(3 pi)) sqrt(m4), the mean summit curvature of a
        Gaussian isotropic surface (Nayak 1971, wide band); the estimate adhbem reports
        (asperity_contact_radius)."""
        return 1.0 / (math.sqrt(8.0 / (3.0 * math.pi)) * math.sqrt(self.m4))

    def jkr_radius(self, dgamma, E=E_STAR):
        """The JKR contact radius at (force-controlled) pull-off of a sphere of the tip radius:
        a_c = (9 pi dgamma R^2/(8 E*))^(1/3)."""
        return (9 * math.pi * dgamma * self.tip_radius() ** 2 / (8 * E)) ** (1 / 3)

    def gamma_for(self, ac, E=E_STAR):
        """The dgamma at which a_c = ac."""
        return 8 * E * ac ** 3 / (9 * math.pi * self.tip_radius() ** 2)


def configuration(name, n1, hurst=0.8, rms_slope=0.1, seed=1, gamma=None):
    """The surface and dgamma of a configuration; lengths in units of the coarsest spacing
    (L = n1). Returns (surface, dgamma, description)."""
    L = float(n1)
    if name == "unresolved":
        s = BandLimitedSurface(L, rolloff=L / 4, cutoff=4.0, hurst=hurst, rms_slope=rms_slope, seed=seed)
        g = 0.004 if gamma is None else gamma
        what = "cut-off 4 coarse spacings, roll-off L/4, dgamma 0.004 (as ./run rough)"
    elif name in ("moderate", "resolved"):
        # the same surface; the smallest asperities' JKR radius a fraction of the cut-off wavelength
        share = {"moderate": 5 / 16, "resolved": 5 / 8}[name]
        s = BandLimitedSurface(L, rolloff=L, cutoff=L / 8, hurst=hurst, rms_slope=rms_slope, seed=seed)
        g = s.gamma_for(share * s.cutoff) if gamma is None else gamma
        what = f"cell of 8 cut-off wavelengths, roll-off at the cell, dgamma from a_c = {share * 16:g}/16 lambda_c"
    else:
        raise ValueError(f"unknown configuration {name!r}")
    if gamma is not None:
        what += f"; dgamma {gamma!r} (--gamma)"
    return s, g, what


def path(d1, legs):
    """The indentations of the path: 0 -> d1 -> 0 -> -d1 (3 legs) or 0 -> d1 -> -d1 (2 legs)."""
    return [0.0, d1, 0.0, -d1] if legs == 3 else [0.0, d1, -d1]


def run(surface, N, h, d1, gamma, criterion, steps, np_, legs=3, extra=(), keep=None, tag=""):
    """build/adhbem under mpirun on the gap profile h (N x N): the curve, the counts, CPU and wall."""
    with tempfile.TemporaryDirectory() as tmp:
        topo = os.path.join(tmp, "gap.npy")
        np.save(topo, np.ascontiguousarray(h, dtype=np.float64))
        out = os.path.join(keep or tmp, f"{tag}_{criterion.replace('/', '+')}_{N}.h5")
        rule, _, attach = criterion.partition("/")  # criterion[/attach rule], the criterion's default attach rule without
        cmd = ["mpirun", "--oversubscribe", "-n", str(np_), EXE,
               "-adh_n", str(N), "-adh_size", repr(surface.L), "-adh_E_star", repr(E_STAR),
               "-adh_boundary", "periodic", "-adh_indenter", "file", "-adh_topography", topo,
               "-adh_topography_kind", "gap", "-adh_gamma", repr(gamma), "-adh_criterion", rule,
               "-adh_start", "adhesive"] + (["-adh_attach", attach] if attach else []) + ["-adh_control", "displacement",
               "-adh_path", ",".join(repr(v) for v in path(d1, legs)), "-adh_steps", str(steps),
               "-adh_output", out] + list(extra)
        env = dict(os.environ)
        env.setdefault("OMP_NUM_THREADS", "1")
        env.setdefault("OPENBLAS_NUM_THREADS", "1")
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True, env=env)
        wall = time.time() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode:
            sys.exit(f"bench convergence: {tag} {criterion} N = {N} failed:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
        import h5py
        with h5py.File(out, "r") as f:
            c = {k: f["curve"][k][()] for k in f["curve"] if k != "path"}
            attrs = {k: f.attrs[k] for k in ("pull_off_force", "complete", "Sigma") if k in f.attrs}
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return c, attrs, cpu, wall


QUANTITIES = (("force_deepest", "force at the deepest state"),
              ("area_deepest", "contact area fraction at the deepest state"),
              ("largest_tension", "largest tension (-min F)"),
              ("loop_energy", "energy dissipated over the loop"),
              ("force_half_retraction", "force on retraction at d1/2"))


def quantities(c, d1, L):
    """The convergence quantities of one curve."""
    d, F = c["d"], c["force"]
    k = int(np.argmax(d))
    ret_d, ret_F = d[k:], F[k:]
    # on the retraction leg d falls: interpolate in reversed order; NaN if it came off before d1/2
    half = float(np.interp(d1 / 2, ret_d[::-1], ret_F[::-1])) if ret_d.min() <= d1 / 2 else float("nan")
    pulled = bool(np.any(c["pulled_off"] > 0))
    return dict(force_deepest=float(F[k]), area_deepest=float(c["area"][k] / (L * L)),
                largest_tension=float(max(0.0, -F.min())), loop_energy=float(loop_energy(d, F)),
                force_half_retraction=half), dict(
        states=len(d), deepest_d=float(d[k]), pulled_off=pulled,
        pull_off_d=float(d[np.argmax(c["pulled_off"] > 0)]) if pulled else None,
        ksp=int(c["ksp_iterations"].sum()), fft_pairs=int(c["fft_pairs"].sum()),
        set_updates=int(c["outer_iterations"].sum()), solve_seconds=float(c["seconds"].sum()))


def richardson(values):
    """From the last three values (grids N/2, N, 2N): observed order p, f_inf, error, note."""
    if len(values) < 3 or any(not math.isfinite(v) for v in values[-3:]):
        return dict(p=None, f_inf=None, error=None, note="needs three finite values")
    f1, f2, f3 = values[-3:]
    e1, e2 = f2 - f1, f3 - f2
    note = ""
    p = None
    if e1 == 0 or e2 == 0:
        note = "a difference is zero"
    elif (e1 > 0) != (e2 > 0):
        note = "oscillates"
    else:
        p = math.log2(abs(e1) / abs(e2))
        if p <= 0:
            note = f"diverges (p = {p:.2f})"
            p = None
    if p is None:
        f_inf = f3 + e2  # order 1 assumed: 2^1 - 1 = 1
        return dict(p=None, p_used=1.0, f_inf=f_inf, error=abs(f_inf - f3), note=f"p assumed 1: {note}")
    f_inf = f3 + e2 / (2 ** p - 1)
    return dict(p=p, p_used=p, f_inf=f_inf, error=abs(f_inf - f3),
                note="slow (p < 0.5): far extrapolation" if p < 0.5 else "")


def finite(x):
    """x with the non-finite floats replaced by None (strict JSON)."""
    if isinstance(x, dict):
        return {k: finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def fmt(v, spec=".5g"):
    return "n/a" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, spec)


def report_config(name, info, results, sizes, criteria):
    """Markdown tables of one configuration."""
    s = info["surface"]
    print(f"\n## {name}: {info['what']}\n")
    print(f"cell L = {s.L:g} (units of the coarsest spacing), roll-off {s.rolloff:g}, cut-off {s.cutoff:g},"
          f" H = {s.hurst:g}, rms slope {math.sqrt(s.m2):.6g}, rms height {s.rms_height:.5g}, {s.modes} modes,"
          f" seed {s.seed}; dgamma = {info['gamma']:.5g} E*; tip radius R = 1/(sqrt(8/(3 pi)) sqrt(m4)) = {s.tip_radius():.4g},"
          f" a_c = {info['ac']:.4g} = {info['ac'] / s.cutoff:.3g} lambda_c")
    print("a_c/h: " + ", ".join(f"N = {n}: {info['ac'] / (s.L / n):.3g}" for n in sizes)
          + "; cut-off over h: " + ", ".join(f"{s.cutoff / (s.L / n):.3g}" for n in sizes))
    print("path " + " -> ".join(f"{v:.6g}" for v in path(info["d1"], info["legs"]))
          + f" (d1: {info['depth']:g} of the finest gap profile below it),"
          f" {info['steps']} steps a leg; zmax = {info['zmax']:.6g} (finest grid), the grids' own max z below it by "
          + ", ".join(f"{v:.2e}" for v in info["zmax_gap"])
          + f"; samples of successive grids agree to {info['agreement']:.1e} at common points")
    for crit in criteria:
        print(f"\n### {name}, {crit}\n")
        head = "| quantity | " + " | ".join(f"N = {n}" for n in sizes) + " | " + \
            " | ".join(f"change {a}->{b}" for a, b in zip(sizes, sizes[1:])) + " | p | Richardson f_inf | note |"
        print(head)
        print("|" + " --- |" * (head.count("|") - 1))
        for key, label in QUANTITIES:
            vals = [results[crit][n]["quantities"][key] for n in sizes]
            changes = [(b - a) / abs(b) if b else float("nan") for a, b in zip(vals, vals[1:])]
            r = info["richardson"][crit][key]
            rich = "n/a" if r["f_inf"] is None else f"{r['f_inf']:.5g} +- {r['error']:.2g}"
            print(f"| {label} | " + " | ".join(fmt(v) for v in vals) + " | "
                  + " | ".join(fmt(100 * c, "+.2f") + "%" if math.isfinite(c) else "n/a" for c in changes)
                  + f" | {fmt(r['p'], '.2f')} | {rich} | {r['note']} |")
    print(f"\n### {name}, counts\n")
    print("| criterion | N | states | pulled off at d | set updates | KSP iterations | FFT pairs | CPU s | wall s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for crit in criteria:
        for n in sizes:
            r = results[crit][n]
            k = r["run"]
            print(f"| {crit} | {n} | {k['states']} | {fmt(k['pull_off_d'], '.4g') if k['pulled_off'] else 'no pull-off'}"
                  f" | {k['set_updates']} | {k['ksp']} | {k['fft_pairs']} | {r['cpu']:.1f} | {r['wall']:.1f} |")


def report_spread(name, results, sizes, criteria, k, eps):
    """How far the answer moves when the heights move by eps of their rms (--perturb)."""
    print(f"\n### {name}, sensitivity: the run and {k} more on heights perturbed by {eps:g} of their rms"
          " (independent Gaussian noise per sample): mean and standard deviation\n")
    head = "| criterion | quantity | " + " | ".join(f"N = {n}" for n in sizes) + " |"
    print(head)
    print("|" + " --- |" * (head.count("|") - 1))
    for crit in criteria:
        for key, label in QUANTITIES:
            cells = []
            for n in sizes:
                r = results[crit][n]
                m, sd = r["mean"][key], r["spread"][key]
                cells.append(f"{fmt(m)} +- {sd:.2g} ({100 * sd / abs(m):.2g}%)" if m and math.isfinite(m) else "n/a")
            print(f"| {crit} | {label} | " + " | ".join(cells) + " |")


def study(name, a, sizes, criteria):
    s, gamma, what = configuration(name, sizes[0], hurst=a.hurst, rms_slope=a.slope, seed=a.seed, gamma=a.gamma)
    if sizes[0] < s.min_grid():
        sys.exit(f"bench convergence: N = {sizes[0]} < 2 L/lambda_c + 1 = {s.min_grid()}")
    Z = {n: s.heights(n) for n in sizes}
    # the same continuous function: common points agree to rounding, and match the direct sum
    agreement = 0.0
    for n, m in zip(sizes, sizes[1:]):
        if m % n:
            sys.exit(f"bench convergence: the grids must double ({n}, {m})")
        agreement = max(agreement, float(np.abs(Z[m][::m // n, ::m // n] - Z[n]).max()))
    assert agreement <= s.rounding(), f"samples of different grids differ by {agreement:.3g} > {s.rounding():.3g}"
    n = sizes[0]
    rng = np.random.default_rng(12345)
    i, j = rng.integers(0, n, 8), rng.integers(0, n, 8)
    direct = s.at((i - n / 2) * s.L / n, (j - n / 2) * s.L / n)
    assert np.abs(direct - Z[n][j, i]).max() <= s.rounding(), "FFT samples differ from the direct sum"
    finest = Z[sizes[-1]]
    zmax = float(finest.max())
    d1 = float(np.quantile(zmax - finest, a.depth))
    info = dict(surface=s, gamma=gamma, what=what, ac=s.jkr_radius(gamma), d1=d1, zmax=zmax, depth=a.depth,
                steps=a.steps, legs=a.legs, zmax_gap=[zmax - float(Z[n].max()) for n in sizes], agreement=agreement,
                richardson={})
    results = {}
    for crit in criteria:
        results[crit] = {}
        for n in sizes:
            c, attrs, cpu, wall = run(s, n, zmax - Z[n], d1, gamma, crit, a.steps, a.np, a.legs, a.extra, a.keep, name)
            q, k = quantities(c, d1, s.L)
            results[crit][n] = dict(quantities=q, run=k, cpu=cpu, wall=wall,
                                    curve={key: c[key].tolist() for key in ("d", "force", "area")},
                                    pull_off_force_attr=float(attrs.get("pull_off_force", float("nan"))))
            print(f"[{name} {crit} N = {n}: {k['states']} states, {k['ksp']} KSP iterations, CPU {cpu:.1f} s,"
                  f" wall {wall:.1f} s]", file=sys.stderr, flush=True)
            # the same run on heights perturbed by a relative amount far below any physical scale:
            # how much of the answer the data determine (a cascade's avalanches can tip either way)
            samples = [q]
            for m in range(a.perturb_first, a.perturb_first + a.perturb):
                noise = np.random.default_rng([a.seed, n, m]).standard_normal(Z[n].shape)
                hm = zmax - Z[n] + a.perturb_size * float(Z[n].std()) * noise
                cm, _, cpum, wallm = run(s, n, hm, d1, gamma, crit, a.steps, a.np, a.legs, a.extra, None, name)
                samples.append(quantities(cm, d1, s.L)[0])
                print(f"[{name} {crit} N = {n}, perturbed {m + 1 - a.perturb_first}/{a.perturb}: CPU {cpum:.1f} s]", file=sys.stderr, flush=True)
            if a.perturb:
                results[crit][n]["perturbed"] = samples[1:]
                # a sample that pulled off before d1/2 has no force there: the others still count
                results[crit][n]["spread"] = {key: float(np.nanstd([v[key] for v in samples], ddof=1)) for key, _ in QUANTITIES}
                results[crit][n]["mean"] = {key: float(np.nanmean([v[key] for v in samples])) for key, _ in QUANTITIES}
        info["richardson"][crit] = {key: richardson([results[crit][n]["quantities"][key] for n in sizes])
                                    for key, _ in QUANTITIES}
    report_config(name, info, results, sizes, criteria)
    if a.perturb:
        report_spread(name, results, sizes, criteria, a.perturb, a.perturb_size)
    sys.stdout.flush()
    return dict(configuration=name, description=what, L=s.L, rolloff=s.rolloff, cutoff=s.cutoff, hurst=s.hurst,
                rms_slope=math.sqrt(s.m2), rms_height=s.rms_height, modes=s.modes, seed=s.seed, gamma=gamma,
                tip_radius=s.tip_radius(), a_c=info["ac"], a_c_over_h={str(n): info["ac"] * n / s.L for n in sizes},
                d1=d1, path=path(d1, a.legs), zmax=zmax, depth=a.depth, steps=a.steps, legs=a.legs, grids=sizes, agreement=agreement,
                zmax_below={str(n): v for n, v in zip(sizes, info["zmax_gap"])},
                richardson=info["richardson"],
                results={crit: {str(n): v for n, v in results[crit].items()} for crit in criteria})


def plot(out, file):
    """The largest tension and the loop's energy against the asperities' a_c/h, a line a criterion,
    with each criterion's Richardson limit (dashed; dotted where the order is assumed; its error
    bar shaded): one row a configuration."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    shown = (("largest_tension", "largest tension"), ("loop_energy", "energy dissipated over the loop"))
    configs = out["configurations"]
    fig, axes = plt.subplots(len(configs), 2, figsize=(8, 3.2 * len(configs)), layout="constrained", squeeze=False)
    for row, c in zip(axes, configs):
        x = [c["a_c_over_h"][str(n)] for n in c["grids"]]
        for ax, (key, label) in zip(row, shown):
            for m, crit in zip("os^v", c["results"]):
                y = [c["results"][crit][str(n)]["quantities"][key] for n in c["grids"]]
                line, = ax.plot(x, y, m + "-", ms=6, lw=1, label=crit + (" (default)" if crit == "crack-closure" else ""))
                r = c["richardson"][crit][key]
                if r["f_inf"] is not None:  # dotted where the order is assumed (1), not observed
                    ax.axhline(r["f_inf"], color=line.get_color(), lw=0.8, ls="--" if r["p"] is not None else ":")
                    ax.axhspan(r["f_inf"] - r["error"], r["f_inf"] + r["error"], color=line.get_color(), alpha=0.12, lw=0)
            ax.set_xscale("log", base=2)
            ax.set_xticks(x, [f"{v:.3g}" for v in x])
            ax.minorticks_off()
            ax.set_xlabel("$a_c/h$ of the smallest asperities")
            ax.set_ylabel(label)
            ax.set_title(f"{c['configuration']}: {label}", fontsize=9)
        row[0].legend(fontsize=8)
    fig.savefig(file, dpi=110)
    print(f"figure: {file}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog="See the module docstring (bench/convergence.py) for the method.")
    ap.add_argument("--config", default="all", choices=("unresolved", "moderate", "resolved", "all"))
    ap.add_argument("--quick", action="store_true", help="grids 48,96,192: a smoke test")
    ap.add_argument("--n", help="grid sizes N1,N2,N3 (each twice the last; default 128,256,512)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--steps", type=int, default=25, help="steps per leg")
    ap.add_argument("--legs", type=int, default=3, choices=(2, 3),
                    help="3: 0 -> d1 -> 0 -> -d1 (default), 2: 0 -> d1 -> -d1 (coarser retraction steps)")
    ap.add_argument("--gamma", type=float, help="dgamma for the chosen configurations (units of the coarsest spacing, E* = 1)")
    ap.add_argument("--criteria", default=",".join(CRITERIA), help="detachment criteria, comma-separated, each with /ATTACH for another attach rule than its "
                         "default (griffith with crack-closure, reach with pohrt-popov): crack-closure/reach")
    ap.add_argument("--seed", type=int, default=1, help="seed of the surface's Fourier coefficients")
    ap.add_argument("--depth", type=float, default=0.25,
                    help="the deepest indentation: the fraction of the (finest) gap profile below it")
    ap.add_argument("--hurst", type=float, default=0.8, help="Hurst exponent")
    ap.add_argument("--slope", type=float, default=0.1, help="rms slope")
    ap.add_argument("--perturb", type=int, default=0, metavar="K",
                    help="also run each case K more times on heights perturbed by --perturb-size of their rms, and report the spread")
    ap.add_argument("--perturb-size", type=float, default=1e-6, help="relative size of --perturb's perturbation (default 1e-6)")
    ap.add_argument("--perturb-first", type=int, default=0, metavar="M",
                    help="number the perturbations from M (default 0): a second ensemble of other samples, for bench work_precision's A.json+B.json")
    ap.add_argument("--json", help="write all numbers to this JSON file")
    ap.add_argument("--plot", help="draw the largest tension and the loop's energy against a_c/h into this PNG "
                                   "(with each criterion's Richardson limit and its error bar)")
    ap.add_argument("--keep", help="keep the results files in this directory")
    ap.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = ap.parse_args()
    sizes = [int(v) for v in a.n.split(",")] if a.n else [48, 96, 192] if a.quick else [128, 256, 512]
    if len(sizes) < 3:
        ap.error("--n: three grids (or more) are needed for the observed order")
    if a.perturb < 0 or not a.perturb_size > 0 or a.perturb_first < 0:
        ap.error("--perturb and --perturb-first must be >= 0 and --perturb-size > 0")
    criteria = [c for c in a.criteria.split(",") if c]
    if a.keep:
        os.makedirs(a.keep, exist_ok=True)
        a.keep = os.path.abspath(a.keep)
    configs = ("unresolved", "moderate", "resolved") if a.config == "all" else (a.config,)
    print(f"# Grid convergence of adhesive rough contact: grids {', '.join(map(str, sizes))},"
          f" criteria {', '.join(criteria)}, {a.np} rank(s) a run")
    out = dict(grids=sizes, criteria=criteria, np=a.np, steps=a.steps, legs=a.legs, depth=a.depth, seed=a.seed,
               perturb_first=a.perturb_first, perturb_size=a.perturb_size, configurations=[study(name, a, sizes, criteria) for name in configs])
    if a.json:
        with open(a.json, "w") as f:
            json.dump(finite(out), f, indent=1)
        print(f"\nwrote {a.json}")
    if a.plot:
        plot(out, a.plot)


if __name__ == "__main__":
    main()
