"""Resources checked before anything is allocated (src/estimate.c): a grid the 32-bit indices
cannot address and a grid that clearly does not fit into memory stop at once with one message
naming -adh_n; the memory estimate (-adh_view) bounds the measured peak from above, within 2x."""
import re
import subprocess

import pytest

from adhbem import PETSc
from adhbem_build import EXE


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


@pytest.mark.parametrize("args, says", [
    (["-adh_n", "200000"], "GB of memory"),                                          # 4e10 points, 8 TB
    (["-adh_n", "200000", "-adh_memory_check", "0"], "64-bit indices"),              # 1.6e11 padded points
    (["-adh_n", "40000,30000", "-adh_boundary", "periodic"], "GB of memory"),         # 1.2e9 points, 120 GB
])
def test_too_large_grids_stop_at_once(tmp_path, args, says):
    serial_only()
    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, *args, "-adh_path", "0.01,0", "-adh_output", str(out)], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode != 0
    text = r.stderr + r.stdout
    assert says in text and "-adh_n" in text
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


@pytest.mark.parametrize("boundary", ["free", "periodic"])
def test_estimate_bounds_the_peak(boundary):
    serial_only()
    r = subprocess.run([EXE, "-adh_n", "512", "-adh_boundary", boundary, "-adh_gamma", "1e-3", "-adh_path", "0.005,-0.001",
                        "-adh_steps", "2", "-adh_view", "-memory_view"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    estimate = float(re.search(r"memory estimate: ([0-9.e+]+) MB in all", r.stdout).group(1)) * 1e6
    peak = float(re.search(r"Maximum \(over computational time\) process memory:\s+total ([0-9.e+]+)", r.stdout).group(1))
    print(f"\n{boundary} 512^2: estimate {estimate / 1e6:.0f} MB, measured peak {peak / 1e6:.0f} MB")
    assert peak <= estimate <= 2 * peak
