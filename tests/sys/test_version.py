"""The version, written once (CMakeLists.txt's project()), is the same everywhere a user meets it:
``adhbem --version``, ``AdhGetVersion()`` (through the extension), ``adhbem.__version__``, every
results file, ``-adh_view``, CHANGELOG.md's latest release and CITATION.cff."""
import os
import re
import subprocess

import h5py
import pytest

import adhbem
from adhbem import PETSc, _adhbem
from adhbem_build import EXE
from common import ROOT


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(adhbem VERSION (\d+\.\d+\.\d+)", f.read()).group(1)


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def test_python_and_extension():
    assert re.fullmatch(r"\d+\.\d+\.\d+", adhbem.__version__)
    assert adhbem.__version__ == project_version() == _adhbem.version


def test_executable_version():
    serial_only()
    for flag in ("--version", "-version"):
        r = subprocess.run([EXE, flag], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0 and not r.stderr
        first, second = r.stdout.strip().splitlines()
        running = ".".join(str(v) for v in PETSc.Sys.getVersion())
        assert first == f"adhbem {project_version()} (PETSc {running})"
        assert second.startswith(f"built against PETSc {running} with {8 * PETSc.IntType().itemsize}-bit indices")


def test_results_file_and_view(tmp_path):
    serial_only()
    r = subprocess.run([EXE, "-adh_n", "16", "-adh_path", "0.01,0", "-adh_steps", "1", "-adh_view",
                        "-adh_output", str(tmp_path / "v.h5")], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    running = ".".join(str(v) for v in PETSc.Sys.getVersion())
    assert f"  adhbem {project_version()} (PETSc {running})\n" in r.stdout
    with h5py.File(tmp_path / "v.h5", "r") as f:
        assert f.attrs["adhbem_version"].decode() == project_version()
        assert f.attrs["petsc_version"].decode() == running
    assert adhbem.load(tmp_path / "v.h5").params["adhbem_version"] == project_version()


def test_changelog_and_citation():
    with open(os.path.join(ROOT, "CHANGELOG.md")) as f:
        releases = re.findall(r"^## \[(\d+\.\d+\.\d+)\] - (\d{4}-\d\d-\d\d)", f.read(), re.M)
    assert releases and releases[0][0] == project_version()
    with open(os.path.join(ROOT, "CITATION.cff")) as f:
        cff = f.read()
    assert re.search(r"^version: (\S+)$", cff, re.M).group(1) == project_version()
    assert re.search(r'^date-released: "(\S+)"$', cff, re.M).group(1) == releases[0][1]
    assert re.search(r"^license: (\S+)$", cff, re.M).group(1) == "BSD-2-Clause"
    assert "Pohrt" in cff and "Facta Universitatis" in cff


def test_licence_everywhere():
    with open(os.path.join(ROOT, "LICENSE")) as f:
        assert f.readline().strip() == "BSD 2-Clause License"
    with open(os.path.join(ROOT, "pyproject.toml")) as f:
        assert 'license = { text = "BSD-2-Clause" }' in f.read()
    with open(os.path.join(ROOT, "cmake", "adhbemConfig.cmake.in")) as f:
        assert 'set(adhbem_LICENSE "@ADHBEM_LICENSE@")' in f.read()
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        assert 'set(ADHBEM_LICENSE "BSD-2-Clause")' in f.read()
