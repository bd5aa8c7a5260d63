"""./run bench contactmechanics_layer --peer-python VENV/bin/python [--n 64] [--thickness 0.1] [--nu 0.3]
    [--cases sphere,incompressible,rough,exponential]

adhbem's elastic layer on a rigid base (-adh_elastic layer, bonded) against ContactMechanics'
finite-thickness PeriodicFFTElasticHalfSpace (Carbone and Mangialardi's Green's function), on one
core, the same periodic cells 1 x 1 (E1 = 1, a rigid indenter):

  sphere          R = 1, no adhesion, five indentations (ContactMechanics' constrained
                  conjugate gradients, pentol 1e-12);
  incompressible  the same with nu = 0.5 (the peer's 0.5 - 1e-9: its mean mode's stiffness divides
                  by 1 - 2 nu; the symbol moves by 1e-9);
  rough           a rough surface of adhbem's generator (Hurst 0.8, rms slope 0.1), no adhesion,
                  the thickness halved, at offsets 0.2 to 0.8 of full contact's;
  exponential     the sphere with the exponential law (dgamma 2e-3, range 0.01) behind a hard wall,
                  in and out, each state from the last: the Adhesion package's
                  BoundedSmoothContactSystem (L-BFGS-B, gtol --peer-gtol) against adhbem's
                  -adh_criterion exponential (-adh_minimize_rtol 1e-11).

ContactMechanics gives the layer's mean mode the oedometer's stiffness k0 = E1 (1 - nu) /
(T (1 + nu)(1 - 2 nu)), so its offset is the approach to the base; adhbem's d leaves the uniform
compression out (the mean plane of the surface). The same state is at d = offset - F / (k0 A):
the peer runs first, adhbem at those d. Both are timed as process CPU time around the path. The
table: each state's forces, their difference over the largest, and the contact points.

Neither ContactMechanics nor Adhesion is a dependency of adhbem: install them in a virtual
environment of your own and name its interpreter, e.g.
    python3 -m venv ~/venv-peers && ~/venv-peers/bin/pip install --only-binary=:all: ContactMechanics Adhesion
    ./run bench contactmechanics_layer --peer-python ~/venv-peers/bin/python
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

PROFILE = r"""
import sys, numpy as np, adhbem
n, kind, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
opts = dict(n=n, boundary="periodic", gamma=0.0, path=[0.0, 0.001], steps=1, progress=False)
if kind == "rough":
    opts.update(indenter="rough", hurst=0.8, rms_slope=0.1, seed=7)
with adhbem.Solver(**opts) as s:
    np.save(out, s.profile_array())
"""

PEER = r"""
import sys, time, json, numpy as np
from ContactMechanics import PeriodicFFTElasticHalfSpace
from ContactMechanics.Systems import NonSmoothContactSystem
from SurfaceTopography import Topography
h = np.load(sys.argv[1]); c = json.loads(sys.argv[2]); n = h.shape[0]
sub = PeriodicFFTElasticHalfSpace((n, n), c["E1"], physical_sizes=(1.0, 1.0), thickness=c["T"], poisson=c.get("peer_nu", c["nu"]))
top = Topography(np.ascontiguousarray(-h.T), physical_sizes=(1.0, 1.0))
F, points = [], []
t = time.process_time()
if c["gamma"] > 0:
    from Adhesion.Interactions import Exponential
    from Adhesion.System import BoundedSmoothContactSystem
    system = BoundedSmoothContactSystem(sub, Exponential(c["gamma"], c["rho"]), top)
    disp = None
    for o in c["offsets"]:
        r = system.minimize_proxy(offset=o, initial_displacements=disp, options=dict(gtol=c["peer_gtol"], ftol=0, maxcor=3, maxiter=100000))
        if not r.success:
            sys.exit(f"Adhesion: no convergence at offset {o}: {r.message}")
        disp = r.x.reshape(sub.nb_domain_grid_pts)
        F.append(float(system.compute_normal_force())); points.append(int(np.count_nonzero(system.compute_gap(disp, o) <= 0)))
else:
    system = NonSmoothContactSystem(sub, top)
    for o in c["offsets"]:
        r = system.minimize_proxy(offset=o, pentol=1e-12, maxiter=100000)
        if not r.success:
            sys.exit(f"ContactMechanics: no convergence at offset {o}: {r.message}")
        F.append(float(r.jac.sum())); points.append(int(np.count_nonzero(r.jac > 0)))
t = time.process_time() - t
np.savez(sys.argv[3], force=np.array(F), points=np.array(points), cpu=t)
"""

ADHBEM = r"""
import sys, time, json, numpy as np, adhbem
h = np.load(sys.argv[1]); c = json.loads(sys.argv[2]); n = h.shape[0]
opts = dict(n=n, boundary="periodic", elastic="layer", layer_thickness=c["T"], E1=c["E1"], nu1=c["nu"], gamma=c["gamma"],
            topography=h, topography_kind="gap", path=[c["d"][0]] + c["d"], steps=1, start="hertz", progress=False,
            stop_at_pulloff=False)
if c["gamma"] > 0:
    opts.update(criterion="exponential", exponential_range=c["rho"], start="adhesive", minimize_rtol=1e-11)
else:
    opts.update(ksp_rtol=1e-13)
with adhbem.Solver(**opts) as s:
    t = time.process_time(); curve = s.solve_path(); t = time.process_time() - t
np.savez(sys.argv[3], force=curve["force"][1:], points=curve["contact_points"][1:], cpu=t,
         ffts=int(np.sum(curve["fft_pairs"])), its=int(np.sum(curve["ksp_iterations"])))
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peer-python", default=os.environ.get("CONTACTMECHANICS_PYTHON"),
                    help="a Python with ContactMechanics and Adhesion installed (or CONTACTMECHANICS_PYTHON)")
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--thickness", type=float, default=0.1)
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--cases", default="sphere,incompressible,rough,exponential")
    ap.add_argument("--peer-gtol", type=float, default=1e-12, help="L-BFGS-B's gtol for the Adhesion package (tighter may end ABNORMAL)")
    a = ap.parse_args()
    if not a.peer_python:
        sys.exit("bench contactmechanics_layer: --peer-python: name a Python that has ContactMechanics and Adhesion "
                 "(python3 -m venv DIR && DIR/bin/pip install --only-binary=:all: ContactMechanics Adhesion)")
    import json
    import numpy as np
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"), OMP_NUM_THREADS="1")
    cases = {
        "sphere": dict(nu=a.nu, T=a.thickness, gamma=0.0, offsets=[0.002, 0.004, 0.006, 0.008, 0.01], profile="sphere"),
        "incompressible": dict(nu=0.5, peer_nu=0.5 - 1e-9, T=a.thickness, gamma=0.0, offsets=[0.002, 0.004, 0.006, 0.008, 0.01], profile="sphere"),
        "rough": dict(nu=a.nu, T=a.thickness / 2, gamma=0.0, fractions=[0.2, 0.4, 0.6, 0.8], profile="rough"),
        "exponential": dict(nu=a.nu, T=a.thickness, gamma=2e-3, rho=0.01, offsets=[0.0, 0.002, 0.004, 0.006, 0.004, 0.002, 0.0, -0.002, -0.004],
                            profile="sphere"),
    }
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.cases.split(","):
            c = dict(cases[name], E1=1.0, peer_gtol=a.peer_gtol)
            hfile, peer, mine = (os.path.join(tmp, f"{name}_{x}") for x in ("h.npy", "peer.npz", "adhbem.npz"))
            subprocess.run([sys.executable, "-c", PROFILE, str(a.n), c["profile"], hfile], check=True, env=env)
            if "fractions" in c:  # a rough surface: offsets at fractions of full contact, d = mean(h)
                c["offsets"] = [f * float(np.mean(np.load(hfile))) for f in c.pop("fractions")]
            p = subprocess.run([a.peer_python, "-c", PEER, hfile, json.dumps(c), peer], capture_output=True, text=True,
                               env=dict(os.environ, OMP_NUM_THREADS="1"))
            if p.returncode:
                sys.exit(f"bench contactmechanics_layer: the peer failed on {name}:\n{p.stderr[-2000:]}")
            y = np.load(peer)
            h = np.load(hfile)
            nu = c.get("peer_nu", c["nu"])
            k0 = c["E1"] * (1 - nu) / (c["T"] * (1 + nu) * (1 - 2 * nu))
            c["d"] = [float(o - F / k0) for o, F in zip(c["offsets"], y["force"])]
            subprocess.run([sys.executable, "-c", ADHBEM, hfile, json.dumps(c), mine], check=True, env=env)
            x = np.load(mine)
            Fa, Fp = x["force"], y["force"]
            scale = float(np.max(np.abs(Fp)))
            print(f"# {name}: bonded layer T = {c['T']}, nu = {c['nu']}, {a.n}^2 cell"
                  + (f", exponential law dgamma {c['gamma']}, range {c['rho']}" if c["gamma"] > 0 else ", no adhesion"))
            print(f"{'offset':>8} {'d':>11} {'adhbem F':>17} {'peer F':>17} {'|dF|/max|F|':>12} {'points':>7} {'peer':>6}")
            for k, o in enumerate(c["offsets"]):
                print(f"{o:>+8.4f} {c['d'][k]:>+11.7f} {Fa[k]:>+17.10e} {Fp[k]:>+17.10e} {abs(Fa[k] - Fp[k]) / scale:>12.2e}"
                      f" {int(x['points'][k]):>7} {int(y['points'][k]):>6}")
            err = float(np.max(np.abs(Fa - Fp)) / scale)
            worst = max(worst, err)
            print(f"largest |dF|/max|F| {err:.2e}; CPU: adhbem {float(x['cpu']):.2f} s ({int(x['its'])} iterations,"
                  f" {int(x['ffts'])} FFT pairs), peer {float(y['cpu']):.2f} s\n")
    print(f"all cases: largest |dF|/max|F| {worst:.2e}")


if __name__ == "__main__":
    main()
