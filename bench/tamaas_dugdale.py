"""./run bench tamaas_dugdale --peer-python VENV/bin/python [--n 128] [--lambda 1] [--steps 12]
    [--config resolved] [--tolerance 1e-12] [-- ADHBEM OPTIONS]

Finite-range adhesion side by side with a peer on the same physics: adhbem's -adh_criterion
dugdale against Tamaas' Polonsky-Keer-Rey solver with its Maugis (Dugdale) adhesion functional
(tamaas.MaugisAdhesionFunctional: the traction dgamma/rho within the range rho of contact, the
same cohesive law), on one core, the same surface, range and path.

The surface is ./run bench convergence's configuration (--config, default resolved) sampled on
--n; dgamma is the configuration's and the range dgamma/s0 follows from --lambda, the Tabor-Maugis
parameter of the smallest asperities (as ./run bench tabor). The path is the indentation d from
first touch to d1 (a quarter of the gap profile below it) and back to -d1/2 in --steps steps a leg,
under displacement control: adhbem's d is Tamaas' mean gap mean(h) - d (the periodic compliance has
no mean mode), each Tamaas solve warm-started from the previous state as adhbem's steps are.
Tamaas runs with E = 1, nu = 0 (E* = 1) to --tolerance; adhbem with its defaults but the route:
the sharp law's fixed point (-adh_dugdale_route fixed-point), the law Tamaas' functional is.

The table gives per state both forces and contact and zone counts. The cohesive law has several
equilibria at one d where the path passes a jump: each solver picks one, from its previous
state, so the two may differ there while both are equilibria; where the state is unique they
agree to the solvers' tolerances. The summary counts the states that agree (forces within 1e-6
relative, the same contact count), the median and largest differences of force and contact count
over the states, the largest tension of each and their process CPU times
(getrusage of adhbem's process; time.process_time around Tamaas' solves), with adhbem's counts.

Tamaas is not a dependency: install it in a virtual environment of your own, e.g.
    python3 -m venv ~/venv-peers && ~/venv-peers/bin/pip install tamaas numpy
"""
import argparse
import importlib.util
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
spec = importlib.util.spec_from_file_location("bench_convergence", os.path.join(ROOT, "bench", "convergence.py"))
convergence = importlib.util.module_from_spec(spec)
spec.loader.exec_module(convergence)
spec = importlib.util.spec_from_file_location("bench_tabor", os.path.join(ROOT, "bench", "tabor.py"))
tabor = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tabor)

TAMAAS = r"""
import sys, time, numpy as np, tamaas as tm
z = np.load(sys.argv[1]); N = z.shape[0]; L = float(sys.argv[2]); gamma = float(sys.argv[3]); rho = float(sys.argv[4])
tol = float(sys.argv[5]); g0s = [float(v) for v in sys.argv[6].split(",")]
tm.set_log_level(tm.LogLevel.error)
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [N, N])
model.E = 1.0; model.nu = 0.0
solver = tm.PolonskyKeerRey(model, z, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
solver.max_iter = 50000
adhesion = tm.MaugisAdhesionFunctional(z)
adhesion.parameters = {"rho": rho, "surface_energy": gamma}
solver.addFunctionalTerm(adhesion)
cpu = 0.0
for g0 in g0s:
    t0 = time.process_time(); solver.solve(g0); cpu += time.process_time() - t0
    p = np.array(model.traction); g = np.array(model.displacement) - z
    print("STATE", g0, p.mean() * L * L, int((g < 1e-9 * rho).sum()), int(((g >= 1e-9 * rho) & (g <= rho)).sum()), flush=True)
print("CPU", cpu, flush=True)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peer-python", required=True, help="a Python that has tamaas")
    ap.add_argument("--n", type=int, default=128, help="grid N (N x N)")
    ap.add_argument("--lambda", dest="lam", type=float, default=1.0, help="Tabor-Maugis parameter of the smallest asperities")
    ap.add_argument("--steps", type=int, default=12, help="steps per leg")
    ap.add_argument("--config", default="resolved", choices=("resolved", "moderate", "unresolved"))
    ap.add_argument("--tolerance", type=float, default=1e-12, help="Tamaas' tolerance")
    ap.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = ap.parse_args()
    s, gamma, what = convergence.configuration(a.config, 64)  # lengths in spacings of a 64 grid: L = 64
    z = s.heights(a.n)
    h = z.max() - z
    d1 = float(np.quantile(h, 0.25))
    s0 = tabor.s0_for(a.lam, s, gamma)
    rho = gamma / s0
    path = [0.0, d1, -d1 / 2]
    ds = [path[0] + (path[1] - path[0]) * k / a.steps for k in range(a.steps + 1)]
    ds += [path[1] + (path[2] - path[1]) * k / a.steps for k in range(1, a.steps + 1)]
    meanh = float(h.mean())
    print(f"# Dugdale adhesion, adhbem against Tamaas: {a.config} surface ({what}) on {a.n}^2 (L = {s.L:g}), dgamma {gamma:.5g}, "
          f"lambda {a.lam:g}: s0 {s0:.5g}, range {rho:.5g} ({rho * a.n / s.L:.3g} spacings); path 0 -> {d1:.4g} -> {-d1 / 2:.4g}, "
          f"{a.steps} steps a leg")
    with tempfile.TemporaryDirectory() as tmp:
        zfile, hfile, out = (os.path.join(tmp, f) for f in ("z.npy", "h.npy", "a.h5"))
        np.save(zfile, np.ascontiguousarray(z))
        np.save(hfile, np.ascontiguousarray(h))
        cmd = [convergence.EXE, "-adh_n", str(a.n), "-adh_size", repr(s.L), "-adh_boundary", "periodic",
               "-adh_indenter", "file", "-adh_topography", hfile, "-adh_topography_kind", "gap", "-adh_gamma", repr(gamma),
               "-adh_criterion", "dugdale", "-adh_dugdale_stress", repr(s0), "-adh_dugdale_route", "fixed-point",  # Tamaas' law is the sharp one
               "-adh_start", "adhesive",
               "-adh_path", ",".join(repr(v) for v in path), "-adh_steps", str(a.steps), "-adh_output", out, "-adh_progress", "0"] + a.extra
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"))
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode:
            sys.exit(f"bench tamaas_dugdale: adhbem failed:\n{p.stderr[-2000:]}")
        cpu_adhbem = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        import h5py
        with h5py.File(out, "r") as f:
            c = {k: f["curve"][k][()] for k in ("d", "force", "contact_points", "cohesive_area", "ksp_iterations", "fft_pairs", "outer_iterations")}
        cell = (s.L / a.n) ** 2
        script = os.path.join(tmp, "peer.py")
        with open(script, "w") as fh:
            fh.write(TAMAAS)
        g0s = ",".join(repr(meanh - d) for d in c["d"])
        t = subprocess.run([a.peer_python, script, zfile, repr(s.L), repr(gamma), repr(rho), repr(a.tolerance), g0s],
                           capture_output=True, text=True)
        if t.returncode:
            sys.exit(f"bench tamaas_dugdale: Tamaas failed:\n{t.stderr[-2000:]}")
    peer = [line.split()[1:] for line in t.stdout.splitlines() if line.startswith("STATE")]
    cpu_peer = float([line.split()[1] for line in t.stdout.splitlines() if line.startswith("CPU")][0])
    print(f"\n{'state':>5} {'d':>9} {'F adhbem':>12} {'F Tamaas':>12} {'dF/|F|':>9} {'contact':>8} {'(Tamaas)':>8} {'zone':>6} {'(Tamaas)':>8}  agree")
    agree = 0
    dF, dn = [], []
    for k, (d, F, n, zone) in enumerate(zip(c["d"], c["force"], c["contact_points"], c["cohesive_area"])):
        _, Ft, nt, zt = peer[k]
        Ft, nt, zt = float(Ft), int(nt), int(zt)
        same = abs(F - Ft) <= 1e-6 * max(abs(F), abs(Ft), 1e-300) and n == nt
        agree += same
        rel = abs(F - Ft) / max(abs(F), abs(Ft), 1e-300)
        dF.append(rel)
        dn.append(abs(int(n) - nt) / max(int(n), nt, 1))
        print(f"{k:>5} {d:>9.4g} {F:>12.6g} {Ft:>12.6g} {rel:>9.2e} {int(n):>8} {nt:>8} {round(zone / cell):>6} {zt:>8}  {'yes' if same else 'no'}")
    Ft = np.array([float(v[1]) for v in peer])
    print(f"\n{agree} of {len(c['d'])} states agree (force within 1e-6, the same contact); largest tension adhbem "
          f"{-c['force'].min():.6g}, Tamaas {-Ft.min():.6g}")
    print(f"forces differ by {np.median(dF):.2%} in the median state, {max(dF):.2%} at most; contact counts by "
          f"{np.median(dn):.2%} in the median state, {max(dn):.2%} at most")
    print(f"CPU seconds: adhbem {cpu_adhbem:.2f} (the process: {int(c['outer_iterations'].sum())} set updates, "
          f"{int(c['ksp_iterations'].sum())} KSP iterations, {int(c['fft_pairs'].sum())} FFT pairs), Tamaas {cpu_peer:.2f} (its solves)")


if __name__ == "__main__":
    main()
