"""The C API reference, made from the source when the docs are built, so it cannot drift from it.

``include/adhbem.h`` says what is public and in which section ("/* ---- grid/grid.c: ... ---- */");
each public function's manual page is the PETSc ``/*@ ... @*/`` comment above its definition in
``src/`` and each registered type's the ``/*MC ... M*/`` page. The pages are PETSc's doctext
(the summary line, Collective, Input/Output Parameters, Options Database Keys, Level, Notes,
.seealso); they become Sphinx C-domain entries, cross-linked (a `Name()` in a page links to Name).

The directive ``.. adhbem-c-api:: LAYER`` writes the entries of the header sections whose file is
in LAYER (``sys``, ``grid``, ``geometry``, ``solver``, ``results``): functions, types, enums,
macros and the registered types' pages.
"""
from __future__ import annotations

import glob
import os
import re
from dataclasses import dataclass, field

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@dataclass
class Section:
    where: str          # "grid/grid.c", "solver/"
    title: str          # what the header says of it
    functions: list = field(default_factory=list)   # names, in header order
    types: list = field(default_factory=list)       # (kind, name, declaration, comment)


def _read(path):
    with open(path) as f:
        return f.read()


def header_sections(header: str) -> list[Section]:
    """The public declarations of adhbem.h by section; declarations before the first section go to
    "sys/package.c"."""
    sections = [Section("sys/package.c", "the package: initialisation, log events, threads")]
    comment = ""
    lines = header.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        m = re.match(r"/\* ---- (\S+?):? (.*?) ---- \*/", line)
        if m:
            sections.append(Section(m.group(1), m.group(2).rstrip(". ")))
            i += 1
            continue
        if line.startswith("/*"):
            # a comment block: kept for the declaration that follows
            block = [line]
            while "*/" not in block[-1] and i + 1 < len(lines):
                i += 1
                block.append(lines[i])
            comment = " ".join(re.sub(r"^\s*(/\*|\*/|\*)?\s*", "", b).replace("*/", "").strip() for b in block).strip()
            i += 1
            continue
        sec = sections[-1]
        fm = re.match(r"PETSC_EXTERN\s+[\w ]+?\**\s*\b(\w+)\s*\(", line)
        if fm:
            sec.functions.append(fm.group(1))
        elif line.startswith("typedef enum"):
            m = re.match(r"typedef enum \{(.*)\} (\w+);", line)
            if m:
                sec.types.append(("enum", m.group(2), [e.strip() for e in m.group(1).split(",")], comment))
        elif line.startswith("typedef struct {"):
            body = []
            while not lines[i].startswith("}"):
                i += 1
                body.append(lines[i])
            name = re.match(r"\}\s*(\w+);", lines[i]).group(1)
            members = []
            for b in body[:-1]:
                mm = re.match(r"\s*(.+?);\s*(?:/\*\s*(.*?)\s*\*/)?\s*$", b)
                if mm:
                    members.append((mm.group(1), mm.group(2) or ""))
            sec.types.append(("struct", name, members, comment))
        elif line.startswith("typedef"):
            m = re.match(r"typedef (.+?)\s*\b(\w+);\s*(?:/\*\s*(.*?)\s*\*/)?", line)
            if m:
                sec.types.append(("type", m.group(2), m.group(1), m.group(3) or comment))
        elif line.startswith("#define ADH") and not line.startswith("#define ADHBEM_H"):
            m = re.match(r"#define (\w+)\s+(.*)", line)
            sec.types.append(("macro", m.group(1), m.group(2).strip(), comment))
        elif line.startswith("PETSC_EXTERN"):
            m = re.match(r"PETSC_EXTERN\s+(.+?)\s*;", line)
            if m:
                for decl in _split_variables(m.group(1)):
                    sec.types.append(("var", re.findall(r"\w+", decl.split("[")[0])[-1], decl, comment))
        if not line.startswith("/*") and line.strip():
            comment = ""
        i += 1
    return [s for s in sections if s.functions or s.types]


def _split_variables(decl):
    """'PetscLogEvent A, B' -> ['PetscLogEvent A', 'PetscLogEvent B']."""
    first, *rest = [d.strip() for d in decl.split(",")]
    base = first.rsplit(" ", 1)[0].rstrip("*")
    return [first] + [f"{base} {r}" for r in rest]


@dataclass
class Page:
    name: str
    summary: str
    body: list          # the page's lines after the summary line
    signature: str      # the definition's, with parameter names ("" for a type page)
    source: str         # src/... where it is defined


def manual_pages() -> dict[str, Page]:
    """Every /*@ ... @*/ and /*MC ... M*/ page in src/, by name."""
    pages = {}
    for path in sorted(glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True)):
        text = _read(path)
        rel = os.path.relpath(path, os.path.join(ROOT, "src"))
        for m in re.finditer(r"/\*(@C?|MC)\n(.*?)\n\s*(@|M)\*/\n", text, re.S):
            lines = m.group(2).splitlines()
            head = re.match(r"\s*(\w+) - (.*)", lines[0])
            if not head:
                continue
            body = lines[1:]
            # a summary that goes on over the next lines, up to the first blank one
            summary = [head.group(2).strip()]
            while body and body[0].strip():
                summary.append(body.pop(0).strip())
            signature = ""
            if m.group(1) != "MC":
                after = text[m.end():]
                signature = " ".join(after[:after.index("{")].split())
            pages[head.group(1)] = Page(head.group(1), " ".join(summary), body, signature, rel)
    return pages


def inline(text: str, known: dict[str, str]) -> str:
    """PETSc doctext inline markup as reST: `Name()` a link to a function, `NAME` to a known macro,
    type or variable (known: name -> C-domain role), other `...` literal; reST's special characters
    escaped elsewhere."""
    out, pos = [], 0
    for m in re.finditer(r"`([^`]+)`", text):
        out.append(_escape(text[pos:m.start()]))
        code = m.group(1)
        fn = re.fullmatch(r"(\w+)\(\)", code)
        if fn and known.get(fn.group(1)) == "func":
            out.append(f":c:func:`{fn.group(1)}`")
        elif code in known:
            out.append(f":c:{known[code]}:`{code}`")
        else:
            out.append("``" + code + "``")
        pos = m.end()
    out.append(_escape(text[pos:]))
    return "".join(out)


def _escape(text: str) -> str:
    text = text.replace("\\", "\\\\")
    for c in "*|":
        text = text.replace(c, "\\" + c)
    # a word ending in _ would be a reference; a leading _ or an inline literal marker too
    text = re.sub(r"(\w)_(?=\W|$)", r"\1\\_", text)
    return text


_FIELD = re.compile(r"^\s*(Input Parameters?|Output Parameters?|Options Database Keys?|Notes?|Level|Developer Notes?|"
                    r"Fortran Notes?|Example|Calling sequence.*?):\s*(.*)$")


def page_rst(page: Page, known: dict[str, str]) -> list[str]:
    """The page's body as reST lines (indented under a C-domain directive by the caller)."""
    out = [inline(page.summary, known), ""]
    lines = page.body
    i = 0
    while i < len(lines):
        line = lines[i].rstrip()
        s = line.strip()
        if not s:
            i += 1
            continue
        if s.startswith(".seealso:"):
            refs = s[len(".seealso:"):]
            i += 1
            while i < len(lines) and lines[i].strip() and not _FIELD.match(lines[i]):
                refs += " " + lines[i].strip()
                i += 1
            out += [f"**See also:** {inline(refs.strip(), known)}", ""]
            continue
        if s in ("Collective", "Not Collective", "Logically Collective") or s.startswith(("Collective on", "Not collective")):
            out += [f"*{s}*", ""]
            i += 1
            continue
        fm = _FIELD.match(line)
        if fm:
            label, rest = fm.group(1), fm.group(2).strip()
            if label == "Level":
                out += [f"**Level:** {rest}", ""]
                i += 1
                continue
            out += [f".. rubric:: {label}", ""]
            i += 1
            if rest:
                out += [inline(rest, known), ""]
            continue
        if re.match(r"^[+.\-]\s+\S", s):
            # a parameter list: "+ name - text" (first), ". name - text", "- name - text" (last), text going on
            items = []
            while i < len(lines) and lines[i].strip():
                t = lines[i].strip()
                m = re.match(r"^[+.\-]\s+(.+?)\s+-\s+(.*)$", t)
                if m:
                    items.append([m.group(1), m.group(2)])
                elif items:
                    items[-1][1] += " " + t
                i += 1
            for name, text in items:
                out += [f"``{name}``", f"   {inline(text, known)}", ""]
            continue
        # a paragraph
        para = []
        while i < len(lines) and lines[i].strip() and not _FIELD.match(lines[i]) and not lines[i].strip().startswith(".seealso:"):
            para.append(lines[i].strip())
            i += 1
        out += [inline(" ".join(para), known), ""]
    return out


def _c_decl(signature: str) -> str:
    """A definition's signature as the C domain takes it."""
    sig = re.sub(r"\bPETSC_(EXTERN|INTERN)\s+", "", signature)
    return sig.strip()


class CApiDirective(SphinxDirective):
    """.. adhbem-c-api:: LAYER"""
    required_arguments = 1

    def run(self):
        layer = self.arguments[0].strip("/")
        header_path = os.path.join(ROOT, "include", "adhbem.h")
        self.env.note_dependency(header_path)
        sections = header_sections(_read(header_path))
        pages = manual_pages()
        for path in glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True):
            self.env.note_dependency(path)
        roles = {"enum": "enum", "struct": "struct", "macro": "macro", "var": "var", "type": "type"}
        known = {}
        for s in sections:
            known.update((f, "func") for f in s.functions)
            known.update((t[1], roles[t[0]]) for t in s.types)
        rst = []
        for sec in sections:
            if sec.where.split("/")[0] != layer:
                continue
            title = f"{sec.where}: {sec.title}"
            rst += [title, "-" * len(title), ""]
            for kind, name, decl, comment in sec.types:
                rst += self._type(kind, name, decl, comment, pages, known)
            for name in sec.functions:
                rst += self._function(name, pages, known, sec)
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, StringList(rst, source=header_path), node)
        return node.children

    def _function(self, name, pages, known, sec):
        page = pages.get(name)
        if page is None or not page.signature:
            raise self.error(f"adhbem-c-api: {name} (include/adhbem.h, {sec.where}) has no manual page in src/")
        out = [f".. c:function:: {_c_decl(page.signature)}", ""]
        out += ["   " + v if v else "" for v in page_rst(page, known)]
        out += [f"   *Defined in* ``src/{page.source}``.", ""]
        return out

    def _type(self, kind, name, decl, comment, pages, known):
        page = pages.get(name)
        text = page_rst(page, known) if page else ([inline(comment, known), ""] if comment else [])
        ind = ["   " + v if v else "" for v in text]
        if kind == "enum":
            out = [f".. c:enum:: {name}", ""] + ind
            for e in decl:
                out += [f"   .. c:enumerator:: {e}", ""]
            return out
        if kind == "struct":
            out = [f".. c:struct:: {name}", ""] + ind
            for member, what in decl:
                for m in _split_variables(member):
                    out += [f"   .. c:member:: {m}", ""]
                    if what:
                        out += [f"      {inline(what, known)}", ""]
            return out
        if kind == "macro":
            value = decl if not page else ""
            out = [f".. c:macro:: {name}", ""] + ind
            if value:
                out += [f"   Value: ``{value}``", ""]
            return out
        if kind == "var":
            return [f".. c:var:: {decl}", ""] + ind
        # a typedef
        return [f".. c:type:: {name}", ""] + ind + ([f"   ``typedef {decl} {name}``", ""])


def setup(app):
    app.add_directive("adhbem-c-api", CApiDirective)
    return {"version": "1", "parallel_read_safe": True}
