"""Every public function of the C library has a PETSc manual page (/*@ ... @*/) at its definition,
and every registered type a /*MC ... M*/ page: they are the C API reference."""
import glob
import os
import re

from common import ROOT


def public_functions():
    """The functions include/adhbem.h declares PETSC_EXTERN."""
    with open(os.path.join(ROOT, "include", "adhbem.h")) as f:
        header = f.read()
    return sorted(set(re.findall(r"PETSC_EXTERN\s+[\w ]+?\**\s*\b(\w+)\s*\(", header)))


def sources():
    text = {}
    for path in glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True):
        with open(path) as f:
            text[os.path.relpath(path, ROOT)] = f.read()
    return text


def test_every_public_function_has_a_manual_page():
    functions = public_functions()
    assert len(functions) > 70, "the declarations were not found"
    text = sources()
    missing, misplaced = [], []
    for name in functions:
        definition = r"^(?!static)[A-Za-z_][\w ]*?\**\s*\b%s\([^;{]*\)\s*\{" % name
        where = [p for p, t in text.items() if re.search(definition, t, re.M)]
        if not where:
            continue  # a variable or a function defined in a header
        body = text[where[0]]
        m = re.search(definition, body, re.M)
        before = body[:m.start()]
        page = before.rfind("/*@")
        if page < 0 or before.rfind("@*/") < page:
            missing.append(f"{name} ({where[0]})")
            continue
        first = before[page:].split("\n", 2)
        if not re.match(r"\s*%s - \S" % name, first[1] if len(first) > 1 else ""):
            misplaced.append(f"{name} ({where[0]}): the page above it is not its own")
        if "Level:" not in before[page:] or ("Collective" not in before[page:]):
            misplaced.append(f"{name} ({where[0]}): no Level: or collectivity")
    assert not missing, f"public functions without a manual page: {missing}"
    assert not misplaced, misplaced


def test_every_registered_type_has_a_page():
    with open(os.path.join(ROOT, "include", "adhbem.h")) as f:
        types = re.findall(r"#define (ADH(?:CRITERION|CONTROL|PREDICTOR)\w+)\s", f.read())
    assert len(types) >= 6
    text = "\n".join(sources().values())
    for t in types:
        assert re.search(r"/\*MC\s+%s - " % t, text), f"{t} has no /*MC ... M*/ page"
