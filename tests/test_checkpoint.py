"""Checkpoint and restart (-adh_checkpoint, -adh_restart): a run stopped by SIGTERM (which ends
the step, writes the checkpoint and the results so far) or killed by SIGKILL goes on from its
checkpoint to the curve of the uninterrupted run: bit for bit on the same number of ranks
(deterministic FFT plans: -adh_fftw_planner estimate), to 1e-10 on another; checkpoints that do
not fit the run, or are damaged, are refused naming the option."""
import os
import signal
import subprocess

import numpy as np
import pytest

from adhbem import PETSc
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
    assert rc != 0 and "Stopped by signal 15" in err and f"-adh_restart {ck}" in err
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
    for bad, says in ((cut, "not a readable HDF5 file"), (results, "not an adhbem checkpoint"),
                      (tmp_path / "none.h5", "cannot read")):
        r = subprocess.run([EXE, *OPTS, "-adh_path", "0,0.9", "-adh_steps", "3", "-adh_restart", str(bad)],
                           capture_output=True, text=True, env=ENV)
        assert r.returncode != 0 and says in r.stderr and "-adh_restart" in r.stderr, r.stderr
