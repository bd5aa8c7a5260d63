"""./run bench scale runs a path of hours to its end across kills: stopped by SIGTERM to its mpirun
(a batch system's time limit), the same command goes on from the last checkpoint, to the curve
of an uninterrupted run; called once more it runs nothing, and with other options it is refused.
On a 128^2 cell of one roll-off wavelength, ./run rough's surface and dgamma, 6 steps a leg (up to
19 states, a few seconds a run: the stop must come before the path's end)."""
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from adhbem import PETSc

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH = [sys.executable, os.path.join(ROOT, "bench", "scale.py"), "--n", "128", "--rolloff", "128", "--steps", "6",
         "--cutoff", "32", "--gamma", "0.209",
         "--np", "2"]
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
PLANNER = ["--", "-adh_fftw_planner", "estimate"]  # bit-reproducible transforms: the curves compare exactly
sys.path.insert(0, os.path.join(ROOT, "bench"))
import scale  # noqa: E402  (the benchmark's helpers: numpy only at import)

WAIT = 600  # seconds: the longest a run may take on a slow, shared machine


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")


def bench(directory, *more):
    return subprocess.run(BENCH + ["--dir", str(directory), *more] + PLANNER, capture_output=True, text=True, env=ENV,
                          timeout=WAIT)


def curve(directory):
    return np.genfromtxt(os.path.join(directory, "rough.csv"), delimiter=",", names=True)


def segments(directory):
    return json.load(open(os.path.join(directory, "segments.json")))


def test_bench_scale_goes_on_after_a_kill(tmp_path):
    ref = bench(tmp_path / "ref")
    assert ref.returncode == 0, ref.stdout[-2000:] + ref.stderr[-2000:]
    reference = curve(tmp_path / "ref")
    states = len(reference)
    assert states > 6 and f"| all | {states} |" in ref.stdout and "(the run is not finished)" not in ref.stdout

    # stopped through mpirun once the second state is recorded (state 0 and the first checkpoint)
    run = tmp_path / "run"
    p = subprocess.Popen(BENCH + ["--dir", str(run)] + PLANNER, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         env=ENV, start_new_session=True)
    journal, t0 = run / "rough.csv.part", time.time()
    while not (journal.exists() and len(journal.read_text().splitlines()) >= 3):
        assert p.poll() is None and time.time() - t0 < WAIT, "the run ended before its second state"
        time.sleep(0.05)
    (mpirun, _), = scale.children(p.pid, "mpirun")
    os.kill(mpirun, signal.SIGTERM)
    out = p.communicate(timeout=WAIT)[0]
    assert p.returncode != 0 and "the same command goes on from" in out, out[-2000:]
    assert "(the run is not finished)" in out, out[-3000:]
    recorded = len(np.atleast_1d(np.genfromtxt(run / "rough.csv", delimiter=",", names=True)))
    assert 2 <= recorded < states

    again = bench(run)
    assert again.returncode == 0, again.stdout[-2000:] + again.stderr[-2000:]
    assert "-adh_restart" in again.stdout
    resumed = curve(run)
    assert len(resumed) == len(reference)
    for name in ("d", "force", "area", "outer_iterations", "fft_pairs"):
        np.testing.assert_array_equal(resumed[name], reference[name], err_msg=name)
    assert [s["restart"] for s in segments(run)] == [False, True]
    assert segments(run)[0]["exit"] != 0 and segments(run)[1]["exit"] == 0
    assert segments(run)[0]["cpu"] > 0.2  # the killed ranks' time, not lost with them

    done = bench(run)  # finished: the table again, no run
    assert done.returncode == 0 and "mpirun" not in done.stdout and f"| all | {states} |" in done.stdout
    assert len(segments(run)) == 2

    other = bench(run, "--gamma", "0.1")
    assert other.returncode != 0 and "holds a run with other options" in other.stderr
