"""A disk that fills up or fails under a running job: one line that names the file and the cause
("No space left on device"), a non-zero exit and no signal, HDF5's error stack not printed, and
every state written before still readable from FILE.h5.part and FILE.csv.part; a checkpoint that
cannot be written leaves the previous one whole, and it restarts.

The full disk comes from failwrite.c, an LD_PRELOAD interposer (built here) that fails the writes,
reservations and renames of the files whose path holds a pattern after a budget of bytes, and
once from a real 3 MB tmpfs where the machine lets root mount one. Each job starts its own
mpirun, so these tests run serially."""
import os
import re
import subprocess
import sys

import h5py
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
# a JKR sphere, 21 states with their fields (about 100 kB a state)
JOB = ["-adh_n", "64", "-adh_radius", "1", "-adh_gamma", "2e-3", "-adh_start", "adhesive",
       "-adh_path", "0,0.02,-0.03", "-adh_steps", "10", "-adh_fields", "-adh_fftw_planner", "estimate"]
STATES = 21
KEPT = re.compile(r"the (\d+) states written before are in (\S+) and (\S+) \(adhbem.load reads them\)")


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")


def run(cwd, *args, ranks=1, fault=None, lib=None):
    """adhbem under mpirun in cwd; fault: (errno name, bytes, path pattern[, op]) for the interposer."""
    cmd = ["mpirun", "-n", str(ranks)]
    if fault:
        errno, after, pattern, *op = fault
        for name, value in [("LD_PRELOAD", lib), ("ADHBEM_FAULT_ERRNO", errno), ("ADHBEM_FAULT_AFTER", str(after)),
                            ("ADHBEM_FAULT_PATH", pattern), ("ADHBEM_FAULT_OP", op[0] if op else "write")]:
            cmd += ["-x", f"{name}={value}"]
    p = subprocess.run(cmd + [EXE, *JOB, *args], cwd=cwd, env=ENV, capture_output=True, text=True, timeout=300)
    return p


def error_lines(p):
    lines = [line for line in p.stderr.splitlines() + p.stdout.splitlines() if line.startswith("adhbem: error")]
    return lines


def check_failed_cleanly(p, says):
    """A non-zero exit, no signal, one error line (matching says), no HDF5 stack; the line."""
    assert p.returncode not in (0, 124) and p.returncode < 128, (p.returncode, p.stderr[-2000:])
    assert "HDF5-DIAG" not in p.stderr and "PETSC ERROR" not in p.stderr, p.stderr[-2000:]
    assert "MPI_ABORT" not in p.stderr and "Segmentation" not in p.stderr, p.stderr[-2000:]
    lines = error_lines(p)
    assert len(lines) == 1, p.stderr[-2000:]
    assert re.search(says, lines[0]), lines[0]
    return lines[0]


def check_kept(cwd, line, ahead=0):
    """The states the error says were written are in FILE.h5.part and FILE.csv.part, whole (every
    column as long). ahead: how many states more the ranks that did not fail may have written
    (a rank that fails alone knows only its own writes)."""
    m = KEPT.search(line)
    assert m, line
    n = int(m.group(1))
    assert 0 < n < STATES
    r = adhbem.load(str(cwd / m.group(2)))
    assert n <= len(r.curve["d"]) <= n + ahead
    assert {len(v) for v in r.curve.values()} == {len(r.curve["d"])}
    with open(cwd / m.group(3)) as f:
        assert n + 1 <= len(f.read().splitlines()) <= n + 1 + ahead  # the header and n rows
    return n


@pytest.mark.parametrize("ranks", [1, 2])
def test_full_disk_while_writing_fields(tmp_path, failwrite, ranks):
    p = run(tmp_path, "-adh_output", "out.h5", ranks=ranks, fault=("ENOSPC", 3_000_000, "out.h5"), lib=failwrite)
    # the fields or, when they fitted, the curve's rows after them
    line = check_failed_cleanly(p, r"^adhbem: error: -adh_output: cannot write (the fields of state \d+ to )?out\.h5\.part: "
                                   r"No space left on device; ")
    n = check_kept(tmp_path, line)
    with h5py.File(tmp_path / "out.h5.part", "r") as f:
        assert f.attrs["complete"] == 0
        assert len(f["fields/state"]) == n
    assert not (tmp_path / "out.h5").exists()


def test_full_disk_before_the_first_state(tmp_path, failwrite):
    p = run(tmp_path, "-adh_output", "out.h5", ranks=2, fault=("ENOSPC", 0, "out.h5"), lib=failwrite)
    check_failed_cleanly(p, r"^adhbem: error: -adh_output: cannot write out\.h5\.part: No space left on device$")
    assert not (tmp_path / "out.h5.part").exists() and not (tmp_path / "out.h5").exists()


def test_full_disk_at_the_final_rename(tmp_path, failwrite):
    p = run(tmp_path, "-adh_output", "out.h5", ranks=2, fault=("ENOSPC", 0, "out.h5", "rename"), lib=failwrite)
    line = check_failed_cleanly(p, r"^adhbem: error: -adh_output: could not move out\.h5\.part to out\.h5: No space left on device; ")
    assert int(KEPT.search(line).group(1)) == STATES
    assert len(adhbem.load(str(tmp_path / "out.h5.part")).curve["d"]) == STATES


def test_full_disk_at_a_checkpoint_keeps_the_previous_one(tmp_path, failwrite):
    # the first checkpoints fit, a later one does not
    p = run(tmp_path, "-adh_output", "out.h5", "-adh_checkpoint", "ck.h5", ranks=2,
            fault=("ENOSPC", 2_500_000, "ck.h5"), lib=failwrite)
    line = check_failed_cleanly(p, r"^adhbem: error: -adh_checkpoint: cannot write ck\.h5\.part: No space left on device; "
                                   r"the checkpoint ck\.h5 of state (\d+) is kept, whole$")
    state = int(re.search(r"of state (\d+)", line).group(1))
    assert not (tmp_path / "ck.h5.part").exists()
    # the results up to the failure are there, marked incomplete
    with h5py.File(tmp_path / "out.h5", "r") as f:
        assert f.attrs["complete"] == 0
    # and the run goes on from the kept checkpoint to the end
    p = run(tmp_path, "-adh_output", "out.h5", "-adh_checkpoint", "ck.h5", "-adh_restart", "ck.h5", ranks=2)
    assert p.returncode == 0, p.stderr[-2000:]
    assert f"restart after state {state}" in p.stdout
    assert len(adhbem.load(str(tmp_path / "out.h5")).curve["d"]) == STATES


def test_io_error_on_one_rank(tmp_path, failwrite):
    """EIO (not prevented by a reservation): one line naming the file and MPI-IO's words, no signal."""
    p = run(tmp_path, "-adh_output", "out.h5", ranks=1, fault=("EIO", 300_000, "out.h5"), lib=failwrite)
    check_failed_cleanly(p, r"^adhbem: error: -adh_output: cannot write out\.h5\.part: .*input/output error")


@pytest.mark.parametrize("ranks", [2, 3])
def test_io_error_on_some_ranks(tmp_path, failwrite, ranks):
    """EIO that the ranks meet at different writes (each has its own budget of bytes): parallel HDF5
    cannot go on, so the rank that failed alone says so in one line and ends the job, within the
    wait of ADHBEM_ERROR_WAIT; the states written before load from the parts, whole (the ranks that
    did not fail may have written one more)."""
    p = run(tmp_path, "-adh_output", "out.h5", ranks=ranks, fault=("EIO", 1_000_000, "out.h5"), lib=failwrite)
    line = check_failed_cleanly(p, r"^adhbem: error: -adh_output: cannot write out\.h5\.part: .*input/output error'?, "
                                   rf"on rank \d of {ranks} alone \(parallel HDF5 cannot go on")
    check_kept(tmp_path, line, ahead=1)


@pytest.mark.parametrize("ranks", [1, 2, 3])
def test_io_error_on_the_first_write(tmp_path, failwrite, ranks):
    """EIO before the file's first flush (its superblock), on every rank: one line, no MPI_Abort, no hang."""
    p = run(tmp_path, "-adh_output", "out.h5", ranks=ranks, fault=("EIO", 0, "out.h5"), lib=failwrite)
    check_failed_cleanly(p, r"^adhbem: error: -adh_output: cannot write out\.h5\.part: .*input/output error.*; no state was written")
    assert not list(tmp_path.glob("out*")), "a file that holds no state is not left behind"


def test_io_error_on_the_first_write_from_python(tmp_path, failwrite):
    """The same from a script on 2 ranks: the exception, told once, and status 1 on every rank."""
    script = tmp_path / "job.py"
    script.write_text("import adhbem\n"
                      "adhbem.Solver(n=64, radius=1, gamma=2e-3, steps=4, output='out.h5').solve_path()\n")
    cmd = ["mpirun", "-n", "2", "-x", "PYTHONPATH"]
    for name, value in [("LD_PRELOAD", failwrite), ("ADHBEM_FAULT_ERRNO", "EIO"), ("ADHBEM_FAULT_AFTER", "0"),
                        ("ADHBEM_FAULT_PATH", "out.h5"), ("ADHBEM_FAULT_OP", "write")]:
        cmd += ["-x", f"{name}={value}"]
    p = subprocess.run(cmd + [sys.executable, str(script)], cwd=tmp_path, env=ENV, capture_output=True, text=True, timeout=120)
    assert p.returncode == 1, p.stderr[-2000:]
    assert "MPI_ABORT" not in p.stderr and "alone" not in p.stderr, p.stderr[-2000:]
    assert p.stderr.count("Traceback") == 1, p.stderr[-2000:]
    assert re.search(r"^OSError: -adh_output: cannot write out\.h5\.part: .*input/output error", p.stderr, re.M), p.stderr[-2000:]
    assert not list(tmp_path.glob("out*"))


@pytest.mark.parametrize("ranks,after", [(1, 100_000), (2, 100_000), (3, 100_000), (2, 0), (3, 0)])
def test_io_error_on_a_checkpoint(tmp_path, failwrite, ranks, after):
    """EIO in a checkpoint after some bytes (a rank fails alone) or on the first write (all do):
    one line, and the checkpoint's part removed."""
    p = run(tmp_path, "-adh_output", "out.h5", "-adh_checkpoint", "ck.h5", ranks=ranks, fault=("EIO", after, "ck.h5"), lib=failwrite)
    check_failed_cleanly(p, r"^adhbem: error: -adh_checkpoint: cannot write ck\.h5\.part: .*input/output error")
    assert not (tmp_path / "ck.h5.part").exists()


@pytest.fixture
def small_disk(tmp_path):
    """A 3 MB tmpfs (root only; skipped where mounting is not allowed)."""
    mnt = tmp_path / "disk"
    mnt.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=3m", "tmpfs", str(mnt)],
                                            capture_output=True).returncode:
        pytest.skip("cannot mount a small tmpfs here")
    yield mnt
    subprocess.run(["umount", str(mnt)], check=False)


def test_a_real_full_disk(small_disk):
    """The issue's case: a 128^2 sphere writing its fields into a 3 MB file system, on 2 ranks."""
    out = small_disk / "out.h5"
    p = run(small_disk, "-adh_n", "128", "-adh_output", str(out), ranks=2)
    line = check_failed_cleanly(p, rf"^adhbem: error: -adh_output: cannot write (the fields of state \d+ to )?{out}\.part: "
                                   r"No space left on device; ")
    n = int(KEPT.search(line).group(1))
    assert len(adhbem.load(str(out) + ".part").curve["d"]) == n
    # what the reservation took beyond the file's end is given back
    assert os.stat(str(out) + ".part").st_blocks * 512 <= os.path.getsize(str(out) + ".part") + 2 * 4096
