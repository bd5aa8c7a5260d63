"""A pull-off ends the path (-adh_stop_at_pulloff, true by default): a sphere pulled off on its
second leg does not run its third (a re-approach) unless told; the summary says where it stopped,
and the executable, solve_path(), iterate_path() and a restart from the pull-off's checkpoint all
record the same states. With the option false the legs after the pull-off run and the sphere comes
back into contact."""
import re
import subprocess

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE

# pulled off near d = -0.02 on the second leg; the third leg presses it in again
PATH = [0.0, 0.02, -0.03, 0.02]
OPTIONS = dict(n=64, radius=1.0, gamma=1e-3, start="adhesive", path=PATH, steps=10)
ARGS = ["-adh_n", "64", "-adh_radius", "1", "-adh_gamma", "1e-3", "-adh_start", "adhesive",
        "-adh_path", ",".join(map(str, PATH)), "-adh_steps", "10"]
STOPPED = re.compile(r"^adhbem: path: stopped where the surfaces came apart \(state (\d+), d = (\S+)\), with legs left: "
                     r"-adh_stop_at_pulloff false runs them$", re.M)


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")


def run(tmp_path, *args):
    p = subprocess.run([EXE, *ARGS, *args], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_the_path_stops_at_the_pull_off(tmp_path):
    serial_only()
    out = run(tmp_path, "-adh_output", "out.h5")
    m = STOPPED.search(out)
    assert m, out
    r = adhbem.load(str(tmp_path / "out.h5"))
    n = len(r.curve["d"])
    assert int(m.group(1)) == n - 1 and r.curve["pulled_off"][-1] == 1
    assert n < 1 + 3 * 10  # the third leg did not run
    assert float(m.group(2)) == pytest.approx(r.curve["d"][-1])
    assert re.search(rf"^adhbem: {n} states; pull-off force", out, re.M)


def test_stop_at_pulloff_false_runs_the_legs_after_it(tmp_path):
    serial_only()
    out = run(tmp_path, "-adh_output", "out.h5", "-adh_stop_at_pulloff", "false")
    assert not STOPPED.search(out) and "adhbem: path:" not in out
    c = adhbem.load(str(tmp_path / "out.h5")).curve
    k = int(np.argmax(c["pulled_off"]))
    assert c["pulled_off"][k] == 1 and k < len(c["d"]) - 1
    assert c["d"][-1] == pytest.approx(PATH[-1]) and c["contact_points"][-1] > 0  # back in contact


def test_python_routes_stop_where_the_executable_does(tmp_path):
    s = adhbem.Solver(**OPTIONS)
    curve = s.solve_path(progress=False)
    stopped = s.resolution["stopped"]
    assert stopped == len(curve["d"]) - 1 and curve["pulled_off"][-1] == 1
    t = adhbem.Solver(**OPTIONS)
    states = list(t.iterate_path())
    assert len(states) == len(curve["d"])
    assert np.array_equal([st["force"] for st in states], curve["force"])
    u = adhbem.Solver(**OPTIONS, stop_at_pulloff=False)
    longer = u.solve_path(progress=False)
    assert u.resolution["stopped"] == -1 and len(longer["d"]) > len(curve["d"])
    assert len(list(adhbem.Solver(**OPTIONS, stop_at_pulloff=False).iterate_path())) == len(longer["d"])
    # a new curve on the same solver is not described by the earlier path's stop
    list(s.iterate_path())
    assert s.resolution["stopped"] == -1


def test_a_run_without_adhesion_says_the_surfaces_came_apart_not_pull_off(tmp_path):
    """Without adhesion the contact is lost at d = 0 on the way out; the path stops there with
    the words that fit both (no 'pull-off' for a run that carried no tension)."""
    serial_only()
    p = subprocess.run([EXE, "-adh_n", "32", "-adh_path", "0,0.01,-0.01,0.01", "-adh_steps", "4"], cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert STOPPED.search(p.stdout) and "no tension carried; contact lost at d = " in p.stdout, p.stdout
    assert "pull-off" not in p.stdout.replace("-adh_stop_at_pulloff", ""), p.stdout


def test_a_restart_from_the_pull_off_ends_the_path(tmp_path):
    serial_only()
    run(tmp_path, "-adh_output", "out.h5", "-adh_checkpoint", "ck.h5")
    n = len(adhbem.load(str(tmp_path / "out.h5")).curve["d"])
    out = run(tmp_path, "-adh_output", "again.h5", "-adh_restart", "ck.h5")
    m = STOPPED.search(out)
    assert m and int(m.group(1)) == n - 1, out
    assert len(adhbem.load(str(tmp_path / "again.h5")).curve["d"]) == n
