"""The stickiness report of a rough surface (stickiness.c): the Persson-Tosatti, Pastewka-Robbins
and generalised Tabor criteria against their closed forms on a wave, and the verdict against runs."""
import math
import re
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("serial")


def wave(N, D, waves):
    """A cosine wave along x, waves wavelengths across a unit cell of N x 4 points."""
    x = (np.arange(N) + 0.5) / N
    return D * (1 - np.cos(2 * math.pi * waves * np.tile(x, (4, 1))))


@pytest.mark.mpi
@pytest.mark.parametrize("criterion", [{}, dict(criterion="exponential", exponential_range=0.002),
                                       dict(criterion="dugdale", dugdale_stress=0.05)])
def test_a_wave_against_the_closed_forms(criterion):
    """h = D (1 - cos kx): full contact stores U_el/A = E* k D^2 / 8 (Johnson 1995: the pressure
    E* k D / 2 cos kx on the displacement), h'_rms = D k / sqrt(2), h''_rms = D k^2 / (2 sqrt(2)),
    and the two range criteria from those, on 1, 2 and 3 ranks."""
    N, D, waves, Estar, dgamma = 64, 0.01, 2, 2.5, 3e-5
    s = adhbem.Solver(n=(N, 4), size=(1.0, 4 / N), boundary="periodic", topography=wave(N, D, waves),
                      topography_kind="gap", E_star=Estar, gamma=dgamma, **criterion)
    st = s.stickiness
    k = 2 * math.pi * waves
    U = Estar * k * D ** 2 / 8
    h1, h2 = D * k / math.sqrt(2), D * k ** 2 / (2 * math.sqrt(2))
    assert st["full_contact_energy"] == pytest.approx(U, rel=1e-10)
    assert st["rms_slope"] == pytest.approx(h1, rel=1e-10)
    assert st["rms_curvature"] == pytest.approx(h2, rel=1e-10)
    assert st["work_of_adhesion"] == pytest.approx(dgamma, rel=1e-14)
    assert st["persson_tosatti"] == pytest.approx(U / dgamma, rel=1e-10)
    assert st["sticks_everywhere"] == (U < dgamma)
    if not criterion:
        assert st["range"] == 0 and st["pastewka_robbins"] == 0 and st["generalized_tabor"] == 0
        return
    dr = 0.002 if "exponential_range" in criterion else dgamma / 0.05
    assert st["range"] == pytest.approx(dr, rel=1e-14)
    pr = h1 * Estar * dr / (2 * dgamma) * (h1 ** 2 / (h2 * dr)) ** (2 / 3)
    assert st["pastewka_robbins"] == pytest.approx(pr, rel=1e-10)
    assert st["generalized_tabor"] == pytest.approx(((1 / h2) * dgamma ** 2 / (Estar ** 2 * dr ** 3)) ** (1 / 3), rel=1e-10)
    assert st["sticky"] == (U < dgamma or pr < 1)


@pytest.mark.mpi
def test_a_gamma_field_counts_with_its_mean():
    N, D = 32, 0.01
    field = np.full((4, N), 2e-5)
    field[:, : N // 2] = 6e-5
    s = adhbem.Solver(n=(N, 4), size=(1.0, 4 / N), boundary="periodic", topography=wave(N, D, 1), topography_kind="gap",
                      gamma=1e-3, gamma_field=field)
    assert s.stickiness["work_of_adhesion"] == pytest.approx(4e-5, rel=1e-12)


@pytest.mark.mpi
@pytest.mark.parametrize("kwargs", [dict(n=32), dict(n=32, boundary="periodic", gamma=0.0, indenter="rough"),
                                    dict(n=32, boundary="periodic", indenter="sphere")])
def test_no_estimate_where_it_means_nothing(kwargs):
    """A sphere, and a rough cell without adhesion, get none (None, and no line)."""
    assert adhbem.Solver(**kwargs).stickiness is None


ROUGH = ["-adh_n", "32", "-adh_size", "32", "-adh_boundary", "periodic", "-adh_indenter", "rough", "-adh_hurst", "0.8",
         "-adh_rms_slope", "0.1", "-adh_rolloff_wavelength", "16", "-adh_seed", "7", "-adh_start", "adhesive",
         "-adh_control", "force", "-adh_path", "2,-2", "-adh_steps", "4"]


def run(tmp_path, *args):
    p = subprocess.run(["mpirun", "-n", "1", EXE, *ROUGH, *args], cwd=tmp_path, capture_output=True, text=True, timeout=300,
                       env=dict(__import__("os").environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
    assert p.returncode == 0, p.stderr[-2000:]
    return p.stdout


def test_the_verdict_is_what_the_run_does(tmp_path):
    """Persson-Tosatti below 1: the line says the surface sticks everywhere, before the path, and the
    run goes to full contact under a small compressive load; well above 1 it says partial contact,
    and the run stays in partial contact. The results file holds the same numbers."""
    serial_only()
    sticky = run(tmp_path, "-adh_gamma", "0.02", "-adh_output", "sticky.h5")
    line = next(line for line in sticky.splitlines() if line.startswith("adhbem: stickiness:"))
    assert sticky.index("adhbem: stickiness:") < re.search(r"^adhbem: \d+ states", sticky, re.M).start()  # before the path
    ratio = float(re.search(r"U_el/\(dgamma A\) = (\S+?):", line).group(1))
    assert ratio < 1 and "sticks everywhere" in line, line
    with h5py.File(tmp_path / "sticky.h5", "r") as f:
        assert f.attrs["stickiness_persson_tosatti"] == pytest.approx(ratio, rel=1e-2)
        assert f.attrs["sticks_everywhere"] and f.attrs["sticky"]
        assert "stickiness_pastewka_robbins" not in f.attrs  # crack closure has no range
        assert (f["curve/contact_points"][:] == 32 * 32).any()
    weak = run(tmp_path, "-adh_gamma", "0.0005", "-adh_output", "weak.h5")
    line = next(line for line in weak.splitlines() if line.startswith("adhbem: stickiness:"))
    ratio = float(re.search(r"U_el/\(dgamma A\) = (\S+?):", line).group(1))
    assert ratio > 3 and "partial contact" in line, line
    with h5py.File(tmp_path / "weak.h5", "r") as f:
        assert not f.attrs["sticks_everywhere"]
        assert (f["curve/contact_points"][:] < 32 * 32).all()
