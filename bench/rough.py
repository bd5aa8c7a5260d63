"""./run bench rough: adhesive contact of a self-affine periodic surface at growing N.

The surface: Hurst 0.8, rms slope 0.1, cut-off at 4 grid spacings, roll-off at the cell size,
grid spacing 1, E* = 1, dgamma = 0.004 (-adh_boundary periodic -adh_start adhesive
-adh_attach reach). The path: from first touch (d = 0) to the indentation at which a quarter of
the gap profile lies below it, then back to -0.6 times that, --steps steps a leg. Each run is
build/adhbem under mpirun; the table gives the wall time, the operation counts (set updates,
KSP iterations, compliance applications, all FFT pairs including the preconditioner's; these do
not depend on the machine) and the peak resident memory of all ranks together over N^2.

    ./run bench rough [--n 256,512,1024] [--np 1,2] [--steps 25] [--gamma 0.004] [--breakdown] [-- OPTIONS]

With --breakdown, where the KSP iterations go: each solve of each step, from PETSc's -info
lines, by what the solve decided (a certified stop before points let go or join, a full solve
that let points go or join, the last full solve of a step).
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from adhbem_build import EXE  # noqa: E402  (no PETSc, no MPI: this process starts mpirun)


def depth(n, quantile=0.25, **surface):
    """The indentation at which `quantile` of the gap profile h = max(z) - z lies below it, on this
    bench's surface (Hurst 0.8, rms slope 0.1, seed 1; further keywords of adhbem.rough_surface in
    surface), in a process of its own: this one starts mpirun and must not initialise MPI."""
    code = ("import sys, numpy as np, adhbem\n"
            f"z, _ = adhbem.rough_surface({n}, size={float(n)}, hurst=0.8, rms_slope=0.1, seed=1, **{surface!r})\n"
            "h = z.getArray().max() - z.getArray()\n"
            f"print(repr(float(np.quantile(h, {quantile}))))\n")
    path = os.pathsep.join(filter(None, [os.path.join(ROOT, "python"), os.environ.get("PYTHONPATH")]))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env=dict(os.environ, PYTHONPATH=path))
    return float(out.stdout.split()[-1])


UPDATE = re.compile(r"update (\d+): (\d+) KSP iterations so far( \(certified (stop|attach)\))?, (\d+) points let go, (\d+) joined")
KINDS = ("certified, let go", "certified, joined", "full, let go", "full, joined", "full, last of a step")


def breakdown(info):
    """{kind: [solves, KSP iterations]} from the -info lines of AdhSolverStep_Displacement."""
    out = collections.OrderedDict((k, [0, 0]) for k in KINDS)
    before = 0
    for line in info.splitlines():
        if not line.startswith("[0] "):  # every rank prints the line: count rank 0's
            continue
        m = UPDATE.search(line)
        if not m:
            continue
        update, sofar, _, cert, gone, joined = m.groups()
        its = int(sofar) - (0 if update == "1" else before)
        before = int(sofar)
        if cert:
            kind = "certified, let go" if cert == "stop" else "certified, joined"
        else:
            kind = "full, let go" if int(gone) else "full, joined" if int(joined) else "full, last of a step"
        out[kind][0] += 1
        out[kind][1] += its
    return out


def run(n, np_, d1, steps, gamma, info=False, extra=()):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "rough.h5")
        cmd = ["mpirun", "--oversubscribe", "-n", str(np_), EXE,
               "-adh_n", str(n), "-adh_size", str(n), "-adh_indenter", "rough", "-adh_hurst", "0.8",
               "-adh_rms_slope", "0.1", "-adh_seed", "1", "-adh_boundary", "periodic",
               "-adh_gamma", str(gamma), "-adh_start", "adhesive", "-adh_attach", "reach",
               "-adh_path", f"0,{d1!r},{-0.6 * d1!r}", "-adh_steps", str(steps),
               "-adh_output", out, "-memory_view"] + (["-info", ":sys"] if info else []) + list(extra)
        t0 = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.time() - t0
        if p.returncode:
            sys.exit(f"bench rough: N = {n} on {np_} ranks failed:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
        import h5py
        with h5py.File(out, "r") as f:
            c = {k: f["curve"][k][()] for k in f["curve"]}
    mem = float(re.search(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)", p.stdout).group(1))
    states = len(c["d"])
    return dict(wall=wall, solve=c["seconds"].sum(), states=states, updates=int(c["outer_iterations"].sum()),
                ksp=int(c["ksp_iterations"].sum()), kapps=int(c["compliance_applications"].sum()),
                ffts=int(c["fft_pairs"].sum()), worst=int(c["outer_iterations"].max()), mem=mem,
                breakdown=breakdown(p.stdout) if info else None)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", default="256,512,1024", help="grid sizes N (N x N), comma-separated")
    ap.add_argument("--np", default="1,2", help="numbers of ranks, comma-separated")
    ap.add_argument("--steps", type=int, default=25, help="steps per leg (2 legs)")
    ap.add_argument("--gamma", type=float, default=0.004, help="work of adhesion")
    ap.add_argument("--breakdown", action="store_true", help="also where the KSP iterations go, by kind of solve")
    ap.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = ap.parse_args()
    sizes = [int(v) for v in a.n.split(",")]
    ranks = [int(v) for v in a.np.split(",")]
    print(f"rough periodic adhesion, dgamma = {a.gamma}, {a.steps} steps a leg (0 -> d1 -> -0.6 d1)")
    print(f"{'N':>6} {'ranks':>5} {'d1':>8} {'states':>6} {'wall s':>8} {'solve s':>8} {'updates':>8} {'worst':>6}"
          f" {'KSP':>8} {'KSP/step':>8} {'K apps':>8} {'FFT pairs':>9} {'MB':>8} {'B/pt':>6}")
    for n in sizes:
        d1 = depth(n)
        for np_ in ranks:
            r = run(n, np_, d1, a.steps, a.gamma, a.breakdown, a.extra)
            steps = r["states"] - 1
            print(f"{n:>6} {np_:>5} {d1:>8.4g} {r['states']:>6} {r['wall']:>8.1f} {r['solve']:>8.1f} {r['updates']:>8}"
                  f" {r['worst']:>6} {r['ksp']:>8} {r['ksp'] / steps:>8.0f} {r['kapps']:>8} {r['ffts']:>9}"
                  f" {r['mem'] / 1e6:>8.1f} {r['mem'] / n / n:>6.0f}", flush=True)
            if r["breakdown"]:
                for kind, (solves, its) in r["breakdown"].items():
                    if solves:
                        print(f"{'':>12} {kind:<22} {solves:>6} solves {its:>8} KSP ({100 * its / r['ksp']:4.1f}%)"
                              f" {its / solves:6.1f} per solve, {solves / steps:5.1f} per step", flush=True)


if __name__ == "__main__":
    main()
