"""The results file as h5py and pandas users open it: /curve holds columns of one length each (a
row per state; the path is a root attribute), counts are integers, text attributes are str, a
periodic cell has mean pressure and area fraction columns, and adhbem.load(...).to_pandas() gives
the curve as a DataFrame. Files of the earlier layout (/curve/path, float counts, byte strings)
still read."""
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE

COUNTS = ("contact_points", "outer_iterations", "ksp_iterations", "compliance_applications", "fft_pairs",
          "patches", "pulled_off", "smallest_tensile_patch")


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def run(tmp_path, name, *args):
    out = tmp_path / f"{name}.h5"
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gamma", "1e-3", "-adh_steps", "4", *args, "-adh_output", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    return out


@pytest.fixture(scope="module")
def periodic(tmp_path_factory):
    """A periodic wavy cell (Lx = 2, Ly = 0.25: the cell's area is 0.5) loaded and unloaded."""
    serial_only()
    z = np.tile(0.01 * np.cos(2 * np.pi * (np.arange(32) + 0.5) / 32), (32, 1))
    tmp = tmp_path_factory.mktemp("format")
    np.save(tmp / "z.npy", z)
    return run(tmp, "wave", "-adh_boundary", "periodic", "-adh_size", "2,0.25", "-adh_topography", str(tmp / "z.npy"),
               "-adh_path", "0,0.008,-0.002")


def test_h5py_sees_equal_columns_ints_and_str(periodic):
    with h5py.File(periodic, "r") as f:
        lengths = {k: f["curve"][k].shape for k in f["curve"]}
        assert len(set(lengths.values())) == 1, lengths
        n = lengths["d"][0]
        assert n == 9
        assert "path" not in f["curve"]
        np.testing.assert_array_equal(f.attrs["path"], [0, 0.008, -0.002])
        for k in COUNTS:
            assert f["curve"][k].dtype.kind == "i", k
        for k in ("boundary", "indenter", "criterion", "control", "attach", "ksp_type", "topography"):
            assert isinstance(f.attrs[k], str), (k, type(f.attrs[k]))
        assert f.attrs["boundary"] == "periodic"
        c = f["curve"]
        cell = f.attrs["Lx"] * f.attrs["Ly"]
        assert cell == 0.5
        np.testing.assert_allclose(c["mean_pressure"][()], c["force"][()] / cell, rtol=1e-15)
        np.testing.assert_allclose(c["area_fraction"][()], c["area"][()] / cell, rtol=1e-15)
        np.testing.assert_allclose(c["area_fraction"][()], c["contact_points"][()] / 32 ** 2, rtol=1e-14)
        assert 0 < c["area_fraction"][()].max() <= 1


def test_pandas_round_trip(periodic, tmp_path):
    pd = pytest.importorskip("pandas")
    with adhbem.load(periodic) as r:
        frame = r.to_pandas()
        curve = r.curve
    assert list(frame.index) == list(range(9)) and frame.index.name == "state"
    assert set(frame.columns) == set(curve)
    assert frame["contact_points"].dtype == np.int64
    # through the CSV beside it, as pandas users read it, and back
    csv = pd.read_csv(str(periodic).replace(".h5", ".csv"), index_col="step", float_precision="round_trip")
    for k in ("d", "force", "area", "mean_pressure", "area_fraction", "contact_points"):
        np.testing.assert_array_equal(csv[k].to_numpy(), frame[k].to_numpy(), err_msg=k)
    frame.to_csv(tmp_path / "again.csv")
    again = pd.read_csv(tmp_path / "again.csv", index_col="state", float_precision="round_trip")
    pd.testing.assert_frame_equal(again, frame, check_exact=False, rtol=1e-15)
    # the h5py route gives the same frame
    with h5py.File(periodic, "r") as f:
        direct = pd.DataFrame({k: f["curve"][k][()] for k in f["curve"]})
    assert direct.shape == frame.shape


def test_free_boundary_has_the_area_fraction_and_no_mean_pressure(tmp_path):
    """A free boundary's file has area_fraction, the grid's share in contact (for a measured map,
    the scan's), in /curve and in the CSV; a mean pressure over a free grid is no cell's."""
    serial_only()
    out = run(tmp_path, "sphere", "-adh_path", "0.01,-0.004")
    with h5py.File(out, "r") as f:
        c, cell = f["curve"], f.attrs["Lx"] * f.attrs["Ly"]
        np.testing.assert_allclose(c["area_fraction"][()], c["area"][()] / cell, rtol=1e-15)
        assert 0 < c["area_fraction"][()].max() < 1
        assert "mean_pressure" not in c
    csv = np.genfromtxt(str(out).replace(".h5", ".csv"), delimiter=",", names=True)
    assert "area_fraction" in csv.dtype.names and "mean_pressure" not in csv.dtype.names
    with adhbem.load(out) as r:
        assert "mean_pressure" not in r.curve and "area_fraction" in r.curve
        assert isinstance(r.params["boundary"], str)
        np.testing.assert_array_equal(r.params["path"], [0.01, -0.004])


def test_files_of_the_earlier_layout_still_read(periodic, tmp_path):
    """An earlier file: /curve/path of its own length, float64 counts, byte-string attributes,
    no cell columns. load() gives what a new file gives."""
    old = tmp_path / "old.h5"
    with h5py.File(periodic, "r") as f, h5py.File(old, "w") as g:
        for k, v in f.attrs.items():
            if k == "path":
                continue
            g.attrs[k] = np.bytes_(v) if isinstance(v, str) else v
        for k in f["curve"]:
            if k not in ("mean_pressure", "area_fraction"):  # columns an earlier file lacks
                g["curve/" + k] = f["curve"][k][()].astype(np.float64)
        g["curve/path"] = f.attrs["path"]
    with adhbem.load(periodic) as new, adhbem.load(old) as r:
        assert set(r.curve) == set(new.curve)
        for k in new.curve:
            assert r.curve[k].dtype == new.curve[k].dtype, k
            np.testing.assert_allclose(r.curve[k], new.curve[k], rtol=1e-15, err_msg=k)
        np.testing.assert_array_equal(r.params["path"], new.params["path"])
        assert r.params["boundary"] == "periodic"


def test_solver_curve_has_the_files_columns(periodic):
    """Solver.curve() of the same run has the file's columns and values."""
    z = np.tile(0.01 * np.cos(2 * np.pi * (np.arange(32) + 0.5) / 32), (32, 1))
    s = adhbem.Solver(n=32, size=(2, 0.25), gamma=1e-3, boundary="periodic", topography=z,
                      path=[0, 0.008, -0.002], steps=4)
    c = s.solve_path()
    with adhbem.load(periodic) as r:
        assert set(c) == set(r.curve)
        for k in ("d", "force", "area", "mean_pressure", "area_fraction", "contact_points"):
            np.testing.assert_allclose(c[k], r.curve[k], rtol=1e-9, atol=1e-14, err_msg=k)
        assert c["contact_points"].dtype.kind == "i"


def test_every_state_dict_has_the_files_columns():
    """start(), step(), state(), iterate_path() and a monitor give the derived columns too:
    area_fraction on every boundary, mean_pressure on a periodic cell, equal to curve()'s."""
    free = adhbem.Solver(n=32, gamma=1e-3, path=[0.01, -0.004], steps=3)
    seen = []
    free.monitor(lambda step, state: seen.append(state))
    states = list(free.iterate_path())
    c = free.curve()
    assert "mean_pressure" not in states[0] and "mean_pressure" not in c
    np.testing.assert_array_equal([s["area_fraction"] for s in states], c["area_fraction"])
    np.testing.assert_array_equal([s["area_fraction"] for s in seen], c["area_fraction"])
    assert free.state()["area_fraction"] == c["area_fraction"][-1]
    z = np.tile(0.01 * np.cos(2 * np.pi * (np.arange(32) + 0.5) / 32), (32, 1))
    cell = adhbem.Solver(n=32, size=(2, 0.25), boundary="periodic", topography=z, path=[0, 0.008], steps=2)
    first = cell.start(0.0)
    step = cell.step(0.008)
    c = cell.curve()
    for k in ("area_fraction", "mean_pressure"):
        np.testing.assert_array_equal([first[k], step[k]], c[k], err_msg=k)
    assert step["area_fraction"] == step["area"] / 0.5 and step["mean_pressure"] == step["force"] / 0.5
