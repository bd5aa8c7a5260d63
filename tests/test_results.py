"""adhbem.load (the results file as NumPy arrays, fields read lazily) and python3 -m adhbem.plot
(curves against the analytic solution where there is one, area against force, contact maps),
on the output of every indenter and both boundaries; both work without petsc4py."""
import subprocess
import sys

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem.plot import analytic
from adhbem_build import EXE
from common import python_env


CASES = {
    "sphere": ["-adh_indenter", "sphere", "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.004"],
    "hertz": ["-adh_indenter", "sphere", "-adh_gamma", "0", "-adh_path", "0,0.01"],
    "punch": ["-adh_indenter", "punch", "-adh_punch_radius", "0.25", "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.05"],
    "cone": ["-adh_indenter", "cone", "-adh_cone_slope", "0.1", "-adh_gamma", "1e-4", "-adh_path", "0.02,-0.002"],
    "rough": ["-adh_indenter", "rough", "-adh_boundary", "periodic", "-adh_size", "32", "-adh_gamma", "0.004",
              "-adh_start", "adhesive", "-adh_attach", "reach", "-adh_path", "0,0.3,-0.3"],
    "periodic sphere": ["-adh_indenter", "sphere", "-adh_boundary", "periodic", "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.004"],
}


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def run(tmp_path, name, args, fields=True):
    out = tmp_path / f"{name.replace(' ', '_')}.h5"
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_steps", "4", *args, *(["-adh_fields"] if fields else []),
                        "-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    return out


@pytest.mark.parametrize("name", list(CASES))
def test_plot_every_indenter_and_boundary(tmp_path, name):
    serial_only()
    out = run(tmp_path, name, CASES[name])
    r = subprocess.run([sys.executable, "-m", "adhbem.plot", str(out)], capture_output=True, text=True, env=python_env())
    assert r.returncode == 0, r.stderr[-2000:]
    png = out.with_suffix(".png")
    assert r.stdout.strip() == str(png) and png.stat().st_size > 10000
    with adhbem.load(out) as res:
        ref = analytic(res.params, res.curve["d"], res.curve["area"])
        expected = {"sphere": "JKR", "hertz": "Hertz", "punch": "Kendall", "cone": "JKR-type cone"}.get(name)
        assert (ref[0] if ref else None) == expected


def test_load_gives_the_curve_and_the_fields(tmp_path):
    serial_only()
    out = run(tmp_path, "sphere", CASES["sphere"])
    s = adhbem.Solver(n=32, indenter="sphere", gamma=1e-3, path=[0.01, -0.004], steps=4)
    c = s.solve_path()
    with adhbem.load(out) as r:
        for key in ("d", "force", "contact_points", "patches", "detach_ratio"):
            assert np.array_equal(r.curve[key], c[key]), key
        assert r.params["indenter"] == "sphere" and r.params["Nx"] == 32 and r.params["complete"] == 1
        assert r.field_names == ["pressure", "displacement", "gap", "contact"]
        assert np.array_equal(r.states, np.arange(len(c["d"])))
        p = r.field("pressure", -1)
        assert p.shape == (32, 32)
        assert np.array_equal(p, adhbem.gather(s.pressure, s.compliance))
        assert int(r.field("contact", 2).sum()) == c["contact_points"][2]
        assert r.profile.shape == (32, 32) and r.critical_stress.shape == (32, 32)
        with pytest.raises(KeyError, match="no fields of state"):
            r.field("pressure", 99)
    nofields = run(tmp_path, "plain", CASES["sphere"], fields=False)
    with adhbem.load(nofields) as r:
        assert r.field_names == [] and len(r.states) == 0
        with pytest.raises(KeyError, match="-adh_fields"):
            r.field("gap", 0)


def test_plot_of_a_missing_file_says_so(tmp_path):
    serial_only()
    r = subprocess.run([sys.executable, "-m", "adhbem.plot", str(tmp_path / "none.h5")], capture_output=True, text=True, env=python_env())
    assert r.returncode == 1 and "none.h5" in r.stderr and "Traceback" not in r.stderr


# A Python without PETSc (a laptop that reads results): petsc4py, mpi4py and adhbem's C extension
# cannot be imported in it.
WITHOUT_PETSC = """
import importlib.abc, runpy, sys

class Blocked(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("petsc4py", "mpi4py") or name == "adhbem._adhbem":
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None

sys.meta_path.insert(0, Blocked())
results, png = sys.argv[1:]

import adhbem
with adhbem.load(results) as r:
    assert r.params["indenter"] == "sphere" and len(r.curve["d"]) > 2, r.params
    assert r.field("pressure", -1).shape == (32, 32)
try:
    adhbem.Solver
    raise AssertionError("adhbem.Solver without petsc4py")
except ImportError as e:
    assert "petsc4py" in str(e) and "adhbem.load" in str(e), e

sys.argv = ["python3 -m adhbem.plot", results, "--out", png]
try:
    runpy.run_module("adhbem.plot", run_name="__main__", alter_sys=True)
except SystemExit as e:
    assert e.code == 0, e.code
loaded = [m for m in sys.modules if m.split(".")[0] in ("petsc4py", "mpi4py") or m == "adhbem._adhbem"]
assert not loaded, loaded
print("read and plotted without PETSc")
"""


def test_load_and_plot_without_petsc4py(tmp_path):
    serial_only()
    out = run(tmp_path, "sphere", CASES["sphere"])
    png = tmp_path / "laptop.png"
    r = subprocess.run([sys.executable, "-c", WITHOUT_PETSC, str(out), str(png)], capture_output=True, text=True,
                       env=python_env(), timeout=120)
    assert r.returncode == 0, r.stderr[-3000:]
    assert "read and plotted without PETSc" in r.stdout and png.stat().st_size > 10000
    # and where petsc4py is installed, import adhbem alone does not start PETSc either
    r = subprocess.run([sys.executable, "-c", "import sys, adhbem; print(sorted(m for m in sys.modules if 'petsc' in m))"],
                       capture_output=True, text=True, env=python_env(), timeout=60)
    assert r.returncode == 0 and r.stdout.strip() == "[]", r.stdout + r.stderr[-2000:]
