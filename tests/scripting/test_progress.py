"""A run is not silent unless asked to be: the executable prints a progress line now and then (the
state, the time so far, an estimate of the time left), -adh_monitor a table with a header, units
and the time left; from Python, solve_path() shows a tqdm bar (when tqdm is there) or the
library's lines, and progress=False is quiet."""
import re
import subprocess
import sys

import pytest

from adhbem import PETSc
from adhbem_build import EXE
from common import python_env

RUN = [EXE, "-adh_n", "32", "-adh_gamma", "2e-3", "-adh_path", "0.02,-0.02", "-adh_steps", "12"]
LINE = re.compile(r"^adhbem: state (\d+) of at most (\d+) \(d = \S+, force \S+, \d+ points in contact\): "
                  r"(\d+) s so far, about (\d+) s left$")
# Long enough (some 40 states of about equal cost) that a stall of the machine in one state cannot
# swallow the lines after it: a line comes when a tenth of the time so far has passed.
RUN_LONG = [EXE, "-adh_n", "96", "-adh_gamma", "2e-3", "-adh_path", "0.02,-0.02", "-adh_steps", "40"]


@pytest.fixture(autouse=True)
def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def test_progress_lines_and_quiet():
    r = subprocess.run(RUN_LONG + ["-adh_progress", "1e-6"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    lines = [m for m in map(LINE.match, r.stdout.splitlines()) if m]
    states = [int(m[1]) for m in lines]
    assert lines and all(m[2] == "40" for m in lines), r.stdout
    # the first at once, then every tenth of the time so far: a few lines, in order
    assert len(states) >= 3 and states == sorted(set(states)) and states[0] == 0, r.stdout
    r = subprocess.run(RUN + ["-adh_progress", "0"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "so far" not in r.stdout
    r = subprocess.run(RUN + ["-adh_progress", "-1"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 1 and "-adh_progress must be >= 0 seconds" in r.stderr


def test_monitor_has_a_header_with_units_and_the_time_left():
    r = subprocess.run(RUN + ["-adh_monitor"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0].split() == ["state", "d", "force", "area", "points", "patches", "outer", "ksp", "K-mults", "seconds", "left"]
    assert lines[1].split() == ["[length]", "[force]", "[length^2]", "[s]", "[s]"]
    rows = [line.split() for line in lines[2:] if re.match(r"^\s+\d+ ", line)]
    assert len(rows) == 13 and float(rows[-1][-1]) == 0.0
    assert all(float(row[-1]) >= 0 for row in rows)
    assert "so far" not in r.stdout  # the table replaces the progress lines


def test_summary_words(tmp_path):
    """One meaning a word: the pull-off force is the largest tension of a path that came apart;
    'contact lost' where a leg ends; a path that never touches says so, with no pull-off or resolution line."""
    r = subprocess.run(RUN, capture_output=True, text=True, timeout=120)
    # this path ends with the sphere still stuck: its largest tension is no pull-off force
    assert re.search(r"^adhbem: 13 states; the surfaces did not come apart \(the path ended with \d+ points in contact\): "
                     r"the largest tension \S+ at d = \S+ is not a pull-off force; \d+ set updates", r.stdout, re.M), r.stdout
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gamma", "2e-3", "-adh_path", "0.02,-0.06", "-adh_steps", "12"],
                       capture_output=True, text=True, timeout=120)
    assert re.search(r"^adhbem: \d+ states; pull-off force \(the largest tension\) \S+ at d = \S+; contact lost at d = \S+; "
                     r"\d+ set updates", r.stdout, re.M), r.stdout
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gamma", "2e-3", "-adh_path", "-0.2,-0.1", "-adh_steps", "2"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0
    assert "adhbem: 3 states; the surfaces never touched;" in r.stdout
    assert "pull-off" not in r.stdout and "resolution" not in r.stdout and "tension" not in r.stdout


def python(code, *args):
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=python_env(), timeout=300)


def test_python_progress_bar_lines_and_quiet():
    pytest.importorskip("tqdm")
    job = ("import sys, adhbem\n"
           "s = adhbem.Solver(n=32, gamma=2e-3, path=[0.02, -0.02], steps=12, progress=1e-6)\n"
           "arg = sys.argv[1]\n"
           "s.solve_path(progress={'bar': True, 'quiet': False, 'default': None}[arg])\n")
    r = python(job, "bar")
    assert r.returncode == 0, r.stderr
    assert "13/13" in r.stderr and "so far" not in r.stdout  # the bar, not the lines
    assert "adhbem: resolution:" in r.stdout
    r = python(job, "default")  # not a terminal: the library's lines
    assert r.returncode == 0 and "so far, about" in r.stdout and "13/13" not in r.stderr
    r = python(job, "quiet")
    assert r.returncode == 0 and r.stdout == "" and "13/13" not in r.stderr


def test_a_solver_with_a_bar_is_freed():
    """The bar's monitor holds the solver weakly: a solver that showed one is freed when dropped."""
    pytest.importorskip("tqdm")
    import gc
    import weakref
    import adhbem
    s = adhbem.Solver(n=16, gamma=2e-3, path=[0.01, 0.0], steps=2)
    s.solve_path(progress=True)
    gone = weakref.ref(s)
    del s
    gc.collect()
    assert gone() is None
