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


def compliance():
    """The prototype's compliance, as a dense matrix on the N^2 points (columns: unit pressures)."""
    m = np.fft.fftfreq(N, 1.0 / N)
    MX, MY = np.meshgrid(m, np.fft.rfftfreq(N, 1.0 / N), indexing="ij")
    k = 2 * np.pi * np.sqrt(MX**2 + MY**2)
    sym = 2.0 / np.sqrt(k**2 + (2 * np.pi)**2) * np.sinc(MX / N)**2 * np.sinc(MY / N)**2
    col = np.fft.irfft2(sym, s=(N, N))
    i, j = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    idx = np.stack([i.ravel(), j.ravel()], 1)
    di = (idx[:, None, 0] - idx[None, :, 0]) % N
    dj = (idx[:, None, 1] - idx[None, :, 1]) % N
    return col[di, dj]


def test_every_state_of_a_small_window_is_an_exact_cascade_state(tmp_path):
    f = run(tmp_path, "--w", "2")
    K, h, Sigma = compliance(), f["h"].ravel(), float(f["Sigma"])
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
    exact, local = f["F_exact"], f["F_w32"]
    assert len(exact) > 20 and exact.max() > 0  # a path with tension, to pull-off
    assert len(local) == len(exact)
    assert np.array_equal(f["sets_w32"], f["sets_exact"])
    assert np.abs(local - exact).max() <= 1e-6 * np.abs(exact).max()
    solves, local_solves = f["counts_w32"][0], f["counts_w32"][3]
    assert local_solves > 0 and solves < f["counts_exact"][0]
