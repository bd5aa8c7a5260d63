"""./run bench tamaas --peer-python VENV/bin/python [--n 512,1024,2048] [--pressure 0.005] [--repeat 3]
    [--tolerance 1e-10] [--predictor polonsky-keer|none]

Non-adhesive rough contact against Tamaas' PolonskyKeerRey solver, on one core: the same
periodic self-affine surface (adhbem's generator: Hurst 0.8, rms slope 0.1, seed 1, grid spacing
1, E* = 1), the same mean pressure (--pressure, in units of E*). adhbem runs build/adhbem as one
process under force control (-adh_control force -adh_start hertz -adh_path 0,F with F = mean
pressure x cell area; its counts are the step to F; "solve" is that step's wall time, the
process CPU time includes reading the surface, FFTW's planning and the output), and again under
displacement control to the indentation d that the force-controlled run found (-adh_path 0,d:
the cost of one state at a known indentation); Tamaas runs with E = 1, nu = 0 to a tolerance of
1e-10 (--tolerance; at 1024^2 it stalls above 1e-12), at most 20 000 iterations. Both are timed
as process CPU time (getrusage of the child; time.process_time around Tamaas' solve), the best
of --repeat runs. Equal accuracy is checked by the contact area:
the two contact sets must count the same points to within 0.1%.

Tamaas is not a dependency of adhbem: install it in a virtual environment of your own and name
its interpreter, e.g.
    python3 -m venv ~/venv-peers && ~/venv-peers/bin/pip install tamaas numpy
    ./run bench tamaas --peer-python ~/venv-peers/bin/python
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import adhbem_build  # noqa: E402  (knows the build directory; starts neither PETSc nor MPI)

TAMAAS = r"""
import sys, time, numpy as np, tamaas as tm
z = np.load(sys.argv[1]); N = z.shape[0]; pressure = float(sys.argv[2]); tol = float(sys.argv[3])
tm.set_log_level(tm.LogLevel.info)
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [float(N), float(N)], [N, N])
model.E = 1.0; model.nu = 0.0
solver = tm.PolonskyKeerRey(model, z, tol)
solver.max_iter = 20000
t0 = time.process_time(); solver.solve(pressure); t1 = time.process_time()
p = np.array(model.traction)
print("RESULT", t1 - t0, int((p > 0).sum()), flush=True)
"""


def surface(n, path):
    """adhbem's surface as an (N, N) .npy height map (in a process of its own: no MPI here)."""
    code = ("import numpy as np, adhbem\n"
            f"z, _ = adhbem.rough_surface({n}, size={float(n)}, hurst=0.8, rms_slope=0.1, seed=1)\n"
            f"np.save({path!r}, adhbem.gather(z, z))\n")
    subprocess.run([sys.executable, "-c", code], check=True, env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python")))


def run_adhbem(n, zfile, target, tmp, control="force", predictor=None):
    """One step from the contact-free state to target: a force, or (displacement) an indentation."""
    import h5py
    out = os.path.join(tmp, "a.h5")
    cmd = [adhbem_build.EXE, "-adh_n", str(n), "-adh_size", str(n), "-adh_boundary", "periodic",
           "-adh_indenter", "file", "-adh_topography", zfile, "-adh_gamma", "0", "-adh_control", control,
           "-adh_start", "hertz", "-adh_path", f"0,{target!r}", "-adh_steps", "1", "-adh_output", out]
    if predictor:
        cmd += ["-adh_predictor", predictor]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode:
        sys.exit(f"bench tamaas: adhbem failed at N = {n}:\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    with h5py.File(out, "r") as f:
        c = {k: f["curve"][k][()] for k in f["curve"]}
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return dict(cpu=cpu, solve=float(c["seconds"][-1]), points=int(c["contact_points"][-1]), d=float(c["d"][-1]),
                updates=int(c["outer_iterations"][-1]), ksp=int(c["ksp_iterations"][-1]),
                ffts=int(c["fft_pairs"][-1]))


def run_tamaas(python, zfile, pressure, tol):
    p = subprocess.run([python, "-c", TAMAAS, zfile, repr(pressure), repr(tol)], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode:
        sys.exit(f"bench tamaas: Tamaas failed:\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    its = 0
    for line in (p.stdout + p.stderr).splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[0].isdigit():
            its = max(its, int(parts[0]))
        if line.startswith("RESULT"):
            _, cpu, points = line.split()
    return dict(cpu=float(cpu), points=int(points), its=its)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peer-python", default=os.environ.get("TAMAAS_PYTHON"),
                    help="a Python with tamaas installed (or TAMAAS_PYTHON)")
    ap.add_argument("--n", default="512,1024,2048", help="grid sizes N (N x N), comma-separated")
    ap.add_argument("--pressure", type=float, default=0.005, help="mean pressure / E*")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each; the least CPU time counts")
    ap.add_argument("--predictor", help="adhbem's -adh_predictor (default: its own, polonsky-keer on a periodic "
                    "cell; none: the set-update loop alone)")
    ap.add_argument("--tolerance", type=float, default=1e-10, help="Tamaas' tolerance (at most 20 000 iterations)")
    a = ap.parse_args()
    if not a.peer_python or not os.access(a.peer_python, os.X_OK):
        sys.exit("bench tamaas: --peer-python: name a Python that has tamaas (python3 -m venv DIR && "
                 "DIR/bin/pip install tamaas numpy; then --peer-python DIR/bin/python)")
    print(f"non-adhesive periodic rough contact, mean pressure {a.pressure} E*, 1 core, CPU seconds (best of {a.repeat})")
    print(f"{'N':>6} {'control':>12} {'adhbem s':>9} {'(solve)':>8} {'updates':>7} {'KSP':>6} {'FFT pairs':>9}"
          f" {'points':>9} {'Tamaas s':>9} {'its':>6} {'points':>9} {'speed-up':>8}")
    with tempfile.TemporaryDirectory() as tmp:
        for n in [int(v) for v in a.n.split(",")]:
            zfile = os.path.join(tmp, f"z{n}.npy")
            surface(n, zfile)
            ad = min((run_adhbem(n, zfile, a.pressure * n * n, tmp, "force", a.predictor) for _ in range(a.repeat)), key=lambda r: r["cpu"])
            dc = min((run_adhbem(n, zfile, ad["d"], tmp, "displacement", a.predictor) for _ in range(a.repeat)), key=lambda r: r["cpu"])
            tm = min((run_tamaas(a.peer_python, zfile, a.pressure, a.tolerance) for _ in range(a.repeat)), key=lambda r: r["cpu"])
            for name, r in (("force", ad), ("displacement", dc)):
                agree = abs(r["points"] - tm["points"]) <= 1e-3 * tm["points"]
                print(f"{n:>6} {name:>12} {r['cpu']:>9.2f} {r['solve']:>8.2f} {r['updates']:>7} {r['ksp']:>6} {r['ffts']:>9}"
                      f" {r['points']:>9} {tm['cpu']:>9.2f} {tm['its']:>6} {tm['points']:>9} {tm['cpu'] / r['cpu']:>7.2f}x"
                      f"{'' if agree else '  (contact areas differ!)'}", flush=True)

if __name__ == "__main__":
    main()
