"""adhbem installed, used from outside its tree as a user would: ``cmake --install`` into a
temporary prefix, a program of one's own built against it once with ``pkg-config --cflags --libs
adhbem`` and once with ``find_package(adhbem)``, run on 2 ranks and compared with the installed
executable; the Python package pip-installed into a virtual environment of its own and run from
another folder, with no PYTHONPATH and no build folder.

The installed artefacts are used, never the tree's: no LD_LIBRARY_PATH, no PYTHONPATH (the
installed library and executable find what they need through their RPATH), and every check looks
at where a thing was found.
"""
import json
import os
import subprocess
import sys

import h5py
import pytest

from adhbem import PETSc
from adhbem_build import BUILD
from common import ROOT

EXTERNAL = os.path.join(ROOT, "tests", "sys", "external")
# a small JKR sphere pressed and pulled on (it stays in contact: the answers, its largest tension, are compared, not their accuracy)
JOB_OPTIONS = dict(n=32, size=1, radius=1, E_star=1, gamma=0.02, start="hertz", path="0.05,-0.03", steps=10)
JOB = [v for key, value in JOB_OPTIONS.items() for v in (f"-adh_{key}", str(value))]
INDEX_BITS = 8 * PETSc.IntType().itemsize


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("installs and starts its own processes")


def clean_env(**extra):
    """The environment of a user's shell: none of the tree's paths, nothing the build set."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LD_LIBRARY_PATH", "ADHBEM_BUILD")}
    return dict(env, **extra)


def pkg_config_path(prefix):
    """adhbem's installed pkg-config folder first, then the user's (where their own PETSc may be)."""
    return os.pathsep.join(filter(None, [str(prefix / "lib" / "pkgconfig"), os.environ.get("PKG_CONFIG_PATH")]))


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, **kw)
    assert r.returncode == 0, f"{' '.join(map(str, cmd))} failed:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    """`cmake --install` of the suite's build into a temporary prefix."""
    serial_only()
    p = tmp_path_factory.mktemp("prefix")
    run(["cmake", "--install", BUILD, "--prefix", str(p)])
    return p


def mpirun(exe, *args, cwd):
    return run(["mpirun", "--oversubscribe", "-n", "2", str(exe), *args], cwd=cwd, env=clean_env())


@pytest.fixture(scope="module")
def executable_answer(prefix, tmp_path_factory):
    """The installed executable's largest tension on the job, on 2 ranks, from its results file."""
    work = tmp_path_factory.mktemp("exe")
    mpirun(prefix / "bin" / "adhbem", *JOB, "-adh_output", "job.h5", cwd=work)
    with h5py.File(work / "job.h5", "r") as f:
        return float(f.attrs["largest_tension"]), f.attrs["adhbem_version"]


def largest_tension(stdout):
    version, line = stdout.strip().splitlines()[-2:]
    assert line.startswith("largest tension ")
    return version, float(line.split()[-1])


def test_installed_layout(prefix):
    """What a user, a packager and another build system look for, where GNUInstallDirs puts it."""
    for path in ("include/adhbem.h", "include/adhbemversion.h", "bin/adhbem", "lib/pkgconfig/adhbem.pc",
                 "lib/cmake/adhbem/adhbemConfig.cmake", "lib/cmake/adhbem/adhbemConfigVersion.cmake",
                 "lib/cmake/adhbem/adhbemTargets.cmake", "share/doc/adhbem/LICENSE"):
        assert (prefix / path).exists(), path
    libs = sorted(p.name for p in (prefix / "lib").glob("libadhbem.so*"))
    major, minor = (int(v) for v in run([prefix / "bin" / "adhbem", "--version"], env=clean_env()).stdout.split()[1].split(".")[:2])
    assert libs == ["libadhbem.so", f"libadhbem.so.{major}.{minor}", f"libadhbem.so.{major}.{minor}.{libs[-1].rsplit('.', 1)[-1]}"]
    soname = run(["readelf", "-d", prefix / "lib" / "libadhbem.so"]).stdout
    assert f"[libadhbem.so.{major}.{minor}]" in soname


def test_installed_executable_runs_without_library_path(prefix):
    """The installed executable finds the installed library (RPATH $ORIGIN/../lib), not the build's,
    and the library finds its PETSc where it was linked with it (RUNPATH: a PETSC_DIR outside the
    system's paths is found without LD_LIBRARY_PATH)."""
    r = run(["ldd", prefix / "bin" / "adhbem"], env=clean_env())
    line = next(v for v in r.stdout.splitlines() if "libadhbem" in v)
    assert os.path.realpath(line.split("=>")[1].split()[0]).startswith(os.path.realpath(prefix)), line
    out = run([prefix / "bin" / "adhbem", "--version"], env=clean_env()).stdout
    assert out.startswith("adhbem ") and "PETSc" in out
    petsc_libdir = run(["pkg-config", "--variable=libdir", "PETSc" if INDEX_BITS == 32 else "PETSc64"]).stdout.strip()
    runpath = run(["readelf", "-d", prefix / "lib" / "libadhbem.so"]).stdout
    line = next(v for v in runpath.splitlines() if "RUNPATH" in v or "RPATH" in v)
    assert os.path.realpath(petsc_libdir) in [os.path.realpath(p) for p in line.split("[")[1].rstrip("]").split(":")]


def test_pkg_config_program(prefix, executable_answer, tmp_path):
    """cc $(pkg-config --cflags --libs adhbem): PETSc and MPI come through Requires."""
    env = clean_env(PKG_CONFIG_PATH=pkg_config_path(prefix))
    flags = run(["pkg-config", "--cflags", "--libs", "adhbem"], env=env).stdout.split()
    assert any(f.startswith("-I") and os.path.realpath(f[2:]) == os.path.realpath(prefix / "include") for f in flags)
    assert "-lpetsc_real" in flags or any(f.startswith("-lpetsc") for f in flags)
    exe = tmp_path / "external"
    run(["cc", os.path.join(EXTERNAL, "external.c"), "-o", str(exe), *flags], env=env)
    version, tension = largest_tension(mpirun(exe, *JOB, cwd=tmp_path).stdout)
    expected, file_version = executable_answer
    assert version.startswith(f"adhbem {file_version.decode()} (PETSc ")
    assert tension > 0 and tension == pytest.approx(expected, rel=1e-12)


def test_own_ksp_example(prefix, tmp_path):
    """examples/c/own_ksp.c (the how-to "the compliance operator in your own KSP"), built as its
    comment says: a flat punch's force against Boussinesq's 2 a E* d, the same on 1 and 2 ranks."""
    env = clean_env(PKG_CONFIG_PATH=pkg_config_path(prefix))
    flags = run(["pkg-config", "--cflags", "--libs", "adhbem"], env=env).stdout.split()
    exe = tmp_path / "own_ksp"
    run(["cc", os.path.join(ROOT, "examples", "c", "own_ksp.c"), "-o", str(exe), *flags], env=env)

    def force(out):
        line = out.strip().splitlines()[-1]
        F, exact = (float(w.rstrip(",")) for w in (line.split("F = ")[1].split()[0], line.split()[-1]))
        return F, exact
    F2, exact = force(mpirun(exe, cwd=tmp_path).stdout)
    F1, _ = force(run([str(exe)], cwd=tmp_path, env=clean_env()).stdout)
    assert F1 == pytest.approx(F2, rel=1e-6)           # printed to 6 digits
    assert abs(F2 / exact - 1) < 0.01                    # a/h = 32: the punch's edge costs 0.5%


def test_cmake_package_program(prefix, executable_answer, tmp_path):
    """find_package(adhbem) in a CMake project of its own: adhbem::adhbem brings PETSc, MPI, FFTW."""
    build = tmp_path / "build"
    # the compiler CMake finds by itself (cc), not PETSc's mpicc: the target must bring MPI along
    run(["cmake", "-S", EXTERNAL, "-B", str(build), f"-DCMAKE_PREFIX_PATH={prefix}"], env=clean_env())
    run(["cmake", "--build", str(build)], env=clean_env())
    version, tension = largest_tension(mpirun(build / "external", *JOB, cwd=tmp_path).stdout)
    assert tension == pytest.approx(executable_answer[0], rel=1e-12)


def test_cmake_package_in_a_cxx_project(prefix, tmp_path):
    """A C++ project (C not enabled) gets MPI through MPI's C++ component."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.18)\nproject(cxxuser CXX)\n"
                                        "find_package(adhbem 0.1 REQUIRED CONFIG)\nadd_executable(v v.cxx)\n"
                                        "target_link_libraries(v PRIVATE adhbem::adhbem)\n")
    (src / "v.cxx").write_text("#include <adhbem.h>\n#include <cstdio>\nint main(int argc, char **argv)\n{\n"
                               "  char v[256];\n  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));\n"
                               "  PetscCall(AdhGetVersion(v, sizeof(v)));\n  std::printf(\"%s\\n\", v);\n"
                               "  PetscCall(PetscFinalize());\n  return 0;\n}\n")
    run(["cmake", "-S", str(src), "-B", str(tmp_path / "b"), f"-DCMAKE_PREFIX_PATH={prefix}"], env=clean_env())
    run(["cmake", "--build", str(tmp_path / "b")], env=clean_env())
    out = run([str(tmp_path / "b" / "v")], env=clean_env()).stdout
    assert out.startswith("adhbem ")


def test_cmake_package_refuses_another_version(prefix, tmp_path):
    """find_package(adhbem 9.0) is refused by the version file, with the version found in the message."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.18)\nproject(p C)\nfind_package(adhbem 9.0 REQUIRED CONFIG)\n")
    r = subprocess.run(["cmake", "-S", str(src), "-B", str(tmp_path / "b"), f"-DCMAKE_PREFIX_PATH={prefix}"],
                       capture_output=True, text=True, env=clean_env())
    assert r.returncode != 0 and "adhbem" in r.stderr and "9.0" in r.stderr


# What another PETSc would say, interposed before libpetsc's (as a PETSc whose library name does not
# carry its version or index size, first on the library path, would give), and what adhbem must answer.
OTHER_PETSC = {
    "version": ("PetscErrorCode PetscGetVersionNumber(PetscInt *a, PetscInt *b, PetscInt *c, PetscInt *d)\n"
                "{ if (a) *a = 3; if (b) *b = 99; if (c) *c = 0; if (d) *d = 1; return 0; }\n",
                ("built against PETSc 3.", "runs with PETSc 3.99")),
    "indices": ("PetscErrorCode PetscDataTypeGetSize(PetscDataType t, size_t *s)\n"
                "{ *s = t == PETSC_INT ? 2 * sizeof(PetscInt) : t == PETSC_DOUBLE || t == PETSC_INT64 ? 8 : 4; return 0; }\n",
                (f"built against a PETSc with {INDEX_BITS}-bit indices", f"runs with one with {2 * INDEX_BITS}-bit indices")),
}


@pytest.mark.parametrize("ranks", [1, 2])
@pytest.mark.parametrize("other", sorted(OTHER_PETSC))
def test_library_refuses_another_petsc(prefix, tmp_path, ranks, other):
    """A library built against one PETSc that runs with another major.minor, or another index size,
    stops with one line naming both, on any number of ranks, before it does anything."""
    code, expected = OTHER_PETSC[other]
    shim = tmp_path / "otherpetsc.c"
    shim.write_text("#include <petscsys.h>\n" + code)
    cflags = run(["pkg-config", "--cflags", "PETSc" if INDEX_BITS == 32 else "PETSc64"]).stdout.split()
    lib = tmp_path / "libotherpetsc.so"
    run(["mpicc", "-shared", "-fPIC", str(shim), "-o", str(lib), *cflags])
    r = subprocess.run(["mpirun", "--oversubscribe", "-x", "LD_PRELOAD", "-n", str(ranks), str(prefix / "bin" / "adhbem"),
                        *JOB, "-adh_output", "x.h5"], capture_output=True, text=True,
                       cwd=tmp_path, env=clean_env(LD_PRELOAD=str(lib)), timeout=120)
    assert r.returncode != 0
    assert all(e in r.stderr for e in expected), r.stderr
    # one line from the first rank (mpirun adds its own notice of the exit status), no abort
    assert len([v for v in r.stderr.splitlines() if "adhbem" in v]) == 1 and "MPI_ABORT" not in r.stderr, r.stderr
    assert not (tmp_path / "x.h5").exists()


def make_venv(v):
    """A virtual environment of Debian's Python that sees the system's packages, with
    scikit-build-core from PyPI (skip when PyPI cannot be reached: nothing else gives it here)."""
    if subprocess.run(["/usr/bin/python3", "-m", "pip", "--version"], capture_output=True).returncode:
        pytest.skip("pip is not installed for /usr/bin/python3 (python3-pip)")
    run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(v)])
    if sys.prefix != sys.base_prefix:
        # the suite runs in a virtual environment with its own PETSc's petsc4py (ADHBEM_PETSC=pypi):
        # the new one sees that environment's packages too, as a user's would see their petsc4py
        site = v / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"
        (site / "parent.pth").write_text("\n".join(p for p in sys.path if p.startswith(sys.prefix) and p.endswith("-packages")) + "\n")
    r = subprocess.run([str(v / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check",
                        "--timeout", "30", "scikit-build-core>=0.8"], capture_output=True, text=True, env=clean_env())
    if r.returncode and ("Could not find a version" in r.stderr or "NewConnectionError" in r.stderr or "Temporary failure" in r.stderr):
        pytest.skip(f"PyPI cannot be reached for scikit-build-core: {r.stderr.strip().splitlines()[-1]}")
    assert r.returncode == 0, r.stderr
    return v


@pytest.fixture(scope="module")
def venv(prefix, tmp_path_factory):
    """A virtual environment with the system's packages (petsc4py, mpi4py), scikit-build-core from
    PyPI, and adhbem pip-installed from the source tree (the library built into the extension)."""
    if INDEX_BITS != 32:
        pytest.skip("a --system-site-packages environment sees Debian's default (32-bit) petsc4py")
    v = make_venv(tmp_path_factory.mktemp("venv"))
    pip = [str(v / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    run(pip + ["--no-build-isolation", ROOT], env=clean_env(CMAKE_BUILD_PARALLEL_LEVEL=str(os.cpu_count() or 1)),
        cwd=str(v))
    return v


SOLVE = """
import json, sys, adhbem
print(adhbem.__file__)
print(adhbem._adhbem.__file__)
print(adhbem.__version__)
s = adhbem.Solver(**json.loads(sys.argv[1]))
s.solve_path(progress=False)
print(repr(s.largest_tension))
"""


def test_pip_package_solves_from_another_folder(venv, executable_answer, tmp_path):
    """The installed package, not the tree's: imported from site-packages, its extension there too,
    and its pull-off the executable's."""
    r = run([str(venv / "bin" / "python"), "-c", SOLVE, json.dumps(JOB_OPTIONS)], cwd=tmp_path, env=clean_env())
    module, extension, version, tension = r.stdout.strip().splitlines()[-4:]
    site = os.path.realpath(venv)
    assert os.path.realpath(module).startswith(site) and os.path.realpath(extension).startswith(site)
    assert not os.path.realpath(module).startswith(os.path.realpath(ROOT))
    assert version == executable_answer[1].decode()
    assert float(tension) == pytest.approx(executable_answer[0], rel=1e-9)


def test_pip_package_plot_command(venv, prefix, tmp_path):
    """adhbem-plot FILE.h5, the console script, draws a results file of the installed executable."""
    run([prefix / "bin" / "adhbem", *JOB, "-adh_output", "job.h5"], cwd=tmp_path, env=clean_env())
    run([venv / "bin" / "adhbem-plot", "job.h5", "--out", "job.png"], cwd=tmp_path, env=clean_env(MPLBACKEND="Agg"))
    assert (tmp_path / "job.png").stat().st_size > 10_000


def test_pip_package_against_installed_library(prefix, executable_answer, tmp_path_factory):
    """pip with ADHBEM_BUILD_CORE=OFF builds only the extension, against the installed library."""
    if INDEX_BITS != 32:
        pytest.skip("a --system-site-packages environment sees Debian's default (32-bit) petsc4py")
    v = make_venv(tmp_path_factory.mktemp("venv_core"))
    pip = [str(v / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    # --no-deps: Debian's NumPy, h5py and matplotlib (pip does not see Debian's h5py by its name)
    run(pip + ["--no-build-isolation", "--no-deps", "--config-settings=cmake.define.ADHBEM_BUILD_CORE=OFF",
               f"--config-settings=cmake.define.CMAKE_PREFIX_PATH={prefix}", ROOT], env=clean_env(), cwd=str(v))
    work = tmp_path_factory.mktemp("work_core")
    r = run([str(v / "bin" / "python"), "-c", SOLVE, json.dumps(JOB_OPTIONS)], cwd=work, env=clean_env())
    extension = r.stdout.strip().splitlines()[-3]
    linked = run(["ldd", extension]).stdout
    assert any("libadhbem" in line and os.path.realpath(line.split("=>")[1].split()[0]).startswith(os.path.realpath(prefix))
               for line in linked.splitlines())
    assert float(r.stdout.split()[-1]) == pytest.approx(executable_answer[0], rel=1e-9)



def test_configure_finds_petsc_dir(tmp_path):
    """A PETSc of one's own: PETSC_DIR/PETSC_ARCH in the environment is where CMake looks first (here a
    PETSC_DIR whose PETSc.pc is the system's with a marker in its Cflags, and no PKG_CONFIG_PATH)."""
    serial_only()
    pkg = "PETSc" if INDEX_BITS == 32 else "PETSc64"
    system_pc = run(["pkg-config", "--path", pkg]).stdout.strip()
    arch = tmp_path / "petsc" / "arch-own" / "lib" / "pkgconfig"
    arch.mkdir(parents=True)
    text = open(system_pc).read()
    prefix = run(["pkg-config", "--variable=prefix", pkg]).stdout.strip()
    text = text.replace("${pcfiledir}", os.path.dirname(system_pc)).replace("Cflags:", "Cflags: -DADHBEM_OWN_PETSC_MARK", 1)
    text = "\n".join(f"prefix={prefix}" if line.startswith("prefix=") else line for line in text.splitlines()) + "\n"
    (arch / f"{pkg}.pc").write_text(text)
    env = clean_env(PETSC_DIR=str(tmp_path / "petsc"), PETSC_ARCH="arch-own")
    env.pop("PKG_CONFIG_PATH", None)
    run(["cmake", "-S", ROOT, "-B", str(tmp_path / "b"), f"-DADHBEM_PETSC_PKG={pkg}", "-DADHBEM_BUILD_PYTHON=OFF"], env=env)
    cache = (tmp_path / "b" / "CMakeCache.txt").read_text()
    assert "ADHBEM_OWN_PETSC_MARK" in cache
