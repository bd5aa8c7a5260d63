"""What a Python user discovers of the API: Solver's keywords, defaults and documentation come from
the library's option table (the executable's -help), so every option is there with its default;
curve() documents every column it returns; fields and rough surfaces come back as NumPy arrays."""
import inspect
import re
import subprocess

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem.options import parse_help, solver_options
from adhbem_build import EXE
from common import gamma_for


def test_every_option_of_the_executable_is_a_documented_keyword():
    """The executable's -help lists the options; each is a keyword of Solver's signature, with the
    default -help shows, and has an entry in its docstring."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")
    help_text = subprocess.run([EXE, "-help"], capture_output=True, text=True, timeout=60).stdout
    exe = {o.name: o for o in parse_help(help_text)}
    assert {"n", "gamma", "criterion", "boundary", "path", "fftw_planner", "cascade_local"} <= set(exe)
    sig = inspect.signature(adhbem.Solver).parameters
    doc = adhbem.Solver.__doc__
    for name, o in exe.items():
        if name in ("view", "traceback"):  # the executable's own: Solver.view(), exceptions
            continue
        assert name in sig, name
        if name not in ("topography", "topography_kind", "gamma_field"):  # Python takes more there
            assert sig[name].default == o.default, (name, sig[name].default, o.default)
        assert re.search(rf"^{name} : ", doc, re.M), name
    # and nothing the executable lacks, but the Python-only ones
    extra = set(sig) - set(exe) - {"comm", "petsc_options"}
    assert not extra, extra


def test_defaults_are_the_libraries():
    """A few defaults as -help prints them, so a parser error cannot pass unseen."""
    table = {o.name: o for o in solver_options()}
    assert table["n"].default == 64 and table["n"].kind == "int list"
    assert table["size"].default == 1.0 and table["size"].kind == "real list"
    assert table["gamma"].default == 0.0 and table["gamma"].kind == "real"
    assert table["steps"].default == 10 and table["steps"].kind == "int"
    assert table["certify"].default is True and table["criterion_certify"].default is False
    assert sorted(table["criterion"].choices) == ["crack-closure", "dugdale", "exponential", "lj93", "pohrt-popov"]  # PETSc 3.2x lists them sorted
    assert table["boundary"].default == "free" and table["boundary"].choices == ("free", "periodic")
    assert table["rms_slope"].default == 0.1  # unless rms_height is given
    assert table["rms_height"].default is None and table["rolloff_wavelength"].default is None  # derived from the grid
    assert table["output"].default is None and table["output"].kind == "str"


def test_curve_docstring_names_every_column():
    z = np.tile(np.cos(2 * np.pi * np.arange(16) / 16), (16, 1)) * 0.01
    for kw in (dict(n=16), dict(boundary="periodic", topography=z)):
        c = adhbem.Solver(gamma=1e-3, path=[0.004, 0.0], steps=1, **kw).solve_path()
        for column in c:
            assert f"``{column}``" in adhbem.Solver.curve.__doc__, column


@pytest.mark.mpi
@pytest.mark.ranks3
def test_field_arrays_whole_and_local():
    """Each field as a NumPy array: the whole (Ny, Nx) on every rank, or this rank's rows; equal to
    the petsc4py objects; the contact mask is bool and counts the contact points."""
    N = 24
    s = adhbem.Solver(n=N, gamma=gamma_for(0.15), path=[0.02, -0.002], steps=2)
    curve = s.solve_path()
    s.start(0.02)
    j0, j1 = s.rows
    for name in ("pressure", "displacement", "gap", "profile", "critical_stress", "contact"):
        whole, mine = s.array(name), s.array(name, local=True)
        assert whole.shape == (N, N) and mine.shape == (j1 - j0, N)
        assert np.array_equal(whole[j0:j1], mine)
    assert np.array_equal(s.pressure_array(), adhbem.gather(s.pressure, s.compliance))
    assert s.contact_array().dtype == bool
    assert s.contact_array().sum() == s.state()["contact_points"] > 0
    np.testing.assert_allclose(s.gap_array(), s.profile_array() - 0.02 + s.displacement_array(), rtol=0, atol=1e-15)
    assert abs(s.pressure_array().sum() * (1 / N) ** 2 - s.state()["force"]) < 1e-12
    with pytest.raises(ValueError, match="no field 'stress'"):
        s.array("stress")
    assert len(curve["d"]) >= 2


@pytest.mark.mpi
def test_rough_surface_as_array_and_the_grid_from_its_shape():
    """rough_surface(as_array=True) is the gathered Vec, and a Solver takes its grid from an
    array topography's shape (Ny, Nx) when n is not given."""
    z, stats = adhbem.rough_surface((24, 16), (1.5, 1.0), seed=4, as_array=True)
    v, _ = adhbem.rough_surface((24, 16), (1.5, 1.0), seed=4)
    assert isinstance(z, np.ndarray) and z.shape == (16, 24)
    assert np.array_equal(z, adhbem.gather(v, v))
    assert abs(z.std() - stats["realised_rms_height"]) < 1e-12
    s = adhbem.Solver(topography=z, size=(1.5, 1.0), boundary="periodic")
    assert adhbem.grid_shape(s.compliance) == (24, 16)
    assert np.array_equal(s.profile_array(), z.max() - z)


def test_the_table_prints_as_markdown():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")
    import sys
    from common import python_env
    r = subprocess.run([sys.executable, "-m", "adhbem.options"], capture_output=True, text=True, env=python_env(), timeout=120)
    assert r.returncode == 0, r.stderr
    rows = [line for line in r.stdout.splitlines() if line.startswith("| `-adh_")]
    assert len(rows) == len(solver_options()) > 50
    assert "| `-adh_gamma` (`gamma=`) | `0.0` | Work of adhesion dgamma (0: non-adhesive) |" in r.stdout


@pytest.mark.mpi
def test_destroy_and_the_with_block():
    """destroy() frees the solver on every rank at once; the with-block does it at its end; a
    destroyed solver is refused with a clear error, and what was taken from it stays valid."""
    with adhbem.Solver(n=16, gamma=1e-3, path=[0.01, 0.0], steps=1) as s:
        s.solve_path(progress=False)
        p = s.pressure
        F = s.curve()["force"][-1]
    with pytest.raises(RuntimeError, match="destroyed"):
        s.solve_path()
    assert abs(p.sum() * (1 / 16) ** 2 - F) < 1e-12  # the Vec outlives the solver
    s.destroy()  # twice is harmless
    t = adhbem.Solver(n=16)
    t.destroy()
    with pytest.raises(RuntimeError, match="destroyed"):
        t.pressure_array()
