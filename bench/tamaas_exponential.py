"""./run bench tamaas_exponential --peer-python VENV/bin/python [--n 64] [--range 0.01] [--dgamma 2e-3]
    [--path 0,0.01,-0.03] [--steps 20] [--rtol 1e-10] [--tolerance 1e-12]

The exponential cohesive law against Tamaas' PolonskyKeerRey solver with its
ExponentialAdhesionFunctional, on one core: a periodic cell 1 x 1 with a sphere (R = 1, E* = 1:
Tamaas' E = 1, nu = 0), the law -dgamma exp(-g/rho) behind a hard wall, the same path of mean gaps
(adhbem's displacement control: the mean gap is mean(h) - d), each state from the last in both.
adhbem runs in a Python process of its own (-adh_criterion exponential -adh_start adhesive,
-adh_minimize_rtol --rtol), which also writes the profile h that Tamaas is given (as -h: Tamaas'
surface is the rigid body's heights); Tamaas to its tolerance (--tolerance). Both are timed as
process CPU time around the path. The table: every few states the force of each and their
difference over the largest force, and the contact areas; then the largest difference and the
CPU times.

Tamaas is not a dependency of adhbem: install it in a virtual environment of your own and name
its interpreter, e.g.
    python3 -m venv ~/venv-peers && ~/venv-peers/bin/pip install tamaas numpy
    ./run bench tamaas_exponential --peer-python ~/venv-peers/bin/python
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

ADHBEM = r"""
import sys, time, numpy as np, adhbem
n, rho, dgamma, out, rtol, steps = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4], float(sys.argv[5]), int(sys.argv[6])
path = [float(x) for x in sys.argv[7].split(",")]
with adhbem.Solver(n=n, boundary="periodic", gamma=dgamma, criterion="exponential", exponential_range=rho, path=path,
                   steps=steps, start="adhesive", minimize_rtol=rtol, stop_at_pulloff=False, progress=False) as s:
    t = time.process_time(); c = s.solve_path(); t = time.process_time() - t
    np.savez(out, h=s.profile_array(), d=c["d"], force=c["force"], area=c["area_fraction"], ffts=c["fft_pairs"], its=c["ksp_iterations"], cpu=t)
"""

TAMAAS = r"""
import sys, time, numpy as np, tamaas as tm
a = np.load(sys.argv[1]); rho, dgamma, tol = float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
h = a["h"]; n = h.shape[0]
tm.set_log_level(tm.LogLevel.error)
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n]); model.E = 1.0; model.nu = 0.0
surface = np.ascontiguousarray(-h)
solver = tm.PolonskyKeerRey(model, surface, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
adhesion = tm.ExponentialAdhesionFunctional(surface); adhesion.parameters = {"rho": rho, "surface_energy": dgamma}
solver.addFunctionalTerm(adhesion); solver.max_iter = 100000
F, A = [], []
t = time.process_time()
for d in a["d"]:
    solver.solve(float(h.mean() - d))
    F.append(float(np.mean(model.traction))); A.append(float(np.count_nonzero(model.displacement - surface <= 0)) / n / n)
t = time.process_time() - t
np.savez(sys.argv[5], force=np.array(F), area=np.array(A), cpu=t)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peer-python", default=os.environ.get("TAMAAS_PYTHON"), help="a Python with tamaas installed (or TAMAAS_PYTHON)")
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--range", type=float, default=0.01)
    ap.add_argument("--dgamma", type=float, default=2e-3)
    ap.add_argument("--path", default="0,0.01,-0.03")
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--rtol", type=float, default=1e-10, help="adhbem's -adh_minimize_rtol")
    ap.add_argument("--tolerance", type=float, default=1e-12, help="Tamaas' tolerance")
    a = ap.parse_args()
    if not a.peer_python:
        sys.exit("bench tamaas_exponential: --peer-python: name a Python that has tamaas (python3 -m venv DIR && DIR/bin/pip install tamaas numpy)")
    import numpy as np
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"), OMP_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as tmp:
        mine, theirs = os.path.join(tmp, "adhbem.npz"), os.path.join(tmp, "tamaas.npz")
        subprocess.run([sys.executable, "-c", ADHBEM, str(a.n), repr(a.range), repr(a.dgamma), mine, repr(a.rtol), str(a.steps), a.path],
                       check=True, env=env)
        p = subprocess.run([a.peer_python, "-c", TAMAAS, mine, repr(a.range), repr(a.dgamma), repr(a.tolerance), theirs],
                           capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        if p.returncode:
            sys.exit(f"bench tamaas_exponential: Tamaas failed:\n{p.stderr[-2000:]}")
        x, y = np.load(mine), np.load(theirs)
        Fa, Ft = x["force"], y["force"]
        scale = float(np.max(np.abs(Fa)))
        print(f"# exponential law, periodic {a.n}^2 sphere, rho {a.range}, dgamma {a.dgamma}: {len(Fa)} states")
        print(f"{'d':>9} {'adhbem F':>17} {'Tamaas F':>17} {'|dF|/max|F|':>12} {'area adhbem':>12} {'area Tamaas':>12}")
        for k in range(0, len(Fa), max(1, len(Fa) // 12)):
            print(f"{x['d'][k]:>+9.4f} {Fa[k]:>+17.10e} {Ft[k]:>+17.10e} {abs(Fa[k] - Ft[k]) / scale:>12.2e} {x['area'][k]:>12.5f} {y['area'][k]:>12.5f}")
        print(f"largest |dF|/max|F| {np.max(np.abs(Fa - Ft)) / scale:.2e}; contact areas equal in {int(np.sum(np.isclose(x['area'], y['area'], rtol=0, atol=0.5 / a.n ** 2)))} of {len(Fa)} states")
        print(f"CPU: adhbem {float(x['cpu']):.2f} s ({int(np.sum(x['its']))} iterations, {int(np.sum(x['ffts']))} FFT pairs), Tamaas {float(y['cpu']):.2f} s")


if __name__ == "__main__":
    main()
