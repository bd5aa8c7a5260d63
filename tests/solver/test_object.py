"""The solver is a PETSc object: viewed with -adh_view through PETSc's viewer options, its -info
messages filtered by its class, held from Python as a petsc4py PETSc.Object (named, viewed,
reference counted), and a wrong object handed to it refused. Its grid is a PETSc object too."""
import re
import subprocess

import pytest

import adhbem
from adhbem import PETSc, _adhbem
from adhbem_build import EXE

RUN = [EXE, "-adh_n", "16", "-adh_path", "0.01,0", "-adh_steps", "1"]


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def test_view_through_petscs_viewer_options(tmp_path):
    serial_only()
    r = subprocess.run(RUN + ["-adh_view"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0
    lines = r.stdout.splitlines()
    assert lines[0] == "AdhSolver Object: 1 MPI process" and lines[1].strip() == "type: bem", lines[:3]
    assert any("KSP Object:" in line for line in lines)  # the solver's KSP, viewed inside it
    r = subprocess.run(RUN + ["-adh_view", f"ascii:{tmp_path / 'view.txt'}"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "AdhSolver Object" not in r.stdout
    assert (tmp_path / "view.txt").read_text().startswith("AdhSolver Object: 1 MPI process")


def test_info_filtered_by_class():
    serial_only()
    r = subprocess.run(RUN + ["-info", ":adhsolver"], capture_output=True, text=True, timeout=60)
    info = [line for line in r.stdout.splitlines() if line.startswith("[0]")]
    # PETSc 3.18 tags a line <adhsolver>, current releases <adhsolver:TYPE>
    assert info and all(re.search(r"<adhsolver(:\w+)?>", line) for line in info), info
    assert any("AdhSolverSetUp(): set up: 16 x 16 grid, free boundary" in line for line in info)
    r = subprocess.run(RUN + ["-info", ":~adhsolver"], capture_output=True, text=True, timeout=60)
    assert "<adhsolver" not in r.stdout


@pytest.mark.mpi
def test_a_petsc4py_object(tmp_path):
    with adhbem.Solver(n=16, gamma=1e-3, path=[0.01, 0.0], steps=1) as s:
        obj = s.petsc
        assert isinstance(obj, PETSc.Object) and obj.getClassName() == "AdhSolver" and obj.getType() == "bem"
        assert obj.getRefCount() == 1
        obj.setName("sphere of radius 1")
        viewer = PETSc.Viewer().createASCII(str(tmp_path / "solver.txt"), comm=obj.getComm())
        obj.view(viewer)
        viewer.destroy()
        if obj.getComm().getRank() == 0:
            first = (tmp_path / "solver.txt").read_text().splitlines()[0]
            assert first.startswith("AdhSolver Object: sphere of radius 1 (adhbem") and "MPI process" in first, first
        # the prefix of its options is the object's
        assert obj.getOptionsPrefix().startswith("adhbem") and obj.getOptionsPrefix() == s.prefix


@pytest.mark.mpi
def test_the_grid_a_petsc4py_object(tmp_path):
    """The grid is a PETSc object of its own (class AdhGrid), reference counted: a reference taken
    from Python outlives the solver."""
    s = adhbem.Solver(n=(16, 8), size=(2.0, 1.0), path=[0.01, 0.0], steps=1)
    grid = s.grid
    assert isinstance(grid, PETSc.Object) and grid.getClassName() == "AdhGrid"
    assert grid.getRefCount() == 2  # the solver's and this one
    s.destroy()
    assert grid.getRefCount() == 1
    viewer = PETSc.Viewer().createASCII(str(tmp_path / "grid.txt"), comm=grid.getComm())
    grid.view(viewer)
    viewer.destroy()
    if grid.getComm().getRank() == 0:
        lines = (tmp_path / "grid.txt").read_text().splitlines()
        assert lines[0].startswith("AdhGrid Object:") and "MPI process" in lines[0], lines
        assert lines[1].strip() == "type: slabs", lines
        assert lines[2].strip() == "16 x 8 elements of 0.125 x 0.125, domain 2. x 1., distributed by rows", lines
    grid.destroy()


def test_another_object_is_refused():
    v = PETSc.Vec().createSeq(4, comm=PETSc.COMM_SELF)
    with pytest.raises(TypeError, match="not an adhbem solver"):
        _adhbem.solver_state(v)
