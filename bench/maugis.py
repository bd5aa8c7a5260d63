"""./run bench maugis: -adh_criterion dugdale on the sphere against Maugis' closed form, from near
DMT to near JKR.

For each Tabor-Maugis parameter of --lambdas, a sphere (E* = R = 1) is pressed and pulled under
displacement control on grids sized so that the cohesive zone at pull-off spans --widths elements
(Maugis' (c - a) at the pull-off: the grid follows from it, the free-boundary domain holds the
contact with its zone twice over). The largest tension is compared with Maugis' pull-off force
(adhbem.theory), and the grids' values are extrapolated at first order (the order the sphere
shows: the zone's edge is where an element's centre lies within the range). Pull-off runs from
2 pi dgamma R (DMT, lambda -> 0) to 1.5 pi dgamma R (JKR, large lambda); a zone narrower than the
contact needs a finer grid: at lambda 3 the zone is about a tenth of the contact radius, at 10
about 0.7%, which no grid of this machine resolves (--lambdas 10 with --widths 2,4 tries).

    ./run bench maugis [--lambdas 0.3,1,3] [--widths 5,10] [--steps 80] [--steps-with-grid] [--np P]
        [--route fixed-point,minimize] [--direction newton,polak-ribiere] [--smoothing 0.2] [--n N]
        [--force-control]

--n N: every lambda on one N^2 grid (the domain the largest one a lambda needs), the zone's width
then falling as lambda grows: the cost on the same sphere and grid.

--route: how the steps find the zone, each route on every case: the fixed point of set updates
(Maugis' sharp law) and the energy minimisation of the law smoothed over --smoothing of its range
(-adh_dugdale_route minimize -adh_dugdale_smoothing). --direction: the minimisation's directions
to run it with (-adh_minimize_direction: newton, the default, or polak-ribiere), each a row
(minimize/newton, minimize/polak-ribiere).

The table: lambda, the route, the grid, the zone's width in elements (from the run's resolution
report), the largest tension over Maugis', the first-order extrapolation over Maugis' (the fixed
point's order), the largest distance of the contact radius (from its area) from Maugis' a(d) along
the path in grid spacings (the states in contact on Maugis' branch), the Krylov iterations (the
fixed point's KSP, the Newton steps' conjugate gradients or Polak-Ribiere's; in all, and a state's
median/largest), the outer iterations a state's median (set updates or Newton steps), Maugis' contact radius at pull-off over his
zone's width (a/zone, the scale the minimisation's iterations follow), FFT pairs (in all and a
state) and CPU time; with --force-control, the pull-off of
the same case under force control (a Hertz start at 0.5 F_Maugis to -1.5 F_Maugis) over Maugis',
with its FFT pairs and CPU time.
"""
import argparse
import math
import os
import resource
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from adhbem_build import EXE  # noqa: E402  (no PETSc, no MPI: this process starts mpirun)
import numpy as np  # noqa: E402
from adhbem.theory import maugis_pulloff, maugis_scales, maugis_sphere, tabor_lambda  # noqa: E402  (numpy only)

GAMMA = 0.004655


def case(lam, width):
    """s0, the grid N and the domain size L at which the zone at pull-off spans `width` elements,
    and Maugis' pull-off force, its contact radius and zone width."""
    P, A, D = maugis_pulloff(lam)
    m = float(maugis_sphere(lam, [A])[2][0])
    force, ascale, dscale = maugis_scales(GAMMA)
    a, zone = A * ascale, (m - 1) * A * ascale
    h = zone / width
    L = 4.0 * m * a  # the contact with its zone, twice over
    N = 2 * math.ceil(L / h / 2)
    s0 = lam / tabor_lambda(1.0, GAMMA)
    return s0, N, N * h, -P * force, a, zone, D * dscale


def maugis_branch(lam):
    """Maugis' contact radius against the indentation on the branch displacement control follows
    (the radii beyond the turn of d(a)), in physical units: the arrays d, a increasing."""
    _, ascale, dscale = maugis_scales(GAMMA)
    A = np.geomspace(1e-3, 6.0, 600)
    _, D, _ = maugis_sphere(lam, A)
    k = int(np.argmin(D))
    return D[k:] * dscale, A[k:] * ascale


def radius_error(lam, d, area, h):
    """The largest distance of the run's contact radius (from its area) from Maugis' at the same d,
    in grid spacings, over the states in contact on Maugis' branch after the start."""
    db, ab = maugis_branch(lam)
    a_run = np.sqrt(np.asarray(area) / math.pi)
    on = (a_run > 0) & (np.asarray(d) >= db[0])
    on[0] = False                             # the start, Hertz's contact without adhesion
    if not on.any():
        return float("nan")
    return float(np.max(np.abs(a_run[on] - np.interp(np.asarray(d)[on], db, ab))) / h)


def run(lam, width, steps, np_, route="fixed-point", smoothing=0.2, grid=None, force=False):
    """One run; route fixed-point or minimize/<direction>; grid = (N, L) puts it on that grid
    instead of the one its zone's width sizes; force: under force control from a compression of
    half the pull-off force to 1.5 times the pull-off in tension (the leg ends at the pull-off,
    bisected to 1e-4)."""
    route, _, direction = route.partition("/")
    s0, N, L, F, a, zone, d_pull = case(lam, width)
    if grid:
        N, L = grid
    d0 = 0.5 * a * a  # a preload of about the pull-off contact's Hertz indentation
    if force:  # from a Hertz start in compression, as the JKR sphere's verification
        path = f"{0.5 * F!r},{-1.5 * F!r}"
    else:
        path = f"{d0!r},{2 * d_pull - 0.2 * d0!r}"
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "m.h5")
        cmd = ["mpirun", "--oversubscribe", "-n", str(np_), EXE, "-adh_n", str(N), "-adh_size", repr(L), "-adh_gamma", repr(GAMMA),
               "-adh_criterion", "dugdale", "-adh_dugdale_stress", repr(s0), "-adh_path", path,
               "-adh_steps", str(steps), "-adh_output", out, "-adh_progress", "0", "-adh_dugdale_route", route]
        if force:
            cmd += ["-adh_control", "force", "-adh_pulloff_rtol", "1e-4"]
        if route == "minimize":
            cmd += ["-adh_dugdale_smoothing", repr(smoothing), "-adh_minimize_direction", direction or "newton"]
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"))
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode:
            sys.exit(f"bench maugis: lambda {lam} N {N} failed:\n{p.stderr[-2000:]}")
        import h5py
        with h5py.File(out, "r") as f:
            # under force control the pull-off the run reports (NaN: it never came apart), else the largest tension
            tension = float(f.attrs["pull_off_force"]) if force else -float(f["curve/force"][()].min())
            a_err = float("nan") if force else radius_error(lam, f["curve/d"][()], f["curve/area"][()], L / N)
            width_run = float(f.attrs.get("pull_off_cohesive_width", float("nan")))
            its = f["curve/ksp_iterations"][()]
            outer = f["curve/outer_iterations"][()]
            ksp, ffts = int(its.sum()), int(f["curve/fft_pairs"][()].sum())
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return dict(N=N, L=L, tension=tension, exact=F, width=width_run, ksp=ksp, ffts=ffts, cpu=cpu, steps=steps, a_err=a_err,
                its_median=float(np.median(its)), its_max=int(its.max()), outer_median=float(np.median(outer)), a_over_zone=a / zone)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lambdas", default="0.3,1,3")
    ap.add_argument("--widths", default="5,10", help="the zone's width at pull-off in elements, one grid each (each twice the last)")
    ap.add_argument("--steps", type=int, default=80, help="steps of the path (preload to beyond the pull-off)")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--route", default="fixed-point,minimize", help="the routes to run: fixed-point, minimize or both")
    ap.add_argument("--direction", default="newton", help="the minimize route's directions (-adh_minimize_direction): newton, polak-ribiere or both")
    ap.add_argument("--smoothing", type=float, default=0.2, help="the minimize route's -adh_dugdale_smoothing")
    ap.add_argument("--n", type=int, default=0, help="every lambda on this one grid (its domain the largest the lambdas need), "
                    "instead of grids sized to --widths: the cost of the same sphere and grid as lambda grows")
    ap.add_argument("--force-control", action="store_true",
                    help="also each case under force control (from a compression of half the pull-off force to 1.5 times "
                    "the pull-off in tension, bisected to 1e-4): its pull-off over Maugis'")
    ap.add_argument("--steps-with-grid", action="store_true",
                    help="steps in proportion to the grid's N, --steps on the first case's grid: a step then moves the "
                    "contact's edge across about as many elements at every lambda and width")
    a = ap.parse_args()
    routes = []
    for route in a.route.split(","):
        if route not in ("fixed-point", "minimize"):
            sys.exit(f"bench maugis: --route: unknown route '{route}' (fixed-point, minimize)")
        if route == "fixed-point":
            routes.append(route)
            continue
        for direction in a.direction.split(","):
            if direction not in ("newton", "polak-ribiere"):
                sys.exit(f"bench maugis: --direction: unknown direction '{direction}' (newton, polak-ribiere)")
            routes.append(f"minimize/{direction}")
    lambdas = [float(v) for v in a.lambdas.split(",")]
    widths = [float(v) for v in a.widths.split(",")]
    grid = None
    if a.n:
        if a.n < 8:
            sys.exit(f"bench maugis: --n {a.n}: give a grid of 8 elements or more")
        widths = widths[:1]
        grid = (a.n, max(case(lam, widths[0])[2] for lam in lambdas))
    print(f"# dugdale on the sphere (E* = R = 1, dgamma {GAMMA}) against Maugis: the largest tension under displacement control")
    print(f"{'lambda':>7} {'route':>22} {'Maugis P':>9} {'N':>6} {'steps':>6} {'zone':>6} {'tension/Maugis':>15} {'extrapolated':>13} {'a err/h':>8} {'iterations':>10} {'a state':>9} {'outer':>6} {'a/zone':>7} {'FFT pairs':>10} {'a step':>7} {'CPU s':>7}"
          + (f" {'force control':>14} {'FFT pairs':>10} {'CPU s':>7}" if a.force_control else ""))
    N_ref = grid[0] if grid else case(lambdas[0], widths[0])[1]

    def steps(lam, w):
        if not a.steps_with_grid:
            return a.steps
        return max(1, round(a.steps * (grid[0] if grid else case(lam, w)[1]) / N_ref))
    for lam in lambdas:
        for route in routes:
            rows = [run(lam, w, steps(lam, w), a.np, route, a.smoothing, grid) for w in widths]
            P = rows[0]["exact"] / (math.pi * GAMMA)
            for k, r in enumerate(rows):
                extra = ""
                if k > 0 and route == "fixed-point":  # first order in the spacing, whose ratio is the widths' (the domain is the same)
                    q = widths[k] / widths[k - 1]
                    f_inf = (q * r["tension"] - rows[k - 1]["tension"]) / (q - 1)
                    extra = f"{f_inf / r['exact']:.4f}"
                line = (f"{lam:>7g} {route:>22} {P:>9.4f} {r['N']:>6} {r['steps']:>6} {r['width']:>6.3g} {r['tension'] / r['exact']:>15.4f} {extra:>13} "
                        f"{r['a_err']:>8.2f} {r['ksp']:>10} {r['its_median']:>4.0f}/{r['its_max']:<4d} {r['outer_median']:>6.0f} {r['a_over_zone']:>7.3g} {r['ffts']:>10} {r['ffts'] / (r['steps'] + 1):>7.0f} {r['cpu']:>7.1f}")
                if a.force_control:
                    fc = run(lam, widths[k], steps(lam, widths[k]), a.np, route, a.smoothing, grid, force=True)
                    pulled = f"{fc['tension'] / fc['exact']:.4f}" if math.isfinite(fc["tension"]) else "not apart"
                    line += f" {pulled:>14} {fc['ffts']:>10} {fc['cpu']:>7.1f}"
                print(line, flush=True)


if __name__ == "__main__":
    main()
