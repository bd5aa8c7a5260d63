"""Every options file in examples/ runs (on a small grid: the grid, and for rough cells the path,
are overridden; results and checkpoints go to a temporary directory), so none goes stale."""
import glob
import os
import subprocess

import pytest

from adhbem import PETSc
from adhbem_build import EXE

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
EXAMPLES = sorted(glob.glob(os.path.join(ROOT, "examples", "*.opts")))


def options(path):
    opts = {}
    for line in open(path):
        line = line.split("#")[0].split()
        if line:
            opts[line[0]] = line[1] if len(line) > 1 else None
    return opts


@pytest.mark.parametrize("example", EXAMPLES, ids=[os.path.basename(e) for e in EXAMPLES])
def test_example_runs(tmp_path, example):
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")
    opts = options(example)
    small = ["-adh_n", "48"]
    if opts.get("-adh_indenter") == "rough":
        small += ["-adh_size", "48", "-adh_rolloff_wavelength", "24", "-adh_cutoff_wavelength", "4",
                  "-adh_path", "0,20" if opts.get("-adh_control") == "force" else "0,0.3,-0.3"]
    out = tmp_path / "out.h5"
    small += ["-adh_output", str(out)]
    if "-adh_checkpoint" in opts:
        small += ["-adh_checkpoint", str(tmp_path / "ck.h5")]
    r = subprocess.run([EXE, "-options_file", example, *small], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert out.exists() and "adhbem:" in r.stdout
    if "-adh_fields" in opts:
        assert out.with_suffix(".xmf").exists()
    if "-adh_checkpoint" in opts:
        assert (tmp_path / "ck.h5").exists()
