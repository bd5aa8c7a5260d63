"""Damaged files a batch job meets: topography and dgamma maps cut short or overwritten, results
files cut short, checkpoints with damaged bytes inside their data (which HDF5 does not check:
adhbem's checksum does), and options files of garbage. Each is refused with one line that names
the option and the file (from Python: an exception naming the file), a non-zero exit, no signal,
no PETSc traceback and no HDF5 error stack."""
import os
import shutil
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
N = 32
SMALL = ["-adh_n", str(N), "-adh_steps", "1", "-adh_fftw_planner", "estimate"]
JOB = ["-adh_n", str(N), "-adh_gamma", "2e-3", "-adh_start", "adhesive", "-adh_path", "0,0.02,-0.03",
       "-adh_steps", "5", "-adh_fftw_planner", "estimate"]


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")


def run(cwd, *args, ranks=None):
    cmd = ([] if ranks is None else ["mpirun", "-n", str(ranks)]) + [EXE, *args]
    return subprocess.run(cmd, cwd=cwd, env=ENV, capture_output=True, text=True, timeout=300)


def one_line(p, *words):
    """A non-zero exit without a signal, and one error line holding every word."""
    assert 0 < p.returncode < 128, (p.returncode, p.stderr[-2000:])
    assert "PETSC ERROR" not in p.stderr and "HDF5-DIAG" not in p.stderr and "MPI_ABORT" not in p.stderr, p.stderr[-2000:]
    lines = [line for line in p.stderr.splitlines() if line.startswith("adhbem: error")]
    assert len(lines) == 1, p.stderr[-2000:]
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


def damaged_copies(path, tmp_path):
    """path cut to half, to its first 20 bytes, emptied, and with a block of its bytes overwritten."""
    data = path.read_bytes()
    stem, ext = path.stem, path.suffix
    out = {}
    for case, bytes_ in [("half", data[: len(data) // 2]), ("head", data[:20]), ("empty", b""),
                         ("overwritten", data[:64] + bytes(range(256)) * 2 + data[64 + 512:])]:
        out[case] = tmp_path / f"{stem}_{case}{ext}"
        out[case].write_bytes(bytes_)
    return out


@pytest.fixture
def maps(tmp_path):
    x = (np.arange(N) - N / 2) / N
    z = -(x[None, :] ** 2 + x[:, None] ** 2) / 2
    np.save(tmp_path / "z.npy", z)
    with h5py.File(tmp_path / "z.h5", "w") as f:
        f["h"] = z
        f["gamma"] = np.full((N, N), 2e-3)
    return tmp_path / "z.npy", tmp_path / "z.h5"


@pytest.mark.parametrize("fmt", ["npy", "h5"])
@pytest.mark.parametrize("option", ["topography", "gamma_field"])
def test_damaged_maps(tmp_path, maps, fmt, option):
    good = maps[0] if fmt == "npy" else maps[1]
    extra = ["-adh_gamma_field_dataset", "gamma"] if option == "gamma_field" and fmt == "h5" else []
    for case, path in damaged_copies(good, tmp_path).items():
        p = run(tmp_path, *SMALL, *extra, f"-adh_{option}", path.name)
        one_line(p, f"-adh_{option}", path.name)
        kw = {option: str(path), "n": N}
        if extra:
            kw["gamma_field_dataset"] = "gamma"
        with pytest.raises((ValueError, OSError)) as e:
            adhbem.Solver(**kw)
        assert path.name in str(e.value), (case, str(e.value))


def test_damaged_results_files(tmp_path):
    assert run(tmp_path, *JOB, "-adh_output", "r.h5", "-adh_fields", "pressure").returncode == 0
    os.remove(tmp_path / "r.csv")  # else the curve would come from the CSV journal, with a warning
    for case, path in damaged_copies(tmp_path / "r.h5", tmp_path).items():
        with pytest.raises(OSError) as e:
            adhbem.load(path)
        assert path.name in str(e.value) and "not a readable HDF5 file" in str(e.value), (case, str(e.value))
    with h5py.File(tmp_path / "other.h5", "w") as f:
        f["x"] = np.zeros(3)
    with pytest.raises(ValueError, match="other.h5: not an adhbem results file"):
        adhbem.load(tmp_path / "other.h5")


@pytest.fixture(scope="module")
def checkpoint(tmp_path_factory):
    """A checkpoint written on 2 ranks."""
    d = tmp_path_factory.mktemp("checkpoint")
    p = run(d, *JOB, "-adh_checkpoint", "ck.h5", ranks=2)
    assert p.returncode == 0, p.stderr[-2000:]
    return d / "ck.h5"


def flip(src, dst, dataset, index):
    """A copy of src with one bit of a value of dataset changed on disk."""
    shutil.copy(src, dst)
    with h5py.File(dst, "r") as f:
        d = f[dataset]
        offset = d.id.get_chunk_info(0).byte_offset if d.chunks else d.id.get_offset()
        size = d.dtype.itemsize
    data = bytearray(dst.read_bytes())
    data[offset + size * index + 2] ^= 0x10
    dst.write_bytes(bytes(data))


@pytest.mark.parametrize("ranks", [1, 3])
def test_checkpoint_restarts_on_other_ranks(tmp_path, checkpoint, ranks):
    """The checksum is the same for any partition: the 2-rank checkpoint restarts on 1 and 3."""
    p = run(tmp_path, *JOB, "-adh_restart", str(checkpoint), ranks=ranks)
    assert p.returncode == 0, p.stderr[-2000:]


@pytest.mark.parametrize("dataset, index", [("state/pressure", 100), ("state/contact", 7), ("curve/force", 3)])
def test_damaged_bytes_in_a_checkpoint(tmp_path, checkpoint, dataset, index):
    bad = tmp_path / "bad.h5"
    flip(checkpoint, bad, dataset, index)
    with h5py.File(bad, "r") as f:  # HDF5 itself reads the changed value without a word
        assert f[dataset][()].size > index
    one_line(run(tmp_path, *JOB, "-adh_restart", "bad.h5", ranks=2), "-adh_restart bad.h5", "checksum")


@pytest.mark.parametrize("content, says", [
    (b"\x00\x01garbage\xff\n-adh_n 16\n", "line 1 holds control bytes: not a text file"),
    (bytes(range(256)) * 8, "not a text file"),
    (b"-adh_n 16\n\n  # a comment\nhello world\n", "line 4: 'hello' is not an option"),
    (b"adh_n 16\n", "'adh_n' is not an option (each line is -name [value]; # starts a comment); did you mean -adh_n?"),
])
def test_options_file_of_garbage(tmp_path, content, says):
    (tmp_path / "job.opts").write_bytes(content)
    for ranks in (None, 2):
        p = run(tmp_path, "-options_file", "job.opts", ranks=ranks)
        one_line(p, "-options_file job.opts", says)


def test_options_file_with_comments_and_alias(tmp_path):
    (tmp_path / "job.opts").write_text("# a job\n-adh_n 16   # the grid\n\n\t-adh_path 0.01,0\r\nalias -g -adh_gamma\n-g 1e-3\n")
    p = run(tmp_path, "-options_file", "job.opts", "-adh_steps", "1", "-adh_fftw_planner", "estimate", "-adh_view")
    assert p.returncode == 0, p.stderr[-2000:]
    assert "16 x 16" in p.stdout, p.stdout[:1000]
