"""The solver's options as a table, read from the C library itself: a solver reads its options
with ``-help`` set and PETSc's help text is parsed here. ``Solver``'s keywords, its signature and
its documentation are made from this table, so they list every option the executable has, with
the same defaults and words, and cannot drift from it.

``python3 -m adhbem.options`` prints the table (Markdown).
"""
from __future__ import annotations

import itertools
import os
import re
from dataclasses import dataclass, field

# -PREFIXadh_NAME[:] <DEFAULT>[:] TEXT [(choose one of) | (one of) CHOICES] (MANUAL PAGE)
_ARRAY_DEFAULT = re.compile(r"; default (?P<values>[-+0-9.e]+(?:,[-+0-9.e]+)+) \(-help shows")
_LINE = re.compile(r"^\s+-\w*?adh_(?P<name>\w+)(?P<boolcolon>:?) <(?P<default>[^>]*)>:? (?P<text>.*) \((?P<man>[^()]*)\)$")
_CHOICES = re.compile(r"^(?P<text>.*?) \((?:choose )?one of\) (?P<choices>.*)$")
_FORMERLY = re.compile(r"^now (?P<now>.*?) : formerly .*$")
_REAL_PAIR = re.compile(r"^(?P<now>\S+) : \S+$")
_REAL_TEXT = re.compile(r"^-?(?:[0-9]*\.[0-9]*(?:e[-+]?[0-9]+)?|[0-9]+e[-+]?[0-9]+|inf\.?)$")


@dataclass(frozen=True)
class Option:
    """One option: ``name`` without ``-adh_`` (the Python keyword), the group it is listed under,
    its ``kind`` (``"bool"``, ``"int"``, ``"real"``, ``"str"``, ``"choice"``, ``"int list"``,
    ``"real list"``), the default as -help prints it and as a Python value (``None``: not set,
    the library chooses), the choices of a ``"choice"``, and the help text."""
    name: str
    group: str
    kind: str
    default_text: str
    default: object
    text: str
    choices: tuple = field(default=())

    @property
    def python_type(self) -> str:
        """The type as numpydoc writes it."""
        return {"bool": "bool", "int": "int", "real": "float", "str": "str",
                "int list": "int or sequence of int", "real list": "float or sequence of float",
                "choice": "{" + ", ".join(repr(c) for c in self.choices) + "}"}[self.kind]


def _is_sequence(value):
    """A list, tuple, NumPy array or other sequence of values (not a string, not a 0-d array)."""
    import numpy as np
    if isinstance(value, (str, bytes, os.PathLike)):
        return False
    return np.ndim(value) > 0


def _option_value(value):
    """The option's text: a sequence (list, tuple, NumPy array) as comma-separated values, a real
    number with all its digits."""
    import numbers
    import numpy as np
    if _is_sequence(value):
        return ",".join(_option_value(v) for v in np.asarray(value, dtype=object).ravel())
    if isinstance(value, np.ndarray):  # 0-d
        value = value.item()
    if isinstance(value, (bool, np.bool_)):
        return "1" if value else "0"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    return str(value)


def _real(text):
    """A real as PETSc prints it: always with a '.' ("1.", "1e-08", "inf.")."""
    return float(text[:-1] if text.endswith(".") else text)


def _number(text):
    """An int, or a real when PETSc printed one (it gives every real a '.' or an exponent)."""
    try:
        return int(text)
    except ValueError:
        return _real(text)


# -help's words for a default that is not one number: derived from other options ("(default: the
# cell size ...)", shown as this grid's value) or none ("(default 0: not set, ...")
_DERIVED = re.compile(r"\(default: |\(default \S+: not set")


def _not_set(value, text=""):
    """-help shows some options' 'not set' as a sentinel (-2: the library chooses; a huge modulus:
    a rigid body), or says in its text that the default is derived or none: in Python that is
    None."""
    return bool(_DERIVED.search(text)) or isinstance(value, float) and (value == -2.0 or abs(value) >= 1e300)


def parse_help(text: str) -> list[Option]:
    """The options of a solver's -help text, in the order and groups it prints them."""
    options, group = [], ""
    for line in text.splitlines():
        if line and not line.startswith(" ") and line.endswith(":"):
            group = line[:-1].replace("adhbem ", "", 1)
            continue
        m = _LINE.match(line)
        if not m:
            continue
        name, raw, body = m["name"], m["default"], m["text"]
        if name.startswith(("ksp_", "pc_", "local_ksp_", "local_pc_")):
            continue  # PETSc's own, of the solver's KSPs
        choices = ()
        c = _CHOICES.match(body)
        if c:
            body, choices = c["text"], tuple(c["choices"].split())
        formerly, pair = _FORMERLY.match(raw), _REAL_PAIR.match(raw)
        # PETSc up to 3.2x prints ints and strings as "now X : formerly Y", reals as "X : Y" and
        # bools as "X : Y" after "-name:"; current releases print all three as "now X : formerly Y"
        # (and a colon after every name): a real has a '.' or an exponent, a bool is TRUE or FALSE
        now = formerly["now"] if formerly else pair["now"] if pair else None
        if now is None and raw.strip().upper() in ("TRUE", "FALSE"):  # a bool read outside an options block
            now = raw.strip()
        if now is not None and now.strip().upper() in ("TRUE", "FALSE"):
            kind, default = "bool", now.strip().upper() == "TRUE"
        elif choices:
            kind, default = "choice", now if formerly else raw
        elif now is not None and (pair or _REAL_TEXT.match(now)):
            kind, default = "real", _real(now)
        elif formerly:
            try:
                kind, default = "int", int(now)
            except ValueError:
                kind, default = "str", now or None
        else:  # arrays as "X,Y,..."
            values = [_number(v) for v in raw.split(",") if v]
            kind = "int list" if all(isinstance(v, int) for v in values) else "real list"
            default = values[0] if len(values) == 1 else values
            if kind == "real list":
                default = float(default) if len(values) == 1 else [float(v) for v in values]
            whole = _ARRAY_DEFAULT.search(body)  # -help prints an unset array's first value only
            if whole:
                raw = whole["values"]
                default = [float(v) for v in raw.split(",")]
        if _not_set(default, body):
            default = None
        options.append(Option(name, group, kind, raw, default, body.strip(), choices))
    return options


_table = None
_reads = itertools.count(1)


def solver_options() -> tuple[Option, ...]:
    """The table of the solver's options (read once per process)."""
    global _table
    from . import solver  # noqa: F401 (importing it documents Solver, which reads the table)
    from ._extension import _adhbem
    if _table is None:
        # PETSc prints a group's help once per prefix: each read has a prefix of its own
        _table = tuple(parse_help(_adhbem.option_help(f"adhbemhelp{next(_reads)}_")))
    return _table


def python_text(text: str) -> str:
    """An option's help text with its references to other options as Python keywords."""
    return re.sub(r"-adh_(\w+)", r"``\1``", text)


def markdown() -> str:
    """The table as Markdown: option, Python keyword, default, meaning, by group."""
    out, group = [], None
    for o in solver_options():
        if o.group != group:
            group = o.group
            out += ["", f"## {group[0].upper() + group[1:]}", "", "| option | default | meaning |", "| --- | --- | --- |"]
        choices = f" (one of {', '.join(o.choices)})" if o.choices else ""
        default = "not set" if o.default is None else f"`{o.default}`"
        out.append(f"| `-adh_{o.name}` (`{o.name}=`) | {default} | {o.text}{choices} |".replace("\n", " "))
    return "\n".join(out).strip() + "\n"


if __name__ == "__main__":
    from adhbem import options  # the package's module (this one runs as __main__), which Solver reads
    print(options.markdown(), end="")
