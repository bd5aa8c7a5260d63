"""Errors from the library reach Python as Python's own exceptions, each with the one line the
executable prints (options named as the user gave them, without the solver's internal prefix) and
no C traceback; -adh_traceback asks for PETSc's traceback as it does for the executable."""
import subprocess
import sys

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from common import python_env

SMALL = dict(n=16, path=[0.01, 0.0], steps=1)


@pytest.mark.mpi
@pytest.mark.parametrize("kwargs, kind, words", [
    (dict(gamma=-1e-3), ValueError, "-adh_gamma: the work of adhesion must be >= 0"),
    (dict(topography="no/such/file.npy"), FileNotFoundError, "-adh_topography: cannot open no/such/file.npy"),
    (dict(radius=-1.0), ValueError, "-adh_radius must be positive"),
    (dict(criterion="griffith"), ValueError, "-adh_criterion"),
    (dict(boundary="fre"), ValueError, "Unknown option fre for -adh_boundary. Available options: free periodic"),
    (dict(n=40000, boundary="periodic", memory_check=True), MemoryError, "-adh_n: 40000 x 40000 needs about"),
])
def test_the_matching_python_exception(kwargs, kind, words):
    with pytest.raises(kind) as e:
        adhbem.Solver(**{**SMALL, **kwargs})
    message = str(e.value)
    assert words in message and "\n" not in message and "adhbem1" not in message and "_adh_" not in message
    assert e.value.petsc_error_code > 0
    assert not isinstance(e.value, PETSc.Error)


def test_the_solver_prefix_is_not_shown():
    """A misspelled KSP keyword is named as given (ksp_rtoll), not under the solver's prefix."""
    with pytest.raises(ValueError) as e:
        adhbem.Solver(ksp_rtoll=1e-9, **SMALL).solve_path()
    assert "-adh_ksp_rtoll is not read" in str(e.value) and "-adh_ksp_rtol?" in str(e.value)


def test_a_monitors_exception_propagates():
    """An exception raised in a monitor stops the path and comes out of solve_path() as itself."""
    class Mine(Exception):
        pass

    s = adhbem.Solver(gamma=1e-3, **SMALL)

    def monitor(step, state):
        raise Mine(f"stop at {step}")
    s.monitor(monitor)
    with pytest.raises(Mine, match="stop at 0"):
        s.solve_path()


def test_the_library_works_after_an_error():
    with pytest.raises(ValueError):
        adhbem.Solver(gamma=-1.0, **SMALL)
    assert len(adhbem.Solver(gamma=1e-3, **SMALL).solve_path()["d"]) == 2


def run_child(*args):
    script = "import adhbem\nadhbem.Solver(n=16, gamma=-1e-3)\n"
    return subprocess.run([sys.executable, "-c", script, *args], capture_output=True, text=True,
                          env=python_env(), timeout=120)


def test_no_c_traceback_unless_asked():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")
    r = run_child()
    assert r.returncode == 1
    last = r.stderr.strip().splitlines()[-1]
    assert last == "ValueError: -adh_gamma: the work of adhesion must be >= 0, got -0.001", r.stderr
    assert "[0]" not in r.stderr and "error code" not in r.stderr
    r = run_child("-adh_traceback")
    assert r.returncode == 1
    assert "[0]" in r.stderr and "AdhSolverSetFromOptions() at" in r.stderr, r.stderr


@pytest.mark.mpi
@pytest.mark.parametrize("kwargs, kind, words", [
    (dict(gamma="sticky"), ValueError, "gamma: expected a real number, got 'sticky'"),
    (dict(gamma=float("nan")), ValueError, "gamma: NaN is not a value"),
    (dict(gamma=2e-3 + 1j), TypeError, "gamma: expected a real number, got the complex"),
    (dict(radius=[1.0, 2.0]), TypeError, "radius: expected one number, got a sequence"),
    (dict(steps=2.5), ValueError, "steps: expected an integer, got 2.5"),
    (dict(steps=[1]), TypeError, "steps: expected one number"),
    (dict(steps=True), TypeError, "steps: expected an integer, got bool"),
    (dict(path=[]), ValueError, "path: an empty sequence"),
    (dict(path=[0.01, "deep"]), ValueError, "path: expected a real number, got 'deep'"),
    (dict(path=[0.01, float("nan")]), ValueError, "path: NaN is not a value"),
    (dict(path=""), ValueError, "path: an empty sequence"),
    (dict(path="0.01,deep"), ValueError, "path: expected a real number, got 'deep'"),
])
def test_bad_keyword_values_name_the_keyword(kwargs, kind, words):
    """Nothing is cast silently or replaced by a default: path=[] ran the default path."""
    with pytest.raises(kind) as e:
        adhbem.Solver(**{**SMALL, **kwargs})
    assert words in str(e.value), str(e.value)


@pytest.mark.mpi
@pytest.mark.parametrize("field", ["topography", "gamma_field"])
@pytest.mark.parametrize("value, kind, words", [
    (np.ones((16, 16)) * (1 + 1j), TypeError, "expected real numbers, got complex values"),
    (np.ones((16, 16), dtype=bool), TypeError, "expected real numbers, got booleans"),
    (np.array([[1.0, 2.0], [3.0]], dtype=object), TypeError, "expected real numbers, got Python objects"),
    ([[1.0, 2.0], [3.0]], ValueError, "expected a NumPy array of shape (Ny, Nx) = (16, 16)"),
    (np.full((16, 16), "1"), TypeError, "expected real numbers, got dtype <U1"),
])
def test_bad_arrays_name_the_argument(field, value, kind, words):
    """A complex topography was cast to its real part with only NumPy's ComplexWarning."""
    with pytest.raises(kind) as e:
        adhbem.Solver(**{**SMALL, field: value})
    assert str(e.value).startswith(f"{field}: ") and words in str(e.value), str(e.value)
