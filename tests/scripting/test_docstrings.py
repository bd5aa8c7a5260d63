"""The Python API documents itself the way petsc4py's standard asks: every public function and
method has type hints and a numpydoc docstring (a Parameters section when it takes any)."""
import inspect

import pytest

import adhbem
from adhbem import grid, plot, results, solver, surface, theory, topography

PUBLIC = [grid.compliance, grid.compliance_info, grid.grid_shape, grid.row_range, grid.local_rows,
          grid.set_local_rows, grid.gather, surface.rough_surface, results.load, topography.is_surface_topography,
          topography.from_surface_topography, plot.curve, plot.area, plot.contact_map, plot.resolution,
          plot.figure, plot.plot]
# every closed form of adhbem.theory, found rather than listed, so a new one cannot skip its docstring
PUBLIC += [f for name, f in vars(theory).items()
           if inspect.isfunction(f) and not name.startswith("_") and f.__module__ == theory.__name__]


def methods(cls):
    for name, member in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(member, property):
            yield f"{cls.__name__}.{name}", member.fget, True
        elif inspect.isfunction(member):
            yield f"{cls.__name__}.{name}", member, False


def everything():
    for fn in PUBLIC:
        yield f"{fn.__module__}.{fn.__name__}", fn, False
    for cls in (solver.Solver, results.Results):
        yield from methods(cls)


@pytest.mark.parametrize("name, fn, is_property", list(everything()), ids=lambda v: v if isinstance(v, str) else "")
def test_type_hints_and_numpydoc(name, fn, is_property):
    sig = inspect.signature(fn)
    doc = inspect.getdoc(fn) or ""
    assert doc, f"{name} has no docstring"
    assert sig.return_annotation is not inspect.Signature.empty, f"{name} has no return type hint"
    params = [p for p in sig.parameters.values() if p.name not in ("self", "cls") and p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL)]
    if params and not is_property:
        assert "Parameters\n----------" in doc, f"{name} takes parameters but its docstring has no Parameters section"
        for p in params:
            assert p.name in doc, f"{name}: parameter {p.name!r} is not documented"


def test_the_solver_is_documented_from_the_option_table():
    assert "Parameters\n----------" in adhbem.Solver.__doc__ and "Examples\n--------" in adhbem.Solver.__doc__
