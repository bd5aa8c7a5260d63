"""The fields in the results file (-adh_fields LIST, -adh_fields_stride K): which are written, for
which states, and that they are the states of the curve (the pressure sums to the force, the
contact mask counts the contact points)."""
import os
import subprocess

import numpy as np
import pytest

from adhbem import PETSc
from adhbem_build import EXE

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


def _xdmf_frames(xmf):
    """(time, {name: (hdf5 path, frame or None)}) per grid of an XDMF file, with xml.etree."""
    import xml.etree.ElementTree as ET
    frames = []
    for grid in ET.parse(xmf).getroot().iter("Grid"):
        if grid.get("GridType") != "Uniform":
            continue
        attrs = {}
        for a in grid.iter("Attribute"):
            items = list(a.iter("DataItem"))
            if items[0].get("ItemType") == "HyperSlab":
                start = int(items[1].text.split()[0])
                attrs[a.get("Name")] = (items[2].text.strip(), start)
            else:
                attrs[a.get("Name")] = (items[0].text.strip(), None)
        frames.append((float(grid.find("Time").get("Value")), attrs))
    return frames


def test_xdmf_describes_the_fields(tmp_path):
    """FILE.xmf beside FILE.h5: one grid per state with fields, each attribute pointing at the
    right frame of the right dataset (read here with h5py)."""
    serial_only()
    import h5py
    fields, curve = run(tmp_path, "x", "-adh_fields", "pressure,gap,contact", "-adh_fields_stride", "2")
    xmf = tmp_path / "x.xmf"
    frames = _xdmf_frames(xmf)
    assert [t for t, _ in frames] == list(fields["state"])
    with h5py.File(tmp_path / "x.h5", "r") as f:
        for k, (t, attrs) in enumerate(frames):
            assert set(attrs) == {"pressure", "gap", "contact", "profile", "critical_stress"}
            for name, (where, frame) in attrs.items():
                file, dataset = where.split(":")
                assert file == "x.h5"
                data = f[dataset][()] if frame is None else f[dataset][frame]
                ref = fields[name][k] if frame is not None else fields[name]
                assert frame is None or frame == k
                assert np.array_equal(data, ref)
    # no fields, no XDMF
    run(tmp_path, "plain")
    assert not (tmp_path / "plain.xmf").exists()


def test_paraview_reads_the_xdmf(tmp_path):
    """ParaView's own XDMF reader (pvpython, when installed: apt-get install paraview
    python3-paraview) sees every state as a time step with the values of the HDF5 file."""
    serial_only()
    import shutil
    import json
    pvpython = shutil.which("pvpython")
    if not pvpython:
        pytest.skip("pvpython (Debian: paraview, python3-paraview) is not installed")
    fields, curve = run(tmp_path, "pv", "-adh_fields")
    script = tmp_path / "read.py"
    script.write_text(
        "import sys, json\n"
        "from paraview.simple import XDMFReader, UpdatePipeline\n"
        "from paraview import servermanager as sm\n"
        "from vtk.numpy_interface import dataset_adapter as dsa\n"
        "r = XDMFReader(FileNames=[sys.argv[1]])\n"
        "out = {'times': list(r.TimestepValues), 'frames': []}\n"
        "for t in r.TimestepValues:\n"
        "    UpdatePipeline(time=t, proxy=r)\n"
        "    d = dsa.WrapDataObject(sm.Fetch(r))\n"
        "    out['frames'].append({k: [float(v) for v in d.CellData[k]] for k in ('pressure', 'contact', 'gap', 'displacement', 'profile')})\n"
        "print('JSON' + json.dumps(out))\n")
    r = subprocess.run([pvpython, "--force-offscreen-rendering", str(script), str(tmp_path / "pv.xmf")],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout[r.stdout.index("JSON") + 4:].strip().splitlines()[0])
    assert out["times"] == [float(k) for k in fields["state"]]
    for k, frame in enumerate(out["frames"]):
        for name in ("pressure", "contact", "gap", "displacement"):
            assert np.array_equal(np.array(frame[name]), fields[name][k].ravel()), name
        assert np.array_equal(np.array(frame["profile"]), fields["profile"].ravel())


def test_contact_mask_is_a_byte_per_point_on_any_number_of_ranks(tmp_path):
    """The mask is uint8 (1 byte per point, not 8), and 3 ranks write the same frames as 1."""
    serial_only()
    one, _ = run(tmp_path, "one", "-adh_fields", "contact")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    out = tmp_path / "three.h5"
    r = subprocess.run(["mpirun", "-n", "3", *RUN, "-adh_fields", "contact", "-adh_output", str(out)],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    import h5py
    with h5py.File(out, "r") as f:
        three = f["fields/contact"][()]
    assert one["contact"].dtype == np.uint8 and three.dtype == np.uint8
    assert np.array_equal(one["contact"], three) and one["contact"].sum() > 0


def test_output_folders_are_made_at_every_level_on_every_route(tmp_path):
    """One rule for -adh_output and -adh_checkpoint and the Python route: the missing folders are
    made, all levels, with the umask's permissions (nosuchdir/ was made with mode 0750 and
    deep/er/ refused); a folder that cannot be made is one error naming the option."""
    serial_only()
    import adhbem
    umask = os.umask(0)
    os.umask(umask)
    p = subprocess.run([EXE, "-adh_n", "16", "-adh_path", "0.01,0", "-adh_steps", "1", "-adh_output", "deep/er/out.h5",
                        "-adh_checkpoint", "ck/pt/ck.h5"], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "deep/er/out.h5").is_file() and (tmp_path / "ck/pt/ck.h5").is_file()
    for folder in ("deep", "deep/er", "ck", "ck/pt"):
        assert (tmp_path / folder).stat().st_mode & 0o777 == 0o777 & ~umask
    s = adhbem.Solver(n=16, path=[0.01, 0.0], steps=1, output=str(tmp_path / "py/deep/out.h5"))
    s.solve_path(progress=False)
    s.write(str(tmp_path / "py/write/er/out.h5"))
    assert (tmp_path / "py/deep/out.h5").is_file() and (tmp_path / "py/write/er/out.h5").is_file()
    (tmp_path / "afile").write_text("")
    p = subprocess.run([EXE, "-adh_n", "16", "-adh_output", "afile/out.h5"], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert p.returncode != 0 and p.stderr.strip().startswith("adhbem: error: -adh_output: cannot write afile/out.h5: ")
    assert len(p.stderr.strip().splitlines()) == 1
