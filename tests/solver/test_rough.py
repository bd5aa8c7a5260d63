"""Rough-surface contact end to end: the rough indenter, its record in the results file and the
reuse of that record, the same curve on any number of ranks with adhesion, bad rough-surface
options from the executable, and the ./run rough job on a small grid.

The generator itself is tested in test_surface.py; load control and the periodic mode in
test_control.py and test_periodic.py.
"""
import os
import subprocess
import sys

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import python_env, say  # noqa: E402

from common import ROOT  # noqa: E402

# a small periodic cell with adhesion that matters: grid spacing 1, E* = 1
SURFACE = dict(hurst=0.8, rms_slope=0.1, rolloff_wavelength=16.0, seed=7)


def rough_options(n=64, **extra):
    opts = dict(n=n, size=float(n), E_star=1.0, gamma=0.004, indenter="rough", boundary="periodic",
                start="adhesive", attach="reach", steps=4, **SURFACE)
    opts.update(extra)
    return opts


def depth(n=64, fraction=0.25):
    """The indentation at which `fraction` of the gap profile lies below it."""
    z, _ = adhbem.rough_surface(n, size=float(n), comm=PETSc.COMM_SELF, **SURFACE)
    Z = adhbem.gather(z, z)
    return float(np.quantile(Z.max() - Z, fraction))


def test_rough_indenter_profile_is_max_z_minus_z():
    n = 48
    s = adhbem.Solver(**rough_options(n), path=[0.0, 1.0])
    z, stats = adhbem.rough_surface(n, size=float(n), **SURFACE)
    Z = adhbem.gather(z, z)
    h = adhbem.gather(s.profile, s.compliance)
    assert np.array_equal(h, Z.max() - Z)
    assert h.min() == 0.0 and stats["max_height"] == Z.max()


def test_results_record_the_surface_and_reuse_it(tmp_path):
    """The results file holds the surface's parameters, realised statistics and heights; a run
    on those heights (-adh_topography FILE -adh_topography_dataset topography) gives the same
    curve, bit for bit."""
    import h5py
    n, d1 = 48, depth(48)
    first = tmp_path / "rough.h5"
    s = adhbem.Solver(**rough_options(n), path=[0.0, d1, -d1], output=str(first))
    c = s.solve_path()
    with h5py.File(first, "r") as f:
        attrs = dict(f.attrs)
        Z = f["topography"][()]
    say(f"\nrough record: attributes {sorted(k for k in attrs if 'rms' in k or k in ('hurst', 'seed'))},"
        f" topography {Z.shape}, realised rms slope {attrs['realised_rms_slope']!r}")
    assert attrs["indenter"] == b"rough" or attrs["indenter"] == "rough"
    assert attrs["hurst"] == 0.8 and attrs["seed"] == 7
    assert attrs["rolloff_wavelength"] == 16.0 and attrs["cutoff_wavelength"] == 4.0
    assert abs(attrs["realised_rms_slope"] / 0.1 - 1) < 1e-12 and attrs["rms_slope"] == attrs["realised_rms_slope"]
    assert abs(np.sqrt(np.mean(Z ** 2)) / attrs["realised_rms_height"] - 1) < 1e-12
    assert Z.shape == (n, n)
    h = adhbem.gather(s.profile, s.compliance)
    assert np.array_equal(h, Z.max() - Z)

    again = adhbem.Solver(**{k: v for k, v in rough_options(n).items() if k not in SURFACE and k != "indenter"},
                          topography=str(first), topography_dataset="topography",
                          path=[0.0, d1, -d1])
    c2 = again.solve_path()
    for key in ("d", "force", "contact_points", "patches", "mean_gap"):
        assert np.array_equal(c[key], c2[key]), key
    assert c["contact_points"].max() > 0.1 * n * n and c["force"].min() < 0


@pytest.mark.mpi
@pytest.mark.ranks3
def test_rough_adhesion_same_curve_on_any_number_of_ranks():
    """Approach and retraction of a rough periodic cell with adhesion, on COMM_WORLD and on
    COMM_SELF: the same states (contact counts, patches, pull-off) and forces to 1e-10."""
    n = 64
    d1 = depth(n)
    opts = rough_options(n, path=[0.0, d1, -d1], steps=5)
    world = adhbem.Solver(**opts).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, **opts).solve_path()
    mpi = PETSc.COMM_WORLD.tompi4py()
    from mpi4py import MPI
    same = int(len(world["d"]) == len(alone["d"]))
    same = mpi.allreduce(same, op=MPI.MIN)
    assert same == 1
    scale = np.max(np.abs(alone["force"]))
    rel = mpi.allreduce(float(np.max(np.abs(world["force"] - alone["force"])) / scale), op=MPI.MAX)
    counts = mpi.allreduce(int(all(np.array_equal(world[k], alone[k]) for k in ("contact_points", "patches", "pulled_off"))), op=MPI.MIN)
    tension = mpi.allreduce(int(alone["force"].min() < 0 and alone["max_tension_ratio"].max() > 0.5), op=MPI.MIN)
    say(f"\nrough adhesion, {PETSc.COMM_WORLD.getSize()} ranks vs 1: {len(world['d'])} states, max |dF|/max|F| = {rel:.2e},"
        f" patches {world['patches'].tolist()}, points {world['contact_points'].tolist()}")
    assert counts == 1 and tension == 1
    assert rel < 1e-10


@pytest.mark.parametrize("option, value, says", [
    ("-adh_hurst", "1.5", "-adh_hurst"),
    ("-adh_hurst", "0", "-adh_hurst"),
    ("-adh_rms_height", "-1", "-adh_rms_height"),
    ("-adh_rms_slope", "0", "-adh_rms_slope"),
    ("-adh_cutoff_wavelength", "1.5", "-adh_cutoff_wavelength"),    # shorter than 2 spacings
    ("-adh_cutoff_wavelength", "100", "-adh_cutoff_wavelength"),    # longer than the cell
    ("-adh_rolloff_wavelength", "100", "-adh_rolloff_wavelength"),  # longer than the cell
])
def test_bad_rough_options_from_the_executable(tmp_path, option, value, says):
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")
    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_size", "32", "-adh_indenter", "rough", "-adh_boundary", "periodic",
                        "-adh_path", "0,1", option, value, "-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode != 0
    assert says in r.stderr + r.stdout
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


def test_run_rough_job_on_a_small_grid(tmp_path):
    """The ./run rough job end to end on a 64 x 64 cell: its table, plot and files."""
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own mpirun")
    env = python_env(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                     OMPI_MCA_rmaps_base_oversubscribe="1")
    r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "rough.py"), "--n", "64", "--steps", "4",
                        "--results", str(tmp_path)], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    table = r.stdout[r.stdout.index("rough surface 64 x 64"):]
    say("\n" + table)
    for row in ("pull-off force (the largest tension)", "contact area fraction at the deepest indentation", "energy dissipated over the loop"):
        assert row in table
    for name in ("rough.h5", "rough.csv", "rough_nonadhesive.h5", "rough_nonadhesive.csv", "rough.png"):
        assert (tmp_path / name).stat().st_size > 0
    import h5py
    with h5py.File(tmp_path / "rough.h5", "r") as f, h5py.File(tmp_path / "rough_nonadhesive.h5", "r") as g:
        Fa, Fn = f["curve/force"][()], g["curve/force"][()]
        da, dn = f["curve/d"][()], g["curve/d"][()]
        assert f.attrs["complete"] and g.attrs["complete"]
        # the figure's maps are pressure maps (the README's): the file holds the pressure fields
        assert "pressure" in f["fields"] and "contact" in f["fields"]
    import matplotlib
    matplotlib.use("Agg")
    from adhbem.plot import figure
    fig = figure(str(tmp_path / "rough.h5"), compare=[str(tmp_path / "rough_nonadhesive.h5")])
    maps = [a for a in fig.axes if a.images]
    assert maps and all(a.images[0].get_cmap().name != "from_list" for a in maps)  # no binary contact map
    assert sum(a.get_ylabel() == "pressure $p$" for a in fig.axes) >= 1, [a.get_ylabel() for a in fig.axes]
    assert not any(t.get_text() == "contact" for a in fig.axes for t in a.get_yticklabels())
    # adhesion carries tension and dissipates energy; the non-adhesive loop is reversible
    assert Fa.min() < 0 and Fn.min() == 0.0
    assert np.trapz(Fa, da) > 0 and abs(np.trapz(Fn, dn)) < 1e-8 * Fn.max() * np.ptp(dn)


@pytest.mark.parametrize("boundary", ["periodic", "free"])
def test_fft_pairs_count_the_preconditioner(boundary):
    """fft_pairs counts every transform pair of a step: the compliance's and the
    preconditioner's, which CG applies at least once per iteration (on the whole grid or on the
    bounding-box windows)."""
    n, d1 = 48, depth(48)
    c = adhbem.Solver(**rough_options(n, boundary=boundary), path=[0.0, d1, -d1]).solve_path()
    k, kapps, ffts = c["ksp_iterations"], c["compliance_applications"], c["fft_pairs"]
    say(f"{boundary}: {int(kapps.sum())} compliance applications, {int(k.sum())} KSP iterations, {int(ffts.sum())} FFT pairs")
    assert k.sum() > 0
    assert np.all(ffts >= kapps + k)
    # each solve applies the preconditioner once more than it iterates, and no more
    assert np.all(ffts <= kapps + k + 2 * c["outer_iterations"] + 2)


def test_displacement_and_critical_stress_vectors_follow_the_state():
    """The solver keeps no displacement, nor a critical-stress vector for a uniform dgamma, but
    the Vecs it hands out on request follow later steps: u = K p after every step, Sigma
    everywhere the scalar."""
    n, d1 = 48, depth(48)
    s = adhbem.Solver(**rough_options(n), path=[0.0, d1])
    s.start(0.0)
    u, Sigma = s.displacement, s.critical_stress_field
    s.step(0.5 * d1)
    s.step(d1)
    Ku = s.compliance.createVecLeft()
    s.compliance.mult(s.pressure, Ku)
    assert s.contact_set.getSize() > 0
    assert np.allclose(u.getArray(), Ku.getArray(), rtol=0, atol=1e-12 * np.abs(Ku.getArray()).max())
    assert np.all(Sigma.getArray() == s.critical_stress)
