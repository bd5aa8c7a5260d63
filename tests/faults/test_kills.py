"""Processes killed under a running job: one rank of 2 or 3 killed by SIGKILL (a node's
out-of-memory killer, a lost node) ends the whole job within seconds, with a non-zero exit, the
states recorded before readable and the checkpoint restarting to the end; SIGKILL in the middle
of a checkpoint's write leaves the previous checkpoint whole, and it restarts to the curve of an
uninterrupted run. Each job starts its own mpirun, so these tests run serially."""
import os
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import wait_for

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
# a rough periodic cell, 41 states of a few tenths of a second each
ROUGH = ["-adh_n", "128", "-adh_size", "128", "-adh_indenter", "rough", "-adh_boundary", "periodic",
         "-adh_gamma", "0.004", "-adh_start", "adhesive", "-adh_path", "0,1.2,0.3", "-adh_steps", "20",
         "-adh_fftw_planner", "estimate"]
ROUGH_STATES = 41
# a JKR sphere, 21 states, fast
SPHERE = ["-adh_n", "64", "-adh_gamma", "2e-3", "-adh_start", "adhesive", "-adh_path", "0,0.02,-0.03",
          "-adh_steps", "10", "-adh_fftw_planner", "estimate"]
WAIT = 300


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")


def start(cwd, args, ranks, env=ENV):
    out, err = open(cwd / "stdout", "w"), open(cwd / "stderr", "w")
    return subprocess.Popen(["mpirun", "-n", str(ranks), EXE, *args], cwd=cwd, stdout=out, stderr=err, env=env,
                            start_new_session=True)


def ranks_of(mpirun):
    """The live adhbem processes of mpirun's session."""
    pids = []
    for entry in filter(str.isdigit, os.listdir("/proc")):
        try:
            stat = open(f"/proc/{entry}/stat").read()
        except OSError:
            continue
        name, fields = stat[stat.index("(") + 1:stat.rindex(")")], stat[stat.rindex(")") + 2:].split()
        if int(fields[3]) == mpirun and fields[0] != "Z" and int(entry) != mpirun and name == "adhbem":
            pids.append(int(entry))
    return pids


def journal_rows(path):
    try:
        return max(0, open(path).read().count("\n") - 1)
    except OSError:
        return 0


def kill_all(p):
    for pid in ranks_of(p.pid) + [p.pid]:
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    p.wait(timeout=WAIT)


def restart(cwd, args, ranks):
    p = start(cwd, args, ranks)
    try:
        assert p.wait(timeout=WAIT) == 0, open(cwd / "stderr").read()[-2000:]
    except subprocess.TimeoutExpired:
        kill_all(p)
        pytest.fail("the restart did not end")


@pytest.mark.parametrize("ranks", [2, 3])
def test_one_rank_killed(tmp_path, ranks):
    args = [*ROUGH, "-adh_output", "job.h5", "-adh_checkpoint", "ck.h5"]
    p = start(tmp_path, args, ranks)
    wait_for(lambda: journal_rows(tmp_path / "job.csv.part") >= 3, "3 recorded states", p, WAIT)
    victims = ranks_of(p.pid)
    assert len(victims) == ranks
    os.kill(max(victims), signal.SIGKILL)
    killed = time.monotonic()
    try:
        rc = p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        kill_all(p)
        pytest.fail("mpirun did not end within 60 s of a rank's death")
    took = time.monotonic() - killed
    print(f"\n{ranks} ranks: mpirun ended {took:.2f} s after a rank was killed")
    assert rc != 0 and took < 15
    # no rank outlives the job: on a loaded machine the last one may still be exiting when mpirun
    # returns (gone within half a second), so it gets a few seconds, not the job's lifetime
    deadline = time.monotonic() + 5
    while ranks_of(p.pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not ranks_of(p.pid)
    rows = journal_rows(tmp_path / "job.csv.part")
    assert rows >= 3
    with pytest.warns(UserWarning, match=r"job\.h5\.part is: the run was killed"):
        r = adhbem.load(tmp_path / "job.h5")
    with r:
        assert r.params["complete"] == 0 and len(r.curve["d"]) >= rows
        before = {k: v[:rows] for k, v in r.curve.items() if k != "seconds"}
    with h5py.File(tmp_path / "ck.h5", "r") as f:
        assert 1 <= int(f.attrs["states"]) <= ROUGH_STATES
    restart(tmp_path, [*args, "-adh_restart", "ck.h5"], ranks)
    with adhbem.load(tmp_path / "job.h5") as r:
        assert r.params["complete"] == 1 and len(r.curve["d"]) == ROUGH_STATES
        for k, v in before.items():
            assert np.array_equal(r.curve[k][:rows], v), k


def test_sigkill_during_a_checkpoint_write(tmp_path, failwrite):
    """The interposer holds the sixth checkpoint's write (after five were replaced) until the job is
    killed: ck.h5 is the fifth, whole, and the restart from it ends on the uninterrupted curve."""
    ref = tmp_path / "ref"
    ref.mkdir()
    restart(ref, [*SPHERE, "-adh_output", "ref.h5"], 1)
    env = dict(ENV, LD_PRELOAD=failwrite, ADHBEM_FAULT_OP="stall", ADHBEM_FAULT_RENAMES="5",
               ADHBEM_FAULT_PATH="ck.h5", ADHBEM_FAULT_MARK=str(tmp_path / "stalled"))
    args = [*SPHERE, "-adh_output", "job.h5", "-adh_checkpoint", "ck.h5"]
    cmd = ["mpirun", "-n", "1", "-x", "LD_PRELOAD", "-x", "ADHBEM_FAULT_OP", "-x", "ADHBEM_FAULT_RENAMES",
           "-x", "ADHBEM_FAULT_PATH", "-x", "ADHBEM_FAULT_MARK", EXE, *args]
    p = subprocess.Popen(cmd, cwd=tmp_path, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    wait_for(lambda: (tmp_path / "stalled").exists(), "the held checkpoint write", p, WAIT)
    kill_all(p)
    assert (tmp_path / "ck.h5.part").exists()  # the write that was cut
    with h5py.File(tmp_path / "ck.h5", "r") as f:
        assert int(f.attrs["states"]) == 5
    restart(tmp_path, [*args, "-adh_restart", "ck.h5"], 1)
    with adhbem.load(ref / "ref.h5") as a, adhbem.load(tmp_path / "job.h5") as b:
        assert b.params["complete"] == 1
        for k in a.curve:
            if k != "seconds":
                assert np.array_equal(a.curve[k], b.curve[k]), k
