"""The source tree shows the architecture (docs/code-map.md): one folder per layer of src/, each
layer using only itself and the layers below it, the solver's registered types one file each
under src/solver/impls/<kind>/, registered in one place. Read from the sources, no build."""
import collections
import glob
import os
import re

import pytest

from common import ROOT

SRC = os.path.join(ROOT, "src")
# bottom to top: a layer may use itself and the layers before it
LAYERS = ["sys", "grid", "geometry", "solver", "results"]
# the one place a lower layer names a higher one: the registration of the solver's types and of
# the results writer (the way PETSc's XXXInitializePackage reaches its implementations)
REGISTRATION = "solver/interface/solverregis.c"
KINDS = {"criterion": "AdhCriterionCreate_", "control": "AdhControlCreate_", "predictor": "AdhPredictorCreate_"}


def sources():
    return sorted(os.path.relpath(p, SRC) for p in glob.glob(os.path.join(SRC, "**", "*.[ch]"), recursive=True))


def layer(path):
    return path.split("/")[0]


def code(path, strings=False):
    """The file without comments, and without string literals unless strings."""
    with open(os.path.join(SRC, path)) as f:
        text = f.read()
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    return text if strings else re.sub(r'"(?:\\.|[^"\\])*"', '""', text)


def definitions():
    """Every non-static Adh function, by the file that defines it."""
    where = {}
    for path in sources():
        if not path.endswith(".c"):
            continue
        for m in re.finditer(r"^(?!static)(?:PETSC_INTERN |PETSC_EXTERN )?[A-Za-z_][\w ]*?\**\s*\b(Adh\w+)\(", code(path), re.M):
            where.setdefault(m.group(1), path)
    return where


def test_every_source_file_is_in_a_layer():
    stray = [p for p in sources() if p != "main.c" and layer(p) not in LAYERS]
    assert not stray, f"files of src/ outside the layers {LAYERS}: {stray}"
    assert os.path.exists(os.path.join(ROOT, "include", "adhbem.h"))


def test_layers_use_only_themselves_and_the_layers_below():
    where = definitions()
    assert len(where) > 100, "the definitions were not found: the pattern no longer matches the sources"
    upward = collections.defaultdict(set)
    for path in sources():
        if path == "main.c" or path == REGISTRATION:
            continue
        text, mine = code(path), LAYERS.index(layer(path))
        for header in re.findall(r'#include\s+"([\w/]+\.h)"', code(path, strings=True)):
            if "/" in header and LAYERS.index(header.split("/")[0]) > mine:
                upward[path].add(header)
        for name in set(re.findall(r"\b(Adh\w+)\b", text)):
            home = where.get(name)
            if home and home != "main.c" and LAYERS.index(layer(home)) > mine:
                upward[path].add(f"{name} ({home})")
    assert not upward, "layers that reach up (docs/code-map.md): " + "; ".join(
        f"{p} uses {', '.join(sorted(u))}" for p, u in sorted(upward.items()))


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_each_registered_type_is_one_file_registered_in_one_place(kind):
    """An implementation includes only the solver's private header, defines one public function,
    its create, and solverregis.c registers it: a new type is one file and one line."""
    with open(os.path.join(SRC, REGISTRATION)) as f:
        registration = f.read()
    files = sorted(glob.glob(os.path.join(SRC, "solver", "impls", kind, "*.c")))
    assert len(files) >= 2
    for path in files:
        rel = os.path.relpath(path, SRC)
        text = code(rel)
        assert re.findall(r'#include\s+[<"]([^>"]+)[>"]', code(rel, strings=True)) == ["solver/solverimpl.h"], rel
        public = re.findall(r"^(?!static)[A-Za-z_][\w ]*?\b(Adh\w+)\(", text, re.M)
        assert len(public) == 1 and public[0].startswith(KINDS[kind]), f"{rel}: public functions {public}"
        assert re.search(rf"Register\(\w+, {public[0]}\)", registration), f"{public[0]} is not registered in {REGISTRATION}"
