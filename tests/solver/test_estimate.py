"""Resources checked before anything is allocated (src/solver/interface/estimate.c): a grid the build's PETSc
indices cannot address and a grid that clearly does not fit into memory stop at once with one
message naming -adh_n (the indices first: no option gets past them); the memory estimate
(-adh_view) bounds the measured peak from above, within 2x."""
import os
import re
import subprocess

import pytest

from adhbem import PETSc
from adhbem_build import EXE

INDEX_BITS = 8 * PETSc.IntType().itemsize   # the build's: importing adhbem checked that they agree
MEMORY = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")

# Just beyond 32-bit indices (2^31 - 1 = 2 147 483 647), and just within.
BEYOND_32_BIT = [["-adh_n", "46341", "-adh_boundary", "periodic"],   # 46341^2 = 2 147 488 281 points
                 ["-adh_n", "23171"]]                                # free: 4 x 23171^2 = 2 147 580 964
WITHIN_32_BIT = [["-adh_n", "46340", "-adh_boundary", "periodic"],   # 2 147 395 600
                 ["-adh_n", "23170"]]                                # 4 x 23170^2 = 2 147 395 600


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def refusal(tmp_path, args):
    """Run the executable on a grid it must refuse at set-up: the message, after checking that it
    failed, named -adh_n and wrote no file."""
    serial_only()
    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, *args, "-adh_path", "0.01,0", "-adh_output", str(out)], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode != 0
    text = r.stderr + r.stdout
    assert "-adh_n" in text
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())
    return text


def needs_less_memory_than(gigabytes):
    """Skip on a machine that could hold the grid: the run would go on and allocate it."""
    if MEMORY >= gigabytes * 1e9:
        pytest.skip(f"this machine has {MEMORY / 1e9:.0f} GB: the memory check would let the grid through")


@pytest.mark.parametrize("args, gigabytes", [
    (["-adh_n", "40000,30000", "-adh_boundary", "periodic"], 120),   # 1.2e9 points: within 32-bit indices
    (["-adh_n", "20000"], 80),                                       # free: 4 x 4e8 padded points, within
])
def test_too_large_for_memory_stops_at_once(tmp_path, args, gigabytes):
    needs_less_memory_than(gigabytes)
    assert "GB of memory" in refusal(tmp_path, args)


@pytest.mark.parametrize("args", BEYOND_32_BIT)
def test_beyond_32_bit_indices_says_how_to_get_past(tmp_path, args):
    """The 32-bit-index build refuses the grid whatever the memory check, and names the
    64-bit-index build."""
    if INDEX_BITS != 32:
        pytest.skip(f"this build has {INDEX_BITS}-bit indices (see test_64_bit_indices_address_beyond)")
    text = refusal(tmp_path, [*args, "-adh_memory_check", "0"])
    assert "32-bit indices" in text, text
    assert "ADHBEM_INDICES=64 ./run build" in text and "--with-64-bit-indices" in text, text


@pytest.mark.parametrize("args", BEYOND_32_BIT)
def test_64_bit_indices_address_beyond(tmp_path, args):
    """The 64-bit-index build lets the same grids past its indices: only the memory check (on
    here, so nothing is allocated) refuses them."""
    if INDEX_BITS != 64:
        pytest.skip(f"this build has {INDEX_BITS}-bit indices (see test_beyond_32_bit_indices_says_how_to_get_past)")
    needs_less_memory_than(100)
    text = refusal(tmp_path, args)
    assert "GB of memory" in text and "indices" not in text, text


@pytest.mark.parametrize("args", WITHIN_32_BIT)
def test_just_within_32_bit_indices_is_refused_only_for_memory(tmp_path, args):
    needs_less_memory_than(100)
    text = refusal(tmp_path, args)
    assert "GB of memory" in text and "indices" not in text, text


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
