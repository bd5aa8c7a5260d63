"""./run bench scale: a resolved adhesive rough path at a large grid, run to the end across kills.

A periodic N x N cell (spacing 1, E* = 1) of a self-affine surface (Hurst 0.8, rms slope 0.1,
roll-off at --rolloff 256 spacings, cut-off at --cutoff 64) with dgamma --gamma 0.065 E* h: the
smallest asperities' JKR contact radius at pull-off is about 20 spacings (the run's last lines say
so), a_c = 5/16 of the cut-off wavelength as in `./run bench convergence --config moderate`. With
the roll-off kept at 256 spacings, the cell holds (N/256)^2 independent patches of the same
statistics. The path: from first touch with adhesion (d = 0) to the indentation d1 at which a
quarter of the gap profile lies below it, back to 0 and on to -d1, 25 steps a leg, ending at
pull-off, with the default criterion and attach rule (further adhbem options after --).
`--cutoff 32 --gamma 0.209` is ./run rough's stickier surface (a_c = 5/8 of the cut-off
wavelength): there the contact zips across the cell at first touch, so its cost per state grows
with the cell's side (docs/developers/notebook/performance.md).

Such a run takes hours. It runs in DIR (default bench-scale-N/ under the current directory)
with a checkpoint after every state: calling the bench again with the same DIR goes on from the
last checkpoint (-adh_restart), so a run killed by a time limit or a new session loses at most
the state in progress. The bench's options are kept in DIR/bench.json, and a call with other
ones is refused (but for --np: a segment may run on other ranks). Each run segment's CPU time
(the ranks', getrusage of mpirun's children, or sampled from /proc when the ranks are killed),
wall time and peak memory (-memory_view) are kept in DIR/segments.json.

At the end, and with --report at any time (from the results so far, FILE.csv.part while it
runs), a table per leg: states, set updates, KSP iterations, FFT pairs, the solver's seconds
and seconds per FFT pair; the quantities of the path (largest tension, force and contact area at
the deepest state, loop energy); and the segments' CPU, wall and peak memory per grid point.

    ./run bench scale [--n 4096] [--np 2] [--dir DIR] [--steps 25] [--gamma 0.065] [--cutoff 64]
        [--rolloff 256] [--report] [-- OPTIONS]
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from adhbem_build import EXE  # noqa: E402  (no PETSc, no MPI: this process starts mpirun)
from convergence import loop_energy  # noqa: E402  (tools/rough.py's, as bench convergence judges it)
from rough import depth  # noqa: E402  (bench/rough.py: the depth of a quarter of the gap profile)


PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)")


def surface(a):
    return ["-adh_boundary", "periodic", "-adh_indenter", "rough", "-adh_hurst", "0.8", "-adh_rms_slope", "0.1",
            "-adh_rolloff_wavelength", repr(a.rolloff), "-adh_cutoff_wavelength", repr(a.cutoff), "-adh_seed", "1"]


def curve(results):
    """The curve recorded so far: FILE.csv, or FILE.csv.part while the run goes on (None if neither)."""
    for path in (results[:-3] + ".csv", results[:-3] + ".csv.part"):
        if os.path.exists(path) and os.path.getsize(path):
            c = np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True))
            return c if c.size and c.dtype.names else None
    return None


def finished(results):
    """Whether the path ran to its end: a stopped run closes its results too, with complete = 0."""
    if not os.path.exists(results):
        return False
    import h5py
    with h5py.File(results, "r") as f:
        return bool(f.attrs.get("complete", 0))


def children(parent, name):
    """(pid, the fields of /proc/pid/stat after the name) of the processes called name whose parent
    is parent."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            stat = open(f"/proc/{entry}/stat").read()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        if stat[stat.index("(") + 1:stat.rindex(")")] == name and int(fields[1]) == parent:
            yield int(entry), fields


def ranks_cpu(mpirun):
    """CPU seconds of mpirun's adhbem children so far, from /proc: a rank killed with mpirun is not
    waited for, and its time never reaches getrusage(RUSAGE_CHILDREN)."""
    tick = os.sysconf("SC_CLK_TCK")
    return sum((int(f[11]) + int(f[12])) / tick for _, f in children(mpirun, "adhbem"))  # utime, stime


def segment(a, d1, results, checkpoint, record):
    """One run of build/adhbem, from the checkpoint if there is one; returns its exit code."""
    cmd = ["mpirun", "--oversubscribe", "-n", str(a.np), EXE, "-adh_n", str(a.n), "-adh_size", str(a.n)] + surface(a) + [
        "-adh_gamma", repr(a.gamma), "-adh_start", "adhesive", "-adh_path", f"0,{d1!r},0,{-d1!r}",
        "-adh_steps", str(a.steps), "-adh_output", results, "-adh_checkpoint", checkpoint,
        "-adh_monitor", "-memory_view"] + (["-adh_restart", checkpoint] if os.path.exists(checkpoint) else []) + a.extra
    print(" ".join(cmd), flush=True)
    r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.time()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    log, sampled, seen = [], 0.0, 0.0
    for line in p.stdout:  # the monitor's lines as they come, and kept for the memory line
        sys.stdout.write(line)
        sys.stdout.flush()
        log.append(line)
        if time.time() - sampled > 1:
            sampled, seen = time.time(), max(seen, ranks_cpu(p.pid))
    rc = p.wait()
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    peak = PEAK.search("".join(log))
    segs = json.load(open(record)) if os.path.exists(record) else []
    segs.append(dict(started=time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(t0)), wall=time.time() - t0,
                     cpu=max(seen, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)),
                     peak=float(peak.group(1)) if peak else None, np=a.np, exit=rc, restart="-adh_restart" in cmd))
    with open(record, "w") as f:
        json.dump(segs, f, indent=1)
    return rc


def report(a, d1, results, record):
    c = curve(results)
    if c is None:
        print("no state recorded yet")
        return
    n2 = a.n * a.n
    d = c["d"]
    turn = int(np.argmax(d))
    back = turn + int(np.argmin(np.abs(d[turn:]))) if len(d) > turn + 1 else len(d) - 1
    legs = [("approach 0 -> d1", 0, turn + 1), ("unloading d1 -> 0", turn + 1, back + 1),
            ("retraction 0 -> pull-off", back + 1, len(d))]
    print(f"\n{a.n}^2 periodic cell, resolved adhesive rough path (dgamma {a.gamma:g}, d1 = {d1:.4g}),"
          f" {len(d)} states recorded" + ("" if finished(results) else " (the run is not finished)"))
    print(f"| leg | states | set updates | KSP | FFT pairs | solve s | solve ms / FFT pair |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, i, j in legs + [("all", 0, len(d))]:
        if j <= i:
            continue
        s = c[i:j]
        pairs = int(s["fft_pairs"].sum())
        print(f"| {name} | {j - i} | {int(s['outer_iterations'].sum())} | {int(s['ksp_iterations'].sum())} | {pairs}"
              f" | {s['seconds'].sum():.0f} | {1e3 * s['seconds'].sum() / max(pairs, 1):.1f} |")
    F = c["force"]
    print(f"largest tension {max(0.0, -F.min()):.6g}, at the deepest state force {F[turn]:.6g} and contact area"
          f" {c['area'][turn] / n2:.4f}, loop energy {loop_energy(d, F):.6g}")
    if os.path.exists(record):
        segs = json.load(open(record))
        peaks = [s["peak"] for s in segs if s["peak"]]
        print(f"{len(segs)} segments: {sum(s['cpu'] for s in segs):.0f} s CPU of the ranks,"
              f" {sum(s['wall'] for s in segs):.0f} s wall" +
              (f", peak memory {max(peaks) / 1e6:.0f} MB ({max(peaks) / n2:.0f} B a grid point)" if peaks else ""))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=4096, help="grid points per side")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks")
    ap.add_argument("--steps", type=int, default=25, help="steps a leg")
    ap.add_argument("--gamma", type=float, default=0.065, help="work of adhesion (E* = 1, spacing 1)")
    ap.add_argument("--cutoff", type=float, default=64.0, help="cut-off wavelength in grid spacings")
    ap.add_argument("--rolloff", type=float, default=256.0, help="roll-off wavelength in grid spacings")
    ap.add_argument("--dir", help="where the results and the checkpoint go (default bench-scale-N)")
    ap.add_argument("--report", action="store_true", help="only the table of what is recorded so far")
    ap.add_argument("extra", nargs="*", help="further adhbem options, after --")
    a = ap.parse_args()
    if a.n % a.rolloff:
        sys.exit(f"bench scale: --n {a.n} must be a multiple of --rolloff {a.rolloff:g}")
    a.dir = os.path.abspath(a.dir or f"bench-scale-{a.n}")
    os.makedirs(a.dir, exist_ok=True)
    results, checkpoint = os.path.join(a.dir, "rough.h5"), os.path.join(a.dir, "rough.ck.h5")
    record = os.path.join(a.dir, "segments.json")
    meta = os.path.join(a.dir, "bench.json")
    mine = dict(n=a.n, steps=a.steps, gamma=a.gamma, cutoff=a.cutoff, rolloff=a.rolloff, extra=a.extra)
    if os.path.exists(meta):  # the options and d1 of the run in DIR
        kept = json.load(open(meta))
        d1 = kept.pop("d1")
        if kept != mine:
            sys.exit(f"bench scale: {a.dir} holds a run with other options ({kept}); give another --dir")
    else:
        d1 = depth(a.n, rolloff_wavelength=a.rolloff, cutoff_wavelength=a.cutoff)
        json.dump(dict(mine, d1=d1), open(meta, "w"))
    if not a.report and not finished(results):
        rc = segment(a, d1, results, checkpoint, record)
        if rc and not finished(results):  # (a stop after the path's end loses nothing)
            report(a, d1, results, record)
            sys.exit(f"bench scale: the run stopped (exit {rc}); the same command goes on from {checkpoint}")
    report(a, d1, results, record)


if __name__ == "__main__":
    main()
