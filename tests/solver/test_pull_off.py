"""A pull-off force only where the surfaces came apart: a path that ends with the sphere still in
contact and a sticky rough cell held in full contact under force control carry a largest tension
that is no pull-off force. The executable's summary, the results file's attributes
(pull_off_force NaN, largest_tension, came_apart, full_contact), Solver.pull_off_force and
adhbem.load say so; a path that comes apart keeps its pull-off force on every route."""
import math
import re
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE

SPHERE = ["-adh_n", "64", "-adh_radius", "1", "-adh_gamma", "2e-3", "-adh_start", "adhesive", "-adh_steps", "10"]
# a rough cell sticky enough to jump to full contact at F = 0 and stay there under tension
STICKY = ["-adh_n", "64", "-adh_size", "64", "-adh_indenter", "rough", "-adh_boundary", "periodic",
          "-adh_gamma", "0.3", "-adh_control", "force", "-adh_start", "adhesive", "-adh_path", "0,-50", "-adh_steps", "5"]
SUMMARY = re.compile(r"^adhbem: \d+ states; (.*); \d+ set updates", re.M)


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")


def run(tmp_path, *args):
    p = subprocess.run([EXE, *args, "-adh_output", "out.h5"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    with h5py.File(tmp_path / "out.h5", "r") as f:
        attrs = dict(f.attrs)
    return SUMMARY.search(p.stdout).group(1), p.stdout, attrs


def test_a_path_that_ends_in_contact_has_no_pull_off_force(tmp_path):
    serial_only()
    words, out, attrs = run(tmp_path, *SPHERE, "-adh_path", "0,0.02,-0.005")
    m = re.fullmatch(r"the surfaces did not come apart \(the path ended with (\d+) points in contact\): "
                     r"the largest tension (\S+) at d = -0.005 is not a pull-off force", words)
    assert m, words
    assert "pull-off force (the largest tension)" not in out
    assert "not a pull-off: the surfaces did not come apart" in out  # the resolution line
    assert math.isnan(attrs["pull_off_force"]) and not attrs["came_apart"] and not attrs["full_contact"]
    assert attrs["largest_tension"] == pytest.approx(float(m.group(2)), rel=1e-5)
    r = adhbem.load(str(tmp_path / "out.h5"))
    assert math.isnan(r.pull_off_force) and not r.came_apart
    assert r.largest_tension == attrs["largest_tension"] > 0
    assert int(m.group(1)) == r.curve["contact_points"][-1] > 0


def test_a_sticky_cell_in_full_contact_has_no_pull_off_force(tmp_path):
    serial_only()
    words, out, attrs = run(tmp_path, *STICKY)
    assert re.fullmatch(r"the surfaces did not come apart \(in full contact from state \d+ to the end of the path\): "
                        r"the largest tension 50\.? at d = \S+ is not a pull-off force", words), words
    assert "the whole grid is in contact: no contact edge, no pull-off to resolve" in out
    assert "pull-off force depends" not in out and "(under 10: the largest tension depends on the grid)" in out
    assert math.isnan(attrs["pull_off_force"]) and attrs["full_contact"] and not attrs["came_apart"]
    assert attrs["largest_tension"] == pytest.approx(50.0, rel=1e-9)


def test_a_path_that_comes_apart_keeps_its_pull_off_force(tmp_path):
    serial_only()
    words, out, attrs = run(tmp_path, *SPHERE, "-adh_path", "0,0.02,-0.03")
    m = re.fullmatch(r"pull-off force \(the largest tension\) (\S+) at d = \S+; contact lost at d = -0.03", words)
    assert m, words
    r = adhbem.load(str(tmp_path / "out.h5"))
    assert attrs["came_apart"] and attrs["pull_off_force"] == attrs["largest_tension"] == r.pull_off_force
    assert attrs["pull_off_force"] == pytest.approx(float(m.group(1)), rel=1e-5)
    assert attrs["pull_off_force"] == pytest.approx(-r.curve["force"].min(), rel=1e-14)


@pytest.mark.mpi
def test_python_says_the_same():
    """Solver.pull_off_force is NaN where the surfaces did not come apart, on any number of ranks."""
    s = adhbem.Solver(n=64, radius=1.0, gamma=2e-3, start="adhesive", path=[0.0, 0.02, -0.005], steps=10)
    s.solve_path(progress=False)
    res = s.resolution
    assert res["apart"] == -1 and res["full_contact"] == -1 and res["last_points"] > 0
    assert math.isnan(s.pull_off_force) and s.largest_tension > 0
    s = adhbem.Solver(n=64, radius=1.0, gamma=2e-3, start="adhesive", path=[0.0, 0.02, -0.03], steps=10)
    s.solve_path(progress=False)
    assert s.resolution["apart"] > 0 and s.pull_off_force == s.largest_tension == -s.curve()["force"].min() > 0
    s = adhbem.Solver(n=64, size=64.0, indenter="rough", boundary="periodic", gamma=0.3, control="force",
                      start="adhesive", path=[0.0, -50.0], steps=5)
    s.solve_path(progress=False)
    assert s.resolution["full_contact"] == 0 and s.resolution["apart"] == -1 and math.isnan(s.pull_off_force)
