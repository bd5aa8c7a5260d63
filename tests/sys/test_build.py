"""The build the suite runs against (python/adhbem_build.py: build/, or build64/ with
ADHBEM_INDICES=64): it is the one asked for, and a Python whose petsc4py is the other PETSc's
(32- against 64-bit indices) is refused with a message instead of crashing, when the solver side is
first imported (``import adhbem`` alone needs no PETSc)."""
import os
import subprocess
import sys

import petsc4py
import pytest

from adhbem import PETSc, _adhbem
from adhbem_build import BUILD, EXE
from common import python_env

INDEX_BITS = 8 * PETSc.IntType().itemsize


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def test_the_build_asked_for():
    asked = os.environ.get("ADHBEM_INDICES")
    if not asked:
        pytest.skip("not run through ./run, which sets ADHBEM_INDICES")
    assert 8 * _adhbem.petsc_int_size == INDEX_BITS == int(asked)


def with_the_other_petsc4py(env):
    """env with PYTHONPATH changed so that petsc4py is the other PETSc's, or skip."""
    path = env["PYTHONPATH"].split(os.pathsep)
    if INDEX_BITS == 32:
        r = subprocess.run(["pkg-config", "--variable=prefix", "PETSc64"], capture_output=True, text=True)
        dist = os.path.join(r.stdout.strip(), "lib", "python3", "dist-packages")
        if r.returncode or not os.path.isdir(os.path.join(dist, "petsc4py")):
            pytest.skip("the 64-bit PETSc's petsc4py (python3-petsc4py-64-real) is not installed")
        path.insert(0, dist)
    else:
        # ./run put this petsc4py first on PYTHONPATH; without it Debian's default one is found.
        ours = os.path.realpath(os.path.dirname(os.path.dirname(petsc4py.__file__)))
        path = [p for p in path if os.path.realpath(p) != ours]
    return dict(env, PYTHONPATH=os.pathsep.join(path))


def test_import_with_the_other_petsc4py_says_so():
    serial_only()
    other = 64 if INDEX_BITS == 32 else 32
    r = subprocess.run([sys.executable, "-c", "from adhbem import PETSc"], capture_output=True, text=True,
                       env=with_the_other_petsc4py(python_env()), timeout=60)
    if "No module named 'petsc4py'" in r.stderr:
        pytest.skip(f"no {other}-bit petsc4py is installed")
    assert r.returncode == 1, r.stderr[-2000:]
    assert f"in {BUILD} is built against a PETSc with {INDEX_BITS}-bit indices, but petsc4py" in r.stderr, r.stderr[-2000:]
    assert f"PETSc with {other}-bit indices" in r.stderr and "ADHBEM_INDICES" in r.stderr


@pytest.mark.parametrize("user_threads", [None, "2"])
def test_one_blas_thread_per_rank(user_threads):
    """OpenBLAS (behind PETSc's vector operations) would split long vector updates over a pool of
    threads that spin between calls and compete with the ranks: the executable sets one BLAS
    thread, unless the user chose a count (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OMP_NUM_THREADS).
    It says so under -info."""
    serial_only()
    env = dict(os.environ)
    for name in ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"):
        env.pop(name, None)
    if user_threads:
        env["OPENBLAS_NUM_THREADS"] = user_threads
    r = subprocess.run([EXE, "-adh_n", "16", "-adh_gamma", "1e-3", "-adh_path", "0.001,0", "-adh_steps", "1", "-info"],
                       env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    said = [line for line in r.stdout.splitlines() if "BLAS threads:" in line]
    assert len(said) == 1, r.stdout[-2000:]
    if "not OpenBLAS" in said[0]:
        pytest.skip("the BLAS is not OpenBLAS")
    if user_threads:
        assert "as the environment sets" in said[0]
    else:
        assert "set to 1 per rank" in said[0]


def test_run_exec_runs_where_the_user_stands(tmp_path):
    """./run exec takes -options_file and -adh_output relative to the caller's folder."""
    serial_only()
    if os.environ.get("ADHBEM_BUILD") and os.path.abspath(os.environ["ADHBEM_BUILD"]) != os.path.abspath(BUILD):
        pytest.skip("ADHBEM_BUILD names another build")
    (tmp_path / "job.opts").write_text("-adh_n 16\n-adh_path 0.01,0\n-adh_steps 1\n")
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    r = subprocess.run([os.path.join(root, "run"), "exec", "-options_file", "job.opts", "-adh_output", "out/r.h5"],
                       cwd=tmp_path, capture_output=True, text=True, env=dict(os.environ, NP="1"), timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    assert (tmp_path / "out" / "r.h5").is_file() and (tmp_path / "out" / "r.csv").is_file()


def test_import_with_another_petsc_version_says_so(tmp_path):
    """petsc4py's PETSc of another major.minor than the one the extension is built against (here a
    petsc4py that says 3.99): one ImportError naming both, when the solver side is first imported."""
    serial_only()
    code = ("from petsc4py import PETSc\n"
            "class Sys(PETSc.Sys):\n    @staticmethod\n    def getVersion(*a, **k):\n        return (3, 99, 0)\n"
            "PETSc.Sys = Sys\n"
            "import adhbem\ntry:\n    adhbem.Solver\nexcept ImportError as e:\n    print('ImportError:', e)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, env=python_env())
    assert r.returncode == 0, r.stderr
    built = "%d.%d" % _adhbem.petsc_version[:2]
    assert r.stdout.startswith(f"ImportError: adhbem: the C extension in ") and len(r.stdout.strip().splitlines()) == 1
    assert f"built against PETSc {built}, but petsc4py" in r.stdout and "runs PETSc 3.99" in r.stdout
