"""adhbem.load (the results file as NumPy arrays, fields read lazily) and python3 -m adhbem.plot
(curves against the analytic solution where there is one, area against force, contact maps),
on the output of every indenter and both boundaries; both work without petsc4py. The figure's
labels, legs, markers, units and normalised axes are checked on the Figure object."""
import subprocess
import sys

import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from adhbem.plot import analytic, figure
from adhbem.plot import main as plot_main
from adhbem_build import EXE
from common import python_env


CASES = {
    "sphere": ["-adh_indenter", "sphere", "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.004"],
    "hertz": ["-adh_indenter", "sphere", "-adh_gamma", "0", "-adh_path", "0,0.01"],
    "punch": ["-adh_indenter", "punch", "-adh_punch_radius", "0.25", "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.05"],
    "cone": ["-adh_indenter", "cone", "-adh_cone_slope", "0.1", "-adh_gamma", "1e-4", "-adh_path", "0.02,-0.002"],
    "rough": ["-adh_indenter", "rough", "-adh_boundary", "periodic", "-adh_size", "32", "-adh_gamma", "0.004",
              "-adh_start", "adhesive", "-adh_attach", "reach", "-adh_path", "0,0.3,-0.3"],
    "periodic sphere": ["-adh_indenter", "sphere", "-adh_boundary", "periodic", "-adh_gamma", "1e-3", "-adh_path", "0.01,-0.004"],
}


def serial_only():
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("starts its own process")


def run(tmp_path, name, args, fields=True):
    out = tmp_path / f"{name.replace(' ', '_')}.h5"
    r = subprocess.run([EXE, "-adh_n", "32", "-adh_steps", "4", *args, *(["-adh_fields"] if fields else []),
                        "-adh_output", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    return out


@pytest.mark.parametrize("name", list(CASES))
def test_plot_every_indenter_and_boundary(tmp_path, name):
    serial_only()
    out = run(tmp_path, name, CASES[name])
    r = subprocess.run([sys.executable, "-m", "adhbem.plot", str(out)], capture_output=True, text=True, env=python_env())
    assert r.returncode == 0, r.stderr[-2000:]
    png = out.with_suffix(".png")
    assert r.stdout.strip() == str(png) and png.stat().st_size > 10000
    with adhbem.load(out) as res:
        ref = analytic(res.params, res.curve["d"], res.curve["area"])
        expected = {"sphere": "JKR", "hertz": "Hertz", "punch": "Kendall", "cone": "JKR-type cone"}.get(name)
        assert (ref[0] if ref else None) == expected


def test_load_gives_the_curve_and_the_fields(tmp_path):
    serial_only()
    # the file of this very solver: another process's FFTW plans (and this one's wisdom from earlier
    # tests) may differ from it in the last bits
    out = tmp_path / "sphere.h5"
    s = adhbem.Solver(n=32, indenter="sphere", gamma=1e-3, path=[0.01, -0.004], steps=4, fields="all", output=str(out))
    c = s.solve_path()
    with adhbem.load(out) as r:
        for key in ("d", "force", "contact_points", "patches", "detach_ratio"):
            assert np.array_equal(r.curve[key], c[key]), key
        assert r.params["indenter"] == "sphere" and r.params["Nx"] == 32 and r.params["complete"] == 1
        assert r.field_names == ["pressure", "displacement", "gap", "contact"]
        assert np.array_equal(r.states, np.arange(len(c["d"])))
        p = r.field("pressure", -1)
        assert p.shape == (32, 32)
        assert np.array_equal(p, adhbem.gather(s.pressure, s.compliance))
        assert int(r.field("contact", 2).sum()) == c["contact_points"][2]
        assert r.profile.shape == (32, 32) and r.critical_stress.shape == (32, 32)
        with pytest.raises(KeyError, match="no fields of state"):
            r.field("pressure", 99)
    nofields = run(tmp_path, "plain", CASES["sphere"], fields=False)
    with adhbem.load(nofields) as r:
        assert r.field_names == [] and len(r.states) == 0
        with pytest.raises(KeyError, match="-adh_fields"):
            r.field("gap", 0)


def test_load_keeps_the_states_whole_in_every_column(tmp_path):
    """A part whose write failed on some ranks mid-row has columns of unequal length: load gives
    the states whole in every column (the CSV's, if it has more whole ones), never a ragged curve."""
    serial_only()
    import h5py
    out = tmp_path / "r.h5"
    c = adhbem.Solver(n=16, gamma=1e-3, path=[0.01, -0.004], steps=4, output=str(out)).solve_path()
    n = len(c["d"])
    with h5py.File(out, "r+") as f:  # the next state's row, half written
        for key in ("d", "area"):
            row = f["curve"][key][()]
            del f["curve"][key]
            f["curve"][key] = np.append(row, row[-1])
    with adhbem.load(out) as r:
        assert {len(v) for v in r.curve.values()} == {n}
        assert np.array_equal(r.curve["force"], c["force"]) and np.array_equal(r.curve["d"], c["d"])


def test_plot_of_a_missing_file_says_so(tmp_path):
    serial_only()
    r = subprocess.run([sys.executable, "-m", "adhbem.plot", str(tmp_path / "none.h5")], capture_output=True, text=True, env=python_env())
    assert r.returncode == 1 and "none.h5" in r.stderr and "Traceback" not in r.stderr


# A Python without PETSc (a laptop that reads results): petsc4py, mpi4py and adhbem's C extension
# cannot be imported in it.
WITHOUT_PETSC = """
import importlib.abc, runpy, sys

class Blocked(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("petsc4py", "mpi4py") or name == "adhbem._adhbem":
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None

sys.meta_path.insert(0, Blocked())
results, png = sys.argv[1:]

import adhbem
with adhbem.load(results) as r:
    assert r.params["indenter"] == "sphere" and len(r.curve["d"]) > 2, r.params
    assert r.field("pressure", -1).shape == (32, 32)
try:
    adhbem.Solver
    raise AssertionError("adhbem.Solver without petsc4py")
except ImportError as e:
    assert "petsc4py" in str(e) and "adhbem.load" in str(e), e

sys.argv = ["python3 -m adhbem.plot", results, "--out", png]
try:
    runpy.run_module("adhbem.plot", run_name="__main__", alter_sys=True)
except SystemExit as e:
    assert e.code == 0, e.code
loaded = [m for m in sys.modules if m.split(".")[0] in ("petsc4py", "mpi4py") or m == "adhbem._adhbem"]
assert not loaded, loaded
print("read and plotted without PETSc")
"""


def test_load_and_plot_without_petsc4py(tmp_path):
    serial_only()
    out = run(tmp_path, "sphere", CASES["sphere"])
    png = tmp_path / "laptop.png"
    r = subprocess.run([sys.executable, "-c", WITHOUT_PETSC, str(out), str(png)], capture_output=True, text=True,
                       env=python_env(), timeout=120)
    assert r.returncode == 0, r.stderr[-3000:]
    assert "read and plotted without PETSc" in r.stdout and png.stat().st_size > 10000
    # and where petsc4py is installed, import adhbem alone does not start PETSc either
    r = subprocess.run([sys.executable, "-c", "import sys, adhbem; print(sorted(m for m in sys.modules if 'petsc' in m))"],
                       capture_output=True, text=True, env=python_env(), timeout=60)
    assert r.returncode == 0 and r.stdout.strip() == "[]", r.stdout + r.stderr[-2000:]


# ---- the figure: labels, legs, markers, sizes, normalised axes, bad options ----------------------

def legend(fig):
    """The entries of the figure's legend (figure() draws one, above its panels)."""
    return [t.get_text() for t in fig.legends[0].get_texts()]


def line(ax, label):
    found = [ln for ln in ax.get_lines() if ln.get_label() == label]
    assert len(found) == 1, (label, [ln.get_label() for ln in ax.get_lines()])
    return found[0]


JKR = ["-adh_indenter", "sphere", "-adh_gamma", "1e-3", "-adh_path", "0,0.02,-0.03"]


def test_compare_labels_say_what_differs(tmp_path):
    serial_only()
    paper = ["-adh_criterion", "pohrt-popov"]
    a = run(tmp_path, "a", JKR + paper, fields=False)
    b = run(tmp_path, "b", JKR + ["-adh_criterion", "crack-closure"], fields=False)
    c = run(tmp_path, "c", ["-adh_indenter", "sphere", "-adh_gamma", "2e-3", "-adh_path", "0,0.02,-0.03"] + paper, fields=False)
    names = legend(figure(str(a), compare=[str(b), str(c)]))
    # the attach rule differs too: each criterion's default (reach with the paper's, griffith)
    assert "a: dgamma = 0.001, pohrt-popov, attach reach" in names
    assert "b: dgamma = 0.001, crack-closure (radius 16-64), attach griffith" in names
    assert "c: dgamma = 0.002, pohrt-popov, attach reach" in names
    assert "approach" in names and "retraction" in names  # the legs' line styles, once
    # what is the same (grid, boundary, control) is not repeated; the attach rule when files have it
    assert not any("N = 32" in n or "boundary" in n for n in names)
    import h5py
    with h5py.File(b, "r+") as f:
        f.attrs["attach"] = "reach"
    with h5py.File(a, "r+") as f:
        f.attrs["attach"] = "penetration"
    d = run(tmp_path, "d", JKR + paper + ["-adh_n", "24"], fields=False)
    names = legend(figure(str(a), compare=[str(b), str(d)]))
    assert "a: pohrt-popov, attach penetration, N = 32" in names
    assert "b: crack-closure (radius 16-64), attach reach, N = 32" in names
    assert "d: pohrt-popov, attach reach, N = 24" in names
    names = legend(figure(str(a), compare=[str(b)], labels=["paper", "ours"]))
    assert "paper" in names and "ours" in names


def test_a_gamma_field_is_labelled_as_one(tmp_path):
    serial_only()
    g = tmp_path / "stripes.npy"
    np.save(g, np.where(np.arange(32)[None, :] < 16, 2e-3, 5e-4) * np.ones((32, 1)))
    out = run(tmp_path, "field", ["-adh_indenter", "sphere", "-adh_gamma_field", str(g), "-adh_path", "0,0.02,-0.03"], fields=False)
    from adhbem.plot import run_labels
    with adhbem.load(out) as r:
        assert run_labels([str(out)], [r.params]) == ["dgamma field stripes.npy"]
    names = legend(figure(str(out)))
    assert not any("Hertz" in n or "JKR" in n for n in names)  # no theory for a field


def test_approach_and_retraction_and_the_pull_off_marker(tmp_path):
    serial_only()
    # from before first touch, and a last leg after the contact was lost: states with nothing in contact
    out = run(tmp_path, "jkr", ["-adh_indenter", "sphere", "-adh_gamma", "1e-3", "-adh_path", "-0.02,0.02,-0.03,-0.04"])
    fig = figure(str(out))
    with adhbem.load(out) as r:
        d, F, points = r.curve["d"], r.curve["force"], r.curve["contact_points"]
        pulled = int(np.nonzero(r.curve["pulled_off"])[0][0])
    ax = fig.axes[0]
    up, down = line(ax, "approach"), line(ax, "retraction")
    assert np.all(np.diff(up.get_xdata()) > 0) and np.all(np.diff(down.get_xdata()) < 0)
    assert up.get_linestyle() != down.get_linestyle()
    # every state in contact is drawn, and of those with nothing in contact only the neighbours of one
    drawn = len(up.get_xdata()) + len(down.get_xdata()) - 1  # they share the turning point
    touching = points > 0
    near = touching.copy()
    near[1:] |= touching[:-1]
    near[:-1] |= touching[1:]
    assert drawn == near.sum() and near.sum() < len(d)  # the retraction's empty states are left out
    assert np.count_nonzero(down.get_ydata() == 0) == 1  # but the one where the contact was lost
    star = line(ax, f"pull-off force {-F.min():.3g}")
    assert star.get_ydata()[0] == F.min() and star.get_color() == "red"
    lost = line(ax, "contact lost")
    assert lost.get_xdata()[0] == d[pulled]
    theory = line(ax, "JKR theory")
    # the theory over the data's range only
    assert theory.get_xdata().min() >= min(up.get_xdata().min(), down.get_xdata().min())
    assert theory.get_xdata().max() <= max(up.get_xdata().max(), down.get_xdata().max())
    assert {"approach", "retraction", "JKR theory", "contact lost"} <= set(legend(fig))


def test_labels_titles_and_size_for_a_paper(tmp_path):
    """Column width 3.5 in, page width 7.2 in; symbols on the axes, no units text, no file path
    anywhere; contact maps titled by what the state is, with a colour bar; PDF and SVG by the
    extension of --out."""
    serial_only()
    out = run(tmp_path, "jkr", JKR)
    fig = figure(str(out))
    assert tuple(fig.get_size_inches())[0] == 3.5
    labels = [fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel(), fig.axes[1].get_xlabel(), fig.axes[1].get_ylabel()]
    # forces of a few 1e-3: plain tick labels, the power of ten in the label
    assert labels == ["indentation $d$", "force $F$ ($\\times 10^{-3}$)", "force $F$ ($\\times 10^{-3}$)", "contact area $A$"]
    fig.canvas.draw()
    ticks = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert "0" in ticks and all(len(t) <= 4 for t in ticks), ticks  # short labels: -4.5, not -0.0045
    assert any(t.startswith("\N{MINUS SIGN}") for t in ticks)
    maps = [a for a in fig.axes if a.get_title()]
    titles = [a.get_title() for a in maps]
    assert titles[0].startswith("deepest indentation\n$d$ = 0.02") and titles[1].startswith("largest tension\n")
    assert sum(1 for a in fig.axes if a.get_label() == "<colorbar>") == 2
    texts = [t.get_text() for a in fig.axes for t in a.texts] + [fig._suptitle.get_text() if fig._suptitle else ""]
    texts += titles + legend(fig) + labels
    assert not any(str(tmp_path) in t or "jkr.h5" in t or "input units" in t for t in texts), texts
    wide = figure(str(out), width="double")
    assert tuple(wide.get_size_inches())[0] == 7.2 and len([a for a in wide.axes if a.get_visible()]) == 6  # 4 panels, 2 bars
    for ext, magic in ((".pdf", b"%PDF"), (".svg", b"<?xml"), (".png", b"\x89PNG")):
        target = tmp_path / f"fig{ext}"
        assert plot_main([str(out), "--out", str(target)]) == 0
        assert target.read_bytes()[:len(magic)] == magic
    from PIL import Image
    with Image.open(tmp_path / "fig.png") as im:
        assert im.size[0] == 1050  # 3.5 in at 300 dpi
    assert plot_main([str(out), "--width", "double", "--out", str(tmp_path / "w.png")]) == 0
    with Image.open(tmp_path / "w.png") as im:
        assert im.size[0] == 2160


def test_panels_draw_on_the_users_axes(tmp_path):
    """One function a panel, on axes of the user's own figure."""
    serial_only()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from adhbem import plot as P
    out = run(tmp_path, "rough", CASES["rough"])
    fig, ax = plt.subplots(2, 2)
    P.curve(ax[0, 0], str(out))
    with adhbem.load(out) as r:
        P.area(ax[0, 1], r)  # a loaded file works as well as a name
        row = P.contact_map(ax[1, 0], r, "tension")
        assert row == int(np.argmin(r.curve["force"]))
    P.resolution(ax[1, 1], str(out))
    assert ax[0, 0].get_ylabel().startswith("mean pressure $\\bar p$") and ax[0, 1].get_ylabel() == "contact area fraction"
    assert ax[1, 0].get_title().startswith("largest tension\n")
    assert ax[0, 0].get_legend() is not None
    plt.close(fig)


def test_normalised_jkr_sphere(tmp_path):
    serial_only()
    out = run(tmp_path, "jkr", JKR)
    fig = figure(str(out), normalised=True)
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("indentation $d/|d_c|$", "force $F/F_\\mathrm{adh}$")
    assert fig.axes[1].get_ylabel() == "contact radius $a/a_c$"
    gamma, R, E = 1e-3, 1.0, 1.0
    Fadh, ac = 1.5 * np.pi * gamma * R, (9 * np.pi * gamma * R ** 2 / (8 * E)) ** (1 / 3)
    dc = (3 * np.pi ** 2 * gamma ** 2 * R / (64 * E ** 2)) ** (1 / 3)
    with adhbem.load(out) as r:
        c = r.curve
    up = line(ax, "approach")
    k = len(up.get_xdata())
    assert np.allclose(up.get_xdata(), c["d"][:k] / dc, rtol=1e-12) and np.allclose(up.get_ydata(), c["force"][:k] / Fadh, rtol=1e-12)
    area = line(fig.axes[1], "approach")
    assert np.allclose(area.get_ydata(), np.sqrt(c["area"][:k] / np.pi) / ac, rtol=1e-12)
    star = [ln for ln in ax.get_lines() if ln.get_label().startswith("pull-off force")][0]
    assert star.get_ydata()[0] == c["force"].min() / Fadh
    # the annotations are normalised too, not dimensional
    assert star.get_label() == f"pull-off force {-c['force'].min() / Fadh:.3g} $F_\\mathrm{{adh}}$"
    titles = [a.get_title() for a in fig.axes if a.get_title()]
    assert titles and all("$d/|d_c|$ = " in t and "F_\\mathrm{adh}$ = " in t for t in titles), titles


def test_periodic_cell_in_mean_pressure_and_area_fraction(tmp_path):
    serial_only()
    out = run(tmp_path, "rough", CASES["rough"])
    fig = figure(str(out))
    with adhbem.load(out) as r:
        c, cell = r.curve, r.params["Lx"] * r.params["Ly"]
    assert cell == 32 * 32
    ax = fig.axes[0]
    assert ax.get_ylabel().startswith("mean pressure $\\bar p$")
    assert fig.axes[1].get_ylabel() == "contact area fraction"
    up = line(ax, "approach")
    k = len(up.get_ydata())
    assert np.array_equal(up.get_ydata(), c["force"][:k] / cell)
    area = line(fig.axes[1], "approach")
    assert np.array_equal(area.get_ydata(), c["area"][:k] / cell) and area.get_ydata().max() <= 1


def test_bad_states_and_normalised_are_errors(tmp_path, capsys):
    serial_only()
    out = run(tmp_path, "jkr", JKR)
    with adhbem.load(out) as r:
        n = len(r.curve["d"])
    for states in ("99", f"{n}", f"-{n + 1}", "0,99"):
        with pytest.raises(SystemExit) as e:
            plot_main([str(out), "--states", states, "--out", str(tmp_path / "x.png")])
        err = capsys.readouterr().err
        assert e.value.code == 2 and "--states" in err and f"rows 0 to {n - 1}" in err, err
    assert plot_main([str(out), "--states", f"0,-1,{n - 1},deepest,tension", "--out", str(tmp_path / "x.png")]) == 0
    with pytest.raises(SystemExit):
        plot_main([str(out), "--states", "shallowest"])
    assert "'deepest' or 'tension'" in capsys.readouterr().err
    nofields = run(tmp_path, "nofields", JKR, fields=False)
    with pytest.raises(SystemExit):
        plot_main([str(nofields), "--states", "0"])
    assert "has no fields" in capsys.readouterr().err
    punch = run(tmp_path, "punch", CASES["punch"], fields=False)
    with pytest.raises(SystemExit):
        plot_main([str(punch), "--normalised"])
    assert "--normalised" in capsys.readouterr().err
    # through the command line too
    r = subprocess.run([sys.executable, "-m", "adhbem.plot", str(out), "--states", "99"], capture_output=True, text=True, env=python_env())
    assert r.returncode == 2 and "--states: 99 is not a state" in r.stderr and "Traceback" not in r.stderr


def test_resolution_panel(tmp_path):
    """--resolution adds the panel: the share of the tension in small patches per state, the
    pull-off state marked, the run's verdict as its title."""
    serial_only()
    rough = run(tmp_path, "rough", CASES["rough"], fields=False)
    fig = figure(str(rough), resolution_panel=True)
    a = [ax for ax in fig.axes if ax.get_visible()][-1]
    assert a.get_title().startswith("adhesion not resolved\n($a_c/h$ = ")
    assert any(ln.get_label().startswith("pull-off force: not resolved") for ln in a.get_lines())
    assert not any(ax.get_title().startswith("adhesion") for ax in figure(str(rough)).axes)


def test_runs_that_never_touch_and_fields_of_every_kth_state(tmp_path):
    """A path that never touches plots (nothing to name, no theory range to take); with fields of
    every K-th state the maps are those written nearest, titled as such, one map a drawn state."""
    serial_only()
    for name, args in (("apart", ["-adh_indenter", "sphere", "-adh_gamma", "1e-3", "-adh_path", "-0.2,-0.1"]),
                       ("apart_cell", CASES["rough"][:-2] + ["-adh_path", "-3,-2"])):
        out = run(tmp_path, name, args)
        assert plot_main([str(out), "--out", str(tmp_path / f"{name}.png")]) == 0
    strided = run(tmp_path, "strided", JKR + ["-adh_fields_stride", "3"])
    fig = figure(str(strided))
    titles = [a.get_title() for a in fig.axes if a.get_title()]
    with adhbem.load(strided) as r:
        deepest = int(np.argmax(r.curve["d"]))
        written = list(r.states)
    assert written == list(range(0, written[-1] + 1, 3)) and deepest not in written
    nearest = min(written, key=lambda k: abs(k - deepest))
    assert titles[0].startswith(f"state {nearest}, the written one nearest the deepest indentation\n")
    assert len(titles) == len(set(titles))


def test_force_control_marks_where_the_contact_was_lost(tmp_path):
    serial_only()
    out = run(tmp_path, "force", ["-adh_indenter", "sphere", "-adh_gamma", "1e-3", "-adh_control", "force",
                                  "-adh_path", "0.01,-0.01"], fields=False)
    fig = figure(str(out))
    with adhbem.load(out) as r:
        k = int(np.nonzero(r.curve["pulled_off"])[0][0])
        x = r.curve["force"][k]
    lost = line(fig.axes[0], "contact lost")
    assert lost.get_ydata()[0] == x and fig.axes[0].get_xlabel().endswith("force control")
