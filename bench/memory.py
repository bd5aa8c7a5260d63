"""./run bench memory: peak memory and time per FFT pair of a periodic rough cell against N and ranks.

The cell of `./run bench rough` (Hurst 0.8, rms slope 0.1, cut-off 4 spacings, roll-off at the
cell size, spacing 1, E* = 1) pressed to that bench's deepest indentation d1 in one step without
adhesion and without the contact-set predictor (-adh_gamma 0 -adh_predictor none: the set-update
loop and its CG vectors, as in an adhesive run). Each run is build/adhbem under mpirun with
-memory_view. The table gives the peak resident memory of all ranks together, per grid point, and
per grid point above the ranks' base (the peak of a 64 x 64 run on as many ranks: MPI, PETSc and
FFTW themselves), the share of the cell in contact, and the seconds per FFT pair (compliance and
preconditioner), with the counts behind it.

    ./run bench memory [--n 1024,2048] [--np 1,2] [-- OPTIONS]

4096^2 takes 6-7 minutes a run on a 2-core machine.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from adhbem_build import EXE  # noqa: E402  (no PETSc, no MPI: this process starts mpirun)
from rough import depth  # noqa: E402

PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)")


def run(n, np_, d1, extra=()):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "memory.h5")
        cmd = ["mpirun", "--oversubscribe", "-n", str(np_), EXE,
               "-adh_n", str(n), "-adh_size", str(n), "-adh_indenter", "rough", "-adh_hurst", "0.8",
               "-adh_rms_slope", "0.1", "-adh_seed", "1", "-adh_boundary", "periodic",
               "-adh_gamma", "0", "-adh_predictor", "none", "-adh_path", f"0,{d1!r}", "-adh_steps", "1",
               "-adh_output", out, "-memory_view"] + list(extra)
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode:
            sys.exit(f"bench memory: N = {n} on {np_} ranks failed:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
        import h5py
        with h5py.File(out, "r") as f:
            c = {k: f["curve"][k][()] for k in f["curve"]}
    return dict(mem=float(PEAK.search(p.stdout).group(1)), seconds=float(c["seconds"].sum()),
                ffts=int(c["fft_pairs"].sum()), ksp=int(c["ksp_iterations"].sum()),
                contact=float(c["contact_points"][-1]) / (n * n))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", default="1024,2048", help="grid sizes N (N x N), comma-separated")
    ap.add_argument("--np", default="1,2", help="numbers of ranks, comma-separated")
    ap.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = ap.parse_args()
    sizes = [int(v) for v in a.n.split(",")]
    ranks = [int(v) for v in a.np.split(",")]
    base = {np_: run(64, np_, depth(64), a.extra)["mem"] for np_ in ranks}
    print("periodic rough cell at d1 without adhesion (-adh_gamma 0 -adh_predictor none), one step")
    print("base (64 x 64): " + ", ".join(f"{np_} rank(s) {base[np_] / 1e6:.1f} MB" for np_ in ranks))
    print(f"{'N':>6} {'ranks':>5} {'contact':>8} {'peak MB':>9} {'B/pt':>6} {'above base':>10}"
          f" {'KSP':>6} {'FFT pairs':>9} {'solve s':>8} {'ms/pair':>8}")
    for n in sizes:
        d1 = depth(n)
        for np_ in ranks:
            r = run(n, np_, d1, a.extra)
            print(f"{n:>6} {np_:>5} {100 * r['contact']:>7.1f}% {r['mem'] / 1e6:>9.1f} {r['mem'] / n / n:>6.1f}"
                  f" {(r['mem'] - base[np_]) / n / n:>10.1f} {r['ksp']:>6} {r['ffts']:>9} {r['seconds']:>8.1f}"
                  f" {1e3 * r['seconds'] / r['ffts']:>8.2f}", flush=True)


if __name__ == "__main__":
    main()
