"""Long jobs under mpirun and batch systems lose nothing: a stop through mpirun (Ctrl-C, which the
terminal sends to mpirun's process group, or SIGTERM to mpirun, as a batch system's time limit
and scancel do: mpirun passes SIGTERM on to the ranks and kills them a second later) ends the
path within the step in progress, closes the results (complete = 0, the CSV, no lock files) and
says so in one line; SIGKILL of every process of the job leaves FILE.h5.part and FILE.csv.part
readable up to the last state recorded; a restart from the checkpoint goes on in the same
results file, keeping the earlier states' fields, to the uninterrupted run's curve and fields.

The jobs run under mpirun on 2 ranks in a session of their own; the tests poll the journal
(FILE.csv.part) or the monitor's lines and allow minutes on a slow, shared machine."""
import os
import re
import signal
import subprocess
import time
import warnings

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import wait_for

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
# 41 states of a rough periodic cell, a few tenths of a second each on 2 ranks
JOB = ["-adh_n", "128", "-adh_size", "128", "-adh_indenter", "rough", "-adh_boundary", "periodic",
       "-adh_gamma", "0.004", "-adh_start", "adhesive", "-adh_path", "0,1.2,0.3", "-adh_steps", "20",
       "-adh_fftw_planner", "estimate", "-adh_fields", "pressure,contact"]
STATES = 41
WAIT = 600  # seconds: the longest any job may take here
STOP = re.compile(r"adhbem: stopped by signal (\d+) after state (\d+) \(([0-9.]+) s after the signal\); "
                  r"results up to it in (\S+) \(complete = 0\); go on with the same options and -adh_restart (\S+)")


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")


def start(tmp_path, *args, ranks=2):
    """mpirun -n ranks adhbem in tmp_path, in a session of its own (as a batch job's)."""
    out = open(tmp_path / "stdout", "w")
    err = open(tmp_path / "stderr", "w")
    return subprocess.Popen(["mpirun", "-n", str(ranks), EXE, *args], cwd=tmp_path, stdout=out, stderr=err, env=ENV,
                            start_new_session=True)


def session(pid):
    """The processes of the session that pid leads: mpirun and its ranks (each rank has a process
    group of its own, so mpirun's group is not enough)."""
    pids = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                stat = open(f"/proc/{entry}/stat").read()
            except OSError:
                continue
            fields = stat[stat.rindex(")") + 2:].split()
            if int(fields[3]) == pid and fields[0] != "Z":  # a killed rank stays a zombie until reaped
                pids.append(int(entry))
    return pids


def journal_rows(path):
    """Complete rows of the CSV journal so far."""
    try:
        text = open(path).read()
    except OSError:
        return 0
    return max(0, text.count("\n") - 1)


def finish(p):
    try:
        return p.wait(timeout=WAIT)
    except subprocess.TimeoutExpired:
        for pid in session(p.pid):
            os.kill(pid, signal.SIGKILL)
        pytest.fail("the job did not end")


def csv_curve(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {k: np.atleast_1d(data[k]) for k in data.dtype.names if k != "step"}


def leftovers(tmp_path, expected):
    """Files beside the results that should not be there (MPI-IO lock and data files, parts)."""
    return sorted(p.name for p in tmp_path.iterdir() if p.name not in expected)


def assert_curves_equal(a, b, rows=None):
    for k in a:
        if k not in ("seconds", "path"):
            assert np.array_equal(a[k][:rows], b[k][:rows]), k


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The uninterrupted job: its curve and fields."""
    d = tmp_path_factory.mktemp("reference")
    p = start(d, *JOB, "-adh_output", "ref.h5")
    assert finish(p) == 0, open(d / "stderr").read()[-2000:]
    with adhbem.load(d / "ref.h5") as r:
        assert r.params["complete"] == 1 and len(r.curve["d"]) == STATES
        return r.curve, {s: (r.field("pressure", s), r.field("contact", s)) for s in r.states}


def restart_and_compare(tmp_path, reference, kept):
    """The same options and -adh_restart: the run goes on in job.h5, which ends with every state's
    fields, the earlier ones kept; curve and fields are the uninterrupted run's, bit for bit."""
    p = start(tmp_path, *JOB, "-adh_output", "job.h5", "-adh_checkpoint", "ck.h5", "-adh_restart", "ck.h5")
    assert finish(p) == 0, open(tmp_path / "stderr").read()[-2000:]
    said = open(tmp_path / "stdout").read()
    assert re.search(r"adhbem: restart after state \d+: job.h5 goes on, with the curve and the fields of the earlier "
                     r"states \((\d+) frames\)", said), said[:2000]
    assert int(re.search(r"\((\d+) frames\)", said).group(1)) >= kept
    curve, fields = reference
    with adhbem.load(tmp_path / "job.h5") as r:
        assert r.params["complete"] == 1
        assert_curves_equal(curve, r.curve)
        assert list(r.states) == list(range(STATES))
        for s in r.states:
            assert np.array_equal(r.field("pressure", s), fields[s][0]), s
            assert np.array_equal(r.field("contact", s), fields[s][1]), s
    assert_curves_equal(curve, csv_curve(tmp_path / "job.csv"))
    assert leftovers(tmp_path, {"job.h5", "job.csv", "job.xmf", "ck.h5", "stdout", "stderr"}) == []


@pytest.mark.parametrize("how", ["ctrl-c", "sigterm"])
def test_stop_through_mpirun(tmp_path, reference, how):
    """Ctrl-C (SIGINT to mpirun's process group) or SIGTERM to mpirun, after a few states: the ranks
    get SIGTERM from mpirun a second later and must have closed everything before its SIGKILL, a
    second after that."""
    serial_only()
    p = start(tmp_path, *JOB, "-adh_output", "job.h5", "-adh_checkpoint", "ck.h5")
    wait_for(lambda: journal_rows(tmp_path / "job.csv.part") >= 3, "3 recorded states", p)
    sent = time.monotonic()
    if how == "ctrl-c":
        os.killpg(p.pid, signal.SIGINT)
    else:
        os.kill(p.pid, signal.SIGTERM)
    rc = finish(p)
    ended = time.monotonic() - sent
    err = open(tmp_path / "stderr").read()
    m = STOP.search(err)
    assert rc != 0 and m, err[-3000:]
    sig, last, took = int(m.group(1)), int(m.group(2)), float(m.group(3))
    print(f"\n{how}: stopped after state {last}, {took:.3f} s after the ranks' signal; mpirun ended {ended:.2f} s "
          "after the signal was sent")
    assert sig == signal.SIGTERM and m.group(4) == "job.h5" and m.group(5) == "ck.h5"
    assert took < 0.5  # well within mpirun's second
    assert sum("adhbem:" in line for line in err.splitlines()) == 1
    # the results: whole up to the last state, closed, and nothing else left beside them
    assert leftovers(tmp_path, {"job.h5", "job.csv", "job.xmf", "ck.h5", "stdout", "stderr"}) == []
    with adhbem.load(tmp_path / "job.h5") as r:
        assert r.params["complete"] == 0 and len(r.curve["d"]) == last + 1
        assert list(r.states) == list(range(last + 1))
        assert_curves_equal(reference[0], r.curve, last + 1)
        assert_curves_equal(r.curve, csv_curve(tmp_path / "job.csv"))
    with h5py.File(tmp_path / "ck.h5", "r") as f:
        assert int(f.attrs["states"]) == last + 1
    restart_and_compare(tmp_path, reference, last + 1)


def test_sigkill_of_every_process(tmp_path, reference):
    """SIGKILL of mpirun and every rank (a node lost, a batch system's hard kill): job.h5.part and
    job.csv.part hold every state recorded, adhbem.load("job.h5") reads them, no lock files are
    left, and the restart goes on in the same file."""
    serial_only()
    p = start(tmp_path, *JOB, "-adh_output", "job.h5", "-adh_checkpoint", "ck.h5")
    wait_for(lambda: journal_rows(tmp_path / "job.csv.part") >= 5, "5 recorded states", p)
    procs = session(p.pid)
    assert len(procs) >= 3  # mpirun and two ranks
    for pid in procs:
        os.kill(pid, signal.SIGKILL)
    p.wait(timeout=WAIT)
    time.sleep(0.2)
    assert not session(p.pid)
    rows = journal_rows(tmp_path / "job.csv.part")
    assert rows >= 5
    assert leftovers(tmp_path, {"job.h5.part", "job.csv.part", "ck.h5", "ck.h5.part", "stdout", "stderr"}) == []
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        r = adhbem.load(tmp_path / "job.h5")
    assert any("job.h5.part" in str(w.message) for w in said)
    with r:
        n = len(r.curve["d"])
        assert r.params["complete"] == 0 and n >= rows  # the HDF5 file is flushed before the journal is synced
        assert_curves_equal(reference[0], r.curve, n)
        assert list(r.states) == list(range(len(r.states))) and len(r.states) >= n - 1
        for s in r.states:
            assert np.array_equal(r.field("pressure", s), reference[1][s][0])
    assert_curves_equal(reference[0], csv_curve(tmp_path / "job.csv.part"), rows)
    restart_and_compare(tmp_path, reference, 1)


@pytest.mark.parametrize("route", [["-adh_cascade_local", "0"], [], ["-adh_cascade_local", "3"]], ids=["exact", "default", "local"])
def test_stop_within_a_step(tmp_path, route):
    """SIGTERM to the ranks while a step runs (after its first set update): the step is abandoned
    at once, the results end with the state before it, and a restart computes it; with the exact
    cascade, the default route (local solves on the whole grid) and a window of -adh_cascade_local,
    where the signal may come inside a local solve (and the restart checks the checkpoint's route)."""
    serial_only()
    job = ["-adh_n", "256", "-adh_size", "256", "-adh_indenter", "rough", "-adh_boundary", "periodic",
           "-adh_gamma", "0.004", "-adh_start", "adhesive", "-adh_path", "0,2.0,0.3", "-adh_steps", "1",
           "-adh_fftw_planner", "estimate", "-adh_fields", "pressure", "-adh_output", "job.h5",
           "-adh_checkpoint", "ck.h5", "-adh_monitor", "-adh_monitor_interval", "0", *route]
    p = start(tmp_path, *job)
    # a progress line after state 0's line: step 1 is under way
    wait_for(lambda: re.search(r"^    0 .*\n +\.\.\. d = 2", open(tmp_path / "stdout").read(), re.M), "step 1", p)
    for pid in session(p.pid):
        if pid != p.pid:
            os.kill(pid, signal.SIGTERM)
    assert finish(p) != 0
    err = open(tmp_path / "stderr").read()
    m = STOP.search(err)
    assert m and m.group(2) == "0", err[-3000:]
    with adhbem.load(tmp_path / "job.h5") as r:
        assert len(r.curve["d"]) == 1 and list(r.states) == [0] and r.params["complete"] == 0
    p = start(tmp_path, *job, "-adh_restart", "ck.h5")
    assert finish(p) == 0, open(tmp_path / "stderr").read()[-2000:]
    with adhbem.load(tmp_path / "job.h5") as r:
        assert len(r.curve["d"]) == 3 and list(r.states) == [0, 1, 2] and r.params["complete"] == 1


# ---- A restart goes on in the results of the run it continues ---------------------------------------

SMALL = dict(n=64, size=64, indenter="rough", boundary="periodic", gamma=0.004, start="adhesive",
             path="0,0.9,0.3", steps=4, fftw_planner="estimate")


def small_args(**more):
    opts = dict(SMALL, **more)
    return [a for k, v in opts.items() for a in (f"-adh_{k}", str(v))]


def stopped(tmp_path, at, output="job.h5", fields="pressure,contact"):
    """A run stopped by SIGTERM after state `at` (sent by a monitor: the stop comes between states),
    with its checkpoint ck.h5 and its results `output`, complete = 0."""
    s = adhbem.Solver(**SMALL, output=str(tmp_path / output), checkpoint=str(tmp_path / "ck.h5"), fields=fields)
    s.monitor(lambda step, state: os.kill(os.getpid(), signal.SIGTERM) if step == at else None)
    with pytest.raises(KeyboardInterrupt) as e:
        s.solve_path()
    assert f"stopped by signal 15 after state {at} " in str(e.value), str(e.value)
    with adhbem.load(tmp_path / output) as r:
        assert r.params["complete"] == 0 and len(r.curve["d"]) == at + 1
        return r.curve, list(r.states)


def restart(tmp_path, *args):
    return subprocess.run([EXE, *small_args(), "-adh_checkpoint", "ck.h5", "-adh_restart", "ck.h5", *args], cwd=tmp_path,
                          capture_output=True, text=True, env=ENV, timeout=WAIT)


@pytest.fixture(scope="module")
def small_reference(tmp_path_factory):
    d = tmp_path_factory.mktemp("small")
    r = subprocess.run([EXE, *small_args(), "-adh_fields", "pressure,contact", "-adh_output", "ref.h5"], cwd=d,
                       capture_output=True, text=True, env=ENV, timeout=WAIT)
    assert r.returncode == 0, r.stderr[-2000:]
    with adhbem.load(d / "ref.h5") as f:
        return f.curve, {s: f.field("pressure", s) for s in f.states}


def test_restart_keeps_the_earlier_fields(tmp_path, small_reference):
    """The stopped run's job.h5 (complete = 0, fields of states 0-3) goes on: the restart appends to
    it, and it ends with every state's fields, the earlier ones as they were; one line says so.
    (The stopped run ran in this process, whose FFTW may hold wisdom from other tests: its states
    are the uninterrupted run's to rounding, the restart's to the last bit.)"""
    serial_only()
    before, _ = stopped(tmp_path, 3)
    with adhbem.load(tmp_path / "job.h5") as f:
        earlier = {s: f.field("pressure", s) for s in f.states}
    r = restart(tmp_path, "-adh_fields", "pressure,contact", "-adh_output", "job.h5")
    assert r.returncode == 0, r.stderr[-2000:]
    assert "adhbem: restart after state 3: job.h5 goes on, with the curve and the fields of the earlier states (4 frames)" in r.stdout
    curve, fields = small_reference
    with adhbem.load(tmp_path / "job.h5") as f:
        assert f.params["complete"] == 1
        assert_curves_equal(before, f.curve, 4)
        for k in curve:
            if k not in ("seconds", "path"):
                np.testing.assert_allclose(f.curve[k], curve[k], rtol=1e-9, atol=1e-12, err_msg=k)
        assert list(f.states) == list(range(len(curve["d"])))
        for s in f.states:
            if s < 4:
                assert np.array_equal(f.field("pressure", s), earlier[s]), s
            np.testing.assert_allclose(f.field("pressure", s), fields[s], rtol=1e-9, atol=1e-12 * np.abs(fields[s]).max())
    assert_curves_equal(f.curve, csv_curve(tmp_path / "job.csv"))
    xmf = open(tmp_path / "job.xmf").read()
    assert xmf.count('<Grid Name="state ') == len(curve["d"])


def test_restart_into_another_file_says_where_the_fields_are(tmp_path):
    """-adh_output other.h5 on the restart: other.h5 has the whole curve, the fields after the
    checkpoint, and the line names the earlier file, which stays as it was."""
    serial_only()
    before, states = stopped(tmp_path, 2)
    r = restart(tmp_path, "-adh_fields", "pressure,contact", "-adh_output", "other.h5")
    assert r.returncode == 0, r.stderr[-2000:]
    said = [line for line in r.stdout.splitlines() if line.startswith("adhbem: restart")]
    assert said == [f"adhbem: restart after state 2: other.h5 has the curve from state 0 and the fields from state 3 on; "
                    f"those of the earlier states are in the earlier run's {tmp_path / 'job.h5'}"], r.stdout
    with adhbem.load(tmp_path / "other.h5") as f:
        assert f.params["complete"] == 1 and list(f.states) == list(range(3, len(f.curve["d"])))
        assert_curves_equal(before, f.curve, 3)
    with adhbem.load(tmp_path / "job.h5") as f:
        assert f.params["complete"] == 0 and list(f.states) == states
        assert_curves_equal(before, f.curve)


def test_restart_with_other_fields_is_refused(tmp_path):
    """A restart that writes other fields than the file it would go on in is refused at set-up,
    naming -adh_fields, and leaves that file as it was."""
    serial_only()
    before, states = stopped(tmp_path, 2)
    r = restart(tmp_path, "-adh_fields", "pressure", "-adh_output", str(tmp_path / "job.h5"))
    assert r.returncode != 0
    lines = [line for line in r.stderr.splitlines() if line.startswith("adhbem")]
    assert len(lines) == 1 and "-adh_fields" in lines[0] and "pressure,contact" in lines[0], r.stderr[-2000:]
    assert not (tmp_path / "job.h5.part").exists()
    with adhbem.load(tmp_path / "job.h5") as f:
        assert f.params["complete"] == 0 and list(f.states) == states
        assert_curves_equal(before, f.curve)


@pytest.mark.parametrize("earlier", ["missing", "damaged"])
def test_restart_without_readable_earlier_results(tmp_path, earlier):
    """The earlier results gone, or cut short by a kill so that HDF5 cannot open them: the restart
    writes a new file with the whole curve and says that the earlier fields were not there."""
    serial_only()
    stopped(tmp_path, 2)
    if earlier == "missing":
        os.remove(tmp_path / "job.h5")
    else:
        data = (tmp_path / "job.h5").read_bytes()
        os.remove(tmp_path / "job.h5")
        (tmp_path / "job.h5.part").write_bytes(data[: len(data) // 3])
    r = restart(tmp_path, "-adh_fields", "pressure,contact", "-adh_output", "job.h5")
    assert r.returncode == 0, r.stderr[-2000:]
    said = [line for line in r.stdout.splitlines() if line.startswith("adhbem: restart")]
    assert len(said) == 1 and "has the curve from state 0 and the fields from state 3 on" in said[0], r.stdout
    assert ("could not be read" in said[0]) == (earlier == "damaged")
    with adhbem.load(tmp_path / "job.h5") as f:
        assert f.params["complete"] == 1 and list(f.states) == list(range(3, len(f.curve["d"])))
