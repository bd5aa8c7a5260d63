"""Benchmark of the compliance MatShell: time per MatMult, FFT share, memory per grid point.

    ./run bench compliance [--sizes 256,512,1024,2048] [--ranks 1,2] [--reps K]
                           [--boundaries free,periodic] [--budget SECONDS] [-- PETSC_OPTIONS]

For every N, boundary and rank count the driver starts a worker under
`mpirun --oversubscribe -n P /usr/bin/python3 bench/compliance.py --worker ...`. The worker builds
the operator on an N x N grid, does a few warm-up multiplies, then times `reps` MatMults one by
one (wall clock, slowest rank of each, median reported). The FFT time comes from adhbem's
PetscLogEvents AdhFFTForward + AdhFFTBackward (the bare fftw_execute calls), the multiply time
from AdhComplMult, both read through petsc4py after PETSc.Log.begin(). Memory is ru_maxrss at the
end minus ru_maxrss just before the operator is built (interpreter, NumPy, PETSc, MPI already
loaded): it covers the operator, FFTW's plans and buffers, and the two Vecs of the multiply.

`free` transforms a zero-padded 2N x 2N grid, `periodic` the N x N grid itself. Sizes whose
predicted run time would push the whole benchmark past --budget seconds are skipped (and said so).
Options after `--` go to PETSc in the workers (e.g. `-- -adh_fftw_planner estimate`).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PYTHON = "/usr/bin/python3"


# ---- worker: runs under mpirun ---------------------------------------------------------------

def worker(args, petsc_args):
    import resource

    sys.argv = [sys.argv[0]] + petsc_args  # adhbem hands sys.argv to PETSc
    sys.path.insert(0, os.path.join(ROOT, "python"))
    import adhbem
    from adhbem import PETSc
    from mpi4py import MPI

    comm = PETSc.COMM_WORLD
    mcomm = comm.tompi4py()
    PETSc.Log.begin()

    def maxrss_bytes():
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # Linux: kB

    N = args.n
    mcomm.Barrier()
    base = maxrss_bytes()
    t0 = MPI.Wtime()
    K = adhbem.compliance(N, 1.0, 1.0, args.boundary, comm=comm)
    x, y = K.createVecs()
    x.setRandom()
    mcomm.Barrier()
    setup = mcomm.allreduce(MPI.Wtime() - t0, op=MPI.MAX)

    events = {name: PETSc.Log.Event(name) for name in ("AdhComplMult", "AdhFFTForward", "AdhFFTBackward")}

    def event_times():
        return {name: ev.getPerfInfo()["time"] for name, ev in events.items()}

    def event_counts():
        return {name: ev.getPerfInfo()["count"] for name, ev in events.items()}

    # warm-up; the number of timed multiplies follows from it unless --reps is given
    warm = []
    for _ in range(3):
        mcomm.Barrier()
        t = MPI.Wtime()
        K.mult(x, y)
        warm.append(MPI.Wtime() - t)
    warm = mcomm.allreduce(min(warm), op=MPI.MAX)
    reps = args.reps if args.reps > 0 else int(min(200, max(10, args.target / max(warm, 1e-9))))

    # each multiply timed on its own: wall clock, and the log events' increments (per rank)
    counts_before = event_counts()
    wall, fft, inside = [], [], []
    prev = event_times()
    for _ in range(reps):
        mcomm.Barrier()
        t = MPI.Wtime()
        K.mult(x, y)
        wall.append(MPI.Wtime() - t)
        now = event_times()
        fft.append(now["AdhFFTForward"] - prev["AdhFFTForward"] + now["AdhFFTBackward"] - prev["AdhFFTBackward"])
        inside.append(now["AdhComplMult"] - prev["AdhComplMult"])
        prev = now
    counts_after = event_counts()
    # a misspelt event name would register a new, empty event: insist the events saw every multiply
    counted = all(counts_after[k] - counts_before[k] == reps for k in counts_after)
    counted = mcomm.allreduce(counted, op=MPI.LAND)

    def median_of_slowest(samples):
        """the slowest rank for each multiply, then the median over the multiplies"""
        return statistics.median(max(ts) for ts in zip(*mcomm.allgather(samples)))

    mult_med, fft_med, inside_med = median_of_slowest(wall), median_of_slowest(fft), median_of_slowest(inside)
    fractions = [f / m for f, m in zip(fft, inside)]
    frac_med = statistics.median(max(fs) for fs in zip(*mcomm.allgather(fractions)))
    peak = maxrss_bytes() - base
    peaks = mcomm.allgather(peak)
    info = adhbem.compliance_info(K)
    if comm.getRank() == 0:
        fft_n = 2 * N if args.boundary == "free" else N
        result = dict(N=N, boundary=args.boundary, ranks=comm.getSize(), fft_grid=fft_n, reps=reps,
                      setup_s=setup,
                      mult_ms_median=1e3 * mult_med, mult_ms_min=1e3 * min(wall),
                      event_mult_ms=1e3 * inside_med, fft_ms=1e3 * fft_med, fft_fraction=frac_med,
                      events_ok=bool(counted),
                      peak_mb_max_rank=max(peaks) / 2**20, bytes_total=sum(peaks),
                      bytes_per_point=sum(peaks) / (N * N), mult_count=info["mult_count"])
        print("RESULT " + json.dumps(result), flush=True)


# ---- driver -------------------------------------------------------------------------------------

def run_worker(N, boundary, P, args, petsc_args):
    cmd = ["mpirun", "--oversubscribe", "-n", str(P), PYTHON, os.path.abspath(__file__), "--worker",
           "--n", str(N), "--boundary", boundary, "--reps", str(args.reps), "--target", str(args.target)]
    if petsc_args:
        cmd += ["--"] + petsc_args
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMP_NUM_THREADS", "1")
    env["PYTHONPATH"] = os.path.join(ROOT, "python") + (":" + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    t = time.time()
    try:
        proc = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              timeout=args.worker_timeout)
    except subprocess.TimeoutExpired:
        sys.stderr.write(f"worker N={N} {boundary} P={P} timed out after {args.worker_timeout:.0f} s\n")
        return None
    elapsed = time.time() - t
    for line in proc.stdout.splitlines():
        if line.startswith("RESULT "):
            result = json.loads(line[len("RESULT "):])
            result["wall_s"] = elapsed
            return result
    sys.stderr.write(f"worker N={N} {boundary} P={P} failed (exit {proc.returncode}):\n{proc.stdout}\n{proc.stderr}\n")
    return None


HEADER = (f"{'N':>5} {'boundary':>8} {'ranks':>5} {'FFT grid':>9} {'reps':>4} {'ms/MatMult':>10} "
          f"{'ms FFT':>8} {'FFT frac':>8} {'setup s':>7} {'peak MB':>8} {'B/point':>8}")


def row(r):
    flag = "" if r.get("events_ok", True) else "  (log events did not count every multiply!)"
    return (f"{r['N']:>5} {r['boundary']:>8} {r['ranks']:>5} {r['fft_grid']:>4}^2    {r['reps']:>4} "
            f"{r['mult_ms_median']:>10.2f} {r['fft_ms']:>8.2f} {r['fft_fraction']:>8.2f} "
            f"{r['setup_s']:>7.2f} {r['peak_mb_max_rank']:>8.1f} {r['bytes_per_point']:>8.0f}" + flag)


def main():
    argv = sys.argv[1:]
    petsc_args = []
    if "--" in argv:
        k = argv.index("--")
        argv, petsc_args = argv[:k], argv[k + 1:]
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="256,512,1024,2048")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--boundaries", default="free,periodic")
    ap.add_argument("--reps", type=int, default=0, help="timed multiplies (default: about --target seconds, 10..200)")
    ap.add_argument("--target", type=float, default=1.5, help="seconds of timed multiplies per case when --reps is not given")
    ap.add_argument("--budget", type=float, default=300.0, help="skip cases predicted to end past this many seconds")
    ap.add_argument("--worker-timeout", type=float, default=300.0, help="seconds before a worker is given up (a hung collective)")
    ap.add_argument("--json", help="also write the results to this file")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--n", type=int, help=argparse.SUPPRESS)
    ap.add_argument("--boundary", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        return worker(args, petsc_args)

    sizes = [int(s) for s in args.sizes.split(",") if s]
    ranks = [int(s) for s in args.ranks.split(",") if s]
    boundaries = [b for b in args.boundaries.split(",") if b]
    start = time.time()
    results, last = [], {}
    print(f"adhbem compliance benchmark: MatMult of the N x N half-space compliance "
          f"(free: padded 2N x 2N FFT, periodic: N x N); {os.cpu_count()} cores; PETSc options: {' '.join(petsc_args) or '(none)'}")
    load = os.getloadavg()[0]
    if load > 0.5:
        print(f"warning: load average {load:.2f} before starting: other work on this machine will inflate the times")
    print(HEADER, flush=True)
    for N in sizes:
        for boundary in boundaries:
            for P in ranks:
                key = (boundary, P)
                if key in last:  # predict from the previous size: cost ~ N^2 log N
                    prevN, prev_wall = last[key]
                    predicted = prev_wall * (N / prevN) ** 2 * 1.15
                    if time.time() - start + predicted > args.budget:
                        print(f"{N:>5} {boundary:>8} {P:>5}   skipped: predicted {predicted:.0f} s would pass the "
                              f"{args.budget:.0f} s budget (--budget)", flush=True)
                        continue
                r = run_worker(N, boundary, P, args, petsc_args)
                if r is None:
                    print(f"{N:>5} {boundary:>8} {P:>5}   FAILED (see stderr)", flush=True)
                    continue
                last[key] = (N, r["wall_s"])
                results.append(r)
                print(row(r), flush=True)
    print(f"total {time.time() - start:.0f} s, load average now {os.getloadavg()[0]:.2f}")
    print("  ms/MatMult: wall time of one multiply on the slowest rank, median over the reps\n"
          "  ms FFT:     AdhFFTForward + AdhFFTBackward (the bare fftw_execute calls) in one multiply,\n"
          "              slowest rank, median; FFT frac: that over the AdhComplMult time of the same multiply\n"
          "  setup s:    building the operator (FFTW plans, kernel transform, diagonal)\n"
          "  peak MB:    ru_maxrss growth from just before the build, max over ranks (operator, plans, 2 Vecs)\n"
          "  B/point:    that growth summed over the ranks, per physical grid point")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0 if results else 1


if __name__ == "__main__":
    sys.exit(main())
