"""The Python Solver as scripts use it: options from any sequence or NumPy array, manual start()
and step() recorded in the curve (and in write()'s file), every state's fields during a path
(iterate_path() and monitors) the same as solve_path()'s, the pull-off force, and the README's
Python examples run as they are written. Tests marked `mpi` assert on values every rank has."""
import math
import os
import re

import numpy as np
import pytest

import adhbem
from adhbem import PETSc

from common import ROOT  # noqa: E402
# JKR sphere, loaded from first touch and pulled off (a_c about 7 h)
OPTS = dict(n=32, size=1.0, E_star=1.0, gamma=1e-3, radius=1.0, steps=6)
PATH = [0.0, 0.02, -0.03]


def mpi():
    return PETSc.COMM_WORLD.tompi4py()


@pytest.fixture
def tmp(tmp_path):
    """A directory every rank sees: rank 0's."""
    return mpi().bcast(str(tmp_path), root=0)


def same_curve(a, b):
    """The columns of two curves equal to the last bit, but for the wall time."""
    return sorted(a) == sorted(b) and all(np.array_equal(a[k], b[k]) for k in a if k != "seconds")


@pytest.mark.mpi
def test_options_from_arrays_and_sequences():
    listed = adhbem.Solver(path=PATH, **OPTS).solve_path()
    for path in (np.array(PATH), tuple(PATH), [np.float64(v) for v in PATH], np.array([PATH]).T):
        c = adhbem.Solver(path=path, **OPTS).solve_path()
        assert same_curve(c, listed), path
    # a grid as an array too, and NumPy scalars
    c = adhbem.Solver(**dict(OPTS, n=np.array([32, 32]), steps=np.int64(6), gamma=np.float64(1e-3)), path=np.array(PATH)).solve_path()
    assert same_curve(c, listed)


@pytest.mark.mpi
def test_manual_steps_are_recorded(tmp):
    s = adhbem.Solver(path=PATH, **OPTS)
    seen = []
    s.monitor(lambda row, state: seen.append((row, state["d"])))
    states = [s.start(0.01), s.step(0.015), s.step(0.02), s.step(0.01)]
    c = s.curve()
    assert len(c["d"]) == 4 and seen == [(k, st["d"]) for k, st in enumerate(states)]
    for k, st in enumerate(states):
        assert all(c[key][k] == st[key] for key in st), k
    assert np.all(c["seconds"] > 0)
    out = os.path.join(tmp, "manual.h5")
    s.write(out)
    with adhbem.load(out) as r:
        assert np.array_equal(r.curve["d"], [0.01, 0.015, 0.02, 0.01])
        assert np.array_equal(r.curve["force"], c["force"])
    # start() begins a new curve, as a path does
    s.start(0.005)
    assert np.array_equal(s.curve()["d"], [0.005])


@pytest.mark.mpi
def test_iterate_path_gives_every_state_of_solve_path(tmp):
    """iterate_path() takes the states solve_path() takes, to the last bit, with the fields of each
    current in the loop: the pressure a monitor of solve_path() sees, and the results file's."""
    ref = adhbem.Solver(path=PATH, fields="pressure", output=os.path.join(tmp, "path.h5"), **OPTS)
    monitored = []
    ref.monitor(lambda row, state: monitored.append(adhbem.gather(ref.pressure, ref.compliance)))
    c_ref = ref.solve_path()
    assert c_ref["pulled_off"][-1] == 1 and len(c_ref["d"]) < 1 + 2 * OPTS["steps"]
    # after the path only the pulled-off state is left: nothing in contact
    assert ref.contact_set.getSize() == 0 and adhbem.gather(ref.pressure, ref.compliance).max() == 0

    s = adhbem.Solver(path=PATH, **OPTS)
    iterated = [(state, adhbem.gather(s.pressure, s.compliance)) for state in s.iterate_path()]
    c = s.curve()
    assert same_curve(c, c_ref)
    assert len(iterated) == len(monitored) == len(c["d"])
    with adhbem.load(os.path.join(tmp, "path.h5")) as r:
        for row, ((state, p), q) in enumerate(zip(iterated, monitored)):
            assert state["d"] == c["d"][row] and np.array_equal(p, q) and np.array_equal(p, r.field("pressure", row)), row
    # the largest load compresses, the largest tension pulls
    assert iterated[int(np.argmax(c["d"]))][1].max() > 0 and iterated[int(np.argmin(c["force"]))][1].min() < 0

    # a break ends the path there; the curve has the states taken
    s = adhbem.Solver(path=PATH, **OPTS)
    for k, state in enumerate(s.iterate_path()):
        if k == 3:
            break
    assert same_curve({key: v[:4] for key, v in c_ref.items()}, s.curve())


@pytest.mark.mpi
def test_iterate_path_writes_the_file_of_solve_path_as_it_goes(tmp):
    """With output, iterate_path() writes every state's row and fields (it kept only the last
    state's fields, through write()): the file solve_path() writes, state for state; a break gives
    the states taken, marked incomplete; checkpoints stay solve_path()'s."""
    ref = adhbem.Solver(path=PATH, fields="pressure,contact", output=os.path.join(tmp, "ref.h5"), **OPTS)
    ref.solve_path(progress=False)
    s = adhbem.Solver(path=PATH, fields="pressure,contact", output=os.path.join(tmp, "it.h5"), **OPTS)
    seen = []
    for state in s.iterate_path():
        seen.append(adhbem.gather(s.pressure, s.compliance))
        with open(os.path.join(tmp, "it.csv.part")) as f:  # written before it is yielded
            rows = [line for line in f if line.strip() and not line.startswith("#")][1:]
        assert len(rows) == len(seen) and float(rows[-1].split(",")[1]) == pytest.approx(state["d"], rel=1e-12)
        if len(seen) == 2:  # another file while this one is open: refused, this one goes on
            with pytest.raises(RuntimeError, match="it.h5 is being written state by state"):
                s.write(os.path.join(tmp, "other.h5"))
            assert not os.path.exists(os.path.join(tmp, "other.h5"))
    assert not os.path.exists(os.path.join(tmp, "it.h5.part"))
    with adhbem.load(os.path.join(tmp, "ref.h5")) as a, adhbem.load(os.path.join(tmp, "it.h5")) as b:
        assert b.params["complete"] == 1 and same_curve(a.curve, b.curve)
        assert len(seen) == len(b.curve["d"]) > 4
        for row, p in enumerate(seen):
            assert np.array_equal(b.field("pressure", row), a.field("pressure", row))
            assert np.array_equal(b.field("pressure", row), p), row
            assert np.array_equal(b.field("contact", row), a.field("contact", row))
    s = adhbem.Solver(path=PATH, output=os.path.join(tmp, "cut.h5"), **OPTS)
    for k, state in enumerate(s.iterate_path()):
        if k == 3:
            break
    with adhbem.load(os.path.join(tmp, "cut.h5")) as r:
        assert r.params["complete"] == 0 and len(r.curve["d"]) == 4
    s = adhbem.Solver(path=PATH, checkpoint=os.path.join(tmp, "ck.h5"), **OPTS)
    with pytest.raises(ValueError, match="option 'checkpoint' is solve_path"):
        next(s.iterate_path())


@pytest.mark.mpi
def test_pull_off_force(tmp):
    s = adhbem.Solver(path=PATH, **OPTS)
    assert math.isnan(s.pull_off_force) and s.largest_tension == 0.0  # no curve yet: nothing came apart
    c = s.solve_path()
    assert s.pull_off_force == -c["force"].min() > 0
    # JKR's 1.5 pi dgamma R, with the criterion's error on this coarse grid
    assert abs(s.pull_off_force / (1.5 * np.pi * OPTS["gamma"]) - 1) < 0.3
    out = os.path.join(tmp, "pulloff.h5")
    s.write(out)
    with adhbem.load(out) as r:
        assert r.params["pull_off_force"] == s.pull_off_force == r.pull_off_force
    hertz = adhbem.Solver(path=[0.0, 0.01], **dict(OPTS, gamma=0.0))
    hertz.solve_path()
    # loading only: the surfaces never came apart, and carried no tension
    assert math.isnan(hertz.pull_off_force) and hertz.largest_tension == 0.0


def readme_python_blocks():
    """The Python code blocks of the scripting guide (docs/getting-started/python.md), in order."""
    with open(os.path.join(ROOT, "docs", "getting-started", "python.md")) as f:
        text = f.read()
    return re.findall(r"```python\n(.*?)```", text, re.S)


def test_readme_python_examples(tmp_path, monkeypatch):
    """Exactly the scripting guide's code: the fields read during the path mean something (compression at
    the largest load, tension before pull-off), and the files it writes hold what it says."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("writes into its working directory")
    blocks = readme_python_blocks()
    assert len(blocks) == 2 and "iterate_path()" in blocks[0]
    monkeypatch.chdir(tmp_path)
    ns = {}
    exec(compile(blocks[0], "python.md", "exec"), ns)
    z = ns["z"]
    exec(compile(blocks[1], "python.md", "exec"), ns)
    curve, pressure = ns["curve"], ns["pressure"]
    assert len(pressure) == len(curve["d"]) and curve["pulled_off"][-1] == 1
    assert ns["at_load"].max() > 0 and ns["at_tension"].min() < 0 and not pressure[-1].any()
    assert ns["F_pull"] == -curve["force"].min()
    assert round(ns["F_pull"], 4) == 0.0099  # the number the guide gives
    with adhbem.load(tmp_path / "jkr.h5") as r:
        assert np.array_equal(r.curve["force"], curve["force"]) and r.params["pull_off_force"] == ns["F_pull"]
    with adhbem.load(tmp_path / "bump.h5") as r:
        import h5py
        with h5py.File(tmp_path / "bump.h5", "r") as f:
            assert np.array_equal(f["topography"][()], z)
        assert r.params["indenter"] == "array" and r.params["gamma_field"] == 1
        assert np.array_equal(r.curve["force"], ns["bump"]["force"])
    assert abs(ns["stats"]["realised_rms_slope"] - 0.1) < 1e-12


def test_readme_python_example(tmp_path, monkeypatch):
    """The README's Python example runs as printed and means what it says: the sphere's largest
    tension near JKR's 1.5 pi dgamma R on a grid that resolves it, a results file written."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("writes into its working directory")
    with open(os.path.join(ROOT, "README.md")) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    assert len(blocks) == 1 and len(blocks[0].splitlines()) <= 12
    monkeypatch.chdir(tmp_path)
    ns = {}
    exec(compile(blocks[0], "README.md", "exec"), ns)
    s = ns["s"]
    assert s.resolution["resolved"] and abs(s.pull_off_force / (1.5 * np.pi * 2e-3) - 1) < 0.03
    assert ns["p"].shape == (128, 128) and (tmp_path / "sphere.h5").exists()
    assert ns["K"].getSize() == (128 * 128, 128 * 128)
