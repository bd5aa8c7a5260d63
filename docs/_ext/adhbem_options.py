"""The option reference, made when the docs are built from the options the library itself reads
(``adhbem.options.solver_options()``, parsed from what ``adhbem -help`` prints), so the list cannot
drift from ``-help``: one table per -help group, with the Python keyword, the default and the text.

``.. adhbem-options::`` writes all groups; ``:group: TEXT`` only those whose title contains TEXT.
"""
from __future__ import annotations

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles


def _cell(text: str) -> str:
    """Option text as one reST table cell: special characters escaped, -adh_x options literal."""
    import re
    text = text.replace("\\", "\\\\").replace("*", "\\*").replace("|", "\\|").replace("`", "\\`")
    text = re.sub(r"(?<![\w-])(-\w*adh_\w+)", r"``\1``", text)
    return re.sub(r"(\w)_(?=\W|$)", r"\1\\_", text)


class OptionsDirective(SphinxDirective):
    option_spec = {"group": directives.unchanged}

    def run(self):
        from adhbem.options import solver_options
        only = self.options.get("group")
        rst, group = [], None
        for o in solver_options():
            if only and only not in o.group:
                continue
            if o.group != group:
                group = o.group
                title = group[0].upper() + group[1:]
                rst += ["", f".. rubric:: {title}", "", ".. list-table::", "   :header-rows: 1",
                        "   :widths: 30 15 55", "", "   * - option (Python keyword)", "     - default", "     - meaning"]
            choices = f" (one of {', '.join(o.choices)})" if o.choices else ""
            default = "not set" if o.default is None else f"``{o.default}``"
            rst += [f"   * - ``-adh_{o.name}`` (``{o.name}=``)", f"     - {default}", f"     - {_cell(o.text + choices)}"]
        if not rst:
            raise self.error(f"adhbem-options: no option group matches {only!r}")
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, StringList(rst, source="adhbem -help"), node)
        return node.children


def setup(app):
    app.add_directive("adhbem-options", OptionsDirective)
    return {"version": "1", "parallel_read_safe": True}
