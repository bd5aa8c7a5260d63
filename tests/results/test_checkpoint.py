"""Checkpoint and restart (-adh_checkpoint, -adh_restart): a run stopped by SIGTERM (which abandons
the step in progress and closes the results so far; tests/results/test_stop.py stops jobs through mpirun)
or killed by SIGKILL goes on from its
checkpoint to the curve of the uninterrupted run: bit for bit on the same number of ranks
(deterministic FFT plans: -adh_fftw_planner estimate), to 1e-10 on another; checkpoints that do
not fit the run, or are damaged, are refused naming the option."""
import os
import signal
import sys
import subprocess

import h5py
import numpy as np
import pytest

from adhbem import PETSc
import adhbem_build
from adhbem_build import EXE

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
OPTS = ["-adh_n", "64", "-adh_size", "64", "-adh_indenter", "rough", "-adh_boundary", "periodic", "-adh_gamma", "0.004",
        "-adh_start", "adhesive", "-adh_attach", "reach", "-adh_path", "0,1.2,0.3", "-adh_steps", "8",
        "-adh_fftw_planner", "estimate"]


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")


def adhbem(ranks, *args, **kw):
    return subprocess.run(["mpirun", "-n", str(ranks), EXE, *OPTS, *args], capture_output=True, text=True, env=ENV,
                          timeout=300, **kw)


def curve(path):
    import h5py
    with h5py.File(path, "r") as f:
        return {k: f["curve"][k][()] for k in f["curve"]}, int(f.attrs["complete"])


def stop_after(ranks, states, sig, *args):
    """Runs with -adh_monitor and, once the monitor has printed `states` states, sends sig to
    every rank (as a batch system does; SIGKILL to the whole job, mpirun included)."""
    p = subprocess.Popen(["mpirun", "-n", str(ranks), EXE, *OPTS, "-adh_monitor", *args], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=ENV, start_new_session=True)
    seen = 0
    for line in p.stdout:
        if line.split() and line.split()[0].isdigit():
            seen += 1
            if seen == states:
                if sig == signal.SIGKILL:
                    os.killpg(p.pid, signal.SIGKILL)
                else:
                    ranks_ = subprocess.run(["pgrep", "-P", str(p.pid), "-x", "adhbem"], capture_output=True, text=True)
                    for pid in ranks_.stdout.split():
                        os.kill(int(pid), sig)
                break
    out, err = p.communicate(timeout=300)
    return p.returncode, err


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "full.h5"
    r = adhbem(2, "-adh_output", str(out))
    assert r.returncode == 0, r.stderr[-2000:]
    c, complete = curve(out)
    assert complete == 1 and len(c["d"]) == 17
    return c


def test_sigterm_then_restart(tmp_path, reference):
    serial_only()
    ck, part = tmp_path / "ck.h5", tmp_path / "part.h5"
    rc, err = stop_after(2, 5, signal.SIGTERM, "-adh_checkpoint", str(ck), "-adh_output", str(part))
    assert rc != 0 and "adhbem: stopped by signal 15 after state" in err and f"-adh_restart {ck}" in err
    done, complete = curve(part)
    assert complete == 0 and 5 <= len(done["d"]) < 17
    assert not (tmp_path / "ck.h5.part").exists()
    for k in ("d", "force", "contact_points"):
        assert np.array_equal(done[k], reference[k][:len(done["d"])])
    for ranks in (2, 1):
        out = tmp_path / f"rest{ranks}.h5"
        r = adhbem(ranks, "-adh_restart", str(ck), "-adh_output", str(out))
        assert r.returncode == 0, r.stderr[-2000:]
        c, complete = curve(out)
        assert complete == 1 and len(c["d"]) == len(reference["d"])
        assert np.array_equal(c["contact_points"], reference["contact_points"])
        if ranks == 2:
            for k in ("d", "force", "patches", "mean_gap", "ksp_iterations"):
                assert np.array_equal(c[k], reference[k]), k
        else:
            assert np.max(np.abs(c["force"] - reference["force"])) <= 1e-10 * np.max(np.abs(reference["force"]))


def test_sigkill_then_restart(tmp_path, reference):
    """Killed at a random state (printed), so that any state's checkpoint gets exercised."""
    serial_only()
    import random
    k = random.randint(2, 15)
    print(f"\nSIGKILL after {k} monitored states")
    ck = tmp_path / "ck.h5"
    rc, _ = stop_after(2, k, signal.SIGKILL, "-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "part.h5"))
    assert rc != 0 and ck.exists()
    out = tmp_path / "rest.h5"
    r = adhbem(2, "-adh_restart", str(ck), "-adh_output", str(out))
    assert r.returncode == 0, r.stderr[-2000:]
    c, complete = curve(out)
    assert complete == 1
    for k in ("d", "force", "contact_points", "patches"):
        assert np.array_equal(c[k], reference[k]), k


@pytest.fixture(scope="module")
def checkpoint(tmp_path_factory):
    ck = tmp_path_factory.mktemp("ck") / "ck.h5"
    r = subprocess.run([EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "3", "-adh_checkpoint", str(ck)],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr[-2000:]
    return ck


@pytest.mark.parametrize("args, says", [
    (["-adh_n", "32"], "-adh_n (Nx)"),
    (["-adh_boundary", "free"], "-adh_boundary"),
    (["-adh_gamma", "0.005"], "-adh_gamma"),
    (["-adh_control", "force"], "-adh_control"),
    (["-adh_path", "0,0.8"], "-adh_path"),
    (["-adh_seed", "8"], "-adh_indenter"),
    (["-adh_rms_slope", "0.11"], "-adh_indenter"),
])
def test_restart_with_other_options_is_refused(tmp_path, checkpoint, args, says):
    serial_only()
    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "3", *args, "-adh_restart", str(checkpoint),
                        "-adh_output", str(out)], capture_output=True, text=True, env=ENV)
    assert r.returncode != 0 and says in r.stderr and "-adh_restart" in r.stderr
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


def test_damaged_checkpoints_are_refused(tmp_path, checkpoint):
    serial_only()
    data = checkpoint.read_bytes()
    cut = tmp_path / "cut.h5"
    cut.write_bytes(data[: len(data) // 2])
    results = tmp_path / "results.h5"
    assert subprocess.run([EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "1", "-adh_output", str(results)],
                          capture_output=True, env=ENV).returncode == 0
    # a checkpoint of the version before (another set-update loop, a fixed averaging window)
    older = tmp_path / "older.h5"
    older.write_bytes(data)
    with h5py.File(older, "r+") as f:
        f.attrs["version"] = np.array(6, dtype=f.attrs["version"].dtype)
    for bad, says in ((cut, "not a readable HDF5 file"), (results, "not an adhbem checkpoint"),
                      (tmp_path / "none.h5", "cannot read"), (older, "it has version 6")):
        r = subprocess.run([EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "3", "-adh_restart", str(bad)],
                           capture_output=True, text=True, env=ENV)
        assert r.returncode != 0 and says in r.stderr and "-adh_restart" in r.stderr, r.stderr


class LockedSemaphores:
    """Named POSIX semaphores left locked (value 0), as Open MPI's "sm" shared-file-pointer
    component leaves the one it keys on a file's base name when a job is killed during a write."""

    def __init__(self, names):
        import ctypes
        self.libc = ctypes.CDLL(None, use_errno=True)
        self.libc.sem_open.restype = ctypes.c_void_p
        self.libc.sem_open.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_uint, ctypes.c_uint]
        self.names = [b"/OMPIO_" + n.encode() for n in names]
        for n in self.names:
            self.libc.sem_unlink(n)
            assert self.libc.sem_open(n, os.O_CREAT | os.O_EXCL, 0o644, 0), n

    def remove(self):
        for n in self.names:
            self.libc.sem_unlink(n)


def run_to_end(cmd, cwd, env=ENV):
    """Runs cmd in a session of its own; a run still going after 120 s is killed with its whole
    process group (a hung MPI job) and fails the test."""
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        out, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        pytest.fail(f"{cmd[0]} hung writing its files")
    assert p.returncode == 0, err[-2000:]


def test_a_write_lock_left_by_a_killed_job_does_not_hang(tmp_path):
    """A batch job killed while writing must not hang the next job that writes files of the same
    names: adhbem and its Python layer keep Open MPI from using the semaphores above."""
    serial_only()
    import uuid
    name = uuid.uuid4().hex[:12]
    files = [f"{name}{k}.h5" for k in ("a", "b", "c")]
    locks = LockedSemaphores(f for file in files for f in (file, file + ".part"))
    try:
        short = [*OPTS, "-adh_path", "0,0.6", "-adh_steps", "2"]
        run_to_end([EXE, *short, "-adh_output", files[0], "-adh_checkpoint", "ck" + files[0]], tmp_path)
        run_to_end(["mpirun", "-n", "2", EXE, *short, "-adh_output", files[1]], tmp_path)
        code = ("import adhbem; s = adhbem.Solver(n=32, size=32, indenter='rough', boundary='periodic', gamma=0.004, "
                f"path=[0, 0.6], steps=2); s.solve_path(); s.write({files[2]!r})")
        python = os.path.dirname(os.path.abspath(adhbem_build.__file__))
        run_to_end([sys.executable, "-c", code], tmp_path,
                   dict(ENV, PYTHONPATH=os.pathsep.join([python, os.environ.get("PYTHONPATH", "")])))
    finally:
        locks.remove()
    for f in files:
        assert (tmp_path / f).exists() and not (tmp_path / (f + ".part")).exists()


def test_restart_of_a_checkpoint_from_before_the_default_route(tmp_path):
    """A checkpoint without the -adh_cascade_local attribute was written when the exact cascade was
    every run's route: a restart with crack-closure's default route (local solves on the whole
    grid) is refused, naming -adh_cascade_local 0, and goes on with it."""
    serial_only()
    ck = tmp_path / "ck.h5"
    run = [EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "3", "-adh_criterion", "crack-closure"]
    r = subprocess.run([*run, "-adh_cascade_local", "0", "-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(ck, "r+") as f:
        assert float(f.attrs["-adh_cascade_local"]) == 0
        del f.attrs["-adh_cascade_local"]
    r = subprocess.run([*run, "-adh_restart", str(ck), "-adh_output", str(tmp_path / "x.h5")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode != 0 and "has -adh_cascade_local 0, this run inf" in r.stderr, r.stderr[-2000:]
    r = subprocess.run([*run, "-adh_cascade_local", "0", "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr[-2000:]


@pytest.mark.parametrize("changed, option", [
    (["-adh_criterion_radius", "12"], "-adh_criterion_radius"),
    (["-adh_criterion_radius_max", "32"], "-adh_criterion_radius_max"),
    (["-adh_attach", "penetration"], "-adh_attach"),
    (["-adh_critical_stress", "0.5"], "-adh_critical_stress"),
    (["-adh_cascade_apart", "8"], "-adh_cascade_apart"),
    (["-adh_cascade_local", "3"], "-adh_cascade_local"),
    (["-adh_cascade_local", "0"], "-adh_cascade_local"),
])
def test_restart_that_changes_the_answer_is_refused(tmp_path, changed, option):
    """What shapes the answer besides the problem (crack-closure's averaging radii, the attach
    rule, a fixed critical stress, the route through the cascade) must be repeated by a restart, which names the option (and one
    that repeats them goes on). The results file records them."""
    serial_only()
    ck = tmp_path / "ck.h5"
    run = [EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "3", "-adh_criterion", "crack-closure"]
    r = subprocess.run([*run, "-adh_checkpoint", str(ck), "-adh_output", str(tmp_path / "a.h5")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(tmp_path / "a.h5", "r") as f:
        assert f.attrs["attach"] == "reach" and "critical_stress" not in f.attrs
        assert float(f.attrs["criterion_radius"]) == 16 and float(f.attrs["criterion_radius_max"]) == 64
        # crack-closure's default route: local solves on the whole grid
        assert int(f.attrs["cascade_apart"]) == 0 and float(f.attrs["cascade_local"]) == np.inf
        assert float(f.attrs["cascade_local_rtol"]) == 1e-3
    r = subprocess.run([*run, *changed, "-adh_restart", str(ck), "-adh_output", str(tmp_path / "x.h5")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode != 0 and f"has {option} " in r.stderr and "-adh_restart" in r.stderr, r.stderr[-2000:]
    assert not (tmp_path / "x.h5").exists()
    r = subprocess.run([*run, "-adh_restart", str(ck), "-adh_output", str(tmp_path / "b.h5")],
                       capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr[-2000:]
