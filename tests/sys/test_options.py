"""adhbem's own options: the list the checks use is the list -help shows, besides the types' own
options, which it shows in a group of each type's; a misspelled -adh_
option stops the executable, naming the nearest option; a misspelled keyword of Solver() is a
TypeError; PETSc's own options under the prefix (-adh_ksp_*) are PETSc's, and one that the
solver's KSP does not read is refused at set-up. Other mistakes (a missing options file, PETSc's
options without the prefix, an output naming a directory, an unreachable first force) stop the
run at set-up with one line naming the option; a topography on the default free boundary gets a
warning line."""
import os
import re
import subprocess

import pytest

import adhbem
from adhbem import PETSc, _adhbem
from adhbem_build import EXE



def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def test_option_list_is_what_help_shows():
    """The solver's own options are the list the checks use; each registered type's own options are
    shown in a group of the type's, "adhbem <kind> <type> (-adh_<kind> <type>):", whichever type is
    in use."""
    serial_only()
    r = subprocess.run([EXE, "-help", "-adh_path", "0.01,0", "-adh_steps", "1"], capture_output=True, text=True)
    groups, title = {}, ""
    for line in r.stdout.splitlines():
        if line and not line.startswith(" ") and line.endswith(":"):
            title = line[:-1]
        for m in re.findall(r"^\s*-(adh_[A-Za-z0-9_]+)", line):
            if not m.startswith(("adh_ksp_", "adh_pc_", "adh_local_ksp_", "adh_local_pc_")):
                groups.setdefault(title, set()).add(m)
    typed = {t: o for t, o in groups.items() if re.search(r"\(-adh_(elastic|criterion|control|predictor) [\w-]+\)$", t)}
    assert set(typed) >= {"adhbem elastic body layer (-adh_elastic layer)",
                          "adhbem detachment criterion crack-closure (-adh_criterion crack-closure)",
                          "adhbem load control force (-adh_control force)",
                          "adhbem contact-set predictor polonsky-keer (-adh_predictor polonsky-keer)"}
    assert typed["adhbem load control force (-adh_control force)"] == {"adh_pulloff_rtol"}
    assert typed["adhbem elastic body layer (-adh_elastic layer)"] == {"adh_layer_thickness", "adh_layer_base"}
    own = set().union(*(o for t, o in groups.items() if t not in typed))
    assert own == set(_adhbem.option_names())


def test_misspelled_option_stops_the_executable(tmp_path):
    serial_only()
    out = tmp_path / "x.h5"
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_gama", "0.01", "-adh_path", "0.01,0", "-adh_output", str(out)],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "Unknown option -adh_gama (did you mean -adh_gamma?)" in r.stderr + r.stdout
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())


def test_petsc_options_under_the_prefix_are_petscs():
    serial_only()
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_path", "0.01,0", "-adh_steps", "1", "-adh_ksp_converged_reason"],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "Linear adh_ solve converged" in r.stdout


def test_misspelled_keyword_is_a_type_error():
    with pytest.raises(TypeError, match=r"unknown option 'radus' \(did you mean 'radius'\?\)"):
        adhbem.Solver(n=32, radus=1.0)
    adhbem.Solver(n=32, radius=1.0, ksp_rtol=1e-9)  # PETSc's options pass


@pytest.mark.parametrize("ranks", [1, 2])
def test_an_error_is_one_line(tmp_path, ranks):
    """The message once, first and alone (not inside PETSc's traceback of every frame and rank);
    -adh_traceback brings the traceback back."""
    serial_only()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    cmd = ["mpirun", "-n", str(ranks), EXE, "-adh_n", "32", "-adh_steps", "0", "-adh_path", "0.01,0"]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode != 0
    lines = [l for l in (r.stderr + r.stdout).splitlines() if "adhbem" in l or "PETSC" in l]
    assert lines[0] == "adhbem: error: -adh_steps must be >= 1, got 0"
    assert sum("adhbem: error" in l for l in lines) == 1 and not any("PETSC ERROR" in l for l in lines)
    r = subprocess.run(cmd + ["-adh_traceback"], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode != 0 and "PETSC ERROR" in r.stderr + r.stdout and "-adh_steps must be >= 1" in r.stderr + r.stdout


# ---- Mistakes: one line naming the option, at set-up, before any solve -------------------------------

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
BASE = ["-adh_n", "32", "-adh_path", "0.01,0", "-adh_steps", "2", "-adh_monitor"]


def refused(tmp_path, *args, ranks=1):
    """Runs adhbem with args (and -adh_output in tmp_path); checks it stopped before any state with
    one line of adhbem's and no PETSc dump, leaving no results; returns that line."""
    out = tmp_path / "x.h5"
    cmd = [EXE, *args, "-adh_output", str(out)]
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks), *cmd]
    r = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=300)
    assert r.returncode != 0
    lines = [l for l in (r.stderr + r.stdout).splitlines() if "adhbem" in l or "PETSC" in l]
    assert len(lines) == 1 and lines[0].startswith("adhbem: error: "), r.stderr[-3000:] + r.stdout[-1000:]
    assert not re.search(r"^\s+0 ", r.stdout, re.M), r.stdout  # no state was computed
    assert not any(p.name.startswith("x.") for p in tmp_path.iterdir())
    return lines[0]


@pytest.mark.parametrize("ranks", [1, 2])
def test_missing_options_file(tmp_path, ranks):
    serial_only()
    line = refused(tmp_path, "-options_file", str(tmp_path / "none.opts"), *BASE, ranks=ranks)
    assert line == f"adhbem: error: -options_file {tmp_path / 'none.opts'}: no such file (or not readable)"


@pytest.mark.parametrize("option, says", [
    ("-adh_ksp_rtoll", "Option -adh_ksp_rtoll is not read by the solver's KSP (cg) or its preconditioner (did you mean -adh_ksp_rtol?)"),
    ("-adh_pc_tpye", "(did you mean -adh_pc_type?)"),
    ("-adh_ksp_gmres_restart", "Option -adh_ksp_gmres_restart is not read by the solver's KSP (cg)"),
    ("-ksp_rtol", "-ksp_rtol does nothing: the solver's KSP and PC options have the prefix adh_ (-adh_ksp_rtol)"),
    ("-pc_type", "-pc_type does nothing"),
    ("-adh_ksp_guess_type", "-adh_ksp_guess_type: PETSc's initial guesses (KSPGuess) need one operator size"),
])
def test_ksp_options_nothing_reads(tmp_path, option, says):
    """A misspelled option of the solver's KSP (or one of another KSP type), and PETSc's options
    without adhbem's prefix, which no KSP of adhbem's reads."""
    serial_only()
    value = "none" if "pc_t" in option else "30" if "gmres" in option else "fischer" if "guess" in option else "1e-8"
    assert says in refused(tmp_path, *BASE, option, value)


def test_solve_time_ksp_options_pass(tmp_path):
    """Options that PETSc reads only when it solves are not mistaken for misspelled ones."""
    serial_only()
    r = subprocess.run([EXE, *BASE, "-adh_ksp_converged_reason", "-adh_ksp_view_final_residual", "-adh_ksp_rtol", "1e-9"],
                       capture_output=True, text=True, env=ENV, timeout=300)
    assert r.returncode == 0 and "Linear adh_ solve converged" in r.stdout, r.stderr[-2000:]


def test_a_ksp_option_misspelled_in_python_is_refused():
    """The same check for the Python Solver's KSP keywords, at set-up."""
    with pytest.raises(ValueError) as e:
        adhbem.Solver(n=16, path=[0.01, 0.0], steps=1, ksp_rtoll=1e-9).solve_path()
    assert "ksp_rtoll is not read by the solver's KSP" in str(e.value) and "ksp_rtol?" in str(e.value)


@pytest.mark.parametrize("name", ["dir", "dir/"])
def test_output_naming_a_directory(tmp_path, name):
    serial_only()
    (tmp_path / "dir").mkdir()
    out = str(tmp_path / name)
    r = subprocess.run([EXE, *BASE, "-adh_output", out], capture_output=True, text=True, env=ENV, timeout=300)
    assert r.returncode != 0
    assert r.stderr.strip() == f"adhbem: error: -adh_output: cannot write {out}: it is a directory; give a file name (DIR/run.h5)"
    assert not re.search(r"^\s+0 ", r.stdout, re.M)
    r = subprocess.run([EXE, *BASE, "-adh_checkpoint", str(tmp_path / "dir")], capture_output=True, text=True, env=ENV,
                       timeout=300)
    assert r.returncode != 0 and "-adh_checkpoint" in r.stderr and "it is a directory" in r.stderr


def test_unreachable_first_force(tmp_path):
    """Force control from first touch cannot start under tension: refused naming -adh_path (it
    recorded a pull-off of the unpressed contact, and F = 0 for the states after it)."""
    serial_only()
    line = refused(tmp_path, *BASE, "-adh_gamma", "1e-3", "-adh_control", "force", "-adh_start", "adhesive",
                   "-adh_path", "-0.001,0.01")
    assert "-adh_path: the first force is -0.001, a tension the start cannot reach" in line


def test_topography_on_the_default_free_boundary_warns(tmp_path):
    """A rough surface or a topography file on the free boundary by default: one warning line, at
    set-up, saying how to choose the periodic cell; none when -adh_boundary is given."""
    serial_only()
    import numpy as np
    np.save(tmp_path / "h.npy", np.add.outer(np.arange(16.0), np.arange(16.0)) % 5 * 0.01)
    runs = {"rough": ["-adh_n", "16", "-adh_size", "16", "-adh_indenter", "rough", "-adh_path", "0,0.2", "-adh_steps", "1"],
            "file": ["-adh_n", "16", "-adh_topography", str(tmp_path / "h.npy"), "-adh_path", "0,0.02", "-adh_steps", "1"]}
    for kind, args in runs.items():
        r = subprocess.run([EXE, *args, "-adh_monitor"], capture_output=True, text=True, env=ENV, timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
        warned = [l for l in r.stdout.splitlines() if l.startswith("adhbem: warning")]
        assert len(warned) == 1 and "default free boundary" in warned[0] and "add -adh_boundary periodic" in warned[0], r.stdout
        assert r.stdout.index("adhbem: warning") < r.stdout.index("state "), r.stdout  # at set-up
        for boundary in ("free", "periodic"):
            r = subprocess.run([EXE, *args, "-adh_boundary", boundary], capture_output=True, text=True, env=ENV, timeout=300)
            assert r.returncode == 0 and "warning" not in r.stdout + r.stderr, r.stdout


def test_help_lists_adhbems_options_first():
    """-help: the intro, then adhbem's groups, with no PETSc option before the first of them and
    no sentinel default (-adh_E2 shows inf, a rigid body); a line at the end points to PETSc's
    options for every program, which -help petsc lists before adhbem's."""
    serial_only()
    out = subprocess.run([EXE, "-help"], capture_output=True, text=True, timeout=60).stdout
    lines = out.splitlines()
    first = next(k for k, line in enumerate(lines) if re.match(r"\s+-\w", line))
    assert lines[first].lstrip().startswith(("-adh_n ", "-adh_n:")), lines[:first + 1]
    assert "Options for all PETSc programs" not in out and "-on_error_attach_debugger" not in out
    assert "4.49423e+307" not in out and re.search(r"^  -adh_E2:? <(now )?inf\. : (formerly )?inf\.>", out, re.M)
    assert "PETSc's options for every program (-log_view, -info, -options_file, -malloc_debug, the debugger, ...): adhbem -help petsc" in out
    full = subprocess.run([EXE, "-help", "petsc"], capture_output=True, text=True, timeout=60).stdout
    assert full.index("Options for all PETSc programs") < full.index("adhbem grid:")


def test_help_shows_the_surfaces_defaults_of_this_grid():
    """The rough surface's defaults that depend on the grid are shown as this grid's values (the
    cell size and 4 spacings), not as a -2 that means "default"; a -2 given is refused, not taken
    for the default."""
    serial_only()
    out = subprocess.run([EXE, "-adh_n", "64,32", "-adh_size", "32,8", "-help"], capture_output=True, text=True,
                         timeout=60).stdout
    assert re.search(r"^  -adh_rolloff_wavelength:? <32\. : 32\.>", out, re.M), out
    assert re.search(r"^  -adh_cutoff_wavelength:? <2\. : 2\.>", out, re.M), out
    assert re.search(r"^  -adh_rms_slope:? <0\.1 : 0\.1>", out, re.M), out
    assert not re.search(r"^  -adh_\w+:? <-2\.", out, re.M), out
    for option in ("-adh_rolloff_wavelength", "-adh_cutoff_wavelength"):
        r = subprocess.run([EXE, "-adh_indenter", "rough", "-adh_boundary", "periodic", option, "-2"], capture_output=True,
                           text=True, timeout=60)
        assert r.returncode != 0 and f"{option} must be positive and finite, got -2" in r.stdout + r.stderr, r.stdout
