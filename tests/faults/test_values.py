"""Every numeric option given a value a batch script can produce by mistake: NaN, inf, -inf, a
negative, zero, a huge number, an integer beyond PetscInt, a word, an empty value, on the command
line and from Python. Each case either runs to a curve of finite numbers (the value has a meaning:
a huge modulus, inf for "never") or stops with one line that names the option (a Python exception
naming it), a non-zero exit and no signal or hang; a value that is not a number of the option's
kind is always refused. The options come from -help, so a new numeric option is swept too."""
import math
import os
import subprocess

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem.options import solver_options
from adhbem_build import EXE

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
SMALL = dict(n=16, steps=2, path=[0.01, 0.0], fftw_planner="estimate")
ROUGH = dict(indenter="rough", boundary="periodic")
# where an option is read: the choices that make the solver read it
CONTEXT = {
    "hurst": ROUGH, "rolloff_wavelength": ROUGH, "cutoff_wavelength": ROUGH, "rms_height": ROUGH,
    "rms_slope": ROUGH, "seed": ROUGH,
    "punch_radius": dict(indenter="punch"), "cone_slope": dict(indenter="cone"),
    "critical_stress": dict(gamma=1e-3), "criterion_radius": dict(gamma=1e-3), "criterion_radius_max": dict(gamma=1e-3),
    "dugdale_stress": dict(criterion="dugdale", gamma=1e-3),
    "dugdale_smoothing": dict(criterion="dugdale", gamma=1e-3, dugdale_stress=0.1, dugdale_route="minimize"),
    "exponential_range": dict(criterion="exponential", gamma=1e-3),
    "minimize_rtol": dict(criterion="exponential", gamma=1e-3, exponential_range=0.01),
    "minimize_max_it": dict(criterion="exponential", gamma=1e-3, exponential_range=0.01),
    "minimize_trust_region": dict(criterion="exponential", gamma=1e-3, exponential_range=0.01),
    "pulloff_rtol": dict(control="force", boundary="periodic"),
    "fields_stride": dict(fields="pressure"),
}
NUMERIC = [o for o in solver_options() if o.kind in ("int", "real", "int list", "real list")]
NOT_A_NUMBER = ["nan", "abc", "", "1e999"]   # never a value
MAYBE = ["inf", "-inf", "-1", "0", "1e300"]  # a value for some options, refused by others
BEYOND = "99999999999"                       # beyond 32-bit PetscInt: an integer option's wrong value


def cases(values):
    for o in NUMERIC:
        integer = o.kind.startswith("int")
        for v in values + ([BEYOND] if integer and PETSc.IntType().itemsize == 4 else []):
            yield pytest.param(o.name, v, id=f"{o.name}={v or 'empty'}")


# Python, in one process, gets every value (the range checks are the library's, the same on both
# routes); the executable, a process a case, a word on every option (the check before the read
# that Python's own checks stand in front of) and every value on two (a real and an integer).
PYTHON_CASES = list(cases([v for v in NOT_A_NUMBER + MAYBE if v != "1e999"]))  # Python's float("1e999") is inf
EXECUTABLE_CASES = list(cases(["abc"])) + [  # a word shows the check is made before each read
    pytest.param(name, v, id=f"{name}={v or 'empty'}") for name in ("gamma", "steps") for v in ["nan", "", "1e999", "-inf", "0", "1e300"]]


def flags(kw):
    out = []
    for k, v in kw.items():
        out += [f"-adh_{k}", ",".join(map(str, v)) if isinstance(v, list) else str(v)]
    return out


def refused(value, integer):
    return value in NOT_A_NUMBER or (value == BEYOND and integer)


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")


@pytest.mark.parametrize("name, value", EXECUTABLE_CASES)
def test_the_executable(tmp_path, name, value):
    integer = next(o for o in NUMERIC if o.name == name).kind.startswith("int")
    kw = {**SMALL, **CONTEXT.get(name, {})}
    kw.pop(name, None)
    cmd = [EXE, *flags(kw), f"-adh_{name}", value, "-adh_output", "out.h5"]
    try:
        p = subprocess.run(cmd, cwd=tmp_path, env=ENV, capture_output=True, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        pytest.fail(f"-adh_{name} {value!r}: still running after 120 s")
    assert 0 <= p.returncode < 128, (p.returncode, p.stderr[-2000:])  # no signal
    errors = [line for line in p.stderr.splitlines() if line.startswith("adhbem: error")]
    if p.returncode == 0:
        assert not refused(value, integer), f"-adh_{name} {value!r} was taken"
        with adhbem.load(tmp_path / "out.h5") as r:
            for column in ("d", "force"):
                assert np.all(np.isfinite(r.curve[column])), (column, r.curve[column])
    else:
        assert "PETSC ERROR" not in p.stderr and "MPI_ABORT" not in p.stderr, p.stderr[-2000:]
        assert len(errors) == 1, p.stderr[-2000:]
        assert f"-adh_{name}" in errors[0], errors[0]
        if (tmp_path / "out.h5").exists():  # refused after the first state: what was written loads
            adhbem.load(tmp_path / "out.h5").close()


def python_value(value, integer):
    """The value as a Python script would pass it: a number where Python has one, else the string."""
    try:
        x = float(value)
    except ValueError:
        return value
    if integer and math.isfinite(x) and x.is_integer():
        return int(x)
    return x


@pytest.mark.parametrize("name, value", PYTHON_CASES)
def test_python(name, value):
    option = next(o for o in NUMERIC if o.name == name)
    integer = option.kind.startswith("int")
    kw = {**SMALL, **CONTEXT.get(name, {})}
    kw[name] = python_value(value, integer)
    if option.kind.endswith("list") and name != "path":
        kw[name] = [kw[name]]
    try:
        curve = adhbem.Solver(**kw).solve_path()
    except (ValueError, TypeError, OverflowError, MemoryError) as e:
        message = str(e)
        assert "\n" not in message and (name in message), message
        return
    assert not refused(value, integer), f"{name}={kw[name]!r} was taken"
    assert np.all(np.isfinite(curve["d"])) and np.all(np.isfinite(curve["force"]))
