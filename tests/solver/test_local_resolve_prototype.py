"""bench/local_resolve.py, the NumPy prototype of local re-solves: every state it records must be
one the exact cascade's rules accept (it ends on a global solve: no point beyond -Sigma, none
penetrating, the pressure the set's solution), and with a window over the whole set and tight
local solves it must be the exact cascade, state for state; so that the differences it reports
for small windows come from the windows and not from the prototype's own loop."""
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "bench", "local_resolve.py")
N = 32


def run(tmp_path, *args):
    out = tmp_path / "curves.npz"
    subprocess.run([sys.executable, SCRIPT, "--n", str(N), "--save", str(out), *args], check=True,
                   capture_output=True, timeout=300)
    return np.load(out)


def dense(kernel):
    """The compliance as a dense matrix on the N^2 points, from the displacement of one unit
    pressure that the prototype saved (the same periodic convolution, written out)."""
    i, j = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    i, j = i.ravel(), j.ravel()
    return kernel[(i[:, None] - i[None, :]) % N, (j[:, None] - j[None, :]) % N]


def test_every_state_of_a_small_window_is_an_exact_cascade_state(tmp_path):
    f = run(tmp_path, "--w", "2")
    K, h, Sigma = dense(f["kernel"]), f["h"].ravel(), float(f["Sigma"])
    for d, C, p in zip(f["d"], f["sets_w2"], f["p_w2"]):
        C, p = C.ravel(), p.ravel()
        assert np.all(p[~C] == 0) and np.all(p[C] >= -Sigma)
        gap = h - d + K @ p
        assert np.all(gap[~C] >= -1e-9)  # nobody penetrates: the attach test let nobody join
        if C.any():  # the pressure solves the set's equations (a direct solve of the dense system)
            exact = np.linalg.solve(K[np.ix_(C, C)], (d - h)[C])
            assert np.abs(p[C] - exact).max() <= 1e-5 * np.abs(exact).max()


def test_a_window_over_the_whole_set_is_the_exact_cascade(tmp_path):
    f = run(tmp_path, "--w", str(N), "--local-rtol", "1e-6")
    exact, local = f["F_exact"], f[f"F_w{N}"]
    assert len(exact) > 20 and exact.max() > 0  # a path with tension, to pull-off
    assert len(local) == len(exact)
    assert np.array_equal(f[f"sets_w{N}"], f["sets_exact"])
    assert np.abs(local - exact).max() <= 1e-6 * np.abs(exact).max()
    solves, local_solves = f[f"counts_w{N}"][0], f[f"counts_w{N}"][3]
    assert local_solves > 0 and solves < f["counts_exact"][0]
