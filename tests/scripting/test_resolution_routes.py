"""The resolution estimate (the JKR contact radius of the smallest asperities, in grid spacings) is
that of the heights the solver runs on, whichever way they arrive: a NumPy array, a Vec, a file
(from Python and from the executable), a generated rough surface, a SurfaceTopography object. It
once was the default sphere's for an array (0.891 at this dgamma, R = 1) where the executable gave
the surface's 12.85."""
import subprocess

import h5py
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem_build import EXE
from common import FakeSurfaceTopography, jkr_scales

N, L = 64, 64.0  # grid spacing 1
GAMMA = 0.2
SURFACE = dict(hurst=0.8, cutoff_wavelength=16.0, rms_slope=0.1, seed=3)  # self-affine, cut off at 16 spacings
PERIODIC = dict(n=N, size=L, gamma=GAMMA, boundary="periodic")
SPHERE_AC = jkr_scales(GAMMA)[0]  # what the estimate gave for an array: the default sphere's (R = 1)


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("runs the executable itself")


def executable_estimate(tmp_path, *args):
    """asperity_contact_radius of the executable's results file for a path that never touches."""
    out = tmp_path / "exe.h5"
    r = subprocess.run([EXE, "-adh_n", str(N), "-adh_size", str(L), "-adh_gamma", str(GAMMA),
                        "-adh_boundary", "periodic", "-adh_path", "-2,-1", "-adh_steps", "1",
                        "-adh_output", str(out), *args], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        return float(f.attrs["asperity_contact_radius"])


def heights():
    z, _ = adhbem.rough_surface(N, L, **SURFACE)
    return adhbem.gather(z, z)


def test_every_route_gives_the_executables_estimate(tmp_path):
    serial_only()
    Z = heights()
    np.save(tmp_path / "z.npy", Z)
    want = executable_estimate(tmp_path, "-adh_topography", str(tmp_path / "z.npy"))
    generated = executable_estimate(tmp_path, "-adh_indenter", "rough",
                                     *[a for k, v in SURFACE.items() for a in (f"-adh_{k}", str(v))])
    assert want > 3 * SPHERE_AC  # a surface's estimate, not the sphere's
    assert generated == pytest.approx(want, rel=1e-12)  # the same heights, generated in C

    z_vec = adhbem.Solver(**PERIODIC).make_field(Z)
    routes = {
        "array": adhbem.Solver(topography=Z, **PERIODIC),
        "Vec": adhbem.Solver(topography=z_vec, **PERIODIC),
        "file": adhbem.Solver(topography=tmp_path / "z.npy", **PERIODIC),
        "generated": adhbem.Solver(indenter="rough", **SURFACE, **PERIODIC),
        "SurfaceTopography": adhbem.Solver(gamma=GAMMA, topography=FakeSurfaceTopography(Z.T.copy(), (L, L), True)),
        "set_topography": adhbem.Solver(**PERIODIC),
    }
    routes["set_topography"].set_topography(Z)
    for name, s in routes.items():
        got = s.resolution["asperity_contact_radius"]
        assert got == pytest.approx(want, rel=1e-12), name


def test_the_estimate_follows_a_new_topography():
    """Replacing the profile replaces the estimate: a rougher surface (twice the slopes, twice the
    curvatures) has smaller asperities, a_c ~ R^(2/3)."""
    Z = heights()
    s = adhbem.Solver(topography=Z, **PERIODIC)
    first = s.resolution["asperity_contact_radius"]
    s.set_topography(2 * Z)
    assert s.resolution["asperity_contact_radius"] == pytest.approx(first * 2 ** (-2 / 3), rel=1e-12)


def test_the_python_route_prints_the_resolution_lines(tmp_path):
    """solve_path() prints what the executable prints at the end of a run, and the dict says the same."""
    serial_only()
    script = tmp_path / "job.py"
    script.write_text(
        "import numpy as np, adhbem\n"
        "s = adhbem.Solver(n=48, gamma=2e-3, radius=1.0, path=[0.0, 0.02, -0.02], steps=4)\n"
        "s.solve_path()\n"
        "r = s.resolution\n"
        "print('DICT', r['asperity_contact_radius'], r['state'], r['resolved'])\n")
    from common import python_env
    import sys
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=python_env(), timeout=300)
    assert r.returncode == 0, r.stderr
    lines = [line for line in r.stdout.splitlines() if line.startswith("adhbem: resolution:")]
    assert len(lines) == 2, r.stdout
    assert "JKR contact radius at pull-off of the sphere" in lines[0]
    _, radius, state, resolved = next(line for line in r.stdout.splitlines() if line.startswith("DICT")).split()
    assert f"about {float(radius):.3g} grid spacings" in lines[0]
    assert f"(state {state}," in lines[1]
    assert ("the grid resolves the adhesion" in lines[1]) == (resolved == "True")


def test_an_array_topography_on_the_default_free_boundary_warns(tmp_path):
    """One rule in both routes: a topography (file, rough, array) on the free boundary by default
    warns; a boundary given, either one, silences it."""
    serial_only()
    import sys
    from common import python_env
    script = tmp_path / "job.py"
    script.write_text(
        "import sys, numpy as np, adhbem\n"
        "z = np.random.default_rng(1).random((16, 16))\n"
        "kw = {} if sys.argv[1] == 'none' else {'boundary': sys.argv[1]}\n"
        "adhbem.Solver(n=16, topography=z, **kw)\n")
    for boundary, warns in (("none", True), ("free", False), ("periodic", False)):
        r = subprocess.run([sys.executable, str(script), boundary], capture_output=True, text=True,
                           env=python_env(), timeout=120)
        assert r.returncode == 0, r.stderr
        assert ("warning: a topography array on the default free boundary" in r.stdout) == warns, (boundary, r.stdout)


def verdict_run(tmp_path, n, **extra):
    """A JKR sphere on an n^2 grid from Python, its results file's verdict attributes and its last line."""
    out = tmp_path / f"v{n}.h5"
    s = adhbem.Solver(n=n, size=1.0, radius=1.0, gamma=2e-3, start="adhesive", path=[0.0, 0.02, -0.03], steps=10,
                      output=str(out), **extra)
    s.solve_path()
    with h5py.File(out, "r") as f:
        attrs = (bool(f.attrs["adhesion_resolved"]), f.attrs["adhesion_unresolved_by"])
    return s.resolution, attrs


def test_the_verdict_says_which_part_of_the_rule_failed(tmp_path, capfd):
    """One rule, said the same way in the last line, the results file and Python: a coarse grid
    whose JKR radius is under 10 spacings is not resolved *because of it*, in words and as a flag;
    a fine one is resolved, with no reason."""
    serial_only()
    r, (resolved, why) = verdict_run(tmp_path, 16)
    line = [l for l in capfd.readouterr().out.splitlines() if "at the largest tension" in l][-1]
    assert r["asperity_contact_radius"] < 10 and r["resolved"] is False and not resolved
    assert "asperities" in r["unresolved"]
    words = f"the JKR contact radius of the sphere, {r['asperity_contact_radius']:.3g} grid spacings, under 10"
    assert words in why and f"depends on the grid ({why})" in line, (why, line)
    r, (resolved, why) = verdict_run(tmp_path, 64)
    assert r["resolved"] is True and resolved and r["unresolved"] == [] and why == ""
