"""bench/local_resolve.py, the NumPy prototype of local re-solves: with a window that covers the
whole set and tight local solves, its local cascade must be the exact cascade (the same states,
with fewer global solves), so that the differences it reports for small windows come from the
windows and not from the prototype's own loop."""
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "bench", "local_resolve.py")


def run(tmp_path, *args):
    out = tmp_path / "curves.npz"
    subprocess.run([sys.executable, SCRIPT, "--n", "32", "--save", str(out), *args], check=True,
                   capture_output=True, timeout=300)
    return np.load(out)


def test_a_window_over_the_whole_set_is_the_exact_cascade(tmp_path):
    f = run(tmp_path, "--w", "32", "--local-rtol", "1e-10")
    exact, local = f["F_exact"], f["F_w32"]
    assert len(exact) > 20 and exact.max() > 0  # a path with tension, to pull-off
    assert len(local) == len(exact)
    assert np.abs(local - exact).max() <= 1e-8 * np.abs(exact).max()
    solves, _, local_solves = f["counts_w32"][:3]
    assert local_solves > 0 and solves < f["counts_exact"][0]


def test_loose_local_solves_on_a_large_window_move_the_answer(tmp_path):
    # the reason the local solves' tolerance is an option: at 1e-2 a window over the whole set
    # lets points go on unconverged pressures, as the loose cascade does
    f = run(tmp_path, "--w", "32", "--local-rtol", "1e-2")
    assert abs(f["F_w32"].max() / f["F_exact"].max() - 1) > 0.05
