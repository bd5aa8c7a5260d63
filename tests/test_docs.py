"""The documentation site builds with Sphinx without a warning (``./run docs`` builds it in full),
its tutorials run (small, ADHBEM_TUTORIAL_QUICK), and its references hold every public C function
and type of include/adhbem.h and every Python entry point: they are made from the code, so a
function without a manual page or a docstring that Sphinx cannot read fails here."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from common import ROOT
from test_manual_pages import public_functions

pytestmark = pytest.mark.timeout(1200)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    from adhbem import PETSc
    if PETSc.COMM_WORLD.getSize() > 1:
        pytest.skip("builds the site in a process of its own")
    out = tmp_path_factory.mktemp("site")
    # The quick tutorials' pages (sphinx-gallery writes them into the source tree, docs/tutorials/,
    # and reuses them while the scripts are unchanged) must never reach the site ./run docs builds:
    # the quick site is built from a tree of its own, the project's folders linked and docs/ copied.
    tree = out / "tree"
    tree.mkdir()
    for entry in os.listdir(ROOT):
        if entry != "docs" and not entry.startswith("."):
            os.symlink(os.path.join(ROOT, entry), tree / entry)
    shutil.copytree(os.path.join(ROOT, "docs"), tree / "docs", ignore=shutil.ignore_patterns("tutorials"))
    before = published_tutorials()
    env = dict(os.environ, ADHBEM_TUTORIAL_QUICK="1", MPLBACKEND="Agg")
    env.setdefault("ADHBEM_BUILD", os.path.join(ROOT, "build"))
    r = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                        "-d", str(out / "doctrees"), str(tree / "docs"), str(out / "html")],
                       capture_output=True, text=True, env=env, timeout=1200)
    assert r.returncode == 0, f"the site does not build cleanly:\n{r.stderr[-6000:]}"
    assert published_tutorials() == before, "the quick tutorials were written where ./run docs reads them"
    return out / "html"


def published_tutorials():
    """What docs/tutorials/ (sphinx-gallery's pages for ./run docs) holds: names and times."""
    folder = os.path.join(ROOT, "docs", "tutorials")
    if not os.path.isdir(folder):
        return {}
    return {os.path.join(d, f): os.stat(os.path.join(d, f)).st_mtime_ns for d, _, fs in os.walk(folder) for f in fs}


def text_of(path):
    with open(path) as f:
        return re.sub(r"<[^>]+>", "", f.read())


def test_every_public_c_function_in_the_reference(site):
    """Each has an entry of its own (the C domain's anchor c.NAME), not only a mention."""
    pages = "".join((p).read_text() for p in (site / "reference" / "c-api").glob("*.html"))
    missing = [f for f in public_functions() if f'id="c.{f}"' not in pages]
    assert not missing, f"public functions missing from the C API reference: {missing}"
    with open(os.path.join(ROOT, "include", "adhbem.h")) as f:
        header = f.read()
    types = set(re.findall(r"^typedef .*?\b(\w+);", header, re.M)) | set(re.findall(r"^\} (\w+);", header, re.M))
    assert len(types) > 10 and not [t for t in types if f'id="c.{t}"' not in pages]


def test_every_python_entry_point_in_the_reference(site):
    page = text_of(site / "reference" / "python-api.html")
    for name in ("adhbem.Solver", "solve_path", "iterate_path", "adhbem.load", "adhbem.compliance",
                 "adhbem.rough_surface", "adhbem.plot.figure", "adhbem.plot.curve", "adhbem.theory.maugis_pulloff"):
        assert name.split(".")[-1] in page, name


def test_every_option_in_the_reference(site):
    from adhbem.options import solver_options
    page = text_of(site / "reference" / "options.html")
    missing = [o.name for o in solver_options() if f"-adh_{o.name}" not in page]
    assert not missing, missing


def test_tutorials_ran_with_figures(site):
    tutorials = sorted(p for p in os.listdir(os.path.join(ROOT, "tutorials")) if p.startswith("tutorial_") and p.endswith(".py"))
    assert len(tutorials) >= 6, tutorials
    for t in tutorials:
        page = site / "tutorials" / t.replace(".py", ".html")
        assert page.exists(), t
        assert re.search(r'<img [^>]*src="\.\./_images/sphx_glr_' + t[:-3], page.read_text()), f"{t} made no figure"


def howto_python_blocks():
    """(page, code) for each how-to page with Python code blocks, its blocks joined in order."""
    folder = os.path.join(ROOT, "docs", "howto")
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name)) as f:
            blocks = re.findall(r"^```python\n(.*?)^```", f.read(), re.S | re.M)
        if blocks:
            yield name, "\n".join(blocks)


@pytest.mark.parametrize("page,code", list(howto_python_blocks()), ids=lambda v: v if v.endswith(".md") else "")
def test_howto_python_blocks_run(page, code, tmp_path, monkeypatch, capsys):
    """The how-to guides' Python examples run as written (in a folder of their own), and what they
    print is checked where they print a result against theory."""
    monkeypatch.chdir(tmp_path)
    if "results/rough_example.h5" in code:   # the file examples/rough.opts writes, made small here
        import adhbem
        os.makedirs("results")
        adhbem.Solver(n=32, size=32.0, boundary="periodic", indenter="rough", gamma=0.01, start="adhesive",
                      path=[0.0, 0.5, -0.5], steps=4, output="results/rough_example.h5",
                      fields="all").solve_path(progress=False)
    exec(compile(code, page, "exec"), {"__name__": "__howto__"})
    out = capsys.readouterr().out
    if page == "own-ksp.md":  # the flat punch against Boussinesq's 2 a E* d
        F, exact = (float(x) for x in re.search(r"F = ([\d.e-]+), Boussinesq 2 a E\* d = ([\d.e-]+)", out).groups())
        assert abs(F / exact - 1) < 0.01, out


def test_howto_guides_have_python_examples():
    assert {"load-control.md", "own-ksp.md"} <= {p for p, _ in howto_python_blocks()}
