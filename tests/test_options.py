"""adhbem's own options: the list the checks use is the list -help shows; a misspelled -adh_
option stops the executable, naming the nearest option; a misspelled keyword of Solver() is a
TypeError; PETSc's own options under the prefix (-adh_ksp_*) are left to PETSc."""
import os
import re
import subprocess

import pytest

import adhbem
from adhbem import PETSc, _adhbem
from adhbem_build import EXE



def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def test_option_list_is_what_help_shows():
    serial_only()
    r = subprocess.run([EXE, "-help", "-adh_path", "0.01,0", "-adh_steps", "1"], capture_output=True, text=True)
    shown = {m for m in re.findall(r"^\s*-(adh_[A-Za-z0-9_]+)", r.stdout, re.M) if not m.startswith(("adh_ksp_", "adh_pc_"))}
    assert shown == set(_adhbem.option_names())


def test_misspelled_option_stops_the_executable(tmp_path):
    serial_only()
    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gama", "0.01", "-adh_path", "0.01,0", "-adh_output", str(out)],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "Unknown option -adh_gama (did you mean -adh_gamma?)" in r.stderr + r.stdout
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


def test_petsc_options_under_the_prefix_are_petscs():
    serial_only()
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_path", "0.01,0", "-adh_steps", "1", "-adh_ksp_converged_reason"],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "Linear adh_ solve converged" in r.stdout


def test_misspelled_keyword_is_a_type_error():
    with pytest.raises(TypeError, match=r"unknown option 'radus' \(did you mean 'radius'\?\)"):
        adhbem.Solver(n=32, radus=1.0)
    adhbem.Solver(n=32, radius=1.0, ksp_rtol=1e-9)  # PETSc's options pass


@pytest.mark.parametrize("ranks", [1, 2])
def test_an_error_is_one_line(tmp_path, ranks):
    """The message once, first and alone (not inside PETSc's traceback of every frame and rank);
    -adh_traceback brings the traceback back."""
    serial_only()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    cmd = ["mpirun", "-n", str(ranks), EXE, "-adh_n", "32", "-adh_steps", "0", "-adh_path", "0.01,0"]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode != 0
    lines = [l for l in (r.stderr + r.stdout).splitlines() if "adhbem" in l or "PETSC" in l]
    assert lines[0] == "adhbem: error: -adh_steps must be >= 1, got 0"
    assert sum("adhbem: error" in l for l in lines) == 1 and not any("PETSC ERROR" in l for l in lines)
    r = subprocess.run(cmd + ["-adh_traceback"], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode != 0 and "PETSC ERROR" in r.stderr + r.stdout and "-adh_steps must be >= 1" in r.stderr + r.stdout
