"""The fields in the results file (-adh_fields LIST, -adh_fields_stride K): which are written, for
which states, and that they are the states of the curve (the pressure sums to the force, the
contact mask counts the contact points)."""
import os
import subprocess

import numpy as np
import pytest

from adhbem import PETSc

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
EXE = os.path.join(ROOT, "build", "adhbem")
N = 32
RUN = [EXE, "-adh_n", str(N), "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.004", "-adh_steps", "5"]


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def run(tmp_path, name, *args):
    out = tmp_path / f"{name}.h5"
    r = subprocess.run(RUN + list(args) + ["-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    import h5py
    with h5py.File(out, "r") as f:
        fields = {k: f["fields"][k][()] for k in f["fields"]} if "fields" in f else {}
        curve = {k: f["curve"][k][()] for k in f["curve"]}
    return fields, curve


def test_all_fields_of_every_state(tmp_path):
    serial_only()
    fields, curve = run(tmp_path, "all", "-adh_fields")
    n = len(curve["d"])
    assert set(fields) == {"pressure", "displacement", "gap", "contact", "profile", "critical_stress", "state"}
    assert np.array_equal(fields["state"], np.arange(n))
    h = 1.0 / N
    for k in range(n):
        assert abs(fields["pressure"][k].sum() * h * h - curve["force"][k]) <= 1e-12 * max(1.0, abs(curve["force"][k]))
        assert int(fields["contact"][k].sum()) == curve["contact_points"][k]
        # the gap is h - d + u, and it vanishes on the contact
        np.testing.assert_allclose(fields["gap"][k], fields["profile"] - curve["d"][k] + fields["displacement"][k], atol=1e-12)
        assert np.max(np.abs(fields["gap"][k][fields["contact"][k] > 0])) < 1e-9


def test_chosen_fields_every_second_state(tmp_path):
    serial_only()
    full, curve = run(tmp_path, "all", "-adh_fields", "all")
    some, curve2 = run(tmp_path, "some", "-adh_fields", "pressure,contact", "-adh_fields_stride", "2")
    assert np.array_equal(curve["force"], curve2["force"])
    assert set(some) == {"pressure", "contact", "profile", "critical_stress", "state"}
    rows = np.arange(0, len(curve["d"]), 2)
    assert np.array_equal(some["state"], rows)
    assert np.array_equal(some["pressure"], full["pressure"][rows])
    assert np.array_equal(some["contact"], full["contact"][rows])
    none, _ = run(tmp_path, "none", "-adh_fields", "none")
    assert none == {}


@pytest.mark.parametrize("args, says", [
    (["-adh_fields", "pressure,gapp"], "-adh_fields"),
    (["-adh_fields", "gap", "-adh_fields_stride", "0"], "-adh_fields_stride"),
])
def test_bad_fields_options(tmp_path, args, says):
    serial_only()
    out = tmp_path / "x.h5"
    r = subprocess.run(RUN + args + ["-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode != 0 and says in r.stderr + r.stdout
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())
