"""adhbem.load (the results file as NumPy arrays, fields read lazily) and python3 -m adhbem.plot
(curves against the analytic solution where there is one, area against force, contact maps),
on the output of every indenter and both boundaries."""
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
    # the file of this very solver: another process's FFTW plans (and this one's wisdom from earlier
    # tests) may differ from it in the last bits
    out = tmp_path / "sphere.h5"
    s = adhbem.Solver(n=32, indenter="sphere", gamma=1e-3, path=[0.01, -0.004], steps=4, fields="all", output=str(out))
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
