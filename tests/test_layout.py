"""The source tree shows the architecture (docs/developers/code-map.md): one folder per layer of src/, each
layer using only itself and the layers below it, the solver's registered types one file each
under src/solver/impls/<kind>/, registered in one place. Read from the sources."""
import collections
import glob
import os
import re

import pytest

from common import ROOT

SRC = os.path.join(ROOT, "src")
# bottom to top: a layer may use itself and the layers before it
LAYERS = ["sys", "grid", "geometry", "solver", "results"]
# the one place a lower layer names a higher one: the solver's package, which binds the results
# writer and registers the built-in types (the way PETSc's XXXInitializePackage reaches its
# implementations); it may name the results layer's functions and the types' registration, nothing
# else above it. The types are registered in TYPES, beside them, so that a new type edits no
# interface file.
REGISTRATION = "solver/interface/solverpackage.c"
REGISTERED = r"^AdhSolverRegisterAll_Private$|^Adh(Output|Checkpoint)\w*_Private$"
TYPES = "solver/impls/register.c"
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
    """Every non-static function and variable of adhbem (a name with Adh in it), by the file that
    defines it: a function's body follows its parameters (a prototype ends with ';'), a
    variable's definition is at the start of a line, outside any function."""
    where = {}
    for path in sources():
        if not path.endswith(".c"):
            continue
        text = code(path)
        for m in re.finditer(r"^(?!static)(?:PETSC_INTERN |PETSC_EXTERN )?[A-Za-z_][\w ]*?\**\s*\b(\w*Adh\w*)\([^;{]*\)\s*\{", text, re.M):
            where.setdefault(m.group(1), path)
        for m in re.finditer(r"^(?!static|extern|typedef|PETSC_INTERN|PETSC_EXTERN|#)[A-Za-z_][\w *]*?\b(\w*Adh\w*)(?:\[\w*\])?\s*(?:=|;)", text, re.M):
            where.setdefault(m.group(1), path)
    return where


def includes(path):
    """The headers a file includes, as paths under src/ ("solver/solverimpl.h"), whatever the
    quotes or a relative path."""
    found = []
    for h in re.findall(r'#include\s+[<"]([^>"]+)[>"]', code(path, strings=True)):
        parts = [p for p in os.path.normpath(os.path.join(os.path.dirname(path), h)).split(os.sep) if p not in ("..", ".")]
        if h.startswith("."):
            found.append("/".join(parts))
        elif "/" in h and h.split("/")[0] in LAYERS:
            found.append(h)
    return found


def test_every_source_file_is_in_a_layer():
    stray = [p for p in sources() if p != "main.c" and layer(p) not in LAYERS]
    assert not stray, f"files of src/ outside the layers {LAYERS}: {stray}"
    assert os.path.exists(os.path.join(ROOT, "include", "adhbem.h"))


def test_layers_use_only_themselves_and_the_layers_below():
    where = definitions()
    assert len(where) > 100, "the definitions were not found: the pattern no longer matches the sources"
    upward = collections.defaultdict(set)
    for path in sources():
        if path == "main.c":
            continue
        text, mine = code(path), LAYERS.index(layer(path))
        for header in includes(path):
            if header.split("/")[0] in LAYERS and LAYERS.index(header.split("/")[0]) > mine \
                    and not (path == REGISTRATION and header == "results/resultsimpl.h"):
                upward[path].add(header)
        for name in set(re.findall(r"\b(\w*Adh\w*)\b", text)):
            home = where.get(name)
            if not home or home == "main.c" or home == path:
                continue
            above = LAYERS.index(layer(home)) > mine
            # an interface file names no implementation: it reaches them through the ops tables
            impl = home.startswith("solver/impls/") and not path.startswith("solver/impls/") and path != REGISTRATION
            if (above or impl) and not (path == REGISTRATION and re.match(REGISTERED, name)):
                upward[path].add(f"{name} ({home})")
    assert not upward, "layers that reach up (docs/developers/code-map.md): " + "; ".join(
        f"{p} uses {', '.join(sorted(u))}" for p, u in sorted(upward.items()))


def type_units(kind):
    """Each registered type of a kind, as the list of its C files: a file impls/<kind>/NAME.c, or a
    folder impls/<kind>/NAME/ (a type that outgrew one file) with a local header NAMEimpl.h."""
    base = os.path.join(SRC, "solver", "impls", kind)
    units = [[p] for p in sorted(glob.glob(os.path.join(base, "*.c")))]
    units += [sorted(glob.glob(os.path.join(d, "*.c"))) for d in sorted(glob.glob(os.path.join(base, "*", "")))]
    return units


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_each_registered_type_is_one_file_registered_in_one_place(kind):
    """An implementation includes only the solver's private header (a folder's files only the
    folder's header, which includes it), defines one public function, its create (a folder's files
    share what else they need as ..._Private), and impls/register.c registers it: a new type is one
    file or folder and its prototype and registration line there."""
    with open(os.path.join(SRC, TYPES)) as f:
        registration = f.read()
    units = type_units(kind)
    assert len(units) >= 2
    for files in units:
        public = []
        folder = len(files) > 1 or os.path.basename(os.path.dirname(files[0])) != kind
        for path in files:
            rel = os.path.relpath(path, SRC)
            text = code(rel)
            headers = re.findall(r'#include\s+[<"]([^>"]+)[>"]', code(rel, strings=True))
            if folder:
                local = os.path.basename(os.path.dirname(path)) + "impl.h"
                assert headers == [local], f"{rel} includes {headers}, not only the type's {local}"
            else:
                assert includes(rel) == ["solver/solverimpl.h"] and len(headers) == 1, rel
            public += [n for n in re.findall(r"^(?!static)[A-Za-z_][\w ]*?\b(\w*Adh\w*)\([^;{]*\)\s*\{", text, re.M)
                       if not n.endswith("_Private")]
        if folder:
            header = os.path.join(os.path.dirname(files[0]), os.path.basename(os.path.dirname(files[0])) + "impl.h")
            with open(header) as f:
                assert re.findall(r'#include\s+"([^"]+)"', f.read()) == ["solver/solverimpl.h"], header
        where = os.path.relpath(os.path.dirname(files[0]) if folder else files[0], SRC)
        assert len(public) == 1 and public[0].startswith(KINDS[kind]), f"{where}: public functions {public}"
        assert re.search(rf"Register\([\w\"-]+, {public[0]}\)", registration), f"{public[0]} is not registered in {TYPES}"


def test_the_interface_reads_no_types_options_and_branches_on_no_type():
    """A type owns its options: none that a type reads (PetscOptions* in impls/) is read in
    interface/, and interface/ names a built-in type only where it chooses the defaults (the
    solver's creation and set-up), so that adding a type edits no interface file."""
    read = collections.defaultdict(set)
    for path in sources():
        if path.startswith("solver/") and path.endswith(".c"):
            for name in re.findall(r'(?:PetscOptions|AdhOptions)\w+\(\s*"(-adh_\w+)"', code(path, strings=True)):
                read[name].add(path)
    typed = {n for n, paths in read.items() if any(p.startswith("solver/impls/") for p in paths)}
    assert {"-adh_criterion_radius", "-adh_pulloff_rtol", "-adh_predictor_rtol"} <= typed, "the pattern no longer finds the types' options"
    shared = {n: sorted(p for p in paths if p.startswith("solver/interface/")) for n, paths in read.items() if n in typed}
    assert not any(shared.values()), f"types' options read in the interface: {shared}"
    defaults = {"solver/interface/solverbasic.c", "solver/interface/solversetup.c"}
    named = {p: sorted(set(re.findall(r"\bADH(?:CRITERION|CONTROL|PREDICTOR)[A-Z]+\b", code(p))))
             for p in sources() if p.startswith("solver/interface/") and p not in defaults}
    assert not any(named.values()), f"interface files that name a type: { {p: n for p, n in named.items() if n} }"


def test_the_public_header_holds_only_the_api():
    """include/adhbem.h declares the API: the objects (solver, grid) are opaque, their structs and
    the transform's in the layers' private headers."""
    with open(os.path.join(ROOT, "include", "adhbem.h")) as f:
        header = re.sub(r"/\*.*?\*/", " ", f.read(), flags=re.S)
    assert re.search(r"typedef struct _p_AdhGrid \*AdhGrid;", header) and re.search(r"typedef struct _p_AdhSolver \*AdhSolver;", header)
    bodies = re.findall(r"struct\s+(_[pn]_\w+)\s*\{", header)
    assert not bodies, f"object structs in the public header: {bodies}"
    assert "AdhTransform" not in header and "_Private" not in header
